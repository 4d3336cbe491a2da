//! Runs a scene to its end with everything a run writes: the frames and
//! CSV series as it goes, checkpoints, the plots at the end, and a clean
//! stop on request.
//!
//! ```no_run
//! use mpdem::runner::{RunOptions, Runner};
//! use std::sync::atomic::AtomicBool;
//!
//! let path = std::path::Path::new("scenes/wave_1d.ron");
//! let scene = mpdem::scene::Scene::load(path)?;
//! let mut runner = Runner::new(&scene, Some(path), RunOptions::into_folder("out/wave_1d"))?;
//! let summary = runner.run(&AtomicBool::new(false), |_| {})?;
//! println!("state hash {:016x}", summary.state_hash);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::checkpoint::CheckpointError;
use crate::distributed::{
    DistributeError, Domain, Transport, attach, unsupported_parts, with_all_points,
};
use crate::io::RunOutput;
pub use crate::io::manifest::SceneOrigin;
use crate::io::manifest::written_by;
use crate::math::Real;
use crate::plugins::DefaultPlugins;
use crate::resources::{EnergyLog, EnergySample, StageLog, StagePlan};
use crate::scene::{Scene, SceneError, whole_steps};
use crate::simulation::{PluginError, Simulation, StepError};
use crate::warning::Warning;
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// The checkpoint's file name in the output folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// The file whose lock a run holds while it writes into its output folder,
/// so that a second run into the same folder is refused instead of mixing
/// its files with the first's. It is empty; the system releases the lock
/// when the run's process ends, however it ends.
pub const LOCK_FILE: &str = ".mpdem.lock";

/// How long a step may run on after a stop request before a front end cuts
/// it short (see [`Runner::interrupt_steps_on`]): a step of milliseconds
/// ends well within it, with its checkpoint; a step of seconds is cut
/// short, so that a stop is honoured within a second.
pub const STOP_GRACE: Duration = Duration::from_millis(500);

/// What to do with a checkpoint in the output folder.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Start {
    /// Start at the scene's beginning; a checkpoint in the folder refuses
    /// the run, so that a mistaken rerun cannot replace it.
    #[default]
    Fresh,
    /// Carry on from the folder's checkpoint.
    Resume,
    /// Start at the beginning and remove the folder's checkpoint.
    Restart,
}

/// How a run writes its results.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The output folder.
    pub out: PathBuf,
    /// Simulated time between checkpoints (s). Without it a fresh run
    /// writes none, and a resumed run writes its checkpoint only at a stop
    /// and at the end.
    pub checkpoint_every: Option<Real>,
    /// What to do with a checkpoint in the folder.
    pub start: Start,
    /// Clear a folder that another scene file's run wrote, or write into
    /// one holding files no mpdem run wrote (both refused otherwise).
    pub replace_other_scene: bool,
}

impl RunOptions {
    /// A fresh run into `out`, without checkpoints.
    pub fn into_folder(out: impl Into<PathBuf>) -> Self {
        Self {
            out: out.into(),
            checkpoint_every: None,
            start: Start::Fresh,
            replace_other_scene: false,
        }
    }
}

