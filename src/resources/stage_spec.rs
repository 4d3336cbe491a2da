//! The stages of a scene as it writes them: a sequence of loading steps (geostatic settling,
//! surcharge, driving a pile...) that each change the setup on entry and
//! end after a duration or when the model has settled.

use super::{EdgeCondition, EdgeConditions};
use crate::components::RigidVelocity;
use crate::math::{DVec2, Real};
use crate::rules;
use serde::{Deserialize, Deserializer, Serialize};

/// One stage. Every change is optional: what a stage does not set stays as
/// the previous stage (or the scene) left it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StageSpec {
    /// Name, used in `stages.csv` and messages.
    pub name: String,
    /// When the stage ends.
    pub end: StageEnd,
    /// PIC fraction β from this stage on.
    #[serde(default, deserialize_with = "de_optional_fraction")]
    pub pic_fraction: Option<Real>,
    /// Grid damping α_g from this stage on.
    #[serde(default, deserialize_with = "de_optional_damping")]
    pub grid_damping: Option<Real>,
    /// Particle damping α_p from this stage on.
    #[serde(default, deserialize_with = "de_optional_damping")]
    pub particle_damping: Option<Real>,
    /// Gravity from this stage on (m/s²).
    #[serde(default)]
    pub gravity: Option<DVec2>,
    /// Grid edge conditions from this stage on: the edges given change
    /// (e.g. a wall removed by setting its edge `Free`), the others keep
    /// theirs.
    #[serde(default)]
    pub edges: Option<EdgeChanges>,
    /// Blocks (by name) that leave the scene on entry.
    #[serde(default)]
    pub remove_blocks: Vec<String>,
    /// Blocks (by name, declared in `blocks` with `present: false`) that
    /// enter the scene on entry.
    #[serde(default)]
    pub add_blocks: Vec<String>,
    /// Velocities given to kinematic blocks on entry.
    #[serde(default)]
    pub block_velocities: Vec<BlockVelocity>,
    /// Surface tractions set on entry; each replaces any earlier traction on
    /// the same body and side.
    #[serde(default)]
    pub tractions: Vec<SurfaceTraction>,
}

impl StageSpec {
    /// A stage named `name` that changes nothing and ends at `end` (for
    /// scenes built in code: set the changes it makes on the result).
    pub fn new(name: impl Into<String>, end: StageEnd) -> Self {
        Self {
            name: name.into(),
            end,
            pic_fraction: None,
            grid_damping: None,
            particle_damping: None,
            gravity: None,
            edges: None,
            remove_blocks: Vec::new(),
            add_blocks: Vec::new(),
            block_velocities: Vec::new(),
            tractions: Vec::new(),
        }
    }
}

/// A stage's changes to the grid's edge conditions, written like
/// `GridSpec::edges` (e.g. `(left: Free)`): each edge given is set, each
/// left out keeps the condition it had.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeChanges {
    /// Edge x = x_min.
    #[serde(
        default,
        deserialize_with = "some_edge",
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::rules::ser_some"
    )]
    pub left: Option<EdgeCondition>,
    /// Edge x = x_max.
    #[serde(
        default,
        deserialize_with = "some_edge",
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::rules::ser_some"
    )]
    pub right: Option<EdgeCondition>,
    /// Edge y = y_min.
    #[serde(
        default,
        deserialize_with = "some_edge",
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::rules::ser_some"
    )]
    pub bottom: Option<EdgeCondition>,
    /// Edge y = y_max.
    #[serde(
        default,
        deserialize_with = "some_edge",
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::rules::ser_some"
    )]
    pub top: Option<EdgeCondition>,
}

impl EdgeChanges {
    /// `edges` with these changes made.
    pub fn apply(&self, edges: EdgeConditions) -> EdgeConditions {
        EdgeConditions {
            left: self.left.unwrap_or(edges.left),
            right: self.right.unwrap_or(edges.right),
            bottom: self.bottom.unwrap_or(edges.bottom),
            top: self.top.unwrap_or(edges.top),
        }
    }
}

