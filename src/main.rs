//! The `mpdem` command line: run, check and benchmark scenes, and verify
//! the engine against the paper's validation cases.

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mpdem::StepError;
use mpdem::runner::{Progress, RunError, RunOptions, Runner, Start};
use mpdem::scene::{Scene, SceneError};
use mpdem::verify::{CASES, Case, CaseReport, Context, RunEvent, Verdict};
use mpdem::{Simulation, bench, verify};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Material point method with DEM-enriched contact (2D: plane strain or
/// axisymmetric).
///
/// Exit status: 0 when the command did what it was asked; 1 on an error
/// (a refused scene, a failed run, an output that cannot be written; the
/// message says which); 2 on a command line it cannot read; 130 when a
/// run was stopped by Ctrl-C, SIGTERM or SIGHUP (its results up to the
/// stop are written). A closed standard output (`mpdem run ... | head`)
/// drops what is printed and changes no status.
#[derive(Parser)]
#[command(version, about, long_about)]
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
        /// scene (its time.end may have grown since), into the same folder;
        /// the checkpoint is kept current at a stop and at the end.
        #[arg(long, conflicts_with = "restart")]
        resume: bool,
        /// Start over in a folder that holds a checkpoint, removing it (a
        /// run into such a folder is refused without --resume or --restart).
        #[arg(long)]
        restart: bool,
        /// Write into a folder that another scene file's run wrote,
        /// replacing its results, or that holds files no mpdem run wrote
        /// (both refused otherwise).
        #[arg(long)]
        overwrite: bool,
    },
    /// Validate scenes without running them (each is checked; the status
    /// is 1 if any is refused).
    Check {
        /// The RON scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
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
        /// Timings of the standard blocks, taken in turn; the median and
        /// the spread (slowest less fastest, over the median) are reported
        /// [default: 5; not with --scene].
        #[arg(long, conflicts_with = "scene", value_parser = clap::value_parser!(u64).range(1..))]
        repeats: Option<u64>,
        /// Also report the wall-clock time of each set of the step, per
        /// step and as a share of the timed steps.
        #[arg(long)]
        by_set: bool,
    },
    /// Run the paper's validation cases at full size and measure each
    /// against its target (the table is also written to OUT/verify.csv;
    /// with --report, a Markdown report with figures too). Exits with
    /// failure if a target is missed. All cases take about an hour and a half on 2
    /// cores.
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
        /// Also write DIR/verification.md, the cases' checks as a Markdown
        /// report, and a figure per case of its computed curves against
        /// their references in DIR/verification/ (e.g. --report docs/).
        #[arg(long, value_name = "DIR")]
        report: Option<PathBuf>,
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
            restart,
            overwrite,
        } => with_threads(threads, || {
            let start = match (resume, restart) {
                (true, _) => Start::Resume,
                (false, true) => Start::Restart,
                (false, false) => Start::Fresh,
            };
            let request = RunRequest {
                out: out.as_deref(),
                quiet,
                checkpoint_every,
                start,
                overwrite,
            };
            run(&scene, request)
        }),
        Command::Check { scenes } => check_all(&scenes),
        Command::Bench {
            points,
            steps,
            threads,
            scene,
            warmup,
            repeats,
            by_set,
        } => with_threads(threads, || {
            let timing = BenchTiming {
                warmup,
                steps,
                by_set,
            };
            match scene {
                Some(path) => bench_scene(&path, timing),
                None => run_bench(points as usize, timing, repeats.unwrap_or(5) as usize),
            }
        }),
        Command::Verify {
            cases,
            list,
            scenes,
            out,
            threads,
            quiet,
            report,
        } => {
            if list {
                list_cases()
            } else {
                let places = VerifyPlaces {
                    scenes: &scenes,
                    out: &out,
                    report: report.as_deref(),
                };
                with_threads(threads, || verify(&cases, places, quiet))
            }
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(stopped @ Failure::Run(RunError::Stopped { .. })) => {
            say_err(&stopped.to_string());
            ExitCode::from(STOPPED_STATUS)
        }
        Err(failure) => {
            say_err(&format!("error: {failure}"));
            ExitCode::FAILURE
        }
    }
}

