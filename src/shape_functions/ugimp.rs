//! Undeformed generalised interpolation (uGIMP; Bardenhagen and Kober 2004):
//! the hat function averaged over the point's domain [x_p − l, x_p + l]
//! (paper eq. 9a), with l fixed at its initial value.

use super::Kernel;
use crate::math::Real;

/// uGIMP weight S_ip and gradient G_ip (eqs. 9a/9b) for a domain half-size
/// `l ≤ h/2`. Piecewise:
/// * |d| < l: 1 − (d² + l²) / (2hl)
/// * l ≤ |d| ≤ h − l: 1 − |d|/h
/// * h − l < |d| < h + l: (h + l − |d|)² / (4hl)
#[derive(Clone, Copy, Debug, Default)]
pub struct UGimp;

impl Kernel for UGimp {
    #[inline(always)]
    fn eval(&self, d: Real, h: Real, l: Real) -> (Real, Real) {
        let r = d.abs();
        if r < l {
            (1.0 - (d * d + l * l) / (2.0 * h * l), -d / (h * l))
        } else if r <= h - l {
            (1.0 - r / h, -d.signum() / h)
        } else if r < h + l {
            let s = h + l - r;
            (s * s / (4.0 * h * l), -d.signum() * s / (2.0 * h * l))
        } else {
            (0.0, 0.0)
        }
    }
}
