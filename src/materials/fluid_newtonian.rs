//! Weakly compressible Newtonian fluid (paper eq. 22), after Monaghan's
//! equation of state:
//!
//! σ = 2 μ_w D′ − p I  (22a),  p = K [(ρ/ρ₀)^γ − 1]  (22b),
//!
//! with D′ = D − (tr D / 3) I the deviator of the rate of deformation in
//! three dimensions (D_zz = 0 in plane strain, so σ_zz = −2 μ_w tr D / 3 − p)
//! and ρ/ρ₀ = 1/J, J = det F. The paper's "Stokes condition" is read as
//! zero bulk viscosity: viscosity acts on the deviator only, and the volume
//! change is resisted by the equation of state alone.
//!
//! The stress is computed afresh each step from D and F (no history), so it
//! is objective without a co-rotational term. The equation of state is kept
//! as written: it gives tension (p down to −K) when the fluid expands.

use super::{ConstitutiveModel, PointStep};
use crate::math::{DMat2, Real, SymTensor};
use crate::rules::{ParameterError, positive};
use serde::{Deserialize, Serialize};

/// Parameters of the model (scene `NewtonianFluid((...))`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NewtonianFluid {
    /// Bulk modulus K of the equation of state (Pa), > 0. Weakly compressible
    /// models choose it well below water's 2.2 GPa (the paper's dam break
    /// uses 3e4 Pa) so that the time step stays practical.
    #[serde(deserialize_with = "crate::rules::de_modulus")]
    pub bulk_modulus: Real,
    /// Exponent γ of the equation of state, > 0. Default 7, Monaghan's value
    /// for water (the paper's choice).
    #[serde(
        default = "default_gamma",
        deserialize_with = "crate::rules::de_positive"
    )]
    pub gamma: Real,
    /// Dynamic viscosity μ_w (Pa·s), from 0 (inviscid) to 1e13. Water:
    /// 8.9e-4.
    #[serde(deserialize_with = "crate::rules::de_viscosity")]
    pub viscosity: Real,
}

/// Monaghan's exponent for water.
fn default_gamma() -> Real {
    7.0
}

impl NewtonianFluid {
    /// Checks the parameter ranges; the message names the field.
    pub fn check(&self) -> Result<(), ParameterError> {
        crate::rules::modulus(self.bulk_modulus).map_err(|e| e.at("bulk_modulus"))?;
        positive(self.gamma).map_err(|e| e.at("gamma"))?;
        crate::rules::viscosity(self.viscosity).map_err(|e| e.at("viscosity"))?;
        Ok(())
    }

    /// The pressure p = K (J^−γ − 1) of eq. 22b (compression positive) at
    /// the volume ratio J = V/V₀ = ρ₀/ρ.
    pub fn pressure(&self, j: Real) -> Real {
        self.bulk_modulus * (j.powf(-self.gamma) - 1.0)
    }
}

impl ConstitutiveModel for NewtonianFluid {
    /// The pressure from the density.
    fn stress_from_deformation(&self) -> bool {
        true
    }

    /// σ = 2 μ_w D′ − p I from the step's D and J = det F^{n+1} F_zz (eq. 22);
    /// the incoming stress is not read. The viscous stress dissipates
    /// 2 μ_w D′ : D′ Δt per unit volume.
    #[inline]
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real {
        let d = step.d;
        let p = self.pressure(step.f.determinant() * step.f_zz);
        let two_mu = 2.0 * self.viscosity;
        let third_trace = (d.xx + d.yy + d.zz) / 3.0;
        *stress = SymTensor::new(
            two_mu * (d.xx - third_trace) - p,
            two_mu * (d.yy - third_trace) - p,
            two_mu * d.xy,
            two_mu * (d.zz - third_trace) - p,
        );
        let (_, deviator) = d.mean_and_deviator();
        two_mu * deviator.contract(&deviator) * step.dt
    }

    /// K γ, the tangent dp/d(ln ρ) of eq. 22b at ρ = ρ₀: the sound speed is
    /// √(K γ / ρ₀). A fluid has no shear modulus, so this is also its P-wave
    /// modulus. The viscous time-step limit ρ h² / (2 μ_w) is not included
    /// (it is far longer than the acoustic one for water-like viscosities).
    fn p_wave_modulus(&self) -> Real {
        self.bulk_modulus * self.gamma
    }

