//! Undeformed generalised interpolation (uGIMP; Bardenhagen and Kober 2004):
//! the hat function averaged over the point's domain [x_p − l, x_p + l]
//! (paper eq. 9a), with l fixed at its initial value.

use super::{Kernel, eval_each};
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

    /// Each node's possible pieces are known from its side of the point when
    /// λ ≤ ½ (every point of a regular layout) and ξ0 ≥ ½: the first node,
    /// at ξ0 ≥ ½ ≥ λ, is in the middle or outer piece or beyond; the middle
    /// node, at |ξ| ≤ ½ ≤ 1 − λ, in the inner or middle piece; the last, at
    /// ξ ≤ −½, as the first. Each piece's arithmetic is `eval`'s with the
    /// sign known, so the values are the same bit for bit.
    #[inline(always)]
    fn eval_three(&self, xi0: Real, half: Real, inv_half: Real) -> ([Real; 3], [Real; 3]) {
        // ξ0 falls short of ½ by a rounding only just below s = ½, where
        // s + ½ rounds up to 1. (A NaN half-size takes the general path too.)
        if half > 0.5 || half.is_nan() || xi0 < 0.5 {
            return eval_each(self, xi0, half, inv_half);
        }
        // An outer node at distance r ≥ ½ from the point, `side` the sign of ξ.
        let outer = |r: Real, side: Real| {
            if r <= 1.0 - half {
                (1.0 - r, -side)
            } else if r < 1.0 + half {
                let s = 1.0 + half - r;
                (0.25 * s * s * inv_half, -0.5 * side * s * inv_half)
            } else {
                (0.0, 0.0)
            }
        };
        let (w0, g0) = outer(xi0, 1.0);
        let xi1 = xi0 - 1.0;
        let (w1, g1) = if xi1.abs() < half {
            (
                1.0 - 0.5 * (xi1 * xi1 + half * half) * inv_half,
                -xi1 * inv_half,
            )
        } else {
            (1.0 - xi1.abs(), -xi1.signum())
        };
        let (w2, g2) = outer(-(xi0 - 2.0), -1.0);
        ([w0, w1, w2], [g0, g1, g2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three nodes' values are `eval`'s, bit for bit, for domains up to
    /// and beyond half a cell, across the whole of ξ0's range and just below
    /// it.
    #[test]
    fn three_nodes_at_once_are_eval_at_each() {
        let mut places: Vec<Real> = (0..=2000).map(|k| 0.5 + k as Real / 2000.0).collect();
        let below_half = Real::from_bits(Real::to_bits(0.5) - 1);
        places.extend([below_half, 1.5 - Real::EPSILON, 0.75, 1.25]);
        for half in [0.125, 0.25, 0.5 / 3.0, 0.5, 0.6, Real::NAN] {
            let inv_half = 1.0 / half;
            for &xi0 in &places {
                let (w, g) = UGimp.eval_three(xi0, half, inv_half);
                for k in 0..3 {
                    let (wk, gk) = UGimp.eval(xi0 - k as Real, half, inv_half);
                    assert_eq!(
                        (w[k].to_bits(), g[k].to_bits()),
                        (wk.to_bits(), gk.to_bits()),
                        "node {k} at ξ0 = {xi0}, λ = {half}"
                    );
                }
            }
        }
    }
}
