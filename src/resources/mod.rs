//! ECS resources: the state shared by every body (grid, clock, settings,
//! gravity) and the run's records (probes, energy, diagnostics).

mod body_contacts;
mod clock;
mod contact_settings;
mod contact_work;
mod diagnostics;
mod grid;
mod load_work;
mod records;
mod settings;
mod shared_layers;
mod stage_spec;
mod stages;
mod step_interrupt;

pub use crate::geometry::Geometry;
pub use body_contacts::{BodyContacts, BodyPairLaw, PairSummary};
pub(crate) use body_contacts::{BodyPairContact, MAX_CONTACT_BODIES, PairTally, law_between};
pub use clock::Clock;
pub(crate) use contact_settings::{BlockContactHistory, BlockContactKey, BlockPairLaws};
pub use contact_settings::{ContactSettings, Penetration};
pub use contact_work::ContactWork;
pub use diagnostics::{Diagnostics, FailureSite, NumericalFailure};
pub use grid::{EdgeCondition, EdgeConditions, Grid, GridEdge};
pub use load_work::LoadWork;
pub(crate) use load_work::LoadedEdge;
pub use records::{
    BlockLog, BlockPartSample, BlockSample, BodyPairLog, BodyPairSample, EnergyLog, EnergySample,
    Probe, ProbeSample, Probes, Sampling,
};
pub use settings::{GRANULAR_RELAXATION, Gravity, PositionUpdate, Settings, UpdateScheme};
pub(crate) use shared_layers::SharedLayers;
pub use stage_spec::{BlockVelocity, EdgeChanges, Side, StageEnd, StageSpec, SurfaceTraction};
pub(crate) use stages::{AppliedLoad, StagePlan, StageProgress};
pub use stages::{StageEndReason, StageLog, StageRecord};
pub use step_interrupt::StepInterrupt;
