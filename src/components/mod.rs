//! ECS components. A deformable body is one entity carrying its material
//! points as columns ([`MaterialPoints`]), its [`Material`], its own
//! [`GridLayer`] and the scratch space of its grid transfers.

mod block_template;
mod body;
mod grid_layer;
mod material_points;
mod rigid;
mod transfer_scratch;

pub use crate::node_rect::NodeRect;
pub(crate) use block_template::BlockTemplate;
pub use body::{
    BodyAcceleration, BodyIndex, BodyName, Material, RegionConstraint, bodies_in_scene_order,
};
pub(crate) use body::{RegionConstraints, sort_into_scene_order};
pub(crate) use grid_layer::{Fix, NodeConstraint};
pub use grid_layer::{GridLayer, GridNode};
pub use material_points::{DampedEnergy, MaterialPoints, PointEnergies};
pub(crate) use material_points::{NewPoint, StepTravel, hoop_radius};
pub(crate) use rigid::BlockContactLaw;
pub use rigid::{
    BlockContacts, BlockId, BlockOutline, NeighbourList, PartReactions, PointContact, Pose,
    Reaction, RigidMass, RigidMotion, RigidShape, RigidVelocity,
};
pub(crate) use transfer_scratch::{MassMomentumForce, RemapScratch, TransferScratch};
