//! Health of the run.

use crate::math::Real;
use bevy_ecs::prelude::Resource;

/// Where and how the numerics broke down.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("step {step} (t = {time:.6e} s): {at}: {field} {detail}")]
pub struct NumericalFailure {
    /// Step during which it happened (1-based: the step being computed).
    pub step: u64,
    /// Simulated time at the start of that step (s).
    pub time: Real,
    /// What broke down.
    pub at: FailureSite,
    /// The offending field (e.g. "stress").
    pub field: &'static str,
    /// What is wrong with it.
    pub detail: String,
}

/// What a numerical failure is in.
#[derive(Clone, Debug, PartialEq)]
pub enum FailureSite {
    /// A material point.
    Point {
        /// Name of the body.
        body: String,
        /// Index of the point in its body.
        point: usize,
    },
    /// A rigid block, by name.
    Block(String),
    /// A recorded series, by its file.
    Record(&'static str),
}

impl std::fmt::Display for FailureSite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Point { body, point } => write!(f, "body '{body}', point {point}"),
            Self::Block(name) => write!(f, "block '{name}'"),
            Self::Record(file) => write!(f, "the record {file}"),
        }
    }
}

/// Run-health record written by the systems. The first failure of a step is
/// kept; the simulation stops after the step in which one was recorded.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct Diagnostics {
    /// The first numerical failure, if any.
    pub failure: Option<NumericalFailure>,
    /// Warnings found while stepping, in the order found (e.g. a point too
    /// loose for the time step); the run goes on.
    pub warnings: Vec<crate::warning::Warning>,
}

impl Diagnostics {
    /// Records `failure` unless an earlier one is already recorded.
    pub fn report(&mut self, failure: NumericalFailure) {
        self.failure.get_or_insert(failure);
    }
}
