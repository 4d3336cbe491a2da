//! Why a command did not succeed.

use mpdem::StepError;
use mpdem::runner::RunError;
use mpdem::scene::SceneError;
use mpdem_verify::{CASES, Tally};
use std::path::PathBuf;

/// Why a command did not succeed.
#[derive(Debug, thiserror::Error)]
pub enum Failure {
    /// Writing to standard output failed (not a closed pipe).
    #[error("cannot write to standard output: {0}")]
    Stdout(std::io::Error),
    /// `--threads` out of range, or the threads could not be started.
    #[error("--threads: {0}")]
    Threads(#[from] mpdem::threads::ThreadsError),
    /// A scene could not be read or built.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A step failed.
    #[error(transparent)]
    Step(#[from] StepError),
    /// A run failed, or stopped on request with its results written.
    #[error(transparent)]
    Run(#[from] RunError),
    /// Of several scenes checked, some were refused (each told before).
    #[error("{refused} of {checked} scenes refused")]
    Refused {
        /// How many were refused.
        refused: usize,
        /// How many were checked.
        checked: usize,
    },
    /// `mpdem verify` was asked for a case it does not have.
    #[error("no case '{name}'; the cases are {}", CASES.iter().map(|c| c.name).collect::<Vec<_>>().join(", "))]
    UnknownCase {
        /// The name asked for.
        name: String,
    },
    /// No scenes folder where `verify` looks.
    #[error("no scenes folder at {}: run from the repository's root or pass --scenes", .0.display())]
    NoScenes(PathBuf),
    /// The verify table could not be written.
    #[error("{}: cannot write the table: {source}", path.display())]
    VerifyTable {
        /// The table.
        path: PathBuf,
        /// What failed.
        source: std::io::Error,
    },
    /// The verify report could not be written.
    #[error("cannot write the report: {0}")]
    Report(#[from] mpdem_verify::report::ReportError),
    /// Verify cases missed their targets or could not be run.
    #[error("{}", .0.problems())]
    Verify(Tally),
}
