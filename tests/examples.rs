//! Every example runs to its end without an error: one per extension
//! point (a user system, a constitutive model defined outside the crate,
//! a recorded quantity added by a plugin, the built-in plugins disabled
//! and replaced, a scene
//! built in code, stages, resuming from a checkpoint, running with the
//! outputs from a program).

#[path = "../examples/custom_model.rs"]
mod custom_model;
#[path = "../examples/custom_system.rs"]
mod custom_system;
#[path = "../examples/plugin_group.rs"]
mod plugin_group;
#[path = "../examples/recorded_quantity.rs"]
mod recorded_quantity;
#[path = "../examples/resume.rs"]
mod resume;
#[path = "../examples/run_with_outputs.rs"]
mod run_with_outputs;
#[path = "../examples/scene_in_code.rs"]
mod scene_in_code;
#[path = "../examples/stages.rs"]
mod stages;

#[test]
fn a_constitutive_model_defined_outside_the_crate() {
    custom_model::main()
        .expect("the example runs and its points stay on or inside the yield surface");
}

#[test]
fn the_built_in_plugins_changed() {
    plugin_group::main().expect("the records disabled, the core replaced, duplicates refused");
}

#[test]
fn a_user_system() {
    custom_system::main().expect("the example runs");
}

#[test]
fn a_recorded_quantity_written_and_resumed() {
    recorded_quantity::main()
        .expect("the example runs and its resumed series is the straight one's");
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
