//! A body's own layer of nodal quantities on the shared background grid.

use crate::math::{DVec2, Real};
use crate::node_rect::NodeRect;
use bevy_ecs::prelude::Component;
use rayon::prelude::*;

/// Nodal quantities of one layer at one grid node.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridNode {
    /// Lumped mass m_i (eq. 8d).
    pub mass: Real,
    /// Momentum p_i (eq. 8c).
    pub momentum: DVec2,
    /// External force f_i,ext: gravity and point loads (eq. 7b).
    pub external_force: DVec2,
    /// Internal force f_i,int = −Σ V_p σ_p · G_ip (eq. 7a).
    pub internal_force: DVec2,
    /// Velocity at the start of the step, p_i / m_i, after boundary conditions.
    pub velocity: DVec2,
    /// Velocity at the end of the step after the momentum update (eq. 8a).
    pub velocity_new: DVec2,
}

/// Which velocity components a constraint holds at zero.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Fix {
    /// Hold the x component.
    pub x: bool,
    /// Hold the y component.
    pub y: bool,
}

impl Fix {
    /// Zeroes the held components of `v`.
    #[inline]
    pub fn apply(self, v: &mut DVec2) {
        if self.x {
            v.x = 0.0;
        }
        if self.y {
            v.y = 0.0;
        }
    }
}

/// A constrained node of a layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeConstraint {
    /// The node's column and row.
    pub node: [u32; 2],
    /// The held components.
    pub fix: Fix,
}

/// Fewest nodes a layer's storage reaches past its active nodes on each
/// side when it has to move or grow: a body travels at most a cell per step
/// (CFL), so the storage moves at most every eight steps, in practice
/// hundreds of steps apart.
pub const WINDOW_MARGIN_NODES: usize = 8;

/// One body's layer of the grid, row-major over its `window`: the rectangle
/// of nodes its storage covers, which holds the `active` nodes, those the
/// body's points reach this step (see [`GridLayer::reset`]), plus a margin,
/// so a small body on a large grid stores only the nodes around it. Layers
/// never exchange momentum; bodies meet only through contact, except the
/// bodies of one contact group, whose copies of the layer are summed after
/// every scatter (the contact groups' shared layers).
///
/// Only the active nodes are reset and solved each step (and smoothed by
/// XPIC). Every other node holds zero, stored in the window or not: a
/// system that writes nodes must stay inside `active`, and points must not
/// move between `GridReset` and `ParticleToGrid`, as `active` is set from
/// their positions at the reset.
#[derive(Component, Clone, Debug)]
pub struct GridLayer {
    /// Nodal quantities of the window's nodes, row-major.
    nodes: Vec<GridNode>,
    /// The nodes stored.
    window: NodeRect,
    /// The nodes this step's points can reach (for a contact group, the
    /// union of its members').
    active: NodeRect,
    /// Nodes of the whole grid along x and y.
    grid_nodes: [usize; 2],
    /// Nodes whose velocity is constrained (grid edges and regions), sorted by row then column.
    pub constraints: Vec<NodeConstraint>,
    /// Nodes lighter than this (kg) are treated as empty: their velocity is zero.
    /// Set to 1e-9 of the body's smallest point mass, far below any real node
    /// mass yet well above round-off.
    pub mass_cutoff: Real,
}

impl GridLayer {
    /// An empty layer for a grid of `nodes` nodes along x and y: it stores
    /// and activates nodes at its first reset.
    pub fn new(nodes: [usize; 2], mass_cutoff: Real) -> Self {
        Self {
            nodes: Vec::new(),
            window: NodeRect::default(),
            active: NodeRect::default(),
            grid_nodes: nodes,
            constraints: Vec::new(),
            mass_cutoff,
        }
    }

    /// The stored nodes, row-major over [`Self::window`].
    pub fn nodes(&self) -> &[GridNode] {
        &self.nodes
    }

    /// The stored nodes, row-major over [`Self::window`], to write: only the
    /// active ones may be changed.
    pub fn nodes_mut(&mut self) -> &mut [GridNode] {
        &mut self.nodes
    }

    /// Nodes of the whole grid along x and y.
    pub fn grid_nodes(&self) -> [usize; 2] {
        self.grid_nodes
    }

    /// The rectangle of nodes stored.
    pub fn window(&self) -> NodeRect {
        self.window
    }

    /// The nodes this step's points can reach.
    pub fn active(&self) -> NodeRect {
        self.active
    }

    /// Active node (`i`, `j`) to write; `None` if it is not active (then it
    /// holds zero and must stay so).
    pub fn node_mut(&mut self, at: [usize; 2]) -> Option<&mut GridNode> {
        if !self.active.contains(at) {
            return None;
        }
        self.window.index_of(at).map(|k| &mut self.nodes[k])
    }

