//! Points between processes: the ids that give them their one-process
//! order, the first sharing out, the migration at the start of every step,
//! and the gathering of every point on rank 0.

use super::lists::{follow_moved_points, gather_lists, keep_listed, swap_lists};
use super::{Domain, Strips, Transport};
use crate::Simulation;
use crate::components::{MaterialPoints, bodies_in_scene_order};
use crate::resources::{Clock, Grid};
use crate::shape_functions::StencilGrid;
use crate::systems::{DiagnosticsStep, MpmSystems};
use bevy_ecs::prelude::*;

/// Steps between two rebalancings of the strips: the points' counts per
/// tile column are gathered, and strips cut anew if they have changed.
pub const REBALANCE_EVERY: u64 = 64;

/// The index of every point of a body in the one-process run, in the order
/// the points are stored: each process stores its points in the order of
/// their ids, as one process stores them all.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct PointIds(pub Vec<u64>);

/// Makes `sim`, built from the whole scene on every process, this process's
/// part of a distributed run over `transport`: the grid is cut into strips
/// of tile columns balanced by point count, the process keeps the points of
/// its strip, and every step starts by moving the points that left it.
/// A scene with parts the distributed step does not yet cover is refused
/// ([`DistributeError::Unsupported`]), the same on every process.
pub fn attach(sim: &mut Simulation, transport: Box<dyn Transport>) -> Result<(), DistributeError> {
    let unsupported = unsupported_parts(sim.scene());
    if !unsupported.is_empty() {
        return Err(DistributeError::Unsupported(unsupported));
    }
    let world = sim.world_mut();
    let grid = world.resource::<Grid>().stencil_grid();
    let bodies = bodies_in_scene_order(world);
    let columns = |points: &MaterialPoints| -> Vec<u32> {
        points
            .position
            .iter()
            .map(|x| Strips::column_of(grid.base_column(x.x)))
            .collect()
    };
    let mut counts = vec![0u64; grid_columns(&grid) as usize];
    for &body in &bodies {
        if let Some(points) = world.get::<MaterialPoints>(body) {
            for column in columns(points) {
                counts[column as usize] += 1;
            }
        }
    }
    let strips = Strips::balanced(&counts, transport.ranks());
    let rank = transport.rank();
    for &body in &bodies {
        let Some(points) = world.get::<MaterialPoints>(body) else {
            continue;
        };
        let own: Vec<usize> = columns(points)
            .iter()
            .enumerate()
            .filter(|(_, c)| strips.owner(**c) == rank)
            .map(|(p, _)| p)
            .collect();
        let kept = points.select(&own);
        let ids = PointIds(own.iter().map(|&p| p as u64).collect());
        world.entity_mut(body).insert((kept, ids));
        keep_listed(world, body, &own);
    }
    world.insert_non_send(Domain::new(transport, strips, grid_columns(&grid)));
    world.init_resource::<super::ContactHalfSizes>();
    sim.add_systems((
        migrate_points
            .in_set(MpmSystems::GridReset)
            .before(crate::systems::reset_grid_layers),
        // Before the loose points' check, which every process makes only
        // after a step none failed.
        super::failures::agree_on_failures
            .in_set(DiagnosticsStep::CheckFinite)
            .after(crate::systems::check_finite)
            .before(crate::systems::check_loose_points),
    ))?;
    Ok(())
}

/// Why a simulation cannot be made part of a distributed run.
#[derive(Debug, thiserror::Error)]
pub enum DistributeError {
    /// The scene has parts whose steps read or write points of other
    /// processes, which the distributed step does not yet exchange.
    #[error(
        "a distributed run does not yet cover {}: run this scene on one process",
        .0.join(", ")
    )]
    Unsupported(Vec<&'static str>),
    /// The distributed step's systems could not be added.
    #[error(transparent)]
    Systems(#[from] crate::StepError),
}

/// The parts of `scene` the distributed step does not yet cover: body
/// contacts pair points of different processes, and stages keep lists of
/// points.
pub fn unsupported_parts(scene: &crate::scene::Scene) -> Vec<&'static str> {
    [
        (!scene.body_contacts.is_empty(), "body contacts"),
        (!scene.stages.is_empty(), "stages"),
    ]
    .into_iter()
    .filter_map(|(found, part)| found.then_some(part))
    .collect()
}

/// The tile columns of the grid's base nodes.
fn grid_columns(grid: &StencilGrid) -> u32 {
    grid.nodes[0].div_ceil(crate::scatter::TILE_CELLS[0]) as u32
}

/// A body's points to send: their ids and every column.
type Parcel = (Vec<u64>, MaterialPoints);

