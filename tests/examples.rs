//! Every example runs to its end without an error: one per extension
//! point (a user system, a scene built in code, stages, resuming from a
//! checkpoint, running with the outputs from a program).

#[path = "../examples/custom_system.rs"]
mod custom_system;
#[path = "../examples/resume.rs"]
mod resume;
#[path = "../examples/run_with_outputs.rs"]
mod run_with_outputs;
#[path = "../examples/scene_in_code.rs"]
mod scene_in_code;
#[path = "../examples/stages.rs"]
mod stages;

#[test]
fn a_user_system() {
    custom_system::main().expect("the example runs");
}

#[test]
fn a_scene_built_in_code() {
    scene_in_code::main().expect("the example runs");
}

#[test]
fn stages_in_code() {
    stages::main().expect("the example runs");
}

#[test]
fn resuming_from_a_checkpoint() {
    resume::main().expect("the example runs");
}

#[test]
fn running_with_the_outputs() {
    run_with_outputs::main().expect("the example runs");
}
