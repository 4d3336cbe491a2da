//! The paper's validation cases at full size, each measured against its
//! target (an analytical solution, published data or a reference computation):
//! what `mpdem verify` runs and tabulates, and what the tests and the long
//! (`--ignored`) tests assert.
//!
//! A [`Case`] loads its scene(s) from the scenes folder, runs them through a
//! [`Context`] (which reports progress to the caller) and returns its
//! [`Check`]s: a measured value, its target and whether the target is met,
//! or, where the paper only compares with published data, the comparison
//! reported without a verdict. One file per case; each states its
//! tolerances and why.

pub mod bench;
pub mod bui;
pub mod collapse;
pub mod dam_break;
mod deposit_run;
pub mod elastic_block;
pub mod elastic_disk;
pub mod footing;
pub mod geostatic;
pub mod hertz;
pub mod pile;
pub mod punch;
pub mod punch_elements;
pub mod quad4;
pub mod report;
pub mod rings;
pub mod sliding;
pub mod stacked_blocks;
pub mod stress_characteristics;
mod tally;
pub mod toppling;
pub mod wave;

use mpdem::components::MaterialPoints;
use mpdem::math::{DVec2, Real};
use mpdem::resources::{BlockLog, ProbeSample, Probes, StageEndReason, StageLog};
use mpdem::scene::{Scene, SceneError};
use mpdem::{Simulation, StepError};
use std::path::{Path, PathBuf};

pub use tally::Tally;

/// Whether a check's target is met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The measured value meets the target.
    Met,
    /// The measured value misses the target.
    Missed,
    /// Compared with published data or another code, no target to meet
    /// (e.g. the plane-strain pile's q_c, which the published band for an
    /// axisymmetric cone does not judge).
    Reported,
}

impl Verdict {
    /// The word printed in the verdict column.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Met => "met",
            Verdict::Missed => "MISSED",
            Verdict::Reported => "reported",
        }
    }
}

/// One measured quantity of a case against its target.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is measured, e.g. "max |v − v_exact| at the midpoint".
    pub quantity: String,
    /// The measured value, formatted with its unit.
    pub measured: String,
    /// The target, or the published value it is compared with.
    pub target: String,
    /// Whether the target is met.
    pub verdict: Verdict,
    /// Why the target or its tolerance is what it is, where the case says.
    pub reason: Option<String>,
}

impl Check {
    /// A check with a target: met when `met`.
    pub fn judged(
        quantity: impl Into<String>,
        measured: impl Into<String>,
        target: impl Into<String>,
        met: bool,
    ) -> Self {
        Check {
            quantity: quantity.into(),
            measured: measured.into(),
            target: target.into(),
            verdict: if met { Verdict::Met } else { Verdict::Missed },
            reason: None,
        }
    }

    /// A measurement compared with `published`, without a verdict.
    pub fn reported(
        quantity: impl Into<String>,
        measured: impl Into<String>,
        published: impl Into<String>,
    ) -> Self {
        Check {
            quantity: quantity.into(),
            measured: measured.into(),
            target: published.into(),
            verdict: Verdict::Reported,
            reason: None,
        }
    }

    /// The check with the reason for its target or tolerance.
    pub fn because(mut self, reason: impl Into<String>) -> Self {
        self.reason = Some(reason.into());
        self
    }
}

/// Whether a curve of a [`Figure`] is the case's result or what it is
/// compared with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveKind {
    /// Computed by the case's runs.
    Computed,
    /// The reference a check compares with: an exact solution, a law, a
    /// reference computation or published values.
    Reference,
}

/// One labelled curve of a [`Figure`].
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Legend entry.
    pub label: String,
    /// (x, y) samples in drawing order.
    pub points: Vec<(Real, Real)>,
    /// Computed or reference.
    pub kind: CurveKind,
}

impl Curve {
    /// A curve computed by the case's runs.
    pub fn computed(label: impl Into<String>, points: Vec<(Real, Real)>) -> Self {
        Curve {
            label: label.into(),
            points,
            kind: CurveKind::Computed,
        }
    }

    /// A reference curve.
    pub fn reference(label: impl Into<String>, points: Vec<(Real, Real)>) -> Self {
        Curve {
            label: label.into(),
            points,
            kind: CurveKind::Reference,
        }
    }
}