/// Why a run did not reach its end.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The scene could not be built.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// The plugins asked for cannot make a simulation.
    #[error("{0}")]
    Plugins(PluginError),
    /// The checkpoint could not be read or written.
    #[error("{0}")]
    Checkpoint(#[from] CheckpointError),
    /// The checkpoint interval is not a positive time.
    #[error("the checkpoint interval must be a positive time in seconds, got {0}")]
    CheckpointInterval(Real),
    /// `Start::Resume` without a checkpoint in the folder.
    #[error(
        "no checkpoint at {}: a run writes one when given a checkpoint interval (--checkpoint-every T)",
        .0.display()
    )]
    NoCheckpoint(PathBuf),
    /// A fresh run into a folder holding a checkpoint.
    #[error(
        "{} holds a checkpoint of an earlier run: --resume carries that run on; --restart starts over and removes it",
        .0.display()
    )]
    CheckpointInTheWay(PathBuf),
    /// Another run is writing into the output folder.
    #[error(
        "{} is being written by another run, which holds its lock ({LOCK_FILE}): wait for that run to end, or choose another folder (--out)",
        .0.display()
    )]
    FolderInUse(PathBuf),
    /// The folder holds files that no mpdem run listed as its own.
    #[error(
        "{} holds files that no mpdem run wrote (such as {}), which a run could overwrite: choose another folder (--out), or --overwrite to write into it anyway",
        dir.display(),
        example.display()
    )]
    ForeignFolder {
        /// The output folder.
        dir: PathBuf,
        /// One of its entries.
        example: PathBuf,
    },
    /// The folder holds a symbolic link, which the run would write through,
    /// outside the folder.
    #[error(
        "{} is a symbolic link: a run writes only inside its output folder, and would write through it; remove it, or choose another folder (--out)",
        .0.display()
    )]
    SymbolicLink(PathBuf),
    /// The folder holds the results of another scene's run.
    #[error(
        "{} holds the results of {theirs}, not of {ours}: choose another folder (--out), or --overwrite to replace them",
        dir.display()
    )]
    OtherScenesFolder {
        /// The output folder.
        dir: PathBuf,
        /// The scene whose run wrote it.
        theirs: SceneOrigin,
        /// The scene of this run.
        ours: SceneOrigin,
    },
    /// The checkpoint is at or past the run's end: its scene's end, or
    /// where its last stage ended it.
    #[error(
        "{}: the checkpoint is at step {step} (t = {time:.6e} s), where the run has ended (the scene's end is step {end_step}, time.end = {end:e} s, unless its last stage ended it sooner): nothing to run, and the outputs are left as they are; give a later time.end to carry on a run that time.end ended",
        path.display()
    )]
    PastTheEnd {
        /// The checkpoint.
        path: PathBuf,
        /// Its step and time.
        step: u64,
        /// Its time (s).
        time: Real,
        /// The scene's last step.
        end_step: u64,
        /// The scene's end time (s).
        end: Real,
    },
    /// Writing the results failed.
    #[error("cannot write the output: {0}")]
    Output(std::io::Error),
    /// The scene cannot run distributed, or its distributed step could not
    /// be set up.
    #[error("{0}")]
    Distribute(#[from] DistributeError),
    /// Another process of a distributed run failed, and says why.
    #[error("rank {rank} of the distributed run failed (its message says why)")]
    OnAnotherRank {
        /// The first rank that failed.
        rank: usize,
    },
    /// [`Runner::run`] was called a second time.
    #[error("this runner has run: build a new one (with Start::Resume to carry the run on)")]
    RanAlready,
    /// A step failed (a numerical breakdown, an output that could not be
    /// written mid-run); the results up to it are written.
    #[error("{message}\nresults up to the failure are in {}", dir.display())]
    Failed {
        /// What failed, at which step.
        message: String,
        /// The output folder.
        dir: PathBuf,
    },
    /// The run was asked to stop; the results up to the step it stopped at
    /// are written (and a checkpoint, if the run writes them).
    #[error(
        "stopped at step {step} (t = {time:.6e} s); results up to there are in {}{}",
        dir.display(),
        match checkpoint {
            Some(Ok(())) => "; `--resume` carries it on".to_string(),
            Some(Err(e)) => format!("; the checkpoint could not be written: {e}"),
            None => String::new(),
        }
    )]
    Stopped {
        /// The last step taken.
        step: u64,
        /// Its time (s).
        time: Real,
        /// The output folder.
        dir: PathBuf,
        /// Whether a checkpoint was written at the stop, if the run writes
        /// them.
        checkpoint: Option<Result<(), Box<CheckpointError>>>,
    },
    /// The run was asked to stop, and its step in progress was cut short
    /// (see [`Runner::interrupt_steps_on`]); the results up to the last
    /// whole step are written, without a checkpoint of the half-updated
    /// state.
    #[error(
        "stopped inside step {}, which was cut short; results up to step {step} (t = {time:.6e} s) are in {}; {}",
        step + 1,
        dir.display(),
        match checkpoint {
            Some(at) => format!("the checkpoint of step {at} stays current, and `--resume` carries on from it"),
            None => "no checkpoint was written".to_string(),
        }
    )]
    CutShort {
        /// The last whole step.
        step: u64,
        /// Its time (s).
        time: Real,
        /// The output folder.
        dir: PathBuf,
        /// The step of the folder's checkpoint, if it holds one.
        checkpoint: Option<u64>,
    },
}

