//! The energy suite at the default numerical settings: scenes that name no
//! numerical option and no damping keep their energy through DEM contact.
//!
//! Each case's energy balance (kinetic + strain + contact + gravity +
//! inelastic + loads + blocks + dissipated + damped, `energy.csv`'s
//! `balance`) may move by at most 2% of the run's largest energy: the
//! largest magnitude any one of its terms (kinetic, strain, contact,
//! gravity, loads, blocks) reaches during the run. An undamped explicit
//! scheme conserves energy only to its integration error, which is small
//! but not zero; 2% is the bound the engine's defaults are held to. A
//! scheme that feeds the contact springs (the paper's eq. 11b without
//! damping) moves it by many times that.
//!
//! `cargo test --release --test safe_defaults -- --ignored --nocapture`
//! prints the same suite for every candidate setting, and runs the case
//! the defaults do not meet yet (a block held by friction on a slope).

mod common;

use mpdem::prelude::*;
use mpdem::resources::{BlockLog, EnergyLog, EnergySample, PositionUpdate, Settings, UpdateScheme};
use std::path::Path;

/// What one case measured.
struct Outcome {
    /// The largest departure of the balance from its start (J/m).
    swing: f64,
    /// The run's largest energy (J/m).
    scale: f64,
}

impl Outcome {
    fn of(samples: &[EnergySample]) -> Self {
        let first = samples[0].balance();
        let swing = samples
            .iter()
            .map(|s| (s.balance() - first).abs())
            .fold(0.0, f64::max);
        let scale = samples
            .iter()
            .flat_map(|s| [s.kinetic, s.strain, s.contact, s.gravity, s.loads, s.blocks])
            .map(f64::abs)
            .fold(0.0, f64::max);
        Self { swing, scale }
    }

    fn ratio(&self) -> f64 {
        self.swing / self.scale
    }
}

/// The suite's bound on the balance, a fraction of the run's largest energy.
const BOUND: f64 = 0.02;

/// Whether `value` is at most `bound` (a NaN is not).
fn within(value: f64, bound: f64) -> bool {
    value <= bound
}

/// A scene's energy samples after running it with `settings` (the scene's
/// own settings replaced: every case is undamped).
fn energies(mut scene: Scene, settings: Settings) -> Vec<EnergySample> {
    scene.settings = Settings {
        geometry: scene.settings.geometry,
        affine_transfer: scene.settings.affine_transfer,
        ..settings
    };
    let sim = common::run_scene(&scene);
    sim.world().resource::<EnergyLog>().samples.clone()
}

/// (a) The elastic block of `block_on_ground.ron` resting on rigid ground,
/// undamped, for 2 s.
fn block_resting(settings: Settings) -> Outcome {
    let mut scene = common::load_scene("block_on_ground.ron");
    scene.time.end = 2.0;
    Outcome::of(&energies(scene, settings))
}

/// (b) The same block dropped from 5 cm above the ground, for 1 s.
fn block_dropped(settings: Settings) -> Outcome {
    let mut scene = common::load_scene("block_on_ground.ron");
    scene.bodies[0].shape = mpdem::scene::Shape::Rectangle {
        min: DVec2::new(0.1, 0.15),
        max: DVec2::new(0.2, 0.55),
    };
    scene.grid.cells = (15, 32);
    scene.time.end = 1.0;
    Outcome::of(&energies(scene, settings))
}

