//! Distributed runs: one scene on many processes, each stepping the points
//! of its strip of the grid, with the same results as one process (see
//! `docs/distributed.md`).
//!
//! A process owns whole columns of the scatter's tiles ([`Strips`]), so it
//! forms every patch of its tiles as one process does; the nodes on the
//! edge of its strip also take patches of its neighbours' tiles, which
//! the halo exchange brings, in their tiles' places. The engine talks to
//! the other processes through a [`Transport`]: the command line's `mpi`
//! feature gives one over MPI, and [`LocalRanks`] one over channels between
//! threads.

mod contacts;
mod failures;
mod halo;
mod lists;
#[cfg(feature = "mpi")]
mod mpi_ranks;
mod points;
mod records;
mod strips;
mod transport;

pub(crate) use contacts::{
    ContactHalfSizes, SharedContact, add_in_order, largest, local_index, share_contacts,
};
pub(crate) use halo::foreign_patches;
#[cfg(feature = "mpi")]
pub use mpi_ranks::MpiRanks;
pub use points::{
    DistributeError, PointIds, REBALANCE_EVERY, attach, unsupported_parts, with_all_points,
};
pub(crate) use records::{add_tile_sums, gather_columns, record_probes};
pub use strips::Strips;
pub use transport::{LocalRanks, Transport};

use std::ops::Range;

/// This process's part of a distributed run, held by its world as a
/// non-send resource (a transport may be tied to the thread that made it).
pub struct Domain {
    transport: Box<dyn Transport>,
    strips: Strips,
    /// Tile columns of the whole grid.
    grid_columns: u32,
}

impl Domain {
    /// A domain over `transport`, cut into `strips` over a grid of
    /// `grid_columns` tile columns.
    pub fn new(transport: Box<dyn Transport>, strips: Strips, grid_columns: u32) -> Self {
        assert_eq!(strips.ranks(), transport.ranks(), "a strip for every rank");
        Self {
            transport,
            strips,
            grid_columns,
        }
    }

    /// This process's rank.
    pub fn rank(&self) -> usize {
        self.transport.rank()
    }

    /// The number of processes.
    pub fn ranks(&self) -> usize {
        self.transport.ranks()
    }

    /// The strips of every rank.
    pub fn strips(&self) -> &Strips {
        &self.strips
    }

    /// The messages to the other processes.
    pub fn transport(&self) -> &dyn Transport {
        &*self.transport
    }

    /// The ranks this one shares nodes with, and the node columns shared.
    pub fn neighbours(&self) -> Vec<(usize, Range<usize>)> {
        self.strips.neighbours(self.rank(), self.grid_columns)
    }
}
