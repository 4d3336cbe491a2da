//! Numerical settings and gravity.

use crate::geometry::Geometry;
use crate::math::{DVec2, Real};
use crate::rules::{ParameterError, damping, fraction, positive, xpic_order};
use crate::shape_functions::ShapeFunction;
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

/// When and from which nodal velocity the stress is updated (scene
/// `settings.scheme`). Read once, when the step schedule is built (it fixes
/// the order of the sets).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum UpdateScheme {
    /// Update stress first (the paper's Algorithm 1): strain rate from the
    /// nodal velocity mapped from the points at the start of the step.
    /// Default: with the default `PositionUpdate::RemappedVelocity` it keeps
    /// the energy of undamped DEM contacts (`verify/tests/safe_defaults.rs`).
    #[default]
    Usf,
    /// Update stress last, with the strain rate from the nodal solve's
    /// v^{n+1}. Plain USL damps the modes the grid resolves poorly: the
    /// strain follows the whole change of the nodal velocity, the points
    /// keep only what the map to them and back returns (an undamped elastic
    /// footing under a step traction loses a fifth of the load's largest
    /// work in about 45 of its periods; see `update_stress`).
    Usl,
    /// Modified USL (Sulsky et al. 1995): update stress last, with the
    /// strain rate from ṽ, the points' new velocities mapped back to the
    /// nodes. Material, points and contacts follow one velocity field, and
    /// undamped FLIP keeps the energy of elastic bodies and of DEM contact
    /// springs (in fast impacts on blocks less closely than USF with
    /// remapped positions). Costs one more momentum scatter and gather per
    /// step than USF with the paper's eq. 11b.
    Musl,
}

/// How G2P moves the points (scene `settings.position_update`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum PositionUpdate {
    /// The paper's eq. 11b: x += (v^n + v^{n+1})/2 Δt − β/2 (V^n − v^n) Δt,
    /// the nodal velocities interpolated at the point. With a force that
    /// depends on positions (a DEM contact spring of frequency ω) and the
    /// velocity updated by the force at x^n, each step multiplies the
    /// spring's phase-space area by 1 + (ωΔt)²/2: undamped contacts gain
    /// energy (a block resting undamped on the ground jumps off it). Damped
    /// scenes, as the paper's, do not show it.
    PaperEq11b,
    /// x += v^{n+1} Δt, the interpolated new nodal velocity: symplectic
    /// Euler for the contact springs. Under USF the strain follows the
    /// velocity mapped from the points, not this one, and undamped contacts
    /// gain energy slowly.
    NewGridVelocity,
    /// x += ṽ Δt with ṽ = Σ S_ip ṽ_i, where ṽ_i = Σ_p S_ip m_p V_p^{n+1} / m_i
    /// (with `affine_transfer`, V_p^{n+1} + C_p (x_i − x̄_p); constrained;
    /// summed over a contact group's members) maps the points' new
    /// velocities back to the nodes as P2G does, with the stencils at x^n:
    /// the field from which the next step's strain rate is computed. The
    /// material and the contact springs then see one displacement field
    /// (under MUSL exactly), and the springs are integrated by symplectic
    /// Euler. Default under the FLIP/PIC update (XPIC moves the points by
    /// its own eq. 12b).
    RemappedVelocity,
}

