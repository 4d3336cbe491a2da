//! The transport over MPI (the `mpi` feature): one rank per process of an
//! `mpirun` job.

use super::Transport;
use mpi::datatype::PartitionMut;
use mpi::environment::Universe;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// This process's rank of the MPI job it was started in.
pub struct MpiRanks {
    /// Finalizes MPI when dropped.
    _universe: Universe,
    world: SimpleCommunicator,
}

impl MpiRanks {
    /// Initializes MPI: `None` if it was initialized before. A program
    /// started without `mpirun` is a job of one rank.
    pub fn init() -> Option<Self> {
        let universe = mpi::initialize()?;
        let world = universe.world();
        Some(Self {
            _universe: universe,
            world,
        })
    }

    /// Ends the whole job at once with `code`, from any thread of a
    /// process of the job (after a failure on this rank, which the others
    /// would otherwise wait for).
    pub fn abort(code: i32) -> ! {
        SimpleCommunicator::world().abort(code)
    }
}

impl Transport for MpiRanks {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn ranks(&self) -> usize {
        self.world.size() as usize
    }

    fn exchange(&self, to: Vec<(usize, Vec<u8>)>, from: &[usize]) -> Vec<Vec<u8>> {
        mpi::request::scope(|scope| {
            let sends: Vec<_> = to
                .iter()
                .map(|(rank, bytes)| {
                    self.world
                        .process_at_rank(*rank as i32)
                        .immediate_send(scope, &bytes[..])
                })
                .collect();
            let received = from
                .iter()
                .map(|&rank| {
                    self.world
                        .process_at_rank(rank as i32)
                        .receive_vec::<u8>()
                        .0
                })
                .collect();
            for send in sends {
                send.wait();
            }
            received
        })
    }

    fn all_gather(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
        let ranks = self.ranks();
        let mut lengths = vec![0u64; ranks];
        self.world
            .all_gather_into(&(bytes.len() as u64), &mut lengths[..]);
        if lengths.iter().all(|&n| n == 0) {
            // MPI refuses a gather of nothing; the lengths' gather was the
            // call every rank makes.
            return vec![Vec::new(); ranks];
        }
        let counts: Vec<i32> = lengths.iter().map(|&n| n as i32).collect();
        let starts: Vec<i32> = counts
            .iter()
            .scan(0, |at, &n| {
                let start = *at;
                *at += n;
                Some(start)
            })
            .collect();
        let mut all = vec![0u8; lengths.iter().sum::<u64>() as usize];
        {
            let mut partition = PartitionMut::new(&mut all[..], &counts[..], &starts[..]);
            self.world
                .all_gather_varcount_into(&bytes[..], &mut partition);
        }
        counts
            .iter()
            .zip(&starts)
            .map(|(&n, &start)| all[start as usize..(start + n) as usize].to_vec())
            .collect()
    }
}
