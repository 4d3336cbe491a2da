//! Rigid blocks: shapes from the scene, mass properties, and the
//! integration of their motion.

mod integrate;
mod placement;
mod shapes;
mod substeps;

pub(crate) use integrate::{advance, integrate_dynamic, velocity_at};
pub(crate) use placement::{PlacementChecks, placement_warnings};
pub use shapes::{BlockShape, BlockShapeError};
pub(crate) use substeps::{MAX_SUBSTEPS, substeps_needed};
