//! Scenes written for earlier releases of the format still load: each file
//! of `tests/scene_compat/` is a scene as an earlier release wrote it
//! (from the history of `scenes/`, one per renamed or restructured name),
//! beside the same scene in the present spelling. The old file is read
//! with a warning that gives the new spelling, and both give the same
//! state.

mod common;

use mpdem::prelude::*;
use std::path::{Path, PathBuf};

/// Steps compared: enough for every point and block to have moved.
const STEPS: usize = 40;

fn corpus() -> Vec<(PathBuf, PathBuf)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scene_compat");
    let mut pairs: Vec<_> = std::fs::read_dir(&dir)
        .expect("the corpus")
        .map(|e| e.expect("an entry").path())
        .filter(|p| {
            let name = p.file_name().unwrap_or_default().to_string_lossy();
            name.ends_with(".ron") && !name.ends_with(".present.ron")
        })
        .map(|old| {
            let present = old.with_extension("present.ron");
            (old, present)
        })
        .collect();
    pairs.sort();
    pairs
}

fn state_after_steps(scene: &Scene) -> (u64, Vec<Warning>) {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..STEPS {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
    (sim.state_hash(), sim.warnings().to_vec())
}

#[test]
fn scenes_of_earlier_releases_load_and_give_the_present_spellings_state() {
    let pairs = corpus();
    assert_eq!(pairs.len(), 5, "one scene per rename: {pairs:?}");
    for (old, present) in pairs {
        let old_scene = Scene::load(&old).unwrap_or_else(|e| panic!("{e}"));
        let present_scene = Scene::load(&present).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            old_scene.settings,
            present_scene.settings,
            "{}",
            old.display()
        );
        let (old_hash, old_warnings) = state_after_steps(&old_scene);
        let (present_hash, present_warnings) = state_after_steps(&present_scene);
        assert_eq!(old_hash, present_hash, "{}", old.display());
        let spelling = |w: &Warning| w.kind == WarningKind::OldSpelling;
        assert_eq!(
            old_warnings.iter().filter(|w| spelling(w)).count(),
            1,
            "{}: {old_warnings:?}",
            old.display()
        );
        assert!(
            !present_warnings.iter().any(spelling),
            "{present_warnings:?}"
        );
    }
}

#[test]
fn an_old_spelling_is_named_with_its_new_one_by_check() {
    let old =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scene_compat/forward_two_rings.ron");
    let sim = Simulation::from_scene_file(&old).unwrap_or_else(|e| panic!("{e}"));
    let warning = sim
        .warnings()
        .iter()
        .find(|w| w.kind == WarningKind::OldSpelling)
        .expect("a warning");
    assert_eq!(warning.field, "settings.position_update");
    assert_eq!(
        warning.message,
        "`settings.position_update: Forward` is the spelling of an earlier release, read as `settings.position_update: Some(NewGridVelocity)`; write the present spelling, as a later release may no longer read the old one"
    );
}
