//! Contacts between two rigid blocks through parry's contact manifolds
//! (one or two points per pair of convex parts).

use crate::math::{DVec2, Real};
use parry2d_f64::math::Pose;
use parry2d_f64::query::{ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher};
use parry2d_f64::shape::{Shape, SharedShape};

/// One contact point between block A and block B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeContact {
    /// Penetration depth (m), > 0.
    pub depth: Real,
    /// Unit normal from B to A.
    pub normal: DVec2,
    /// Contact point, midway between the two surfaces (m).
    pub point: DVec2,
    /// What identifies the point from step to step, to carry its tangential
    /// spring: the pair of convex parts and the touching features (vertex or
    /// face) of each, as parry tracks them.
    pub features: (u32, u32, u32),
}

/// The convex parts of a shape placed at `pose`: the parts of a compound, or
/// the shape itself (no allocation).
fn convex_parts<'a>(
    shape: &'a SharedShape,
    pose: &Pose,
) -> impl Iterator<Item = (Pose, &'a dyn Shape)> + Clone {
    let compound = shape.as_compound();
    let pose = *pose;
    let parts = compound.map_or(&[][..], |c| c.shapes());
    let whole = compound.is_none().then_some((pose, &**shape));
    parts
        .iter()
        .map(move |(part_pose, part)| (pose * *part_pose, &**part))
        .chain(whole)
}

/// Appends to `out` every overlapping point between `a` at `pose_a` and `b`
/// at `pose_b`, convex parts paired one by one.
pub fn shape_shape_contacts(
    a: &SharedShape,
    pose_a: &Pose,
    b: &SharedShape,
    pose_b: &Pose,
    out: &mut Vec<ShapeContact>,
) {
    let count_b = convex_parts(b, pose_b).count();
    for (i, (part_a_pose, part_a)) in convex_parts(a, pose_a).enumerate() {
        for (j, (part_b_pose, part_b)) in convex_parts(b, pose_b).enumerate() {
            let pos12 = part_a_pose.inv_mul(&part_b_pose);
            let mut manifold = ContactManifold::<(), ()>::new();
            let found = DefaultQueryDispatcher.contact_manifold_convex_convex(
                &pos12,
                part_a,
                part_b,
                None,
                None,
                0.0,
                &mut manifold,
            );
            if found.is_err() {
                continue;
            }
            let normal = -part_a_pose.transform_vector(manifold.local_n1);
            for point in &manifold.points {
                if point.dist >= 0.0 {
                    continue;
                }
                let p1 = part_a_pose.transform_point(point.local_p1);
                let p2 = part_b_pose.transform_point(point.local_p2);
                let features = ((i * count_b + j) as u32, point.fid1.0, point.fid2.0);
                out.push(ShapeContact {
                    depth: -point.dist,
                    normal,
                    point: 0.5 * (p1 + p2),
                    features,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_sunk_into_the_ground_has_two_contact_points() {
        let ground = SharedShape::cuboid(2.0, 0.5);
        let block = SharedShape::cuboid(0.5, 0.5);
        let mut out = Vec::new();
        // Block bottom at y = 0.49, ground top at y = 0.5: 0.01 deep.
        shape_shape_contacts(
            &block,
            &Pose::translation(0.0, 0.99),
            &ground,
            &Pose::IDENTITY,
            &mut out,
        );
        assert_eq!(out.len(), 2, "{out:?}");
        for c in &out {
            assert!(
                (c.depth - 0.01).abs() < 1e-12 && (c.normal - DVec2::Y).length() < 1e-12,
                "{c:?}"
            );
        }
    }
}
