//! Deterministic parallel point-to-grid scatter (DESIGN.md section 6).
//!
//! The grid is cut into fixed tiles of [`TILE_CELLS`] (16 × 16) stencil
//! base nodes, counted from the grid's first node. A point belongs
//! to the tile of its stencil's base node ([`ScatterOrder`]); each tile's
//! points, in stored order, scatter into the tile's own small dense patch;
//! the patches are then added into the layer row by row, each row visiting
//! the patches in tile order (row of tiles, then column). Every nodal sum is
//! therefore formed in one fixed order that depends on the points' places
//! and stored order only: not on the number of threads, nor on how the
//! points are shared out, so that a domain cut along tile edges sums the
//! same. The patches stay small however far the points have moved from the
//! order they were stored in. Patch buffers are kept between steps: after
//! the first steps a scatter allocates nothing.

use crate::math::{DVec2, Real};
use crate::node_rect::NodeRect;
use crate::shape_functions::{STENCIL_WIDTH, Stencil};
use rayon::prelude::*;
use std::ops::{AddAssign, Range};

/// Stencil base nodes of a scatter tile along x and y: fixed (its sums do
/// not depend on the thread count). 16 × 16 cells hold 1024 points at 2 × 2
/// points per cell, enough to amortise a patch (18 × 18 nodes for the widest
/// stencil), and are fine enough to cut a domain into strips.
pub const TILE_CELLS: [usize; 2] = [16, 16];

/// Tiles per parallel task, at least: a task per tile would cost more in
/// scheduling than a small tile's scatter.
const TILES_PER_TASK: usize = 4;

/// Points per task of the parallel pass that finds each point's tile.
const KEY_CHUNK: usize = 4096;

/// The order in which the scatters of a step visit a body's points: by the
/// tile of their stencil's base node, tiles row by row, and within a tile in
/// stored order (a stable counting sort: the order follows from the
/// positions and the stored order, never from the number of threads).
#[derive(Clone, Debug, Default)]
pub struct ScatterOrder {
    /// Point indices, sorted by tile.
    points: Vec<u32>,
    /// Per point, its tile among the window's, row by row.
    keys: Vec<u32>,
    /// Per tile of the window: its points, then its next place in `points`.
    tiles: Vec<u32>,
    /// The ranges of `points` of the tiles that hold points, in tile order.
    chunks: Vec<Range<usize>>,
    /// The layer's window the stencils lie in.
    window: NodeRect,
    /// The tiles of the whole grid.
    grid_tiles: usize,
    /// Per chunk, the nodes its stencils cover: the same for every scatter
    /// of the step.
    patches: Vec<NodeRect>,
}

/// The tiles, along x and y, that the base nodes of `window` fall in.
fn tile_span(window: NodeRect) -> [Range<usize>; 2] {
    [0, 1].map(|d| {
        window.start[d] / TILE_CELLS[d]
            ..window.end[d]
                .max(window.start[d] + 1)
                .div_ceil(TILE_CELLS[d])
    })
}

impl ScatterOrder {
    /// Sorts the points by the tile of their stencil's base node, given as
    /// `bases` (one per point, [`Stencil::base`]); every stencil lies in
    /// `window` (a layer's window covers its points' stencils), of a grid
    /// of `grid_nodes` nodes along x and y.
    pub fn sort_by_tile(&mut self, bases: &[[u32; 2]], window: NodeRect, grid_nodes: [usize; 2]) {
        self.grid_tiles = tile_span(NodeRect::whole(grid_nodes))
            .iter()
            .map(|t| t.len())
            .product();
        // Room for every tile of the grid, made once: a window that grows,
        // or a tile that fills for the first time, does not grow a list.
        let tiles = self.grid_tiles;
        self.tiles.reserve(tiles.saturating_sub(self.tiles.len()));
        self.chunks.reserve(tiles.saturating_sub(self.chunks.len()));
        self.patches
            .reserve(tiles.saturating_sub(self.patches.len()));
        self.sort_points(bases, window);
        self.patches.resize(self.chunks.len(), NodeRect::default());
        self.patches
            .par_iter_mut()
            .zip(self.chunks.par_iter())
            .with_min_len(TILES_PER_TASK)
            .for_each(|(patch, chunk)| {
                let points = &self.points[chunk.clone()];
                *patch = covered_nodes(points.iter().map(|&p| bases[p as usize]));
            });
    }