/// (c) A dynamic box (0.4 m × 0.2 m, 2500 kg/m³) set on a fixed box through
/// undamped block–block springs, for 1 s: its kinetic and gravitational
/// energy and the springs' (two corners each sunk by δ, 2 · ½ k_n δ²; it
/// stays level), against m g times its deepest sinking.
fn box_on_box(settings: Settings) -> Outcome {
    let (stiffness, mass, g) = (1e7, 2500.0 * 0.4 * 0.2, 9.81);
    let text = format!(
        "Scene(
            grid: (origin: (0.0, 0.0), cell_size: 0.1, cells: (20, 10)),
            time: (dt: 1e-4, end: 1.0),
            gravity: (0.0, -{g}),
            materials: [], bodies: [],
            blocks: [
                (name: \"base\", shape: Cuboid(half_extents: (1.0, 0.1)), position: (1.0, 0.1),
                 motion: Fixed,
                 contact: (normal_stiffness: {stiffness}, tangential_stiffness: {stiffness}, friction: 0.5)),
                (name: \"box\", shape: Cuboid(half_extents: (0.2, 0.1)), position: (1.0, 0.3),
                 motion: Dynamic(density: 2500.0),
                 contact: (normal_stiffness: {stiffness}, tangential_stiffness: {stiffness}, friction: 0.5)),
            ],
        )"
    );
    let mut scene =
        Scene::parse(&text, Path::new("box_on_box.ron")).unwrap_or_else(|e| panic!("{e}"));
    scene.settings = settings;
    let sim = common::run_scene(&scene);
    let log = sim.world().resource::<BlockLog>();
    let inertia = mass * (0.4f64.powi(2) + 0.2f64.powi(2)) / 12.0;
    let energy: Vec<(f64, f64)> = log
        .samples
        .iter()
        .filter(|s| s.block == 1)
        .map(|s| {
            let kinetic =
                0.5 * mass * s.velocity.length_squared() + 0.5 * inertia * s.angular.powi(2);
            let potential = mass * g * (s.origin.y - 0.3);
            let sunk = (0.3 - s.origin.y).max(0.0);
            let springs = stiffness * sunk * sunk;
            (kinetic + potential + springs, mass * g * (0.3 - s.origin.y))
        })
        .collect();
    let swing = energy
        .iter()
        .map(|(e, _)| (e - energy[0].0).abs())
        .fold(0.0, f64::max);
    let scale = energy.iter().map(|(_, w)| w.abs()).fold(0.0, f64::max);
    Outcome { swing, scale }
}

/// (d) The two rings of `two_rings.ron` colliding at ±30 m/s.
fn two_rings(settings: Settings) -> Outcome {
    Outcome::of(&energies(common::load_scene("two_rings.ron"), settings))
}

/// (e) The block of `sliding_45.ron` sliding 2 s down its frictional slope.
fn block_sliding(settings: Settings) -> Outcome {
    Outcome::of(&energies(common::load_scene("sliding_45.ron"), settings))
}

/// A squat block of `block_on_ground.ron`'s material (0.4 m along the slope,
/// 0.1 m high, so that it slides before it topples) on its ground as a
/// slope of `slope` degrees (gravity turned, as in the toppling scenes)
/// with friction `friction`:
/// gravity from the start, or brought in over ten stages of 0.05 s. Returns
/// the energies after `hold` seconds at full gravity, and how far the
/// block's centre moved along the slope then (m).
fn block_on_a_slope(
    settings: Settings,
    slope: f64,
    friction: f64,
    ramped: bool,
    hold: f64,
) -> (Vec<EnergySample>, f64, f64) {
    let mut scene = common::load_scene("block_on_ground.ron");
    let angle = slope.to_radians();
    let full = 9.81 * DVec2::new(angle.sin(), -angle.cos());
    scene.gravity = full;
    scene.bodies[0].shape = mpdem::scene::Shape::Rectangle {
        min: DVec2::new(0.1, 0.1),
        max: DVec2::new(0.5, 0.2),
    };
    scene.blocks[0].position = DVec2::new(0.35, 0.05);
    scene.grid.cells = (35, 15);
    scene.blocks[0].contact.friction = friction;
    let ramp = if ramped { 0.5 } else { 0.0 };
    if ramped {
        scene.stages = (1..=10)
            .map(|k| {
                let mut stage = mpdem::scene::StageSpec::new(
                    format!("ramp {k}"),
                    mpdem::scene::StageEnd::Duration(0.05),
                );
                stage.gravity = Some(full * (k as f64 / 10.0));
                stage
            })
            .collect();
        let mut held = mpdem::scene::StageSpec::new("hold", mpdem::scene::StageEnd::Duration(hold));
        held.gravity = Some(full);
        scene.stages.push(held);
    }
    scene.time.end = ramp + hold;
    scene.probes.clear();
    scene.settings = Settings { ..settings };
    let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    sim.run_until(ramp).unwrap_or_else(|e| panic!("{e}"));
    let centre = |sim: &mut Simulation| {
        let points = sim.points_of("block").expect("block");
        let sum: DVec2 = points.position.iter().copied().sum();
        sum.x / points.len() as f64
    };
    let start = centre(&mut sim);
    let mut largest: f64 = 0.0;
    let steps = (hold / scene.time.dt).round() as u64;
    for _ in 0..steps {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
        largest = largest.max((centre(&mut sim) - start).abs());
    }
    let creep = centre(&mut sim) - start;
    let samples = sim.world().resource::<EnergyLog>().samples.clone();
    let held: Vec<EnergySample> = samples
        .into_iter()
        .filter(|s| s.time >= ramp - 1e-12)
        .collect();
    (held, creep, largest)
}

