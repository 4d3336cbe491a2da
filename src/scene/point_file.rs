//! Bodies from a list of points (DESIGN.md section 5): the CSV file that
//! `Shape::Points` names, e.g. the integration points of a mesh made with
//! another tool.
//!
//! The file has a header naming its columns, `x` and `y` (m) and optionally
//! `volume` (m² per metre of thickness), in any order and letter case, then
//! one point per line, values separated by commas; headers and values may be
//! double-quoted. Lines starting with `#` and blank lines
//! are skipped; spaces around values, a byte-order mark and CRLF line ends
//! are accepted. Parsed here rather than with the `csv` crate: numbers need
//! no quoting, and errors must give the line as an editor shows it, which
//! the crate's record positions do not after comments or CRLF ends.

use super::{Scene, SceneError, Shape, SourceLocation};
use crate::math::{DVec2, Real};
use crate::rules::echo;
use std::path::Path;

/// One point of a point list: its position and, when the file has a
/// `volume` column, its volume (otherwise the body's lattice volume,
/// (h / n)²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ListedPoint {
    /// Position (m).
    pub position: DVec2,
    /// Volume (m² per metre of thickness), > 0 when given.
    pub volume: Option<Real>,
    /// Its line in the point file (1-based), for messages; 0 when it has
    /// none (a lattice's point, or one listed in code).
    pub line: usize,
}

impl ListedPoint {
    /// " (line n)" for messages, or nothing for a point without a line.
    pub fn at_line(&self) -> String {
        if self.line > 0 {
            format!(" (line {})", self.line)
        } else {
            String::new()
        }
    }

    /// The point's volume and uGIMP domain half-size: a square of the listed
    /// area (half-size √V / 2), or the lattice's for the point spacing
    /// `spacing` (h / n).
    pub fn domain(&self, spacing: Real) -> (Real, DVec2) {
        match self.volume {
            Some(v) => (v, DVec2::splat(0.5 * v.sqrt())),
            None => (spacing * spacing, DVec2::splat(0.5 * spacing)),
        }
    }
}

/// Lower-left and upper-right corners of the box around the points'
/// domains ([`ListedPoint::domain`], `spacing` h / n).
pub fn domain_bounds(points: &[ListedPoint], spacing: Real) -> (DVec2, DVec2) {
    points.iter().fold(
        (
            DVec2::splat(Real::INFINITY),
            DVec2::splat(Real::NEG_INFINITY),
        ),
        |(lo, hi), p| {
            let half = p.domain(spacing).1;
            (lo.min(p.position - half), hi.max(p.position + half))
        },
    )
}

impl Scene {
    /// Reads the file of every `Points` body, relative to `folder` (the
    /// scene file's folder; [`Self::load`] and [`Self::parse`] do this). The
    /// error names the body, the file, its line and what was expected.
    pub fn read_point_files(&mut self, folder: &Path) -> Result<(), SceneError> {
        self.read_point_files_in(folder)
            .map_err(|(_, message)| SceneError::Invalid {
                location: SourceLocation::default(),
                message,
            })
    }

    /// [`Self::read_point_files`], the error with the body's name.
    pub(super) fn read_point_files_in(&mut self, folder: &Path) -> Result<(), (String, String)> {
        for body in &mut self.bodies {
            if let Shape::Points { file, points } = &mut body.shape {
                *points = read_point_file(&folder.join(&*file))
                    .map_err(|e| (body.name.clone(), format!("body '{}': {e}", body.name)))?;
            }
        }
        Ok(())
    }
}

