//! The granular column collapse (aspect ratio H/L = 0.5, Drucker–Prager
//! sand on a rough floor). The column is run at the engine's default
//! transfer at the scene's cell h and at 2h, with the same time step: the
//! run-out, read at the deposit's toe where it thins below 2% of H0 as
//! Lube et al. read theirs, and the final height must first change by at
//! most 5% from 2h to h, and are then judged at h against Lube et al.'s
//! law for sand. The farthest point is reported, a bound on the spray.
//! The scene as written (the paper's transfer: eq. 11b with 1% PIC) is
//! reported at h beside them, and two runs at 2h with GeoTaichi's
//! position update are reported beside GeoTaichi's own. The final
//! deposits of every run go to `deposit.csv`.

use super::deposit_run::DepositRun;
use super::{
    Check, Context, Curve, Figure, Measured, VerifyError, at_cell, largest, percent, write_csv,
};
use mpdem::math::Real;
use mpdem::resources::{PositionUpdate, Settings};
use mpdem::scene::Scene;

/// The scene's aspect ratio H/L, at which the published laws are read.
const ASPECT: Real = 0.5;

/// Lube et al. (2005)'s run-out of sand for a < 1.8: ΔL/L0 = 1.2 a.
const SAND_RUN_OUT: Real = 1.2 * ASPECT;

/// How far from the sand law's run-out the computed one may lie.
const SAND_TOLERANCE: Real = 0.15;

/// How far from H0 the final height may lie: for a < 1.15 the top of the
/// column is left undisturbed (Lube et al. 2005), so it loses only its
/// elastic settlement, ρ g H0 / E ≈ 0.13% in this scene.
const HEIGHT_TOLERANCE: Real = 0.01;

/// The largest change of the run-out and of the final height from cell 2h
/// to h for the column to count as converged in the cell.
const CONVERGED_CHANGE: Real = 0.05;

/// The column computed with GeoTaichi (Shi, Guo and Yang 2024; commit
/// 8e22a64 of its repository) on this scene's set-up at cell 2h with
/// Δt = 2e-5 s, FLIP with `alphaPIC` 0.01 and 0, positions moved by the
/// new grid velocity, its `Inscribed` Drucker–Prager (eq. 16's cone) and
/// uGIMP, to 1.5 s: the final farthest point and the x within which 99.9%
/// of the points lie (m), and the peak kinetic energy (J/m).
const GEOTAICHI: [(Real, [Real; 3]); 2] =
    [(0.01, [2.920, 2.898, 819.3]), (0.0, [4.951, 4.283, 1148.6])];

/// The column at the engine's default transfer at 2h and h, the scene as
/// written at h, and GeoTaichi's update at 2h (about 30 minutes on 2
/// cores).
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let written = ctx.scene("column_collapse.ron")?;
    let defaults = Scene {
        settings: Settings::default(),
        ..written.clone()
    };
    let doubled = at_cell(&defaults, 2.0);
    let coarse = DepositRun::measure(
        ctx,
        "column_collapse, defaults, cell doubled",
        "defaults, cell 2h",
        &doubled,
    )?;
    let fine = DepositRun::measure(
        ctx,
        "column_collapse, defaults",
        "defaults, cell h",
        &defaults,
    )?;
    let paper = DepositRun::measure(
        ctx,
        "column_collapse, the scene's transfer",
        "the scene's transfer (eq. 11b, 1% PIC), cell h",
        &written,
    )?;
    let mut cross_code = Vec::new();
    for (pic, reference) in GEOTAICHI {
        let mut scene = at_cell(&written, 2.0);
        scene.time.dt = 2.0 * written.time.dt;
        scene.settings.position_update = Some(PositionUpdate::NewGridVelocity);
        scene.settings.pic_fraction = pic;
        scene.settings.granular_relaxation = None;
        let label = if pic == 0.0 {
            "GeoTaichi's update, FLIP, cell 2h"
        } else {
            "GeoTaichi's update, 1% PIC, cell 2h"
        };
        let run = DepositRun::measure(ctx, &format!("column_collapse, {label}"), label, &scene)?;
        cross_code.push((run, reference));
    }
    let scene_runs = [&coarse, &fine, &paper];
    let runs = scene_runs
        .into_iter()
        .chain(cross_code.iter().map(|(run, _)| run));
    let dir = ctx.out_dir("column_collapse")?;
    let rows: Vec<String> = runs
        .flat_map(|run| {
            run.surface
                .iter()
                .map(move |(x, height)| format!("\"{}\",{x:e},{height:e}", run.label))
        })
        .collect();
    write_csv(&dir, "deposit.csv", "run,x (m),surface height (m)", &rows)?;
    let mut checks: Vec<Check> = scene_runs.iter().flat_map(|run| run_checks(run)).collect();
    checks.extend(judged(&coarse, &fine));
    checks.extend(
        cross_code
            .iter()
            .map(|(run, reference)| against_geotaichi(run, reference)),
    );
    Ok(Measured {
        checks,
        figures: vec![history_figure(&scene_runs), deposit_figure(&scene_runs)],
    })
}

