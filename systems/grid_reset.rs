//! Algorithm 1, line 2: background nodes reset.

use crate::components::{GridLayer, GridNode};
use crate::transfer::MIN_NODES_PER_TASK;
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Zeroes every node of every layer.
///
/// Reads: nothing. Writes: `GridLayer::nodes`.
pub fn reset_grid_layers(mut layers: Query<&mut GridLayer>) {
    for mut layer in &mut layers {
        layer
            .nodes
            .par_iter_mut()
            .with_min_len(MIN_NODES_PER_TASK)
            .for_each(|n| *n = GridNode::default());
    }
}