/// A case's computed curves beside their references, for the report.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// Title above the chart.
    pub title: String,
    /// The x axis's quantity and unit.
    pub x_label: String,
    /// The y axis's quantity and unit.
    pub y_label: String,
    /// The curves, in legend order.
    pub curves: Vec<Curve>,
}

impl Figure {
    /// A figure without curves yet.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Figure {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            curves: Vec::new(),
        }
    }

    /// The figure with `curve` added.
    pub fn with(mut self, curve: Curve) -> Self {
        self.curves.push(curve);
        self
    }
}

/// What a case measured: its checks, and the figures of its curves
/// against their references (none where it has no curve).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measured {
    /// The checks, in the order printed.
    pub checks: Vec<Check>,
    /// The figures, in the order shown.
    pub figures: Vec<Figure>,
}

/// A validation case.
pub struct Case {
    /// Name on the command line (`mpdem verify NAME`).
    pub name: &'static str,
    /// Where it comes from: the paper's section, or the published source.
    pub source: &'static str,
    /// One line on what it is.
    pub about: &'static str,
    /// Rough cost in minutes on 2 cores, in release (measured).
    pub minutes: Real,
    /// Runs the case and measures it.
    pub run: fn(&Context) -> Result<Measured, VerifyError>,
}

/// Every case: the quick ones in the paper's order, then the long ones.
pub const CASES: &[Case] = &[
    Case {
        name: "wave_1d",
        source: "paper 4.1",
        about: "elastic wave in a bar against the exact solution",
        minutes: 0.1,
        run: wave::run,
    },
    Case {
        name: "toppling",
        source: "paper 4.2.1",
        about: "elastic block toppling on slopes of 14–20° against the same block by finite elements",
        minutes: 0.2,
        run: toppling::run,
    },
    Case {
        name: "sliding_45",
        source: "paper 4.2.2",
        about: "elastic block sliding on a 45° slope against rigid-block kinematics",
        minutes: 0.1,
        run: sliding::run,
    },
    Case {
        name: "geostatic_column",
        source: "paper 4.3, geostatic stage",
        about: "geostatic stage then a 150 kPa surcharge: σ_v and K0",
        minutes: 0.1,
        run: geostatic::run,
    },
    Case {
        name: "axisymmetric_punch",
        source: "finite elements (Sneddon 1946)",
        about: "rigid flat punch on an elastic cylinder as a body of revolution: stiffness at three cells against finite elements",
        minutes: 0.3,
        run: punch::run,
    },
    Case {
        name: "strip_footing",
        source: "Prandtl 1920, Reissner 1924",
        about: "smooth rigid strip footing on a weightless frictional soil under a surcharge: collapse load at three cells against N_q",
        minutes: 3.5,
        run: footing::run_strip,
    },
    Case {
        name: "circular_footing",
        source: "Cox, Eason and Hopkins 1961 (stress characteristics)",
        about: "smooth rigid circular footing on a weightless frictional soil under a surcharge, as a body of revolution: collapse load at three cells against N_q",
        minutes: 6.0,
        run: footing::run_circle,
    },
    Case {
        name: "two_rings",
        source: "paper 4.4.1",
        about: "two Neo-Hookean rings colliding at ±30 m/s: rebound, energy, no fragmentation",
        minutes: 0.1,
        run: rings::run,
    },
    Case {
        name: "stacked_blocks",
        source: "paper 4.5.1",
        about: "granular column collapsing onto three stacked blocks: arrival, blocks knocked off, block 2 at rest",
        minutes: 0.7,
        run: stacked_blocks::run,
    },
    Case {
        name: "hertz_disks",
        source: "paper 4.4.2",
        about: "two elastic disks pressed together against the 2D Hertz law, four resolutions",
        minutes: 9.5,
        run: hertz::run,
    },
    Case {
        name: "pile_penetration",
        source: "paper 4.3",
        about: "pile driven into Mohr–Coulomb sand at two cells: the cone resistance q_c and its convergence",
        minutes: 15.0,
        run: pile::run,
    },
    Case {
        name: "pile_penetration_axisymmetric",
        source: "paper 4.3, axisymmetric",
        about: "the same pile and sand axisymmetric, Susila and Hryciw's geometry, at two cells: q_c = 2 f_c / R²",
        minutes: 15.0,
        run: pile::run_axisymmetric,
    },
    Case {
        name: "pile_penetration_deep",
        source: "paper 4.3, to 12R",
        about: "both piles driven to z/R = 12 with the fixed base 6R below the tip: whether q_c levels off",
        minutes: 14.0,
        run: pile::run_deep,
    },
    Case {
        name: "dam_break",
        source: "paper 4.5.2",
        about: "dam break on an elastic cantilever beam: the impact on the beam",
        minutes: 2.0,
        run: dam_break::run,
    },
    Case {
        name: "granular_collapse_bui",
        source: "Bui et al. 2008 (experiment)",
        about: "plane-strain collapse of aluminium rods at the defaults, at three cells: the final surface and toe against the measured deposit",
        minutes: 6.0,
        run: bui::run,
    },
    Case {
        name: "column_collapse",
        source: "Lube et al. 2005",
        about: "granular column collapse, H/L = 0.5, at the default transfer at two cells: the toe and final height against Lube et al.'s sand law",
        minutes: 30.0,
        run: collapse::run,
    },
];

