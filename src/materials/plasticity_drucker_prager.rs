//! Drucker–Prager elastoplasticity with a tension cut-off (paper eqs. 15–17),
//! perfectly plastic, non-associated, on a linear elastic Jaumann predictor.
//!
//! Stress is tension-positive: σ_m = tr σ / 3 (positive in tension), s the
//! deviator, τ = √J₂ = √(s : s / 2). Shear yield (eq. 15a) F = τ + η σ_m − ξ c,
//! potential (eq. 15b) G = τ + η̄ σ_m; tension cut-off (eq. 17) F_t = σ_m − σ_t,
//! G_t = σ_m. η, ξ, η̄ follow eq. 16 (the plane-strain match to Mohr–Coulomb).
//! Under `settings.geometry: Axisymmetric` the same match holds, so in
//! triaxial compression the cone is weaker than Mohr–Coulomb (at φ = 30°,
//! q/p = 0.83 at failure against Mohr–Coulomb's 1.2); use `MohrCoulomb`
//! where the axisymmetric strength matters.

use super::elasticity_linear::PreparedElastic;
use super::{ElasticPlastic, LinearElastic, PointStep, looser_than};
use crate::math::{Real, SymTensor};
use crate::rules::{ParameterError, poisson_ratio};
use serde::{Deserialize, Serialize};

/// Parameters of the model (scene `DruckerPrager((...))`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DruckerPrager {
    /// Young's modulus E (Pa), > 0.
    pub youngs_modulus: Real,
    /// Poisson's ratio ν in (−1, 0.5).
    pub poisson_ratio: Real,
    /// Friction angle φ (degrees), in [0, 90).
    pub friction_angle: Real,
    /// Dilation angle ψ (degrees), in [0, φ]. Default 0: no volume change
    /// in plastic shear, the usual choice for sands at critical state.
    #[serde(default)]
    pub dilation_angle: Real,
    /// Cohesion c (Pa), 0 to 1e13. Default 0: a cohesionless soil.
    #[serde(default)]
    pub cohesion: Real,
    /// Tension cut-off σ_t (Pa), 0 to 1e13; capped at the apex ξ c / η. Default 0:
    /// a cohesionless soil carries no tension.
    #[serde(default)]
    pub tension_cutoff: Real,
    /// Volume ratio V / V⁰ above which the material is disconnected, written
    /// `Some(j)`, > 0: looser than its critical density, a granular
    /// gas whose grains have lost contact, it carries no stress (Dunatunga
    /// and Kamrin 2015). 1 takes the density the body was placed at as the
    /// critical one. The stress of a disconnected point is zero and its
    /// stored energy counts as dissipated; compressed back below the ratio,
    /// the point loads again from zero stress. Default `None`: never
    /// disconnected.
    #[serde(default, deserialize_with = "crate::rules::de_option_positive")]
    pub disconnected_above: Option<Real>,
}

/// η (or η̄) of eq. 16a/16c for an angle in degrees.
fn eta(angle: Real) -> Real {
    let t = angle.to_radians().tan();
    3.0 * t / (9.0 + 12.0 * t * t).sqrt()
}

/// ξ of eq. 16b.
fn xi(angle: Real) -> Real {
    let t = angle.to_radians().tan();
    3.0 / (9.0 + 12.0 * t * t).sqrt()
}

impl DruckerPrager {
    /// Checks the parameter ranges; the message names the field.
    pub fn check(&self) -> Result<(), ParameterError> {
        crate::rules::modulus(self.youngs_modulus).map_err(|e| e.at("youngs_modulus"))?;
        poisson_ratio(self.poisson_ratio).map_err(|e| e.at("poisson_ratio"))?;
        if !(0.0..90.0).contains(&self.friction_angle) {
            return Err(ParameterError::Inconsistent(format!(
                "friction_angle must be in [0, 90) degrees, got {}",
                self.friction_angle
            )));
        }
        if !(0.0..=self.friction_angle).contains(&self.dilation_angle) {
            return Err(ParameterError::Inconsistent(format!(
                "dilation_angle must be in [0, friction_angle], got {}",
                self.dilation_angle
            )));
        }
        crate::rules::stress(self.cohesion).map_err(|e| e.at("cohesion"))?;
        crate::rules::stress(self.tension_cutoff).map_err(|e| e.at("tension_cutoff"))?;
        Ok(())
    }

