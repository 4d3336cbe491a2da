//! Mohr–Coulomb elastoplasticity (paper eqs. 13–14) with a Rankine tension
//! cut-off, perfectly plastic and non-associated, on the linear elastic
//! Jaumann predictor of [`LinearElastic`].
//!
//! **Yield surface** (eq. 13, the Menetrey–Willam form of Mohr–Coulomb):
//! F = R_mc(Θ, φ) q − p tan φ − c, with
//! R_mc = sin(Θ + π/3) / (√3 cos φ) + cos(Θ + π/3) tan φ / 3. Here p is the
//! mean stress *compression-positive* (p = −tr σ / 3 with our tension-positive
//! σ), q = √(3 J₂), and Θ ∈ [0, π/3] the Lode angle with
//! cos 3Θ = 27 J₃ / (2 q³) (Θ = 0 on the meridian of one tensile-most
//! principal stress, Θ = π/3 on the compression meridian). With principal
//! stresses σ₁ ≥ σ₂ ≥ σ₃ (tension positive) this is exactly
//! F = [(σ₁ − σ₃) + (σ₁ + σ₃) sin φ − 2 c cos φ] / (2 cos φ),
//! so a hydrostatic compression gives F = −p tan φ − c < 0.
//!
//! **Flow potential** (eq. 14):
//! G = √((ε c tan ψ)² + (R_mw q)²) − p tan ψ, with the Willam–Warnke
//! ellipse R_mw(Θ, e) = [4(1 − e²) cos²Θ + (2e − 1)²] /
//! [2(1 − e²) cos Θ + (2e − 1) √(4(1 − e²) cos²Θ + 5e² − 4e)] · R_mc(π/3, φ)
//! and R_mc(π/3, φ) = (3 − sin φ) / (6 cos φ) (eq. 14c). The paper prints the
//! first denominator term as 2(1 − e)² cos Θ; we use Menetrey and Willam's
//! 2(1 − e²) cos Θ, the only reading for which R_mw(π/3) = R_mc(π/3), i.e.
//! for which the factor of eq. 14c means what it says.
//!
//! **Tension cut-off** (Rankine): σ₁ ≤ σ_t with associated flow, σ_t capped
//! at the apex of the Mohr–Coulomb pyramid, c cot φ.
//!
//! **Return mapping** (backward Euler), in principal stresses: isotropy
//! keeps the principal directions; in plane strain σ_zz is one principal
//! stress, the in-plane pair comes from the 2 × 2 block and is rotated back
//! with its eigenvectors. Within the sextant σ₁ ≥ σ₂ ≥ σ₃, F is linear in σ,
//! so for a flow direction taken at a given Lode angle the multiplier
//! follows from F = 0 in closed form and the landing point is on the face
//! exactly. What remains is one unknown, the Lode angle at which the flow
//! is taken, which must equal the landing point's own: a scalar root,
//! bracketed by the two meridians (a flow taken on a meridian is symmetric
//! in the two stresses equal there and keeps their order), found by a
//! safeguarded secant search. Because G is smooth, the face return exists
//! (its landing may lie on an edge, e.g. for an axisymmetric trial) unless
//! it overshoots the apex, so no separate edge return is needed. In order:
//! 1. the Mohr–Coulomb face (abandoned if it overshoots the apex);
//! 2. if σ₁ > σ_t after that, the Rankine plane (then its edge σ₁ = σ₂ = σ_t
//!    and its apex);
//! 3. if that violates F, the line where both meet: σ₁ = σ_t and, from F = 0,
//!    σ₃ = [σ_t (1 + sin φ) − 2 c cos φ] / (1 − sin φ), with σ₂ from both
//!    flows (same scalar root) clamped to [σ₃, σ_t], whose ends are the
//!    corners.
//!
//! Every branch ends on or inside the admissible set, so a finite trial
//! always gives a finite, admissible stress.

