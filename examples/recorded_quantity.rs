//! Adding a recorded quantity, in this one file: the height of each body's
//! highest point, sampled with the other records, written to `heights.csv`
//! while the run goes and drawn as `heights.png` at its end, each point's
//! rise as a field of the VTK frames, and the samples carried by
//! checkpoints, so that a run stopped and resumed writes the same series as
//! one that never stopped.
//!
//! Run with `cargo run --release --example recorded_quantity`.

use mpdem::checkpoint::{Checkpointed, TimeRecord};
use mpdem::components::BodyIndex;
use mpdem::io::csv::CsvSeries;
use mpdem::io::figure::{Curve, Figure, FigureContext};
use mpdem::prelude::*;
use mpdem::resources::{Sampling, UpdateScheme};
use mpdem::runner::{RunError, RunOptions, Runner, Start};
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicBool, Ordering};

/// One sample: a body's highest point at a time.
#[derive(Clone, Copy, Serialize, Deserialize)]
struct Height {
    time: Real,
    body: usize,
    top: Real,
}

/// The record: samples in time order, bodies in scene order within a time.
#[derive(Resource, Default)]
struct Heights {
    samples: Vec<Height>,
}

/// Appends every body's top at `time`, bodies in scene order.
fn sample<'a>(
    heights: &mut Heights,
    time: Real,
    bodies: impl Iterator<Item = (&'a BodyIndex, &'a MaterialPoints)>,
) {
    let first = heights.samples.len();
    heights.samples.extend(bodies.map(|(index, points)| {
        Height {
            time,
            body: index.0 as usize,
            top: points
                .position
                .iter()
                .map(|x| x.y)
                .fold(Real::MIN, Real::max),
        }
    }));
    heights.samples[first..].sort_unstable_by_key(|h| h.body);
}

/// Samples every body's top on the steps the engine samples its records.
fn record_heights(
    clock: Res<Clock>,
    sampling: Res<Sampling>,
    bodies: Query<(&BodyIndex, &MaterialPoints)>,
    mut heights: ResMut<Heights>,
) {
    if sampling.due(&clock) {
        sample(&mut heights, clock.time, bodies.iter());
    }
}

/// Checkpoints carry the samples.
impl Checkpointed for Heights {
    type Stored = Vec<Height>;

    fn stored(&self) -> Vec<Height> {
        self.samples.clone()
    }

    /// In place: the room reserved for the run stays.
    fn restore(&mut self, samples: Vec<Height>) {
        self.samples.clear();
        self.samples.extend(samples);
    }
}

/// A run stopped between samples sampled its last step; a resumed run
/// that does not sample there forgets it.
impl TimeRecord for Heights {
    fn forget_from(&mut self, time: Real) {
        self.samples.retain(|h| h.time < time);
    }
}

/// `heights.csv`: time (s), body, top (m).
impl CsvSeries for Heights {
    const HEADER: &'static str = "time,body,top";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(
        &self,
        k: usize,
        bodies: &[String],
        out: &mut dyn std::io::Write,
    ) -> std::io::Result<()> {
        let h = self.samples[k];
        writeln!(out, "{:e},{},{:e}", h.time, bodies[h.body], h.top)
    }
}

/// `heights.png`: each body's top against time.
fn heights_figure(heights: &Heights, context: &FigureContext) -> Vec<Figure> {
    let curves = context
        .bodies
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let of_body = heights.samples.iter().filter(move |h| h.body == k);
            Curve::new(name.as_str(), of_body.map(|h| (h.time, h.top)))
        })
        .collect();
    vec![Figure {
        file: "heights.png".into(),
        title: "Top of each body".into(),
        x_label: "time (s)".into(),
        y_label: "height (m)".into(),
        curves,
    }]
}

/// The field `rise` of the VTK frames: how far each point of a body has
/// risen above where it started (m).
fn rise(world: &World, body: Entity, column: &mut Vec<Real>) {
    if let Some(points) = world.get::<MaterialPoints>(body) {
        column.extend((0..points.len()).map(|p| points.displacement(p).y));
    }
}

/// The whole feature: its resource, its record, its figure, its field of
/// the frames and its system.
struct HeightsPlugin;

impl MpmPlugin for HeightsPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), mpdem::scene::SceneError> {
        // Room for the whole run's samples, and the first one, at t = 0.
        let bodies = setup.scene.bodies.len();
        let mut heights = Heights {
            samples: Vec::with_capacity(setup.samples_in_run() * bodies),
        };
        let mut query = setup.world.query::<(&BodyIndex, &MaterialPoints)>();
        sample(&mut heights, 0.0, query.iter(setup.world));
        setup.world.insert_resource(heights);
        setup.record::<Heights>("heights", "heights.csv");
        setup.plot::<Heights>(heights_figure);
        setup.point_field("rise", rise);
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems(record_heights.in_set(MpmSystems::Last));
    }
}

/// Runs `scene` with the plugin into `out`, from `start`, raising the stop
/// flag at step `stop_at` if given.
fn run(
    scene: &Scene,
    out: &std::path::Path,
    start: Start,
    stop_at: Option<u64>,
) -> Result<(), Box<dyn std::error::Error>> {
    let options = RunOptions {
        checkpoint_every: Some(scene.time.end),
        start,
        ..RunOptions::into_folder(out)
    };
    let mut runner = Runner::new(scene, None, options)?;
    runner.simulation_mut().add_plugin(&HeightsPlugin)?;
    let stop = AtomicBool::new(false);
    let result = runner.run(&stop, |p| {
        if stop_at.is_some_and(|s| p.step >= s) {
            stop.store(true, Ordering::SeqCst);
        }
    });
    match result {
        Ok(_) | Err(RunError::Stopped { .. }) => Ok(()),
        Err(e) => Err(e.into()),
    }
}

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/two_rings.ron");
    let mut scene = Scene::load(path.as_ref())?;
    scene.time.end = 200.0 * scene.time.dt;
    scene.output.probe_interval = Some(7.0 * scene.time.dt);
    let temp = std::env::temp_dir().join(format!("mpdem-example-heights-{}", std::process::id()));
    let (straight, stopped) = (temp.join("straight"), temp.join("stopped"));
    run(&scene, &straight, Start::Restart, None)?;
    run(&scene, &stopped, Start::Restart, Some(100))?;
    run(&scene, &stopped, Start::Resume, None)?;
    let read = |dir: &std::path::Path| std::fs::read_to_string(dir.join("heights.csv"));
    let (whole, resumed) = (read(&straight)?, read(&stopped)?);
    println!("{whole}");
    let frame = std::fs::read_to_string(straight.join("vtk/points_00000.vtu"))?;
    if !straight.join("heights.png").is_file() || !frame.contains(r#"Name="rise""#) {
        return Err("the figure and the frames' field are written".into());
    }
    std::fs::remove_dir_all(&temp)?;
    if whole != resumed {
        return Err("the resumed run's heights.csv differs from the straight run's".into());
    }
    Ok(())
}
