//! `mpdem run`: run a scene and write its results, with progress on a
//! terminal or as log lines.

use crate::console::{progress_bar, say, say_err, say_warning, with_threads};
use crate::failure::Failure;
use crate::signals::stop_on_signals;
use mpdem::runner::{Progress, RunOptions, Runner, Start};
use mpdem::scene::Scene;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The arguments of `mpdem run`.
#[derive(clap::Args)]
pub struct RunArgs {
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
}

/// Runs the scene on the threads asked for; `over_mpi`, over the ranks of
/// the MPI job this process belongs to (the `mpi` feature).
pub fn run(args: RunArgs, over_mpi: bool) -> Result<(), Failure> {
    let start = match (args.resume, args.restart) {
        (true, _) => Start::Resume,
        (false, true) => Start::Restart,
        (false, false) => Start::Fresh,
    };
    let request = RunRequest {
        out: args.out.as_deref(),
        quiet: args.quiet,
        checkpoint_every: args.checkpoint_every,
        start,
        overwrite: args.overwrite,
        over_mpi,
    };
    with_threads(args.threads, || run_scene(&args.scene, request))
}

const LOG_PROGRESS_EVERY: Duration = Duration::from_secs(15);

/// What `mpdem run` was asked to do besides the scene.
struct RunRequest<'a> {
    out: Option<&'a Path>,
    quiet: bool,
    checkpoint_every: Option<f64>,
    start: Start,
    overwrite: bool,
    over_mpi: bool,
}

fn run_scene(path: &Path, request: RunRequest) -> Result<(), Failure> {
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
        say_warning(path, w);
    }
    #[cfg(feature = "mpi")]
    let transport = request.over_mpi.then(crate::mpi_job::join);
    #[cfg(not(feature = "mpi"))]
    let transport = None;
    let signals = stop_on_signals(request.over_mpi);
    runner.interrupt_steps_on(signals.cut_short);
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
    let report = |p: &Progress| {
        let stage = p.stage.map_or(String::new(), |s| format!(", stage '{s}'"));
        let of = match p.stage {
            Some(_) => format!("at most {}", p.length),
            None => p.length.to_string(),
        };
        notices_shown += p.notices.len();
        for notice in p.notices {
            bar.suspend(|| say_err(notice));
        }
        for w in p.warnings {
            bar.suspend(|| say_warning(path, w));
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
    };
    let result = match transport {
        Some(transport) => runner.run_distributed(transport, &signals.stop, report),
        None => runner.run(&signals.stop, report),
    };
    bar.finish_and_clear();
    if let Some(line) = unlogged.filter(|_| log_lines) {
        say_err(&line);
    }
    for w in runner.stage_warnings() {
        say_warning(path, w);
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