/// Where a run is, as reported to its progress callback.
#[derive(Clone, Debug)]
pub struct Progress<'a> {
    /// Steps taken.
    pub step: u64,
    /// The step this run started from: 0, or the checkpoint's step after a
    /// resume (the pace of the run counts the steps from it).
    pub first_step: u64,
    /// The most steps the run can take: the scene's, or fewer when stages
    /// may end it before `time.end` (each at its `Duration` or `max_time`).
    pub length: u64,
    /// Simulated time (s).
    pub time: Real,
    /// The stage in progress, if the scene has stages.
    pub stage: Option<&'a str>,
    /// Wall time since the run started.
    pub elapsed: Duration,
    /// What the run says as it opens its output, with the first report:
    /// where it resumed, the files of an earlier run it removed, gaps in
    /// resumed frames (see [`Runner::notices`]); empty afterwards.
    pub notices: &'a [String],
    /// Warnings the run found while stepping since the last report (see
    /// [`Simulation::step_warnings`]); a new one brings a report forward.
    pub warnings: &'a [Warning],
    /// Whether the stepping is over and the run is writing its results (the
    /// last frame, the collections, the CSV files, the plots and the
    /// animation), which can take a while: the last report.
    pub writing_results: bool,
}

/// What a finished run reached.
#[derive(Clone, Debug)]
pub struct RunSummary {
    /// The scene's name.
    pub name: String,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time reached (s).
    pub time: Real,
    /// The final state's hash (see [`Simulation::state_hash`]).
    pub state_hash: u64,
    /// Wall time of the run.
    pub elapsed: Duration,
    /// The output folder.
    pub dir: PathBuf,
}

/// A scene's run and its output folder. Build it with [`Runner::new`], add
/// user systems through [`Runner::simulation_mut`], then [`Runner::run`].
pub struct Runner {
    scene: Scene,
    source: Option<PathBuf>,
    options: RunOptions,
    sim: Simulation,
    notices: Vec<String>,
    /// Whether `run` was called: a runner runs once.
    ran: bool,
    /// The request that cuts a step short (see [`Runner::interrupt_steps_on`]).
    interrupt: Option<Arc<AtomicBool>>,
}

impl Runner {
    /// Builds the scene's simulation for a run into `options.out`, after
    /// checking that the run may write there: a fresh run refuses a folder
    /// holding a checkpoint, and any folder another scene file's run
    /// wrote or holding files no mpdem run wrote (unless
    /// `replace_other_scene`); a resumed run needs the checkpoint. `source` is the scene's file, if it has one. Nothing is
    /// written yet.
    pub fn new(
        scene: &Scene,
        source: Option<&Path>,
        options: RunOptions,
    ) -> Result<Self, RunError> {
        Self::with_plugins(scene, source, options, DefaultPlugins::default())
    }

    /// As [`Runner::new`], with the built-in plugins changed as `plugins`
    /// says (see [`Simulation::with_plugins`]).
    pub fn with_plugins(
        scene: &Scene,
        source: Option<&Path>,
        mut options: RunOptions,
        plugins: DefaultPlugins,
    ) -> Result<Self, RunError> {
        if options.out.as_os_str().is_empty() {
            // An empty folder name is the current folder, with its checks.
            options.out = PathBuf::from(".");
        }
        if let Some(t) = options.checkpoint_every
            && !(t.is_finite() && t > 0.0)
        {
            return Err(RunError::CheckpointInterval(t));
        }
        let checkpoint = options.out.join(CHECKPOINT_FILE);
        match options.start {
            Start::Fresh if checkpoint.exists() => {
                return Err(RunError::CheckpointInTheWay(checkpoint));
            }
            Start::Resume if !checkpoint.is_file() => {
                return Err(RunError::NoCheckpoint(checkpoint));
            }
            _ => {}
        }
        let source = source.map(|path| {
            std::fs::canonicalize(path)
                .or_else(|_| std::path::absolute(path))
                .unwrap_or(path.to_path_buf())
        });
        if options.start != Start::Resume && !options.replace_other_scene {
            // A scene without a file is told apart by its name.
            let ours = SceneOrigin::of(scene, source.as_deref());
            if let Some(theirs) = written_by(&options.out).map_err(RunError::Output)?
                && theirs != ours
            {
                return Err(RunError::OtherScenesFolder {
                    dir: options.out.clone(),
                    theirs,
                    ours,
                });
            }
            if let Some(example) = foreign_entry(&options.out).map_err(RunError::Output)? {
                return Err(RunError::ForeignFolder {
                    dir: options.out.clone(),
                    example,
                });
            }
        }
        if let Some(link) = symbolic_link_in(&options.out).map_err(RunError::Output)? {
            return Err(RunError::SymbolicLink(link));
        }
        let sim = match Simulation::with_plugins(scene, plugins) {
            Ok(sim) => sim,
            Err(PluginError::Build(e)) => return Err(e.into()),
            Err(e) => return Err(RunError::Plugins(e)),
        };
        Ok(Self {
            scene: scene.clone(),
            notices: checkpoint_notices(options.checkpoint_every, sim.clock().dt),
            source,
            options,
            sim,
            ran: false,
            interrupt: None,
        })
    }

