//! Shape functions: how a material point spreads onto, and reads from, the
//! nodes of the background grid.
//!
//! Each kernel is one-dimensional and stateless (`Kernel`); the 2D weight is
//! the tensor product S_ip = S(x_p − x_i) S(y_p − y_i) and the generalised
//! gradient is G_ip = (S'(x) S(y), S(x) S'(y)) (paper eqs. 9a/9b). Every
//! kernel here touches at most three nodes per direction, so a point's
//! `Stencil` is always 3 × 3 nodes (unused entries carry zero weight).

mod bspline;
mod linear;
mod ugimp;

pub(crate) use bspline::QuadraticBSpline;
pub(crate) use linear::LinearHat;
pub(crate) use ugimp::UGimp;

use crate::math::{DVec2, Real};
use crate::parallel::MIN_POINTS_PER_TASK;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// A one-dimensional shape function, in cell units.
pub(crate) trait Kernel: Copy + Send + Sync {
    /// Weight and its derivative with respect to ξ, for a point at signed
    /// distance ξ = (x_p − x_i)/h from a node, with particle domain
    /// half-size `half` = l/h and its inverse `inv_half` (GIMP only; the
    /// inverse is passed so the hot loop does no division).
    fn eval(&self, xi: Real, half: Real, inv_half: Real) -> (Real, Real);

    /// Weights and derivatives at a point's three nodes, ξ0 from the first
    /// (in [½, 3⁄2), or a rounding below ½): `eval` at ξ0, ξ0 − 1 and
    /// ξ0 − 2. A kernel may give them from what it knows of each node's
    /// side of the point.
    #[inline(always)]
    fn eval_three(&self, xi0: Real, half: Real, inv_half: Real) -> ([Real; 3], [Real; 3]) {
        eval_each(self, xi0, half, inv_half)
    }
}

/// [`Kernel::eval`] at ξ0, ξ0 − 1 and ξ0 − 2: the weights and derivatives.
#[inline(always)]
fn eval_each<K: Kernel>(
    kernel: &K,
    xi0: Real,
    half: Real,
    inv_half: Real,
) -> ([Real; 3], [Real; 3]) {
    let (w0, g0) = kernel.eval(xi0, half, inv_half);
    let (w1, g1) = kernel.eval(xi0 - 1.0, half, inv_half);
    let (w2, g2) = kernel.eval(xi0 - 2.0, half, inv_half);
    ([w0, w1, w2], [g0, g1, g2])
}

/// The shape function chosen for a simulation (scene `settings.shape_function`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ShapeFunction {
    /// Linear hat functions (original MPM): cheap, but cell-crossing noise.
    Linear,
    /// Undeformed GIMP (default): the paper's choice; smooth cell crossing,
    /// domain half-size fixed at h / (2 × points per cell).
    #[default]
    UGimp,
    /// Quadratic B-spline: smooth, but needs one cell of margin between a
    /// body and the grid edge (its support is 1.5 cells).
    QuadraticBSpline,
}

impl ShapeFunction {
    /// The stencil of a point at `position` with domain half-size `half_size`,
    /// or `None` when the point has left `grid`.
    pub(crate) fn stencil(
        self,
        position: DVec2,
        half_size: DVec2,
        grid: &StencilGrid,
    ) -> Option<Stencil> {
        match self {
            Self::Linear => Stencil::new(LinearHat, position, half_size, grid),
            Self::UGimp => Stencil::new(UGimp, position, half_size, grid),
            Self::QuadraticBSpline => Stencil::new(QuadraticBSpline, position, half_size, grid),
        }
    }

    /// Computes the stencil of every point into `out` (same length as the
    /// columns), and each stencil's base node into `bases`, in parallel, and
    /// returns the index of the first point that has left the grid (its
    /// stencil is then empty), if any.
    pub(crate) fn fill_stencils(
        self,
        positions: &[DVec2],
        half_sizes: &[DVec2],
        grid: &StencilGrid,
        out: (&mut [Stencil], &mut [[u32; 2]]),
    ) -> Option<usize> {
        match self {
            Self::Linear => fill(LinearHat, positions, half_sizes, grid, out),
            Self::UGimp => fill(UGimp, positions, half_sizes, grid, out),
            Self::QuadraticBSpline => fill(QuadraticBSpline, positions, half_sizes, grid, out),
        }
    }