use super::elasticity_linear::PreparedElastic;
use super::{ElasticPlastic, LinearElastic, PointStep, looser_than};
use crate::math::{Real, SymTensor};
use crate::rules::{ParameterError, RuleError, non_negative, poisson_ratio};
use serde::{Deserialize, Deserializer, Serialize, de::Error};
use std::f64::consts::{FRAC_PI_3, PI};

/// Parameters of the model (scene `MohrCoulomb((...))`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MohrCoulomb {
    /// Young's modulus E (Pa), > 0.
    #[serde(deserialize_with = "crate::rules::de_modulus")]
    pub youngs_modulus: Real,
    /// Poisson's ratio ν in (−1, 0.5).
    #[serde(deserialize_with = "crate::rules::de_poisson_ratio")]
    pub poisson_ratio: Real,
    /// Friction angle φ (degrees), in [0, 90); not 0 together with a
    /// cohesion of 0 (no strength: `DruckerPrager` models such a solid).
    #[serde(deserialize_with = "de_angle")]
    pub friction_angle: Real,
    /// Dilation angle ψ (degrees), in [0, φ]. Default 0: no volume change in
    /// plastic shear, the usual choice for sands at critical state.
    #[serde(default, deserialize_with = "de_angle")]
    pub dilation_angle: Real,
    /// Cohesion c (Pa), 0 to 1e13. Default 0: a cohesionless soil.
    #[serde(default, deserialize_with = "crate::rules::de_stress")]
    pub cohesion: Real,
    /// Rankine tension cut-off σ_t (Pa), 0 to 1e13: the largest principal stress
    /// allowed; capped at the apex c cot φ. Default 0: a cohesionless soil
    /// carries no tension.
    #[serde(default, deserialize_with = "crate::rules::de_stress")]
    pub tension_cutoff: Real,
    /// Meridional eccentricity ε of the flow potential (eq. 14a), ≥ 0: how
    /// far the hyperbola rounds the potential's apex. Default 0.1, Abaqus's
    /// default; with c = 0 or ψ = 0 the term vanishes.
    #[serde(
        default = "default_meridional_eccentricity",
        deserialize_with = "crate::rules::de_non_negative"
    )]
    pub meridional_eccentricity: Real,
    /// Deviatoric eccentricity e of the flow potential (eq. 14b), in
    /// (0.5, 1], written `Some(e)`; 1 makes the potential's deviatoric
    /// section a circle. Default (`None`): (3 − sin φ) / (3 + sin φ), as
    /// Abaqus, so the potential's section passes through the corners of the
    /// Mohr–Coulomb hexagon.
    #[serde(default, deserialize_with = "de_eccentricity")]
    pub deviatoric_eccentricity: Option<Real>,
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

/// Abaqus's default meridional eccentricity.
fn default_meridional_eccentricity() -> Real {
    0.1
}

/// An angle in degrees must lie in [0, 90).
fn angle(value: Real) -> Result<Real, RuleError> {
    if (0.0..90.0).contains(&value) {
        Ok(value)
    } else {
        Err(RuleError::Angle(value))
    }
}

/// The deviatoric eccentricity must lie in (0.5, 1]: 0.5 makes the
/// potential's section a triangle with sharp corners, above 1 it is not
/// convex.
fn eccentricity(value: Real) -> Result<Real, RuleError> {
    if value > 0.5 && value <= 1.0 {
        Ok(value)
    } else {
        Err(RuleError::Eccentricity(value))
    }
}

/// `deserialize_with` form of [`angle`].
fn de_angle<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    angle(Real::deserialize(d)?).map_err(D::Error::custom)
}

/// `deserialize_with` form of [`eccentricity`] for the optional field.
fn de_eccentricity<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Real>, D::Error> {
    Option::<Real>::deserialize(d)?
        .map(eccentricity)
        .transpose()
        .map_err(D::Error::custom)
}

/// Cap on the iterations of a return (the search on the Lode angle, and the
/// hyperbola's weight); both settle in far fewer, and every iterate is
/// already on the yield surface.
const MAX_ITERATIONS: usize = 50;

