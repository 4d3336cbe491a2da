//! Scenes: the RON schema of a scenario, its validation, and spawning its
//! bodies and blocks into a bevy `World`.
//!
//! Every struct denies unknown fields; every optional field documents its
//! default and why. Units are SI; the model is plane strain with unit
//! thickness, so masses, forces and energies are per metre, or with
//! `settings.geometry: Axisymmetric` a body of revolution, counted per
//! radian.

mod axisymmetry;
mod builder;
mod compat;
mod contact_stability;
pub(crate) mod input_file;
mod layout_warnings;
mod location;
pub(crate) mod point_file;
mod shapes;
mod spawn;
mod spawn_blocks;
mod step_warnings;
mod transfer_warnings;
mod validate;
mod velocity_field;

pub use crate::resources::{
    BlockVelocity, EdgeChanges, Side, StageEnd, StageSpec, SurfaceTraction,
};
pub use crate::rules::{ParameterError, RuleError};
pub use builder::SceneBuilder;
pub(crate) use contact_stability::{body_contact_stability_warnings, undamped_contact_warning};
pub(crate) use layout_warnings::{
    body_overlap_warnings, empty_region_warnings, free_edge_warnings,
};
pub use location::SourceLocation;
pub use point_file::{ListedPoint, PointFileError, PointListProblem};
pub use shapes::{Shape, ShapeError};
pub(crate) use spawn::spawn_scene;
pub(crate) use spawn_blocks::block_pair_laws;
pub(crate) use step_warnings::off_step_warnings;
pub(crate) use transfer_warnings::granular_transfer_warning;
pub use velocity_field::{VelocityField, VelocityFieldError};

use crate::components::{BodyAcceleration, RegionConstraint, RigidVelocity};
use crate::contact::ContactLaw;
use crate::materials::MaterialModel;
use crate::math::{DVec2, Real};
use crate::resources::ContactSettings;
use crate::resources::{EdgeConditions, Settings};
use crate::rigid::BlockShape;
use crate::rules;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A complete scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Name of the scene, used for the output folder. Default: the file stem.
    #[serde(default)]
    pub name: Option<String>,
    /// The background grid.
    pub grid: GridSpec,
    /// Time step and duration.
    pub time: TimeSpec,
    /// Gravitational acceleration (m/s²). Default (0, −9.81): Earth, y up.
    #[serde(default = "default_gravity")]
    pub gravity: DVec2,
    /// Numerical settings. Default: uGIMP, USF, FLIP (β = 0), positions
    /// moved by the remapped velocity, no damping (see [`Settings`]).
    #[serde(default)]
    pub settings: Settings,
    /// Named materials.
    pub materials: Vec<MaterialSpec>,
    /// Deformable bodies, in the order they are spawned.
    pub bodies: Vec<BodySpec>,
    /// Rigid blocks, in the order they are spawned. Default: none.
    #[serde(default)]
    pub blocks: Vec<BlockSpec>,
    /// Contact settings. Default: see [`ContactSettings`].
    #[serde(default)]
    pub contact: ContactSettings,
    /// DEM contact laws between pairs of bodies or groups (section 3.3).
    /// Bodies of different groups with no law between them do not interact:
    /// each group (or body without one) has its own grid layer. Default: none.
    #[serde(default)]
    pub body_contacts: Vec<BodyContactSpec>,
    /// DEM contact laws for particular pairs with a block: a block and a
    /// body (the law of that body's points against the block, instead of
    /// the block's `contact`), or two blocks (instead of the softer
    /// stiffnesses and smaller friction of their two laws). Default: none.
    #[serde(default)]
    pub block_contacts: Vec<BlockContactSpec>,
    /// Watched points. Default: none.
    #[serde(default)]
    pub probes: Vec<ProbeSpec>,
    /// Output cadence. Default: see [`OutputSpec`].
    #[serde(default)]
    pub output: OutputSpec,
    /// Loading stages, run in order; the run ends with the last one (or at
    /// `time.end`, whichever comes first). Default: none, one stage to
    /// `time.end`.
    #[serde(default)]
    pub stages: Vec<StageSpec>,
    /// Warnings about how the scene's file is written: the spellings of
    /// earlier releases it was read with, each with its present one. Shown
    /// with the scene's other warnings; empty for a scene built in code.
    #[serde(skip)]
    pub file_warnings: Vec<crate::warning::Warning>,
}

