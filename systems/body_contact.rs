//! Algorithm 1, line 9 for bodies against bodies (paper section 3.3).

use crate::components::{BodyIndex, MaterialPoints, sort_into_scene_order};
use crate::contact::pair_force;
use crate::math::DVec2;
use crate::resources::{BodyContacts, BodyPairContact, Clock, Grid, law_between};
use bevy_ecs::prelude::*;

/// Nonrigid–nonrigid DEM contacts. Each body keeps its own layer; contact is
/// sought only where the bodies meet: every cell is marked with the bodies
/// whose points lie in it, a point is a candidate when a body it has a law
/// with lies in its cell or the eight around it (the cells whose nodes carry
/// the mass of both layers), and candidates of different bodies in
/// neighbouring cells are tested disk against disk (a disk is at most half
/// a cell wide, so overlapping disks are never further apart). Each overlap
/// gets eq. 18 with the pair's law: the normal from q to p, δ the overlap,
/// the relative velocity of the two materials at the contact point
/// (V + L (x_c − x) for each), the tangential spring kept per pair while in
/// contact. Equal and opposite forces go to the two points' `contact_force`,
/// pairs in (body, point, body, point) order.
///
/// Reads: `Grid`, `Clock`, `BodyIndex`, `MaterialPoints` (position,
/// velocity, velocity gradient, contact radius). Writes: `BodyContacts`,
/// `MaterialPoints::contact_force`.
pub fn compute_body_contacts(
    grid: Res<Grid>,
    clock: Res<Clock>,
    mut contacts: ResMut<BodyContacts>,
    mut order: Local<Vec<(BodyIndex, Entity)>>,
    mut bodies: Query<(Entity, &BodyIndex, &mut MaterialPoints)>,
) {
    if contacts.laws.is_empty() {
        return;
    }
    sort_into_scene_order(&mut order, bodies.iter().map(|(e, i, _)| (*i, e)));
    let [nx, ny] = grid.cells;
    let cell_of = |x: DVec2| {
        let c = ((x - grid.origin) / grid.cell_size).floor();
        let i = (c.x.max(0.0) as usize).min(nx - 1);
        let j = (c.y.max(0.0) as usize).min(ny - 1);
        (i, j)
    };
    let BodyContacts {
        laws,
        current,
        previous,
        cell_bodies,
        candidates,
    } = &mut *contacts;
    std::mem::swap(previous, current);
    current.clear();
    cell_bodies.clear();
    cell_bodies.resize(nx * ny, 0);
    for (index, entity) in order.iter() {
        let Ok((_, _, points)) = bodies.get(*entity) else {
            continue;
        };
        for x in &points.position {
            let (i, j) = cell_of(*x);
            cell_bodies[j * nx + i] |= 1 << index.0;
        }
    }
    // The bodies each body has a law with.
    let partners = |k: u32| {
        laws.iter().fold(0u64, |m, l| {
            if l.a == k {
                m | 1 << l.b
            } else if l.b == k {
                m | 1 << l.a
            } else {
                m
            }
        })
    };
    let around = |i: usize, j: usize| {
        let mut mask = 0;
        for jj in j.saturating_sub(1)..=(j + 1).min(ny - 1) {
            for ii in i.saturating_sub(1)..=(i + 1).min(nx - 1) {
                mask |= cell_bodies[jj * nx + ii];
            }
        }
        mask
    };
    candidates.clear();
    for (index, entity) in order.iter() {
        let wanted = partners(index.0);
        if wanted == 0 {
            continue;
        }
        let Ok((_, _, points)) = bodies.get(*entity) else {
            continue;
        };
        for (p, x) in points.position.iter().enumerate() {
            let (i, j) = cell_of(*x);
            if around(i, j) & wanted != 0 {
                candidates.push(((j * nx + i) as u32, index.0, p as u32));
            }
        }
    }
    candidates.sort_unstable();
    let dt = clock.dt;
    for &(cell, a, p) in candidates.iter() {
        let (i, j) = (cell as usize % nx, cell as usize / nx);
        let Ok((_, _, first)) = bodies.get(order[a as usize].1) else {
            continue;
        };
        let (xp, rp) = (first.position[p as usize], first.contact_radius[p as usize]);
        for jj in j.saturating_sub(1)..=(j + 1).min(ny - 1) {
            for ii in i.saturating_sub(1)..=(i + 1).min(nx - 1) {
                let near = (jj * nx + ii) as u32;
                let start = candidates.partition_point(|c| c.0 < near);
                for &(_, b, q) in candidates[start..].iter().take_while(|c| c.0 == near) {
                    if b <= a {
                        continue;
                    }
                    let Some(&law) = law_between(laws, a, b) else {
                        continue;
                    };
                    let Ok((_, _, second)) = bodies.get(order[b as usize].1) else {
                        continue;
                    };
                    let (xq, rq) = (
                        second.position[q as usize],
                        second.contact_radius[q as usize],
                    );
                    let gap = xp - xq;
                    let distance = gap.length();
                    let overlap = rp + rq - distance;
                    if overlap <= 0.0 || distance == 0.0 {
                        continue;
                    }
                    let normal = gap / distance;
                    let at = xq + normal * (rq - 0.5 * overlap);
                    let material = |points: &MaterialPoints, k: usize| {
                        points.velocity[k] + points.velocity_gradient[k] * (at - points.position[k])
                    };
                    let relative = material(first, p as usize) - material(second, q as usize);
                    let key = (a, p, b, q);
                    let carried = previous
                        .binary_search_by(|c| c.key().cmp(&key))
                        .map_or(DVec2::ZERO, |k| previous[k].tangential);
                    let f = pair_force(&law, overlap, normal, relative, carried, dt);
                    current.push(BodyPairContact {
                        a,
                        p,
                        b,
                        q,
                        force: f.force,
                        tangential: f.tangential,
                        overlap,
                        at,
                        radius: 0.5 * (rp + rq),
                    });
                }
            }
        }
    }
    current.sort_unstable_by_key(BodyPairContact::key);
    for contact in current.iter() {
        for (body, point, force) in [
            (contact.a, contact.p, contact.force),
            (contact.b, contact.q, -contact.force),
        ] {
            if let Ok((_, _, mut points)) = bodies.get_mut(order[body as usize].1) {
                points.contact_force[point as usize] += force;
            }
        }
    }
}
