//! `scenes/granular_slab.ron` at twice its cell: a Drucker–Prager slab
//! (φ = 33°, ψ = 0) sliding at 2 m/s onto a no-slip floor, with and without
//! `flip_from_unconstrained`, under pure FLIP (`granular_relaxation:
//! None`): what a no-slip wall does to FLIP's momentum; and at the default
//! granular relaxation.
//!
//! A Coulomb plug's centre of mass travels at least v0² / (2 g tan φ'),
//! tan φ' the cone's largest stress ratio on any plane (sin φ' = η of
//! eq. 16 in plane strain), and stops by v0 / (g sin φ') = 0.39 s, sin φ'
//! the ratio its base shears at (Davis 1968). The full scene and finer
//! cells are measured in `docs/cases.md`.

mod common;

use mpdem::prelude::*;

/// The scene at cell 0.028 m, run to 0.8 s: the centre of mass's travel
/// (m), the kinetic energy at the end over the start's, and the base
/// probe's speed at the end (m/s).
fn slide(flip_from_unconstrained: bool, relaxation: Option<Real>) -> (Real, Real, Real) {
    let mut scene = common::load_scene("granular_slab.ron");
    scene.grid.cell_size = 0.028;
    scene.grid.cells = (215, 18);
    scene.time.dt = 2e-5;
    scene.time.end = 0.8;
    scene.settings.flip_from_unconstrained = flip_from_unconstrained;
    scene.settings.granular_relaxation = relaxation;
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let centre_and_kinetic = |sim: &mut Simulation| {
        let points = sim.points_of("slab").expect("slab");
        let mass = points.total_mass();
        let centre: Real = points
            .mass
            .iter()
            .zip(&points.position)
            .map(|(m, x)| m * x.x)
            .sum();
        let kinetic: Real = points
            .mass
            .iter()
            .zip(&points.velocity)
            .map(|(m, v)| 0.5 * m * v.length_squared())
            .sum();
        (centre / mass, kinetic)
    };
    let (start, kinetic_start) = centre_and_kinetic(&mut sim);
    sim.run().unwrap();
    let (end, kinetic_end) = centre_and_kinetic(&mut sim);
    let base = common::probe_samples(&sim, "base");
    let speed = base.last().expect("samples").velocity.length();
    (end - start, kinetic_end / kinetic_start, speed)
}

/// The least travel of a Coulomb plug sliding at 2 m/s on the cone's
/// plane-strain friction (m).
fn shortest_travel() -> Real {
    let eta = {
        let t = 33.0_f64.to_radians().tan();
        3.0 * t / (9.0 + 12.0 * t * t).sqrt()
    };
    2.0 * 2.0 / (2.0 * 9.81 * eta.asin().tan())
}

#[test]
fn a_granular_slab_stops_on_a_no_slip_floor_when_the_floor_takes_what_it_holds() {
    let shortest = shortest_travel();
    let (travel, kinetic, speed) = slide(true, None);
    let (kept_travel, kept_kinetic, kept_speed) = slide(false, None);
    println!(
        "flip_from_unconstrained: travel {travel:.3} m, kinetic energy at 0.8 s {kinetic:.1e}, \
         base {speed:.3} m/s; without: {kept_travel:.3} m, {kept_kinetic:.1e}, {kept_speed:.3} m/s \
         (the plug travels at least {shortest:.3} m)"
    );
    // No Coulomb friction stops the slab sooner (measured 0.384 m).
    assert!(travel >= shortest, "travel {travel}");
    // The plug is at rest by 0.39 s; at 0.8 s only the transfer's noise
    // moves (measured 1.2e-3 of the start's energy), and the base point is
    // at rest (measured 0.010 m/s).
    assert!(kinetic <= 1e-2, "kinetic energy {kinetic:e}");
    assert!(speed <= 0.05, "base probe at {speed} m/s");
    // Without it the base point keeps what the floor holds back (measured
    // 1.37 m/s while it does not move), and that energy stays.
    assert!(kept_speed >= 0.5, "base probe at {kept_speed} m/s");
    assert!(kept_kinetic > 1e-2, "kinetic energy {kept_kinetic:e}");
}

#[test]
fn at_the_default_relaxation_the_slab_slides_as_a_coulomb_plug_and_stops() {
    let shortest = shortest_travel();
    let (travel, kinetic, speed) = slide(false, Settings::default().granular_relaxation);
    println!(
        "default relaxation: travel {travel:.3} m, kinetic energy at 0.8 s {kinetic:.1e}, \
         base {speed:.3} m/s (the plug travels at least {shortest:.3} m)"
    );
    // The relaxation pulls toward the velocity the points carry, not the
    // no-slip wall's: no drag beyond the material's friction (measured
    // 0.427 m), and the slab at rest (measured 8e-8 of the start's energy).
    assert!(travel >= shortest, "travel {travel}");
    assert!(kinetic <= 1e-2, "kinetic energy {kinetic:e}");
    assert!(speed <= 0.05, "base probe at {speed} m/s");
}