fn default_gravity() -> DVec2 {
    DVec2::new(0.0, -9.81)
}

/// The background grid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Lower-left corner (m). Default (0, 0): most scenes put their base there.
    #[serde(default)]
    pub origin: DVec2,
    /// Cell size h (m), > 0.
    #[serde(deserialize_with = "rules::de_positive")]
    pub cell_size: Real,
    /// Number of cells along x and y, each ≥ 2.
    pub cells: (usize, usize),
    /// Conditions on the four edges. Default: all `Free`, nothing imposed unasked.
    #[serde(default)]
    pub edges: EdgeConditions,
}

impl GridSpec {
    /// The grid resource this spec describes.
    pub fn grid(&self) -> crate::resources::Grid {
        crate::resources::Grid {
            origin: self.origin,
            cell_size: self.cell_size,
            cells: [self.cells.0, self.cells.1],
            edges: self.edges,
        }
    }

    /// Upper-right corner (m).
    pub fn max(&self) -> DVec2 {
        self.origin + DVec2::new(self.cells.0 as Real, self.cells.1 as Real) * self.cell_size
    }
}

/// Time stepping. A scene gives `(dt, end)` or `(dt, steps)`; a number of
/// steps becomes the end time steps × Δt.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TimeInput")]
pub struct TimeSpec {
    /// Fixed time step Δt (s), > 0. A warning gives the CFL limit when Δt exceeds it.
    pub dt: Real,
    /// End time (s), > 0.
    pub end: Real,
    /// The most steps the run may take (default `None`: [`MAX_STEPS`]). A
    /// scene whose `end / dt` is larger is refused as a likely slip in `dt`
    /// or `end`; name a larger count here to run that long.
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "rules::ser_some"
    )]
    pub max_steps: Option<u64>,
}

/// The default cap on a run's steps, `time.max_steps`: 10⁸, days of
/// running for a small scene.
pub const MAX_STEPS: u64 = 100_000_000;

/// The cap on the rows a run records: its samples (`end` over
/// `output.probe_interval`) times its records (energies, probes, blocks
/// and their parts, pairs of bodies under a law), each kept in memory,
/// about 100 bytes a row, until the run ends.
pub const MAX_SAMPLES: u64 = 10_000_000;

impl TimeSpec {
    /// A time step and an end time, with the default cap on the steps.
    pub fn new(dt: Real, end: Real) -> Self {
        Self {
            dt,
            end,
            max_steps: None,
        }
    }
}

/// The error for a time entry with both an end and a number of steps.
const TIME_END_TWICE: &str = "time takes end (s) or steps, not both";
/// The error for a time entry with neither.
const TIME_END_MISSING: &str = "time needs end (s) or steps";

/// [`TimeSpec`] as written in a scene: the end as a time or as a number of
/// steps.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "TimeSpec")]
struct TimeInput {
    #[serde(deserialize_with = "rules::de_positive")]
    dt: Real,
    #[serde(default, deserialize_with = "rules::de_some_positive")]
    end: Option<Real>,
    #[serde(default, deserialize_with = "rules::de_some_step_count")]
    steps: Option<u64>,
    #[serde(default, deserialize_with = "rules::de_some_step_count")]
    max_steps: Option<u64>,
}

/// Why a `time` section has no end, or two.
#[derive(Debug, thiserror::Error)]
pub enum TimeEndError {
    /// Both `end` and `steps`.
    #[error("{}", TIME_END_TWICE)]
    Twice,
    /// Neither.
    #[error("{}", TIME_END_MISSING)]
    Missing,
}

impl TryFrom<TimeInput> for TimeSpec {
    type Error = TimeEndError;

