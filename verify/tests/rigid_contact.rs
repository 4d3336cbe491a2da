//! Rigid–nonrigid DEM contact (paper section 3.2).

mod common;

use mpdem::components::{BlockContacts, GridLayer, MaterialPoints};
use mpdem::contact::ForceApplication;
use mpdem::prelude::*;
use mpdem::resources::{BlockLog, EnergyLog, EnergySample, PositionUpdate, UpdateScheme};

#[test]
fn ground_carries_the_weight_of_a_block_at_rest() {
    let sim = common::run_scene(&common::load_scene("block_on_ground.ron"));
    let log = sim.world().resource::<BlockLog>();
    let weight = 3000.0 * 0.1 * 0.4 * 9.81;
    let last = log.samples.last().expect("samples");
    let error = (-last.force.y / weight - 1.0).abs();
    println!(
        "block on ground: reaction {:.3} N/m vs m g = {weight:.3} N/m ({:+.4}%)",
        -last.force.y,
        100.0 * error
    );
    // Target of the issue: 2%.
    assert!(error <= 0.02, "reaction {} vs {weight}", last.force.y);
    // The block comes to rest: its top's vertical speed decays.
    let top = common::probe_samples(&sim, "top");
    let early = top
        .iter()
        .filter(|s| s.time < 0.1)
        .map(|s| s.velocity.y.abs())
        .fold(0.0, Real::max);
    let late = top
        .iter()
        .filter(|s| s.time > 0.4)
        .map(|s| s.velocity.y.abs())
        .fold(0.0, Real::max);
    println!("block on ground: top speed {early:.3e} m/s early, {late:.3e} m/s late");
    assert!(late < 1e-2 * early, "speed {early} -> {late}");
}

/// Total external force on the layer after one step's transfer, and the sum
/// of gravity and contact forces on the points.
fn delivered(application: ForceApplication) -> (DVec2, DVec2) {
    let mut scene = common::load_scene("block_on_ground.ron");
    scene.contact.force_application = application;
    let mut sim = Simulation::from_scene(&scene).unwrap();
    // Let the block press on the ground first.
    for _ in 0..200 {
        sim.step().unwrap();
    }
    let body = sim.bodies()[0].0;
    let world = sim.world();
    let points = world.get::<MaterialPoints>(body).unwrap();
    let layer = world.get::<GridLayer>(body).unwrap();
    let on_grid: DVec2 = layer.nodes().iter().map(|n| n.external_force).sum();
    let expected: DVec2 = (0..points.len())
        .map(|p| points.mass[p] * DVec2::new(0.0, -9.81) + points.contact_force[p])
        .sum();
    let contacts: usize = world
        .iter_entities()
        .filter_map(|e| e.get::<BlockContacts>())
        .map(|c| c.current.len())
        .sum();
    assert!(contacts > 0, "no contact after 200 steps");
    (on_grid, expected)
}

#[test]
fn both_force_applications_deliver_the_whole_contact_force() {
    for application in [
        ForceApplication::BodyForce,
        ForceApplication::Traction { points: 5 },
    ] {
        let (on_grid, expected) = delivered(application);
        // Partition of unity of S_ip and of the hat functions: round-off of a
        // few hundred terms of order 1e3 N.
        assert!(
            (on_grid - expected).length() < 1e-9 * expected.length(),
            "{application:?}: {on_grid} vs {expected}"
        );
    }
}

#[test]
fn block_slides_down_a_slope_at_the_friction_limited_acceleration() {
    // The centre of mass's travel and velocity at 2 s within 2% of the
    // rigid block's: see mpdem_verify::sliding.
    common::verify_case("sliding_45");
}

