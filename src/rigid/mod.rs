//! Rigid blocks: shapes from the scene, mass properties, and the
//! integration of their motion.

mod integrate;
mod shapes;
mod substeps;

pub use integrate::{advance, integrate_dynamic, velocity_at};
pub use shapes::BlockShape;
pub use substeps::{MAX_SUBSTEPS, substeps_needed};
