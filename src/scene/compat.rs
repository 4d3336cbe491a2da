//! Scene files written for earlier releases of the format. Their old
//! spellings are rewritten to the present ones before the file is parsed,
//! each with a warning that gives the new spelling; line numbers are kept,
//! so messages still point into the file as written. A renamed field or
//! value stays readable this way for at least one release after its
//! rename (`CHANGELOG.md` names each).

use super::location::section_field;
use crate::warning::{Warning, WarningKind};
use std::ops::Range;

/// The text of a scene file in the present spelling, and a warning for
/// each old spelling it held; `None` when it holds none.
pub(crate) fn present_spelling(source: &str) -> Option<(String, Vec<Warning>)> {
    let mut edits: Vec<(Range<usize>, &str)> = Vec::new();
    let mut warnings = Vec::new();
    if let Some((name, _)) = section_field(source, "settings", "damping") {
        edits.push((name, "grid_damping"));
        warnings.push(renamed(
            "settings.damping",
            "settings.damping",
            "settings.grid_damping",
        ));
    }
    if let Some((_, value)) = section_field(source, "settings", "position_update") {
        let value_of = |field| section_field(source, "settings", field).map(|(_, v)| v);
        let written = |range: &Option<Range<usize>>| range.clone().map(|r| &source[r]);
        let scheme = value_of("scheme");
        let xpic = value_of("xpic_order");
        let under_xpic = written(&xpic).is_some_and(|v| v != "None");
        let present = match &source[value.clone()] {
            // With USL this pair was the modified USL, now a scheme of its own.
            "Remapped" if written(&scheme) == Some("Usl") => {
                if let Some(scheme) = scheme {
                    edits.push((scheme, "Musl"));
                }
                warnings.push(renamed(
                    "settings.scheme",
                    "settings: (scheme: Usl, position_update: Remapped)",
                    "settings: (scheme: Musl, position_update: Some(RemappedVelocity))",
                ));
                Some("Some(RemappedVelocity)")
            }
            "Remapped" => Some("Some(RemappedVelocity)"),
            "Forward" => Some("Some(NewGridVelocity)"),
            // XPIC moves the points its own way (eq. 12b), which was the
            // default's meaning under it.
            "Midpoint" if under_xpic => Some("None"),
            "Midpoint" => Some("Some(PaperEq11b)"),
            _ => None,
        };
        if let Some(present) = present {
            let old = format!("settings.position_update: {}", &source[value.clone()]);
            if !warnings.iter().any(|w| w.field == "settings.scheme") {
                warnings.push(renamed(
                    "settings.position_update",
                    &old,
                    &format!("settings.position_update: {present}"),
                ));
            }
            edits.push((value, present));
        }
    }
    if edits.is_empty() {
        return None;
    }
    edits.sort_by_key(|(range, _)| std::cmp::Reverse(range.start));
    let mut text = source.to_string();
    for (range, present) in edits {
        text.replace_range(range, present);
    }
    Some((text, warnings))
}

/// The warning for an old spelling read as its present one, about the
/// field `field`.
fn renamed(field: &str, old: &str, present: &str) -> Warning {
    Warning::new(
        WarningKind::OldSpelling,
        field,
        format!(
            "`{old}` is the spelling of an earlier release, read as `{present}`; write the present spelling, as a later release may no longer read the old one"
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn old_spellings_are_rewritten_and_comments_left_alone() {
        let old = "Scene(\n  // damping: 0.5 was the old name\n  settings: (damping: 0.1, position_update: Forward),\n)";
        let (text, warnings) = present_spelling(old).expect("rewritten");
        assert_eq!(
            text,
            "Scene(\n  // damping: 0.5 was the old name\n  settings: (grid_damping: 0.1, position_update: Some(NewGridVelocity)),\n)"
        );
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        assert_eq!(
            (warnings[0].kind, warnings[0].field.as_str()),
            (WarningKind::OldSpelling, "settings.damping")
        );
        assert!(warnings[0].message.contains("`settings.grid_damping`"));
        assert_eq!(warnings[1].field, "settings.position_update");
        assert!(
            warnings[1]
                .message
                .contains("`settings.position_update: Some(NewGridVelocity)`")
        );
    }

    #[test]
    fn usl_with_remapped_positions_is_the_modified_usl() {
        let old = "Scene(settings: (scheme: Usl, position_update: Remapped))";
        let (text, warnings) = present_spelling(old).expect("rewritten");
        assert_eq!(
            text,
            "Scene(settings: (scheme: Musl, position_update: Some(RemappedVelocity)))"
        );
        assert_eq!(warnings.len(), 1, "{warnings:?}");
    }

    #[test]
    fn the_midpoint_update_under_xpic_is_xpics_own() {
        let old = "Scene(settings: (xpic_order: Some(2), position_update: Midpoint))";
        let (text, _) = present_spelling(old).expect("rewritten");
        assert_eq!(
            text,
            "Scene(settings: (xpic_order: Some(2), position_update: None))"
        );
    }

    #[test]
    fn the_present_spelling_is_left_as_it_is() {
        let present = "Scene(settings: (grid_damping: 0.1, particle_damping: 0.2, position_update: Some(PaperEq11b)), blocks: [(contact: (normal_damping: 1.0))])";
        assert_eq!(present_spelling(present), None);
    }
}
