//! The probes' and energies' records: `probes.csv` and `energy.csv`.

use super::{MpmPlugin, PluginSetup};
use crate::checkpoint::{Checkpointed, TimeRecord};
use crate::components::{Material, MaterialPoints, bodies_in_scene_order};
use crate::io::csv::{CsvSeries, field, time};
use crate::io::figure::{Curve, Figure, FigureContext};
use crate::math::Real;
use crate::resources::{Clock, EnergyLog, EnergySample, Probe, ProbeSample, Probes, UpdateScheme};
use crate::rules::file_safe;
use crate::scene::{PROBE_PLOT_PREFIX, Scene, SceneError, SourceLocation};
use crate::systems::{DiagnosticsStep, record_probes_and_energy};
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;
use std::io::Write;

/// Probes and energies, sampled every `output.probe_every` steps, at the
/// start and at the run's last step.
pub struct RecordsPlugin;

impl MpmPlugin for RecordsPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        let scene = setup.scene;
        let bodies = bodies_in_scene_order(setup.world);
        let (mut probes, warnings) = place_probes(scene, setup.world, &bodies);
        setup.warn_all(warnings);
        let samples = setup.samples_in_run();
        let world = &mut *setup.world;
        probes.samples.reserve_exact(samples * probes.probes.len());
        probes.record(0.0, |e| world.get::<MaterialPoints>(e));
        let mut energy = EnergyLog {
            samples: Vec::with_capacity(samples),
        };
        let initial = EnergySample::of(
            0.0,
            bodies.iter().filter_map(|e| {
                Some((world.get::<MaterialPoints>(*e)?, world.get::<Material>(*e)?))
            }),
            scene.gravity,
            scene.settings.geometry,
            &mut Vec::new(),
        );
        if let Some(term) = initial.first_non_finite() {
            return Err(SceneError::Invalid {
                location: SourceLocation::default(),
                message: format!(
                    "the {term} energy of the initial state is not finite: the bodies' sizes, densities, stiffnesses, initial stress and velocities are out of scale with one another"
                ),
            });
        }
        energy.samples.push(initial);
        world.insert_resource(probes);
        world.insert_resource(energy);
        setup.record::<Probes>("probes", "probes.csv");
        setup.record::<EnergyLog>("energy", "energy.csv");
        setup.plot::<EnergyLog>(energy_figure);
        setup.plot::<Probes>(probe_figures);
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems(record_probes_and_energy.in_set(DiagnosticsStep::Energy));
    }
}

