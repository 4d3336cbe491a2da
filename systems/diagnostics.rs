//! End of the step: finiteness check, clock, probes, energies, blocks and body pairs.

use crate::components::{
    BlockContacts, BlockId, BodyIndex, BodyName, DampedEnergy, Material, MaterialPoints,
    PartReactions, PointEnergies, Pose, Reaction, RigidVelocity, TransferScratch,
    sort_into_scene_order,
};
use crate::distributed::{Domain, PointIds, add_tile_sums, record_probes};
use crate::math::DVec2;
use crate::parallel::MIN_POINTS_PER_TASK;
use crate::resources::{
    BlockLog, BodyContacts, BodyPairLog, BodyPairSample, Clock, ContactWork, Diagnostics,
    EnergyLog, EnergySample, FailureSite, Gravity, LoadWork, MAX_CONTACT_BODIES, NumericalFailure,
    PairTally, Probes, Sampling, Settings,
};
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// Stops a blow-up before it reaches any output: reports the first point of
/// each body with a non-finite position, velocity or stress, or a
/// non-positive volume (an inverted deformation gradient), and each block
/// whose pose, velocity or reaction is not finite.
///
/// Reads: `Clock`, `BodyIndex`, `BodyName`, `MaterialPoints`, `BlockId`,
/// `Pose`, `RigidVelocity`, `Reaction`. Writes: `Diagnostics`.
/// What `check_finite` reads of a block.
type BlockState<'a> = (
    &'a BlockId,
    &'a Pose,
    &'a RigidVelocity,
    Option<&'a Reaction>,
);

pub fn check_finite(
    clock: Res<Clock>,
    mut diagnostics: ResMut<Diagnostics>,
    mut order: Local<Vec<(BodyIndex, Entity)>>,
    bodies: Query<(Entity, &BodyIndex, &BodyName, &MaterialPoints, &Material)>,
    blocks: Query<(&BlockId, &Pose, &RigidVelocity, Option<&Reaction>)>,
) {
    sort_into_scene_order(&mut order, bodies.iter().map(|(e, i, ..)| (*i, e)));
    for (name, points, material) in order
        .iter()
        .filter_map(|(_, e)| bodies.get(*e).ok().map(|b| (b.2, b.3, b.4)))
    {
        if all_finite(points) {
            continue;
        }
        let first_bad = (0..points.len()).position(|p| first_bad_field(points, p).is_some());
        if let Some(p) = first_bad
            && let Some((field, detail)) = first_bad_field(points, p)
        {
            diagnostics.report(NumericalFailure {
                step: clock.step + 1,
                time: clock.time,
                at: FailureSite::Point {
                    body: name.0.clone(),
                    point: p,
                },
                field,
                detail: detail + granular_hint(material),
            });
        }
    }
    let broken = |(_, pose, velocity, reaction): &BlockState| {
        [
            ("pose", pose.origin.is_finite() && pose.angle.is_finite()),
            (
                "velocity",
                velocity.linear.is_finite() && velocity.angular.is_finite(),
            ),
            (
                "reaction",
                reaction.is_none_or(|r| r.force.is_finite() && r.torque.is_finite()),
            ),
        ]
        .into_iter()
        .find_map(|(field, finite)| (!finite).then_some(field))
    };
    if blocks.iter().all(|b| broken(&b).is_none()) {
        return;
    }
    // After a failure only: the first broken block in scene order.
    let mut in_order: Vec<BlockState> = blocks.iter().collect();
    in_order.sort_unstable_by_key(|(id, ..)| id.index);
    if let Some((id, field)) = in_order.iter().find_map(|b| Some((b.0, broken(b)?))) {
        diagnostics.report(NumericalFailure {
            step: clock.step + 1,
            time: clock.time,
            at: FailureSite::Block(id.name.clone()),
            field,
            detail: "is not finite".into(),
        });
    }
}

/// For a granular material that is never disconnected, what often breaks
/// it and the option against it; nothing for other materials.
fn granular_hint(material: &Material) -> &'static str {
    let model = material.model.as_model();
    let never_disconnected = model.granular() && !model.disconnects_loose_points();
    if never_disconnected {
        "; in a granular flow, points stretched far beyond their placed volume and then squeezed can do this: the material's `disconnected_above: Some(1.0)` lets points looser than placed carry no stress"
    } else {
        ""
    }
}

/// Whether every position, velocity and stress is finite and every volume
/// positive: one vectorisable pass per column (the common case), the
/// point-by-point search only runs after a failure.
fn all_finite(points: &MaterialPoints) -> bool {
    all_in_chunks(&points.position, |x| x.is_finite())
        && all_in_chunks(&points.velocity, |v| v.is_finite())
        && all_in_chunks(&points.stress, |s| s.is_finite())
        && all_in_chunks(&points.volume, |v| *v > 0.0)
}