/// Relative change of the hyperbola's weight R q / √((ε c tan ψ)² + (R q)²)
/// between two landings at which it is settled.
const WEIGHT_TOLERANCE: Real = 1e-10;

/// Mismatch (radians) between the Lode angle of the flow and that of the
/// returned stress at which the return is settled: the flow direction is
/// then right to ~1e-9 relative, far below the explicit step's own error
/// (the stress is on the yield surface exactly whatever this tolerance).
const LODE_TOLERANCE: Real = 1e-9;

/// Principal stresses sorted σ₁ ≥ σ₂ ≥ σ₃ (tension positive).
type Principal = [Real; 3];

impl MohrCoulomb {
    /// Checks the parameter ranges; the message names the field.
    pub fn check(&self) -> Result<(), ParameterError> {
        crate::rules::modulus(self.youngs_modulus).map_err(|e| e.at("youngs_modulus"))?;
        poisson_ratio(self.poisson_ratio).map_err(|e| e.at("poisson_ratio"))?;
        angle(self.friction_angle).map_err(|e| e.at("friction_angle"))?;
        if !(0.0..=self.friction_angle).contains(&self.dilation_angle) {
            return Err(ParameterError::Inconsistent(format!(
                "dilation_angle must be in [0, friction_angle], got {}",
                self.dilation_angle
            )));
        }
        crate::rules::stress(self.cohesion).map_err(|e| e.at("cohesion"))?;
        if self.friction_angle == 0.0 && self.cohesion == 0.0 {
            // The pyramid shrinks to the hydrostatic axis, which the return
            // mapping does not handle: it sent every stress to zero and the
            // body collapsed to a line, silently.
            return Err(ParameterError::Inconsistent(
                "friction_angle 0 with cohesion 0 leaves the material no shear strength, which this model cannot return to; give either a value, or use DruckerPrager (a frictionless, cohesionless solid) or NewtonianFluid".into(),
            ));
        }
        crate::rules::stress(self.tension_cutoff).map_err(|e| e.at("tension_cutoff"))?;
        non_negative(self.meridional_eccentricity).map_err(|e| e.at("meridional_eccentricity"))?;
        if let Some(e) = self.deviatoric_eccentricity {
            eccentricity(e).map_err(|e| e.at("deviatoric_eccentricity"))?;
        }
        Ok(())
    }

    /// The yield function F of eq. 13 at `stress`, evaluated in its
    /// principal-stress form (module docs), which equals the (p, q, Θ) form
    /// but stays accurate on the meridians, where acos of the J₃ ratio loses
    /// half the digits.
    pub fn yield_function(&self, stress: &SymTensor) -> Real {
        Surfaces::new(self).yield_value(&principal(stress))
    }

    /// The tension cut-off in force: σ_t capped at the apex c cot φ.
    pub fn cutoff(&self) -> Real {
        let phi = self.friction_angle.to_radians();
        if phi > 0.0 {
            self.tension_cutoff.min(self.cohesion / phi.tan())
        } else {
            self.tension_cutoff
        }
    }
}

/// Principal stresses of a plane-strain stress, sorted σ₁ ≥ σ₂ ≥ σ₃.
fn principal(s: &SymTensor) -> Principal {
    let centre = 0.5 * (s.xx + s.yy);
    let half = 0.5 * (s.xx - s.yy);
    let radius = (half * half + s.xy * s.xy).sqrt();
    let v = [centre + radius, centre - radius, s.zz];
    let o = descending(&v);
    [v[o[0]], v[o[1]], v[o[2]]]
}

/// Indices of `v` from the largest value to the smallest.
fn descending(v: &[Real; 3]) -> [usize; 3] {
    let mut order = [0, 1, 2];
    if v[order[0]] < v[order[1]] {
        order.swap(0, 1);
    }
    if v[order[1]] < v[order[2]] {
        order.swap(1, 2);
    }
    if v[order[0]] < v[order[1]] {
        order.swap(0, 1);
    }
    order
}

