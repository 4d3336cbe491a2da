//! The grid: its cells and edges.

use super::Locator;
use crate::rules;
use crate::scene::{Scene, SceneError};

/// Most nodes a grid may have: 5e7 nodes make an 4.4 GB layer per body (88
/// bytes a node), beyond what a 2D run on one machine can use; node indices
/// are stored as u32, which this also keeps in range.
const MAX_NODES: u128 = 50_000_000;

impl Scene {
    /// The grid: its origin, cell size and counts.
    pub(super) fn check_grid(&self, v: &Locator) -> Result<(), SceneError> {
        let grid = &self.grid;
        rules::positive(grid.cell_size).map_err(|e| v.field(&["grid", "cell_size"], e))?;
        if !grid.origin.is_finite() {
            return Err(v.invalid(
                &["grid", "origin"],
                format!("grid.origin must be finite, got {}", grid.origin),
            ));
        }
        // In u128 each factor fits, and their product saturates rather than
        // wrap for counts near usize::MAX.
        let nodes = (grid.cells.0 as u128 + 1).saturating_mul(grid.cells.1 as u128 + 1);
        if nodes > MAX_NODES {
            return Err(v.invalid(
                &["grid", "cells"],
                format!(
                    "grid.cells {:?} give more than the {MAX_NODES} nodes a layer may hold",
                    grid.cells
                ),
            ));
        }
        if grid.cells.0 < 2 || grid.cells.1 < 2 {
            return Err(v.invalid(
                &["grid", "cells"],
                format!(
                    "grid.cells must be at least 2 in each direction, got {:?}",
                    grid.cells
                ),
            ));
        }
        Ok(())
    }
}
