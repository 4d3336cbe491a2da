//! The probes' and energies' records: `probes.csv` and `energy.csv`.

use super::{MpmPlugin, PluginSetup};
use crate::checkpoint::{Checkpointed, TimeRecord};
use crate::components::{Material, MaterialPoints, bodies_in_scene_order};
use crate::math::Real;
use crate::resources::{Clock, EnergyLog, EnergySample, Probe, ProbeSample, Probes, UpdateScheme};
use crate::scene::{Scene, SceneError};
use crate::systems::{DiagnosticsStep, record_probes_and_energy};
use bevy_ecs::prelude::*;

/// Probes and energies, sampled every `output.probe_every` steps, at the
/// start and at the run's last step.
pub struct RecordsPlugin;

impl MpmPlugin for RecordsPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        let scene = setup.scene;
        let bodies = bodies_in_scene_order(setup.world);
        let (mut probes, warnings) = place_probes(scene, setup.world, &bodies);
        setup.warn_all(warnings);
        let world = &mut *setup.world;
        let samples = samples_in_run(world.resource::<Clock>(), probes.every);
        probes.samples.reserve_exact(samples * probes.probes.len());
        probes.record(0.0, |e| world.get::<MaterialPoints>(e));
        let mut energy = EnergyLog {
            samples: Vec::with_capacity(samples),
        };
        energy.samples.push(EnergySample::of(
            0.0,
            bodies.iter().filter_map(|e| {
                Some((world.get::<MaterialPoints>(*e)?, world.get::<Material>(*e)?))
            }),
            scene.gravity,
            scene.settings.geometry,
            &mut Vec::new(),
        ));
        world.insert_resource(probes);
        world.insert_resource(energy);
        setup.record::<Probes>("probes", "probes.csv");
        setup.record::<EnergyLog>("energy", "energy.csv");
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems(record_probes_and_energy.in_set(DiagnosticsStep::Energy));
    }
}

/// How many samples a record may take in the run: the first, one per
/// interval of `every` steps, and one at the end when it falls between.
/// Records reserve this room when they are built, so that recording never
/// allocates inside the step.
pub(crate) fn samples_in_run(clock: &Clock, every: u64) -> usize {
    (clock.total_steps() / every.max(1) + 2) as usize
}

impl Checkpointed for Probes {
    type Stored = Vec<ProbeSample>;

    fn stored(&self) -> Vec<ProbeSample> {
        self.samples.clone()
    }

    fn restore(&mut self, samples: Vec<ProbeSample>) {
        refill(&mut self.samples, samples);
    }
}

impl TimeRecord for Probes {
    fn forget_from(&mut self, time: Real) {
        self.samples.retain(|s| s.time < time);
    }
}

impl Checkpointed for EnergyLog {
    type Stored = Vec<EnergySample>;

    fn stored(&self) -> Vec<EnergySample> {
        self.samples.clone()
    }

    fn restore(&mut self, samples: Vec<EnergySample>) {
        refill(&mut self.samples, samples);
    }
}

impl TimeRecord for EnergyLog {
    fn forget_from(&mut self, time: Real) {
        self.samples.retain(|s| s.time < time);
    }
}

/// Puts `stored` into `record` in place, keeping the room it reserved.
pub(crate) fn refill<T>(record: &mut Vec<T>, stored: Vec<T>) {
    record.clear();
    record.extend(stored);
}

/// The probes, each on the point of its body nearest where it is placed,
/// and warnings for those placed more than a cell from it.
fn place_probes(scene: &Scene, world: &World, bodies: &[Entity]) -> (Probes, Vec<String>) {
    let mut warnings = Vec::new();
    let mut probes = Probes {
        probes: Vec::new(),
        every: scene.output.probe_every(scene.time.end, scene.time.dt),
        samples: Vec::new(),
    };
    for spec in &scene.probes {
        let Some(k) = scene.bodies.iter().position(|b| b.name == spec.body) else {
            continue;
        };
        let points = world
            .get::<MaterialPoints>(bodies[k])
            .map(|p| &p.position[..])
            .unwrap_or(&[]);
        let nearest = (0..points.len())
            .min_by(|&a, &b| {
                points[a]
                    .distance_squared(spec.at)
                    .total_cmp(&points[b].distance_squared(spec.at))
            })
            .unwrap_or(0);
        if let Some(x) = points.get(nearest)
            && x.distance(spec.at) > scene.grid.cell_size
        {
            warnings.push(format!(
                "probe '{}' at {} records the nearest point of body '{}', at {x}, {:.3e} m away (more than a cell): is `at` where you meant?",
                spec.name,
                spec.at,
                spec.body,
                x.distance(spec.at)
            ));
        }
        probes.probes.push(Probe {
            name: spec.name.clone(),
            body: bodies[k],
            point: nearest,
        });
    }
    (probes, warnings)
}
