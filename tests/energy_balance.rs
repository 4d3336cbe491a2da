//! The energy balance with what works on the bodies from outside, the
//! stages' surface loads (`energy.csv`'s `loads`) and the blocks, moved or
//! moving (`blocks`), and with what the materials dissipate (`inelastic`).

mod common;

use mpdem::prelude::*;
use mpdem::resources::{BlockLog, EnergyLog, EnergySample};
use std::path::Path;

/// A pad of `model` (a RON material model), 0.4 m wide and 0.2 m high
/// (ρ = 2000 kg/m³, cell 0.02 m, 2 × 2 points per cell), on the grid's
/// fixed bottom between slip walls, no gravity, undamped unless `settings`
/// say otherwise, with `blocks` and `stages` (RON lists) above it.
fn pad(model: &str, settings: &str, blocks: &str, stages: &str, end: f64) -> Scene {
    let text = format!(
        "Scene(
            grid: (origin: (0.0, 0.0), cell_size: 0.02, cells: (20, 20),
                   edges: (left: Slip, right: Slip, bottom: Fixed, top: Free)),
            time: (dt: 2e-5, end: {end}),
            gravity: (0.0, 0.0),
            settings: ({settings}),
            materials: [(name: \"pad\", density: 2000.0, model: {model})],
            bodies: [(name: \"pad\", material: \"pad\",
                      shape: Rectangle(min: (0.0, 0.0), max: (0.4, 0.2)), points_per_cell: 2)],
            blocks: [{blocks}],
            stages: [{stages}],
            output: (probe_interval: Some(2e-5)),
        )"
    );
    Scene::parse(&text, Path::new("pad.ron")).unwrap_or_else(|e| panic!("{e}"))
}

/// Linear elasticity, E = 1e7 Pa and Poisson's ratio `poisson`.
fn elastic(poisson: f64) -> String {
    format!("LinearElastic((youngs_modulus: 1e7, poisson_ratio: {poisson}))")
}

/// The pad's top row's mean settlement (m), at its points' centres, half a
/// spacing (5 mm) below the loaded surface.
fn top_settlement(points: &MaterialPoints) -> f64 {
    let top: Vec<f64> = (0..points.len())
        .filter(|&p| points.initial_position[p].y > 0.19)
        .map(|p| points.initial_position[p].y - points.position[p].y)
        .collect();
    top.iter().sum::<f64>() / top.len() as f64
}

/// The widest swing of the balance over the run.
fn balance_swing(samples: &[EnergySample]) -> f64 {
    let first = samples[0].balance();
    samples
        .iter()
        .map(|s| (s.balance() - first).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_surcharge_s_work_closes_the_balance() {
    // A surcharge p = 1e5 Pa on the pad's top (ν = 0: uniaxial strain,
    // u = p H / E = 2 mm), settled by grid damping. At rest the loads have
    // done W = p L u, half of it stored as strain energy, half taken by the
    // damping.
    let scene = pad(
        &elastic(0.0),
        "grid_damping: 0.2",
        "",
        "(name: \"load\", end: Duration(0.3),
          tractions: [(body: \"pad\", side: Top, traction: (0.0, -1e5))])",
        0.3,
    );
    let mut sim = common::run_scene(&scene);
    let energy = sim.world().resource::<EnergyLog>().samples.clone();
    let last = *energy.last().expect("samples");
    let points = sim.points_of("pad").expect("pad");
    let settlement = top_settlement(points);
    // The surface settles by u = p H / E = 2 mm; the loads' work p L u.
    let (pressure, width, height, modulus) = (1e5, 0.4, 0.2, 1e7);
    let exact = pressure * width * pressure * height / modulus;
    let swing = balance_swing(&energy);
    println!(
        "surcharge: top points settle {settlement:.5e} m (p y / E = 1.95e-3), loads {:.3} J/m \
         (p L u = {exact}), strain {:.3}, damped {:.3}, kinetic {:.2e}; balance swing {swing:.3e} J/m",
        last.loads, last.strain, last.damped, last.kinetic
    );
    // Uniaxial strain of a linear elastic pad: the top points' settlement
    // within 1% of p y / E (the kinetic energy left at the end is 1e-5 of
    // the work).
    assert!(
        (settlement / 1.95e-3 - 1.0).abs() < 0.01,
        "settlement {settlement}"
    );
    // The loads column is minus the dead load's work on the surface's
    // settlement: within 1% (taken at the points' centres it would be 2.5%
    // short).
    assert!(
        (-last.loads / exact - 1.0).abs() < 0.01,
        "loads {} against p L u {exact}",
        last.loads
    );
    // Half the work is stored (a linear body loaded from rest), within 2%.
    assert!(
        (last.strain / (0.5 * exact) - 1.0).abs() < 0.02,
        "strain {}",
        last.strain
    );
    // The balance holds to the scheme's error: within 1% of the work over
    // the run, as for the column settling under gravity (verify/tests/damping.rs);
    // measured 0.4%; leaving out the loads would miss it by 100%. (Settled
    // by PIC 1.0 instead, the `damped` column takes 0.95% of W more than
    // W − U; with particle damping 0.7 as well, 3%, and the top points
    // settle 6% further than the strain says: eq. 11b's damped points
    // drift from the material, see `position_update` in the README.)
    assert!(swing < 0.01 * exact, "balance swings by {swing} of {exact}");
}

/// Trapezoidal integral of the power the blocks' motion puts into the
/// bodies, −(F · v + T ω) (F and T the points' force and torque on the
/// block), over the block log.
fn work_from_block_log(log: &BlockLog) -> f64 {
    log.samples
        .windows(2)
        .map(|w| {
            let power = |s: &mpdem::resources::BlockSample| {
                -(s.force.dot(s.velocity) + s.torque * s.angular)
            };
            0.5 * (power(&w[0]) + power(&w[1])) * (w[1].time - w[0].time)
        })
        .sum()
}

/// A kinematic punch 0.2 m wide whose disks touch the pad's top points',
/// driven down at 0.05 m/s while it turns at 0.1 rad/s, μ = 0.3.
const TURNING_PUNCH: &str = "(name: \"punch\", shape: Cuboid(half_extents: (0.1, 0.05)),
    position: (0.2, 0.25), motion: Kinematic((linear: (0.0, -0.05), angular: 0.1)),
    contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.3))";

#[test]
fn a_punch_driven_into_the_pad_is_counted_by_its_work() {
    // A kinematic punch 0.2 m wide, touching the pad's top points' disks,
    // driven 1.5 mm into it at 0.05 m/s while it turns at 0.1 rad/s (its
    // edges 0.3 mm apart in height at the end: the work of its torque
    // counts too), undamped, positions remapped (the paper's eq. 11b lets
    // undamped springs gain energy; see `position_update`).
    let scene = pad(
        &elastic(0.3),
        "scheme: Usf, position_update: Some(RemappedVelocity)",
        TURNING_PUNCH,
        "",
        0.03,
    );
    let sim = common::run_scene(&scene);
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let last = *energy.last().expect("samples");
    let driven = work_from_block_log(sim.world().resource::<BlockLog>());
    let swing = balance_swing(energy);
    println!(
        "punch: blocks {:.4} J/m, from the reaction's power {driven:.4}; kinetic {:.4}, strain {:.4}, \
         contact {:.4}, dissipated {:.4}; balance swing {swing:.3e} J/m",
        last.blocks, last.kinetic, last.strain, last.contact, last.dissipated
    );
    assert!(-last.blocks > 0.0, "the punch gives the pad energy");
    // The blocks column against the reaction's power integrated over the
    // samples (every step): two quadratures of one work, within 1%.
    assert!(
        (-last.blocks / driven - 1.0).abs() < 0.01,
        "blocks {} against {driven}",
        last.blocks
    );
    // Undamped, the rest of the balance is the scheme's error: within 2% of
    // the punch's work, measured 0.27% (leaving the punch out would miss
    // by 100%).
    assert!(
        swing < 0.02 * driven,
        "balance swings by {swing} of {driven}"
    );
}

#[test]
fn a_dynamic_block_s_loss_is_the_pads_gain() {
    // A 200 kg/m box thrown down at 1 m/s and spinning at 3 rad/s onto the
    // pad (1 mm above it, so one corner lands first), undamped, positions
    // remapped: the energy the bodies' `blocks` column says the box gave
    // them is what the box lost of ½ M v² + ½ I ω².
    let scene = pad(
        &elastic(0.3),
        "scheme: Usf, position_update: Some(RemappedVelocity)",
        "(name: \"box\", shape: Cuboid(half_extents: (0.2, 0.05)), position: (0.2, 0.251),
          motion: Dynamic(density: 5000.0, velocity: (linear: (0.0, -1.0), angular: 3.0)),
          contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.3))",
        "",
        0.03,
    );
    let sim = common::run_scene(&scene);
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let blocks = &sim.world().resource::<BlockLog>().samples;
    let mass = 5000.0 * 0.4 * 0.1;
    let inertia = mass * (0.4f64.powi(2) + 0.1f64.powi(2)) / 12.0;
    let box_energy = |s: &mpdem::resources::BlockSample| {
        0.5 * mass * s.velocity.length_squared() + 0.5 * inertia * s.angular * s.angular
    };
    let start = 0.5 * mass + 0.5 * inertia * 9.0;
    // The box moves by symplectic Euler (v += F Δt / M, then x += v Δt), so
    // its kinetic energy changes by F · Δx − |F|² Δt² / (2M) (and the
    // same for the turning) each step, while the work the contacts count
    // is F · Δx: the box loses Σ |F|² Δt² / (2M) + T² Δt² / (2I) more than
    // it gives, its integrator's own error.
    let dt = scene.time.dt;
    let mut integrator = 0.0;
    // Energy and block samples both start at t = 0 (every step here).
    let worst = blocks
        .iter()
        .zip(energy.iter())
        .map(|(b, e)| {
            assert_eq!(b.time, e.time);
            integrator +=
                (b.force.length_squared() / mass + b.torque * b.torque / inertia) * dt * dt / 2.0;
            (start - box_energy(b) + e.blocks - integrator).abs()
        })
        .fold(0.0, f64::max);
    let least = blocks.iter().map(box_energy).fold(f64::INFINITY, f64::min);
    let swing = balance_swing(energy);
    println!(
        "box: least kinetic energy {least:.2} of {start:.0} J/m; its integrator's loss {integrator:.3} J/m; \
         worst |loss + blocks − that| {worst:.3e} J/m; bodies' balance swing {swing:.3e} J/m"
    );
    assert!(least < 0.2 * start, "the box was stopped by the pad");
    // What the box lost is what the bodies' `blocks` column says it gave
    // them, plus its integrator's error, up to the chord of each step's
    // turn against its arc: the contacts count f · Δs, Δs the surface
    // point's actual motion, which differs from the torque's T ω Δt by
    // ½ (ω Δt)² f · r, r the arm from the box's centre (ω Δt ≤ 6e-5 here:
    // at most 1e-2 J/m over the impact; measured 3.6e-4, 2.3e-11 for a box
    // that does not turn). Within 1e-5 of its energy.
    assert!(worst < 1e-5 * start, "loss and gain differ by {worst}");
    // The bodies' own balance with the box's work: within 3% of its
    // energy, measured 1.4% (1.7% for a box that does not turn), as the block on the ground's drop onto its
    // springs (1.6% of gravity's work, verify/tests/rigid_contact.rs): the contact
    // springs' time integration.
    assert!(swing < 0.03 * start, "balance swings by {swing}");
}

#[test]
fn a_punch_into_a_plastic_pad_is_balanced_by_the_plastic_work() {
    // The punch of the test above driven 10 mm into a cohesive
    // Mohr–Coulomb pad (c = 20 kPa, φ = 20°, ψ = 0; Prandtl's bearing
    // pressure is about 15 c, 60 kN/m for the punch), undamped: most of its
    // work goes into plastic flow, which the `inelastic` column counts.
    let scene = pad(
        "MohrCoulomb((youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 20.0,
                      dilation_angle: 0.0, cohesion: 2e4, tension_cutoff: 2e4))",
        "scheme: Usf, position_update: Some(RemappedVelocity)",
        "(name: \"punch\", shape: Cuboid(half_extents: (0.1, 0.05)), position: (0.2, 0.25),
          motion: Kinematic((linear: (0.0, -0.1), angular: 0.0)),
          contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.3))",
        "",
        0.1,
    );
    let sim = common::run_scene(&scene);
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let last = *energy.last().expect("samples");
    let driven = -last.blocks;
    let swing = balance_swing(energy);
    println!(
        "plastic punch: blocks {:.2} J/m; inelastic {:.2}, strain {:.2}, kinetic {:.2}, contact {:.2}, \
         dissipated {:.2}; balance swing {swing:.3e} J/m",
        last.blocks, last.inelastic, last.strain, last.kinetic, last.contact, last.dissipated
    );
    // The pad yields: most of the punch's work is plastic (measured 59%).
    assert!(
        last.inelastic > 0.5 * driven,
        "inelastic {} of {driven}",
        last.inelastic
    );
    // The balance with the plastic work: within 2% of the punch's work, as
    // for the elastic pad, measured 0.4% (leaving it out would miss by
    // more than half).
    assert!(
        swing < 0.02 * driven,
        "balance swings by {swing} of {driven}"
    );
}