    fn try_from(input: TimeInput) -> Result<Self, TimeEndError> {
        let end = match (input.end, input.steps) {
            (Some(end), None) => end,
            (None, Some(steps)) => steps as Real * input.dt,
            (Some(_), Some(_)) => return Err(TimeEndError::Twice),
            (None, None) => return Err(TimeEndError::Missing),
        };
        Ok(Self {
            dt: input.dt,
            end,
            max_steps: input.max_steps,
        })
    }
}

/// A named material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Name, referred to by bodies.
    pub name: String,
    /// Mass density ρ (kg/m³), from 0.1 (below air's) to 1e9 (the densest
    /// metal, mass-scaled).
    #[serde(deserialize_with = "rules::de_density")]
    pub density: Real,
    /// Constitutive model, e.g. `LinearElastic((youngs_modulus: 1e5, poisson_ratio: 0.0))`.
    pub model: MaterialModel,
}

/// A deformable body generated from a shape.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique name.
    pub name: String,
    /// Name of a material of the scene.
    pub material: String,
    /// Outline to fill with points.
    pub shape: Shape,
    /// Points per cell along each direction (n × n per cell), 1 to 8.
    /// Default 2, the usual choice for uGIMP (domain half-size h/4).
    #[serde(default = "default_points_per_cell")]
    pub points_per_cell: u32,
    /// Initial velocity. Default: at rest, the usual start of a quasi-static run.
    #[serde(default)]
    pub velocity: InitialVelocity,
    /// Initial stress. Default: none (stress free). Not for `NeoHookean` or
    /// `NewtonianFluid` bodies, whose stress follows the deformation.
    #[serde(default)]
    pub initial_stress: Option<InitialStress>,
    /// Velocity constraints on nodes of this body's layer. Default: none.
    #[serde(default)]
    pub constraints: Vec<RegionConstraint>,
    /// Radius of each point's DEM disk (m), > 0, at most half a cell in a
    /// scene with body contacts. Default: half the point spacing, h / (2 n),
    /// so the disks reach the body's outline (for a point list with
    /// volumes, √V / 2: the disk reaches the sides of the point's square).
    #[serde(default)]
    pub contact_radius: Option<Real>,
    /// A body force per unit mass on this body, on top of gravity, e.g.
    /// `acceleration: Some((value: (1e3, 0.0), ramp_time: 1e-4))`. Default:
    /// none.
    #[serde(default)]
    pub acceleration: Option<BodyAcceleration>,
    /// Contact group: bodies with the same group share one grid layer and
    /// act as one continuum through it (standard MPM: they stick where they
    /// meet), and `body_contacts` may name the group for all its bodies.
    /// The members' region `constraints` then hold for the whole group, and
    /// the group uses its members' smallest node mass cutoff. Default: none,
    /// the body has a layer of its own.
    #[serde(default)]
    pub group: Option<String>,
}

/// A rigid block.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Unique name.
    pub name: String,
    /// Geometry in the block's frame.
    pub shape: BlockShape,
    /// Position of the block's frame origin (m). Default (0, 0).
    #[serde(default)]
    pub position: DVec2,
    /// Rotation of the block's frame (degrees, counter-clockwise). Default 0.
    #[serde(default)]
    pub angle: Real,
    /// How the block moves.
    pub motion: MotionSpec,
    /// The DEM law of its contacts with material points.
    pub contact: ContactLaw,
    /// Whether the block is there from the start. Default true; a block
    /// with `false` enters when a stage adds it.
    #[serde(default = "default_present")]
    pub present: bool,
}

fn default_present() -> bool {
    true
}

