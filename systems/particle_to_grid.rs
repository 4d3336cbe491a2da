//! Algorithm 1, line 12: mass, momentum and external force to each body's
//! layer (eqs. 7b, 8c, 8d; the momentum affine with
//! `Settings::affine_transfer`), then the nodal velocity p_i / m_i.

use crate::components::{
    BodyAcceleration, BodyName, GridLayer, MassMomentumForce, MaterialPoints, NodeRect,
    TransferScratch,
};
use crate::contact::ForceApplication;
use crate::math::DVec2;
use crate::math::Real;
use crate::resources::{
    Clock, ContactSettings, Diagnostics, Geometry, Gravity, Grid, NumericalFailure, Settings,
    SharedLayers,
};
use crate::shape_functions::Stencil;
use crate::transfer::MIN_POINTS_PER_TASK;
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// The resources P2G reads.
type StepInputs<'w> = (
    Res<'w, Grid>,
    Res<'w, Settings>,
    Res<'w, Gravity>,
    Res<'w, ContactSettings>,
    Res<'w, Clock>,
);

/// Computes every point's stencil at x^n and the step's scatter order,
/// scatters S_ip m_p, S_ip m_p V_p (with `Settings::affine_transfer`,
/// S_ip m_p (V_p + C_p (x_i − x̄_p)), x̄_p = Σ_i S_ip x_i, x_p away from walls) and
/// S_ip (m_p (g + b(t)) + f_p,ext [+ f_p,contact in `BodyForce` mode]) to
/// the body's layer (b the body's own `BodyAcceleration`, if any, at the
/// step's start time), makes the layers of a contact group their sum
/// (`SharedLayers`), and sets the nodal velocity,
/// constrained. A point whose support leaves the grid is reported as a
/// numerical failure and contributes nothing.
///
/// Reads: `Grid`, `Settings`, `Gravity`, `ContactSettings`, `Clock`, `BodyName`,
/// `BodyAcceleration`, `MaterialPoints`.
/// Writes: `TransferScratch` (stencils, order, patches), `GridLayer::nodes` (mass, momentum, external force, velocity),
/// `SharedLayers` (scratch), `Diagnostics`.
pub fn particle_to_grid(
    (grid, settings, gravity, contact, clock): StepInputs,
    mut diagnostics: ResMut<Diagnostics>,
    mut shared: ResMut<SharedLayers>,
    mut bodies: P2gBodies,
) {
    let nodes = grid.nodes();
    let stencil_grid = grid.stencil_grid();
    let cell = grid.cell_size;
    let (kernel, g) = (settings.shape_function, gravity.0);
    let body_force = contact.force_application == ForceApplication::BodyForce;
    let axisymmetric = settings.geometry == Geometry::Axisymmetric;
    for (name, own, points, mut layer, mut scratch) in &mut bodies {
        let g = g + own.map_or(DVec2::ZERO, |a| a.at(clock.time));
        let TransferScratch {
            stencils,
            order,
            mass_momentum,
            planar_weight,
            ..
        } = &mut *scratch;
        stencils.resize(points.len(), Stencil::default());
        let outside =
            kernel.fill_stencils(&points.position, &points.half_size, &stencil_grid, stencils);
        if let Some(p) = outside {
            // Its stencil is a zero one at node (0, 0): store the whole grid
            // so every index stays valid until the run stops.
            layer.expand(NodeRect::whole(nodes));
            diagnostics.report(NumericalFailure {
                step: clock.step + 1,
                time: clock.time,
                body: name.0.clone(),
                point: p,
                field: "position",
                detail: grid.why_outside(points.position[p], points.half_size[p]),
            });
        }
        let window = layer.window();
        order.sort_by_row(stencils, window);
        // The weights of the velocity projection: the masses, or in
        // axisymmetry the masses per unit radius (see below).
        let weights: &[Real] = if axisymmetric {
            planar_weight.resize(points.len(), 0.0);
            planar_weight
                .par_iter_mut()
                .enumerate()
                .with_min_len(MIN_POINTS_PER_TASK)
                .for_each(|(p, w)| *w = points.mass[p] / points.hoop_radius(p));
            planar_weight
        } else {
            &points.mass
        };
        let force_on = |p: usize| {
            let contact = if body_force {
                points.contact_force[p]
            } else {
                DVec2::ZERO
            };
            points.mass[p] * g + points.external_force[p] + contact
        };
        if settings.affine_transfer {
            let stencils = &*stencils;
            mass_momentum.scatter(
                stencils,
                order,
                |p| {
                    let mean = stencils[p].mean_place();
                    let velocity = (points.velocity[p], points.affine_gradient[p], mean);
                    (weights[p], velocity, force_on(p))
                },
                |&(m, (v, c, mean), f), w, _, node| {
                    let offset = Stencil::offset_from_mean(mean, node, cell);
                    MassMomentumForce {
                        mass: w * m,
                        momentum: (w * m) * (v + c * offset),
                        external_force: w * f,
                    }
                },
            );
        } else {
            mass_momentum.scatter(
                stencils,
                order,
                |p| (weights[p], points.velocity[p], force_on(p)),
                |&(m, v, f), w, _, _| MassMomentumForce {
                    mass: w * m,
                    momentum: (w * m) * v,
                    external_force: w * f,
                },
            );
        }
        mass_momentum.add_into(layer.nodes_mut(), window, |n, t| {
            n.mass += t.mass;
            n.momentum += t.momentum;
            n.external_force += t.external_force;
        });
    }
    shared.share(
        |entity, f| {
            if let Ok((.., mut layer, _)) = bodies.get_mut(entity) {
                f(&mut layer);
            }
        },
        |sum, n| {
            sum.mass += n.mass;
            sum.momentum += n.momentum;
            sum.external_force += n.external_force;
        },
        |n, sum| {
            n.mass = sum.mass;
            n.momentum = sum.momentum;
            n.external_force = sum.external_force;
        },
    );
    if axisymmetric {
        project_per_radian(&mut shared, &mut bodies);
    }
    for (.., mut layer, _) in &mut bodies {
        let cutoff = layer.mass_cutoff;
        layer.for_each_active(|n| {
            n.velocity = if n.mass > cutoff {
                n.momentum / n.mass
            } else {
                DVec2::ZERO
            };
        });
        layer.apply_constraints(|n| &mut n.velocity);
    }
}

