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
//! prints the same suite for every candidate setting.

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
/// undamped block–block springs, for 1 s (the rigid-block integrator alone:
/// no body, so the numerical settings do not enter): its kinetic and gravitational
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
/// with friction `friction`, gravity applied at once or, with
/// `ramp_stages`, brought in over 0.5 s by that many equal steps (one
/// stage each). Returns the energy samples of the `hold` seconds at full
/// gravity and how far the block's centre of mass moved along the slope
/// then (m).
fn block_on_a_slope(
    settings: Settings,
    slope: f64,
    friction: f64,
    ramp_stages: usize,
    hold: f64,
) -> (Vec<EnergySample>, f64) {
    let mut scene = common::load_scene("block_on_ground.ron");
    let angle = slope.to_radians();
    let full = 9.81 * DVec2::new(angle.sin(), -angle.cos());
    scene.gravity = full;
    scene.bodies[0].shape = mpdem::scene::Shape::Rectangle {
        min: DVec2::new(0.1, 0.1),
        max: DVec2::new(0.5, 0.2),
    };
    scene.blocks[0].position = DVec2::new(0.35, 0.05);
    scene.grid.cells = (40, 15);
    scene.blocks[0].contact.friction = friction;
    scene.probes.clear();
    scene.settings = settings;
    let ramp = if ramp_stages > 0 { 0.5 } else { 0.0 };
    if ramp_stages > 0 {
        let each = ramp / ramp_stages as f64;
        scene.stages = (1..=ramp_stages)
            .map(|k| {
                let mut stage = mpdem::scene::StageSpec::new(
                    format!("ramp {k}"),
                    mpdem::scene::StageEnd::Duration(each),
                );
                stage.gravity = Some(full * (k as f64 / ramp_stages as f64));
                stage
            })
            .collect();
        let mut held = mpdem::scene::StageSpec::new("hold", mpdem::scene::StageEnd::Duration(hold));
        held.gravity = Some(full);
        scene.stages.push(held);
    }
    scene.time.end = ramp + hold;
    let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    let centre = |sim: &mut Simulation| {
        let points = sim.points_of("block").expect("block");
        let moment: DVec2 = points
            .position
            .iter()
            .zip(&points.mass)
            .map(|(x, m)| *m * *x)
            .sum();
        moment.x / points.mass.iter().sum::<f64>()
    };
    sim.run_until(ramp).unwrap_or_else(|e| panic!("{e}"));
    let start = centre(&mut sim);
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    let creep = centre(&mut sim) - start;
    let held = sim
        .world()
        .resource::<EnergyLog>()
        .samples
        .iter()
        .filter(|s| s.time >= ramp - 1e-12)
        .copied()
        .collect();
    (held, creep)
}

/// (f) On a 20° slope with μ = 0.5 (tan 20° = 0.36), gravity ramped in over
/// 0.5 s in 100 steps of 1% (every 5 ms, about one and a half periods of
/// the block bouncing on its springs, 3.4 ms): the balance over the second
/// after the ramp, and the creep then. (In ten steps of 10% the ramp sets
/// the block bouncing: the contacts lose their normal force in turn and
/// the block slides 17 mm in that second, as a block loaded at once does,
/// see `a_suddenly_loaded_block_creeps_down_its_slope_as_by_finite_elements`.)
fn block_held_by_friction(settings: Settings) -> (Outcome, f64) {
    let (samples, creep) = block_on_a_slope(settings, 20.0, 0.5, 100, 1.0);
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
    failed.extend(held_by_friction(label, settings));
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
    let schemes = [
        (Usf, PaperEq11b),
        (Usf, NewGridVelocity),
        (Usf, RemappedVelocity),
        (Usl, PaperEq11b),
        (Usl, RemappedVelocity),
        (Musl, RemappedVelocity),
        (Musl, NewGridVelocity),
    ]
    .map(|(scheme, update)| {
        let settings = Settings {
            scheme,
            position_update: Some(update),
            ..Settings::default()
        };
        (format!("{scheme:?} {update:?}"), settings)
    });
    let walls = Settings {
        flip_from_unconstrained: true,
        ..Settings::default()
    };
    let candidates = schemes
        .into_iter()
        .chain([("defaults with flip_from_unconstrained".to_string(), walls)]);
    for (label, settings) in candidates {
        match std::panic::catch_unwind(|| suite(&label, settings)) {
            Ok(failed) => println!("{label}: over the bound: {failed:?}"),
            Err(_) => println!("{label}: a case failed to run (see the panic above)"),
        }
    }
}

#[test]
fn a_suddenly_loaded_block_creeps_down_its_slope_as_by_finite_elements() {
    // The squat block on a 20° slope with μ = 0.4, 10% above tan 20°,
    // gravity applied at once, undamped, 0.5 s. It drops onto its contact
    // springs and bounces on them, its normal force swinging between about
    // zero and twice its weight, so friction lets it slip while the force
    // is low: it creeps down the slope. The same elastic block on the same
    // disks and springs by explicit finite elements
    // (`mpdem_verify::elastic_block`) creeps alike, so the creep is the
    // model's stick–slip, not the material point method's error.
    let angle = 20f64.to_radians();
    let friction = 0.4;
    let (samples, creep) = block_on_a_slope(Settings::default(), 20.0, friction, 0, 0.5);
    let balance = Outcome::of(&samples);
    let scene = common::load_scene("block_on_ground.ron");
    let fe = mpdem_verify::elastic_block::ElasticBlock {
        size: DVec2::new(0.4, 0.1),
        material: match scene.materials[0].model {
            mpdem::materials::MaterialModel::LinearElastic(m) => m,
            _ => panic!("the block is linear elastic"),
        },
        density: scene.materials[0].density,
        gravity: 9.81 * DVec2::new(angle.sin(), -angle.cos()),
        point_spacing: 0.01,
        contact: mpdem::contact::ContactLaw {
            friction,
            ..scene.blocks[0].contact
        },
    };
    let reference = fe.centre_displacements(&[0.5])[0].x;
    println!(
        "suddenly loaded block, μ = {friction}: creeps {creep:.4e} m in 0.5 s (finite elements \
         {reference:.4e} m, {:+.1}%); balance swing {:.2}% of the largest energy {:.3e} J/m",
        100.0 * (creep / reference - 1.0),
        100.0 * balance.ratio(),
        balance.scale
    );
    // The finite-element block does creep (a rigid block on these springs
    // would not move at all), by centimetres.
    assert!(reference > 0.01, "the reference creeps {reference} m");
    // Stick–slip sums many slips, each set off by the contact forces'
    // fluctuations, which the two discretisations carry differently: 10%
    // (measured 3.8%; halving the engine's step moves its creep by 17%,
    // 27.6 -> 23.0 mm, so it is resolved to about that).
    assert!(
        (creep / reference - 1.0).abs() < 0.1,
        "creep {creep} m against {reference} m by finite elements"
    );
    assert!(
        within(balance.ratio(), BOUND),
        "balance {:.2}%",
        100.0 * balance.ratio()
    );
}
