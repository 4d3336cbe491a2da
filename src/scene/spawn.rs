//! Turning a validated scene into a bevy `World`.

use super::contact_stability::{body_contact_stability_warnings, undamped_contact_warning};
use super::layout_warnings::{body_overlap_warnings, free_edge_warnings};
use super::step_warnings::off_step_warnings;
use super::{InitialStress, InitialVelocity, Scene, SceneError, SourceLocation, VelocityField};
use crate::components::{
    BlockId, BodyIndex, BodyName, DampedEnergy, GridLayer, Material, MaterialPoints, NewPoint,
    PartReactions, Pose, Reaction, RegionConstraint, RegionConstraints, RigidVelocity, StepTravel,
    TransferScratch,
};
use crate::math::{DVec2, Real, SymTensor};
use crate::resources::{
    BlockLog, BodyContacts, BodyPairLaw, BodyPairLog, BodyPairSample, Clock, Diagnostics,
    EnergyLog, EnergySample, Gravity, Grid, PairSummary, Probe, Probes, SharedLayers, StageLog,
    StagePlan, StageProgress,
};
use bevy_ecs::prelude::*;

/// Builds the world of a scene that passed [`Scene::validate`]: resources,
/// then one entity per body in scene order, then the step-0 probe, energy,
/// block and body-pair samples. Returns the world and warnings for the
/// user (e.g. a time step above the CFL limit).
pub fn spawn_scene(scene: &Scene) -> Result<(World, Vec<String>), SceneError> {
    let mut world = World::new();
    let grid = Grid {
        origin: scene.grid.origin,
        cell_size: scene.grid.cell_size,
        cells: [scene.grid.cells.0, scene.grid.cells.1],
        edges: scene.grid.edges,
    };
    let clock = Clock {
        step: 0,
        time: 0.0,
        dt: scene.time.dt,
        end: scene.time.end,
    };
    let mut warnings = Vec::new();
    let (bodies, body_warnings) = spawn_bodies(scene, &mut world, &grid)?;
    warnings.extend(body_warnings);
    warnings.extend(time_step_warnings(scene, &clock, &grid));
    let (block_warnings, absent_blocks) =
        super::spawn_blocks::spawn_blocks(scene, &mut world, &bodies)?;
    warnings.extend(block_warnings);
    let (mut probes, probe_warnings) = place_probes(scene, &world, &bodies);
    warnings.extend(probe_warnings);
    // Room for every sample of the run (the first, one per interval, and
    // one at the end when it falls between), so that recording never
    // allocates inside the step.
    let samples = (clock.total_steps() / probes.every + 2) as usize;
    probes.samples.reserve_exact(samples * probes.probes.len());
    probes.record(0.0, |e| world.get::<MaterialPoints>(e));
    let initial_energy = EnergySample::of(
        0.0,
        bodies
            .iter()
            .filter_map(|e| Some((world.get::<MaterialPoints>(*e)?, world.get::<Material>(*e)?))),
        scene.gravity,
        scene.settings.geometry,
        &mut Vec::new(),
    );
    world.insert_resource(grid);
    world.insert_resource(clock);
    world.insert_resource(scene.settings);
    world.insert_resource(scene.contact);
    world.insert_resource(crate::resources::BlockContactHistory::default());
    let mut block_log = BlockLog {
        names: scene.blocks.iter().map(|b| b.name.clone()).collect(),
        samples: Vec::with_capacity(samples * scene.blocks.len()),
        parts: Vec::with_capacity(
            samples
                * scene
                    .blocks
                    .iter()
                    .map(|b| match &b.shape {
                        crate::rigid::BlockShape::Compound { parts } => parts.len(),
                        _ => 0,
                    })
                    .sum::<usize>(),
        ),
    };
    record_blocks_at_the_start(&mut world, &mut block_log);
    world.insert_resource(block_log);
    world.insert_resource(Gravity(scene.gravity));
    world.insert_resource(Diagnostics::default());
    world.insert_resource(probes);
    let mut energy = EnergyLog {
        samples: Vec::with_capacity(samples),
    };
    energy.samples.push(initial_energy);
    world.insert_resource(energy);
    world.insert_resource(StageLog::default());
    let laws = body_pair_laws(scene);
    warnings.extend(layout_warnings(scene, &world, &bodies, &laws));
    warnings.extend(undamped_contact_warning(scene));
    // Room for every sample, as for the probes: recording never allocates.
    // The first, at the start, has no contacts yet.
    let mut pair_log = BodyPairLog {
        samples: Vec::with_capacity(samples * laws.len()),
    };
    pair_log.samples.extend(laws.iter().map(|l| BodyPairSample {
        time: 0.0,
        a: l.a,
        b: l.b,
        summary: PairSummary::default(),
    }));
    world.insert_resource(pair_log);
    let shared = share_layers(&mut world, &bodies, &scene.shared_layers());
    world.insert_resource(shared);
    world.insert_resource(BodyContacts {
        laws,
        ..Default::default()
    });
    world.insert_resource(crate::resources::ContactWork::default());
    world.insert_resource(crate::resources::LoadWork::default());
    if !scene.stages.is_empty() {
        let mut plan = StagePlan {
            stages: scene.stages.clone(),
            absent_blocks,
            bodies: Vec::new(),
            dynamic_blocks: Vec::new(),
            progress: StageProgress::default(),
        };
        warnings.extend(crate::systems::enter_stage(&mut world, &mut plan, 0));
        world.insert_resource(plan);
    }
    Ok((world, warnings))
}