/// The bodies P2G reads and writes.
type P2gBodies<'w, 's> = Query<
    'w,
    's,
    (
        &'static BodyName,
        Option<&'static BodyAcceleration>,
        &'static MaterialPoints,
        &'static mut GridLayer,
        &'static mut TransferScratch,
    ),
>;

/// Axisymmetry: the layers hold Σ S_ip m_p / r_p as their mass and
/// Σ S_ip (m_p / r_p) V_p as their momentum (scattered with the planar
/// weights); this turns them into the mass per radian m_i = Σ S_ip m_p,
/// which the momentum balance of per-radian forces takes, and the momentum
/// m_i v_i of the velocity v_i projected with the planar weights, which
/// is kept in `TransferScratch::planar_mass` for G2P's maps.
///
/// Why not project with the masses per radian: they grow with r, so the
/// projection leans outwards, most near the axis. Uniform expansion
/// v_r = a r with 2 × 2 points per cell gives the first node 1.19 a h and
/// the second 1.047 × 2 a h (a tester found the first cell's stress rate
/// 19% high); the planar weights give a h and 2 a h, as plane strain does.
/// The step's change of momentum, S_ip m_p Δv, is still the forces' impulse.
fn project_per_radian(shared: &mut SharedLayers, bodies: &mut P2gBodies) {
    for (_, _, points, mut layer, mut scratch) in bodies.iter_mut() {
        let TransferScratch {
            stencils,
            order,
            planar_mass,
            mass_per_radian,
            ..
        } = &mut *scratch;
        let (active, window) = (layer.active(), layer.window());
        planar_mass.resize(layer.nodes().len(), 0.0);
        active
            .rows_mut(window, planar_mass)
            .zip(active.rows_mut(window, layer.nodes_mut()))
            .for_each(|((_, planar), (_, nodes))| {
                for (planar, n) in planar.iter_mut().zip(nodes) {
                    *planar = n.mass;
                    // The velocity until the mass per radian is in.
                    n.velocity = if n.mass > 0.0 {
                        n.momentum / n.mass
                    } else {
                        DVec2::ZERO
                    };
                    n.mass = 0.0;
                }
            });
        mass_per_radian.scatter(stencils, order, |p| points.mass[p], |m, w, _, _| w * m);
        mass_per_radian.add_into(layer.nodes_mut(), window, |n, m| n.mass += m);
    }
    shared.share(
        |entity, f| {
            if let Ok((.., mut layer, _)) = bodies.get_mut(entity) {
                f(&mut layer);
            }
        },
        |sum, n| sum.mass += n.mass,
        |n, sum| n.mass = sum.mass,
    );
    for (.., mut layer, _) in bodies.iter_mut() {
        layer.for_each_active(|n| n.momentum = n.mass * n.velocity);
    }
}
