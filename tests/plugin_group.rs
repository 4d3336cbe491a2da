//! The built-in plugins as a group: each but the core can be disabled and
//! the scene still steps; a replacement takes its place in the build
//! order; a plugin type is added once.

mod common;

use common::TempFolder;
use mpdem::PluginError;
use mpdem::plugins::{
    BodyContactPlugin, CorePlugin, DefaultPlugins, FrontsPlugin, RecordsPlugin, RigidBlocksPlugin,
    StagesPlugin,
};
use mpdem::prelude::*;
use mpdem::resources::{BlockLog, BodyPairLog, EnergyLog, StageLog, UpdateScheme};
use mpdem::runner::{RunOptions, Runner};
use mpdem::scene::SceneError;

/// The dam break (stages, rigid blocks, body contact), with its fronts
/// recorded: a scene every built-in plugin has work in.
fn every_feature() -> Scene {
    let mut scene = common::load_scene("dam_break.ron");
    scene.output.fronts = true;
    scene
}

/// Builds the scene without the plugin `P`, steps it and returns whether
/// the resource `R` that `P` adds is absent.
fn steps_without<P: MpmPlugin, R: Resource>() -> bool {
    let plugins = DefaultPlugins::default().disable::<P>();
    let mut sim = Simulation::with_plugins(&every_feature(), plugins)
        .unwrap_or_else(|e| panic!("{}: {e}", std::any::type_name::<P>()));
    for _ in 0..5 {
        sim.step()
            .unwrap_or_else(|e| panic!("{}: {e}", std::any::type_name::<P>()));
    }
    !sim.world().contains_resource::<R>()
}

#[test]
fn each_built_in_plugin_but_the_core_can_be_disabled() {
    assert!(steps_without::<RecordsPlugin, EnergyLog>());
    assert!(steps_without::<FrontsPlugin, mpdem::plugins::FrontLog>());
    assert!(steps_without::<RigidBlocksPlugin, BlockLog>());
    assert!(steps_without::<BodyContactPlugin, BodyPairLog>());
    assert!(steps_without::<StagesPlugin, StageLog>());
    let without_core = DefaultPlugins::default().disable::<CorePlugin>();
    assert!(matches!(
        Simulation::with_plugins(&every_feature(), without_core),
        Err(PluginError::NoCore)
    ));
}

#[test]
fn a_run_without_the_records_writes_the_rest() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.time.end = 0.01;
    let out = TempFolder::new("plugins");
    let plugins = DefaultPlugins::default().disable::<RecordsPlugin>();
    let options = RunOptions::into_folder(out.join("run"));
    let mut runner = Runner::with_plugins(&scene, None, options, plugins).expect("built");
    let stop = std::sync::atomic::AtomicBool::new(false);
    runner.run(&stop, |_| {}).expect("runs to its end");
    assert!(out.join("run/points.pvd").is_file());
    assert!(!out.join("run/energy.csv").exists());
    assert!(!out.join("run/probes.csv").exists());
}

/// The built-in core, delegated to.
struct WrappedCore;

impl MpmPlugin for WrappedCore {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        CorePlugin.build(setup)
    }

    fn add_systems(&self, schedule: &mut Schedule, scheme: UpdateScheme) {
        CorePlugin.add_systems(schedule, scheme);
    }
}

#[test]
fn a_replacement_is_built_in_the_place_of_the_plugin_it_replaces() {
    let scene = every_feature();
    let mut default = Simulation::from_scene(&scene).expect("built");
    let plugins = DefaultPlugins::default().replace::<CorePlugin>(WrappedCore);
    let mut replaced = Simulation::with_plugins(&scene, plugins).expect("built");
    for _ in 0..20 {
        default.step().expect("steps");
        replaced.step().expect("steps");
    }
    assert_eq!(default.state_hash(), replaced.state_hash());
    // The place of the core is taken: the built-in core is refused beside
    // its replacement, and the replacement is refused a second time.
    for again in [&CorePlugin as &dyn MpmPlugin, &WrappedCore] {
        match replaced.add_plugin(again) {
            Err(PluginError::Duplicate(name)) => assert!(name.contains("Core"), "{name}"),
            other => panic!("added twice: {:?}", other.err()),
        }
    }
}

#[test]
fn a_plugin_added_twice_is_refused_with_its_name() {
    let mut sim = Simulation::from_scene(&common::load_scene("wave_1d.ron")).expect("built");
    let error = sim.add_plugin(&RecordsPlugin).expect_err("refused");
    assert_eq!(
        error.to_string(),
        "the plugin mpdem::plugins::records::RecordsPlugin is added twice: a simulation holds each plugin once"
    );
    // A plugin disabled may be added afterwards, once.
    let plugins = DefaultPlugins::default().disable::<RecordsPlugin>();
    let mut sim =
        Simulation::with_plugins(&common::load_scene("wave_1d.ron"), plugins).expect("built");
    sim.add_plugin(&RecordsPlugin).expect("added once");
    assert!(matches!(
        sim.add_plugin(&RecordsPlugin),
        Err(PluginError::Duplicate(_))
    ));
}
