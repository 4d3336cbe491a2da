//! The material point method itself: the grid, the clock, the settings and
//! gravity; grid reset, boundary conditions, particle-to-grid, stress
//! update, nodal solve, grid-to-particle, the finiteness check and the
//! clock.

use super::{MpmPlugin, PluginSetup, placed_bodies};
use crate::checkpoint::Checkpointed;
use crate::components::{
    GridLayer, MaterialPoints, RegionConstraint, RegionConstraints, bodies_in_scene_order,
};
use crate::math::Real;
use crate::resources::{
    Clock, ContactWork, Diagnostics, EdgeConditions, Gravity, Grid, Sampling, Settings,
    SharedLayers, UpdateScheme,
};
use crate::scene::{
    Scene, SceneError, empty_region_warnings, free_edge_warnings, granular_transfer_warning,
    off_step_warnings, undamped_contact_warning,
};
use crate::systems::{
    ContactTransferStep, DiagnosticsStep, MpmSystems, account_contact_work, advance_clock,
    check_finite, check_loose_points, grid_to_particle, particle_to_grid, rebuild_node_constraints,
    reset_grid_layers, solve_nodal_momentum, transfer_contact_forces, update_stress,
};
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;

/// The core of the step (Algorithm 1 without its contacts).
pub struct CorePlugin;

impl MpmPlugin for CorePlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        let scene = setup.scene;
        let grid = scene.grid.grid();
        let clock = Clock {
            step: 0,
            time: 0.0,
            dt: scene.time.dt,
            end: scene.time.end,
        };
        setup.warn_all(time_step_warnings(scene, &clock, &grid));
        let bodies = bodies_in_scene_order(setup.world);
        let points = bodies
            .iter()
            .filter_map(|&b| setup.world.get::<MaterialPoints>(b))
            .map(MaterialPoints::len)
            .sum();
        setup.warn_all(frame_count_warning(scene, &clock, points));
        setup.warn_all(free_edge_warnings_at_the_start(
            scene,
            setup.world,
            &bodies,
            &grid,
        ));
        setup.warn_all(empty_region_warnings(scene));
        setup.warn_all(undamped_contact_warning(scene));
        setup.warn_all(granular_transfer_warning(scene));
        let shared = share_layers(setup.world, &bodies, &scene.shared_layers());
        let world = &mut *setup.world;
        world.insert_resource(grid);
        world.insert_resource(clock);
        world.insert_resource(scene.settings);
        world.insert_resource(Gravity(scene.gravity));
        // How contact forces reach the points, which the transfer reads,
        // and the work they do, for the energy balance: of the blocks' and
        // the bodies' contacts alike.
        world.insert_resource(scene.contact);
        world.insert_resource(ContactWork::default());
        world.insert_resource(Diagnostics::default());
        world.insert_resource(Sampling {
            every: scene.output.probe_every(scene.time.end, scene.time.dt),
        });
        world.insert_resource(shared);
        // Stages change the settings, gravity and the grid's edges.
        setup.keep_resource::<Settings>("settings");
        setup.keep_resource::<Gravity>("gravity");
        setup.keep_resource::<ContactWork>("contact work");
        setup.keep_checkpointed::<Grid>("grid edges");
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, scheme: UpdateScheme) {
        schedule.add_systems((
            reset_grid_layers.in_set(MpmSystems::GridReset),
            rebuild_node_constraints.in_set(MpmSystems::Boundary),
            particle_to_grid.in_set(MpmSystems::ParticleToGrid),
            update_stress(scheme).in_set(MpmSystems::StressUpdate),
            solve_nodal_momentum.in_set(MpmSystems::NodalSolve),
            grid_to_particle.in_set(MpmSystems::GridToParticle),
            // The contacts' forces reach the nodes, and their work is
            // counted, whichever plugins found them (blocks, bodies).
            transfer_contact_forces.in_set(ContactTransferStep::Forces),
            account_contact_work.in_set(DiagnosticsStep::ContactWork),
            check_finite.in_set(DiagnosticsStep::CheckFinite),
            check_loose_points
                .in_set(DiagnosticsStep::CheckFinite)
                .after(check_finite),
            advance_clock.in_set(DiagnosticsStep::Clock),
        ));
    }
}

impl Checkpointed for Grid {
    type Stored = EdgeConditions;

    fn stored(&self) -> EdgeConditions {
        self.edges
    }

    fn restore(&mut self, edges: EdgeConditions) {
        self.edges = edges;
    }
}

/// Warnings about the time step: off the end or an interval, and above a
/// material's CFL limit on this grid.
fn time_step_warnings(scene: &Scene, clock: &Clock, grid: &Grid) -> Vec<Warning> {
    let mut warnings = off_step_warnings(scene, clock);
    for material in &scene.materials {
        let wave_speed = (material.model.as_model().p_wave_modulus() / material.density).sqrt();
        let limit = grid.cell_size / wave_speed;
        if clock.dt > limit {
            warnings.push(Warning::new(WarningKind::TimeStep, "time.dt", format!(
                "time.dt = {:e} s exceeds the CFL limit h / c = {limit:.4e} s of material '{}' (c = {wave_speed:.4e} m/s): the run will likely blow up",
                clock.dt, material.name
            )));
        }
    }
    warnings
}

/// Frames above which the VTK output draws a warning: ten thousand frames
/// of a body of some ten thousand points fill tens of gigabytes.
const MANY_FRAMES: u64 = 10_000;

/// Bytes a frame's `.vtu` file takes per point (its positions and
/// fields as written, measured on the files).
const FRAME_BYTES_PER_POINT: Real = 220.0;

/// A warning when the run would write more than [`MANY_FRAMES`] frames of
/// its `points`, with the room they would take.
fn frame_count_warning(scene: &Scene, clock: &Clock, points: usize) -> Option<Warning> {
    let every = scene.output.frame_every(clock.end, clock.dt);
    let frames = clock.total_steps() / every + 1;
    let gigabytes = frames as Real * points as Real * FRAME_BYTES_PER_POINT / 1e9;
    (frames > MANY_FRAMES).then(|| {
        Warning::new(WarningKind::Output, "output.frame_interval", format!(
            "output: the run writes up to {frames} VTK frames (one every {every} steps), about {gigabytes:.1} GB for its {points} points; a longer output.frame_interval writes fewer"
        ))
    })
}

/// Warnings about bodies resting on a free edge that gravity does not pull
/// them off, with the edges and gravity the run starts with: the first
/// stage's, if it sets them.
fn free_edge_warnings_at_the_start(
    scene: &Scene,
    world: &World,
    bodies: &[Entity],
    grid: &Grid,
) -> Vec<Warning> {
    let placed = placed_bodies(scene, world, bodies);
    let first = scene.stages.first();
    let mut start = grid.clone();
    start.edges = first
        .and_then(|s| s.edges)
        .map_or(start.edges, |c| c.apply(start.edges));
    let gravity = first.and_then(|s| s.gravity).unwrap_or(scene.gravity);
    free_edge_warnings(&start, gravity, &placed)
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
