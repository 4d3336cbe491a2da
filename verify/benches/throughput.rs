//! Throughput of the standard elastic block (`mpdem bench` without the CLI):
//! particle-updates per second at 10k, 40k and 160k points on the global
//! thread pool. Run with `cargo bench` (release profile).

use mpdem::Simulation;
use mpdem_verify::bench::{elastic_block_scene, measure, threads_label};

fn main() {
    for points in [10_000, 40_000, 160_000] {
        let scene = elastic_block_scene(points);
        let result = Simulation::from_scene(&scene)
            .map_err(|e| e.to_string())
            .and_then(|mut sim| measure(&mut sim, 5, 100).map_err(|e| e.to_string()));
        match result {
            Ok(t) => println!(
                "elastic block, {} points, {}: {:.2} M particle-updates/s",
                t.points,
                threads_label(),
                t.updates_per_second() / 1e6
            ),
            Err(e) => eprintln!("bench failed: {e}"),
        }
    }
}
