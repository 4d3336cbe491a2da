//! Stop signals: the first one asks the run to stop after its step and
//! write its results, cutting the step short if it is still running
//! [`STOP_GRACE`] later; a later one ends the process at once.

use crate::STOPPED_STATUS;
use crate::console::say_err;
use mpdem::runner::STOP_GRACE;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How long after a stop signal another one counts as the same request:
/// `timeout` and job control send a signal to the process and to its
/// group at once, so one request can arrive twice within microseconds.
const SIGNAL_REPEAT_WINDOW: Duration = Duration::from_secs(1);

/// What the stop signals raise.
pub struct StopRequest {
    /// Raised by the first signal: the run stops after its step.
    pub stop: Arc<AtomicBool>,
    /// Raised [`STOP_GRACE`] after the first signal: the step in progress
    /// is cut short.
    pub cut_short: Arc<AtomicBool>,
}

/// Flags the first Ctrl-C, SIGTERM or SIGHUP raises, so that the run stops
/// after its step (or cuts a long step short) and writes its results (and
/// a checkpoint, if it writes them and its step was whole); another one,
/// [`SIGNAL_REPEAT_WINDOW`] or more after the first, ends the process at
/// once. As a rank of an MPI job (`in_job`), SIGUSR1 and SIGUSR2 stop the
/// run too: `mpirun` passes them on to every rank and waits for the job,
/// where it gives the ranks only a moment after a SIGTERM before it kills
/// them. A distributed run stops after its step, never inside it.
pub fn stop_on_signals(in_job: bool) -> StopRequest {
    let request = StopRequest {
        stop: Arc::new(AtomicBool::new(false)),
        cut_short: Arc::new(AtomicBool::new(false)),
    };
    let stop = Arc::clone(&request.stop);
    let cut_short = Arc::clone(&request.cut_short);
    let mut first: Option<Instant> = None;
    let handler = ctrlc::set_handler(move || {
        stop.store(true, Ordering::SeqCst);
        match first {
            None => {
                first = Some(Instant::now());
                say_err(if in_job {
                    "stop requested: the run stops after its step and writes its results (another stop signal a second or more from now ends it at once, without them)"
                } else {
                    "stop requested: the run stops after its step (cut short if it runs on for half a second) and writes its results (another stop signal a second or more from now ends it at once, without them)"
                });
                let cut_short = Arc::clone(&cut_short);
                std::thread::spawn(move || {
                    std::thread::sleep(STOP_GRACE);
                    cut_short.store(true, Ordering::SeqCst);
                });
            }
            Some(at) if at.elapsed() >= SIGNAL_REPEAT_WINDOW => {
                say_err("second stop signal: exiting now, without the results not yet written");
                std::process::exit(STOPPED_STATUS.into());
            }
            Some(_) => {}
        }
    });
    if let Err(e) = handler {
        say_err(&format!(
            "warning: a stop signal will end the run without writing its results: {e}"
        ));
    }
    #[cfg(feature = "mpi")]
    if in_job {
        for signal in [signal_hook::consts::SIGUSR1, signal_hook::consts::SIGUSR2] {
            if let Err(e) = signal_hook::flag::register(signal, Arc::clone(&request.stop)) {
                say_err(&format!(
                    "warning: SIGUSR1 and SIGUSR2 will not stop the run: {e}"
                ));
            }
        }
    }
    request
}
