//! Spawning the rigid blocks of a validated scene, with the warnings a user
//! needs before running (blocks overlapping bodies, a time step above the
//! contact stability limit, block contacts needing more sub-steps than are
//! taken); the blocks stages add are kept as templates.

use super::{BlockSpec, MotionSpec, Scene, SceneError, SourceLocation};
use crate::components::{
    BlockContactLaw, BlockId, BlockOutline, BlockTemplate, Pose, RigidMass, RigidMotion,
    RigidShape, RigidVelocity,
};
use crate::contact::ContactLaw;
use crate::math::Real;
use crate::resources::BlockPairLaws;
use crate::rigid::{MAX_SUBSTEPS, PlacementChecks, placement_warnings, substeps_needed};
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;

/// Spawns one entity per block present at the start (`present`), in scene
/// order; `bodies` are the body entities in scene order. Returns the
/// warnings and the templates of the blocks absent at the start (which
/// stages add), in scene order.
pub fn spawn_blocks(
    scene: &Scene,
    world: &mut World,
    bodies: &[Entity],
) -> Result<(Vec<Warning>, Vec<BlockTemplate>), SceneError> {
    let mut warnings = Vec::new();
    let mut absent = Vec::new();
    let mut substep_input = Vec::with_capacity(scene.blocks.len());
    let checks = PlacementChecks {
        dt: scene.time.dt,
        penetration: scene.contact.penetration,
        geometry: scene.settings.geometry,
    };
    for (index, spec) in scene.blocks.iter().enumerate() {
        let mut template = block_template(spec, index)?;
        template.law.bodies = body_laws(scene, &spec.name, bodies);
        substep_input.push((
            index as u32,
            template.motion,
            template.mass.mass,
            spec.contact,
        ));
        if spec.present {
            warnings.extend(placement_warnings(&template, world, bodies, checks));
            template.spawn(world);
        } else {
            absent.push(template);
        }
    }
    let needed = substeps_needed(&substep_input, &block_pair_laws(scene), scene.time.dt);
    if needed > MAX_SUBSTEPS {
        warnings.push(Warning::new(WarningKind::TimeStep, "time.dt", format!(
            "the block-block contacts need {needed} sub-steps per step (ten per contact period 2π sqrt(m / k_n)); only {MAX_SUBSTEPS} are taken, so they will likely blow up: lower time.dt or the normal_stiffness of the stiffest pair's law (a block's contact, or its block_contacts entry)"
        )));
    }
    Ok((warnings, absent))
}

/// The laws `block_contacts` gives the block named `block` with bodies,
/// each with the body's entity (`bodies` in scene order).
fn body_laws(scene: &Scene, block: &str, bodies: &[Entity]) -> Vec<(Entity, ContactLaw)> {
    scene
        .block_contacts
        .iter()
        .filter_map(|spec| {
            let (a, b) = (&spec.between.0, &spec.between.1);
            let other = if a == block {
                b
            } else if b == block {
                a
            } else {
                return None;
            };
            let k = scene.bodies.iter().position(|body| &body.name == other)?;
            Some((bodies[k], spec.law))
        })
        .collect()
}

/// The laws `block_contacts` gives pairs of blocks, by scene indices.
pub(crate) fn block_pair_laws(scene: &Scene) -> BlockPairLaws {
    let index = |name: &str| scene.blocks.iter().position(|b| b.name == name);
    let mut laws: Vec<((u32, u32), ContactLaw)> = scene
        .block_contacts
        .iter()
        .filter_map(|spec| {
            let (a, b) = (index(&spec.between.0)?, index(&spec.between.1)?);
            Some(((a.min(b) as u32, a.max(b) as u32), spec.law))
        })
        .collect();
    laws.sort_unstable_by_key(|(pair, _)| *pair);
    BlockPairLaws(laws)
}

/// The components of block `index` of the scene, `spec`.
fn block_template(spec: &BlockSpec, index: usize) -> Result<BlockTemplate, SceneError> {
    let shape = spec
        .shape
        .build()
        .map_err(|e| invalid(format!("block '{}': {e}", spec.name)))?;
    let (motion, mass, velocity) = block_motion(spec)?;
    Ok(BlockTemplate {
        id: BlockId {
            name: spec.name.clone(),
            index: index as u32,
        },
        outline: BlockOutline(spec.shape.outline()),
        shape: RigidShape(shape),
        pose: Pose {
            origin: spec.position,
            angle: spec.angle.to_radians(),
        },
        velocity,
        motion,
        mass,
        law: BlockContactLaw {
            own: spec.contact,
            bodies: Vec::new(),
        },
    })
}

fn invalid(message: String) -> SceneError {
    SceneError::Invalid {
        location: SourceLocation::default(),
        message,
    }
}

/// A block's motion, mass properties and initial velocity.
fn block_motion(spec: &BlockSpec) -> Result<(RigidMotion, RigidMass, RigidVelocity), SceneError> {
    let shape = spec
        .shape
        .build()
        .map_err(|e| invalid(format!("block '{}': {e}", spec.name)))?;
    let mass_of = |density: Real| {
        let props = spec.shape.mass_properties(&shape, density);
        RigidMass {
            mass: props.mass(),
            inertia: props.principal_inertia(),
            local_center: props.local_com,
        }
    };
    // Fixed and kinematic blocks need only their centre of mass (the
    // point a kinematic spin turns about): any density will do.
    Ok(match &spec.motion {
        MotionSpec::Fixed => (RigidMotion::Fixed, mass_of(1.0), RigidVelocity::default()),
        MotionSpec::Kinematic(v) => (RigidMotion::Kinematic, mass_of(1.0), *v),
        MotionSpec::Dynamic { density, velocity } => {
            (RigidMotion::Dynamic, mass_of(*density), *velocity)
        }
        MotionSpec::DynamicWithMass {
            mass,
            inertia,
            center,
            velocity,
        } => (
            RigidMotion::Dynamic,
            RigidMass {
                mass: *mass,
                inertia: *inertia,
                local_center: *center,
            },
            *velocity,
        ),
    })
}
