//! The scene's stages: entering one (its changes to the setup) and ending
//! it (after its duration, or once the model has settled).

use crate::components::{
    BlockContacts, BlockId, BodyName, MaterialPoints, RigidMass, RigidMotion, RigidVelocity,
    bodies_in_scene_order, sort_into_scene_order,
};
use crate::math::{DVec2, Real};
use crate::resources::{
    AppliedLoad, Clock, ContactWork, Geometry, Gravity, Grid, Settings, StageEndReason, StageLog,
    StagePlan, StageRecord,
};
use crate::resources::{ContactSettings, Side, StageEnd};
use crate::rigid::{PlacementChecks, placement_warnings};
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;
use std::collections::BTreeMap;

/// After each step: ends the current stage when its duration has elapsed,
/// its settling condition holds (kinetic energy of the bodies and the
/// dynamic blocks down to `ratio` of the stage's peak, once something has
/// moved, or no stress component changed by `below` in the step, once some
/// step of the stage changed one by more) or
/// its `max_time` has passed (a warning), then enters the next stage; after
/// the last one the run ends (the clock's end is set to now). Reaching the
/// scene's `time.end` first ends the stage with a warning. Does nothing in a
/// scene without stages.
///
/// Reads and writes the whole world (exclusive): `StagePlan`, `StageLog`,
/// `Clock`, and on entry what the stage changes.
pub fn advance_stages(world: &mut World) {
    let Some(mut plan) = world.remove_resource::<StagePlan>() else {
        return;
    };
    if !plan.progress.finished {
        let reason = stage_end(world, &mut plan);
        if let Some(reason) = reason {
            finish_stage(world, &mut plan, reason);
        }
    }
    world.insert_resource(plan);
}

/// Why the current stage ends after this step, if it does.
fn stage_end(world: &mut World, plan: &mut StagePlan) -> Option<StageEndReason> {
    let clock = *world.resource::<Clock>();
    let elapsed = clock.time - plan.progress.started;
    let elapsed_enough = |t: Real| elapsed >= t - 0.5 * clock.dt;
    let bodies = &plan.bodies;
    let end = plan.stages[plan.progress.current].end.clone();
    let settled = match end {
        StageEnd::Duration(d) => {
            if elapsed_enough(d) {
                return Some(StageEndReason::Duration);
            }
            false
        }
        StageEnd::KineticEnergyRatio { ratio, .. } => {
            let kinetic = bodies
                .iter()
                .filter_map(|e| world.get::<MaterialPoints>(*e))
                .map(|p| {
                    p.mass
                        .iter()
                        .zip(&p.velocity)
                        .map(|(m, v)| 0.5 * m * v.length_squared())
                        .sum::<Real>()
                })
                .sum::<Real>()
                + dynamic_blocks_kinetic_energy(world, &plan.dynamic_blocks);
            plan.progress.peak_kinetic = plan.progress.peak_kinetic.max(kinetic);
            // Nothing has moved yet (a stage that starts at rest): the
            // model has not settled, it has not begun.
            plan.progress.peak_kinetic > 0.0 && kinetic <= ratio * plan.progress.peak_kinetic
        }
        StageEnd::StressChange { below, .. } => {
            let mut largest: Real = 0.0;
            for (k, e) in bodies.iter().enumerate() {
                let Some(points) = world.get::<MaterialPoints>(*e) else {
                    continue;
                };
                let previous = &mut plan.progress.previous_stress[k];
                for (old, new) in previous.iter_mut().zip(&points.stress) {
                    let (new_c, old_c) = (new.to_array(), old.to_array());
                    largest = new_c
                        .iter()
                        .zip(&old_c)
                        .fold(largest, |m, (a, b)| m.max((a - b).abs()));
                    *old = *new;
                }
            }
            let moved = plan.progress.peak_stress_change > below;
            plan.progress.peak_stress_change = plan.progress.peak_stress_change.max(largest);
            moved && largest <= below
        }
    };
    if settled {
        Some(StageEndReason::Condition)
    } else if elapsed_enough(end.max_time()) {
        Some(StageEndReason::MaxTime)
    } else if clock.finished() {
        Some(StageEndReason::SceneEnd)
    } else {
        None
    }
}

