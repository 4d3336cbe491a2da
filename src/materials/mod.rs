//! Constitutive models, one file each. A model turns the rate of deformation
//! and spin of one material point into a new Cauchy stress.
//!
//! The engine calls models through [`ConstitutiveModel`], monomorphised per
//! body so the stress loop has no dynamic dispatch inside it; the scene picks
//! a model through [`MaterialModel`]. A model defined outside the crate
//! plugs in as [`MaterialModel::User`] in a scene built in code (see
//! [`UserModel`]).

mod elasticity_linear;
mod elasticity_neo_hookean;
mod fluid_newtonian;
mod plasticity_drucker_prager;
mod plasticity_mohr_coulomb;

pub use elasticity_linear::LinearElastic;
pub use elasticity_neo_hookean::NeoHookean;
pub use fluid_newtonian::NewtonianFluid;
pub use plasticity_drucker_prager::DruckerPrager;
pub use plasticity_mohr_coulomb::MohrCoulomb;

use crate::math::{DMat2, Real, SymTensor};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The motion of one material point over one step, as a model sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointStep {
    /// Rate of deformation D = sym L (1/s); D_zz is 0 in plane strain and
    /// the hoop rate v_r / r in axisymmetry.
    pub d: SymTensor,
    /// In-plane spin W_xy = ½ (L_xy − L_yx) (1/s).
    pub w: Real,
    /// In-plane deformation gradient at the end of the step, F^{n+1}.
    pub f: DMat2,
    /// Its out-of-plane component F_zz^{n+1}: 1 in plane strain, the hoop
    /// stretch F_θθ = exp(ε_θθ) in axisymmetry.
    pub f_zz: Real,
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
            f_zz: 1.0,
            dt,
        }
    }
}

/// A stress update rule for one material point (tension positive; σ_zz is
/// the out-of-plane stress in plane strain, the hoop stress in axisymmetry).
pub trait ConstitutiveModel: Send + Sync {
    /// Advances `stress` over one step (objective: rate-form models rotate
    /// with the spin, hyperelastic ones compute σ from F) and returns the
    /// energy the step dissipated per unit volume at the step's end
    /// (J/m³): plastic work, viscous work; zero for the elastic models.
    /// What the stress's work on the step's strain stores is in
    /// [`Self::stored_energy_density`].
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real;

    /// As [`Self::update_stress`], returning also the equivalent plastic
    /// strain the step added, √(2/3 Δe_p : Δe_p) with Δe_p the deviator of
    /// the plastic strain increment (the points' `plastic_strain`). The
    /// default, for models without plastic strain, adds none.
    fn update_stress_and_plastic_strain(
        &self,
        stress: &mut SymTensor,
        step: &PointStep,
    ) -> (Real, Real) {
        (self.update_stress(stress, step), 0.0)
    }

    /// Whether the model can dissipate (return other than zero from
    /// [`Self::update_stress`]); the stress update keeps no account for
    /// those that cannot (a store per point and step saved).
    fn dissipates() -> bool
    where
        Self: Sized,
    {
        true
    }

    /// The constrained (P-wave) modulus λ + 2μ, which sets the elastic wave
    /// speed for the time-step (CFL) limit.
    fn p_wave_modulus(&self) -> Real;

    /// Elastic energy stored per unit current volume at `stress` and
    /// deformation gradient `f` with out-of-plane component `f_zz` (1 in
    /// plane strain, the hoop stretch in axisymmetry) (J/m³).
    fn stored_energy_density(&self, stress: &SymTensor, f: &DMat2, f_zz: Real) -> Real;

    /// Whether the material is granular: its strength is friction, so
    /// where it flows its points' velocities relax toward the grid's
    /// (`Settings::granular_relaxation`). False by default.
    fn granular(&self) -> bool {
        false
    }

    /// Whether the model can leave points that have grown loose carrying
    /// no stress (Drucker–Prager and Mohr–Coulomb with
    /// `disconnected_above`). False by default.
    fn disconnects_loose_points(&self) -> bool {
        false
    }