    /// The simulation, to add user systems or register the state they keep
    /// in checkpoints before the run.
    pub fn simulation_mut(&mut self) -> &mut Simulation {
        &mut self.sim
    }

    /// The simulation.
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }

    /// The scene's warnings (see [`Simulation::warnings`]).
    pub fn warnings(&self) -> &[Warning] {
        self.sim.warnings()
    }

    /// What the run has to say besides its warnings: where it resumed, the
    /// files of an earlier run it removed, gaps in resumed frames, the
    /// bodies still moving at the end.
    pub fn notices(&self) -> &[String] {
        &self.notices
    }

    /// The stages' warnings of the run, once it has ended: a stage that
    /// reached its max_time, or that time.end cut short.
    pub fn stage_warnings(&self) -> &[Warning] {
        self.sim
            .world()
            .get_resource::<StageLog>()
            .map_or(&[], |log| &log.warnings)
    }

    /// The output folder.
    pub fn dir(&self) -> &Path {
        &self.options.out
    }

    /// Makes the run cut its step in progress short once `request` is
    /// raised, instead of finishing it (see
    /// [`Simulation::interrupt_steps_on`]): for a stop that cannot wait
    /// for a long step. The run then ends with [`RunError::CutShort`].
    pub fn interrupt_steps_on(&mut self, request: Arc<AtomicBool>) {
        self.interrupt = Some(request);
    }

    /// Runs to the scene's end, or until `stop` is raised (after the step
    /// in progress), writing the results; calls `progress` every 64 steps
    /// and at the end. It holds the folder's lock ([`LOCK_FILE`]) from the
    /// start, and is refused while another run holds it.
    pub fn run(
        &mut self,
        stop: &AtomicBool,
        progress: impl FnMut(&Progress),
    ) -> Result<RunSummary, RunError> {
        self.run_over(None, stop, progress)
    }

    /// As [`Runner::run`], as this process's part of a distributed run over
    /// `transport` (see [`crate::distributed`]): every process of the job
    /// builds its runner alike and runs it with this. Rank 0 alone locks
    /// and writes the output folder, from every process's points gathered,
    /// and its files are the ones a run on one process writes; a stop
    /// raised on any process stops every one after the same step; every
    /// process returns the same summary, or an error (a process whose
    /// error another one found returns [`RunError::OnAnotherRank`]). A
    /// distributed run is not cut short inside a step (its processes wait
    /// for each other's messages): [`Runner::interrupt_steps_on`] is
    /// ignored. A scene the distributed step does not cover is refused.
    /// Rank 0 writes nothing until every process has called this, so that
    /// no process's runner checks a folder rank 0 is writing.
    pub fn run_distributed(
        &mut self,
        transport: Box<dyn Transport>,
        stop: &AtomicBool,
        progress: impl FnMut(&Progress),
    ) -> Result<RunSummary, RunError> {
        let unsupported = unsupported_parts(&self.scene);
        if !unsupported.is_empty() {
            return Err(DistributeError::Unsupported(unsupported).into());
        }
        transport.all_gather(Vec::new());
        self.run_over(Some(transport), stop, progress)
    }

    /// The run, on one process or over `transport`.
    fn run_over(
        &mut self,
        transport: Option<Box<dyn Transport>>,
        stop: &AtomicBool,
        mut progress: impl FnMut(&Progress),
    ) -> Result<RunSummary, RunError> {
        if std::mem::replace(&mut self.ran, true) {
            return Err(RunError::RanAlready);
        }
        let started = Instant::now();
        let dir = self.options.out.clone();
        let checkpoint = dir.join(CHECKPOINT_FILE);
        // Rank 0 of a distributed run writes, as one process does.
        let writes = transport.as_ref().is_none_or(|t| t.rank() == 0);
        let opened = if writes {
            // The lock is held until the run returns.
            lock_folder(&dir)
                .and_then(|lock| Ok((Some(lock), Some(self.open_output(&checkpoint)?))))
        } else if self.options.start == Start::Resume {
            self.sim
                .restore_checkpoint(&self.scene, &checkpoint)
                .map(|()| (None, None))
                .map_err(RunError::from)
        } else {
            Ok((None, None))
        };
        let (_lock, mut output) = match transport {
            Some(transport) => {
                let flag = u8::from(opened.is_err());
                let failed_on = first_raised(&transport.all_gather(vec![flag]), 1);
                let opened = match failed_on {
                    Some(rank) if opened.is_ok() => Err(RunError::OnAnotherRank { rank }),
                    _ => opened,
                }?;
                attach(&mut self.sim, transport)?;
                opened
            }
            None => {
                let opened = opened?;
                if let Some(request) = &self.interrupt {
                    self.sim.interrupt_steps_on(Arc::clone(request));
                }
                opened
            }
        };
        let sim = &mut self.sim;
        let frame_every = crate::io::output::frame_every(&self.scene, sim);
        let clock = sim.clock();
        let checkpoint_steps = self
            .options
            .checkpoint_every
            .map(|t| whole_steps(t, clock.dt));
        // A resumed run keeps its folder's checkpoint current, at a stop
        // and at the end, also without an interval.
        let keeps_checkpoint = checkpoint_steps.is_some() || self.options.start == Start::Resume;
        let total = clock.total_steps();
        let first_step = clock.step;
        // Step warnings already reported; the opening's notices go with
        // the first report.
        let reported = Cell::new(0);
        let opening = Cell::new(&self.notices[..]);
        let report =
            |sim: &Simulation, writing_results: bool, progress: &mut dyn FnMut(&Progress)| {
                let clock = sim.clock();
                let (stage, length) = stage_and_length(sim, total);
                let notices = opening.take();
                let warnings = &sim.step_warnings()[reported.get()..];
                reported.set(reported.get() + warnings.len());
                progress(&Progress {
                    step: clock.step,
                    first_step,
                    length,
                    time: clock.time,
                    stage,
                    elapsed: started.elapsed(),
                    notices,
                    warnings,
                    writing_results,
                });
            };
        report(sim, false, &mut progress);
        let mut failure = None;
        // The step of the folder's current checkpoint.
        let mut checkpoint_at = (self.options.start == Start::Resume).then_some(first_step);
        while !sim.clock().finished() {
            match sim.step() {
                Ok(()) => {}
                // `sim.cut_short()` tells it from here on.
                Err(StepError::Interrupted(_)) => break,
                Err(e) => {
                    failure = Some(e.to_string());
                    break;
                }
            }
            let now = sim.clock();
            let at = |e: &dyn std::fmt::Display| {
                format!("step {} (t = {:.6e} s): {e}", now.step, now.time)
            };
            // A frame reads every process's points.
            let written = with_points(sim, now.step.is_multiple_of(frame_every), |sim| {
                output.as_mut().map_or(Ok(()), |o| o.after_step(sim))
            });
            if let Err(e) = written {
                failure = Some(format!("cannot write the output at {}", at(&e)));
            }
            let due = checkpoint_steps.is_some_and(|n| now.step.is_multiple_of(n));
            if failure.is_none() && (due || (keeps_checkpoint && now.finished())) {
                let written = with_points(sim, true, |sim| sim.write_checkpoint(&checkpoint));
                match written {
                    Ok(()) => checkpoint_at = Some(now.step),
                    Err(e) => failure = Some(format!("cannot write the checkpoint at {}", at(&e))),
                }
            }
            // Every process of a distributed run stops after the same step.
            let mut raised = 0;
            if failure.is_some() {
                raised |= FAILED;
            }
            if stop.load(Ordering::SeqCst) {
                raised |= STOP;
            }
            let (raised, failed_on) = raised_on_any_rank(sim, raised);
            if failure.is_none()
                && let Some(rank) = failed_on
            {
                failure = Some(RunError::OnAnotherRank { rank }.to_string());
            }
            if failure.is_some() || raised & STOP != 0 {
                break;
            }
            if now.step.is_multiple_of(64)
                || now.finished()
                || sim.step_warnings().len() > reported.get()
            {
                report(sim, false, &mut progress);
            }
        }
        report(sim, true, &mut progress);
        // A stopped run's checkpoint first: it matters more than the plots.
        let now = sim.clock();
        let cut_short = sim.cut_short();
        let stopped = failure.is_none() && !now.finished();
        let stop_checkpoint = (stopped && keeps_checkpoint && !cut_short).then(|| {
            with_points(sim, true, |sim| sim.write_checkpoint(&checkpoint)).map_err(Box::new)
        });
        let failed = failure.is_some() || cut_short;
        let finished = with_points(sim, true, |sim| {
            output.as_mut().map_or(Ok(()), |o| o.finish(sim, failed))
        });
        // Rank 0's writing is the job's.
        let finished = match (
            raised_on_any_rank(sim, u8::from(finished.is_err()) * FAILED),
            finished,
        ) {
            ((_, Some(rank)), Ok(())) if failure.is_none() => Err(std::io::Error::other(
                RunError::OnAnotherRank { rank }.to_string(),
            )),
            (_, finished) => finished,
        };
        if let Err(e) = finished {
            let written = format!("cannot write the output: {e}");
            let message = match failure {
                Some(f) => format!("{f}\n{written}"),
                None => written,
            };
            return Err(RunError::Failed { message, dir });
        }
        if let Some(message) = failure {
            return Err(RunError::Failed { message, dir });
        }
        if cut_short {
            return Err(RunError::CutShort {
                step: now.step,
                time: now.time,
                dir,
                checkpoint: checkpoint_at,
            });
        }
        if stopped {
            return Err(RunError::Stopped {
                step: now.step,
                time: now.time,
                dir,
                checkpoint: stop_checkpoint,
            });
        }
        if let Some(energy) = sim.world().get_resource::<EnergyLog>() {
            self.notices.extend(still_moving_notice(&energy.samples));
        }
        Ok(RunSummary {
            name: sim.name().to_owned(),
            steps: now.step,
            time: now.time,
            state_hash: state_hash_of_all_points(sim),
            elapsed: started.elapsed(),
            dir,
        })
    }

    /// Restores the checkpoint when resuming (and removes it when
    /// restarting), then opens the output folder.
    fn open_output(&mut self, checkpoint: &Path) -> Result<RunOutput, RunError> {
        let Self {
            scene,
            source,
            options,
            sim,
            notices,
            ..
        } = self;
        let dir = &options.out;
        match options.start {
            Start::Resume => {
                sim.restore_checkpoint(scene, checkpoint)?;
                let clock = sim.clock();
                if clock.finished() {
                    let end = scene.time.end;
                    return Err(RunError::PastTheEnd {
                        path: checkpoint.to_path_buf(),
                        step: clock.step,
                        time: clock.time,
                        end_step: (end / clock.dt).round() as u64,
                        end,
                    });
                }
                notices.push(format!(
                    "resuming at step {} (t = {:.6e} s) from {}",
                    clock.step,
                    clock.time,
                    checkpoint.display()
                ));
                let (output, gaps) =
                    RunOutput::resume(dir, scene, sim, checkpoint).map_err(|e| {
                        RunError::Output(std::io::Error::new(
                            e.kind(),
                            format!("{}: cannot carry on the output: {e}", dir.display()),
                        ))
                    })?;
                notices.extend(gaps);
                Ok(output)
            }
            Start::Fresh | Start::Restart => {
                // The checkpoint goes only once the new run's folder is open.
                let (output, removed) = RunOutput::create(dir, scene, source.as_deref(), sim)
                    .map_err(RunError::Output)?;
                if options.start == Start::Restart && checkpoint.exists() {
                    std::fs::remove_file(checkpoint)
                        .map_err(|e| RunError::Output(crate::files::located(checkpoint, e)))?;
                }
                if removed > 0 {
                    notices.push(format!(
                        "removed the {removed} files an earlier run wrote into {} (listed in its outputs.txt)",
                        dir.display()
                    ));
                }
                Ok(output)
            }
        }
    }
}

