//! The halo exchange of a scatter: each process sends the processes it
//! shares node columns with its patches' values there, and takes theirs
//! into its nodal sums in their tiles' places (see
//! [`Scatter::add_into_with`]).

use super::Domain;
use crate::components::MassMomentumForce;
use crate::math::{DVec2, Real};
use crate::node_rect::NodeRect;
use crate::scatter::{Scatter, SharedPatch};

/// A scattered quantity as reals, to send.
pub(crate) trait NodalValue: Copy + Default + std::ops::AddAssign + Send + Sync {
    /// Reals per value.
    const REALS: usize;
    /// Appends the value's reals.
    fn put(&self, out: &mut Vec<Real>);
    /// The value from its [`Self::REALS`] reals.
    fn take(reals: &[Real]) -> Self;
}

impl NodalValue for Real {
    const REALS: usize = 1;
    fn put(&self, out: &mut Vec<Real>) {
        out.push(*self);
    }
    fn take(reals: &[Real]) -> Self {
        reals[0]
    }
}

impl NodalValue for DVec2 {
    const REALS: usize = 2;
    fn put(&self, out: &mut Vec<Real>) {
        out.extend(self.to_array());
    }
    fn take(reals: &[Real]) -> Self {
        DVec2::new(reals[0], reals[1])
    }
}

impl NodalValue for MassMomentumForce {
    const REALS: usize = 5;
    fn put(&self, out: &mut Vec<Real>) {
        out.push(self.mass);
        self.momentum.put(out);
        self.external_force.put(out);
    }
    fn take(reals: &[Real]) -> Self {
        Self {
            mass: reals[0],
            momentum: DVec2::take(&reals[1..3]),
            external_force: DVec2::take(&reals[3..5]),
        }
    }
}

/// Reals that head each patch: its tile (row, column) and its nodes.
const HEADER: usize = 6;

/// The patches of other processes this one takes into the last scatter's
/// nodal sums: none without a domain (one process holds every tile).
pub(crate) fn foreign_patches<T: NodalValue>(
    domain: Option<&Domain>,
    scatter: &Scatter<T>,
) -> Vec<SharedPatch<T>> {
    domain.map_or_else(Vec::new, |domain| exchange_shared(domain, scatter))
}

/// Sends every neighbour of this process the last scatter's values on the
/// node columns they share, and returns the neighbours' patches, in tile
/// order. Every process of the run calls it for the same scatter.
pub(crate) fn exchange_shared<T: NodalValue>(
    domain: &Domain,
    scatter: &Scatter<T>,
) -> Vec<SharedPatch<T>> {
    let neighbours = domain.neighbours();
    let messages = neighbours
        .iter()
        .map(|(rank, columns)| (*rank, encode(&scatter.shared(columns.clone()))))
        .collect();
    let ranks: Vec<usize> = neighbours.iter().map(|(rank, _)| *rank).collect();
    let mut patches: Vec<SharedPatch<T>> = domain
        .transport()
        .exchange(messages, &ranks)
        .iter()
        .flat_map(|bytes| decode(bytes))
        .collect();
    patches.sort_by_key(|p| p.tile);
    patches
}

fn encode<T: NodalValue>(patches: &[SharedPatch<T>]) -> Vec<u8> {
    let mut reals = Vec::new();
    for patch in patches {
        let r = patch.rect;
        let head = [
            patch.tile[0],
            patch.tile[1],
            r.start[0],
            r.start[1],
            r.end[0],
            r.end[1],
        ];
        reals.extend(head.map(|k| k as Real));
        for value in &patch.values {
            value.put(&mut reals);
        }
    }
    reals.iter().flat_map(|r| r.to_le_bytes()).collect()
}

