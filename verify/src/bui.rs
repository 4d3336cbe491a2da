//! The plane-strain collapse of aluminium rods of Bui et al. (2008), at
//! the engine's defaults, at cells L0/40, L0/80 (the scene's) and L0/160:
//! the final surface against the measured one, the toe where the deposit
//! thins below 5% of H0 against the measured toe, the farthest point as a
//! bound on the spray, and the toe's convergence in the cell.

use super::deposit_run::DepositRun;
use super::{Check, Context, Curve, Figure, Measured, VerifyError, at_cell, percent, write_csv};
use mpdem::math::Real;

/// The measured final surface (x, y in m): Bui, Fukagawa, Sako and Ohno
/// (2008), Int. J. Numer. Anal. Methods Geomech. 32, 1537–1570, as
/// digitised with the open GPU MPM code of Wyser et al. (2021), Geosci.
/// Model Dev. 14, 7749–7774.
const MEASURED_SURFACE: [(Real, Real); 23] = [
    (0.000123, 0.099232),
    (0.019604, 0.099282),
    (0.039837, 0.095872),
    (0.060043, 0.089001),
    (0.080267, 0.084437),
    (0.100084, 0.077565),
    (0.120302, 0.072232),
    (0.140128, 0.066514),
    (0.160349, 0.061566),
    (0.180159, 0.053924),
    (0.199979, 0.047437),
    (0.220200, 0.042488),
    (0.240790, 0.034849),
    (0.262186, 0.030673),
    (0.282024, 0.026493),
    (0.302245, 0.021545),
    (0.322094, 0.018903),
    (0.342313, 0.013571),
    (0.362162, 0.010929),
    (0.382398, 0.007904),
    (0.402236, 0.003724),
    (0.422094, 0.002237),
    (0.442348, 0.001520),
];

/// The column's initial height (m).
const H0: Real = 0.1;

/// The measured toe where the deposit is 5% of H0 thick: ΔL/L0.
const MEASURED_TOE_5: Real = 0.98;

/// The measured deposit's edge, 1.5 mm thick: ΔL/L0.
const MEASURED_EDGE: Real = 1.21;

/// How far from the measured toe the computed one may lie: the rods'
/// friction angle is known to about a degree, and the run-out of a
/// collapse changes by several percent per degree.
const TOE_TOLERANCE: Real = 0.10;

/// How far past the measured edge a point may lie: the deposit's last
/// grains, not material thrown ahead of it.
const SPRAY_BOUND: Real = 0.15;

/// The largest rms distance of the final surface from the measured one, a
/// fraction of H0: the digitised surface's scatter and the rods' size,
/// 1–1.5 mm, are of that order.
const SURFACE_TOLERANCE: Real = 0.03;

/// The largest change of the toe at the last halving of the cell.
const CONVERGED_CHANGE: Real = 0.05;

/// The collapse at L0/40, L0/80 and L0/160 (about 6 minutes on 2 cores).
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let scene = ctx.scene("granular_collapse_bui.ron")?;
    let mut runs = Vec::new();
    for (factor, cell) in [(2.0, "L0/40"), (1.0, "L0/80"), (0.5, "L0/160")] {
        let at = at_cell(&scene, factor);
        runs.push(DepositRun::measure(
            ctx,
            &format!("granular_collapse_bui, cell {cell}"),
            format!("defaults, cell {cell}"),
            &at,
        )?);
    }
    let dir = ctx.out_dir("granular_collapse_bui")?;
    let rows: Vec<String> = runs
        .iter()
        .flat_map(|run| {
            run.surface
                .iter()
                .map(move |(x, h)| format!("\"{}\",{x:e},{h:e}", run.label))
        })
        .collect();
    write_csv(&dir, "deposit.csv", "run,x (m),surface height (m)", &rows)?;
    let mut checks: Vec<Check> = runs.iter().map(reported).collect();
    if let [.., coarse, fine] = &runs[..] {
        checks.extend(judged(coarse, fine));
    }
    Ok(Measured {
        checks,
        figures: vec![surface_figure(&runs)],
    })
}

/// The rms distance of a run's final surface from the measured one, at
/// the measured points (m).
fn surface_rms(run: &DepositRun) -> Real {
    let sum: Real = MEASURED_SURFACE
        .iter()
        .map(|&(x, y)| (run.height_at(x) - y).powi(2))
        .sum();
    (sum / MEASURED_SURFACE.len() as Real).sqrt()
}

