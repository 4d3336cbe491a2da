//! `output.animation` writes `animation.gif`: one GIF frame per VTK frame
//! of a short run, which show the points moving.

mod common;

use mpdem::prelude::*;
use mpdem::runner::{RunOptions, Runner, Start};
use mpdem::scene::AnimatedField;
use std::sync::atomic::AtomicBool;

/// The frames of the GIF at `path`, as RGBA buffers, with the image size.
fn gif_frames(path: &std::path::Path) -> (Vec<Vec<u8>>, (u16, u16)) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut decoder = options.read_info(file).expect("a GIF");
    let size = (decoder.width(), decoder.height());
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().expect("a GIF frame") {
        frames.push(frame.buffer.to_vec());
    }
    (frames, size)
}

#[test]
fn an_animation_has_a_frame_per_vtk_frame_and_shows_the_motion() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/elastic_column.ron");
    let mut scene = Scene::load(path.as_ref()).unwrap_or_else(|e| panic!("{e}"));
    // 0.1 s: the column falls under gravity against the fixed base.
    scene.time.end = 0.1;
    scene.output.frame_interval = Some(0.01);
    scene.output.animation = Some(AnimatedField::Displacement);
    let out = common::TempFolder::new("animation");
    let options = RunOptions {
        start: Start::Restart,
        ..RunOptions::into_folder(out.to_path_buf())
    };
    let mut runner = Runner::new(&scene, None, options).unwrap_or_else(|e| panic!("{e}"));
    runner
        .run(&AtomicBool::new(false), |_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    let (frames, (width, height)) = gif_frames(&out.join("animation.gif"));
    let listed = std::fs::read_to_string(out.join("outputs.txt")).expect("the list");
    // Frames at t = 0, 0.01, ..., 0.1.
    assert_eq!(frames.len(), 11);
    assert_eq!(width, 1000);
    assert!(height >= 300, "{height}");
    assert!(
        frames.first() != frames.last(),
        "the first and last frames are the same picture"
    );
    assert!(listed.lines().any(|l| l == "animation.gif"), "{listed}");
}
