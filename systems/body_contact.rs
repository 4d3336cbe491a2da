//! Algorithm 1, line 9 for bodies against bodies (paper section 3.3).

use crate::components::{BodyIndex, MaterialPoints};
use crate::contact::{ContactLaw, DiskOverlap, disk_overlap, pair_force};
use crate::math::{DVec2, Real};
use crate::parallel::MIN_POINTS_PER_TASK;
use crate::resources::{
    BodyContacts, BodyPairContact, BodyPairLaw, Clock, Grid, MAX_CONTACT_BODIES, law_between,
};
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Nonrigid–nonrigid DEM contacts. Each body keeps its own layer; contact is
/// sought only where the bodies meet: every cell is marked with the bodies
/// whose points lie in it, a point is a candidate when a body it has a law
/// with lies in its cell or the eight around it (the cells whose nodes carry
/// the mass of both layers), and candidates of different bodies in
/// neighbouring cells are tested disk against disk (a disk's radius is at
/// most half a cell, so overlapping disks are never further apart). Each overlap
/// gets eq. 18 with the pair's law: the normal from q to p, δ the overlap,
/// the relative velocity at the contact point, the tangential spring kept
/// per pair while in contact. The relative velocity is, for a pair in
/// contact last step, the actual relative motion over that step of the two
/// materials at last step's contact point, (Δ(x_p − x_q) + (L_p a_p −
/// L_q a_q) Δt)/Δt with a the arms from the centres and L the gradients of
/// the velocity that moved the points, and for a new pair that of the FLIP
/// velocities, V_p − V_q (see `compute_rigid_contacts` for why the actual
/// motion). Equal and opposite forces go to the two points' `contact_force`,
/// pairs in (body, point, body, point) order.
///
/// The cost grows with the points (one cell lookup each) and the candidates
/// near other bodies, not with the pairs of bodies or the grid. The cell
/// lookups, the candidate search and the disk tests run in parallel over
/// fixed chunks whose buffers are reused; the sorted outputs make the result
/// independent of the thread count.
///
/// Reads: `Grid`, `Clock`, `BodyIndex`, `MaterialPoints` (position,
/// velocity, velocity gradient, contact radius). Writes: `BodyContacts`,
/// `MaterialPoints::contact_force`.
pub fn compute_body_contacts(
    grid: Res<Grid>,
    clock: Res<Clock>,
    mut contacts: ResMut<BodyContacts>,
    mut bodies: Query<(Entity, &BodyIndex, &mut MaterialPoints)>,
) {
    if contacts.laws.is_empty() {
        return;
    }
    let cells = CellIndex::new(&grid);
    let BodyContacts {
        laws,
        current,
        previous,
        cell_bodies,
        near_bodies,
        marked_cells,
        point_cells,
        candidates,
        chunks,
    } = &mut *contacts;
    std::mem::swap(previous, current);
    current.clear();
    // Each body's points and entity at its scene index, which the laws and
    // the one-bit-per-body cell marks use (at most MAX bodies take part; a
    // body a user has removed leaves its slot empty).
    let mut slots: [Option<(Entity, &MaterialPoints)>; MAX_CONTACT_BODIES] =
        [None; MAX_CONTACT_BODIES];
    for (entity, index, points) in bodies.iter() {
        if let Some(slot) = slots.get_mut(index.0 as usize) {
            *slot = Some((entity, points));
        }
    }
    let used = slots.iter().rposition(Option::is_some).map_or(0, |k| k + 1);
    let points = slots.map(|slot| slot.map(|(_, p)| p));
    let points = &points[..used];

    // Each point's cell (in parallel), then every cell marked with the
    // bodies whose points lie in it. Only last step's marked cells are
    // cleared, so the cost follows the points, not the grid (the marks are
    // sized once, or again when the grid changes).
    if cell_bodies.len() == cells.count() {
        for &(cell, _) in marked_cells.iter() {
            cell_bodies[cell as usize] = 0;
            near_bodies[cell as usize] = 0;
        }
    } else {
        for marks in [&mut *cell_bodies, &mut *near_bodies] {
            marks.clear();
            marks.resize(cells.count(), 0);
        }
    }
    marked_cells.clear();
    point_cells.resize_with(points.len(), Vec::new);
    for (k, (own, body)) in point_cells.iter_mut().zip(points).enumerate() {
        let Some(body) = body else {
            own.clear();
            continue;
        };
        own.resize(body.len(), 0);
        own.par_iter_mut()
            .zip(body.position.par_iter())
            .with_min_len(MIN_POINTS_PER_TASK)
            .for_each(|(cell, x)| *cell = cells.of(*x) as u32);
        for &cell in own.iter() {
            let mark = &mut cell_bodies[cell as usize];
            if *mark == 0 {
                marked_cells.push((cell, 0));
            }
            *mark |= 1 << k;
        }
    }
    // The bodies in the 3 x 3 cells around each marked cell, found once per
    // cell (in parallel) rather than once per point.
    let marks: &[u64] = cell_bodies;
    marked_cells
        .par_iter_mut()
        .with_min_len(MIN_POINTS_PER_TASK)
        .for_each(|(cell, around)| *around = cells.mask_around(marks, *cell as usize));
    for &(cell, around) in marked_cells.iter() {
        near_bodies[cell as usize] = around;
    }
    let near: &[u64] = near_bodies;

    // Candidates: points with a body they have a law with in their 3 x 3
    // cells, gathered per chunk of points, then sorted by (cell, body, point).
    candidates.clear();
    chunks.resize_with(CHUNKS, Default::default);
    for (k, own) in point_cells.iter().enumerate() {
        let wanted = partners(laws, k as u32);
        if wanted == 0 || points[k].is_none() {
            continue;
        }
        let per_chunk = own.len().div_ceil(CHUNKS).max(1);
        chunks.par_iter_mut().enumerate().for_each(|(c, chunk)| {
            chunk.candidates.clear();
            let range = (c * per_chunk).min(own.len())..((c + 1) * per_chunk).min(own.len());
            // Room for every point of the range at once, so the buffer is
            // sized on the first step, not as contact spreads.
            chunk.candidates.reserve(range.len());
            for p in range {
                let cell = own[p] as usize;
                if near[cell] & wanted != 0 {
                    chunk.candidates.push((cell as u32, k as u32, p as u32));
                }
            }
        });
        for chunk in chunks.iter() {
            candidates.extend_from_slice(&chunk.candidates);
        }
    }
    candidates.sort_unstable();

    // Disk–disk tests of each candidate against the candidates of bodies
    // after it in its 3 x 3 cells; every pair is found once, from its lower
    // body. Chunks of candidates run in parallel; the contacts are sorted by
    // key afterwards, so the result does not depend on the split.
    let dt = clock.dt;
    let candidates: &[(u32, u32, u32)] = candidates;
    let previous: &[BodyPairContact] = previous;
    let per_chunk = candidates.len().div_ceil(CHUNKS).max(1);
    chunks.par_iter_mut().enumerate().for_each(|(c, chunk)| {
        chunk.contacts.clear();
        let range =
            (c * per_chunk).min(candidates.len())..((c + 1) * per_chunk).min(candidates.len());
        for &(cell, a, p) in &candidates[range] {
            let Some(first) = points[a as usize] else {
                continue;
            };
            for row in cells.rows_around(cell as usize) {
                let start = candidates.partition_point(|c| (c.0 as usize) < row.start);
                for &(_, b, q) in candidates[start..]
                    .iter()
                    .take_while(|c| (c.0 as usize) < row.end)
                {
                    if b <= a {
                        continue;
                    }
                    let (Some(&law), Some(second)) = (law_between(laws, a, b), points[b as usize])
                    else {
                        continue;
                    };
                    if let Some(contact) =
                        disk_pair(&law, (a, first, p), (b, second, q), previous, dt)
                    {
                        chunk.contacts.push(contact);
                    }
                }
            }
        }
    });
    for chunk in chunks.iter() {
        current.extend_from_slice(&chunk.contacts);
    }
    current.sort_unstable_by_key(BodyPairContact::key);
    let entities = slots.map(|slot| slot.map(|(entity, _)| entity));
    for contact in current.iter() {
        for (body, point, force) in [
            (contact.a, contact.p, contact.force),
            (contact.b, contact.q, -contact.force),
        ] {
            if let Some(entity) = entities[body as usize]
                && let Ok((_, _, mut points)) = bodies.get_mut(entity)
            {
                points.contact_force[point as usize] += force;
            }
        }
    }
}

