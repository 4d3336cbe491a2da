//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses a different subset

use mpdem::prelude::*;
use std::path::PathBuf;

/// Path of a file in `scenes/`.
pub fn scene_path(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file)
}

/// Loads and validates a scene of `scenes/`.
pub fn load_scene(file: &str) -> Scene {
    Scene::load(&scene_path(file)).unwrap_or_else(|e| panic!("{e}"))
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
        .expect("probe exists");
    probes.series(index).copied().collect()
}

/// Runs `f` on a rayon pool of `threads` workers.
pub fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}

/// Writes the wave scene with `from` replaced by `to` into a fresh temporary
/// folder named after `tag`; returns the folder and the scene file.
pub fn edited_wave_scene(tag: &str, from: &str, to: &str) -> (PathBuf, PathBuf) {
    let base = std::env::temp_dir().join(format!("mpdem-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&base).expect("temporary folder");
    let text = std::fs::read_to_string(scene_path("wave_1d.ron")).expect("wave scene");
    assert!(text.contains(from), "'{from}' not in wave_1d.ron");
    let scene = base.join(format!("{tag}.ron"));
    std::fs::write(&scene, text.replacen(from, to, 1)).expect("scene written");
    (base, scene)
}

/// The mass-weighted mean of a column of a body's points (e.g. positions:
/// the centre of mass).
pub fn mass_weighted_mean(points: &MaterialPoints, column: &[DVec2]) -> DVec2 {
    points
        .mass
        .iter()
        .zip(column)
        .map(|(m, x)| *m * *x)
        .sum::<DVec2>()
        / points.total_mass()
}

/// Motion of a body's centre of mass: (displacement, velocity).
pub fn centre_of_mass_motion(points: &MaterialPoints) -> (DVec2, DVec2) {
    let mean = |column: &[DVec2]| mass_weighted_mean(points, column);
    (
        mean(&points.position) - mean(&points.initial_position),
        mean(&points.velocity),
    )
}

/// The mean σ_yy of a body's lowest row of points (within 1 µm of the
/// lowest), e.g. the base stress of a soil column.
pub fn base_stress(points: &MaterialPoints) -> Real {
    let lowest = points
        .position
        .iter()
        .map(|x| x.y)
        .fold(Real::INFINITY, Real::min);
    let base: Vec<Real> = points
        .position
        .iter()
        .zip(&points.stress)
        .filter(|(x, _)| x.y < lowest + 1e-6)
        .map(|(_, s)| s.yy)
        .collect();
    base.iter().sum::<Real>() / base.len() as Real
}
