//! Each body's front along +x over time, `fronts.csv`, and its deposit's
//! surface at the frames, `deposit.csv` (with `output.fronts`): the
//! run-out of a collapse or a dam break, measured as experiments measure
//! it (see [`crate::deposit`]).

use super::records::refill;
use super::{MpmPlugin, PluginSetup};
use crate::checkpoint::{Checkpointed, TimeRecord};
use crate::components::{BodyIndex, MaterialPoints};
use crate::deposit::{DepositDatum, SurfaceProfile, TOE_LEVELS, share_beyond};
use crate::distributed::{Domain, PointIds, gather_columns};
use crate::io::csv::CsvSeries;
use crate::io::figure::{Curve, Figure, FigureContext};
use crate::math::{DVec2, Real};
use crate::resources::{Clock, Diagnostics, Grid, Sampling, UpdateScheme};
use crate::scene::SceneError;
use crate::systems::{DiagnosticsStep, record_probes_and_energy};
use bevy_ecs::prelude::*;
use serde::{Deserialize, Serialize};

/// Share of a body's points allowed beyond its bulk front: a few points
/// thrown ahead of the flow move the farthest point but not the bulk.
const AHEAD: Real = 1e-3;

/// One body's front at one time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrontSample {
    /// Simulated time (s).
    pub time: Real,
    /// The body's index in the scene.
    pub body: u32,
    /// Largest x of the body's points (m).
    pub farthest: Real,
    /// The x beyond which 0.1% of the body's points lie (m).
    pub bulk: Real,
    /// The toe: the x where the body's surface first thins below 2% of its
    /// initial height H0, along +x from its highest column (m).
    pub toe_2: Real,
    /// The same where it thins below 5% of H0 (m).
    pub toe_5: Real,
    /// The share of the body's mass beyond the toe at 2% of H0: material
    /// thrown ahead of the deposit.
    pub spray: Real,
}

/// One column of one body's surface at one frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DepositColumn {
    /// Simulated time (s).
    pub time: Real,
    /// The body's index in the scene.
    pub body: u32,
    /// The x of the column's centre (m).
    pub x: Real,
    /// The height of the body's surface over the column above its initial
    /// base (m).
    pub height: Real,
}

/// The fronts, sampled with the probes.
#[derive(Resource, Debug)]
pub struct FrontLog {
    /// Samples in time order, bodies in scene order within a time.
    pub samples: Vec<FrontSample>,
    /// Each body's initial base and height, in scene order.
    datums: Vec<DepositDatum>,
    /// One body's surface, one bin per column of the grid, reused.
    profile: SurfaceProfile,
    /// The x of one body's points, reused between samples.
    scratch: Vec<Real>,
}

impl FrontLog {
    /// A log of the bodies of `bodies`, their surfaces binned by the
    /// columns of `grid`'s cells.
    fn new<'a>(
        grid: &Grid,
        bodies: impl Iterator<Item = (&'a BodyIndex, &'a MaterialPoints)>,
    ) -> Self {
        let mut placed: Vec<_> = bodies.collect();
        placed.sort_unstable_by_key(|(index, _)| index.0);
        let largest = placed.iter().map(|(_, p)| p.len()).max().unwrap_or(0);
        Self {
            samples: Vec::new(),
            datums: placed
                .iter()
                .map(|(_, p)| DepositDatum::of(&p.position, &p.half_size))
                .collect(),
            profile: SurfaceProfile::new(grid.origin.x, grid.cell_size, grid.cells[0]),
            scratch: Vec::with_capacity(largest),
        }
    }

    /// Appends the front of every body of `bodies` at `time`, in scene
    /// order.
    fn record<'a>(&mut self, time: Real, bodies: impl Iterator<Item = BodyOutline<'a>>) {
        let first = self.samples.len();
        for (index, points) in bodies {
            self.scratch.clear();
            self.scratch.extend(points.position.iter().map(|x| x.x));
            let (farthest, bulk) = fronts(&mut self.scratch);
            let datum = self.datums[index.0 as usize];
            self.profile
                .measure(points.position, points.half_size, datum.base);
            let [toe_2, toe_5] = TOE_LEVELS.map(|f| self.profile.toe(f * datum.height));
            self.samples.push(FrontSample {
                time,
                body: index.0,
                farthest,
                bulk,
                toe_2,
                toe_5,
                spray: share_beyond(toe_2, points.position, points.mass),
            });
        }
        self.samples[first..].sort_unstable_by_key(|s| s.body);
    }
}

