//! The `mpdem` command line: run, check and benchmark scenes, and verify
//! the engine against the paper's validation cases.

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mpdem::io::RunOutput;
use mpdem::resources::{StageLog, StagePlan};
use mpdem::scene::Scene;
use mpdem::verify::{CASES, Case, CaseReport, Context, RunEvent, Verdict};
use mpdem::{Simulation, bench, verify};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Material point method with DEM-enriched contact (2D, plane strain).
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene and write its results (VTK, CSV, PNG).
    Run {
        /// The RON scene file.
        scene: PathBuf,
        /// Output folder [default: out/<scene name>].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads [default: all cores]. Results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Write the run's state to OUT/checkpoint.bin every this many
        /// seconds of simulated time, and at the end.
        #[arg(long, value_name = "SECONDS")]
        checkpoint_every: Option<f64>,
        /// Carry on from OUT/checkpoint.bin, written by a run of the same
        /// scene (its time.end may have grown since), into the same folder.
        #[arg(long)]
        resume: bool,
    },
    /// Validate a scene without running it.
    Check {
        /// The RON scene file.
        scene: PathBuf,
    },
    /// Measure particle-updates per second on the standard elastic block, without and with a rigid ground contact.
    Bench {
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
    },
    /// Run the paper's validation cases at full size and measure each
    /// against its target (the table is also written to OUT/verify.csv).
    /// Exits with failure if a target is missed. All cases take about an
    /// hour on 2 cores.
    Verify {
        /// Cases to run, by name [default: all]; see --list.
        cases: Vec<String>,
        /// List the cases with their cost and stop.
        #[arg(long)]
        list: bool,
        /// Folder of the scene files.
        #[arg(long, default_value = "scenes")]
        scenes: PathBuf,
        /// Output folder for verify.csv and the cases' plots.
        #[arg(long, default_value = "out/verify")]
        out: PathBuf,
        /// Worker threads [default: all cores]. Results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            scene,
            out,
            threads,
            quiet,
            checkpoint_every,
            resume,
        } => with_threads(threads, || {
            let checkpoints = Checkpoints {
                every: checkpoint_every,
                resume,
            };
            run(&scene, out.as_deref(), quiet, checkpoints)
        }),
        Command::Check { scene } => check(&scene),
        Command::Bench {
            points,
            steps,
            threads,
            scene,
            warmup,
        } => with_threads(threads, || match scene {
            Some(path) => bench_scene(&path, warmup, steps),
            None => run_bench(points as usize, warmup, steps),
        }),
        Command::Verify {
            cases,
            list,
            scenes,
            out,
            threads,
            quiet,
        } => {
            if list {
                list_cases();
                Ok(())
            } else {
                with_threads(threads, || verify(&cases, &scenes, &out, quiet))
            }
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) if message.starts_with(STOPPED_BY_CTRL_C) => {
            eprintln!("{message}");
            ExitCode::from(130)
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Runs `f` on a rayon pool of `threads` workers (default: rayon's, one
/// per core or `RAYON_NUM_THREADS`). The step runs on one of the pool's
/// threads: work handed to the pool from outside it goes through a shared
/// queue that allocates, work from inside does not.
fn with_threads(
    threads: Option<usize>,
    f: impl FnOnce() -> Result<(), String> + Send,
) -> Result<(), String> {
    // The main thread's usual stack, 8 MiB, for the scene parsing and
    // stepping that now run on a worker (rayon's default is 2 MiB).
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(8 << 20);
    match threads {
        None => {}
        Some(0) => return Err("--threads must be at least 1".into()),
        Some(n) => pool = pool.num_threads(n),
    }
    pool.build()
        .map_err(|e| match threads {
            Some(n) => format!("cannot start {n} threads: {e}"),
            None => format!("cannot start the threads: {e}"),
        })?
        .install(f)
}

fn check(path: &Path) -> Result<(), String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let sim = Simulation::from_scene(&scene).map_err(|e| e.to_string())?;
    for w in sim.warnings() {
        eprintln!("warning: {w}");
    }
    let clock = sim.clock();
    let geometry = match scene.settings.geometry {
        mpdem::resources::Geometry::PlaneStrain => "plane strain",
        mpdem::resources::Geometry::Axisymmetric => "axisymmetric, per radian",
    };
    println!(
        "{}: ok ({geometry}; bodies: {}, steps: {} of {:e} s)",
        path.display(),
        scene.bodies.len(),
        clock.total_steps(),
        clock.dt
    );
    Ok(())
}

/// How the message of a run stopped by Ctrl-C starts; the process then
/// exits with status 130, as a shell reports an interrupted command.
const STOPPED_BY_CTRL_C: &str = "stopped by Ctrl-C";

/// The checkpoint's file name in the output folder.
const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// What `mpdem run` does with checkpoints.
struct Checkpoints {
    /// Simulated time between two checkpoints (s), if any are written.
    every: Option<f64>,
    /// Start from the output folder's checkpoint.
    resume: bool,
}

fn run(
    path: &Path,
    out: Option<&Path>,
    quiet: bool,
    checkpoints: Checkpoints,
) -> Result<(), String> {
    if checkpoints
        .every
        .is_some_and(|t| !(t.is_finite() && t > 0.0))
    {
        return Err("--checkpoint-every must be a positive time in seconds".into());
    }
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let dir = out.map_or_else(
        || Path::new("out").join(scene.display_name()),
        Path::to_path_buf,
    );
    let checkpoint = dir.join(CHECKPOINT_FILE);
    let mut sim = if checkpoints.resume {
        if !checkpoint.is_file() {
            return Err(format!(
                "--resume: no checkpoint at {}; a run writes one when given --checkpoint-every T",
                checkpoint.display()
            ));
        }
        Simulation::resume(&scene, &checkpoint).map_err(|e| e.to_string())?
    } else {
        Simulation::from_scene(&scene).map_err(|e| e.to_string())?
    };
    for w in sim.warnings() {
        eprintln!("warning: {w}");
    }
    let clock = sim.clock();
    if checkpoints.resume && clock.step > clock.total_steps() {
        return Err(format!(
            "{}: the checkpoint is at step {} (t = {:.6e} s), past the scene's end at step {} (time.end = {:e} s): nothing to run; give a later time.end to carry the run on",
            checkpoint.display(),
            clock.step,
            clock.time,
            clock.total_steps(),
            clock.end
        ));
    }
    let mut output = if checkpoints.resume {
        eprintln!(
            "resuming at step {} (t = {:.6e} s) from {}",
            clock.step,
            clock.time,
            checkpoint.display()
        );
        let (output, gaps) = RunOutput::resume(&dir, &scene, &sim, &checkpoint)
            .map_err(|e| format!("{}: cannot carry on the output: {e}", dir.display()))?;
        if let Some(gaps) = gaps {
            eprintln!("warning: {gaps}");
        }
        output
    } else {
        let (output, removed) = RunOutput::create(&dir, &scene, &mut sim)
            .map_err(|e| format!("cannot write the output: {e}"))?;
        if removed > 0 {
            eprintln!(
                "removed the {removed} files an earlier run wrote into {} (listed in its outputs.txt)",
                dir.display()
            );
        }
        output
    };
    let checkpoint_steps = checkpoints
        .every
        .map(|t| mpdem::scene::whole_steps(t, clock.dt));
    let total = clock.total_steps();
    let progress = progress_bar(total, quiet, "{bar:40} {msg} elapsed {elapsed} ETA {eta}");
    progress.set_position(clock.step);
    let (message, length) = progress_message(&sim, total);
    progress.set_length(length);
    progress.set_message(message);
    progress.reset_eta();
    let started = std::time::Instant::now();
    let interrupted = stop_on_ctrl_c();
    let mut failure = None;
    while !sim.clock().finished() {
        if let Err(e) = sim.step() {
            failure = Some(e.to_string());
            break;
        }
        let now = sim.clock();
        let at =
            |e: &dyn std::fmt::Display| format!("step {} (t = {:.6e} s): {e}", now.step, now.time);
        if let Err(e) = output.after_step(&mut sim) {
            failure = Some(format!("cannot write a frame at {}", at(&e)));
            break;
        }
        if checkpoint_steps.is_some_and(|n| now.step.is_multiple_of(n) || now.finished())
            && let Err(e) = sim.write_checkpoint(&checkpoint)
        {
            failure = Some(format!("cannot write the checkpoint at {}", at(&e)));
            break;
        }
        if interrupted.load(Ordering::SeqCst) {
            break;
        }
        if now.step % 64 == 0 || now.finished() {
            // The message carries the step with its time (the bar's own
            // position may be drawn a refresh apart from the message).
            progress.set_position(now.step);
            let (message, length) = progress_message(&sim, total);
            progress.set_length(length);
            progress.set_message(message);
        }
    }
    progress.finish_and_clear();
    for w in &sim.world().resource::<StageLog>().warnings {
        eprintln!("warning: {w}");
    }
    if let Err(e) = output.finish(&mut sim, failure.is_some()) {
        let written = format!("cannot write the output: {e}");
        return Err(match failure {
            Some(f) => format!("{f}\n{written}"),
            None => written,
        });
    }
    if let Some(message) = failure {
        return Err(format!(
            "{message}\nresults up to the failure are in {}",
            dir.display()
        ));
    }
    let now = sim.clock();
    if !now.finished() {
        let resume = if checkpoint_steps.is_some() {
            match sim.write_checkpoint(&checkpoint) {
                Ok(()) => "; `--resume` carries it on".to_string(),
                Err(e) => format!("; the checkpoint could not be written: {e}"),
            }
        } else {
            String::new()
        };
        return Err(format!(
            "{STOPPED_BY_CTRL_C} at step {} (t = {:.6e} s); results up to there are in {}{resume}",
            now.step,
            now.time,
            dir.display()
        ));
    }
    let hash = sim.state_hash();
    println!(
        "{}: {} steps to t = {:.6} s in {:.1} s; state hash {hash:016x}; results in {}",
        sim.name(),
        now.step,
        now.time,
        started.elapsed().as_secs_f64(),
        output.dir().display()
    );
    Ok(())
}

/// A flag a first Ctrl-C raises, so that the run stops after its step and
/// writes its results (and a checkpoint, if it writes them); a second
/// Ctrl-C ends the process at once, as without the handler.
fn stop_on_ctrl_c() -> Arc<AtomicBool> {
    let interrupted = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&interrupted);
    let handler = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
    if let Err(e) = handler {
        eprintln!("warning: Ctrl-C will end the run without writing its results: {e}");
    }
    interrupted
}