#[test]
fn the_slopes_energy_balance_closes_with_the_work_of_friction() {
    let scene = common::load_scene("sliding_45.ron");
    let mut sim = common::run_scene(&scene);
    let points = sim.points_of("block").expect("block");
    let (u, v) = mpdem_verify::sliding::centre_of_mass_motion(points);
    let mass = points.total_mass();
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let (first, last) = (energy[0], *energy.last().expect("samples"));
    // Gravity's work goes to the block's motion and deformation and to
    // friction; nothing else takes work here (no damping, a fixed slope).
    let released = -last.gravity;
    let drift = (last.balance() - first.balance()) / released;
    // For comparison only: friction's work on the centre of mass, μ N s
    // (N = m g cos θ, the scene's gravity across the slope). What the
    // sliding dissipates is less: part of the friction force's work feeds
    // the elastic block's vibration (its kinetic energy beyond the centre's
    // and its strain energy).
    let on_centre = 0.5 * mass * -scene.gravity.y * u.x;
    println!(
        "sliding 45: gravity released {released:.0} J/m; kinetic {:.0} (of which vibration {:.0}), \
         strain {:.0}, contact {:.2}, dissipated {:.0} J/m (mu N s = {on_centre:.0}); \
         balance drift {:+.2}% of gravity's work",
        last.kinetic,
        last.kinetic - 0.5 * mass * v.length_squared(),
        last.strain,
        last.contact,
        last.dissipated,
        100.0 * drift
    );
    // The drift left is the MPM scheme's own numerical dissipation (FLIP
    // transfers, 16 x 16 points crossing cells for 2 s), measured +0.28%;
    // leaving out what the contacts dissipated would miss by 45%.
    assert!(drift.abs() <= 0.02, "balance drift {drift}");
}

#[test]
fn bad_blocks_are_refused_and_risky_ones_warned() {
    use mpdem::rigid::BlockShape;
    let base = common::load_scene("block_on_ground.ron");
    // A non-convex polygon: the message says to use a compound.
    let mut scene = base.clone();
    scene.blocks[0].shape = BlockShape::Polygon {
        vertices: vec![
            DVec2::ZERO,
            DVec2::new(0.3, 0.0),
            DVec2::new(0.15, 0.02),
            DVec2::new(0.15, 0.1),
        ],
    };
    let message = common::refusal(&scene);
    assert!(message.contains("Compound"), "{message}");
    // Negative friction.
    let mut scene = base.clone();
    scene.blocks[0].contact.friction = -0.1;
    let message = common::refusal(&scene);
    assert!(
        message.contains("friction: expected a friction coefficient from 0 to 10"),
        "{message}"
    );
    // A time step above 2 sqrt(m_p / k_n) and a block sunk into the body.
    let mut scene = base;
    scene.blocks[0].contact.normal_stiffness = 1e11;
    scene.blocks[0].position.y += 0.004;
    let sim = Simulation::from_scene(&scene).unwrap();
    let warnings = common::warning_text(sim.warnings());
    assert!(warnings.contains("contact stability limit"), "{warnings}");
    assert!(
        warnings.contains("block 'ground' overlaps body 'block' by 4"),
        "{warnings}"
    );
    // Block-block contacts far too stiff for the step: more sub-steps than
    // are taken: with k_n = 1e18 N/m the dropped box (200 kg/m) has a
    // contact period 2π sqrt(m / k_n) = 8.9e-8 s, 11 000 sub-steps of 1e-4 s.
    let mut scene = common::load_scene("rigid_drop.ron");
    scene.blocks[0].contact.normal_stiffness = 1e18;
    scene.blocks[1].contact.normal_stiffness = 1e18;
    let sim = Simulation::from_scene(&scene).unwrap();
    let warnings = common::warning_text(sim.warnings());
    assert!(warnings.contains("sub-steps per step"), "{warnings}");
    let quiet = Simulation::from_scene(&common::load_scene("rigid_drop.ron")).unwrap();
    assert!(quiet.warnings().is_empty(), "{:?}", quiet.warnings());
}

/// The samples of the block named `name`.
fn block_samples(sim: &Simulation, name: &str) -> Vec<mpdem::resources::BlockSample> {
    let log = sim.world().resource::<BlockLog>();
    let index = log
        .names
        .iter()
        .position(|n| n == name)
        .expect("block exists") as u32;
    log.samples
        .iter()
        .filter(|s| s.block == index)
        .copied()
        .collect()
}

#[test]
fn a_dropped_box_comes_to_rest_without_drift() {
    let sim = common::run_scene(&common::load_scene("rigid_drop.ron"));
    let samples = block_samples(&sim, "box");
    let last = samples.last().expect("samples");
    // Rest height: ground top 0.2 + half height 0.1 − m g / (2 k_n).
    let rest = 0.3 - 2500.0 * 0.4 * 0.2 * 9.81 / 2e7;
    println!(
        "rigid drop: y = {:.7} m vs {rest:.7} m, x drift {:e} m, angle {:e} rad",
        last.origin.y,
        last.origin.x - 1.0,
        last.angle
    );
    // 1e-7 m: far below the 1e-4 m sink, yet above round-off of the springs.
    assert!((last.origin.y - rest).abs() < 1e-7);
    assert!((last.origin.x - 1.0).abs() < 1e-12 && last.angle.abs() < 1e-12);
    // No creep over the last half second.
    let settled: Vec<_> = samples.iter().filter(|s| s.time > 1.0).collect();
    let spread = settled
        .iter()
        .map(|s| s.origin.y)
        .fold(Real::NEG_INFINITY, Real::max)
        - settled
            .iter()
            .map(|s| s.origin.y)
            .fold(Real::INFINITY, Real::min);
    assert!(spread < 1e-9, "creep of {spread:e} m");
}