/// The exit status of a run stopped by a signal, as a shell reports a
/// command interrupted by Ctrl-C.
const STOPPED_STATUS: u8 = 130;

/// Why a command did not succeed.
#[derive(Debug, thiserror::Error)]
enum Failure {
    /// Writing to standard output failed (not a closed pipe).
    #[error("cannot write to standard output: {0}")]
    Stdout(std::io::Error),
    /// `--threads 0`.
    #[error("--threads must be at least 1")]
    NoThreads,
    /// The thread pool could not be started.
    #[error("cannot start {}: {source}", threads.map_or("the threads".to_string(), |n| format!("{n} threads")))]
    Threads {
        /// The threads asked for.
        threads: Option<usize>,
        /// What failed.
        source: rayon::ThreadPoolBuildError,
    },
    /// A scene could not be read or built.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A step failed.
    #[error(transparent)]
    Step(#[from] StepError),
    /// A run failed, or stopped on request with its results written.
    #[error(transparent)]
    Run(#[from] RunError),
    /// Of several scenes checked, some were refused (each told before).
    #[error("{refused} of {checked} scenes refused")]
    Refused {
        /// How many were refused.
        refused: usize,
        /// How many were checked.
        checked: usize,
    },
    /// `mpdem verify` was asked for a case it does not have.
    #[error("no case '{name}'; the cases are {}", CASES.iter().map(|c| c.name).collect::<Vec<_>>().join(", "))]
    UnknownCase {
        /// The name asked for.
        name: String,
    },
    /// No scenes folder where `verify` looks.
    #[error("no scenes folder at {}: run from the repository's root or pass --scenes", .0.display())]
    NoScenes(PathBuf),
    /// The verify table could not be written.
    #[error("{}: cannot write the table: {source}", path.display())]
    VerifyTable {
        /// The table.
        path: PathBuf,
        /// What failed.
        source: std::io::Error,
    },
    /// The verify report could not be written.
    #[error("cannot write the report: {0}")]
    Report(#[from] verify::report::ReportError),
    /// Verify cases missed their targets or could not be run.
    #[error("{}", verify_problems(*missed, failed))]
    Verify {
        /// Checks that missed their target.
        missed: usize,
        /// Cases that could not be run.
        failed: Vec<String>,
    },
}

/// What a verify run that did not pass says of itself.
fn verify_problems(missed: usize, failed: &[String]) -> String {
    let mut problems = Vec::new();
    if missed > 0 {
        let checks = mpdem::verify::report::counted(missed, "check");
        let target = if missed == 1 {
            "its target"
        } else {
            "their targets"
        };
        problems.push(format!("{checks} missed {target}"));
    }
    if !failed.is_empty() {
        problems.push(format!(
            "these cases could not be run: {}",
            failed.join(", ")
        ));
    }
    problems.join("; ")
}

/// Prints a line on standard output. A closed pipe (`| head`) drops it;
/// any other failure (a full disk) is an error.
fn say(line: &str) -> Result<(), Failure> {
    match writeln!(std::io::stdout(), "{line}") {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::Stdout(e)),
        _ => Ok(()),
    }
}

/// Prints a line on standard error; a failure there has nowhere to be
/// told, so it is dropped.
fn say_err(line: &str) {
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// Runs `f` on a rayon pool of `threads` workers (default: rayon's, one
/// per core or `RAYON_NUM_THREADS`). The step runs on one of the pool's
/// threads: work handed to the pool from outside it goes through a shared
/// queue that allocates, work from inside does not.
fn with_threads(
    threads: Option<usize>,
    f: impl FnOnce() -> Result<(), Failure> + Send,
) -> Result<(), Failure> {
    // The main thread's usual stack, 8 MiB, for the scene parsing and
    // stepping that now run on a worker (rayon's default is 2 MiB).
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(8 << 20);
    match threads {
        None => {}
        Some(0) => return Err(Failure::NoThreads),
        Some(n) => pool = pool.num_threads(n),
    }
    pool.build()
        .map_err(|source| Failure::Threads { threads, source })?
        .install(f)
}

/// Checks every scene, reporting each accepted one as it comes; an error
/// if any is refused: a single scene's refusal, or, of several, each
/// refusal printed and their count.
fn check_all(paths: &[PathBuf]) -> Result<(), Failure> {
    let mut refused = Vec::new();
    for path in paths {
        if let Err(failure) = check(path) {
            refused.push(failure);
        }
    }
    match refused.pop() {
        None => Ok(()),
        Some(last) if paths.len() == 1 => Err(last),
        Some(last) => {
            for failure in refused.iter().chain([&last]) {
                say_err(&format!("error: {failure}"));
            }
            Err(Failure::Refused {
                refused: refused.len() + 1,
                checked: paths.len(),
            })
        }
    }
}

fn check(path: &Path) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    let sim = Simulation::from_scene(&scene)?;
    // Named by file: `check` may be given several scenes.
    for w in sim.warnings() {
        say_err(&format!("warning: {}: {w}", path.display()));
    }
    let clock = sim.clock();
    let geometry = match scene.settings.geometry {
        mpdem::resources::Geometry::PlaneStrain => "plane strain",
        mpdem::resources::Geometry::Axisymmetric => "axisymmetric, per radian",
    };
    say(&format!(
        "{}: ok ({geometry}; bodies: {}, steps: {} of {:e} s)",
        path.display(),
        scene.bodies.len(),
        clock.total_steps(),
        clock.dt
    ))?;
    Ok(())
}

/// How often a run whose standard error is not a terminal (a log file, a
/// batch system) prints a progress line.
const LOG_PROGRESS_EVERY: Duration = Duration::from_secs(15);

/// What `mpdem run` was asked to do besides the scene.
struct RunRequest<'a> {
    out: Option<&'a Path>,
    quiet: bool,
    checkpoint_every: Option<f64>,
    start: Start,
    overwrite: bool,
}

fn run(path: &Path, request: RunRequest) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    let out = request.out.map_or_else(
        || Path::new("out").join(scene.display_name()),
        Path::to_path_buf,
    );
    let options = RunOptions {
        out,
        checkpoint_every: request.checkpoint_every,
        start: request.start,
        replace_other_scene: request.overwrite,
    };
    let mut runner = Runner::new(&scene, Some(path), options)?;
    for w in runner.warnings() {
        say_err(&format!("warning: {w}"));
    }
    let stop = stop_on_signals();
    let bar = progress_bar(
        0,
        request.quiet,
        "{bar:40} {msg} elapsed {elapsed} ETA {eta}",
    );
    let log_lines = !request.quiet && !std::io::stderr().is_terminal();
    let mut last_line: Option<Instant> = None;
    // The latest report not yet logged, logged when the run ends.
    let mut unlogged: Option<String> = None;
    let mut notices_shown = 0;
    let result = runner.run(&stop, |p| {
        let stage = p.stage.map_or(String::new(), |s| format!(", stage '{s}'"));
        let of = match p.stage {
            Some(_) => format!("at most {}", p.length),
            None => p.length.to_string(),
        };
        notices_shown += p.notices.len();
        for line in p
            .notices
            .iter()
            .cloned()
            .chain(p.warnings.iter().map(|w| format!("warning: {w}")))
        {
            bar.suspend(|| say_err(&line));
        }
        let message = if p.writing_results {
            format!(
                "step {}/{of} t = {:.4e} s: writing the results",
                p.step, p.time
            )
        } else {
            format!("step {}/{of} t = {:.4e} s{stage}", p.step, p.time)
        };
        bar.set_length(p.length);
        bar.set_position(p.step);
        if p.step == p.first_step {
            // A resumed run starts far along: its pace counts from here.
            bar.reset_eta();
        }
        bar.set_message(message.clone());
        let line = format!(
            "{message}, elapsed {}, ETA {}",
            clock_time(p.elapsed),
            eta(p)
                .filter(|_| !p.writing_results)
                .map_or("-".into(), clock_time)
        );
        let due = last_line.is_none_or(|t| t.elapsed() >= LOG_PROGRESS_EVERY);
        if log_lines && (due || p.step >= p.length || p.writing_results) {
            last_line = Some(Instant::now());
            say_err(&line);
            unlogged = None;
        } else {
            unlogged = Some(line);
        }
    });
    bar.finish_and_clear();
    if let Some(line) = unlogged.filter(|_| log_lines) {
        say_err(&line);
    }
    for notice in &runner.notices()[notices_shown..] {
        say_err(notice);
    }
    match result {
        Ok(summary) => say(&format!(
            "{}: {} steps to t = {:.6} s in {:.1} s; state hash {:016x}; results in {}",
            summary.name,
            summary.steps,
            summary.time,
            summary.elapsed.as_secs_f64(),
            summary.state_hash,
            summary.dir.display()
        )),
        Err(e) => Err(e.into()),
    }
}

