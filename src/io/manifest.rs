//! The list of files a run wrote into its output folder (`outputs.txt`), so
//! that a new run into the same folder removes the earlier run's files,
//! and only those: frames beyond the new run's last, plots of probes or
//! curves the new scene no longer has. Files a user put into the folder are
//! never touched: only a list whose first line is [`SIGNATURE`] is
//! followed (an `outputs.txt` of anything else is left alone), and only
//! the regular files it names inside the folder are removed.
//!
//! Each file is appended to the list before it is first written, so the
//! list is complete also after a run that was stopped or failed. The
//! checkpoint is not listed: a new run started without `--resume` by
//! mistake must not destroy the state an earlier run took hours to reach.

use crate::files::{PARTIAL_PREFIX, located};
use std::collections::BTreeSet;
use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Write};
use std::path::{Component, Path, PathBuf};

/// The list's file name in the output folder.
pub const MANIFEST_FILE: &str = "outputs.txt";

/// The list's first line, which marks it as mpdem's.
pub const SIGNATURE: &str =
    "# mpdem: the files this run wrote; a new run into this folder removes them";

/// The start of the list's second line, which names the scene file whose
/// run wrote the folder (absolute), when the run had one.
pub const SCENE_PREFIX: &str = "# scene: ";

/// The start of the list's second line for a run of a scene without a
/// file (built in code, from text or from a dict): the scene's name.
pub const SCENE_NAME_PREFIX: &str = "# scene without a file: ";

/// The scene a run is of, as the folder's list names it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneOrigin {
    /// A scene file (absolute path).
    File(PathBuf),
    /// A scene without a file, by its name.
    Named(String),
}

impl SceneOrigin {
    /// The origin of `scene`: its file `source` if it has one, else its name.
    pub fn of(scene: &crate::scene::Scene, source: Option<&Path>) -> Self {
        match source {
            Some(source) => Self::File(source.to_path_buf()),
            None => Self::Named(scene.display_name().to_owned()),
        }
    }
}

impl std::fmt::Display for SceneOrigin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::File(path) => write!(f, "{}", path.display()),
            Self::Named(name) => write!(f, "the scene '{name}' (built without a file)"),
        }
    }
}

/// The files of a run's output folder, relative to it, as written to
/// [`MANIFEST_FILE`].
pub struct OutputManifest {
    dir: PathBuf,
    listed: BTreeSet<String>,
    file: File,
}

impl OutputManifest {
    /// Starts a new run's list in `dir` (and in its `vtk/`): removes every
    /// regular file an earlier run's list names and every temporary file a
    /// killed run left, then starts the list anew, naming the scene the run
    /// is of (if given). Returns how many files were removed.
    pub fn start(dir: &Path, scene: Option<&SceneOrigin>) -> std::io::Result<(Self, usize)> {
        let mut doomed: Vec<PathBuf> = read_list(dir)?.iter().map(|n| dir.join(n)).collect();
        for folder in [dir.to_path_buf(), dir.join("vtk")] {
            let Ok(entries) = std::fs::read_dir(&folder) else {
                continue;
            };
            for entry in entries.flatten() {
                if entry
                    .file_name()
                    .to_string_lossy()
                    .starts_with(PARTIAL_PREFIX)
                {
                    doomed.push(entry.path());
                }
            }
        }
        let mut removed = 0;
        for path in doomed {
            let is_file = std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file());
            if !is_file {
                continue;
            }
            std::fs::remove_file(&path).map_err(|e| located(&path, e))?;
            removed += 1;
        }
        let path = dir.join(MANIFEST_FILE);
        let mut file = File::create(&path).map_err(|e| located(&path, e))?;
        writeln!(file, "{SIGNATURE}").map_err(|e| located(&path, e))?;
        let origin = match scene {
            Some(SceneOrigin::File(source)) => Some(format!("{SCENE_PREFIX}{}", source.display())),
            Some(SceneOrigin::Named(name)) => Some(format!("{SCENE_NAME_PREFIX}{name}")),
            None => None,
        };
        if let Some(line) = origin {
            writeln!(file, "{line}").map_err(|e| located(&path, e))?;
        }
        let manifest = Self {
            dir: dir.to_path_buf(),
            listed: BTreeSet::new(),
            file,
        };
        Ok((manifest, removed))
    }

    /// Carries on the list of a resumed run in `dir` (starting it, for a
    /// folder written before the list existed).
    pub fn resume(dir: &Path) -> std::io::Result<Self> {
        let listed: BTreeSet<String> = read_list(dir)?.into_iter().collect();
        let path = dir.join(MANIFEST_FILE);
        let mut file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| located(&path, e))?;
        let empty = file.metadata().map_err(|e| located(&path, e))?.len() == 0;
        if empty {
            writeln!(file, "{SIGNATURE}").map_err(|e| located(&path, e))?;
        }
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

