//! A body's own layer of nodal quantities on the shared background grid.

use crate::math::{DVec2, Real};
use bevy_ecs::prelude::Component;

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

/// One body's layer: every node of the grid, row-major (index j × nx + i).
/// Layers never exchange momentum; bodies meet only through contact, except
/// the bodies of one contact group, whose copies of the layer are summed
/// after every scatter ([`crate::resources::SharedLayers`]).
#[derive(Component, Clone, Debug, Default)]
pub struct GridLayer {
    /// Nodal quantities.
    pub nodes: Vec<GridNode>,
    /// Nodes whose velocity is constrained (grid edges and regions), sorted by node.
    pub constraints: Vec<NodeConstraint>,
    /// Nodes lighter than this (kg) are treated as empty: their velocity is zero.
    /// Set to 1e-9 of the body's smallest point mass, far below any real node
    /// mass yet well above round-off.
    pub mass_cutoff: Real,
}

impl GridLayer {
    /// A zeroed layer for a grid of `node_count` nodes.
    pub fn new(node_count: usize, mass_cutoff: Real) -> Self {
        Self {
            nodes: vec![GridNode::default(); node_count],
            constraints: Vec::new(),
            mass_cutoff,
        }
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
