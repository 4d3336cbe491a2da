//! Algorithm 1, line 9: rigid–nonrigid contact detection and DEM forces
//! (paper section 3.2.2).

use crate::components::{
    BlockContactLaw, BlockContacts, BlockId, BodyIndex, MaterialPoints, NeighbourList,
    PartReactions, PointContact, Pose, Reaction, RigidMass, RigidShape, RigidVelocity,
    sort_into_scene_order,
};
use crate::contact::{disk_shape_contact, overlap_area, overlap_area_integral, pair_force};
use crate::distributed::{
    ContactHalfSizes, Domain, PointIds, SharedContact, local_index, share_contacts,
};
use crate::math::{DVec2, Real};
use crate::resources::{Clock, ContactSettings, Geometry, Penetration, Settings};
use crate::rigid::velocity_at;
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Fewest listed points one parallel task tests: a disk–shape query costs
/// about a microsecond, so smaller tasks cost more to hand out than they save.
const MIN_CONTACTS_PER_TASK: usize = 256;

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
    &'static mut PartReactions,
);

/// For every block (in scene order) and every listed point (in list order):
/// the point's disk against the block's shape (parry's contact query gives
/// the depth and the normal from block to point; δ is that depth or the
/// disk's overlap area, per `ContactSettings::penetration`), then eq. 18 with
/// the pair's tangential spring from the previous step (dropped on
/// separation; in axisymmetry the law's stiffnesses per metre times the
/// point's radius, as its mass is, so forces are per radian) and the
/// relative velocity at the contact point x_c:
/// * for a pair in contact last step, the actual motion over that step of
///   the material at last step's contact point relative to the block's
///   surface point it touched: (Δx_p + L_p (x_c − x_p) Δt − Δx_surface)/Δt,
///   with L_p the gradient of the velocity that moved the point (written by
///   G2P) and last step's arm x_c − x_p;
/// * for a new contact, the point's velocity less the block's there,
///   V_p − (v + ω × r).
///
/// The tangential spring is thus stretched by the motion its force does
/// work on: the point moves with the grid's velocity, not with its FLIP
/// velocity V_p, and the contact transfer applies the tangential force at
/// x_c (its moment about the point reaches the body; in `BodyForce` mode,
/// while `Traction` puts it on the domain's edge near x_c), so the material's
/// rotation about the point, which lets a rolling body roll without
/// dragging its spring, is motion the force works on. A spring stretched by
/// anything else does work it does not store, and fed energy into a body
/// at rest on a block. The
/// force goes to the point's `contact_force`, the opposite force and its
/// torque about the centre of mass to the block's `Reaction`, both summed in
/// that fixed order.
///
/// In a distributed run each process tests its own points, names each
/// contact's point by its one-process index, and every process takes the
/// contacts of all (in the order one process finds them) before summing:
/// every process then holds every block's contacts and reaction.
///
/// Reads: `Clock`, `ContactSettings`, `Settings::geometry`, blocks (shape, pose, velocity, mass, law, neighbour list),
/// `MaterialPoints` (position, velocity, velocity gradient, contact radius).
/// Writes: `MaterialPoints::contact_force`, `BlockContacts`, `Reaction`.
#[allow(clippy::too_many_arguments)] // the distributed run's share is one more
pub fn compute_rigid_contacts(
    clock: Res<Clock>,
    settings: Res<ContactSettings>,
    numerics: Res<Settings>,
    mut order: Local<Vec<(u32, Entity)>>,
    mut found: Local<Vec<Option<PointContact>>>,
    mut bodies: Query<(&mut MaterialPoints, Option<&PointIds>, &BodyIndex)>,
    mut blocks: Query<(Entity, BlockData)>,
    domain: Option<NonSend<Domain>>,
    mut half_sizes: Option<ResMut<ContactHalfSizes>>,
    mut shared: Local<Vec<SharedContact>>,
) {
    // The first contact system of the step: it resets every point's
    // contact force (also when there is no block, for the body contacts).
    for (mut points, ..) in &mut bodies {
        points.contact_force.fill(DVec2::ZERO);
    }
    if blocks.is_empty() {
        return;
    }
    shared.clear();
    sort_into_scene_order(&mut order, blocks.iter().map(|(e, b)| (b.0.index, e)));
    for (_, entity) in order.iter() {
        let Ok((
            _,
            (id, shape, pose, velocity, mass, law, list, mut contacts, mut reaction, mut parts),
        )) = blocks.get_mut(*entity)
        else {
            continue;
        };
        let contacts = &mut *contacts;
        std::mem::swap(&mut contacts.previous, &mut contacts.current);
        contacts.current.clear();
        // Narrow phase in parallel, one result per listed point, in list order.
        let parry_pose = pose.to_parry();
        let previous = &contacts.previous;
        let readable = &bodies;
        list.points
            .par_iter()
            .with_min_len(MIN_CONTACTS_PER_TASK)
            .map(|&(body, i)| {
                let (points, ids, _) = readable.get(body).ok()?;
                let i = i as usize;
                // The point's one-process index.
                let p = ids.map_or(i as u32, |ids| ids.0[i] as u32);
                let radius = points.contact_radius[i];
                let geometry =
                    disk_shape_contact(points.position[i], radius, &*shape.0, &parry_pose)?;
                let before = previous
                    .binary_search_by(|c| (c.body, c.point).cmp(&(body, p)))
                    .ok()
                    .map(|k| &previous[k]);
                let relative = match before {
                    Some(c) => {
                        let surface_moved = pose.to_world(c.at_on_block) - c.at;
                        let turned = points.velocity_gradient[i] * c.arm();
                        (points.position[i] - c.from - surface_moved) / clock.dt + turned
                    }
                    None => points.velocity[i] - velocity_at(pose, velocity, mass, geometry.point),
                };
                let carried = before.map_or(DVec2::ZERO, |c| c.tangential);
                let law = law.with_body(body);
                let law = &match numerics.geometry {
                    Geometry::PlaneStrain => *law,
                    Geometry::Axisymmetric => law.over_thickness(points.hoop_radius(i)),
                };
                let (delta, normal_potential) = match settings.penetration {
                    Penetration::Depth => (geometry.depth, 0.5 * geometry.depth.powi(2)),
                    Penetration::Area => (
                        overlap_area(radius, geometry.depth),
                        overlap_area_integral(radius, geometry.depth),
                    ),
                };
                let f = pair_force(law, delta, geometry.normal, relative, carried, clock.dt);
                let tangential_potential = law.tangential_energy(f.tangential);
                let spring_work_correction = match before {
                    Some(_) => 0.5 * (f.tangential - carried).dot(relative * clock.dt),
                    None => 0.0,
                };
                Some(PointContact {
                    body,
                    point: p,
                    force: f.force,
                    tangential: f.tangential,
                    at: geometry.point,
                    at_on_block: pose.to_block(geometry.point),
                    from: points.position[i],
                    potential: law.normal_stiffness * normal_potential + tangential_potential,
                    tangential_potential,
                    spring_work_correction,
                })
            })
            .collect_into_vec(&mut found);
        if domain.is_some() {
            for contact in found.iter().flatten() {
                let Ok((points, ids, index)) = bodies.get(contact.body) else {
                    continue;
                };
                let i = local_index(ids, contact.point).expect("a point of this process");
                shared.push(SharedContact {
                    block: id.index,
                    body: index.0,
                    contact: *contact,
                    half_size: points.half_size[i],
                });
            }
            continue;
        }
        let contacts_found = found.iter().flatten().copied();
        let block = (
            shape,
            pose,
            mass,
            &mut *contacts,
            &mut *reaction,
            &mut *parts,
        );
        sum_contacts(block, contacts_found, &mut bodies);
    }
    let Some(domain) = domain else {
        return;
    };
    // Every process's contacts, in the one-process order.
    let all = share_contacts(&domain, &shared);
    let half_sizes = half_sizes
        .as_mut()
        .expect("a distributed run's contact half-sizes");
    half_sizes.0.clear();
    half_sizes.0.extend(
        all.iter()
            .map(|c| ((c.block, c.contact.body, c.contact.point), c.half_size)),
    );
    half_sizes.0.sort_unstable_by_key(|e| e.0);
    let mut rest = &all[..];
    for (index, entity) in order.iter() {
        let Ok((_, (_, shape, pose, _, mass, _, _, mut contacts, mut reaction, mut parts))) =
            blocks.get_mut(*entity)
        else {
            continue;
        };
        let count = rest.iter().take_while(|c| c.block == *index).count();
        let (these, later) = rest.split_at(count);
        rest = later;
        let block = (
            shape,
            pose,
            mass,
            &mut *contacts,
            &mut *reaction,
            &mut *parts,
        );
        sum_contacts(block, these.iter().map(|c| c.contact), &mut bodies);
    }
}

