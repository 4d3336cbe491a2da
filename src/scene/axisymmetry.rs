//! What an axisymmetric scene (`settings.geometry: Axisymmetric`) must
//! keep: the plane is a meridian, x = r ≥ 0 from the axis at the grid's
//! left edge, and everything is a body of revolution about it.

use super::{MotionSpec, Scene};
use crate::components::Pose;
use crate::resources::{EdgeCondition, Geometry};
use crate::shape_functions::ShapeFunction;

/// The first rule of axisymmetry `scene` breaks, as the anchors of the
/// entry at fault (for the error's line) and the message; `None` for a
/// plane-strain scene or one that keeps them all.
pub(super) fn axisymmetry_error(scene: &Scene) -> Option<(Vec<String>, String)> {
    if scene.settings.geometry != Geometry::Axisymmetric {
        return None;
    }
    let at = |anchors: &[&str], message: String| {
        Some((anchors.iter().map(|a| a.to_string()).collect(), message))
    };
    let quoted = |name: &str| format!("\"{name}\"");
    if scene.grid.origin.x != 0.0 {
        return at(
            &["grid", "origin"],
            format!(
                "grid.origin.x must be 0 under settings.geometry: Axisymmetric (the grid's left edge is the axis r = 0), got {}",
                scene.grid.origin.x
            ),
        );
    }
    if scene.grid.edges.left == EdgeCondition::Free {
        return at(
            &["grid", "edges", "left"],
            "grid.edges.left must be Slip (or Fixed) under settings.geometry: Axisymmetric: the left edge is the axis, where the radial velocity is zero".into(),
        );
    }
    if scene.settings.shape_function == ShapeFunction::QuadraticBSpline {
        return at(
            &["settings", "shape_function"],
            "settings.shape_function: QuadraticBSpline needs a cell between a body and the grid's edge, and under settings.geometry: Axisymmetric that edge is the axis (a solid body of revolution could not reach it); use UGimp or Linear".into(),
        );
    }
    if scene.gravity.x != 0.0 {
        return at(
            &["gravity"],
            format!(
                "gravity must lie along the axis (g_x = 0) under settings.geometry: Axisymmetric, got {}",
                scene.gravity
            ),
        );
    }
    for b in &scene.bodies {
        if b.acceleration.is_some_and(|a| a.value.x != 0.0) {
            return at(
                &["bodies", &quoted(&b.name), "acceleration"],
                format!(
                    "body '{}': acceleration must lie along the axis (x = 0) under settings.geometry: Axisymmetric",
                    b.name
                ),
            );
        }
    }
    if !scene.body_contacts.is_empty() {
        return at(
            &["body_contacts"],
            "body_contacts are not available under settings.geometry: Axisymmetric yet (rigid blocks are)".into(),
        );
    }
    for block in &scene.blocks {
        // A body of revolution's meridian lies on one side of its axis.
        let reach = block.shape.build().ok().map(|shape| {
            let pose = Pose {
                origin: block.position,
                angle: block.angle.to_radians(),
            };
            shape.compute_aabb(&pose.to_parry()).mins.x
        });
        if let Some(min_x) = reach.filter(|&x| x < -1e-9 * (1.0 + block.position.length())) {
            return at(
                &["blocks", &quoted(&block.name), "position"],
                format!(
                    "block '{}' reaches x = {min_x} across the axis under settings.geometry: Axisymmetric: a body of revolution's outline lies at x ≥ 0",
                    block.name
                ),
            );
        }
        let along_axis =
            |v: &crate::components::RigidVelocity| v.linear.x == 0.0 && v.angular == 0.0;
        let message = match &block.motion {
            MotionSpec::Fixed => None,
            MotionSpec::Kinematic(v) if along_axis(v) => None,
            MotionSpec::Kinematic(_) => {
                Some("a kinematic block must move along the axis (linear.x = 0, angular = 0)")
            }
            MotionSpec::Dynamic { .. } | MotionSpec::DynamicWithMass { .. } => Some(
                "dynamic blocks are not available yet (a block is a body of revolution: its mass and reactions would be taken about the axis); use Fixed or Kinematic",
            ),
        };
        if let Some(message) = message {
            return at(
                &["blocks", &quoted(&block.name), "motion"],
                format!(
                    "block '{}': {message} under settings.geometry: Axisymmetric",
                    block.name
                ),
            );
        }
    }
    for stage in &scene.stages {
        let name = quoted(&stage.name);
        if stage.gravity.is_some_and(|g| g.x != 0.0) {
            return at(
                &["stages", &name, "gravity"],
                format!(
                    "stage '{}': gravity must lie along the axis (g_x = 0) under settings.geometry: Axisymmetric",
                    stage.name
                ),
            );
        }
        if let Some(change) = stage
            .block_velocities
            .iter()
            .find(|c| c.velocity.linear.x != 0.0 || c.velocity.angular != 0.0)
        {
            return at(
                &["stages", &name, "block_velocities"],
                format!(
                    "stage '{}': block '{}' must move along the axis (linear.x = 0, angular = 0) under settings.geometry: Axisymmetric",
                    stage.name, change.block
                ),
            );
        }
        if stage
            .edges
            .as_ref()
            .is_some_and(|e| e.left == Some(EdgeCondition::Free))
        {
            return at(
                &["stages", &name, "edges"],
                format!(
                    "stage '{}': the left edge is the axis under settings.geometry: Axisymmetric and cannot be made Free",
                    stage.name
                ),
            );
        }
    }
    None
}
