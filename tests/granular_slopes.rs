//! Cohesionless slopes brought under gravity at the default settings: one
//! gentler than the friction angle stays where it was placed, one steeper
//! fails. A stable slope's points must come to rest, not carry velocities
//! the grid does not: under pure FLIP the face of the gentle slope keeps
//! points moving at over 1 cm/s and its toe creeps.

use mpdem::plugins::FrontLog;
use mpdem::prelude::*;
use std::path::Path;

/// The slope's height (m).
const HEIGHT: Real = 0.2;

/// A Drucker–Prager slope (φ = 35°, c = 0) 0.2 m high against a slip wall
/// on a rough floor, its crest 0.1 m long and its face reaching the floor
/// at x = `toe`, from rest and stress-free under gravity for 2 s. No
/// numerical option is named.
fn slope(toe: Real) -> Scene {
    let source = format!(
        r#"Scene(
    grid: (origin: (0.0, 0.0), cell_size: 0.02, cells: (40, 15), edges: (left: Slip, bottom: Fixed)),
    time: (dt: 1e-4, end: 2.0),
    gravity: (0.0, -9.81),
    materials: [
        (name: "sand", density: 2000.0, model: DruckerPrager((
            youngs_modulus: 5e6, poisson_ratio: 0.3, friction_angle: 35.0,
            dilation_angle: 0.0, cohesion: 0.0))),
    ],
    bodies: [
        (name: "slope", material: "sand", points_per_cell: 2,
         shape: Polygon(vertices: [(0.0, 0.0), ({toe}, 0.0), (0.1, {HEIGHT}), (0.0, {HEIGHT})])),
    ],
    output: (probe_interval: Some(0.01), fronts: true),
)"#
    );
    Scene::parse(&source, Path::new("slope.ron")).expect("the slope scene is valid")
}

/// The slope run to its end: its points' largest speed at the end (m/s)
/// and how far its toe, where the surface thins below 5% of the height,
/// moved (m).
fn settle(toe: Real) -> (Real, Real) {
    let mut sim = Simulation::from_scene(&slope(toe)).unwrap();
    sim.run().expect("the slope runs to its end");
    let fronts = &sim.world().resource::<FrontLog>().samples;
    let moved = fronts.last().unwrap().toe_5 - fronts.first().unwrap().toe_5;
    let points = sim.points_of("slope").unwrap();
    let fastest = points
        .velocity
        .iter()
        .map(|v| v.length())
        .fold(0.0, Real::max);
    (fastest, moved)
}

#[test]
fn a_slope_gentler_than_its_friction_angle_settles_and_a_steeper_one_fails() {
    // 1:2, 26.6° against φ = 35°: at rest within 5 mm/s, its toe within 1%
    // of the height of where it was placed (measured: 0.4 mm/s, 0.03 mm).
    let (fastest, moved) = settle(0.5);
    assert!(
        fastest < 5e-3,
        "the gentle slope's points move at {fastest} m/s"
    );
    assert!(
        moved.abs() < 0.01 * HEIGHT,
        "the gentle slope's toe moved {moved} m"
    );
    // 2:1, 63°: the face slides out, its toe by a good part of the height
    // (measured: 8 cm).
    let (_, moved) = settle(0.2);
    assert!(
        moved > 0.1 * HEIGHT,
        "the steep slope's toe moved {moved} m"
    );
}
