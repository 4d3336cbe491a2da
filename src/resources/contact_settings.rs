//! Settings of the DEM contacts.

use crate::contact::{ContactLaw, ForceApplication};
use crate::math::{DVec2, Real};
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

/// How contacts are searched and imposed (scene `contact`).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ContactSettings {
    /// Steps between neighbour-list rebuilds (Algorithm 1's `iterperiod`).
    /// Default (`None`): 10, a common DEM choice; the travel guard rebuilds
    /// earlier whenever a point could have crossed the margin.
    pub iter_period: Option<u32>,
    /// Extra distance around a block's bounding box in which points are
    /// listed (m). Default (`None`): one cell, so a rebuild every 10 steps
    /// is enough while points move less than a tenth of a cell per step.
    pub margin: Option<Real>,
    /// Body force (default) or traction (section 3.2.3).
    pub force_application: ForceApplication,
    /// What δ of eq. 18a measures for a point against a block.
    pub penetration: Penetration,
}

/// The penetration measure δ of rigid–nonrigid contacts (section 3.2.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Penetration {
    /// Depth of the disk in the block (m); k_n in N/m per metre of
    /// thickness. Default: the classic DEM measure.
    #[default]
    Depth,
    /// Area of the disk beyond the block's face (m²); k_n in N/m² per
    /// metre, so the force grows as δ^(3/2) like a Hertzian contact.
    Area,
}

impl ContactSettings {
    /// The rebuild period in steps.
    pub fn period(&self) -> u32 {
        self.iter_period.unwrap_or(10)
    }

    /// The list margin for a grid of cell size `h`.
    pub fn margin_or(&self, h: Real) -> Real {
        self.margin.unwrap_or(h)
    }
}

/// Identifies a block–block contact point from step to step: block a, block
/// b (scene indices, a < b) and the point's features (see
/// `ShapeContact::features`).
pub type BlockContactKey = (u32, u32, (u32, u32, u32));

/// Tangential springs of the block–block contacts, carried from step to
/// step: (key, force on a), sorted by key. A point that separates is dropped.
#[derive(Resource, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BlockContactHistory(pub Vec<(BlockContactKey, DVec2)>);

/// The laws the scene gives for particular pairs of blocks
/// (`block_contacts`), by scene indices (a < b), sorted; other pairs take
/// [`ContactLaw::pair`] of the blocks' own laws.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct BlockPairLaws(pub Vec<((u32, u32), ContactLaw)>);

impl BlockPairLaws {
    /// The law between blocks `a` and `b` (scene indices), whose own laws
    /// are `own_a` and `own_b`.
    pub fn between(&self, a: u32, b: u32, own_a: &ContactLaw, own_b: &ContactLaw) -> ContactLaw {
        self.0
            .binary_search_by_key(&(a.min(b), a.max(b)), |(pair, _)| *pair)
            .map_or_else(|_| own_a.pair(own_b), |k| self.0[k].1)
    }
}
