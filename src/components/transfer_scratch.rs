//! Per-body scratch space of the grid transfers, kept between steps so the
//! step allocates nothing once the first step has sized it.

use crate::math::{DVec2, Real};
use crate::scatter::{Scatter, ScatterOrder};
use crate::shape_functions::Stencil;
use bevy_ecs::prelude::Component;
use std::ops::AddAssign;

/// What a point gives a node in the particle-to-grid pass (eqs. 7b, 8c, 8d).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MassMomentumForce {
    /// S_ip m_p.
    pub mass: Real,
    /// S_ip m_p V_p (S_ip m_p (V_p + C_p (x_i − x̄_p)) with
    /// `Settings::affine_transfer`).
    pub momentum: DVec2,
    /// S_ip (m_p b + f_p,ext).
    pub external_force: DVec2,
}

impl AddAssign for MassMomentumForce {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        self.mass += o.mass;
        self.momentum += o.momentum;
        self.external_force += o.external_force;
    }
}

/// Stencils of this step and the scatter patches of one body.
#[derive(Component, Clone, Debug, Default)]
pub struct TransferScratch {
    /// Each point's stencil at the start of the step (positions x^n). Every
    /// transfer of the step uses these, including the stress update of USL
    /// and MUSL after the positions have moved.
    pub stencils: Vec<Stencil>,
    /// Each stencil's base node, `stencils[p].base`, as a compact column:
    /// the scatter order reads these alone, and a pass over them touches a
    /// fourteenth of the memory of one over the stencils.
    pub stencil_bases: Vec<[u32; 2]>,
    /// The order in which this step's scatters visit the points, sorted
    /// from `stencil_bases` by particle-to-grid.
    pub order: ScatterOrder,
    /// Patches of the mass / momentum / external force scatter.
    pub mass_momentum: Scatter<MassMomentumForce>,
    /// Patches of the internal force scatter.
    pub internal_force: Scatter<DVec2>,
    /// With grid damping, each node's velocity v^{n+1} without it, for the
    /// energy balance; sized on first use.
    pub undamped: Vec<DVec2>,
    /// With `Settings::flip_from_unconstrained`, what the constraints took
    /// from each node's start velocity: v_i^n less p_i / m_i, zero but at a
    /// constrained node; sized on first use.
    pub held_back: Vec<DVec2>,
    /// Each point's energy taken by this step's velocity update (see
    /// [`crate::components::DampedEnergy`]), sized on first use.
    pub damped: Vec<Real>,
    /// The energy of `damped` summed per tile of the scatter order, with
    /// room for every tile of the grid.
    pub damped_by_tile: Vec<Real>,
    /// Work space of G2P's maps from the points back to the nodes, sized
    /// on first use.
    pub remap: RemapScratch,
}

/// Work space of one body's maps from the points back to its nodes in G2P:
/// the XPIC(m) iteration (eq. 12) and the remapped velocity of
/// [`crate::resources::PositionUpdate::RemappedVelocity`] and MUSL.
#[derive(Clone, Debug, Default)]
pub struct RemapScratch {
    /// Velocities interpolated to the points, S u_{k−1}.
    pub point_velocity: Vec<DVec2>,
    /// Patches of the momentum scatter S m_p V_p (affine as in P2G for the
    /// remapped positions).
    pub momentum: Scatter<DVec2>,
    /// Nodal velocities of the previous XPIC iterate u_{k−1}.
    pub previous: Vec<DVec2>,
    /// Nodal velocities mapped back from the points: the current XPIC
    /// iterate u_k, or the remapped velocity.
    pub current: Vec<DVec2>,
    /// The XPIC nodal velocity v* = Σ_k (−1)^{k+1} C(m, k) u_k.
    pub star: Vec<DVec2>,
}
