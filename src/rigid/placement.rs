//! The checks of a block's placement against the bodies, made when it
//! enters the world (at the start, or when a stage adds it).

use crate::components::{
    BlockId, BlockTemplate, BodyName, MaterialPoints, Pose, RigidMotion, RigidShape,
};
use crate::contact::disk_shape_contact;
use crate::math::Real;
use crate::resources::{Geometry, Penetration};
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;
use parry2d_f64::query::contact;

/// Overlap between a block and a body's disks where the block is placed
/// above which a warning is given: a tenth of the disk radius, more than
/// the few per-mille a body placed exactly on a block shows through
/// round-off.
const OVERLAP_WARNING_FRACTION: Real = 0.1;

/// What the placement checks compare the contact springs with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacementChecks {
    /// The time step (s).
    pub dt: Real,
    /// What δ of eq. 18a measures.
    pub penetration: Penetration,
    /// Plane strain or axisymmetry.
    pub geometry: Geometry,
}

/// Overlap of two blocks where one is placed, beyond which a warning is
/// given (m): far above the round-off of blocks placed exactly touching,
/// far below any overlap a user means.
const BLOCK_OVERLAP_WARNING: Real = 1e-9;

/// The warnings about placing `template` among `bodies` (entities in
/// scene order) and the blocks already in `world`: a body's disks or
/// another block overlapping it, and a time step above the stability
/// limit of its springs on a body's lightest point.
pub fn placement_warnings(
    template: &BlockTemplate,
    world: &World,
    bodies: &[Entity],
    checks: PlacementChecks,
) -> Vec<Warning> {
    let name = &template.id.name;
    let mut warnings = block_overlap_warnings(template, world);
    for &body in bodies {
        let law = *template.law.with_body(body);
        let Some(points) = world.get::<MaterialPoints>(body) else {
            continue;
        };
        let body_name = world.get::<BodyName>(body).map_or("", |n| n.0.as_str());
        warnings.extend(overlap_warning(template, body_name, points));
        // Per metre of contact: in axisymmetry both the point's mass and
        // the spring go with the radius.
        let lightest = (0..points.len())
            .map(|p| points.mass[p] / checks.geometry.thickness(points.position[p]))
            .fold(Real::INFINITY, Real::min);
        // In `Area` mode the stiffness is per area; the largest slope of
        // the overlap area, d A / d δ = 2 r at δ = r, makes it a spring.
        let widest = points.contact_radius.iter().copied().fold(0.0, Real::max);
        let spring = law.normal_stiffness.max(law.tangential_stiffness);
        let stiffness = match checks.penetration {
            Penetration::Depth => spring,
            Penetration::Area => spring * 2.0 * widest,
        };
        let limit = 2.0 * (lightest / stiffness).sqrt();
        if checks.dt > limit {
            warnings.push(Warning::new(WarningKind::TimeStep, "time.dt", format!(
                "time.dt = {:e} s exceeds the contact stability limit 2 sqrt(m_p / max(k_n, k_t)) = {limit:.4e} s of block '{name}' (lightest point {lightest:.4e} kg/m)",
                checks.dt
            )));
        }
    }
    warnings
}

/// A warning for each block in `world` that `template` overlaps where it
/// is placed, in scene order, when either is dynamic: their contact pushes
/// them apart at once, and throws the dynamic one out. (Fixed and
/// kinematic blocks may overlap: a container of two walls, say.)
fn block_overlap_warnings(template: &BlockTemplate, world: &World) -> Vec<Warning> {
    let Some(mut blocks) = world.try_query::<(&BlockId, &RigidShape, &Pose, &RigidMotion)>() else {
        return Vec::new();
    };
    let dynamic = |motion: &RigidMotion| *motion == RigidMotion::Dynamic;
    let placed = template.pose.to_parry();
    let mut overlaps: Vec<(u32, String, Real)> = blocks
        .iter(world)
        .filter(|(id, .., motion)| {
            id.index != template.id.index && (dynamic(motion) || dynamic(&template.motion))
        })
        .filter_map(|(id, shape, pose, _)| {
            let found = contact(
                &placed,
                &*template.shape.0,
                &pose.to_parry(),
                &*shape.0,
                0.0,
            );
            let depth = -found.ok()??.dist;
            (depth > BLOCK_OVERLAP_WARNING).then(|| (id.index, id.name.clone(), depth))
        })
        .collect();
    overlaps.sort_unstable_by_key(|(index, ..)| *index);
    overlaps
        .into_iter()
        .map(|(_, other, depth)| {
            Warning::new(
                WarningKind::Layout,
                format!("blocks[\"{}\"].position", template.id.name),
                format!(
                    "block '{}' overlaps block '{other}' by {depth:.3e} m where it is placed: their contact pushes them apart at once (a dynamic block is thrown out); move it apart by at least that",
                    template.id.name
                ),
            )
        })
        .collect()
}

/// A warning with the deepest overlap of the body's disks into the
/// block, if it exceeds [`OVERLAP_WARNING_FRACTION`] of the disk radius.
fn overlap_warning(
    template: &BlockTemplate,
    body: &str,
    points: &MaterialPoints,
) -> Option<Warning> {
    let parry_pose = template.pose.to_parry();
    let (depth, radius) = (0..points.len())
        .filter_map(|p| {
            let r = points.contact_radius[p];
            disk_shape_contact(points.position[p], r, &*template.shape.0, &parry_pose)
                .map(|c| (c.depth, r))
        })
        .fold((0.0, 0.0), |worst, c| if c.0 > worst.0 { c } else { worst });
    (depth > OVERLAP_WARNING_FRACTION * radius).then(|| {
        Warning::new(WarningKind::Layout, format!("blocks[\"{}\"].position", template.id.name), format!(
            "block '{}' overlaps body '{body}' by {depth:e} m where it is placed (disk radius {radius:e} m): its contacts push the body away at once",
            template.id.name
        ))
    })
}