    /// Distance from a body's outline to the grid edge that this kernel needs
    /// so that no weight falls outside the grid, as a multiple of the cell size.
    pub fn required_margin_cells(self) -> Real {
        match self {
            Self::Linear | Self::UGimp => 0.0,
            Self::QuadraticBSpline => 1.0,
        }
    }
}

/// [`ShapeFunction::fill_stencils`] for one kernel, monomorphised so the
/// loop has no dispatch inside it.
fn fill<K: Kernel>(
    kernel: K,
    positions: &[DVec2],
    half_sizes: &[DVec2],
    grid: &StencilGrid,
    (out, bases): (&mut [Stencil], &mut [[u32; 2]]),
) -> Option<usize> {
    assert_eq!(out.len(), bases.len(), "a base node per stencil");
    out.par_chunks_mut(MIN_POINTS_PER_TASK)
        .zip(bases.par_chunks_mut(MIN_POINTS_PER_TASK))
        .enumerate()
        .filter_map(|(c, (chunk, chunk_bases))| {
            let first = c * MIN_POINTS_PER_TASK;
            let columns = positions[first..].iter().zip(&half_sizes[first..]);
            let mut outside = None;
            let outputs = chunk.iter_mut().zip(chunk_bases.iter_mut());
            for (k, ((stencil, base), (x, half))) in outputs.zip(columns).enumerate() {
                *stencil = Stencil::new(kernel, *x, *half, grid).unwrap_or_else(|| {
                    outside.get_or_insert(first + k);
                    Stencil::default()
                });
                *base = stencil.base;
            }
            outside
        })
        .min()
}

/// Nodes per direction of every stencil: the widest kernel support (the
/// B-spline's 1.5 cells, uGIMP's h + l ≤ 1.5 cells) touches three nodes.
pub(crate) const STENCIL_WIDTH: usize = 3;

/// What a stencil needs to know of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StencilGrid {
    /// Position of node (0, 0) (m).
    pub origin: DVec2,
    /// Inverse cell size 1/h (1/m), so stencils need no division by h.
    pub inv_cell_size: Real,
    /// Nodes along x and y (each ≥ 3).
    pub nodes: [usize; 2],
    /// `walls[axis][side]`: whether the edge (side 0 low, 1 high) is a wall
    /// (a fixed or slip condition). A point's domain may press against and
    /// slightly into a wall, as the points next to it move: its weights are
    /// then those of the part of its support inside the grid (eq. 9 over
    /// Ω_p ∩ Ω). Beyond an open edge any weight above round-off means the
    /// point has left the grid.
    pub walls: [[bool; 2]; 2],
}

impl StencilGrid {
    /// The column of the base node of every kernel's stencil at `x`, as
    /// [`Stencil::new`] finds it: floor(s − ½) in cells, kept off the
    /// grid's edges (a point off the grid takes the nearest column).
    pub(crate) fn base_column(&self, x: Real) -> u32 {
        let s = (x - self.origin.x) * self.inv_cell_size;
        let first = if s >= 0.0 { (s + 0.5) as i64 - 1 } else { 0 };
        first.clamp(0, self.nodes[0] as i64 - 3) as u32
    }
}

/// The 3 × 3 nodes a point maps to, with the 1D weights and derivatives per
/// direction. Node (a, b) of the stencil is grid node (`base[0] + a`, `base[1] + b`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Stencil {
    /// Grid index of the stencil's lower-left node.
    pub base: [u32; 2],
    /// Per direction, the first of the stencil's nodes whose weight or
    /// derivative is not zero (0 or 1), and with `reached` the nodes from
    /// it that have one: a uGIMP point whose support ends on or short of a
    /// node (half the time at 2 × 2 points per cell) reaches two nodes in
    /// that direction, not three. The transfers visit only these; the
    /// others would add exact zeros.
    pub first_reached: [u8; 2],
    /// Per direction, how many nodes from `first_reached` the point reaches
    /// (1 to 3).
    pub reached: [u8; 2],
    /// Weights along x for nodes `base[0]` to `base[0] + 2`.
    pub wx: [Real; 3],
    /// Weights along y for nodes `base[1]` to `base[1] + 2`.
    pub wy: [Real; 3],
    /// Derivatives of `wx` with respect to the point's x.
    pub gx: [Real; 3],
    /// Derivatives of `wy` with respect to the point's y.
    pub gy: [Real; 3],
}

