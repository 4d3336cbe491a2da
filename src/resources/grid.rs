//! The shared background grid and the conditions on its edges.

use crate::components::{Fix, NodeConstraint, NodeRect, RegionConstraint};
use crate::math::{DVec2, Real};
use crate::shape_functions::StencilGrid;
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

/// The velocity condition on one edge of the grid, for every layer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum EdgeCondition {
    /// Nothing imposed (default): the edge is open.
    #[default]
    Free,
    /// No-slip: both velocity components are zero on the edge nodes.
    Fixed,
    /// Roller: the normal velocity component is zero, the tangential free.
    Slip,
}

impl EdgeCondition {
    /// Whether the edge is a wall (fixed or slip) that points may not cross.
    pub fn is_wall(self) -> bool {
        self != Self::Free
    }
}

/// Conditions on the four edges of the grid.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EdgeConditions {
    /// Edge x = x_min.
    pub left: EdgeCondition,
    /// Edge x = x_max.
    pub right: EdgeCondition,
    /// Edge y = y_min.
    pub bottom: EdgeCondition,
    /// Edge y = y_max.
    pub top: EdgeCondition,
}

/// One edge of the grid as seen from a box inside it (see
/// [`Grid::edges_around`]), for messages.
#[derive(Clone, Debug, PartialEq)]
pub struct GridEdge {
    /// `left`, `right`, `bottom` or `top` (as in `grid.edges`).
    pub name: &'static str,
    /// Its velocity condition.
    pub condition: EdgeCondition,
    /// Distance from the box to the edge (m).
    pub gap: Real,
    /// Where it is, e.g. `y = 0`.
    pub at: String,
    /// Its outward unit normal.
    pub outward: DVec2,
}

/// A uniform grid of square cells.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct Grid {
    /// Position of node (0, 0), the lower-left corner (m).
    pub origin: DVec2,
    /// Cell size h (m).
    pub cell_size: Real,
    /// Number of cells along x and y.
    pub cells: [usize; 2],
    /// Velocity conditions on the edges.
    pub edges: EdgeConditions,
}

impl Grid {
    /// Number of nodes along x and y.
    pub fn nodes(&self) -> [usize; 2] {
        [self.cells[0] + 1, self.cells[1] + 1]
    }

    /// The grid as the shape functions see it: walls where an edge is fixed or slip.
    pub(crate) fn stencil_grid(&self) -> StencilGrid {
        StencilGrid {
            origin: self.origin,
            inv_cell_size: 1.0 / self.cell_size,
            nodes: self.nodes(),
            walls: [
                [self.edges.left.is_wall(), self.edges.right.is_wall()],
                [self.edges.bottom.is_wall(), self.edges.top.is_wall()],
            ],
        }
    }

    /// The box points may not leave through a wall: per axis, the low and
    /// high bounds, the grid's edge where it is fixed or slip and unbounded
    /// where it is free.
    pub fn wall_bounds(&self) -> (DVec2, DVec2) {
        let bound = |c: EdgeCondition, at: Real, open: Real| {
            if c.is_wall() { at } else { open }
        };
        let (lo, hi) = (self.origin, self.max());
        (
            DVec2::new(
                bound(self.edges.left, lo.x, Real::NEG_INFINITY),
                bound(self.edges.bottom, lo.y, Real::NEG_INFINITY),
            ),
            DVec2::new(
                bound(self.edges.right, hi.x, Real::INFINITY),
                bound(self.edges.top, hi.y, Real::INFINITY),
            ),
        )
    }

    /// The grid's four edges seen from the box from `low` to `high` (inside
    /// the grid): each with its gap to the box.
    pub fn edges_around(&self, low: DVec2, high: DVec2) -> [GridEdge; 4] {
        let (lo, hi) = (self.origin, self.max());
        // Axis 0 or 1, on its low or high side.
        let edge = |name, condition, axis: usize, high_side: bool| {
            let (gap, at, outward) = if high_side {
                (hi[axis] - high[axis], hi[axis], DVec2::AXES[axis])
            } else {
                (low[axis] - lo[axis], lo[axis], -DVec2::AXES[axis])
            };
            let at = format!("{} = {at}", ["x", "y"][axis]);
            GridEdge {
                name,
                condition,
                gap,
                at,
                outward,
            }
        };
        [
            edge("left", self.edges.left, 0, false),
            edge("right", self.edges.right, 0, true),
            edge("bottom", self.edges.bottom, 1, false),
            edge("top", self.edges.top, 1, true),
        ]
    }

