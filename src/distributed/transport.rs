//! How the processes of a distributed run talk: the few operations the
//! step needs, over bytes, so that the engine does not depend on MPI. The
//! command line's `mpi` feature implements them with MPI; [`LocalRanks`]
//! implements them with threads and channels in one process, for tests.

use std::sync::mpsc::{Receiver, Sender, channel};

/// The messages of a distributed run. Every process makes the same calls
/// in the same order; messages between two processes arrive in the order
/// they were sent.
pub trait Transport {
    /// This process's rank, 0 to [`Self::ranks`] − 1.
    fn rank(&self) -> usize;

    /// The number of processes.
    fn ranks(&self) -> usize;

    /// Sends each message of `to` to its rank, then receives one message
    /// from each rank of `from`, returned in that order. A rank sent to
    /// lists this one in its `from` of the same call.
    fn exchange(&self, to: Vec<(usize, Vec<u8>)>, from: &[usize]) -> Vec<Vec<u8>>;

    /// Every rank's `bytes`, in rank order: every process calls it.
    fn all_gather(&self, bytes: Vec<u8>) -> Vec<Vec<u8>>;
}

/// One rank of a distributed run held in one process: each rank's
/// simulation steps on its own thread, and messages go through channels.
pub struct LocalRanks {
    rank: usize,
    /// A sender to every rank, this one's included.
    to: Vec<Sender<Vec<u8>>>,
    /// A receiver from every rank, this one's included.
    from: Vec<Receiver<Vec<u8>>>,
}

impl LocalRanks {
    /// The `ranks` connected ends, rank 0 first.
    pub fn connected(ranks: usize) -> Vec<Self> {
        // channels[s][r] carries messages from s to r.
        let mut senders: Vec<Vec<Sender<Vec<u8>>>> = (0..ranks).map(|_| Vec::new()).collect();
        let mut receivers: Vec<Vec<Receiver<Vec<u8>>>> = (0..ranks).map(|_| Vec::new()).collect();
        for sending in senders.iter_mut() {
            for receiving in receivers.iter_mut() {
                let (tx, rx) = channel();
                sending.push(tx);
                receiving.push(rx);
            }
        }
        senders
            .into_iter()
            .zip(receivers)
            .enumerate()
            .map(|(rank, (to, from))| Self { rank, to, from })
            .collect()
    }

    fn send(&self, rank: usize, bytes: Vec<u8>) {
        self.to[rank]
            .send(bytes)
            .unwrap_or_else(|_| panic!("rank {rank} has ended"));
    }

    fn receive(&self, rank: usize) -> Vec<u8> {
        self.from[rank]
            .recv()
            .unwrap_or_else(|_| panic!("rank {rank} has ended"))
    }
}

impl Transport for LocalRanks {
    fn rank(&self) -> usize {
        self.rank
    }

    fn ranks(&self) -> usize {
        self.to.len()
    }

    fn exchange(&self, to: Vec<(usize, Vec<u8>)>, from: &[usize]) -> Vec<Vec<u8>> {
        for (rank, bytes) in to {
            self.send(rank, bytes);
        }
        from.iter().map(|&rank| self.receive(rank)).collect()
    }

    fn all_gather(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
        for rank in 0..self.ranks() {
            self.send(rank, bytes.clone());
        }
        (0..self.ranks()).map(|rank| self.receive(rank)).collect()
    }
}
