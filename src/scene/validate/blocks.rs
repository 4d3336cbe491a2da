//! The rigid blocks and their contact settings.

use super::{Locator, nth_name};
use crate::components::RigidVelocity;
use crate::contact::ForceApplication;
use crate::math::Real;
use crate::rules;
use crate::scene::{BlockSpec, MotionSpec, Scene, SceneError};
use glam::DVec2;
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
            rules::rigid_velocity(initial.linear, initial.angular)
                .map_err(|e| fail("motion", e))?;
            if let MotionSpec::DynamicWithMass {
                mass,
                inertia,
                center,
                ..
            } = block.motion
            {
                check_mass_properties(block, mass, inertia, center)
                    .map_err(|(field, e)| fail(field, e))?;
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

/// Given mass properties that a body of the block's shape can have: a
/// density (mass over area) within the materials' range, a centre of mass
/// within the shape's bounds, and an inertia between 10⁻⁶ and 1 times
/// m d², d the distance from that centre to the bounds' farthest corner
/// (1: all the mass there; far less spins the block faster than any step
/// resolves). On refusal, the field and the message.
fn check_mass_properties(
    block: &BlockSpec,
    mass: Real,
    inertia: Real,
    center: DVec2,
) -> Result<(), (&'static str, String)> {
    rules::positive(mass).map_err(|e| ("mass", format!("mass: {e}")))?;
    rules::positive(inertia).map_err(|e| ("inertia", format!("inertia: {e}")))?;
    if !center.is_finite() {
        return Err(("center", "center must be finite".to_string()));
    }
    let Ok(shape) = block.shape.build() else {
        return Ok(()); // the shape's own check says why
    };
    let area = block.shape.mass_properties(&shape, 1.0).mass();
    if rules::density(mass / area).is_err() {
        let message = format!(
            "mass: {} kg/m over the block's {} m² is a density of {} kg/m³; expected from {} to {:e} kg/m³, as a material's",
            rules::shown(mass),
            rules::shown_rounded(area),
            rules::shown_rounded(mass / area),
            rules::MIN_DENSITY,
            rules::MAX_DENSITY,
        );
        return Err(("mass", message));
    }
    let bounds = shape.compute_local_aabb();
    let (low, high) = (
        DVec2::new(bounds.mins.x, bounds.mins.y),
        DVec2::new(bounds.maxs.x, bounds.maxs.y),
    );
    if center.cmplt(low).any() || center.cmpgt(high).any() {
        let message = format!(
            "center ({}, {}) lies outside the block's bounds, ({}, {}) to ({}, {}) in its frame: a centre of mass lies within its body",
            rules::shown(center.x),
            rules::shown(center.y),
            rules::shown_rounded(low.x),
            rules::shown_rounded(low.y),
            rules::shown_rounded(high.x),
            rules::shown_rounded(high.y)
        );
        return Err(("center", message));
    }
    let farthest = [
        low,
        high,
        DVec2::new(low.x, high.y),
        DVec2::new(high.x, low.y),
    ]
    .into_iter()
    .map(|corner| corner.distance_squared(center))
    .fold(0.0, Real::max);
    let most = mass * farthest;
    if !(MIN_INERTIA_SHARE * most..=most).contains(&inertia) {
        let message = format!(
            "inertia: {} kg m²/m; a block of mass {} kg/m within {} m of its centre of mass has from {} to {} kg m²/m",
            rules::shown(inertia),
            rules::shown(mass),
            rules::shown_rounded(farthest.sqrt()),
            rules::shown_rounded(MIN_INERTIA_SHARE * most),
            rules::shown_rounded(most)
        );
        return Err(("inertia", message));
    }
    Ok(())
}

/// The smallest inertia a block with given mass properties may have, as
/// a share of the largest its mass and extent allow.
const MIN_INERTIA_SHARE: Real = 1e-6;
