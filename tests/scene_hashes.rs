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
    ("axisymmetric_punch.ron", 0xff890d8a07e8fa7a),
    ("block_on_ground.ron", 0x1c6910f25cb1b279),
    ("circular_footing.ron", 0xabf87e049d380849),
    ("column_collapse.ron", 0x1128b0038a36ed70),
    ("dam_break.ron", 0xaaf9972e19b2ab4c),
    ("elastic_column.ron", 0x1b825400700f46b5),
    ("geostatic_column.ron", 0xdebaa4daaa25eb85),
    ("granular_collapse_bui.ron", 0x47ee834829b07451),
    ("granular_slab.ron", 0xbf0a299b8be6137f),
    ("hertz_disks.ron", 0xe34b374a911de2c5),
    ("pile_penetration.ron", 0x531af9a72f49c376),
    ("pile_penetration_axisymmetric.ron", 0x281bfc1cf401e21b),
    ("rigid_drop.ron", 0x6dc257a3d1bc84a3),
    ("rigid_tip.ron", 0x0b0e92d9e2f72adb),
    ("sliding_45.ron", 0xc088f66365b9ba31),
    ("stacked_blocks.ron", 0xb62e410b3f3ec1e0),
    ("strip_footing.ron", 0x5cc766d766dd9aa6),
    ("toppling_14.ron", 0x176867ad54d76f86),
    ("toppling_16.ron", 0xed1a58fdaa918b35),
    ("toppling_18.ron", 0x8b6258e1a6ce2ee9),
    ("toppling_20.ron", 0x26333d5171c20622),
    ("two_rings.ron", 0x2138579752f4ab97),
    ("wave_1d.ron", 0xa621e35cac6734b6),
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