/// Each body's surface at the frames and at the run's last step, the
/// columns it covers in x order (`deposit.csv`).
#[derive(Resource, Debug)]
pub struct DepositLog {
    /// Columns in time order, bodies in scene order within a time.
    pub columns: Vec<DepositColumn>,
    /// Steps between two profiles: the frames'.
    every: u64,
    /// Each body's initial base, in scene order.
    bases: Vec<Real>,
    /// One body's surface, reused.
    profile: SurfaceProfile,
}

impl DepositLog {
    /// Appends the surface of every body of `bodies` at `time`, in scene
    /// order, each column with material over it.
    fn record<'a>(&mut self, time: Real, bodies: impl Iterator<Item = BodyOutline<'a>>) {
        let first = self.columns.len();
        for (index, points) in bodies {
            let base = self.bases[index.0 as usize];
            self.profile
                .measure(points.position, points.half_size, base);
            let profile = &self.profile;
            let covered = profile
                .heights
                .iter()
                .enumerate()
                .filter(|(_, h)| **h > 0.0);
            self.columns
                .extend(covered.map(|(k, &height)| DepositColumn {
                    time,
                    body: index.0,
                    x: profile.centre(k),
                    height,
                }));
        }
        // Within a body the columns are in x order, each x once.
        self.columns[first..]
            .sort_unstable_by(|a, b| a.body.cmp(&b.body).then(a.x.total_cmp(&b.x)));
    }

    /// Whether the step the clock has just taken writes a profile.
    fn due(&self, clock: &Clock) -> bool {
        clock.step.is_multiple_of(self.every) || clock.step == clock.total_steps()
    }
}

/// The largest of `xs` and the value beyond which a share [`AHEAD`] of
/// them lie (NaN for none); reorders `xs`.
fn fronts(xs: &mut [Real]) -> (Real, Real) {
    let Some(last) = xs.len().checked_sub(1) else {
        return (Real::NAN, Real::NAN);
    };
    let k = ((xs.len() as Real) * (1.0 - AHEAD)) as usize;
    let (_, bulk, _) = xs.select_nth_unstable_by(k.min(last), Real::total_cmp);
    let bulk = *bulk;
    let farthest = xs.iter().copied().fold(Real::NEG_INFINITY, Real::max);
    (farthest, bulk)
}

/// A body's index and the columns of its points the fronts and the
/// deposits read.
type BodyOutline<'a> = (&'a BodyIndex, OutlineColumns<'a>);

/// The columns of a body's points the fronts and the deposits read, each
/// in the points' one-process order.
#[derive(Clone, Copy)]
struct OutlineColumns<'a> {
    position: &'a [DVec2],
    half_size: &'a [DVec2],
    mass: &'a [Real],
}

impl<'a> OutlineColumns<'a> {
    fn of(points: &'a MaterialPoints) -> Self {
        Self {
            position: &points.position,
            half_size: &points.half_size,
            mass: &points.mass,
        }
    }
}

/// The outlines of `bodies`.
fn outlines<'a>(
    bodies: impl Iterator<Item = (&'a BodyIndex, &'a MaterialPoints)>,
) -> impl Iterator<Item = BodyOutline<'a>> {
    bodies.map(|(index, points)| (index, OutlineColumns::of(points)))
}