/// Spawns one entity per body, in scene order, with its points, material,
/// layer and scratch; returns the entities and the warnings about them.
fn spawn_bodies(
    scene: &Scene,
    world: &mut World,
    grid: &Grid,
) -> Result<(Vec<Entity>, Vec<String>), SceneError> {
    let mut warnings = Vec::new();
    let mut bodies = Vec::with_capacity(scene.bodies.len());
    for (index, spec) in scene.bodies.iter().enumerate() {
        let invalid = |message: String| SceneError::Invalid {
            location: SourceLocation::default(),
            message,
        };
        let material = scene
            .materials
            .iter()
            .find(|m| m.name == spec.material)
            .ok_or_else(|| {
                invalid(format!(
                    "body '{}': unknown material '{}'",
                    spec.name, spec.material
                ))
            })?;
        let points = fill_body(scene, spec, material.density)
            .map_err(|e| invalid(format!("body '{}': {e}", spec.name)))?;
        let outside = points
            .stress
            .iter()
            .filter(|s| !material.model.admits(s))
            .count();
        if outside > 0 {
            warnings.push(format!(
                "body '{}': the initial stress of {outside} of its {} points lies outside the yield surface of material '{}' (a `k0` below its active or above its passive ratio?): the first step returns them to it, and energy.csv's balance misses part of that return's energy",
                spec.name,
                points.len(),
                material.name
            ));
        }
        let lightest = points.mass.iter().copied().fold(Real::INFINITY, Real::min);
        let entity = world
            .spawn((
                BodyName(spec.name.clone()),
                BodyIndex(index as u32),
                Material {
                    name: material.name.clone(),
                    density: material.density,
                    model: material.model.clone(),
                },
                points,
                GridLayer::new(grid.nodes(), 1e-9 * lightest),
                TransferScratch::default(),
                StepTravel::default(),
                DampedEnergy::default(),
                RegionConstraints(spec.constraints.clone()),
            ))
            .id();
        if let Some(acceleration) = spec.acceleration {
            world.entity_mut(entity).insert(acceleration);
        }
        bodies.push(entity);
    }
    Ok((bodies, warnings))
}

