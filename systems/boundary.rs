//! Algorithm 1, line 3: boundary conditions of each layer.

use crate::components::{GridLayer, RegionConstraints};
use crate::resources::Grid;
use bevy_ecs::prelude::*;

/// Rebuilds a layer's list of constrained nodes when the grid's edge
/// conditions or the body's region constraints have changed (always on the
/// first step), so a system or stage may change either between steps.
///
/// Reads: `Grid`, `RegionConstraints`. Writes: `GridLayer::constraints`.
pub fn rebuild_node_constraints(
    grid: Res<Grid>,
    mut layers: Query<(&mut GridLayer, Ref<RegionConstraints>)>,
) {
    for (mut layer, regions) in &mut layers {
        if grid.is_changed() || regions.is_changed() {
            layer.constraints = grid.layer_constraints(&regions.0);
        }
    }
}
