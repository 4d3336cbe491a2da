//! Rigid blocks and their DEM contacts with the points (section 3.2):
//! neighbour lists, contact forces, their transfer, the blocks' motion,
//! the contacts' work, and the blocks' record, `blocks.csv`.

use super::records::refill;
use super::{MpmPlugin, PluginSetup};
use crate::checkpoint::{Checkpointed, TimeRecord};
use crate::components::{BlockId, PartReactions, Pose, Reaction, RigidVelocity};
use crate::io::csv::{CsvSeries, field, time};
use crate::io::figure::{Curve, Figure, FigureContext};
use crate::math::Real;
use crate::resources::{BlockContactHistory, BlockLog, BlockPartSample, BlockSample, UpdateScheme};
use crate::rigid::BlockShape;
use crate::scene::MotionSpec;
use crate::scene::{SceneError, block_pair_laws};
use crate::systems::{
    ContactStep, DiagnosticsStep, MpmSystems, compute_rigid_contacts, move_rigid_blocks,
    rebuild_neighbour_lists, record_blocks,
};
use bevy_ecs::prelude::*;
use std::io::Write;

/// Rigid blocks, their contacts and their record.
pub struct RigidBlocksPlugin;

impl MpmPlugin for RigidBlocksPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        let scene = setup.scene;
        let samples = setup.samples_in_run();
        let world = &mut *setup.world;
        let compound_parts: usize = scene
            .blocks
            .iter()
            .map(|b| match &b.shape {
                BlockShape::Compound { parts } => parts.len(),
                _ => 0,
            })
            .sum();
        let mut log = BlockLog {
            names: scene.blocks.iter().map(|b| b.name.clone()).collect(),
            samples: Vec::with_capacity(samples * scene.blocks.len()),
            parts: Vec::with_capacity(samples * compound_parts),
        };
        record_blocks_at_the_start(world, &mut log);
        world.insert_resource(log);
        world.insert_resource(BlockContactHistory::default());
        world.insert_resource(block_pair_laws(scene));
        setup.keep_resource::<BlockContactHistory>("block springs");
        if scene.blocks.is_empty() {
            setup.keep_checkpointed::<BlockLog>("blocks");
        } else {
            setup.record::<BlockLog>("blocks", "blocks.csv");
            setup.plot::<BlockLog>(rotation_figure);
        }
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems((
            rebuild_neighbour_lists.in_set(MpmSystems::Neighbours),
            compute_rigid_contacts.in_set(ContactStep::Blocks),
            move_rigid_blocks.in_set(MpmSystems::RigidBodies),
            record_blocks.in_set(DiagnosticsStep::Blocks),
        ));
    }
}

impl Checkpointed for BlockLog {
    type Stored = (Vec<BlockSample>, Vec<BlockPartSample>);

    fn stored(&self) -> Self::Stored {
        (self.samples.clone(), self.parts.clone())
    }

    fn restore(&mut self, (samples, parts): Self::Stored) {
        refill(&mut self.samples, samples);
        refill(&mut self.parts, parts);
    }
}

impl TimeRecord for BlockLog {
    fn forget_from(&mut self, time: Real) {
        self.samples.retain(|s| s.time < time);
        self.parts.retain(|s| s.time < time);
    }
}

/// The blocks present at the start, as `record_blocks` samples them after
/// a step, in scene order: at t = 0, with no reaction yet.
fn record_blocks_at_the_start(world: &mut World, log: &mut BlockLog) {
    let mut query = world.query::<(&BlockId, &Reaction, &PartReactions, &Pose, &RigidVelocity)>();
    let mut blocks: Vec<_> = query.iter(world).collect();
    blocks.sort_unstable_by_key(|(id, ..)| id.index);
    for block in blocks {
        log.record(0.0, block);
    }
}

/// `block_rotation.png`: the rotation of every block that is not fixed, in
/// degrees against time (`blocks.csv` has it in radians); none without
/// such a block.
fn rotation_figure(blocks: &BlockLog, context: &FigureContext) -> Vec<Figure> {
    let moving: Vec<&str> = context
        .scene
        .blocks
        .iter()
        .filter(|b| b.motion != MotionSpec::Fixed)
        .map(|b| b.name.as_str())
        .collect();
    if moving.is_empty() {
        return Vec::new();
    }
    let curves = moving
        .iter()
        .map(|name| {
            let index = blocks.names.iter().position(|n| n == name);
            let samples = blocks
                .samples
                .iter()
                .filter(move |s| Some(s.block as usize) == index);
            Curve::new(*name, samples.map(|s| (s.time, s.angle.to_degrees())))
        })
        .collect();
    vec![Figure {
        file: "block_rotation.png".into(),
        title: "Rotation of the blocks".into(),
        x_label: "time (s)".into(),
        y_label: "rotation (degrees, counter-clockwise)".into(),
        curves,
    }]
}

/// `blocks.csv`: one row per block and sample time, columns block, time,
/// fx, fy, torque (the points' reaction on the block), x, y, angle (frame
/// origin, rad), vx, vy, omega (centre of mass).
impl CsvSeries for BlockLog {
    const HEADER: &'static str = "block,time,fx,fy,torque,x,y,angle,vx,vy,omega";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        let name = field(self.names.get(s.block as usize).map_or("?", String::as_str));
        writeln!(
            out,
            "{name},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            time(s.time),
            s.force.x,
            s.force.y,
            s.torque,
            s.origin.x,
            s.origin.y,
            s.angle,
            s.velocity.x,
            s.velocity.y,
            s.angular
        )
    }
}
