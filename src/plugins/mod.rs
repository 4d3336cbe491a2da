//! The engine's features as plugins. A plugin sets its feature up in one
//! place: the resources it adds to a world spawned from a scene, the state
//! of them that checkpoints carry, the records it writes as CSV, and its
//! systems in the step. A user plugin does the same through
//! [`crate::Simulation::add_plugin`].

mod body_contact;
mod core;
mod fronts;
mod group;
mod records;
mod rigid_blocks;
mod stages;

pub use body_contact::BodyContactPlugin;
pub use core::CorePlugin;
pub use fronts::{DepositColumn, DepositLog, FrontLog, FrontSample, FrontsPlugin};
pub use group::DefaultPlugins;
pub use records::RecordsPlugin;
pub use rigid_blocks::RigidBlocksPlugin;
pub use stages::StagesPlugin;

use crate::checkpoint::{Checkpointed, KeptState, TimeRecord};
use crate::components::BlockTemplate;
use crate::io::csv::{CsvRecord, CsvSeries};
use crate::io::figure::{Figure, FigureContext, FigureRecord};
use crate::io::vtk::{FRAME_FIELDS, PointFieldRecord};
use crate::math::Real;
use crate::resources::UpdateScheme;
use crate::scene::{Scene, SceneError};
use crate::warning::Warning;
use bevy_ecs::prelude::*;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::any::Any;

/// A feature of the engine: what it adds to the world of a scene and to
/// the step. Modelled on bevy's `Plugin`, over a [`World`] and the
/// [`crate::systems::MpmSchedule`]. A simulation holds each plugin type
/// once: adding one a second time is refused.
pub trait MpmPlugin: Any + Send + Sync {
    /// The plugin's name in messages: its type's, by default.
    fn name(&self) -> &str {
        std::any::type_name::<Self>()
    }

    /// Sets the feature up in a world spawned from a scene (its bodies and
    /// blocks are there, and the resources of the plugins built before; a
    /// user's plugin comes after the engine's, so after the first stage
    /// was entered): inserts its resources, registers the state
    /// checkpoints carry and the records the outputs write. The default
    /// does nothing.
    fn build(&self, _setup: &mut PluginSetup) -> Result<(), SceneError> {
        Ok(())
    }

    /// Adds the feature's systems to `schedule`, built for `scheme`, each
    /// in its set (see [`crate::systems::MpmSystems`], and within a set
    /// shared by several features its ordered step:
    /// [`crate::systems::ContactStep`],
    /// [`crate::systems::ContactTransferStep`],
    /// [`crate::systems::DiagnosticsStep`]).
    fn add_systems(&self, schedule: &mut Schedule, scheme: UpdateScheme);
}

/// What a plugin sets its feature up with: the scene, the world spawned
/// from it, and the registries of checkpointed state and recorded series.
pub struct PluginSetup<'a> {
    /// The scene the world was spawned from.
    pub scene: &'a Scene,
    /// The world: the scene's bodies and blocks, and the resources of the
    /// plugins built so far.
    pub world: &'a mut World,
    kept: &'a mut KeptState,
    records: &'a mut Vec<CsvRecord>,
    figures: &'a mut Vec<FigureRecord>,
    point_fields: &'a mut Vec<PointFieldRecord>,
    warnings: &'a mut Vec<Warning>,
    absent_blocks: &'a mut Vec<BlockTemplate>,
}

impl<'a> PluginSetup<'a> {
    pub(crate) fn new(
        scene: &'a Scene,
        world: &'a mut World,
        registries: &'a mut Registries,
        absent_blocks: &'a mut Vec<BlockTemplate>,
    ) -> Self {
        Self {
            scene,
            world,
            kept: &mut registries.kept,
            records: &mut registries.records,
            figures: &mut registries.figures,
            point_fields: &mut registries.point_fields,
            warnings: &mut registries.warnings,
            absent_blocks,
        }
    }

    /// Adds a warning for the user (shown by `mpdem check` and `run`).
    pub fn warn(&mut self, warning: Warning) {
        self.warnings.push(warning);
    }

    /// Adds warnings for the user.
    pub fn warn_all(&mut self, warnings: impl IntoIterator<Item = Warning>) {
        self.warnings.extend(warnings);
    }

    /// Makes checkpoints carry the resource `R` whole, under `name` (see
    /// [`crate::Simulation::keep_in_checkpoints`]).
    pub fn keep_resource<R: Resource + Serialize + DeserializeOwned>(&mut self, name: &str) {
        self.kept.keep_resource::<R>(name);
    }

