//! Writing files so that a stop or a failure leaves no half-written one:
//! each is written under a temporary name beside it and renamed into
//! place; errors name the file.

use std::path::{Path, PathBuf};

/// The start of the temporary names files are written under before they
/// are renamed into place (see `RunOutput`): one left by a run killed while
/// writing is removed by the next run.
pub const PARTIAL_PREFIX: &str = ".partial-";

/// The temporary name `path` is written under before it is renamed into
/// place: in the same folder, [`PARTIAL_PREFIX`] before its name (so its
/// extension, which the PNG writer reads, is kept).
pub fn partial_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    path.with_file_name(format!("{PARTIAL_PREFIX}{}", name.unwrap_or_default()))
}

/// `e` with the file it concerns.
pub fn located(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}