/// A progress bar on stderr drawn with `template` (indicatif's), hidden
/// with `quiet`.
fn progress_bar(total: u64, quiet: bool, template: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let style =
        ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}

fn bench_scene(path: &Path, warmup: u64, steps: u64) -> Result<(), String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let mut runs = vec![("", scene.clone())];
    if !scene.body_contacts.is_empty() {
        let mut without = scene;
        without.body_contacts.clear();
        runs.push((" without body contacts", without));
    }
    for (label, scene) in runs {
        let mut sim = Simulation::from_scene(&scene).map_err(|e| e.to_string())?;
        let t = bench::measure(&mut sim, warmup, steps).map_err(|e| e.to_string())?;
        println!(
            "{}{label}: {} points, {} steps after {warmup}, {}: {:.3} s, {:.2} M particle-updates/s",
            sim.name(),
            t.points,
            t.steps,
            bench::threads_label(),
            t.seconds,
            t.updates_per_second() / 1e6
        );
    }
    Ok(())
}

/// The progress bar's message and length: the step of the run's `total`
/// steps, the time and the stage in progress. With stages the run may end
/// before `time.end`: the length is then the most steps the stages can
/// take (each at its `Duration` or `max_time`), within `total`.
fn progress_message(sim: &Simulation, total: u64) -> (String, u64) {
    let clock = sim.clock();
    let Some((name, cap)) = sim.world().get_resource::<StagePlan>().and_then(|plan| {
        let stages = &plan.scene.stages;
        let current = stages.get(plan.progress.current)?;
        // The latest the stages can end: the current one's start and every
        // stage from it at its longest.
        let started = (plan.progress.started / clock.dt).round() as u64;
        let latest = stages[plan.progress.current..]
            .iter()
            .fold(started, |steps, s| {
                steps.saturating_add(s.end.most_steps(clock.dt))
            });
        let cap = latest.clamp(clock.step, total);
        Some((current.name.clone(), cap))
    }) else {
        let message = format!("step {}/{total} t = {:.4e} s", clock.step, clock.time);
        return (message, total);
    };
    let message = format!(
        "step {}/at most {cap} t = {:.4e} s, stage '{name}'",
        clock.step, clock.time
    );
    (message, cap)
}

