//! A material point's DEM disk against a rigid shape, through parry's
//! contact query (GJK/EPA for convex shapes, per part for compounds).

use crate::math::{DVec2, Real};
use parry2d_f64::math::Pose;
use parry2d_f64::query::contact;
use parry2d_f64::shape::{Ball, Shape};

/// Geometry of a disk–shape contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskContact {
    /// Penetration depth δ > 0 (m).
    pub depth: Real,
    /// Unit normal from the shape to the disk.
    pub normal: DVec2,
    /// Contact point: the middle of the overlap along the normal (m).
    pub point: DVec2,
}

/// The contact of a disk (centre `center`, radius `radius`) with `shape`
/// placed at `pose`, if they overlap.
pub fn disk_shape_contact(
    center: DVec2,
    radius: Real,
    shape: &dyn Shape,
    pose: &Pose,
) -> Option<DiskContact> {
    let disk = Ball::new(radius);
    let found = contact(&Pose::from_translation(center), &disk, pose, shape, 0.0).ok()??;
    if found.dist >= 0.0 {
        return None;
    }
    Some(DiskContact {
        depth: -found.dist,
        normal: found.normal2,
        point: 0.5 * (found.point1 + found.point2),
    })
}

/// Area of the part of a disk of radius `radius` beyond a straight boundary
/// at depth `depth` (a circular segment): the 2D "overlap area" measure of
/// penetration (section 3.2.2), exact for a flat face and a close
/// approximation while the disk is small against the block's features.
pub fn overlap_area(radius: Real, depth: Real) -> Real {
    let d = depth.clamp(0.0, 2.0 * radius);
    let h = radius - d;
    radius * radius * (h / radius).acos() - h * (2.0 * radius * d - d * d).sqrt()
}

/// ∫₀^δ A(s) ds for the segment area A of [`overlap_area`]: the potential
/// energy per unit normal stiffness of a contact whose normal force is
/// k_n A(δ) (J/m per N/m³). In closed form, with h = r − δ:
/// r² √(r² − h²) − (r² − h²)^{3/2} / 3 − r² h acos(h / r); beyond δ = 2r the
/// whole disk is inside and the force stays k_n π r².
pub fn overlap_area_integral(radius: Real, depth: Real) -> Real {
    let d = depth.clamp(0.0, 2.0 * radius);
    let r2 = radius * radius;
    let h = radius - d;
    let chord2 = (r2 - h * h).max(0.0);
    let within = r2 * chord2.sqrt() - chord2 * chord2.sqrt() / 3.0 - r2 * h * (h / radius).acos();
    within + std::f64::consts::PI * r2 * (depth - 2.0 * radius).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use parry2d_f64::shape::Cuboid;

    #[test]
    fn overlap_area_of_half_and_whole_disks() {
        let r: Real = 0.1;
        assert!((overlap_area(r, r) - std::f64::consts::PI * r * r / 2.0).abs() < 1e-15);
        assert!((overlap_area(r, 2.0 * r) - std::f64::consts::PI * r * r).abs() < 1e-15);
        assert_eq!(overlap_area(r, 0.0), 0.0);
        // Shallow: the segment's area is (4/3) sqrt(2 r) δ^(3/2) to leading order.
        let d: Real = 1e-6;
        let shallow = 4.0 / 3.0 * (2.0 * r).sqrt() * d.powf(1.5);
        assert!((overlap_area(r, d) / shallow - 1.0).abs() < 1e-4);
    }

    #[test]
    fn overlap_area_integral_is_the_area_summed_over_depth() {
        let r: Real = 0.1;
        // Half-way, ∫ y dA over a half disk: 2 r³ / 3; at 2r, π r³ (A(s) +
        // A(2r − s) = π r²); beyond, π r² per extra metre.
        assert!((overlap_area_integral(r, r) - 2.0 * r.powi(3) / 3.0).abs() < 1e-16);
        let pi = std::f64::consts::PI;
        assert!((overlap_area_integral(r, 2.0 * r) - pi * r.powi(3)).abs() < 1e-16);
        assert!((overlap_area_integral(r, 0.3) - pi * r.powi(3) - pi * r * r * 0.1).abs() < 1e-16);
        assert_eq!(overlap_area_integral(r, 0.0), 0.0);
        // Its slope is the area (central difference, error of order ε²).
        for d in [0.01, 0.07, 0.15] {
            let eps = 1e-6;
            let slope = (overlap_area_integral(r, d + eps) - overlap_area_integral(r, d - eps))
                / (2.0 * eps);
            assert!((slope / overlap_area(r, d) - 1.0).abs() < 1e-7, "at {d}");
        }
    }

    #[test]
    fn disk_resting_into_a_box() {
        // Box top at y = 1; disk of radius 0.1 centred at y = 1.05: 0.05 deep.
        let ground = Cuboid::new(DVec2::new(2.0, 1.0));
        let c = disk_shape_contact(DVec2::new(0.3, 1.05), 0.1, &ground, &Pose::IDENTITY).unwrap();
        assert!((c.depth - 0.05).abs() < 1e-12);
        assert!((c.normal - DVec2::Y).length() < 1e-12, "{}", c.normal);
        assert!(disk_shape_contact(DVec2::new(0.3, 1.2), 0.1, &ground, &Pose::IDENTITY).is_none());
    }

    #[test]
    fn normal_of_a_turned_box_is_its_face_normal() {
        let slope = Cuboid::new(DVec2::new(5.0, 0.5));
        let angle: Real = 0.3;
        let pose = Pose::new(DVec2::ZERO, angle);
        let up = DVec2::new(-angle.sin(), angle.cos());
        let c = disk_shape_contact(up * 0.55, 0.1, &slope, &pose).unwrap();
        assert!((c.normal - up).length() < 1e-9 && (c.depth - 0.05).abs() < 1e-9);
    }
}
