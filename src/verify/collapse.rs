//! The granular column collapse (aspect ratio H/L = 0.5,
//! Drucker–Prager sand on a rough floor): run-out and final height against
//! the published laws: a comparison, not a target, so
//! the checks are reported without a verdict.

use super::{Check, Context, VerifyError, body, largest};
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

/// The full scene to 1.5 s (about 20 minutes on 2 cores).
pub fn run(ctx: &Context) -> Result<Vec<Check>, VerifyError> {
    let scene = ctx.scene("column_collapse.ron")?;
    let mut sim = ctx.run("column_collapse", &scene)?;
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
    Ok(vec![
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
    ])
}
