//! Algorithm 1, lines 5–8: the neighbour lists of the rigid blocks.

use crate::components::{
    BodyIndex, MaterialPoints, NeighbourList, Pose, RigidShape, RigidVelocity, StepTravel,
    sort_into_scene_order,
};
use crate::distributed::{Domain, largest};
use crate::math::{DVec2, Real};
use crate::resources::{Clock, ContactSettings, Grid};
use bevy_ecs::prelude::*;

/// Rebuilds a block's list of nearby points every `iter_period` steps, or
/// earlier when the points and the block together could have moved by the
/// margin since the last rebuild (the travel guard; counted in
/// `NeighbourList::early_rebuilds`). A point's share of the travel is the
/// largest actual step of any point (`StepTravel`, from the last update),
/// the block's is its speed bound |v| + |ω| × (AABB diagonal) times Δt. Listed are the points whose disk
/// reaches the block's bounding box grown by the margin, bodies in scene
/// order, points in order.
///
/// In a distributed run a process lists its own points, by where it
/// stores them, and the largest step is every process's: the lists are
/// rebuilt at the same steps on every process.
///
/// Reads: `Clock`, `Grid`, `ContactSettings`, `MaterialPoints`, `StepTravel`, block pose,
/// velocity and shape. Writes: `NeighbourList`.
#[allow(clippy::too_many_arguments)] // the distributed run's domain is one more
pub fn rebuild_neighbour_lists(
    clock: Res<Clock>,
    grid: Res<Grid>,
    settings: Res<ContactSettings>,
    mut order: Local<Vec<(BodyIndex, Entity)>>,
    bodies: Query<(Entity, &BodyIndex, &MaterialPoints, &StepTravel)>,
    mut blocks: Query<(&RigidShape, &Pose, &RigidVelocity, &mut NeighbourList)>,
    domain: Option<NonSend<Domain>>,
) {
    if blocks.is_empty() {
        return;
    }
    sort_into_scene_order(&mut order, bodies.iter().map(|(e, i, _, _)| (*i, e)));
    let mut point_step = bodies
        .iter()
        .map(|(_, _, _, travel)| travel.0)
        .fold(0.0, Real::max);
    if let Some(domain) = domain {
        point_step = largest(&domain, point_step);
    }
    let margin = settings.margin_or(grid.cell_size);
    for (shape, pose, velocity, mut list) in &mut blocks {
        let aabb = shape.0.compute_aabb(&pose.to_parry());
        let reach = (aabb.maxs - aabb.mins).length();
        let block_speed = velocity.linear.length() + velocity.angular.abs() * reach;
        list.travel += point_step + block_speed * clock.dt;
        // Age 0: never built (a new block).
        let due = list.age == 0 || list.age >= settings.period();
        let unsafe_travel = list.travel >= margin;
        if !(due || unsafe_travel) {
            list.age += 1;
            continue;
        }
        if unsafe_travel && !due {
            list.early_rebuilds += 1;
        }
        let (lo, hi) = (
            aabb.mins - DVec2::splat(margin),
            aabb.maxs + DVec2::splat(margin),
        );
        list.points.clear();
        for (_, entity) in order.iter() {
            let Ok((_, _, points, _)) = bodies.get(*entity) else {
                continue;
            };
            for (p, (x, r)) in points
                .position
                .iter()
                .zip(&points.contact_radius)
                .enumerate()
            {
                if x.cmpge(lo - *r).all() && x.cmple(hi + *r).all() {
                    list.points.push((*entity, p as u32));
                }
            }
        }
        list.age = 1;
        list.travel = 0.0;
    }
}