/// How a block moves.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MotionSpec {
    /// Never moves.
    Fixed,
    /// Moves with a prescribed velocity of its centre of mass and spin.
    Kinematic(RigidVelocity),
    /// Moves under reactions and gravity; mass and inertia from a density (kg/m³).
    Dynamic {
        /// Density (kg/m³), > 0.
        density: Real,
        /// Initial velocity. Default: at rest.
        #[serde(default)]
        velocity: RigidVelocity,
    },
    /// Moves under reactions and gravity, with mass properties given.
    DynamicWithMass {
        /// Mass (kg per metre of thickness): over the shape's area, a
        /// density within a material's range.
        mass: Real,
        /// Moment of inertia about the centre of mass (kg m² per metre): from
        /// 10⁻⁶ to 1 times the mass times the squared distance to the farthest
        /// corner of the shape's bounds.
        inertia: Real,
        /// Centre of mass in the block's frame (m), within the shape's bounds.
        /// Default: the frame origin.
        #[serde(default)]
        center: DVec2,
        /// Initial velocity. Default: at rest.
        #[serde(default)]
        velocity: RigidVelocity,
    },
}

fn default_points_per_cell() -> u32 {
    2
}

/// Initial velocity of a body's points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum InitialVelocity {
    /// The same velocity everywhere (m/s).
    Constant(DVec2),
    /// Expressions of the position, e.g. `Field(x: "x*(1-x)", y: "0")`.
    Field {
        /// vx(x, y).
        x: String,
        /// vy(x, y).
        y: String,
    },
}

impl Default for InitialVelocity {
    fn default() -> Self {
        Self::Constant(DVec2::ZERO)
    }
}

/// Initial stress of a body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum InitialStress {
    /// At-rest state under gravity: σ_yy = −ρ |g_y| (surface − y),
    /// σ_xx = σ_zz = K0 σ_yy, no shear (compression negative).
    Geostatic {
        /// Lateral earth pressure coefficient K0, 0 to 10 (ν/(1−ν) for an
        /// elastic soil).
        #[serde(deserialize_with = "rules::de_non_negative")]
        k0: Real,
        /// Height of the free surface (m). Default: the top of the body, a body
        /// with nothing resting on it. Points above it start stress-free.
        #[serde(default)]
        surface: Option<Real>,
    },
}

/// The DEM law between the points of two bodies.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyContactSpec {
    /// The two sides: each a body's name or a contact group's (all its bodies).
    pub between: (String, String),
    /// Stiffnesses (N/m per metre of thickness), friction and damping.
    pub law: ContactLaw,
}

/// The DEM law of a pair with a block.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockContactSpec {
    /// The two sides: a block's name and a body's, or two blocks' names.
    pub between: (String, String),
    /// Stiffnesses (N/m per metre of thickness), friction and damping.
    pub law: ContactLaw,
}

/// A watched material point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// Name, used in the CSV and the plot file name.
    pub name: String,
    /// Name of the body.
    pub body: String,
    /// The point of the body nearest this location at the start is watched (m).
    pub at: DVec2,
}

/// What is written and how often.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// Simulated time between VTK frames (s). Default: end / 100, a hundred
    /// frames whatever the duration.
    pub frame_interval: Option<Real>,
    /// Simulated time between probe and energy samples (s). Default: end /
    /// 1000, a thousand samples, smooth plots at a negligible cost; set it to
    /// `time.dt` to sample every step.
    pub probe_interval: Option<Real>,
    /// Reaction–displacement curves of blocks (e.g. a pile's cone
    /// resistance against depth), written as `<name>.csv` and `<name>.png`.
    pub curves: Vec<CurveSpec>,
    /// Writes `animation.gif` from the frames: the points coloured by this
    /// field, the block outlines and the time. Default: none.
    pub animation: Option<AnimatedField>,
    /// Records each body's front along +x with the probes, in
    /// `fronts.csv` and `fronts.png`: its farthest point and the x beyond
    /// which 0.1% of its points lie. Default false.
    pub fronts: bool,
}

/// The field an animation colours the points by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum AnimatedField {
    /// The displacement's magnitude |u| (m).
    Displacement,
    /// The velocity's magnitude |v| (m/s).
    Velocity,
    /// The mean stress p = (σ_xx + σ_yy + σ_zz) / 3 (Pa, tension positive).
    MeanStress,
    /// The body (its index in `bodies`).
    Body,
}