/// Raised after a step by a process whose run stops there.
const STOP: u8 = 1;
/// Raised after a step by a process that failed in it.
const FAILED: u8 = 2;

/// Runs `f` with every point of the run when `all_points` (in a
/// distributed run, on rank 0 with every process's points gathered, and
/// the other processes return `Ok`), or else with this process's points.
fn with_points<E>(
    sim: &mut Simulation,
    all_points: bool,
    f: impl FnOnce(&mut Simulation) -> Result<(), E>,
) -> Result<(), E> {
    if all_points {
        with_all_points(sim, f).unwrap_or(Ok(()))
    } else {
        f(sim)
    }
}

/// The bits `raised` by any process of a distributed run (every process
/// calls it), and the first rank that raised [`FAILED`]; on one process,
/// `raised` and no rank.
fn raised_on_any_rank(sim: &Simulation, raised: u8) -> (u8, Option<usize>) {
    let Some(domain) = sim.world().get_non_send::<Domain>() else {
        return (raised, None);
    };
    let all = domain.transport().all_gather(vec![raised]);
    let any = all.iter().fold(0, |any, bits| any | bits[0]);
    (any, first_raised(&all, FAILED))
}

/// The first rank whose one byte in `all` has `bit` raised.
fn first_raised(all: &[Vec<u8>], bit: u8) -> Option<usize> {
    all.iter().position(|bits| bits[0] & bit != 0)
}

