//! Algorithm 1, lines 14–15: nodal forces and the momentum update (eqs. 7a, 8a, 8b).

use crate::components::{DampedEnergy, GridLayer, MaterialPoints, TransferScratch};
use crate::math::{DVec2, Real, local_damping};
use crate::resources::{Clock, Settings, SharedLayers};
use bevy_ecs::prelude::*;

/// Scatters the internal force f_i,int = −Σ_p V_p σ_p · G_ip, sums it over
/// the layers of a contact group (`SharedLayers`), then per node
/// f_i = f_ext + f_int, less grid damping α_g |f| sign(v) per component
/// (Cundall 1987), p_i ← p_i + f_i Δt and v_i^{n+1} = p_i / m_i, constrained;
/// adds what grid damping took to the body's `DampedEnergy`.
///
/// Reads: `Settings`, `Clock`, `SharedLayers::groups`, `MaterialPoints` (volume, stress),
/// `TransferScratch::stencils` and `order`, `GridLayer::nodes` (mass, external force, velocity).
/// Writes: `TransferScratch::internal_force`, `GridLayer::nodes` (internal force, momentum, new velocity),
/// `SharedLayers` (scratch), `DampedEnergy`.
pub fn solve_nodal_momentum(
    settings: Res<Settings>,
    clock: Res<Clock>,
    mut shared: ResMut<SharedLayers>,
    mut bodies: Query<(
        Entity,
        &MaterialPoints,
        &mut GridLayer,
        &mut TransferScratch,
        &mut DampedEnergy,
    )>,
) {
    let (dt, alpha) = (clock.dt, settings.grid_damping);
    for (_, points, mut layer, mut scratch, _) in &mut bodies {
        let TransferScratch {
            stencils,
            order,
            internal_force,
            ..
        } = &mut *scratch;
        internal_force.scatter(
            stencils,
            order,
            |p| (points.volume[p], points.stress[p]),
            |(volume, stress), _, g| -*volume * stress.dot(g),
        );
        let window = layer.window();
        internal_force.add_into(layer.nodes_mut(), window, |n, f| n.internal_force += f);
    }
    shared.share(
        |entity, f| {
            if let Ok((_, _, mut layer, ..)) = bodies.get_mut(entity) {
                f(&mut layer);
            }
        },
        |sum, n| sum.internal_force += n.internal_force,
        |n, sum| n.internal_force = sum.internal_force,
    );
    for (entity, _, mut layer, _, mut damped) in &mut bodies {
        let cutoff = layer.mass_cutoff;
        layer.for_each_active(|n| {
            if n.mass <= cutoff {
                n.velocity_new = DVec2::ZERO;
                return;
            }
            let force = n.external_force + n.internal_force;
            n.momentum += local_damping(force, n.velocity, alpha) * dt;
            n.velocity_new = n.momentum / n.mass;
        });
        layer.apply_constraints(|n| &mut n.velocity_new);
        if alpha != 0.0 && !shared.groups.iter().any(|g| g[1..].contains(&entity)) {
            damped.0 += work_taken_by_grid_damping(&layer, alpha, dt);
        }
    }
}

/// The energy grid damping took from the layer's nodes this step,
/// −Σ_i d_i · ½(v_i^n + v_i^{n+1}) Δt with d_i the damping force (the
/// constrained components of both velocities are zero: no work there).
/// Node by node in row order, on one thread: the same sum for any thread
/// count (a pass over the active nodes, with grid damping only: about a
/// hundredth of a step's cost).
fn work_taken_by_grid_damping(layer: &GridLayer, alpha: Real, dt: Real) -> Real {
    let (active, window, nodes) = (layer.active(), layer.window(), layer.nodes());
    let cutoff = layer.mass_cutoff;
    let mut taken = 0.0;
    for j in active.start[1]..active.end[1] {
        for n in active.row(window, nodes, j) {
            if n.mass > cutoff {
                let force = n.external_force + n.internal_force;
                let damping = local_damping(force, n.velocity, alpha) - force;
                taken -= damping.dot(0.5 * (n.velocity + n.velocity_new)) * dt;
            }
        }
    }
    taken
}
