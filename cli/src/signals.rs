//! Stop signals: the first one asks the run to stop after its step and
//! write its results; a later one ends the process at once.

use crate::STOPPED_STATUS;
use crate::console::say_err;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How long after a stop signal another one counts as the same request:
/// `timeout` and job control send a signal to the process and to its
/// group at once, so one request can arrive twice within microseconds.
const SIGNAL_REPEAT_WINDOW: Duration = Duration::from_secs(1);

/// A flag the first Ctrl-C, SIGTERM or SIGHUP raises, so that the run
/// stops after its step and writes its results (and a checkpoint, if it
/// writes them); another one, [`SIGNAL_REPEAT_WINDOW`] or more after the
/// first, ends the process at once.
pub fn stop_on_signals() -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let mut first: Option<Instant> = None;
    let handler = ctrlc::set_handler(move || {
        flag.store(true, Ordering::SeqCst);
        match first {
            None => {
                first = Some(Instant::now());
                say_err(
                    "stop requested: the run stops after its step and writes its results (another stop signal a second or more from now ends it at once, without them)",
                );
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
    stop
}