impl Stencil {
    /// Builds the stencil for one kernel; `None` when the point has left the grid.
    #[inline(always)]
    pub fn new<K: Kernel>(
        kernel: K,
        position: DVec2,
        half_size: DVec2,
        grid: &StencilGrid,
    ) -> Option<Self> {
        let inv_h = grid.inv_cell_size;
        let s = (position - grid.origin) * inv_h;
        let half = half_size * inv_h;
        let (bx, wx, gx) = axis(kernel, s.x, half.x, grid.nodes[0], grid.walls[0])?;
        let (by, wy, gy) = axis(kernel, s.y, half.y, grid.nodes[1], grid.walls[1])?;
        let (gx, gy) = (gx.map(|g| g * inv_h), gy.map(|g| g * inv_h));
        let (x_reach, y_reach) = (reach(&wx, &gx), reach(&wy, &gy));
        Some(Self {
            base: [bx, by],
            first_reached: [x_reach.0, y_reach.0],
            reached: [x_reach.1, y_reach.1],
            wx,
            wy,
            gx,
            gy,
        })
    }

    /// The weights' mean of the stencil's node places, (Σ_a w_x,a a,
    /// Σ_b w_y,b b) in cells from `base`: the point's own place where its
    /// support lies inside the grid (the kernels reproduce linear fields),
    /// the mean of the nodes it reaches where a wall cuts its support.
    #[inline(always)]
    pub fn mean_place(&self) -> DVec2 {
        DVec2::new(self.wx[1] + 2.0 * self.wx[2], self.wy[1] + 2.0 * self.wy[2])
    }

    /// x_i − x̄_p (m) for stencil node `node` = (a, b), x̄_p = Σ_i S_ip x_i
    /// the nodes' mean position (`mean` from [`Self::mean_place`], `cell`
    /// the cell size): x_i − x_p where the support lies inside the grid.
    /// The offsets' weighted sum is zero, so a momentum built on them (the
    /// affine transfer) adds none, at walls too.
    #[inline(always)]
    pub fn offset_from_mean(mean: DVec2, node: [usize; 2], cell: Real) -> DVec2 {
        cell * (DVec2::new(node[0] as Real, node[1] as Real) - mean)
    }

    /// Folds `f(acc, value, S_ip, G_ip)` over the stencil nodes the point
    /// reaches (`reached`) of a row-major field `values` whose first value is
    /// grid node `origin`, with `row_len` nodes per row.
    #[inline(always)]
    pub fn gather<T, A>(
        &self,
        values: &[T],
        origin: [u32; 2],
        row_len: usize,
        acc: A,
        f: impl FnMut(A, &T, Real, DVec2) -> A,
    ) -> A {
        let at = self.place(origin, row_len);
        let start = self.first_reached.map(usize::from);
        match self.reached {
            [2, 3] => self.gather_block::<2, 3, T, A>(values, at, start, row_len, acc, f),
            [3, 2] => self.gather_block::<3, 2, T, A>(values, at, start, row_len, acc, f),
            [2, 2] => self.gather_block::<2, 2, T, A>(values, at, start, row_len, acc, f),
            _ => self.gather_block::<3, 3, T, A>(values, at, [0, 0], row_len, acc, f),
        }
    }

    /// The place of the stencil's node (0, 0) in a row-major rectangle of
    /// nodes whose lower-left node is grid node `origin`.
    #[inline(always)]
    fn place(&self, origin: [u32; 2], row_len: usize) -> usize {
        (self.base[0] - origin[0]) as usize + (self.base[1] - origin[1]) as usize * row_len
    }

    /// The weights and derivatives along x of the N nodes from stencil node
    /// `first`, checked once so that the loops over them need no check.
    #[inline(always)]
    fn reached_x<const N: usize>(&self, first: usize) -> (&[Real; N], &[Real; N]) {
        (
            self.wx[first..first + N].try_into().unwrap(),
            self.gx[first..first + N].try_into().unwrap(),
        )
    }