/// The model's constants for one return: trigonometry of the angles and the
/// elastic moduli.
#[derive(Clone, Copy)]
struct Surfaces {
    /// sin φ.
    sin_phi: Real,
    /// cos φ.
    cos_phi: Real,
    /// Cohesion c.
    cohesion: Real,
    /// Tension cut-off in force σ_t.
    cutoff: Real,
    /// tan ψ.
    tan_psi: Real,
    /// ε c tan ψ, the hyperbola's offset in eq. 14a.
    hyperbola: Real,
    /// Deviatoric eccentricity e.
    e: Real,
    /// R_mc(π/3, φ) of eq. 14c.
    r_mc_third: Real,
    /// Lamé λ.
    lambda: Real,
    /// 2μ.
    two_mu: Real,
}

impl Surfaces {
    /// The constants of `model`.
    fn new(model: &MohrCoulomb) -> Self {
        let phi = model.friction_angle.to_radians();
        let (sin_phi, cos_phi) = phi.sin_cos();
        let tan_psi = model.dilation_angle.to_radians().tan();
        let elastic = model.elastic();
        Self {
            sin_phi,
            cos_phi,
            cohesion: model.cohesion,
            cutoff: model.cutoff(),
            tan_psi,
            hyperbola: model.meridional_eccentricity * model.cohesion * tan_psi,
            e: model
                .deviatoric_eccentricity
                .unwrap_or((3.0 - sin_phi) / (3.0 + sin_phi)),
            r_mc_third: (3.0 - sin_phi) / (6.0 * cos_phi),
            lambda: elastic.lame_lambda(),
            two_mu: 2.0 * elastic.shear_modulus(),
        }
    }

    /// F (eq. 13) of sorted principal stresses.
    fn yield_value(&self, s: &Principal) -> Real {
        self.gradient_dot(s) - self.cohesion
    }

    /// a · x with a = ∂F/∂σ in the sextant σ₁ ≥ σ₂ ≥ σ₃ (F = a · σ − c).
    fn gradient_dot(&self, x: &Principal) -> Real {
        (x[0] * (1.0 + self.sin_phi) - x[2] * (1.0 - self.sin_phi)) / (2.0 * self.cos_phi)
    }

    /// The elastic stiffness applied to principal strains: λ tr(x) + 2μ x.
    fn stiffness(&self, x: &Principal) -> Principal {
        let volumetric = self.lambda * (x[0] + x[1] + x[2]);
        x.map(|c| volumetric + self.two_mu * c)
    }

    /// R_mw(Θ, e) / R_mc(π/3, φ) of eq. 14b and its derivative in Θ, from
    /// sin Θ and cos Θ.
    fn ellipse(&self, sin: Real, cos: Real) -> (Real, Real) {
        let e = self.e;
        let k = 4.0 * (1.0 - e * e);
        let b = 2.0 * e - 1.0;
        let root = (k * cos * cos + 5.0 * e * e - 4.0 * e).sqrt();
        let numerator = k * cos * cos + b * b;
        let denominator = 0.5 * k * cos + b * root;
        let d_numerator = 2.0 * k * cos;
        let d_denominator = 0.5 * k + b * k * cos / root;
        let ratio = numerator / denominator;
        let d_ratio_d_cos =
            (d_numerator * denominator - numerator * d_denominator) / (denominator * denominator);
        (ratio, -sin * d_ratio_d_cos)
    }