/// The state hash of every point of the run (in a distributed run, formed
/// on rank 0 and sent to every process).
fn state_hash_of_all_points(sim: &mut Simulation) -> u64 {
    let hash = with_all_points(sim, Simulation::state_hash);
    let Some(domain) = sim.world().get_non_send::<Domain>() else {
        return hash.expect("one process hashes its own state");
    };
    let bytes = hash.map_or(Vec::new(), |h| h.to_le_bytes().to_vec());
    let all = domain.transport().all_gather(bytes);
    u64::from_le_bytes(all[0][..].try_into().expect("rank 0 sends 8 bytes"))
}

/// Share of its peak that the kinetic energy, averaged over the last tenth
/// of a run, must pass for the run to be said to end in motion.
const STILL_MOVING: Real = 0.1;

/// A note when the bodies have not come to rest at the run's end (the
/// kinetic energy of the last tenth of the run, averaged over the energy
/// record's samples, above [`STILL_MOVING`] of its peak): an undamped
/// static problem ends at some moment of its oscillation, and its last
/// frame and samples are not its state of rest.
fn still_moving_notice(samples: &[EnergySample]) -> Option<String> {
    let peak = samples.iter().map(|s| s.kinetic).fold(0.0, Real::max);
    let end = samples.last()?.time;
    let last: Vec<Real> = samples
        .iter()
        .filter(|s| s.time >= 0.9 * end)
        .map(|s| s.kinetic)
        .collect();
    let mean = last.iter().sum::<Real>() / last.len() as Real;
    (peak > 0.0 && mean > STILL_MOVING * peak).then(|| {
        format!(
            "note: the bodies are still moving at the end: over the last tenth of the run their kinetic energy averaged {:.0}% of its peak, so the last frame and samples are a moment of the motion, not a state of rest (damping, or a longer run, settles a static problem)",
            100.0 * mean / peak
        )
    })
}

