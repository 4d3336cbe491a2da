//! One scene stepped on the ranks of an MPI job, checked against the same
//! steps on one process (needs the `mpi` feature):
//!
//! ```text
//! cargo build --release --features mpi --example distributed_state
//! mpirun -n 4 target/release/examples/distributed_state scenes/wave_1d.ron 300
//! ```
//!
//! Rank 0 prints the state hash and a checksum of every recorded series,
//! and exits with status 1 if any differs from one process's. A rank that
//! panics ends the whole job, naming itself.

use mpdem::distributed::{MpiRanks, Transport, attach, with_all_points};
use mpdem::prelude::*;
use std::path::PathBuf;

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
    attach(&mut sim, Box::new(ranks)).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
    let Some(distributed) = with_all_points(&mut sim, end_of) else {
        return;
    };
    let mut one = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        one.step().unwrap_or_else(|e| panic!("{e}"));
    }
    let one = end_of(&mut one);
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
