//! A point that carries stress and has grown too loose for the time step
//! is warned of, once per body, and the run goes on.

mod common;

use mpdem::components::MaterialPoints;
use mpdem::prelude::*;

/// Scales point `p`'s deformation gradient so that its volume is `ratio`
/// times its placed volume (the stress update keeps V = det F V⁰).
fn loosen(sim: &mut Simulation, p: usize, ratio: Real) {
    let world = sim.world_mut();
    let mut query = world.query::<&mut MaterialPoints>();
    let mut points = query.single_mut(world).expect("one body");
    let stretch = ratio.sqrt() / points.deformation_gradient[p].determinant().sqrt();
    points.deformation_gradient[p] *= stretch;
    points.volume[p] = ratio * points.initial_volume[p];
}

#[test]
fn a_point_too_loose_for_the_step_is_warned_of_once() {
    // The column: h / (c Δt) = 0.025 / (82 m/s × 1e-4 s) = 3.0, so a point
    // is stable up to V/V⁰ = 9.3 (the system checks every 64 steps).
    let mut sim = Simulation::from_scene(&common::load_scene("elastic_column.ron")).unwrap();
    for _ in 0..64 {
        sim.step().unwrap();
    }
    assert!(sim.step_warnings().is_empty(), "{:?}", sim.step_warnings());
    // Just within the limit: still quiet.
    loosen(&mut sim, 40, 8.5);
    sim.step().unwrap();
    assert!(sim.step_warnings().is_empty(), "{:?}", sim.step_warnings());
    for _ in 0..63 {
        sim.step().unwrap();
    }
    // Beyond it: one warning naming the body, the point and its ratio.
    loosen(&mut sim, 40, 12.0);
    sim.step().unwrap();
    let warnings = sim.step_warnings().to_vec();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(
        (warnings[0].kind, warnings[0].field.as_str()),
        (WarningKind::TimeStep, "bodies[\"column\"]")
    );
    let ratio: Real = warnings[0]
        .message
        .split("carries stress at ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|r| r.parse().ok())
        .expect("the ratio in the warning");
    // One step after the loosening: the column's motion moved it a little.
    assert!((ratio - 12.0).abs() < 0.05, "{ratio}");
    assert!(
        warnings[0].message.contains("body 'column', point 40 ")
            && warnings[0].message.contains("disconnected_above"),
        "{}",
        warnings[0]
    );
    // Once per body: the next check stays quiet.
    for _ in 0..64 {
        let _ = sim.step();
    }
    assert_eq!(sim.step_warnings().len(), 1);
}
