//! Nonrigid–nonrigid contact on the multi-layer grid (paper section 3.3):
//! two colliding rings.

mod common;

use mpdem::prelude::*;
use mpdem::resources::PositionUpdate;
use mpdem_verify::rings::{energy_drift, energy_samples, widest_balance_swing};

/// The two-rings scene, with 1 point per cell instead of 2 × 2 when
/// `reduced` (a quarter of the points; the collision is the same) and then
/// the default contact radius (half the spacing: the scene's radius is set
/// for 2 × 2 points and would leave gaps between the disks).
fn rings(reduced: bool, with_contact: bool) -> Scene {
    let mut scene = common::load_scene("two_rings.ron");
    if reduced {
        for body in &mut scene.bodies {
            body.points_per_cell = 1;
            body.contact_radius = None;
        }
    }
    if !with_contact {
        scene.body_contacts.clear();
    }
    scene
}

/// Centre of mass of a ring and its velocity.
fn centre(sim: &mut Simulation, name: &str) -> (DVec2, DVec2) {
    mpdem_verify::rings::centre(sim, name).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn rings_on_separate_layers_pass_through_each_other_without_a_contact_law() {
    let mut scene = rings(true, false);
    scene.time.end = 2.5e-3;
    let mut sim = common::run_scene(&scene);
    let (left, v_left) = centre(&mut sim, "left");
    let (right, _) = centre(&mut sim, "right");
    println!(
        "no contact law: centres at {:.4} / {:.4} m",
        left.x, right.x
    );
    // 2.5 ms at 30 m/s: each centre moves 75 mm, so they have crossed.
    assert!(left.x > right.x, "{left} vs {right}");
    assert!(
        (v_left.x - 30.0).abs() < 1e-6 * 30.0,
        "untouched ring keeps its speed: {v_left}"
    );
}

#[test]
fn colliding_rings_rebound_and_stay_whole() {
    // The scene as it is (2 × 2 points per cell, ~12 s; with 1 point per
    // cell the rings rebound at only 4 m/s and distort far more, measured):
    // rebound, no point torn off, energy within 5%, the balance with what
    // the contacts dissipated within 2%: see mpdem_verify::rings.
    common::verify_case("two_rings");
}

#[test]
fn a_ring_thrown_at_a_rigid_wall_keeps_its_energy_balance() {
    // The left ring of the scene at +30 m/s against a fixed wall where the
    // right ring was, one point per cell (the balance, not the rebound, is
    // checked), with the rings' law: the point–block springs' energy and
    // friction enter the balance.
    let text = std::fs::read_to_string(common::scene_path("two_rings.ron")).expect("scene");
    let right = text
        .find("        (\n            name: \"right\"")
        .expect("right ring");
    let output = text.find("    output:").expect("output");
    let wall = "    ],\n    blocks: [(\n        name: \"wall\",\n        shape: Cuboid(half_extents: (0.01, 0.1)),\n        \
                position: (0.1, 0.05),\n        motion: Fixed,\n        \
                contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.2),\n    )],\n";
    let text = format!("{}{wall}{}", &text[..right], &text[output..]);
    let mut scene =
        Scene::parse(&text, &common::scene_path("ring_wall.ron")).unwrap_or_else(|e| panic!("{e}"));
    scene.bodies[0].points_per_cell = 1;
    scene.bodies[0].contact_radius = None;
    let sim = common::run_scene(&scene);
    let samples = energy_samples(&sim);
    let last = samples[samples.len() - 1];
    let peak_contact = samples.iter().map(|s| s.contact).fold(0.0, Real::max);
    let widest = widest_balance_swing(samples);
    println!(
        "ring on a wall: energy {:.1} -> {:.1} J/m, contact springs up to {:.1} J/m, dissipated {:.2} J/m, \
         balance widest swing {:.2}%",
        samples[0].total(),
        last.total(),
        peak_contact,
        last.dissipated,
        100.0 * widest
    );
    // The springs hold 9.6% of the energy at the impact (measured), so
    // leaving them out would show; what the balance still moves by is the
    // scheme's own error, measured 1.21% under the scene's eq. 11b (the
    // energy itself falls 4.4%, the tangential forces having taken 5.1%;
    // before the contacts took the actual motion, 1.4%, and 0.5% with the
    // forward update).
    assert!(peak_contact > 0.05 * samples[0].total(), "{peak_contact}");
    assert!(widest <= 0.02, "balance swings by {widest}");
}

/// What a run's body contacts looked like over all its steps.
struct ContactShape {
    /// Mean |n_y| of the normals weighted by the normal force: 0 for
    /// normals along the line of centres (x), 1 across it.
    across: Real,
    /// Mean overlap of the pairs in contact, as a fraction of the disks'
    /// radius, over all steps.
    mean_overlap: Real,
    /// Deepest overlap, as a fraction of the disks' radius.
    deepest: Real,
}

/// Runs a scene to its end and returns it with the shape of its contacts.
fn run_measuring_contacts(scene: &Scene) -> (Simulation, ContactShape) {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    let (mut across, mut total, mut deepest) = (0.0, 0.0, 0.0);
    let (mut overlaps, mut pairs) = (0.0, 0);
    while !sim.clock().finished() {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
        let contacts = sim.world().resource::<mpdem::resources::BodyContacts>();
        for c in &contacts.current {
            let normal = c.force - c.tangential;
            across += normal.y.abs();
            total += normal.length();
            deepest = Real::max(deepest, c.overlap / c.radius);
            overlaps += c.overlap / c.radius;
            pairs += 1;
        }
    }
    (
        sim,
        ContactShape {
            across: across / total,
            mean_overlap: overlaps / Real::from(pairs),
            deepest,
        },
    )
}

#[test]
#[ignore = "the full scene three times, 1 minute: why the scene's disks cover the points' domains"]
fn disks_that_only_reach_the_outline_interlock_and_dissipate() {
    // The impact pressure, about ρ c v = 1010 × 394 × 30 = 1.2e7 Pa, puts
    // 9.5e3 N/m on each pair of surface points (one per 0.8 mm): the
    // paper's k_n = 1e7 N/m² needs overlaps near a disk's diameter. With
    // disks of half the spacing (the default), a surface is a row of bumps
    // with valleys a disk deep: the other ring's points sink into them and
    // the surfaces interlock rows deep, with normals far from the line of
    // centres, and μ = 0.2 friction on those pairs dissipates. The scene's
    // disks through the corners of the points' domains (radius spacing/√2)
    // leave valleys 0.41 of a disk deep: fewer pairs, shallower overlaps,
    // normals nearer the line of centres, little friction.
    let peak_contacts = |sim: &Simulation| {
        sim.world()
            .resource::<mpdem::resources::BodyPairLog>()
            .samples
            .iter()
            .map(|s| s.summary.contacts)
            .max()
            .unwrap_or(0)
    };
    let dissipated = |sim: &Simulation| {
        let samples = energy_samples(sim);
        samples[samples.len() - 1].dissipated / samples[0].total()
    };
    let mut half = rings(false, true);
    for body in &mut half.bodies {
        body.contact_radius = None;
    }
    let (covering, covering_shape) = run_measuring_contacts(&rings(false, true));
    let (outline, outline_shape) = run_measuring_contacts(&half);
    half.body_contacts[0].law.friction = 0.0;
    let frictionless_default = energy_drift(&common::run_scene(&half));
    half.settings.position_update = Some(PositionUpdate::PaperEq11b);
    let frictionless_outline = energy_drift(&common::run_scene(&half));
    half.settings.position_update = Some(PositionUpdate::NewGridVelocity);
    let frictionless_forward = energy_drift(&common::run_scene(&half));
    let report = |name: &str, sim: &Simulation, shape: &ContactShape| {
        println!(
            "{name}: {} pairs at most, mean |n_y| {:.2}, overlap {:.2} r mean, {:.2} r deepest, \
             dissipated {:.2}%, drift {:+.2}%",
            peak_contacts(sim),
            shape.across,
            shape.mean_overlap,
            shape.deepest,
            100.0 * dissipated(sim),
            100.0 * energy_drift(sim)
        );
    };
    report("disks of half the spacing", &outline, &outline_shape);
    report("disks covering the domains", &covering, &covering_shape);
    println!(
        "disks of half the spacing without friction: drift {:+.2}% (eq. 11b), {:+.2}% (forward update), \
         {:+.2}% (the default remapped update)",
        100.0 * frictionless_outline,
        100.0 * frictionless_forward,
        100.0 * frictionless_default
    );
    // Each bound sits between the two measured values with a margin
    // (measured: 225 / 99 pairs at most, mean |n_y| 0.65 / 0.35, mean
    // overlap 0.55 / 0.30 r, dissipated 8.48% / 2.25%, drift −8.30% / −2.33%).
    assert!(
        outline_shape.across > 0.6,
        "half-spacing disks' normals {}",
        outline_shape.across
    );
    assert!(
        covering_shape.across < outline_shape.across - 0.2,
        "covering disks' normals {}",
        covering_shape.across
    );
    assert!(
        3 * peak_contacts(&covering) < 2 * peak_contacts(&outline),
        "{} vs {} pairs",
        peak_contacts(&covering),
        peak_contacts(&outline)
    );
    assert!(
        outline_shape.mean_overlap > 0.4 && covering_shape.mean_overlap < 0.4,
        "mean overlaps {} and {}",
        outline_shape.mean_overlap,
        covering_shape.mean_overlap
    );
    assert!(dissipated(&outline) > 0.05 && dissipated(&covering) < 0.03);
    assert!(
        energy_drift(&outline) < -0.05,
        "the issue's 5% is missed with half-spacing disks"
    );
    assert!(energy_drift(&covering).abs() <= 0.05);
    // Without friction the deep pairs' springs, whose force is taken at
    // x^n, vibrate and gain energy under eq. 11b, which moves the points
    // with the mean of the old and new velocities (phase-space area ×
    // (1 + (ωΔt)²/2) a step; measured +13.7%); the forward update is
    // symplectic Euler for them (measured −2.5%), and the default remapped
    // update moves them by the momentum the points carry (measured +0.6%).
    assert!(
        frictionless_outline > 0.10,
        "eq. 11b drift {frictionless_outline}"
    );
    assert!(
        frictionless_forward.abs() < 0.05,
        "forward drift {frictionless_forward}"
    );
    assert!(
        frictionless_default.abs() < 0.05,
        "remapped drift {frictionless_default}"
    );
}

#[test]
fn body_contacts_give_the_same_state_for_one_and_two_threads() {
    let mut scene = rings(true, true);
    scene.time.end = 6e-4;
    let hash = || {
        let mut sim = Simulation::from_scene(&scene).unwrap();
        sim.run().unwrap();
        assert!(
            !sim.world()
                .resource::<mpdem::resources::BodyContacts>()
                .current
                .is_empty()
        );
        sim.state_hash()
    };
    let one = common::with_threads(1, hash);
    let two = common::with_threads(2, hash);
    assert_eq!(one, two);
}

#[test]
fn bad_body_contacts_are_refused() {
    let mut scene = rings(true, true);
    scene.body_contacts[0].between.1 = "middle".into();
    let message = common::refusal(&scene);
    assert!(
        message.contains("unknown body or group 'middle'"),
        "{message}"
    );
    let mut scene = rings(true, true);
    scene.body_contacts[0].law.friction = -1.0;
    let message = common::refusal(&scene);
    assert!(
        message.contains("friction: expected a friction coefficient from 0 to 10"),
        "{message}"
    );
    let mut scene = rings(true, true);
    scene.bodies[1].contact_radius = Some(scene.grid.cell_size);
    let message = common::refusal(&scene);
    assert!(message.contains("more than half a cell"), "{message}");
}

#[test]
fn frictionless_rings_keep_their_energy() {
    let mut scene = rings(false, true);
    scene.body_contacts[0].law.friction = 0.0;
    let drift = energy_drift(&common::run_scene(&scene));
    println!("energy drift without friction: {drift:+.4}");
    // Without friction nothing dissipates: what is left is the scheme's
    // own error (measured −0.1%), held to the 2% of the energy balance.
    assert!(drift.abs() < 0.02, "drift {drift}");
}
