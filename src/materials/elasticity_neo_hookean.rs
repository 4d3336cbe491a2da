//! Compressible neo-Hookean hyperelasticity, plane strain or axisymmetric.
//!
//! The stress is a function of the deformation gradient F alone (no rate
//! form, so it is objective by construction):
//!
//! σ = (μ / J)(b − I) + (λ ln J / J) I,  b = F Fᵀ,  J = det F,
//!
//! with F_zz = 1 in plane strain, so b_zz = 1 and σ_zz = λ ln J / J; in
//! axisymmetry F_zz is the hoop stretch F_θθ, b_zz = F_θθ² and J = det F
//! F_θθ. The stored energy per unit reference volume is
//!
//! W = μ/2 (tr b − 3 − 2 ln J) + λ/2 (ln J)²,
//!
//! where tr b counts b_zz; σ = (1/J) ∂W/∂F Fᵀ. For small strain ε the
//! model reduces to Hooke's law σ = λ tr ε I + 2μ ε with the same λ and μ.

use super::{ConstitutiveModel, LinearElastic, PointStep};
use crate::math::{DMat2, Real, SymTensor};
use crate::rules::{ParameterError, poisson_ratio};
use serde::{Deserialize, Serialize};

/// Parameters of the model (scene `NeoHookean((...))`). The Lamé constants
/// follow from E and ν as in [`LinearElastic`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeoHookean {
    /// Young's modulus E (Pa) at small strain, > 0.
    #[serde(deserialize_with = "crate::rules::de_modulus")]
    pub youngs_modulus: Real,
    /// Poisson's ratio ν at small strain, in (−1, 0.5).
    #[serde(deserialize_with = "crate::rules::de_poisson_ratio")]
    pub poisson_ratio: Real,
}

impl NeoHookean {
    /// Checks the parameter ranges; the message names the field.
    pub fn check(&self) -> Result<(), ParameterError> {
        crate::rules::modulus(self.youngs_modulus).map_err(|e| e.at("youngs_modulus"))?;
        poisson_ratio(self.poisson_ratio).map_err(|e| e.at("poisson_ratio"))?;
        Ok(())
    }

    /// The linear elastic model with the same E and ν (the small-strain limit).
    fn small_strain(&self) -> LinearElastic {
        LinearElastic {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }

    /// The Cauchy stress for the in-plane deformation gradient `f` and the
    /// out-of-plane stretch `f_zz` (1 in plane strain, the hoop stretch in
    /// axisymmetry): σ = μ/J (b − I) + λ ln J / J I, J = det(f) f_zz,
    /// b_zz = f_zz². An inverted point (J ≤ 0) gives a non-finite stress,
    /// which the engine's finiteness check reports.
    pub fn stress(&self, f: &DMat2, f_zz: Real) -> SymTensor {
        let elastic = self.small_strain();
        let (mu, lambda) = (elastic.shear_modulus(), elastic.lame_lambda());
        let j = f.determinant() * f_zz;
        let b = *f * f.transpose();
        let volumetric = lambda * j.ln() / j;
        let shear = mu / j;
        // glam is column-major: b.y_axis.x is b_xy (row x, column y).
        SymTensor::new(
            shear * (b.x_axis.x - 1.0) + volumetric,
            shear * (b.y_axis.y - 1.0) + volumetric,
            shear * b.y_axis.x,
            shear * (f_zz * f_zz - 1.0) + volumetric,
        )
    }
}

impl ConstitutiveModel for NeoHookean {
    /// σ from F.
    fn stress_from_deformation(&self) -> bool {
        true
    }

    /// Sets σ from F^{n+1}; the incoming stress is not read, so an initial
    /// stress given in a scene is replaced at the first step. Dissipates
    /// nothing.
    #[inline]
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real {
        *stress = self.stress(&step.f, step.f_zz);
        0.0
    }

    fn dissipates() -> bool {
        false
    }

    /// λ + 2μ, the tangent at F = I. The tangent stiffens under compression
    /// (J < 1), so the time step needs the usual CFL safety factor.
    fn p_wave_modulus(&self) -> Real {
        self.small_strain().p_wave_modulus()
    }

