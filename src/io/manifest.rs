//! The list of files a run wrote into its output folder (`outputs.txt`), so
//! that a new run into the same folder removes the earlier run's files,
//! and only those: frames beyond the new run's last, plots of probes or
//! curves the new scene no longer has, a checkpoint of another run. Files a
//! user put into the folder are never touched.
//!
//! Each file is appended to the list before it is first written, so the
//! list is complete also after a run that was stopped or failed.

use std::collections::BTreeSet;
use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Write};
use std::path::{Component, Path, PathBuf};

/// The list's file name in the output folder.
pub const MANIFEST_FILE: &str = "outputs.txt";

/// The files of a run's output folder, relative to it, as written to
/// [`MANIFEST_FILE`].
pub struct OutputManifest {
    dir: PathBuf,
    listed: BTreeSet<String>,
    file: File,
}

impl OutputManifest {
    /// Starts a new run's list in `dir`: removes every file an earlier
    /// run's list names (and the list), and returns how many were removed.
    pub fn start(dir: &Path) -> std::io::Result<(Self, usize)> {
        let mut removed = 0;
        for name in read_list(dir)? {
            match std::fs::remove_file(dir.join(&name)) {
                Ok(()) => removed += 1,
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => return Err(located(&dir.join(&name), e)),
            }
        }
        let path = dir.join(MANIFEST_FILE);
        let file = File::create(&path).map_err(|e| located(&path, e))?;
        let manifest = Self {
            dir: dir.to_path_buf(),
            listed: BTreeSet::new(),
            file,
        };
        Ok((manifest, removed))
    }

    /// Carries on the list of a resumed run in `dir`.
    pub fn resume(dir: &Path) -> std::io::Result<Self> {
        let listed = read_list(dir)?.into_iter().collect();
        let path = dir.join(MANIFEST_FILE);
        let file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| located(&path, e))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            listed,
            file,
        })
    }

    /// Adds `relative` (a path inside the folder, `/`-separated) to the list
    /// unless it is there already; call before writing the file.
    pub fn record(&mut self, relative: &str) -> std::io::Result<()> {
        if self.listed.insert(relative.to_string()) {
            writeln!(self.file, "{relative}")
                .and_then(|()| self.file.flush())
                .map_err(|e| located(&self.dir.join(MANIFEST_FILE), e))?;
        }
        Ok(())
    }
}

/// The names an earlier run listed in `dir` (none without a list). A line
/// that is not a plain path inside the folder (absolute, or climbing out of
/// it with `..`) is skipped: the list may have been edited by hand.
fn read_list(dir: &Path) -> std::io::Result<Vec<String>> {
    let path = dir.join(MANIFEST_FILE);
    let file = match File::open(&path) {
        Ok(file) => file,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(located(&path, e)),
    };
    let mut names = Vec::new();
    for line in BufReader::new(file).lines() {
        let line = line.map_err(|e| located(&path, e))?;
        let inside = Path::new(&line)
            .components()
            .all(|c| matches!(c, Component::Normal(_)));
        if !line.is_empty() && inside {
            names.push(line);
        }
    }
    Ok(names)
}

/// `e` with the file it concerns.
pub fn located(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("mpdem-manifest-{tag}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(dir.join("vtk")).unwrap();
        dir
    }

    #[test]
    fn a_new_run_removes_the_files_the_last_run_listed_and_no_others() {
        let dir = folder("new");
        let (mut first, removed) = OutputManifest::start(&dir).unwrap();
        assert_eq!(removed, 0);
        for name in ["energy.csv", "vtk/points_00000.vtu", "vtk/points_00001.vtu"] {
            first.record(name).unwrap();
            std::fs::write(dir.join(name), "x").unwrap();
        }
        first.record("energy.csv").unwrap();
        std::fs::write(dir.join("mine.csv"), "the user's").unwrap();
        drop(first);

        let mut resumed = OutputManifest::resume(&dir).unwrap();
        resumed.record("vtk/points_00001.vtu").unwrap();
        resumed.record("vtk/points_00002.vtu").unwrap();
        std::fs::write(dir.join("vtk/points_00002.vtu"), "x").unwrap();
        drop(resumed);
        let list = std::fs::read_to_string(dir.join(MANIFEST_FILE)).unwrap();
        assert_eq!(list.lines().count(), 4, "each file listed once: {list}");

        let (_, removed) = OutputManifest::start(&dir).unwrap();
        assert_eq!(removed, 4);
        assert!(
            dir.join("mine.csv").is_file(),
            "a file the run did not write was removed"
        );
        assert!(!dir.join("vtk/points_00001.vtu").exists());
        assert_eq!(
            std::fs::read_to_string(dir.join(MANIFEST_FILE)).unwrap(),
            ""
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn lines_that_leave_the_folder_are_not_followed() {
        let dir = folder("outside");
        let outside = dir.with_extension("keep");
        std::fs::write(&outside, "keep").unwrap();
        let escape = format!("../{}", outside.file_name().unwrap().to_string_lossy());
        std::fs::write(
            dir.join(MANIFEST_FILE),
            format!("{escape}\n{}\n", outside.display()),
        )
        .unwrap();
        let (_, removed) = OutputManifest::start(&dir).unwrap();
        assert_eq!(removed, 0);
        assert!(outside.is_file());
        std::fs::remove_file(&outside).ok();
        std::fs::remove_dir_all(&dir).ok();
    }
}
