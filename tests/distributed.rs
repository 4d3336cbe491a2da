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
