//! The granular column collapse (aspect ratio H/L = 0.5, Drucker–Prager
//! sand on a rough floor). The column is run at the engine's default
//! transfer at the scene's cell h and at 2h, with the same time step: the
//! run-out and the final height must first change by at most 5% from 2h to
//! h, and are then judged at h against Lube et al.'s law for sand. The
//! scene as written (the paper's transfer: eq. 11b with 1% PIC) is
//! reported at h beside them, and two runs at 2h with GeoTaichi's
//! position update are reported beside GeoTaichi's own. The final deposits
//! of every run go to `deposit.csv`.

use super::{
    Check, Context, Curve, Figure, Measured, VerifyError, at_cell, body, largest, percent,
    write_csv,
};
use crate::math::{DVec2, Real};
use crate::plugins::fronts;
use crate::resources::{EnergyLog, PositionUpdate, Settings};
use crate::scene::Scene;

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

/// Steps between two samples of the run-out for the figure.
const SAMPLE_EVERY: u64 = 1000;

/// What one run of the collapse measured. Fronts and tops are point
/// centres (m).
struct Collapse {
    /// The run's label in the checks and figures.
    label: &'static str,
    /// Initial farthest and highest point: L0 and H0.
    start: (Real, Real),
    /// Final farthest point.
    front: Real,
    /// Final x beyond which 0.1% of the points lie: a few points thrown
    /// ahead of the deposit move the farthest point but not this one.
    bulk_front: Real,
    /// Final highest point.
    top: Real,
    /// Peak kinetic energy (J/m).
    peak_kinetic: Real,
    /// Kinetic energy at the end over its peak.
    resting: Real,
    /// (t, ΔL/L0) over the run.
    history: Vec<(Real, Real)>,
    /// The final deposit: (x, highest point) per column of the coarse cell.
    deposit: Vec<(Real, Real)>,
}

impl Collapse {
    /// ΔL/L0 at the farthest point.
    fn run_out(&self) -> Real {
        (self.front - self.start.0) / self.start.0
    }

    /// ΔL/L0 at the bulk front.
    fn bulk_run_out(&self) -> Real {
        (self.bulk_front - self.start.0) / self.start.0
    }

    /// H∞/H0.
    fn height(&self) -> Real {
        self.top / self.start.1
    }
}

