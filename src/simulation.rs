//! The library entry point: a world and its step schedule.

use crate::checkpoint::StateHasher;
use crate::checkpoint::{CheckpointError, SceneFingerprint, restore_checkpoint, write_checkpoint};
use crate::components::{
    BlockId, BodyName, MaterialPoints, Pose, RigidVelocity, bodies_in_scene_order,
};
use crate::io::csv::CsvRecord;
use crate::io::figure::FigureRecord;
use crate::io::vtk::PointFieldRecord;
use crate::math::Real;
use crate::plugins::{CorePlugin, DefaultPlugins, MpmPlugin, PluginSetup, Registries};
use crate::resources::{Clock, Diagnostics, NumericalFailure, StepInterrupt};
use crate::scene::{Scene, SceneError, spawn_scene};
use crate::systems::build_schedule;
use crate::warning::Warning;
use bevy_ecs::prelude::*;
use bevy_ecs::system::ScheduleSystem;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::any::{Any, TypeId};
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

/// Why a step could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum StepError {
    /// The numerics broke down (non-finite value, point out of the grid, ...).
    #[error("numerical failure at {0}")]
    Numerical(#[from] NumericalFailure),
    /// The schedule could not be built (e.g. two user systems in one set
    /// touching the same data without an order between them).
    #[error("the step schedule is invalid: {0}")]
    Schedule(String),
    /// The step was cut short on request (see
    /// [`Simulation::interrupt_steps_on`]); the simulation takes no
    /// further step.
    #[error(
        "step {0} was cut short on request: its state is half updated, and the simulation takes no further step"
    )]
    Interrupted(u64),
}

/// Why a plugin could not be added.
#[derive(Debug, thiserror::Error)]
pub enum PluginError {
    /// The plugin could not set its feature up for the scene.
    #[error(transparent)]
    Build(#[from] SceneError),
    /// Its systems make the schedule invalid.
    #[error(transparent)]
    Step(#[from] StepError),
    /// A plugin of this type is in the simulation already.
    #[error("the plugin {0} is added twice: a simulation holds each plugin once")]
    Duplicate(String),
    /// The plugins do not include the core of the step.
    #[error(
        "the plugins must include mpdem::plugins::CorePlugin (or a replacement for it): it holds the step itself"
    )]
    NoCore,
}

/// A running simulation: the ECS world (bodies, grid, clock, records) and
/// the step schedule.
///
/// ```no_run
/// use mpdem::prelude::*;
/// let mut sim = Simulation::from_scene_file("scenes/wave_1d.ron".as_ref())?;
/// sim.run_until(0.1)?;
/// println!("state hash {:016x}", sim.state_hash());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Simulation {
    world: World,
    schedule: Schedule,
    /// The scene the world was spawned from, which plugins set up from.
    scene: Scene,
    /// The blocks absent at the start, until the stages' plugin takes them.
    absent_blocks: Vec<crate::components::BlockTemplate>,
    /// What the plugins registered: the state checkpoints carry (and the
    /// user state), the CSV series, the warnings.
    registries: Registries,
    /// The scene's fingerprint, which a checkpoint must match.
    fingerprint: SceneFingerprint,
    /// The types of the plugins added, each once.
    plugins: Vec<TypeId>,
}

impl Simulation {
    /// Loads, validates and spawns a scene file.
    pub fn from_scene_file(path: &Path) -> Result<Self, SceneError> {
        Self::from_scene(&Scene::load(path)?)
    }

