//! A block ready to be spawned: its components, built once from its scene
//! entry (at the start, or kept until a stage adds it).

use super::{
    BlockContactLaw, BlockContacts, BlockId, BlockOutline, NeighbourList, PartReactions, Pose,
    Reaction, RigidMass, RigidMotion, RigidShape, RigidVelocity,
};
use crate::math::DVec2;
use bevy_ecs::prelude::*;

/// The components a block is spawned with.
#[derive(Clone)]
pub struct BlockTemplate {
    /// Name and scene index.
    pub id: BlockId,
    /// The outline drawn in the outputs.
    pub outline: BlockOutline,
    /// The shape.
    pub shape: RigidShape,
    /// Where it is placed.
    pub pose: Pose,
    /// Its initial velocity.
    pub velocity: RigidVelocity,
    /// Fixed, kinematic or dynamic.
    pub motion: RigidMotion,
    /// Its mass properties.
    pub mass: RigidMass,
    /// Its contact law with the points.
    pub law: BlockContactLaw,
}

impl BlockTemplate {
    /// Spawns the block into `world`.
    pub fn spawn(&self, world: &mut World) -> Entity {
        let parts = self.shape.0.as_compound().map_or(1, |c| c.shapes().len());
        world
            .spawn((
                self.id.clone(),
                self.outline.clone(),
                self.shape.clone(),
                self.pose,
                self.velocity,
                self.motion,
                self.mass,
                self.law.clone(),
                NeighbourList::default(),
                BlockContacts::default(),
                Reaction::default(),
                PartReactions(vec![DVec2::ZERO; parts]),
            ))
            .id()
    }
}
