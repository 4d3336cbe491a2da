//! What the commands print, and the thread pool they run on.

use crate::failure::Failure;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mpdem::Warning;
use std::io::Write;
use std::path::Path;

/// Prints a line on standard output. A closed pipe (`| head`) drops it;
/// any other failure (a full disk) is an error.
pub fn say(line: &str) -> Result<(), Failure> {
    match writeln!(std::io::stdout(), "{line}") {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::Stdout(e)),
        _ => Ok(()),
    }
}

/// Prints a line on standard error; a failure there has nowhere to be
/// told, so it is dropped.
pub fn say_err(line: &str) {
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// Prints a warning about the scene `file` on standard error, as `check`
/// and `run` print each: the file, then what the warning says.
pub fn say_warning(file: &Path, warning: &Warning) {
    say_err(&format!("warning: {}: {warning}", file.display()));
}

/// A progress bar on stderr drawn with `template` (indicatif's), hidden
/// with `quiet`.
pub fn progress_bar(total: u64, quiet: bool, template: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let style =
        ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}

/// Runs `f` on a rayon pool of `threads` workers (default: rayon's, one
/// per core or `RAYON_NUM_THREADS`). The step runs on one of the pool's
/// threads: work handed to the pool from outside it goes through a shared
/// queue that allocates, work from inside does not.
pub fn with_threads(
    threads: Option<usize>,
    f: impl FnOnce() -> Result<(), Failure> + Send,
) -> Result<(), Failure> {
    // The main thread's usual stack, 8 MiB, for the scene parsing and
    // stepping that now run on a worker (rayon's default is 2 MiB).
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(8 << 20);
    match threads {
        None => {}
        Some(0) => return Err(Failure::NoThreads),
        Some(n) => pool = pool.num_threads(n),
    }
    pool.build()
        .map_err(|source| Failure::Threads { threads, source })?
        .install(f)
}
