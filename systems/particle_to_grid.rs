//! Algorithm 1, line 12: mass, momentum and external force to each body's
//! layer (eqs. 7b, 8c, 8d; the momentum affine with
//! `Settings::affine_transfer`), then the nodal velocity p_i / m_i.

use crate::components::{
    BodyAcceleration, BodyName, GridLayer, MassMomentumForce, Material, MaterialPoints, NodeRect,
    TransferScratch,
};
use crate::contact::ForceApplication;
use crate::distributed::{Domain, foreign_patches};
use crate::math::DVec2;
use crate::resources::{
    Clock, ContactSettings, Diagnostics, FailureSite, Gravity, Grid, NumericalFailure, Settings,
    SharedLayers,
};
use crate::shape_functions::Stencil;
use bevy_ecs::prelude::*;

/// The resources P2G reads.
type StepInputs<'w> = (
    Res<'w, Grid>,
    Res<'w, Settings>,
    Res<'w, Gravity>,
    Res<'w, ContactSettings>,
    Res<'w, Clock>,
);

/// The bodies' components that the particle-to-grid transfer reads and
/// writes.
type P2gData = (
    &'static BodyName,
    Option<&'static BodyAcceleration>,
    &'static MaterialPoints,
    &'static mut GridLayer,
    &'static mut TransferScratch,
    &'static Material,
);

/// Computes every point's stencil at x^n and the step's scatter order,
/// scatters S_ip m_p, S_ip m_p V_p (with `Settings::affine_transfer`,
/// S_ip m_p (V_p + C_p (x_i − x̄_p)), x̄_p = Σ_i S_ip x_i, x_p away from walls) and
/// S_ip (m_p (g + b(t)) + f_p,ext [+ f_p,contact in `BodyForce` mode]) to
/// the body's layer (b the body's own `BodyAcceleration`, if any, at the
/// step's start time), makes the layers of a contact group their sum
/// (`SharedLayers`), and sets the nodal velocity,
/// constrained (with `Settings::flip_from_unconstrained`, and for a body
/// that takes the granular relaxation, keeping what the constraints took
/// in `TransferScratch::held_back`). A point whose support leaves the grid is reported as a
/// numerical failure and contributes nothing.
///
/// Reads: `Grid`, `Settings`, `Gravity`, `ContactSettings`, `Clock`, `BodyName`,
/// `BodyAcceleration`, `MaterialPoints`, `Material` (whether the body is
/// granular).
/// Writes: `TransferScratch` (stencils, order, patches, held back), `GridLayer::nodes` (mass, momentum, external force, velocity),
/// `SharedLayers` (scratch), `Diagnostics`.
pub fn particle_to_grid(
    (grid, settings, gravity, contact, clock): StepInputs,
    mut diagnostics: ResMut<Diagnostics>,
    mut shared: ResMut<SharedLayers>,
    mut bodies: Query<P2gData>,
    domain: Option<NonSend<Domain>>,
) {
    let nodes = grid.nodes();
    let stencil_grid = grid.stencil_grid();
    let cell = grid.cell_size;
    let (kernel, g) = (settings.shape_function, gravity.0);
    let body_force = contact.force_application == ForceApplication::BodyForce;
    for (name, own, points, mut layer, mut scratch, _) in &mut bodies {
        let g = g + own.map_or(DVec2::ZERO, |a| a.at(clock.time));
        let TransferScratch {
            stencils,
            stencil_bases,
            order,
            mass_momentum,
            ..
        } = &mut *scratch;
        stencils.resize(points.len(), Stencil::default());
        stencil_bases.resize(points.len(), [0; 2]);
        let outside = kernel.fill_stencils(
            &points.position,
            &points.half_size,
            &stencil_grid,
            (stencils, stencil_bases),
        );
        if let Some(p) = outside {
            // Its stencil is a zero one at node (0, 0): store the whole grid
            // so every index stays valid until the run stops.
            layer.expand(NodeRect::whole(nodes));
            diagnostics.report(NumericalFailure {
                step: clock.step + 1,
                time: clock.time,
                at: FailureSite::Point {
                    body: name.0.clone(),
                    point: p,
                },
                field: "position",
                detail: grid.why_outside(points.position[p], points.half_size[p]),
            });
        }
        let window = layer.window();
        order.sort_by_tile(stencil_bases, window, layer.grid_nodes());
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
                    (points.mass[p], velocity, force_on(p))
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
                |p| (points.mass[p], points.velocity[p], force_on(p)),
                |&(m, v, f), w, _, _| MassMomentumForce {
                    mass: w * m,
                    momentum: (w * m) * v,
                    external_force: w * f,
                },
            );
        }
        let foreign = foreign_patches(domain.as_deref(), mass_momentum);
        let active = layer.active();
        mass_momentum.add_into_with(&foreign, layer.nodes_mut(), (window, active), |n, t| {
            n.mass += t.mass;
            n.momentum += t.momentum;
            n.external_force += t.external_force;
        });
    }
    shared.share(
        |entity, f| {
            if let Ok((.., mut layer, _, _)) = bodies.get_mut(entity) {
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
    for (.., mut layer, mut scratch, material) in &mut bodies {
        let cutoff = layer.mass_cutoff;
        layer.for_each_active(|n| {
            n.velocity = if n.mass > cutoff {
                n.momentum / n.mass
            } else {
                DVec2::ZERO
            };
        });
        if settings.flip_from_unconstrained
            || settings.relaxes(material.model.as_model().granular())
        {
            let held_back = &mut scratch.held_back;
            held_back.clear();
            held_back.resize(layer.nodes().len(), DVec2::ZERO);
            layer.for_each_constrained(|fix, k, n| {
                let free = n.velocity;
                fix.apply(&mut n.velocity);
                held_back[k] = n.velocity - free;
            });
        } else {
            layer.apply_constraints(|n| &mut n.velocity);
        }
    }
}
