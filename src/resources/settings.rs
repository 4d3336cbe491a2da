//! Numerical settings and gravity.

use crate::math::{DVec2, Real};
use crate::scene::rules::{damping, fraction};
use crate::shape_functions::ShapeFunction;
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

/// When the stress is updated relative to the nodal momentum update. Read
/// once, when the step schedule is built (it fixes the order of the sets).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum UpdateScheme {
    /// Update stress first (Algorithm 1): strain rate from the nodal velocity
    /// mapped at the start of the step. Default, as in the paper.
    #[default]
    Usf,
    /// Update stress last: strain rate from the updated nodal velocity.
    Usl,
}

/// Numerical choices of a simulation (scene `settings`).
#[derive(Resource, Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Shape function (default uGIMP, the paper's choice).
    pub shape_function: ShapeFunction,
    /// Update scheme (default USF, Algorithm 1).
    pub scheme: UpdateScheme,
    /// PIC fraction β of eq. 11 in [0, 1]: 0 is pure FLIP, 1 pure PIC.
    /// Default 0: FLIP conserves energy, which dynamic benchmarks need.
    #[serde(deserialize_with = "crate::scene::rules::de_fraction")]
    pub pic_fraction: Real,
    /// Local non-viscous damping coefficient α in [0, 1) (Cundall 1987):
    /// each nodal force component is reduced by α |f| in the direction of
    /// motion. Default 0: no damping, so dynamics are not altered unasked.
    #[serde(deserialize_with = "crate::scene::rules::de_damping")]
    pub damping: Real,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            shape_function: ShapeFunction::UGimp,
            scheme: UpdateScheme::Usf,
            pic_fraction: 0.0,
            damping: 0.0,
        }
    }
}

impl Settings {
    /// Checks the ranges; the message names the field and the allowed range.
    pub fn check(&self) -> Result<(), String> {
        fraction(self.pic_fraction).map_err(|e| format!("pic_fraction: {e}"))?;
        damping(self.damping).map_err(|e| format!("damping: {e}"))?;
        Ok(())
    }
}

/// Gravitational acceleration b of eq. 1 (m/s²), the same for every body.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct Gravity(pub DVec2);