    /// Makes checkpoints carry the part of the resource `R` that it stores
    /// (see [`Checkpointed`]), under `name`.
    ///
    /// # Panics
    /// If `R` is not in the world yet (restoring puts the part back into
    /// it), or `name` is one the engine's state is kept under.
    pub fn keep_checkpointed<R: Checkpointed>(&mut self, name: &str) {
        assert!(
            self.world.contains_resource::<R>(),
            "{}: insert the resource before keeping it in checkpoints",
            std::any::type_name::<R>()
        );
        self.kept.keep_checkpointed::<R>(name);
    }

    /// Makes the time record `R` a series of the run: checkpoints carry
    /// it under `name`, and the outputs write it as the CSV file `file`,
    /// appended to as the run records it (see [`CsvSeries`]).
    ///
    /// # Panics
    /// As [`PluginSetup::keep_checkpointed`].
    pub fn record<R: TimeRecord + CsvSeries>(&mut self, name: &str, file: &'static str) {
        self.keep_checkpointed::<R>(name);
        self.kept.keep_record::<R>(name);
        self.write_csv::<R>(file);
    }

    /// Makes the outputs write the resource `R` as the CSV file `file`,
    /// appended to as the run adds rows (see [`CsvSeries`]). Checkpoints
    /// carry it only if it is also kept.
    pub fn write_csv<R: Resource + CsvSeries>(&mut self, file: &'static str) {
        self.records.push(CsvRecord::of::<R>(file));
    }

    /// Makes the outputs draw the resource `R` at the run's end: `draw`
    /// gives its figures, line charts as data (see [`Figure`]), each
    /// written as the PNG its `file` names. Nothing is drawn when `R` is
    /// not in the world.
    pub fn plot<R: Resource>(&mut self, draw: fn(&R, &FigureContext) -> Vec<Figure>) {
        self.figures.push(FigureRecord::of::<R>(draw));
    }

    /// Adds the scalar field `name` to the points of the VTK frames:
    /// `fill` appends one value per point of a body (given its entity), in
    /// its points' order, to the column it is given.
    ///
    /// # Panics
    /// If `name` is one of the frame's own fields (`velocity`,
    /// `displacement`, `stress`, `body`) or was added before.
    pub fn point_field(&mut self, name: &'static str, fill: fn(&World, Entity, &mut Vec<Real>)) {
        assert!(
            !FRAME_FIELDS.contains(&name) && self.point_fields.iter().all(|f| f.name != name),
            "the point field '{name}' is in the frames already"
        );
        self.point_fields.push(PointFieldRecord { name, fill });
    }

    /// How many samples a record may take in the run (the first, one per
    /// sampling interval, one at the end): reserve this room when building
    /// a record, so that recording never allocates inside the step.
    pub fn samples_in_run(&self) -> usize {
        let every = self
            .world
            .get_resource::<crate::resources::Sampling>()
            .map_or(1, |s| s.every);
        records::samples_in_run(self.world.resource::<crate::resources::Clock>(), every)
    }

    /// Adds `hook`, run once a checkpoint's whole state is restored, to
    /// rebuild what the feature derives from it.
    pub fn after_restore(&mut self, hook: fn(&mut World)) {
        self.kept.after_restore(hook);
    }

    /// The blocks absent at the start, which stages add: taken by the
    /// stages' plugin.
    pub(crate) fn take_absent_blocks(&mut self) -> Vec<BlockTemplate> {
        std::mem::take(self.absent_blocks)
    }
}

/// Every body's name and points, in scene order (`bodies` their entities).
fn placed_bodies<'w>(
    scene: &'w Scene,
    world: &'w World,
    bodies: &[Entity],
) -> Vec<(&'w str, &'w crate::components::MaterialPoints)> {
    scene
        .bodies
        .iter()
        .zip(bodies)
        .filter_map(|(spec, &e)| Some((spec.name.as_str(), world.get(e)?)))
        .collect()
}

/// What the plugins of a simulation registered: the state checkpoints
/// carry, the CSV series, figures and point fields the outputs write, and
/// the warnings they raised.
#[derive(Default)]
pub(crate) struct Registries {
    pub kept: KeptState,
    pub records: Vec<CsvRecord>,
    pub figures: Vec<FigureRecord>,
    pub point_fields: Vec<PointFieldRecord>,
    pub warnings: Vec<Warning>,
}