/// A block's parts the sum of its contacts reads and writes.
type SummedBlock<'a> = (
    &'a RigidShape,
    &'a Pose,
    &'a RigidMass,
    &'a mut BlockContacts,
    &'a mut Reaction,
    &'a mut PartReactions,
);

/// Sums a block's `found` contacts sequentially, in the order given (the
/// list's): each force onto its point's contact force (if this process
/// holds the point), and the opposite force and its torque about the
/// centre of mass onto the block's reaction and the part nearest the
/// contact; the contacts become the block's current ones, sorted by body
/// and point.
fn sum_contacts(
    (shape, pose, mass, contacts, reaction, parts): SummedBlock,
    found: impl Iterator<Item = PointContact>,
    bodies: &mut Query<(&mut MaterialPoints, Option<&PointIds>, &BodyIndex)>,
) {
    *reaction = Reaction::default();
    parts.0.iter_mut().for_each(|f| *f = DVec2::ZERO);
    let center = mass.center(pose);
    let parry_pose = pose.to_parry();
    let compound = shape.0.as_compound();
    for contact in found {
        if let Ok((mut points, ids, _)) = bodies.get_mut(contact.body)
            && let Some(i) = local_index(ids, contact.point)
        {
            points.contact_force[i] += contact.force;
        }
        reaction.force -= contact.force;
        reaction.torque -= (contact.at - center).perp_dot(contact.force);
        let part = compound.map_or(0, |c| nearest_part(c, &parry_pose, contact.at));
        parts.0[part] -= contact.force;
        contacts.current.push(contact);
    }
    contacts.current.sort_unstable_by_key(|c| (c.body, c.point));
}

/// Index of the part of `compound` (placed at `pose`) nearest `point`; the
/// first of equally near parts.
fn nearest_part(
    compound: &parry2d_f64::shape::Compound,
    pose: &parry2d_f64::math::Pose,
    point: DVec2,
) -> usize {
    let mut best = (0, Real::INFINITY);
    for (k, (local, part)) in compound.shapes().iter().enumerate() {
        let distance = part.distance_to_point(&(*pose * *local), point, true);
        if distance < best.1 {
            best = (k, distance);
        }
    }
    best.0
}
