//! The blocks' neighbour lists of a distributed run. A process lists only
//! its own points, by where it stores them: the lists follow the points
//! when they move between processes, and are gathered, by one-process
//! index, with the points on rank 0.

use super::{Domain, PointIds};
use crate::components::{
    BlockId, BodyIndex, NeighbourList, StepTravel, bodies_in_scene_order, sort_into_scene_order,
};
use crate::math::Real;
use bevy_ecs::prelude::*;

/// The blocks, in scene order.
fn blocks_in_scene_order(world: &mut World) -> Vec<Entity> {
    let mut order = Vec::new();
    let mut query = world.query::<(Entity, &BlockId)>();
    sort_into_scene_order(&mut order, query.iter(world).map(|(e, id)| (id.index, e)));
    order.into_iter().map(|(_, e)| e).collect()
}

/// Keeps, in every block's list, the entries of `body`'s points this
/// process stores, at their places in `kept` (one-process indices, in
/// order), as a process does when it takes its strip of the whole scene.
pub(crate) fn keep_listed(world: &mut World, body: Entity, kept: &[usize]) {
    let mut lists = world.query::<&mut NeighbourList>();
    for mut list in lists.iter_mut(world) {
        list.points.retain_mut(|(entity, p)| {
            if *entity != body {
                return true;
            }
            match kept.binary_search(&(*p as usize)) {
                Ok(k) => {
                    *p = k as u32;
                    true
                }
                Err(_) => false,
            }
        });
    }
}

/// Moves the entries of `body`'s points in every block's list from their
/// places among the ids `before` to their places among the ids `after`,
/// dropping the points that left, and lists the points that arrived in
/// every list: a list may hold more points than come near its block,
/// never fewer.
pub(crate) fn follow_moved_points(
    world: &mut World,
    body: Entity,
    before: &PointIds,
    after: &PointIds,
) {
    let arrived: Vec<u32> = after
        .0
        .iter()
        .enumerate()
        .filter(|(_, id)| before.0.binary_search(id).is_err())
        .map(|(k, _)| k as u32)
        .collect();
    let mut lists = world.query::<&mut NeighbourList>();
    for mut list in lists.iter_mut(world) {
        list.points.retain_mut(|(entity, p)| {
            if *entity != body {
                return true;
            }
            match after.0.binary_search(&before.0[*p as usize]) {
                Ok(k) => {
                    *p = k as u32;
                    true
                }
                Err(_) => false,
            }
        });
        list.points.extend(arrived.iter().map(|&p| (body, p)));
        list.points.sort_unstable();
    }
}

/// Every block's list, and each body's largest step, as one process holds
/// them: what a process sends rank 0.
type HeldLists = (Vec<Vec<(u32, u64)>>, Vec<Real>);

/// Each block's neighbour list and each body's largest step, by entity.
type Lists = (Vec<(Entity, NeighbourList)>, Vec<(Entity, StepTravel)>);

/// On rank 0, every block's list of every process's points by one-process
/// index, and each body's largest step over every process (the other
/// processes send theirs and get `None`). Every process calls it.
pub(crate) fn gather_lists(world: &mut World) -> Option<Lists> {
    let bodies = bodies_in_scene_order(world);
    let blocks = blocks_in_scene_order(world);
    if blocks.is_empty() {
        return None;
    }
    let index_of = |world: &World, body: Entity| world.get::<BodyIndex>(body).map(|i| i.0);
    let held: HeldLists = (
        blocks
            .iter()
            .map(|&block| {
                let list = world.get::<NeighbourList>(block).expect("a block's list");
                list.points
                    .iter()
                    .filter_map(|&(body, p)| {
                        let ids = world.get::<PointIds>(body)?;
                        Some((index_of(world, body)?, ids.0[p as usize]))
                    })
                    .collect()
            })
            .collect(),
        bodies
            .iter()
            .map(|&body| world.get::<StepTravel>(body).map_or(0.0, |t| t.0))
            .collect(),
    );
    let domain = world.non_send::<Domain>();
    if domain.rank() != 0 {
        let bytes = postcard::to_stdvec(&held).expect("lists encode");
        domain.transport().exchange(vec![(0, bytes)], &[]);
        return None;
    }
    let others: Vec<usize> = (1..domain.ranks()).collect();
    let (mut lists, mut travel) = held;
    for bytes in domain.transport().exchange(Vec::new(), &others) {
        let (their_lists, their_travel): HeldLists =
            postcard::from_bytes(&bytes).expect("lists decode");
        for (list, theirs) in lists.iter_mut().zip(their_lists) {
            list.extend(theirs);
        }
        for (step, theirs) in travel.iter_mut().zip(their_travel) {
            *step = step.max(theirs);
        }
    }
    let whole_lists = blocks
        .iter()
        .zip(lists)
        .map(|(&block, mut entries)| {
            entries.sort_unstable();
            let mut list = world
                .get::<NeighbourList>(block)
                .expect("a block's list")
                .clone();
            list.points = entries
                .into_iter()
                .map(|(body, id)| (bodies[body as usize], id as u32))
                .collect();
            (block, list)
        })
        .collect();
    let steps = bodies
        .iter()
        .zip(travel)
        .map(|(&body, step)| (body, StepTravel(step)))
        .collect();
    Some((whole_lists, steps))
}

/// Puts `lists` and `steps` in place, returning those they replace.
pub(crate) fn swap_lists(world: &mut World, (lists, steps): Lists) -> Lists {
    let lists = lists
        .into_iter()
        .map(|(block, list)| {
            let mut held = world
                .get_mut::<NeighbourList>(block)
                .expect("a block's list");
            (block, std::mem::replace(&mut *held, list))
        })
        .collect();
    let steps = steps
        .into_iter()
        .filter_map(|(body, step)| {
            let mut held = world.get_mut::<StepTravel>(body)?;
            Some((body, std::mem::replace(&mut *held, step)))
        })
        .collect();
    (lists, steps)
}