    /// The counting sort of [`Self::sort_by_tile`]. Points rarely change
    /// tiles from one step to the next: when none did, the order stands.
    fn sort_points(&mut self, bases: &[[u32; 2]], window: NodeRect) {
        let [across, up] = tile_span(window);
        let same_tiles = self.keys.len() == bases.len()
            && tile_span(self.window) == [across.clone(), up.clone()];
        self.window = window;
        let columns = across.len() as u32;
        let (first_column, first_row) = (across.start as u32, up.start as u32);
        let (low, high) = (window.start.map(|k| k as u32), window.end.map(|k| k as u32));
        self.keys.resize(bases.len(), 0);
        let (outside, moved) = self
            .keys
            .par_chunks_mut(KEY_CHUNK)
            .zip(bases.par_chunks(KEY_CHUNK))
            .map(|(keys, bases)| {
                let (mut outside, mut moved) = (false, false);
                for (key, &base) in keys.iter_mut().zip(bases) {
                    outside |= base[0] < low[0]
                        || base[0] >= high[0]
                        || base[1] < low[1]
                        || base[1] >= high[1];
                    // Constant divisors: shifts, not divisions, per point.
                    let k = (base[1] / TILE_CELLS[1] as u32)
                        .wrapping_sub(first_row)
                        .wrapping_mul(columns)
                        .wrapping_add((base[0] / TILE_CELLS[0] as u32).wrapping_sub(first_column));
                    moved |= *key != k;
                    *key = k;
                }
                (outside, moved)
            })
            .reduce(|| (false, false), |a, b| (a.0 | b.0, a.1 | b.1));
        let changed = moved || !same_tiles;
        if outside {
            let stray = bases.iter().find(|b| {
                !(window.start[0]..window.end[0]).contains(&(b[0] as usize))
                    || !(window.start[1]..window.end[1]).contains(&(b[1] as usize))
            });
            panic!("a stencil at {stray:?} lies outside the layer's stored nodes {window:?}");
        }
        if !changed {
            return;
        }
        self.tiles.clear();
        self.tiles.resize(across.len() * up.len(), 0);
        for &key in &self.keys {
            self.tiles[key as usize] += 1;
        }
        self.chunks.clear();
        let mut first = 0;
        for count in &mut self.tiles {
            let n = *count as usize;
            if n > 0 {
                self.chunks.push(first..first + n);
            }
            *count = first as u32;
            first += n;
        }
        self.points.resize(bases.len(), 0);
        for (p, &key) in self.keys.iter().enumerate() {
            let place = &mut self.tiles[key as usize];
            self.points[*place as usize] = p as u32;
            *place += 1;
        }
    }

    /// The point indices in scatter order.
    pub fn points(&self) -> &[u32] {
        &self.points
    }

    /// The number of tiles of the whole grid.
    pub fn grid_tiles(&self) -> usize {
        self.grid_tiles
    }

    /// The tiles (row, column among the grid's) that hold points, in tile
    /// order.
    pub fn tiles(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        self.patches.iter().map(tile_of)
    }

    /// The point indices of each tile that holds points, in tile order.
    pub fn tile_points(&self) -> impl IndexedParallelIterator<Item = &[u32]> {
        self.chunks.par_iter().map(|c| &self.points[c.clone()])
    }
}

/// Reusable patches for one scattered quantity of one body: a slot of
/// [`PATCH_NODES`] values per tile holding points, slot k for the k-th, each
/// row-major over the nodes its tile's stencils cover.
#[derive(Clone, Debug, Default)]
pub struct Scatter<T> {
    /// The slots, in one buffer made once with room for every tile of the
    /// grid: room never written takes address space, not memory (the
    /// system gives a page only when it is first written), and a tile that
    /// fills for the first time finds its slot ready.
    values: Vec<T>,
    /// The nodes each slot of the last scatter covers.
    rects: Vec<NodeRect>,
}

/// The most nodes a patch covers: a tile's base nodes and its stencils' reach.
const PATCH_NODES: usize =
    (TILE_CELLS[0] + STENCIL_WIDTH - 1) * (TILE_CELLS[1] + STENCIL_WIDTH - 1);