/// Reads a point list. The error names the file, the line and what was
/// expected there.
pub fn read_point_file(path: &Path) -> Result<Vec<ListedPoint>, PointFileError> {
    let text = super::input_file::read_input(path).map_err(|source| PointFileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse_point_list(&text).map_err(|(line, problem)| PointFileError::Line {
        path: path.to_path_buf(),
        line,
        problem,
    })
}

/// Why a point list cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum PointFileError {
    /// The file cannot be read.
    #[error("{}: cannot read the point list: {source}", path.display())]
    Read {
        /// The file.
        path: std::path::PathBuf,
        /// What failed.
        source: std::io::Error,
    },
    /// A line is wrong.
    #[error("{}:{line}: {problem}", path.display())]
    Line {
        /// The file.
        path: std::path::PathBuf,
        /// The line's number.
        line: usize,
        /// What is wrong there.
        problem: PointListProblem,
    },
}

/// What is wrong on a line of a point list.
#[derive(Debug, thiserror::Error)]
pub enum PointListProblem {
    /// No header.
    #[error("the point list is empty; expected a header x,y or x,y,volume")]
    Empty,
    /// A column the list does not know.
    #[error("unknown column '{}' in the header; expected x, y and optionally volume", echo(.0))]
    UnknownColumn(String),
    /// A column named twice.
    #[error("the header names column '{}' twice", echo(.0))]
    TwiceNamed(String),
    /// No x or no y column.
    #[error(
        "the header must name the columns x and y (and optionally volume), got '{}'",
        echo(.0)
    )]
    NoPosition(String),
    /// A row with another count of values than the header.
    #[error("expected {expected} values ({columns}) as in the header, got {found}")]
    Values {
        /// The header's count.
        expected: usize,
        /// The header's columns.
        columns: String,
        /// The row's count.
        found: usize,
    },
    /// A value that is not a finite number.
    #[error("expected a finite number in column {column}, got '{}'", echo(value))]
    Number {
        /// The column.
        column: String,
        /// The value.
        value: String,
    },
    /// A position listed twice.
    #[error("the point at {at} is listed twice (first on line {first})")]
    Twice {
        /// The position.
        at: DVec2,
        /// The line of its first listing.
        first: usize,
    },
    /// A volume not positive.
    #[error("volume must be > 0, got {0}")]
    Volume(Real),
    /// A header without points.
    #[error("the point list has a header but no point")]
    NoPoint,
}

/// A CSV field without its surrounding spaces and double quotes.
fn unquoted(field: &str) -> &str {
    let field = field.trim();
    field
        .strip_prefix('"')
        .and_then(|f| f.strip_suffix('"'))
        .unwrap_or(field)
        .trim()
}

/// The columns a point list may have.
const COLUMNS: [&str; 3] = ["x", "y", "volume"];

