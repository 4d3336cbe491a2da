//! Rectangles of grid nodes: the windows a layer stores and the nodes a
//! step touches, with row-wise access to fields laid out over them.

use crate::parallel::MIN_NODES_PER_TASK;
use rayon::prelude::*;

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

    /// Nodes per row (zero when empty).
    pub fn width(self) -> usize {
        self.end[0].saturating_sub(self.start[0])
    }

    /// Number of rows (zero when empty).
    pub fn height(self) -> usize {
        self.end[1].saturating_sub(self.start[1])
    }

    /// Number of nodes.
    pub fn area(self) -> usize {
        self.width() * self.height()
    }

    /// Whether node (`i`, `j`) lies in the rectangle.
    pub fn contains(self, [i, j]: [usize; 2]) -> bool {
        (self.start[0]..self.end[0]).contains(&i) && (self.start[1]..self.end[1]).contains(&j)
    }

    /// Whether every node of `other` lies in the rectangle (an empty `other`
    /// always does).
    pub fn covers(self, other: Self) -> bool {
        other.is_empty()
            || (0..2).all(|d| self.start[d] <= other.start[d] && other.end[d] <= self.end[d])
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

    /// The nodes in both (empty if they do not meet).
    pub fn intersection(self, other: Self) -> Self {
        Self {
            start: [0, 1].map(|d| self.start[d].max(other.start[d])),
            end: [0, 1].map(|d| self.end[d].min(other.end[d])),
        }
    }

    /// The rectangle widened by `margin[d]` nodes on both sides along each
    /// direction d, clipped to a grid of `nodes` nodes.
    pub fn grown(self, margin: [usize; 2], nodes: [usize; 2]) -> Self {
        Self {
            start: [0, 1].map(|d| self.start[d].saturating_sub(margin[d])),
            end: [0, 1].map(|d| (self.end[d] + margin[d]).min(nodes[d])),
        }
    }

    /// Where node (`i`, `j`) sits in a row-major field stored over this
    /// rectangle; `None` outside it.
    #[inline]
    pub fn index_of(self, [i, j]: [usize; 2]) -> Option<usize> {
        self.contains([i, j])
            .then(|| (j - self.start[1]) * self.width() + i - self.start[0])
    }

    /// The rectangle's part of each row of `values`, a row-major field
    /// stored over `storage` (which must cover the rectangle), with the
    /// row's grid index, rows in parallel.
    pub fn rows_mut<T: Send>(
        self,
        storage: Self,
        values: &mut [T],
    ) -> impl IndexedParallelIterator<Item = (usize, &mut [T])> {
        debug_assert!(storage.covers(self) && values.len() == storage.area());
        let row_len = storage.width().max(1);
        let rows = if self.is_empty() {
            0..0
        } else {
            self.start[1] - storage.start[1]..self.end[1] - storage.start[1]
        };
        let columns = if self.is_empty() {
            0..0
        } else {
            self.start[0] - storage.start[0]..self.end[0] - storage.start[0]
        };
        let first = storage.start[1] + rows.start;
        values[rows.start * row_len..rows.end * row_len]
            .par_chunks_mut(row_len)
            .with_min_len(MIN_NODES_PER_TASK.div_ceil(columns.len().max(1)))
            .enumerate()
            .map(move |(k, row)| (first + k, &mut row[columns.clone()]))
    }

    /// The rectangle's part of grid row `j` (one of its rows) of `values`, a
    /// row-major field stored over `storage` (which must cover the rectangle).
    pub fn row<T>(self, storage: Self, values: &[T], j: usize) -> &[T] {
        if self.is_empty() {
            return &[];
        }
        let first = (j - storage.start[1]) * storage.width() + self.start[0] - storage.start[0];
        &values[first..first + self.width()]
    }
}
