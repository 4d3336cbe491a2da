//! Deterministic parallel point-to-grid scatter (DESIGN.md section 6).
//!
//! Points are cut into fixed-size chunks of [`CHUNK_POINTS`] in their stored
//! order, whatever the number of threads. Each chunk scatters into its own
//! small dense patch covering the chunk's stencils; the patches are then added
//! into the layer row by row, each row visiting the patches in chunk order.
//! Every nodal sum is therefore formed in one fixed order, so the result is
//! bit-identical for any thread count. Patch buffers are kept between steps:
//! after the first step a scatter allocates nothing.

use crate::components::NodeRect;
use crate::math::{DVec2, Real};
use crate::shape_functions::{STENCIL_WIDTH, Stencil};
use rayon::prelude::*;
use std::ops::AddAssign;

/// Fewest points one parallel task handles in the per-point loops: below
/// this, splitting costs more (thread wake-ups) than it gains, and small
/// bodies run on one thread.
pub const MIN_POINTS_PER_TASK: usize = 1024;

/// Fewest nodes one parallel task handles in the per-node loops: a node
/// update is a few flops, so smaller tasks cost more to hand out than they
/// save (measured on the standard bench: no gain below 4096).
pub const MIN_NODES_PER_TASK: usize = 4096;

/// Points per scatter chunk. Fixed (not derived from the thread count) so that
/// results do not depend on it; large enough to amortise the patch overhead,
/// small enough to give both cores many chunks at 10⁴ points.
pub const CHUNK_POINTS: usize = 1024;

/// A dense rectangle of nodes receiving one chunk's contributions.
#[derive(Clone, Debug, Default)]
struct Patch<T> {
    /// Grid index of the lower-left node.
    origin: [usize; 2],
    /// Nodes per row.
    width: usize,
    /// Number of rows.
    height: usize,
    /// Row-major values.
    values: Vec<T>,
}

/// Reusable patches for one scattered quantity of one body.
#[derive(Clone, Debug, Default)]
pub struct Scatter<T> {
    patches: Vec<Patch<T>>,
}

impl<T: Copy + Default + AddAssign + Send + Sync> Scatter<T> {
    /// Scatters every point into the patches: for point p, `per_point(p)`
    /// computes what the point carries once, then `per_node(&carried, S_ip, G_ip)`
    /// gives its contribution to each stencil node.
    pub fn scatter<P>(
        &mut self,
        stencils: &[Stencil],
        per_point: impl Fn(usize) -> P + Sync,
        per_node: impl Fn(&P, Real, DVec2) -> T + Sync,
    ) {
        let chunks = stencils.len().div_ceil(CHUNK_POINTS);
        self.patches.resize_with(chunks, Patch::default);
        self.patches
            .par_iter_mut()
            .enumerate()
            .for_each(|(c, patch)| {
                let first = c * CHUNK_POINTS;
                let chunk = &stencils[first..(first + CHUNK_POINTS).min(stencils.len())];
                patch.cover(chunk);
                for (k, stencil) in chunk.iter().enumerate() {
                    let carried = per_point(first + k);
                    let origin = [patch.origin[0] as u32, patch.origin[1] as u32];
                    stencil.scatter(&mut patch.values, origin, patch.width, |value, w, g| {
                        *value += per_node(&carried, w, g);
                    });
                }
            });
    }

    /// Adds the scattered values into `nodes`, a row-major field stored
    /// over `window`, with `merge`, rows in parallel, patches in chunk order
    /// per row. Every patch must lie inside the window (a layer's window
    /// covers its active nodes, which cover its points' stencils).
    pub fn add_into<N: Send>(
        &self,
        nodes: &mut [N],
        window: NodeRect,
        merge: impl Fn(&mut N, T) + Sync,
    ) {
        for patch in &self.patches {
            let rect = NodeRect {
                start: patch.origin,
                end: [
                    patch.origin[0] + patch.width,
                    patch.origin[1] + patch.height,
                ],
            };
            assert!(
                window.covers(rect),
                "a scatter patch {rect:?} reaches past the layer's stored nodes {window:?}"
            );
        }
        window.rows_mut(window, nodes).for_each(|(j, row)| {
            for patch in &self.patches {
                if j < patch.origin[1] || j >= patch.origin[1] + patch.height {
                    continue;
                }
                let start = (j - patch.origin[1]) * patch.width;
                let values = &patch.values[start..start + patch.width];
                let first = patch.origin[0] - window.start[0];
                for (node, value) in row[first..].iter_mut().zip(values) {
                    merge(node, *value);
                }
            }
        });
    }
}

impl<T: Copy + Default> Patch<T> {
    /// Resizes and zeroes the patch to cover every node of `stencils`.
    fn cover(&mut self, stencils: &[Stencil]) {
        let mut lo = [u32::MAX; 2];
        let mut hi = [0u32; 2];
        for s in stencils {
            for d in 0..2 {
                lo[d] = lo[d].min(s.base[d]);
                hi[d] = hi[d].max(s.base[d] + STENCIL_WIDTH as u32 - 1);
            }
        }
        self.origin = [lo[0] as usize, lo[1] as usize];
        self.width = (hi[0] - lo[0] + 1) as usize;
        self.height = (hi[1] - lo[1] + 1) as usize;
        self.values.clear();
        self.values.resize(self.width * self.height, T::default());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape_functions::{ShapeFunction, StencilGrid};

    /// Scatter of the weights of scattered points must equal a plain
    /// sequential sum up to round-off, and be bit-identical for 1 and 2 threads.
    #[test]
    fn scatter_matches_a_sequential_sum_and_ignores_the_thread_count() {
        let nodes = [41usize, 31];
        let h = 0.1;
        let grid = StencilGrid {
            origin: DVec2::ZERO,
            inv_cell_size: 1.0 / h,
            nodes,
            walls: [[false; 2]; 2],
        };
        let stencils: Vec<Stencil> = (0..5000)
            .map(|k| {
                let t = k as Real * 0.618_033_988_75;
                let p = DVec2::new(0.5 + 3.0 * t.fract(), 0.5 + 2.0 * (t * 0.37).fract());
                ShapeFunction::UGimp
                    .stencil(p, DVec2::splat(h / 4.0), &grid)
                    .unwrap()
            })
            .collect();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut scatter = Scatter::<Real>::default();
                scatter.scatter(&stencils, |p| 1.0 + p as Real, |m, w, _| m * w);
                let mut grid = vec![0.0; nodes[0] * nodes[1]];
                scatter.add_into(&mut grid, NodeRect::whole(nodes), |n, v| *n += v);
                grid
            })
        };
        let one = run(1);
        let two = run(2);
        assert!(
            one.iter()
                .zip(&two)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
        let mut reference = vec![0.0; nodes[0] * nodes[1]];
        for (p, s) in stencils.iter().enumerate() {
            s.scatter(&mut reference, [0, 0], nodes[0], |r, w, _| {
                *r += (1.0 + p as Real) * w
            });
        }
        let total: Real = reference.iter().sum();
        for (a, b) in one.iter().zip(&reference) {
            assert!((a - b).abs() <= 1e-12 * total);
        }
    }
}
