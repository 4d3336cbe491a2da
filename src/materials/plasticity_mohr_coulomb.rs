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

use super::{ElasticPlastic, LinearElastic};
use crate::math::{Real, SymTensor};
use crate::rules::{non_negative, poisson_ratio, positive};
use serde::{Deserialize, Deserializer, Serialize, de::Error};
use std::f64::consts::{FRAC_PI_3, PI};

/// Parameters of the model (scene `MohrCoulomb((...))`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MohrCoulomb {
    /// Young's modulus E (Pa), > 0.
    #[serde(deserialize_with = "crate::rules::de_positive")]
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
    /// Cohesion c (Pa), ≥ 0. Default 0: a cohesionless soil.
    #[serde(default, deserialize_with = "crate::rules::de_non_negative")]
    pub cohesion: Real,
    /// Rankine tension cut-off σ_t (Pa), ≥ 0: the largest principal stress
    /// allowed; capped at the apex c cot φ. Default 0: a cohesionless soil
    /// carries no tension.
    #[serde(default, deserialize_with = "crate::rules::de_non_negative")]
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
}

/// Abaqus's default meridional eccentricity.
fn default_meridional_eccentricity() -> Real {
    0.1
}

/// An angle in degrees must lie in [0, 90).
fn angle(value: Real) -> Result<Real, String> {
    if (0.0..90.0).contains(&value) {
        Ok(value)
    } else {
        Err(format!("expected an angle in [0, 90) degrees, got {value}"))
    }
}

