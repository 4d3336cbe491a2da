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
    /// Points next to another body: (cell, body, point), sorted.
    pub candidates: Vec<(u32, u32, u32)>,
}

/// The law between bodies `i` and `j` in `laws` (sorted by (a, b)), if any.
pub fn law_between(laws: &[BodyPairLaw], i: u32, j: u32) -> Option<&ContactLaw> {
    let (a, b) = (i.min(j), i.max(j));
    laws.binary_search_by(|l| (l.a, l.b).cmp(&(a, b)))
        .ok()
        .map(|k| &laws[k].law)
}

impl BodyContacts {
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
