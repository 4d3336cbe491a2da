//! Linear hat function N(ξ) = 1 − |ξ| of the original MPM (Sulsky et al.),
//! ξ the distance to the node in cells.

use super::Kernel;
use crate::math::Real;

/// The linear hat: support of one cell on each side of the node. Its
/// derivative jumps at nodes; a point exactly on a node takes the derivative
/// of the cell to its right (ξ ∈ [0, 1) for the left node, ξ ∈ [−1, 0) for
/// the right one), so the gradients of a point always sum to zero.
#[derive(Clone, Copy, Debug, Default)]
pub struct LinearHat;

impl Kernel for LinearHat {
    #[inline(always)]
    fn eval(&self, xi: Real, _half: Real, _inv_half: Real) -> (Real, Real) {
        if (0.0..1.0).contains(&xi) {
            (1.0 - xi, -1.0)
        } else if (-1.0..0.0).contains(&xi) {
            (1.0 + xi, 1.0)
        } else {
            (0.0, 0.0)
        }
    }
}