/// Whether `ok` holds for every element: chunks in parallel, and inside each
/// a fold that tests every element without stopping at the first failure,
/// which the compiler turns into vector code (rayon's per-element `all`
/// checks a shared flag every item, and a plain `all` branches on each).
fn all_in_chunks<T: Sync>(column: &[T], ok: impl Fn(&T) -> bool + Sync) -> bool {
    column
        .par_chunks(MIN_POINTS_PER_TASK)
        .all(|chunk| chunk.iter().fold(true, |all, x| all & ok(x)))
}

/// The first broken field of point `p` and what it holds, if any.
fn first_bad_field(points: &MaterialPoints, p: usize) -> Option<(&'static str, String)> {
    if !points.position[p].is_finite() {
        Some(("position", format!("is {}", points.position[p])))
    } else if !points.velocity[p].is_finite() {
        Some(("velocity", format!("is {}", points.velocity[p])))
    } else if !points.stress[p].is_finite() {
        Some(("stress", format!("is {:?}", points.stress[p].to_array())))
    } else if points.volume[p].is_nan() || points.volume[p] <= 0.0 {
        Some((
            "volume",
            format!("is {:e} (inverted deformation gradient)", points.volume[p]),
        ))
    } else {
        None
    }
}

/// Advances the clock by one step.
///
/// Writes: `Clock`.
pub fn advance_clock(mut clock: ResMut<Clock>) {
    clock.advance();
}

/// Reused space of the energy record: bodies in scene order, the per-chunk
/// energy sums and the blocks in scene order.
type EnergyScratch = (
    Vec<(BodyIndex, Entity)>,
    Vec<PointEnergies>,
    Vec<(u32, Entity)>,
);

/// Records probes and energies at the steps `Sampling` picks, unless the step
/// failed (a broken state is never recorded); an energy that is not finite
/// is a numerical failure, and nothing of its step is recorded. The contact and load terms
/// count from the plugins that are built.
///
/// Reads: `Clock`, `Sampling`, `Diagnostics`, `Gravity`, `Settings::geometry`, `MaterialPoints`, `Material`,
/// `BodyIndex`, `BodyContacts`, `BlockContacts` (the contact springs'
/// energy), `ContactWork`, `LoadWork`, `DampedEnergy`. Writes: `Probes`,
/// `EnergyLog`.
#[allow(clippy::too_many_arguments)] // one resource or query per energy term
pub fn record_probes_and_energy(
    (clock, sampling): (Res<Clock>, Res<Sampling>),
    mut diagnostics: ResMut<Diagnostics>,
    (gravity, settings): (Res<Gravity>, Res<Settings>),
    mut probes: ResMut<Probes>,
    mut energy: ResMut<EnergyLog>,
    body_contacts: Option<Res<BodyContacts>>,
    (work, load_work): (Option<Res<ContactWork>>, Option<Res<LoadWork>>),
    mut scratch: Local<EnergyScratch>,
    bodies: Query<(
        Entity,
        &BodyIndex,
        &MaterialPoints,
        &Material,
        &DampedEnergy,
        &TransferScratch,
    )>,
    blocks: Query<(Entity, &BlockId, &BlockContacts)>,
    (domain, ids): (Option<NonSend<Domain>>, Query<&PointIds>),
) {
    if diagnostics.failure.is_some() || !sampling.due(&clock) {
        return;
    }
    let (order, sums, block_order) = &mut *scratch;
    sort_into_scene_order(order, bodies.iter().map(|(e, i, ..)| (*i, e)));
    let ordered = || order.iter().filter_map(|(_, e)| bodies.get(*e).ok());
    // Each body's points are summed tile by tile in the step's scatter
    // order, tiles in order: the same sums on any number of processes.
    let mut points_energy = PointEnergies::default();
    for (_, _, points, material, _, scratch) in ordered() {
        let model = material.model.as_model();
        let (g, geometry) = (gravity.0, settings.geometry);
        let order = &scratch.order;
        points_energy = points_energy
            + if order.points().len() == points.len() {
                points.energies_of_groups(model, g, geometry, order.tile_points(), sums);
                add_tile_sums(domain.as_deref(), order.tiles(), sums)
            } else {
                points.energies(model, g, geometry, sums)
            };
    }
    let mut sample = EnergySample::of_points(clock.time, points_energy);
    sample.damped = ordered().map(|b| b.4.0).sum();
    sort_into_scene_order(block_order, blocks.iter().map(|(e, id, ..)| (id.index, e)));
    let (mut springs, mut tangential) = body_contacts.map_or((0.0, 0.0), |c| c.spring_energies());
    for (_, _, contacts) in block_order.iter().filter_map(|(_, e)| blocks.get(*e).ok()) {
        for c in &contacts.current {
            springs += c.potential;
            tangential += c.tangential_potential;
        }
    }
    sample.contact = springs;
    let (tangential_work, block_work) =
        work.map_or((0.0, 0.0), |w| (w.tangential_work, w.block_work));
    sample.dissipated = -tangential_work - tangential;
    sample.blocks = -block_work;
    sample.loads = -load_work.map_or(0.0, |w| w.work);
    if let Some(term) = sample.first_non_finite() {
        // A broken sample is not recorded: the run stops with the series
        // up to the step before.
        diagnostics.report(NumericalFailure {
            step: clock.step,
            time: clock.time,
            at: FailureSite::Record("energy.csv"),
            field: term,
            detail: "is not finite".into(),
        });
        return;
    }
    match domain.as_deref() {
        None => probes.record(clock.time, |entity| bodies.get(entity).ok().map(|b| b.2)),
        Some(domain) => record_probes(domain, &mut probes, clock.time, |entity| {
            Some((bodies.get(entity).ok()?.2, ids.get(entity).ok()?))
        }),
    }
    energy.samples.push(sample);
}

