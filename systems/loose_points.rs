//! End of the step: a warning when a point that carries stress has grown so
//! loose that the time step is beyond its stable step.
//!
//! A point's internal force is its volume V times its stress, while its
//! mass stays m: its elastic wave crosses a cell as if its modulus M acted
//! on the density m / V = ρ⁰ / (V/V⁰), so the step it needs is
//! h / (c √(V/V⁰)), c = √(M / ρ⁰) the speed the scene's CFL warning checks.
//! A material that dilates without end under shear (Mohr–Coulomb or
//! Drucker–Prager with dilation_angle > 0, at the edge of a footing, say)
//! or a point stretched loose and squeezed again can grow V/V⁰ tenfold and
//! more, and the run then blows up long after the check at the start.

use crate::components::{BodyIndex, BodyName, Material, MaterialPoints, sort_into_scene_order};
use crate::distributed::{Domain, PointIds};
use crate::math::{DVec2, Real};
use crate::parallel::MIN_POINTS_PER_TASK;
use crate::resources::{Clock, Diagnostics, Grid};
use crate::warning::{Warning, WarningKind};
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Steps between two checks: a volume grows over many steps, and a pass
/// over the points every step would cost a few percent of the run.
const LOOSE_POINT_CHECK_EVERY: u64 = 64;

/// Every `LOOSE_POINT_CHECK_EVERY` steps (after a step that did not fail), for each body (in scene order)
/// not warned yet: its loosest point that carries stress, and a warning in
/// `Diagnostics::warnings` if Δt exceeds that point's stable step
/// h / (c √(V/V⁰)). Points with zero stress (disconnected, or at a
/// cohesionless apex) carry no stiffness and are left out. In a
/// distributed run the loosest point is every process's, named by its
/// one-process index, and every process warns alike.
///
/// Reads: `Clock`, `Grid`, `BodyIndex`, `BodyName`, `Material`,
/// `MaterialPoints` (position, volume, initial volume, stress). Writes:
/// `Diagnostics::warnings`.
pub fn check_loose_points(
    (clock, grid): (Res<Clock>, Res<Grid>),
    mut diagnostics: ResMut<Diagnostics>,
    mut order: Local<Vec<(BodyIndex, Entity)>>,
    mut warned: Local<Vec<Entity>>,
    bodies: Query<(Entity, &BodyIndex, &BodyName, &MaterialPoints, &Material)>,
    (domain, ids): (Option<NonSend<Domain>>, Query<&PointIds>),
) {
    // A failed step's state may hold NaNs; its failure is what to say.
    if !clock.step.is_multiple_of(LOOSE_POINT_CHECK_EVERY) || diagnostics.failure.is_some() {
        return;
    }
    sort_into_scene_order(&mut order, bodies.iter().map(|(e, i, ..)| (*i, e)));
    for &(_, entity) in order.iter() {
        if warned.contains(&entity) {
            continue;
        }
        let Ok((_, _, name, points, material)) = bodies.get(entity) else {
            continue;
        };
        let wave_speed = (material.model.as_model().p_wave_modulus() / material.density).sqrt();
        let Some(limit) = loosest_stable_ratio(grid.cell_size, wave_speed, clock.dt) else {
            continue;
        };
        let mut loosest = loosest_stressed_point(points).map(|(ratio, p)| {
            let id = ids.get(entity).map_or(p as u64, |ids| ids.0[p]);
            (ratio, id, points.position[p])
        });
        if let Some(domain) = &domain {
            loosest = loosest_of_all(domain, loosest);
        }
        let Some((ratio, p, at)) = loosest else {
            continue;
        };
        if ratio <= limit {
            continue;
        }
        warned.push(entity);
        let stable = grid.cell_size / (wave_speed * ratio.sqrt());
        diagnostics.warnings.push(Warning::new(WarningKind::TimeStep, format!("bodies[\"{}\"]", name.0), format!(
            "step {} (t = {:.6e} s): body '{}', point {p} at ({:.4}, {:.4}) carries stress at {ratio:.3} times its placed volume; at that density its elastic wave crosses a cell in h / (c sqrt(V/V0)) = {stable:.3e} s, less than time.dt = {:e} s, so the run may blow up. A material that dilates without end under shear (dilation_angle > 0) does this, as does a point stretched loose and squeezed again: `disconnected_above` takes the stress off points looser than a critical density, and a smaller time.dt follows the point further",
            clock.step, clock.time, name.0, at.x, at.y, clock.dt
        )));
    }
}

