//! Changing the engine's built-in plugins: a parameter sweep that needs
//! only each run's final state disables the records (no probes, no energy
//! series), and replaces the core with one of its own that also counts
//! the steps. A plugin added twice is refused, and so is a built-in one
//! beside its replacement.
//!
//! Run with `cargo run --release --example plugin_group`.

use mpdem::PluginError;
use mpdem::plugins::{CorePlugin, DefaultPlugins, RecordsPlugin};
use mpdem::prelude::*;
use mpdem::resources::{EnergyLog, UpdateScheme};
use mpdem::scene::SceneError;

/// Steps taken, counted by the replacement core.
#[derive(Resource, Default)]
struct StepCount(u64);

fn count(mut steps: ResMut<StepCount>) {
    steps.0 += 1;
}

/// The built-in core, and a step counter after each step.
struct CountingCore;

impl MpmPlugin for CountingCore {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        CorePlugin.build(setup)?;
        setup.world.init_resource::<StepCount>();
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, scheme: UpdateScheme) {
        CorePlugin.add_systems(schedule, scheme);
        schedule.add_systems(count.in_set(MpmSystems::Last));
    }
}

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/elastic_column.ron");
    let mut scene = Scene::load(path.as_ref())?;
    scene.time.end = 0.05;
    for youngs_modulus in [5e5, 1e6] {
        if let mpdem::materials::MaterialModel::LinearElastic(m) = &mut scene.materials[0].model {
            m.youngs_modulus = youngs_modulus;
        }
        let plugins = DefaultPlugins::default()
            .disable::<RecordsPlugin>()
            .replace::<CorePlugin>(CountingCore);
        let mut sim = Simulation::with_plugins(&scene, plugins)?;
        sim.run()?;
        let steps = sim.world().resource::<StepCount>().0;
        if steps != sim.clock().step || sim.world().contains_resource::<EnergyLog>() {
            return Err("the replacement core counts every step, and no energy is recorded".into());
        }
        println!(
            "E = {youngs_modulus:e} Pa: {steps} steps, state hash {:016x}",
            sim.state_hash()
        );
        // The core's place is taken by the replacement: the built-in core
        // cannot be added beside it, nor the replacement again.
        match sim.add_plugin(&CorePlugin) {
            Err(PluginError::Duplicate(_)) => {}
            _ => return Err("the replaced core is refused".into()),
        }
        match sim.add_plugin(&CountingCore) {
            Err(PluginError::Duplicate(name)) => println!("refused: {name} added twice"),
            _ => return Err("a plugin added twice is refused".into()),
        }
    }
    Ok(())
}
