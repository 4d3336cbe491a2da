//! Positions in a scene file for error messages.

use std::fmt;
use std::path::{Path, PathBuf};

/// Where an error is: file, line and column (1-based), or only the file, or
/// nothing for a scene built in code.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SourceLocation {
    /// The scene file, if the scene came from one.
    pub path: Option<PathBuf>,
    /// Line and column, if known.
    pub line_col: Option<(usize, usize)>,
}

impl SourceLocation {
    /// A position in a file.
    pub fn at(path: &Path, line: usize, col: usize) -> Self {
        Self {
            path: Some(path.to_path_buf()),
            line_col: Some((line, col)),
        }
    }

    /// The position of the first match of the last of `anchors` found by
    /// searching for each anchor after the previous one (e.g. `["bodies",
    /// "\"column\"", "material"]`); the file alone when they are not found.
    pub fn find(source: &str, path: &Path, anchors: &[&str]) -> Self {
        let mut offset = 0;
        let mut found = None;
        for anchor in anchors {
            match source[offset..].find(anchor) {
                Some(k) => {
                    found = Some(offset + k);
                    offset += k + anchor.len();
                }
                None => {
                    return Self {
                        path: Some(path.to_path_buf()),
                        line_col: None,
                    };
                }
            }
        }
        let line_col = found.map(|at| {
            let before = &source[..at];
            let line = before.matches('\n').count() + 1;
            let col = before.len() - before.rfind('\n').map_or(0, |k| k + 1) + 1;
            (line, col)
        });
        Self {
            path: Some(path.to_path_buf()),
            line_col,
        }
    }
}

impl fmt::Display for SourceLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.path, self.line_col) {
            (Some(p), Some((line, col))) => write!(f, "{}:{line}:{col}", p.display()),
            (Some(p), None) => write!(f, "{}", p.display()),
            (None, _) => write!(f, "scene"),
        }
    }
}
