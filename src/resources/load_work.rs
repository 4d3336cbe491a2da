//! Work the surface loads have done since the start of the run.

use crate::math::{DVec2, Real};
use bevy_ecs::prelude::Resource;

/// The work of the stages' surface tractions on the bodies (J/m; per radian
/// in axisymmetry), for the energy balance: Σ over steps and loaded points
/// of F · Δx_edge, F the force the step applied at the middle of the
/// point's outer domain edge and Δx_edge the material's motion there over
/// the step (`systems::account_load_work`).
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct LoadWork {
    /// The work since the start of the run (J/m).
    pub work: Real,
    /// (force, where the material at the middle of the point's outer edge
    /// is) of every point this step loaded, at the step's start, in the order of the stage's loads
    /// (`systems::apply_surface_loads`), until the step's end adds their
    /// work (`systems::account_load_work`); capacity kept between steps.
    pub applied: Vec<(DVec2, DVec2)>,
}

impl LoadWork {
    /// A record holding `work` done so far, as a checkpoint stores it.
    pub fn done(work: Real) -> Self {
        Self {
            work,
            applied: Vec::new(),
        }
    }
}