/// The kinetic energy of the dynamic blocks the plan lists, ½ m |v|² +
/// ½ I ω², summed in scene order (a resumed run spawns them in another
/// order). Kinematic blocks move as they are told: their motion is no sign
/// of the model settling, so the plan does not list them.
fn dynamic_blocks_kinetic_energy(world: &World, blocks: &[Entity]) -> Real {
    blocks
        .iter()
        .filter_map(|e| Some((world.get::<RigidMass>(*e)?, world.get::<RigidVelocity>(*e)?)))
        .map(|(mass, v)| {
            0.5 * mass.mass * v.linear.length_squared() + 0.5 * mass.inertia * v.angular * v.angular
        })
        .sum()
}

/// The dynamic blocks present in the world, in scene order.
pub fn dynamic_blocks_in_scene_order(world: &mut World) -> Vec<Entity> {
    let mut order = Vec::new();
    let mut query = world.query::<(Entity, &BlockId, &RigidMotion)>();
    sort_into_scene_order(
        &mut order,
        query
            .iter(world)
            .filter(|(_, _, motion)| **motion == RigidMotion::Dynamic)
            .map(|(e, id, _)| (id.index, e)),
    );
    order.into_iter().map(|(_, e)| e).collect()
}

/// Records the end of the current stage and enters the next, or ends the run.
fn finish_stage(world: &mut World, plan: &mut StagePlan, reason: StageEndReason) {
    let clock = *world.resource::<Clock>();
    let stage = &plan.stages[plan.progress.current];
    let mut log = world.resource_mut::<StageLog>();
    log.records.push(StageRecord {
        index: plan.progress.current,
        name: stage.name.clone(),
        start: plan.progress.started,
        end: clock.time,
        steps: ((clock.time - plan.progress.started) / clock.dt).round() as u64,
        reason,
    });
    match reason {
        StageEndReason::MaxTime => log.warnings.push(Warning::new(WarningKind::Stage, format!("stages[\"{}\"].end", stage.name), format!(
            "stage '{}' reached its max_time of {} s at t = {} s without meeting its end condition",
            stage.name,
            stage.end.max_time(),
            clock.time
        ))),
        StageEndReason::SceneEnd => {
            let later = plan.stages.len() - 1 - plan.progress.current;
            let rest = match later {
                0 => String::new(),
                1 => "; the stage after it was not run".into(),
                n => format!("; the {n} stages after it were not run"),
            };
            let cut = if clock.time > plan.progress.started {
                format!("during stage '{}': the stage was cut short", stage.name)
            } else {
                format!(
                    "as stage '{}' began: its changes were made, none of its steps run",
                    stage.name
                )
            };
            log.warnings.push(Warning::new(
                WarningKind::Stage,
                "time.end",
                format!("time.end = {} s came {cut}{rest}", clock.end),
            ));
        }
        StageEndReason::Duration | StageEndReason::Condition => {}
    }
    let next = plan.progress.current + 1;
    if reason != StageEndReason::SceneEnd && next < plan.stages.len() {
        let warnings = enter_stage(world, plan, next);
        world.resource_mut::<StageLog>().warnings.extend(warnings);
        // time.end on the boundary: the next stage has begun (as in a run
        // with a later end, which a resumed run then is) and is cut short.
        if clock.finished() {
            finish_stage(world, plan, StageEndReason::SceneEnd);
        }
    } else {
        plan.progress.finished = true;
        world.resource_mut::<Clock>().end = clock.time;
    }
}

