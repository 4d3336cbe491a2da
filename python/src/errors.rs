//! The package's exceptions and the engine's errors turned into them.

use mpdem::StepError;
use mpdem::resources::NumericalFailure as EngineFailure;
use mpdem::runner::RunError as EngineRunError;
use mpdem::scene::SceneError as EngineSceneError;
use pyo3::exceptions::{PyRuntimeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    mpdem,
    SceneError,
    PyValueError,
    "A scene that cannot be read or is not valid. Attributes: `message` (what \
     is wrong and what was expected), `file`, `line` and `column` (1-based; \
     None where unknown) and `key_path` (for a scene built from a dict, the \
     keys leading to the offending value, e.g. \
     `materials[0].model.DruckerPrager.friction_angle`)."
);
pyo3::create_exception!(
    mpdem,
    NumericalFailure,
    PyRuntimeError,
    "The numerics broke down during a step (a value that is not finite, a \
     point out of the grid, ...). Attributes: `message`, `step` and `time` \
     (the step being computed and the time at its start, s)."
);
pyo3::create_exception!(
    mpdem,
    RunError,
    PyRuntimeError,
    "A run that could not start or finish writing its output folder (a \
     folder another run holds, a checkpoint in the way, a failed write). \
     Attribute: `message`."
);
pyo3::create_exception!(
    mpdem,
    SceneWarning,
    PyUserWarning,
    "A warning the engine raises about a scene or a run: a time step near \
     its stability limit, a body touching an open edge, a stage cut short."
);

/// Where a scene error is, besides its message.
#[derive(Default)]
pub struct ErrorPlace {
    /// The scene file, when the scene came from one.
    pub file: Option<String>,
    /// Line and column (1-based).
    pub line_col: Option<(usize, usize)>,
    /// The keys leading to the value, for a scene built from a dict.
    pub key_path: Option<String>,
}

/// A `SceneError` with `message` at `place`; its text is the engine's:
/// `file:line:column: message`, or `key.path: message` for a dict.
pub fn scene_error(py: Python<'_>, message: &str, place: ErrorPlace) -> PyErr {
    let prefix = match (&place.file, place.line_col, &place.key_path) {
        // A message that names its field already is not prefixed twice.
        (_, _, Some(keys)) if message.starts_with(&format!("{keys}:")) => String::new(),
        (_, _, Some(keys)) => format!("{keys}: "),
        (Some(file), Some((line, col)), None) => format!("{file}:{line}:{col}: "),
        (Some(file), None, None) => format!("{file}: "),
        (None, Some((line, col)), None) => format!("line {line}, column {col}: "),
        (None, None, None) => String::new(),
    };
    let err = SceneError::new_err(format!("{prefix}{message}"));
    let value = err.value(py);
    let _ = value.setattr("message", message);
    let _ = value.setattr("file", place.file);
    let _ = value.setattr("line", place.line_col.map(|(l, _)| l));
    let _ = value.setattr("column", place.line_col.map(|(_, c)| c));
    let _ = value.setattr("key_path", place.key_path);
    err
}

/// The engine's scene error as a `SceneError`: `file_shown` says whether
/// the location's path is a real file (a scene given as text has none).
pub fn from_scene_error(py: Python<'_>, e: &EngineSceneError, file_shown: bool) -> PyErr {
    match e {
        EngineSceneError::Read { path, source } => scene_error(
            py,
            &format!("cannot read the scene: {source}"),
            ErrorPlace {
                file: Some(path.display().to_string()),
                ..ErrorPlace::default()
            },
        ),
        EngineSceneError::Parse { location, message }
        | EngineSceneError::Invalid { location, message } => scene_error(
            py,
            message,
            ErrorPlace {
                file: location
                    .path
                    .as_ref()
                    .filter(|_| file_shown)
                    .map(|p| p.display().to_string()),
                line_col: location.line_col,
                key_path: None,
            },
        ),
    }
}

/// A numerical failure as a `NumericalFailure`, with its step and time.
pub fn numerical_failure(py: Python<'_>, failure: &EngineFailure) -> PyErr {
    let err = NumericalFailure::new_err(format!("numerical failure at {failure}"));
    let value = err.value(py);
    let _ = value.setattr("message", failure.to_string());
    let _ = value.setattr("step", failure.step);
    let _ = value.setattr("time", failure.time);
    err
}

/// A step's error as the exception it stands for.
pub fn from_step_error(py: Python<'_>, e: &StepError) -> PyErr {
    match e {
        StepError::Numerical(failure) => numerical_failure(py, failure),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

/// A run's error: a scene error as `SceneError`, a failed step as
/// `NumericalFailure` (its message names the folder holding the results up
/// to it), the rest as `RunError`.
pub fn from_run_error(py: Python<'_>, e: &EngineRunError, file_shown: bool) -> PyErr {
    match e {
        EngineRunError::Scene(scene) => from_scene_error(py, scene, file_shown),
        EngineRunError::Failed { message, .. } => {
            let err = NumericalFailure::new_err(e.to_string());
            let _ = err.value(py).setattr("message", message);
            err
        }
        other => {
            let err = RunError::new_err(other.to_string());
            let _ = err.value(py).setattr("message", other.to_string());
            err
        }
    }
}

/// Issues `message` as a `SceneWarning`.
pub fn warn(py: Python<'_>, message: &str) -> PyResult<()> {
    let category = py.get_type::<SceneWarning>();
    let text = std::ffi::CString::new(message.replace('\0', " ")).expect("NUL bytes were replaced");
    PyErr::warn(py, &category, &text, 1)
}

/// Adds the exception types to the module.
pub fn register(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    module.add("SceneError", py.get_type::<SceneError>())?;
    module.add("NumericalFailure", py.get_type::<NumericalFailure>())?;
    module.add("RunError", py.get_type::<RunError>())?;
    module.add("SceneWarning", py.get_type::<SceneWarning>())?;
    Ok(())
}
