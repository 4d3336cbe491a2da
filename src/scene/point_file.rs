//! Bodies from a list of points (DESIGN.md section 5): the CSV file that
//! `Shape::Points` names, e.g. the integration points of a mesh made with
//! another tool.
//!
//! The file has a header naming its columns, `x` and `y` (m) and optionally
//! `volume` (m² per metre of thickness), in any order, then one point per
//! line. Lines starting with `#` are comments; spaces around values are
//! ignored.

use crate::math::{DVec2, Real};
use std::path::Path;

/// One point of a point list: its position and, when the file gives one,
/// its volume (otherwise the body's lattice volume, (h / n)²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ListedPoint {
    /// Position (m).
    pub position: DVec2,
    /// Volume (m² per metre of thickness), > 0 when given.
    pub volume: Option<Real>,
}

/// Reads a point list. The error names the file, the line and what was
/// expected there.
pub fn read_point_file(path: &Path) -> Result<Vec<ListedPoint>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the point list: {e}", path.display()))?;
    parse_point_list(&text).map_err(|e| format!("{}:{e}", path.display()))
}

/// Parses the text of a point list; errors start with the line number.
fn parse_point_list(text: &str) -> Result<Vec<ListedPoint>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| format!("{}: {e}", line_of(e.position())))?
        .clone();
    let column = |name: &str| header.iter().position(|h| h == name);
    if let Some(unknown) = header.iter().find(|h| !["x", "y", "volume"].contains(h)) {
        return Err(format!(
            "1: unknown column '{unknown}' in the header; expected x, y and optionally volume"
        ));
    }
    let (Some(x), Some(y)) = (column("x"), column("y")) else {
        return Err(format!(
            "1: the header must name the columns x and y (and optionally volume), got '{}'",
            header.iter().collect::<Vec<_>>().join(",")
        ));
    };
    let volume = column("volume");
    let mut points = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| format!("{}: {e}", line_of(e.position())))?;
        let line = record.position().map_or(0, csv::Position::line);
        let number = |k: usize, name: &str| -> Result<Real, String> {
            let field = record.get(k).unwrap_or_default();
            match field.parse::<Real>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(format!(
                    "{line}: expected a finite number in column {name}, got '{field}'"
                )),
            }
        };
        let position = DVec2::new(number(x, "x")?, number(y, "y")?);
        let volume = match volume {
            Some(k) => {
                let v = number(k, "volume")?;
                if v <= 0.0 {
                    return Err(format!("{line}: volume must be > 0, got {v}"));
                }
                Some(v)
            }
            None => None,
        };
        points.push(ListedPoint { position, volume });
    }
    if points.is_empty() {
        return Err("1: the point list has a header but no point".into());
    }
    Ok(points)
}

/// The line of a CSV error, or "?" when the reader gives none.
fn line_of(position: Option<&csv::Position>) -> String {
    position.map_or_else(|| "?".into(), |p| p.line().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_in_any_order_with_comments_and_spaces() {
        let points =
            parse_point_list("# from a mesher\nvolume, y, x\n0.5, 2.0, 1.0\n# done\n0.25,4,3\n")
                .unwrap();
        assert_eq!(
            points,
            vec![
                ListedPoint {
                    position: DVec2::new(1.0, 2.0),
                    volume: Some(0.5)
                },
                ListedPoint {
                    position: DVec2::new(3.0, 4.0),
                    volume: Some(0.25)
                },
            ]
        );
        let bare = parse_point_list("x,y\n1,2\n").unwrap();
        assert_eq!(bare[0].volume, None);
    }

    #[test]
    fn errors_give_the_line_and_what_was_expected() {
        let bad_number = parse_point_list("x,y\n1,2\n1,two\n").unwrap_err();
        assert_eq!(
            bad_number,
            "3: expected a finite number in column y, got 'two'"
        );
        let missing = parse_point_list("x,y\n1,2\n3\n").unwrap_err();
        assert!(missing.starts_with("3: "), "{missing}");
        assert!(
            parse_point_list("x,z\n1,2\n")
                .unwrap_err()
                .contains("unknown column 'z'")
        );
        assert!(
            parse_point_list("x,volume\n1,2\n")
                .unwrap_err()
                .contains("x and y")
        );
        assert!(parse_point_list("x,y\n").unwrap_err().contains("no point"));
        assert!(
            parse_point_list("x,y,volume\n1,2,0\n")
                .unwrap_err()
                .contains("2: volume must be > 0")
        );
        assert!(
            parse_point_list("x,y\n1,inf\n")
                .unwrap_err()
                .contains("finite")
        );
    }
}
