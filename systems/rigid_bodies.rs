//! Motion of the rigid blocks.

use crate::components::{Pose, Reaction, RigidMass, RigidMotion, RigidVelocity};
use crate::resources::{Clock, Gravity};
use crate::rigid::{advance, integrate_dynamic};
use bevy_ecs::prelude::*;

/// Dynamic blocks: symplectic Euler from this step's reaction of the points
/// plus gravity; kinematic blocks: moved with their prescribed velocity;
/// fixed blocks stay. Block–block contact is not handled yet.
///
/// Reads: `Clock`, `Gravity`, `Reaction`, `RigidMass`, `RigidMotion`.
/// Writes: `Pose`, `RigidVelocity`.
pub fn move_rigid_blocks(
    clock: Res<Clock>,
    gravity: Res<Gravity>,
    mut blocks: Query<(
        &RigidMotion,
        &RigidMass,
        &Reaction,
        &mut Pose,
        &mut RigidVelocity,
    )>,
) {
    for (motion, mass, reaction, mut pose, mut velocity) in &mut blocks {
        match motion {
            RigidMotion::Fixed => {}
            RigidMotion::Kinematic => advance(&mut pose, &velocity, mass, clock.dt),
            RigidMotion::Dynamic => {
                let force = reaction.force + mass.mass * gravity.0;
                integrate_dynamic(
                    &mut pose,
                    &mut velocity,
                    mass,
                    force,
                    reaction.torque,
                    clock.dt,
                );
            }
        }
    }
}
