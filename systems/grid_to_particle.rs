//! Algorithm 1, line 16: velocity and position of the points (eqs. 11a/11b,
//! or XPIC, eqs. 12a/12b).

use crate::components::{
    DampedEnergy, GridLayer, Material, MaterialPoints, RemapScratch, StepTravel, TransferScratch,
};
use crate::distributed::{Domain, add_tile_sums, foreign_patches};
use crate::math::{DMat2, DVec2, Real, local_damping, outer};
use crate::parallel::MIN_POINTS_PER_TASK;
use crate::resources::{Clock, Grid, PositionUpdate, Settings, SharedLayers};
use crate::scatter::{Scatter, ScatterOrder};
use crate::shape_functions::Stencil;
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// The points' stencils and scatter order, and the domain of a distributed
/// run (the halo of each scatter).
type Transfer<'a> = (&'a [Stencil], &'a ScatterOrder, Option<&'a Domain>);

/// With v^n = Σ S_ip v_i^n, v^{n+1} = Σ S_ip v_i^{n+1} interpolated at x^n
/// and the point's acceleration a_p Δt = v^{n+1} − v^n, less particle
/// damping α_p |a_p| sign(V^n) per component:
/// * eq. 11a: V^{n+1} = (1 − β)(V^n + a_p Δt) + β (v^n + a_p Δt);
/// * eq. 11b: x^{n+1} = x^n + ½(v^n + v^{n+1}) Δt − ½ β (V^n − v^n) Δt, or
///   with `PositionUpdate::NewGridVelocity`, x^{n+1} = x^n + v^{n+1} Δt, or
///   with `PositionUpdate::RemappedVelocity`, x^{n+1} = x^n + Σ S_ip ṽ_i Δt,
///   ṽ_i the new point velocities mapped back to the nodes as P2G maps them
///   (mass-weighted, affine with `Settings::affine_transfer`, constrained,
///   summed over a contact group's members), which MUSL's stress update
///   reads too;
///
/// or, with an XPIC order m (eq. 12), v* = Σ_{k=1..m} (−1)^{k+1} C(m, k) u_k
/// on the nodes, u_1 = v_i^n and u_k = S⁺ S u_{k−1} (interpolated to the
/// points, mapped back mass-weighted, constrained), so that
/// S v* = [I − (I − S S⁺)^m] V^n:
/// * eq. 12a: V^{n+1} = Σ S_ip v*_i + a_p Δt;
/// * eq. 12b: x^{n+1} = x^n + v^n Δt + ½ (V^{n+1} − V^n) Δt.
///
/// A point the update would carry through a fixed or slip wall (the grid
/// velocity there has no normal component, but the PIC/FLIP terms of V_p can
/// still move it) is put back on the wall, and its velocity's component
/// into the wall removed.
///
/// Reads: `Grid`, `Settings`, `Clock`, `SharedLayers` (groups), `Material` (a
/// granular body's PIC fraction), `GridLayer`, `TransferScratch::stencils`, `held_back`,
/// `order` and `undamped`, `MaterialPoints` (mass, contact force: the
/// points in contact this step).
/// Writes: `MaterialPoints` (position, velocity, velocity gradient of the
/// motion; with `Settings::affine_transfer`, C_p = Σ_i v_i^{n+1} ⊗ G_ip for
/// the next P2G), `TransferScratch::remap`
/// and `damped`, `DampedEnergy` (what the update took from the points),
/// `StepTravel` (the largest |x^{n+1} − x^n|, a maximum, so exact for any
/// thread count).
pub fn grid_to_particle(
    grid: Res<Grid>,
    settings: Res<Settings>,
    clock: Res<Clock>,
    mut shared: ResMut<SharedLayers>,
    mut bodies: Query<G2pData>,
    domain: Option<NonSend<Domain>>,
) {
    let walls = grid.wall_bounds();
    let TransferOptions {
        dt,
        alpha,
        position_update,
        remapped,
        remaps,
        affine,
        order,
        moved_by: (of_old, of_new),
        grid_damped,
        takes,
        from_unconstrained,
    } = TransferOptions::new(&settings, clock.dt);
    for (mut points, mut travel, mut damped, layer, mut scratch, material) in &mut bodies {
        let granular = material.model.as_model().granular();
        let beta = settings.pic_fraction_for(granular, dt);
        let takes = takes || beta != 0.0;
        // The relaxation pulls toward the velocity the points map to the
        // nodes before the walls' constraints: the part of V_p the grid
        // does not carry, not what a no-slip wall holds back.
        let toward_free = settings.relaxes(granular) && !from_unconstrained;
        let TransferScratch {
            stencils,
            order: scatter_order,
            damped: taken,
            damped_by_tile,
            undamped,
            held_back,
            remap,
            ..
        } = &mut *scratch;
        if order >= 1 {
            let transfer = (&stencils[..], &*scatter_order, domain.as_deref());
            xpic_velocities(order, &points.mass, layer, transfer, remap);
        }
        let window = layer.window();
        let (origin, row_len) = (window.start.map(|k| k as u32), window.width());
        let MaterialPoints {
            position,
            velocity,
            velocity_gradient,
            affine_gradient,
            mass,
            contact_force,
            ..
        } = &mut *points;
        let touched = &*contact_force;
        let nodes = layer.nodes();
        let (star, undamped, held_back) = (&remap.star, &*undamped, &*held_back);
        taken.resize(position.len(), 0.0);
        travel.0 = (
            position.par_iter_mut(),
            velocity.par_iter_mut(),
            stencils.par_iter(),
            mass.par_iter(),
        )
            .into_par_iter()
            .with_min_len(MIN_POINTS_PER_TASK)
            .zip(taken.par_iter_mut())
            .zip((
                velocity_gradient.par_iter_mut(),
                affine_gradient.par_iter_mut(),
                touched.par_iter(),
            ))
            .map(|(((x, v, stencil, m), taken), (l, c, contact))| {
                let zero = (DVec2::ZERO, DVec2::ZERO);
                let (grid_old, grid_new) =
                    stencil.gather(nodes, origin, row_len, zero, |(old, new), node, w, _| {
                        (old + w * node.velocity, new + w * node.velocity_new)
                    });
                if affine {
                    *c = stencil.gather(nodes, origin, row_len, DMat2::ZERO, |c, node, _, g| {
                        c + outer(node.velocity_new, g)
                    });
                }
                // Remapped positions: taken below.
                *l = if *contact == DVec2::ZERO || remapped {
                    DMat2::ZERO
                } else {
                    stencil.gather(nodes, origin, row_len, DMat2::ZERO, |l, node, _, g| {
                        l + outer(of_old * node.velocity + of_new * node.velocity_new, g)
                    })
                };
                // The FLIP change's start: v^n, or p_i / m_i before the
                // walls' constraints.
                let free_start = (from_unconstrained || toward_free)
                    .then(|| grid_old - held_back_at(stencil, held_back, origin, row_len));
                let start = match free_start {
                    Some(free) if from_unconstrained => free,
                    _ => grid_old,
                };
                // At α = 0 this is the undamped change, bit for bit.
                let change = local_damping(grid_new - start, *v, alpha);
                // What the undamped pure FLIP update would give, for the
                // energy balance.
                let flip = if grid_damped {
                    let free = stencil.interpolate(undamped, origin, row_len);
                    *v + (free - start)
                } else {
                    *v + (grid_new - start)
                };
                let step = if order >= 1 {
                    let smoothed = stencil.interpolate(star, origin, row_len);
                    xpic_update(v, smoothed, change, grid_old, dt)
                } else {
                    // The PIC term's damped change is from v^n: the FLIP
                    // change itself unless that starts from p_i / m_i.
                    let pic_change = if from_unconstrained && alpha != 0.0 {
                        local_damping(grid_new - grid_old, *v, alpha)
                    } else {
                        change
                    };
                    let nodal = NodalVelocities {
                        old: grid_old,
                        new: grid_new,
                        change,
                        pic_change,
                        pic_start: free_start.filter(|_| toward_free),
                    };
                    flip_pic_update(v, nodal, (beta, alpha), position_update, dt)
                };
                if takes {
                    *taken = 0.5 * m * (flip.length_squared() - v.length_squared());
                }
                if remapped {
                    return 0.0;
                }
                move_point(x, v, step, walls)
            })
            .reduce(|| 0.0, Real::max);
        if remaps {
            let transfer = (&stencils[..], &*scatter_order, domain.as_deref());
            let affine = affine.then(|| AffineMap {
                gradient: affine_gradient,
                cell: grid.cell_size,
            });
            let RemapScratch {
                momentum, current, ..
            } = remap;
            scatter_momentum(mass, velocity, affine, layer, transfer, momentum, current);
        }
        if takes {
            // Tile by tile in the step's scatter order, tiles in order: the
            // same sum for any number of threads or processes.
            damped_by_tile.reserve(
                scatter_order
                    .grid_tiles()
                    .saturating_sub(damped_by_tile.len()),
            );
            scatter_order
                .tile_points()
                .map(|points| points.iter().map(|&p| taken[p as usize]).sum::<Real>())
                .collect_into_vec(damped_by_tile);
            damped.0 += add_tile_sums(domain.as_deref(), scatter_order.tiles(), damped_by_tile);
        }
    }
    if remaps {
        finish_the_remap(&mut shared, &mut bodies, remapped.then_some((dt, walls)));
    }
}

