//! A scene built in code rather than read from a file: a rubber block
//! dropped onto a rigid floor, run with the default numerical settings.
//!
//! Run with `cargo run --release --example scene_in_code`.

use mpdem::contact::ContactLaw;
use mpdem::materials::{MaterialModel, NeoHookean};
use mpdem::prelude::*;
use mpdem::rigid::BlockShape;
use mpdem::scene::{BlockSpec, BodySpec, GridSpec, MotionSpec, Shape};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rubber = MaterialModel::NeoHookean(NeoHookean {
        youngs_modulus: 1e6,
        poisson_ratio: 0.3,
    });
    let floor = BlockSpec::new(
        "floor",
        BlockShape::Cuboid {
            half_extents: DVec2::new(0.5, 0.05),
        },
        DVec2::new(0.5, 0.05),
        MotionSpec::Fixed,
        ContactLaw {
            normal_stiffness: 1e7,
            tangential_stiffness: 1e7,
            friction: 0.3,
            normal_damping: 0.0,
        },
    );
    let block = Shape::Rectangle {
        min: DVec2::new(0.4, 0.15),
        max: DVec2::new(0.6, 0.35),
    };
    let scene = Scene::builder(GridSpec::new(DVec2::ZERO, 0.02, (50, 25)), 5e-5, 0.2)
        .name("rubber_drop")
        .material("rubber", 1100.0, rubber)
        .body(BodySpec::new("block", "rubber", block))
        .block(floor)
        .build()?;
    let mut sim = Simulation::from_scene(&scene)?;
    sim.run()?;
    let points = sim.points_of("block").ok_or("no block")?;
    let lowest = points
        .position
        .iter()
        .map(|x| x.y)
        .fold(Real::INFINITY, Real::min);
    println!(
        "after {} steps the block's lowest point is at y = {lowest:.4} m (the floor's top at 0.1 m); state hash {:016x}",
        sim.clock().step,
        sim.state_hash()
    );
    Ok(())
}