/// The deviatoric eccentricity must lie in (0.5, 1]: 0.5 makes the
/// potential's section a triangle with sharp corners, above 1 it is not
/// convex.
fn eccentricity(value: Real) -> Result<Real, String> {
    if value > 0.5 && value <= 1.0 {
        Ok(value)
    } else {
        Err(format!(
            "expected a deviatoric eccentricity in (0.5, 1], got {value}"
        ))
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
    pub fn check(&self) -> Result<(), String> {
        positive(self.youngs_modulus).map_err(|e| format!("youngs_modulus: {e}"))?;
        poisson_ratio(self.poisson_ratio).map_err(|e| format!("poisson_ratio: {e}"))?;
        angle(self.friction_angle).map_err(|e| format!("friction_angle: {e}"))?;
        if !(0.0..=self.friction_angle).contains(&self.dilation_angle) {
            return Err(format!(
                "dilation_angle must be in [0, friction_angle], got {}",
                self.dilation_angle
            ));
        }
        non_negative(self.cohesion).map_err(|e| format!("cohesion: {e}"))?;
        if self.friction_angle == 0.0 && self.cohesion == 0.0 {
            // The pyramid shrinks to the hydrostatic axis, which the return
            // mapping does not handle: it sent every stress to zero and the
            // body collapsed to a line, silently.
            return Err(
                "friction_angle 0 with cohesion 0 leaves the material no shear strength, which this model cannot return to; give either a value, or use DruckerPrager (a frictionless, cohesionless solid) or NewtonianFluid".into(),
            );
        }
        non_negative(self.tension_cutoff).map_err(|e| format!("tension_cutoff: {e}"))?;
        non_negative(self.meridional_eccentricity)
            .map_err(|e| format!("meridional_eccentricity: {e}"))?;
        if let Some(e) = self.deviatoric_eccentricity {
            eccentricity(e).map_err(|e| format!("deviatoric_eccentricity: {e}"))?;
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
    /// The elastic part.
    fn elastic(&self) -> LinearElastic {
        LinearElastic {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
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
        let Some(returned) = Surfaces::new(self).return_principal(sorted) else {
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
mod tests {
    use super::*;
    use crate::materials::rotated;
    use crate::materials::{ConstitutiveModel, PointStep};

    /// The paper's pile-penetration sand (section 4.3) with some cohesion so
    /// that the cut-off and the cohesion both matter.
    const SAND: MohrCoulomb = MohrCoulomb {
        youngs_modulus: 1.6e7,
        poisson_ratio: 0.3,
        friction_angle: 32.0,
        dilation_angle: 5.0,
        cohesion: 5e3,
        tension_cutoff: 2e3,
        meridional_eccentricity: 0.1,
        deviatoric_eccentricity: None,
    };

    /// Eq. 13 literally: F = R_mc(Θ, φ) q − p tan φ − c with p = −tr σ / 3,
    /// q = √(3 J₂) and cos 3Θ = 27 J₃ / (2 q³).
    fn invariant_form(model: &MohrCoulomb, stress: &SymTensor) -> Real {
        let phi = model.friction_angle.to_radians();
        let (mean, s) = stress.mean_and_deviator();
        let (p, q) = (-mean, (1.5 * s.contract(&s)).sqrt());
        let j3 = s.zz * (s.xx * s.yy - s.xy * s.xy);
        let theta = (13.5 * j3 / (q * q * q)).clamp(-1.0, 1.0).acos() / 3.0;
        let r_mc = (theta + FRAC_PI_3).sin() / (3.0_f64.sqrt() * phi.cos())
            + (theta + FRAC_PI_3).cos() * phi.tan() / 3.0;
        r_mc * q - p * phi.tan() - model.cohesion
    }

    /// Mohr–Coulomb's deviator at failure for a compression-positive minor
    /// stress `minor`: 2c cos φ / (1 − sin φ) + 2 minor sin φ / (1 − sin φ).
    fn failure_deviator(model: &MohrCoulomb, minor: Real) -> Real {
        let (sin, cos) = model.friction_angle.to_radians().sin_cos();
        (2.0 * model.cohesion * cos + 2.0 * minor * sin) / (1.0 - sin)
    }

    fn isotropic(p0: Real) -> SymTensor {
        SymTensor::new(-p0, -p0, 0.0, -p0)
    }

    /// A deterministic pseudo-random number in [−1, 1) (64-bit LCG).
    fn uniform(state: &mut u64) -> Real {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*state >> 11) as Real / (1u64 << 53) as Real) * 2.0 - 1.0
    }

    #[test]
    fn a_material_without_friction_and_cohesion_is_refused() {
        let strengthless = MohrCoulomb {
            friction_angle: 0.0,
            dilation_angle: 0.0,
            cohesion: 0.0,
            ..SAND
        };
        let refusal = strengthless.check().expect_err("accepted");
        assert!(refusal.contains("no shear strength"), "{refusal}");
        // Either alone is a model it returns to (Tresca; cohesionless sand).
        assert!(
            MohrCoulomb {
                cohesion: 1.0,
                ..strengthless
            }
            .check()
            .is_ok()
        );
        assert!(
            MohrCoulomb {
                friction_angle: 1.0,
                ..strengthless
            }
            .check()
            .is_ok()
        );
    }

    #[test]
    fn the_invariant_and_principal_forms_of_the_yield_function_agree() {
        // Eq. 13 through (p, q, Θ) and the principal form used by the return
        // agree only if p is compression-positive and Θ = 0 is the meridian
        // of J₃ > 0. They differ by round-off, except that acos of the J₃
        // ratio near ±1 (the meridians, where R_mc has a kink) loses half
        // the digits: ~1e-8 in Θ, so 1e-7 of the stress scale. Random states
        // and states exactly on both meridians.
        let mut state = 7;
        let mut worst: Real = 0.0;
        for k in 0..4000 {
            let (a, b, c) = (
                1e5 * uniform(&mut state),
                1e5 * uniform(&mut state),
                1e5 * uniform(&mut state),
            );
            let s = match k % 3 {
                0 => SymTensor::new(a, b, 0.5 * c, 1e5 * uniform(&mut state)),
                1 => SymTensor::new(a, a, 0.0, b),
                _ => SymTensor::new(a + c.abs(), a, 0.0, a),
            };
            let error = (invariant_form(&SAND, &s) - SAND.yield_function(&s)).abs();
            worst = worst.max(error);
        }
        assert!(worst < 1e-7 * 1e5, "largest difference {worst}");
        // A hydrostatic compression is inside: F = −p tan φ − c < 0.
        let f = SAND.yield_function(&isotropic(1e5));
        let expected = -1e5 * 32.0_f64.to_radians().tan() - 5e3;
        assert!(f < 0.0 && (f - expected).abs() < 1e-9 * 1e5, "{f}");
    }

    #[test]
    fn below_yield_the_response_is_linear_elastic() {
        // A small shear from an isotropic compression: same result as the
        // elastic model, bit for bit (the trial is returned untouched).
        let d = SymTensor::new(1e-5, -5e-6, 2e-5, 0.0);
        let mut mc = isotropic(1e5);
        let mut elastic = mc;
        for _ in 0..10 {
            SAND.update_stress(&mut mc, &PointStep::rate(d, 0.0, 1.0));
            SAND.elastic()
                .update_stress(&mut elastic, &PointStep::rate(d, 0.0, 1.0));
        }
        assert!(SAND.yield_function(&mc) < 0.0);
        assert_eq!(mc, elastic);
    }

    /// Drives an axisymmetric-like path: in-plane isotropic strain rate
    /// `rate` per step from an isotropic compression p0; returns the stresses.
    fn axisymmetric_path(
        model: &MohrCoulomb,
        p0: Real,
        rate: Real,
        steps: usize,
    ) -> Vec<SymTensor> {
        let mut s = isotropic(p0);
        let d = SymTensor::new(rate, rate, 0.0, 0.0);
        (0..steps)
            .map(|_| {
                model.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
                s
            })
            .collect()
    }

    #[test]
    fn lateral_extension_yields_where_mohr_coulomb_says() {
        // In-plane extension ε from an isotropic compression p0. Elastically
        // σ_xx = σ_yy = −p0 + 2(λ+μ)ε and σ_zz = −p0 + 2λε, so (compression
        // positive) σ_zz is the major stress, σ_xx = σ_yy the minor,
        // σ₁ − σ₃ = 2με with σ₃ = p0 − 2(λ+μ)ε, and yield
        // at ε_y = (2c cos φ + 2 p0 sin φ) / (2μ(1 − sin φ) + 4(λ+μ) sin φ).
        // This is the compression meridian (Θ = π/3, an edge of the pyramid).
        let p0 = 1e5;
        let elastic = SAND.elastic();
        let (lambda, mu) = (elastic.lame_lambda(), elastic.shear_modulus());
        let (sin, cos) = 32.0_f64.to_radians().sin_cos();
        let eps_y = (2.0 * SAND.cohesion * cos + 2.0 * p0 * sin)
            / (2.0 * mu * (1.0 - sin) + 4.0 * (lambda + mu) * sin);
        let rate = eps_y / 200.5;
        let path = axisymmetric_path(&SAND, p0, rate, 600);
        let mut first_plastic = None;
        for (k, s) in path.iter().enumerate() {
            let eps = rate * (k + 1) as Real;
            // Compression-positive principal stresses: zz major, xx = yy minor.
            let (major, minor) = (-s.zz, -s.xx);
            if eps < eps_y {
                // Elastic: the closed form, to round-off of a few hundred
                // increments (1e-9 of p0).
                assert!((s.xx - (-p0 + 2.0 * (lambda + mu) * eps)).abs() < 1e-9 * p0);
                assert!((s.zz - (-p0 + 2.0 * lambda * eps)).abs() < 1e-9 * p0);
            } else {
                first_plastic.get_or_insert(k);
                // On the Mohr–Coulomb surface, in its own textbook form:
                // the return lands on the plane to round-off, 1e-9 of p0.
                let gap = (major - minor) - failure_deviator(&SAND, minor);
                assert!(gap.abs() < 1e-9 * p0, "step {k}: gap {gap}");
                assert!(SAND.yield_function(s).abs() < 1e-9 * p0);
                // The flow taken on the meridian is symmetric in the two
                // lateral stresses, so they stay equal (on the pyramid's edge).
                assert!((s.xx - s.yy).abs() < 1e-9 * p0 && s.xy == 0.0);
            }
        }
        // Yield starts at the first step past ε_y (k = 200: ε = 201 rate).
        assert_eq!(first_plastic, Some(200));
    }

    #[test]
    fn in_plane_compression_yields_where_mohr_coulomb_says() {
        // In-plane compression (rate −d) from p0 with ν = 0.1: σ_xx = σ_yy is
        // the major compression, σ_zz the minor (Θ = 0, the other edge).
        // σ₁ − σ₃ = 2με, σ₃ = p0 + 2λε: yield at
        // ε_y = (2c cos φ + 2 p0 sin φ) / (2μ(1 − sin φ) − 4λ sin φ)
        // (reachable only if the denominator is positive, hence ν = 0.1).
        let model = MohrCoulomb {
            poisson_ratio: 0.1,
            ..SAND
        };
        let p0 = 1e5;
        let elastic = model.elastic();
        let (lambda, mu) = (elastic.lame_lambda(), elastic.shear_modulus());
        let (sin, cos) = 32.0_f64.to_radians().sin_cos();
        let eps_y = (2.0 * model.cohesion * cos + 2.0 * p0 * sin)
            / (2.0 * mu * (1.0 - sin) - 4.0 * lambda * sin);
        let rate = eps_y / 100.5;
        let path = axisymmetric_path(&model, p0, -rate, 300);
        let mut first_plastic = None;
        for (k, s) in path.iter().enumerate() {
            let eps = rate * (k + 1) as Real;
            let (major, minor) = (-s.xx, -s.zz);
            if eps < eps_y {
                assert!((s.xx - (-p0 - 2.0 * (lambda + mu) * eps)).abs() < 1e-9 * p0);
            } else {
                first_plastic.get_or_insert(k);
                let gap = (major - minor) - failure_deviator(&model, minor);
                assert!(gap.abs() < 1e-9 * major, "step {k}: gap {gap}");
                assert!((s.xx - s.yy).abs() < 1e-9 * major && s.xy == 0.0);
            }
        }
        assert_eq!(first_plastic, Some(100));
    }

    #[test]
    fn biaxial_compression_at_constant_confinement_peaks_at_the_criterion() {
        // Plane-strain biaxial test: σ_xx held at −σ_c (mixed control, solved
        // for D_xx each step by secant iteration), compression along y.
        // σ_yy is major, σ_xx minor, σ_zz intermediate; the peak deviator is
        // the criterion's 2c cos φ/(1 − sin φ) + 2σ_c sin φ/(1 − sin φ).
        let confinement = 1e5;
        let d_yy = -5e-5;
        let mut s = isotropic(confinement);
        let target = -confinement;
        let mut d_xx: Real = 0.0;
        let mut peak: Real = 0.0;
        for step in 0..400 {
            // Secant iteration on D_xx so that σ_xx stays at the target;
            // converged to 1e-9 of σ_c (a sharper target than the checks).
            let attempt = |d_xx: Real| {
                let mut trial = s;
                let d = SymTensor::new(d_xx, d_yy, 0.0, 0.0);
                SAND.update_stress(&mut trial, &PointStep::rate(d, 0.0, 1.0));
                trial
            };
            let (mut x0, mut x1) = (d_xx, d_xx + 1e-6);
            let (mut r0, mut r1) = (attempt(x0).xx - target, attempt(x1).xx - target);
            for _ in 0..100 {
                if r1.abs() < 1e-10 * confinement || r1 == r0 {
                    break;
                }
                let x2 = x1 - r1 * (x1 - x0) / (r1 - r0);
                (x0, r0) = (x1, r1);
                x1 = x2;
                r1 = attempt(x1).xx - target;
            }
            d_xx = x1;
            s = attempt(d_xx);
            assert!(
                (s.xx - target).abs() < 1e-9 * confinement,
                "step {step}: σ_xx = {}",
                s.xx
            );
            assert!(SAND.yield_function(&s) < 1e-9 * confinement);
            peak = peak.max(s.xx - s.yy);
            let [t1, _, t3] = principal(&s);
            // σ_zz stays the intermediate stress along this path.
            assert!(t1 >= s.zz - 1e-9 * confinement && s.zz >= t3 - 1e-9 * confinement);
        }
        let expected = failure_deviator(&SAND, confinement);
        // Perfect plasticity: the deviator stops exactly at the criterion
        // (round-off of the return and of the secant, 1e-8 relative).
        assert!(
            (peak - expected).abs() < 1e-8 * expected,
            "peak {peak} vs {expected}"
        );
    }

    #[test]
    fn tension_is_cut_off_at_the_rankine_limit() {
        let cutoff = SAND.cutoff();
        assert_eq!(cutoff, 2e3);
        // Uniaxial, biaxial and isotropic in-plane extension from zero stress:
        // the plane, the edge and (with σ_zz) the apex of the Rankine prism.
        for d in [
            SymTensor::new(1e-4, 0.0, 0.0, 0.0),
            SymTensor::new(1e-4, 1e-4, 0.0, 0.0),
            SymTensor::new(2e-4, -5e-5, 8e-5, 0.0),
        ] {
            let mut s = SymTensor::ZERO;
            for _ in 0..50 {
                SAND.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
                let top = principal(&s)[0];
                // The cut-off holds to round-off: 1e-9 of σ_t.
                assert!(top <= cutoff * (1.0 + 1e-9), "{s:?}");
                assert!(SAND.yield_function(&s) <= 1e-9 * cutoff, "{s:?}");
            }
            let top = principal(&s)[0];
            assert!((top - cutoff).abs() < 1e-9 * cutoff, "{d:?}: {s:?}");
        }
    }

    #[test]
    fn a_rigid_rotation_turns_the_stress_and_keeps_its_invariants() {
        // The return map is isotropic: returning a rotated trial gives the
        // rotated result (1e-9 of the stress scale: eigen-decomposition
        // round-off). Trials on both sides of every surface.
        let mut state = 11;
        for _ in 0..500 {
            let trial = SymTensor::new(
                3e5 * uniform(&mut state),
                3e5 * uniform(&mut state),
                2e5 * uniform(&mut state),
                3e5 * uniform(&mut state),
            );
            let angle = PI * uniform(&mut state);
            let a = rotated(&SAND.return_map(trial), angle);
            let b = SAND.return_map(rotated(&trial, angle));
            let diff = [a.xx - b.xx, a.yy - b.yy, a.xy - b.xy, a.zz - b.zz];
            assert!(diff.iter().all(|c| c.abs() < 1e-9 * 3e5), "{a:?} vs {b:?}");
        }
        // Spin without strain at yield (the Jaumann rate): the principal
        // stresses, so F, stay put while the stress turns. The state comes
        // from simple shear past yield (τ_y = c cos φ + p0 sin φ ≈ 57 kPa at
        // γ ≈ 0.93 %), so its principal axes are not the grid's.
        let mut s = isotropic(1e5);
        let shear = SymTensor::new(0.0, 0.0, 0.5e-4, 0.0);
        for _ in 0..200 {
            SAND.update_stress(&mut s, &PointStep::rate(shear, 0.0, 1.0));
        }
        assert!(SAND.yield_function(&s).abs() < 1e-9 * 1e5);
        let before = principal(&s);
        let xy_before = s.xy;
        for _ in 0..100 {
            SAND.update_stress(&mut s, &PointStep::rate(SymTensor::ZERO, 1e-3, 1.0));
        }
        let after = principal(&s);
        // Turned by 0.1 rad: σ_xy = τ cos 0.2 (xx = yy before), to the
        // explicit rotation's accuracy.
        assert!((s.xy - xy_before * 0.2_f64.cos()).abs() < 1e-3 * xy_before.abs());
        // Explicit rotation: relative error of order (ω dt)² = 1e-6 per
        // step, 1e-4 over the 100 steps.
        for k in 0..3 {
            assert!(
                (after[k] - before[k]).abs() < 1e-4 * 1e5,
                "{before:?} → {after:?}"
            );
        }
        assert!(SAND.yield_function(&s) < 1e-4 * 1e5);
    }

    #[test]
    fn any_trial_returns_to_a_finite_admissible_stress() {
        // Random trials of every sign and size, including the apex region,
        // for cohesive and cohesionless variants, with and without dilation,
        // and exactly hydrostatic tension (q = 0). After the return: finite,
        // F ≤ 0 and σ₁ ≤ σ_t up to round-off (1e-9 of the trial's size).
        let variants = [
            SAND,
            MohrCoulomb {
                cohesion: 0.0,
                tension_cutoff: 0.0,
                dilation_angle: 0.0,
                ..SAND
            },
            MohrCoulomb {
                dilation_angle: 32.0,
                deviatoric_eccentricity: Some(1.0),
                ..SAND
            },
            MohrCoulomb {
                friction_angle: 0.0,
                dilation_angle: 0.0,
                tension_cutoff: 1e9,
                ..SAND
            },
            MohrCoulomb {
                tension_cutoff: 1e9,
                meridional_eccentricity: 0.0,
                ..SAND
            },
        ];
        let mut state = 3;
        for model in &variants {
            let cutoff = model.cutoff();
            for k in 0..20_000 {
                let size = [1e3, 1e5, 1e7][k % 3];
                let trial = if k % 97 == 0 {
                    isotropic(-size)
                } else {
                    SymTensor::new(
                        size * uniform(&mut state),
                        size * uniform(&mut state),
                        size * uniform(&mut state),
                        size * uniform(&mut state),
                    )
                };
                let s = model.return_map(trial);
                assert!(s.is_finite(), "{model:?}: {trial:?} → {s:?}");
                let tolerance = 1e-9 * size;
                assert!(
                    model.yield_function(&s) <= tolerance,
                    "{trial:?} → {s:?}: F = {}",
                    model.yield_function(&s)
                );
                assert!(principal(&s)[0] <= cutoff + tolerance, "{trial:?} → {s:?}");
            }
        }
    }

    #[test]
    fn plastic_returns_land_on_the_yield_surface() {
        // Trials outside F but under the cut-off (compressive enough) return
        // to F = 0 within round-off: 1e-9 of the trial's size.
        let mut state = 5;
        let mut checked = 0;
        for _ in 0..20_000 {
            let size = 1e5;
            let mean = -size * (1.0 + uniform(&mut state));
            let trial = SymTensor::new(
                mean + size * uniform(&mut state),
                mean + size * uniform(&mut state),
                size * uniform(&mut state),
                mean + size * uniform(&mut state),
            );
            if SAND.yield_function(&trial) <= 0.0 {
                continue;
            }
            let s = SAND.return_map(trial);
            if principal(&s)[0] < SAND.cutoff() - 1e-6 {
                checked += 1;
                assert!(
                    SAND.yield_function(&s).abs() < 1e-9 * size,
                    "{trial:?} → {s:?}"
                );
            }
        }
        assert!(checked > 1000, "only {checked} plastic trials");
    }

    /// Eq. 14 literally, at sorted principal stresses: G = √((ε c tan ψ)² +
    /// (R_mw(Θ, e) q)²) − p tan ψ, Θ from cos 3Θ = 27 J₃ / (2 q³).
    fn potential(model: &MohrCoulomb, s: &Principal) -> Real {
        let phi = model.friction_angle.to_radians();
        let tan_psi = model.dilation_angle.to_radians().tan();
        let e = model
            .deviatoric_eccentricity
            .unwrap_or((3.0 - phi.sin()) / (3.0 + phi.sin()));
        let mean = (s[0] + s[1] + s[2]) / 3.0;
        let dev = s.map(|c| c - mean);
        let q = (1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2])).sqrt();
        let j3 = dev[0] * dev[1] * dev[2];
        let theta = (13.5 * j3 / (q * q * q)).clamp(-1.0, 1.0).acos() / 3.0;
        let c2 = theta.cos().powi(2);
        let r_mw = (4.0 * (1.0 - e * e) * c2 + (2.0 * e - 1.0).powi(2))
            / (2.0 * (1.0 - e * e) * theta.cos()
                + (2.0 * e - 1.0) * (4.0 * (1.0 - e * e) * c2 + 5.0 * e * e - 4.0 * e).sqrt())
            * (3.0 - phi.sin())
            / (6.0 * phi.cos());
        let offset = model.meridional_eccentricity * model.cohesion * tan_psi;
        offset.hypot(r_mw * q) + mean * tan_psi
    }

    #[test]
    fn face_returns_follow_the_flow_potential_of_eq_14() {
        // For trials whose return lands inside a face (away from the edges
        // and the cut-off), σ_trial − σ must be parallel to C : ∂G/∂σ at the
        // returned σ, with ∂G/∂σ by central differences of eq. 14 written
        // out literally (independent of the model's analytic gradient).
        // Fourth-order differences with a step of 1e-3 of the scale (at least
        // 1e-2 from any edge): truncation ~1e-8 relative; tolerance 1e-6 on
        // the direction.
        let model = MohrCoulomb {
            dilation_angle: 15.0,
            ..SAND
        };
        let surfaces = Surfaces::new(&model);
        let mut state = 9;
        let mut checked = 0;
        for _ in 0..5000 {
            let size = 1e5;
            let mean = -size * (1.0 + uniform(&mut state));
            let v = [0, 1, 2].map(|_| mean + size * uniform(&mut state));
            let o = descending(&v);
            let trial = [v[o[0]], v[o[1]], v[o[2]]];
            let Some(s) = surfaces.return_principal(trial) else {
                continue;
            };
            let margin = 1e-2 * size;
            if s[0] - s[1] < margin || s[1] - s[2] < margin || s[0] > surfaces.cutoff - margin {
                continue;
            }
            let h = 1e-3 * size;
            let gradient = [0, 1, 2].map(|k| {
                let at = |offset: Real| {
                    let mut x = s;
                    x[k] += offset * h;
                    potential(&model, &x)
                };
                (8.0 * (at(1.0) - at(-1.0)) - (at(2.0) - at(-2.0))) / (12.0 * h)
            });
            let direction = surfaces.stiffness(&gradient);
            let step = [0, 1, 2].map(|k| trial[k] - s[k]);
            let dot = |a: &Principal, b: &Principal| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let scale = dot(&step, &direction) / dot(&direction, &direction);
            let miss = [0, 1, 2].map(|k| step[k] - scale * direction[k]);
            assert!(
                dot(&miss, &miss).sqrt() < 1e-6 * dot(&step, &step).sqrt(),
                "{trial:?} → {s:?}: step {step:?}, C:∂G {direction:?}"
            );
            assert!(scale > 0.0);
            checked += 1;
        }
        assert!(checked > 500, "only {checked} face returns");
    }

    #[test]
    fn the_returned_plastic_work_closes_the_energy_of_a_shear_path() {
        // Simple shear (no volume change imposed) from an isotropic
        // compression to γ = 4% in 4000 steps: the stress's work
        // Σ σ_mid : Δε is what the elastic part stores plus the plastic work
        // the updates return, up to the O(Δσ²) of taking the plastic work
        // with the returned stress (measured 2e-5 of the work): within 0.5%.
        let d = SymTensor::new(0.0, 0.0, 0.5e-5, 0.0);
        let mut s = isotropic(1e5);
        let stored =
            |s: &SymTensor| SAND.stored_energy_density(s, &crate::math::DMat2::IDENTITY, 1.0);
        let start = stored(&s);
        let (mut work, mut plastic) = (0.0, 0.0);
        for _ in 0..4000 {
            let before = s;
            plastic += SAND.update_stress(&mut s, &PointStep::rate(d, 0.0, 1.0));
            work += (before + s).contract(&d) * 0.5;
        }
        let residual = work - (stored(&s) - start) - plastic;
        println!(
            "work {work:.2} J/m3, stored {:.2}, plastic {plastic:.2}, residual {residual:e}",
            stored(&s) - start
        );
        assert!(
            plastic > 0.5 * work,
            "the path yields: plastic {plastic} of {work}"
        );
        assert!(
            residual.abs() < 5e-3 * work,
            "residual {residual} of {work}"
        );
    }
}