/// An edge condition written without `Some` (absent: `None`, with
/// `#[serde(default)]`).
fn some_edge<'de, D: Deserializer<'de>>(d: D) -> Result<Option<EdgeCondition>, D::Error> {
    EdgeCondition::deserialize(d).map(Some)
}

/// When a stage ends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum StageEnd {
    /// After this long (s).
    Duration(#[serde(deserialize_with = "rules::de_positive")] Real),
    /// When the kinetic energy of the bodies and the dynamic blocks has
    /// fallen to `ratio` of the largest it reached during the stage (not
    /// before something has moved: a stage that starts at rest waits), or
    /// after `max_time` (s) with a warning.
    KineticEnergyRatio {
        /// Threshold ratio in (0, 1].
        #[serde(deserialize_with = "rules::de_ratio")]
        ratio: Real,
        /// Longest the stage may last (s).
        #[serde(deserialize_with = "rules::de_positive")]
        max_time: Real,
    },
    /// When no stress component of any point changed by more than `below`
    /// (Pa) in the last step, once some had changed by more during the
    /// stage (from rest the stresses only begin to change: without that,
    /// the first step would end the stage), or after `max_time` (s) with a
    /// warning; a stage in which nothing moves ends at `max_time`.
    StressChange {
        /// Threshold (Pa).
        #[serde(deserialize_with = "rules::de_positive")]
        below: Real,
        /// Longest the stage may last (s).
        #[serde(deserialize_with = "rules::de_positive")]
        max_time: Real,
    },
}

impl StageEnd {
    /// Checks the ranges (as parsing does, for stages built in code).
    pub fn check(&self) -> Result<(), rules::RuleError> {
        match *self {
            Self::Duration(d) => rules::positive(d).map(drop),
            Self::KineticEnergyRatio { ratio, max_time } => {
                rules::ratio(ratio)?;
                rules::positive(max_time).map(drop)
            }
            Self::StressChange { below, max_time } => {
                rules::positive(below)?;
                rules::positive(max_time).map(drop)
            }
        }
    }

    /// The most steps of `dt` the stage can take: it ends on the first step
    /// whose elapsed time reaches its `Duration` or `max_time` less half a
    /// step (systems/stages.rs), and takes at least one.
    pub fn most_steps(&self, dt: Real) -> u64 {
        (self.max_time() / dt - 0.5 - 1e-9).ceil().max(1.0) as u64
    }

    /// The longest the stage can last (s).
    pub fn max_time(&self) -> Real {
        match *self {
            Self::Duration(d) => d,
            Self::KineticEnergyRatio { max_time, .. } | Self::StressChange { max_time, .. } => {
                max_time
            }
        }
    }
}

/// A kinematic block's new velocity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockVelocity {
    /// The block's name.
    pub block: String,
    /// Its velocity from this stage on.
    pub velocity: RigidVelocity,
}

/// A uniform traction on one side of a body's surface, carried by the
/// body's outermost points on that side.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceTraction {
    /// The body's name.
    pub body: String,
    /// Which side of the body.
    pub side: Side,
    /// Traction (Pa = N/m² per metre of thickness), e.g. (0, −150e3) for a
    /// 150 kPa surcharge pressing down on a top surface.
    pub traction: DVec2,
}

/// A side of a body: the points that are outermost in that direction
/// (per column of points for `Top`/`Bottom`, per row for `Left`/`Right`;
/// see `systems::side_points`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Side {
    /// The highest point of each column.
    Top,
    /// The lowest point of each column.
    Bottom,
    /// The leftmost point of each row.
    Left,
    /// The rightmost point of each row.
    Right,
}

fn de_optional_fraction<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Real>, D::Error> {
    optional(d, rules::fraction)
}

fn de_optional_damping<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Real>, D::Error> {
    optional(d, rules::damping)
}

fn optional<'de, D: serde::Deserializer<'de>>(
    d: D,
    rule: fn(Real) -> Result<Real, rules::RuleError>,
) -> Result<Option<Real>, D::Error> {
    Option::<Real>::deserialize(d)?
        .map(rule)
        .transpose()
        .map_err(serde::de::Error::custom)
}
