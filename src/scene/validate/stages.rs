//! The stages.

use super::{Locator, nth_name};
use crate::math::Real;
use crate::rules;
use crate::scene::{MotionSpec, Scene, SceneError};
use std::collections::BTreeSet;

impl Scene {
    /// The stages.
    pub(super) fn check_stages<'s>(
        &'s self,
        v: &Locator,
        body_names: &BTreeSet<&'s str>,
        block_names: &BTreeSet<&'s str>,
    ) -> Result<(), SceneError> {
        let mut stage_names = BTreeSet::new();
        let mut present: BTreeSet<&str> = self
            .blocks
            .iter()
            .filter(|b| b.present)
            .map(|b| b.name.as_str())
            .collect();
        for (k, stage) in self.stages.iter().enumerate() {
            let fail = v.entry("stages", "stage", &stage.name);
            if !stage_names.insert(stage.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("stages", k),
                    format!("stage '{}': the name is used twice", stage.name),
                ));
            }
            stage
                .end
                .check()
                .map_err(|e| fail("end", format!("end: {e}")))?;
            // The same ranges as the file's parser applies (rules.rs), for
            // stages built in code.
            let ranges = [
                (
                    "pic_fraction",
                    stage.pic_fraction,
                    rules::fraction as fn(Real) -> _,
                ),
                ("grid_damping", stage.grid_damping, rules::damping),
                ("particle_damping", stage.particle_damping, rules::damping),
            ];
            for (field, value, rule) in ranges {
                if let Some(v) = value {
                    rule(v).map_err(|e| fail(field, format!("{field}: {e}")))?;
                }
            }
            if let Some(g) = stage.gravity
                && !g.is_finite()
            {
                return Err(fail("gravity", format!("gravity must be finite, got {g}")));
            }
            if let Some(g) = stage.gravity
                && g.length() > super::settings::MAX_GRAVITY
            {
                return Err(fail(
                    "gravity",
                    format!(
                        "gravity must be at most {:e} m/s², got ({}, {})",
                        super::settings::MAX_GRAVITY,
                        rules::shown(g.x),
                        rules::shown(g.y)
                    ),
                ));
            }
            let block = |name: &str, field: &str| {
                self.blocks.iter().find(|b| b.name == name).ok_or_else(|| {
                    fail(
                        field,
                        format!("unknown block '{name}'; expected one of {block_names:?}"),
                    )
                })
            };
            // Removals come first, then additions (systems/stages.rs).
            for (k, name) in stage.remove_blocks.iter().enumerate() {
                block(name, "remove_blocks")?;
                if stage.remove_blocks[..k].contains(name) {
                    return Err(fail(
                        "remove_blocks",
                        format!("block '{name}' is listed twice; list it once"),
                    ));
                }
                if !present.remove(name.as_str()) {
                    return Err(fail(
                        "remove_blocks",
                        format!(
                            "block '{name}' is not there when the stage begins (an earlier stage removed it, or none added it)"
                        ),
                    ));
                }
            }
            for name in &stage.add_blocks {
                if block(name, "add_blocks")?.present {
                    return Err(fail(
                        "add_blocks",
                        format!(
                            "block '{name}' is present from the start; give it `present: false` to add it in a stage"
                        ),
                    ));
                }
                if !present.insert(name.as_str()) {
                    return Err(fail(
                        "add_blocks",
                        format!("block '{name}' is there already: an earlier stage added it"),
                    ));
                }
            }
            for change in &stage.block_velocities {
                let b = block(&change.block, "block_velocities")?;
                if !present.contains(change.block.as_str()) {
                    return Err(fail(
                        "block_velocities",
                        format!(
                            "block '{}' is not there during this stage: add it first",
                            change.block
                        ),
                    ));
                }
                if !matches!(b.motion, MotionSpec::Kinematic(_)) {
                    return Err(fail(
                        "block_velocities",
                        format!(
                            "block '{}' is not Kinematic: only a kinematic block's velocity can be set",
                            change.block
                        ),
                    ));
                }
                crate::rules::rigid_velocity(change.velocity.linear, change.velocity.angular)
                    .map_err(|e| fail("block_velocities", e))?;
            }
            for (k, traction) in stage.tractions.iter().enumerate() {
                if stage.tractions[..k]
                    .iter()
                    .any(|t| t.body == traction.body && t.side == traction.side)
                {
                    return Err(fail(
                        "tractions",
                        format!(
                            "body '{}' is loaded twice on its {:?} side in this stage: one traction per body and side (the last would replace the first)",
                            traction.body, traction.side
                        ),
                    ));
                }
                if !self.bodies.iter().any(|b| b.name == traction.body) {
                    return Err(fail(
                        "tractions",
                        format!(
                            "unknown body '{}'; expected one of {body_names:?}",
                            traction.body
                        ),
                    ));
                }
                if !(traction.traction.is_finite()
                    && traction.traction.length() <= rules::MAX_MODULUS)
                {
                    return Err(fail(
                        "tractions",
                        format!(
                            "a traction must be finite and at most {:e} Pa in size, got ({}, {}) Pa",
                            rules::MAX_MODULUS,
                            rules::shown(traction.traction.x),
                            rules::shown(traction.traction.y)
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}
