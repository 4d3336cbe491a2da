//! Per-body scratch space of the grid transfers, kept between steps so the
//! step allocates nothing once the first step has sized it.

use crate::math::{DVec2, Real};
use crate::shape_functions::Stencil;
use crate::transfer::Scatter;
use bevy_ecs::prelude::Component;
use std::ops::AddAssign;

/// What a point gives a node in the particle-to-grid pass (eqs. 7b, 8c, 8d).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MassMomentumForce {
    /// S_ip m_p.
    pub mass: Real,
    /// S_ip m_p V_p.
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
    /// after the positions have moved.
    pub stencils: Vec<Stencil>,
    /// Patches of the mass / momentum / external force scatter.
    pub mass_momentum: Scatter<MassMomentumForce>,
    /// Patches of the internal force scatter.
    pub internal_force: Scatter<DVec2>,
}
