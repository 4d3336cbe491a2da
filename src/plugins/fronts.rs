//! Each body's front along +x over time, `fronts.csv` (with
//! `output.fronts`): the run-out of a collapse or a dam break.

use super::records::refill;
use super::{MpmPlugin, PluginSetup};
use crate::checkpoint::{Checkpointed, TimeRecord};
use crate::components::{BodyIndex, MaterialPoints};
use crate::io::csv::CsvSeries;
use crate::math::Real;
use crate::resources::{Clock, Diagnostics, Probes, UpdateScheme};
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
}

/// The fronts, sampled with the probes.
#[derive(Resource, Debug, Default)]
pub struct FrontLog {
    /// Samples in time order, bodies in scene order within a time.
    pub samples: Vec<FrontSample>,
    /// The x of one body's points, reused between samples.
    scratch: Vec<Real>,
}

impl FrontLog {
    /// Appends the front of every body of `bodies` at `time`, in scene
    /// order.
    fn record<'a>(
        &mut self,
        time: Real,
        bodies: impl Iterator<Item = (&'a BodyIndex, &'a MaterialPoints)>,
    ) {
        let first = self.samples.len();
        for (index, points) in bodies {
            self.scratch.clear();
            self.scratch.extend(points.position.iter().map(|x| x.x));
            let (farthest, bulk) = fronts(&mut self.scratch);
            self.samples.push(FrontSample {
                time,
                body: index.0,
                farthest,
                bulk,
            });
        }
        self.samples[first..].sort_unstable_by_key(|s| s.body);
    }
}

/// The largest of `xs` and the value beyond which a share [`AHEAD`] of
/// them lie (NaN for none); reorders `xs`.
pub(crate) fn fronts(xs: &mut [Real]) -> (Real, Real) {
    let Some(last) = xs.len().checked_sub(1) else {
        return (Real::NAN, Real::NAN);
    };
    let k = ((xs.len() as Real) * (1.0 - AHEAD)) as usize;
    let (_, bulk, _) = xs.select_nth_unstable_by(k.min(last), Real::total_cmp);
    let bulk = *bulk;
    let farthest = xs.iter().copied().fold(Real::NEG_INFINITY, Real::max);
    (farthest, bulk)
}

/// Samples the fronts when the probes are sampled, unless the step failed.
fn record_fronts(
    clock: Res<Clock>,
    diagnostics: Res<Diagnostics>,
    probes: Res<Probes>,
    mut fronts: ResMut<FrontLog>,
    bodies: Query<(&BodyIndex, &MaterialPoints)>,
) {
    if diagnostics.failure.is_none() && probes.due(&clock) {
        fronts.record(clock.time, bodies.iter());
    }
}

/// `fronts.csv`, when the scene's `output.fronts` asks for it.
pub(crate) struct FrontsPlugin;

impl MpmPlugin for FrontsPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        if !setup.scene.output.fronts {
            return Ok(());
        }
        let bodies = setup.scene.bodies.len();
        let mut log = FrontLog {
            samples: Vec::with_capacity(setup.samples_in_run() * bodies),
            scratch: Vec::new(),
        };
        let mut query = setup.world.query::<(&BodyIndex, &MaterialPoints)>();
        let largest = query.iter(setup.world).map(|(_, p)| p.len()).max();
        log.scratch.reserve(largest.unwrap_or(0));
        log.record(0.0, query.iter(setup.world));
        setup.world.insert_resource(log);
        setup.record::<FrontLog>("fronts", "fronts.csv");
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

impl CsvSeries for FrontLog {
    const HEADER: &'static str = "time,body,farthest,front_99_9";

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
            "{},{},{:e},{:e}",
            crate::io::csv::time(s.time),
            bodies[s.body as usize],
            s.farthest,
            s.bulk
        )
    }
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
            }],
            scratch: Vec::new(),
        };
        let mut row = Vec::new();
        log.write_row(0, &["column".to_string()], &mut row).unwrap();
        assert_eq!(
            String::from_utf8(row).unwrap(),
            "1.8e-2,column,5e-1,2.5e-1\n"
        );
    }
}
