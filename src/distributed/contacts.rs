//! The point–block contacts of a distributed run. Each process finds the
//! contacts of its own points; every process then takes all of them, so
//! that each sums the blocks' reactions, and adds the contact forces to
//! the nodes it shares, in the one-process order, and keeps every
//! contact's tangential spring for the next step whichever process holds
//! its point then.

use super::{Domain, PointIds};
use crate::components::PointContact;
use crate::math::{DVec2, Real};
use bevy_ecs::prelude::*;
use serde::{Deserialize, Serialize};

/// A contact as the processes share it: its block's index in the scene,
/// the contact (its point named by its one-process index), and the point's
/// domain half-size, which places its force on the nodes.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub(crate) struct SharedContact {
    /// The block's index in the scene.
    pub block: u32,
    /// The body's index in the scene.
    pub body: u32,
    /// The contact.
    pub contact: PointContact,
    /// The point's domain half-size (m).
    pub half_size: DVec2,
}

/// The contacts of this step found on every process, by block, then body,
/// then point: the order one process finds them in. This process's
/// `found` are sent to every other.
pub(crate) fn share_contacts(domain: &Domain, found: &[SharedContact]) -> Vec<SharedContact> {
    let bytes = postcard::to_stdvec(found).expect("contacts encode");
    let mut all: Vec<SharedContact> = domain
        .transport()
        .all_gather(bytes)
        .iter()
        .flat_map(|b| postcard::from_bytes::<Vec<SharedContact>>(b).expect("contacts decode"))
        .collect();
    all.sort_unstable_by_key(|c| (c.block, c.body, c.contact.point));
    all
}

/// The half-sizes of the points of this step's contacts, by block, body
/// entity and point, for the contacts whose point another process holds.
#[derive(Resource, Debug, Default)]
pub(crate) struct ContactHalfSizes(pub Vec<((u32, Entity, u32), DVec2)>);

impl ContactHalfSizes {
    /// The half-size of the point of `contact` of block `block`.
    pub fn of(&self, block: u32, contact: &PointContact) -> Option<DVec2> {
        let key = (block, contact.body, contact.point);
        let k = self.0.binary_search_by_key(&key, |e| e.0).ok()?;
        Some(self.0[k].1)
    }
}

/// Where this process stores the point with one-process index `point`:
/// that index on one process (`ids` is `None`), else its place among the
/// ids this process holds, if it holds the point.
pub(crate) fn local_index(ids: Option<&PointIds>, point: u32) -> Option<usize> {
    match ids {
        None => Some(point as usize),
        Some(ids) => ids.0.binary_search(&u64::from(point)).ok(),
    }
}

/// Sums, on every process, terms that each process computes for some of
/// the items of one sequence: `held` gives each term with its place in
/// the sequence; the terms are added to `start` in that order.
pub(crate) fn add_in_order(
    domain: &Domain,
    held: &[(u64, [Real; 2])],
    start: [Real; 2],
) -> [Real; 2] {
    let bytes = postcard::to_stdvec(held).expect("terms encode");
    let mut all: Vec<(u64, [Real; 2])> = domain
        .transport()
        .all_gather(bytes)
        .iter()
        .flat_map(|b| postcard::from_bytes::<Vec<(u64, [Real; 2])>>(b).expect("terms decode"))
        .collect();
    all.sort_unstable_by_key(|t| t.0);
    all.iter().fold(start, |[a, b], (_, [s, t])| [a + s, b + t])
}

/// The largest of every process's `value`.
pub(crate) fn largest(domain: &Domain, value: Real) -> Real {
    domain
        .transport()
        .all_gather(value.to_le_bytes().to_vec())
        .iter()
        .map(|b| Real::from_le_bytes(b[..].try_into().expect("8 bytes")))
        .fold(value, Real::max)
}
