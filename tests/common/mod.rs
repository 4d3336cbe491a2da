//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses a different subset

use mpdem::prelude::*;
use std::path::{Path, PathBuf};

/// A fresh temporary folder, removed with everything in it when dropped,
/// so a test leaves nothing behind whether it passes or fails. It derefs
/// to its path.
pub struct TempFolder(tempfile::TempDir);

impl TempFolder {
    /// A new empty folder whose name starts with `mpdem-{tag}-`.
    pub fn new(tag: &str) -> Self {
        Self(
            tempfile::Builder::new()
                .prefix(&format!("mpdem-{tag}-"))
                .tempdir()
                .expect("temporary folder"),
        )
    }
}

impl std::ops::Deref for TempFolder {
    type Target = Path;
    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for TempFolder {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}

/// The repository's root: the engine's folder, which the workspace's
/// other packages (`cli/`, `verify/`) sit in.
pub fn repository_root() -> PathBuf {
    let package = Path::new(env!("CARGO_MANIFEST_DIR"));
    package
        .ancestors()
        .find(|dir| dir.join("scenes").is_dir())
        .unwrap_or(package)
        .to_path_buf()
}

/// Path of a file in `scenes/`.
pub fn scene_path(file: &str) -> PathBuf {
    repository_root().join("scenes").join(file)
}

/// Loads and validates a scene of `scenes/`.
pub fn load_scene(file: &str) -> Scene {
    Scene::load(&scene_path(file)).unwrap_or_else(|e| panic!("{e}"))
}

/// `rigid_drop`'s box falling 0.1 m onto the ground in one stage, named
/// "drop", that ends once the kinetic energy has fallen to 1e-3 of its peak
/// (at most 1.4 s).
pub fn settling_drop() -> Scene {
    let mut scene = load_scene("rigid_drop.ron");
    scene.stages = vec![mpdem::scene::StageSpec::new(
        "drop",
        mpdem::scene::StageEnd::KineticEnergyRatio {
            ratio: 1e-3,
            max_time: 1.4,
        },
    )];
    scene
}

/// Builds and runs a scene to its end.
pub fn run_scene(scene: &Scene) -> Simulation {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    sim
}

/// The message with which building a simulation from `scene` is refused
/// (panics if it is accepted).
pub fn refusal(scene: &Scene) -> String {
    Simulation::from_scene(scene)
        .err()
        .expect("refused")
        .to_string()
}

/// The samples of the probe named `name`.
pub fn probe_samples(sim: &Simulation, name: &str) -> Vec<mpdem::resources::ProbeSample> {
    let probes = sim.world().resource::<Probes>();
    let index = probes
        .probes
        .iter()
        .position(|p| p.name == name)
        .unwrap_or_else(|| panic!("the scene has no probe '{name}'"));
    probes.series(index).copied().collect()
}

/// The messages of `warnings`, one per line, for a test that looks for
/// words in them.
pub fn warning_text(warnings: &[Warning]) -> String {
    warnings
        .iter()
        .map(|w| w.message.as_str())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Runs `f` on a rayon pool of `threads` workers.
pub fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}

/// Writes the scene `file` of `scenes/`, each `(from, to)` of `edits`
/// replaced once, as `name` into a fresh temporary folder named after
/// `tag`; returns the folder and the scene file.
pub fn write_edited(
    file: &str,
    tag: &str,
    name: &str,
    edits: &[(&str, &str)],
) -> (TempFolder, PathBuf) {
    let base = TempFolder::new(tag);
    let mut text = std::fs::read_to_string(scene_path(file)).expect("scene");
    for (from, to) in edits {
        assert!(text.contains(from), "'{from}' not in {file}");
        text = text.replacen(from, to, 1);
    }
    let scene = base.join(name);
    std::fs::write(&scene, text).expect("scene written");
    (base, scene)
}

/// Writes the wave scene with `from` replaced by `to` into a fresh temporary
/// folder named after `tag`; returns the folder and the scene file.
pub fn edited_wave_scene(tag: &str, from: &str, to: &str) -> (TempFolder, PathBuf) {
    write_edited("wave_1d.ron", tag, &format!("{tag}.ron"), &[(from, to)])
}

/// A fresh temporary folder named after `tag` holding the scene `file` of
/// `scenes/`, under its own name, with `edits` made (e.g. a scenes folder
/// for `mpdem verify`).
pub fn edited_scenes_folder(file: &str, tag: &str, edits: &[(&str, &str)]) -> TempFolder {
    write_edited(file, tag, file, edits).0
}