/// Σ S_ip of what the walls held back (`TransferScratch::held_back`): out
/// of line, so that the per-point update stays small enough to be inlined
/// where this option is off.
#[inline(never)]
fn held_back_at(stencil: &Stencil, held_back: &[DVec2], origin: [u32; 2], row_len: usize) -> DVec2 {
    stencil.interpolate(held_back, origin, row_len)
}

/// What the settings ask of the transfer, read once a step.
struct TransferOptions {
    dt: Real,
    /// The particle damping α.
    alpha: Real,
    position_update: Option<PositionUpdate>,
    /// Whether the points move by the remapped velocity.
    remapped: bool,
    /// Whether the points' new velocities are mapped back to the nodes.
    remaps: bool,
    affine: bool,
    /// The XPIC order, 0 for FLIP/PIC.
    order: u32,
    /// The nodal velocity that moves the points, as weights of v^n and
    /// v^{n+1} (none for the remapped one, taken apart): its gradient is
    /// the material's motion about each point in contact, which its
    /// contacts' springs take next step and whose work the balance counts.
    moved_by: (Real, Real),
    grid_damped: bool,
    /// Whether the update takes energy that the balance must count
    /// (undamped pure FLIP gives the FLIP update itself, bit for bit),
    /// whatever the PIC fraction.
    takes: bool,
    /// `Settings::flip_from_unconstrained`.
    from_unconstrained: bool,
}

