//! # mpdem
//!
//! A two-dimensional (plane-strain or axisymmetric) material point method
//! engine whose contacts are computed the discrete-element way, after H.
//! Chen, S. Zhao, J. Zhao, X. Zhou, "DEM-enriched contact approach for
//! material point method", Comput. Methods Appl. Mech. Engrg. 404 (2023)
//! 115814. Start with [`Simulation`] and the [`prelude`]; the chapter below
//! is `docs/architecture.md`.
#![doc = include_str!("../docs/architecture.md")]
#![deny(missing_docs)]

pub mod checkpoint;
pub mod components;
pub mod contact;
pub mod deposit;
pub mod distributed;
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
pub mod threads;

pub mod warning;

#[path = "../systems/mod.rs"]
pub mod systems;

pub use simulation::{PluginError, Simulation, StepError};
pub use warning::{Warning, WarningKind};

/// The common imports of a user of the library.
pub mod prelude {
    pub use crate::components::{BodyName, GridLayer, Material, MaterialPoints};
    pub use crate::math::{DMat2, DVec2, Real, SymTensor};
    pub use crate::plugins::{MpmPlugin, PluginSetup};
    pub use crate::resources::{Clock, Gravity, Grid, Probes, Settings};
    pub use crate::scene::Scene;
    pub use crate::systems::{MpmSchedule, MpmSystems};
    pub use crate::{PluginError, Simulation, StepError, Warning, WarningKind};
    pub use bevy_ecs::prelude::*;
}