    /// Why a point's stencil was refused (see `StencilGrid`): its position
    /// outside the grid, or, inside it, its support reaching past an open
    /// (`Free`) edge, where there are no nodes to take its weight; the
    /// nearest such edge is named.
    pub fn why_outside(&self, position: DVec2, half_size: DVec2) -> String {
        let (lo, hi) = (self.origin, self.max());
        if !(position.cmpge(lo).all() && position.cmple(hi).all()) {
            return format!("{position} has left the grid, from {lo} to {hi}");
        }
        let edges = self.edges_around(position, position);
        let nearest = edges
            .into_iter()
            .filter(|edge| !edge.condition.is_wall())
            .min_by(|a, b| a.gap.total_cmp(&b.gap));
        match nearest {
            Some(GridEdge {
                name,
                gap: distance,
                at,
                ..
            }) => format!(
                "{position} lies {distance:.3e} m from the grid's {name} edge {at}, and the point's shape functions (domain half-size {half_size}) reach past it; that edge is Free (the default, unless grid.edges or a stage's edges set it), with no nodes beyond it: give it a wall (Slip or Fixed) or extend the grid"
            ),
            None => format!("{position}: the point's shape functions reach past the grid"),
        }
    }

    /// Upper-right corner (m).
    pub fn max(&self) -> DVec2 {
        self.origin + DVec2::new(self.cells[0] as Real, self.cells[1] as Real) * self.cell_size
    }

    /// The nodes within `reach` (m) of the box from `lo` to `hi`, clipped to
    /// the grid; the whole grid if the box is not finite (a point gone
    /// astray, reported elsewhere).
    pub fn nodes_near(&self, lo: DVec2, hi: DVec2, reach: Real) -> NodeRect {
        let nodes = self.nodes();
        if !(lo.is_finite() && hi.is_finite()) {
            return NodeRect::whole(nodes);
        }
        let index = |x: DVec2| (x - self.origin) / self.cell_size;
        let (first, last) = (
            (index(lo) - reach / self.cell_size).floor(),
            (index(hi) + reach / self.cell_size).ceil(),
        );
        NodeRect {
            start: [
                (first.x.max(0.0) as usize).min(nodes[0]),
                (first.y.max(0.0) as usize).min(nodes[1]),
            ],
            end: [
                ((last.x + 1.0).max(0.0) as usize).min(nodes[0]),
                ((last.y + 1.0).max(0.0) as usize).min(nodes[1]),
            ],
        }
    }

    /// Position of the node with row-major index `index`.
    pub fn node_position(&self, index: usize) -> DVec2 {
        let nx = self.nodes()[0];
        self.origin + DVec2::new((index % nx) as Real, (index / nx) as Real) * self.cell_size
    }

