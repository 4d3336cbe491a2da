//! Algorithm 1, line 10 (eq. 7b's traction term): surface loads to the
//! grid, and their work for the energy balance.

use super::contact_transfer::add_with_hat_functions;
use crate::components::{GridLayer, MaterialPoints};
use crate::math::DVec2;
use crate::resources::{Grid, LoadWork, Settings, StagePlan};
use crate::scene::Side;
use bevy_ecs::prelude::*;

/// Adds the surface tractions the stages set (`StageProgress::loads`) to
/// their bodies' layers: each loaded point's force at the middle of its
/// domain's outer edge on the loaded side, with the hat functions N_i.
/// This is eq. 7b's ∫ τ N_i dS over the surface the outermost domains
/// bound. (The same force mapped with S_ip at the point's centre loads only
/// the part of its domain below the centre: the outermost points then
/// carry about half the traction, and the top cell of a column under a
/// surcharge 70% of it.) The loads are dead: fixed forces, in the order
/// the stages set them. In axisymmetry a force per metre of the edge
/// times the edge's radius: per radian. Each applied force is kept in
/// `LoadWork::applied` with where its material is, for its work.
///
/// Reads: `Grid`, `Settings::geometry`, `StagePlan`, `MaterialPoints`
/// (position, half-size, deformation gradient).
/// Writes: `GridLayer` (external force), `LoadWork::applied`.
pub fn apply_surface_loads(
    grid: Res<Grid>,
    settings: Res<Settings>,
    plan: Option<Res<StagePlan>>,
    mut work: ResMut<LoadWork>,
    mut bodies: Query<(&MaterialPoints, &mut GridLayer)>,
) {
    work.applied.clear();
    let Some(plan) = plan else {
        return;
    };
    for load in &plan.progress.loads {
        let Ok((points, mut layer)) = bodies.get_mut(load.body) else {
            continue;
        };
        let outward = outward(load.side);
        for &(p, force) in &load.forces {
            let p = p as usize;
            let edge = points.position[p] + outward * points.half_size[p];
            // A domain pushed past the axis loads nothing there.
            let force = force * settings.geometry.thickness(edge).max(0.0);
            add_with_hat_functions(&grid, &mut layer, edge, force);
            work.applied
                .push((force, material_edge(points, p, outward)));
        }
    }
}

/// Adds the work of this step's surface loads to `LoadWork::work`: each
/// applied force times the motion over the step of the material at the
/// middle of its point's outer edge ([`material_edge`]; taken at the
/// points' centres, a column's settlement under a surcharge would be 2.5%
/// short for 20 points across it). Run after the points have moved and
/// before the stages can change the loads; the loads in the order they
/// were applied.
///
/// Reads: `StagePlan`, `MaterialPoints` (position, deformation gradient,
/// half-size). Writes: `LoadWork`.
pub fn account_load_work(
    plan: Option<Res<StagePlan>>,
    mut work: ResMut<LoadWork>,
    bodies: Query<&MaterialPoints>,
) {
    let Some(plan) = plan else {
        return;
    };
    let LoadWork { work, applied } = &mut *work;
    let mut next = 0;
    for load in &plan.progress.loads {
        let Ok(points) = bodies.get(load.body) else {
            continue;
        };
        let taken = &applied[next..next + load.forces.len()];
        next += load.forces.len();
        let outward = outward(load.side);
        for (&(p, _), (force, from)) in load.forces.iter().zip(taken) {
            *work += force.dot(material_edge(points, p as usize, outward) - *from);
        }
    }
}

/// Where the material at the middle of point `p`'s outer edge on the side
/// `outward` is: x_p + F_p A, A the arm from the point to that edge in the
/// undeformed domain. (The load itself acts at x_p + A: domains keep their
/// undeformed size; the work follows the material.)
fn material_edge(points: &MaterialPoints, p: usize, outward: DVec2) -> DVec2 {
    points.position[p] + points.deformation_gradient[p] * (outward * points.half_size[p])
}

/// The outward normal of a loaded side.
fn outward(side: Side) -> DVec2 {
    match side {
        Side::Top => DVec2::Y,
        Side::Bottom => DVec2::NEG_Y,
        Side::Right => DVec2::X,
        Side::Left => DVec2::NEG_X,
    }
}