/// The case named `name`.
pub fn case(name: &str) -> Option<&'static Case> {
    CASES.iter().find(|c| c.name == name)
}

/// What a case gave: its checks and figures, or why it could not be
/// measured, and how long it took.
#[derive(Debug)]
pub struct CaseReport {
    /// The case's name.
    pub case: &'static str,
    /// Its checks and figures, or why it could not be measured.
    pub outcome: Result<Measured, VerifyError>,
    /// Wall-clock time it took (s).
    pub seconds: f64,
}

impl CaseReport {
    /// Runs `case` in `ctx`.
    pub fn run(case: &'static Case, ctx: &Context) -> Self {
        let started = std::time::Instant::now();
        let outcome = (case.run)(ctx);
        CaseReport {
            case: case.name,
            outcome,
            seconds: started.elapsed().as_secs_f64(),
        }
    }

    /// The checks (none if the case could not be measured).
    pub fn checks(&self) -> &[Check] {
        self.outcome.as_ref().map_or(&[], |m| &m.checks)
    }

    /// The figures (none if the case could not be measured).
    pub fn figures(&self) -> &[Figure] {
        self.outcome.as_ref().map_or(&[], |m| &m.figures)
    }

    /// Whether the case was measured and no check missed its target.
    pub fn all_met(&self) -> bool {
        self.outcome.is_ok() && self.checks().iter().all(|c| c.verdict != Verdict::Missed)
    }
}

impl std::fmt::Display for CaseReport {
    /// The case's name and time, then a line per check:
    /// `verdict  quantity: measured (target: ...)`.
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        writeln!(f, "{} ({:.0} s)", self.case, self.seconds)?;
        match &self.outcome {
            Ok(measured) => measured.checks.iter().try_for_each(|c| {
                writeln!(
                    f,
                    "  {:<8} {}: {} (target: {})",
                    c.verdict.word(),
                    c.quantity,
                    c.measured,
                    c.target
                )
            }),
            Err(e) => writeln!(f, "  FAILED   {e}"),
        }
    }
}

/// Writes the reports as CSV (`case,quantity,measured,target,verdict`,
/// every field quoted; a case that could not be measured has one row with
/// verdict `failed` and the error as its measurement).
pub fn write_table(path: &Path, reports: &[CaseReport]) -> std::io::Result<()> {
    use std::io::Write;
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let quoted = |field: &str| format!("\"{}\"", field.replace('"', "\"\""));
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "case,quantity,measured,target,verdict")?;
    for report in reports {
        let rows: Vec<[String; 4]> = match &report.outcome {
            Ok(measured) => measured
                .checks
                .iter()
                .map(|c| {
                    [
                        c.quantity.clone(),
                        c.measured.clone(),
                        c.target.clone(),
                        c.verdict.word().to_lowercase(),
                    ]
                })
                .collect(),
            Err(e) => vec![[
                "could not be measured".into(),
                e.to_string(),
                String::new(),
                "failed".into(),
            ]],
        };
        for row in rows {
            let fields: Vec<String> = std::iter::once(report.case)
                .chain(row.iter().map(String::as_str))
                .map(quoted)
                .collect();
            writeln!(out, "{}", fields.join(","))?;
        }
    }
    out.flush()
}

/// Progress of the runs of a case, for the caller to show.
#[derive(Clone, Copy, Debug)]
pub enum RunEvent<'a> {
    /// A run starts; it has at most `steps` steps.
    Started {
        /// What is run, e.g. "hertz_disks, cell R/40, 4 pt/cell".
        run: &'a str,
        /// The scene's number of steps (a staged run may end earlier).
        steps: u64,
    },
    /// The run has taken `step` steps.
    Stepped {
        /// Steps taken.
        step: u64,
    },
}