fn run_bench(points: usize, warmup: u64, steps: u64) -> Result<(), String> {
    let scenes = [
        (
            "elastic block on the grid's fixed base",
            bench::elastic_block_scene(points),
        ),
        (
            "elastic block on a rigid ground (DEM contact)",
            bench::elastic_block_on_ground_scene(points),
        ),
    ];
    let mut rates = Vec::new();
    for (label, scene) in scenes {
        let mut sim = Simulation::from_scene(&scene).map_err(|e| e.to_string())?;
        let t = bench::measure(&mut sim, warmup, steps).map_err(|e| e.to_string())?;
        println!(
            "{label}: {} points, {} steps, {}: {:.3} s, {:.2} M particle-updates/s",
            t.points,
            t.steps,
            bench::threads_label(),
            t.seconds,
            t.updates_per_second() / 1e6
        );
        rates.push(t.seconds / t.steps as f64);
    }
    println!(
        "contact adds {:+.1}% to the step",
        100.0 * (rates[1] / rates[0] - 1.0)
    );
    Ok(())
}

fn list_cases() {
    let width = |f: fn(&Case) -> &str| CASES.iter().map(|c| f(c).chars().count()).max();
    let name = width(|c| c.name).unwrap_or(0);
    let source = width(|c| c.source).unwrap_or(0);
    for case in CASES {
        println!(
            "{:<name$} {:<source$} ~{:>4.1} min  {}",
            case.name, case.source, case.minutes, case.about
        );
    }
}

