//! One scene stepped on the ranks of an MPI job, checked against the same
//! steps on one process (needs the `mpi` feature):
//!
//! ```text
//! cargo build --release --features mpi --example distributed_state
//! mpirun -n 4 target/release/examples/distributed_state scenes/wave_1d.ron 300
//! ```
//!
//! Rank 0 prints the time the job took for the steps, the state hash and a
//! checksum of every recorded series, and exits with status 1 if any
//! differs from one process's. A rank that
//! panics ends the whole job, naming itself.

use mpdem::distributed::{MpiRanks, Transport, attach, with_all_points};
use mpdem::prelude::*;
use std::cell::Cell;
use std::path::PathBuf;
use std::rc::Rc;

/// The state hash, and each series' file and CRC-32.
fn end_of(sim: &mut Simulation) -> (u64, Vec<(&'static str, u32)>) {
    let series = sim
        .series_files()
        .into_iter()
        .map(|file| {
            let csv = sim.series_csv(file).unwrap_or_default();
            (file, crc32fast::hash(csv.as_bytes()))
        })
        .collect();
    (sim.state_hash(), series)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let (Some(scene), Some(steps)) = (args.next(), args.next()) else {
        eprintln!("usage: distributed_state SCENE STEPS");
        std::process::exit(2);
    };
    let steps: u64 = steps.parse().expect("STEPS: a whole number");
    let ranks = MpiRanks::init().expect("MPI initializes once");
    let (rank, size) = (ranks.rank(), ranks.ranks());
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        eprintln!("rank {rank} of {size} failed: {info}");
        default_hook(info);
        MpiRanks::abort(101);
    }));
    let scene = Scene::load(&PathBuf::from(&scene)).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    let sent = Rc::new(Sent::default());
    let counted = Counted {
        ranks,
        sent: Rc::clone(&sent),
    };
    attach(&mut sim, Box::new(counted)).unwrap_or_else(|e| panic!("{e}"));
    let before = sent.get();
    let started = std::time::Instant::now();
    for _ in 0..steps {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
    let stepped = started.elapsed();
    let (messages, bytes) = sent.get();
    let per_step = |n: u64, before: u64| (n - before) as f64 / steps.max(1) as f64;
    println!(
        "rank {rank} of {size}: {:.1} messages and {:.0} bytes sent a step",
        per_step(messages, before.0),
        per_step(bytes, before.1)
    );
    let Some(distributed) = with_all_points(&mut sim, end_of) else {
        return;
    };
    let mut one = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        one.step().unwrap_or_else(|e| panic!("{e}"));
    }
    let one = end_of(&mut one);
    println!(
        "{size} ranks: {steps} steps in {:.3} s",
        stepped.as_secs_f64()
    );
    println!("{size} ranks: state hash {:016x}", distributed.0);
    for (file, crc) in &distributed.1 {
        println!("{size} ranks: {file} crc32 {crc:08x}");
    }
    if distributed != one {
        println!("one process: state hash {:016x}, series {:?}", one.0, one.1);
        std::process::exit(1);
    }
    println!("{size} ranks: the same as one process");
}

/// Messages and bytes a rank has sent.
#[derive(Default)]
struct Sent(Cell<(u64, u64)>);

impl Sent {
    fn get(&self) -> (u64, u64) {
        self.0.get()
    }

    fn add(&self, bytes: usize) {
        let (m, b) = self.0.get();
        self.0.set((m + 1, b + bytes as u64));
    }
}

/// The job's transport, counting what this rank sends (a gathering counts
/// one message to each other rank).
struct Counted {
    ranks: MpiRanks,
    sent: Rc<Sent>,
}

impl Transport for Counted {
    fn rank(&self) -> usize {
        self.ranks.rank()
    }

    fn ranks(&self) -> usize {
        self.ranks.ranks()
    }

    fn exchange(&self, to: Vec<(usize, Vec<u8>)>, from: &[usize]) -> Vec<Vec<u8>> {
        for (_, bytes) in &to {
            self.sent.add(bytes.len());
        }
        self.ranks.exchange(to, from)
    }

    fn all_gather(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
        for _ in 1..self.ranks() {
            self.sent.add(bytes.len());
        }
        self.ranks.all_gather(bytes)
    }
}