/// Sends every point whose stencil's base node has left this process's
/// strip to the process that owns it now, and takes the points that came
/// in, keeping the order of ids. Every [`REBALANCE_EVERY`] steps the strips
/// are first cut anew from the points' counts.
fn migrate_points(world: &mut World) {
    let grid = world.resource::<Grid>().stencil_grid();
    let step = world.resource::<Clock>().step;
    let bodies = bodies_in_scene_order(world);
    let column_of = |x: f64| Strips::column_of(grid.base_column(x));
    // Whether the strips were cut anew: then points may go to any rank.
    let mut recut = false;
    if step > 0 && step.is_multiple_of(REBALANCE_EVERY) {
        let mut counts = vec![0u64; grid_columns(&grid) as usize];
        for &body in &bodies {
            if let Some(points) = world.get::<MaterialPoints>(body) {
                for x in &points.position {
                    counts[column_of(x.x) as usize] += 1;
                }
            }
        }
        let domain = world.non_send::<Domain>();
        let bytes = counts.iter().flat_map(|c| c.to_le_bytes()).collect();
        let mut total = vec![0u64; counts.len()];
        for part in domain.transport().all_gather(bytes) {
            for (sum, c) in total.iter_mut().zip(part.chunks_exact(8)) {
                *sum += u64::from_le_bytes(c.try_into().expect("8 bytes"));
            }
        }
        let strips = Strips::balanced(&total, domain.ranks());
        if strips != domain.strips {
            recut = true;
            world.non_send_mut::<Domain>().strips = strips;
        }
    }
    for body in bodies {
        let domain = world.non_send::<Domain>();
        let (rank, ranks) = (domain.rank(), domain.ranks());
        let (Some(points), Some(ids)) = (
            world.get::<MaterialPoints>(body),
            world.get::<PointIds>(body),
        ) else {
            continue;
        };
        // Between cuts a point moves less than a cell a step, so it leaves
        // only for a neighbour: only neighbours exchange. One that jumped
        // further (a step far past its time-step limit) goes to the
        // neighbour on its side, which passes it on.
        let neighbours = domain.neighbours();
        let others: Vec<usize> = if recut {
            (0..ranks).filter(|&r| r != rank).collect()
        } else {
            neighbours.iter().map(|(r, _)| *r).collect()
        };
        let strip = domain.strips.columns(rank);
        let toward = |column: u32| {
            let side = if column < strip.start {
                0
            } else {
                neighbours.len() - 1
            };
            neighbours[side].0
        };
        let mut going: Vec<Vec<usize>> = vec![Vec::new(); ranks];
        for (p, x) in points.position.iter().enumerate() {
            let column = column_of(x.x);
            let owner = domain.strips.owner(column);
            let to = if owner == rank || others.contains(&owner) {
                owner
            } else {
                toward(column)
            };
            going[to].push(p);
        }
        let parcel = |indices: &[usize]| -> Parcel {
            (
                indices.iter().map(|&p| ids.0[p]).collect(),
                points.select(indices),
            )
        };
        let messages = others
            .iter()
            .map(|&r| {
                let bytes = postcard::to_stdvec(&parcel(&going[r])).expect("points encode");
                (r, bytes)
            })
            .collect();
        let staying = going[rank].len() == points.len();
        let arrived: Vec<Parcel> = domain
            .transport()
            .exchange(messages, &others)
            .iter()
            .map(|bytes| postcard::from_bytes(bytes).expect("points decode"))
            .collect();
        if staying && arrived.iter().all(|(ids, _)| ids.is_empty()) {
            continue;
        }
        let (after, points) = in_id_order(parcel(&going[rank]), arrived);
        let before = std::mem::replace(
            &mut *world.get_mut::<PointIds>(body).expect("a body's ids"),
            after.clone(),
        );
        world.entity_mut(body).insert(points);
        follow_moved_points(world, body, &before, &after);
    }
}

/// The points of `first` and `more` together, in the order of their ids.
fn in_id_order(
    first: Parcel,
    more: impl IntoIterator<Item = Parcel>,
) -> (PointIds, MaterialPoints) {
    let (mut all_ids, mut all) = first;
    for (ids, points) in more {
        all_ids.extend(ids);
        all.append(&points);
    }
    let mut order: Vec<usize> = (0..all_ids.len()).collect();
    order.sort_unstable_by_key(|&k| all_ids[k]);
    let ids = PointIds(order.iter().map(|&k| all_ids[k]).collect());
    (ids, all.select(&order))
}

/// Runs `f` on rank 0 with every process's points in its bodies, in their
/// one-process order (the other ranks send theirs and get `None`); without
/// a domain, runs `f` on the simulation as it is. Every process calls it
/// at the same point of the run.
pub fn with_all_points<R>(sim: &mut Simulation, f: impl FnOnce(&mut Simulation) -> R) -> Option<R> {
    let world = sim.world_mut();
    if world.get_non_send::<Domain>().is_none() {
        return Some(f(sim));
    }
    let bodies = bodies_in_scene_order(world);
    let mut gathered = Vec::new();
    for &body in &bodies {
        let domain = world.non_send::<Domain>();
        let (Some(points), Some(ids)) = (
            world.get::<MaterialPoints>(body),
            world.get::<PointIds>(body),
        ) else {
            continue;
        };
        if domain.rank() != 0 {
            let bytes = postcard::to_stdvec(&(&ids.0, points)).expect("points encode");
            domain.transport().exchange(vec![(0, bytes)], &[]);
            continue;
        }
        let others: Vec<usize> = (1..domain.ranks()).collect();
        let arrived = domain
            .transport()
            .exchange(Vec::new(), &others)
            .iter()
            .map(|bytes| postcard::from_bytes::<Parcel>(bytes).expect("points decode"))
            .collect::<Vec<_>>();
        let (_, whole) = in_id_order((ids.0.clone(), points.clone()), arrived);
        let own = std::mem::replace(
            &mut *world
                .get_mut::<MaterialPoints>(body)
                .expect("a body's points"),
            whole,
        );
        gathered.push((body, own));
    }
    let lists = gather_lists(world);
    if world.non_send::<Domain>().rank() != 0 {
        return None;
    }
    let own_lists = lists.map(|lists| swap_lists(sim.world_mut(), lists));
    let result = f(sim);
    let world = sim.world_mut();
    for (body, own) in gathered {
        *world
            .get_mut::<MaterialPoints>(body)
            .expect("a body's points") = own;
    }
    if let Some(own_lists) = own_lists {
        swap_lists(world, own_lists);
    }
    Some(result)
}
