//! Algorithm 1, lines 14–15: nodal forces and the momentum update (eqs. 7a, 8a, 8b).

use crate::components::{GridLayer, MaterialPoints, TransferScratch};
use crate::distributed::{Domain, foreign_patches};
use crate::math::{DVec2, Real, local_damping};
use crate::resources::{Clock, Geometry, Settings, SharedLayers};
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Scatters the internal force f_i,int = −Σ_p V_p σ_p · G_ip (in
/// axisymmetry also −Σ_p V_p σ_θθ,p S_ip / r_p along r), sums it over
/// the layers of a contact group (`SharedLayers`), then per node
/// f_i = f_ext + f_int, less grid damping α_g |f| sign(v) per component
/// (Cundall 1987), p_i ← p_i + f_i Δt and v_i^{n+1} = p_i / m_i, constrained;
/// with grid damping, also the undamped v^{n+1} for the energy balance.
///
/// Reads: `Settings`, `Clock`, `MaterialPoints` (volume, stress; in
/// axisymmetry position and half-size),
/// `TransferScratch::stencils` and `order`, `GridLayer::nodes` (mass, external force, velocity).
/// Writes: `TransferScratch::internal_force`, `GridLayer::nodes` (internal force, momentum, new velocity),
/// `SharedLayers` (scratch), `TransferScratch::undamped`.
pub fn solve_nodal_momentum(
    settings: Res<Settings>,
    clock: Res<Clock>,
    mut shared: ResMut<SharedLayers>,
    mut bodies: Query<(&MaterialPoints, &mut GridLayer, &mut TransferScratch)>,
    domain: Option<NonSend<Domain>>,
) {
    let (dt, alpha) = (clock.dt, settings.grid_damping);
    for (points, mut layer, mut scratch) in &mut bodies {
        let TransferScratch {
            stencils,
            order,
            internal_force,
            ..
        } = &mut *scratch;
        match settings.geometry {
            Geometry::PlaneStrain => internal_force.scatter(
                stencils,
                order,
                |p| (points.volume[p], points.stress[p]),
                |(volume, stress), _, g, _| -*volume * stress.dot(g),
            ),
            // The hoop stress's share of the virtual work, σ_θθ δε_θθ with
            // δε_θθ = δu_r N_i / r: −V_p σ_θθ S_ip / r_p along r.
            Geometry::Axisymmetric => internal_force.scatter(
                stencils,
                order,
                |p| {
                    let hoop = points.stress[p].zz / points.hoop_radius(p);
                    (points.volume[p], points.stress[p], hoop)
                },
                |(volume, stress, hoop), w, g, _| {
                    -*volume * (stress.dot(g) + DVec2::new(hoop * w, 0.0))
                },
            ),
        }
        let window = layer.window();
        let foreign = foreign_patches(domain.as_deref(), internal_force);
        let active = layer.active();
        internal_force.add_into_with(&foreign, layer.nodes_mut(), (window, active), |n, f| {
            n.internal_force += f
        });
    }
    shared.share(
        |entity, f| {
            if let Ok((_, mut layer, _)) = bodies.get_mut(entity) {
                f(&mut layer);
            }
        },
        |sum, n| sum.internal_force += n.internal_force,
        |n, sum| n.internal_force = sum.internal_force,
    );
    for (_, mut layer, mut scratch) in &mut bodies {
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
        if alpha != 0.0 {
            undamped_velocities(&layer, alpha, dt, &mut scratch.undamped);
        }
    }
}

/// Fills `undamped` with the nodal velocity v^{n+1} the layer's active
/// nodes would have without grid damping, constrained alike: the energy
/// balance measures what grid damping took at the points against it (see
/// [`crate::components::DampedEnergy`]). Nodes outside the active ones keep earlier values:
/// no stencil reaches them.
fn undamped_velocities(layer: &GridLayer, alpha: Real, dt: Real, undamped: &mut Vec<DVec2>) {
    let (active, window, nodes) = (layer.active(), layer.window(), layer.nodes());
    let cutoff = layer.mass_cutoff;
    undamped.resize(nodes.len(), DVec2::ZERO);
    active.rows_mut(window, undamped).for_each(|(j, row)| {
        for (v, n) in row.iter_mut().zip(active.row(window, nodes, j)) {
            *v = if n.mass > cutoff {
                // The momentum holds the damped force's impulse: swap it
                // for the undamped one's.
                let force = n.external_force + n.internal_force;
                let damping = local_damping(force, n.velocity, alpha) - force;
                (n.momentum - damping * dt) / n.mass
            } else {
                DVec2::ZERO
            };
        }
    });
    layer.constrain(undamped);
}