    /// [`Self::reached_x`] along y.
    #[inline(always)]
    fn reached_y<const N: usize>(&self, first: usize) -> (&[Real; N], &[Real; N]) {
        (
            self.wy[first..first + N].try_into().unwrap(),
            self.gy[first..first + N].try_into().unwrap(),
        )
    }

    /// [`Self::gather`] over the NX × NY nodes from stencil node `start`,
    /// `at` the place of the stencil's node (0, 0) in `values`; fixed trip
    /// counts let the loops unroll. Any stencil may take the whole 3 × 3.
    #[inline(always)]
    fn gather_block<const NX: usize, const NY: usize, T, A>(
        &self,
        values: &[T],
        at: usize,
        [x0, y0]: [usize; 2],
        row_len: usize,
        mut acc: A,
        mut f: impl FnMut(A, &T, Real, DVec2) -> A,
    ) -> A {
        let start = at + y0 * row_len + x0;
        assert_block_inside::<NX, NY>(start, row_len, values.len());
        let (wxs, gxs) = self.reached_x::<NX>(x0);
        let (wys, gys) = self.reached_y::<NY>(y0);
        for j in 0..NY {
            // SAFETY: the NX values from `start + j row_len` lie in `values`
            // for every j < NY (asserted above).
            let row = unsafe { &*values.as_ptr().add(start + j * row_len).cast::<[T; NX]>() };
            for (i, value) in row.iter().enumerate() {
                let (wx, gx) = (wxs[i], gxs[i]);
                acc = f(
                    acc,
                    value,
                    wx * wys[j],
                    DVec2::new(gx * wys[j], wx * gys[j]),
                );
            }
        }
        acc
    }

    /// Σ_i S_ip u_i of a row-major nodal field `values` (as in [`Self::gather`]).
    #[inline(always)]
    pub fn interpolate(&self, values: &[DVec2], origin: [u32; 2], row_len: usize) -> DVec2 {
        self.gather(values, origin, row_len, DVec2::ZERO, |acc, u, w, _| {
            acc + w * *u
        })
    }

    /// Calls `f(value, S_ip, G_ip, [a, b])` on the stencil nodes the point
    /// reaches (`reached`) of a row-major rectangle `values` of nodes whose
    /// lower-left node is grid node `origin` and whose rows are `row_len`
    /// long; (a, b) is the node's place in the stencil (grid node `base` +
    /// (a, b)), for quantities that depend on where the node is (see
    /// [`Self::offset_from_mean`]).
    #[inline(always)]
    pub fn scatter<T>(
        &self,
        values: &mut [T],
        origin: [u32; 2],
        row_len: usize,
        f: impl FnMut(&mut T, Real, DVec2, [usize; 2]),
    ) {
        let at = self.place(origin, row_len);
        let start = self.first_reached.map(usize::from);
        match self.reached {
            [2, 3] => self.scatter_block::<2, 3, T>(values, at, start, row_len, f),
            [3, 2] => self.scatter_block::<3, 2, T>(values, at, start, row_len, f),
            [2, 2] => self.scatter_block::<2, 2, T>(values, at, start, row_len, f),
            _ => self.scatter_block::<3, 3, T>(values, at, [0, 0], row_len, f),
        }
    }

    /// [`Self::scatter`] over the NX × NY nodes reached (as
    /// [`Self::gather_block`]).
    #[inline(always)]
    fn scatter_block<const NX: usize, const NY: usize, T>(
        &self,
        values: &mut [T],
        at: usize,
        [x0, y0]: [usize; 2],
        row_len: usize,
        mut f: impl FnMut(&mut T, Real, DVec2, [usize; 2]),
    ) {
        let start = at + y0 * row_len + x0;
        assert_block_inside::<NX, NY>(start, row_len, values.len());
        let (wxs, gxs) = self.reached_x::<NX>(x0);
        let (wys, gys) = self.reached_y::<NY>(y0);
        for j in 0..NY {
            // SAFETY: as in `gather_block`; the rows do not overlap (NX ≤ row_len).
            let row = unsafe {
                &mut *values
                    .as_mut_ptr()
                    .add(start + j * row_len)
                    .cast::<[T; NX]>()
            };
            for (i, value) in row.iter_mut().enumerate() {
                let (wx, gx) = (wxs[i], gxs[i]);
                f(
                    value,
                    wx * wys[j],
                    DVec2::new(gx * wys[j], wx * gys[j]),
                    [x0 + i, y0 + j],
                );
            }
        }
    }
}

