//! Algorithm 1, line 2: background nodes reset.

use crate::components::{GridLayer, MaterialPoints, NodeRect};
use crate::math::Real;
use crate::resources::{Grid, SharedLayers};
use bevy_ecs::prelude::*;

/// How far from its points a body's layer is active, in cells: the widest
/// stencil reaches 1.5 h (quadratic B-spline; uGIMP h + l_p ≤ 1.5 h), and a
/// traction's integration point, at most h/2 from its point, loads the
/// nodes of its cell, at most 1.5 h away; rounded up to 2.
pub const ACTIVE_REACH_CELLS: Real = 2.0;

/// Zeroes each layer's active nodes (every other node already holds zero),
/// then makes active the nodes within `ACTIVE_REACH_CELLS` of the body's
/// points, where this step's transfers will write (moving the layer's
/// stored window when they leave it); the members of a contact group all
/// take the union of their rectangles, as they share their nodes.
///
/// Reads: `Grid`, `SharedLayers::groups`, `MaterialPoints::position`.
/// Writes: `GridLayer` (nodes, window, active).
pub fn reset_grid_layers(
    grid: Res<Grid>,
    shared: Res<SharedLayers>,
    mut layers: Query<(&MaterialPoints, &mut GridLayer)>,
) {
    let reach = ACTIVE_REACH_CELLS * grid.cell_size;
    for (points, mut layer) in &mut layers {
        let near = points.bounds().map_or(NodeRect::default(), |(lo, hi)| {
            grid.nodes_near(lo, hi, reach)
        });
        layer.reset(near);
    }
    for group in &shared.groups {
        let union = group
            .iter()
            .filter_map(|&member| layers.get(member).ok())
            .fold(NodeRect::default(), |rect, (_, layer)| {
                rect.union(layer.active())
            });
        for &member in group {
            if let Ok((_, mut layer)) = layers.get_mut(member) {
                layer.expand(union);
            }
        }
    }
}
