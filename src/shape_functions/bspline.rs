//! Quadratic B-spline (Steffen et al. 2008): C¹ weights over 1.5 cells.

use super::Kernel;
use crate::math::Real;

/// Quadratic B-spline in cell units, r = |ξ|:
/// * r < ½: ¾ − r²
/// * ½ ≤ r < 3/2: ½ (3/2 − r)²
#[derive(Clone, Copy, Debug, Default)]
pub struct QuadraticBSpline;

impl Kernel for QuadraticBSpline {
    #[inline(always)]
    fn eval(&self, xi: Real, _half: Real, _inv_half: Real) -> (Real, Real) {
        let r = xi.abs();
        if r < 0.5 {
            (0.75 - r * r, -2.0 * xi)
        } else if r < 1.5 {
            let s = 1.5 - r;
            (0.5 * s * s, -xi.signum() * s)
        } else {
            (0.0, 0.0)
        }
    }
}
