//! Contact groups (scene `group`): bodies that share one grid layer.

use crate::components::{GridLayer, GridNode};
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
    /// For every group, sums the members' active nodes with `add` (into a
    /// zeroed node) and hands the sum to each member's nodes with `set`
    /// (the members share one active rectangle, see `reset_grid_layers`).
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
                    let (rect, row_len) = (layer.active, layer.row_len);
                    if first {
                        total.resize(layer.nodes.len(), GridNode::default());
                        rect.rows_mut(total, row_len)
                            .for_each(|(_, row)| row.fill(GridNode::default()));
                        first = false;
                    }
                    let nodes = &layer.nodes;
                    rect.rows_mut(total, row_len).for_each(|(j, sums)| {
                        for (sum, node) in sums.iter_mut().zip(rect.row(nodes, row_len, j)) {
                            add(sum, node);
                        }
                    });
                });
            }
            for &member in group {
                visit(member, &mut |layer: &mut GridLayer| {
                    let (rect, row_len) = (layer.active, layer.row_len);
                    let total = &*total;
                    rect.rows_mut(&mut layer.nodes, row_len)
                        .for_each(|(j, nodes)| {
                            for (node, sum) in nodes.iter_mut().zip(rect.row(total, row_len, j)) {
                                set(node, sum);
                            }
                        });
                });
            }
        }
    }
}