#[test]
fn a_box_pushed_off_an_edge_tips_over_it() {
    let sim = common::run_scene(&common::load_scene("rigid_tip.ron"));
    let samples = block_samples(&sim, "box");
    let on_table = samples.iter().find(|s| s.time >= 0.15).expect("sample");
    let last = samples.last().expect("samples");
    println!(
        "rigid tip: at 0.15 s angle {:.4} rad, x {:.3}; at {:.2} s angle {:.3} rad, omega {:.3} rad/s",
        on_table.angle, on_table.origin.x, last.time, last.angle, last.angular
    );
    // Still flat while its centre is over the table (edge at x = 1) ...
    assert!(on_table.origin.x < 1.0 && on_table.angle.abs() < 0.01);
    // ... then it turns clockwise over the edge, past 45°, and falls.
    assert!(last.angle < -std::f64::consts::FRAC_PI_4 && last.angular < 0.0);
    assert!(
        last.origin.y < 0.5,
        "box still on the table at y = {}",
        last.origin.y
    );
}

#[test]
fn overlap_area_penetration_also_carries_the_weight() {
    // δ as the disks' overlap area, with an area stiffness giving a similar
    // sink: k_n = 1e7 N/m ÷ ~1e-3 m of chord ≈ 1e10 N/m².
    let mut scene = common::load_scene("block_on_ground.ron");
    scene.contact.penetration = mpdem::resources::Penetration::Area;
    scene.blocks[0].contact.normal_stiffness = 1e10;
    let sim = common::run_scene(&scene);
    let last = *sim
        .world()
        .resource::<BlockLog>()
        .samples
        .last()
        .expect("samples");
    let weight = 3000.0 * 0.1 * 0.4 * 9.81;
    println!(
        "block on ground, area penetration: reaction {:.3} N/m vs {weight:.3}",
        -last.force.y
    );
    assert!((-last.force.y / weight - 1.0).abs() <= 0.02);
}

#[test]
fn given_mass_properties_match_those_from_a_density() {
    // The drop scene's box: 0.4 m x 0.2 m at 2500 kg/m³ is 200 kg with
    // I = m (0.4² + 0.2²) / 12; given explicitly, the run must be identical.
    let from_density = common::load_scene("rigid_drop.ron");
    let mut given = from_density.clone();
    given.blocks[1].motion = mpdem::scene::MotionSpec::DynamicWithMass {
        mass: 200.0,
        inertia: 200.0 * (0.16 + 0.04) / 12.0,
        center: DVec2::ZERO,
        velocity: Default::default(),
    };
    let a = *block_samples(&common::run_scene(&from_density), "box")
        .last()
        .unwrap();
    let b = *block_samples(&common::run_scene(&given), "box")
        .last()
        .unwrap();
    assert!(
        (a.origin - b.origin).length() < 1e-12,
        "{} vs {}",
        a.origin,
        b.origin
    );
}

#[test]
fn travel_guard_rebuilds_early_and_catches_a_falling_block() {
    // The block falls at 2 m/s from 5 cm above the ground with the lists
    // rebuilt only every 100 000 steps: the first list is empty, so only
    // the guard (travel ≥ the 0.02 m margin) can let the contact be seen.
    let mut scene = common::load_scene("block_on_ground.ron");
    scene.blocks[0].position.y -= 0.05;
    scene.bodies[0].velocity = mpdem::scene::InitialVelocity::Constant(DVec2::new(0.0, -2.0));
    scene.contact.iter_period = Some(100_000);
    scene.time.end = 0.1;
    let mut sim = Simulation::from_scene(&scene).expect("scene");
    let ground_top = 0.05;
    let mut lowest = Real::INFINITY;
    while sim.world().resource::<Clock>().time < scene.time.end {
        sim.step().expect("step");
        let points = sim.points_of("block").expect("block");
        let disk_bottom = points
            .position
            .iter()
            .zip(&points.contact_radius)
            .map(|(x, r)| x.y - r)
            .fold(Real::INFINITY, Real::min);
        lowest = lowest.min(disk_bottom);
    }
    let mut lists = sim.world_mut().query::<&mpdem::components::NeighbourList>();
    let early = lists.single(sim.world()).expect("one block").early_rebuilds;
    println!(
        "travel guard: {early} early rebuilds, deepest disk {:.2e} m into the ground",
        ground_top - lowest
    );
    assert!(early >= 2, "the guard never fired ({early})");
    // A rigid block of 120 kg/m stopped from 2 m/s by its 10 bottom springs
    // of 1e7 N/m sinks v sqrt(M / (10 k_n)) = 2.2e-3 m (the elastic block
    // less); passing through would be 0.4 m.
    assert!(
        ground_top - lowest < 2.2e-3,
        "disks sank {} m",
        ground_top - lowest
    );
}

