//! The standard throughput benchmark: an elastic block settling under
//! gravity on a fixed base, sized by its number of points; and a timer of
//! the step's sets.

mod set_timer;

pub use set_timer::{start_set_timer, take_set_seconds};

use mpdem::contact::ContactLaw;
use mpdem::materials::{LinearElastic, MaterialModel};
use mpdem::math::{DVec2, Real};
use mpdem::resources::{EdgeCondition, EdgeConditions};
use mpdem::rigid::BlockShape;
use mpdem::scene::{BlockSpec, BodySpec, GridSpec, MotionSpec, Scene, Shape};
use mpdem::{Simulation, StepError};
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
    let mut grid = GridSpec::new(DVec2::ZERO, h, (side_cells + 4, side_cells + 4));
    grid.edges.bottom = EdgeCondition::Fixed;
    let elastic = MaterialModel::LinearElastic(LinearElastic {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
    });
    let block = Shape::Rectangle {
        min: DVec2::new(2.0 * h, 0.0),
        max: DVec2::new(2.0 * h + side, side),
    };
    Scene::builder(grid, 1e-5, 1.0)
        .name(format!("bench_block_{points}"))
        .material("elastic", 2000.0, elastic)
        .body(BodySpec::new("block", "elastic", block))
        .build()
        .expect("the standard block is a valid scene")
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
    scene.blocks.push(BlockSpec::new(
        "ground",
        BlockShape::Cuboid {
            half_extents: DVec2::new(0.5 * width, 0.5 * h),
        },
        DVec2::new(0.5 * width, 0.5 * h),
        MotionSpec::Fixed,
        ContactLaw {
            normal_stiffness: 1e8,
            tangential_stiffness: 1e8,
            friction: 0.5,
            normal_damping: 0.0,
        },
    ));
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

/// Times each of `sims` for `steps` steps, `repeats` times, taking them in
/// turn so that a slow spell of the machine falls on all of them; each goes
/// on from where its last timing left it. Returns, per simulation, its
/// points and the seconds of each timing.
pub fn time_in_turn(
    sims: &mut [Simulation],
    steps: u64,
    repeats: usize,
) -> Result<Vec<(usize, Vec<Real>)>, StepError> {
    let mut timings = vec![(0, Vec::with_capacity(repeats)); sims.len()];
    for _ in 0..repeats {
        for (sim, (points, seconds)) in sims.iter_mut().zip(&mut timings) {
            let t = measure(sim, 0, steps)?;
            *points = t.points;
            seconds.push(t.seconds);
        }
    }
    Ok(timings)
}

/// The median of `values`, and their spread: the largest less the
/// smallest, over the median. `values` must not be empty.
pub fn median_and_spread(values: &[Real]) -> (Real, Real) {
    let mut sorted = values.to_vec();
    sorted.sort_unstable_by(Real::total_cmp);
    let n = sorted.len();
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    };
    let spread = (sorted[n - 1] - sorted[0]) / median.abs().max(Real::MIN_POSITIVE);
    (median, spread)
}

#[cfg(test)]
mod statistics_tests {
    use super::median_and_spread;

    #[test]
    fn the_median_of_an_even_count_is_the_mean_of_the_middle_two() {
        assert_eq!(median_and_spread(&[4.0, 1.0, 3.0, 2.0]), (2.5, 3.0 / 2.5));
        assert_eq!(median_and_spread(&[2.0, 9.0, 1.0]), (2.0, 4.0));
    }
}
