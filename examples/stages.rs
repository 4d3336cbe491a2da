//! A staged load in code: a soil pad settles under gravity (its stage ends
//! once the kinetic energy has fallen to a thousandth of its peak, with
//! grid damping), then a surcharge is put on its top for 0.2 s.
//!
//! Run with `cargo run --release --example stages`.

use mpdem::materials::{LinearElastic, MaterialModel};
use mpdem::prelude::*;
use mpdem::resources::{EdgeCondition, Side, StageLog, SurfaceTraction};
use mpdem::scene::{BodySpec, GridSpec, Shape, StageEnd, StageSpec};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut grid = GridSpec::new(DVec2::ZERO, 0.05, (20, 12));
    grid.edges.bottom = EdgeCondition::Fixed;
    grid.edges.left = EdgeCondition::Slip;
    grid.edges.right = EdgeCondition::Slip;
    let soil = MaterialModel::LinearElastic(LinearElastic {
        youngs_modulus: 2e7,
        poisson_ratio: 0.3,
    });
    let mut settle = StageSpec::new(
        "settle",
        StageEnd::KineticEnergyRatio {
            ratio: 1e-3,
            max_time: 0.5,
        },
    );
    settle.grid_damping = Some(0.2);
    let mut load = StageSpec::new("surcharge", StageEnd::Duration(0.2));
    load.tractions = vec![SurfaceTraction {
        body: "soil".into(),
        side: Side::Top,
        traction: DVec2::new(0.0, -5e4),
    }];
    let pad = Shape::Rectangle {
        min: DVec2::ZERO,
        max: DVec2::new(1.0, 0.4),
    };
    let scene = Scene::builder(grid, 1e-4, 1.0)
        .name("staged_pad")
        .material("soil", 1800.0, soil)
        .body(BodySpec::new("soil", "soil", pad))
        .stage(settle)
        .stage(load)
        .build()?;
    let mut sim = Simulation::from_scene(&scene)?;
    sim.run()?;
    for record in &sim.world().resource::<StageLog>().records {
        println!(
            "stage '{}': {:.3} s to {:.3} s ({:?})",
            record.name, record.start, record.end, record.reason
        );
    }
    Ok(())
}
