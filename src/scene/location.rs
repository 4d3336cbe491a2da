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
    /// What the error is about, as searched for in the text: a section of
    /// the scene, an entry's quoted name, then field names (e.g.
    /// `["materials", "\"sand\"", "friction_angle"]`); empty when the
    /// error is about the text itself. It places the error in a scene
    /// that has no text, such as one built from a dictionary.
    pub anchors: Vec<String>,
}

impl SourceLocation {
    /// A position in a file.
    pub fn at(path: &Path, line: usize, col: usize) -> Self {
        Self {
            path: Some(path.to_path_buf()),
            line_col: Some((line, col)),
            anchors: Vec::new(),
        }
    }

    /// The place of `anchors` in a scene that has no text (see
    /// [`Self::anchors`]).
    pub fn unplaced(anchors: &[&str]) -> Self {
        Self {
            anchors: anchors.iter().map(|a| a.to_string()).collect(),
            ..Self::default()
        }
    }

    /// The position of the last of `anchors`, each searched for after the
    /// previous one (e.g. `["bodies", "\"column\"", "material"]`); when one
    /// is not found (a field left out), the last found before it, or the
    /// file alone when the first is not found. Comments are skipped; the
    /// first anchor is a section of the scene (a field of its outermost
    /// parentheses, not a field of the same name inside one); a quoted
    /// anchor after a section matches an entry's `name: "..."`, any other
    /// quoted anchor a string literal, and any other anchor a field name
    /// (an identifier followed by `:`). Columns count characters, as ron's
    /// do.
    pub fn find(source: &str, path: &Path, anchors: &[&str]) -> Self {
        let text = without_comments(source);
        let (mut from, mut scope) = (0, text.len());
        let mut found = None;
        for (k, anchor) in anchors.iter().enumerate() {
            let kind = match k {
                0 => Anchor::Section,
                _ if anchor.starts_with('"') && !anchors[k - 1].starts_with('"') => {
                    Anchor::EntryName
                }
                _ => Anchor::Any,
            };
            match find_anchor(&text[..scope], from, anchor, kind) {
                Some(at) => {
                    found = Some(at);
                    from = at + anchor.len();
                    // The next anchor lies inside this one's value, or, for
                    // a quoted name, in the entry it names; a repeated
                    // anchor (the k-th `name` of a list) among its siblings.
                    if anchors.get(k + 1) != Some(anchor) {
                        scope = value_end(&text, from, anchor.starts_with('"')).min(scope);
                    }
                }
                // A field left out (its default taken): the entry that
                // would hold it, if that was found.
                None => break,
            }
        }
        let line_col = found.map(|at| {
            let before = &source[..at];
            let line = before.matches('\n').count() + 1;
            let col = before[before.rfind('\n').map_or(0, |k| k + 1)..]
                .chars()
                .count()
                + 1;
            (line, col)
        });
        Self {
            path: Some(path.to_path_buf()),
            line_col,
            anchors: anchors.iter().map(|a| a.to_string()).collect(),
        }
    }
}

/// Where the field `field` of the scene's section `section` is written in
/// `source` (comments skipped): the byte ranges of its name and of its
/// value; `None` when either is not written.
pub(crate) fn section_field(
    source: &str,
    section: &str,
    field: &str,
) -> Option<(std::ops::Range<usize>, std::ops::Range<usize>)> {
    let text = without_comments(source);
    let at = find_anchor(&text, 0, section, Anchor::Section)? + section.len();
    let scope = value_end(&text, at, false);
    let name = find_anchor(&text[..scope], at, field, Anchor::Any)?;
    let colon = name + field.len() + text[name + field.len()..].find(':')?;
    let end = value_end(&text, colon + 1, false);
    let value = &text[colon + 1..end];
    let start = colon + 1 + (value.len() - value.trim_start().len());
    let end = colon + 1 + value.trim_end().len();
    Some((name..name + field.len(), start..end))
}

/// Which matches of an anchor count.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Anchor {
    /// A field of the scene's outermost parentheses.
    Section,
    /// The string value of a `name` field.
    EntryName,
    /// Any match.
    Any,
}

/// Byte offset of the first match of `anchor` at or after `from`: a string
/// literal (for `Anchor::EntryName` only the value of a `name` field), or a
/// field name as a whole identifier followed by optional white space and
/// `:` (for `Anchor::Section` only inside the outermost brackets, not
/// deeper).
fn find_anchor(text: &str, from: usize, anchor: &str, kind: Anchor) -> Option<usize> {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut start = from;
    while let Some(k) = text[start..].find(anchor) {
        let at = start + k;
        let end = at + anchor.len();
        let quoted = anchor.starts_with('"');
        let whole = if quoted {
            kind != Anchor::EntryName || {
                let before = text[..at].trim_end();
                before.strip_suffix(':').is_some_and(|b| {
                    b.trim_end().ends_with("name")
                        && !b.trim_end()[..b.trim_end().len() - 4]
                            .chars()
                            .next_back()
                            .is_some_and(is_ident)
                })
            }
        } else {
            let (depth, in_string) = depth_and_string(&text[..at]);
            !in_string
                && !text[..at].chars().next_back().is_some_and(is_ident)
                && text[end..].trim_start().starts_with(':')
                && (kind != Anchor::Section || depth == 1)
        };
        if whole {
            return Some(at);
        }
        start = end;
    }
    None
}

