//! The records of a distributed run: what each process holds of them,
//! gathered so that every process records what one process records.

use super::{Domain, PointIds};
use crate::components::MaterialPoints;
use crate::math::{DVec2, Real};
use crate::resources::{ProbeSample, Probes};
use bevy_ecs::prelude::Entity;
use serde::{Serialize, de::DeserializeOwned};

/// Appends every probe's sample at `time`: each process samples the probes
/// whose point it holds (a probe's point is its index in the one-process
/// run), and every process takes all the samples, in probe order.
pub(crate) fn record_probes<'a>(
    domain: &Domain,
    probes: &mut Probes,
    time: Real,
    points_of: impl Fn(Entity) -> Option<(&'a MaterialPoints, &'a PointIds)>,
) {
    let held: Vec<ProbeSample> = probes
        .probes
        .iter()
        .enumerate()
        .filter_map(|(k, probe)| {
            let (points, ids) = points_of(probe.body)?;
            let p = ids.0.binary_search(&(probe.point as u64)).ok()?;
            Some(ProbeSample::of(k, time, points, p))
        })
        .collect();
    let bytes = postcard::to_stdvec(&held).expect("samples encode");
    let mut all: Vec<ProbeSample> = domain
        .transport()
        .all_gather(bytes)
        .iter()
        .flat_map(|b| postcard::from_bytes::<Vec<ProbeSample>>(b).expect("samples decode"))
        .collect();
    all.sort_by_key(|s| s.probe);
    probes.samples.extend(all);
}

/// Sums per tile, from every process, added in tile order: this process
/// gives the sums of its tiles (`tiles`, `sums` alike in order). Without a
/// domain, this process's sums added in order.
pub(crate) fn add_tile_sums<T>(
    domain: Option<&Domain>,
    tiles: impl Iterator<Item = [usize; 2]>,
    sums: &[T],
) -> T
where
    T: Copy + Default + std::ops::Add<Output = T> + Serialize + DeserializeOwned,
{
    let Some(domain) = domain else {
        return sums.iter().fold(T::default(), |total, s| total + *s);
    };
    let held: Vec<([usize; 2], T)> = tiles.zip(sums.iter().copied()).collect();
    let bytes = postcard::to_stdvec(&held).expect("sums encode");
    let mut all: Vec<([usize; 2], T)> = domain
        .transport()
        .all_gather(bytes)
        .iter()
        .flat_map(|b| postcard::from_bytes::<Vec<([usize; 2], T)>>(b).expect("sums decode"))
        .collect();
    all.sort_by_key(|(tile, _)| *tile);
    all.iter().fold(T::default(), |total, (_, s)| total + *s)
}

/// A body's point columns the fronts and deposits read: position,
/// domain half-size and mass.
type OutlineColumns = (Vec<DVec2>, Vec<DVec2>, Vec<Real>);

/// On rank 0, `columns` of every process's points of one body, in the
/// points' one-process order (the other processes send theirs, with their
/// `ids`, and get `None`). Every process calls it for the same body.
pub(crate) fn gather_columns(
    domain: &Domain,
    ids: &PointIds,
    (position, half_size, mass): (&Vec<DVec2>, &Vec<DVec2>, &Vec<Real>),
) -> Option<OutlineColumns> {
    if domain.rank() != 0 {
        let bytes =
            postcard::to_stdvec(&(&ids.0, position, half_size, mass)).expect("columns encode");
        domain.transport().exchange(vec![(0, bytes)], &[]);
        return None;
    }
    let others: Vec<usize> = (1..domain.ranks()).collect();
    let mut all: Vec<(u64, DVec2, DVec2, Real)> = (0..ids.0.len())
        .map(|k| (ids.0[k], position[k], half_size[k], mass[k]))
        .collect();
    for bytes in domain.transport().exchange(Vec::new(), &others) {
        let (their_ids, x, h, m): (Vec<u64>, Vec<DVec2>, Vec<DVec2>, Vec<Real>) =
            postcard::from_bytes(&bytes).expect("columns decode");
        all.extend((0..their_ids.len()).map(|k| (their_ids[k], x[k], h[k], m[k])));
    }
    all.sort_unstable_by_key(|p| p.0);
    Some((
        all.iter().map(|p| p.1).collect(),
        all.iter().map(|p| p.2).collect(),
        all.iter().map(|p| p.3).collect(),
    ))
}
