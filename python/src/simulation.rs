//! `mpdem.Simulation`: a scene's simulation stepped from Python, its
//! fields read as NumPy arrays between steps.

use crate::ctrl_c::watch_for_ctrl_c;
use crate::errors::{NumericalFailure, from_scene_error, from_step_error, warn};
use crate::fields::{Block, Body, block_states, body_snapshot, set_point_column};
use crate::scene::PyScene;
use crate::threads::thread_pool;
use mpdem::Simulation;
use mpdem::StepError;
use mpdem::resources::Clock;
use numpy::PyReadonlyArray2;
use pyo3::exceptions::{PyKeyError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// A running simulation of a scene. Steps run with the GIL released, on
/// `threads` worker threads (default: all cores); the results do not
/// depend on the number. Between steps, Python reads the fields as NumPy
/// arrays and may set velocities and external forces. Ctrl-C stops a
/// stepping call after the step in progress with `KeyboardInterrupt`, the
/// state left at the last whole step; a step still running half a second
/// later is cut short, and the simulation then takes no further step.
#[pyclass(name = "Simulation", module = "mpdem", subclass)]
pub struct PySimulation {
    sim: Simulation,
    pool: rayon::ThreadPool,
    /// The bodies' entities and names, in scene order.
    bodies: Vec<(bevy_ecs::entity::Entity, String)>,
    /// Step warnings already issued.
    warned: usize,
    /// The failure a step raised: the state is the failed step's, which
    /// no further step may start from.
    failed: Option<String>,
    /// Raised when a step runs on [`mpdem::runner::STOP_GRACE`] after
    /// Ctrl-C: the step is cut short.
    cut_short: Arc<AtomicBool>,
}

#[pymethods]
impl PySimulation {
    /// Builds the simulation of `scene`; its warnings are issued as
    /// `mpdem.SceneWarning`.
    #[new]
    #[pyo3(signature = (scene, threads = None))]
    fn new(py: Python<'_>, scene: PyRef<'_, PyScene>, threads: Option<usize>) -> PyResult<Self> {
        let pool = thread_pool(threads)?;
        let scene_ref = &scene.scene;
        let mut sim = py
            .detach(|| pool.install(|| Simulation::from_scene(scene_ref)))
            .map_err(|e| from_scene_error(py, &e, scene.file.is_some()))?;
        for w in sim.warnings() {
            warn(py, &w.to_string())?;
        }
        let bodies = sim.bodies();
        let cut_short = Arc::new(AtomicBool::new(false));
        sim.interrupt_steps_on(Arc::clone(&cut_short));
        Ok(Self {
            sim,
            pool,
            bodies,
            warned: 0,
            failed: None,
            cut_short,
        })
    }

    /// Takes `n` steps (stopping early at the run's end).
    #[pyo3(signature = (n = 1))]
    fn step(slf: &Bound<'_, Self>, n: u64) -> PyResult<()> {
        let target = slf.try_borrow()?.sim.clock().step.saturating_add(n);
        advance(slf, |clock| clock.step >= target, None, None).map(|_| ())
    }

    /// Steps to the end of the run: the scene's `time.end`, or the end of
    /// its last stage if that comes first.
    fn run(slf: &Bound<'_, Self>) -> PyResult<()> {
        advance(slf, |_| false, None, None).map(|_| ())
    }

    /// Steps until the time reaches `t` (s, within half a step) or the
    /// run ends. `callback(sim)` is called between steps: every `every`
    /// seconds of simulated time, or after every step without it. When it
    /// returns True the run stops there. Returns whether `t` (or the run's
    /// end) was reached.
    #[pyo3(signature = (t, every = None, callback = None))]
    fn run_until(
        slf: &Bound<'_, Self>,
        t: f64,
        every: Option<f64>,
        callback: Option<Bound<'_, PyAny>>,
    ) -> PyResult<bool> {
        if !t.is_finite() {
            return Err(PyValueError::new_err(format!(
                "t must be a finite time, got {t}"
            )));
        }
        let dt = slf.try_borrow()?.sim.clock().dt;
        let interval = match every {
            Some(e) if e.is_finite() && e > 0.0 => Some(((e / dt).round() as u64).max(1)),
            Some(e) => {
                return Err(PyValueError::new_err(format!(
                    "every must be a positive time, got {e}"
                )));
            }
            None => None,
        };
        let target = (t / dt).round().max(0.0) as u64;
        advance(slf, |clock| clock.step >= target, callback, interval)
    }

    /// The simulated time (s).
    #[getter]
    fn time(&self) -> f64 {
        self.sim.clock().time
    }

    /// The steps taken.
    #[getter]
    fn step_count(&self) -> u64 {
        self.sim.clock().step
    }

    /// The time step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.sim.clock().dt
    }

    /// The time the run ends at (s): the scene's `time.end`, or the end of
    /// its last stage once known.
    #[getter]
    fn end_time(&self) -> f64 {
        self.sim.clock().end
    }

    /// Whether the run has reached its end.
    #[getter]
    fn finished(&self) -> bool {
        self.sim.clock().finished()
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.sim.name().to_owned()
    }

    /// The hash of the state, as 16 hexadecimal digits: the one the CLI
    /// prints at the end of a run. Equal hashes mean bit-identical states.
    fn state_hash(&mut self) -> String {
        format!("{:016x}", self.sim.state_hash())
    }

    /// The bodies' names, in scene order.
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.bodies.iter().map(|(_, name)| name.clone()).collect()
    }

    /// The blocks' names, in scene order (those present now).
    #[getter]
    fn blocks(&mut self) -> Vec<String> {
        block_states(&mut self.sim)
            .into_iter()
            .map(|b| b.name)
            .collect()
    }

    /// A snapshot of the body `name`'s points: arrays in SI units, one row
    /// per point in the body's fixed order.
    fn body(&self, py: Python<'_>, name: &str) -> PyResult<Body> {
        let entity = self.entity(name)?;
        body_snapshot(py, &self.sim, entity, name)
    }

    /// The state of the block `name`: pose, velocity and the points'
    /// reaction in the last step.
    fn block(&mut self, name: &str) -> PyResult<Block> {
        block_states(&mut self.sim)
            .into_iter()
            .find(|b| b.name == name)
            .ok_or_else(|| PyKeyError::new_err(format!("no block named {name:?}")))
    }

    /// Sets the velocity (m/s) of every point of body `name`: an N × 2 array.
    fn set_velocity(&mut self, name: &str, velocity: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let entity = self.entity(name)?;
        set_point_column(&mut self.sim, entity, &velocity, |p| &mut p.velocity)
    }

    /// Sets the external force (N per metre of thickness) on every point of
    /// body `name`: an N × 2 array, kept until set again (gravity is
    /// separate).
    fn set_external_force(&mut self, name: &str, force: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let entity = self.entity(name)?;
        set_point_column(&mut self.sim, entity, &force, |p| &mut p.external_force)
    }

    /// The names of the recorded series (`energy`, `probes`, ...), each
    /// the stem of the CSV file a run writes.
    #[getter]
    fn series_names(&self) -> Vec<String> {
        self.sim
            .series_files()
            .into_iter()
            .map(|file| file.trim_end_matches(".csv").to_owned())
            .collect()
    }

    /// The series `name` as the CSV text its file would hold now.
    fn series_csv(&self, name: &str) -> PyResult<String> {
        self.sim
            .series_csv(&format!("{name}.csv"))
            .ok_or_else(|| PyKeyError::new_err(format!("no series named {name:?}")))
    }

    /// The warnings the scene raised when the simulation was built, and
    /// those steps have raised since.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.sim
            .warnings()
            .iter()
            .chain(self.sim.step_warnings())
            .map(ToString::to_string)
            .collect()
    }

    fn __repr__(&self) -> String {
        let clock = self.sim.clock();
        format!(
            "Simulation({:?}, step={}, time={:.6e})",
            self.sim.name(),
            clock.step,
            clock.time
        )
    }
}

