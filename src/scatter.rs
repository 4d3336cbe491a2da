//! Deterministic parallel point-to-grid scatter (DESIGN.md section 6).
//!
//! Points are sorted by the grid row of their stencil ([`ScatterOrder`]) and
//! cut, in that order, into fixed-size chunks of [`CHUNK_POINTS`], whatever
//! the number of threads. Each chunk scatters into its own small dense patch
//! covering the chunk's stencils; the patches are then added into the layer
//! row by row, each row visiting the patches in chunk order. Every nodal sum
//! is therefore formed in one fixed order, so the result is bit-identical for
//! any thread count. Sorting keeps the patches small however far the points
//! have moved from the order they were stored in: a chunk spans a few rows
//! of the body, not the whole body. Patch buffers are kept between steps:
//! after the first steps a scatter allocates nothing.

use crate::math::{DVec2, Real};
use crate::node_rect::NodeRect;
use crate::shape_functions::{STENCIL_WIDTH, Stencil};
use rayon::prelude::*;
use std::ops::AddAssign;

/// Points per scatter chunk. Fixed (not derived from the thread count) so that
/// results do not depend on it; large enough to amortise the patch overhead,
/// small enough to give both cores many chunks at 10⁴ points.
pub const CHUNK_POINTS: usize = 1024;

/// The order in which the scatters of a step visit a body's points: by the
/// grid row of their stencil's base node, and within a row in stored order
/// (a stable counting sort: the order follows from the positions and the
/// stored order, never from the number of threads).
///
/// A body's points are stored in the order they were generated, row by row,
/// so chunks of stored points start as thin strips. Once a flow has mixed
/// them (a dam break, a collapsing column), a chunk of stored points can be
/// spread over the whole body, and its patch, the box around its stencils,
/// with it: in a dam break the patches grew to 1.4 times the nodes the points
/// write. Sorted chunks span a few rows of the body at any time.
#[derive(Clone, Debug, Default)]
pub struct ScatterOrder {
    /// Point indices, sorted by row.
    points: Vec<u32>,
    /// Whether `points` is 0, 1, 2, …: the points were stored in row order.
    stored_order: bool,
    /// Points per row of the window, then each row's next place in `points`.
    rows: Vec<u32>,
    /// The layer's window the stencils lie in.
    window: NodeRect,
    /// Per chunk of [`CHUNK_POINTS`] points in this order, the nodes its
    /// stencils cover: the same for every scatter of the step.
    patches: Vec<NodeRect>,
}

impl ScatterOrder {
    /// Sorts the points by the row of their stencil's base node, given as
    /// `bases` (one per point, [`Stencil::base`]); every stencil lies in
    /// `window` (a layer's window covers its points' stencils). Points
    /// already stored in row order, as in a body that has not flowed, cost
    /// one counting pass.
    pub fn sort_by_row(&mut self, bases: &[[u32; 2]], window: NodeRect) {
        self.sort_points(bases, window);
        let chunks = self.points.len().div_ceil(CHUNK_POINTS);
        self.patches.resize(chunks, NodeRect::default());
        self.patches
            .par_iter_mut()
            .zip(self.points.par_chunks(CHUNK_POINTS))
            .for_each(|(patch, chunk)| {
                *patch = covered_nodes(chunk.iter().map(|&p| bases[p as usize]));
            });
    }

    /// The counting sort of [`Self::sort_by_row`]. It takes the points in
    /// runs of one row, as they mostly come: a count or a place kept in a
    /// register over a run, not stored and reloaded at every point.
    fn sort_points(&mut self, bases: &[[u32; 2]], window: NodeRect) {
        self.window = window;
        let low = window.start[1] as u32;
        self.rows.clear();
        self.rows.resize(window.end[1] - window.start[1], 0);
        let mut in_row_order = true;
        let mut previous = 0;
        for run in bases.chunk_by(|a, b| a[1] == b[1]) {
            let base_row = run[0][1];
            let row = base_row.checked_sub(low).map(|r| r as usize);
            let Some(count) = row.and_then(|r| self.rows.get_mut(r)) else {
                panic!(
                    "a stencil at row {base_row} lies outside the layer's stored nodes {window:?}"
                );
            };
            *count += run.len() as u32;
            in_row_order &= base_row >= previous;
            previous = base_row;
        }
        if in_row_order {
            if !self.stored_order || self.points.len() != bases.len() {
                self.points.clear();
                self.points.extend(0..bases.len() as u32);
                self.stored_order = true;
            }
            return;
        }
        let mut first = 0;
        for row in &mut self.rows {
            let count = *row;
            *row = first;
            first += count;
        }
        self.points.resize(bases.len(), 0);
        let mut start = 0;
        for run in bases.chunk_by(|a, b| a[1] == b[1]) {
            let place = &mut self.rows[(run[0][1] - low) as usize];
            let end = start + run.len() as u32;
            let places = *place as usize..(*place + run.len() as u32) as usize;
            for (slot, p) in self.points[places].iter_mut().zip(start..end) {
                *slot = p;
            }
            *place += run.len() as u32;
            start = end;
        }
        self.stored_order = false;
    }

