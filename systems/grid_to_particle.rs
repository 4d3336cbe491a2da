//! Algorithm 1, line 16: velocity and position of the points (eqs. 11a/11b).

use crate::components::{GridLayer, MaterialPoints, StepTravel, TransferScratch};
use crate::math::{DVec2, Real};
use crate::resources::{Clock, Grid, Settings};
use crate::transfer::MIN_POINTS_PER_TASK;
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// With v^n = Σ S_ip v_i^n and v^{n+1} = Σ S_ip v_i^{n+1} interpolated at x^n:
/// * eq. 11a: V^{n+1} = (1 − β)(V^n + v^{n+1} − v^n) + β v^{n+1}, where
///   v^{n+1} − v^n = Σ S_ip a_i Δt;
/// * eq. 11b: x^{n+1} = x^n + ½(v^n + v^{n+1}) Δt − ½ β (V^n − v^n) Δt.
///
/// Reads: `Grid`, `Settings`, `Clock`, `GridLayer`, `TransferScratch::stencils`.
/// Writes: `MaterialPoints` (position, velocity), `StepTravel` (the largest
/// |x^{n+1} − x^n|, a maximum, so exact for any thread count).
pub fn grid_to_particle(
    grid: Res<Grid>,
    settings: Res<Settings>,
    clock: Res<Clock>,
    mut bodies: Query<(
        &mut MaterialPoints,
        &mut StepTravel,
        &GridLayer,
        &TransferScratch,
    )>,
) {
    let row_len = grid.nodes()[0];
    let (dt, beta) = (clock.dt, settings.pic_fraction);
    for (mut points, mut travel, layer, scratch) in &mut bodies {
        let MaterialPoints {
            position, velocity, ..
        } = &mut *points;
        let nodes = &layer.nodes;
        travel.0 = (
            position.par_iter_mut(),
            velocity.par_iter_mut(),
            scratch.stencils.par_iter(),
        )
            .into_par_iter()
            .with_min_len(MIN_POINTS_PER_TASK)
            .map(|(x, v, stencil)| {
                let zero = (DVec2::ZERO, DVec2::ZERO);
                let (grid_old, grid_new) =
                    stencil.gather(nodes, row_len, zero, |(old, new), node, w, _| {
                        (old + w * node.velocity, new + w * node.velocity_new)
                    });
                let step = (0.5 * (grid_old + grid_new) - 0.5 * beta * (*v - grid_old)) * dt;
                *x += step;
                *v = (1.0 - beta) * (*v + grid_new - grid_old) + beta * grid_new;
                step.length()
            })
            .reduce(|| 0.0, Real::max);
    }
}