/// Warnings about the time step: off the end or an interval, and above a
/// material's CFL limit on this grid.
fn time_step_warnings(scene: &Scene, clock: &Clock, grid: &Grid) -> Vec<String> {
    let mut warnings = Vec::new();
    warnings.extend(off_step_warnings(scene, clock));
    for material in &scene.materials {
        let wave_speed = (material.model.as_model().p_wave_modulus() / material.density).sqrt();
        let limit = grid.cell_size / wave_speed;
        if clock.dt > limit {
            warnings.push(format!(
                "time.dt = {:e} s exceeds the CFL limit h / c = {limit:.4e} s of material '{}' (c = {wave_speed:.4e} m/s): the run will likely blow up",
                clock.dt, material.name
            ));
        }
    }
    warnings
}

/// The probes, each on the point of its body nearest where it is placed,
/// and warnings for those placed more than a cell from it.
fn place_probes(scene: &Scene, world: &World, bodies: &[Entity]) -> (Probes, Vec<String>) {
    let clock_end = scene.time.end;
    let mut warnings = Vec::new();
    let mut probes = Probes {
        probes: Vec::new(),
        every: scene.output.probe_every(clock_end, scene.time.dt),
        samples: Vec::new(),
    };
    for spec in &scene.probes {
        let Some(k) = scene.bodies.iter().position(|b| b.name == spec.body) else {
            continue;
        };
        let points = world
            .get::<MaterialPoints>(bodies[k])
            .map(|p| &p.position[..])
            .unwrap_or(&[]);
        let nearest = (0..points.len())
            .min_by(|&a, &b| {
                points[a]
                    .distance_squared(spec.at)
                    .total_cmp(&points[b].distance_squared(spec.at))
            })
            .unwrap_or(0);
        if let Some(x) = points.get(nearest)
            && x.distance(spec.at) > scene.grid.cell_size
        {
            warnings.push(format!(
                "probe '{}' at {} records the nearest point of body '{}', at {x}, {:.3e} m away (more than a cell): is `at` where you meant?",
                spec.name,
                spec.at,
                spec.body,
                x.distance(spec.at)
            ));
        }
        probes.probes.push(Probe {
            name: spec.name.clone(),
            body: bodies[k],
            point: nearest,
        });
    }
    (probes, warnings)
}

/// The contact law of every pair of bodies (a < b), expanded from the
/// scene's laws between bodies or groups, sorted by pair.
fn body_pair_laws(scene: &Scene) -> Vec<BodyPairLaw> {
    let mut laws: Vec<BodyPairLaw> = Vec::new();
    for spec in &scene.body_contacts {
        let members = |name: &str| scene.contact_members(name).unwrap_or_default();
        for i in members(&spec.between.0) {
            for j in members(&spec.between.1) {
                laws.push(BodyPairLaw {
                    a: i.min(j) as u32,
                    b: i.max(j) as u32,
                    law: spec.law,
                });
            }
        }
    }
    laws.sort_unstable_by_key(|l| (l.a, l.b));
    laws
}

/// Warnings about where the bodies start: on a free edge gravity does not
/// pull them off, overlapping under a contact law, and body contact springs
/// the time step cannot follow.
fn layout_warnings(
    scene: &Scene,
    world: &World,
    bodies: &[Entity],
    laws: &[BodyPairLaw],
) -> Vec<String> {
    let mut warnings = Vec::new();
    // Every body was spawned with its points just above.
    let placed: Option<Vec<(&str, &MaterialPoints)>> = scene
        .bodies
        .iter()
        .zip(bodies)
        .map(|(spec, &e)| Some((spec.name.as_str(), world.get::<MaterialPoints>(e)?)))
        .collect();
    if let Some(placed) = placed {
        // The edges and gravity the run starts with: the first stage's, if set.
        let first = scene.stages.first();
        let mut start = world.resource::<Grid>().clone();
        start.edges = first
            .and_then(|s| s.edges)
            .map_or(start.edges, |c| c.apply(start.edges));
        let gravity = first.and_then(|s| s.gravity).unwrap_or(scene.gravity);
        warnings.extend(free_edge_warnings(&start, gravity, &placed));
        warnings.extend(body_overlap_warnings(&placed, laws));
        warnings.extend(body_contact_stability_warnings(
            scene.time.dt,
            &placed,
            laws,
        ));
    }
    warnings
}