/// A body's loosest stressed point: its volume ratio, one-process index
/// and position.
type Loosest = Option<(Real, u64, DVec2)>;

/// The loosest of every process's `loosest`: the largest ratio, the
/// lowest index of equals, as one process picks it.
fn loosest_of_all(domain: &Domain, loosest: Loosest) -> Loosest {
    let bytes = postcard::to_stdvec(&loosest).expect("a point encodes");
    domain
        .transport()
        .all_gather(bytes)
        .iter()
        .filter_map(|b| postcard::from_bytes::<Loosest>(b).expect("a point decodes"))
        .reduce(|a, b| {
            if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
                b
            } else {
                a
            }
        })
}

/// The largest volume ratio V/V⁰ at which a point of wave speed
/// `wave_speed` (m/s) is stable with step `dt` on cells of size `cell`:
/// (h / (c Δt))². `None` for a material without a positive, finite speed.
fn loosest_stable_ratio(cell: Real, wave_speed: Real, dt: Real) -> Option<Real> {
    (wave_speed.is_finite() && wave_speed > 0.0).then(|| (cell / (wave_speed * dt)).powi(2))
}

/// The largest V/V⁰ among the points whose stress is not zero, and the
/// first point that has it; `None` if no point carries stress. A maximum
/// with ties to the lowest index, so the same for any thread count.
fn loosest_stressed_point(points: &MaterialPoints) -> Option<(Real, usize)> {
    let better = |a: (Real, usize), b: (Real, usize)| {
        if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
            b
        } else {
            a
        }
    };
    (&points.volume, &points.initial_volume, &points.stress)
        .into_par_iter()
        .with_min_len(MIN_POINTS_PER_TASK)
        .enumerate()
        .filter(|(_, (_, _, stress))| stress.to_array().iter().any(|&s| s != 0.0))
        .map(|(p, (volume, initial, _))| (volume / initial, p))
        .reduce_with(better)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::SymTensor;

    #[test]
    fn stable_ratio_is_the_square_of_the_cfl_margin() {
        // h / (c Δt) = 0.025 / (365 × 2.5e-5) = 2.740: stable up to V/V⁰ = 7.506.
        let limit = loosest_stable_ratio(0.025, 365.0, 2.5e-5).unwrap();
        assert!((limit - 7.5061).abs() < 1e-4, "{limit}");
        assert_eq!(loosest_stable_ratio(0.1, 0.0, 1e-4), None);
    }

    #[test]
    fn the_loosest_point_is_the_loosest_that_carries_stress() {
        let mut points = MaterialPoints::default();
        let stressed = SymTensor {
            xx: -1e5,
            ..SymTensor::default()
        };
        for (ratio, stress) in [
            (1.0, stressed),
            (40.0, SymTensor::default()),
            (3.0, stressed),
            (3.0, stressed),
        ] {
            points.volume.push(ratio * 2e-4);
            points.initial_volume.push(2e-4);
            points.stress.push(stress);
        }
        let (ratio, p) = loosest_stressed_point(&points).unwrap();
        assert!((ratio - 3.0).abs() < 1e-12 && p == 2, "{ratio} at {p}");
        points
            .stress
            .iter_mut()
            .for_each(|s| *s = SymTensor::default());
        assert_eq!(loosest_stressed_point(&points), None);
    }
}