/// Panics unless NY rows of NX values, `row_len` apart, the first at
/// `start`, lie in a field of `len` values (and NX ≤ `row_len`, so that the
/// rows do not overlap). One check per block lets the transfers read and
/// write its rows without a bounds check per row, which cost a tenth of the
/// step's instructions.
#[inline(always)]
fn assert_block_inside<const NX: usize, const NY: usize>(start: usize, row_len: usize, len: usize) {
    let end = (NY - 1)
        .checked_mul(row_len)
        .and_then(|rows| rows.checked_add(start))
        .and_then(|last_row| last_row.checked_add(NX));
    if NX > row_len || end.is_none_or(|end| end > len) {
        block_outside(NX, NY, start, row_len, len);
    }
}

/// The panic of [`assert_block_inside`], out of the transfers' loops.
#[cold]
#[inline(never)]
fn block_outside(nx: usize, ny: usize, start: usize, row_len: usize, len: usize) -> ! {
    panic!(
        "a stencil's {nx} × {ny} nodes from place {start} (rows of {row_len}) reach past its {len} values"
    )
}

/// Of an axis's three nodes, the first whose weight or derivative is not
/// zero and how many from it have one (a kernel's support is one interval,
/// so those nodes are contiguous).
#[inline(always)]
fn reach(weights: &[Real; 3], derivatives: &[Real; 3]) -> (u8, u8) {
    let zero = |k: usize| u8::from((weights[k] == 0.0) & (derivatives[k] == 0.0));
    let first = zero(0);
    (first, 3 - first - zero(2))
}

/// Largest weight a node beyond an open grid edge may receive and still be
/// dropped: a domain ending exactly on the edge gives such a node a weight of
/// order (round-off)² ≈ 1e-32; a domain crossing it by 1e-6 of a cell, 1e-12.
const ROUND_OFF_WEIGHT: Real = 1e-20;

/// One direction of a stencil: the first node index, weights and
/// derivatives (per cell). `s` is the point coordinate in cells from the grid
/// origin, `half` the domain half-size in cells; `walls` says whether the low
/// and high edges are walls (see [`StencilGrid::walls`]).
#[inline(always)]
fn axis<K: Kernel>(
    kernel: K,
    s: Real,
    half: Real,
    nodes: usize,
    walls: [bool; 2],
) -> Option<(u32, [Real; 3], [Real; 3])> {
    let last_node = nodes as i64 - 1;
    if !(0.0..=last_node as Real).contains(&s) || nodes < 3 {
        return None;
    }
    // The three nodes nearest the point cover every kernel's support
    // (support radius at most 1.5 cells): floor(s − ½), computed by
    // truncation since s ≥ 0 (a call to `floor` costs more than the kernel).
    let first = (s + 0.5) as i64 - 1;
    let inv_half = 1.0 / half;
    if first >= 0 && first + 2 <= last_node {
        // ξ0 = s − first is exact (both are multiples of s's last place, and
        // |s − first| ≤ s), and so are ξ0 − 1 and ξ0 − 2 wherever
        // s − (first + k) is: the same values as `eval(first + k)`.
        let (weights, derivatives) = kernel.eval_three(s - first as Real, half, inv_half);
        return Some((first as u32, weights, derivatives));
    }
    // Next to an edge: the nodes beyond it must have no weight, unless it
    // is a wall, and the weights are those of the support inside the grid.
    let eval = |node: i64| kernel.eval(s - node as Real, half, inv_half);
    for node in first..first + 3 {
        let beyond_open_edge = (node < 0 && !walls[0]) || (node > last_node && !walls[1]);
        if beyond_open_edge && eval(node).0 > ROUND_OFF_WEIGHT {
            return None;
        }
    }
    let base = first.clamp(0, last_node - 2);
    let mut weights = [0.0; 3];
    let mut derivatives = [0.0; 3];
    for k in 0..3 {
        (weights[k], derivatives[k]) = eval(base + k as i64);
    }
    restrict_to_grid(&mut weights, &mut derivatives);
    Some((base as u32, weights, derivatives))
}

