//! `mpdem.Scene`: a validated scene, read from a file, RON text or a dict,
//! and edited from Python.

use crate::errors::{ErrorPlace, from_scene_error, scene_error};
use crate::key_path::{KeyPath, place_of_anchors};
use mpdem::scene::{Scene, SceneError as EngineSceneError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::path::{Path, PathBuf};

/// What pickling a scene gives: the constructor and its arguments.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyAny>, PathBuf));

/// The name a scene given as text takes when it names none, and the file
/// its messages would cite (they cite line and column only).
const TEXT_SCENE_FILE: &str = "scene.ron";

/// A scene that has passed the engine's validation: every range rule and
/// every reference. Build it with `Scene.from_file`, `Scene.from_ron` or
/// `Scene.from_dict`; edit it with `set` (validated again) or through
/// `to_dict` and `from_dict`.
#[pyclass(name = "Scene", module = "mpdem", from_py_object)]
#[derive(Clone)]
pub struct PyScene {
    /// The validated scene.
    pub scene: Scene,
    /// The scene's file, when it came from one.
    pub file: Option<PathBuf>,
    /// The folder the point lists' files are read from.
    pub folder: PathBuf,
}

#[pymethods]
impl PyScene {
    /// Reads, parses and validates a RON scene file.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let scene = Scene::load(&path).map_err(|e| from_scene_error(py, &e, true))?;
        Ok(Self {
            scene,
            folder: path.parent().map_or_else(PathBuf::new, Path::to_path_buf),
            file: Some(path),
        })
    }

    /// Parses and validates RON scene text. Point lists' files are read
    /// relative to `folder` (default: the current folder). A scene without
    /// a `name` is called "scene".
    #[staticmethod]
    #[pyo3(signature = (text, folder = None))]
    fn from_ron(py: Python<'_>, text: &str, folder: Option<PathBuf>) -> PyResult<Self> {
        let folder = folder.unwrap_or_default();
        let scene = Scene::parse(text, &folder.join(TEXT_SCENE_FILE))
            .map_err(|e| from_scene_error(py, &e, false))?;
        Ok(Self {
            scene,
            file: None,
            folder,
        })
    }

    /// Builds and validates a scene from a dict laid out as the RON scene
    /// is (see `to_dict`): structs and maps are dicts, lists and tuples are
    /// lists, an enum variant with fields is a one-key dict
    /// (`{"DruckerPrager": {...}}`), one without is its name (`"Fixed"`),
    /// and an optional value is the value or None. Errors carry the key
    /// path. Point lists' files are read relative to `folder` (default:
    /// the current folder).
    #[staticmethod]
    #[pyo3(signature = (d, folder = None))]
    fn from_dict(py: Python<'_>, d: &Bound<'_, PyAny>, folder: Option<PathBuf>) -> PyResult<Self> {
        let folder = folder.unwrap_or_default();
        let scene = scene_from_dict(py, d, &folder)?;
        Ok(Self {
            scene,
            file: None,
            folder,
        })
    }

    /// The scene as a dict, laid out as `from_dict` reads it (tuples such
    /// as points as lists, so that they can be edited in place).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        tuples_as_lists(pythonize::pythonize(py, &self.scene)?)
    }

    /// The scene as RON text, which `Scene.from_ron` and the CLI read back
    /// to the same scene (comments and the file's own layout are not kept).
    fn to_ron(&self) -> PyResult<String> {
        ron::ser::to_string_pretty(&self.scene, ron::ser::PrettyConfig::new())
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
    }

    /// The value at `key_path` (e.g. `"materials[0].model.DruckerPrager.friction_angle"`,
    /// or `"materials[sand].density"` with an entry's name in the brackets).
    fn get<'py>(&self, py: Python<'py>, key_path: &str) -> PyResult<Bound<'py, PyAny>> {
        let dict = self.to_dict(py)?;
        KeyPath::parse(key_path)?.get(&dict)
    }

    /// Sets the value at `key_path` (as in `get`) and validates the scene
    /// again; on an error the scene is left as it was and a `SceneError`
    /// names the key path.
    fn set(&mut self, py: Python<'_>, key_path: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let dict = self.to_dict(py)?;
        KeyPath::parse(key_path)?.set(&dict, value)?;
        self.scene = scene_from_dict(py, &dict, &self.folder)?;
        Ok(())
    }

    /// The scene's name (its `name`, or its file's name without `.ron`).
    #[getter]
    fn name(&self) -> String {
        self.scene.display_name().to_owned()
    }

    /// The scene's file, if it came from one.
    #[getter]
    fn file(&self) -> Option<PathBuf> {
        self.file.clone()
    }

    /// The warnings validation raised about spellings of earlier releases
    /// (the simulation raises the others when it is built).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene
            .file_warnings
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    /// Pickling (and `copy`) go through the dict, so that a sweep can hand
    /// scenes to worker processes.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let this = slf.borrow();
        let rebuild = slf.get_type().getattr("from_dict")?;
        Ok((rebuild, (this.to_dict(slf.py())?, this.folder.clone())))
    }

    /// Scenes are equal when every field is.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Self>()
            .is_ok_and(|other| other.borrow().scene == self.scene)
    }

    fn __repr__(&self) -> String {
        match &self.file {
            Some(file) => format!("Scene({:?}, file={:?})", self.scene.display_name(), file),
            None => format!("Scene({:?})", self.scene.display_name()),
        }
    }
}

