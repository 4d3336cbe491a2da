//! Nonrigid–nonrigid contacts (paper section 3.3): the laws between bodies
//! and this step's point-pair contacts with their tangential springs.

use crate::contact::ContactLaw;
use crate::math::{DVec2, Real};
use bevy_ecs::prelude::Resource;
use serde::{Deserialize, Serialize};

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
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
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
    /// x_p − x_q when the contact was found (m).
    pub separation: DVec2,
    /// Half the change of the tangential force at this step, f_t − f_t
    /// of the step before, times the relative motion over the step before
    /// that the change was taken from (J/m; zero for a new contact):
    /// added to `ContactWork`'s force-times-motion, it makes the work of
    /// the tangential force the trapezoidal rule's, ½ (f_t,old + f_t,new)
    /// · Δu, which a sticking spring's energy change matches exactly; so
    /// only sliding and the springs of ended contacts count as dissipated.
    pub spring_work_correction: Real,
}

impl BodyPairContact {
    /// The pair's key: contacts are kept sorted by it.
    pub fn key(&self) -> (u32, u32, u32, u32) {
        (self.a, self.p, self.b, self.q)
    }

    /// The arms from the two points' centres to the contact point, x_c −
    /// x_p and x_c − x_q, given the points' disk radii: along the normal
    /// from q to p, each the radius less half the overlap.
    pub fn arms(&self, radius_p: Real, radius_q: Real) -> (DVec2, DVec2) {
        let normal = self.separation.normalize_or_zero();
        let reach = |radius: Real| radius - 0.5 * self.overlap;
        (-normal * reach(radius_p), normal * reach(radius_q))
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
    /// Bodies present in the 3 x 3 cells around each marked cell.
    pub near_bodies: Vec<u64>,
    /// The cells marked this step, each once, with the bodies in the 3 x 3
    /// cells around it.
    pub marked_cells: Vec<(u32, u64)>,
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
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
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
    /// The same spread over each pair's place in the undeformed bodies, the
    /// middle of its two points' initial positions: the zone's half-width as
    /// small-strain theory (Hertz) measures it, which does not tell the
    /// configurations apart. Under load a contact's surface slides towards
    /// its centre by a fraction (1 − 2ν) of order a/R, so the current zone
    /// is narrower than this one (for the Hertz disks at a = 0.2–0.3 R by
    /// 7.5% in small strain, 9% with their law, by finite elements). The
    /// places are projected across the current resultant, which assumes the
    /// pair has not turned since the bodies were placed (a turn θ scales
    /// this width by about cos θ). Pairs whose points are gone (a body
    /// removed) are left out; zero when none is left.
    pub initial_pressure_half_width: Real,
}

/// Running sums of one law's contacts while [`BodyContacts::summaries`]
/// passes over them.
#[derive(Clone, Copy, Debug, Default)]
pub struct PairTally {
    /// The resultant and the count; the widths are filled in by `summary`.
    sums: PairSummary,
    /// Unit vector across the resultant.
    across: DVec2,
    /// Σ |f|.
    weight: Real,
    /// Lowest and highest contact positions across, with their pairs' radii.
    low: (Real, Real),
    high: (Real, Real),
    /// Σ |f| s, then the force-weighted mean position s̄.
    mean: Real,
    /// Σ |f| (s − s̄)².
    spread: Real,
    /// The same three sums over the pairs' initial places.
    initial_weight: Real,
    initial_mean: Real,
    initial_spread: Real,
}

impl PairTally {
    /// The pair's contacts summed up (all zero without contacts).
    pub fn summary(&self) -> PairSummary {
        if self.sums.contacts == 0 {
            return PairSummary::default();
        }
        PairSummary {
            half_width: 0.5 * (self.high.0 - self.low.0) + 0.5 * (self.low.1 + self.high.1),
            pressure_half_width: if self.weight > 0.0 {
                2.0 * (self.spread / self.weight).sqrt()
            } else {
                0.0
            },
            initial_pressure_half_width: if self.initial_weight > 0.0 {
                2.0 * (self.initial_spread / self.initial_weight).sqrt()
            } else {
                0.0
            },
            ..self.sums
        }
    }
}

impl BodyContacts {
    /// The contacts of every law's pair of bodies this step, summed up:
    /// `tallies[k].summary()` for `laws[k]`, `initial_place` giving a
    /// contact's place in the undeformed bodies (none if its points are
    /// gone). Three passes over the contacts (the resultant, then the
    /// positions across it, then their spread), whatever the number of laws;
    /// `tallies` is reused from call to call.
    pub fn summaries(
        &self,
        initial_place: impl Fn(&BodyPairContact) -> Option<DVec2>,
        tallies: &mut Vec<PairTally>,
    ) {
        tallies.clear();
        tallies.resize(self.laws.len(), PairTally::default());
        let law_of = |c: &BodyPairContact| {
            self.laws
                .binary_search_by(|l| (l.a, l.b).cmp(&(c.a, c.b)))
                .ok()
        };
        for c in &self.current {
            if let Some(k) = law_of(c) {
                tallies[k].sums.force += c.force;
                tallies[k].sums.contacts += 1;
            }
        }
        for t in tallies.iter_mut() {
            t.across = t.sums.force.normalize_or_zero().perp();
            t.low = (Real::INFINITY, 0.0);
            t.high = (Real::NEG_INFINITY, 0.0);
        }
        for c in &self.current {
            if let Some(k) = law_of(c) {
                let t = &mut tallies[k];
                let s = c.at.dot(t.across);
                if s < t.low.0 {
                    t.low = (s, c.radius);
                }
                if s > t.high.0 {
                    t.high = (s, c.radius);
                }
                t.weight += c.force.length();
                t.mean += c.force.length() * s;
                if let Some(place) = initial_place(c) {
                    t.initial_weight += c.force.length();
                    t.initial_mean += c.force.length() * place.dot(t.across);
                }
            }
        }
        for t in tallies.iter_mut() {
            t.mean /= t.weight;
            t.initial_mean /= t.initial_weight;
        }
        for c in &self.current {
            if let Some(k) = law_of(c) {
                let t = &mut tallies[k];
                let weight = c.force.length();
                t.spread += weight * (c.at.dot(t.across) - t.mean).powi(2);
                if let Some(place) = initial_place(c) {
                    t.initial_spread += weight * (place.dot(t.across) - t.initial_mean).powi(2);
                }
            }
        }
    }

