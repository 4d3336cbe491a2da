//! Paper section 4.1: elastic wave in a bar fixed at both ends, against the
//! exact (d'Alembert) solution.

mod common;

use common::{load_scene, run_scene, verify_case};
use mpdem::prelude::*;
use mpdem::scene::InitialVelocity;
use mpdem_verify::wave::scaled;

/// Largest |v − v_exact| of the midpoint probe as a fraction of 0.25 a.
fn midpoint_error(sim: &Simulation, a: Real) -> Real {
    mpdem_verify::wave::midpoint_error(sim, a).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn midpoint_velocity_matches_the_exact_solution_and_converges() {
    // The scene (200 cells) within 2% of 0.25 over five periods, and
    // better than at 100 cells: see mpdem_verify::wave.
    verify_case("wave_1d");
}

/// At 1% of the paper's amplitude the run is geometrically linear and the
/// points stay within their cells, so the error is the discretisation
/// error alone; under the engine's default USF it must fall by more than
/// half per halving of the cell (measured 4.6% → 1.8% → 0.6%).
#[test]
fn small_amplitude_error_converges_under_the_default_scheme() {
    let amplitude = 0.01;
    let errors: Vec<Real> = [4.0, 2.0]
        .iter()
        .map(|&factor| {
            let mut scene = scaled(load_scene("wave_1d.ron"), factor);
            scene.settings.scheme = mpdem::resources::UpdateScheme::Usf;
            scene.bodies[0].velocity = InitialVelocity::Field {
                x: format!("{amplitude}*x*(1-x)"),
                y: "0".into(),
            };
            midpoint_error(&run_scene(&scene), amplitude)
        })
        .collect();
    println!(
        "small-amplitude wave, USF: 50 cells {:.3}%, 100 cells {:.3}%",
        100.0 * errors[0],
        100.0 * errors[1]
    );
    assert!(
        errors[1] < 0.5 * errors[0],
        "errors {errors:?} do not converge"
    );
    assert!(errors[1] < 0.02, "100-cell error {} above 2%", errors[1]);
}

/// The wave scene at 20 cells (coarse, so that PIC's smoothing of the wave
/// mode shows within a second) with its settings replaced by `settings`,
/// run for `end` seconds.
fn with_settings(settings: Settings, end: Real) -> Simulation {
    let mut scene = scaled(load_scene("wave_1d.ron"), 10.0);
    scene.settings = settings;
    scene.time.end = end;
    run_scene(&scene)
}

/// Total (kinetic + strain) energy at the end over that at the start.
fn energy_kept(sim: &Simulation) -> Real {
    let log = sim.world().resource::<mpdem::resources::EnergyLog>();
    let total = |s: &mpdem::resources::EnergySample| s.kinetic + s.strain;
    total(log.samples.last().expect("samples")) / total(&log.samples[0])
}

#[test]
fn xpic_of_order_one_is_pic() {
    // Eq. 12 with m = 1 is PIC (β = 1): the two updates differ only by
    // round-off, S v^n + S (v^{n+1} − v^n) against S v^{n+1}.
    let base = load_scene("wave_1d.ron").settings;
    let pic = with_settings(
        Settings {
            pic_fraction: 1.0,
            ..base
        },
        0.05,
    );
    let xpic = with_settings(
        Settings {
            xpic_order: Some(1),
            position_update: None,
            ..base
        },
        0.05,
    );
    let (mut a, mut b) = (pic, xpic);
    let (a, b) = (
        a.points_of("bar").unwrap().clone(),
        b.points_of("bar").unwrap().clone(),
    );
    let scale = a.velocity.iter().map(|v| v.length()).fold(0.0, Real::max);
    for (va, vb) in a.velocity.iter().zip(&b.velocity) {
        assert!((*va - *vb).length() <= 1e-12 * scale, "{va} vs {vb}");
    }
}

#[test]
fn xpic_dissipates_less_as_its_order_grows() {
    // Hammerquist & Nairn: XPIC(m) removes the null-space noise that FLIP
    // keeps without PIC's damping of the resolved modes, more so as m grows:
    // a mode that S S⁺ keeps by a factor λ per step keeps 1 − (1 − λ)^m.
    // Over 0.5 s (2.5 periods of the bar), the energy kept must rise with m
    // (measured: 0% for PIC, 89.7% for m = 2, 99.95% from m = 4; FLIP 99.95%).
    let base = load_scene("wave_1d.ron").settings;
    let kept: Vec<(u32, Real)> = [1, 2, 3, 4, 6, 8]
        .iter()
        .map(|&m| {
            let sim = with_settings(
                Settings {
                    xpic_order: Some(m),
                    position_update: None,
                    ..base
                },
                0.5,
            );
            (m, energy_kept(&sim))
        })
        .collect();
    let flip = energy_kept(&with_settings(base, 0.5));
    for (m, e) in &kept {
        println!(
            "wave, XPIC({m}): {:.4}% of the energy kept over 0.5 s",
            100.0 * e
        );
    }
    println!("wave, FLIP: {:.4}% kept", 100.0 * flip);
    for pair in kept.windows(2) {
        assert!(
            pair[1].1 > pair[0].1,
            "XPIC({}) {} ≤ XPIC({}) {}",
            pair[1].0,
            pair[1].1,
            pair[0].0,
            pair[0].1
        );
    }
}
