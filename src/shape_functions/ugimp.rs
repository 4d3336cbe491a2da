//! Undeformed generalised interpolation (uGIMP; Bardenhagen and Kober 2004):
//! the hat function averaged over the point's domain [x_p − l, x_p + l]
//! (paper eq. 9a), with l fixed at its initial value.

use super::Kernel;
use crate::math::Real;

/// uGIMP weight S_ip and its derivative (eqs. 9a/9b) in cell units: ξ is the
/// distance to the node and λ = l/h ≤ ½ the domain half-size. Piecewise:
/// * |ξ| < λ: 1 − (ξ² + λ²) / (2λ)
/// * λ ≤ |ξ| ≤ 1 − λ: 1 − |ξ|
/// * 1 − λ < |ξ| < 1 + λ: (1 + λ − |ξ|)² / (4λ)
#[derive(Clone, Copy, Debug, Default)]
pub struct UGimp;

impl Kernel for UGimp {
    #[inline(always)]
    fn eval(&self, xi: Real, half: Real, inv_half: Real) -> (Real, Real) {
        let r = xi.abs();
        if r < half {
            (
                1.0 - 0.5 * (xi * xi + half * half) * inv_half,
                -xi * inv_half,
            )
        } else if r <= 1.0 - half {
            (1.0 - r, -xi.signum())
        } else if r < 1.0 + half {
            let s = 1.0 + half - r;
            (0.25 * s * s * inv_half, -0.5 * xi.signum() * s * inv_half)
        } else {
            (0.0, 0.0)
        }
    }
}