/// Numerical choices of a simulation (scene `settings`).
#[derive(Resource, Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Shape function (default uGIMP, the paper's choice).
    pub shape_function: ShapeFunction,
    /// Update scheme (default USF, the paper's Algorithm 1).
    pub scheme: UpdateScheme,
    /// PIC fraction β of eq. 11 in [0, 1]: 0 is pure FLIP, 1 pure PIC.
    /// Default 0: FLIP conserves energy, which dynamic benchmarks need;
    /// granular bodies then relax by `granular_relaxation`. Not used when
    /// `xpic_order` is set.
    #[serde(deserialize_with = "crate::rules::de_fraction")]
    pub pic_fraction: Real,
    /// XPIC order m of eq. 12 (1 to 10; m = 1 is PIC). Default `None`: the
    /// FLIP/PIC blend of eq. 11, the paper's usual update.
    #[serde(deserialize_with = "crate::rules::de_xpic_order")]
    pub xpic_order: Option<u32>,
    /// Grid damping α_g in [0, 1], local non-viscous damping at the nodes
    /// (Cundall 1987): each nodal force component is reduced by α_g |f| in
    /// the direction of the node's motion. Default 0: dynamics are not
    /// altered unasked.
    #[serde(deserialize_with = "crate::rules::de_damping")]
    pub grid_damping: Real,
    /// Particle damping α_p in [0, 1], the same law at the points: each
    /// component of a point's acceleration S a is reduced by α_p |S a| in
    /// the direction of the point's motion before it updates V_p. Default 0.
    #[serde(deserialize_with = "crate::rules::de_damping")]
    pub particle_damping: Real,
    /// How the points move in G2P. Default (`None`): `RemappedVelocity`
    /// under the FLIP/PIC update, eq. 12b under XPIC, which takes no other.
    /// The paper's is `PaperEq11b`. Read it through
    /// [`Settings::position_update`].
    pub position_update: Option<PositionUpdate>,
    /// Affine momentum transfer: P2G maps V_p + C_p (x_i − x_p) to node i,
    /// C_p the gradient at the point of the nodal velocity that G2P last
    /// interpolated (Taylor particle-in-cell, Nakamura et al. 2023; with the
    /// quadratic B-spline it is APIC's affine velocity, Jiang et al. 2015),
    /// so the nodes reproduce an affine velocity field exactly, a body's
    /// rotation included, where a point's support lies inside the grid. At
    /// a wall, whose cut renormalises the weights, the offsets are taken
    /// from the nodes' weighted mean x̄_p = Σ S_ip x_i instead of x_p, so
    /// momentum is still conserved. Without it a node on a body's
    /// edge takes the velocity of its points' mass centre, up to half a
    /// cell inside the body, so a rotating body strains: at one point per
    /// cell a freely spinning block's spin goes into strain and back and
    /// the block does not turn (`verify/tests/spin.rs`). C_p starts at zero, so
    /// the first P2G is eq. 8c's. Default `false`, the paper's eq. 8c; not
    /// with XPIC, whose smoothing maps velocities without it, nor with the
    /// `Linear` kernel (points invert in ordinary flows).
    pub affine_transfer: bool,
    /// Plane strain or axisymmetry (default `PlaneStrain`, as the paper).
    pub geometry: Geometry,
    /// Eq. 11a's FLIP change taken from each node's start velocity before
    /// the walls' constraints, p_i / m_i, instead of after them: a wall then
    /// takes from the points the momentum it holds back, and the points
    /// carry the grid's constrained momentum Σ m_i v_i^{n+1} exactly. Without
    /// it the points keep that momentum: a granular body sliding on a
    /// no-slip floor keeps points that report a velocity they do not move
    /// with, and its travel does not converge with the cell
    /// (`scenes/granular_slab.ron`). With it the walls take the kinetic
    /// energy the points map onto them, a dissipation of first order in the
    /// cell: an undamped elastic body ringing against a no-slip wall loses
    /// energy. Default `false`; not with XPIC, whose smoothing already maps
    /// the constrained velocities.
    pub flip_from_unconstrained: bool,
    /// Relaxation time τ (s) of a granular body's point velocities toward
    /// the velocity field they map to the grid. A granular body
    /// (Drucker–Prager, Mohr–Coulomb) under the FLIP/PIC update with no PIC
    /// share named (`pic_fraction` 0, no `xpic_order`) takes the PIC
    /// fraction β = 1 − exp(−Δt/τ) each step, its PIC term started from the
    /// nodal velocity p_i / m_i before the walls' constraints: the part of
    /// its points' velocities that the grid does not carry, which FLIP
    /// keeps undamped and which throws the points of a flow's thin front
    /// and surface ahead of the deposit, decays in a time τ, whatever the
    /// step, while a no-slip wall resists the body only through its
    /// friction. A rate, not a share per step: β = 1% per step at
    /// Δt = 2.5e-5 s and half that at half the step. Default
    /// `Some(2.5e-3)`; `None` leaves granular bodies under pure FLIP. Other
    /// bodies, and every body when the scene names a PIC share or an XPIC
    /// order, take the scene's update. With `flip_from_unconstrained` the
    /// PIC term starts from the constrained velocity, as the FLIP change
    /// does.
    #[serde(deserialize_with = "crate::rules::de_option_positive")]
    pub granular_relaxation: Option<Real>,
}

/// The default [`Settings::granular_relaxation`] (s): the PIC share of 1%
/// that granular MPM computations commonly use, at the time step of Bui
/// et al.'s (2008) computation of their collapse, 2.5e-5 s.
pub const GRANULAR_RELAXATION: Real = 2.5e-3;

impl Default for Settings {
    fn default() -> Self {
        Self {
            shape_function: ShapeFunction::UGimp,
            scheme: UpdateScheme::Usf,
            pic_fraction: 0.0,
            xpic_order: None,
            grid_damping: 0.0,
            particle_damping: 0.0,
            position_update: None,
            affine_transfer: false,
            geometry: Geometry::PlaneStrain,
            flip_from_unconstrained: false,
            granular_relaxation: Some(GRANULAR_RELAXATION),
        }
    }
}