    /// The equation of state's potential energy per unit current volume,
    /// U(J) / J with U(J) = −∫₁ᴶ p dJ′ = K [(J^(1−γ) − 1)/(γ − 1) + J − 1]
    /// (K (J − 1 − ln J) for γ = 1), zero at J = 1 and positive otherwise.
    /// The viscous stress dissipates and stores nothing, so σ is not read.
    fn stored_energy_density(&self, _stress: &SymTensor, f: &DMat2, f_zz: Real) -> Real {
        let (k, gamma) = (self.bulk_modulus, self.gamma);
        let j = f.determinant() * f_zz;
        let ln_j = j.ln();
        let power_part = if gamma == 1.0 {
            -ln_j
        } else {
            // (J^(1−γ) − 1)/(γ − 1), accurate near J = 1.
            ((1.0 - gamma) * ln_j).exp_m1() / (gamma - 1.0)
        };
        k * (power_part + (j - 1.0)) / j
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DVec2;

    const WATER: NewtonianFluid = NewtonianFluid {
        bulk_modulus: 3e4,
        gamma: 7.0,
        viscosity: 8.9e-4,
    };

    /// A step with rate `d` ending at F = diag(j, 1) (volume ratio j).
    fn step(d: SymTensor, j: Real) -> PointStep {
        PointStep {
            f: DMat2::from_diagonal(DVec2::new(j, 1.0)),
            ..PointStep::rate(d, 0.0, 1e-4)
        }
    }

    #[test]
    fn the_viscous_stress_dissipates_its_work_on_the_rate() {
        // What the step returns is the viscous stress's work σ_v : D Δt,
        // σ_v = σ + p I = 2 μ D′ (the pressure's work is the equation of
        // state's, stored), here with a hoop rate D_zz as in axisymmetry.
        let d = SymTensor::new(30.0, -10.0, 25.0, 5.0);
        let at = step(d, 0.99);
        let mut s = SymTensor::ZERO;
        let dissipated = WATER.update_stress(&mut s, &at);
        let p = WATER.pressure(0.99);
        let viscous = SymTensor::new(s.xx + p, s.yy + p, s.xy, s.zz + p);
        let work = viscous.contract(&d) * at.dt;
        // One product against another of the same terms: 1e-12 relative.
        assert!(work > 0.0);
        assert!(
            (dissipated - work).abs() < 1e-12 * work,
            "{dissipated} vs {work}"
        );
    }

    #[test]
    fn pressure_follows_the_density() {
        // J = 0.99 (ρ/ρ₀ = 1/0.99): p = K (0.99^−7 − 1) ≈ 2.19 kPa.
        // One powf against the same closed form: 1e-12 relative.
        let mut s = SymTensor::ZERO;
        WATER.update_stress(&mut s, &step(SymTensor::ZERO, 0.99));
        let p = 3e4 * (1.0 / Real::powi(0.99, 7) - 1.0);
        for c in [s.xx, s.yy, s.zz] {
            assert!((c + p).abs() < 1e-12 * p, "{c} vs {}", -p);
        }
        assert_eq!(s.xy, 0.0);
    }

    #[test]
    fn shear_rate_gives_the_viscous_shear_stress() {
        // Simple shear γ̇ = 100 1/s (D_xy = 50) at J = 1: τ = 2 μ_w D_xy, no
        // normal stress (tr D = 0, p = 0). Exact arithmetic: 1e-15 relative.
        let d = SymTensor::new(0.0, 0.0, 50.0, 0.0);
        let mut s = SymTensor::ZERO;
        WATER.update_stress(&mut s, &step(d, 1.0));
        assert!((s.xy - 2.0 * 8.9e-4 * 50.0).abs() < 1e-15 * s.xy.abs());
        assert_eq!((s.xx, s.yy, s.zz), (0.0, 0.0, 0.0));
        // A volumetric rate loads the normal components through the 3D
        // deviator: D = diag(10, 0, 0) gives σ_zz = −2 μ_w · 10/3.
        let d = SymTensor::new(10.0, 0.0, 0.0, 0.0);
        WATER.update_stress(&mut s, &step(d, 1.0));
        let two_mu = 2.0 * 8.9e-4;
        assert!((s.xx - two_mu * 20.0 / 3.0).abs() < 1e-15);
        assert!((s.yy + two_mu * 10.0 / 3.0).abs() < 1e-15);
        assert!((s.zz + two_mu * 10.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn a_fluid_at_rest_carries_no_deviatoric_stress() {
        // D = 0: the stress is −p I whatever the (compressed or expanded)
        // state and whatever the previous stress was. Exact.
        for j in [0.95, 1.0, 1.02] {
            let mut s = SymTensor::new(5.0, -3.0, 7.0, 1.0);
            WATER.update_stress(&mut s, &step(SymTensor::ZERO, j));
            assert_eq!(s.xy, 0.0);
            assert_eq!(s.xx, s.yy);
            assert_eq!(s.xx, s.zz);
            assert_eq!(s.xx, -WATER.pressure(j));
        }
    }

    #[test]
    fn stored_energy_is_the_work_of_the_pressure() {
        // U(J) = −∫₁ᴶ p dJ′ per reference volume; Simpson with 1000
        // intervals on a smooth integrand: error ~1e-14 relative, tolerance
        // 1e-9. Also the γ = 1 branch, and zero at J = 1.
        for gamma in [7.0, 1.0, 1.4] {
            let fluid = NewtonianFluid { gamma, ..WATER };
            for j_end in [0.9, 1.1] {
                let n = 1000;
                let h = (j_end - 1.0) / n as Real;
                let work = -(0..=n)
                    .map(|k| {
                        let weight = match k {
                            0 => 1.0,
                            k if k == n => 1.0,
                            k if k % 2 == 1 => 4.0,
                            _ => 2.0,
                        };
                        weight * fluid.pressure(1.0 + k as Real * h)
                    })
                    .sum::<Real>()
                    * h
                    / 3.0;
                let f = DMat2::from_diagonal(DVec2::new(j_end, 1.0));
                let stored = j_end * fluid.stored_energy_density(&SymTensor::ZERO, &f, 1.0);
                assert!(
                    (stored - work).abs() < 1e-9 * work.abs(),
                    "γ {gamma}, J {j_end}: {stored} vs {work}"
                );
            }
            assert_eq!(
                fluid.stored_energy_density(&SymTensor::ZERO, &DMat2::IDENTITY, 1.0),
                0.0
            );
        }
    }
}