impl AnimatedField {
    /// The colour bar's label.
    pub fn label(self) -> &'static str {
        match self {
            Self::Displacement => "|u| (m)",
            Self::Velocity => "|v| (m/s)",
            Self::MeanStress => "mean stress (Pa)",
            Self::Body => "body",
        }
    }
}

/// A block's (or one part's) reaction against the block's displacement,
/// both measured along `direction`: displacement (x − x₀) · d and
/// resistance F · (−d), with d the unit `direction`, F the points' force
/// on the block or part. Sampled with the probes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CurveSpec {
    /// File stem of the CSV and PNG.
    pub name: String,
    /// The block.
    pub block: String,
    /// Part of a compound block (its index in `parts`). Default: the whole block.
    #[serde(default)]
    pub part: Option<usize>,
    /// Direction of travel, e.g. (0, −1) for a pile driven down.
    pub direction: DVec2,
    /// Factor on the resistance (e.g. 1/R for q_c = f_c / R). Default 1.
    #[serde(default = "one")]
    pub force_scale: Real,
    /// Factor on the displacement (e.g. 1/R for z/R). Default 1.
    #[serde(default = "one")]
    pub displacement_scale: Real,
    /// Axis label of the resistance. Default "force (N/m)".
    #[serde(default)]
    pub force_label: Option<String>,
    /// Axis label of the displacement. Default "displacement (m)".
    #[serde(default)]
    pub displacement_label: Option<String>,
}

fn one() -> Real {
    1.0
}

impl OutputSpec {
    /// The frame interval, or its default for a run ending at `end`.
    pub fn frame_interval_or_default(&self, end: Real) -> Real {
        self.frame_interval.unwrap_or(end / 100.0)
    }

    /// The probe interval, or its default for a run ending at `end`.
    pub fn probe_interval_or_default(&self, end: Real) -> Real {
        self.probe_interval.unwrap_or(end / 1000.0)
    }

    /// Steps between frames of a run ending at `end` with steps of `dt`.
    pub fn frame_every(&self, end: Real, dt: Real) -> u64 {
        whole_steps(self.frame_interval_or_default(end), dt)
    }

    /// Steps between probe and energy samples of a run ending at `end` with
    /// steps of `dt`.
    pub fn probe_every(&self, end: Real, dt: Real) -> u64 {
        whole_steps(self.probe_interval_or_default(end), dt)
    }
}

/// An output interval in whole steps of `dt`, the nearest, at least one.
pub fn whole_steps(interval: Real, dt: Real) -> u64 {
    ((interval / dt).round() as u64).max(1)
}

/// The stems of the files a run writes into its folder besides the
/// curves' (`<stem>.csv`, `.png`, `.pvd`, `.gif`, `.txt`, `.bin`): a curve
/// may not take one. Probe plots are `probe_<name>_<quantity>.png`, so no
/// curve name may start with [`PROBE_PLOT_PREFIX`].
pub const RUN_FILE_STEMS: [&str; 13] = [
    "points",
    "blocks",
    "probes",
    "energy",
    "body_contacts",
    "stages",
    "snapshot",
    "checkpoint",
    "fronts",
    "deposit",
    "block_rotation",
    "animation",
    "outputs",
];

/// The longest quantity a probe plot's file name ends with
/// (`probe_<name>_displacement.png`).
pub const PROBE_PLOT_LONGEST_SUFFIX: &str = "_displacement.png";

/// The start of every probe plot's file name.
pub const PROBE_PLOT_PREFIX: &str = "probe_";

/// Errors of loading or validating a scene; each says where and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{path}: cannot read the scene: {source}")]
    Read {
        /// The scene file.
        path: PathBuf,
        /// The IO error.
        source: std::io::Error,
    },
    /// The file is not a valid scene (syntax, unknown field, wrong type or a value out of range).
    #[error("{location}: {message}")]
    Parse {
        /// Where.
        location: SourceLocation,
        /// What was expected.
        message: String,
    },
    /// The scene parses but is inconsistent (unknown name, body outside the grid, ...).
    #[error("{location}: {message}")]
    Invalid {
        /// Where (the file position of the offending entry when known).
        location: SourceLocation,
        /// What is wrong and what was expected.
        message: String,
    },
}

