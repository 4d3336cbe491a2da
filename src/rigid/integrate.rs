//! Time integration of a rigid block.

use crate::components::{Pose, RigidMass, RigidVelocity};
use crate::math::{DVec2, Real};

/// Symplectic Euler for a dynamic block: the velocities from the force and
/// torque (about the centre of mass) first, then the pose from the new
/// velocities, turning about the centre of mass.
pub fn integrate_dynamic(
    pose: &mut Pose,
    velocity: &mut RigidVelocity,
    mass: &RigidMass,
    force: DVec2,
    torque: Real,
    dt: Real,
) {
    velocity.linear += force / mass.mass * dt;
    velocity.angular += torque / mass.inertia * dt;
    advance(pose, velocity, mass, dt);
}

/// Moves the pose with the velocity over `dt` (kinematic blocks, and the
/// second half of [`integrate_dynamic`]).
pub fn advance(pose: &mut Pose, velocity: &RigidVelocity, mass: &RigidMass, dt: Real) {
    let center = mass.center(pose) + velocity.linear * dt;
    pose.angle += velocity.angular * dt;
    pose.origin = center - pose.rotate(mass.local_center);
}

/// The velocity of the block's material at world point `x`: v + ω × r.
pub fn velocity_at(pose: &Pose, velocity: &RigidVelocity, mass: &RigidMass, x: DVec2) -> DVec2 {
    velocity.linear + velocity.angular * (x - mass.center(pose)).perp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_fall_and_spin_about_an_offset_centre() {
        let mass = RigidMass {
            mass: 2.0,
            inertia: 0.5,
            local_center: DVec2::new(1.0, 0.0),
        };
        let mut pose = Pose::default();
        let mut v = RigidVelocity::default();
        integrate_dynamic(&mut pose, &mut v, &mass, DVec2::new(0.0, -19.62), 0.25, 0.1);
        assert!((v.linear.y + 0.981).abs() < 1e-12 && (v.angular - 0.05).abs() < 1e-12);
        // The centre of mass moved straight down; the frame turned about it.
        let c = mass.center(&pose);
        assert!((c - DVec2::new(1.0, -0.0981)).length() < 1e-12, "{c}");
        // Velocity of a point 1 m right of the centre: v + ω ẑ × (1, 0).
        let at = velocity_at(&pose, &v, &mass, c + DVec2::X);
        assert!((at - DVec2::new(0.0, -0.981 + 0.05)).length() < 1e-12);
    }
}
