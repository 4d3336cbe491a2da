//! The records of a distributed run: what each process holds of them,
//! gathered so that every process records what one process records.

use super::{Domain, PointIds};
use crate::components::MaterialPoints;
use crate::math::Real;
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
