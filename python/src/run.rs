//! `mpdem.run`: a scene's run written to an output folder, as the CLI's
//! `mpdem run` writes it.

use crate::ctrl_c::watch_for_ctrl_c;
use crate::errors::{from_run_error, warn};
use crate::scene::PyScene;
use crate::threads::thread_pool;
use mpdem::runner::{RunOptions, Runner, Start};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

/// What a finished run reached.
#[pyclass(module = "mpdem", frozen, get_all)]
#[derive(Clone, Debug)]
pub struct RunSummary {
    /// The scene's name.
    pub name: String,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time reached (s).
    pub time: f64,
    /// The final state's hash, 16 hexadecimal digits, as the CLI prints it.
    pub state_hash: String,
    /// Wall time of the run (s).
    pub elapsed: f64,
    /// The output folder.
    pub out: PathBuf,
}

#[pymethods]
impl RunSummary {
    fn __repr__(&self) -> String {
        format!(
            "RunSummary({:?}, steps={}, time={:.6e}, state_hash={:?}, out={:?})",
            self.name, self.steps, self.time, self.state_hash, self.out
        )
    }
}

/// Runs `scene` to its end and writes into `out` (default
/// `out/<scene name>`) exactly the files `mpdem run` writes: frames, series,
/// plots, the animation, and checkpoints when `checkpoint_every` (s) is
/// given. `resume` carries on from the folder's checkpoint; `restart`
/// starts over, removing it; `overwrite` writes into a folder another
/// scene's run wrote. The run steps with the GIL released. Ctrl-C stops
/// it after the step in progress: the results up to there (and the
/// checkpoint, if the run writes them) are written, then
/// `KeyboardInterrupt` is raised.
#[pyfunction]
#[pyo3(signature = (scene, out = None, threads = None, checkpoint_every = None, resume = false, restart = false, overwrite = false))]
#[allow(clippy::too_many_arguments)]
pub fn run(
    py: Python<'_>,
    scene: PyRef<'_, PyScene>,
    out: Option<PathBuf>,
    threads: Option<usize>,
    checkpoint_every: Option<f64>,
    resume: bool,
    restart: bool,
    overwrite: bool,
) -> PyResult<RunSummary> {
    if resume && restart {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "resume carries the folder's run on and restart starts over: give one",
        ));
    }
    let pool = thread_pool(threads)?;
    let file_shown = scene.file.is_some();
    let options = RunOptions {
        out: out.unwrap_or_else(|| Path::new("out").join(scene.scene.display_name())),
        checkpoint_every,
        start: match (resume, restart) {
            (true, _) => Start::Resume,
            (false, true) => Start::Restart,
            (false, false) => Start::Fresh,
        },
        replace_other_scene: overwrite,
    };
    let (scene_ref, file) = (&scene.scene, scene.file.as_deref());
    let mut runner = py
        .detach(|| pool.install(|| Runner::new(scene_ref, file, options)))
        .map_err(|e| from_run_error(py, &e, file_shown))?;
    for w in runner.warnings() {
        warn(py, &w.to_string())?;
    }
    let stop = AtomicBool::new(false);
    let cut_short = Arc::new(AtomicBool::new(false));
    runner.interrupt_steps_on(Arc::clone(&cut_short));
    let (result, interrupt) =
        py.detach(|| watch_for_ctrl_c(&pool, || runner.run(&stop, |_| {}), &stop, &cut_short));
    for w in runner.stage_warnings() {
        warn(py, &w.to_string())?;
    }
    if let Some(e) = interrupt {
        return Err(e);
    }
    let summary = result.map_err(|e| from_run_error(py, &e, file_shown))?;
    Ok(RunSummary {
        name: summary.name,
        steps: summary.steps,
        time: summary.time,
        state_hash: format!("{:016x}", summary.state_hash),
        elapsed: summary.elapsed.as_secs_f64(),
        out: summary.dir,
    })
}