impl<T: Copy + Default + AddAssign + Send + Sync> Scatter<T> {
    /// Scatters every point into the patches, a chunk per tile of `order`
    /// (sorted from these `stencils`): for point p, `per_point(p)` computes what the
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
        let covered = &order.patches;
        let chunks = &order.chunks;
        let slots = order.grid_tiles.max(covered.len());
        let points = order.points();
        assert_eq!(
            points.len(),
            stencils.len(),
            "the scatter order was sorted for other stencils"
        );
        if self.values.capacity() < slots * PATCH_NODES {
            self.values = Vec::with_capacity(slots * PATCH_NODES);
            self.rects = Vec::with_capacity(slots);
        }
        self.values
            .resize(covered.len() * PATCH_NODES, T::default());
        self.rects.clear();
        self.rects.extend_from_slice(covered);
        self.values
            .par_chunks_mut(PATCH_NODES)
            .zip(chunks.par_iter())
            .zip(covered)
            .with_min_len(TILES_PER_TASK)
            .for_each(|((slot, chunk), nodes)| {
                let width = nodes.width();
                let values = &mut slot[..width * nodes.height()];
                values.fill(T::default());
                let origin = nodes.start.map(|k| k as u32);
                for &p in &points[chunk.clone()] {
                    let carried = per_point(p as usize);
                    stencils[p as usize].scatter(values, origin, width, |value, w, g, k| {
                        *value += per_node(&carried, w, g, k)
                    });
                }
            });
    }

    /// The slots of the last scatter: each tile's nodes and values.
    fn patches(&self) -> impl Iterator<Item = (NodeRect, &[T])> {
        self.rects
            .iter()
            .zip(self.values.chunks(PATCH_NODES))
            .map(|(rect, slot)| (*rect, &slot[..rect.width() * rect.height()]))
    }

    /// Nodes in all patches of the last scatter (what zeroing and merging
    /// them costs, against nine per point for the scatter itself).
    #[cfg(test)]
    fn patch_nodes(&self) -> usize {
        self.patches().map(|(_, values)| values.len()).sum()
    }

    /// Adds the scattered values into `nodes`, a row-major field stored
    /// over `window`, with `merge`, rows in parallel, patches in tile order
    /// per row. Every patch must lie inside the window (a layer's window
    /// covers its active nodes, which cover its points' stencils). The
    /// patches of other processes' tiles (`foreign`, in tile order) are
    /// taken in their tiles' places, so that each nodal sum is formed as
    /// one process holding every tile forms it; a foreign patch adds only
    /// to the `active` nodes (inside the window), which this process zeroes
    /// before each scatter: the nodes past them hold zero, and must keep
    /// it for when they become active.
    pub fn add_into_with<N: Send>(
        &self,
        foreign: &[SharedPatch<T>],
        nodes: &mut [N],
        (window, active): (NodeRect, NodeRect),
        merge: impl Fn(&mut N, T) + Sync,
    ) {
        for (rect, _) in self.patches() {
            assert!(
                window.covers(rect),
                "a scatter patch {rect:?} reaches past the layer's stored nodes {window:?}"
            );
        }
        window.rows_mut(window, nodes).for_each(|(j, row)| {
            // The patches are in tile order, so those that can reach row j,
            // from the tiles of the rows j − 2 to j, lie in one run.
            let first = self.rects.partition_point(|r| {
                tile_of(r)[0] < j.saturating_sub(STENCIL_WIDTH - 1) / TILE_CELLS[1]
            });
            let last = self
                .rects
                .partition_point(|r| tile_of(r)[0] <= j / TILE_CELLS[1]);
            let slots = self.values.chunks(PATCH_NODES).skip(first);
            let mut own = self.rects[first..last].iter().zip(slots).peekable();
            let active_row = (active.start[1]..active.end[1]).contains(&j);
            let mut others = foreign
                .iter()
                .filter(|f| active_row && (f.rect.start[1]..f.rect.end[1]).contains(&j))
                .peekable();
            loop {
                let take_own = match (own.peek(), others.peek()) {
                    (Some((rect, _)), Some(other)) => tile_of(rect) < other.tile,
                    (Some(_), None) => true,
                    (None, Some(_)) => false,
                    (None, None) => break,
                };
                if take_own {
                    let (rect, slot) = own.next().expect("peeked");
                    add_row(row, j, (window, window), *rect, slot, &merge);
                } else {
                    let other = others.next().expect("peeked");
                    add_row(row, j, (window, active), other.rect, &other.values, &merge);
                }
            }
        });
    }

    /// The values of the last scatter's patches on the node columns
    /// `columns`, with their tiles: what a process that shares those nodes
    /// takes into its [`Self::add_into_with`].
    pub fn shared(&self, columns: Range<usize>) -> Vec<SharedPatch<T>> {
        self.patches()
            .filter_map(|(rect, values)| {
                let part = NodeRect {
                    start: [rect.start[0].max(columns.start), rect.start[1]],
                    end: [rect.end[0].min(columns.end), rect.end[1]],
                };
                (part.start[0] < part.end[0]).then(|| SharedPatch {
                    tile: tile_of(&rect),
                    rect: part,
                    values: values
                        .chunks(rect.width())
                        .flat_map(|row| {
                            &row[part.start[0] - rect.start[0]..part.end[0] - rect.start[0]]
                        })
                        .copied()
                        .collect(),
                })
            })
            .collect()
    }
}

/// Part of a tile's patch that another process needs: the values on the
/// nodes `rect` (row-major), of the tile at `tile` (row, column).
#[derive(Clone, Debug, PartialEq)]
pub struct SharedPatch<T> {
    /// The tile's row and column among the grid's tiles.
    pub tile: [usize; 2],
    /// The nodes.
    pub rect: NodeRect,
    /// The values, row-major over `rect`.
    pub values: Vec<T>,
}

