//! The granular column collapse (aspect ratio H/L = 0.5,
//! Drucker–Prager sand on a rough floor): run-out and final height against
//! the published laws: a comparison, not a target, so
//! the checks are reported without a verdict.

use super::{Check, Context, Curve, Figure, Measured, VerifyError, body, largest};
use crate::math::Real;
use crate::resources::EnergyLog;

/// Farthest x and highest y of a body's points.
fn extent(positions: &[crate::math::DVec2]) -> (Real, Real) {
    positions
        .iter()
        .fold((Real::NEG_INFINITY, Real::NEG_INFINITY), |(x, y), p| {
            (x.max(p.x), y.max(p.y))
        })
}

/// The scene's aspect ratio H/L, at which the published laws are read.
const ASPECT: Real = 0.5;

/// Steps between two samples of the run-out and height for the figure.
const SAMPLE_EVERY: u64 = 1000;

/// Run-out ΔL/L0 and height H/H0 of `positions` against the initial
/// front L0 and top H0.
fn normalised(positions: &[crate::math::DVec2], (front0, top0): (Real, Real)) -> (Real, Real) {
    let (front, top) = extent(positions);
    ((front - front0) / front0, top / top0)
}

/// The full scene to 1.5 s (about 20 minutes on 2 cores), with the
/// run-out and the height over time beside the published final values.
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let scene = ctx.scene("column_collapse.ron")?;
    let run = "column_collapse";
    let mut sim = ctx.start(run, &scene)?;
    let mut history = Vec::new();
    ctx.advance(run, &mut sim, |sim| {
        let time = sim.clock().time;
        if sim.clock().step.is_multiple_of(SAMPLE_EVERY)
            && let Some(points) = sim.points_of("column")
        {
            let start = extent(&points.initial_position);
            history.push((time, normalised(&points.position, start)));
        }
        false
    })?;
    let time = sim.clock().time;
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let peak = largest(energy.iter().map(|s| s.kinetic));
    let resting = energy.last().map_or(Real::NAN, |s| s.kinetic) / peak;
    let points = body(&mut sim, "column")?;
    // Front and top: the farthest and highest point centres, before and
    // after. A lone point thrown ahead of the front would count, so the x
    // beyond which only 0.1% of the points lie is given beside it.
    let (front0, top0) = extent(&points.initial_position);
    let (front, top) = extent(&points.position);
    let aspect = top0 / front0;
    let mut xs: Vec<Real> = points.position.iter().map(|p| p.x).collect();
    xs.sort_unstable_by(Real::total_cmp);
    let bulk_front = xs.get(xs.len() * 999 / 1000).copied().unwrap_or(Real::NAN);
    history.push((time, normalised(&points.position, (front0, top0))));
    let figure = figure(&history);
    let checks = vec![
        Check::reported(
            format!(
                "run-out ΔL/L0, front = the farthest point ({front0:.3} → {front:.3} m; 99.9% of \
                 the points within {bulk_front:.3} m), a = {aspect:.2}"
            ),
            format!("{:.3}", (front - front0) / front0),
            "0.60 for sand (Lube et al. 2005: 1.2 a for a < 1.8)",
        ),
        Check::reported(
            format!("final height H∞/H0 (top {top0:.3} → {top:.3} m)"),
            format!("{:.3}", top / top0),
            "1 for a < 1.15 (Lube et al. 2005)",
        ),
        Check::reported(
            "kinetic energy at the end over its peak (the collapse has stopped)",
            format!("{resting:.1e}"),
            "≪ 1",
        ),
    ];
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}

/// Run-out and height over time, (t, (ΔL/L0, H/H0)), beside Lube et al.'s
/// final values for sand at the scene's aspect ratio a: ΔL/L0 = 1.2 a,
/// H∞ = H0.
fn figure(history: &[(Real, (Real, Real))]) -> Figure {
    let end = history.last().map_or(0.0, |h| h.0);
    let level = |value: Real| vec![(0.0, value), (end, value)];
    Figure::new(
        "Granular column collapse, H/L = 0.5",
        "time t (s)",
        "run-out ΔL/L0 and height H/H0",
    )
    .with(Curve::computed(
        "mpdem, run-out ΔL/L0 (farthest point)",
        history
            .iter()
            .map(|&(t, (run_out, _))| (t, run_out))
            .collect(),
    ))
    .with(Curve::reference(
        "Lube et al.: final ΔL/L0 = 1.2 a = 0.60",
        level(1.2 * ASPECT),
    ))
    .with(Curve::computed(
        "mpdem, height H/H0 (highest point)",
        history
            .iter()
            .map(|&(t, (_, height))| (t, height))
            .collect(),
    ))
    .with(Curve::reference("Lube et al.: H∞/H0 = 1", level(1.0)))
}
