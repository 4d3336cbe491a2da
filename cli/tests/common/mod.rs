//! Helpers shared by the command line's tests: the engine's test helpers.
#![allow(dead_code)] // each test binary uses a different subset

#[path = "../../../tests/common/mod.rs"]
mod engine;

pub use engine::*;
