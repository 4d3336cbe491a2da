//! Constitutive models, one file each. A model turns the rate of deformation
//! and spin of one material point into a new Cauchy stress.
//!
//! The engine calls models through [`ConstitutiveModel`], monomorphised per
//! body so the stress loop has no dynamic dispatch inside it; the scene picks
//! a model through [`MaterialModel`].

mod elasticity_linear;
mod plasticity_drucker_prager;

pub use elasticity_linear::LinearElastic;
pub use plasticity_drucker_prager::DruckerPrager;

use crate::math::{DMat2, Real, SymTensor};
use serde::{Deserialize, Serialize};

/// The motion of one material point over one step, as a model sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointStep {
    /// Rate of deformation D = sym L (1/s).
    pub d: SymTensor,
    /// In-plane spin W_xy = ½ (L_xy − L_yx) (1/s).
    pub w: Real,
    /// Deformation gradient at the end of the step, F^{n+1} (in-plane; F_zz = 1).
    pub f: DMat2,
    /// Step length Δt (s).
    pub dt: Real,
}

impl PointStep {
    /// A step of rate `d`, spin `w` and length `dt` from F = I (for tests and
    /// rate-form models that do not read F).
    pub fn rate(d: SymTensor, w: Real, dt: Real) -> Self {
        Self {
            d,
            w,
            f: DMat2::IDENTITY,
            dt,
        }
    }
}

/// A stress update rule for one material point (plane strain, tension positive).
pub trait ConstitutiveModel: Send + Sync {
    /// Advances `stress` over one step (objective: rate-form models rotate
    /// with the spin, hyperelastic ones compute σ from F).
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep);

    /// The constrained (P-wave) modulus λ + 2μ, which sets the elastic wave
    /// speed for the time-step (CFL) limit.
    fn p_wave_modulus(&self) -> Real;

    /// Elastic energy stored per unit current volume at `stress` and
    /// deformation gradient `f` (J/m³).
    fn stored_energy_density(&self, stress: &SymTensor, f: &DMat2) -> Real;
}

/// The constitutive models a scene can choose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MaterialModel {
    /// Isotropic linear elasticity with a Jaumann stress rate.
    LinearElastic(LinearElastic),
    /// Drucker–Prager plasticity with a tension cut-off (eqs. 15–17).
    DruckerPrager(DruckerPrager),
}

impl MaterialModel {
    /// Checks the model's parameter ranges.
    pub fn check(&self) -> Result<(), String> {
        match self {
            Self::LinearElastic(m) => m.check(),
            Self::DruckerPrager(m) => m.check(),
        }
    }

    /// The model as a trait object, for code outside the hot loops.
    pub fn as_model(&self) -> &dyn ConstitutiveModel {
        match self {
            Self::LinearElastic(m) => m,
            Self::DruckerPrager(m) => m,
        }
    }
}

/// The Jaumann (co-rotational) part of the objective stress rate, σ̇ = W σ − σ W,
/// applied over `dt` for the in-plane spin `w` = W_xy. σ_zz does not rotate.
pub fn jaumann_rotation(stress: &SymTensor, w: Real, dt: Real) -> SymTensor {
    SymTensor::new(
        2.0 * w * stress.xy * dt,
        -2.0 * w * stress.xy * dt,
        w * (stress.yy - stress.xx) * dt,
        0.0,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jaumann_rotation_turns_a_uniaxial_stress_with_the_body() {
        // A counter-clockwise rigid spin Ω has W_xy = −Ω. A uniaxial stress s
        // along x, turned by the small angle θ = Ω dt, gains σ_xy = s θ.
        let s = 100.0;
        let omega = 0.01;
        let dt = 1e-3;
        let rate = jaumann_rotation(&SymTensor::new(s, 0.0, 0.0, 0.0), -omega, dt);
        assert!((rate.xy - s * omega * dt).abs() < 1e-15);
        assert_eq!(rate.xx, 0.0);
    }
}
