//! The work of this step's tangential contact forces, for the energy balance.

use crate::components::{
    BlockContacts, BlockId, BodyIndex, MaterialPoints, Pose, sort_into_scene_order,
};
use crate::resources::{BodyContacts, ContactWork};
use bevy_ecs::prelude::*;

/// Adds this step's work of the contacts' tangential forces on the relative
/// motion of what they join to `ContactWork`: for a point–block contact,
/// the tangential force on the point times the point's displacement over
/// the step less that of the block's surface point it touched; for a
/// point–point contact, the tangential force on p times the change of
/// x_p − x_q. Run after the points and the blocks have moved. Blocks in scene order, contacts in their stored order, body
/// contacts after them: one fixed order of summation.
///
/// Only the tangential part is taken: the normal spring k_n δ is a potential
/// of the positions, its energy is in `contact`, and the work of its
/// force over a step would differ from its change only by the time
/// integration's error, which belongs to the balance, not to dissipation.
///
/// Reads: `BlockId`, `BlockContacts`, `Pose`,
/// `BodyContacts`, `BodyIndex`, `MaterialPoints::position`. Writes: `ContactWork`.
pub fn account_contact_work(
    mut work: ResMut<ContactWork>,
    body_contacts: Res<BodyContacts>,
    mut order: Local<Vec<(u32, Entity)>>,
    mut slots: Local<Vec<Option<Entity>>>,
    bodies: Query<(Entity, &BodyIndex, &MaterialPoints)>,
    blocks: Query<(Entity, &BlockId, &Pose, &BlockContacts)>,
) {
    let mut done = work.tangential_work;
    sort_into_scene_order(&mut order, blocks.iter().map(|(e, id, ..)| (id.index, e)));
    for (_, entity) in order.iter() {
        let Ok((_, _, pose, contacts)) = blocks.get(*entity) else {
            continue;
        };
        for c in &contacts.current {
            let Ok((_, _, points)) = bodies.get(c.body) else {
                continue;
            };
            let moved = points.position[c.point as usize] - c.from;
            let surface_moved = pose.to_world(c.at_on_block) - c.at;
            done += c.tangential.dot(moved - surface_moved);
        }
    }
    if !body_contacts.current.is_empty() {
        slots.clear();
        for (entity, index, _) in bodies.iter() {
            let k = index.0 as usize;
            if slots.len() <= k {
                slots.resize(k + 1, None);
            }
            slots[k] = Some(entity);
        }
        let position = |body: u32, point: u32| {
            let entity = slots.get(body as usize).copied().flatten()?;
            let (_, _, points) = bodies.get(entity).ok()?;
            Some(points.position[point as usize])
        };
        for c in &body_contacts.current {
            if let (Some(xp), Some(xq)) = (position(c.a, c.p), position(c.b, c.q)) {
                done += c.tangential.dot(xp - xq - c.separation);
            }
        }
    }
    work.tangential_work = done;
}