impl TransferOptions {
    fn new(settings: &Settings, dt: Real) -> Self {
        let alpha = settings.particle_damping;
        let position_update = settings.position_update();
        let order = settings.xpic_order.unwrap_or(0);
        let grid_damped = settings.grid_damping != 0.0;
        Self {
            dt,
            alpha,
            position_update,
            remapped: position_update == Some(PositionUpdate::RemappedVelocity),
            remaps: settings.remaps_velocity(),
            affine: settings.affine_transfer,
            order,
            moved_by: match position_update {
                // Eq. 12b moves by S v^n + ½ (V^{n+1} − V^n) ≈ ½ S (v^n + v^{n+1}).
                None | Some(PositionUpdate::PaperEq11b) => (0.5, 0.5),
                Some(PositionUpdate::NewGridVelocity) => (0.0, 1.0),
                Some(PositionUpdate::RemappedVelocity) => (0.0, 0.0),
            },
            grid_damped,
            takes: alpha != 0.0 || order >= 1 || grid_damped,
            from_unconstrained: settings.flip_from_unconstrained,
        }
    }
}

/// The bodies' components that the grid-to-particle transfer reads and
/// writes.
type G2pData = (
    &'static mut MaterialPoints,
    &'static mut StepTravel,
    &'static mut DampedEnergy,
    &'static GridLayer,
    &'static mut TransferScratch,
    &'static Material,
);

/// Turns each body's remapped momentum into the remapped velocity field,
/// summed first over each contact group's members, which move with the
/// group's field; with `moving` (Δt and the walls) the points then move
/// by that field (the `RemappedVelocity` position update).
fn finish_the_remap(
    shared: &mut SharedLayers,
    bodies: &mut Query<G2pData>,
    moving: Option<(Real, (DVec2, DVec2))>,
) {
    shared.share_field(|entity, f| {
        if let Ok((.., layer, mut scratch, _)) = bodies.get_mut(entity) {
            f(layer, &mut scratch.remap.current);
        }
    });
    for (mut points, mut travel, _, layer, mut scratch, _) in bodies {
        momentum_to_velocity(layer, &mut scratch.remap.current);
        if let Some((dt, walls)) = moving {
            travel.0 = move_remapped(
                &mut points,
                &scratch.stencils,
                layer,
                &scratch.remap.current,
                dt,
                walls,
            );
        }
    }
}

/// A point's interpolated nodal velocities: v^n, v^{n+1}, the FLIP change
/// to v^{n+1} less particle damping (from v^n, or with
/// `Settings::flip_from_unconstrained` from p_i / m_i), the change from
/// v^n less particle damping for the PIC term, and under the granular
/// relaxation the start of the PIC term, p_i / m_i interpolated (the PIC
/// term is then that plus the change).
#[derive(Clone, Copy)]
struct NodalVelocities {
    old: DVec2,
    new: DVec2,
    change: DVec2,
    pic_change: DVec2,
    pic_start: Option<DVec2>,
}

