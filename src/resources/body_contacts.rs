//! Nonrigid–nonrigid contacts (paper section 3.3): the laws between bodies
//! and this step's point-pair contacts with their tangential springs.

use crate::contact::ContactLaw;
use crate::math::{DVec2, Real};
use bevy_ecs::prelude::Resource;

/// The law between two bodies, by body index in the scene (`a` < `b`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyPairLaw {
    /// The lower body index.
    pub a: u32,
    /// The higher body index.
    pub b: u32,
    /// The DEM law of eq. 18.
    pub law: ContactLaw,
}

/// A contact between point `p` of body `a` and point `q` of body `b`
/// (`a` < `b`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyPairContact {
    /// Body index of the first point.
    pub a: u32,
    /// The first point.
    pub p: u32,
    /// Body index of the second point.
    pub b: u32,
    /// The second point.
    pub q: u32,
    /// Force on p (N/m); q receives the opposite.
    pub force: DVec2,
    /// Tangential spring force on p, carried to the next step.
    pub tangential: DVec2,
    /// Overlap δ of the two disks (m).
    pub overlap: Real,
    /// Contact point, the middle of the overlap (m).
    pub at: DVec2,
    /// Mean radius of the two disks (m): the contact zone reaches this far
    /// beyond the contact point across the normal.
    pub radius: Real,
}

impl BodyPairContact {
    /// The pair's key: contacts are kept sorted by it.
    pub fn key(&self) -> (u32, u32, u32, u32) {
        (self.a, self.p, self.b, self.q)
    }
}

/// The body-contact laws, this step's contacts and last step's (for the
/// tangential springs), and the detection's scratch space.
#[derive(Resource, Clone, Debug, Default)]
pub struct BodyContacts {
    /// Laws, sorted by (a, b).
    pub laws: Vec<BodyPairLaw>,
    /// This step's contacts, sorted by key.
    pub current: Vec<BodyPairContact>,
    /// Last step's contacts, sorted by key.
    pub previous: Vec<BodyPairContact>,
    /// Bodies present in each cell, one bit per body index.
    pub cell_bodies: Vec<u64>,
    /// Each body's points' cells (row-major index), bodies in scene order.
    pub point_cells: Vec<Vec<u32>>,
    /// Points next to another body: (cell, body, point), sorted.
    pub candidates: Vec<(u32, u32, u32)>,
    /// Per-chunk buffers of the parallel detection, reused every step.
    pub chunks: Vec<DetectionChunk>,
}

/// One chunk's output of the parallel detection.
#[derive(Clone, Debug, Default)]
pub struct DetectionChunk {
    /// Candidates found in this chunk of points: (cell, body, point).
    pub candidates: Vec<(u32, u32, u32)>,
    /// Contacts found from this chunk of candidates.
    pub contacts: Vec<BodyPairContact>,
}

/// Most bodies a scene with body contacts may have: the detection marks
/// each cell's bodies in a 64-bit mask.
pub const MAX_CONTACT_BODIES: usize = 64;

/// The law between bodies `i` and `j` in `laws` (sorted by (a, b)), if any.
pub fn law_between(laws: &[BodyPairLaw], i: u32, j: u32) -> Option<&ContactLaw> {
    let (a, b) = (i.min(j), i.max(j));
    laws.binary_search_by(|l| (l.a, l.b).cmp(&(a, b)))
        .ok()
        .map(|k| &laws[k].law)
}

/// The contacts between two bodies summed up: the resultant and the width
/// of the zone they cover. The widths assume one contact zone, measured
/// across the resultant; for bodies touching on opposite sides (a resultant
/// near zero) they mean nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairSummary {
    /// Resultant force on the lower-index body (N/m).
    pub force: DVec2,
    /// Number of point pairs in contact.
    pub contacts: u32,
    /// Half-width a of the contact zone (m): across the resultant's
    /// direction, half the spread of the contact points plus the mean disk
    /// radius of the two outermost pairs (the zone ends between the last
    /// pair in contact and the next, estimated at the outer pair's disk
    /// edge). Zero without contacts.
    pub half_width: Real,
    /// Half-width from the spread of the contact forces across the
    /// resultant: 2 √(Σ |f| (s − s̄)² / Σ |f|), with s̄ the force-weighted
    /// mean position. Exact for the elliptical pressure of Hertz contact
    /// (whose second moment is a²/4), and it grows smoothly as pairs join,
    /// where `half_width` jumps by a point spacing.
    pub pressure_half_width: Real,
}

impl BodyContacts {
    /// The contacts between bodies `a` < `b` this step, summed up.
    pub fn summary(&self, a: u32, b: u32) -> PairSummary {
        let pair = || self.current.iter().filter(|c| c.a == a && c.b == b);
        let force: DVec2 = pair().map(|c| c.force).sum();
        let contacts = pair().count() as u32;
        if contacts == 0 {
            return PairSummary::default();
        }
        let across = force.normalize_or_zero().perp();
        let (mut low, mut high) = ((Real::INFINITY, 0.0), (Real::NEG_INFINITY, 0.0));
        for c in pair() {
            let s = c.at.dot(across);
            if s < low.0 {
                low = (s, c.radius);
            }
            if s > high.0 {
                high = (s, c.radius);
            }
        }
        let weight: Real = pair().map(|c| c.force.length()).sum();
        let mean = pair()
            .map(|c| c.force.length() * c.at.dot(across))
            .sum::<Real>()
            / weight;
        let spread = pair()
            .map(|c| c.force.length() * (c.at.dot(across) - mean).powi(2))
            .sum::<Real>()
            / weight;
        PairSummary {
            force,
            contacts,
            half_width: 0.5 * (high.0 - low.0) + 0.5 * (low.1 + high.1),
            pressure_half_width: if weight > 0.0 {
                2.0 * spread.sqrt()
            } else {
                0.0
            },
        }
    }

    /// The law between bodies `i` and `j`, if any.
    pub fn law(&self, i: u32, j: u32) -> Option<&ContactLaw> {
        law_between(&self.laws, i, j)
    }

    /// Contact potential energy Σ ½ k_n δ² + |f_t|² / (2 k_t) (J/m).
    pub fn potential_energy(&self) -> Real {
        self.current
            .iter()
            .filter_map(|c| {
                let law = self.law(c.a, c.b)?;
                Some(
                    0.5 * law.normal_stiffness * c.overlap * c.overlap
                        + c.tangential.length_squared() / (2.0 * law.tangential_stiffness),
                )
            })
            .sum()
    }
}