/// Enters stage `index`: applies its changes to the world and starts its
/// clock. Returns warnings (e.g. an added block overlapping a body).
pub fn enter_stage(world: &mut World, plan: &mut StagePlan, index: usize) -> Vec<Warning> {
    let mut warnings = Vec::new();
    let spec = plan.stages[index].clone();
    {
        let mut settings = world.resource_mut::<Settings>();
        if let Some(beta) = spec.pic_fraction {
            settings.pic_fraction = beta;
        }
        if let Some(alpha) = spec.grid_damping {
            settings.grid_damping = alpha;
        }
        if let Some(alpha) = spec.particle_damping {
            settings.particle_damping = alpha;
        }
    }
    if let Some(g) = spec.gravity {
        world.resource_mut::<Gravity>().0 = g;
    }
    if let Some(changes) = spec.edges {
        let mut grid = world.resource_mut::<Grid>();
        grid.edges = changes.apply(grid.edges);
    }
    for name in &spec.remove_blocks {
        if let Some(entity) = block_named(world, name) {
            take_springs_along(world, entity);
            world.despawn(entity);
        }
    }
    let bodies = bodies_in_scene_order(world);
    let checks = PlacementChecks {
        dt: world.resource::<Clock>().dt,
        // The blocks' contact settings, or their defaults for a stage's
        // blocks without the rigid blocks' plugin.
        penetration: world
            .get_resource::<ContactSettings>()
            .map_or_else(|| ContactSettings::default().penetration, |c| c.penetration),
        geometry: world.resource::<Settings>().geometry,
    };
    for name in &spec.add_blocks {
        if let Some(template) = plan.absent_blocks.iter().find(|b| &b.id.name == name) {
            warnings.extend(placement_warnings(template, world, &bodies, checks));
            template.spawn(world);
        }
    }
    for change in &spec.block_velocities {
        if let Some(entity) = block_named(world, &change.block)
            && let Some(mut velocity) = world.get_mut::<RigidVelocity>(entity)
        {
            *velocity = change.velocity;
        }
    }
    for traction in &spec.tractions {
        let Some(body) = bodies.iter().copied().find(|e| {
            world
                .get::<BodyName>(*e)
                .is_some_and(|n| n.0 == traction.body)
        }) else {
            continue;
        };
        let Some(points) = world.get::<MaterialPoints>(body) else {
            continue;
        };
        // A new traction on a side replaces the one there.
        plan.progress
            .loads
            .retain(|l| !(l.body == body && l.side == traction.side));
        let forces: Vec<(u32, DVec2)> = side_points(points, traction.side)
            .into_iter()
            .map(|(p, width)| (p, traction.traction * width))
            .collect();
        // In axisymmetry a load acts on the ring at its edge's radius: a
        // side whose every loaded edge lies on the axis has no area.
        let geometry = world.resource::<Settings>().geometry;
        let on_axis = || {
            forces.iter().all(|&(p, _)| {
                let p = p as usize;
                geometry.thickness(points.position[p] - points.half_size[p]) <= 1e-12
            })
        };
        if geometry == Geometry::Axisymmetric && traction.side == Side::Left && on_axis() {
            warnings.push(Warning::new(WarningKind::Stage, format!("stages[\"{}\"].tractions", spec.name), format!(
                "stage '{}': the Left side of body '{}' lies on the axis, where it has no area: its traction loads nothing",
                spec.name, traction.body
            )));
        }
        plan.progress.loads.push(AppliedLoad {
            body,
            side: traction.side,
            forces,
        });
    }
    let time = world.resource::<Clock>().time;
    plan.progress.current = index;
    plan.progress.started = time;
    plan.progress.peak_kinetic = 0.0;
    plan.progress.peak_stress_change = 0.0;
    plan.progress.previous_stress = match spec.end {
        StageEnd::StressChange { .. } => bodies
            .iter()
            .map(|e| {
                world
                    .get::<MaterialPoints>(*e)
                    .map_or_else(Vec::new, |p| p.stress.clone())
            })
            .collect(),
        _ => Vec::new(),
    };
    plan.bodies = bodies;
    plan.dynamic_blocks = dynamic_blocks_in_scene_order(world);
    warnings
}

