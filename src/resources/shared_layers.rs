//! Contact groups (scene `group`): bodies that share one grid layer.

use crate::components::{GridLayer, GridNode};
use crate::transfer::MIN_NODES_PER_TASK;
use bevy_ecs::prelude::{Entity, Resource};
use rayon::prelude::*;

/// The bodies that share a layer, so they act as one continuum (standard
/// MPM between them). Each keeps its own copy of the layer; after every
/// scatter the copies are replaced by their sum, node by node in scene order
/// (deterministic), so each member's nodes carry the group's mass, momentum
/// and forces, and every member moves with the group's velocity field.
#[derive(Resource, Clone, Debug, Default)]
pub struct SharedLayers {
    /// Each group's bodies in scene order; only groups of two or more.
    pub groups: Vec<Vec<Entity>>,
    /// Scratch: one group's summed nodes.
    pub total: Vec<GridNode>,
}

impl SharedLayers {
    /// For every group, sums the members' nodes with `add` (into a zeroed
    /// node) and hands the sum to each member's nodes with `set`.
    /// `visit(entity, f)` must call `f` on that body's layer.
    pub fn share(
        &mut self,
        mut visit: impl FnMut(Entity, &mut dyn FnMut(&mut GridLayer)),
        add: impl Fn(&mut GridNode, &GridNode) + Sync,
        set: impl Fn(&mut GridNode, &GridNode) + Sync,
    ) {
        let Self { groups, total } = self;
        for group in groups.iter() {
            let mut first = true;
            for &member in group {
                visit(member, &mut |layer: &mut GridLayer| {
                    if first {
                        total.clear();
                        total.resize(layer.nodes.len(), GridNode::default());
                        first = false;
                    }
                    total
                        .par_iter_mut()
                        .zip(layer.nodes.par_iter())
                        .with_min_len(MIN_NODES_PER_TASK)
                        .for_each(|(sum, node)| add(sum, node));
                });
            }
            for &member in group {
                visit(member, &mut |layer: &mut GridLayer| {
                    layer
                        .nodes
                        .par_iter_mut()
                        .zip(total.par_iter())
                        .with_min_len(MIN_NODES_PER_TASK)
                        .for_each(|(node, sum)| set(node, sum));
                });
            }
        }
    }
}