/// Where a case finds its scenes and writes its plots, and who hears of
/// its progress.
pub struct Context<'a> {
    scenes: PathBuf,
    out: PathBuf,
    observer: &'a (dyn Fn(RunEvent) + Sync),
}

/// Steps between two progress reports.
const REPORT_EVERY: u64 = 64;

impl<'a> Context<'a> {
    /// Scenes are read from `scenes`; a case writes its plots to
    /// `out/<case>/`; `observer` hears of every run and its progress.
    pub fn new(scenes: &Path, out: &Path, observer: &'a (dyn Fn(RunEvent) + Sync)) -> Self {
        Context {
            scenes: scenes.to_path_buf(),
            out: out.to_path_buf(),
            observer,
        }
    }

    /// Loads and validates the scene file `file` of the scenes folder.
    pub fn scene(&self, file: &str) -> Result<Scene, VerifyError> {
        Ok(Scene::load(&self.scenes.join(file))?)
    }

    /// The folder for the outputs of case `case`, created if needed.
    pub fn out_dir(&self, case: &str) -> Result<PathBuf, VerifyError> {
        let dir = self.out.join(case);
        std::fs::create_dir_all(&dir).map_err(|source| VerifyError::Io {
            path: dir.clone(),
            source,
        })?;
        Ok(dir)
    }

    /// Builds `scene` as the run named `run`.
    pub fn start(&self, run: &str, scene: &Scene) -> Result<Simulation, VerifyError> {
        let sim = Simulation::from_scene(scene)?;
        (self.observer)(RunEvent::Started {
            run,
            steps: sim.clock().total_steps(),
        });
        Ok(sim)
    }

    /// Steps `sim`, the run named `run`, until `done` holds or the run
    /// ends.
    pub fn advance(
        &self,
        run: &str,
        sim: &mut Simulation,
        mut done: impl FnMut(&mut Simulation) -> bool,
    ) -> Result<(), VerifyError> {
        while !sim.clock().finished() && !done(sim) {
            sim.step().map_err(|source| VerifyError::Step {
                run: run.to_string(),
                source,
            })?;
            let step = sim.clock().step;
            if step.is_multiple_of(REPORT_EVERY) {
                (self.observer)(RunEvent::Stepped { step });
            }
        }
        Ok(())
    }

    /// Builds `scene` as the run named `run` and steps it to its end.
    pub fn run(&self, run: &str, scene: &Scene) -> Result<Simulation, VerifyError> {
        let mut sim = self.start(run, scene)?;
        self.advance(run, &mut sim, |_| false)?;
        Ok(sim)
    }
}

/// Why a case could not be measured.
#[derive(Debug, thiserror::Error)]
pub enum VerifyError {
    /// A scene could not be loaded or built.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A run failed.
    #[error("{run}: {source}")]
    Step {
        /// The run's name.
        run: String,
        /// The failure.
        source: StepError,
    },
    /// An output could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The failure.
        source: std::io::Error,
    },
    /// The run did not give what the measurement needs (e.g. a stage that
    /// never ended).
    #[error("{0}")]
    Measurement(String),
}

/// `base` with its cell multiplied by `factor`, for a case's runs at other
/// cells: the grid keeps its extent (its columns rounded, its rows rounded
/// up), and the blocks' contact springs go with the cell, the points'
/// spacing, so that a block meets the same stiffness per metre of its
/// outline.
pub fn at_cell(base: &Scene, factor: Real) -> Scene {
    let mut scene = base.clone();
    let extent = base.grid.max() - base.grid.origin;
    scene.grid.cell_size *= factor;
    scene.grid.cells = (
        (extent.x / scene.grid.cell_size).round() as usize,
        (extent.y / scene.grid.cell_size - 1e-9).ceil() as usize,
    );
    for block in &mut scene.blocks {
        block.contact.normal_stiffness *= factor;
        block.contact.tangential_stiffness *= factor;
    }
    scene
}

