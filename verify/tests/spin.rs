//! A free elastic block spinning in the plane: nothing acts on it, so its
//! angular momentum about its centre of mass is constant and it turns at
//! its initial rate (Euler's laws; its own stresses are internal). The
//! centrifugal stretch is small: ρ ω² r² ≈ 1.2e4 Pa at the block's ends,
//! 1e-4 of E.

mod common;

use mpdem::prelude::*;
use mpdem_verify::mass_weighted_mean;
use std::path::Path;

/// Angular velocity of the spin (rad/s): a whole turn in 0.63 s.
const OMEGA: Real = 10.0;

/// The 0.1 × 0.4 m toppling block (E = 1e8 Pa, ρ = 3000 kg/m³) at one
/// point per 0.02 m cell, spinning about its centre (0.4, 0.4) at `OMEGA`,
/// without gravity, for one turn.
fn spinning_block(affine_transfer: bool) -> Scene {
    let source = format!(
        "Scene(
            grid: (cell_size: 0.02, cells: (40, 40)),
            time: (dt: 5e-5, end: {end}),
            gravity: (0.0, 0.0),
            settings: (affine_transfer: {affine_transfer}),
            materials: [(name: \"elastic\", density: 3000.0,
                model: LinearElastic((youngs_modulus: 1e8, poisson_ratio: 0.22)))],
            bodies: [(name: \"block\", material: \"elastic\",
                shape: Rectangle(min: (0.36, 0.2), max: (0.46, 0.6)), points_per_cell: 1,
                velocity: Field(x: \"-{OMEGA} * (y - 0.4)\", y: \"{OMEGA} * (x - 0.41)\"))],
        )",
        end = std::f64::consts::TAU / OMEGA,
    );
    Scene::parse(&source, Path::new("spin.ron")).unwrap_or_else(|e| panic!("{e}"))
}

/// Angular momentum about the centre of mass (kg m²/s per m), kinetic
/// energy (J/m) and orientation (rad in (−π, π]: the mass-weighted best
/// fit of the points' turn about the centre of mass since the start).
fn spin_of(points: &MaterialPoints) -> (Real, Real, Real) {
    let com = mass_weighted_mean(points, &points.position);
    let start = mass_weighted_mean(points, &points.initial_position);
    let (mut momentum, mut kinetic, mut cross, mut dot) = (0.0, 0.0, 0.0, 0.0);
    for p in 0..points.len() {
        let (m, v) = (points.mass[p], points.velocity[p]);
        let (r0, r) = (points.initial_position[p] - start, points.position[p] - com);
        momentum += m * r.perp_dot(v);
        kinetic += 0.5 * m * v.length_squared();
        cross += m * r0.perp_dot(r);
        dot += m * r0.dot(r);
    }
    (momentum, kinetic, cross.atan2(dot))
}

/// What a run of the spinning block shows.
struct Spin {
    /// Angular momentum at the start and its smallest and largest value
    /// over the run (kg m²/s per m), sampled every 1.5 ms.
    momentum: (Real, Real, Real),
    /// Kinetic energy, likewise (J/m).
    kinetic: (Real, Real, Real),
    /// How far the block turned (rad, summed over the samples, each
    /// under half a turn).
    turned: Real,
    /// The time it had to turn (s).
    elapsed: Real,
}

impl Spin {
    fn print(&self, transfer: &str) {
        let ((l0, l_min, l_max), (k0, k_min, k_max)) = (self.momentum, self.kinetic);
        println!(
            "{transfer}: L {l0:.4} (range {l_min:.4}..{l_max:.4}), kinetic {k0:.4} J/m (range {k_min:.4}..{k_max:.4}), turned {:.2}° in {:.5} s (ω t = {:.2}°)",
            self.turned.to_degrees(),
            self.elapsed,
            (OMEGA * self.elapsed).to_degrees()
        );
    }
}

fn run(affine_transfer: bool) -> Spin {
    let mut sim = Simulation::from_scene(&spinning_block(affine_transfer)).expect("scene");
    let (l0, k0, _) = spin_of(sim.points_of("block").expect("block"));
    let mut spin = Spin {
        momentum: (l0, l0, l0),
        kinetic: (k0, k0, k0),
        turned: 0.0,
        elapsed: 0.0,
    };
    let mut angle = 0.0;
    while !sim.clock().finished() {
        for _ in 0..30 {
            if !sim.clock().finished() {
                sim.step().expect("step");
            }
        }
        let (l, k, now) = spin_of(sim.points_of("block").expect("block"));
        spin.momentum = (l0, spin.momentum.1.min(l), spin.momentum.2.max(l));
        spin.kinetic = (k0, spin.kinetic.1.min(k), spin.kinetic.2.max(k));
        let step: Real = now - angle;
        spin.turned +=
            (step + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
        angle = now;
    }
    spin.elapsed = sim.clock().time;
    spin
}

/// With the affine transfer the block keeps its spin for a whole turn.
/// Tolerances: 0.5% on the angular momentum and the kinetic energy (the
/// points move along tangents by ω Δt = 5e-4 rad per step, and the
/// centrifugal strain takes 1e-5 of the energy), 1° on the turn ω t.
/// Without it (the paper's eq. 8c) the same block's spin turns into strain
/// and back: printed, not asserted, and reported in the README.
#[test]
fn a_freely_spinning_block_keeps_its_angular_momentum_with_the_affine_transfer() {
    let affine = run(true);
    affine.print("affine transfer");
    run(false).print("standard transfer");
    let kept = |(start, low, high): (Real, Real, Real)| {
        (low / start - 1.0).abs() < 5e-3 && (high / start - 1.0).abs() < 5e-3
    };
    assert!(
        kept(affine.momentum),
        "angular momentum {:?}",
        affine.momentum
    );
    assert!(kept(affine.kinetic), "kinetic energy {:?}", affine.kinetic);
    let expected = OMEGA * affine.elapsed;
    assert!(
        (affine.turned - expected).abs() < 1.0_f64.to_radians(),
        "turned {:.2}° instead of {:.2}°",
        affine.turned.to_degrees(),
        expected.to_degrees()
    );
}
