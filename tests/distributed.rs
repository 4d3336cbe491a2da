//! A scene stepped on 1 to 4 ranks (threads of one process joined by
//! channels, `LocalRanks`) ends in the state one process reaches, bit for
//! bit: the state hash over every point, gathered in its one-process order;
//! and a checkpoint written on N ranks resumes on M ranks alike.

mod common;

use mpdem::distributed::{LocalRanks, PointIds, attach, with_all_points};
use mpdem::prelude::*;

/// The ids of the points a rank holds.
fn ids_held(sim: &mut Simulation) -> Vec<u64> {
    let world = sim.world_mut();
    let mut query = world.query::<&PointIds>();
    query.iter(world).flat_map(|ids| ids.0.clone()).collect()
}

/// Every recorded series, as its CSV text.
fn series(sim: &Simulation) -> Vec<(&'static str, String)> {
    sim.series_files()
        .into_iter()
        .map(|file| (file, sim.series_csv(file).expect("a series")))
        .collect()
}

/// What a run ends with: the state hash and the recorded series.
type End = (u64, Vec<(&'static str, String)>);

/// The end of `steps` steps of `scene` on `ranks` ranks (rank 0's series),
/// and whether any point changed rank.
fn end_on_ranks(scene: &Scene, ranks: usize, steps: u64) -> (End, bool) {
    std::thread::scope(|scope| {
        let handles: Vec<_> = LocalRanks::connected(ranks)
            .into_iter()
            .map(|transport| {
                scope.spawn(move || {
                    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
                    attach(&mut sim, Box::new(transport)).unwrap_or_else(|e| panic!("{e}"));
                    let first = ids_held(&mut sim);
                    for _ in 0..steps {
                        sim.step().unwrap_or_else(|e| panic!("{e}"));
                    }
                    let moved = ids_held(&mut sim) != first;
                    let end = with_all_points(&mut sim, |sim| (sim.state_hash(), series(sim)));
                    (end, moved)
                })
            })
            .collect();
        let mut ends: Vec<(Option<End>, bool)> = handles
            .into_iter()
            .map(|h| h.join().expect("a rank panicked"))
            .collect();
        assert!(ends[1..].iter().all(|(end, _)| end.is_none()));
        let moved = ends.iter().any(|(_, moved)| *moved);
        (ends[0].0.take().expect("rank 0 gathers the points"), moved)
    })
}

fn one_process_end(scene: &Scene, steps: u64) -> End {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
    (sim.state_hash(), series(&sim))
}

/// Whether points changed rank on 2 to 4 ranks, after checking that the
/// state and every series on 1 to 4 ranks are the one-process ones.
fn same_state_on_any_number_of_ranks(scene: &Scene, steps: u64) -> Vec<bool> {
    let (one, one_series) = one_process_end(scene, steps);
    assert!(one_series.iter().any(|(file, _)| *file == "energy.csv"));
    let mut moved = Vec::new();
    for ranks in 1..=4 {
        let ((hash, series), any_moved) = end_on_ranks(scene, ranks, steps);
        assert_eq!(hash, one, "{ranks} ranks against one process");
        for ((file, csv), (_, one_csv)) in series.iter().zip(&one_series) {
            assert!(csv == one_csv, "{ranks} ranks: {file} differs");
        }
        assert_eq!(series.len(), one_series.len());
        if ranks > 1 {
            moved.push(any_moved);
        }
    }
    moved
}

#[test]
fn the_wave_on_one_to_four_ranks_is_the_one_process_wave() {
    same_state_on_any_number_of_ranks(&common::load_scene("wave_1d.ron"), 300);
}

/// A reduced collapse (cells twice as large) thrown sideways at 3 m/s, so
/// that within the test's steps its points cross from strip to strip and
/// the strips are cut anew (every 64 steps).
#[test]
fn the_collapse_on_one_to_four_ranks_is_the_one_process_collapse() {
    let mut scene = common::load_scene("column_collapse.ron");
    scene.grid.cell_size *= 2.0;
    scene.grid.cells = (scene.grid.cells.0 / 2, scene.grid.cells.1 / 2);
    scene.time.dt *= 2.0;
    scene.bodies[0].velocity = mpdem::scene::InitialVelocity::Constant(DVec2::new(3.0, 0.0));
    let moved = same_state_on_any_number_of_ranks(&scene, 400);
    assert_eq!(moved, vec![true; 3], "points changed rank on 2, 3, 4 ranks");
}

/// A block sliding on a fixed rigid slope, thrown along it at 20 m/s so
/// that within the test's steps its points cross from strip to strip with
/// their contacts: the slope's reaction gathers forces from every rank.
#[test]
fn the_sliding_block_on_one_to_four_ranks_is_the_one_process_block() {
    let mut scene = common::load_scene("sliding_45.ron");
    scene.bodies[0].velocity = mpdem::scene::InitialVelocity::Constant(DVec2::new(20.0, 0.0));
    let moved = same_state_on_any_number_of_ranks(&scene, 400);
    assert_eq!(moved, vec![true; 3], "points changed rank on 2, 3, 4 ranks");
}

/// A reduced stacked-blocks case (cells twice as large, the grains nearer
/// the blocks and thrown at them at 2 m/s): points of several ranks hit a
/// fixed block and two dynamic ones stacked on it, which every rank moves
/// alike; its fronts and deposits (`fronts.csv`, `deposit.csv`) are
/// recorded from every rank's points.
#[test]
fn the_stacked_blocks_on_one_to_four_ranks_are_the_one_process_blocks() {
    let moved = same_state_on_any_number_of_ranks(&reduced_stacked_blocks(), 400);
    assert_eq!(moved, vec![true; 3], "points changed rank on 2, 3, 4 ranks");
}

/// The reduced stacked-blocks case above.
fn reduced_stacked_blocks() -> Scene {
    let mut scene = common::load_scene("stacked_blocks.ron");
    scene.grid.cell_size *= 2.0;
    scene.grid.cells = (scene.grid.cells.0 / 2, scene.grid.cells.1 / 2);
    scene.bodies[0].shape = mpdem::scene::Shape::Rectangle {
        min: DVec2::new(0.1, 0.0),
        max: DVec2::new(0.275, 0.2),
    };
    scene.bodies[0].velocity = mpdem::scene::InitialVelocity::Constant(DVec2::new(2.0, 0.0));
    scene
}

/// The state hash after `first` steps on `before` ranks, a checkpoint
/// written from rank 0, and `then` steps resumed from it on `after` ranks.
fn hash_through_a_checkpoint(
    scene: &Scene,
    (before, first): (usize, u64),
    (after, then): (usize, u64),
) -> u64 {
    let dir = tempfile::tempdir().expect("a folder");
    let path = dir.path().join("checkpoint.bin");
    std::thread::scope(|scope| {
        for transport in LocalRanks::connected(before) {
            let path = &path;
            scope.spawn(move || {
                let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
                attach(&mut sim, Box::new(transport)).unwrap_or_else(|e| panic!("{e}"));
                for _ in 0..first {
                    sim.step().unwrap_or_else(|e| panic!("{e}"));
                }
                if let Some(written) = with_all_points(&mut sim, |sim| sim.write_checkpoint(path)) {
                    written.unwrap_or_else(|e| panic!("{e}"));
                }
            });
        }
    });
    std::thread::scope(|scope| {
        let handles: Vec<_> = LocalRanks::connected(after)
            .into_iter()
            .map(|transport| {
                let path = &path;
                scope.spawn(move || {
                    let mut sim = Simulation::resume(scene, path).unwrap_or_else(|e| panic!("{e}"));
                    attach(&mut sim, Box::new(transport)).unwrap_or_else(|e| panic!("{e}"));
                    for _ in 0..then {
                        sim.step().unwrap_or_else(|e| panic!("{e}"));
                    }
                    with_all_points(&mut sim, |sim| sim.state_hash())
                })
            })
            .collect();
        let hashes: Vec<Option<u64>> = handles
            .into_iter()
            .map(|h| h.join().expect("a rank panicked"))
            .collect();
        hashes[0].expect("rank 0 gathers the points")
    })
}

/// A checkpoint written on N ranks resumes on M ranks with the one-process
/// result.
#[test]
fn a_checkpoint_from_n_ranks_resumes_on_m_ranks() {
    let scene = common::load_scene("wave_1d.ron");
    let (one, _) = one_process_end(&scene, 200);
    for (before, after) in [(1, 3), (2, 4), (4, 1), (3, 2)] {
        assert_eq!(
            hash_through_a_checkpoint(&scene, (before, 120), (after, 80)),
            one,
            "{before} ranks, then {after}"
        );
    }
    // The grains against the blocks at the checkpoint: the blocks' contact
    // springs and neighbour lists are gathered into it, and shared out of
    // it. Written mid-way between the lists' rebuilds (every 10 steps),
    // so that the first steps resumed use the lists it holds.
    let scene = reduced_stacked_blocks();
    let (one, _) = one_process_end(&scene, 300);
    for (before, after) in [(2, 3), (4, 1)] {
        assert_eq!(
            hash_through_a_checkpoint(&scene, (before, 205), (after, 95)),
            one,
            "stacked blocks: {before} ranks, then {after}"
        );
    }
}

/// The steps taken before the first error, and its message, on each of
/// `ranks` ranks (one process without ranks), at most `steps` steps.
fn failures_on_ranks(scene: &Scene, ranks: Option<usize>, steps: u64) -> Vec<(u64, String)> {
    let run = |transport: Option<LocalRanks>| {
        let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
        if let Some(transport) = transport {
            attach(&mut sim, Box::new(transport)).unwrap_or_else(|e| panic!("{e}"));
        }
        for taken in 0..steps {
            if let Err(e) = sim.step() {
                return (taken, e.to_string());
            }
        }
        (steps, String::new())
    };
    let Some(ranks) = ranks else {
        return vec![run(None)];
    };
    std::thread::scope(|scope| {
        let handles: Vec<_> = LocalRanks::connected(ranks)
            .into_iter()
            .map(|transport| scope.spawn(move || run(Some(transport))))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a rank panicked"))
            .collect()
    })
}

/// A failure on one rank (points of the bar's right end thrown through
/// the wall) ends the same step on every rank, with one message naming
/// the rank that found it, instead of leaving the others waiting.
#[test]
fn a_failure_on_one_rank_ends_the_step_on_all() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.bodies[0].velocity = mpdem::scene::InitialVelocity::Field {
        x: "1e4*x^40".into(),
        y: "0".into(),
    };
    let one = failures_on_ranks(&scene, None, 50);
    let (failed_at, message) = &one[0];
    assert!(*failed_at < 50 && !message.is_empty(), "{one:?}");
    for ranks in 2..=4 {
        let all = failures_on_ranks(&scene, Some(ranks), 50);
        for (taken, text) in &all {
            assert_eq!(taken, failed_at, "{ranks} ranks: {text}");
            assert_eq!(text, &all[0].1, "{ranks} ranks disagree");
            assert!(text.contains(&format!("of {ranks})")), "{text}");
        }
    }
}

/// Every file under `dir`, by its path inside it, with its bytes (the
/// folder's lock aside).
fn files_under(dir: &std::path::Path) -> Vec<(std::path::PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("a folder") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                folders.push(path);
            } else if path.file_name() != Some(mpdem::runner::LOCK_FILE.as_ref()) {
                let bytes = std::fs::read(&path).expect("a file");
                files.push((path.strip_prefix(dir).expect("inside").to_path_buf(), bytes));
            }
        }
    }
    files.sort();
    files
}

