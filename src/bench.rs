//! The standard throughput benchmark: an elastic block settling under
//! gravity on a fixed base, sized by its number of points.

use crate::contact::ContactLaw;
use crate::materials::{LinearElastic, MaterialModel};
use crate::math::{DVec2, Real};
use crate::resources::{EdgeCondition, EdgeConditions, Settings};
use crate::rigid::BlockShape;
use crate::scene::{
    BlockSpec, BodySpec, GridSpec, InitialVelocity, MaterialSpec, MotionSpec, OutputSpec, Scene,
    Shape, TimeSpec,
};
use crate::simulation::{Simulation, StepError};
use std::time::Instant;

/// "1 thread" or "n threads": the pool the bench runs on, for its report.
pub fn threads_label() -> String {
    match rayon::current_num_threads() {
        1 => "1 thread".into(),
        n => format!("{n} threads"),
    }
}

/// A square elastic block of about `points` points (2 × 2 per cell, 0.01 m
/// cells) resting on the fixed base of a grid two cells wider on each side.
pub fn elastic_block_scene(points: usize) -> Scene {
    let side_cells = ((points as Real / 4.0).sqrt().round() as usize).max(1);
    let h = 0.01;
    let side = side_cells as Real * h;
    Scene {
        name: Some(format!("bench_block_{points}")),
        grid: GridSpec {
            origin: DVec2::ZERO,
            cell_size: h,
            cells: (side_cells + 4, side_cells + 4),
            edges: EdgeConditions {
                bottom: EdgeCondition::Fixed,
                ..Default::default()
            },
        },
        time: TimeSpec::new(1e-5, 1.0),
        gravity: DVec2::new(0.0, -9.81),
        settings: Settings::default(),
        materials: vec![MaterialSpec {
            name: "elastic".into(),
            density: 2000.0,
            model: MaterialModel::LinearElastic(LinearElastic {
                youngs_modulus: 1e7,
                poisson_ratio: 0.3,
            }),
        }],
        bodies: vec![BodySpec {
            name: "block".into(),
            material: "elastic".into(),
            shape: Shape::Rectangle {
                min: DVec2::new(2.0 * h, 0.0),
                max: DVec2::new(2.0 * h + side, side),
            },
            points_per_cell: 2,
            velocity: InitialVelocity::default(),
            initial_stress: None,
            constraints: Vec::new(),
            contact_radius: None,
            acceleration: None,
            group: None,
        }],
        blocks: Vec::new(),
        contact: Default::default(),
        probes: Vec::new(),
        output: OutputSpec::default(),
        stages: Vec::new(),
        body_contacts: Vec::new(),
    }
}

/// The same block resting through DEM contacts on a fixed rigid ground
/// block instead of the grid's fixed base: the contact benchmark (its
/// neighbour lists, contact forces and reactions cost what this scene adds
/// over [`elastic_block_scene`]).
pub fn elastic_block_on_ground_scene(points: usize) -> Scene {
    let mut scene = elastic_block_scene(points);
    let h = scene.grid.cell_size;
    let width = scene.grid.cells.0 as Real * h;
    scene.name = Some(format!("bench_block_on_ground_{points}"));
    scene.grid.edges = EdgeConditions::default();
    scene.grid.cells.1 += 1;
    if let Shape::Rectangle { min, max } = &mut scene.bodies[0].shape {
        min.y += h;
        max.y += h;
    }
    scene.blocks.push(BlockSpec {
        name: "ground".into(),
        shape: BlockShape::Cuboid {
            half_extents: DVec2::new(0.5 * width, 0.5 * h),
        },
        position: DVec2::new(0.5 * width, 0.5 * h),
        angle: 0.0,
        motion: MotionSpec::Fixed,
        contact: ContactLaw {
            normal_stiffness: 1e8,
            tangential_stiffness: 1e8,
            friction: 0.5,
            normal_damping: 0.0,
        },
        present: true,
    });
    scene
}

/// The measured throughput of a run of `steps` steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Throughput {
    /// Number of material points.
    pub points: usize,
    /// Steps timed.
    pub steps: u64,
    /// Wall-clock seconds of stepping (building the scene excluded).
    pub seconds: Real,
}

impl Throughput {
    /// Particle-updates per second: points × steps / seconds.
    pub fn updates_per_second(&self) -> Real {
        self.points as Real * self.steps as Real / self.seconds
    }
}

/// Steps `sim` `steps` times after `warmup` untimed steps (which size every
/// scratch buffer) and times the stepping.
pub fn measure(sim: &mut Simulation, warmup: u64, steps: u64) -> Result<Throughput, StepError> {
    for _ in 0..warmup {
        sim.step()?;
    }
    let points = sim
        .bodies()
        .iter()
        .filter_map(|(e, _)| sim.points(*e))
        .map(|p| p.len())
        .sum();
    let start = Instant::now();
    for _ in 0..steps {
        sim.step()?;
    }
    Ok(Throughput {
        points,
        steps,
        seconds: start.elapsed().as_secs_f64(),
    })
}