/// The time left at the run's mean pace so far, once it has one.
fn eta(p: &Progress) -> Option<Duration> {
    let taken = p.step.saturating_sub(p.first_step);
    (taken > 0 && p.length > p.step)
        .then(|| p.elapsed.mul_f64((p.length - p.step) as f64 / taken as f64))
}

/// A duration as h:mm:ss.
fn clock_time(d: Duration) -> String {
    let s = d.as_secs();
    format!("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
}

/// How long after a stop signal another one counts as the same request:
/// `timeout` and job control send a signal to the process and to its
/// group at once, so one request can arrive twice within microseconds.
const SIGNAL_REPEAT_WINDOW: Duration = Duration::from_secs(1);

/// A flag the first Ctrl-C, SIGTERM or SIGHUP raises, so that the run
/// stops after its step and writes its results (and a checkpoint, if it
/// writes them); another one, [`SIGNAL_REPEAT_WINDOW`] or more after the
/// first, ends the process at once.
fn stop_on_signals() -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let mut first: Option<Instant> = None;
    let handler = ctrlc::set_handler(move || {
        flag.store(true, Ordering::SeqCst);
        match first {
            None => {
                first = Some(Instant::now());
                say_err(
                    "stop requested: the run stops after its step and writes its results (another stop signal a second or more from now ends it at once, without them)",
                );
            }
            Some(at) if at.elapsed() >= SIGNAL_REPEAT_WINDOW => {
                say_err("second stop signal: exiting now, without the results not yet written");
                std::process::exit(STOPPED_STATUS.into());
            }
            Some(_) => {}
        }
    });
    if let Err(e) = handler {
        say_err(&format!(
            "warning: a stop signal will end the run without writing its results: {e}"
        ));
    }
    stop
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

fn run_bench(points: usize, timing: BenchTiming, repeats: usize) -> Result<(), Failure> {
    let steps = timing.steps;
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
    let mut sims = Vec::new();
    for (_, scene) in &scenes {
        let mut sim = Simulation::from_scene(scene)?;
        warm_up(&mut sim, timing)?;
        sims.push(sim);
    }
    // The two blocks are timed in turn, so that a slow spell of the machine
    // falls on both; each goes on from where its last timing left it.
    let mut seconds = [Vec::new(), Vec::new()];
    let mut points_of = [0; 2];
    for _ in 0..repeats {
        for (k, sim) in sims.iter_mut().enumerate() {
            let t = bench::measure(sim, 0, steps)?;
            points_of[k] = t.points;
            seconds[k].push(t.seconds);
        }
    }
    for (k, (label, _)) in scenes.iter().enumerate() {
        let (median, spread) = median_and_spread(&seconds[k]);
        say(&format!(
            "{label}: {} points, {steps} steps, {}: median of {repeats} {median:.3} s, {:.2} M particle-updates/s, spread {:.1}%",
            points_of[k],
            bench::threads_label(),
            (points_of[k] as f64 * steps as f64) / median / 1e6,
            100.0 * spread,
        ))?;
        let all_steps = steps * repeats as u64;
        say_set_times(&mut sims[k], all_steps, seconds[k].iter().sum())?;
    }
    let ratios: Vec<f64> = seconds[1]
        .iter()
        .zip(&seconds[0])
        .map(|(with, without)| with / without - 1.0)
        .collect();
    let (median, _) = median_and_spread(&ratios);
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

/// The median of `values`, and their spread: the largest less the
/// smallest, over the median.
fn median_and_spread(values: &[f64]) -> (f64, f64) {
    let mut sorted = values.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    let n = sorted.len();
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    };
    let spread = (sorted[n - 1] - sorted[0]) / median.abs().max(f64::MIN_POSITIVE);
    (median, spread)
}

fn list_cases() -> Result<(), Failure> {
    let width = |f: fn(&Case) -> &str| CASES.iter().map(|c| f(c).chars().count()).max();
    let name = width(|c| c.name).unwrap_or(0);
    let source = width(|c| c.source).unwrap_or(0);
    for case in CASES {
        say(&format!(
            "{:<name$} {:<source$} ~{:>4.1} min  {}",
            case.name, case.source, case.minutes, case.about
        ))?;
    }
    Ok(())
}

/// Where `mpdem verify` reads its scenes and writes its table and report.
#[derive(Clone, Copy)]
struct VerifyPlaces<'a> {
    scenes: &'a Path,
    out: &'a Path,
    report: Option<&'a Path>,
}