/// A warning when checkpoints `every` this interval would be written at
/// every step of `dt`, which slows a run many times over.
fn checkpoint_notices(every: Option<Real>, dt: Real) -> Vec<String> {
    every
        .filter(|&t| t < dt)
        .map(|t| {
            format!(
                "warning: the checkpoint interval {t:e} s is shorter than the time step {dt:e} s: a checkpoint is written at every step, which slows the run"
            )
        })
        .into_iter()
        .collect()
}

/// Creates the output folder `dir` if need be and takes its lock
/// ([`LOCK_FILE`]), refusing the run if another run holds it.
fn lock_folder(dir: &Path) -> Result<std::fs::File, RunError> {
    std::fs::create_dir_all(dir).map_err(|e| RunError::Output(crate::files::located(dir, e)))?;
    let path = dir.join(LOCK_FILE);
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|e| RunError::Output(crate::files::located(&path, e)))?;
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(std::fs::TryLockError::WouldBlock) => Err(RunError::FolderInUse(dir.to_path_buf())),
        Err(std::fs::TryLockError::Error(e)) => {
            Err(RunError::Output(crate::files::located(&path, e)))
        }
    }
}

/// An entry of the folder `dir` that no mpdem run wrote: any entry but the
/// lock, when the folder has no list of a run's outputs
/// ([`crate::io::manifest::MANIFEST_FILE`]). None for a missing or empty
/// folder, or one a run wrote.
fn foreign_entry(dir: &Path) -> std::io::Result<Option<PathBuf>> {
    use crate::io::manifest::MANIFEST_FILE;
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(crate::files::located(dir, e)),
    };
    if dir.join(MANIFEST_FILE).exists() {
        return Ok(None);
    }
    for entry in entries {
        let entry = entry.map_err(|e| crate::files::located(dir, e))?;
        if entry.file_name() != LOCK_FILE {
            return Ok(Some(entry.path()));
        }
    }
    Ok(None)
}