/// The scene whose run wrote the folder `dir`, as its list names it: none
/// without a list or without that line (a folder of an earlier version).
pub fn written_by(dir: &Path) -> std::io::Result<Option<SceneOrigin>> {
    let path = dir.join(MANIFEST_FILE);
    let file = match File::open(&path) {
        Ok(file) => file,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(located(&path, e)),
    };
    let mut lines = BufReader::new(file).lines();
    if !matches!(lines.next(), Some(Ok(first)) if first == SIGNATURE) {
        return Ok(None);
    }
    Ok(match lines.next() {
        Some(Ok(line)) => {
            if let Some(source) = line.strip_prefix(SCENE_PREFIX) {
                Some(SceneOrigin::File(PathBuf::from(source)))
            } else {
                line.strip_prefix(SCENE_NAME_PREFIX)
                    .map(|name| SceneOrigin::Named(name.to_owned()))
            }
        }
        _ => None,
    })
}

/// The names an earlier run listed in `dir`: none without a list (or with
/// an empty one). A list that does not start with [`SIGNATURE`] is not
/// mpdem's: an error, so that it is neither followed nor overwritten. A line that is
/// not a plain path inside the folder (absolute, a drive or root prefix, or
/// climbing out of it with `..`) is skipped: the list may have been edited
/// by hand.
fn read_list(dir: &Path) -> std::io::Result<Vec<String>> {
    let path = dir.join(MANIFEST_FILE);
    let file = match File::open(&path) {
        Ok(file) => file,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(located(&path, e)),
    };
    let mut lines = BufReader::new(file).lines();
    match lines.next() {
        None => return Ok(Vec::new()),
        Some(Ok(first)) if first == SIGNATURE => {}
        Some(Ok(_)) => {
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!(
                    "{}: this file is not a list of mpdem's outputs, and a run would overwrite it: move it, or choose another output folder",
                    path.display()
                ),
            ));
        }
        Some(Err(e)) => return Err(located(&path, e)),
    }
    let mut names = Vec::new();
    for line in lines {
        let line = line.map_err(|e| located(&path, e))?;
        if line.starts_with('#') {
            continue;
        }
        let inside = Path::new(&line)
            .components()
            .all(|c| matches!(c, Component::Normal(_)));
        if !line.is_empty() && inside {
            names.push(line);
        }
    }
    Ok(names)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::partial_path;

    fn folder(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("mpdem-manifest-{tag}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(dir.join("vtk")).unwrap();
        dir
    }

    #[test]
    fn a_new_run_removes_the_files_the_last_run_listed_and_no_others() {
        let dir = folder("new");
        let (mut first, removed) = OutputManifest::start(&dir, None).unwrap();
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
        assert_eq!(list.lines().count(), 1 + 4, "each file listed once: {list}");
        // Temporary files a killed run left (a frame, the checkpoint), and a
        // folder named in the list.
        std::fs::write(dir.join("vtk/.partial-points_00003.vtu"), "half").unwrap();
        let checkpoint = partial_path(&dir.join("checkpoint.bin"));
        assert_eq!(checkpoint, dir.join(".partial-checkpoint.bin"));
        std::fs::write(&checkpoint, "half").unwrap();
        std::fs::create_dir(dir.join("kept")).unwrap();
        std::fs::write(dir.join("kept/inside.txt"), "the user's").unwrap();
        OutputManifest::resume(&dir)
            .unwrap()
            .record("kept")
            .unwrap();

        let (_, removed) = OutputManifest::start(&dir, None).unwrap();
        assert_eq!(removed, 6);
        assert!(!dir.join("vtk/.partial-points_00003.vtu").exists());
        assert!(!checkpoint.exists());
        assert!(
            dir.join("kept/inside.txt").is_file(),
            "a listed folder was touched"
        );
        assert!(
            dir.join("mine.csv").is_file(),
            "a file the run did not write was removed"
        );
        assert!(!dir.join("vtk/points_00001.vtu").exists());
        assert_eq!(
            std::fs::read_to_string(dir.join(MANIFEST_FILE)).unwrap(),
            format!("{SIGNATURE}\n")
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
            format!("{SIGNATURE}\n{escape}\n{}\n", outside.display()),
        )
        .unwrap();
        let (_, removed) = OutputManifest::start(&dir, None).unwrap();
        assert_eq!(removed, 0);
        assert!(outside.is_file());
        std::fs::remove_file(&outside).ok();
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_list_that_is_not_mpdems_is_neither_followed_nor_overwritten() {
        let dir = folder("foreign");
        let foreign = "thesis.tex\nfigures/plot.pdf\n";
        std::fs::write(dir.join(MANIFEST_FILE), foreign).unwrap();
        std::fs::write(dir.join("thesis.tex"), "the user's").unwrap();
        let refusal = OutputManifest::start(&dir, None)
            .err()
            .expect("a foreign list was taken over");
        assert!(
            refusal
                .to_string()
                .contains("not a list of mpdem's outputs"),
            "{refusal}"
        );
        assert!(OutputManifest::resume(&dir).is_err());
        assert!(dir.join("thesis.tex").is_file());
        assert_eq!(
            std::fs::read_to_string(dir.join(MANIFEST_FILE)).unwrap(),
            foreign
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
