//! Warnings about contact springs the time integration cannot follow: a
//! time step beyond their stability limit, and an undamped position update
//! that feeds them energy.

use crate::components::MaterialPoints;
use crate::math::Real;
use crate::resources::{BodyPairLaw, PositionUpdate, UpdateScheme};
use crate::scene::Scene;
use crate::warning::{Warning, WarningKind};

/// A warning when the scene has DEM contacts (blocks with bodies, or body
/// contact laws, not every one with a normal dashpot), runs some stage
/// without damping (grid, particle, PIC fraction or XPIC; the settings as
/// each stage leaves them), and moves its points in a way that feeds
/// undamped contact springs energy: by the paper's eq. 11b under any
/// scheme (a step multiplies a spring's phase-space area by
/// 1 + (ωΔt)²/2), or by the new grid velocity under USF or MUSL (the strain
/// follows another field than the points). It names the setting and the
/// safe alternative.
pub fn undamped_contact_warning(scene: &Scene) -> Option<Warning> {
    let settings = &scene.settings;
    let update = settings.position_update()?;
    let feeds = match update {
        PositionUpdate::PaperEq11b => true,
        PositionUpdate::NewGridVelocity => settings.scheme != UpdateScheme::Usl,
        PositionUpdate::RemappedVelocity => false,
    };
    let dashpots = scene.blocks.iter().all(|b| b.contact.normal_damping > 0.0)
        && scene
            .body_contacts
            .iter()
            .all(|c| c.law.normal_damping > 0.0)
        && scene
            .block_contacts
            .iter()
            .all(|c| c.law.normal_damping > 0.0);
    let contacts = !scene.bodies.is_empty()
        && (!scene.blocks.is_empty() || !scene.body_contacts.is_empty())
        && !dashpots;
    // The damping as each stage leaves it (the first from the start), or
    // the settings' without stages.
    let mut damping = [
        settings.pic_fraction,
        settings.grid_damping,
        settings.particle_damping,
    ];
    let mut undamped = scene.stages.is_empty() && damping.iter().all(|&d| d == 0.0);
    for stage in &scene.stages {
        let changes = [
            stage.pic_fraction,
            stage.grid_damping,
            stage.particle_damping,
        ];
        for (value, change) in damping.iter_mut().zip(changes) {
            *value = change.unwrap_or(*value);
        }
        undamped |= damping.iter().all(|&d| d == 0.0);
    }
    (feeds && contacts && undamped).then(|| {
        Warning::new(WarningKind::Contact, "settings.position_update", format!(
            "settings.position_update: {update:?} under {:?} feeds undamped DEM contact springs energy (an elastic body resting on a block gains energy and leaves it); use the default position update (leave position_update out: RemappedVelocity), or damping",
            settings.scheme
        ))
    })
}

/// A warning for each pair of bodies under a contact law whose stiffest
/// spring, between the lightest points of the two, vibrates too fast for
/// `dt`: a spring k between masses m_a and m_b has the period 2π√(μ/k),
/// μ = m_a m_b / (m_a + m_b), and the explicit step follows it only while
/// Δt ≤ 2√(μ/k). Beyond it the contact gains energy each step and the run
/// blows up (bodies rebound faster than they met, then a point's volume
/// inverts). Body contacts measure depth, so k is in N/m per metre.
/// `bodies` are (name, points) in scene order, `laws` the scene's body
/// pairs with a law. A law between groups of many bodies gives many pairs:
/// the [`LISTED`] with the smallest limits are named, the rest counted.
pub fn body_contact_stability_warnings(
    dt: Real,
    bodies: &[(&str, &MaterialPoints)],
    laws: &[BodyPairLaw],
) -> Vec<Warning> {
    let lightest = |p: &MaterialPoints| p.mass.iter().copied().fold(Real::INFINITY, Real::min);
    let mut warnings: Vec<(Real, Warning)> = Vec::new();
    for pair in laws {
        let (a, b) = (&bodies[pair.a as usize], &bodies[pair.b as usize]);
        let (m_a, m_b) = (lightest(a.1), lightest(b.1));
        if !(m_a.is_finite() && m_b.is_finite()) {
            continue;
        }
        let reduced = m_a * m_b / (m_a + m_b);
        let stiffness = pair.law.normal_stiffness.max(pair.law.tangential_stiffness);
        let limit = 2.0 * (reduced / stiffness).sqrt();
        if dt > limit {
            warnings.push((limit, Warning::new(WarningKind::TimeStep, "time.dt", format!(
                "time.dt = {dt:e} s exceeds the contact stability limit 2 sqrt(m / max(k_n, k_t)) = {limit:.4e} s of bodies '{}' and '{}' (m = {reduced:.4e} kg/m, the reduced mass of their lightest points): the contact will gain energy and the run will likely blow up",
                a.0, b.0
            ))));
        }
    }
    // A stable sort: equal limits keep the scene's pair order.
    warnings.sort_by(|x, y| x.0.total_cmp(&y.0));
    let more = warnings.len().saturating_sub(LISTED);
    let mut listed: Vec<Warning> = warnings.into_iter().take(LISTED).map(|(_, w)| w).collect();
    if more > 0 {
        let pairs = if more == 1 { "pair" } else { "pairs" };
        listed.push(Warning::new(WarningKind::TimeStep, "time.dt", format!(
            "{more} more {pairs} of bodies under contact laws exceed their contact stability limits at time.dt = {dt:e} s"
        )));
    }
    listed
}