/// The `mpdem verify` command line that reproduces a report: the cases
/// named, the scenes folder if not the default, and the report's folder.
fn verify_command(names: &[String], scenes: &Path, report: &Path) -> String {
    let mut command = vec!["mpdem verify".to_string()];
    command.extend(names.iter().cloned());
    if scenes != Path::new("scenes") {
        command.push(format!("--scenes {}", scenes.display()));
    }
    command.push(format!("--report {}", report.display()));
    command.join(" ")
}

fn verify(names: &[String], places: VerifyPlaces, quiet: bool) -> Result<(), Failure> {
    let VerifyPlaces {
        scenes,
        out,
        report: report_dir,
    } = places;
    let cases = if names.is_empty() {
        CASES.iter().collect()
    } else {
        names
            .iter()
            .map(|name| verify::case(name).ok_or(Failure::UnknownCase { name: name.clone() }))
            .collect::<Result<Vec<_>, _>>()?
    };
    if !scenes.is_dir() {
        return Err(Failure::NoScenes(scenes.to_path_buf()));
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
        say_err(&format!(
            "{} ({}): {}, about {minutes} min",
            case.name, case.source, case.about
        ));
        let report = CaseReport::run(case, &ctx);
        progress.finish_and_clear();
        say(report.to_string().trim_end_matches('\n'))?;
        reports.push(report);
        verify::write_table(&table, &reports).map_err(|source| Failure::VerifyTable {
            path: table.clone(),
            source,
        })?;
        if let Some(dir) = report_dir {
            verify::report::write_report(dir, &verify_command(names, scenes, dir), &reports)?;
        }
    }
    if let Some(dir) = report_dir {
        say(&format!(
            "verify: report in {}",
            dir.join("verification.md").display()
        ))?;
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
    let counted = mpdem::verify::report::counted;
    say(&format!(
        "verify: {}; {} met, {missed} missed, {} reported; {} could not be measured; table in {}",
        counted(reports.len(), "case"),
        counted(count(Verdict::Met), "check"),
        count(Verdict::Reported),
        counted(failed.len(), "case"),
        table.display()
    ))?;
    if missed == 0 && failed.is_empty() {
        Ok(())
    } else {
        Err(Failure::Verify {
            missed,
            failed: failed.into_iter().map(String::from).collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_resumed_runs_eta_counts_its_own_steps_only() {
        // Resumed at step 900 of 2000: 100 steps in 10 s leave 1000 steps,
        // 100 s; counting the checkpoint's 900 steps too would say 11 s.
        let p = Progress {
            step: 1000,
            first_step: 900,
            length: 2000,
            time: 0.1,
            stage: None,
            elapsed: Duration::from_secs(10),
            notices: &[],
            warnings: &[],
            writing_results: false,
        };
        assert_eq!(eta(&p), Some(Duration::from_secs(100)));
        // Nothing taken yet: no pace.
        let at_start = Progress { step: 900, ..p };
        assert_eq!(eta(&at_start), None);
    }
}