/// The bracket depth at the end of `text` (strings skipped), and whether
/// `text` ends inside a string literal.
fn depth_and_string(text: &str) -> (usize, bool) {
    let (mut depth, mut in_string, mut escaped) = (0usize, false, false);
    for b in text.bytes() {
        match (in_string, escaped, b) {
            (true, true, _) => escaped = false,
            (true, false, b'\\') => escaped = true,
            (_, false, b'"') => in_string = !in_string,
            (false, _, b'(' | b'[' | b'{') => depth += 1,
            (false, _, b')' | b']' | b'}') => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    (depth, in_string)
}

/// Where the value that begins at `from` ends (byte offset): at the first
/// `,` outside brackets and strings, or where the enclosing bracket closes;
/// with `whole_entry` (after a quoted name) only the latter, so the scope
/// is the rest of the entry the name is in.
fn value_end(text: &str, from: usize, whole_entry: bool) -> usize {
    let bytes = text.as_bytes();
    let (mut depth, mut in_string, mut k) = (0usize, false, from);
    while k < bytes.len() {
        match (in_string, bytes[k]) {
            (true, b'\\') => k += 1,
            (_, b'"') => in_string = !in_string,
            (false, b'(' | b'[' | b'{') => depth += 1,
            (false, b')' | b']' | b'}') => {
                if depth == 0 {
                    return k;
                }
                depth -= 1;
            }
            (false, b',') if depth == 0 && !whole_entry => return k,
            _ => {}
        }
        k += 1;
    }
    bytes.len()
}

/// `source` with every comment replaced by spaces (same byte offsets):
/// `// ...` to the end of the line and `/* ... */`, outside string literals.
fn without_comments(source: &str) -> String {
    let bytes = source.as_bytes();
    let mut out = bytes.to_vec();
    let mut k = 0;
    let mut in_string = false;
    while k < bytes.len() {
        match (in_string, bytes[k], bytes.get(k + 1)) {
            (true, b'\\', _) => k += 1,
            (_, b'"', _) => in_string = !in_string,
            (false, b'/', Some(b'/')) => {
                while k < bytes.len() && bytes[k] != b'\n' {
                    out[k] = b' ';
                    k += 1;
                }
                continue;
            }
            (false, b'/', Some(b'*')) => {
                while k < bytes.len() && !(bytes[k] == b'*' && bytes.get(k + 1) == Some(&b'/')) {
                    out[k] = b' ';
                    k += 1;
                }
                out[k..(k + 2).min(bytes.len())].fill(b' ');
                k += 2;
                continue;
            }
            _ => {}
        }
        k += 1;
    }
    // Only ASCII bytes were replaced by ASCII spaces, and whole comments at
    // that, so the text stays valid UTF-8.
    String::from_utf8(out).unwrap_or_else(|_| source.to_owned())
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchors_are_found_inside_their_parents_only() {
        let text = "Scene(\n  grid: (cells: (2, 2)),\n  stages: [(name: \"s\", edges: (left: Free))],\n  bodies: [(name: \"a\", material: \"m\"), (name: \"b\")],\n)";
        let path = Path::new("s.ron");
        // grid.edges is left out: the grid, not the stage's edges.
        let at = SourceLocation::find(text, path, &["grid", "edges", "left"]);
        assert_eq!(at.line_col, Some((2, 3)));
        // Body "b" has no material: its name, not body "a"'s material.
        let at = SourceLocation::find(text, path, &["bodies", "\"b\"", "material"]);
        assert_eq!(at.line_col, Some((4, 47)));
        let at = SourceLocation::find(text, path, &["bodies", "\"a\"", "material"]);
        assert_eq!(at.line_col, Some((4, 24)));
        // The second `name` of a list, among siblings.
        let at = SourceLocation::find(text, path, &["bodies", "name", "name"]);
        assert_eq!(at.line_col, Some((4, 41)));
    }

    #[test]
    fn anchors_skip_comments_and_match_whole_fields() {
        let text = "// cells: (1, 1) in a comment\nScene(\n  grid: (cells: (2, 2), xcells: 3),\n  /* cells: */ name: \"α cells\",\n)";
        let at = SourceLocation::find(text, Path::new("s.ron"), &["grid", "cells"]);
        assert_eq!(at.line_col, Some((3, 10)));
        let name = SourceLocation::find(text, Path::new("s.ron"), &["\"α cells\""]);
        assert_eq!(name.line_col, Some((4, 22)));
    }

    #[test]
    fn a_section_is_one_of_the_scenes_own_fields_outside_strings() {
        // A block's `contact:` law, and `grid:` inside the name, are not the
        // sections; a body's name matches as the value of its `name:` only.
        let text = "Scene(\n  name: Some(\"grid: coarse\"),\n  blocks: [(name: \"b\", contact: (friction: 0.5))],\n  bodies: [(name: \"x\", material: \"a\"), (name: \"a\", material: \"m\")],\n  contact: (iter_period: Some(0)),\n  grid: (cells: (2, 2)),\n)";
        let path = Path::new("s.ron");
        let at = SourceLocation::find(text, path, &["contact", "iter_period"]);
        assert_eq!(at.line_col, Some((5, 13)));
        let at = SourceLocation::find(text, path, &["grid", "cells"]);
        assert_eq!(at.line_col, Some((6, 10)));
        let at = SourceLocation::find(text, path, &["bodies", "\"a\"", "material"]);
        assert_eq!(at.line_col, Some((4, 52)));
    }
}
