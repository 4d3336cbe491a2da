//! The DEM force law of eq. 18: a linear normal spring and an incremental
//! tangential spring capped by Coulomb friction.

use crate::math::{DVec2, Real};
use crate::rules::ParameterError;
use serde::{Deserialize, Serialize};

/// Stiffnesses and friction of a contact (scene `contact`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactLaw {
    /// Normal stiffness k_n (N/m per metre of thickness), > 0.
    pub normal_stiffness: Real,
    /// Tangential stiffness k_t (N/m per metre of thickness), > 0.
    pub tangential_stiffness: Real,
    /// Friction coefficient μ, from 0 to 10.
    pub friction: Real,
    /// Normal viscous damping c_n (N s/m per metre), ≥ 0. Default 0: eq. 18
    /// has none; add some to settle impacts faster.
    #[serde(default)]
    pub normal_damping: Real,
}

impl ContactLaw {
    /// Checks the ranges; the message names the field.
    pub fn check(&self) -> Result<(), ParameterError> {
        let positive = |name: &str, v: Real| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ParameterError::Inconsistent(format!(
                    "{name} must be > 0, got {v}"
                )))
            }
        };
        let non_negative = |name: &str, v: Real| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(ParameterError::Inconsistent(format!(
                    "{name} must be ≥ 0, got {v}"
                )))
            }
        };
        positive("normal_stiffness", self.normal_stiffness)?;
        positive("tangential_stiffness", self.tangential_stiffness)?;
        for (name, k) in [
            ("normal_stiffness", self.normal_stiffness),
            ("tangential_stiffness", self.tangential_stiffness),
        ] {
            crate::rules::stiffness(k)
                .map_err(|e| ParameterError::Inconsistent(format!("{name}: {e}")))?;
        }
        crate::rules::friction(self.friction)
            .map_err(|e| ParameterError::Inconsistent(format!("friction: {e}")))?;
        non_negative("normal_damping", self.normal_damping)
    }

    /// Energy held by a tangential spring of force `tangential`:
    /// |f_t|² / (2 k_t) (J/m).
    pub fn tangential_energy(&self, tangential: DVec2) -> Real {
        tangential.length_squared() / (2.0 * self.tangential_stiffness)
    }

    /// The law for a contact `thickness` metres long out of the plane (per
    /// radian in axisymmetry: the point's radius): stiffnesses and damping
    /// times it, the friction unchanged. Forces and energies then come per
    /// unit of thickness the outputs count in.
    pub fn over_thickness(&self, thickness: Real) -> ContactLaw {
        ContactLaw {
            normal_stiffness: self.normal_stiffness * thickness,
            tangential_stiffness: self.tangential_stiffness * thickness,
            friction: self.friction,
            normal_damping: self.normal_damping * thickness,
        }
    }

    /// The law of a contact between two blocks with laws `self` and `other`:
    /// the softer stiffnesses, the smaller friction and the larger damping.
    pub fn pair(&self, other: &ContactLaw) -> ContactLaw {
        ContactLaw {
            normal_stiffness: self.normal_stiffness.min(other.normal_stiffness),
            tangential_stiffness: self.tangential_stiffness.min(other.tangential_stiffness),
            friction: self.friction.min(other.friction),
            normal_damping: self.normal_damping.max(other.normal_damping),
        }
    }
}

/// The force of one contact on body A and its new tangential spring.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairForce {
    /// Total force on A (normal + tangential); B receives the opposite.
    pub force: DVec2,
    /// The tangential spring force after this step, kept for the next step.
    pub tangential: DVec2,
}

/// Eq. 18 for a contact of penetration `delta` ≥ 0 along the unit normal `n`
/// (from B to A), relative velocity `v_rel` = v_A − v_B at the contact point,
/// and last step's tangential force `tangential` (zero for a new contact):
/// * f_n = k_n δ n − c_n (v_rel · n) n (eq. 18a, plus optional damping);
/// * the old tangential force is turned onto the current tangent plane,
///   keeping its magnitude, then Δf_t = −k_t Δu with Δu the tangential
///   relative displacement (v_rel − (v_rel · n) n) Δt (eqs. 18c, 18d): the
///   spring resists the sliding of A on B;
/// * |f_t| ≤ μ |f_n| (eq. 18b): beyond it the contact slides at the cap.
pub fn pair_force(
    law: &ContactLaw,
    delta: Real,
    n: DVec2,
    v_rel: DVec2,
    tangential: DVec2,
    dt: Real,
) -> PairForce {
    let normal_speed = v_rel.dot(n);
    let normal = (law.normal_stiffness * delta - law.normal_damping * normal_speed).max(0.0) * n;
    let projected = tangential - tangential.dot(n) * n;
    let carried = if projected.length_squared() > 0.0 {
        projected * (tangential.length() / projected.length())
    } else {
        DVec2::ZERO
    };
    let slip = (v_rel - normal_speed * n) * dt;
    let mut tangent = carried - law.tangential_stiffness * slip;
    let cap = law.friction * normal.length();
    if tangent.length() > cap {
        tangent *= cap / tangent.length();
    }
    PairForce {
        force: normal + tangent,
        tangential: tangent,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAW: ContactLaw = ContactLaw {
        normal_stiffness: 1e6,
        tangential_stiffness: 5e5,
        friction: 0.5,
        normal_damping: 0.0,
    };

    #[test]
    fn normal_spring_pushes_a_out_of_b() {
        let f = pair_force(&LAW, 1e-3, DVec2::Y, DVec2::ZERO, DVec2::ZERO, 1e-4);
        assert_eq!(f.force, DVec2::new(0.0, 1e3));
    }

    #[test]
    fn tangential_spring_resists_sliding_and_is_capped_by_friction() {
        // A slides at +1 m/s along x: the spring grows against the motion.
        let dt = 1e-4;
        let first = pair_force(&LAW, 1e-3, DVec2::Y, DVec2::X, DVec2::ZERO, dt);
        assert!((first.tangential.x + 5e5 * 1e-4).abs() < 1e-9);
        // Keep sliding: the force saturates at μ f_n = 500 N.
        let mut t = first.tangential;
        for _ in 0..100 {
            t = pair_force(&LAW, 1e-3, DVec2::Y, DVec2::X, t, dt).tangential;
        }
        assert!((t.length() - 500.0).abs() < 1e-9 && t.x < 0.0);
    }

    #[test]
    fn the_spring_follows_a_turning_normal() {
        // The old tangential force is turned onto the new tangent plane with its magnitude.
        let n = DVec2::new(0.1, 1.0).normalize();
        let f = pair_force(&LAW, 1e-3, n, DVec2::ZERO, DVec2::new(-100.0, 0.0), 1e-4);
        assert!(f.tangential.dot(n).abs() < 1e-9);
        assert!((f.tangential.length() - 100.0).abs() < 1e-9);
    }
}
