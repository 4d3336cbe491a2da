//! What the plane of a simulation stands for: a slice of a long body, or
//! the meridian of a body of revolution.

use crate::math::{DVec2, Real};
use serde::{Deserialize, Serialize};

/// What the plane of the simulation stands for (scene `settings.geometry`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Geometry {
    /// A slice of unit thickness of a long body: ε_zz = 0, masses, forces
    /// and energies per metre. Default, as the paper.
    #[default]
    PlaneStrain,
    /// A body of revolution about the y axis, the plane its meridian
    /// (x = r ≥ 0, y = z): ε_θθ = v_r / r (σ_zz is the hoop stress σ_θθ),
    /// and masses, volumes, forces and energies per radian (a point of
    /// area A at radius r holds V = A r). The grid's left edge is the axis.
    Axisymmetric,
}

impl Geometry {
    /// What extensive quantities are counted per: "m" (of thickness) or
    /// "rad" (of the revolution), for units in labels.
    pub fn per(self) -> &'static str {
        match self {
            Self::PlaneStrain => "m",
            Self::Axisymmetric => "rad",
        }
    }

    /// The extent out of the plane, per unit the outputs are counted in, of
    /// material at `at`: 1 m in plane strain, the radius r (m per radian)
    /// in axisymmetry. Volumes, masses, loads and contact stiffnesses given
    /// per metre of thickness are multiplied by it.
    #[inline]
    pub fn thickness(self, at: DVec2) -> Real {
        match self {
            Self::PlaneStrain => 1.0,
            Self::Axisymmetric => at.x,
        }
    }
}