    /// Whether the model computes the stress from the deformation (the
    /// deformation gradient, or the density) rather than advancing it by
    /// a rate, so that a stress set before the first step is lost at it.
    /// False by default.
    fn stress_from_deformation(&self) -> bool {
        false
    }

    /// Whether `stress` is admissible: on or inside the model's yield
    /// surface. True by default (a model without one).
    fn admits(&self, _stress: &SymTensor) -> bool {
        true
    }
}

/// A plasticity model on a linear elastic predictor: the elastic trial
/// stress (Jaumann rate), then the model's return to its admissible set.
/// Such a model is a [`ConstitutiveModel`] through this trait, with the
/// elastic part's wave speed and stored energy, and the return's plastic
/// work as what a step dissipates.
pub trait ElasticPlastic: Send + Sync {
    /// The elastic part.
    fn elastic(&self) -> LinearElastic;

    /// Returns a trial stress to the admissible set.
    fn return_map(&self, trial: SymTensor) -> SymTensor;

    /// Whether the strength is friction (a granular material, see
    /// [`ConstitutiveModel::granular`]). False by default.
    fn frictional(&self) -> bool {
        false
    }

    /// The elastic trial: `stress` advanced over `step` by the elastic
    /// part (a model with its moduli worked out overrides it).
    #[inline]
    fn elastic_trial(&self, stress: &mut SymTensor, step: &PointStep) {
        self.elastic().update_stress(stress, step);
    }

    /// Whether the point is disconnected at the end of `step` and carries
    /// no stress (a granular material looser than its critical density);
    /// never by default.
    fn disconnected(&self, _step: &PointStep) -> bool {
        false
    }

    /// Whether [`Self::disconnected`] can ever hold. False by default.
    fn disconnects(&self) -> bool {
        false
    }
}

impl<T: ElasticPlastic> ConstitutiveModel for T {
    /// The elastic trial, the return, and the plastic work of the return,
    /// σ^{n+1} : Δε_p with Δε_p = C⁻¹ : (σ_trial − σ^{n+1}) (the strain the
    /// return took out of the elastic part).
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real {
        self.update_stress_and_plastic_strain(stress, step).0
    }

    /// The plastic strain increment is the strain the return took out of
    /// the elastic part, Δε_p = C⁻¹ : (σ_trial − σ^{n+1}), whose deviator
    /// is dev(σ_trial − σ^{n+1}) / 2G. A disconnected point releases its
    /// stored energy without plastic strain.
    fn update_stress_and_plastic_strain(
        &self,
        stress: &mut SymTensor,
        step: &PointStep,
    ) -> (Real, Real) {
        let elastic = self.elastic();
        if self.disconnected(step) {
            let released = 0.5 * elastic.compliance_product(stress, stress);
            *stress = SymTensor::ZERO;
            return (released, 0.0);
        }
        let mut trial = *stress;
        self.elastic_trial(&mut trial, step);
        *stress = self.return_map(trial);
        if *stress == trial {
            // Inside the admissible set: no plastic strain.
            return (0.0, 0.0);
        }
        let taken = trial - *stress;
        let (_, deviator) = taken.mean_and_deviator();
        let plastic =
            (2.0 / 3.0 * deviator.contract(&deviator)).sqrt() / (2.0 * elastic.shear_modulus());
        (elastic.compliance_product(stress, &taken), plastic)
    }

    fn p_wave_modulus(&self) -> Real {
        self.elastic().p_wave_modulus()
    }

    fn stored_energy_density(&self, stress: &SymTensor, f: &DMat2, f_zz: Real) -> Real {
        self.elastic().stored_energy_density(stress, f, f_zz)
    }

    fn granular(&self) -> bool {
        self.frictional()
    }

    fn disconnects_loose_points(&self) -> bool {
        self.disconnects()
    }

    /// Admissible if the return leaves it unchanged.
    fn admits(&self, stress: &SymTensor) -> bool {
        self.return_map(*stress) == *stress
    }
}