/// A run of the reduced, thrown collapse (frames every 0.01 s over 0.12 s)
/// on 3 ranks writes, from rank 0, every file a run on one process writes,
/// byte for byte, and every rank returns its state hash; a stop raised on
/// one rank alone stops every rank after the same step.
#[test]
fn a_run_on_three_ranks_writes_the_files_of_one_process() {
    use mpdem::runner::{RunError, RunOptions, Runner};
    use std::sync::atomic::AtomicBool;
    let mut scene = common::load_scene("column_collapse.ron");
    scene.grid.cell_size *= 2.0;
    scene.grid.cells = (scene.grid.cells.0 / 2, scene.grid.cells.1 / 2);
    scene.time.dt *= 2.0;
    scene.time.end = 0.012;
    scene.output.frame_interval = Some(0.001);
    scene.bodies[0].velocity = mpdem::scene::InitialVelocity::Constant(DVec2::new(3.0, 0.0));
    let one = common::TempFolder::new("distributed-one");
    let mut runner =
        Runner::new(&scene, None, RunOptions::into_folder(&*one)).unwrap_or_else(|e| panic!("{e}"));
    let hash = runner
        .run(&AtomicBool::new(false), |_| {})
        .unwrap_or_else(|e| panic!("{e}"))
        .state_hash;
    let three = common::TempFolder::new("distributed-three");
    // Rank 2 alone is asked to stop, on its own count of steps.
    let run_on_ranks = |dir: &std::path::Path, stop_at: Option<u64>| {
        std::thread::scope(|scope| {
            let handles: Vec<_> = LocalRanks::connected(3)
                .into_iter()
                .map(|transport| {
                    let scene = &scene;
                    scope.spawn(move || {
                        let rank = mpdem::distributed::Transport::rank(&transport);
                        let mut runner = Runner::new(scene, None, RunOptions::into_folder(dir))
                            .unwrap_or_else(|e| panic!("{e}"));
                        let stop = AtomicBool::new(false);
                        runner.run_distributed(Box::new(transport), &stop, |p| {
                            if rank == 2 && stop_at.is_some_and(|s| p.step >= s) {
                                stop.store(true, std::sync::atomic::Ordering::SeqCst);
                            }
                        })
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("a rank panicked"))
                .collect::<Vec<_>>()
        })
    };
    for result in run_on_ranks(&three, None) {
        let summary = result.unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(summary.state_hash, hash, "every rank returns the hash");
    }
    let (ones, threes) = (files_under(&one), files_under(&three));
    let names = |files: &[(std::path::PathBuf, Vec<u8>)]| {
        files.iter().map(|f| f.0.clone()).collect::<Vec<_>>()
    };
    assert_eq!(names(&ones), names(&threes));
    assert!(
        ones.len() > 20,
        "frames, series and plots: {:?}",
        names(&ones)
    );
    for ((name, a), (_, b)) in ones.iter().zip(&threes) {
        assert!(a == b, "{} differs", name.display());
    }
    // Progress is reported after step 64, past that step's stop check:
    // rank 2 raises its stop there, and every rank stops after step 65.
    let stopped = common::TempFolder::new("distributed-stopped");
    for result in run_on_ranks(&stopped, Some(64)) {
        match result {
            Err(RunError::Stopped { step, .. }) => assert_eq!(step, 65),
            other => panic!("stopped after step 65, not {other:?}"),
        }
    }
}

/// A scene with parts the distributed step does not cover is refused
/// before anything runs, saying which.
#[test]
fn a_scene_with_body_contacts_is_refused_with_what_is_not_covered() {
    use mpdem::runner::{RunOptions, Runner};
    let scene = common::load_scene("dam_break.ron");
    let dir = common::TempFolder::new("distributed-refused");
    let mut runner =
        Runner::new(&scene, None, RunOptions::into_folder(&*dir)).unwrap_or_else(|e| panic!("{e}"));
    let transport = LocalRanks::connected(1).pop().expect("one rank");
    let stop = std::sync::atomic::AtomicBool::new(false);
    let refusal = runner
        .run_distributed(Box::new(transport), &stop, |_| {})
        .expect_err("refused")
        .to_string();
    assert!(
        refusal.contains("body contacts, stages")
            && refusal.contains("run this scene on one process"),
        "{refusal}"
    );
}

/// A point grown too loose for the time step on one rank is warned of on
/// every rank, named as one process names it, with one process's message.
#[test]
fn a_loose_point_on_one_rank_is_warned_of_on_all() {
    use mpdem::components::MaterialPoints;
    let scene = common::load_scene("elastic_column.ron");
    // Scales point `id`'s deformation gradient, on the rank holding it, to
    // 12 times its placed volume (stable up to 9.3: see loose_points.rs).
    let loosen = |sim: &mut Simulation, id: u64| {
        let world = sim.world_mut();
        let mut query = world.query::<(&mut MaterialPoints, Option<&PointIds>)>();
        for (mut points, ids) in query.iter_mut(world) {
            let held = ids.map_or(Some(id as usize), |ids| ids.0.binary_search(&id).ok());
            if let Some(p) = held {
                let stretch = 12.0_f64.sqrt() / points.deformation_gradient[p].determinant().sqrt();
                points.deformation_gradient[p] *= stretch;
                points.volume[p] = 12.0 * points.initial_volume[p];
            }
        }
    };
    let run = |sim: &mut Simulation| {
        for _ in 0..64 {
            sim.step().unwrap_or_else(|e| panic!("{e}"));
        }
        loosen(sim, 40);
        for _ in 0..64 {
            sim.step().unwrap_or_else(|e| panic!("{e}"));
        }
        sim.step_warnings().to_vec()
    };
    let mut one = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    let expected = run(&mut one);
    assert_eq!(expected.len(), 1, "{expected:?}");
    assert!(expected[0].message.contains("point 40 "), "{}", expected[0]);
    std::thread::scope(|scope| {
        let handles: Vec<_> = LocalRanks::connected(3)
            .into_iter()
            .map(|transport| {
                let scene = &scene;
                scope.spawn(move || {
                    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
                    attach(&mut sim, Box::new(transport)).unwrap_or_else(|e| panic!("{e}"));
                    run(&mut sim)
                })
            })
            .collect();
        for handle in handles {
            assert_eq!(handle.join().expect("a rank panicked"), expected);
        }
    });
}