    /// The shear yield function F = τ + η σ_m − ξ c at `stress` (eq. 15a).
    pub fn shear_yield(&self, stress: &SymTensor) -> Real {
        let (mean, _, tau) = invariants(stress);
        tau + eta(self.friction_angle) * mean - xi(self.friction_angle) * self.cohesion
    }

    /// The tension cut-off in force: σ_t capped at the apex of the cone.
    fn cutoff(&self) -> Real {
        let eta = eta(self.friction_angle);
        if eta > 0.0 {
            self.tension_cutoff
                .min(xi(self.friction_angle) * self.cohesion / eta)
        } else {
            self.tension_cutoff
        }
    }
}

/// Relative margin, on the size of F's terms η σ_m and ξ c, by which τ must
/// fall short of the cone for the return to skip its square root: a
/// thousand times the rounding error of F, so that the early verdict is
/// always the one F ≤ 0 would give.
const INSIDE_MARGIN: Real = 1e-12;

/// Mean stress σ_m, deviator s and τ = √J₂ of a plane-strain stress.
fn invariants(stress: &SymTensor) -> (Real, SymTensor, Real) {
    let (mean, s) = stress.mean_and_deviator();
    (mean, s, (0.5 * s.contract(&s)).sqrt())
}

impl ElasticPlastic for DruckerPrager {
    fn frictional(&self) -> bool {
        true
    }

    /// The elastic part.
    fn elastic(&self) -> LinearElastic {
        LinearElastic {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }

    /// Returns a trial stress to the admissible region: shear return along
    /// G, tension return along G_t, and the corner where both meet.
    fn return_map(&self, trial: SymTensor) -> SymTensor {
        self.prepared().return_map(trial)
    }

    fn disconnected(&self, step: &PointStep) -> bool {
        looser_than(self.disconnected_above, step)
    }

    fn disconnects(&self) -> bool {
        self.disconnected_above.is_some()
    }
}

impl DruckerPrager {
    /// The model with the constants of its cone worked out once, as the
    /// stress update calls it for every point.
    pub(crate) fn prepared(&self) -> PreparedDruckerPrager {
        let elastic = self.elastic();
        PreparedDruckerPrager {
            elastic: elastic.prepared(),
            eta: eta(self.friction_angle),
            xi: xi(self.friction_angle),
            eta_bar: eta(self.dilation_angle),
            cohesion: self.cohesion,
            sigma_t: self.cutoff(),
            shear: elastic.shear_modulus(),
            bulk: elastic.lame_lambda() + 2.0 / 3.0 * elastic.shear_modulus(),
            disconnected_above: self.disconnected_above,
        }
    }
}

/// A [`DruckerPrager`] model with η, ξ and η̄ (eq. 16), the cut-off in
/// force and the elastic moduli worked out once, for the per-point return.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedDruckerPrager {
    elastic: PreparedElastic,
    eta: Real,
    xi: Real,
    eta_bar: Real,
    cohesion: Real,
    sigma_t: Real,
    shear: Real,
    bulk: Real,
    disconnected_above: Option<Real>,
}

impl ElasticPlastic for PreparedDruckerPrager {
    fn frictional(&self) -> bool {
        true
    }

    fn elastic(&self) -> LinearElastic {
        self.elastic.model()
    }

    #[inline(always)]
    fn elastic_trial(&self, stress: &mut SymTensor, step: &PointStep) {
        self.elastic.advance(stress, step);
    }

    fn disconnected(&self, step: &PointStep) -> bool {
        looser_than(self.disconnected_above, step)
    }

    fn disconnects(&self) -> bool {
        self.disconnected_above.is_some()
    }

