//! Work the surface loads have done since the start of the run.

use crate::math::{DMat2, DVec2, Real};
use bevy_ecs::prelude::{Entity, Resource};

/// The work of the stages' surface tractions on the bodies (J/m; per radian
/// in axisymmetry), for the energy balance: Σ over steps and loaded points
/// of F · Δx_edge, F the force the step applied at the middle of the
/// point's outer domain edge and Δx_edge the material's motion there over
/// the step (`systems::account_load_work`).
#[derive(Resource, Clone, Debug, Default)]
pub struct LoadWork {
    /// The work since the start of the run (J/m).
    pub work: Real,
    /// Every point this step loaded, in the order the loads were applied
    /// (`systems::apply_surface_loads`), until the step's end adds their
    /// work and clears it (`systems::account_load_work`); capacity kept
    /// between steps.
    pub applied: Vec<LoadedEdge>,
}

impl LoadWork {
    /// A record of `work` done so far and no load pending, as a checkpoint
    /// restores it.
    pub fn with_work(work: Real) -> Self {
        Self {
            work,
            applied: Vec::new(),
        }
    }
}

/// One point's surface load in this step, with what its work needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadedEdge {
    /// The loaded body.
    pub body: Entity,
    /// The point's index in its body.
    pub point: u32,
    /// The force applied (N/m; per radian in axisymmetry).
    pub force: DVec2,
    /// From the point's centre to where the force acts, the middle of its
    /// domain's outer edge (m; domains keep their undeformed size).
    pub arm: DVec2,
    /// The point's position at the step's start (m).
    pub from: DVec2,
    /// The point's deformation gradient at the step's start.
    pub deformation_from: DMat2,
}
