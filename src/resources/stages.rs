//! The stage plan of a run and the record of its stage transitions.

use super::{Side, StageSpec};
use crate::components::BlockTemplate;
use crate::math::{DVec2, Real, SymTensor};
use bevy_ecs::prelude::{Entity, Resource};
use serde::{Deserialize, Serialize};

/// The scene's stages and where the run is in them.
#[derive(Resource, Clone)]
pub struct StagePlan {
    /// The scene's stages, in order.
    pub stages: Vec<StageSpec>,
    /// The blocks absent at the start, ready for the stages that add them
    /// (in scene order).
    pub absent_blocks: Vec<BlockTemplate>,
    /// The bodies in scene order, taken when the current stage began (the
    /// end conditions read them each step without querying the world).
    pub bodies: Vec<Entity>,
    /// The dynamic blocks present, in scene order, taken when the current
    /// stage began or the run resumed (blocks come and go only on a
    /// stage's entry): the kinetic-energy end reads them each step
    /// without querying the world.
    pub dynamic_blocks: Vec<Entity>,
    /// Where the run is in the stages (what a checkpoint keeps).
    pub progress: StageProgress,
}

/// The state of the stage plan that changes during a run.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StageProgress {
    /// Index of the current stage in the scene's stages.
    pub current: usize,
    /// Simulated time at which the current stage began (s).
    pub started: Real,
    /// Largest kinetic energy of the current stage so far (J/m).
    pub peak_kinetic: Real,
    /// Largest change of a stress component in one step during the
    /// current stage so far (Pa).
    pub peak_stress_change: Real,
    /// Stresses of every body (scene order) after the previous step, kept
    /// only while a stage ends on the stress change.
    pub previous_stress: Vec<Vec<SymTensor>>,
    /// Surface loads in force, per body and side.
    pub loads: Vec<AppliedLoad>,
    /// Whether the last stage has ended.
    pub finished: bool,
}

/// The forces a surface traction puts on a body's outermost points, at
/// the outer edges of their domains (`systems::apply_surface_loads`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AppliedLoad {
    /// The body.
    pub body: Entity,
    /// The loaded side.
    pub side: Side,
    /// (point index, force in N/m) of every loaded point.
    pub forces: Vec<(u32, DVec2)>,
}

/// Why a stage ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum StageEndReason {
    /// Its duration elapsed.
    Duration,
    /// Its settling condition was met.
    Condition,
    /// Its `max_time` elapsed before the condition was met.
    MaxTime,
    /// The scene's `time.end` came first.
    SceneEnd,
}

impl StageEndReason {
    /// The word written to `stages.csv`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Duration => "duration",
            Self::Condition => "condition",
            Self::MaxTime => "max_time",
            Self::SceneEnd => "scene_end",
        }
    }
}

/// One finished stage.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StageRecord {
    /// Index in the scene's stages.
    pub index: usize,
    /// Name.
    pub name: String,
    /// Start time (s).
    pub start: Real,
    /// End time (s).
    pub end: Real,
    /// Steps taken in the stage.
    pub steps: u64,
    /// Why it ended.
    pub reason: StageEndReason,
}

/// The stages run so far and the warnings they raised.
#[derive(Resource, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StageLog {
    /// Finished stages, in order.
    pub records: Vec<StageRecord>,
    /// Warnings for the user (a stage that hit its `max_time`).
    pub warnings: Vec<crate::warning::Warning>,
}