/// The tile (row, column) of a patch: the tile of its first base node.
fn tile_of(rect: &NodeRect) -> [usize; 2] {
    [rect.start[1] / TILE_CELLS[1], rect.start[0] / TILE_CELLS[0]]
}

/// Merges row `j` of a patch over `rect` into `row`, row `j` of a field
/// stored over `window`, at the nodes both cover.
fn add_row<N, T: Copy>(
    row: &mut [N],
    j: usize,
    (window, within): (NodeRect, NodeRect),
    rect: NodeRect,
    values: &[T],
    merge: &impl Fn(&mut N, T),
) {
    if j < rect.start[1] || j >= rect.end[1] {
        return;
    }
    let width = rect.width();
    let values = &values[(j - rect.start[1]) * width..][..width];
    let (from, to) = (
        rect.start[0].max(within.start[0]),
        rect.end[0].min(within.end[0]),
    );
    if from >= to {
        return;
    }
    let nodes = &mut row[from - window.start[0]..to - window.start[0]];
    for (node, value) in nodes.iter_mut().zip(&values[from - rect.start[0]..]) {
        merge(node, *value);
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
            order.sort_by_tile(&bases_of(stencils), NodeRect::whole(nodes), nodes);
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
            let whole = NodeRect::whole(nodes);
            scatter.add_into_with(&[], &mut sums, (whole, whole), |n, s| *n += s);
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
                order.sort_by_tile(&bases_of(&stencils), NodeRect::whole(nodes), nodes);
                let mut scatter = Scatter::<Real>::default();
                scatter.scatter(&stencils, &order, |p| 1.0 + p as Real, |m, w, _, _| m * w);
                let mut grid = vec![0.0; nodes[0] * nodes[1]];
                let whole = NodeRect::whole(nodes);
                scatter.add_into_with(&[], &mut grid, (whole, whole), |n, v| *n += v);
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
            order.sort_by_tile(&bases_of(stencils), NodeRect::whole(grid.nodes), grid.nodes);
            let mut scatter = Scatter::<Real>::default();
            scatter.scatter(stencils, &order, |_| 1.0, |m, w, _, _| m * w);
            scatter.patch_nodes()
        };
        let (sorted, unsorted) = (patch_nodes(&ordered), patch_nodes(&mixed));
        // One patch per tile of 16 × 16 base nodes, each at most
        // (16 + 3) × (16 + 3) nodes, whatever the stored order.
        let tiles = (columns + 1).div_ceil(TILE_CELLS[0]) * (rows + 1).div_ceil(TILE_CELLS[1]);
        assert_eq!(
            sorted, unsorted,
            "{sorted} nodes in order, {unsorted} mixed"
        );
        let widest = (TILE_CELLS[0] + STENCIL_WIDTH) * (TILE_CELLS[1] + STENCIL_WIDTH);
        assert!(sorted <= tiles * widest, "{sorted} nodes in {tiles} tiles");
    }

    /// The order is a permutation of the points, by tile (tiles row by row,
    /// counted from the grid's first node) and stable within a tile,
    /// through successive sorts, a shorter body and a window that does not
    /// start at the grid's first node.
    #[test]
    fn the_order_is_a_stable_permutation_by_tile() {
        let at = |base: [u32; 2]| Stencil {
            base,
            ..Stencil::default()
        };
        let window = NodeRect {
            start: [5, 10],
            end: [60, 50],
        };
        let tile = |s: &Stencil| {
            let t = TILE_CELLS.map(|t| t as u32);
            (s.base[1] / t[1], s.base[0] / t[0])
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
                let (ta, tb) = (tile(&stencils[a]), tile(&stencils[b]));
                assert!(ta < tb || (ta == tb && a < b), "{points:?}");
            }
            let chunks: usize = order.chunks.iter().map(|c| c.len()).sum();
            assert_eq!(chunks, stencils.len());
        };
        let mut order = ScatterOrder::default();
        for bases in [
            vec![
                [40, 13],
                [6, 11],
                [17, 13],
                [15, 12],
                [59, 49],
                [16, 11],
                [5, 17],
            ],
            vec![[20, 11], [21, 11], [20, 12], [50, 33], [50, 32]],
            vec![[12, 31], [11, 31]],
            vec![[5, 10]],
            vec![],
        ] {
            let stencils: Vec<Stencil> = bases.into_iter().map(at).collect();
            order.sort_by_tile(&bases_of(&stencils), window, window.end);
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
        ScatterOrder::default().sort_by_tile(&[stray.base], window, window.end);
    }
}
