//! End of the step: finiteness check, clock, probes and energies.

use crate::components::{BodyIndex, BodyName, Material, MaterialPoints};
use crate::resources::{Clock, Diagnostics, EnergyLog, EnergySample, NumericalFailure, Probes};
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Stops a blow-up before it reaches any output: reports the first point of
/// each body with a non-finite position, velocity or stress, or a
/// non-positive volume (an inverted deformation gradient).
///
/// Reads: `Clock`, `MaterialPoints`, `BodyName`. Writes: `Diagnostics`.
pub fn check_finite(
    clock: Res<Clock>,
    mut diagnostics: ResMut<Diagnostics>,
    mut order: Local<Vec<(BodyIndex, Entity)>>,
    bodies: Query<(Entity, &BodyIndex, &BodyName, &MaterialPoints)>,
) {
    scene_order(&mut order, bodies.iter().map(|(e, i, _, _)| (*i, e)));
    for (_, name, points) in order
        .iter()
        .filter_map(|(_, e)| bodies.get(*e).ok().map(|b| (b.1, b.2, b.3)))
    {
        let bad = [
            (
                "position",
                points
                    .position
                    .par_iter()
                    .position_first(|x| !x.is_finite()),
            ),
            (
                "velocity",
                points
                    .velocity
                    .par_iter()
                    .position_first(|v| !v.is_finite()),
            ),
            (
                "stress",
                points.stress.par_iter().position_first(|s| !s.is_finite()),
            ),
            (
                "volume",
                points.volume.par_iter().position_first(|v| !(*v > 0.0)),
            ),
        ];
        for (field, point) in bad {
            if let Some(p) = point {
                let detail = match field {
                    "position" => format!("is {}", points.position[p]),
                    "velocity" => format!("is {}", points.velocity[p]),
                    "stress" => format!("is {:?}", points.stress[p].to_array()),
                    _ => format!("is {:e} (inverted deformation gradient)", points.volume[p]),
                };
                diagnostics.report(NumericalFailure {
                    step: clock.step + 1,
                    time: clock.time,
                    body: name.0.clone(),
                    point: p,
                    field,
                    detail,
                });
            }
        }
    }
}

/// Advances the clock by one step.
///
/// Writes: `Clock`.
pub fn advance_clock(mut clock: ResMut<Clock>) {
    clock.advance();
}

/// Records probes and energies every `Probes::every` steps.
///
/// Reads: `Clock`, `MaterialPoints`, `Material`, `BodyIndex`. Writes: `Probes`, `EnergyLog`.
pub fn record_probes_and_energy(
    clock: Res<Clock>,
    mut probes: ResMut<Probes>,
    mut energy: ResMut<EnergyLog>,
    mut order: Local<Vec<(BodyIndex, Entity)>>,
    bodies: Query<(Entity, &BodyIndex, &MaterialPoints, &Material)>,
) {
    if clock.step % probes.every.max(1) != 0 {
        return;
    }
    probes.record(clock.time, |entity| bodies.get(entity).ok().map(|b| b.2));
    scene_order(&mut order, bodies.iter().map(|(e, i, _, _)| (*i, e)));
    let ordered = order
        .iter()
        .filter_map(|(_, e)| bodies.get(*e).ok())
        .map(|b| (b.2, b.3));
    energy.samples.push(EnergySample::of(clock.time, ordered));
}

/// Fills `order` with the bodies sorted by their scene index, reusing its storage.
fn scene_order(
    order: &mut Vec<(BodyIndex, Entity)>,
    bodies: impl Iterator<Item = (BodyIndex, Entity)>,
) {
    order.clear();
    order.extend(bodies);
    order.sort_unstable();
}
