//! Contact groups (scene `group`): bodies that share one grid layer.

use crate::components::{GridLayer, GridNode, NodeRect};
use crate::math::DVec2;
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
    /// Scratch: one group's summed nodal field (see [`Self::share_field`]).
    pub field_total: Vec<DVec2>,
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
        let Self { groups, total, .. } = self;
        for group in groups.iter() {
            // The members share one active rectangle (or, after a point has
            // left the grid, the whole grid for one of them: then all take it).
            let mut rect = NodeRect::default();
            for &member in group {
                visit(member, &mut |layer: &mut GridLayer| {
                    rect = rect.union(layer.active());
                });
            }
            // The sums, row-major over the rectangle.
            total.clear();
            total.resize(rect.area(), GridNode::default());
            for &member in group {
                visit(member, &mut |layer: &mut GridLayer| {
                    layer.expand(rect);
                    let (window, nodes) = (layer.window(), layer.nodes());
                    rect.rows_mut(rect, total).for_each(|(j, sums)| {
                        for (sum, node) in sums.iter_mut().zip(rect.row(window, nodes, j)) {
                            add(sum, node);
                        }
                    });
                });
            }
            for &member in group {
                visit(member, &mut |layer: &mut GridLayer| {
                    let window = layer.window();
                    let total = &*total;
                    rect.rows_mut(window, layer.nodes_mut())
                        .for_each(|(j, nodes)| {
                            for (node, sum) in nodes.iter_mut().zip(rect.row(rect, total, j)) {
                                set(node, sum);
                            }
                        });
                });
            }
        }
    }

    /// For every group, replaces each member's nodal field (laid out like
    /// its layer's stored nodes) by the members' sum on their shared active
    /// rectangle, summed in scene order. `visit(entity, f)` must call `f`
    /// on that body's layer and field.
    pub fn share_field(
        &mut self,
        mut visit: impl FnMut(Entity, &mut dyn FnMut(&GridLayer, &mut Vec<DVec2>)),
    ) {
        let Self {
            groups,
            field_total: total,
            ..
        } = self;
        for group in groups.iter() {
            let mut rect = NodeRect::default();
            for &member in group {
                visit(member, &mut |layer, _| rect = rect.union(layer.active()));
            }
            total.clear();
            total.resize(rect.area(), DVec2::ZERO);
            for &member in group {
                visit(member, &mut |layer, field| {
                    let window = layer.window();
                    // P2G made every member's active nodes the group's.
                    debug_assert!(
                        window.covers(rect),
                        "a member's window misses the group's nodes"
                    );
                    rect.rows_mut(rect, total).for_each(|(j, sums)| {
                        for (sum, value) in sums.iter_mut().zip(rect.row(window, field, j)) {
                            *sum += *value;
                        }
                    });
                });
            }
            for &member in group {
                visit(member, &mut |layer, field| {
                    let total = &*total;
                    rect.rows_mut(layer.window(), field)
                        .for_each(|(j, values)| {
                            values.copy_from_slice(rect.row(rect, total, j));
                        });
                });
            }
        }
    }
}