/// Chunks the detection's loops are split into: enough to balance the
/// cores, few enough that each chunk's buffer is reused step after step.
const CHUNKS: usize = 16;

/// The bodies `body` has a law with, one bit per body.
fn partners(laws: &[BodyPairLaw], body: u32) -> u64 {
    laws.iter().fold(0u64, |mask, l| {
        if l.a == body {
            mask | 1 << l.b
        } else if l.b == body {
            mask | 1 << l.a
        } else {
            mask
        }
    })
}

/// Eq. 18 between point `p` of body `a` and point `q` of body `b` (a < b)
/// if their disks overlap: the normal from q to p, δ the overlap, the
/// relative velocity at the middle of the overlap (the materials' actual
/// motion there over the last step, or for a new pair the FLIP
/// velocities), the pair's
/// tangential spring from `previous` (sorted by key).
fn disk_pair(
    law: &ContactLaw,
    (a, first, p): (u32, &MaterialPoints, u32),
    (b, second, q): (u32, &MaterialPoints, u32),
    previous: &[BodyPairContact],
    dt: Real,
) -> Option<BodyPairContact> {
    let (xp, rp) = (first.position[p as usize], first.contact_radius[p as usize]);
    let (xq, rq) = (
        second.position[q as usize],
        second.contact_radius[q as usize],
    );
    let DiskOverlap {
        normal,
        overlap,
        at,
        separation: gap,
    } = disk_overlap(xp, rp, xq, rq)?;
    let key = (a, p, b, q);
    let before = previous
        .binary_search_by(|c| c.key().cmp(&key))
        .ok()
        .map(|k| &previous[k]);
    let relative = match before {
        Some(c) => {
            let (arm_p, arm_q) = c.arms(rp, rq);
            let turned = first.velocity_gradient[p as usize] * arm_p
                - second.velocity_gradient[q as usize] * arm_q;
            (gap - c.separation) / dt + turned
        }
        None => first.velocity[p as usize] - second.velocity[q as usize],
    };
    let carried = before.map_or(DVec2::ZERO, |c| c.tangential);
    let f = pair_force(law, overlap, normal, relative, carried, dt);
    let spring_work_correction = match before {
        Some(_) => 0.5 * (f.tangential - carried).dot(relative * dt),
        None => 0.0,
    };
    Some(BodyPairContact {
        a,
        p,
        b,
        q,
        force: f.force,
        tangential: f.tangential,
        overlap,
        at,
        radius: 0.5 * (rp + rq),
        separation: gap,
        spring_work_correction,
    })
}