/// Whether a point of a granular material whose `disconnected_above` is
/// `ratio` is looser than that at the end of `step` (V / V⁰ = det F F_zz).
fn looser_than(ratio: Option<Real>, step: &PointStep) -> bool {
    ratio.is_some_and(|j| step.f.determinant() * step.f_zz > j)
}

/// The constitutive models a scene can choose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MaterialModel {
    /// Isotropic linear elasticity with a Jaumann stress rate.
    LinearElastic(LinearElastic),
    /// Compressible neo-Hookean hyperelasticity (σ from F).
    NeoHookean(NeoHookean),
    /// Mohr–Coulomb plasticity with a Rankine tension cut-off (eqs. 13–14).
    MohrCoulomb(MohrCoulomb),
    /// Drucker–Prager plasticity with a tension cut-off (eqs. 15–17).
    DruckerPrager(DruckerPrager),
    /// Weakly compressible Newtonian fluid (eq. 22).
    NewtonianFluid(NewtonianFluid),
    /// A model defined outside the crate, for scenes built in code (a scene
    /// file cannot name it, and a scene holding one cannot be serialized).
    #[serde(skip)]
    User(UserModel),
}

/// A constitutive model defined outside the crate, by name. The stress
/// update calls it through a pointer (one indirect call per point and
/// step); the engine's own models are called directly.
#[derive(Clone)]
pub struct UserModel {
    name: String,
    model: Arc<dyn ConstitutiveModel>,
}

impl UserModel {
    /// The model `model`, named `name` in messages and in the scene's
    /// fingerprint, which a checkpoint must match. The fingerprint sees the
    /// name only, not the model's parameters: give a model with other
    /// parameters another name, or a checkpoint of the old one resumes
    /// under the new.
    pub fn new(name: impl Into<String>, model: impl ConstitutiveModel + 'static) -> Self {
        Self {
            name: name.into(),
            model: Arc::new(model),
        }
    }

    /// The model's name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl std::fmt::Debug for UserModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "UserModel({:?})", self.name)
    }
}

/// The same model: the same name and the same instance.
impl PartialEq for UserModel {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name && Arc::ptr_eq(&self.model, &other.model)
    }
}

impl ConstitutiveModel for UserModel {
    fn update_stress(&self, stress: &mut SymTensor, step: &PointStep) -> Real {
        self.model.update_stress(stress, step)
    }

    fn p_wave_modulus(&self) -> Real {
        self.model.p_wave_modulus()
    }

    fn stored_energy_density(&self, stress: &SymTensor, f: &DMat2, f_zz: Real) -> Real {
        self.model.stored_energy_density(stress, f, f_zz)
    }

    fn granular(&self) -> bool {
        self.model.granular()
    }

    fn disconnects_loose_points(&self) -> bool {
        self.model.disconnects_loose_points()
    }

    fn stress_from_deformation(&self) -> bool {
        self.model.stress_from_deformation()
    }

    fn admits(&self, stress: &SymTensor) -> bool {
        self.model.admits(stress)
    }
}

impl MaterialModel {
    /// Checks the model's parameter ranges.
    pub fn check(&self) -> Result<(), crate::rules::ParameterError> {
        match self {
            Self::LinearElastic(m) => m.check(),
            Self::NeoHookean(m) => m.check(),
            Self::MohrCoulomb(m) => m.check(),
            Self::DruckerPrager(m) => m.check(),
            Self::NewtonianFluid(m) => m.check(),
            Self::User(_) => Ok(()),
        }
    }

    /// Whether `stress` is admissible for the model: on or inside its
    /// yield surface ([`ConstitutiveModel::admits`]).
    pub fn admits(&self, stress: &SymTensor) -> bool {
        self.as_model().admits(stress)
    }

