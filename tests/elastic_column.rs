//! An elastic column settled under gravity between slip walls: uniaxial
//! strain, σ_yy = −ρ g (H − y), σ_xx / σ_yy = ν / (1 − ν).

mod common;

use common::{load_scene, run_scene};
use mpdem::prelude::*;

const RHO: Real = 2000.0;
const G: Real = 9.81;
const H: Real = 1.0;
const NU: Real = 0.3;

#[test]
fn settled_column_carries_its_weight() {
    let mut sim = run_scene(&load_scene("elastic_column.ron"));
    let points = sim.points_of("column").expect("column").clone();
    let lowest = points
        .initial_position
        .iter()
        .map(|p| p.y)
        .fold(Real::INFINITY, Real::min);
    let base: Vec<usize> = (0..points.len())
        .filter(|&p| points.initial_position[p].y == lowest)
        .collect();
    let mean =
        |f: &dyn Fn(usize) -> Real| base.iter().map(|&p| f(p)).sum::<Real>() / base.len() as Real;
    let syy = mean(&|p| points.stress[p].yy);
    let sxx = mean(&|p| points.stress[p].xx);
    let weight = RHO * G * H;
    let ratio = sxx / syy;
    let k0 = NU / (1.0 - NU);
    println!(
        "column base: sigma_yy = {syy:.1} Pa vs rho g H = {weight:.1} Pa ({:+.2}%), sigma_xx/sigma_yy = {ratio:.5} vs {k0:.5} ({:+.3}%)",
        100.0 * (-syy / weight - 1.0),
        100.0 * (ratio / k0 - 1.0)
    );
    // Targets of the issue: 2% on the base stress (measured −1.25%: the
    // lowest points carry the stress of the bottom cell's centre, h/2 above
    // the base) and 3% on the stress ratio.
    assert!((-syy / weight - 1.0).abs() <= 0.02);
    assert!((ratio / k0 - 1.0).abs() <= 0.03);
    // At rest: the largest speed is a residue of the settling.
    let fastest = points
        .velocity
        .iter()
        .map(|v| v.length())
        .fold(0.0, Real::max);
    assert!(fastest < 1e-4, "column still moving at {fastest} m/s");
}

#[test]
fn stress_grows_linearly_with_depth() {
    let mut sim = run_scene(&load_scene("elastic_column.ron"));
    let h = sim.world().resource::<Grid>().cell_size;
    let points = sim.points_of("column").expect("column").clone();
    // With linear interpolation in each cell the strain is uniform across
    // it; compare every point with the exact stress at its cell's centre.
    // 1% of the base stress allows the uGIMP smoothing between cells.
    for p in 0..points.len() {
        let y0 = points.initial_position[p].y;
        let centre = ((y0 / h).floor() + 0.5) * h;
        let exact = -RHO * G * (H - centre);
        let error = (points.stress[p].yy - exact).abs() / (RHO * G * H);
        assert!(
            error < 0.01,
            "point {p} at y = {y0}: {} vs {exact}",
            points.stress[p].yy
        );
    }
}
