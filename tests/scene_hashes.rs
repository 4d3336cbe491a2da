//! Every shipped scene's state after its first 100 steps, pinned by its
//! state hash: a change that moves one changes the engine's results, and
//! its commit says why. (Rust float arithmetic is IEEE without contraction;
//! scenes with expression fields call libm, so their hashes hold on this
//! project's x86-64 Linux machines.)

mod common;

use mpdem::prelude::*;

const STEPS: u64 = 100;

/// (scene file, state hash after `STEPS` steps).
const PINNED: &[(&str, u64)] = &[
    ("axisymmetric_punch.ron", 0x42e273b8d8974872),
    ("block_on_ground.ron", 0x4fbed33aa69f083b),
    ("circular_footing.ron", 0xa233b7e990fb4b64),
    ("column_collapse.ron", 0x3c35c822cc0cdd3a),
    ("dam_break.ron", 0x848c7d2dd5726860),
    ("elastic_column.ron", 0x5a215d03792a755b),
    ("geostatic_column.ron", 0xc9f7de9f4488a1ad),
    ("granular_collapse_bui.ron", 0x0d15eace16529ca9),
    ("granular_slab.ron", 0x809063ee51aad227),
    ("hertz_disks.ron", 0xbf8384653b8a8555),
    ("pile_penetration.ron", 0x7070aac1170bd179),
    ("pile_penetration_axisymmetric.ron", 0xfcc6edc8acfbfda9),
    ("rigid_drop.ron", 0x6dc257a3d1bc84a3),
    ("rigid_tip.ron", 0x0b0e92d9e2f72adb),
    ("sliding_45.ron", 0xdfd1106791f3df8c),
    ("stacked_blocks.ron", 0x7de56ee5d66af5cb),
    ("strip_footing.ron", 0xba6201f8508505d8),
    ("toppling_14.ron", 0x874217670774047b),
    ("toppling_16.ron", 0xeeb23c6d78316156),
    ("toppling_18.ron", 0x93d028cbb40431c8),
    ("toppling_20.ron", 0xe4abe6f837c40872),
    ("two_rings.ron", 0x656b58610190aec6),
    ("wave_1d.ron", 0xbdb5c1f1a4df64b8),
];

#[test]
fn every_shipped_scene_gives_its_pinned_state() {
    let mut files: Vec<String> = std::fs::read_dir(common::scene_path(""))
        .expect("scenes/")
        .map(|e| {
            e.expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|name| name.ends_with(".ron"))
        .collect();
    files.sort();
    let mut found = Vec::new();
    for file in &files {
        let mut sim =
            Simulation::from_scene(&common::load_scene(file)).unwrap_or_else(|e| panic!("{e}"));
        for _ in 0..STEPS {
            sim.step().unwrap_or_else(|e| panic!("{file}: {e}"));
        }
        found.push((file.clone(), sim.state_hash()));
    }
    let listing: String = found
        .iter()
        .map(|(file, hash)| format!("    (\"{file}\", 0x{hash:016x}),\n"))
        .collect();
    let pinned: Vec<(String, u64)> = PINNED.iter().map(|(f, h)| (f.to_string(), *h)).collect();
    assert_eq!(found, pinned, "the scenes' hashes now:\n{listing}");
}