/// The points of one body: positions from the shape, then mass, velocity and
/// initial stress.
fn fill_body(
    scene: &Scene,
    spec: &super::BodySpec,
    density: Real,
) -> Result<MaterialPoints, String> {
    let h = scene.grid.cell_size;
    let spacing = h / spec.points_per_cell as Real;
    let velocity_at: Box<dyn Fn(DVec2) -> Result<DVec2, String>> = match &spec.velocity {
        InitialVelocity::Constant(v) => {
            let v = *v;
            Box::new(move |_| Ok(v))
        }
        InitialVelocity::Field { x, y } => {
            let field = VelocityField::parse(x, y)?;
            Box::new(move |p| field.at(p))
        }
    };
    let listed = spec
        .shape
        .points(scene.grid.origin, h, spec.points_per_cell);
    // The body's top: the outline's, or a point list's highest domain edge.
    let top = spec.shape.extent(spacing).1.y;
    let mut points = MaterialPoints::default();
    for point in &listed {
        let position = point.position;
        let (area, half_size) = point.domain(spacing);
        // Per metre in plane strain, per radian (A r) in axisymmetry.
        let volume = area * scene.settings.geometry.thickness(position);
        let velocity = velocity_at(position)?;
        let stress = match spec.initial_stress {
            Some(InitialStress::Geostatic { k0, surface }) => {
                let vertical = -density
                    * scene.gravity.y.abs()
                    * (surface.unwrap_or(top) - position.y).max(0.0);
                SymTensor::new(k0 * vertical, vertical, 0.0, k0 * vertical)
            }
            None => SymTensor::ZERO,
        };
        points.push(NewPoint {
            // Default: the disk reaches the sides of the point's domain
            // (half the spacing on the lattice).
            contact_radius: spec.contact_radius.unwrap_or(half_size.x),
            position,
            velocity,
            volume,
            mass: density * volume,
            half_size,
            stress,
        });
    }
    Ok(points)
}

/// The contact groups' bodies: each member's layer gets the region
/// constraints of the whole group and the group's smallest mass cutoff, so
/// the shared copies stay equal.
fn share_layers(world: &mut World, bodies: &[Entity], groups: &[Vec<usize>]) -> SharedLayers {
    let groups: Vec<Vec<Entity>> = groups
        .iter()
        .map(|g| g.iter().map(|&i| bodies[i]).collect())
        .collect();
    for group in &groups {
        let regions: Vec<RegionConstraint> = group
            .iter()
            .filter_map(|&e| world.get::<RegionConstraints>(e))
            .flat_map(|r| r.0.iter().copied())
            .collect();
        let cutoff = group
            .iter()
            .filter_map(|&e| world.get::<GridLayer>(e))
            .map(|l| l.mass_cutoff)
            .fold(Real::INFINITY, Real::min);
        for &member in group {
            let mut entity = world.entity_mut(member);
            entity.insert(RegionConstraints(regions.clone()));
            if let Some(mut layer) = entity.get_mut::<GridLayer>() {
                layer.mass_cutoff = cutoff;
            }
        }
    }
    SharedLayers {
        groups,
        ..SharedLayers::default()
    }
}

/// The blocks present at the start, as `record_blocks` samples them after
/// a step, in scene order: at t = 0, with no reaction yet.
fn record_blocks_at_the_start(world: &mut World, log: &mut BlockLog) {
    let mut query = world.query::<(&BlockId, &Reaction, &PartReactions, &Pose, &RigidVelocity)>();
    let mut blocks: Vec<_> = query.iter(world).collect();
    blocks.sort_unstable_by_key(|(id, ..)| id.index);
    for block in blocks {
        log.record(0.0, block);
    }
}
