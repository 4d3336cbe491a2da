//! Scalar and tensor types shared by the whole engine.
//!
//! mpdem is two-dimensional and works in plane strain with unit thickness:
//! in-plane vectors and tensors are `glam` double-precision types, and the
//! Cauchy stress carries its out-of-plane normal component explicitly.
//! Stress and strain are tension-positive everywhere in storage.

pub use glam::{DMat2, DVec2};

/// The floating-point type of every physical quantity (f64 throughout).
pub type Real = f64;

/// A symmetric plane-strain tensor: the in-plane components and the
/// out-of-plane normal component (`zz`). Used for Cauchy stress (Pa) and for
/// small strain (dimensionless). Tension-positive.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SymTensor {
    /// Normal component along x.
    pub xx: Real,
    /// Normal component along y.
    pub yy: Real,
    /// In-plane shear component.
    pub xy: Real,
    /// Out-of-plane normal component.
    pub zz: Real,
}

impl SymTensor {
    /// The zero tensor.
    pub const ZERO: Self = Self {
        xx: 0.0,
        yy: 0.0,
        xy: 0.0,
        zz: 0.0,
    };

    /// Builds a tensor from its four independent components.
    pub const fn new(xx: Real, yy: Real, xy: Real, zz: Real) -> Self {
        Self { xx, yy, xy, zz }
    }

    /// Traction on a plane of unit normal `n` (in-plane part): σ · n.
    pub fn dot(&self, n: DVec2) -> DVec2 {
        DVec2::new(self.xx * n.x + self.xy * n.y, self.xy * n.x + self.yy * n.y)
    }

    /// Sum of the three normal components (tr σ).
    pub fn trace3(&self) -> Real {
        self.xx + self.yy + self.zz
    }

    /// Mean normal stress tr σ / 3 and the deviator σ − (tr σ / 3) I.
    pub fn mean_and_deviator(&self) -> (Real, Self) {
        let mean = self.trace3() / 3.0;
        (
            mean,
            Self::new(self.xx - mean, self.yy - mean, self.xy, self.zz - mean),
        )
    }

    /// Full double contraction a : b, counting the shear component twice.
    pub fn contract(&self, other: &Self) -> Real {
        self.xx * other.xx + self.yy * other.yy + self.zz * other.zz + 2.0 * self.xy * other.xy
    }

    /// The components as `[xx, yy, xy, zz]` (the order used by every output).
    pub fn to_array(&self) -> [Real; 4] {
        [self.xx, self.yy, self.xy, self.zz]
    }

    /// Whether every component is finite.
    pub fn is_finite(&self) -> bool {
        self.to_array().iter().all(|c| c.is_finite())
    }
}

impl std::ops::Add for SymTensor {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(
            self.xx + o.xx,
            self.yy + o.yy,
            self.xy + o.xy,
            self.zz + o.zz,
        )
    }
}

impl std::ops::Sub for SymTensor {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(
            self.xx - o.xx,
            self.yy - o.yy,
            self.xy - o.xy,
            self.zz - o.zz,
        )
    }
}

impl std::ops::AddAssign for SymTensor {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl std::ops::Mul<Real> for SymTensor {
    type Output = Self;
    fn mul(self, s: Real) -> Self {
        Self::new(self.xx * s, self.yy * s, self.xy * s, self.zz * s)
    }
}

/// The symmetric part of an in-plane velocity gradient `l` (the rate of
/// deformation D; plane strain, so D_zz = 0).
pub fn rate_of_deformation(l: DMat2) -> SymTensor {
    SymTensor::new(l.x_axis.x, l.y_axis.y, 0.5 * (l.y_axis.x + l.x_axis.y), 0.0)
}

/// The spin (skew part) of an in-plane velocity gradient `l`, as the single
/// independent component W_xy = ½(L_xy − L_yx).
pub fn spin(l: DMat2) -> Real {
    // glam is column-major: l.y_axis.x is L_xy (row x, column y).
    0.5 * (l.y_axis.x - l.x_axis.y)
}

/// Local non-viscous damping (Cundall 1987) of a force (or acceleration)
/// `f` acting on something moving at `v`: each component less α |f_c|
/// sign(v_c), sign(0) = 0 so that a body at rest feels the whole force.
#[inline(always)]
pub fn local_damping(f: DVec2, v: DVec2, alpha: Real) -> DVec2 {
    let sign = |x: Real| {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    f - alpha * f.abs() * DVec2::new(sign(v.x), sign(v.y))
}

/// The outer product a ⊗ b as a matrix whose entry (row i, column j) is a_i b_j.
pub fn outer(a: DVec2, b: DVec2) -> DMat2 {
    DMat2::from_cols(a * b.x, a * b.y)
}

/// Why a polygon is not a convex one.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum PolygonError {
    /// Fewer than three vertices.
    #[error("polygon needs at least 3 vertices, got {0}")]
    TooFew(usize),
    /// A vertex not finite.
    #[error("polygon vertex {index} ({at}) is not finite")]
    NotFinite {
        /// The vertex's index.
        index: usize,
        /// Where it is.
        at: DVec2,
    },
    /// A turn goes the other way.
    #[error("polygon is not convex at vertex {index} ({at})")]
    NotConvex {
        /// The vertex's index.
        index: usize,
        /// Where it is.
        at: DVec2,
    },
    /// Every vertex lies on one line.
    #[error("polygon has no area (all vertices on a line)")]
    NoArea,
}

/// Accepts a polygon with three or more finite vertices whose turns all go
/// the same way (either winding; collinear vertices allowed); the error
/// says what is wrong and where.
pub(crate) fn check_convex_polygon(vertices: &[DVec2]) -> Result<(), PolygonError> {
    if vertices.len() < 3 {
        return Err(PolygonError::TooFew(vertices.len()));
    }
    if let Some(index) = vertices.iter().position(|v| !v.is_finite()) {
        return Err(PolygonError::NotFinite {
            index,
            at: vertices[index],
        });
    }
    let n = vertices.len();
    let mut sign = 0.0;
    for k in 0..n {
        let (a, b, c) = (vertices[k], vertices[(k + 1) % n], vertices[(k + 2) % n]);
        let turn = (b - a).perp_dot(c - b);
        if turn != 0.0 {
            if sign != 0.0 && turn.signum() != sign {
                return Err(PolygonError::NotConvex {
                    index: (k + 1) % n,
                    at: b,
                });
            }
            sign = turn.signum();
        }
    }
    if sign == 0.0 {
        return Err(PolygonError::NoArea);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outer_product_rows_and_columns() {
        let m = outer(DVec2::new(1.0, 2.0), DVec2::new(3.0, 5.0));
        // Row x, column y is a_x b_y = 5.
        assert_eq!(m.y_axis.x, 5.0);
        assert_eq!(m.x_axis.y, 6.0);
        assert_eq!(m * DVec2::new(0.0, 1.0), DVec2::new(5.0, 10.0));
    }

    #[test]
    fn rate_and_spin_split_the_gradient() {
        // L = [[1, 4], [2, 3]] (rows): D_xy = 3, W_xy = 1.
        let l = DMat2::from_cols(DVec2::new(1.0, 2.0), DVec2::new(4.0, 3.0));
        let d = rate_of_deformation(l);
        assert_eq!((d.xx, d.yy, d.xy), (1.0, 3.0, 3.0));
        assert_eq!(spin(l), 1.0);
    }
}
