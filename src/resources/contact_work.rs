//! Work the contact forces have done since the start of the run.

use crate::math::Real;
use bevy_ecs::prelude::Resource;

/// Work of the point contacts' forces (point–block and point–point) on the
/// relative motion of what they join, since the start of the run (J/m):
/// each step, Σ f · Δ(x_p − x_other) over the step's contacts, with Δ the
/// change over the step of the point's position relative to the other
/// point or to the block's surface point it touched. Negative when the
/// contacts take energy; what they take and do not hold in their springs
/// is dissipated (see [`crate::resources::EnergySample::dissipated`]).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactWork {
    /// The work, summed step by step in the contact systems' order (J/m).
    pub work: Real,
}