/// The first symbolic link in the output folder `dir` or its `vtk/`, the
/// folders a run writes into (the folder itself may be one: the user
/// chose it).
fn symbolic_link_in(dir: &Path) -> std::io::Result<Option<PathBuf>> {
    for folder in [dir.to_path_buf(), dir.join("vtk")] {
        let entries = match std::fs::read_dir(&folder) {
            Ok(entries) => entries,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) if e.kind() == std::io::ErrorKind::NotADirectory => continue,
            Err(e) => return Err(crate::files::located(&folder, e)),
        };
        for entry in entries {
            let entry = entry.map_err(|e| crate::files::located(&folder, e))?;
            let kind = entry
                .file_type()
                .map_err(|e| crate::files::located(&entry.path(), e))?;
            if kind.is_symlink() {
                return Ok(Some(entry.path()));
            }
        }
    }
    Ok(None)
}

/// The stage in progress and the most steps the run can take: the
/// scene's `total`, or with stages the current one's start and every stage
/// from it at its longest (each at its `Duration` or `max_time`), within
/// `total`.
fn stage_and_length(sim: &Simulation, total: u64) -> (Option<&str>, u64) {
    let clock = sim.clock();
    let Some(plan) = sim.world().get_resource::<StagePlan>() else {
        return (None, total);
    };
    let stages = &plan.stages;
    let Some(current) = stages.get(plan.progress.current) else {
        return (None, total);
    };
    let started = (plan.progress.started / clock.dt).round() as u64;
    let latest = stages[plan.progress.current..]
        .iter()
        .fold(started, |steps, s| {
            steps.saturating_add(s.end.most_steps(clock.dt))
        });
    (Some(current.name.as_str()), latest.clamp(clock.step, total))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Samples every 0.01 s to 1 s of a kinetic energy `kinetic(t)`.
    fn samples(kinetic: impl Fn(Real) -> Real) -> Vec<EnergySample> {
        (0..=100)
            .map(|k| {
                let time = 0.01 * k as Real;
                EnergySample {
                    time,
                    kinetic: kinetic(time),
                    strain: 0.0,
                    contact: 0.0,
                    gravity: 0.0,
                    inelastic: 0.0,
                    loads: 0.0,
                    blocks: 0.0,
                    dissipated: 0.0,
                    damped: 0.0,
                }
            })
            .collect()
    }

    /// An undamped oscillation ends in motion (over 0.9–1 s its kinetic
    /// energy sin²(20 t) averages 32% of its peak, at the samples); one
    /// damped to 1% of its peak by the end does not, nor does a run that
    /// never moved.
    #[test]
    fn a_run_that_ends_in_motion_is_noted() {
        let undamped = samples(|t| (20.0 * t).sin().powi(2));
        let note = still_moving_notice(&undamped).expect("a note");
        assert!(note.contains("averaged 32% of its peak"), "{note}");
        let damped = samples(|t| (-4.6 * t).exp() * (20.0 * t).sin().powi(2));
        assert_eq!(still_moving_notice(&damped), None);
        assert_eq!(still_moving_notice(&samples(|_| 0.0)), None);
        assert_eq!(still_moving_notice(&[]), None);
    }
}
