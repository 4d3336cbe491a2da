//! The geostatic check (the loading procedure of the paper's section 4.3):
//! an elastic soil column settled under gravity, then under a 150 kPa
//! surcharge, against σ_v = ρ g z and σ_h = K0 σ_v.

use super::{
    Check, Context, Curve, Figure, Measured, VerifyError, base_stress, body, largest, percent,
    stages_as_planned,
};
use mpdem::Simulation;
use mpdem::math::Real;
use mpdem::resources::{StageEndReason, StageLog};
use std::collections::BTreeMap;

/// Density (kg/m³), gravity (m/s²), column height and cell size (m),
/// Poisson's ratio and surcharge (Pa) of `scenes/geostatic_column.ron`.
const DENSITY: Real = 1620.0;
const GRAVITY: Real = 9.81;
const HEIGHT: Real = 4.0;
const CELL: Real = 0.2;
const POISSON_RATIO: Real = 0.3;
const SURCHARGE: Real = 150e3;

/// Base stress σ_yy of the soil's lowest row of points and the largest
/// departure of σ_xx / σ_yy from `k0` over the points carrying more than
/// 1 kPa.
pub fn base_stress_and_k0_error(
    sim: &mut Simulation,
    k0: Real,
) -> Result<(Real, Real), VerifyError> {
    let points = body(sim, "soil")?;
    let k0_error = largest(
        points
            .stress
            .iter()
            .filter(|s| s.yy < -1e3)
            .map(|s| (s.xx / s.yy - k0).abs() / k0),
    );
    Ok((base_stress(points), k0_error))
}

/// The mean σ_yy (Pa) of every row of points, by the row's initial
/// height X (m), from the lowest row up.
pub fn row_stresses(sim: &mut Simulation) -> Result<Vec<(Real, Real)>, VerifyError> {
    let points = body(sim, "soil")?;
    let mut rows: BTreeMap<i64, (Real, Real, usize)> = BTreeMap::new();
    for (x, s) in points.initial_position.iter().zip(&points.stress) {
        // Rows of the lattice are 0.1 m apart: a micrometre tells them apart.
        let row = rows
            .entry((x.y * 1e6).round() as i64)
            .or_insert((x.y, 0.0, 0));
        row.1 += s.yy;
        row.2 += 1;
    }
    Ok(rows
        .values()
        .map(|&(height, sum, count)| (height, sum / count as Real))
        .collect())
}

/// The expected σ_yy (Pa) at initial height X: −(ρ g (H − X) +
/// `surcharge`), the weight of the soil above and the load on its surface.
fn expected_stress(height: Real, surcharge: Real) -> Real {
    -(DENSITY * GRAVITY * (HEIGHT - height) + surcharge)
}

/// The largest departure, over `rows` ([`row_stresses`]), of a row's mean
/// σ_yy from ρ g (H − X) + `surcharge`: the weight of the soil above a row
/// and the load on its surface. The rows nearest the surface show how the
/// surcharge reaches the body (at the point centres, the top row carried
/// 69%).
pub fn worst_row_error(rows: &[(Real, Real)], surcharge: Real) -> Real {
    largest(
        rows.iter()
            .map(|&(height, mean)| (mean / expected_stress(height, surcharge) - 1.0).abs()),
    )
}

/// The rows' σ_v (kPa, compression positive) against depth below the
/// surface (m), computed (labelled with `stage`) and expected under
/// `surcharge` (labelled `reference`).
fn profile(rows: &[(Real, Real)], surcharge: Real, stage: &str, reference: &str) -> [Curve; 2] {
    let depth = |height: Real| HEIGHT - height;
    [
        Curve::computed(
            format!("mpdem, {stage}"),
            rows.iter()
                .map(|&(height, mean)| (depth(height), -mean / 1e3))
                .collect(),
        ),
        Curve::reference(
            reference,
            rows.iter()
                .map(|&(height, _)| (depth(height), -expected_stress(height, surcharge) / 1e3))
                .collect(),
        ),
    ]
}

/// Both stages of the scene, measured at the end of each.
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let scene = ctx.scene("geostatic_column.ron")?;
    let run = "geostatic_column";
    let mut sim = ctx.start(run, &scene)?;
    let k0 = POISSON_RATIO / (1.0 - POISSON_RATIO);
    // The lowest points carry the stress of the bottom cell's centre, h/2
    // above the base (linear shape functions: uniform strain in a cell).
    let geostatic = -DENSITY * GRAVITY * (HEIGHT - 0.5 * CELL);
    ctx.advance(run, &mut sim, |sim| {
        !sim.world().resource::<StageLog>().records.is_empty()
    })?;
    let mut checks = Vec::new();
    // The targets: σ_v within 3%, σ_h / σ_v close to K0 (held to 1%).
    let mut judge = |stage: &str, reference: &str, base: Real, expected: Real, k0_error: Real| {
        let error = base / expected - 1.0;
        checks.push(Check::judged(
            format!("{stage}: base σ_v against {reference} at the bottom cell's centre"),
            format!("{:.1} kPa ({})", base / 1e3, percent(error, 3)),
            "within 3%",
            error.abs() <= 0.03,
        ));
        checks.push(Check::judged(
            format!("{stage}: largest |σ_h/σ_v − K0| / K0, K0 = ν/(1−ν)"),
            format!("{:.1e}%", 100.0 * k0_error),
            "≤ 1%",
            k0_error <= 0.01,
        ));
    };
    let (base, k0_error) = base_stress_and_k0_error(&mut sim, k0)?;
    judge("geostatic stage", "ρ g z", base, geostatic, k0_error);
    let geostatic_rows = row_stresses(&mut sim)?;
    ctx.advance(run, &mut sim, |_| false)?;
    let (base, k0_error) = base_stress_and_k0_error(&mut sim, k0)?;
    judge(
        "150 kPa surcharge",
        "ρ g z + 150 kPa",
        base,
        geostatic - SURCHARGE,
        k0_error,
    );
    // The validation's 3% at every depth, the surface included.
    let rows = row_stresses(&mut sim)?;
    let row_error = worst_row_error(&rows, SURCHARGE);
    checks.push(Check::judged(
        "150 kPa surcharge: every row of points' mean σ_v against ρ g z + 150 kPa at its initial depth",
        format!("largest departure {:.1}%", 100.0 * row_error),
        "within 3%",
        row_error <= 0.03,
    )
    .because("the validation's 3% on σ_v, held at every depth, the surface included"));
    let (stages, as_planned) = stages_as_planned(
        &sim,
        &[
            ("geostatic", StageEndReason::Condition),
            ("surcharge", StageEndReason::Condition),
        ],
    );
    let time = sim.clock().time;
    checks.push(Check::judged(
        "the stages, in order, and how they ended",
        format!("{stages}, ended at t = {time:.2} s"),
        "geostatic then surcharge, each on its kinetic-energy condition, before half of time.end",
        as_planned && time < 0.5 * scene.time.end,
    ));
    let mut figure = Figure::new(
        "Soil column: σ_v of each row of points",
        "depth below the surface z (m)",
        "vertical stress σ_v (kPa, compression positive)",
    );
    figure
        .curves
        .extend(profile(&geostatic_rows, 0.0, "geostatic stage", "ρ g z"));
    figure.curves.extend(profile(
        &rows,
        SURCHARGE,
        "150 kPa surcharge",
        "ρ g z + 150 kPa",
    ));
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}
