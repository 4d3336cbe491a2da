//! Consistency checks of a whole scene: ranges, names and geometry, one
//! file per section of the scene.

mod blocks;
mod bodies;
mod contacts;
mod grid;
mod materials;
mod outputs;
mod settings;
mod stages;
mod time;

use super::{Scene, SceneError, SourceLocation};
use crate::rules;
use std::path::Path;

/// Where a validation error is: the scene's text and file, if it came from
/// one.
struct Locator<'t> {
    source: Option<(&'t str, &'t Path)>,
}

impl<'t> Locator<'t> {
    /// What makes the errors of the entry of `section` named `name` (its
    /// path typed once): given a field of the entry and the detail, the
    /// error at that field whose message starts `{label} '{name}': `.
    fn entry<'a>(
        &'a self,
        section: &'static str,
        label: &'static str,
        name: &'a str,
    ) -> impl Fn(&str, String) -> SceneError + 'a {
        let anchor = quoted(name);
        move |field, detail| {
            self.invalid(
                &[section, &anchor, field],
                format!("{label} '{name}': {detail}"),
            )
        }
    }

    /// The error `detail` about the field at `path` (a section and its
    /// fields, e.g. `["time", "dt"]`): the message names the field as
    /// `time.dt: {detail}`, and the location is the field's in the text.
    fn field(&self, path: &[&str], detail: impl std::fmt::Display) -> SceneError {
        self.invalid(path, format!("{}: {detail}", path.join(".")))
    }

    /// The error `message` at the last of `anchors` found in the text (see
    /// [`SourceLocation::find`]).
    fn invalid(&self, anchors: &[&str], message: String) -> SceneError {
        SceneError::Invalid {
            location: match self.source {
                Some((text, path)) => SourceLocation::find(text, path, anchors),
                None => SourceLocation::unplaced(anchors),
            },
            message,
        }
    }
}

/// Longest name an entry may have (bytes): a file name's limit, as names
/// name output files and are echoed in messages.
const NAME_MAX_BYTES: usize = 255;

/// What is wrong with an entry's name, without echoing it: empty, too
/// long, or holding control characters (which would garble messages and
/// terminals).
fn name_problem(name: &str) -> Option<String> {
    if name.trim().is_empty() {
        Some("has an empty name".into())
    } else if name.len() > NAME_MAX_BYTES {
        Some(format!(
            "has a name {} bytes long; names are at most {NAME_MAX_BYTES}",
            name.len()
        ))
    } else if name.chars().any(char::is_control) {
        Some("has a name holding control characters (a newline, a tab, an escape); names are printable text".into())
    } else {
        None
    }
}

/// A name as the quoted string that anchors its entry.
fn quoted(name: &str) -> String {
    format!("\"{name}\"")
}

/// The `name` field of entry k of a section (each entry has one), for a
/// name used twice: the place of its second use.
fn nth_name(section: &'static str, k: usize) -> Vec<&'static str> {
    std::iter::once(section)
        .chain(std::iter::repeat_n("name", k + 1))
        .collect()
}

impl Scene {
    /// Validates; `source` (text and path) lets errors point into the file.
    pub(super) fn validate_in(&self, source: Option<(&str, &Path)>) -> Result<(), SceneError> {
        let v = Locator { source };
        self.check_name(&v)?;
        self.check_entry_names(&v)?;
        self.check_grid(&v)?;
        self.check_time(&v)?;
        self.check_settings(&v)?;
        let materials = self.check_materials(&v)?;
        let bodies = self.check_bodies(&v, &materials)?;
        let blocks = self.check_blocks(&v)?;
        self.check_contact(&v)?;
        self.check_probes_and_output(&v, &bodies, &blocks)?;
        self.check_body_contacts(&v, &bodies)?;
        self.check_block_contacts(&v, &bodies, &blocks)?;
        self.check_stages(&v, &bodies, &blocks)?;
        Ok(())
    }

    /// The scene's name, which names the output folder.
    fn check_name(&self, v: &Locator) -> Result<(), SceneError> {
        if let Some(name) = &self.name {
            if name.len() > rules::FILE_NAME_MAX_BYTES {
                return Err(v.field(&["name"], format!("{} bytes long, past the {} that file systems allow in a folder's name (the output folder is out/<name>): shorten it",
                        name.len(),
                        rules::FILE_NAME_MAX_BYTES
                    ),
                ));
            }
            rules::file_name(name).map_err(|e| {
                v.field(&["name"], format!("{e} (the output folder is out/<name>)"))
            })?;
        }
        Ok(())
    }

    /// Every named entry has a name: the messages, the outputs and the
    /// entries that refer to one another go by it.
    fn check_entry_names(&self, v: &Locator) -> Result<(), SceneError> {
        let sections: [(&'static str, Vec<&str>); 5] = [
            (
                "materials",
                self.materials.iter().map(|m| m.name.as_str()).collect(),
            ),
            (
                "bodies",
                self.bodies.iter().map(|b| b.name.as_str()).collect(),
            ),
            (
                "blocks",
                self.blocks.iter().map(|b| b.name.as_str()).collect(),
            ),
            (
                "probes",
                self.probes.iter().map(|p| p.name.as_str()).collect(),
            ),
            (
                "stages",
                self.stages.iter().map(|s| s.name.as_str()).collect(),
            ),
        ];
        for (section, names) in sections {
            for (k, name) in names.iter().enumerate() {
                if let Some(problem) = name_problem(name) {
                    return Err(v.invalid(
                        &nth_name(section, k),
                        format!("{section}: entry {} {problem}", k + 1),
                    ));
                }
            }
        }
        for (k, body) in self.bodies.iter().enumerate() {
            if let Some(problem) = body.group.as_deref().and_then(name_problem) {
                return Err(v.invalid(
                    &["bodies", &quoted(&body.name), "group"],
                    format!("bodies: entry {}: the contact group {problem}", k + 1),
                ));
            }
        }
        Ok(())
    }
}