#[test]
fn under_particle_damping_remapped_points_settle_with_their_strain() {
    // The surcharged pad settled as the pile's stages settle the soil
    // (particle damping 0.7 with PIC 1.0): with the positions remapped the
    // top points settle by their strain, p y / E = 1.95 mm, and the
    // surcharge's work is p L u; under the paper's eq. 11b they drift
    // from it (measured +5.8%), which made the pile's q_c depend on the
    // cell (see scenes/pile_penetration.ron).
    let settled = |update: &str| {
        let scene = pad(
            &elastic(0.0),
            &format!(
                "scheme: Usf, pic_fraction: 1.0, particle_damping: 0.7, position_update: Some({update})"
            ),
            "",
            "(name: \"load\", end: Duration(0.3),
              tractions: [(body: \"pad\", side: Top, traction: (0.0, -1e5))])",
            0.3,
        );
        let mut sim = common::run_scene(&scene);
        let loads = sim
            .world()
            .resource::<EnergyLog>()
            .samples
            .last()
            .expect("samples")
            .loads;
        (top_settlement(sim.points_of("pad").expect("pad")), -loads)
    };
    let (remapped, work) = settled("RemappedVelocity");
    let (midpoint, _) = settled("PaperEq11b");
    println!(
        "damped pad: top points settle {remapped:.5e} m remapped, {midpoint:.5e} under eq. 11b \
         (p y / E = 1.95e-3); the load's work {work:.3} J/m (p L u = 80)"
    );
    // Within 1%, as the grid-damped pad's.
    assert!(
        (remapped / 1.95e-3 - 1.0).abs() < 0.01,
        "settlement {remapped}"
    );
    assert!((work / 80.0 - 1.0).abs() < 0.01, "work {work}");
}

/// An elastic footing, 0.2 m wide and 0.1 m high (E = 5e6 Pa, ν = 0.3,
/// ρ = 1800 kg/m³, cell 0.02 m, 2 × 2 points per cell), its base on the
/// grid's fixed (no-slip) floor and its sides free, under a step surcharge
/// of 1e4 Pa for 0.3 s, undamped: about 45 of its periods, with every mode
/// the step excites ringing. Returns the balance's widest swing and its
/// value at the end, over the largest work of the load.
fn footing_under_a_step_load(settings: &str) -> (f64, f64) {
    let text = format!(
        "Scene(
            grid: (origin: (0.0, 0.0), cell_size: 0.02, cells: (30, 20),
                   edges: (left: Slip, right: Slip, bottom: Fixed, top: Free)),
            time: (dt: 2.5e-5, end: 0.3),
            gravity: (0.0, 0.0),
            settings: ({settings}),
            materials: [(name: \"soil\", density: 1800.0,
                         model: LinearElastic((youngs_modulus: 5e6, poisson_ratio: 0.3)))],
            bodies: [(name: \"footing\", material: \"soil\",
                      shape: Rectangle(min: (0.1, 0.0), max: (0.3, 0.1)), points_per_cell: 2)],
            stages: [(name: \"load\", end: Duration(0.3),
                      tractions: [(body: \"footing\", side: Top, traction: (0.0, -1e4))])],
            output: (probe_interval: Some(2.5e-4)),
        )"
    );
    let scene = Scene::parse(&text, Path::new("footing.ron")).unwrap_or_else(|e| panic!("{e}"));
    let sim = common::run_scene(&scene);
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let work = energy.iter().map(|s| -s.loads).fold(0.0, f64::max);
    let end = energy.last().map_or(f64::NAN, EnergySample::balance) - energy[0].balance();
    (balance_swing(energy) / work, end / work)
}

#[test]
fn under_musl_an_undamped_footing_keeps_a_step_load_s_work() {
    let (musl, _) = footing_under_a_step_load("scheme: Musl");
    let (usl_swing, usl_end) =
        footing_under_a_step_load("scheme: Usl, position_update: Some(NewGridVelocity)");
    println!(
        "footing under a step load: balance swing {musl:.2e} (MUSL), {usl_swing:.2e} (USL, \
         {usl_end:.2e} at the end)"
    );
    // MUSL's strain follows the velocities the points keep: the balance
    // holds to the scheme's error, within 1% of the work as the surcharged
    // pad's (measured 0.35%; USF with `Remapped` 1.2% here, 0.6% at half the
    // step). With the stress update reading the nodal solve's velocity
    // instead, the measure is plain USL's.
    assert!(
        musl < 0.01,
        "MUSL's balance swings by {musl:.4} of the work"
    );
    // A control of the case, not a requirement on USL: plain USL damps the
    // modes the map to the points and back keeps only a fraction λ < 1 of
    // (a step scales their phase-space area by 1 − (1 − λ)(ωΔt)²), and
    // loses 21% of the work here (measured). That this case shows the
    // loss, with its sign, is what makes the check above able to fail; if
    // USL stops damping, this control goes, not the scheme.
    assert!(
        usl_end < -0.1,
        "plain USL's balance ends at {usl_end:.4} of the work"
    );
}

/// A kinematic punch 0.1 m wide pushed 4 mm into an undamped Neo-Hookean
/// pad of one point per cell (USF, `Remapped`; forces applied as tractions
/// on five points of the domain's edge; the contact's `friction`), then
/// held still for 0.2 s. Returns the punch's work and the balance's
/// largest growth while it is held (J/m).
fn held_punch(friction: f64) -> (f64, f64) {
    let text = format!(
        "Scene(
        grid: (origin: (0.0, 0.0), cell_size: 0.02, cells: (30, 15),
               edges: (left: Slip, right: Slip, bottom: Fixed, top: Free)),
        time: (dt: 2e-5, end: 0.3),
        gravity: (0.0, 0.0),
        settings: (scheme: Usf, position_update: Some(RemappedVelocity)),
        materials: [(name: \"pad\", density: 2000.0,
                     model: NeoHookean((youngs_modulus: 2e7, poisson_ratio: 0.3)))],
        bodies: [(name: \"pad\", material: \"pad\",
                  shape: Rectangle(min: (0.0, 0.0), max: (0.6, 0.2)), points_per_cell: 1)],
        blocks: [(name: \"punch\", shape: Cuboid(half_extents: (0.05, 0.03)),
                  position: (0.3, 0.23), motion: Kinematic((linear: (0.0, 0.0), angular: 0.0)),
                  contact: (normal_stiffness: 5e7, tangential_stiffness: 5e7, friction: {friction}))],
        stages: [
            (name: \"push\", end: Duration(0.1),
             block_velocities: [(block: \"punch\", velocity: (linear: (0.0, -0.04), angular: 0.0))]),
            (name: \"hold\", end: Duration(0.2),
             block_velocities: [(block: \"punch\", velocity: (linear: (0.0, 0.0), angular: 0.0))]),
        ],
        contact: (force_application: Traction(points: 5)),
        output: (probe_interval: Some(1e-3)),
    )"
    );
    let scene = Scene::parse(&text, Path::new("held_punch.ron")).unwrap_or_else(|e| panic!("{e}"));
    let sim = common::run_scene(&scene);
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let pushed = energy
        .iter()
        .min_by(|a, b| (a.time - 0.1).abs().total_cmp(&(b.time - 0.1).abs()))
        .expect("samples");
    let work = -pushed.blocks;
    let held = energy
        .iter()
        .filter(|s| s.time >= pushed.time)
        .map(|s| s.balance() - pushed.balance())
        .fold(0.0, f64::max);
    println!(
        "held punch, friction {friction}: the punch's work {work:.1} J/m, balance at the end of \
         the push {:.2} J/m, its largest growth while held {held:.3} J/m",
        pushed.balance()
    );
    (work, held)
}

#[test]
fn a_frictional_punch_held_still_feeds_no_energy_through_tractions() {
    // Nothing moves the punch while it is held, so friction may not make
    // the balance grow then. `Traction` itself makes it grow a little,
    // friction or not: its edge points are not the contact point (about
    // 1% of the work without friction, the same at half the step; 0.04%
    // with `BodyForce`). The edge faces the contact's normal: turned to
    // the force, as the paper turns it, it would swing with the friction
    // force and feed energy while the punch is held.
    let (work, frictional) = held_punch(0.3);
    let (_, frictionless) = held_punch(0.0);
    // The push went in: about 190 J/m of work.
    assert!(work > 150.0, "the punch's work {work}");
    // Friction's share of the growth within 0.5% of the work.
    assert!(
        frictional < frictionless + 0.005 * work,
        "the balance grew by {frictional} while held, {frictionless} without friction, of {work}"
    );
}

#[test]
fn a_block_a_stage_removes_takes_its_springs_energy_along() {
    // The punch pressed 1.5 mm into the pad (with friction, so that its
    // tangential springs hold energy too), then removed by a stage: the
    // contact springs' energy vanishes from `contact`, and the `blocks`
    // column books it as taken by the block, so the balance does not jump.
    let scene = pad(
        &elastic(0.3),
        "scheme: Usf, position_update: Some(RemappedVelocity)",
        TURNING_PUNCH,
        "(name: \"press\", end: Duration(0.03)),
         (name: \"release\", end: Duration(0.01), remove_blocks: [\"punch\"])",
        0.04,
    );
    let sim = common::run_scene(&scene);
    let energy = &sim.world().resource::<EnergyLog>().samples;
    // The sample at the removal (the stage change at 0.03 s) and the one
    // before it.
    let at = energy
        .iter()
        .position(|s| s.time >= 0.03 - 1e-9)
        .expect("the removal is sampled");
    let (before, after) = (energy[at - 1], energy[at]);
    let jump = after.balance() - before.balance();
    let step = before.balance() - energy[at - 2].balance();
    println!(
        "removal: contact {:.4} -> {:.4} J/m, blocks {:.4} -> {:.4}; balance step {jump:.3e} \
         (the step before {step:.3e})",
        before.contact, after.contact, before.blocks, after.blocks
    );
    assert!(
        before.contact > 1.0 && after.contact == 0.0,
        "the springs held energy"
    );
    // The balance moves at the removal as on any step (the scheme's
    // error, 1e-4 of the springs' energy a step here), not by the springs'
    // energy: within 1% of it.
    assert!(
        jump.abs() < 0.01 * before.contact,
        "balance jumps by {jump}"
    );
}

/// An elastic disk (radius 0.1 m, E = 1e7 Pa, ν = 0.3, ρ = 1000 kg/m³,
/// cell 0.01 m, 2 × 2 points per cell) dropped from 0.1 m onto a fixed
/// ground with μ = 0.5, undamped, to 0.2 s: it lands near 0.14 s and
/// leaves the ground again by 0.2 s. Its contacts stick: their tangential
/// springs take and give back energy, and what they keep or dissipate must
/// not show as energy created.
#[test]
fn a_frictional_bounce_books_no_energy_from_its_sticking_springs() {
    let text = "Scene(
        grid: (origin: (0.0, 0.0), cell_size: 0.01, cells: (60, 50)),
        time: (dt: 2e-5, end: 0.2),
        gravity: (0.0, -9.81),
        materials: [(name: \"elastic\", density: 1000.0,
                     model: LinearElastic((youngs_modulus: 1e7, poisson_ratio: 0.3)))],
        bodies: [(name: \"disk\", material: \"elastic\",
                  shape: Disk(center: (0.3, 0.3), radius: 0.1), points_per_cell: 2)],
        blocks: [(name: \"ground\", shape: Cuboid(half_extents: (0.3, 0.05)),
                  position: (0.3, 0.05), motion: Fixed,
                  contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.5))],
        output: (probe_interval: Some(2e-4)),
    )";
    let scene = Scene::parse(text, Path::new("disk_bounce.ron")).unwrap_or_else(|e| panic!("{e}"));
    let sim = common::run_scene(&scene);
    let samples = &sim.world().resource::<EnergyLog>().samples;
    let work = samples.iter().map(|s| -s.gravity).fold(0.0, f64::max);
    let last = samples.last().expect("samples");
    let balance = samples
        .iter()
        .map(|s| s.balance().abs())
        .fold(0.0, f64::max);
    println!(
        "frictional bounce: dissipated {:.4} J/m at the end, balance within {:.3}% of gravity's largest work {work:.2} J/m",
        last.dissipated,
        100.0 * balance / work
    );
    // Taken with the force at each step's start, a sticking spring's work
    // booked k_t |Δu|² / 2 a step as energy the friction created: −0.38 J/m
    // (1.3% of gravity's work) by the end of this bounce, and the balance
    // off by as much. The trapezoidal rule leaves what slid and the springs
    // of contacts that ended (+0.035 J/m), and the balance within 1%, which
    // the same drop without friction keeps too (the scheme's own error).
    assert!(last.dissipated >= 0.0, "dissipated {}", last.dissipated);
    assert!(balance < 0.01 * work, "balance {balance} of {work}");
}
