//! How a contact force reaches the grid (paper section 3.2.3).

use crate::math::{DVec2, Real};
use serde::{Deserialize, Serialize};

/// The imposition of contact forces on material points (scene
/// `contact.force_application`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ForceApplication {
    /// The force is a body force of the point, mapped with S_ip like
    /// gravity (the paper's BodyForce runs), plus the tangential force's
    /// first moment about the point, (f_t ⊗ (x_c − x_p)) G_ip, so that it
    /// acts at the contact point x_c, where the contact's tangential spring
    /// measures the motion (default: cheapest).
    #[default]
    BodyForce,
    /// The force is a traction on the edge of the point's domain that faces
    /// the contact (turned to the contact's normal; the paper turns it to
    /// the force, which makes a frictional contact feed energy in), split
    /// evenly over `points` points, each share mapped with the grid's hat
    /// functions N_i. The edge points lie near the contact point, not at
    /// it: the tangential spring's motion and the force's work then match
    /// less closely than with `BodyForce`.
    Traction {
        /// Number of segments of the edge, each loaded at its centre (≥ 1;
        /// the paper's resolution i = 5 splits the edge into 4 segments:
        /// `points: 4`).
        points: u32,
    },
}

/// The integration points of a traction (section 3.2.3, Fig. 4): the point's
/// square domain (half-size `half_size`) is turned to face `direction`
/// (unit, pointing into the point: the contact's normal; the paper turns it
/// to the force, see `add_traction` in systems/contact_transfer.rs) and
/// shrunk by √2/2, the paper's recommendation, so that its nodes match the
/// uGIMP nodes; the edge on the contact side is cut into `count` equal
/// segments and their centres are returned.
pub fn traction_points(
    center: DVec2,
    half_size: Real,
    direction: DVec2,
    count: u32,
) -> impl Iterator<Item = DVec2> {
    let reach = half_size * std::f64::consts::FRAC_1_SQRT_2;
    let edge_center = center - reach * direction;
    let along = direction.perp();
    (0..count).map(move |k| {
        let t = -1.0 + (2 * k + 1) as Real / count as Real;
        edge_center + (t * reach) * along
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traction_points_lie_on_the_contact_edge() {
        let points: Vec<DVec2> = traction_points(DVec2::new(1.0, 1.0), 0.1, DVec2::Y, 5).collect();
        assert_eq!(points.len(), 5);
        let reach = 0.1 * std::f64::consts::FRAC_1_SQRT_2;
        for p in &points {
            assert!((p.y - (1.0 - reach)).abs() < 1e-15);
            assert!((p.x - 1.0).abs() <= reach);
        }
        // Symmetric about the centre line.
        let mean: DVec2 = points.iter().copied().sum::<DVec2>() / 5.0;
        assert!((mean.x - 1.0).abs() < 1e-15);
    }
}