/// Eqs. 12a/12b: V^{n+1} = S v* + a_p Δt (`smoothed` is S v*), and the step
/// x^{n+1} − x^n = (v^n + ½ (V^{n+1} − V^n)) Δt.
#[inline(always)]
fn xpic_update(v: &mut DVec2, smoothed: DVec2, change: DVec2, grid_old: DVec2, dt: Real) -> DVec2 {
    let next = smoothed + change;
    let step = (grid_old + 0.5 * (next - *v)) * dt;
    *v = next;
    step
}

/// Eq. 11a with PIC fraction β and particle damping α, and the step of the
/// position update (eq. 11b, the new grid velocity, or none for the
/// remapped velocity, which moves the points once every point has its new
/// velocity).
#[inline(always)]
fn flip_pic_update(
    v: &mut DVec2,
    nodal: NodalVelocities,
    (beta, alpha): (Real, Real),
    update: Option<PositionUpdate>,
    dt: Real,
) -> DVec2 {
    let NodalVelocities {
        old,
        new,
        change,
        pic_change,
        pic_start,
    } = nodal;
    let step = match update {
        Some(PositionUpdate::NewGridVelocity) => new * dt,
        Some(PositionUpdate::RemappedVelocity) => DVec2::ZERO,
        _ => (0.5 * (old + new) - 0.5 * beta * (*v - old)) * dt,
    };
    // Undamped, v^n + a_p Δt is v^{n+1} itself (kept exact).
    let pic = match pic_start {
        Some(free) => free + pic_change,
        None if alpha == 0.0 => new,
        None => old + pic_change,
    };
    *v = (1.0 - beta) * (*v + change) + beta * pic;
    step
}

/// Moves every point by x += Σ S_ip ṽ_i Δt (`PositionUpdate::RemappedVelocity`)
/// and, for the points in contact, sets the gradient of that motion; returns
/// the largest distance moved.
fn move_remapped(
    points: &mut MaterialPoints,
    stencils: &[Stencil],
    layer: &GridLayer,
    remapped_velocity: &[DVec2],
    dt: Real,
    walls: (DVec2, DVec2),
) -> Real {
    let window = layer.window();
    let (origin, row_len) = (window.start.map(|k| k as u32), window.width());
    let MaterialPoints {
        position,
        velocity,
        velocity_gradient,
        contact_force,
        ..
    } = points;
    (
        position.par_iter_mut(),
        velocity.par_iter_mut(),
        velocity_gradient.par_iter_mut(),
        stencils.par_iter(),
        contact_force.par_iter(),
    )
        .into_par_iter()
        .with_min_len(MIN_POINTS_PER_TASK)
        .map(|(x, v, l, stencil, contact)| {
            let u = stencil.interpolate(remapped_velocity, origin, row_len);
            if *contact != DVec2::ZERO {
                *l = stencil.gather(
                    remapped_velocity,
                    origin,
                    row_len,
                    DMat2::ZERO,
                    |l, node_u, _, g| l + outer(*node_u, g),
                );
            }
            move_point(x, v, u * dt, walls)
        })
        .reduce(|| 0.0, Real::max)
}

/// Moves a point by `step`, puts it back on a wall it would cross (its
/// velocity's component into the wall removed) and returns how far it moved.
#[inline(always)]
fn move_point(x: &mut DVec2, v: &mut DVec2, step: DVec2, (lo, hi): (DVec2, DVec2)) -> Real {
    let (before, moved) = (*x, *x + step);
    *x = moved.clamp(lo, hi);
    if x.x != moved.x {
        v.x = 0.0;
    }
    if x.y != moved.y {
        v.y = 0.0;
    }
    (*x - before).length()
}

/// What an affine map to the nodes needs besides the velocities (see
/// `Settings::affine_transfer`).
struct AffineMap<'a> {
    /// C_p of each point.
    gradient: &'a [DMat2],
    /// The cell size (m).
    cell: Real,
}

/// Maps point velocities back to the layer's active nodes:
/// u_i = Σ_p S_ip m_p V_p / m_i, or with `affine`
/// Σ_p S_ip m_p (V_p + C_p (x_i − x̄_p)) / m_i as P2G maps them (zero below
/// the layer's mass cutoff), constrained like the nodal velocities. Nodes
/// outside the active ones keep earlier values: no stencil reaches them.
fn map_to_nodes(
    mass: &[Real],
    velocity: &[DVec2],
    affine: Option<AffineMap>,
    layer: &GridLayer,
    transfer: Transfer,
    momentum: &mut Scatter<DVec2>,
    into: &mut Vec<DVec2>,
) {
    scatter_momentum(mass, velocity, affine, layer, transfer, momentum, into);
    momentum_to_velocity(layer, into);
}

