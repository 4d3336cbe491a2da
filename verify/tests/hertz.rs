//! The 2D Hertz problem (paper section 4.4.2): two elastic disks pressed
//! together by opposite ramped body forces, on separate layers, meeting
//! only through the disk–disk DEM contact. The runs and their measurement
//! are in mpdem_verify::hertz.

mod common;

use mpdem_verify::hertz::{LoadingCurve, Resolution, Zone};

#[test]
fn coarse_disks_carry_the_applied_load_along_the_line_of_centres() {
    let resolution = Resolution {
        cells_per_radius: 20,
        points_per_cell: 1,
        angle: 0.0,
        linear_elastic: false,
        shift: 0.0,
    };
    let base = common::load_scene("hertz_disks.ron");
    let scene = resolution.scene(&base).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = common::run_scene(&scene);
    let curve =
        LoadingCurve::of(&mut sim, &scene, Zone::Undeformed).unwrap_or_else(|e| panic!("{e}"));
    let current =
        LoadingCurve::of(&mut sim, &scene, Zone::Current).unwrap_or_else(|e| panic!("{e}"));
    let applied = curve.applied;
    let (error, count) = curve.hertz_error();
    println!(
        "R/20, 1 pt/cell: contact force {:.4e} N/m for an applied {:.4e}; F(a) error {:.1}% over {count} samples",
        curve.final_force.x,
        -applied.x,
        100.0 * error
    );
    // Quasi-static at the end of the ramp: the contact carries the body
    // force of the left disk. 5%: particle damping makes the disks lag the
    // ramp by a little (measured +1.8%; −2% with half this load and the
    // linear elastic disks of before).
    assert!(
        (curve.final_force.x / -applied.x - 1.0).abs() < 0.05,
        "contact force {} vs applied {}",
        curve.final_force,
        -applied
    );
    // Across the line of centres: frictionless disks pressed along it are
    // in unstable equilibrium against sliding sideways, so round-off grows
    // into a small transverse force (measured 0.4% of F). 2% bounds that
    // and would catch a real asymmetry of the contact.
    println!(
        "force across the line of centres: {:e}",
        curve.final_force.y
    );
    assert!(curve.final_force.y.abs() < 0.02 * curve.final_force.x.abs());
    // The zone in the undeformed disks is wider than over the current
    // positions: under load the surface slides towards the contact's
    // centre, by 7.5–9% at the end's a ≈ 0.3 R (the finite-element disks,
    // small strain and the finite-strain laws). At this resolution the
    // ratio is 1.079 (1.082 with the linear elastic law); 1.02–1.2 fails a
    // summary that takes the current positions or pairs the wrong points.
    let last = |c: &LoadingCurve| c.samples.last().map_or(0.0, |s| s.0);
    let ratio = last(&curve) / last(&current);
    println!("half-width, undeformed over current, at the end: {ratio:.4}");
    assert!((1.02..1.2).contains(&ratio), "{ratio}");
}

#[test]
#[ignore = "seven runs and the placement study, about 9 minutes"]
fn hertz_disks_follow_the_2d_hertz_law_and_converge() {
    // The targets: within 10% at the finest resolution, the error
    // falling with resolution, the turned pair within 5% of the unturned;
    // F(a) of every run is plotted to out/verify/hertz_disks/f_of_a.png.
    common::verify_case("hertz_disks");
}

#[test]
fn a_non_finite_body_acceleration_is_refused() {
    let mut scene = common::load_scene("hertz_disks.ron");
    if let Some(load) = scene.bodies[0].acceleration.as_mut() {
        load.value.x = f64::INFINITY;
    }
    let message = scene.validate().expect_err("refused").to_string();
    assert!(message.contains("acceleration must be finite"), "{message}");
}