    /// Zeroes the active nodes, then makes `rect` the active nodes.
    pub fn reset(&mut self, rect: NodeRect) {
        self.for_each_active(|n| *n = GridNode::default());
        self.active = NodeRect::default();
        self.expand(rect);
    }

    /// Adds `rect` (clipped to the grid) to the active nodes, keeping every
    /// value. When the window does not cover them, it moves to cover them
    /// with a margin of `WINDOW_MARGIN_NODES` or a quarter of their size,
    /// whichever is larger: an allocation, made only when a body leaves its
    /// window. A window that still covers the active nodes is kept, however
    /// much larger (e.g. the whole grid after a point has left it).
    pub fn expand(&mut self, rect: NodeRect) {
        let active = self
            .active
            .union(rect.intersection(NodeRect::whole(self.grid_nodes)));
        if !self.window.covers(active) {
            let margin = [0, 1].map(|d| {
                let size = active.end[d] - active.start[d];
                WINDOW_MARGIN_NODES.max(size / 4)
            });
            let window = active.grown(margin, self.grid_nodes);
            let mut nodes = vec![GridNode::default(); window.area()];
            let (old, old_window) = (&self.nodes, self.window);
            self.active
                .rows_mut(window, &mut nodes)
                .for_each(|(j, row)| row.copy_from_slice(self.active.row(old_window, old, j)));
            self.nodes = nodes;
            self.window = window;
        }
        self.active = active;
    }

    /// Applies `f` to every active node, rows in parallel.
    pub fn for_each_active(&mut self, f: impl Fn(&mut GridNode) + Sync + Send) {
        self.active
            .rows_mut(self.window, &mut self.nodes)
            .for_each(|(_, row)| row.iter_mut().for_each(&f));
    }

    /// Applies the constraints of the active nodes to the field selected by
    /// `field` (the others hold zero).
    pub fn apply_constraints(&mut self, field: impl Fn(&mut GridNode) -> &mut DVec2) {
        self.for_each_constrained(|fix, _, n| fix.apply(field(n)));
    }

    /// Calls `f` with what each active constrained node holds, its place in
    /// the window's nodes and the node.
    pub fn for_each_constrained(&mut self, mut f: impl FnMut(Fix, usize, &mut GridNode)) {
        let Self {
            nodes,
            window,
            active,
            constraints,
            ..
        } = self;
        for c in constraints.iter() {
            let at = c.node.map(|k| k as usize);
            if active.contains(at)
                && let Some(k) = window.index_of(at)
            {
                f(c.fix, k, &mut nodes[k]);
            }
        }
    }

    /// Applies the constraints of the active nodes to `values`, one per
    /// node of the window (row-major).
    pub fn constrain(&self, values: &mut [DVec2]) {
        for c in &self.constraints {
            let at = c.node.map(|k| k as usize);
            if self.active.contains(at)
                && let Some(k) = self.window.index_of(at)
            {
                c.fix.apply(&mut values[k]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_layer_keeps_its_values_when_its_window_moves() {
        let mut layer = GridLayer::new([100, 50], 0.0);
        let rect = |i: usize, j: usize| NodeRect {
            start: [i, j],
            end: [i + 5, j + 4],
        };
        layer.reset(rect(10, 10));
        let window = layer.window();
        // A margin of eight nodes, clipped to the grid.
        assert_eq!(window.start, [2, 2]);
        assert_eq!(window.end, [23, 22]);
        assert_eq!(layer.nodes().len(), window.area());
        layer.node_mut([12, 11]).unwrap().mass = 3.0;
        // Inside the window: no move.
        layer.expand(rect(14, 12));
        assert_eq!(layer.window(), window);
        // Beyond it: the window moves and the value stays at its node.
        layer.expand(rect(40, 30));
        assert!(layer.window().covers(layer.active()));
        assert_eq!(layer.node_mut([12, 11]).unwrap().mass, 3.0);
        let total: Real = layer.nodes().iter().map(|n| n.mass).sum();
        assert_eq!(total, 3.0);
        // A reset zeroes the active nodes; nodes outside them, stored or
        // not, cannot be written.
        layer.reset(rect(90, 40));
        assert!(layer.nodes().iter().all(|n| n.mass == 0.0));
        assert_eq!(layer.node_mut([0, 0]), None);
        assert!(layer.window().contains([88, 40]));
        assert_eq!(layer.node_mut([88, 40]), None);
        // Rectangles are clipped to the grid.
        assert_eq!(layer.active().end, [95, 44]);
        layer.reset(rect(98, 48));
        assert_eq!(layer.active().end, [100, 50]);
        assert!(layer.window().covers(layer.active()));
    }
}
