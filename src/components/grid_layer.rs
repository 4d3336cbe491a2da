//! A body's own layer of nodal quantities on the shared background grid.

use crate::math::{DVec2, Real};
use crate::transfer::MIN_NODES_PER_TASK;
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
    /// Row-major node index.
    pub node: u32,
    /// The held components.
    pub fix: Fix,
}

/// A rectangle of grid nodes: columns `start[0]..end[0]` and rows
/// `start[1]..end[1]` (half-open; empty when an end is not past its start).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NodeRect {
    /// First column and first row.
    pub start: [usize; 2],
    /// One past the last column and one past the last row.
    pub end: [usize; 2],
}

impl NodeRect {
    /// Every node of a grid of `nodes` nodes along x and y.
    pub fn whole(nodes: [usize; 2]) -> Self {
        Self {
            start: [0, 0],
            end: nodes,
        }
    }

    /// Whether the rectangle holds no node.
    pub fn is_empty(self) -> bool {
        self.end[0] <= self.start[0] || self.end[1] <= self.start[1]
    }

    /// Whether node (`i`, `j`) lies in the rectangle.
    pub fn contains(self, [i, j]: [usize; 2]) -> bool {
        (self.start[0]..self.end[0]).contains(&i) && (self.start[1]..self.end[1]).contains(&j)
    }

    /// The smallest rectangle holding both.
    pub fn union(self, other: Self) -> Self {
        if self.is_empty() {
            return other;
        }
        if other.is_empty() {
            return self;
        }
        Self {
            start: [
                self.start[0].min(other.start[0]),
                self.start[1].min(other.start[1]),
            ],
            end: [self.end[0].max(other.end[0]), self.end[1].max(other.end[1])],
        }
    }

    /// The rectangle's part of each row of `values` (row-major, `row_len`
    /// per row), with the row's index, rows in parallel.
    pub fn rows_mut<T: Send>(
        self,
        values: &mut [T],
        row_len: usize,
    ) -> impl IndexedParallelIterator<Item = (usize, &mut [T])> {
        let [first, last] = [self.start[1], self.end[1].max(self.start[1])];
        let columns = self.start[0]..self.end[0].max(self.start[0]);
        let width = columns.len().max(1);
        values[first * row_len..last * row_len]
            .par_chunks_mut(row_len)
            .with_min_len(MIN_NODES_PER_TASK.div_ceil(width))
            .enumerate()
            .map(move |(k, row)| (first + k, &mut row[columns.clone()]))
    }

    /// The rectangle's part of row `j` of `values` (row-major, `row_len` per row).
    pub fn row<T>(self, values: &[T], row_len: usize, j: usize) -> &[T] {
        let first = j * row_len;
        &values[first + self.start[0]..first + self.end[0].max(self.start[0])]
    }
}

/// One body's layer: every node of the grid, row-major (index j × nx + i).
/// Layers never exchange momentum; bodies meet only through contact, except
/// the bodies of one contact group, whose copies of the layer are summed
/// after every scatter ([`crate::resources::SharedLayers`]).
///
/// Only the nodes of `active`, around the body's points, are reset and
/// solved each step (and smoothed by XPIC). Every
/// node outside `active` holds zero: a system that writes nodes must stay
/// inside it, and points must not move between `GridReset` and
/// `ParticleToGrid`, as `active` is set from their positions at the reset.
#[derive(Component, Clone, Debug)]
pub struct GridLayer {
    /// Nodal quantities.
    pub nodes: Vec<GridNode>,
    /// Nodes per row (the grid's nx).
    pub row_len: usize,
    /// The nodes this step's points can reach (set when the layer is reset;
    /// for a contact group, the union of its members').
    pub active: NodeRect,
    /// Nodes whose velocity is constrained (grid edges and regions), sorted by node.
    pub constraints: Vec<NodeConstraint>,
    /// Nodes lighter than this (kg) are treated as empty: their velocity is zero.
    /// Set to 1e-9 of the body's smallest point mass, far below any real node
    /// mass yet well above round-off.
    pub mass_cutoff: Real,
}

impl GridLayer {
    /// A zeroed layer for a grid of `nodes` nodes along x and y, all active
    /// until its first reset.
    pub fn new(nodes: [usize; 2], mass_cutoff: Real) -> Self {
        Self {
            nodes: vec![GridNode::default(); nodes[0] * nodes[1]],
            row_len: nodes[0],
            active: NodeRect::whole(nodes),
            constraints: Vec::new(),
            mass_cutoff,
        }
    }

    /// Applies `f` to every active node, rows in parallel.
    pub fn for_each_active(&mut self, f: impl Fn(&mut GridNode) + Sync + Send) {
        self.active
            .rows_mut(&mut self.nodes, self.row_len)
            .for_each(|(_, row)| row.iter_mut().for_each(&f));
    }

    /// Applies the constraints to the field selected by `field`.
    pub fn apply_constraints(&mut self, field: impl Fn(&mut GridNode) -> &mut DVec2) {
        for c in &self.constraints {
            c.fix.apply(field(&mut self.nodes[c.node as usize]));
        }
    }

    /// Applies the constraints to `values`, one per node (row-major).
    pub fn constrain(&self, values: &mut [DVec2]) {
        for c in &self.constraints {
            c.fix.apply(&mut values[c.node as usize]);
        }
    }
}