/// The reported measurements of one run.
fn run_checks(run: &DepositRun) -> Vec<Check> {
    let label = &run.label;
    vec![
        Check::reported(
            format!("{label}: run-out ΔL/L0 at the toe, where the deposit thins below 5% of H0"),
            format!("{:.3}", run.toe_5()),
            "0.60 for sand at 2% of H0 (Lube et al. 2005: 1.2 a for a < 1.8)",
        ),
        Check::reported(
            format!(
                "{label}: run-out ΔL/L0 at the farthest point, and the mass beyond the toe at 2%"
            ),
            format!("{:.3}, {}", run.farthest(), percent(run.spray, 2)),
            "a bound on the spray: one point is a parcel with no thickness",
        ),
        Check::reported(
            format!("{label}: kinetic energy at the end over its peak"),
            format!("{:.1e}", run.resting),
            "≪ 1 (the collapse has stopped)",
        ),
    ]
}

/// The judged checks: the default transfer converged in the cell from 2h
/// to h, then at h against the sand law.
fn judged(coarse: &DepositRun, fine: &DepositRun) -> Vec<Check> {
    let change = |of: fn(&DepositRun) -> Real, what: &str| {
        let (a, b) = (of(coarse), of(fine));
        let relative = b / a - 1.0;
        Check::judged(
            format!("defaults: {what} from cell 2h to h"),
            format!("{a:.3} → {b:.3} ({})", percent(relative, 1)),
            format!("within {}%", CONVERGED_CHANGE * 100.0),
            relative.abs() <= CONVERGED_CHANGE,
        )
        .because("converged in the cell before it is compared with experiments")
    };
    let run_out = fine.toe_2();
    let height = fine.height();
    vec![
        change(DepositRun::toe_2, "run-out ΔL/L0 (toe at 2% of H0)"),
        change(DepositRun::height, "final height H∞/H0"),
        Check::judged(
            "defaults, cell h: run-out ΔL/L0 at the toe, where the deposit thins below 2% of H0, against sand",
            format!(
                "{run_out:.3} ({} from {SAND_RUN_OUT:.2})",
                percent(run_out / SAND_RUN_OUT - 1.0, 0)
            ),
            format!(
                "{SAND_RUN_OUT:.2} within {}% (Lube et al. 2005)",
                SAND_TOLERANCE * 100.0
            ),
            (run_out / SAND_RUN_OUT - 1.0).abs() <= SAND_TOLERANCE,
        )
        .because(
            "the law fits several granular materials, whose constants differ (Balmforth and \
             Kerswell 2005 find them material-dependent)",
        ),
        Check::judged(
            "defaults, cell h: final height H∞/H0 (the surface's highest point)",
            format!("{height:.3}"),
            format!("1 within {}%", HEIGHT_TOLERANCE * 100.0),
            (height - 1.0).abs() <= HEIGHT_TOLERANCE,
        )
        .because("the top stays undisturbed for a < 1.15 and settles only elastically"),
    ]
}

/// A run with GeoTaichi's update beside GeoTaichi's own run of the same
/// set-up (`GEOTAICHI`): GeoTaichi's figures are point centres.
fn against_geotaichi(run: &DepositRun, [front, bulk, peak]: &[Real; 3]) -> Check {
    Check::reported(
        format!(
            "{}, Δt = 2e-5 s: final farthest point, peak kinetic energy",
            run.label
        ),
        format!("{:.3} m, {:.1} J/m", run.farthest, run.peak_kinetic),
        format!(
            "GeoTaichi (Shi, Guo and Yang 2024), the same set-up: {front:.3} m ({bulk:.3} m where 99.9% of the points lie), {peak:.1} J/m"
        ),
    )
}

/// Run-out at the toe over time of every run, beside Lube et al.'s final
/// value.
fn history_figure(runs: &[&DepositRun]) -> Figure {
    let end = largest(runs.iter().filter_map(|r| r.history.last().map(|h| h.0)));
    let mut figure = Figure::new(
        "Granular column collapse, H/L = 0.5",
        "time t (s)",
        "run-out ΔL/L0 (toe at 2% of H0)",
    );
    for run in runs {
        figure = figure.with(Curve::computed(run.label.clone(), run.history.clone()));
    }
    figure.with(Curve::reference(
        "Lube et al.: final ΔL/L0 = 1.2 a = 0.60",
        vec![(0.0, SAND_RUN_OUT), (end, SAND_RUN_OUT)],
    ))
}

/// The final deposits, beside the toe that Lube et al.'s law gives.
fn deposit_figure(runs: &[&DepositRun]) -> Figure {
    let mut figure = Figure::new(
        "Granular column collapse, H/L = 0.5: final deposit",
        "x (m)",
        "surface height (m)",
    );
    for run in runs {
        figure = figure.with(Curve::computed(run.label.clone(), run.surface.clone()));
    }
    let (front0, top0) = runs.first().map_or((Real::NAN, Real::NAN), |r| r.start);
    let lube = front0 * (1.0 + SAND_RUN_OUT);
    figure.with(Curve::reference(
        "Lube et al.: toe at L0 (1 + 1.2 a)",
        vec![(lube, 0.0), (lube, top0)],
    ))
}
