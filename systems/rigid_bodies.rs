//! Motion of the rigid blocks, with block–block contacts.

use crate::components::{
    BlockContactLaw, BlockId, Pose, Reaction, RigidMass, RigidMotion, RigidShape, RigidVelocity,
};
use crate::contact::{ContactLaw, ShapeContact, pair_force, shape_shape_contacts};
use crate::math::{DVec2, Real};
use crate::resources::{BlockContactHistory, BlockContactKey, BlockPairLaws, Clock, Gravity};
use crate::rigid::{MAX_SUBSTEPS, advance, integrate_dynamic, substeps_needed, velocity_at};
use bevy_ecs::prelude::*;

/// The components of a block this system reads and writes.
type BlockData = (
    &'static BlockId,
    &'static RigidMotion,
    &'static RigidMass,
    &'static RigidShape,
    &'static BlockContactLaw,
    &'static Reaction,
    &'static mut Pose,
    &'static mut RigidVelocity,
);

/// A block's state while the blocks are integrated.
struct BlockState {
    index: u32,
    motion: RigidMotion,
    mass: RigidMass,
    shape: RigidShape,
    law: ContactLaw,
    reaction: Reaction,
    pose: Pose,
    velocity: RigidVelocity,
}

/// Scratch space of the system, reused from step to step.
#[derive(Default)]
pub struct RigidScratch {
    blocks: Vec<BlockState>,
    contacts: Vec<ShapeContact>,
    forces: Vec<(DVec2, Real)>,
    history: Vec<(BlockContactKey, DVec2)>,
    substep_input: Vec<(u32, RigidMotion, Real, ContactLaw)>,
}

/// Dynamic blocks: symplectic Euler from this step's reaction of the points,
/// gravity and the contacts with other blocks (parry manifolds, eq. 18 at
/// each manifold point with its tangential spring kept while in contact);
/// kinematic blocks move with their prescribed velocity; fixed blocks stay.
/// When a dynamic block shares the scene with another block, the step is cut
/// into sub-steps of at most a tenth of the pair's contact period 2π √(m/k_n)
/// (m the lighter dynamic block of the pair), capped at [`MAX_SUBSTEPS`];
/// the points' reaction is held over the step. Pairs are
/// visited in scene order.
///
/// Reads: `Clock`, `Gravity`, `Reaction`, `RigidMass`, `RigidMotion`,
/// `RigidShape`, `BlockContactLaw`. Writes: `Pose`, `RigidVelocity`, `BlockContactHistory`.
pub fn move_rigid_blocks(
    clock: Res<Clock>,
    gravity: Res<Gravity>,
    mut history: ResMut<BlockContactHistory>,
    pair_laws: Res<BlockPairLaws>,
    mut scratch: Local<RigidScratch>,
    mut blocks: Query<BlockData>,
) {
    let scratch = &mut *scratch;
    scratch.blocks.clear();
    for (id, motion, mass, shape, law, reaction, pose, velocity) in &blocks {
        scratch.blocks.push(BlockState {
            index: id.index,
            motion: *motion,
            mass: *mass,
            shape: shape.clone(),
            law: law.own,
            reaction: *reaction,
            pose: *pose,
            velocity: *velocity,
        });
    }
    scratch.blocks.sort_unstable_by_key(|b| b.index);
    scratch.substep_input.clear();
    scratch.substep_input.extend(
        scratch
            .blocks
            .iter()
            .map(|b| (b.index, b.motion, b.mass.mass, b.law)),
    );
    let substeps = substeps_needed(&scratch.substep_input, &pair_laws, clock.dt).min(MAX_SUBSTEPS);
    let dt = clock.dt / substeps as Real;
    for _ in 0..substeps {
        block_forces(scratch, &pair_laws, gravity.0, dt, &mut history.0);
        for (block, (force, torque)) in scratch.blocks.iter_mut().zip(&scratch.forces) {
            match block.motion {
                RigidMotion::Fixed => {}
                RigidMotion::Kinematic => {
                    advance(&mut block.pose, &block.velocity, &block.mass, dt)
                }
                RigidMotion::Dynamic => integrate_dynamic(
                    &mut block.pose,
                    &mut block.velocity,
                    &block.mass,
                    *force,
                    *torque,
                    dt,
                ),
            }
        }
    }
    for (id, _, _, _, _, _, mut pose, mut velocity) in &mut blocks {
        if let Ok(k) = scratch.blocks.binary_search_by_key(&id.index, |b| b.index) {
            *pose = scratch.blocks[k].pose;
            *velocity = scratch.blocks[k].velocity;
        }
    }
}

/// Force and torque on every block for one sub-step: the points' reaction,
/// gravity for dynamic blocks, and the block–block contacts, whose
/// tangential springs are read from and written back to `history`.
fn block_forces(
    scratch: &mut RigidScratch,
    pair_laws: &BlockPairLaws,
    gravity: DVec2,
    dt: Real,
    history: &mut Vec<(BlockContactKey, DVec2)>,
) {
    let RigidScratch {
        blocks,
        contacts,
        forces,
        history: next,
        ..
    } = scratch;
    forces.clear();
    forces.extend(blocks.iter().map(|b| {
        let weight = if b.motion == RigidMotion::Dynamic {
            b.mass.mass * gravity
        } else {
            DVec2::ZERO
        };
        (b.reaction.force + weight, b.reaction.torque)
    }));
    next.clear();
    for i in 0..blocks.len() {
        for j in i + 1..blocks.len() {
            let (a, b) = (&blocks[i], &blocks[j]);
            if a.motion != RigidMotion::Dynamic && b.motion != RigidMotion::Dynamic {
                continue;
            }
            contacts.clear();
            shape_shape_contacts(
                &a.shape.0,
                &a.pose.to_parry(),
                &b.shape.0,
                &b.pose.to_parry(),
                contacts,
            );
            let law = pair_laws.between(a.index, b.index, &a.law, &b.law);
            let (center_a, center_b) = (a.mass.center(&a.pose), b.mass.center(&b.pose));
            for c in contacts.iter() {
                let key = (a.index, b.index, c.features);
                let previous = history
                    .binary_search_by_key(&key, |h| h.0)
                    .map_or(DVec2::ZERO, |k| history[k].1);
                let relative = velocity_at(&a.pose, &a.velocity, &a.mass, c.point)
                    - velocity_at(&b.pose, &b.velocity, &b.mass, c.point);
                let f = pair_force(&law, c.depth, c.normal, relative, previous, dt);
                forces[i].0 += f.force;
                forces[i].1 += (c.point - center_a).perp_dot(f.force);
                forces[j].0 -= f.force;
                forces[j].1 -= (c.point - center_b).perp_dot(f.force);
                next.push((key, f.tangential));
            }
        }
    }
    next.sort_unstable_by_key(|h| h.0);
    std::mem::swap(history, next);
}
