//! Simulated time.

use crate::math::Real;
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

/// Step counter and simulated time. The time step is fixed for the run.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Clock {
    /// Number of completed steps.
    pub step: u64,
    /// Simulated time at the end of the last completed step (s).
    pub time: Real,
    /// Time step Δt (s).
    pub dt: Real,
    /// Time at which the scene ends (s).
    pub end: Real,
}

impl Clock {
    /// Number of steps of the whole run: the end time over Δt, rounded to the
    /// nearest step so that 1.0 / 1e-4 gives exactly 10 000 steps.
    pub fn total_steps(&self) -> u64 {
        (self.end / self.dt).round() as u64
    }

    /// Whether the run has reached its end.
    pub fn finished(&self) -> bool {
        self.step >= self.total_steps()
    }

    /// Advances by one step. Time is step × Δt (not a running sum), so it
    /// carries no accumulated round-off.
    pub fn advance(&mut self) {
        self.step += 1;
        self.time = self.step as Real * self.dt;
    }
}