    /// The constraints of a layer: the edge conditions plus the layer's own
    /// regions, merged per node, sorted by row, then column.
    pub fn layer_constraints(&self, regions: &[RegionConstraint]) -> Vec<NodeConstraint> {
        let [nx, ny] = self.nodes();
        let edge_fix = |condition: EdgeCondition, normal_is_x: bool| match condition {
            EdgeCondition::Free => Fix::default(),
            EdgeCondition::Fixed => Fix { x: true, y: true },
            EdgeCondition::Slip => Fix {
                x: normal_is_x,
                y: !normal_is_x,
            },
        };
        // Nodes on a region's edge count as inside despite round-off.
        let tolerance = 1e-9 * self.cell_size;
        let mut constraints = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let mut fix = Fix::default();
                let mut merge = |f: Fix| {
                    fix.x |= f.x;
                    fix.y |= f.y;
                };
                if i == 0 {
                    merge(edge_fix(self.edges.left, true));
                }
                if i == nx - 1 {
                    merge(edge_fix(self.edges.right, true));
                }
                if j == 0 {
                    merge(edge_fix(self.edges.bottom, false));
                }
                if j == ny - 1 {
                    merge(edge_fix(self.edges.top, false));
                }
                let x = self.node_position(j * nx + i);
                for r in regions {
                    let inside =
                        x.cmpge(r.min - tolerance).all() && x.cmple(r.max + tolerance).all();
                    if inside {
                        merge(Fix {
                            x: r.fix_x,
                            y: r.fix_y,
                        });
                    }
                }
                if fix.x || fix.y {
                    constraints.push(NodeConstraint {
                        node: [i as u32, j as u32],
                        fix,
                    });
                }
            }
        }
        constraints
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refused_point_is_explained_by_the_nearest_open_edge() {
        let grid = Grid {
            origin: DVec2::ZERO,
            cell_size: 1.0,
            cells: [10, 10],
            edges: EdgeConditions {
                left: EdgeCondition::Slip,
                ..Default::default()
            },
        };
        let half = DVec2::splat(0.5);
        // Nearer the Slip left edge than the Free bottom one: the bottom is named.
        let near = grid.why_outside(DVec2::new(0.2, 0.4), half);
        assert!(
            near.contains("4.000e-1 m from the grid's bottom edge y = 0"),
            "{near}"
        );
        let gone = grid.why_outside(DVec2::new(5.0, -1.0), half);
        assert!(
            gone.contains("has left the grid, from [0, 0] to [10, 10]"),
            "{gone}"
        );
        let edges = grid.edges_around(DVec2::new(1.0, 2.0), DVec2::new(3.0, 4.0));
        let gaps: Vec<Real> = edges.iter().map(|e| e.gap).collect();
        assert_eq!(gaps, vec![1.0, 7.0, 2.0, 6.0]);
        assert_eq!(edges[3].outward, DVec2::Y);
    }

    #[test]
    fn slip_holds_the_normal_component_and_corners_merge() {
        let grid = Grid {
            origin: DVec2::ZERO,
            cell_size: 1.0,
            cells: [2, 2],
            edges: EdgeConditions {
                left: EdgeCondition::Slip,
                bottom: EdgeCondition::Slip,
                ..Default::default()
            },
        };
        let c = grid.layer_constraints(&[]);
        // The bottom row, then the left column.
        let nodes: Vec<[u32; 2]> = c.iter().map(|c| c.node).collect();
        assert_eq!(nodes, vec![[0, 0], [1, 0], [2, 0], [0, 1], [0, 2]]);
        assert_eq!(c[0].fix, Fix { x: true, y: true });
        assert_eq!(c[1].fix, Fix { x: false, y: true });
        assert_eq!(c[3].fix, Fix { x: true, y: false });
    }

    #[test]
    fn region_constraints_hold_the_nodes_inside_and_merge_with_edges() {
        let grid = Grid {
            origin: DVec2::ZERO,
            cell_size: 0.5,
            cells: [4, 2],
            edges: EdgeConditions {
                bottom: EdgeCondition::Slip,
                ..Default::default()
            },
        };
        // A symmetry line x = 1 (column 2) holding x only.
        let line = RegionConstraint {
            min: DVec2::new(1.0, 0.0),
            max: DVec2::new(1.0, 1.0),
            fix_x: true,
            fix_y: false,
        };
        let c = grid.layer_constraints(&[line]);
        let at = |node: [u32; 2]| c.iter().find(|c| c.node == node).map(|c| c.fix);
        assert_eq!(at([2, 1]), Some(Fix { x: true, y: false }));
        assert_eq!(at([2, 2]), Some(Fix { x: true, y: false }));
        // Node (2, 0) is also on the slip bottom edge: both components held.
        assert_eq!(at([2, 0]), Some(Fix { x: true, y: true }));
        assert_eq!(at([1, 1]), None);
    }
}