/// One run's measurements, reported.
fn reported(run: &DepositRun) -> Check {
    Check::reported(
        format!(
            "{}: toe ΔL/L0 at 5% and 2% of H0, farthest point, mass beyond the toe at 2%, surface rms",
            run.label
        ),
        format!(
            "{:.3}, {:.3}, {:.3}, {}, {} of H0",
            run.toe_5(),
            run.toe_2(),
            run.farthest(),
            percent(run.spray, 2),
            percent(surface_rms(run) / H0, 1)
        ),
        "measured: 0.98, 1.12, 1.21 (the edge, 1.5 mm thick)",
    )
}

/// The judged checks at the finest cell and its halving.
fn judged(coarse: &DepositRun, fine: &DepositRun) -> Vec<Check> {
    let rms = surface_rms(fine) / H0;
    let toe = fine.toe_5();
    let farthest = fine.farthest();
    let bound = MEASURED_EDGE * (1.0 + SPRAY_BOUND);
    let change = toe / coarse.toe_5() - 1.0;
    vec![
        Check::judged(
            format!("{}: final surface, rms from the measured one", fine.label),
            format!("{} of H0", percent(rms, 1)),
            format!("within {}% of H0", SURFACE_TOLERANCE * 100.0),
            rms <= SURFACE_TOLERANCE,
        )
        .because("the digitised surface's scatter and the rods' size are of that order"),
        Check::judged(
            format!(
                "{}: toe ΔL/L0 where the deposit is 5% of H0 thick",
                fine.label
            ),
            format!(
                "{toe:.3} ({} from {MEASURED_TOE_5})",
                percent(toe / MEASURED_TOE_5 - 1.0, 1)
            ),
            format!("{MEASURED_TOE_5} within {}%", TOE_TOLERANCE * 100.0),
            (toe / MEASURED_TOE_5 - 1.0).abs() <= TOE_TOLERANCE,
        )
        .because("the rods' friction angle is known to about a degree"),
        Check::judged(
            format!("{}: farthest point ΔL/L0", fine.label),
            format!("{farthest:.3}"),
            format!(
                "at most {bound:.2}, {}% past the measured edge",
                SPRAY_BOUND * 100.0
            ),
            farthest <= bound,
        )
        .because("no material thrown ahead of the deposit"),
        Check::judged(
            format!(
                "toe ΔL/L0 at 5% of H0 from {} to {}",
                coarse.label, fine.label
            ),
            format!("{:.3} → {toe:.3} ({})", coarse.toe_5(), percent(change, 1)),
            format!("within {}%", CONVERGED_CHANGE * 100.0),
            change.abs() <= CONVERGED_CHANGE,
        )
        .because("converged in the cell"),
    ]
}

/// The final surfaces beside the measured one.
fn surface_figure(runs: &[DepositRun]) -> Figure {
    let mut figure = Figure::new(
        "Collapse of aluminium rods (Bui et al. 2008): final surface",
        "x (m)",
        "surface height (m)",
    );
    for run in runs {
        figure = figure.with(Curve::computed(run.label.clone(), run.surface.clone()));
    }
    figure.with(Curve::reference(
        "measured (Bui et al. 2008)",
        MEASURED_SURFACE.to_vec(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measured_toes_are_read_off_the_measured_surface() {
        const L0: Real = 0.2;
        // The surface passes 5 mm at x ≈ 0.396 m and ends at 0.442 m.
        let crossing = MEASURED_SURFACE
            .windows(2)
            .find(|w| w[0].1 >= 0.05 * H0 && w[1].1 < 0.05 * H0)
            .map(|w| w[0].0 + (w[0].1 - 0.05 * H0) / (w[0].1 - w[1].1) * (w[1].0 - w[0].0))
            .unwrap();
        assert!(
            ((crossing - L0) / L0 - MEASURED_TOE_5).abs() < 0.01,
            "{crossing}"
        );
        let edge = MEASURED_SURFACE.last().unwrap().0;
        assert!(((edge - L0) / L0 - MEASURED_EDGE).abs() < 0.01, "{edge}");
    }
}
