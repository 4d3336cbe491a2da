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
pub use block_template::BlockTemplate;
pub use body::{
    BodyAcceleration, BodyIndex, BodyName, Material, RegionConstraint, RegionConstraints,
    bodies_in_scene_order, sort_into_scene_order,
};
pub use grid_layer::{Fix, GridLayer, GridNode, NodeConstraint, WINDOW_MARGIN_NODES};
pub use material_points::{
    DampedEnergy, MaterialPoints, NewPoint, PointEnergies, StepTravel, hoop_radius,
};
pub use rigid::{
    BlockContactLaw, BlockContacts, BlockId, BlockOutline, NeighbourList, PartReactions,
    PointContact, Pose, Reaction, RigidMass, RigidMotion, RigidShape, RigidVelocity,
};
pub use transfer_scratch::{MassMomentumForce, RemapScratch, TransferScratch};