/// The outermost points of a body on `side`, with the width of surface
/// each carries, in point order.
///
/// The side is cut into strips (columns for `Top` and `Bottom`, rows for
/// `Left` and `Right`) from the body's first domain edge, as wide as its
/// narrowest point domain, or a sixteenth of its widest if that is wider
/// (so a sliver point cannot cut the side into millions of strips). Each
/// strip goes to the outermost point (highest for `Top`, lowest for
/// `Bottom`, rightmost for `Right`, leftmost for `Left`, by initial
/// position) whose domain holds the strip's centre, and a point carries the
/// width of the strips it gets. A body filled on the lattice has one strip
/// per lattice column (row), held by that column's points alone; a point
/// list's wider domains hold several strips, so every strip of its side is
/// loaded once whatever the points' sizes. Strips start at a domain edge so
/// that domains tiling a lattice never have a strip centre on their edges.
pub fn side_points(points: &MaterialPoints, side: Side) -> Vec<(u32, Real)> {
    let across_side = |half: DVec2| match side {
        Side::Top | Side::Bottom => half.x,
        Side::Left | Side::Right => half.y,
    };
    let along_side = |x: DVec2| match side {
        Side::Top | Side::Bottom => x.x,
        Side::Left | Side::Right => x.y,
    };
    let (mut narrowest, mut widest, mut start) = (Real::INFINITY, 0.0, Real::INFINITY);
    for (x, half) in points.initial_position.iter().zip(&points.half_size) {
        let half = across_side(*half);
        narrowest = narrowest.min(2.0 * half);
        widest = Real::max(widest, 2.0 * half);
        start = start.min(along_side(*x) - half);
    }
    let strip = narrowest.max(widest / 16.0);
    let mut outermost: BTreeMap<i64, (u32, Real)> = BTreeMap::new();
    for (p, (x, half)) in points
        .initial_position
        .iter()
        .zip(&points.half_size)
        .enumerate()
    {
        let (along, half) = (along_side(*x) - start, across_side(*half));
        let outward = match side {
            Side::Top => x.y,
            Side::Bottom => -x.y,
            Side::Right => x.x,
            Side::Left => -x.x,
        };
        // Strip k's centre is at (k + 1/2) strip from the start: the strips
        // whose centre lies inside [along - half, along + half].
        let first = ((along - half) / strip - 0.5).ceil() as i64;
        let last = ((along + half) / strip - 0.5).floor() as i64;
        for k in first..=last {
            let entry = outermost.entry(k).or_insert((p as u32, outward));
            if outward > entry.1 {
                *entry = (p as u32, outward);
            }
        }
    }
    let mut strips_of: BTreeMap<u32, u32> = BTreeMap::new();
    for (p, _) in outermost.into_values() {
        *strips_of.entry(p).or_insert(0) += 1;
    }
    strips_of
        .into_iter()
        .map(|(p, count)| (p, Real::from(count) * strip))
        .collect()
}

/// Books the energy in the springs of a block about to be removed as taken
/// by the block (`ContactWork::block_work`), so that `energy.csv`'s balance
/// does not jump when its contacts vanish: the springs' whole energy as
/// the block's negative work, and their tangential part back out of the
/// tangential work, where `dissipated` would otherwise count it as released.
fn take_springs_along(world: &mut World, block: Entity) {
    let Some(contacts) = world.get::<BlockContacts>(block) else {
        return;
    };
    let (whole, tangential) = contacts.current.iter().fold((0.0, 0.0), |(w, t), c| {
        (w + c.potential, t + c.tangential_potential)
    });
    if let Some(mut work) = world.get_resource_mut::<ContactWork>() {
        work.block_work -= whole;
        work.tangential_work += tangential;
    }
}

fn block_named(world: &mut World, name: &str) -> Option<Entity> {
    let mut query = world.query::<(Entity, &BlockId)>();
    query
        .iter(world)
        .find(|(_, id)| id.name == name)
        .map(|(e, _)| e)
}