/// `energy.png`: every column of `energy.csv`, so the balance can be
/// checked from the figure.
fn energy_figure(energy: &EnergyLog, context: &FigureContext) -> Vec<Figure> {
    type Term = (&'static str, fn(&EnergySample) -> Real);
    const TERMS: [Term; 11] = [
        ("kinetic", |s| s.kinetic),
        ("strain", |s| s.strain),
        ("contact", |s| s.contact),
        ("total", |s| s.total()),
        ("gravity", |s| s.gravity),
        ("inelastic", |s| s.inelastic),
        ("loads", |s| s.loads),
        ("blocks", |s| s.blocks),
        ("dissipated", |s| s.dissipated),
        ("damped", |s| s.damped),
        ("balance", |s| s.balance()),
    ];
    vec![Figure {
        file: "energy.png".into(),
        title: "Energy".into(),
        x_label: "time (s)".into(),
        y_label: format!("energy (J/{})", context.per),
        curves: TERMS
            .iter()
            .map(|(name, f)| Curve::new(*name, energy.samples.iter().map(|s| (s.time, f(s)))))
            .collect(),
    }]
}

/// A probe quantity: its name in the legend and how to read it from a sample.
type ProbeCurve = (&'static str, fn(&ProbeSample) -> Real);

/// The figures of each probe: `probe_<name>_<group>.png`, with the group's
/// axis label and curves.
const PROBE_FIGURES: [(&str, &str, &[ProbeCurve]); 3] = [
    (
        "velocity",
        "velocity (m/s)",
        &[
            ("vx", |s| s.velocity.x),
            ("vy", |s| s.velocity.y),
            ("|v|", |s| s.velocity.length()),
        ],
    ),
    (
        "displacement",
        "displacement (m)",
        &[
            ("ux", |s| s.displacement.x),
            ("uy", |s| s.displacement.y),
            ("|u|", |s| s.displacement.length()),
        ],
    ),
    (
        "stress",
        "stress (Pa)",
        // szz: out of the plane, or the hoop stress in axisymmetry.
        &[
            ("sxx", |s| s.stress.xx),
            ("syy", |s| s.stress.yy),
            ("sxy", |s| s.stress.xy),
            ("szz", |s| s.stress.zz),
        ],
    ),
];

/// Each probe's velocity, displacement and stress against time.
fn probe_figures(probes: &Probes, _: &FigureContext) -> Vec<Figure> {
    let mut figures = Vec::new();
    for (k, probe) in probes.probes.iter().enumerate() {
        for (group, unit, picks) in PROBE_FIGURES {
            figures.push(Figure {
                file: format!("{PROBE_PLOT_PREFIX}{}_{group}.png", file_safe(&probe.name)),
                title: format!("Probe '{}': {group}", probe.name),
                x_label: "time (s)".into(),
                y_label: unit.into(),
                curves: picks
                    .iter()
                    .map(|(name, f)| Curve::new(*name, probes.series(k).map(|s| (s.time, f(s)))))
                    .collect(),
            });
        }
    }
    figures
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
fn place_probes(scene: &Scene, world: &World, bodies: &[Entity]) -> (Probes, Vec<Warning>) {
    let mut warnings = Vec::new();
    let mut probes = Probes {
        probes: Vec::new(),
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
            warnings.push(Warning::new(WarningKind::Probe, format!("probes[\"{}\"].at", spec.name), format!(
                "probe '{}' at {} records the nearest point of body '{}', at {x}, {:.3e} m away (more than a cell): is `at` where you meant?",
                spec.name,
                spec.at,
                spec.body,
                x.distance(spec.at)
            )));
        }
        probes.probes.push(Probe {
            name: spec.name.clone(),
            body: bodies[k],
            point: nearest,
        });
    }
    (probes, warnings)
}

/// `probes.csv`: one row per probe and sample time, columns probe, time,
/// x, y, ux, uy, vx, vy, sxx, syy, sxy, szz (SI, stress tension-positive).
impl CsvSeries for Probes {
    const HEADER: &'static str = "probe,time,x,y,ux,uy,vx,vy,sxx,syy,sxy,szz";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        let name = field(&self.probes[s.probe].name);
        let [sxx, syy, sxy, szz] = s.stress.to_array();
        writeln!(
            out,
            "{name},{},{:e},{:e},{:e},{:e},{:e},{:e},{sxx:e},{syy:e},{sxy:e},{szz:e}",
            time(s.time),
            s.position.x,
            s.position.y,
            s.displacement.x,
            s.displacement.y,
            s.velocity.x,
            s.velocity.y
        )
    }
}

/// `energy.csv`: time, kinetic, strain, contact, total, gravity,
/// inelastic, loads, blocks, dissipated, damped, balance (J per metre of
/// thickness). `total` sums the kinetic, strain and contact (the point
/// contacts' springs) energies, conserved by free elastic bodies;
/// `balance` adds gravity's potential, what the materials dissipated, minus
/// the work of the surface loads and of the blocks, what the contacts
/// dissipated and what damping and the PIC part took (see
/// [`crate::resources::EnergySample::balance`] for what it still leaves
/// out).
impl CsvSeries for EnergyLog {
    const HEADER: &'static str = "time,kinetic,strain,contact,total,gravity,inelastic,loads,blocks,dissipated,damped,balance";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        writeln!(
            out,
            "{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            time(s.time),
            // + 0.0 writes a minus zero (a work negated) as 0.
            s.kinetic + 0.0,
            s.strain + 0.0,
            s.contact + 0.0,
            s.total() + 0.0,
            s.gravity + 0.0,
            s.inelastic + 0.0,
            s.loads + 0.0,
            s.blocks + 0.0,
            s.dissipated + 0.0,
            s.damped + 0.0,
            s.balance() + 0.0
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::PROBE_PLOT_LONGEST_SUFFIX;

    #[test]
    fn the_scenes_check_allows_for_the_longest_probe_figure_name() {
        for (group, ..) in PROBE_FIGURES {
            assert!(group.len() + "_.png".len() <= PROBE_PLOT_LONGEST_SUFFIX.len());
        }
    }
}
