//! Local (non-viscous) damping at the nodes and at the points, against its
//! analytical rate of energy loss.

mod common;

use mpdem::prelude::*;

/// Fraction of the ringing bar's energy (wave scene, 20 cells, FLIP) left
/// after `end` seconds with `edit` applied to the scene's settings.
fn energy_kept(end: Real, edit: impl FnOnce(&mut Settings)) -> Real {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.grid.cell_size *= 10.0;
    scene.grid.cells = (20, 2);
    scene.bodies[0].shape = mpdem::scene::Shape::Rectangle {
        min: DVec2::ZERO,
        max: DVec2::new(1.0, 2.0 * scene.grid.cell_size),
    };
    scene.probes[0].at = DVec2::new(0.5, scene.grid.cell_size);
    edit(&mut scene.settings);
    scene.time.end = end;
    let sim = common::run_scene(&scene);
    let log = sim.world().resource::<mpdem::resources::EnergyLog>();
    let total = |s: &mpdem::resources::EnergySample| s.kinetic + s.strain;
    total(log.samples.last().expect("samples")) / total(&log.samples[0])
}

#[test]
fn local_damping_removes_four_alpha_of_the_energy_per_cycle() {
    // A node (or point) in harmonic motion loses α ∮ |f| |dx| = 4 α W per
    // cycle to Cundall's local damping (α small). The bar rings in its first
    // mode (period 2 L / c = 0.2 s; the higher modes carry < 0.2% of the
    // energy), so 0.5 s is 2.5 cycles: kept ≈ (1 − 4α)^2.5.
    let alpha: Real = 0.01;
    let undamped = energy_kept(0.5, |_| {});
    let expected = undamped * (1.0 - 4.0 * alpha).powf(2.5);
    let grid = energy_kept(0.5, |s| s.grid_damping = alpha);
    let particle = energy_kept(0.5, |s| s.particle_damping = alpha);
    println!(
        "local damping α = {alpha}: kept {:.4} (grid), {:.4} (points), expected {expected:.4}; undamped {undamped:.6}",
        grid, particle
    );
    // 10% of the expected loss: the law is exact for an oscillator; the
    // bar's nodes move nearly, not exactly, in phase.
    let loss = undamped - expected;
    assert!(
        (grid - expected).abs() <= 0.1 * loss,
        "grid {grid} vs {expected}"
    );
    assert!(
        (particle - expected).abs() <= 0.1 * loss,
        "points {particle} vs {expected}"
    );
}

#[test]
fn particle_damping_acts_under_pic() {
    // The paper's settling stages use PIC = 1 with particle damping: the
    // damping must act there too (it damps the acceleration, which PIC
    // keeps). Over 0.05 s (a quarter cycle, before PIC alone has taken most
    // of the energy), α = 0.1 removes about 4 α / 4 = 10% from a free
    // oscillator; at least half of that must go.
    let alpha: Real = 0.1;
    let pic = energy_kept(0.05, |s| s.pic_fraction = 1.0);
    let damped = energy_kept(0.05, |s| {
        s.pic_fraction = 1.0;
        s.particle_damping = alpha;
    });
    let ratio = damped / pic;
    println!("PIC: kept {pic:.4}; with particle damping {alpha}: {damped:.4} (ratio {ratio:.4})");
    assert!(ratio <= 1.0 - 0.5 * alpha, "ratio {ratio}");
}
