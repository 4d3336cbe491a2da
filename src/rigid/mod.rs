//! Rigid blocks: shapes from the scene, mass properties, and the
//! integration of their motion.

mod integrate;
mod shapes;

pub use integrate::{advance, integrate_dynamic, velocity_at};
pub use shapes::BlockShape;