    /// The point indices in scatter order.
    pub fn points(&self) -> &[u32] {
        &self.points
    }
}

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
    /// Scatters every point into the patches, in chunks of `order` (sorted
    /// from these `stencils`): for point p, `per_point(p)` computes what the
    /// point carries once, then `per_node(&carried, S_ip, G_ip, [a, b])`
    /// gives its contribution to stencil node (a, b) (see
    /// [`Stencil::scatter`]).
    pub fn scatter<P>(
        &mut self,
        stencils: &[Stencil],
        order: &ScatterOrder,
        per_point: impl Fn(usize) -> P + Sync,
        per_node: impl Fn(&P, Real, DVec2, [usize; 2]) -> T + Sync,
    ) {
        let widest = order.window.width();
        let covered = &order.patches;
        let order = order.points();
        assert_eq!(
            order.len(),
            stencils.len(),
            "the scatter order was sorted for other stencils"
        );
        self.patches.resize_with(covered.len(), Patch::default);
        self.patches
            .par_iter_mut()
            .zip(order.par_chunks(CHUNK_POINTS))
            .zip(covered)
            .for_each(|((patch, chunk), &nodes)| {
                patch.cover(nodes, widest);
                let origin = [patch.origin[0] as u32, patch.origin[1] as u32];
                for &p in chunk {
                    let carried = per_point(p as usize);
                    stencils[p as usize].scatter(
                        &mut patch.values,
                        origin,
                        patch.width,
                        |value, w, g, k| *value += per_node(&carried, w, g, k),
                    );
                }
            });
    }

    /// Nodes in all patches of the last scatter (what zeroing and merging
    /// them costs, against nine per point for the scatter itself).
    #[cfg(test)]
    fn patch_nodes(&self) -> usize {
        self.patches.iter().map(|p| p.values.len()).sum()
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

/// The nodes that the stencils at `bases` (at least one) cover: the box
/// around their 3 × 3 blocks.
fn covered_nodes(bases: impl Iterator<Item = [u32; 2]>) -> NodeRect {
    let mut lo = [u32::MAX; 2];
    let mut hi = [0u32; 2];
    for base in bases {
        for d in 0..2 {
            lo[d] = lo[d].min(base[d]);
            hi[d] = hi[d].max(base[d] + STENCIL_WIDTH as u32);
        }
    }
    NodeRect {
        start: lo.map(|k| k as usize),
        end: hi.map(|k| k as usize),
    }
}

impl<T: Copy + Default> Patch<T> {
    /// Resizes and zeroes the patch to cover `nodes`. A patch that outgrows
    /// its buffer gets room for rows `widest` nodes long (the layer window's
    /// width, which no patch exceeds): as a body spreads sideways its
    /// patches widen, and they should not reallocate at each widening. Room
    /// never written (a contact group's window can be much wider than one
    /// body) takes address space, not memory: the system gives a page only
    /// when it is first written.
    fn cover(&mut self, nodes: NodeRect, widest: usize) {
        self.origin = nodes.start;
        self.width = nodes.width();
        self.height = nodes.height();
        self.values.clear();
        let needed = self.width * self.height;
        if self.values.capacity() < needed {
            self.values
                .reserve_exact(widest.max(self.width) * self.height);
        }
        self.values.resize(needed, T::default());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DMat2;
    use crate::shape_functions::{ShapeFunction, StencilGrid};
    use glam::DVec3;

    /// The stencils' base nodes, as particle-to-grid gives them to the order.
    fn bases_of(stencils: &[Stencil]) -> Vec<[u32; 2]> {
        stencils.iter().map(|s| s.base).collect()
    }

    /// The node places passed to `per_node` locate the nodes: points
    /// carrying an affine velocity field v(x) = v0 + A x as V_p = v(x_p)
    /// and C_p = A, scattered as S_ip m_p (V_p + C_p (x_i − x̄_p)), give
    /// every node v(x_i) exactly (to round-off), for every kernel, even
    /// where few points reach a node; and where a wall cuts the supports,
    /// the offsets from the nodes' mean keep the total momentum Σ m_p V_p.
    #[test]
    fn affine_momenta_reproduce_an_affine_field_at_every_node() {
        let nodes = [21usize, 17];
        let h = 0.1;
        let grid = StencilGrid {
            origin: DVec2::new(-0.3, 0.2),
            inv_cell_size: 1.0 / h,
            nodes,
            walls: [[false; 2]; 2],
        };
        let (v0, a) = (
            DVec2::new(0.3, -1.2),
            DMat2::from_cols_array(&[0.5, 2.0, -1.5, 0.25]),
        );
        let field = |x: DVec2| v0 + a * x;
        // Unit masses at `points` carrying the field affinely: each node's
        // momentum in x and y, its mass in z.
        let scatter_field = |points: &[DVec2], stencils: &[Stencil]| {
            let mut order = ScatterOrder::default();
            order.sort_by_row(&bases_of(stencils), NodeRect::whole(nodes));
            let mut scatter = Scatter::<DVec3>::default();
            scatter.scatter(
                stencils,
                &order,
                |p| (field(points[p]), stencils[p].mean_place()),
                |&(v, mean), w, _, node| {
                    let offset = Stencil::offset_from_mean(mean, node, h);
                    (w * (v + a * offset)).extend(w)
                },
            );
            let mut sums = vec![DVec3::ZERO; nodes[0] * nodes[1]];
            scatter.add_into(&mut sums, NodeRect::whole(nodes), |n, s| *n += s);
            sums
        };
        let positions: Vec<DVec2> = (0..300)
            .map(|k| {
                let t = k as Real * 0.618_033_988_75;
                grid.origin + DVec2::new(0.3 + 1.4 * t.fract(), 0.3 + 1.0 * (t * 0.37).fract())
            })
            .collect();
        for kernel in [
            ShapeFunction::Linear,
            ShapeFunction::UGimp,
            ShapeFunction::QuadraticBSpline,
        ] {
            let stencils: Vec<Stencil> = positions
                .iter()
                .map(|&x| kernel.stencil(x, DVec2::splat(h / 4.0), &grid).unwrap())
                .collect();
            let sums = scatter_field(&positions, &stencils);
            let mut reached = 0;
            for (k, sum) in sums.iter().enumerate() {
                if sum.z > 1e-6 {
                    reached += 1;
                    let at = grid.origin
                        + h * DVec2::new((k % nodes[0]) as Real, (k / nodes[0]) as Real);
                    let error = (sum.truncate() / sum.z - field(at)).length();
                    assert!(error < 1e-12, "{kernel:?}: node {k} off by {error}");
                }
            }
            assert!(reached > 100, "{kernel:?}: {reached} nodes reached");
        }
        // At a wall the cut renormalises the weights, Σ S_ip x_i ≠ x_p: the
        // offsets from the nodes' mean still add no momentum.
        let walled = StencilGrid {
            walls: [[true; 2]; 2],
            ..grid
        };
        let near: Vec<DVec2> = (0..40)
            .map(|k| grid.origin + DVec2::new(0.01 + 0.002 * k as Real, 0.5 + 0.01 * k as Real))
            .collect();
        let stencils: Vec<Stencil> = near
            .iter()
            .map(|&x| {
                ShapeFunction::UGimp
                    .stencil(x, DVec2::splat(h / 4.0), &walled)
                    .unwrap()
            })
            .collect();
        let cut = stencils
            .iter()
            .zip(&near)
            .filter(|(st, x)| {
                let base = DVec2::new(Real::from(st.base[0]), Real::from(st.base[1]));
                (grid.origin + (base + st.mean_place()) * h - **x).length() > 1e-9
            })
            .count();
        assert!(cut >= 5, "{cut} points cut by the wall");
        let total: DVec2 = scatter_field(&near, &stencils)
            .iter()
            .map(|n| n.truncate())
            .sum();
        let expected: DVec2 = near.iter().map(|&x| field(x)).sum();
        assert!((total - expected).length() < 1e-12, "{total} vs {expected}");
    }

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
                let mut order = ScatterOrder::default();
                order.sort_by_row(&bases_of(&stencils), NodeRect::whole(nodes));
                let mut scatter = Scatter::<Real>::default();
                scatter.scatter(&stencils, &order, |p| 1.0 + p as Real, |m, w, _, _| m * w);
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
            s.scatter(&mut reference, [0, 0], nodes[0], |r, w, _, _| {
                *r += (1.0 + p as Real) * w
            });
        }
        let total: Real = reference.iter().sum();
        for (a, b) in one.iter().zip(&reference) {
            assert!((a - b).abs() <= 1e-12 * total);
        }
    }

    /// Points stored in an order that has nothing to do with their place (as
    /// after a flow has mixed a body) give patches no larger than points
    /// stored row by row: a chunk covers a few rows, never the whole body.
    #[test]
    fn mixed_points_scatter_into_patches_as_small_as_ordered_ones() {
        let h = 0.1;
        let (columns, rows) = (200usize, 50usize);
        let grid = StencilGrid {
            origin: DVec2::ZERO,
            inv_cell_size: 1.0 / h,
            nodes: [columns + 3, rows + 3],
            walls: [[false; 2]; 2],
        };
        let stencil = |k: usize| {
            let p = DVec2::new(
                ((k % columns) as Real + 1.5) * h,
                ((k / columns) as Real + 1.5) * h,
            );
            ShapeFunction::UGimp
                .stencil(p, DVec2::splat(h / 2.0), &grid)
                .unwrap()
        };
        let ordered: Vec<Stencil> = (0..columns * rows).map(stencil).collect();
        // A fixed permutation: k ↦ 7919 k mod n scatters neighbours far apart.
        let n = ordered.len();
        let mixed: Vec<Stencil> = (0..n).map(|k| ordered[(7919 * k) % n]).collect();
        let patch_nodes = |stencils: &[Stencil]| {
            let mut order = ScatterOrder::default();
            order.sort_by_row(&bases_of(stencils), NodeRect::whole(grid.nodes));
            let mut scatter = Scatter::<Real>::default();
            scatter.scatter(stencils, &order, |_| 1.0, |m, w, _, _| m * w);
            scatter.patch_nodes()
        };
        let (sorted, unsorted) = (patch_nodes(&ordered), patch_nodes(&mixed));
        // Each chunk of 1024 points spans ⌈1024 / 200⌉ + 1 = 7 rows of one
        // point per cell, so its patch has at most 7 + 2 rows of 202 nodes.
        assert_eq!(
            sorted, unsorted,
            "{sorted} nodes in order, {unsorted} mixed"
        );
        assert!(
            sorted <= n.div_ceil(CHUNK_POINTS) * 9 * (columns + 2),
            "{sorted}"
        );
    }

    /// The order is a permutation of the points, stable by row, through
    /// mixed and ordered steps, a shorter body and a window that does not
    /// start at row 0.
    #[test]
    fn the_order_is_a_stable_permutation_by_row() {
        let at_row = |row: u32| Stencil {
            base: [4, row],
            ..Stencil::default()
        };
        let window = NodeRect {
            start: [0, 10],
            end: [20, 20],
        };
        let check = |order: &ScatterOrder, stencils: &[Stencil]| {
            let points = order.points();
            let mut seen = vec![false; stencils.len()];
            for &p in points {
                assert!(!std::mem::replace(&mut seen[p as usize], true), "{p} twice");
            }
            assert!(seen.iter().all(|&s| s), "not every point: {points:?}");
            for pair in points.windows(2) {
                let (a, b) = (pair[0] as usize, pair[1] as usize);
                let (ra, rb) = (stencils[a].base[1], stencils[b].base[1]);
                assert!(ra < rb || (ra == rb && a < b), "{points:?}");
            }
        };
        let mut order = ScatterOrder::default();
        for rows in [
            vec![13, 11, 13, 12, 11, 17],
            vec![11, 11, 12, 13, 13, 17],
            vec![12, 11, 19],
            vec![10, 10],
            vec![],
        ] {
            let stencils: Vec<Stencil> = rows.into_iter().map(at_row).collect();
            order.sort_by_row(&bases_of(&stencils), window);
            check(&order, &stencils);
        }
    }

    #[test]
    #[should_panic(expected = "outside the layer's stored nodes")]
    fn a_stencil_outside_the_window_is_refused_clearly() {
        let window = NodeRect {
            start: [0, 10],
            end: [20, 20],
        };
        let stray = Stencil {
            base: [4, 9],
            ..Stencil::default()
        };
        ScatterOrder::default().sort_by_row(&[stray.base], window);
    }
}