    /// ∂G/∂σ (eq. 14a) in principal stresses at Lode angle `theta` ∈
    /// [0, π/3] and deviatoric stress `q` (which sets the hyperbola's weight).
    fn flow(&self, theta: Real, q: Real) -> Principal {
        let (sin, cos) = theta.sin_cos();
        let (ratio, d_ratio) = self.ellipse(sin, cos);
        let (r, dr) = (self.r_mc_third * ratio, self.r_mc_third * d_ratio);
        let a = (self.hyperbola * self.hyperbola + r * q * r * q).sqrt();
        let weight = if a > 0.0 { r * q / a } else { 0.0 };
        // ∂(R q)/∂u and ∂(R q)/∂v in the deviatoric coordinates u = q sin β,
        // v = q cos β, β = Θ + π/3 (polar form: no singularity on the
        // meridians, where dR/dΘ = 0).
        let half_root3 = 0.5 * 3.0_f64.sqrt();
        let (sin_b, cos_b) = (0.5 * sin + half_root3 * cos, 0.5 * cos - half_root3 * sin);
        let h_u = weight * (r * sin_b + dr * cos_b);
        let h_v = weight * (r * cos_b - dr * sin_b);
        let volumetric = self.tan_psi / 3.0;
        [
            half_root3 * h_u + 0.5 * h_v + volumetric,
            -h_v + volumetric,
            -half_root3 * h_u + 0.5 * h_v + volumetric,
        ]
    }

    /// The whole return; `None` when the trial is admissible (elastic step).
    fn return_principal(&self, p: Principal) -> Option<Principal> {
        let f_trial = self.yield_value(&p);
        if f_trial <= 0.0 && p[0] <= self.cutoff {
            return None;
        }
        if f_trial > 0.0
            && let Some(s) = self.face_return(p, f_trial)
            && s[0] <= self.cutoff
        {
            return Some(s);
        }
        if p[0] > self.cutoff {
            let s = self.rankine_return(p);
            if self.yield_value(&s) <= 0.0 {
                return Some(s);
            }
        }
        Some(self.corner_return(p, f_trial))
    }

    /// Finds the landing point whose own Lode angle is the one its flow was
    /// taken at (backward Euler). For a flow taken at Θ, `solve` turns the
    /// direction C : ∂G into the landing point; the root sought is that of
    /// r(Θ) = Θ(landing(Θ)) − Θ on [0, π/3]. A flow taken on a meridian is
    /// symmetric in the two stresses equal there, so it keeps their
    /// difference: r(0) ≥ 0 ≥ r(π/3), a bracket. The search starts at the
    /// trial's own Lode angle, steps by the fixed point and then by secants,
    /// tries an end of the interval when a step points past it, and bisects
    /// when a step would leave the bracket otherwise. An end that does not
    /// bracket (a landing that overshoots the apex, or the Rankine corner,
    /// whose flow is not symmetric) is where the search ends, for the caller
    /// to check or clamp. q, which only sets the hyperbola's weight, is
    /// carried from one landing to the next and must have settled too.
    fn settle(
        &self,
        p: &Principal,
        solve: impl Fn(&Principal) -> Option<Principal>,
    ) -> Option<Principal> {
        let (mut low, mut high) = (0.0, FRAC_PI_3);
        let mut ends_tried = (false, false);
        let mut q = deviatoric_stress(p);
        let mut theta = lode_angle(p).clamp(low, high);
        let mut previous: Option<(Real, Real)> = None;
        let mut s = *p;
        for _ in 0..MAX_ITERATIONS {
            s = solve(&self.stiffness(&self.flow(theta, q)))?;
            let r = lode_angle(&s) - theta;
            // The weight w = 1/√(1 + z²), z = ε c tan ψ / (R q), changes by
            // z²/(1 + z²) · Δq/q (R taken as R_mc(π/3) for this estimate).
            let q_landed = deviatoric_stress(&s);
            let z = self.hyperbola / (self.r_mc_third * q_landed);
            let weight_settled = self.hyperbola == 0.0
                || z * z / (1.0 + z * z) * (q_landed - q).abs() <= WEIGHT_TOLERANCE * q_landed;
            q = q_landed;
            if r.abs() <= LODE_TOLERANCE && weight_settled {
                break;
            }
            if r > 0.0 {
                low = theta;
            } else {
                high = theta;
            }
            if high - low <= LODE_TOLERANCE {
                break;
            }
            let step = match previous {
                Some((theta_0, r_0)) if r_0 != r => r * (theta - theta_0) / (r_0 - r),
                _ => r,
            };
            let next = theta + step;
            previous = Some((theta, r));
            theta = if next > low && next < high {
                next
            } else if next <= low && low == 0.0 && !ends_tried.0 {
                ends_tried.0 = true;
                0.0
            } else if next >= high && high == FRAC_PI_3 && !ends_tried.1 {
                ends_tried.1 = true;
                FRAC_PI_3
            } else {
                0.5 * (low + high)
            };
        }
        Some(s)
    }