impl Settings {
    /// How G2P moves the points: the scene's choice or the default
    /// `RemappedVelocity`; `None` under XPIC (eq. 12b).
    pub fn position_update(&self) -> Option<PositionUpdate> {
        match self.xpic_order {
            Some(_) => None,
            None => Some(
                self.position_update
                    .unwrap_or(PositionUpdate::RemappedVelocity),
            ),
        }
    }

    /// The PIC fraction β of eq. 11 for a body, `granular` or not, at steps
    /// of `dt`: the scene's, or for a granular body when the scene names
    /// none, the one of [`Settings::granular_relaxation`].
    pub fn pic_fraction_for(&self, granular: bool, dt: Real) -> Real {
        match self.granular_relaxation {
            Some(tau) if self.relaxes(granular) => -(-dt / tau).exp_m1(),
            _ => self.pic_fraction,
        }
    }

    /// Whether a body, `granular` or not, takes the granular relaxation:
    /// its PIC fraction from [`Settings::granular_relaxation`], toward the
    /// nodal velocity the points map to the grid before the walls'
    /// constraints (see `grid_to_particle`).
    pub fn relaxes(&self, granular: bool) -> bool {
        granular
            && self.granular_relaxation.is_some()
            && self.pic_fraction == 0.0
            && self.xpic_order.is_none()
    }

    /// Whether G2P maps the points' new velocities back to the nodes (ṽ):
    /// the remapped position update and MUSL's stress update read them.
    pub fn remaps_velocity(&self) -> bool {
        self.scheme == UpdateScheme::Musl
            || self.position_update() == Some(PositionUpdate::RemappedVelocity)
    }

    /// Checks the ranges; the message names the field and the allowed range.
    pub fn check(&self) -> Result<(), ParameterError> {
        fraction(self.pic_fraction).map_err(|e| e.at("pic_fraction"))?;
        damping(self.grid_damping).map_err(|e| e.at("grid_damping"))?;
        damping(self.particle_damping).map_err(|e| e.at("particle_damping"))?;
        if let Some(tau) = self.granular_relaxation {
            positive(tau).map_err(|e| e.at("granular_relaxation"))?;
        }
        if self.affine_transfer && self.shape_function == ShapeFunction::Linear {
            // The dam break and a Drucker–Prager column collapse invert a
            // point within 240 and 5 000 steps, while uGIMP and the
            // B-spline run the same scenes through.
            return Err(ParameterError::Inconsistent(
                "affine_transfer: with the Linear kernel the affine velocity inverts points in ordinary flows; use UGimp or QuadraticBSpline".into(),
            ));
        }
        if let Some(m) = self.xpic_order {
            xpic_order(m).map_err(|e| e.at("xpic_order"))?;
            if self.affine_transfer {
                return Err(ParameterError::Inconsistent(
                    "affine_transfer: XPIC's smoothing maps the point velocities without their gradients; use one or the other".into(),
                ));
            }
            if self.flip_from_unconstrained {
                return Err(ParameterError::Inconsistent(
                    "flip_from_unconstrained: XPIC's update (eq. 12a) has no FLIP change to take from the walls; use one or the other".into(),
                ));
            }
            if let Some(update) = self.position_update {
                return Err(ParameterError::Inconsistent(format!(
                    "position_update: {update:?} is a choice of eq. 11 (the FLIP/PIC update); XPIC moves the points its own way (eq. 12b): leave position_update out"
                )));
            }
        }
        Ok(())
    }
}

/// Gravitational acceleration b of eq. 1 (m/s²), the same for every body.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Gravity(pub DVec2);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xpic_takes_only_its_own_position_update() {
        let xpic = |position_update| Settings {
            xpic_order: Some(2),
            position_update,
            ..Settings::default()
        };
        assert!(xpic(None).check().is_ok());
        for other in [
            PositionUpdate::PaperEq11b,
            PositionUpdate::NewGridVelocity,
            PositionUpdate::RemappedVelocity,
        ] {
            let message = xpic(Some(other)).check().expect_err("refused").to_string();
            assert!(
                message.contains(&format!("{other:?} is a choice of eq. 11")),
                "{message}"
            );
        }
    }

    #[test]
    fn xpic_has_no_flip_change_to_take_from_the_walls() {
        let settings = Settings {
            xpic_order: Some(2),
            flip_from_unconstrained: true,
            ..Settings::default()
        };
        let message = settings.check().expect_err("refused").to_string();
        assert!(
            message.starts_with("flip_from_unconstrained: "),
            "{message}"
        );
        let flip = Settings {
            flip_from_unconstrained: true,
            ..Settings::default()
        };
        assert!(flip.check().is_ok());
    }

    #[test]
    fn the_affine_transfer_is_not_for_xpic() {
        let settings = Settings {
            xpic_order: Some(3),
            affine_transfer: true,
            ..Settings::default()
        };
        let message = settings.check().expect_err("refused").to_string();
        assert!(message.starts_with("affine_transfer:"), "{message}");
    }
}