fn verify(names: &[String], scenes: &Path, out: &Path, quiet: bool) -> Result<(), String> {
    let cases = if names.is_empty() {
        CASES.iter().collect()
    } else {
        names
            .iter()
            .map(|name| {
                verify::case(name).ok_or_else(|| {
                    let known: Vec<&str> = CASES.iter().map(|c| c.name).collect();
                    format!("no case '{name}'; the cases are {}", known.join(", "))
                })
            })
            .collect::<Result<Vec<_>, _>>()?
    };
    if !scenes.is_dir() {
        return Err(format!(
            "no scenes folder at {}: run from the repository's root or pass --scenes",
            scenes.display()
        ));
    }
    let table = out.join("verify.csv");
    let progress = progress_bar(
        0,
        quiet,
        "{bar:40} step {pos}/{len} {msg} elapsed {elapsed} ETA {eta}",
    );
    let observe = |event: RunEvent| match event {
        RunEvent::Started { run, steps } => {
            // reset() also brings back a bar finished and cleared by the
            // previous case, and restarts its clock.
            progress.reset();
            progress.set_length(steps);
            progress.set_message(run.to_string());
        }
        RunEvent::Stepped { step } => progress.set_position(step),
    };
    let ctx = Context::new(scenes, out, &observe);
    let mut reports = Vec::new();
    for case in cases {
        let minutes = case.minutes;
        eprintln!(
            "{} ({}): {}, about {minutes} min",
            case.name, case.source, case.about
        );
        let report = CaseReport::run(case, &ctx);
        progress.finish_and_clear();
        print!("{report}");
        reports.push(report);
        verify::write_table(&table, &reports)
            .map_err(|e| format!("{}: cannot write the table: {e}", table.display()))?;
    }
    let count = |verdict| {
        reports
            .iter()
            .flat_map(|r| r.checks())
            .filter(|c| c.verdict == verdict)
            .count()
    };
    let failed: Vec<&str> = reports
        .iter()
        .filter(|r| r.outcome.is_err())
        .map(|r| r.case)
        .collect();
    let missed = count(Verdict::Missed);
    println!(
        "verify: {} cases; {} checks met, {missed} missed, {} reported; {} cases could not be measured; table in {}",
        reports.len(),
        count(Verdict::Met),
        count(Verdict::Reported),
        failed.len(),
        table.display()
    );
    let mut problems = Vec::new();
    if missed > 0 {
        problems.push(format!("{missed} checks missed their target"));
    }
    if !failed.is_empty() {
        problems.push(format!(
            "these cases could not be run: {}",
            failed.join(", ")
        ));
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems.join("; "))
    }
}
