//! Checkpoints (DESIGN.md section 1, io/): a run written to a checkpoint
//! and resumed continues bit-identically to the run that never stopped,
//! through block and body contacts, dynamic blocks, stages (their end
//! conditions, surcharges, blocks they add or remove) and a later end
//! time, and with the resources and components user systems registered; a checkpoint of
//! another scene, or a file that is not one, is refused with its path.

mod common;

use mpdem::checkpoint::CheckpointError;
use mpdem::components::{BlockContacts, BlockId, NeighbourList};
use mpdem::prelude::*;
use mpdem::resources::{BlockLog, BodyPairLog, EnergyLog, Probes, StageEndReason, StageLog};
use mpdem::scene::StageEnd;
use std::path::PathBuf;

/// A fresh file path for one test's checkpoint, in a temporary folder
/// that goes when the folder is dropped.
fn checkpoint_file(tag: &str) -> (common::TempFolder, PathBuf) {
    let folder = common::TempFolder::new("checkpoint");
    let file = folder.join(format!("{tag}.bin"));
    (folder, file)
}

fn build(scene: &Scene) -> Simulation {
    Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"))
}

fn step_to(sim: &mut Simulation, step: u64) {
    while sim.clock().step < step {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
}

fn stage(sim: &Simulation) -> usize {
    sim.stage_index().expect("a stage is running")
}

/// Steps until stage `index` has begun, then `more` steps; returns the step.
fn step_into_stage(sim: &mut Simulation, index: usize, more: u64) -> u64 {
    while stage(sim) < index {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
    let step = sim.clock().step + more;
    step_to(sim, step);
    step
}

fn resume(scene: &Scene, file: &std::path::Path) -> Simulation {
    Simulation::resume(scene, file).unwrap_or_else(|e| panic!("{e}"))
}

/// Every point and block state (the state hash), every point column,
/// every record the outputs are written from, and the whole state a
/// checkpoint stores (how far the points moved in the last step, the
/// springs between blocks, ...) are equal.
fn assert_same_run(resumed: &mut Simulation, straight: &mut Simulation) {
    assert_eq!(resumed.clock(), straight.clock());
    assert_eq!(resumed.state_hash(), straight.state_hash());
    for (entity, name) in straight.bodies() {
        assert_eq!(
            resumed.points(entity),
            straight.points(entity),
            "body '{name}'"
        );
    }
    // Every block's neighbour list (its age, travel and points) and
    // contacts with their springs.
    let blocks = |sim: &mut Simulation| {
        let world = sim.world_mut();
        let mut blocks: Vec<_> = world
            .query::<(&BlockId, &NeighbourList, &BlockContacts)>()
            .iter(world)
            .map(|(id, list, contacts)| (id.index, list.clone(), contacts.clone()))
            .collect();
        blocks.sort_unstable_by_key(|b| b.0);
        blocks
    };
    assert!(
        blocks(resumed) == blocks(straight),
        "blocks' contacts differ"
    );
    // Records are long: report which differs, not their contents.
    let (a, b) = (resumed.world(), straight.world());
    assert!(
        a.resource::<Probes>() == b.resource::<Probes>(),
        "probes differ"
    );
    assert!(
        a.resource::<EnergyLog>() == b.resource::<EnergyLog>(),
        "energy differs"
    );
    assert!(
        a.resource::<BlockLog>() == b.resource::<BlockLog>(),
        "block records differ"
    );
    assert!(
        a.resource::<BodyPairLog>() == b.resource::<BodyPairLog>(),
        "body pair records differ"
    );
    assert_eq!(a.resource::<StageLog>(), b.resource::<StageLog>());
    let state = |sim: &mut Simulation| sim.encoded_state().unwrap_or_else(|e| panic!("{e}"));
    assert!(
        state(resumed) == state(straight),
        "the checkpointed states differ"
    );
}

/// Runs `scene` to `checkpoint_at`, writes a checkpoint, resumes it in a
/// new simulation and compares both at step `end`.
fn resumes_bit_identically(tag: &str, scene: &Scene, checkpoint_at: u64, end: u64) {
    let (_folder, file) = checkpoint_file(tag);
    let mut straight = build(scene);
    step_to(&mut straight, checkpoint_at);
    straight.write_checkpoint(&file).expect("checkpoint");
    step_to(&mut straight, end);
    let mut resumed = resume(scene, &file);
    assert_eq!(resumed.clock().step, checkpoint_at);
    step_to(&mut resumed, end);
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn point_block_contacts_resume_between_neighbour_list_rebuilds() {
    // Neighbour lists are rebuilt every 10 steps: stop between two.
    let scene = common::load_scene("sliding_45.ron");
    resumes_bit_identically("sliding", &scene, 155, 400);
    // Before the next rebuild the lists still add up the points' travel,
    // which must carry over the checkpoint.
    resumes_bit_identically("sliding-between", &scene, 155, 158);
}

#[test]
fn the_fronts_record_resumes_with_its_samples() {
    // The stacked blocks record each body's front (`output.fronts`); stop
    // between two of its samples (every 10 steps).
    let mut scene = common::load_scene("stacked_blocks.ron");
    scene.grid.cell_size *= 2.0;
    scene.grid.cells = (scene.grid.cells.0 / 2, scene.grid.cells.1 / 2);
    assert!(scene.output.fronts);
    resumes_bit_identically("fronts", &scene, 205, 400);
}

#[test]
fn body_contacts_resume_with_their_tangential_springs() {
    let mut rings = common::load_scene("two_rings.ron");
    for body in &mut rings.bodies {
        body.points_per_cell = 1;
    }
    // The rings touch at 0.2 ms (200 steps): stop in contact.
    resumes_bit_identically("rings", &rings, 705, 1000);
}

/// The box tipping over the table's edge (block–block springs), ending at
/// `first_end` and, resumed, at `later_end`, sampled every 10 steps (the
/// default interval follows the end time).
fn tip_scenes(first_end: Real, later_end: Real) -> (Scene, Scene) {
    let mut first = common::load_scene("rigid_tip.ron");
    first.time.end = first_end;
    first.output.probe_interval = Some(1e-3);
    let mut later = first.clone();
    later.time.end = later_end;
    (first, later)
}

/// `first` run to its end and checkpointed (as `tag`), then resumed as
/// `later`, not yet stepped; and the first run.
fn run_and_resume(tag: &str, first: &Scene, later: &Scene) -> (Simulation, Simulation) {
    let (_folder, file) = checkpoint_file(tag);
    let mut run = build(first);
    run.run().expect("run");
    run.write_checkpoint(&file).expect("checkpoint");
    (resume(later, &file), run)
}

#[test]
fn a_dynamic_block_resumes_and_runs_on_to_a_later_end() {
    let (short, long) = tip_scenes(0.25, 0.35);
    let (mut resumed, _) = run_and_resume("tip", &short, &long);
    resumed.run().expect("run");
    let mut straight = build(&long);
    straight.run().expect("run");
    assert_eq!(straight.clock().step, 3500);
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn a_kinetic_energy_stage_resumes_counting_its_dynamic_blocks() {
    // The box enters in a second stage and falls; that stage ends once its
    // kinetic energy has settled. The checkpoint is taken mid-fall, so the
    // resumed stage must count the box (spawned again on resuming, absent
    // from the scene's start) to end where the straight run's does.
    let mut scene = common::load_scene("rigid_drop.ron");
    let the_box = scene.blocks.iter_mut().find(|b| b.name == "box").unwrap();
    the_box.present = false;
    let mut drop = mpdem::scene::StageSpec::new(
        "drop",
        StageEnd::KineticEnergyRatio {
            ratio: 1e-3,
            max_time: 1.4,
        },
    );
    drop.add_blocks = vec!["box".into()];
    scene.stages = vec![
        mpdem::scene::StageSpec::new("wait", StageEnd::Duration(0.01)),
        drop,
    ];
    let (_folder, file) = checkpoint_file("drop");
    let mut straight = build(&scene);
    step_into_stage(&mut straight, 1, 500);
    straight.write_checkpoint(&file).expect("checkpoint");
    straight.run().expect("run");
    let mut resumed = resume(&scene, &file);
    resumed.run().expect("run");
    let record = &straight.world().resource::<StageLog>().records[1];
    assert_eq!(record.reason, StageEndReason::Condition, "{record:?}");
    assert!(record.end - record.start > 0.14, "{record:?}");
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn a_run_that_ended_between_samples_resumes_without_its_end_sample() {
    // The first run ends at step 2 505, between two samples (every 10
    // steps), and samples its end; resumed with a later end, that sample
    // goes, as a run that never stopped has none there.
    let (short, long) = tip_scenes(0.2505, 0.35);
    let (mut resumed, first) = run_and_resume("tip-between", &short, &long);
    assert_eq!(last_energy_sample(&first), Some(first.clock().time));
    resumed.run().expect("run");
    let mut straight = build(&long);
    straight.run().expect("run");
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn a_sample_on_the_first_runs_interval_is_kept_when_the_resumed_interval_differs() {
    // The first run samples every 10 steps and ends on one, step 2 500;
    // the resumed scene samples every 15 steps, which would not reach 2 500,
    // but that sample was the first run's, not an end sample: it stays.
    let (short, mut long) = tip_scenes(0.25, 0.35);
    long.output.probe_interval = Some(1.5e-3);
    let (resumed, _) = run_and_resume("tip-interval", &short, &long);
    assert_eq!(last_energy_sample(&resumed), Some(0.25));
}

fn last_energy_sample(sim: &Simulation) -> Option<Real> {
    let samples = &sim.world().resource::<EnergyLog>().samples;
    samples.last().map(|s| s.time)
}

/// The pile at the reduced size of verify/tests/pile.rs, driven for 0.1 s, then
/// a fourth stage that removes the pile.
fn reduced_pile() -> Scene {
    let mut scene = common::load_scene("pile_penetration.ron");
    scene.grid.cell_size = 0.16;
    scene.grid.cells = (50, 35);
    scene.time.dt = 2e-4;
    scene.stages[2].end = StageEnd::Duration(0.1);
    let mut pulled = scene.stages[1].clone();
    pulled.name = "pulled".into();
    pulled.end = StageEnd::Duration(0.02);
    pulled.tractions.clear();
    pulled.remove_blocks = vec!["pile".into()];
    scene.stages.push(pulled);
    scene
}

#[test]
fn stages_resume_mid_stage_with_their_loads_and_blocks() {
    let scene = reduced_pile();
    let folder = common::TempFolder::new("checkpoint");
    let files = ["geostatic", "driven", "pulled"].map(|t| folder.join(format!("pile-{t}.bin")));
    let mut straight = build(&scene);
    // In the geostatic stage (its kinetic energy peak so far matters),
    // while the pile is driven (surcharge, the pile's set velocity), and
    // after the pile is removed (the rebuilt world has it: it must go).
    step_to(&mut straight, 2000);
    straight.write_checkpoint(&files[0]).expect("checkpoint");
    let driven = step_into_stage(&mut straight, 2, 50);
    straight.write_checkpoint(&files[1]).expect("checkpoint");
    let pulled = step_into_stage(&mut straight, 3, 20);
    straight.write_checkpoint(&files[2]).expect("checkpoint");
    straight.run().expect("run");
    assert_eq!(straight.world().resource::<StageLog>().records.len(), 4);
    for (file, from) in files.iter().zip([2000, driven, pulled]) {
        let mut resumed = resume(&scene, file);
        assert_eq!(resumed.clock().step, from);
        resumed.run().expect("run");
        assert_same_run(&mut resumed, &mut straight);
    }
}

#[test]
fn a_stress_change_stage_resumes_with_its_peak_change() {
    // The geostatic column settling on StressChange (about 2 350 steps),
    // resumed one step before the stage ends: only a restored peak change
    // (and the previous step's stresses) ends it on the same step; a peak
    // started afresh would not count the small change of that step.
    let mut scene = common::load_scene("geostatic_column.ron");
    scene.stages[0].end = StageEnd::StressChange {
        below: 0.01,
        max_time: 8.0,
    };
    let mut straight = build(&scene);
    straight.run().expect("run");
    let record = straight.world().resource::<StageLog>().records[0].clone();
    assert_eq!(record.reason, StageEndReason::Condition);
    let (_folder, file) = checkpoint_file("stress-change");
    let mut first = build(&scene);
    step_to(&mut first, record.steps - 1);
    first.write_checkpoint(&file).expect("checkpoint");
    let mut resumed = resume(&scene, &file);
    resumed.run().expect("run");
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn a_stage_cut_short_by_the_end_time_goes_on_when_the_end_grows() {
    // The run ends (time.end) in the geostatic stage, which is recorded as
    // cut short; resumed with a later end, that stage goes on, as in a run
    // given the later end from the start.
    let mut short = reduced_pile();
    short.time.end = 0.2;
    short.output.probe_interval = Some(0.01);
    let mut long = short.clone();
    long.time.end = 0.4;
    let (_folder, file) = checkpoint_file("pile-cut-short");
    let mut first = build(&short);
    first.run().expect("run");
    let log = first.world().resource::<StageLog>();
    assert_eq!(
        log.records.last().map(|r| r.reason),
        Some(StageEndReason::SceneEnd)
    );
    first.write_checkpoint(&file).expect("checkpoint");
    let mut resumed = resume(&long, &file);
    assert!(resumed.world().resource::<StageLog>().records.is_empty());
    resumed.run().expect("run");
    let mut straight = build(&long);
    straight.run().expect("run");
    assert_eq!(straight.clock().step, 2000);
    assert_same_run(&mut resumed, &mut straight);
    // Resumed with the same end, the run stays finished.
    let again = resume(&short, &file);
    assert!(again.clock().finished());
    assert_eq!(again.world().resource::<StageLog>().records.len(), 1);
}

#[test]
fn a_stage_begun_at_the_end_time_goes_on_when_the_end_grows() {
    // time.end on the boundary of two stages: the second has begun (its
    // surcharge is on) and is cut short at once; resumed with a later end,
    // it runs on as in a run given the later end from the start.
    let mut short = common::load_scene("geostatic_column.ron");
    short.stages[0].end = StageEnd::Duration(0.02);
    short.stages[1].end = StageEnd::Duration(0.02);
    short.time.end = 0.02;
    short.output.probe_interval = Some(0.01);
    let mut long = short.clone();
    long.time.end = 0.04;
    let (mut resumed, first) = run_and_resume("column-boundary", &short, &long);
    let records = &first.world().resource::<StageLog>().records;
    assert_eq!(records.len(), 2, "{records:?}");
    assert_eq!(records[1].reason, StageEndReason::SceneEnd);
    assert_eq!(records[1].steps, 0);
    resumed.run().expect("run");
    let mut straight = build(&long);
    straight.run().expect("run");
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn a_block_a_stage_added_is_spawned_again_on_resuming() {
    let mut scene = reduced_pile();
    scene.stages.pop();
    let pile = scene.blocks.iter_mut().find(|b| b.name == "pile").unwrap();
    pile.present = false;
    scene.stages[2].add_blocks = vec!["pile".into()];
    let (_folder, file) = checkpoint_file("pile-added");
    let mut straight = build(&scene);
    let at = step_into_stage(&mut straight, 2, 30);
    straight.write_checkpoint(&file).expect("checkpoint");
    step_to(&mut straight, at + 60);
    let mut resumed = resume(&scene, &file);
    step_to(&mut resumed, at + 60);
    assert_same_run(&mut resumed, &mut straight);
}

#[test]
fn a_checkpoint_of_another_scene_or_no_checkpoint_is_refused() {
    let scene = common::load_scene("wave_1d.ron");
    let (_folder, file) = checkpoint_file("wave");
    let mut sim = build(&scene);
    step_to(&mut sim, 10);
    sim.write_checkpoint(&file).expect("checkpoint");
    let mut other = scene.clone();
    other.time.dt *= 0.5;
    let refusal = |scene: &Scene, file: &std::path::Path| match Simulation::resume(scene, file) {
        Ok(_) => panic!("{} was resumed", file.display()),
        Err(e) => e,
    };
    let error = refusal(&other, &file);
    assert!(
        matches!(error, CheckpointError::OtherScene { .. }),
        "{error}"
    );
    assert!(
        error.to_string().contains("written for a different scene")
            && error.to_string().contains("(`time` changed)"),
        "{error}"
    );
    // The refusal names each part that differs: a body changed, a probe
    // added.
    let mut moved = scene.clone();
    moved.bodies[0].contact_radius = Some(0.001);
    let mut probe = moved.probes[0].clone();
    probe.name = "another".into();
    moved.probes.push(probe);
    let error = refusal(&moved, &file).to_string();
    let body = format!("body \"{}\" changed", scene.bodies[0].name);
    assert!(
        error.contains(&format!("({body}, probe \"another\" added)")),
        "{error}"
    );
    // The fronts are recorded from the start or not at all.
    let mut fronts = scene.clone();
    fronts.output.fronts = !scene.output.fronts;
    let error = refusal(&fronts, &file).to_string();
    assert!(error.contains("(`output.fronts` changed)"), "{error}");
    // The name, the end time and the other outputs may change.
    let mut renamed = scene.clone();
    renamed.name = Some("wave, longer".into());
    renamed.time.end *= 2.0;
    renamed.output.frame_interval = Some(0.01);
    assert_eq!(resume(&renamed, &file).clock().step, 10);
    // A file cut short, one that is not a checkpoint, and none at all.
    let bytes = std::fs::read(&file).expect("checkpoint");
    let (_cut_folder, cut) = checkpoint_file("cut");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).expect("write");
    let error = refusal(&scene, &cut);
    assert!(
        matches!(error, CheckpointError::Damaged { .. })
            && error
                .to_string()
                .contains("bytes of state where its header says"),
        "{error}"
    );
    let scene_file = common::scene_path("wave_1d.ron");
    let error = refusal(&scene, &scene_file);
    assert!(
        error.to_string().contains("does not start as one"),
        "{error}"
    );
    let (_missing_folder, missing) = checkpoint_file("missing");
    let error = refusal(&scene, &missing);
    assert!(matches!(error, CheckpointError::Io { .. }), "{error}");
    assert!(error.to_string().contains("missing.bin"), "{error}");
}

#[test]
fn a_checkpoint_with_a_flipped_bit_is_refused_and_left_as_it_is() {
    let scene = common::load_scene("wave_1d.ron");
    let (_folder, file) = checkpoint_file("flipped");
    let mut sim = build(&scene);
    step_to(&mut sim, 10);
    sim.write_checkpoint(&file).expect("checkpoint");
    let bytes = std::fs::read(&file).expect("checkpoint");
    // Bits in the length and checksum, and spread over the state (24 bytes
    // of header: magic, layout, length, checksum).
    let mut places: Vec<usize> = vec![13, 21];
    places.extend((1..=20).map(|k| 24 + k * (bytes.len() - 25) / 20));
    for (n, &at) in places.iter().enumerate() {
        let bit = n % 8;
        let mut flipped = bytes.clone();
        flipped[at] ^= 1 << bit;
        let (_damaged_folder, damaged) = checkpoint_file(&format!("flipped_{n}"));
        std::fs::write(&damaged, &flipped).expect("write");
        match Simulation::resume(&scene, &damaged) {
            Ok(_) => panic!("byte {at}, bit {bit} flipped: resumed"),
            Err(error) => assert!(
                matches!(error, CheckpointError::Damaged { .. })
                    && error.to_string().contains("the checkpoint is damaged"),
                "byte {at}, bit {bit}: {error}"
            ),
        }
        assert_eq!(
            std::fs::read(&damaged).expect("read"),
            flipped,
            "left as it is"
        );
    }
}

/// A user controller's state: a push on the bar that follows the integral
/// of the bar's mean velocity, so it depends on the whole history.
#[derive(
    Resource, Default, Clone, Copy, PartialEq, Debug, serde::Serialize, serde::Deserialize,
)]
struct Controller {
    integral: Real,
    applied: Real,
}

/// Replaces last step's push on every point by −k ∫ v̄ dt.
fn control(
    mut controller: ResMut<Controller>,
    clock: Res<Clock>,
    mut points: Query<&mut MaterialPoints>,
) {
    for mut p in &mut points {
        let mean = p.velocity.iter().map(|v| v.x).sum::<Real>() / p.len() as Real;
        controller.integral += mean * clock.dt;
        let push = -50.0 * controller.integral;
        let change = push - controller.applied;
        p.external_force.iter_mut().for_each(|f| f.x += change);
        controller.applied = push;
    }
}

/// The wave bar to 0.03 s (300 steps) with the controller; its user
/// resource is kept in checkpoints when `kept`.
fn controlled(scene: &Scene, kept: bool) -> Simulation {
    let mut sim = build(scene);
    sim.world_mut().init_resource::<Controller>();
    sim.add_systems(control.in_set(MpmSystems::Boundary))
        .unwrap_or_else(|e| panic!("{e}"));
    if kept {
        sim.keep_in_checkpoints::<Controller>("controller");
    }
    sim
}

/// `first` (a run with user state) stepped to step 120 and written to
/// `file` of `scene`, and `restored`, a fresh one, restored from it.
fn written_and_restored(
    (mut first, mut restored): (Simulation, Simulation),
    scene: &Scene,
    file: &std::path::Path,
) -> (Simulation, Simulation) {
    step_to(&mut first, 120);
    first
        .write_checkpoint(file)
        .unwrap_or_else(|e| panic!("{e}"));
    restored
        .restore_checkpoint(scene, file)
        .unwrap_or_else(|e| panic!("{e}"));
    (first, restored)
}

#[test]
fn a_user_resource_registered_for_checkpoints_resumes_bit_identically() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.time.end = 0.03;
    let mut straight = controlled(&scene, true);
    straight.run().unwrap_or_else(|e| panic!("{e}"));

    let (_folder, file) = checkpoint_file("controller");
    let (first, mut resumed) = written_and_restored(
        (controlled(&scene, true), controlled(&scene, true)),
        &scene,
        &file,
    );
    assert_eq!(
        resumed.world().resource::<Controller>(),
        first.world().resource::<Controller>()
    );
    resumed.run().unwrap_or_else(|e| panic!("{e}"));
    assert_same_run(&mut resumed, &mut straight);
    assert_eq!(
        resumed.world().resource::<Controller>(),
        straight.world().resource::<Controller>()
    );

    // Without the controller's state the resumed run differs: the test can
    // tell the two apart.
    let (_unkept_folder, unkept) = checkpoint_file("controller-unkept");
    let (_, mut fresh) = written_and_restored(
        (controlled(&scene, false), controlled(&scene, false)),
        &scene,
        &unkept,
    );
    fresh.run().unwrap_or_else(|e| panic!("{e}"));
    assert_ne!(fresh.state_hash(), straight.state_hash());

    // A run that keeps what the checkpoint lacks, or the reverse, is refused.
    for (kept, written) in [(true, &unkept), (false, &file)] {
        let message = controlled(&scene, kept)
            .restore_checkpoint(&scene, written)
            .expect_err("refused")
            .to_string();
        assert!(message.contains("user state"), "{message}");
    }
    // So is restoring into a simulation that has stepped.
    let mut stepped = controlled(&scene, true);
    step_to(&mut stepped, 1);
    let message = stepped
        .restore_checkpoint(&scene, &file)
        .expect_err("refused")
        .to_string();
    assert!(message.contains("already stepped"), "{message}");
    // And restoring into a simulation built from another scene.
    let mut other = scene.clone();
    other.time.dt *= 0.5;
    let message = controlled(&other, true)
        .restore_checkpoint(&scene, &file)
        .expect_err("refused")
        .to_string();
    assert!(message.contains("another scene"), "{message}");
}

/// A user field on a body, one value per point: each point's displacement
/// along x integrated from its velocity, and the tether force −k u last
/// applied to it, so the run depends on the field's whole history.
#[derive(Component, Clone, PartialEq, Debug, serde::Serialize, serde::Deserialize)]
struct Tether {
    displacement: Vec<Real>,
    applied: Vec<Real>,
}

/// Replaces last step's tether force on every point by −k u.
fn tether(clock: Res<Clock>, mut bodies: Query<(&mut MaterialPoints, &mut Tether)>) {
    for (mut points, mut tether) in &mut bodies {
        let Tether {
            displacement,
            applied,
        } = &mut *tether;
        let MaterialPoints {
            velocity,
            external_force,
            ..
        } = &mut *points;
        for (((u, f_old), v), f) in displacement
            .iter_mut()
            .zip(applied.iter_mut())
            .zip(velocity.iter())
            .zip(external_force.iter_mut())
        {
            *u += v.x * clock.dt;
            let force = -2e3 * *u;
            f.x += force - *f_old;
            *f_old = force;
        }
    }
}

/// The wave bar with the tether system; the field is put on the bar when
/// `fielded` and kept in checkpoints when `kept`.
fn tethered(scene: &Scene, fielded: bool, kept: bool) -> Simulation {
    let mut sim = build(scene);
    if fielded {
        let (bar, _) = sim.bodies()[0].clone();
        let n = sim
            .world()
            .get::<MaterialPoints>(bar)
            .map_or(0, |p| p.len());
        sim.world_mut().entity_mut(bar).insert(Tether {
            displacement: vec![0.0; n],
            applied: vec![0.0; n],
        });
    }
    sim.add_systems(tether.in_set(MpmSystems::Boundary))
        .unwrap_or_else(|e| panic!("{e}"));
    if kept {
        sim.keep_components_in_checkpoints::<Tether>("tether");
    }
    sim
}

fn the_tether(sim: &mut Simulation) -> Option<Tether> {
    let bar = sim.bodies()[0].0;
    sim.world().get::<Tether>(bar).cloned()
}

#[test]
fn a_user_component_registered_for_checkpoints_resumes_bit_identically() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.time.end = 0.03;
    let mut straight = tethered(&scene, true, true);
    straight.run().unwrap_or_else(|e| panic!("{e}"));

    // The field is not put on the bar before restoring: the checkpoint
    // puts it there.
    let (_folder, file) = checkpoint_file("tether");
    let (mut first, mut resumed) = written_and_restored(
        (tethered(&scene, true, true), tethered(&scene, false, true)),
        &scene,
        &file,
    );
    assert_eq!(the_tether(&mut resumed), the_tether(&mut first));
    resumed.run().unwrap_or_else(|e| panic!("{e}"));
    assert_same_run(&mut resumed, &mut straight);
    assert_eq!(the_tether(&mut resumed), the_tether(&mut straight));

    // Without it, a resumed run that starts the field afresh differs: the
    // test can tell the two apart.
    let (_unkept_folder, unkept) = checkpoint_file("tether-unkept");
    let (_, mut fresh) = written_and_restored(
        (tethered(&scene, true, false), tethered(&scene, true, false)),
        &scene,
        &unkept,
    );
    fresh.run().unwrap_or_else(|e| panic!("{e}"));
    assert_ne!(fresh.state_hash(), straight.state_hash());

    // A checkpoint whose bar had no field removes one put on before
    // restoring: the resumed run is the one that was written.
    let (_bare_folder, bare) = checkpoint_file("tether-bare");
    let (_, mut restored) = written_and_restored(
        (tethered(&scene, false, true), tethered(&scene, true, true)),
        &scene,
        &bare,
    );
    assert_eq!(the_tether(&mut restored), None);

    // A name stored as a component but kept as a resource is refused.
    let mut mixed = build(&scene);
    mixed.keep_in_checkpoints::<Controller>("tether");
    let message = mixed
        .restore_checkpoint(&scene, &file)
        .expect_err("refused")
        .to_string();
    assert!(message.contains("stored as a component"), "{message}");
}

/// A user count on bodies and blocks, one more every step.
#[derive(Component, Clone, Copy, PartialEq, Debug, serde::Serialize, serde::Deserialize)]
struct Count(u64);

fn count(mut counts: Query<&mut Count>) {
    for mut c in &mut counts {
        c.0 += 1;
    }
}

/// The reduced pile with the count system, the count put on the soil and
/// the pile when `counted`, and kept in checkpoints when `kept`.
fn counted_pile(scene: &Scene, counted: bool, kept: bool) -> Simulation {
    let mut sim = build(scene);
    if counted {
        let soil = sim.bodies()[0].0;
        let pile = the_pile(&mut sim).expect("the pile is present");
        sim.world_mut().entity_mut(soil).insert(Count(0));
        sim.world_mut().entity_mut(pile).insert(Count(0));
    }
    sim.add_systems(count.in_set(MpmSystems::Boundary))
        .unwrap_or_else(|e| panic!("{e}"));
    if kept {
        sim.keep_components_in_checkpoints::<Count>("count");
    }
    sim
}

fn the_pile(sim: &mut Simulation) -> Option<Entity> {
    let world = sim.world_mut();
    let mut blocks = world.query::<(Entity, &BlockId)>();
    blocks
        .iter(world)
        .find(|(_, id)| id.name == "pile")
        .map(|(e, _)| e)
}

/// The counts on the soil and on the pile (None where there is none).
fn counts(sim: &mut Simulation) -> (Option<Count>, Option<Count>) {
    let soil = sim.bodies()[0].0;
    let pile = the_pile(sim);
    let world = sim.world();
    (
        world.get::<Count>(soil).copied(),
        pile.and_then(|p| world.get::<Count>(p).copied()),
    )
}

#[test]
fn user_components_follow_the_bodies_and_the_blocks_a_stage_removes() {
    let scene = reduced_pile();
    let mut run = counted_pile(&scene, true, true);
    let (_driven_folder, driven) = checkpoint_file("count-driven");
    let (_pulled_folder, pulled) = checkpoint_file("count-pulled");
    step_into_stage(&mut run, 2, 10);
    run.write_checkpoint(&driven).expect("checkpoint");
    let while_driven = counts(&mut run);
    step_into_stage(&mut run, 3, 5);
    run.write_checkpoint(&pulled).expect("checkpoint");
    let once_pulled = counts(&mut run);
    assert!(while_driven.0.is_some() && while_driven.1.is_some());
    assert!(
        once_pulled.0.is_some() && once_pulled.1.is_none(),
        "{once_pulled:?}"
    );

    // Restored onto the soil and onto the pile, put there by nothing else.
    let mut restored = counted_pile(&scene, false, true);
    restored
        .restore_checkpoint(&scene, &driven)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(counts(&mut restored), while_driven);
    // Once the stage has removed the pile, only the soil's count returns.
    let mut restored = counted_pile(&scene, true, true);
    restored
        .restore_checkpoint(&scene, &pulled)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(counts(&mut restored), once_pulled);

    // A refused restore leaves the simulation as it was built.
    let mut unkept = counted_pile(&scene, true, false);
    let message = unkept
        .restore_checkpoint(&scene, &driven)
        .expect_err("refused")
        .to_string();
    assert!(message.contains("user state"), "{message}");
    assert_eq!(unkept.clock().step, 0);
    assert_eq!(counts(&mut unkept), (Some(Count(0)), Some(Count(0))));
}

/// A user's state may not take a name the engine keeps its own under: the
/// engine's energy record would drop out of checkpoints.
#[test]
#[should_panic(expected = "is the engine's")]
fn user_state_cannot_take_an_engine_name() {
    let scene = Scene::load(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/wave_1d.ron").as_ref())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut sim = build(&scene);
    sim.world_mut().init_resource::<Controller>();
    sim.keep_in_checkpoints::<Controller>("energy");
}
