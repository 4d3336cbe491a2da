//! Turning a validated scene into a bevy `World`: its bodies and blocks.
//! What each feature of the step needs besides (the grid, the clock, the
//! records, the stages) its plugin adds (see [`crate::plugins`]).

use super::velocity_field::VelocityFieldError;
use super::{InitialStress, InitialVelocity, Scene, SceneError, SourceLocation, VelocityField};
use crate::components::{
    BlockTemplate, BodyIndex, BodyName, DampedEnergy, GridLayer, Material, MaterialPoints,
    NewPoint, RegionConstraints, StepTravel, TransferScratch,
};
use crate::math::{DVec2, Real, SymTensor};
use crate::resources::Grid;
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;

/// A scene's bodies and blocks in a new world.
pub(crate) struct SpawnedScene {
    /// The world, holding the bodies and the blocks present at the start.
    pub world: World,
    /// The blocks absent at the start (stages add them), in scene order.
    pub absent_blocks: Vec<BlockTemplate>,
    /// Warnings for the user about the bodies and blocks.
    pub warnings: Vec<Warning>,
}

/// Spawns the bodies of a scene that passed [`Scene::validate`], one
/// entity each in scene order, then its blocks present at the start.
pub(crate) fn spawn_scene(scene: &Scene) -> Result<SpawnedScene, SceneError> {
    let mut world = World::new();
    let (bodies, body_warnings) = spawn_bodies(scene, &mut world, &scene.grid.grid())?;
    let (block_warnings, absent_blocks) =
        super::spawn_blocks::spawn_blocks(scene, &mut world, &bodies)?;
    let mut warnings = scene.file_warnings.clone();
    warnings.extend(body_warnings);
    warnings.extend(block_warnings);
    Ok(SpawnedScene {
        world,
        absent_blocks,
        warnings,
    })
}

/// Spawns one entity per body, in scene order, with its points, material,
/// layer and scratch; returns the entities and the warnings about them.
fn spawn_bodies(
    scene: &Scene,
    world: &mut World,
    grid: &Grid,
) -> Result<(Vec<Entity>, Vec<Warning>), SceneError> {
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
            warnings.push(Warning::new(WarningKind::InitialStress, format!("bodies[\"{}\"].initial_stress", spec.name), format!(
                "body '{}': the initial stress of {outside} of its {} points lies outside the yield surface of material '{}' (a `k0` below its active or above its passive ratio?): the first step returns them to it, and energy.csv's balance misses part of that return's energy",
                spec.name,
                points.len(),
                material.name
            )));
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

/// The points of one body: positions from the shape, then mass, velocity and
/// initial stress.
fn fill_body(
    scene: &Scene,
    spec: &super::BodySpec,
    density: Real,
) -> Result<MaterialPoints, VelocityFieldError> {
    let h = scene.grid.cell_size;
    let spacing = h / spec.points_per_cell as Real;
    let velocity_at: Box<dyn Fn(DVec2) -> Result<DVec2, VelocityFieldError>> = match &spec.velocity
    {
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
