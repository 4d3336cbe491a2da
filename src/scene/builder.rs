//! Scenes built in code, with the defaults a scene file has for every
//! field it leaves out.

use super::{
    BlockSpec, BodyContactSpec, BodySpec, GridSpec, InitialVelocity, MaterialSpec, MotionSpec,
    OutputSpec, ProbeSpec, Scene, SceneError, Shape, StageSpec, TimeSpec,
};
use crate::contact::ContactLaw;
use crate::materials::MaterialModel;
use crate::math::{DVec2, Real};
use crate::resources::{ContactSettings, EdgeConditions, Settings};
use crate::rigid::BlockShape;

/// Builds a [`Scene`] in code: [`Scene::builder`], then the parts, then
/// [`SceneBuilder::build`], which validates it as a scene file is.
///
/// ```
/// use mpdem::materials::{LinearElastic, MaterialModel};
/// use mpdem::prelude::*;
/// use mpdem::scene::{BodySpec, GridSpec, Shape};
///
/// let elastic = MaterialModel::LinearElastic(LinearElastic {
///     youngs_modulus: 1e7,
///     poisson_ratio: 0.3,
/// });
/// let scene = Scene::builder(GridSpec::new(DVec2::ZERO, 0.05, (20, 20)), 1e-4, 0.01)
///     .name("drop")
///     .material("rubber", 1000.0, elastic)
///     .body(BodySpec::new(
///         "block",
///         "rubber",
///         Shape::Rectangle { min: DVec2::new(0.3, 0.3), max: DVec2::new(0.7, 0.7) },
///     ))
///     .build()?;
/// let mut sim = Simulation::from_scene(&scene)?;
/// sim.run()?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    scene: Scene,
}

impl Scene {
    /// A scene on `grid` from t = 0 to `end` by steps of `dt` (s), with a
    /// scene file's defaults: gravity (0, −9.81), the default
    /// [`Settings`] and [`ContactSettings`], no material, body, block,
    /// contact law, probe or stage, and the default [`OutputSpec`].
    pub fn builder(grid: GridSpec, dt: Real, end: Real) -> SceneBuilder {
        SceneBuilder {
            scene: Scene {
                name: None,
                grid,
                time: TimeSpec::new(dt, end),
                gravity: DVec2::new(0.0, -9.81),
                settings: Settings::default(),
                materials: Vec::new(),
                bodies: Vec::new(),
                blocks: Vec::new(),
                contact: ContactSettings::default(),
                body_contacts: Vec::new(),
                block_contacts: Vec::new(),
                probes: Vec::new(),
                output: OutputSpec::default(),
                stages: Vec::new(),
                file_warnings: Vec::new(),
            },
        }
    }
}

impl SceneBuilder {
    /// The scene's name (the output folder's). Default: none (`scene`).
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.scene.name = Some(name.into());
        self
    }

    /// Gravitational acceleration (m/s²).
    pub fn gravity(mut self, gravity: DVec2) -> Self {
        self.scene.gravity = gravity;
        self
    }

    /// The numerical settings.
    pub fn settings(mut self, settings: Settings) -> Self {
        self.scene.settings = settings;
        self
    }

    /// The contact settings.
    pub fn contact(mut self, contact: ContactSettings) -> Self {
        self.scene.contact = contact;
        self
    }

    /// The output cadence and curves.
    pub fn output(mut self, output: OutputSpec) -> Self {
        self.scene.output = output;
        self
    }

    /// Adds a material named `name` of `density` (kg/m³).
    pub fn material(
        mut self,
        name: impl Into<String>,
        density: Real,
        model: MaterialModel,
    ) -> Self {
        self.scene.materials.push(MaterialSpec {
            name: name.into(),
            density,
            model,
        });
        self
    }

    /// Adds a body (see [`BodySpec::new`] for its defaults).
    pub fn body(mut self, body: BodySpec) -> Self {
        self.scene.bodies.push(body);
        self
    }

    /// Adds a rigid block (see [`BlockSpec::new`] for its defaults).
    pub fn block(mut self, block: BlockSpec) -> Self {
        self.scene.blocks.push(block);
        self
    }

    /// Adds a contact law between two bodies or groups.
    pub fn body_contact(mut self, contact: BodyContactSpec) -> Self {
        self.scene.body_contacts.push(contact);
        self
    }

    /// Adds a probe.
    pub fn probe(mut self, probe: ProbeSpec) -> Self {
        self.scene.probes.push(probe);
        self
    }

    /// Adds a stage, after those added before.
    pub fn stage(mut self, stage: StageSpec) -> Self {
        self.scene.stages.push(stage);
        self
    }

    /// The scene, validated as a scene file is (the errors name no file).
    pub fn build(self) -> Result<Scene, SceneError> {
        self.scene.validate()?;
        Ok(self.scene)
    }
}

impl GridSpec {
    /// A grid of `cells` cells of size `cell_size` (m) from `origin`, every
    /// edge `Free` (a scene file's default).
    pub fn new(origin: DVec2, cell_size: Real, cells: (usize, usize)) -> Self {
        Self {
            origin,
            cell_size,
            cells,
            edges: EdgeConditions::default(),
        }
    }
}

impl BodySpec {
    /// A body of `material` filling `shape`, with a scene file's defaults:
    /// 2 × 2 points per cell, at rest, stress free, no constraint, the
    /// default contact radius, no body force of its own, no contact group.
    pub fn new(name: impl Into<String>, material: impl Into<String>, shape: Shape) -> Self {
        Self {
            name: name.into(),
            material: material.into(),
            shape,
            points_per_cell: super::default_points_per_cell(),
            velocity: InitialVelocity::default(),
            initial_stress: None,
            constraints: Vec::new(),
            contact_radius: None,
            acceleration: None,
            group: None,
        }
    }
}

impl BlockSpec {
    /// A block of `shape` with its frame at `position`, unrotated, moving
    /// as `motion`, meeting the points by `contact`, present from the start.
    pub fn new(
        name: impl Into<String>,
        shape: BlockShape,
        position: DVec2,
        motion: MotionSpec,
        contact: ContactLaw,
    ) -> Self {
        Self {
            name: name.into(),
            shape,
            position,
            angle: 0.0,
            motion,
            contact,
            present: true,
        }
    }
}
