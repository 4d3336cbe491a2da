//! A numerical failure on one process ends the step on every process, with
//! the same message: each step's diagnostics gather what each process
//! found, and all report the failure of the lowest rank that found one.

use super::{Domain, PointIds};
use crate::components::BodyName;
use crate::math::Real;
use crate::resources::{Diagnostics, FailureSite, NumericalFailure};
use bevy_ecs::prelude::*;
use serde::{Deserialize, Serialize};

/// A failure as it travels: a point named by its id.
#[derive(Serialize, Deserialize)]
struct Found {
    step: u64,
    time: Real,
    site: Site,
    field: String,
    detail: String,
}

#[derive(Serialize, Deserialize)]
enum Site {
    Point { body: String, id: u64 },
    Block(String),
    Record(String),
}

/// Gathers every process's failure of this step, if any, and makes the
/// lowest rank's the failure of every process.
pub(crate) fn agree_on_failures(world: &mut World) {
    let failure = world.resource::<Diagnostics>().failure.clone();
    let found = failure.as_ref().map(|f| Found {
        step: f.step,
        time: f.time,
        site: match &f.at {
            FailureSite::Point { body, point } => Site::Point {
                body: body.clone(),
                id: point_id(world, body, *point),
            },
            FailureSite::Block(name) => Site::Block(name.clone()),
            FailureSite::Record(file) => Site::Record((*file).to_owned()),
        },
        field: f.field.to_owned(),
        detail: f.detail.clone(),
    });
    let domain = world.non_send::<Domain>();
    let ranks = domain.ranks();
    let bytes = postcard::to_stdvec(&found).expect("a failure encodes");
    let first = domain
        .transport()
        .all_gather(bytes)
        .iter()
        .enumerate()
        .find_map(|(rank, b)| {
            let found: Option<Found> = postcard::from_bytes(b).expect("a failure decodes");
            found.map(|f| (rank, f))
        });
    let Some((rank, f)) = first else {
        return;
    };
    // The failure's names are static in one process; one that came from
    // another is kept for the rest of the run, which it ends.
    let leak = |s: String| -> &'static str { Box::leak(s.into_boxed_str()) };
    let failure = NumericalFailure {
        step: f.step,
        time: f.time,
        at: match f.site {
            Site::Point { body, id } => FailureSite::Point {
                body,
                point: id as usize,
            },
            Site::Block(name) => FailureSite::Block(name),
            Site::Record(file) => FailureSite::Record(leak(file)),
        },
        field: leak(f.field),
        detail: format!("{} (found by rank {rank} of {ranks})", f.detail),
    };
    world.resource_mut::<Diagnostics>().failure = Some(failure);
}

/// The one-process index of point `point` of the body named `body`.
fn point_id(world: &mut World, body: &str, point: usize) -> u64 {
    let mut bodies = world.query::<(&BodyName, &PointIds)>();
    bodies
        .iter(world)
        .find(|(name, _)| name.0 == body)
        .and_then(|(_, ids)| ids.0.get(point).copied())
        .unwrap_or(point as u64)
}
