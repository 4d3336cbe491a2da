//! Algorithm 1, line 9: rigid–nonrigid contact detection and DEM forces
//! (paper section 3.2.2).

use crate::components::{
    BlockContactLaw, BlockContacts, BlockId, MaterialPoints, NeighbourList, PointContact, Pose,
    Reaction, RigidMass, RigidShape, RigidVelocity,
};
use crate::contact::{disk_shape_contact, overlap_area, pair_force};
use crate::math::DVec2;
use crate::resources::{Clock, ContactSettings, Penetration};
use crate::rigid::velocity_at;
use bevy_ecs::prelude::*;

/// The blocks' data the contact system reads and writes.
type BlockData = (
    &'static BlockId,
    &'static RigidShape,
    &'static Pose,
    &'static RigidVelocity,
    &'static RigidMass,
    &'static BlockContactLaw,
    &'static NeighbourList,
    &'static mut BlockContacts,
    &'static mut Reaction,
);

/// For every block (in scene order) and every listed point (in list order):
/// the point's disk against the block's shape (parry's contact query gives
/// the depth and the normal from block to point; δ is that depth or the
/// disk's overlap area, per `ContactSettings::penetration`), then eq. 18 with the
/// relative velocity V_p − (v + ω × r) at the contact point and the pair's
/// tangential spring from the previous step (dropped on separation). The
/// force goes to the point's `contact_force`, the opposite force and its
/// torque about the centre of mass to the block's `Reaction`, both summed in
/// that fixed order.
///
/// Reads: `Clock`, `ContactSettings`, blocks (shape, pose, velocity, mass, law, neighbour list),
/// `MaterialPoints` (position, velocity, contact radius).
/// Writes: `MaterialPoints::contact_force`, `BlockContacts`, `Reaction`.
pub fn compute_rigid_contacts(
    clock: Res<Clock>,
    settings: Res<ContactSettings>,
    mut order: Local<Vec<(u32, Entity)>>,
    mut bodies: Query<&mut MaterialPoints>,
    mut blocks: Query<(Entity, BlockData)>,
) {
    for mut points in &mut bodies {
        points
            .contact_force
            .iter_mut()
            .for_each(|f| *f = DVec2::ZERO);
    }
    order.clear();
    order.extend(blocks.iter().map(|(e, b)| (b.0.index, e)));
    order.sort_unstable();
    for (_, entity) in order.iter() {
        let Ok((_, (_, shape, pose, velocity, mass, law, list, mut contacts, mut reaction))) =
            blocks.get_mut(*entity)
        else {
            continue;
        };
        let contacts = &mut *contacts;
        std::mem::swap(&mut contacts.previous, &mut contacts.current);
        contacts.current.clear();
        *reaction = Reaction::default();
        let parry_pose = pose.to_parry();
        let center = mass.center(pose);
        for &(body, p) in &list.points {
            let Ok(mut points) = bodies.get_mut(body) else {
                continue;
            };
            let i = p as usize;
            let Some(geometry) = disk_shape_contact(
                points.position[i],
                points.contact_radius[i],
                &*shape.0,
                &parry_pose,
            ) else {
                continue;
            };
            let relative = points.velocity[i] - velocity_at(pose, velocity, mass, geometry.point);
            let previous = contacts
                .previous
                .binary_search_by(|c| (c.body, c.point).cmp(&(body, p)))
                .map_or(DVec2::ZERO, |k| contacts.previous[k].tangential);
            let delta = match settings.penetration {
                Penetration::Depth => geometry.depth,
                Penetration::Area => overlap_area(points.contact_radius[i], geometry.depth),
            };
            let f = pair_force(&law.0, delta, geometry.normal, relative, previous, clock.dt);
            points.contact_force[i] += f.force;
            reaction.force -= f.force;
            reaction.torque -= (geometry.point - center).perp_dot(f.force);
            contacts.current.push(PointContact {
                body,
                point: p,
                force: f.force,
                tangential: f.tangential,
                at: geometry.point,
            });
        }
        contacts.current.sort_unstable_by_key(|c| (c.body, c.point));
    }
}
