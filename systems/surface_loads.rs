//! Algorithm 1, line 10 (eq. 7b's traction term): surface loads to the grid.

use super::contact_transfer::add_with_hat_functions;
use crate::components::{GridLayer, MaterialPoints};
use crate::math::DVec2;
use crate::resources::Side;
use crate::resources::{Grid, LoadWork, LoadedEdge, Settings, StagePlan};
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
/// `LoadWork::applied` for its work (`account_load_work`).
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
        let outward = match load.side {
            Side::Top => DVec2::Y,
            Side::Bottom => DVec2::NEG_Y,
            Side::Right => DVec2::X,
            Side::Left => DVec2::NEG_X,
        };
        for &(p, force) in &load.forces {
            let k = p as usize;
            let arm = outward * points.half_size[k];
            let edge = points.position[k] + arm;
            // A domain pushed past the axis loads nothing there.
            let force = force * settings.geometry.thickness(edge).max(0.0);
            add_with_hat_functions(&grid, &mut layer, edge, force);
            work.applied.push(LoadedEdge {
                body: load.body,
                point: p,
                force,
                arm,
                from: points.position[k],
                deformation_from: points.deformation_gradient[k],
            });
        }
    }
}
