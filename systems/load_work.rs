//! The work of this step's surface loads, for the energy balance.

use crate::components::MaterialPoints;
use crate::resources::LoadWork;
use bevy_ecs::prelude::*;

/// Adds the work of this step's surface loads (`LoadWork::applied`, as
/// `apply_surface_loads` left them) to `LoadWork::work` and clears them:
/// each force times the motion over the step of the material where it
/// acts, the point's displacement plus (F F₀⁻¹ − I) a, a the arm from the
/// point's centre to the middle of its outer edge and F₀, F its deformation
/// gradient at the step's start and end. (Taken at the points' centres, a
/// column's settlement under a surcharge is half a point spacing short:
/// 2.5% for 20 rows of points.) In the order the loads were applied. A
/// force share that fell on a node outside the grid (a point that left it)
/// is counted all the same.
///
/// Reads: `MaterialPoints` (position, deformation gradient). Writes:
/// `LoadWork`.
pub fn account_load_work(mut work: ResMut<LoadWork>, bodies: Query<&MaterialPoints>) {
    let LoadWork { work, applied } = &mut *work;
    for load in applied.iter() {
        let Ok(points) = bodies.get(load.body) else {
            continue;
        };
        let p = load.point as usize;
        let stretched =
            points.deformation_gradient[p] * load.deformation_from.inverse() * load.arm - load.arm;
        *work += load.force.dot(points.position[p] - load.from + stretched);
    }
    applied.clear();
}
