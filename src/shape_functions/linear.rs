//! Linear hat function N(d) = 1 − |d|/h of the original MPM (Sulsky et al.).

use super::Kernel;
use crate::math::Real;

/// The linear hat: support of one cell on each side of the node. Its
/// derivative jumps at nodes; a point exactly on a node takes the derivative
/// of the cell to its right (d ∈ [0, h) for the left node, d ∈ [−h, 0) for
/// the right one), so the gradients of a point always sum to zero.
#[derive(Clone, Copy, Debug, Default)]
pub struct LinearHat;

impl Kernel for LinearHat {
    #[inline(always)]
    fn eval(&self, d: Real, h: Real, _half_size: Real) -> (Real, Real) {
        if (0.0..h).contains(&d) {
            (1.0 - d / h, -1.0 / h)
        } else if (-h..0.0).contains(&d) {
            (1.0 + d / h, 1.0 / h)
        } else {
            (0.0, 0.0)
        }
    }
}