/// How many pairs of bodies the stability warning names.
const LISTED: usize = 3;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::NewPoint;
    use crate::contact::ContactLaw;
    use crate::math::{DVec2, SymTensor};

    /// A body of one point of mass `mass`.
    fn points(mass: Real) -> MaterialPoints {
        let mut p = MaterialPoints::default();
        p.push(NewPoint {
            position: DVec2::ZERO,
            velocity: DVec2::ZERO,
            volume: 1.0,
            mass,
            half_size: DVec2::splat(0.5),
            stress: SymTensor::ZERO,
            contact_radius: 0.5,
        });
        p
    }

    #[test]
    fn a_step_beyond_the_springs_limit_warns_and_one_within_does_not() {
        // Two points of 2 kg/m and 2 kg/m: μ = 1 kg/m; k_t = 1e4 N/m is
        // the stiffer spring, so the limit is 2 sqrt(1 / 1e4) = 0.02 s.
        let (a, b) = (points(2.0), points(2.0));
        let bodies = [("a", &a), ("b", &b)];
        let laws = [BodyPairLaw {
            a: 0,
            b: 1,
            law: ContactLaw {
                normal_stiffness: 1e3,
                tangential_stiffness: 1e4,
                friction: 0.2,
                normal_damping: 0.0,
            },
        }];
        assert!(body_contact_stability_warnings(0.0199, &bodies, &laws).is_empty());
        let warned = body_contact_stability_warnings(0.0201, &bodies, &laws);
        assert_eq!(warned.len(), 1);
        assert!(
            warned[0]
                .message
                .contains("= 2.0000e-2 s of bodies 'a' and 'b'"),
            "{}",
            warned[0]
        );
    }

    #[test]
    fn many_pairs_are_named_up_to_the_listed_number_with_the_smallest_limits_first() {
        // Five bodies, lighter down the list, all under one law: ten pairs.
        let bodies: Vec<MaterialPoints> = (0..5).map(|k| points(10.0 - k as Real)).collect();
        let names = ["a", "b", "c", "d", "e"];
        let placed: Vec<(&str, &MaterialPoints)> = names.iter().copied().zip(&bodies).collect();
        let law = ContactLaw {
            normal_stiffness: 1e6,
            tangential_stiffness: 1e6,
            friction: 0.0,
            normal_damping: 0.0,
        };
        let laws: Vec<BodyPairLaw> = (0..5u32)
            .flat_map(|a| (a + 1..5).map(move |b| BodyPairLaw { a, b, law }))
            .collect();
        let warned = body_contact_stability_warnings(1.0, &placed, &laws);
        assert_eq!(warned.len(), LISTED + 1, "{warned:?}");
        // The two lightest bodies, d and e, make the smallest limit.
        assert!(
            warned[0].message.contains("bodies 'd' and 'e'"),
            "{}",
            warned[0]
        );
        assert!(
            warned[LISTED].message.starts_with("7 more pairs"),
            "{}",
            warned[LISTED]
        );
    }
}