    /// Return to the Mohr–Coulomb face along the flow of eq. 14 (F is linear
    /// in the sextant, so every landing point is on the face exactly); `None`
    /// if the flow does not reduce F or the return overshoots the apex (a
    /// tension state for the cut-off to handle). A landing overshoots when
    /// the trial's largest principal stress ends below its smallest: a root
    /// has them in order, and a landing that only crosses one meridian while
    /// the Lode angle is searched keeps them in order too.
    fn face_return(&self, p: Principal, f_trial: Real) -> Option<Principal> {
        let solve = |direction: &Principal| {
            let rate = self.gradient_dot(direction);
            if rate.is_nan() || rate <= 0.0 {
                return None;
            }
            let multiplier = f_trial / rate;
            let s = [0, 1, 2].map(|k| p[k] - multiplier * direction[k]);
            (s.iter().all(|c| c.is_finite()) && s[0] >= s[2]).then_some(s)
        };
        let s = self.settle(&p, solve)?;
        // A settled landing is in order up to the Lode tolerance times q.
        let slack = 1e-9 * (p[0].abs() + p[2].abs());
        (s[0] >= s[1] - slack && s[1] >= s[2] - slack).then_some(s)
    }

    /// Return to the Rankine planes σᵢ ≤ σ_t (associated flow): the plane of
    /// σ₁, then the edge σ₁ = σ₂ = σ_t, then the apex. Needs σ₁ > σ_t.
    fn rankine_return(&self, p: Principal) -> Principal {
        let t = self.cutoff;
        let (lambda, k) = (self.lambda, self.lambda + self.two_mu);
        let d1 = (p[0] - t) / k;
        let s = [t, p[1] - lambda * d1, p[2] - lambda * d1];
        if s[1] <= t {
            return s;
        }
        let det = k * k - lambda * lambda;
        let (e0, e1) = (p[0] - t, p[1] - t);
        let (d1, d2) = ((k * e0 - lambda * e1) / det, (k * e1 - lambda * e0) / det);
        let third = p[2] - lambda * (d1 + d2);
        if third <= t { [t, t, third] } else { [t; 3] }
    }

    /// Return to the line σ₁ = σ_t, F = 0 with both flows (eq. 14 and
    /// Rankine). On that line σ₃ is fixed by F = 0, so only σ₂ is found; it
    /// is clamped to [σ₃, σ_t], whose ends are the corners with the edges.
    fn corner_return(&self, p: Principal, f_trial: Real) -> Principal {
        let t = self.cutoff;
        // ≤ σ_t since σ_t ≤ c cot φ; min() absorbs the round-off at the apex.
        let lowest = ((t * (1.0 + self.sin_phi) - 2.0 * self.cohesion * self.cos_phi)
            / (1.0 - self.sin_phi))
            .min(t);
        if lowest >= t {
            // σ_t is the apex: the line is a point.
            return [t; 3];
        }
        let k = self.lambda + self.two_mu;
        let rankine = [k, self.lambda, self.lambda];
        let a_rankine = self.gradient_dot(&rankine);
        let solve = |direction: &Principal| {
            // [direction₁, k; a·direction, a·rankine] (Δλ, Δτ) = (p₁ − σ_t, F_trial).
            let a_direction = self.gradient_dot(direction);
            let det = direction[0] * a_rankine - k * a_direction;
            let shear = ((p[0] - t) * a_rankine - k * f_trial) / det;
            let tension = (direction[0] * f_trial - a_direction * (p[0] - t)) / det;
            let middle = p[1] - shear * direction[1] - tension * self.lambda;
            middle.is_finite().then_some([t, middle, lowest])
        };
        let middle = self.settle(&p, solve).map_or(p[1], |s| s[1]);
        [t, middle.clamp(lowest, t), lowest]
    }
}

