//! How finely block–block contacts cut an MPM step.

use crate::components::RigidMotion;
use crate::contact::ContactLaw;
use crate::math::Real;
use crate::resources::BlockPairLaws;

/// Most sub-steps of one MPM step: beyond this the block contacts are too
/// stiff for the time step by far, and the run is better with a smaller dt.
/// The scene loader warns when a scene needs more.
pub const MAX_SUBSTEPS: u32 = 1000;

/// Sub-steps per step (before the [`MAX_SUBSTEPS`] cap) for blocks given as
/// (scene index, motion, mass, own contact law) in scene order: ten per
/// contact period 2π √(m/k_n) of the stiffest pair with a dynamic block, m
/// the lighter dynamic block of the pair and k_n the pair's (`pair_laws`,
/// or [`ContactLaw::pair`] of their own). One when no pair has a dynamic
/// block.
pub fn substeps_needed(
    blocks: &[(u32, RigidMotion, Real, ContactLaw)],
    pair_laws: &BlockPairLaws,
    dt: Real,
) -> u32 {
    let mut shortest = Real::INFINITY;
    for (i, a) in blocks.iter().enumerate() {
        for b in &blocks[i + 1..] {
            let lightest = [a, b]
                .iter()
                .filter(|(_, motion, _, _)| *motion == RigidMotion::Dynamic)
                .map(|(_, _, mass, _)| *mass)
                .fold(Real::INFINITY, Real::min);
            if lightest.is_finite() {
                let k = pair_laws.between(a.0, b.0, &a.3, &b.3).normal_stiffness;
                shortest = shortest.min(std::f64::consts::TAU * (lightest / k).sqrt());
            }
        }
    }
    if shortest.is_finite() {
        (10.0 * dt / shortest).ceil().clamp(1.0, u32::MAX as Real) as u32
    } else {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAW: ContactLaw = ContactLaw {
        normal_stiffness: 1e6,
        tangential_stiffness: 1e6,
        friction: 0.5,
        normal_damping: 0.0,
    };

    #[test]
    fn ten_substeps_per_contact_period_of_the_lightest_dynamic_block() {
        // m = 1 kg, k = 1e6 N/m: period 2π 1e-3 s; dt = 2π 1e-3 needs ten.
        let blocks = [
            (0, RigidMotion::Fixed, 1e9, LAW),
            (1, RigidMotion::Dynamic, 1.0, LAW),
            (2, RigidMotion::Dynamic, 4.0, LAW),
        ];
        let dt = std::f64::consts::TAU * 1e-3;
        let none = BlockPairLaws::default();
        assert_eq!(substeps_needed(&blocks, &none, dt), 10);
        assert_eq!(substeps_needed(&blocks[..1], &none, dt), 1);
        assert_eq!(substeps_needed(&[blocks[0], blocks[0]], &none, dt), 1);
        // A pair law four times stiffer halves the period.
        let stiff = ContactLaw {
            normal_stiffness: 4e6,
            ..LAW
        };
        let pair = BlockPairLaws(vec![((0, 1), stiff)]);
        assert_eq!(substeps_needed(&blocks, &pair, dt), 20);
    }
}
