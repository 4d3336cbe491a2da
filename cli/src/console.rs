//! What the commands print, and the thread pool they run on.

use crate::failure::Failure;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mpdem::Warning;
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether this process prints nothing: a rank of an MPI job other than
/// the first.
static SILENT: AtomicBool = AtomicBool::new(false);

/// Makes this process print nothing from here on.
pub fn silence() {
    SILENT.store(true, Ordering::Relaxed);
}

/// Whether this process prints nothing (see [`silence`]).
pub fn silent() -> bool {
    SILENT.load(Ordering::Relaxed)
}

/// Prints a line on standard output. A closed pipe (`| head`) drops it;
/// any other failure (a full disk) is an error.
pub fn say(line: &str) -> Result<(), Failure> {
    if silent() {
        return Ok(());
    }
    match writeln!(std::io::stdout(), "{line}") {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::Stdout(e)),
        _ => Ok(()),
    }
}

/// Prints a line on standard error, made [`printable`]; a failure there
/// has nowhere to be told, so it is dropped.
pub fn say_err(line: &str) {
    if silent() {
        return;
    }
    let _ = writeln!(std::io::stderr(), "{}", printable(line));
}

/// Longest word of a message printed whole (characters): longer ones are
/// echoed input (a name, a line of a file) and are cut.
const LONGEST_WORD: usize = 200;

/// Characters of a cut word that are kept.
const CUT_WORD_KEEPS: usize = 80;

/// `line` safe for a terminal and readable: control characters but line
/// breaks escaped (`\u{1b}`, `\t`), so that input echoed in a message
/// cannot move the cursor or colour the terminal, and words longer than
/// [`LONGEST_WORD`] cut to their first [`CUT_WORD_KEEPS`] characters with
/// their length.
pub fn printable(line: &str) -> String {
    let mut out = String::with_capacity(line.len().min(4096));
    for (k, word) in line.split(' ').enumerate() {
        if k > 0 {
            out.push(' ');
        }
        let length = word.chars().count();
        let kept = if length > LONGEST_WORD {
            CUT_WORD_KEEPS
        } else {
            length
        };
        for c in word.chars().take(kept) {
            if c.is_control() && c != '\n' {
                out.extend(c.escape_default());
            } else {
                out.push(c);
            }
        }
        if kept < length {
            out.push_str(&format!("… ({length} characters)"));
        }
    }
    out
}

/// Prints a warning about the scene `file` on standard error, as `check`
/// and `run` print each: the file, then what the warning says.
pub fn say_warning(file: &Path, warning: &Warning) {
    say_err(&format!("warning: {}: {warning}", file.display()));
}

/// A progress bar on stderr drawn with `template` (indicatif's), hidden
/// with `quiet`.
pub fn progress_bar(total: u64, quiet: bool, template: &str) -> ProgressBar {
    if quiet || silent() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let style =
        ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}

/// Runs `f` on a pool of `threads` workers ([`mpdem::threads::worker_pool`]).
/// The step runs on one of the pool's threads: work handed to the pool
/// from outside it goes through a shared queue that allocates, work from
/// inside does not.
pub fn with_threads(
    threads: Option<usize>,
    f: impl FnOnce() -> Result<(), Failure> + Send,
) -> Result<(), Failure> {
    mpdem::threads::worker_pool(threads)?.install(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn echoed_input_is_escaped_and_cut() {
        assert_eq!(
            printable("body 'a\u{1b}[31mred' at\tx"),
            "body 'a\\u{1b}[31mred' at\\tx"
        );
        let long = format!("name '{}'", "x".repeat(1000));
        let shown = printable(&long);
        assert!(shown.ends_with("… (1002 characters)"), "{shown}");
        assert_eq!(
            shown.chars().count(),
            5 + 80 + "… (1002 characters)".chars().count()
        );
        assert_eq!(printable("two\nlines"), "two\nlines");
    }
}
