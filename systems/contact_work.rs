//! The work of this step's point contacts, for the energy balance: their
//! tangential forces on the relative motion, the blocks on the points.

use crate::components::{
    BlockContacts, BlockId, BodyIndex, MaterialPoints, Pose, sort_into_scene_order,
};
use crate::distributed::{Domain, PointIds, add_in_order, local_index};
use crate::math::Real;
use crate::resources::{BodyContacts, Clock, ContactWork};
use bevy_ecs::prelude::*;

/// Adds this step's work of the contacts' tangential forces on the relative
/// motion of what they join to `ContactWork`: for a point–block contact,
/// the tangential force on the point times the motion of the material at
/// the contact point over the step (the point's displacement plus
/// L_p (x_c − x_p) Δt, L_p the gradient of the velocity that moved it, the
/// force acting at x_c) less that of the block's surface point it touched;
/// for a point–point contact, the tangential force on p times the change
/// of x_p − x_q plus (L_p a_p − L_q a_q) Δt, a the arms from the points'
/// centres to the contact point when it was found. Run after the points
/// and the blocks have moved. Blocks in scene order, contacts in their stored order, body
/// contacts after them: one fixed order of summation.
///
/// Adds, too, the work of each block on the points it touches: the force on
/// the point times the motion of the block's surface point it touched
/// (`ContactWork::block_work`), what a moving block gives the bodies.
///
/// Of the relative motion, only the tangential force's work is taken: the
/// normal spring k_n δ is a potential of the positions, its energy is in
/// `contact`, and the work of its force over a step would differ from its
/// change only by the time integration's error, which belongs to the
/// balance, not to dissipation.
///
/// In a distributed run each process forms the terms of the contacts of
/// its own points, and every process adds all of them in that order.
///
/// Reads: `Clock`, `BlockId`, `BlockContacts`, `Pose`, `BodyContacts`,
/// `BodyIndex`, `MaterialPoints` (position, velocity gradient, contact
/// radius). Writes: `ContactWork`.
#[allow(clippy::too_many_arguments)] // the distributed run's share is three more
pub fn account_contact_work(
    clock: Res<Clock>,
    mut work: ResMut<ContactWork>,
    body_contacts: Option<Res<BodyContacts>>,
    mut order: Local<Vec<(u32, Entity)>>,
    mut slots: Local<Vec<Option<Entity>>>,
    bodies: Query<(Entity, &BodyIndex, &MaterialPoints)>,
    blocks: Query<(Entity, &BlockId, &Pose, &BlockContacts)>,
    domain: Option<NonSend<Domain>>,
    ids: Query<&PointIds>,
    mut held: Local<Vec<(u64, [Real; 2])>>,
) {
    let mut done = work.tangential_work;
    let mut by_blocks = work.block_work;
    sort_into_scene_order(&mut order, blocks.iter().map(|(e, id, ..)| (id.index, e)));
    held.clear();
    let mut place = 0u64;
    for (_, entity) in order.iter() {
        let Ok((_, _, pose, contacts)) = blocks.get(*entity) else {
            continue;
        };
        for c in &contacts.current {
            place += 1;
            let Ok((_, _, points)) = bodies.get(c.body) else {
                continue;
            };
            let Some(k) = local_index(ids.get(c.body).ok(), c.point) else {
                continue;
            };
            let turned = points.velocity_gradient[k] * c.arm() * clock.dt;
            let moved = points.position[k] - c.from + turned;
            let surface_moved = pose.to_world(c.at_on_block) - c.at;
            let terms = [
                c.tangential.dot(moved - surface_moved) + c.spring_work_correction,
                c.force.dot(surface_moved),
            ];
            if domain.is_some() {
                held.push((place, terms));
            } else {
                done += terms[0];
                by_blocks += terms[1];
            }
        }
    }
    // Every process holds the same blocks.
    if let Some(domain) = domain.filter(|_| !order.is_empty()) {
        [done, by_blocks] = add_in_order(&domain, &held, [done, by_blocks]);
    }
    if let Some(body_contacts) = body_contacts.filter(|c| !c.current.is_empty()) {
        slots.clear();
        for (entity, index, _) in bodies.iter() {
            let k = index.0 as usize;
            if slots.len() <= k {
                slots.resize(k + 1, None);
            }
            slots[k] = Some(entity);
        }
        let points_of = |body: u32| {
            let entity = slots.get(body as usize).copied().flatten()?;
            bodies.get(entity).ok().map(|(_, _, points)| points)
        };
        for c in &body_contacts.current {
            let (Some(first), Some(second)) = (points_of(c.a), points_of(c.b)) else {
                continue;
            };
            let (p, q) = (c.p as usize, c.q as usize);
            let (arm_p, arm_q) = c.arms(first.contact_radius[p], second.contact_radius[q]);
            let turned = (first.velocity_gradient[p] * arm_p - second.velocity_gradient[q] * arm_q)
                * clock.dt;
            let moved = first.position[p] - second.position[q] - c.separation;
            done += c.tangential.dot(moved + turned) + c.spring_work_correction;
        }
    }
    work.tangential_work = done;
    work.block_work = by_blocks;
}