/// Records the contacts of every pair of bodies with a law (resultant,
/// count, zone half-width, now and in the undeformed bodies) when the
/// records sample (`Sampling`), unless the step failed.
///
/// Reads: `Clock`, `Diagnostics`, `Sampling`, `BodyContacts`,
/// `BodyIndex`, `MaterialPoints::initial_position`. Writes: `BodyPairLog`.
pub fn record_body_pairs(
    clock: Res<Clock>,
    diagnostics: Res<Diagnostics>,
    sampling: Res<Sampling>,
    contacts: Res<BodyContacts>,
    bodies: Query<(&BodyIndex, &MaterialPoints)>,
    mut log: ResMut<BodyPairLog>,
    mut tallies: Local<Vec<PairTally>>,
) {
    if diagnostics.failure.is_some() || !sampling.due(&clock) {
        return;
    }
    let time = clock.time;
    let mut initial: [Option<&[DVec2]>; MAX_CONTACT_BODIES] = [None; MAX_CONTACT_BODIES];
    for (index, points) in bodies.iter() {
        if let Some(slot) = initial.get_mut(index.0 as usize) {
            *slot = Some(&points.initial_position);
        }
    }
    let place = |body: u32, point: u32| {
        initial[body as usize].and_then(|positions| positions.get(point as usize).copied())
    };
    // The middle of the pair's initial positions; none for a point whose
    // body is gone.
    contacts.summaries(
        |c| Some(0.5 * (place(c.a, c.p)? + place(c.b, c.q)?)),
        &mut tallies,
    );
    log.samples.extend(
        contacts
            .laws
            .iter()
            .zip(tallies.iter())
            .map(|(l, t)| BodyPairSample {
                time,
                a: l.a,
                b: l.b,
                summary: t.summary(),
            }),
    );
}

/// Records every block's reaction, pose and velocity when the probes are
/// sampled (`Sampling`), blocks in scene order, unless the step failed.
///
/// Reads: `Clock`, `Diagnostics`, `Sampling`, block components. Writes: `BlockLog`.
pub fn record_blocks(
    clock: Res<Clock>,
    diagnostics: Res<Diagnostics>,
    sampling: Res<Sampling>,
    mut log: ResMut<BlockLog>,
    mut order: Local<Vec<(u32, Entity)>>,
    blocks: Query<(
        Entity,
        &BlockId,
        &Reaction,
        &PartReactions,
        &Pose,
        &RigidVelocity,
    )>,
) {
    if blocks.is_empty() || diagnostics.failure.is_some() || !sampling.due(&clock) {
        return;
    }
    sort_into_scene_order(&mut order, blocks.iter().map(|(e, id, ..)| (id.index, e)));
    for (_, entity) in order.iter() {
        let Ok((_, id, reaction, parts, pose, velocity)) = blocks.get(*entity) else {
            continue;
        };
        log.record(clock.time, (id, reaction, parts, pose, velocity));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::{DruckerPrager, LinearElastic, MaterialModel};

    #[test]
    fn a_granular_material_that_never_disconnects_gets_the_hint() {
        let material = |model| Material {
            name: "m".into(),
            density: 1300.0,
            model,
        };
        let sand = DruckerPrager {
            youngs_modulus: 5e4,
            poisson_ratio: 0.4,
            friction_angle: 22.0,
            dilation_angle: 0.0,
            cohesion: 0.0,
            tension_cutoff: 0.0,
            disconnected_above: None,
        };
        let hint = granular_hint(&material(MaterialModel::DruckerPrager(sand)));
        assert!(hint.contains("disconnected_above"), "{hint}");
        let disconnecting = DruckerPrager {
            disconnected_above: Some(1.0),
            ..sand
        };
        assert_eq!(
            granular_hint(&material(MaterialModel::DruckerPrager(disconnecting))),
            ""
        );
        let elastic = LinearElastic {
            youngs_modulus: 1e6,
            poisson_ratio: 0.3,
        };
        assert_eq!(
            granular_hint(&material(MaterialModel::LinearElastic(elastic))),
            ""
        );
    }
}
