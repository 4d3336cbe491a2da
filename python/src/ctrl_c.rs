//! Ctrl-C while the engine works on its pool: Python runs its signal
//! handlers on the main thread only, so the calling thread watches for
//! them while the work runs.

use mpdem::runner::STOP_GRACE;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

/// How often the calling thread looks for Ctrl-C while the work runs.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `work` on `pool` while the calling thread looks for Ctrl-C every
/// [`SIGNAL_POLL`]. On Ctrl-C it raises `stop` (the work stops after its
/// step), and `cut_short` [`STOP_GRACE`] later if the work is still
/// running (the step in progress is cut short); it returns the work's
/// result and the signal's error. A panic of the work is raised again.
pub fn watch_for_ctrl_c<T: Send>(
    pool: &rayon::ThreadPool,
    work: impl FnOnce() -> T + Send,
    stop: &AtomicBool,
    cut_short: &AtomicBool,
) -> (T, Option<PyErr>) {
    let (finished, outcome) = mpsc::channel();
    let mut signal: Option<PyErr> = None;
    let mut signalled_at: Option<Instant> = None;
    let result = pool.in_place_scope(|scope| {
        scope.spawn(move |_| {
            let _ = finished.send(work());
        });
        loop {
            match outcome.recv_timeout(SIGNAL_POLL) {
                Ok(result) => return Some(result),
                // The work panicked: the scope raises its panic.
                Err(RecvTimeoutError::Disconnected) => return None,
                Err(RecvTimeoutError::Timeout) => {}
            }
            if signal.is_none()
                && let Err(e) = Python::attach(|py| py.check_signals())
            {
                signal = Some(e);
                signalled_at = Some(Instant::now());
                stop.store(true, Ordering::SeqCst);
            }
            if signalled_at.is_some_and(|at| at.elapsed() >= STOP_GRACE) {
                cut_short.store(true, Ordering::SeqCst);
            }
        }
    });
    let result = result.expect("work that panicked raises its panic from the scope");
    (result, signal)
}