/// Samples the fronts when the probes are sampled and the surfaces at the
/// frames, unless the step failed. In a distributed run rank 0 gathers the
/// columns it reads from every process, and records alone: the records
/// are written, and checkpointed, from rank 0.
fn record_fronts(
    (clock, diagnostics, sampling): (Res<Clock>, Res<Diagnostics>, Res<Sampling>),
    mut fronts: ResMut<FrontLog>,
    mut deposits: ResMut<DepositLog>,
    bodies: Query<(&BodyIndex, &MaterialPoints, Option<&PointIds>)>,
    domain: Option<NonSend<Domain>>,
) {
    if diagnostics.failure.is_some() {
        return;
    }
    let (fronts_due, deposits_due) = (sampling.due(&clock), deposits.due(&clock));
    if !(fronts_due || deposits_due) {
        return;
    }
    let Some(domain) = domain else {
        let held = || outlines(bodies.iter().map(|(index, points, _)| (index, points)));
        if fronts_due {
            fronts.record(clock.time, held());
        }
        if deposits_due {
            deposits.record(clock.time, held());
        }
        return;
    };
    let mut ordered: Vec<_> = bodies.iter().collect();
    ordered.sort_unstable_by_key(|(index, ..)| index.0);
    let mut gathered = Vec::with_capacity(ordered.len());
    for (index, points, ids) in ordered {
        let ids = ids.expect("a distributed body's ids");
        let columns = (&points.position, &points.half_size, &points.mass);
        if let Some(whole) = gather_columns(&domain, ids, columns) {
            gathered.push((index, whole));
        }
    }
    let whole = || {
        gathered.iter().map(|(index, (position, half_size, mass))| {
            let columns = OutlineColumns {
                position,
                half_size,
                mass,
            };
            (*index, columns)
        })
    };
    if fronts_due && !gathered.is_empty() {
        fronts.record(clock.time, whole());
    }
    if deposits_due && !gathered.is_empty() {
        deposits.record(clock.time, whole());
    }
}

/// Each body's front and deposit (`fronts.csv`, `deposit.csv`), when the
/// scene's `output.fronts` asks for them.
pub struct FrontsPlugin;

impl MpmPlugin for FrontsPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        if !setup.scene.output.fronts {
            return Ok(());
        }
        let bodies = setup.scene.bodies.len();
        let samples = setup.samples_in_run();
        let grid = setup.world.resource::<Grid>().clone();
        let clock = *setup.world.resource::<Clock>();
        let mut query = setup.world.query::<(&BodyIndex, &MaterialPoints)>();
        let mut log = FrontLog::new(&grid, query.iter(setup.world));
        log.samples.reserve_exact(samples * bodies);
        log.record(0.0, outlines(query.iter(setup.world)));
        let every = setup.scene.output.frame_every(clock.end, clock.dt).max(1);
        let profiles = (clock.total_steps() / every + 2) as usize;
        let mut deposits = DepositLog {
            columns: Vec::with_capacity(profiles * bodies * grid.cells[0]),
            every,
            bases: log.datums.iter().map(|d| d.base).collect(),
            profile: log.profile.clone(),
        };
        deposits.record(0.0, outlines(query.iter(setup.world)));
        setup.world.insert_resource(log);
        setup.world.insert_resource(deposits);
        setup.record::<FrontLog>("fronts", "fronts.csv");
        setup.record::<DepositLog>("deposit", "deposit.csv");
        setup.plot::<FrontLog>(fronts_figure);
        setup.plot::<DepositLog>(deposit_figure);
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems(
            record_fronts
                .in_set(DiagnosticsStep::Energy)
                .after(record_probes_and_energy)
                .run_if(resource_exists::<FrontLog>),
        );
    }
}

impl Checkpointed for FrontLog {
    type Stored = Vec<FrontSample>;

    fn stored(&self) -> Vec<FrontSample> {
        self.samples.clone()
    }

    fn restore(&mut self, samples: Vec<FrontSample>) {
        refill(&mut self.samples, samples);
    }
}

impl TimeRecord for FrontLog {
    fn forget_from(&mut self, time: Real) {
        self.samples.retain(|s| s.time < time);
    }
}

impl Checkpointed for DepositLog {
    type Stored = Vec<DepositColumn>;

    fn stored(&self) -> Vec<DepositColumn> {
        self.columns.clone()
    }

    fn restore(&mut self, columns: Vec<DepositColumn>) {
        refill(&mut self.columns, columns);
    }
}

impl TimeRecord for DepositLog {
    fn forget_from(&mut self, time: Real) {
        self.columns.retain(|c| c.time < time);
    }
}

impl CsvSeries for DepositLog {
    const HEADER: &'static str = "time,body,x,height";

    fn rows(&self) -> usize {
        self.columns.len()
    }

    fn write_row(
        &self,
        k: usize,
        bodies: &[String],
        out: &mut dyn std::io::Write,
    ) -> std::io::Result<()> {
        let c = self.columns[k];
        writeln!(
            out,
            "{},{},{:e},{:e}",
            crate::io::csv::time(c.time),
            bodies[c.body as usize],
            c.x,
            c.height
        )
    }
}

