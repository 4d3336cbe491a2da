//! Isotropic linear elasticity with the Jaumann objective stress rate:
//! σ̇ = λ tr(D) I + 2μ D + W σ − σ W. In plane strain D_zz = 0, so σ_zz
//! follows λ tr D; in axisymmetry D_zz is the hoop rate v_r / r.

use super::{ConstitutiveModel, PointStep, jaumann_rotation};
use crate::math::{DMat2, Real, SymTensor};
use crate::rules::{ParameterError, poisson_ratio};
use serde::{Deserialize, Serialize};

/// Hooke's law in rate form. Fields are the scene's names.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinearElastic {
    /// Young's modulus E (Pa), > 0.
    #[serde(deserialize_with = "crate::rules::de_modulus")]
    pub youngs_modulus: Real,
    /// Poisson's ratio ν, in (−1, 0.5).
    #[serde(deserialize_with = "crate::rules::de_poisson_ratio")]
    pub poisson_ratio: Real,
}

impl LinearElastic {
    /// Checks the parameter ranges.
    pub fn check(&self) -> Result<(), ParameterError> {
        crate::rules::modulus(self.youngs_modulus).map_err(|e| e.at("youngs_modulus"))?;
        poisson_ratio(self.poisson_ratio).map_err(|e| e.at("poisson_ratio"))?;
        Ok(())
    }

    /// Shear modulus μ = E / (2(1 + ν)).
    pub fn shear_modulus(&self) -> Real {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Lamé's first parameter λ = E ν / ((1 + ν)(1 − 2ν)).
    pub fn lame_lambda(&self) -> Real {
        let nu = self.poisson_ratio;
        self.youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    }

    /// a : C⁻¹ : b, C⁻¹ the isotropic compliance in three dimensions (the
    /// zz components are the out-of-plane or hoop ones): the strain C⁻¹ : b
    /// has normal parts (b_ii − ν (b_jj + b_kk)) / E and shear part
    /// (1 + ν) b_xy / E (J/m³ for stresses in Pa).
    pub fn compliance_product(&self, a: &SymTensor, b: &SymTensor) -> Real {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        let normal = a.xx * (b.xx - nu * (b.yy + b.zz))
            + a.yy * (b.yy - nu * (b.zz + b.xx))
            + a.zz * (b.zz - nu * (b.xx + b.yy));
        (normal + 2.0 * (1.0 + nu) * a.xy * b.xy) / e
    }
}

impl LinearElastic {
    /// The model with λ and μ worked out once, as the stress update calls
    /// it for every point.
    pub(crate) fn prepared(&self) -> PreparedElastic {
        PreparedElastic {
            model: *self,
            lambda: self.lame_lambda(),
            shear: self.shear_modulus(),
        }
    }
}

/// A [`LinearElastic`] model with its Lamé constants worked out.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedElastic {
    model: LinearElastic,
    lambda: Real,
    shear: Real,
}

impl PreparedElastic {
    /// The model it was prepared from.
    pub(crate) fn model(&self) -> LinearElastic {
        self.model
    }

    /// The Jaumann-rate update of `stress` over `step`.
    #[inline(always)]
    pub(crate) fn advance(&self, stress: &mut SymTensor, step: &PointStep) {
        let PointStep { d, w, dt, .. } = *step;
        let lambda_tr = self.lambda * (d.xx + d.yy + d.zz) * dt;
        let two_mu = 2.0 * self.shear * dt;
        let elastic = SymTensor::new(
            lambda_tr + two_mu * d.xx,
            lambda_tr + two_mu * d.yy,
            two_mu * d.xy,
            lambda_tr + two_mu * d.zz,
        );
        *stress += jaumann_rotation(stress, w, dt) + elastic;
    }
}

impl ConstitutiveModel for PreparedElastic {
    #[inline]
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real {
        self.advance(stress, step);
        0.0
    }

    fn dissipates() -> bool {
        false
    }

    fn p_wave_modulus(&self) -> Real {
        self.model.p_wave_modulus()
    }

    fn stored_energy_density(&self, s: &SymTensor, f: &DMat2, f_zz: Real) -> Real {
        self.model.stored_energy_density(s, f, f_zz)
    }
}

impl ConstitutiveModel for LinearElastic {
    /// The Jaumann-rate update; dissipates nothing.
    #[inline]
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real {
        self.prepared().advance(stress, step);
        0.0
    }

    fn dissipates() -> bool {
        false
    }

    fn p_wave_modulus(&self) -> Real {
        self.lame_lambda() + 2.0 * self.shear_modulus()
    }

    /// Complementary energy ½ σ : C⁻¹ : σ, which equals the stored strain
    /// energy for linear elasticity (including any initial stress).
    fn stored_energy_density(&self, s: &SymTensor, _f: &DMat2, _f_zz: Real) -> Real {
        0.5 * self.compliance_product(s, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STEEL: LinearElastic = LinearElastic {
        youngs_modulus: 2e11,
        poisson_ratio: 0.3,
    };

    #[test]
    fn uniaxial_strain_gives_the_constrained_modulus() {
        let mut s = SymTensor::ZERO;
        let d = SymTensor::new(1e-3, 0.0, 0.0, 0.0);
        STEEL.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
        let m = STEEL.p_wave_modulus();
        assert!((s.xx - m * 1e-3).abs() < 1e-6 * s.xx.abs());
        // Lateral and out-of-plane stresses are λ ε.
        assert!((s.yy - STEEL.lame_lambda() * 1e-3).abs() < 1e-6 * s.yy.abs());
        assert_eq!(s.yy, s.zz);
    }

    #[test]
    fn stored_energy_is_half_stress_times_strain() {
        // ε = (1e-3, -2e-4, 3e-4 shear); energy must be ½ σ:ε.
        let eps = SymTensor::new(1e-3, -2e-4, 3e-4, 0.0);
        let mut s = SymTensor::ZERO;
        STEEL.update_stress(&mut s, &PointStep::rate(eps, 0.0, 1.0));
        let expected = 0.5 * s.contract(&eps);
        let got = STEEL.stored_energy_density(&s, &DMat2::IDENTITY, 1.0);
        assert!(
            (got - expected).abs() < 1e-9 * expected,
            "{got} vs {expected}"
        );
    }
}