/// Row-major cells of the grid: the cell of a position (clamped to the
/// grid) and the cells around a cell.
struct CellIndex {
    origin: DVec2,
    inverse_size: Real,
    nx: usize,
    ny: usize,
    /// The last cell's place, (nx − 1, ny − 1).
    last: DVec2,
}

impl CellIndex {
    fn new(grid: &Grid) -> Self {
        Self {
            origin: grid.origin,
            inverse_size: 1.0 / grid.cell_size,
            nx: grid.cells[0],
            ny: grid.cells[1],
            last: DVec2::new(grid.cells[0] as Real - 1.0, grid.cells[1] as Real - 1.0),
        }
    }

    fn count(&self) -> usize {
        self.nx * self.ny
    }

    fn of(&self, x: DVec2) -> usize {
        // Clamped into [0, n − 1] cells first: truncation is then the
        // floor, and the index lies in the grid.
        let c = ((x - self.origin) * self.inverse_size)
            .max(DVec2::ZERO)
            .min(self.last);
        c.y as u32 as usize * self.nx + c.x as u32 as usize
    }

    /// The cells of the 3 x 3 block around `cell` (fewer at the edges), as
    /// one range of row-major indices per row.
    fn rows_around(&self, cell: usize) -> impl Iterator<Item = std::ops::Range<usize>> {
        let (i, j) = (cell % self.nx, cell / self.nx);
        let (low, high) = (i.saturating_sub(1), (i + 1).min(self.nx - 1));
        let nx = self.nx;
        (j.saturating_sub(1)..=(j + 1).min(self.ny - 1))
            .map(move |row| row * nx + low..row * nx + high + 1)
    }

    /// The OR of `marks` over the 3 x 3 block around `cell`.
    fn mask_around(&self, marks: &[u64], cell: usize) -> u64 {
        let mut mask = 0;
        for row in self.rows_around(cell) {
            for m in &marks[row] {
                mask |= m;
            }
        }
        mask
    }
}
