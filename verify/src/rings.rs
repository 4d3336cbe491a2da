//! Paper section 4.4.1: two Neo-Hookean rings colliding at ±30 m/s, on
//! separate grid layers, meeting only through the disk–disk DEM contact.

use super::{
    Check, Context, Curve, Figure, Measured, VerifyError, body, centre_of_mass, first, largest,
    percent,
};
use mpdem::Simulation;
use mpdem::math::{DVec2, Real};
use mpdem::resources::{EnergyLog, EnergySample};

/// Outer radius of the scene's rings (m).
const OUTER_RADIUS: Real = 0.04;

/// Centre of mass of a body and its velocity.
pub fn centre(sim: &mut Simulation, name: &str) -> Result<(DVec2, DVec2), VerifyError> {
    Ok(centre_of_mass(body(sim, name)?))
}

/// Largest distance of a body's points from its centre of mass.
pub fn reach(sim: &mut Simulation, name: &str) -> Result<Real, VerifyError> {
    let (c, _) = centre(sim, name)?;
    Ok(largest(
        body(sim, name)?.position.iter().map(|x| x.distance(c)),
    ))
}

/// The energies a run recorded.
pub fn energy_samples(sim: &Simulation) -> &[EnergySample] {
    &sim.world().resource::<EnergyLog>().samples
}

/// The first and last energy samples of a run.
pub fn first_and_last(sim: &Simulation) -> Result<(EnergySample, EnergySample), VerifyError> {
    let samples = energy_samples(sim);
    let start = *first(samples, "energy samples")?;
    Ok((start, *samples.last().unwrap_or(&start)))
}

/// Relative change of kinetic + strain + contact energy over a run (NaN
/// if it recorded no energy).
pub fn energy_drift(sim: &Simulation) -> Real {
    first_and_last(sim).map_or(Real::NAN, |(first, last)| {
        last.total() / first.total() - 1.0
    })
}

/// The largest relative departure of the energy balance (total plus what
/// the contacts dissipated and damping took) from its start (NaN for no
/// samples).
pub fn widest_balance_swing(samples: &[EnergySample]) -> Real {
    let Some(start) = samples.first().map(EnergySample::balance) else {
        return Real::NAN;
    };
    largest(samples.iter().map(|s| (s.balance() / start - 1.0).abs()))
}

/// The energies of `samples` over time (ms): kinetic, strain, contact,
/// their sum and the balance, computed, against the balance's start held
/// constant.
pub fn energy_figure(samples: &[EnergySample]) -> Figure {
    let series = |f: fn(&EnergySample) -> Real| -> Vec<(Real, Real)> {
        samples.iter().map(|s| (1e3 * s.time, f(s))).collect()
    };
    let start = samples.first().map_or(Real::NAN, EnergySample::balance);
    Figure::new(
        "Two rings colliding: energies",
        "time t (ms)",
        "energy (J/m)",
    )
    .with(Curve::computed("kinetic", series(|s| s.kinetic)))
    .with(Curve::computed("strain", series(|s| s.strain)))
    .with(Curve::computed("contact springs", series(|s| s.contact)))
    .with(Curve::computed(
        "kinetic + strain + contact",
        series(EnergySample::total),
    ))
    .with(Curve::computed(
        "balance: the same + dissipated by the contacts and damping",
        series(EnergySample::balance),
    ))
    .with(Curve::reference(
        "the balance at the start (energy conserved)",
        samples.iter().map(|s| (1e3 * s.time, start)).collect(),
    ))
}

/// The scene to its end (3.8 ms).
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let scene = ctx.scene("two_rings.ron")?;
    let mut sim = ctx.run("two_rings", &scene)?;
    let (_, v_left) = centre(&mut sim, "left")?;
    let (_, v_right) = centre(&mut sim, "right")?;
    let reaches = [reach(&mut sim, "left")?, reach(&mut sim, "right")?];
    let (first, last) = first_and_last(&sim)?;
    let drift = energy_drift(&sim);
    let balance_drift = last.balance() / first.balance() - 1.0;
    let widest = widest_balance_swing(energy_samples(&sim));
    let farthest = largest(reaches);
    let figure = energy_figure(energy_samples(&sim));
    let checks = vec![
        // Rebound: the relative velocity of the centres has reversed.
        Check::judged(
            "centre velocities at the end (they met at +30 / −30 m/s)",
            format!("{:+.2} / {:+.2} m/s", v_left.x, v_right.x),
            "relative velocity reversed",
            v_left.x - v_right.x < 0.0,
        ),
        // No fragmentation: every point stays within 1.25 outer radii of
        // its ring's centre (the rebounding rings still ring; a point torn
        // off would be carried away at tens of m/s).
        Check::judged(
            "farthest point from its ring's centre",
            format!("{:.2} mm", 1e3 * farthest),
            format!("< 1.25 × {:.0} mm", 1e3 * OUTER_RADIUS),
            farthest < 1.25 * OUTER_RADIUS,
        )
        .because(
            "the rebounding rings still ring; a point torn off would be carried away at tens of m/s",
        ),
        // The target (measured −1.58%, of which 2.34% taken by
        // friction; −7.58% with disks that only reach the outline).
        Check::judged(
            "drift of kinetic + strain + contact energy over the run",
            percent(drift, 2),
            "within 5%",
            drift.abs() <= 0.05,
        )
        .because("the validation's 5%; friction (μ = 0.2) takes part of the energy"),
        // What the contacts' tangential forces took and their springs do
        // not hold closes the balance up to the scheme's own error,
        // measured +0.7% at every sample; held to 2% as for a ring on a
        // wall (a work of the wrong sign would leave −2.7%).
        Check::judged(
            "energy balance (total + dissipated by the contacts) at the end",
            percent(balance_drift, 2),
            "within 2%",
            balance_drift.abs() <= 0.02,
        )
        .because(
            "what the contacts' tangential forces took closes the balance up to the scheme's own \
             error; held to 2% as for a ring on a wall",
        ),
        Check::judged(
            "energy balance, widest swing over the run (through the impact)",
            format!("{:.2}%", 100.0 * widest),
            "within 2%",
            widest <= 0.02,
        ),
        Check::reported(
            "energy the contacts dissipated",
            format!(
                "{:.1} J/m ({:.2}% of the start)",
                last.dissipated,
                100.0 * last.dissipated / first.total()
            ),
            "μ = 0.2 friction",
        ),
    ];
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}