/// Runs `scene` to its end as the run `run` and measures it, the deposit
/// in columns `bin` wide (the coarse run's cell, so that every run has
/// points in every column its deposit covers).
fn collapse(
    ctx: &Context,
    (run, label): (&str, &'static str),
    scene: &Scene,
    bin: Real,
) -> Result<Collapse, VerifyError> {
    let mut sim = ctx.start(run, scene)?;
    let mut history = Vec::new();
    let mut start = None;
    ctx.advance(run, &mut sim, |sim| {
        if sim.clock().step.is_multiple_of(SAMPLE_EVERY)
            && let Some(points) = sim.points_of("column")
        {
            let (front0, _) = *start.get_or_insert_with(|| extent(&points.initial_position));
            let (front, _) = extent(&points.position);
            history.push((sim.clock().time, (front - front0) / front0));
        }
        false
    })?;
    let time = sim.clock().time;
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let peak = largest(energy.iter().map(|s| s.kinetic));
    let resting = energy.last().map_or(Real::NAN, |s| s.kinetic) / peak;
    let points = body(&mut sim, "column")?;
    let start = extent(&points.initial_position);
    let mut xs: Vec<Real> = points.position.iter().map(|p| p.x).collect();
    let (front, bulk_front) = fronts(&mut xs);
    let top = extent(&points.position).1;
    if history.last().is_none_or(|&(sampled, _)| sampled < time) {
        history.push((time, (front - start.0) / start.0));
    }
    Ok(Collapse {
        label,
        start,
        front,
        bulk_front,
        top,
        peak_kinetic: peak,
        resting,
        history,
        deposit: deposit(&points.position, bin),
    })
}

/// Farthest x and highest y of a body's points.
fn extent(positions: &[DVec2]) -> (Real, Real) {
    positions
        .iter()
        .fold((Real::NEG_INFINITY, Real::NEG_INFINITY), |(x, y), p| {
            (x.max(p.x), y.max(p.y))
        })
}

/// The deposit's surface: for each column of width `bin` from x = 0 that
/// holds points, its centre and its highest point, in x order.
fn deposit(positions: &[DVec2], bin: Real) -> Vec<(Real, Real)> {
    let columns = positions
        .iter()
        .map(|p| (p.x / bin).floor().max(0.0) as usize + 1)
        .max()
        .unwrap_or(0);
    let mut tops = vec![Real::NEG_INFINITY; columns];
    for p in positions {
        let k = (p.x / bin).floor().max(0.0) as usize;
        tops[k] = tops[k].max(p.y);
    }
    tops.iter()
        .enumerate()
        .filter(|(_, top)| top.is_finite())
        .map(|(k, &top)| ((k as Real + 0.5) * bin, top))
        .collect()
}

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
    let bin = doubled.grid.cell_size;
    let coarse = collapse(
        ctx,
        (
            "column_collapse, defaults, cell doubled",
            "defaults, cell 2h",
        ),
        &doubled,
        bin,
    )?;
    let fine = collapse(
        ctx,
        ("column_collapse, defaults", "defaults, cell h"),
        &defaults,
        bin,
    )?;
    let paper = collapse(
        ctx,
        (
            "column_collapse, the scene's transfer",
            "the scene's transfer (eq. 11b, 1% PIC), cell h",
        ),
        &written,
        bin,
    )?;
    let mut cross_code = Vec::new();
    for (pic, reference) in GEOTAICHI {
        let mut scene = at_cell(&written, 2.0);
        scene.time.dt = 2.0 * written.time.dt;
        scene.settings.position_update = Some(PositionUpdate::NewGridVelocity);
        scene.settings.pic_fraction = pic;
        let label = if pic == 0.0 {
            "GeoTaichi's update, FLIP, cell 2h"
        } else {
            "GeoTaichi's update, 1% PIC, cell 2h"
        };
        let run = collapse(
            ctx,
            (&format!("column_collapse, {label}"), label),
            &scene,
            bin,
        )?;
        cross_code.push((run, reference));
    }
    let scene_runs = [&coarse, &fine, &paper];
    let runs = scene_runs
        .into_iter()
        .chain(cross_code.iter().map(|(run, _)| run));
    let dir = ctx.out_dir("column_collapse")?;
    let rows: Vec<String> = runs
        .flat_map(|run| {
            run.deposit
                .iter()
                .map(move |(x, top)| format!("\"{}\",{x:e},{top:e}", run.label))
        })
        .collect();
    write_csv(&dir, "deposit.csv", "run,x (m),highest point (m)", &rows)?;
    let mut checks: Vec<Check> = scene_runs.iter().flat_map(|run| run_checks(run)).collect();
    checks.push(Check::reported(
        "defaults: run-out ΔL/L0 where 99.9% of the points lie, from cell 2h to h",
        format!(
            "{:.3} → {:.3} ({})",
            coarse.bulk_run_out(),
            fine.bulk_run_out(),
            percent(fine.bulk_run_out() / coarse.bulk_run_out() - 1.0, 1)
        ),
        "the farthest point's change, judged below",
    ));
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
fn run_checks(run: &Collapse) -> Vec<Check> {
    let label = run.label;
    vec![
        Check::reported(
            format!(
                "{label}: run-out ΔL/L0, front = the farthest point ({:.3} → {:.3} m)",
                run.start.0, run.front
            ),
            format!("{:.3}", run.run_out()),
            "0.60 for sand (Lube et al. 2005: 1.2 a for a < 1.8)",
        ),
        Check::reported(
            format!(
                "{label}: run-out ΔL/L0, front = where 99.9% of the points lie ({:.3} m)",
                run.bulk_front
            ),
            format!("{:.3}", run.bulk_run_out()),
            "0.60 for sand",
        ),
        Check::reported(
            format!(
                "{label}: final height H∞/H0 (top {:.3} → {:.3} m)",
                run.start.1, run.top
            ),
            format!("{:.3}", run.height()),
            "1 for a < 1.15 (Lube et al. 2005)",
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
fn judged(coarse: &Collapse, fine: &Collapse) -> Vec<Check> {
    let change = |of: fn(&Collapse) -> Real, what: &str| {
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
    let run_out = fine.run_out();
    let height = fine.height();
    vec![
        change(Collapse::run_out, "run-out ΔL/L0 (farthest point)"),
        change(Collapse::height, "final height H∞/H0"),
        Check::judged(
            "defaults, cell h: run-out ΔL/L0 (farthest point) against sand",
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
            "defaults, cell h: final height H∞/H0",
            format!("{height:.3}"),
            format!("1 within {}%", HEIGHT_TOLERANCE * 100.0),
            (height - 1.0).abs() <= HEIGHT_TOLERANCE,
        )
        .because("the top stays undisturbed for a < 1.15 and settles only elastically"),
    ]
}

/// A run with GeoTaichi's update beside GeoTaichi's own run of the same
/// set-up (`GEOTAICHI`).
fn against_geotaichi(run: &Collapse, [front, bulk, peak]: &[Real; 3]) -> Check {
    Check::reported(
        format!(
            "{}, Δt = 2e-5 s: final farthest point, where 99.9% of the points lie, peak kinetic \
             energy",
            run.label
        ),
        format!(
            "{:.3} m, {:.3} m, {:.1} J/m",
            run.front, run.bulk_front, run.peak_kinetic
        ),
        format!(
            "GeoTaichi (Shi, Guo and Yang 2024), the same set-up: {front:.3} m, {bulk:.3} m, {peak:.1} J/m"
        ),
    )
}

/// Run-out over time of every run, beside Lube et al.'s final value.
fn history_figure(runs: &[&Collapse]) -> Figure {
    let end = largest(runs.iter().filter_map(|r| r.history.last().map(|h| h.0)));
    let mut figure = Figure::new(
        "Granular column collapse, H/L = 0.5",
        "time t (s)",
        "run-out ΔL/L0 (farthest point)",
    );
    for run in runs {
        figure = figure.with(Curve::computed(run.label, run.history.clone()));
    }
    figure.with(Curve::reference(
        "Lube et al.: final ΔL/L0 = 1.2 a = 0.60",
        vec![(0.0, SAND_RUN_OUT), (end, SAND_RUN_OUT)],
    ))
}

/// The final deposits, beside the front that Lube et al.'s law gives.
fn deposit_figure(runs: &[&Collapse]) -> Figure {
    let mut figure = Figure::new(
        "Granular column collapse, H/L = 0.5: final deposit",
        "x (m)",
        "highest point y (m)",
    );
    for run in runs {
        figure = figure.with(Curve::computed(run.label, run.deposit.clone()));
    }
    let (front0, top0) = runs.first().map_or((Real::NAN, Real::NAN), |r| r.start);
    let lube = front0 * (1.0 + SAND_RUN_OUT);
    figure.with(Curve::reference(
        "Lube et al.: front at L0 (1 + 1.2 a)",
        vec![(lube, 0.0), (lube, top0)],
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_deposit_is_the_highest_point_of_each_occupied_column() {
        let points = [
            DVec2::new(0.01, 0.5),
            DVec2::new(0.02, 0.7),
            DVec2::new(0.05, 0.3),
            DVec2::new(0.13, 0.1),
        ];
        let deposit = deposit(&points, 0.04);
        assert_eq!(deposit.len(), 3, "{deposit:?}");
        let expected = [(0.02, 0.7), (0.06, 0.3), (0.14, 0.1)];
        for ((x, top), (ex, etop)) in deposit.iter().zip(expected) {
            assert!((x - ex).abs() < 1e-12 && *top == etop, "{deposit:?}");
        }
    }
}
