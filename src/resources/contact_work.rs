//! Work the point contacts have done since the start of the run: their
//! tangential forces on the relative motion, and the blocks' surfaces on the
//! points.

use crate::math::Real;
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

/// Two works of the point contacts since the start of the run (J/m): that
/// of their tangential forces (point–block and point–point) on the actual
/// relative motion of what they join, of which what their springs do not
/// hold was dissipated (see [`crate::resources::EnergySample::dissipated`]),
/// and that of the blocks on the points (see
/// [`crate::resources::EnergySample::blocks`]).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactWork {
    /// Σ over steps and contacts of ½ (f_t + f_t') · Δ(x_p − x_other), with
    /// Δ the motion over the step of the material at the contact point (the
    /// point's displacement plus its material's rotation about it) relative
    /// to the other point's or to the block's surface point it touched, f_t
    /// the force found at the step's start and f_t' the one found from that
    /// motion at the next step's (J/m): the trapezoidal rule, whose work on
    /// a sticking spring is exactly its energy change. Negative when the
    /// contacts take energy.
    pub tangential_work: Real,
    /// Σ over steps and point–block contacts of f · Δs, f the force on the
    /// point and Δs the motion over the step of the block's surface point
    /// it touched: the work the blocks did on the bodies (J/m; per radian
    /// in axisymmetry). Moving blocks, kinematic or dynamic, give (or take)
    /// the bodies' energy through it; a fixed block does none (to
    /// round-off). A block a stage removes takes its springs' energy
    /// along (`systems::enter_stage`).
    pub block_work: Real,
}