/// (f) On a 20° slope with μ = 0.5 (tan 20° = 0.36), gravity ramped in over
/// 0.5 s: the balance over the second after the ramp, and the creep then.
fn block_held_by_friction(settings: Settings) -> (Outcome, f64) {
    let (samples, creep, _) = block_on_a_slope(settings, 20.0, 0.5, true, 1.0);
    (Outcome::of(&samples), creep)
}

/// (g) A kinematic punch pushed 4 mm into an undamped Neo-Hookean pad, then
/// held still (the scene of `tests/energy_balance.rs`'s held punch, with
/// the default force application). The scale is the punch's work.
fn punch_pushed_then_held(settings: Settings) -> Outcome {
    let text = "Scene(
        grid: (origin: (0.0, 0.0), cell_size: 0.02, cells: (30, 15),
               edges: (left: Slip, right: Slip, bottom: Fixed, top: Free)),
        time: (dt: 2e-5, end: 0.3),
        gravity: (0.0, 0.0),
        materials: [(name: \"pad\", density: 2000.0,
                     model: NeoHookean((youngs_modulus: 2e7, poisson_ratio: 0.3)))],
        bodies: [(name: \"pad\", material: \"pad\",
                  shape: Rectangle(min: (0.0, 0.0), max: (0.6, 0.2)), points_per_cell: 1)],
        blocks: [(name: \"punch\", shape: Cuboid(half_extents: (0.05, 0.03)),
                  position: (0.3, 0.23), motion: Kinematic((linear: (0.0, 0.0), angular: 0.0)),
                  contact: (normal_stiffness: 5e7, tangential_stiffness: 5e7, friction: 0.3))],
        stages: [
            (name: \"push\", end: Duration(0.1),
             block_velocities: [(block: \"punch\", velocity: (linear: (0.0, -0.04), angular: 0.0))]),
            (name: \"hold\", end: Duration(0.2),
             block_velocities: [(block: \"punch\", velocity: (linear: (0.0, 0.0), angular: 0.0))]),
        ],
        output: (probe_interval: Some(1e-3)),
    )";
    let scene = Scene::parse(text, Path::new("punch.ron")).unwrap_or_else(|e| panic!("{e}"));
    Outcome::of(&energies(scene, settings))
}

/// Runs the whole suite under `settings`, prints each case and returns the
/// cases over the bound (and (f)'s creep over 1 mm).
fn suite(label: &str, settings: Settings) -> Vec<String> {
    let mut failed = Vec::new();
    let mut judge = |case: &str, outcome: Outcome| {
        println!(
            "{label}: {case}: balance swing {:.3e} of the largest energy {:.3e} J/m = {:.2}%",
            outcome.swing,
            outcome.scale,
            100.0 * outcome.ratio()
        );
        if !within(outcome.ratio(), BOUND) {
            failed.push(format!("{case}: {:.2}%", 100.0 * outcome.ratio()));
        }
    };
    judge("(a) block resting 2 s", block_resting(settings));
    judge("(b) block dropped 5 cm", block_dropped(settings));
    judge("(c) box on a box", box_on_box(settings));
    judge("(d) two rings", two_rings(settings));
    judge("(e) block sliding on a 45° slope", block_sliding(settings));
    judge(
        "(g) punch pushed then held",
        punch_pushed_then_held(settings),
    );
    failed
}

/// Case (f) under `settings`: prints it and returns what is over the
/// bound (the balance, and the creep over 1 mm).
fn held_by_friction(label: &str, settings: Settings) -> Vec<String> {
    let (held, creep) = block_held_by_friction(settings);
    println!(
        "{label}: (f) block held by friction on a 20° slope: balance swing {:.3e} of the largest \
         energy {:.3e} J/m = {:.2}%; creep along the slope in the second after the ramp {creep:.3e} m",
        held.swing,
        held.scale,
        100.0 * held.ratio()
    );
    let mut failed = Vec::new();
    if !within(held.ratio(), BOUND) {
        failed.push(format!("(f) balance {:.2}%", 100.0 * held.ratio()));
    }
    if !within(creep.abs(), 1e-3) {
        failed.push(format!("(f) creep {creep:.3e} m"));
    }
    failed
}

#[test]
fn the_defaults_keep_the_energy_of_every_suite_case() {
    let failed = suite("defaults", Settings::default());
    assert!(
        failed.is_empty(),
        "over the bound at the defaults: {failed:?}"
    );
}

/// Known limit: an undamped elastic block held by friction on a slope
/// creeps. Every candidate setting fails it (USF with remapped positions:
/// 17 mm in the second after the ramp, the balance 3.1%); a normal dashpot
/// on the contact (c_n = 1e3 N s/m, about 0.3 of critical for one point on
/// its spring) stops the creep (5e-8 m), so the creep comes from the
/// points' undamped vibration on their contact springs, each slipping
/// while its normal force dips.
#[test]
#[ignore = "known limit: undamped point contacts ratchet down a slope held by friction"]
fn the_defaults_hold_a_block_on_a_slope_by_friction() {
    let failed = held_by_friction("defaults", Settings::default());
    assert!(
        failed.is_empty(),
        "over the bound at the defaults: {failed:?}"
    );
}

#[test]
fn the_defaults_are_usf_with_remapped_positions_and_pure_flip() {
    let settings = Settings::default();
    assert_eq!(settings.scheme, UpdateScheme::Usf);
    assert_eq!(
        settings.position_update(),
        Some(PositionUpdate::RemappedVelocity)
    );
    assert_eq!(settings.pic_fraction, 0.0);
    assert!(!settings.affine_transfer);
}

#[test]
#[ignore = "a measurement: prints the suite for every candidate setting"]
fn the_suite_for_every_candidate() {
    use PositionUpdate::*;
    use UpdateScheme::*;
    for (scheme, update) in [
        (Usf, PaperEq11b),
        (Usf, NewGridVelocity),
        (Usf, RemappedVelocity),
        (Usl, PaperEq11b),
        (Usl, RemappedVelocity),
        (Musl, RemappedVelocity),
        (Musl, NewGridVelocity),
    ] {
        let settings = Settings {
            scheme,
            position_update: Some(update),
            ..Settings::default()
        };
        let label = format!("{scheme:?} {update:?}");
        match std::panic::catch_unwind(|| {
            let mut failed = suite(&label, settings);
            failed.extend(held_by_friction(&label, settings));
            failed
        }) {
            Ok(failed) => println!("{label}: over the bound: {failed:?}"),
            Err(_) => println!("{label}: a case failed to run (see the panic above)"),
        }
    }
}