    /// The law between bodies `i` and `j`, if any.
    pub fn law(&self, i: u32, j: u32) -> Option<&ContactLaw> {
        law_between(&self.laws, i, j)
    }

    /// Energy of this step's contact springs, (Σ ½ k_n δ² + |f_t|² / (2 k_t),
    /// its tangential part Σ |f_t|² / (2 k_t)) (J/m).
    pub fn spring_energies(&self) -> (Real, Real) {
        self.current
            .iter()
            .filter_map(|c| Some((c, self.law(c.a, c.b)?)))
            .fold((0.0, 0.0), |(all, tangential), (c, law)| {
                let t = law.tangential_energy(c.tangential);
                (
                    all + 0.5 * law.normal_stiffness * c.overlap * c.overlap + t,
                    tangential + t,
                )
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAW: ContactLaw = ContactLaw {
        normal_stiffness: 1.0,
        tangential_stiffness: 1.0,
        friction: 0.0,
        normal_damping: 0.0,
    };

    fn contact(p: u32, b: u32, force: DVec2, at: DVec2) -> BodyPairContact {
        BodyPairContact {
            a: 0,
            p,
            b,
            q: p,
            force,
            tangential: DVec2::ZERO,
            overlap: 0.0,
            at,
            radius: 0.01,
            separation: DVec2::ZERO,
            spring_work_correction: 0.0,
        }
    }

    /// Hertz's elliptical pressure at `s` across a zone of half-width `a`,
    /// over its peak.
    fn hertz_pressure(s: Real, a: Real) -> Real {
        (1.0 - (s / a).powi(2)).max(0.0).sqrt()
    }

    /// `current` contacts between bodies with a law for each of `pairs`.
    fn contacts_between(pairs: &[(u32, u32)], current: Vec<BodyPairContact>) -> BodyContacts {
        BodyContacts {
            laws: pairs
                .iter()
                .map(|&(a, b)| BodyPairLaw { a, b, law: LAW })
                .collect(),
            current,
            ..BodyContacts::default()
        }
    }

    #[test]
    fn summaries_keep_each_pair_apart_and_measure_a_hertz_zone() {
        // Body 0 touches body 1 along x with Hertz's elliptical pressure
        // over |y| ≤ a, sampled at 201 points, body 2 at one point far
        // away, body 3 without force and body 4, which has no law; their
        // contacts interleave in key order.
        let a = 0.2;
        let mut current = Vec::new();
        for k in 0..=200u32 {
            let y = a * (Real::from(k) / 100.0 - 1.0);
            let pressure = hertz_pressure(y, a);
            current.push(contact(
                2 * k,
                1,
                DVec2::new(pressure, 0.0),
                DVec2::new(1.0, y),
            ));
            if k == 100 {
                current.push(contact(
                    2 * k + 1,
                    2,
                    DVec2::new(0.0, -5.0),
                    DVec2::new(3.0, 4.0),
                ));
                // Touching without force, and with a body that has no law.
                current.push(contact(2 * k + 1, 3, DVec2::ZERO, DVec2::new(5.0, 5.0)));
                current.push(contact(2 * k + 1, 4, DVec2::new(9.0, 9.0), DVec2::ZERO));
            }
        }
        let contacts = contacts_between(&[(0, 1), (0, 2), (0, 3), (1, 2)], current);
        let mut tallies = Vec::new();
        // The bodies' initial places: moved, and stretched twofold across
        // the contact.
        contacts.summaries(
            |c| Some(DVec2::new(0.3 + 5.0 * c.at.x, 0.7 + 2.0 * c.at.y)),
            &mut tallies,
        );
        let [hertz, single, unloaded, none] = [0, 1, 2, 3].map(|k| tallies[k].summary());
        assert_eq!(hertz.contacts, 201);
        assert!(hertz.force.y == 0.0 && hertz.force.x > 0.0);
        // The extent: the outermost pairs at ±a, plus a disk radius.
        assert!((hertz.half_width - (a + 0.01)).abs() < 1e-12);
        // The second moment of the semi-ellipse is a²/4. Sampled at 201
        // points the estimate is −0.06% off (the sampling misses part of
        // the edges' square-root profile); 0.5% bounds that.
        assert!(
            (hertz.pressure_half_width / a - 1.0).abs() < 5e-3,
            "{}",
            hertz.pressure_half_width
        );
        assert!(
            (hertz.initial_pressure_half_width / hertz.pressure_half_width - 2.0).abs() < 1e-12
        );
        assert_eq!(
            (
                single.initial_pressure_half_width,
                unloaded.initial_pressure_half_width
            ),
            (0.0, 0.0)
        );
        assert_eq!(single.contacts, 1);
        assert_eq!(single.force, DVec2::new(0.0, -5.0));
        assert_eq!((single.half_width, single.pressure_half_width), (0.01, 0.0));
        // A touch without force: counted, its extent only, no pressure.
        assert_eq!(unloaded.contacts, 1);
        assert_eq!(unloaded.force, DVec2::ZERO);
        assert_eq!(
            (unloaded.half_width, unloaded.pressure_half_width),
            (0.01, 0.0)
        );
        assert_eq!(none, PairSummary::default());
        // Points whose body is gone have no initial place: left out.
        contacts.summaries(|_| None, &mut tallies);
        let hertz = tallies[0].summary();
        assert_eq!(hertz.initial_pressure_half_width, 0.0);
        assert!(hertz.pressure_half_width > 0.0);
    }

    #[test]
    fn both_zones_are_measured_across_a_turned_resultant() {
        // A Hertz zone across a resultant turned 0.5 rad from the axes, and
        // initial places that are the contact points stretched twofold
        // across it and moved. Measured across the resultant, both widths
        // are exact and their ratio is 2; along y either would be cos 0.5
        // = 0.88 of it.
        let (a, along) = (0.2, DVec2::from_angle(0.5));
        let across = along.perp();
        let current = (0..=200u32)
            .map(|k| {
                let s = a * (Real::from(k) / 100.0 - 1.0);
                contact(k, 1, along * hertz_pressure(s, a), DVec2::ONE + across * s)
            })
            .collect();
        let contacts = contacts_between(&[(0, 1)], current);
        let mut tallies = Vec::new();
        contacts.summaries(
            |c| Some(DVec2::new(0.3, 0.7) + across * 2.0 * (c.at - DVec2::ONE).dot(across)),
            &mut tallies,
        );
        let zone = tallies[0].summary();
        // 0.5%: the 201 samples' −0.06% (see the test above).
        assert!((zone.pressure_half_width / a - 1.0).abs() < 5e-3);
        assert!((zone.initial_pressure_half_width / zone.pressure_half_width - 2.0).abs() < 1e-9);
    }
}
