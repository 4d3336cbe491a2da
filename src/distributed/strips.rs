//! The domains of a distributed run: strips of whole columns of scatter
//! tiles, one per rank, from left to right. A tile's points scatter on the
//! rank that owns its column, so every tile's patch is formed whole on one
//! rank, in the order one process forms it.

use crate::scatter::TILE_CELLS;
use std::ops::Range;

/// Rank r owns the tile columns `cuts[r]..cuts[r + 1]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Strips {
    cuts: Vec<u32>,
}

impl Strips {
    /// Strips for `ranks` ranks over tile columns holding `counts` points
    /// each, column 0 first: each cut between ranks r − 1 and r falls on the
    /// column edge whose points to the left come nearest r shares of the
    /// total. Integer arithmetic, so every rank that has the same counts
    /// cuts the same.
    pub fn balanced(counts: &[u64], ranks: usize) -> Self {
        assert!(ranks > 0, "at least one rank");
        let n = ranks as u128;
        let total: u128 = counts.iter().map(|&c| u128::from(c)).sum();
        let columns = counts.len() as u32;
        let mut cuts = Vec::with_capacity(ranks + 1);
        cuts.push(0);
        // `left`: the points in the columns before `column`, times `ranks`.
        let (mut column, mut left) = (0u32, 0u128);
        for r in 1..n {
            let target = r * total;
            while column < columns && left < target {
                left += u128::from(counts[column as usize]) * n;
                column += 1;
            }
            let before = left - u128::from(counts[column.saturating_sub(1) as usize]) * n;
            let previous = *cuts.last().expect("the first cut");
            let cut = if column > previous && left >= target && target - before < left - target {
                column - 1
            } else {
                column
            };
            cuts.push(cut);
        }
        cuts.push(columns);
        Self { cuts }
    }

    /// The number of ranks.
    pub fn ranks(&self) -> usize {
        self.cuts.len() - 1
    }

    /// The tile columns of `rank`.
    pub fn columns(&self, rank: usize) -> Range<u32> {
        self.cuts[rank]..self.cuts[rank + 1]
    }

    /// The rank whose strip holds tile column `column`; the last rank for
    /// columns past the grid's (a stray point's, which the step reports).
    pub fn owner(&self, column: u32) -> usize {
        let after = self.cuts[1..].partition_point(|&end| end <= column);
        after.min(self.ranks() - 1)
    }

    /// The tile column of a stencil base node's column.
    pub fn column_of(base_x: u32) -> u32 {
        base_x / TILE_CELLS[0] as u32
    }

    /// The ranks `rank` shares nodes with: the owners of the columns just
    /// left and right of its strip (none for an empty strip), each with
    /// the node columns the two share, [first, first + stencil reach).
    pub fn neighbours(&self, rank: usize, grid_columns: u32) -> Vec<(usize, Range<usize>)> {
        let Range { start, end } = self.columns(rank);
        let mut out = Vec::new();
        if start == end {
            return out;
        }
        let reach = crate::shape_functions::STENCIL_WIDTH - 1;
        let node = |column: u32| column as usize * TILE_CELLS[0];
        if start > 0 {
            out.push((self.owner(start - 1), node(start)..node(start) + reach));
        }
        if end < grid_columns {
            out.push((self.owner(end), node(end)..node(end) + reach));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_share_the_points_and_cover_every_column() {
        // 200 points: an unsplittable column of 100 takes a rank alone.
        let counts = [0, 10, 40, 40, 10, 0, 0, 100];
        let strips = Strips::balanced(&counts, 3);
        assert_eq!(strips.cuts, vec![0, 3, 7, 8]);
        for (column, rank) in [(0, 0), (2, 0), (3, 1), (6, 1), (7, 2), (9, 2)] {
            assert_eq!(strips.owner(column), rank, "column {column}");
        }
        assert_eq!(Strips::balanced(&counts, 1).cuts, vec![0, 8]);
        assert_eq!(Strips::balanced(&counts, 2).cuts, vec![0, 5, 8]);
        // More ranks than columns with points: some strips are empty.
        let strips = Strips::balanced(&[0, 5, 0], 4);
        assert_eq!(strips.cuts, vec![0, 1, 2, 2, 3]);
        assert_eq!(
            (strips.owner(0), strips.owner(1), strips.owner(2)),
            (0, 1, 3)
        );
        assert!(strips.neighbours(2, 3).is_empty());
        assert_eq!(strips.neighbours(0, 3), vec![(1, 16..18)]);
        assert_eq!(strips.neighbours(1, 3), vec![(0, 16..18), (3, 32..34)]);
        assert_eq!(strips.neighbours(3, 3), vec![(1, 32..34)]);
    }
}