    /// Returns a trial stress to the admissible region (Huang et al. 2015
    /// for the corner): shear return along G, tension return along G_t, and
    /// the corner where both surfaces meet.
    #[inline(always)]
    fn return_map(&self, trial: SymTensor) -> SymTensor {
        let Self {
            eta,
            xi,
            eta_bar,
            cohesion,
            sigma_t,
            shear,
            bulk,
            ..
        } = *self;
        let (mean, deviator) = trial.mean_and_deviator();
        let tau_squared = 0.5 * deviator.contract(&deviator);
        let f_tension = mean - sigma_t;
        // Well inside the cone (by a margin far above the rounding of F),
        // the trial stands, and τ's square root is not needed: the same
        // verdict as F ≤ 0 below, sooner.
        let (pressure_term, cohesion_term) = (eta * mean, xi * cohesion);
        let reach = cohesion_term - pressure_term;
        let margin = INSIDE_MARGIN * (pressure_term.abs() + cohesion_term.abs());
        if f_tension <= 0.0 && reach > margin && tau_squared < (reach - margin).powi(2) {
            return trial;
        }
        let tau = tau_squared.sqrt();
        let f_shear = tau + eta * mean - xi * cohesion;
        if f_shear <= 0.0 && f_tension <= 0.0 {
            return trial;
        }
        // τ at the corner of the two surfaces and the slope of the line
        // dividing the shear and tension return regions.
        let tau_corner = xi * cohesion - eta * sigma_t;
        let alpha = (1.0 + eta * eta).sqrt() - eta;
        let region = tau - tau_corner - alpha * (mean - sigma_t);
        let (new_mean, new_tau) = if f_shear > 0.0 && region > 0.0 {
            let lambda = f_shear / (shear + bulk * eta * eta_bar);
            let (m, t) = (mean - lambda * bulk * eta_bar, tau - lambda * shear);
            if t < 0.0 {
                (sigma_t.min(m), 0.0)
            } else {
                (m, t)
            }
        } else {
            (sigma_t, tau.min(tau_corner.max(0.0)))
        };
        let scale = if tau > 0.0 { new_tau / tau } else { 0.0 };
        let s = deviator * scale;
        SymTensor::new(s.xx + new_mean, s.yy + new_mean, s.xy, s.zz + new_mean)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::ConstitutiveModel;
    use crate::math::{DMat2, DVec2};

    const SAND: DruckerPrager = DruckerPrager {
        youngs_modulus: 2e7,
        poisson_ratio: 0.3,
        friction_angle: 30.0,
        dilation_angle: 0.0,
        cohesion: 1e4,
        tension_cutoff: 5e3,
        disconnected_above: None,
    };

    /// Drives simple shear γ̇ in steps from an isotropic state σ_m = p0.
    fn shear_path(model: &DruckerPrager, p0: Real, steps: usize, dgamma: Real) -> Vec<SymTensor> {
        let mut s = SymTensor::new(p0, p0, 0.0, p0);
        let d = SymTensor::new(0.0, 0.0, 0.5 * dgamma, 0.0);
        (0..steps)
            .map(|_| {
                model.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
                s
            })
            .collect()
    }

    #[test]
    fn shear_is_elastic_then_stays_on_the_yield_surface_where_the_criterion_says() {
        // Under simple shear at constant mean stress (ψ = 0: no dilation)
        // τ = G γ until τ_y = ξ c − η σ_m (eq. 15a), then τ = τ_y.
        let p0 = -1e5;
        let g = SAND.elastic().shear_modulus();
        let tau_y = xi(30.0) * SAND.cohesion - eta(30.0) * p0;
        let dgamma = 1e-5;
        let path = shear_path(&SAND, p0, 2000, dgamma);
        for (k, s) in path.iter().enumerate() {
            let (mean, _, tau) = invariants(s);
            let elastic = g * dgamma * (k + 1) as Real;
            // Round-off of a few thousand increments: 1e-9 relative.
            assert!(
                (mean - p0).abs() < 1e-9 * p0.abs(),
                "mean drifted to {mean}"
            );
            if elastic < tau_y {
                assert!(
                    (tau - elastic).abs() < 1e-9 * tau_y,
                    "step {k}: {tau} vs elastic {elastic}"
                );
            } else {
                assert!(
                    (tau - tau_y).abs() < 1e-9 * tau_y,
                    "step {k}: {tau} vs yield {tau_y}"
                );
            }
        }
    }

    #[test]
    fn plastic_strain_is_the_shear_past_yield() {
        // Simple shear at constant mean stress (ψ = 0): elastic until
        // τ = τ_y at γ_y = τ_y / G, then every increment is plastic, and a
        // simple shear Δγ has the equivalent strain Δγ / √3.
        let p0 = -1e5;
        let g = SAND.elastic().shear_modulus();
        let gamma_y = (xi(30.0) * SAND.cohesion - eta(30.0) * p0) / g;
        let (dgamma, steps) = (1e-5, 2000);
        let mut s = SymTensor::new(p0, p0, 0.0, p0);
        let d = SymTensor::new(0.0, 0.0, 0.5 * dgamma, 0.0);
        let plastic: Real = (0..steps)
            .map(|_| {
                SAND.update_stress_and_plastic_strain(&mut s, &PointStep::rate(d, 0.0, 1.0))
                    .1
            })
            .sum();
        let expected = (steps as Real * dgamma - gamma_y) / 3.0_f64.sqrt();
        assert!(expected > 0.0);
        // The yield step is partly elastic: within one increment.
        assert!(
            (plastic - expected).abs() < dgamma / 3.0_f64.sqrt(),
            "{plastic} vs {expected}"
        );
        // The elastic model adds none.
        let elastic = SAND.elastic();
        let mut s = SymTensor::ZERO;
        let step = PointStep::rate(d, 0.0, 1.0);
        assert_eq!(
            elastic.update_stress_and_plastic_strain(&mut s, &step).1,
            0.0
        );
    }

    #[test]
    fn dilation_lowers_the_mean_stress_while_shearing() {
        let dilatant = DruckerPrager {
            dilation_angle: 10.0,
            ..SAND
        };
        let path = shear_path(&dilatant, -1e5, 2000, 1e-5);
        let last = path.last().unwrap();
        let (mean, _, _) = invariants(last);
        // Plastic dilation under constrained volume raises confinement
        // (compression grows): the mean stress becomes more negative.
        assert!(mean < -1e5, "{mean}");
        assert!(dilatant.shear_yield(last).abs() < 1e-6 * 1e5);
    }

    #[test]
    fn a_point_looser_than_its_critical_density_carries_no_stress() {
        let granular = DruckerPrager {
            disconnected_above: Some(1.0),
            ..SAND
        };
        let compressed = SymTensor::new(-2e4, -1e4, 3e3, -1.5e4);
        let step = |j: Real| PointStep {
            f: DMat2::from_diagonal(DVec2::new(j, 1.0)),
            ..PointStep::rate(SymTensor::ZERO, 0.0, 1e-4)
        };
        // Denser than placed (J < 1): the stress stays and nothing is
        // dissipated (a zero rate, inside the cone).
        let mut s = compressed;
        let kept = granular.prepared().update_stress(&mut s, &step(0.99));
        assert_eq!((s, kept), (compressed, 0.0));
        // Looser (J > 1): the stress is zero, and its stored energy,
        // ½ σ : C⁻¹ : σ, is what the step dissipated.
        let stored = 0.5
            * granular
                .elastic()
                .compliance_product(&compressed, &compressed);
        let released = granular.prepared().update_stress(&mut s, &step(1.01));
        assert_eq!(s, SymTensor::ZERO);
        assert!(
            (released - stored).abs() <= 1e-12 * stored,
            "{released} vs {stored}"
        );
        // Loaded again from zero once it is denser than placed.
        let d = SymTensor::new(-1e-3, 0.0, 0.0, 0.0);
        granular
            .prepared()
            .update_stress(&mut s, &PointStep { d, ..step(0.99) });
        assert!(s.xx < 0.0);
    }

    #[test]
    fn tension_is_cut_off() {
        // Isotropic extension: σ_m stops at σ_t.
        let mut s = SymTensor::ZERO;
        let d = SymTensor::new(1e-4, 1e-4, 0.0, 0.0);
        for _ in 0..100 {
            SAND.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
        }
        let (mean, _, tau) = invariants(&s);
        assert!(
            (mean - SAND.tension_cutoff).abs() < 1e-9 * SAND.tension_cutoff,
            "{mean}"
        );
        assert!(tau <= xi(30.0) * SAND.cohesion - eta(30.0) * mean + 1e-9);
        // A cohesionless sand carries no tension at all.
        let loose = DruckerPrager {
            cohesion: 0.0,
            tension_cutoff: 0.0,
            ..SAND
        };
        let mut s = SymTensor::ZERO;
        loose.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
        assert!(
            invariants(&s).0.abs() < 1e-9 && invariants(&s).2.abs() < 1e-9,
            "{s:?}"
        );
    }

    #[test]
    fn a_rigid_rotation_turns_the_stress_and_keeps_its_invariants() {
        // At yield, spin without strain: the Jaumann rate rotates σ, the
        // invariants (and so F) do not change to first order in ω dt.
        let path = shear_path(&SAND, -1e5, 2000, 1e-5);
        let mut s = *path.last().unwrap();
        let before = invariants(&s);
        let spin = 1e-3;
        for _ in 0..100 {
            SAND.update_stress(&mut s, &PointStep::rate(SymTensor::ZERO, spin, 1.0));
        }
        let after = invariants(&s);
        // Explicit rotation: relative error of order (ω dt)² per step.
        assert!((after.0 - before.0).abs() < 1e-6 * before.0.abs());
        assert!(
            (after.2 - before.2).abs() < 1e-4 * before.2,
            "{} vs {}",
            after.2,
            before.2
        );
        assert!(SAND.shear_yield(&s) < 1e-4 * before.2);
    }

    #[test]
    fn the_returned_plastic_work_closes_the_energy_of_a_shear_and_pull_path() {
        // A dilating sand sheared under confinement (shear returns), then
        // pulled apart in plane until it opens (tension cut-off and corner
        // returns): at every step the returned plastic work is not
        // negative, and over the path Σ σ_mid : Δε is what the elastic part
        // stores plus that work, up to the O(Δσ²) of taking it with the
        // returned stress (measured 3e-4 of the work done): within 0.5%.
        let model = DruckerPrager {
            dilation_angle: 10.0,
            ..SAND
        };
        let stored =
            |s: &SymTensor| model.stored_energy_density(s, &crate::math::DMat2::IDENTITY, 1.0);
        let mut s = SymTensor::new(-1e5, -1e5, 0.0, -1e5);
        let start = stored(&s);
        let (mut work, mut plastic, mut least, mut done) = (0.0, 0.0, Real::INFINITY, 0.0);
        let shear = SymTensor::new(0.0, 0.0, 0.5e-5, 0.0);
        let pull = SymTensor::new(2e-5, 2e-5, 0.0, 0.0);
        for d in std::iter::repeat_n(shear, 3000).chain(std::iter::repeat_n(pull, 3000)) {
            let before = s;
            let step_plastic = model.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
            least = least.min(step_plastic);
            plastic += step_plastic;
            let step_work = (before + s).contract(&d) * 0.5;
            work += step_work;
            done += step_work.abs();
        }
        let residual = work - (stored(&s) - start) - plastic;
        println!(
            "work {work:.2} J/m3 ({done:.2} done), plastic {plastic:.2}, least step {least:e}, residual {residual:e}"
        );
        let mean = invariants(&s).0;
        assert!(
            (mean - model.cutoff()).abs() < 1e-6 * model.cutoff(),
            "the path opens: {mean}"
        );
        assert!(least >= 0.0, "a step returned {least}");
        assert!(plastic > 0.5 * done, "plastic {plastic} of {done}");
        assert!(
            residual.abs() < 5e-3 * done,
            "residual {residual} of {done}"
        );
    }
}