    /// Validates and spawns a scene (e.g. one built in code), with the
    /// built-in plugins.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        match Self::with_plugins(scene, DefaultPlugins::default()) {
            Ok(sim) => Ok(sim),
            Err(PluginError::Build(e)) => Err(e),
            Err(e) => unreachable!("the built-in plugins are each added once: {e}"),
        }
    }

    /// Validates and spawns a scene with `plugins`: the built-in ones, of
    /// which some may be disabled or replaced (see [`DefaultPlugins`]).
    /// Refused if a plugin type comes twice, or without the core.
    pub fn with_plugins(scene: &Scene, plugins: DefaultPlugins) -> Result<Self, PluginError> {
        if !plugins.contains::<CorePlugin>() {
            return Err(PluginError::NoCore);
        }
        scene.validate()?;
        let spawned = spawn_scene(scene)?;
        let mut sim = Self {
            world: spawned.world,
            schedule: build_schedule(scene.settings.scheme),
            scene: scene.clone(),
            absent_blocks: spawned.absent_blocks,
            registries: Registries {
                warnings: spawned.warnings,
                ..Registries::default()
            },
            fingerprint: SceneFingerprint::of(scene),
            plugins: Vec::new(),
        };
        for (place, plugin) in plugins.iter() {
            if place != (plugin as &dyn Any).type_id() {
                sim.plugins.push(place);
            }
            sim.build_plugin(plugin)?;
            plugin.add_systems(&mut sim.schedule, scene.settings.scheme);
        }
        sim.registries.kept.seal();
        Ok(sim)
    }

    /// Builds `plugin` into the world, refusing a plugin type added before.
    fn build_plugin(&mut self, plugin: &dyn MpmPlugin) -> Result<(), PluginError> {
        let id = (plugin as &dyn Any).type_id();
        if self.plugins.contains(&id) {
            return Err(PluginError::Duplicate(plugin.name().to_string()));
        }
        self.plugins.push(id);
        let mut setup = PluginSetup::new(
            &self.scene,
            &mut self.world,
            &mut self.registries,
            &mut self.absent_blocks,
        );
        Ok(plugin.build(&mut setup)?)
    }

    /// Builds the scene, then puts into it the state of the checkpoint at
    /// `path`, written by [`Simulation::write_checkpoint`] in a run of the
    /// same scene (whose `time.end`, name and output but `output.fronts` may have changed since):
    /// stepping on gives bit-identically what the run that wrote it would
    /// have given. A checkpoint of another scene is refused.
    ///
    /// A run whose user systems keep state registered with
    /// [`Simulation::keep_in_checkpoints`] or
    /// [`Simulation::keep_components_in_checkpoints`], or that has plugins
    /// of its own, is built with [`Simulation::from_scene`], registers its
    /// state and adds its plugins, then calls
    /// [`Simulation::restore_checkpoint`].
    pub fn resume(scene: &Scene, path: &Path) -> Result<Self, CheckpointError> {
        let mut sim = Self::from_scene(scene)?;
        sim.restore_checkpoint(scene, path)?;
        Ok(sim)
    }

    /// Puts the state of the checkpoint at `path` into this simulation,
    /// which must be built from `scene` (pass the same scene: its `time.end`
    /// is the run's end) and not have stepped yet; the checkpoint must hold
    /// exactly the user state registered with
    /// [`Simulation::keep_in_checkpoints`] and
    /// [`Simulation::keep_components_in_checkpoints`], and replaces it
    /// (insert nothing after it). See [`Simulation::resume`]. On an error the
    /// simulation may be partly restored: discard it.
    pub fn restore_checkpoint(
        &mut self,
        scene: &Scene,
        path: &Path,
    ) -> Result<(), CheckpointError> {
        let refuse = |reason: &'static str| CheckpointError::Restore {
            path: path.to_path_buf(),
            reason,
        };
        if self.clock().step != 0 {
            return Err(refuse("the simulation has already stepped"));
        }
        if scene != &self.scene {
            return Err(refuse(
                "the simulation was built from another scene (or another time.end)",
            ));
        }
        restore_checkpoint(
            &mut self.world,
            scene,
            &self.fingerprint,
            &self.registries.kept,
            path,
        )
    }

    /// Writes the state of the run to `path` (see [`crate::checkpoint`]),
    /// replacing the file only once the new one is whole. Fails if a
    /// resource registered with [`Simulation::keep_in_checkpoints`] is
    /// missing from the world.
    pub fn write_checkpoint(&mut self, path: &Path) -> Result<(), CheckpointError> {
        if self.cut_short() {
            return Err(CheckpointError::CutShort {
                path: path.to_path_buf(),
            });
        }
        write_checkpoint(
            &mut self.world,
            &self.fingerprint,
            &self.registries.kept,
            path,
        )
    }

    /// Makes checkpoints carry the resource `R` that user systems keep
    /// (e.g. a controller's integral), under `name`: without it a resumed
    /// run would start that state afresh and differ from one that never
    /// stopped. Register it before writing and before restoring a
    /// checkpoint; registering a name of the user's again replaces the
    /// type.
    ///
    /// # Panics
    /// If `name` is one the engine's own state is kept under.
    pub fn keep_in_checkpoints<R: Resource + Serialize + DeserializeOwned>(&mut self, name: &str) {
        self.registries.kept.keep_resource::<R>(name);
    }

    /// Makes checkpoints carry the component `C` that user systems keep on
    /// the bodies and blocks (e.g. a field of their own per point, or a
    /// block's controller), under `name`, wherever it is at the
    /// checkpoint: restoring puts it on the same bodies and blocks and
    /// removes it from the others. Register it before writing and before
    /// restoring a checkpoint; registering a name of the user's again
    /// replaces the type.
    /// Components on entities the user spawned are not carried.
    ///
    /// # Panics
    /// If `name` is one the engine's own state is kept under.
    pub fn keep_components_in_checkpoints<C: Component + Serialize + DeserializeOwned>(
        &mut self,
        name: &str,
    ) {
        self.registries.kept.keep_component::<C>(name);
    }

    /// The scene's name.
    pub fn name(&self) -> &str {
        self.scene.display_name()
    }

    /// Warnings found while building (e.g. a time step above the CFL limit).
    pub fn warnings(&self) -> &[Warning] {
        &self.registries.warnings
    }

    /// Warnings found while stepping, in the order found (e.g. a point
    /// grown too loose for the time step); the run goes on after them.
    pub fn step_warnings(&self) -> &[Warning] {
        &self.world.resource::<Diagnostics>().warnings
    }

    /// The index in the scene's `stages` of the stage running, if the scene
    /// has stages and the last has not ended.
    pub fn stage_index(&self) -> Option<usize> {
        let plan = self.world.get_resource::<crate::resources::StagePlan>()?;
        (!plan.progress.finished).then_some(plan.progress.current)
    }

    /// The whole state a checkpoint would store, encoded: equal for two
    /// simulations of one scene exactly when a checkpoint of either would
    /// resume the same run. For tests of resuming.
    #[doc(hidden)]
    pub fn encoded_state(&mut self) -> Result<Vec<u8>, CheckpointError> {
        crate::checkpoint::encoded_state(&mut self.world, &self.fingerprint, &self.registries.kept)
    }

    /// The records the outputs write as CSV, in the order they were
    /// registered.
    pub(crate) fn csv_records(&self) -> &[CsvRecord] {
        &self.registries.records
    }

    /// The records' figures, in the order they were registered.
    pub(crate) fn figure_records(&self) -> &[FigureRecord] {
        &self.registries.figures
    }

    /// The plugins' scalar fields of the VTK frames.
    pub(crate) fn point_fields(&self) -> &[PointFieldRecord] {
        &self.registries.point_fields
    }

    /// The files of the series the records hold (`energy.csv`,
    /// `probes.csv`, …, as the scene asks for them), in registration order.
    pub fn series_files(&self) -> Vec<&'static str> {
        self.registries.records.iter().map(|r| r.file).collect()
    }

    /// The text a run writes into the series file `file` (one of
    /// [`Self::series_files`]) for the samples recorded so far: the header
    /// line, then one line per sample; `None` for another name.
    pub fn series_csv(&self, file: &str) -> Option<String> {
        let record = self.registries.records.iter().find(|r| r.file == file)?;
        let bodies: Vec<String> = self.scene.bodies.iter().map(|b| b.name.clone()).collect();
        let series = (record.series)(&self.world);
        let mut text = format!("{}\n", series.header()).into_bytes();
        for k in 0..series.rows() {
            series
                .write_row(k, &bodies, &mut text)
                .expect("writing into memory cannot fail");
        }
        Some(String::from_utf8(text).expect("the series write UTF-8 text"))
    }

    /// The names of the scalar point fields the plugins add to the frames
    /// (see [`crate::plugins::PluginSetup::point_field`]).
    pub fn point_field_names(&self) -> Vec<&'static str> {
        self.registries
            .point_fields
            .iter()
            .map(|f| f.name)
            .collect()
    }

    /// The plugins' scalar point field `name` of `body`, one value per
    /// point; `None` when no plugin adds a field of that name.
    pub fn point_field(&self, body: Entity, name: &str) -> Option<Vec<Real>> {
        let record = self
            .registries
            .point_fields
            .iter()
            .find(|f| f.name == name)?;
        let mut values = Vec::new();
        (record.fill)(&self.world, body, &mut values);
        Some(values)
    }

    /// The scene the simulation was built from.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The ECS world: bodies, resources and records.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The ECS world, mutable (spawn entities, insert resources, edit points).
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// The clock.
    pub fn clock(&self) -> Clock {
        *self.world.resource::<Clock>()
    }

    /// Adds user systems to the step, e.g.
    /// `sim.add_systems(my_load.in_set(MpmSystems::Boundary))`. The schedule
    /// is rebuilt at once, so an ambiguous addition is reported here.
    pub fn add_systems<M>(
        &mut self,
        systems: impl IntoScheduleConfigs<ScheduleSystem, M>,
    ) -> Result<(), StepError> {
        self.schedule.add_systems(systems);
        self.initialize_schedule()
    }

    /// Adds a feature to the simulation (see [`MpmPlugin`]): sets it up
    /// in the world (its resources, the state checkpoints carry, its CSV
    /// records), then adds its systems to the step; like
    /// [`Simulation::add_systems`], an ambiguous addition is reported here.
    /// Add plugins before the first step and before restoring a checkpoint.
    /// A plugin type added before (a built-in one included) is refused
    /// ([`PluginError::Duplicate`]); to change a built-in plugin, build
    /// with [`Simulation::with_plugins`].
    pub fn add_plugin(&mut self, plugin: &dyn MpmPlugin) -> Result<(), PluginError> {
        self.build_plugin(plugin)?;
        plugin.add_systems(&mut self.schedule, self.scene.settings.scheme);
        Ok(self.initialize_schedule()?)
    }

    fn initialize_schedule(&mut self) -> Result<(), StepError> {
        match self.schedule.initialize(&mut self.world) {
            Ok(_) => Ok(()),
            Err(e) => Err(StepError::Schedule(
                e.to_string(self.schedule.graph(), &self.world),
            )),
        }
    }

    /// Takes one step. A numerical failure found during the step is returned
    /// (and the state is left as the failed step made it).
    pub fn step(&mut self) -> Result<(), StepError> {
        if self.cut_short() {
            return Err(StepError::Interrupted(self.clock().step + 1));
        }
        self.initialize_schedule()?;
        self.schedule.run(&mut self.world);
        // The world records every removal (a stage's plan is taken out and
        // put back each step) until told the step is over, as an app's
        // frame loop does; without this the record grows with every step.
        self.world.clear_trackers();
        if let Some(failure) = self.world.resource_mut::<Diagnostics>().failure.take() {
            return Err(failure.into());
        }
        if self.cut_short() {
            return Err(StepError::Interrupted(self.clock().step + 1));
        }
        Ok(())
    }

    /// Cuts the step in progress short once `request` is raised: the step
    /// skips its remaining sets and returns [`StepError::Interrupted`],
    /// and the simulation takes no further step and writes no checkpoint.
    /// For a stop that cannot wait for a long step to end; a stop between
    /// steps needs none of this.
    pub fn interrupt_steps_on(&mut self, request: Arc<AtomicBool>) {
        self.world.insert_resource(StepInterrupt::new(request));
    }

    /// Whether a step was cut short (see [`Simulation::interrupt_steps_on`]).
    pub fn cut_short(&self) -> bool {
        self.world
            .get_resource::<StepInterrupt>()
            .is_some_and(StepInterrupt::cut_short)
    }

    /// Steps until the simulated time reaches `time` (within half a step).
    pub fn run_until(&mut self, time: Real) -> Result<(), StepError> {
        let target = (time / self.clock().dt).round() as u64;
        while self.clock().step < target {
            self.step()?;
        }
        Ok(())
    }

    /// Steps to the end of the run: the scene's end time, or the end of its
    /// last stage if that comes first.
    pub fn run(&mut self) -> Result<(), StepError> {
        while !self.clock().finished() {
            self.step()?;
        }
        Ok(())
    }

    /// Bodies in scene order with their names.
    pub fn bodies(&mut self) -> Vec<(Entity, String)> {
        bodies_in_scene_order(&mut self.world)
            .into_iter()
            .map(|e| {
                let name = self.world.get::<BodyName>(e);
                (e, name.map_or_else(String::new, |n| n.0.clone()))
            })
            .collect()
    }

    /// The points of a body.
    pub fn points(&self, body: Entity) -> Option<&MaterialPoints> {
        self.world.get::<MaterialPoints>(body)
    }

    /// The points of the body named `name`.
    pub fn points_of(&mut self, name: &str) -> Option<&MaterialPoints> {
        let entity = self.bodies().into_iter().find(|(_, n)| n == name)?.0;
        self.points(entity)
    }

    /// FNV-1a hash of the state every step evolves: each point's position,
    /// velocity, deformation gradient, velocity gradient, affine gradient,
    /// volume, stress and strain, body by body in scene order; each block's
    /// pose and velocity in scene order; and the clock's step. (Columns a
    /// step does not evolve, such as mass and initial position, are left
    /// out, and so are the records of what happened, such as the points'
    /// inelastic work, which no step reads back.) Equal hashes mean
    /// bit-identical states.
    pub fn state_hash(&mut self) -> u64 {
        let mut hasher = StateHasher::default();
        let clock = self.clock();
        hasher.add_u64(clock.step);
        for (entity, _) in self.bodies() {
            if let Some(points) = self.points(entity) {
                hasher.add_points(points);
            }
        }
        let mut blocks: Vec<_> = self
            .world
            .query::<(&BlockId, &Pose, &RigidVelocity)>()
            .iter(&self.world)
            .map(|(id, pose, v)| {
                (
                    id.index,
                    [
                        pose.origin.x,
                        pose.origin.y,
                        pose.angle,
                        v.linear.x,
                        v.linear.y,
                        v.angular,
                    ],
                )
            })
            .collect();
        blocks.sort_unstable_by_key(|b| b.0);
        for (_, state) in blocks {
            hasher.add_reals(state);
        }
        hasher.finish()
    }
}