    /// W / J with W = μ/2 (tr b − 3 − 2 ln J) + λ/2 (ln J)² (per unit
    /// current volume); read from F, the stress is not needed.
    fn stored_energy_density(&self, _stress: &SymTensor, f: &DMat2, f_zz: Real) -> Real {
        let elastic = self.small_strain();
        let (mu, lambda) = (elastic.shear_modulus(), elastic.lame_lambda());
        let j = f.determinant() * f_zz;
        let ln_j = j.ln();
        let b = *f * f.transpose();
        let trace_b = b.x_axis.x + b.y_axis.y + f_zz * f_zz;
        (0.5 * mu * (trace_b - 3.0 - 2.0 * ln_j) + 0.5 * lambda * ln_j * ln_j) / j
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::rotated;
    use crate::math::{DVec2, rate_of_deformation};

    const RUBBER: NeoHookean = NeoHookean {
        youngs_modulus: 1e6,
        poisson_ratio: 0.3,
    };

    /// F from its rows.
    fn rows(xx: Real, xy: Real, yx: Real, yy: Real) -> DMat2 {
        DMat2::from_cols(DVec2::new(xx, yx), DVec2::new(xy, yy))
    }

    /// Largest component difference of two tensors.
    fn max_diff(a: &SymTensor, b: &SymTensor) -> Real {
        let (a, b) = (a.to_array(), b.to_array());
        (0..4).map(|k| (a[k] - b[k]).abs()).fold(0.0, Real::max)
    }

    /// Largest component magnitude.
    fn max_abs(a: &SymTensor) -> Real {
        a.to_array().iter().fold(0.0, |m, c| m.max(c.abs()))
    }

    #[test]
    fn small_strain_matches_linear_elasticity_to_first_order() {
        // F = I + ε with a symmetric ε of size 1e-6: Hooke's law is the first
        // order term, the difference is O(E ε²), i.e. relative O(ε). Bound:
        // 10 ε relative to the stress (a few times the quadratic terms).
        let size: Real = 1e-6;
        let eps = SymTensor::new(size, -0.4 * size, 0.7 * size, 0.0);
        let f = rows(1.0 + eps.xx, eps.xy, eps.xy, 1.0 + eps.yy);
        let hyper = RUBBER.stress(&f, 1.0);
        let mut linear = SymTensor::ZERO;
        RUBBER
            .small_strain()
            .update_stress(&mut linear, &PointStep::rate(eps, 0.0, 1.0));
        let relative = max_diff(&hyper, &linear) / max_abs(&linear);
        assert!(relative < 10.0 * size, "relative difference {relative}");
    }

    #[test]
    fn finite_uniaxial_stretch_matches_the_closed_form() {
        // F = diag(s, 1): J = s, b = diag(s², 1, 1), so
        // σ_xx = μ (s² − 1)/s + λ ln s / s, σ_yy = σ_zz = λ ln s / s, σ_xy = 0.
        // Same arithmetic as the model up to ordering: 1e-12 relative.
        let elastic = RUBBER.small_strain();
        let (mu, lambda) = (elastic.shear_modulus(), elastic.lame_lambda());
        for s in [0.5, 0.9, 1.3, 2.0] {
            let mut sigma = SymTensor::ZERO;
            let step = PointStep {
                f: rows(s, 0.0, 0.0, 1.0),
                ..PointStep::rate(SymTensor::ZERO, 0.0, 1.0)
            };
            RUBBER.update_stress(&mut sigma, &step);
            let lateral = lambda * s.ln() / s;
            let expected = SymTensor::new(mu * (s * s - 1.0) / s + lateral, lateral, 0.0, lateral);
            assert!(
                max_diff(&sigma, &expected) < 1e-12 * max_abs(&expected),
                "stretch {s}: {sigma:?} vs {expected:?}"
            );
        }
    }

    #[test]
    fn a_rigid_rotation_of_the_deformation_rotates_the_stress() {
        // σ(R F) = R σ(F) Rᵀ; both sides are a few dozen flops from the same
        // inputs: 1e-12 relative.
        let f = rows(1.2, 0.3, -0.1, 0.8);
        let sigma = RUBBER.stress(&f, 1.0);
        for angle in [0.3, 1.0, 2.5, -0.7] {
            let r = DMat2::from_angle(angle);
            let turned = RUBBER.stress(&(r * f), 1.0);
            let expected = rotated(&sigma, angle);
            assert!(
                max_diff(&turned, &expected) < 1e-12 * max_abs(&sigma),
                "angle {angle}: {turned:?} vs {expected:?}"
            );
        }
    }

    #[test]
    fn stored_energy_is_zero_at_rest_and_equals_the_stress_work() {
        assert_eq!(
            RUBBER.stored_energy_density(&SymTensor::ZERO, &DMat2::IDENTITY, 1.0),
            0.0
        );
        // Along F(t) = I + t A in the plane and F_zz(t) = 1 + t c out of it
        // (c = 0 in plane strain, c ≠ 0 for a hoop stretch), t ∈ [0, 1], the
        // work per unit reference volume ∫ J σ : D dt (D = sym(Ḟ F⁻¹),
        // D_zz = c / F_zz) must equal W(F(1)) = J w. Composite Simpson rule
        // with 2000 intervals: error O(h⁴) ≈ 1e-13 of the smooth integrand's
        // scale; tolerance 1e-9 relative.
        let a = rows(0.4, 0.25, -0.15, -0.3);
        for c in [0.0, 0.3, -0.2] {
            let integrand = |t: Real| {
                let (f, f_zz) = (DMat2::IDENTITY + a * t, 1.0 + c * t);
                let mut d = rate_of_deformation(a * f.inverse());
                d.zz = c / f_zz;
                f.determinant() * f_zz * RUBBER.stress(&f, f_zz).contract(&d)
            };
            let n = 2000;
            let h = 1.0 / n as Real;
            let work = (0..=n)
                .map(|k| {
                    let weight = if k == 0 || k == n {
                        1.0
                    } else if k % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    weight * integrand(k as Real * h)
                })
                .sum::<Real>()
                * h
                / 3.0;
            let (f_end, f_zz) = (DMat2::IDENTITY + a, 1.0 + c);
            let stress = RUBBER.stress(&f_end, f_zz);
            let stored =
                f_end.determinant() * f_zz * RUBBER.stored_energy_density(&stress, &f_end, f_zz);
            assert!(
                (stored - work).abs() < 1e-9 * work.abs(),
                "c = {c}: stored {stored} vs work {work}"
            );
        }
    }
}
