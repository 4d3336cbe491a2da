//! `mpdem bench`: particle-updates per second on the standard elastic
//! block, or on a scene.

use crate::console::{say, with_threads};
use crate::failure::Failure;
use mpdem::Simulation;
use mpdem::scene::Scene;
use mpdem_verify::bench;
use std::path::{Path, PathBuf};

/// The arguments of `mpdem bench`.
#[derive(clap::Args)]
pub struct BenchArgs {
    /// Number of material points (approximate: the block is square), at
    /// least 100.
    #[arg(long, default_value_t = 40_000, value_parser = clap::value_parser!(u64).range(100..))]
    points: u64,
    /// Timed steps, at least 1.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..))]
    steps: u64,
    /// Worker threads [default: all cores].
    #[arg(long)]
    threads: Option<usize>,
    /// Time this scene instead of the standard block; a scene with body
    /// contact laws is also timed without them, for the cost of contact.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Untimed steps before the timed ones, e.g. to reach the contact
    /// phase of a scene (the default sizes every buffer).
    #[arg(long, default_value_t = 5)]
    warmup: u64,
    /// Timings of the standard blocks, taken in turn; the median and
    /// the spread (slowest less fastest, over the median) are reported
    /// [default: 5; not with --scene].
    #[arg(long, conflicts_with = "scene", value_parser = clap::value_parser!(u64).range(1..))]
    repeats: Option<u64>,
    /// Also report the wall-clock time of each set of the step, per
    /// step and as a share of the timed steps.
    #[arg(long)]
    by_set: bool,
}

/// Times the scene asked for, or the standard blocks.
pub fn bench(args: BenchArgs) -> Result<(), Failure> {
    let timing = BenchTiming {
        warmup: args.warmup,
        steps: args.steps,
        by_set: args.by_set,
    };
    with_threads(args.threads, || match &args.scene {
        Some(path) => bench_scene(path, timing),
        None => bench_blocks(
            args.points as usize,
            timing,
            args.repeats.unwrap_or(5) as usize,
        ),
    })
}

/// How a bench times its runs.
#[derive(Clone, Copy)]
struct BenchTiming {
    /// Untimed steps first.
    warmup: u64,
    /// Timed steps.
    steps: u64,
    /// Also time each set of the step.
    by_set: bool,
}

/// Steps `sim` through the warm-up, then starts the set timer if asked.
fn warm_up(sim: &mut Simulation, timing: BenchTiming) -> Result<(), Failure> {
    bench::measure(sim, timing.warmup, 0)?;
    if timing.by_set {
        bench::start_set_timer(sim)?;
    }
    Ok(())
}

/// The set timer's table for `sim`, over timed steps that took `seconds`
/// in all; nothing if the timer is off.
fn say_set_times(sim: &mut Simulation, steps: u64, seconds: f64) -> Result<(), Failure> {
    let sets = bench::take_set_seconds(sim);
    if sets.is_empty() {
        return Ok(());
    }
    let row = |label: &str, s: f64| {
        let (per_step, share) = (1e3 * s / steps as f64, 100.0 * s / seconds);
        say(&format!(
            "  {label:<16} {per_step:>9.3} ms/step {share:>5.1}%"
        ))
    };
    for (set, s) in &sets {
        row(&format!("{set:?}"), *s)?;
    }
    row(
        "between sets",
        seconds - sets.iter().map(|(_, s)| s).sum::<f64>(),
    )
}

fn bench_scene(path: &Path, timing: BenchTiming) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    let mut runs = vec![("", scene.clone())];
    if !scene.body_contacts.is_empty() {
        let mut without = scene;
        without.body_contacts.clear();
        runs.push((" without body contacts", without));
    }
    for (label, scene) in runs {
        let mut sim = Simulation::from_scene(&scene)?;
        warm_up(&mut sim, timing)?;
        let t = bench::measure(&mut sim, 0, timing.steps)?;
        say(&format!(
            "{}{label}: {} points, {} steps after {}, {}: {:.3} s, {:.2} M particle-updates/s",
            sim.name(),
            t.points,
            t.steps,
            timing.warmup,
            bench::threads_label(),
            t.seconds,
            t.updates_per_second() / 1e6
        ))?;
        say_set_times(&mut sim, t.steps, t.seconds)?;
    }
    Ok(())
}

fn bench_blocks(points: usize, timing: BenchTiming, repeats: usize) -> Result<(), Failure> {
    let steps = timing.steps;
    let labels = [
        "elastic block on the grid's fixed base",
        "elastic block on a rigid ground (DEM contact)",
    ];
    let scenes = [
        bench::elastic_block_scene(points),
        bench::elastic_block_on_ground_scene(points),
    ];
    let mut sims = Vec::new();
    for scene in &scenes {
        let mut sim = Simulation::from_scene(scene)?;
        warm_up(&mut sim, timing)?;
        sims.push(sim);
    }
    let timings = bench::time_in_turn(&mut sims, steps, repeats)?;
    for (k, (label, (points, seconds))) in labels.iter().zip(&timings).enumerate() {
        let (median, spread) = bench::median_and_spread(seconds);
        say(&format!(
            "{label}: {points} points, {steps} steps, {}: median of {repeats} {median:.3} s, {:.2} M particle-updates/s, spread {:.1}%",
            bench::threads_label(),
            (*points as f64 * steps as f64) / median / 1e6,
            100.0 * spread,
        ))?;
        let all_steps = steps * repeats as u64;
        say_set_times(&mut sims[k], all_steps, seconds.iter().sum())?;
    }
    let ratios: Vec<f64> = timings[1]
        .1
        .iter()
        .zip(&timings[0].1)
        .map(|(with, without)| with / without - 1.0)
        .collect();
    let (median, _) = bench::median_and_spread(&ratios);
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
            (lo.min(*r), hi.max(*r))
        });
    say(&format!(
        "contact adds {:+.1}% to the step (median of {repeats}; {:+.1}% to {:+.1}%)",
        100.0 * median,
        100.0 * lo,
        100.0 * hi
    ))?;
    Ok(())
}
