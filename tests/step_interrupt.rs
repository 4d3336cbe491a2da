//! A step cut short on request: it skips its remaining sets, the
//! simulation refuses further steps and checkpoints, and a run so stopped
//! keeps its last whole checkpoint, from which a resumed run ends exactly
//! as a run that was never stopped.

mod common;

use mpdem::checkpoint::CheckpointError;
use mpdem::prelude::*;
use mpdem::resources::EnergyLog;
use mpdem::runner::{CHECKPOINT_FILE, RunError, RunOptions, Runner, Start};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The sets a spy saw, with the clock's step.
#[derive(Resource, Default)]
struct Seen(Vec<(&'static str, u64)>);

fn spy(label: &'static str) -> impl FnMut(Res<Clock>, ResMut<Seen>) {
    move |clock, mut seen| seen.0.push((label, clock.step))
}

/// A user system in the contact set that raises `request` during step
/// `at` (counted from 1), as a stop signal arriving mid-step would.
fn raise_during_step(
    request: Arc<AtomicBool>,
    at: u64,
) -> impl FnMut(Res<Clock>) + Send + Sync + 'static {
    move |clock| {
        if clock.step + 1 == at {
            request.store(true, Ordering::SeqCst);
        }
    }
}

fn short_sliding_block() -> Scene {
    let mut scene = common::load_scene("sliding_45.ron");
    scene.time.end = 0.003; // 30 steps
    scene
}

#[test]
fn a_step_cut_short_skips_its_remaining_sets_and_is_the_last() {
    let mut sim = Simulation::from_scene(&short_sliding_block()).unwrap();
    let request = Arc::new(AtomicBool::new(false));
    sim.interrupt_steps_on(Arc::clone(&request));
    sim.world_mut().init_resource::<Seen>();
    sim.add_systems(raise_during_step(Arc::clone(&request), 3).in_set(MpmSystems::Contact))
        .unwrap();
    sim.add_systems(spy("stress").in_set(MpmSystems::StressUpdate))
        .unwrap();
    sim.add_systems(spy("last").in_set(MpmSystems::Last))
        .unwrap();
    sim.step().unwrap();
    sim.step().unwrap();
    let samples = sim.world().resource::<EnergyLog>().samples.len();
    let error = sim.step().unwrap_err();
    assert!(matches!(error, StepError::Interrupted(3)), "{error}");
    // The request came in the contact set: the sets after it did not run,
    // nor did the diagnostics (the clock stays at the last whole step).
    let seen = &sim.world().resource::<Seen>().0;
    assert_eq!(
        seen,
        &[("stress", 0), ("last", 1), ("stress", 1), ("last", 2)]
    );
    assert_eq!(sim.clock().step, 2);
    assert_eq!(sim.world().resource::<EnergyLog>().samples.len(), samples);
    assert!(sim.cut_short());
    // No further step, and no checkpoint of the half-updated state.
    assert!(matches!(sim.step(), Err(StepError::Interrupted(3))));
    assert_eq!(sim.clock().step, 2);
    let folder = common::TempFolder::new("interrupt");
    let file = folder.join("half.bin");
    let refused = sim.write_checkpoint(&file).unwrap_err();
    assert!(
        matches!(refused, CheckpointError::CutShort { .. }),
        "{refused}"
    );
    assert!(!file.exists());
}

#[test]
fn a_run_cut_short_keeps_its_last_checkpoint_and_resumes_exactly() {
    let scene = short_sliding_block();
    let folder = common::TempFolder::new("interrupt-run");
    let options = |out: &str, start| RunOptions {
        checkpoint_every: Some(5e-4), // every 5 steps
        start,
        ..RunOptions::into_folder(folder.join(out))
    };
    let never_stopped = Runner::new(&scene, None, options("straight", Start::Fresh))
        .unwrap()
        .run(&AtomicBool::new(false), |_| {})
        .unwrap();

    let mut runner = Runner::new(&scene, None, options("stopped", Start::Fresh)).unwrap();
    let request = Arc::new(AtomicBool::new(false));
    runner.interrupt_steps_on(Arc::clone(&request));
    runner
        .simulation_mut()
        .add_systems(raise_during_step(request, 13).in_set(MpmSystems::Contact))
        .unwrap();
    let stopped = runner.run(&AtomicBool::new(false), |_| {}).unwrap_err();
    let RunError::CutShort {
        step, checkpoint, ..
    } = stopped
    else {
        panic!("{stopped}");
    };
    assert_eq!((step, checkpoint), (12, Some(10)));
    let message = stopped.to_string();
    assert!(
        message.contains("stopped inside step 13")
            && message.contains("the checkpoint of step 10 stays current"),
        "{message}"
    );
    // The series end at the last whole step.
    let energy = std::fs::read_to_string(folder.join("stopped/energy.csv")).unwrap();
    let last = energy.lines().last().unwrap();
    assert!(last.starts_with("1.2e-3,"), "last energy row: {last}");
    assert!(folder.join("stopped").join(CHECKPOINT_FILE).is_file());

    let resumed = Runner::new(&scene, None, options("stopped", Start::Resume))
        .unwrap()
        .run(&AtomicBool::new(false), |_| {})
        .unwrap();
    assert_eq!(resumed.steps, never_stopped.steps);
    assert_eq!(
        format!("{:016x}", resumed.state_hash),
        format!("{:016x}", never_stopped.state_hash)
    );
}
