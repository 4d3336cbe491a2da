//! Stopping a run, writing its state to a checkpoint, and carrying it on
//! later: the resumed run is bit-identical to one that never stopped.
//!
//! Run with `cargo run --release --example resume`.

use mpdem::prelude::*;

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/two_rings.ron");
    let mut scene = Scene::load(path.as_ref())?;
    scene.time.end = 1e-3;
    let checkpoint = std::env::temp_dir().join(format!("mpdem-example-{}.bin", std::process::id()));

    let mut first = Simulation::from_scene(&scene)?;
    first.run_until(5e-4)?;
    first.write_checkpoint(&checkpoint)?;

    let mut resumed = Simulation::resume(&scene, &checkpoint)?;
    resumed.run()?;
    let mut straight = Simulation::from_scene(&scene)?;
    straight.run()?;
    println!(
        "resumed at step {} of {}: state hash {:016x}, without stopping {:016x}",
        first.clock().step,
        straight.clock().step,
        resumed.state_hash(),
        straight.state_hash()
    );
    std::fs::remove_file(&checkpoint)?;
    if resumed.state_hash() != straight.state_hash() {
        return Err("the resumed run differs".into());
    }
    Ok(())
}