    /// The model as a trait object, for code outside the hot loops.
    pub fn as_model(&self) -> &dyn ConstitutiveModel {
        match self {
            Self::LinearElastic(m) => m,
            Self::NeoHookean(m) => m,
            Self::MohrCoulomb(m) => m,
            Self::DruckerPrager(m) => m,
            Self::NewtonianFluid(m) => m,
            Self::User(m) => m,
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

/// `stress` turned counter-clockwise by `angle` in the plane: R σ Rᵀ.
#[cfg(test)]
pub(crate) fn rotated(stress: &SymTensor, angle: Real) -> SymTensor {
    let (s, c) = angle.sin_cos();
    let SymTensor { xx, yy, xy, zz } = *stress;
    SymTensor::new(
        c * c * xx + s * s * yy - 2.0 * c * s * xy,
        s * s * xx + c * c * yy + 2.0 * c * s * xy,
        c * s * (xx - yy) + (c * c - s * s) * xy,
        zz,
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

    #[test]
    fn scenes_select_the_new_models_by_name_and_bad_values_are_refused() {
        let parse = |text: &str| ron::from_str::<MaterialModel>(text);
        let mc = parse(
            "MohrCoulomb((youngs_modulus: 1.6e7, poisson_ratio: 0.3, friction_angle: 32.0, \
             dilation_angle: 0.01, cohesion: 0.0, tension_cutoff: 10.0))",
        )
        .unwrap();
        let MaterialModel::MohrCoulomb(m) = &mc else {
            panic!("{mc:?}")
        };
        // Defaults of the flow potential: ε = 0.1, e from φ.
        assert_eq!(m.meridional_eccentricity, 0.1);
        assert_eq!(m.deviatoric_eccentricity, None);
        assert!(mc.check().is_ok());
        let with_e = parse(
            "MohrCoulomb((youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30.0, \
             meridional_eccentricity: 0.2, deviatoric_eccentricity: Some(0.8)))",
        )
        .unwrap();
        assert!(with_e.check().is_ok());

        let nh = parse("NeoHookean((youngs_modulus: 1e6, poisson_ratio: 0.3))").unwrap();
        assert!(matches!(nh, MaterialModel::NeoHookean(_)) && nh.check().is_ok());

        let water = parse("NewtonianFluid((bulk_modulus: 3e4, viscosity: 8.9e-4))").unwrap();
        let MaterialModel::NewtonianFluid(f) = &water else {
            panic!("{water:?}")
        };
        assert_eq!(f.gamma, 7.0);
        assert!(water.check().is_ok());
        // The time step sees the equation of state's tangent K γ.
        assert_eq!(water.as_model().p_wave_modulus(), 3e4 * 7.0);

        // Refused while parsing, with the rule in the message.
        for (bad, rule) in [
            (
                "NewtonianFluid((bulk_modulus: 3e4, viscosity: -1e-3))",
                "≥ 0",
            ),
            (
                "NewtonianFluid((bulk_modulus: 0.0, viscosity: 1e-3))",
                "modulus from 1",
            ),
            (
                "NeoHookean((youngs_modulus: 1e6, poisson_ratio: 0.5))",
                "Poisson",
            ),
            (
                "MohrCoulomb((youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 95.0))",
                "angle",
            ),
            (
                "MohrCoulomb((youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30.0, \
                 deviatoric_eccentricity: Some(0.4)))",
                "eccentricity",
            ),
        ] {
            let error = parse(bad).expect_err(bad).to_string();
            assert!(error.contains(rule), "{bad}: {error}");
        }
        // A rule across fields is checked by `check` (scene validation).
        let steep = parse(
            "MohrCoulomb((youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30.0, \
             dilation_angle: 40.0))",
        )
        .unwrap();
        assert!(
            steep
                .check()
                .unwrap_err()
                .to_string()
                .contains("dilation_angle")
        );
        let sticky = MaterialModel::NewtonianFluid(NewtonianFluid {
            viscosity: -1.0,
            ..*f
        });
        assert!(
            sticky
                .check()
                .unwrap_err()
                .to_string()
                .contains("viscosity")
        );
    }
}