impl Scene {
    /// Reads, parses and validates a scene file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let source = input_file::read_input(path).map_err(|source| SceneError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&source, path)
    }

    /// Parses and validates scene text; `path` is used in messages, for
    /// the default name, and its folder for the point lists' files.
    pub fn parse(source: &str, path: &Path) -> Result<Self, SceneError> {
        // Editors on Windows may start a UTF-8 file with a byte-order mark.
        let source = source.strip_prefix('\u{feff}').unwrap_or(source);
        let present = compat::present_spelling(source);
        let (source, file_warnings) = match &present {
            Some((text, warnings)) => (text.as_str(), warnings.clone()),
            None => (source, Vec::new()),
        };
        let mut scene: Scene = ron::from_str(source).map_err(|e| {
            let mut message = e.code.to_string();
            if matches!(e.code, ron::Error::ExpectedOption) {
                // An optional field is written Some(value), or left out.
                message = "expected an optional value: Some(...) or None".into();
            }
            if matches!(e.code, ron::Error::ExceededRecursionLimit) {
                message = "brackets nested too deep: a scene nests a few levels (a stage in the list of stages, a part in a compound); look for brackets opened and never closed".into();
            }
            // The parser stands past the time entry when it finds its end
            // missing or given twice: point at the entry instead.
            let location = if [TIME_END_TWICE, TIME_END_MISSING].contains(&message.as_str()) {
                SourceLocation::find(source, path, &["time"])
            } else {
                SourceLocation::at(path, e.span.start.line, e.span.start.col)
            };
            SceneError::Parse { location, message }
        })?;
        if scene.name.is_none() {
            let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
            if let Some(Err(e)) = stem.as_deref().map(rules::file_name) {
                return Err(SceneError::Invalid {
                    location: SourceLocation::find(source, path, &[]),
                    message: format!(
                        "the scene takes its name, and its output folder's, from the file name: {e}; give it a `name`"
                    ),
                });
            }
            scene.name = stem;
        }
        scene.file_warnings = file_warnings;
        let folder = path.parent().unwrap_or(Path::new(""));
        if let Err((body, message)) = scene.read_point_files_in(folder) {
            return Err(SceneError::Invalid {
                location: SourceLocation::find(
                    source,
                    path,
                    &["bodies", &format!("\"{body}\""), "shape"],
                ),
                message,
            });
        }
        scene.validate_in(Some((source, path)))?;
        Ok(scene)
    }

    /// Validates a scene built in code: every range rule and every reference.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.validate_in(None)
    }

    /// The bodies (scene indices, ascending) that `name` stands for in
    /// `body_contacts`: the body of that name, or the bodies of that contact
    /// group; `None` when it is neither.
    pub fn contact_members(&self, name: &str) -> Option<Vec<usize>> {
        if let Some(i) = self.bodies.iter().position(|b| b.name == name) {
            return Some(vec![i]);
        }
        let members: Vec<usize> = (0..self.bodies.len())
            .filter(|&i| self.bodies[i].group.as_deref() == Some(name))
            .collect();
        (!members.is_empty()).then_some(members)
    }

    /// The contact groups with two or more bodies, as scene indices
    /// (ascending), groups in the order of their first body.
    pub fn shared_layers(&self) -> Vec<Vec<usize>> {
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for (i, body) in self.bodies.iter().enumerate() {
            let Some(group) = &body.group else { continue };
            match groups
                .iter_mut()
                .find(|g| self.bodies[g[0]].group.as_ref() == Some(group))
            {
                Some(members) => members.push(i),
                None => groups.push(vec![i]),
            }
        }
        groups.retain(|g| g.len() > 1);
        groups
    }

    /// The scene's name, or "scene" when it has none.
    pub fn display_name(&self) -> &str {
        self.name.as_deref().unwrap_or("scene")
    }
}
