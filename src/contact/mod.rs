//! DEM contact, pure numerics with no ECS (paper section 3): the linear
//! spring + Coulomb law of eq. 18, the geometry of a point's disk against a
//! rigid shape or another point's disk, and the imposition of a contact force on a material point
//! (section 3.2.3).

mod disk_disk;
mod disk_shape;
mod force_application;
mod linear_spring;
mod shape_shape;

pub(crate) use disk_disk::{DiskOverlap, disk_overlap};
pub use disk_shape::{DiskContact, disk_shape_contact};
pub(crate) use disk_shape::{overlap_area, overlap_area_integral};
pub use force_application::ForceApplication;
pub(crate) use force_application::traction_points;
pub use linear_spring::ContactLaw;
pub use linear_spring::{PairForce, pair_force};
pub(crate) use shape_shape::{ShapeContact, shape_shape_contacts};