/// Eq. 9 integrates over Ω_p ∩ Ω: when part of a point's support lies beyond
/// a wall, the weights are those of the part inside, S_i / ΣS, with
/// derivatives (G_i − S_i ΣG / ΣS) / ΣS. Partition of unity and Σ G = 0
/// then hold for every point, so a body sliding along a slip wall gains no
/// spurious strain rate.
fn restrict_to_grid(weights: &mut [Real; 3], derivatives: &mut [Real; 3]) {
    let total: Real = weights.iter().sum();
    let slope: Real = derivatives.iter().sum();
    for (w, g) in weights.iter_mut().zip(derivatives.iter_mut()) {
        *g = (*g - *w * slope / total) / total;
        *w /= total;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: Real = 0.1;
    const NODES: [usize; 2] = [21, 21];
    const OPEN: StencilGrid = StencilGrid {
        origin: DVec2::ZERO,
        inv_cell_size: 1.0 / H,
        nodes: NODES,
        walls: [[false; 2]; 2],
    };
    const KINDS: [ShapeFunction; 3] = [
        ShapeFunction::Linear,
        ShapeFunction::UGimp,
        ShapeFunction::QuadraticBSpline,
    ];

    /// Positions that sweep across several cell boundaries, including points
    /// exactly on nodes and on the edges of a GIMP domain.
    fn positions() -> impl Iterator<Item = DVec2> {
        (0..=400).map(|k| {
            let t = 0.5 + k as Real * 0.0025; // 0.5 .. 1.5: crosses 10 cells
            DVec2::new(t, 1.3 - 0.37 * t)
        })
    }

    fn sums(kind: ShapeFunction, p: DVec2, half: DVec2) -> (Real, DVec2, DVec2, DMat2Sum) {
        let st = kind.stencil(p, half, &OPEN).expect("inside the grid");
        let nodes: Vec<DVec2> = (0..NODES[0] * NODES[1])
            .map(|k| DVec2::new((k % NODES[0]) as Real * H, (k / NODES[0]) as Real * H))
            .collect();
        let zero = (0.0, DVec2::ZERO, DVec2::ZERO, DMat2Sum::default());
        st.gather(
            &nodes,
            [0, 0],
            NODES[0],
            zero,
            |(s, g, x, mut gx), xi, w, grad| {
                gx.add(*xi, grad);
                (s + w, g + grad, x + w * *xi, gx)
            },
        )
    }

    /// Σ x_i ⊗ G_ip, which must be the identity for linear reproduction.
    #[derive(Default)]
    struct DMat2Sum([Real; 4]);
    impl DMat2Sum {
        fn add(&mut self, xi: DVec2, g: DVec2) {
            self.0[0] += xi.x * g.x;
            self.0[1] += xi.x * g.y;
            self.0[2] += xi.y * g.x;
            self.0[3] += xi.y * g.y;
        }
    }

    // Tolerance: sums of nine O(1) terms in f64, so a few ulps of 1.
    const TOL: Real = 1e-12;

    /// The transfers visit only the nodes a stencil reaches: every node left
    /// out has neither weight nor derivative, for every kernel and place;
    /// a uGIMP point a quarter cell wide each side reaches two nodes per
    /// direction in the middle half of its cell and three elsewhere.
    #[test]
    fn the_nodes_a_stencil_leaves_out_have_no_weight() {
        for kind in KINDS {
            for half in [H / 4.0, H / 2.0] {
                for p in positions() {
                    let st = kind.stencil(p, DVec2::splat(half), &OPEN).unwrap();
                    for (d, (w, g)) in [(st.wx, st.gx), (st.wy, st.gy)].into_iter().enumerate() {
                        let first = usize::from(st.first_reached[d]);
                        let end = first + usize::from(st.reached[d]);
                        for k in (0..first).chain(end..3) {
                            assert!(w[k] == 0.0 && g[k] == 0.0, "{kind:?} at {p}: {d} {k}");
                        }
                    }
                }
            }
        }
        let reached = |f: Real| {
            let p = DVec2::splat((10.0 + f) * H);
            let st = ShapeFunction::UGimp
                .stencil(p, DVec2::splat(H / 4.0), &OPEN)
                .unwrap();
            st.reached
        };
        assert_eq!(reached(0.3), [2, 2]);
        assert_eq!(reached(0.5), [2, 2]);
        assert_eq!(reached(0.1), [3, 3]);
        assert_eq!(reached(0.9), [3, 3]);
    }

    #[test]
    fn partition_of_unity_and_zero_gradient_sum() {
        for kind in KINDS {
            for half in [H / 4.0, H / 2.0] {
                for p in positions() {
                    let (s, g, _, _) = sums(kind, p, DVec2::splat(half));
                    assert!((s - 1.0).abs() < TOL, "{kind:?} at {p}: Σ S = {s}");
                    assert!(g.length() < TOL / H, "{kind:?} at {p}: Σ G = {g}");
                }
            }
        }
    }

    #[test]
    fn reproduces_a_linear_field() {
        for kind in KINDS {
            for p in positions() {
                let (_, _, x, gx) = sums(kind, p, DVec2::splat(H / 4.0));
                assert!((x - p).length() < TOL, "{kind:?}: Σ S x_i = {x} at {p}");
                let m = gx.0;
                assert!(
                    (m[0] - 1.0).abs() < 1e-9 && m[1].abs() < 1e-9,
                    "{kind:?} {m:?}"
                );
                assert!(
                    m[2].abs() < 1e-9 && (m[3] - 1.0).abs() < 1e-9,
                    "{kind:?} {m:?}"
                );
            }
        }
    }

    #[test]
    fn gradient_is_the_derivative_of_the_weight() {
        // Central difference with step 1e-7 cells: truncation O(1e-14),
        // round-off O(1e-9) relative to 1/h.
        let eps = 1e-8;
        for kind in KINDS {
            for p in positions() {
                let half = DVec2::splat(H / 4.0);
                let st = kind.stencil(p, half, &OPEN).unwrap();
                let plus = kind.stencil(p + DVec2::X * eps, half, &OPEN).unwrap();
                let minus = kind.stencil(p - DVec2::X * eps, half, &OPEN).unwrap();
                // The hat's derivative jumps at nodes: skip differences that straddle one.
                let on_node = ((p.x / H) - (p.x / H).round()).abs() * H < 2.0 * eps;
                if plus.base != minus.base || (kind == ShapeFunction::Linear && on_node) {
                    continue;
                }
                for a in 0..3 {
                    let fd = (plus.wx[a] - minus.wx[a]) / (2.0 * eps);
                    assert!(
                        (fd - st.gx[a]).abs() < 1e-5 / H,
                        "{kind:?} at {p}: {fd} vs {}",
                        st.gx[a]
                    );
                }
            }
        }
    }

    /// A stencil inside the grid holds each kernel's `eval` at s − node for
    /// its three nodes, bit for bit, also just below and above powers of
    /// two, where s + ½ and s have different last places (just below s = ½,
    /// s + ½ rounds up to 1 and ξ0 = s < ½).
    #[test]
    fn interior_stencils_hold_eval_at_each_node() {
        // Unit cells, so that a place in cells is the position itself.
        let grid = StencilGrid {
            nodes: [2100, 2100],
            inv_cell_size: 1.0,
            ..OPEN
        };
        let mut places: Vec<Real> = (0..4000).map(|k| 0.7 + k as Real * 0.0123).collect();
        for power in [1.0, 2.0, 4.0, 1024.0] {
            for at in [power - 0.5, power] {
                let below = Real::from_bits(Real::to_bits(at) - 1);
                places.extend([below, at, Real::from_bits(Real::to_bits(at) + 1)]);
            }
        }
        // The cell coordinate and half-size as `Stencil::new` forms them.
        let inv_h = grid.inv_cell_size;
        for half in [0.25, 0.5] {
            let (half_cells, domain) = (half * inv_h, DVec2::splat(half));
            let inv_half = 1.0 / half_cells;
            for &s in &places {
                let x = DVec2::new(s, 1.0);
                let cells = (x.x - grid.origin.x) * inv_h;
                for kind in KINDS {
                    let st = kind.stencil(x, domain, &grid).unwrap();
                    for k in 0..3 {
                        let xi = cells - (st.base[0] as usize + k) as Real;
                        let (w, g) = match kind {
                            ShapeFunction::Linear => LinearHat.eval(xi, half_cells, inv_half),
                            ShapeFunction::UGimp => UGimp.eval(xi, half_cells, inv_half),
                            ShapeFunction::QuadraticBSpline => {
                                QuadraticBSpline.eval(xi, half_cells, inv_half)
                            }
                        };
                        let (got, want) = ((st.wx[k], st.gx[k]), (w, g * inv_h));
                        assert_eq!(
                            (got.0.to_bits(), got.1.to_bits()),
                            (want.0.to_bits(), want.1.to_bits()),
                            "{kind:?} at s = {cells}, node {k}"
                        );
                    }
                }
            }
        }
    }

    /// A field too short for a stencil's block is refused before any row is
    /// read, in gathers and in scatters.
    #[test]
    fn a_block_past_its_field_is_refused() {
        let st = ShapeFunction::UGimp
            .stencil(DVec2::splat(0.55), DVec2::splat(H / 4.0), &OPEN)
            .unwrap();
        let field = vec![DVec2::ONE; NODES[0] * NODES[1]];
        let inside = st.interpolate(&field, [0, 0], NODES[0]);
        assert!((inside - DVec2::ONE).length() < TOL, "{inside}");
        let short = &field[..(st.base[1] as usize + 1) * NODES[0]];
        let gather = std::panic::catch_unwind(|| st.interpolate(short, [0, 0], NODES[0]));
        let mut scatter_into = short.to_vec();
        let scatter = std::panic::catch_unwind(move || {
            st.scatter(&mut scatter_into, [0, 0], NODES[0], |v, w, _, _| *v *= w)
        });
        for outcome in [gather.map(|_| ()), scatter] {
            let message = outcome.expect_err("a block past its field must be refused");
            let text = message
                .downcast_ref::<String>()
                .expect("a formatted message");
            assert!(text.contains("reach past"), "{text}");
        }
    }

    #[test]
    fn support_outside_the_grid_is_refused() {
        let half = DVec2::splat(H / 4.0);
        // A GIMP domain that crosses the left grid edge.
        assert!(
            ShapeFunction::UGimp
                .stencil(DVec2::new(0.01, 1.0), half, &OPEN)
                .is_none()
        );
        // A GIMP domain that touches the edge from inside is fine.
        assert!(
            ShapeFunction::UGimp
                .stencil(DVec2::new(0.025, 1.0), half, &OPEN)
                .is_some()
        );
        // The B-spline needs a node beyond the edge for a point in the first cell.
        assert!(
            ShapeFunction::QuadraticBSpline
                .stencil(DVec2::new(0.025, 1.0), half, &OPEN)
                .is_none()
        );
        assert!(
            ShapeFunction::Linear
                .stencil(DVec2::new(-0.01, 1.0), half, &OPEN)
                .is_none()
        );
    }

    #[test]
    fn a_domain_may_press_into_a_wall_but_a_point_may_not_cross_it() {
        let half = DVec2::splat(H / 4.0);
        let walled = StencilGrid {
            walls: [[true, false], [false, false]],
            ..OPEN
        };
        let st = ShapeFunction::UGimp
            .stencil(DVec2::new(0.024, 1.0), half, &walled)
            .unwrap();
        // The node beyond the wall had weight 0.001²/(4·0.1·0.025) = 1e-4;
        // the weights inside are renormalised: still a partition of unity.
        let sum: Real = st.wx.iter().sum();
        let slope: Real = st.gx.iter().sum();
        assert!((sum - 1.0).abs() < 1e-12, "{sum}");
        assert!(slope.abs() < 1e-12 / H, "{slope}");
        assert!(
            ShapeFunction::UGimp
                .stencil(DVec2::new(-0.001, 1.0), half, &walled)
                .is_none()
        );
    }
}
