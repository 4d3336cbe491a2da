//! # mpdem
//!
//! A two-dimensional (plane-strain) material point method engine whose
//! contacts are computed the discrete-element way, after "DEM-enriched
//! contact approach for material point method" (see `shared/reference`).
//!
//! The engine is an entity-component-system program on `bevy_ecs`:
//! * a deformable body is an entity with its points as columns
//!   ([`components::MaterialPoints`]), its [`components::Material`] and its
//!   own [`components::GridLayer`] (shared, as a summed copy, with the other
//!   bodies of its contact group, if any);
//! * the grid, clock, settings and records are [`resources`];
//! * the time step is the [`systems::MpmSchedule`], whose
//!   [`systems::MpmSystems`] sets follow Algorithm 1 of the paper, and into
//!   which a user adds systems of their own;
//! * a scenario is a RON [`scene::Scene`], and a [`Simulation`] runs it.
//!
//! `systems/` sits beside `src/` (declared here with `#[path]`) so the
//! schedule is visible at a glance, while staying one crate.

#![deny(missing_docs)]

#[doc(hidden)]
pub mod bench;
pub mod checkpoint;
pub mod components;
pub mod contact;
pub(crate) mod files;
pub mod geometry;
pub mod io;
pub mod materials;
pub mod math;
pub(crate) mod node_rect;
pub(crate) mod parallel;
pub mod plugins;
pub mod resources;
pub mod rigid;
pub(crate) mod rules;
pub mod runner;
pub(crate) mod scatter;
pub mod scene;
pub mod shape_functions;
mod simulation;
#[doc(hidden)]
pub mod verify;

#[path = "../systems/mod.rs"]
pub mod systems;

pub use simulation::{PluginError, Simulation, StepError};

/// The common imports of a user of the library.
pub mod prelude {
    pub use crate::components::{BodyName, GridLayer, Material, MaterialPoints};
    pub use crate::math::{DMat2, DVec2, Real, SymTensor};
    pub use crate::plugins::{MpmPlugin, PluginSetup};
    pub use crate::resources::{Clock, Gravity, Grid, Probes, Settings};
    pub use crate::scene::Scene;
    pub use crate::systems::{MpmSchedule, MpmSystems};
    pub use crate::{PluginError, Simulation, StepError};
    pub use bevy_ecs::prelude::*;
}