impl CsvSeries for FrontLog {
    const HEADER: &'static str = "time,body,farthest,front_99_9,toe_2,toe_5,spray";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(
        &self,
        k: usize,
        bodies: &[String],
        out: &mut dyn std::io::Write,
    ) -> std::io::Result<()> {
        let s = self.samples[k];
        writeln!(
            out,
            "{},{},{:e},{:e},{:e},{:e},{:e}",
            crate::io::csv::time(s.time),
            bodies[s.body as usize],
            s.farthest,
            s.bulk,
            s.toe_2,
            s.toe_5,
            s.spray
        )
    }
}

/// `fronts.png`: each body's farthest point, bulk front and toe against
/// time.
fn fronts_figure(fronts: &FrontLog, context: &FigureContext) -> Vec<Figure> {
    let mut curves = Vec::new();
    for (k, body) in context.bodies.iter().enumerate() {
        let of_body = || fronts.samples.iter().filter(move |s| s.body as usize == k);
        curves.push(Curve::new(
            format!("{body}, farthest"),
            of_body().map(|s| (s.time, s.farthest)),
        ));
        curves.push(Curve::new(
            format!("{body}, 99.9%"),
            of_body().map(|s| (s.time, s.bulk)),
        ));
        curves.push(Curve::new(
            format!("{body}, toe at 2% of H0"),
            of_body().map(|s| (s.time, s.toe_2)),
        ));
    }
    vec![Figure {
        file: "fronts.png".into(),
        title: "Fronts along +x".into(),
        x_label: "time (s)".into(),
        y_label: "front x (m)".into(),
        curves,
    }]
}

/// `deposit.png`: each body's surface at the start and at the last
/// profile.
fn deposit_figure(deposits: &DepositLog, context: &FigureContext) -> Vec<Figure> {
    let last = deposits.columns.last().map_or(0.0, |c| c.time);
    let mut curves = Vec::new();
    for (k, body) in context.bodies.iter().enumerate() {
        for (time, when) in [(0.0, "start"), (last, "last")] {
            let columns = deposits
                .columns
                .iter()
                .filter(|c| c.body as usize == k && c.time == time);
            curves.push(Curve::new(
                format!("{body}, {when} (t = {time:.3} s)"),
                columns.map(|c| (c.x, c.height)),
            ));
        }
    }
    vec![Figure {
        file: "deposit.png".into(),
        title: "Surface of each body".into(),
        x_label: "x (m)".into(),
        y_label: "height above the initial base (m)".into(),
        curves,
    }]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bulk_front_leaves_out_the_points_thrown_ahead() {
        // 2000 points on [0, 1) and two thrown to x = 5: the farthest is a
        // thrown one; 0.1% of the 2002, two points, lie beyond the bulk
        // front, the largest of the others.
        let mut xs: Vec<Real> = (0..2000).map(|k| k as Real / 2000.0).collect();
        xs.extend([5.0, 5.0]);
        let (farthest, bulk) = fronts(&mut xs);
        assert_eq!(farthest, 5.0);
        assert_eq!(bulk, 1999.0 / 2000.0);
        assert!(fronts(&mut []).0.is_nan());
    }

    /// The time column is written as the other series write it, so that
    /// the files join on it: step 180 of 1e-4 s reads `1.8e-2`.
    #[test]
    fn times_are_written_as_in_the_other_series() {
        let log = FrontLog {
            samples: vec![FrontSample {
                time: 180.0 * 1e-4,
                body: 0,
                farthest: 0.5,
                bulk: 0.25,
                toe_2: 0.375,
                toe_5: 0.125,
                spray: 0.5,
            }],
            datums: Vec::new(),
            profile: SurfaceProfile::new(0.0, 1.0, 0),
            scratch: Vec::new(),
        };
        let mut row = Vec::new();
        log.write_row(0, &["column".to_string()], &mut row).unwrap();
        assert_eq!(
            String::from_utf8(row).unwrap(),
            "1.8e-2,column,5e-1,2.5e-1,3.75e-1,1.25e-1,5e-1\n"
        );
    }
}
