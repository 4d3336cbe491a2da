//! Running a scene with everything `mpdem run` writes (frames, CSV
//! series, plots, checkpoints) from a program of your own, through the
//! library's `Runner`, with a stop flag you may raise from anywhere.
//!
//! Run with `cargo run --release --example run_with_outputs`.

use mpdem::prelude::*;
use mpdem::runner::{RunOptions, Runner, Start};
use std::sync::atomic::AtomicBool;

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/wave_1d.ron"));
    let mut scene = Scene::load(&path)?;
    scene.time.end = 0.05;
    let out = std::env::temp_dir().join(format!("mpdem-example-run-{}", std::process::id()));
    let options = RunOptions {
        checkpoint_every: Some(0.01),
        start: Start::Restart,
        ..RunOptions::into_folder(&out)
    };
    let mut runner = Runner::new(&scene, Some(&path), options)?;
    let stop = AtomicBool::new(false);
    let summary = runner.run(&stop, |p| {
        if p.step % 100 == 0 {
            println!("step {} of {}, t = {:.3e} s", p.step, p.length, p.time);
        }
    })?;
    println!(
        "{} steps; state hash {:016x}; results in {}",
        summary.steps,
        summary.state_hash,
        summary.dir.display()
    );
    std::fs::remove_dir_all(&out)?;
    Ok(())
}