/// u = q sin β and v = q cos β, the deviatoric-plane coordinates of sorted
/// principal stresses (β = Θ + π/3).
fn deviatoric_coordinates(s: &Principal) -> (Real, Real) {
    (
        0.5 * 3.0_f64.sqrt() * (s[0] - s[2]),
        -0.5 * (2.0 * s[1] - s[0] - s[2]),
    )
}

/// q = √(3 J₂) of principal stresses.
fn deviatoric_stress(s: &Principal) -> Real {
    let (u, v) = deviatoric_coordinates(s);
    (u * u + v * v).sqrt()
}

/// The Lode angle Θ = β − π/3 of principal stresses in the sextant's
/// labelling, not clamped: it leaves [0, π/3] continuously when the
/// ordering breaks, within [−π, π) (β's cut is put at −2π/3, the direction
/// of the fully reversed order, which a landing reaches only by overshooting
/// the hydrostatic axis).
fn lode_angle(s: &Principal) -> Real {
    let (u, v) = deviatoric_coordinates(s);
    let beta = u.atan2(v);
    let beta = if beta < -2.0 * FRAC_PI_3 {
        beta + 2.0 * PI
    } else {
        beta
    };
    beta - FRAC_PI_3
}

impl ElasticPlastic for MohrCoulomb {
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

    /// Returns a trial stress to the admissible set (see the module docs).
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

impl MohrCoulomb {
    /// The model with the constants of its surfaces worked out once, as
    /// the stress update calls it for every point.
    pub(crate) fn prepared(&self) -> PreparedMohrCoulomb {
        PreparedMohrCoulomb {
            elastic: self.elastic().prepared(),
            surfaces: Surfaces::new(self),
            disconnected_above: self.disconnected_above,
        }
    }
}

/// A [`MohrCoulomb`] model with the trigonometry of its angles and its
/// moduli worked out once, for the per-point return.
#[derive(Clone, Copy)]
pub(crate) struct PreparedMohrCoulomb {
    elastic: PreparedElastic,
    surfaces: Surfaces,
    disconnected_above: Option<Real>,
}

impl ElasticPlastic for PreparedMohrCoulomb {
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

    /// Returns a trial stress to the admissible set (see the module docs).
    fn return_map(&self, trial: SymTensor) -> SymTensor {
        let centre = 0.5 * (trial.xx + trial.yy);
        let half = 0.5 * (trial.xx - trial.yy);
        let radius = (half * half + trial.xy * trial.xy).sqrt();
        let (cos2, sin2) = if radius > 0.0 {
            (half / radius, trial.xy / radius)
        } else {
            (1.0, 0.0)
        };
        // Principal values: major in-plane, minor in-plane, out-of-plane.
        let values = [centre + radius, centre - radius, trial.zz];
        let order = descending(&values);
        let sorted = [values[order[0]], values[order[1]], values[order[2]]];
        let Some(returned) = self.surfaces.return_principal(sorted) else {
            return trial;
        };
        let mut out = [0.0; 3];
        for (slot, &index) in order.iter().enumerate() {
            out[index] = returned[slot];
        }
        let (mean, deviation) = (0.5 * (out[0] + out[1]), 0.5 * (out[0] - out[1]));
        SymTensor::new(
            mean + deviation * cos2,
            mean - deviation * cos2,
            deviation * sin2,
            out[2],
        )
    }
}

#[cfg(test)]
#[path = "plasticity_mohr_coulomb_tests.rs"]
mod tests;
