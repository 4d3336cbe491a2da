//! The probes and the outputs.

use super::{Locator, nth_name, quoted};
use crate::rules;
use crate::scene::{
    PROBE_PLOT_LONGEST_SUFFIX, PROBE_PLOT_PREFIX, RUN_FILE_STEMS, Scene, SceneError,
};
use std::collections::{BTreeMap, BTreeSet};

impl Scene {
    /// The probes and the output intervals and curves.
    pub(super) fn check_probes_and_output<'s>(
        &'s self,
        v: &Locator,
        body_names: &BTreeSet<&'s str>,
        block_names: &BTreeSet<&'s str>,
    ) -> Result<(), SceneError> {
        if self.output.fronts && self.bodies.is_empty() {
            return Err(v.field(
                &["output", "fronts"],
                "the scene has no body whose front to follow; leave fronts out",
            ));
        }
        let mut probe_names = BTreeSet::new();
        let mut probe_files = BTreeMap::new();
        for (k, p) in self.probes.iter().enumerate() {
            let at = ["probes", &quoted(&p.name)];
            let fail = v.entry("probes", "probe", &p.name);
            if !probe_names.insert(p.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("probes", k),
                    format!("probe name '{}' is used twice", p.name),
                ));
            }
            // Compared without case: macOS and Windows file systems ignore it.
            let file = rules::file_safe(&p.name).to_ascii_lowercase();
            if let Some(other) = probe_files.insert(file, p.name.as_str()) {
                return Err(v.invalid(
                    &at,
                    format!(
                        "probes '{other}' and '{}' would write the same plot files ({PROBE_PLOT_PREFIX}{}_*.png): file names keep only letters, digits, '-' and '_'",
                        p.name,
                        rules::file_safe(&p.name)
                    ),
                ));
            }
            let longest = format!(
                "{PROBE_PLOT_PREFIX}{}{PROBE_PLOT_LONGEST_SUFFIX}",
                rules::file_safe(&p.name)
            );
            rules::fits_in_file_name(&longest)
                .map_err(|e| v.invalid(&at, format!("probe '{}': {e}", p.name)))?;
            if !p.at.is_finite() {
                return Err(fail("at", format!("location must be finite, got {}", p.at)));
            }
            if !body_names.contains(p.body.as_str()) {
                return Err(fail(
                    "body",
                    format!("unknown body '{}'; expected one of {body_names:?}", p.body),
                ));
            }
        }
        for (field, value) in [
            ("frame_interval", self.output.frame_interval),
            ("probe_interval", self.output.probe_interval),
        ] {
            if let Some(value) = value {
                rules::positive(value).map_err(|e| v.field(&["output", field], e))?;
            }
        }

        let mut curve_names = BTreeSet::new();
        for (k, curve) in self.output.curves.iter().enumerate() {
            let at = quoted(&curve.name);
            let fail = |field: &str, message: String| {
                v.invalid(
                    &["output", "curves", &at, field],
                    format!("curve '{}': {message}", curve.name),
                )
            };
            let fail_name = |message: String| {
                v.invalid(
                    &["output", "curves", &at],
                    format!("curve '{}': {message}", curve.name),
                )
            };
            rules::file_name(&curve.name)
                .and_then(|()| rules::fits_in_file_name(&format!("{}.csv", curve.name)))
                .map_err(|e| fail_name(e.to_string()))?;
            // Compared without case: macOS and Windows file systems ignore it.
            let file = curve.name.to_lowercase();
            if !curve_names.insert(file.clone()) {
                return Err(v.invalid(
                    &[&["output"], nth_name("curves", k).as_slice()].concat(),
                    format!(
                        "curve '{}': the name is used twice (names are files: letter case does not tell them apart)",
                        curve.name
                    ),
                ));
            }
            if RUN_FILE_STEMS.contains(&file.as_str()) || file.starts_with(PROBE_PLOT_PREFIX) {
                return Err(fail_name(format!(
                    "the name would overwrite the run's own files ({RUN_FILE_STEMS:?}, {PROBE_PLOT_PREFIX}*); choose another"
                )));
            }
            let Some(block) = self.blocks.iter().find(|b| b.name == curve.block) else {
                return Err(fail(
                    "block",
                    format!(
                        "unknown block '{}'; expected one of {block_names:?}",
                        curve.block
                    ),
                ));
            };
            if let Some(part) = curve.part {
                let parts = match &block.shape {
                    crate::rigid::BlockShape::Compound { parts } => parts.len(),
                    _ => 1,
                };
                if part >= parts {
                    return Err(fail(
                        "part",
                        format!(
                            "block '{}' has {parts} part(s), so part {part} does not exist (parts count from 0)",
                            curve.block
                        ),
                    ));
                }
            }
            if !(curve.direction.is_finite() && curve.direction.length() > 0.0) {
                return Err(fail(
                    "direction",
                    "direction must be a finite, non-zero vector".into(),
                ));
            }
            if !(curve.force_scale.is_finite() && curve.displacement_scale.is_finite()) {
                return Err(fail("force_scale", "scales must be finite".into()));
            }
        }
        Ok(())
    }
}