/// Fills `into` on the layer's active nodes with the momentum
/// Σ_p S_ip m_p V_p, or with `affine` Σ_p S_ip m_p (V_p + C_p (x_i − x̄_p))
/// as P2G maps it. Nodes outside the active ones keep earlier values.
fn scatter_momentum(
    mass: &[Real],
    velocity: &[DVec2],
    affine: Option<AffineMap>,
    layer: &GridLayer,
    (stencils, scatter_order, domain): Transfer,
    momentum: &mut Scatter<DVec2>,
    into: &mut Vec<DVec2>,
) {
    let (active, window) = (layer.active(), layer.window());
    into.resize(layer.nodes().len(), DVec2::ZERO);
    if let Some(AffineMap { gradient, cell }) = affine {
        momentum.scatter(
            stencils,
            scatter_order,
            |p| (mass[p], velocity[p], gradient[p], stencils[p].mean_place()),
            |&(m, v, c, mean), w, _, node| {
                (w * m) * (v + c * Stencil::offset_from_mean(mean, node, cell))
            },
        );
    } else {
        momentum.scatter(
            stencils,
            scatter_order,
            |p| mass[p] * velocity[p],
            |mv, w, _, _| w * *mv,
        );
    }
    active
        .rows_mut(window, into)
        .for_each(|(_, row)| row.fill(DVec2::ZERO));
    let foreign = foreign_patches(domain, momentum);
    momentum.add_into_with(&foreign, into, (window, active), |u, mv| *u += mv);
}

/// Turns the nodal momentum in `field` into velocity on the layer's active
/// nodes, over the layer's nodal mass (zero below its mass cutoff), and
/// constrains it like the nodal velocities.
fn momentum_to_velocity(layer: &GridLayer, field: &mut [DVec2]) {
    let (active, window, nodes) = (layer.active(), layer.window(), layer.nodes());
    let cutoff = layer.mass_cutoff;
    active.rows_mut(window, field).for_each(|(j, row)| {
        for (u, node) in row.iter_mut().zip(active.row(window, nodes, j)) {
            *u = if node.mass > cutoff {
                *u / node.mass
            } else {
                DVec2::ZERO
            };
        }
    });
    layer.constrain(field);
}

/// Fills `remap.star` with the XPIC(m) nodal velocity v* of eq. 12 on the
/// layer's active nodes. Nodes outside them keep earlier values: no stencil
/// reaches them.
fn xpic_velocities(
    order: u32,
    mass: &[Real],
    layer: &GridLayer,
    (stencils, scatter_order, domain): Transfer,
    xpic: &mut RemapScratch,
) {
    let RemapScratch {
        point_velocity,
        momentum,
        previous,
        current,
        star,
    } = xpic;
    let (active, window, nodes) = (layer.active(), layer.window(), layer.nodes());
    let (origin, row_len) = (window.start.map(|k| k as u32), window.width());
    let m = Real::from(order);
    for field in [&mut *star, &mut *previous] {
        field.resize(nodes.len(), DVec2::ZERO);
    }
    active
        .rows_mut(window, star)
        .zip(active.rows_mut(window, previous))
        .for_each(|((j, star), (_, previous))| {
            let row = active.row(window, nodes, j);
            for ((s, u), node) in star.iter_mut().zip(previous.iter_mut()).zip(row) {
                *s = m * node.velocity;
                *u = node.velocity;
            }
        });
    point_velocity.resize(stencils.len(), DVec2::ZERO);
    let mut coefficient = m;
    for k in 2..=order {
        // C(m, k) = C(m, k − 1) (m − k + 1) / k, alternating in sign.
        coefficient *= -(m - Real::from(k) + 1.0) / Real::from(k);
        let from = &*previous;
        point_velocity
            .par_iter_mut()
            .zip(stencils.par_iter())
            .with_min_len(MIN_POINTS_PER_TASK)
            .for_each(|(v, stencil)| {
                *v = stencil.interpolate(from, origin, row_len);
            });
        map_to_nodes(
            mass,
            point_velocity,
            None,
            layer,
            (stencils, scatter_order, domain),
            momentum,
            current,
        );
        active
            .rows_mut(window, star)
            .zip(active.rows_mut(window, current))
            .for_each(|((_, star), (_, current))| {
                for (s, u) in star.iter_mut().zip(current.iter()) {
                    *s += coefficient * *u;
                }
            });
        std::mem::swap(previous, current);
    }
}