/// Parses the text of a point list; an error comes with its line number.
fn parse_point_list(text: &str) -> Result<Vec<ListedPoint>, (usize, PointListProblem)> {
    let mut lines = text
        .trim_start_matches('\u{feff}')
        .lines()
        .enumerate()
        .map(|(k, line)| (k + 1, line.trim()))
        .filter(|(_, line)| !line.is_empty() && !line.starts_with('#'));
    let Some((header_line, header)) = lines.next() else {
        return Err((1, PointListProblem::Empty));
    };
    // Spreadsheets and meshers write `"X"` as readily as `x`.
    let names: Vec<String> = header
        .split(',')
        .map(|h| unquoted(h).to_ascii_lowercase())
        .collect();
    let column = |name: &str| names.iter().position(|h| h == name);
    for (k, name) in names.iter().enumerate() {
        if !COLUMNS.contains(&name.as_str()) {
            return Err((header_line, PointListProblem::UnknownColumn(name.clone())));
        }
        if names[..k].contains(name) {
            return Err((header_line, PointListProblem::TwiceNamed(name.clone())));
        }
    }
    let (Some(x), Some(y)) = (column("x"), column("y")) else {
        return Err((header_line, PointListProblem::NoPosition(header.to_owned())));
    };
    let volume = column("volume");
    let mut points = Vec::new();
    // Each position's first line: two points in one place would share a
    // domain twice over, and their contact disks would overlap fully.
    let mut placed = std::collections::HashMap::new();
    for (line, text) in lines {
        let values: Vec<&str> = text.split(',').map(unquoted).collect();
        if values.len() != names.len() {
            return Err((
                line,
                PointListProblem::Values {
                    expected: names.len(),
                    columns: names.join(", "),
                    found: values.len(),
                },
            ));
        }
        let number = |k: usize| -> Result<Real, (usize, PointListProblem)> {
            match values[k].parse::<Real>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err((
                    line,
                    PointListProblem::Number {
                        column: names[k].clone(),
                        value: values[k].to_owned(),
                    },
                )),
            }
        };
        let position = DVec2::new(number(x)?, number(y)?);
        // + 0.0 makes −0 and 0 one place.
        let key = ((position.x + 0.0).to_bits(), (position.y + 0.0).to_bits());
        if let Some(first) = placed.insert(key, line) {
            return Err((
                line,
                PointListProblem::Twice {
                    at: position,
                    first,
                },
            ));
        }
        let volume = match volume {
            Some(k) => {
                let v = number(k)?;
                if v <= 0.0 {
                    return Err((line, PointListProblem::Volume(v)));
                }
                Some(v)
            }
            None => None,
        };
        points.push(ListedPoint {
            position,
            volume,
            line,
        });
    }
    if points.is_empty() {
        return Err((header_line, PointListProblem::NoPoint));
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_and_values_may_be_quoted_and_capitalised() {
        let points = parse_point_list("\"X\", \"Y\"\n\"1.5\", 2\n").unwrap();
        assert_eq!(points[0].position, DVec2::new(1.5, 2.0));
    }

    #[test]
    fn a_point_listed_twice_is_refused_with_both_lines() {
        let (line, problem) = parse_point_list("x,y\n1,2\n3,4\n# again\n1.0,2.0\n").unwrap_err();
        let e = format!("{line}: {problem}");
        assert_eq!(
            e,
            "5: the point at [1, 2] is listed twice (first on line 2)"
        );
    }

    #[test]
    fn columns_in_any_order_with_comments_and_spaces() {
        let points = parse_point_list(
            "\u{feff}# from a mesher\nvolume, y, x\n0.5, 2.0, 1.0\n\n# done\n0.25,4,3\n",
        )
        .unwrap();
        assert_eq!(
            points,
            vec![
                ListedPoint {
                    position: DVec2::new(1.0, 2.0),
                    volume: Some(0.5),
                    line: 3,
                },
                ListedPoint {
                    position: DVec2::new(3.0, 4.0),
                    volume: Some(0.25),
                    line: 6,
                },
            ]
        );
        let bare = parse_point_list("x,y\r\n1,2\r\n").unwrap();
        assert_eq!(bare[0].volume, None);
    }

    #[test]
    fn errors_give_the_line_as_an_editor_shows_it() {
        let error = |text: &str| {
            let (line, problem) = parse_point_list(text).unwrap_err();
            format!("{line}: {problem}")
        };
        assert_eq!(
            error("x,y\n1,2\n1,two\n"),
            "3: expected a finite number in column y, got 'two'"
        );
        // Comments, blank lines and CRLF ends count as lines.
        assert!(error("# c\nx,y\n1,2\n\n# c\n1,two\n").starts_with("6: "));
        assert!(error("x,y\r\n1,2\r\n1,two\r\n").starts_with("3: "));
        assert_eq!(
            error("x,y\n1,2\n3\n"),
            "3: expected 2 values (x, y) as in the header, got 1"
        );
        assert!(error("# c\nx,z\n1,2\n").starts_with("2: unknown column 'z'"));
        assert!(error("x,x,y\n1,2,3\n").contains("names column 'x' twice"));
        assert!(error("x,volume\n1,2\n").contains("x and y"));
        assert!(error("x,y\n").contains("no point"));
        assert!(error("").contains("empty"));
        assert!(error("x,y,volume\n1,2,0\n").starts_with("2: volume must be > 0"));
        assert!(error("x,y\n1,inf\n").contains("finite"));
    }
}