/// `value` with every tuple in it, at any depth, turned into a list.
fn tuples_as_lists(value: Bound<'_, PyAny>) -> PyResult<Bound<'_, PyAny>> {
    let py = value.py();
    if let Ok(tuple) = value.cast::<PyTuple>() {
        let items: Vec<_> = tuple.iter().map(tuples_as_lists).collect::<PyResult<_>>()?;
        return Ok(PyList::new(py, items)?.into_any());
    }
    if let Ok(list) = value.cast::<PyList>() {
        for k in 0..list.len() {
            list.set_item(k, tuples_as_lists(list.get_item(k)?)?)?;
        }
    } else if let Ok(dict) = value.cast::<PyDict>() {
        for (key, item) in dict.iter() {
            dict.set_item(key, tuples_as_lists(item)?)?;
        }
    }
    Ok(value)
}

/// Deserializes and validates the dict `d`, reading point lists from
/// `folder`; errors carry the key path.
fn scene_from_dict(py: Python<'_>, d: &Bound<'_, PyAny>, folder: &Path) -> PyResult<Scene> {
    if !d.is_instance_of::<PyDict>() {
        return Err(scene_error(
            py,
            &format!(
                "a scene is a dict, got {}",
                d.get_type().name().map_or("?".into(), |n| n.to_string())
            ),
            ErrorPlace::default(),
        ));
    }
    let mut input = pythonize::Depythonizer::from_object(d);
    let mut scene: Scene = serde_path_to_error::deserialize(&mut input).map_err(|e| {
        // The root is ".", an unknown place "?": no key path to give.
        let path = Some(e.path().to_string()).filter(|p| p != "." && p != "?");
        scene_error(
            py,
            &e.into_inner().to_string(),
            ErrorPlace {
                key_path: path,
                ..ErrorPlace::default()
            },
        )
    })?;
    let located = |e: EngineSceneError| match &e {
        EngineSceneError::Parse { location, message }
        | EngineSceneError::Invalid { location, message } => scene_error(
            py,
            message,
            ErrorPlace {
                key_path: place_of_anchors(d, &location.anchors),
                ..ErrorPlace::default()
            },
        ),
        EngineSceneError::Read { .. } => from_scene_error(py, &e, true),
    };
    scene.read_point_files(folder).map_err(located)?;
    scene.validate().map_err(located)?;
    Ok(scene)
}
