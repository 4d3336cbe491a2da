//! The bilinear quadrilateral (Q4) element of the finite-element
//! references: its shape functions and their gradients at local
//! coordinates s = (ξ, η) ∈ [−1, 1]², nodes counter-clockwise from
//! (−1, −1), and its 2 × 2 Gauss points.

use mpdem::math::{DVec2, Real};

/// Local coordinates of the four nodes, counter-clockwise.
pub const CORNERS: [(Real, Real); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];

/// The 2 × 2 Gauss points (±1/√3, ±1/√3), each of weight 1.
pub fn gauss_points() -> [DVec2; 4] {
    let g = 1.0 / Real::sqrt(3.0);
    CORNERS.map(|(a, b)| DVec2::new(a, b) * g)
}

/// Shape function values at local coordinates `s`.
pub fn shape(s: DVec2) -> [Real; 4] {
    CORNERS.map(|(a, b)| 0.25 * (1.0 + a * s.x) * (1.0 + b * s.y))
}

/// Shape function gradients with respect to the local coordinates at `s`.
pub fn local_gradients(s: DVec2) -> [DVec2; 4] {
    CORNERS.map(|(a, b)| DVec2::new(a * (1.0 + b * s.y), b * (1.0 + a * s.x)) * 0.25)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_interpolate_an_affine_field_exactly() {
        let field = |p: DVec2| 2.0 + 3.0 * p.x - 0.5 * p.y;
        let s = DVec2::new(0.3, -0.7);
        let nodal = CORNERS.map(|(a, b)| field(DVec2::new(a, b)));
        let value: Real = shape(s).iter().zip(nodal).map(|(w, f)| w * f).sum();
        let gradient: DVec2 = local_gradients(s)
            .iter()
            .zip(nodal)
            .map(|(g, f)| *g * f)
            .sum();
        assert!((value - field(s)).abs() < 1e-14);
        assert!((gradient - DVec2::new(3.0, -0.5)).length() < 1e-14);
        assert!((shape(s).iter().sum::<Real>() - 1.0).abs() < 1e-15);
    }
}
