//! The rigid blocks and their contact settings.

use super::{Locator, nth_name};
use crate::components::RigidVelocity;
use crate::contact::ForceApplication;
use crate::rules;
use crate::scene::{MotionSpec, Scene, SceneError};
use std::collections::BTreeSet;

/// Most points a contact traction is split over (the paper's 4 resolve a
/// point's edge; each point costs a stencil per contact and step).
const MAX_TRACTION_POINTS: u32 = 64;

impl Scene {
    /// The rigid blocks; returns their names.
    pub(super) fn check_blocks<'s>(&'s self, v: &Locator) -> Result<BTreeSet<&'s str>, SceneError> {
        let mut block_names = BTreeSet::new();
        for (k, block) in self.blocks.iter().enumerate() {
            let fail = v.entry("blocks", "block", &block.name);
            if !block_names.insert(block.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("blocks", k),
                    format!("block name '{}' is used twice", block.name),
                ));
            }
            block
                .shape
                .build()
                .map_err(|e| fail("shape", e.to_string()))?;
            if !(block.position.is_finite() && block.angle.is_finite()) {
                return Err(fail(
                    "position",
                    "position and angle must be finite".to_string(),
                ));
            }
            block
                .contact
                .check()
                .map_err(|e| fail("contact", e.to_string()))?;
            let initial = match &block.motion {
                MotionSpec::Fixed => RigidVelocity::default(),
                MotionSpec::Kinematic(v)
                | MotionSpec::Dynamic { velocity: v, .. }
                | MotionSpec::DynamicWithMass { velocity: v, .. } => *v,
            };
            if !(initial.linear.is_finite() && initial.angular.is_finite()) {
                return Err(fail("motion", "velocity must be finite".to_string()));
            }
            if let MotionSpec::DynamicWithMass {
                mass,
                inertia,
                center,
                ..
            } = block.motion
            {
                rules::positive(mass).map_err(|e| fail("mass", format!("mass: {e}")))?;
                rules::positive(inertia).map_err(|e| fail("inertia", format!("inertia: {e}")))?;
                if !center.is_finite() {
                    return Err(fail("center", "center must be finite".to_string()));
                }
            }
            if let MotionSpec::Dynamic { density, .. } = block.motion {
                rules::density(density).map_err(|e| fail("density", format!("density: {e}")))?;
            }
        }
        Ok(block_names)
    }

    /// The contact settings.
    pub(super) fn check_contact(&self, v: &Locator) -> Result<(), SceneError> {
        if self.contact.iter_period == Some(0) {
            return Err(v.invalid(
                &["contact", "iter_period"],
                "contact.iter_period must be at least 1".into(),
            ));
        }
        if let ForceApplication::Traction { points } = self.contact.force_application
            && !(1..=MAX_TRACTION_POINTS).contains(&points)
        {
            return Err(v.field(
                &["contact", "force_application"],
                format!(
                    "Traction takes 1 to {MAX_TRACTION_POINTS} points on the edge of a point's domain, got {points}: more segments than that resolve nothing finer and only cost time (the paper splits the edge in 4)"
                ),
            ));
        }
        if let Some(margin) = self.contact.margin {
            rules::positive(margin).map_err(|e| v.field(&["contact", "margin"], e))?;
        }
        Ok(())
    }
}
