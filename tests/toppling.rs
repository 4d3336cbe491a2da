//! Toppling of an elastic block on a slope (paper section 4.2.1) against the
//! exact motion of a rigid block rocking on its downhill corner.
//!
//! The material points are DEM disks inset by half a point spacing, so the
//! outline the slope touches is the block with its corners rounded to the
//! disk radius r. Its exact motion (rigid, no slip, the corner arc rolling)
//! is what the engine must reproduce; with r = 0 it is the sharp-corner
//! pendulum of the issue, φ'' = (3g/(4L)) sin φ.

mod common;

use mpdem::prelude::*;

/// Rotation ψ (rad, toppling positive) at `times` of a rigid w × h block on
/// a slope of `slope_deg`, resting at first on its downhill corner, rounded
/// with radius `r`, rolling without slip from rest.
///
/// With the arc's centre C at c = (w/2 − r, −(h/2 − r)) from the centre of
/// mass in the body frame, rolling keeps C at height r and moves it by r ψ,
/// so the centre of mass is x(ψ) = (r ψ, r) − R(ψ) c with R the clockwise
/// rotation. Lagrange's equation for the one coordinate ψ is
/// (|x'|² + I/m) ψ'' + (x' · x'') ψ'² = g · x', integrated with RK4 at 1e-5 s
/// (converged to 1e-6 rad).
fn rocking_block(w: Real, h: Real, r: Real, slope_deg: Real, times: &[Real]) -> Vec<Real> {
    let theta = slope_deg.to_radians();
    let g = DVec2::new(9.81 * theta.sin(), -9.81 * theta.cos());
    let c = DVec2::new(w / 2.0 - r, -(h / 2.0 - r));
    let inertia = (w * w + h * h) / 12.0;
    let acceleration = |psi: Real, omega: Real| {
        let (s, co) = psi.sin_cos();
        let x1 = DVec2::new(r + s * c.x - co * c.y, co * c.x + s * c.y);
        let x2 = DVec2::new(co * c.x + s * c.y, -s * c.x + co * c.y);
        (g.dot(x1) - x1.dot(x2) * omega * omega) / (x1.length_squared() + inertia)
    };
    let dt = 1e-5;
    let (mut psi, mut omega, mut t) = (0.0, 0.0, 0.0);
    let mut out = Vec::new();
    for &target in times {
        while t < target - 0.5 * dt {
            let k1 = (omega, acceleration(psi, omega));
            let k2 = (
                omega + 0.5 * dt * k1.1,
                acceleration(psi + 0.5 * dt * k1.0, omega + 0.5 * dt * k1.1),
            );
            let k3 = (
                omega + 0.5 * dt * k2.1,
                acceleration(psi + 0.5 * dt * k2.0, omega + 0.5 * dt * k2.1),
            );
            let k4 = (
                omega + dt * k3.1,
                acceleration(psi + dt * k3.0, omega + dt * k3.1),
            );
            psi += dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            omega += dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            t += dt;
        }
        out.push(psi);
    }
    out
}

/// Runs `scenes/toppling_<slope>.ron` to `end` and returns the block's
/// rotation ψ (rad) at `times`, from its top and bottom probes.
fn simulated_rotation(slope: u32, end: Real, times: &[Real]) -> Vec<Real> {
    let mut scene = common::load_scene(&format!("toppling_{slope}.ron"));
    scene.time.end = end;
    let sim = common::run_scene(&scene);
    let top = common::probe_samples(&sim, "top");
    let bottom = common::probe_samples(&sim, "bottom");
    let axis0 = top[0].position - bottom[0].position;
    times
        .iter()
        .map(|&t| {
            let k = top
                .iter()
                .position(|s| (s.time - t).abs() < 1e-9)
                .expect("a probe sample at this time");
            let axis = top[k].position - bottom[k].position;
            // Toppling downhill (+x) turns the axis clockwise.
            -axis0.perp_dot(axis).atan2(axis0.dot(axis))
        })
        .collect()
}

#[test]
fn reference_with_a_sharp_corner_is_the_pendulum_of_the_issue() {
    // The issue's values for r = 0: ψ(0.3 s), ψ(0.4 s) = 4.09°/8.83° (16°),
    // 8.25°/17.76° (18°), 12.38°/26.57° (20°), quoted to 0.01°.
    for (slope, expected) in [
        (16.0, [4.09, 8.83]),
        (18.0, [8.25, 17.76]),
        (20.0, [12.38, 26.57]),
    ] {
        let psi = rocking_block(0.1, 0.4, 0.0, slope, &[0.3, 0.4]);
        for (got, want) in psi.iter().zip(expected) {
            assert!(
                (got.to_degrees() - want).abs() < 0.006,
                "{slope}°: {} vs {want}",
                got.to_degrees()
            );
        }
    }
}

#[test]
fn toppling_block_follows_the_rigid_block_with_the_outline_of_its_disks() {
    // 400 points in 2 × 2 per 0.02 m cell: spacing 0.01 m, disk radius
    // 0.005 m, so the corners the slope touches are rounded to r = 0.005 m.
    let r = 0.005;
    let times = [0.3, 0.4];
    for slope in [14, 16, 18, 20] {
        let psi = simulated_rotation(slope, 0.4, &times);
        let rounded = rocking_block(0.1, 0.4, r, slope as Real, &times);
        let sharp = rocking_block(0.1, 0.4, 0.0, slope as Real, &times);
        for k in 0..times.len() {
            println!(
                "toppling {slope}°: ψ({}) = {:.2}° | rounded-corner rigid {:.2}° ({:+.1}%) | sharp-corner pendulum {:.2}° ({:+.1}%)",
                times[k],
                psi[k].to_degrees(),
                rounded[k].to_degrees(),
                100.0 * (psi[k] / rounded[k] - 1.0),
                sharp[k].to_degrees(),
                100.0 * (psi[k] / sharp[k] - 1.0),
            );
        }
        // 5% at 18° and 20°: the block is elastic (E = 1e8 Pa), starts
        // stress-free (it rings as its weight comes on) and rests on springs
        // (k_n = 2e8 N/m), all absent from the rigid reference. 20% at 16°
        // (the issue's tolerance there): it starts only 3° past the rounded
        // block's critical angle (13.0°), where the early ringing grows the
        // most. 14° is printed, not asserted: 1° past that angle, the early
        // ringing decides the timing (measured +34% at 0.3 s).
        if slope == 14 {
            continue;
        }
        let tolerance = if slope == 16 { 0.20 } else { 0.05 };
        for k in 0..times.len() {
            assert!(
                (psi[k] / rounded[k] - 1.0).abs() <= tolerance,
                "{slope}° at {} s: {:.2}° vs {:.2}°",
                times[k],
                psi[k].to_degrees(),
                rounded[k].to_degrees()
            );
        }
    }
}