impl PySimulation {
    fn entity(&self, name: &str) -> PyResult<bevy_ecs::entity::Entity> {
        self.bodies
            .iter()
            .find(|(_, n)| n == name)
            .map(|(e, _)| *e)
            .ok_or_else(|| PyKeyError::new_err(format!("no body named {name:?}")))
    }
}

/// How long the steps run between two hand-backs to Python (warnings,
/// callbacks, signals).
const SLICE: Duration = Duration::from_millis(50);

/// Why a run of steps on the pool came back to Python.
enum Pause {
    /// `done` said so, or the run ended.
    Reached,
    /// The callback is due.
    Callback,
    /// A slice of time has passed, or Ctrl-C came.
    Slice,
}

/// Steps until `done` says so or the run ends, calling `callback` between
/// steps (every `interval` steps, or every step), and stopping when it
/// returns True; returns whether it ran to `done` or the end. The steps
/// run on the pool with the GIL released, in slices of up to [`SLICE`]
/// (one hand-over to the pool per slice, not per step); warnings are
/// issued between slices. The calling thread looks for Ctrl-C while a
/// slice runs: the steps stop after the one in progress, or cut it short
/// if it runs on for [`mpdem::runner::STOP_GRACE`].
fn advance(
    slf: &Bound<'_, PySimulation>,
    done: impl Fn(&Clock) -> bool + Send + Sync,
    callback: Option<Bound<'_, PyAny>>,
    interval: Option<u64>,
) -> PyResult<bool> {
    let py = slf.py();
    let calls_back = callback.is_some();
    loop {
        let pause = {
            // Another thread stepping the simulation holds it: a
            // RuntimeError, not a panic.
            let mut this = slf.try_borrow_mut()?;
            if let Some(failure) = &this.failed {
                return Err(NumericalFailure::new_err(format!(
                    "the simulation failed before ({failure}); build a new one to run again"
                )));
            }
            if this.sim.cut_short() {
                return Err(PyRuntimeError::new_err(
                    "a step was cut short by Ctrl-C, so the state is half updated; build a new simulation to run again",
                ));
            }
            let PySimulation {
                sim,
                pool,
                warned,
                failed,
                cut_short,
                ..
            } = &mut *this;
            let stop = AtomicBool::new(false);
            let slice = || {
                let started = Instant::now();
                loop {
                    let clock = sim.clock();
                    if done(&clock) || clock.finished() {
                        return Ok(Pause::Reached);
                    }
                    if stop.load(Ordering::SeqCst) {
                        return Ok(Pause::Slice);
                    }
                    sim.step()?;
                    let step = sim.clock().step;
                    if calls_back && interval.is_none_or(|k| step.is_multiple_of(k)) {
                        return Ok(Pause::Callback);
                    }
                    if started.elapsed() >= SLICE {
                        return Ok(Pause::Slice);
                    }
                }
            };
            let (result, signal) = py.detach(|| watch_for_ctrl_c(pool, slice, &stop, cut_short));
            // A request raised as the step in progress ended whole must not
            // cut the next call's first step.
            cut_short.store(false, Ordering::SeqCst);
            let result = result.inspect_err(|e: &StepError| {
                if !matches!(e, StepError::Interrupted(_)) {
                    *failed = Some(e.to_string());
                }
            });
            for w in &sim.step_warnings()[*warned..] {
                warn(py, &w.to_string())?;
            }
            *warned = sim.step_warnings().len();
            if let Some(interrupt) = signal {
                return Err(interrupt);
            }
            result.map_err(|e| from_step_error(py, &e))?
        };
        py.check_signals()?;
        match (pause, &callback) {
            (Pause::Reached, _) => return Ok(true),
            (Pause::Callback, Some(callback)) if callback.call1((slf,))?.is_truthy()? => {
                return Ok(false);
            }
            _ => {}
        }
    }
}
