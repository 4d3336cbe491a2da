//! Spawning the rigid blocks of a validated scene, with the warnings a user
//! needs before running (blocks overlapping bodies, a time step above the
//! contact stability limit, block contacts needing more sub-steps than are
//! taken).

use super::{BlockSpec, MotionSpec, Scene, SceneError, SourceLocation};
use crate::components::{
    BlockContactLaw, BlockContacts, BlockId, BlockOutline, BodyName, MaterialPoints, NeighbourList,
    PartReactions, Pose, Reaction, RigidMass, RigidMotion, RigidShape, RigidVelocity,
};
use crate::contact::disk_shape_contact;
use crate::math::{DVec2, Real};
use crate::resources::Penetration;
use crate::rigid::{MAX_SUBSTEPS, substeps_needed};
use bevy_ecs::prelude::*;

/// Overlap between a block and a body's disks where the block is placed
/// (at the start, or when a stage adds it) above which a
/// warning is given: a tenth of the disk radius, more than the few
/// per-mille a body placed exactly on a block shows through round-off.
const OVERLAP_WARNING_FRACTION: Real = 0.1;

/// Spawns one entity per block present at the start (`present`), in scene
/// order; `bodies` are the body entities in scene order. Returns the
/// warnings.
pub fn spawn_blocks(
    scene: &Scene,
    world: &mut World,
    bodies: &[Entity],
) -> Result<Vec<String>, SceneError> {
    let mut warnings = Vec::new();
    let mut substep_input = Vec::with_capacity(scene.blocks.len());
    for (index, spec) in scene.blocks.iter().enumerate() {
        let (motion, mass, _) = block_motion(spec)?;
        substep_input.push((motion, mass.mass, spec.contact));
        if spec.present {
            warnings.extend(spawn_block(scene, index, world, bodies)?);
        }
    }
    let needed = substeps_needed(&substep_input, scene.time.dt);
    if needed > MAX_SUBSTEPS {
        warnings.push(format!(
            "the block-block contacts need {needed} sub-steps per step (ten per contact period 2π sqrt(m / k_n)); only {MAX_SUBSTEPS} are taken, so they will likely blow up: lower time.dt or the blocks' normal_stiffness"
        ));
    }
    Ok(warnings)
}

/// Spawns block `index` of the scene (at the start, or when a stage adds
/// it). Returns the warnings about it (overlap with a body, a time step
/// above the contact stability limit).
pub fn spawn_block(
    scene: &Scene,
    index: usize,
    world: &mut World,
    bodies: &[Entity],
) -> Result<Vec<String>, SceneError> {
    let spec = &scene.blocks[index];
    let mut warnings = Vec::new();
    let shape = spec
        .shape
        .build()
        .map_err(|e| invalid(format!("block '{}': {e}", spec.name)))?;
    let pose = Pose {
        origin: spec.position,
        angle: spec.angle.to_radians(),
    };
    let (motion, mass, velocity) = block_motion(spec)?;
    let part_count = shape.as_compound().map_or(1, |c| c.shapes().len());
    for &body in bodies {
        let Some(points) = world.get::<MaterialPoints>(body) else {
            continue;
        };
        let name = world.get::<BodyName>(body).map_or("", |n| n.0.as_str());
        warnings.extend(overlap_warning(&spec.name, name, points, &shape, &pose));
        // Per metre of contact: in axisymmetry both the point's mass and
        // the spring go with the radius.
        let geometry = scene.settings.geometry;
        let lightest = (0..points.len())
            .map(|p| points.mass[p] / geometry.thickness(points.position[p]))
            .fold(Real::INFINITY, Real::min);
        // In `Area` mode the stiffness is per area; the largest slope of the
        // overlap area, d A / d δ = 2 r at δ = r, makes it a spring.
        let widest = points.contact_radius.iter().copied().fold(0.0, Real::max);
        let spring = spec
            .contact
            .normal_stiffness
            .max(spec.contact.tangential_stiffness);
        let stiffness = match scene.contact.penetration {
            Penetration::Depth => spring,
            Penetration::Area => spring * 2.0 * widest,
        };
        let limit = 2.0 * (lightest / stiffness).sqrt();
        if scene.time.dt > limit {
            warnings.push(format!(
                "time.dt = {:e} s exceeds the contact stability limit 2 sqrt(m_p / max(k_n, k_t)) = {limit:.4e} s of block '{}' (lightest point {lightest:.4e} kg/m)",
                scene.time.dt, spec.name
            ));
        }
    }
    world.spawn((
        BlockId {
            name: spec.name.clone(),
            index: index as u32,
        },
        BlockOutline(spec.shape.outline()),
        RigidShape(shape),
        pose,
        velocity,
        motion,
        mass,
        BlockContactLaw(spec.contact),
        NeighbourList::default(),
        BlockContacts::default(),
        Reaction::default(),
        PartReactions(vec![DVec2::ZERO; part_count]),
    ));
    Ok(warnings)
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

/// A warning with the deepest overlap of the body's disks into the block,
/// if it exceeds [`OVERLAP_WARNING_FRACTION`] of the disk radius.
fn overlap_warning(
    block: &str,
    body: &str,
    points: &MaterialPoints,
    shape: &parry2d_f64::shape::SharedShape,
    pose: &Pose,
) -> Option<String> {
    let parry_pose = pose.to_parry();
    let (depth, radius) = (0..points.len())
        .filter_map(|p| {
            let r = points.contact_radius[p];
            disk_shape_contact(points.position[p], r, &**shape, &parry_pose).map(|c| (c.depth, r))
        })
        .fold((0.0, 0.0), |worst, c| if c.0 > worst.0 { c } else { worst });
    (depth > OVERLAP_WARNING_FRACTION * radius).then(|| {
        format!(
            "block '{block}' overlaps body '{body}' by {depth:e} m where it is placed (disk radius {radius:e} m): its contacts push the body away at once"
        )
    })
}