/// The block of `block_on_ground.ron` without its grid damping, run to
/// 1 s under `scheme` and `position_update`: the largest gain and the
/// largest loss of its energy balance (kinetic + strain + contact +
/// gravity + dissipated) over the largest work gravity did on it (the drop
/// onto the springs). With no damping nothing settles the bounce; no
/// energy may come from nowhere, nor vanish.
fn undamped_block_drift(scheme: UpdateScheme, position_update: PositionUpdate) -> (Real, Real) {
    let mut scene = common::load_scene("block_on_ground.ron");
    scene.settings.grid_damping = 0.0;
    scene.settings.scheme = scheme;
    scene.settings.position_update = Some(position_update);
    scene.time.end = 1.0;
    let sim = common::run_scene(&scene);
    let samples = &sim.world().resource::<EnergyLog>().samples;
    let work = samples.iter().map(|s| -s.gravity).fold(0.0, Real::max);
    let balance = || samples.iter().map(EnergySample::balance);
    let gain = balance().fold(0.0, Real::max);
    let loss = -balance().fold(0.0, Real::min);
    let end = samples.last().map_or(0.0, EnergySample::balance);
    println!(
        "undamped block, {scheme:?}, {position_update:?}: largest balance gain {gain:.3e} J/m, loss {loss:.3e} J/m, at the end {end:.3e} J/m, gravity's largest work {work:.3e} J/m"
    );
    (gain / work, loss / work)
}

// Target for the consistent updates: neither a gain nor a loss of 5% of
// gravity's work. The drop onto the stiff springs gains 1.6% at once in
// integration error under USF (measured), then nothing grows; before the
// contacts took the actual motion, the kinetic energy alone reached 500%
// in 0.5 s.

#[test]
fn an_undamped_block_on_the_ground_keeps_its_energy_under_musl() {
    let (gain, loss) = undamped_block_drift(UpdateScheme::Musl, PositionUpdate::RemappedVelocity);
    assert!(gain < 0.05, "balance gain {gain:.3e} of gravity's work");
    assert!(loss < 0.05, "balance loss {loss:.3e} of gravity's work");
}

#[test]
fn an_undamped_block_on_the_ground_keeps_its_energy_under_usf_with_remapped_positions() {
    let (gain, loss) = undamped_block_drift(UpdateScheme::Usf, PositionUpdate::RemappedVelocity);
    assert!(gain < 0.05, "balance gain {gain:.3e} of gravity's work");
    assert!(loss < 0.05, "balance loss {loss:.3e} of gravity's work");
}

/// Known limit: the paper's eq. 11b update (`PaperEq11b`) moves the points with the mean of the old and new nodal
/// velocities while the contact force was found at x^n, which multiplies
/// each contact spring's phase-space area by 1 + (ωΔt)²/2 per step; the
/// undamped block's balance gains many times gravity's work.
/// `NewGridVelocity` under USF gains slowly (the points move with the grid velocity, the
/// strain follows the velocity mapped from the points). This is the target
/// they should meet; they fail today.
#[test]
#[ignore = "known limit: PaperEq11b and USF NewGridVelocity feed undamped contact springs"]
fn an_undamped_block_on_the_ground_keeps_its_energy_under_the_other_updates() {
    for position_update in [PositionUpdate::PaperEq11b, PositionUpdate::NewGridVelocity] {
        let (gain, loss) = undamped_block_drift(UpdateScheme::Usf, position_update);
        assert!(
            gain < 0.05 && loss < 0.05,
            "{position_update:?}: balance gain {gain:.3e}, loss {loss:.3e} of gravity's work"
        );
    }
}