/// For a block pressed down (a punch, a footing), at each of its samples:
/// how far it has sunk since its first sample (m) and its vertical
/// reaction (N per metre, or per radian in axisymmetry); `what` names the
/// block in the error when it was never sampled.
pub fn pressed_block(sim: &Simulation, what: &str) -> Result<Vec<(Real, Real)>, VerifyError> {
    let log = sim.world().resource::<BlockLog>();
    let start = log
        .samples
        .first()
        .ok_or_else(|| VerifyError::Measurement(format!("the {what} was never sampled")))?
        .origin;
    Ok(log
        .samples
        .iter()
        .map(|s| (start.y - s.origin.y, s.force.y))
        .collect())
}

/// Writes `rows` under `header` as `dir/file`.
pub(crate) fn write_csv(
    dir: &Path,
    file: &str,
    header: &str,
    rows: &[String],
) -> Result<(), VerifyError> {
    let path = dir.join(file);
    let text = std::iter::once(header.to_string())
        .chain(rows.iter().cloned())
        .collect::<Vec<_>>()
        .join("\n")
        + "\n";
    std::fs::write(&path, text).map_err(|source| VerifyError::Io { path, source })
}

/// `value` as a signed percentage with `decimals` decimals, e.g. "+1.25%".
pub fn percent(value: Real, decimals: usize) -> String {
    format!("{:+.*}%", decimals, 100.0 * value)
}

/// The samples of the probe named `name`.
pub fn probe_samples(sim: &Simulation, name: &str) -> Result<Vec<ProbeSample>, VerifyError> {
    let probes = sim.world().resource::<Probes>();
    let index = probes
        .probes
        .iter()
        .position(|p| p.name == name)
        .ok_or_else(|| VerifyError::Measurement(format!("the scene has no probe '{name}'")))?;
    Ok(probes.series(index).copied().collect())
}

/// The mass-weighted mean of a column of a body's points (e.g. positions:
/// the centre of mass).
pub fn mass_weighted_mean(points: &MaterialPoints, column: &[DVec2]) -> DVec2 {
    points
        .mass
        .iter()
        .zip(column)
        .map(|(m, x)| *m * *x)
        .sum::<DVec2>()
        / points.total_mass()
}

/// Centre of mass of a body's points, and its velocity.
pub fn centre_of_mass(points: &MaterialPoints) -> (DVec2, DVec2) {
    (
        mass_weighted_mean(points, &points.position),
        points.momentum() / points.total_mass(),
    )
}

/// The mean σ_yy of a body's lowest row of points (within 1 µm of the
/// lowest), e.g. the base stress of a soil column.
pub fn base_stress(points: &MaterialPoints) -> Real {
    let lowest = points
        .position
        .iter()
        .map(|x| x.y)
        .fold(Real::INFINITY, Real::min);
    let base: Vec<Real> = points
        .position
        .iter()
        .zip(&points.stress)
        .filter(|(x, _)| x.y < lowest + 1e-6)
        .map(|(_, s)| s.yy)
        .collect();
    base.iter().sum::<Real>() / base.len() as Real
}

/// The points of the body named `name`.
pub fn body<'s>(sim: &'s mut Simulation, name: &str) -> Result<&'s MaterialPoints, VerifyError> {
    sim.points_of(name)
        .ok_or_else(|| VerifyError::Measurement(format!("the scene has no body '{name}'")))
}

/// The largest of `values` (0 for none). A NaN among them gives NaN, so a
/// run that broke down cannot meet a target.
pub fn largest(values: impl IntoIterator<Item = Real>) -> Real {
    values
        .into_iter()
        .fold(0.0, |acc, v| if v.is_nan() || v > acc { v } else { acc })
}

/// The first of `items`, or an error saying the run recorded no `what`.
pub fn first<'s, T>(items: &'s [T], what: &str) -> Result<&'s T, VerifyError> {
    items
        .first()
        .ok_or_else(|| VerifyError::Measurement(format!("the run recorded no {what}")))
}

/// The stages `sim` went through, by name and how each ended, with the
/// number of stage warnings (for the measured column), and whether they
/// are exactly `planned` without a warning.
pub fn stages_as_planned(sim: &Simulation, planned: &[(&str, StageEndReason)]) -> (String, bool) {
    let log = sim.world().resource::<StageLog>();
    let stages: Vec<(&str, StageEndReason)> = log
        .records
        .iter()
        .map(|r| (r.name.as_str(), r.reason))
        .collect();
    let listed: Vec<String> = stages
        .iter()
        .map(|(name, reason)| format!("{name}: {}", reason.label()))
        .collect();
    (
        format!("{}; {} warnings", listed.join(", "), log.warnings.len()),
        stages == planned && log.warnings.is_empty(),
    )
}