fn decode<T: NodalValue>(bytes: &[u8]) -> Vec<SharedPatch<T>> {
    let reals: Vec<Real> = bytes
        .chunks_exact(8)
        .map(|b| Real::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect();
    let mut patches = Vec::new();
    let mut rest = &reals[..];
    while !rest.is_empty() {
        let head: Vec<usize> = rest[..HEADER].iter().map(|&r| r as usize).collect();
        let rect = NodeRect {
            start: [head[2], head[3]],
            end: [head[4], head[5]],
        };
        let count = rect.area() * T::REALS;
        let values = rest[HEADER..HEADER + count]
            .chunks_exact(T::REALS)
            .map(T::take)
            .collect();
        patches.push(SharedPatch {
            tile: [head[0], head[1]],
            rect,
            values,
        });
        rest = &rest[HEADER + count..];
    }
    patches
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distributed::{LocalRanks, Strips, Transport};
    use crate::scatter::ScatterOrder;
    use crate::shape_functions::{ShapeFunction, Stencil, StencilGrid};

    /// The halo exchange of a rank's scatter.
    type Exchange<'a> =
        dyn Fn(&Scatter<MassMomentumForce>) -> Vec<SharedPatch<MassMomentumForce>> + 'a;

    fn bits(v: &MassMomentumForce) -> [u64; 5] {
        let mut reals = Vec::new();
        v.put(&mut reals);
        std::array::from_fn(|k| reals[k].to_bits())
    }

    /// Points scattered on 1 to 4 ranks, each holding the points of its
    /// strip and taking its neighbours' patches on the nodes they share,
    /// give every node their stencils reach the bits one process gives it.
    #[test]
    fn nodal_sums_on_any_number_of_ranks_are_one_process_sums() {
        let nodes = [90usize, 40];
        let h = 0.1;
        let grid = StencilGrid {
            origin: DVec2::ZERO,
            inv_cell_size: 1.0 / h,
            nodes,
            walls: [[false; 2]; 2],
        };
        let whole = NodeRect::whole(nodes);
        let stencils: Vec<Stencil> = (0..6000)
            .map(|k| {
                let t = k as Real * 0.618_033_988_75;
                let x = DVec2::new(0.3 + 8.2 * t.fract(), 0.3 + 3.2 * (t * 0.37).fract());
                ShapeFunction::UGimp
                    .stencil(x, DVec2::splat(h / 4.0), &grid)
                    .unwrap()
            })
            .collect();
        let mass = |p: usize| 1.0 + (p % 7) as Real;
        let velocity = |p: usize| DVec2::new((p % 11) as Real - 5.0, 0.3 * (p % 5) as Real);
        // The scatter of the points `ids` (indices into `stencils`).
        let scatter_of = |ids: &[usize], foreign: Option<&Exchange<'_>>| {
            let own: Vec<Stencil> = ids.iter().map(|&p| stencils[p]).collect();
            let bases: Vec<[u32; 2]> = own.iter().map(|s| s.base).collect();
            let mut order = ScatterOrder::default();
            order.sort_by_tile(&bases, whole, nodes);
            let mut scatter = Scatter::<MassMomentumForce>::default();
            scatter.scatter(
                &own,
                &order,
                |k| (mass(ids[k]), velocity(ids[k])),
                |&(m, v), w, g, _| MassMomentumForce {
                    mass: w * m,
                    momentum: (w * m) * v,
                    external_force: g * m,
                },
            );
            let shared = foreign.map(|f| f(&scatter)).unwrap_or_default();
            let mut sums = vec![MassMomentumForce::default(); whole.area()];
            scatter.add_into_with(&shared, &mut sums, (whole, whole), |n, t| *n += t);
            sums
        };
        let all: Vec<usize> = (0..stencils.len()).collect();
        let one = scatter_of(&all, None);
        let column = |p: usize| Strips::column_of(stencils[p].base[0]);
        let grid_columns = Strips::column_of(nodes[0] as u32 - 1) + 1;
        let mut counts = vec![0u64; grid_columns as usize];
        for p in 0..stencils.len() {
            counts[column(p) as usize] += 1;
        }
        for ranks in 1..=4 {
            let strips = Strips::balanced(&counts, ranks);
            std::thread::scope(|scope| {
                for transport in LocalRanks::connected(ranks) {
                    let (strips, one, scatter_of) = (strips.clone(), &one, &scatter_of);
                    let (stencils, column) = (&stencils, &column);
                    scope.spawn(move || {
                        let rank = transport.rank();
                        let domain = Domain::new(Box::new(transport), strips.clone(), grid_columns);
                        let ids: Vec<usize> = (0..stencils.len())
                            .filter(|&p| strips.owner(column(p)) == rank)
                            .collect();
                        let exchange = |s: &Scatter<MassMomentumForce>| exchange_shared(&domain, s);
                        let sums = scatter_of(&ids, Some(&exchange));
                        let mut checked = 0;
                        for &p in &ids {
                            let base = stencils[p].base.map(|k| k as usize);
                            for b in 0..3 {
                                for a in 0..3 {
                                    let k = base[0] + a + (base[1] + b) * nodes[0];
                                    assert_eq!(
                                        bits(&sums[k]),
                                        bits(&one[k]),
                                        "{ranks} ranks, rank {rank}: node {k}"
                                    );
                                    checked += 1;
                                }
                            }
                        }
                        assert!(ids.is_empty() || checked > 0);
                    });
                }
            });
        }
    }
}
