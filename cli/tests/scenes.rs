//! Every scene in `scenes/` is valid; bad input is refused with the file,
//! line and column and what was expected, and nothing is written.

mod common;

use mpdem::prelude::*;
use mpdem::scene::SceneError;
use std::path::Path;

#[test]
fn every_shipped_scene_is_valid() {
    let dir = common::repository_root().join("scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "ron") {
            let sim = Simulation::from_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                sim.warnings().is_empty(),
                "{}: {:?}",
                path.display(),
                sim.warnings()
            );
            count += 1;
        }
    }
    assert!(count >= 2);
}

/// The wave scene with `from` replaced by `to`, parsed as `bad.ron`.
fn parse_edited(from: &str, to: &str) -> SceneError {
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron")).unwrap();
    assert!(
        text.contains(from),
        "fixture text '{from}' not in wave_1d.ron"
    );
    let edited = text.replacen(from, to, 1);
    Scene::parse(&edited, Path::new("bad.ron")).expect_err("bad scene accepted")
}

/// 1-based line of the first occurrence of `needle` in the edited wave scene.
fn line_of(from: &str, to: &str, needle: &str) -> usize {
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron"))
        .unwrap()
        .replacen(from, to, 1);
    text[..text.find(needle).unwrap()].matches('\n').count() + 1
}

fn assert_error(error: SceneError, line: usize, expected: &str) {
    let message = error.to_string();
    assert!(
        message.starts_with(&format!("bad.ron:{line}:")),
        "wrong place: {message}"
    );
    assert!(
        message.contains(expected),
        "'{message}' does not say '{expected}'"
    );
}

#[test]
fn a_density_outside_the_range_of_materials_is_refused() {
    let e = parse_edited("density: 1000.0", "density: -5.0");
    assert_error(
        e,
        line_of("density: 1000.0", "density: -5.0", "density: -5.0"),
        "expected a density from 0.1 to 1e9 kg/m³, got -5 kg/m³",
    );
}

#[test]
fn incompressible_poisson_ratio_is_refused() {
    let e = parse_edited("poisson_ratio: 0.0", "poisson_ratio: 0.5");
    assert_error(
        e,
        line_of(
            "poisson_ratio: 0.0",
            "poisson_ratio: 0.5",
            "poisson_ratio: 0.5",
        ),
        "Poisson's ratio in (-1, 0.5), got 0.5",
    );
}

#[test]
fn non_positive_time_step_is_refused() {
    let e = parse_edited("dt: 1e-4", "dt: 0.0");
    assert_error(
        e,
        line_of("dt: 1e-4", "dt: 0.0", "dt: 0.0"),
        "expected a finite value > 0, got 0",
    );
}

#[test]
fn the_end_may_be_given_as_a_number_of_steps() {
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron")).unwrap();
    let by_steps = text.replacen("end: 1.0", "steps: 10000", 1);
    let scene = Scene::parse(&by_steps, Path::new("steps.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.time.end, 10000.0 * 1e-4);
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.clock().total_steps(), 10000);

    let both = parse_edited("end: 1.0", "end: 1.0, steps: 10");
    let line = line_of("end: 1.0", "end: 1.0, steps: 10", "steps: 10");
    assert_error(both, line, "time takes end (s) or steps, not both");
    let neither = parse_edited("dt: 1e-4, end: 1.0", "dt: 1e-4");
    let line = line_of("dt: 1e-4, end: 1.0", "dt: 1e-4", "dt: 1e-4");
    assert_error(neither, line, "time needs end (s) or steps");
    // Written over several lines, the error still points at the entry.
    let spread = "time: (\n        dt: 1e-4,\n        end: 1.0,\n        steps: 10,\n    ),";
    let both = parse_edited("time: (dt: 1e-4, end: 1.0),", spread);
    assert_error(
        both,
        line_of("time: (dt: 1e-4, end: 1.0),", spread, "time: ("),
        "not both",
    );
    let zero = parse_edited("end: 1.0", "steps: 0");
    let line = line_of("end: 1.0", "steps: 0", "steps: 0");
    assert_error(zero, line, "expected a number of steps ≥ 1, got 0");
}

#[test]
fn unknown_fields_are_refused() {
    let e = parse_edited("points_per_cell: 2", "points_per_cel: 2");
    assert_error(
        e,
        line_of("points_per_cell: 2", "points_per_cel: 2", "points_per_cel"),
        "points_per_cel",
    );
}

#[test]
fn unknown_fields_inside_variants_are_refused() {
    // A misspelt optional field inside an enum's variant (a block's motion,
    // a shape, an initial state, a stage's end) would otherwise be skipped
    // and its default taken without a word.
    let cases = [
        (
            "pile_penetration.ron",
            "Kinematic((linear: (0.0, 0.0), angular: 0.0))",
            "Kinematic((linear: (0.0, 0.0), angluar: 0.0))",
            "angluar",
        ),
        (
            "rigid_drop.ron",
            "Dynamic(density: 2500.0)",
            "Dynamic(density: 2500.0, velocty: (linear: (0.0, 1.0)))",
            "velocty",
        ),
        (
            "rigid_drop.ron",
            "Cuboid(half_extents: (0.2, 0.1))",
            "Cuboid(half_extents: (0.2, 0.1), rounding: 0.01)",
            "rounding",
        ),
        (
            "rigid_drop.ron",
            "gravity: (0.0, -9.81),",
            "gravity: (0.0, -9.81), contact: (force_application: Traction(points: 5, pionts: 3)),",
            "pionts",
        ),
        (
            "wave_1d.ron",
            "Rectangle(min: (0.0, 0.0), max: (1.0, 0.01))",
            "Rectangle(min: (0.0, 0.0), max: (1.0, 0.01), points_per_cell: 4)",
            "points_per_cell",
        ),
        (
            "wave_1d.ron",
            "Field(x: \"x*(1-x)\", y: \"0\")",
            "Field(x: \"x*(1-x)\", y: \"0\", z: \"1\")",
            "`z`",
        ),
        (
            "column_collapse.ron",
            "Geostatic(k0: 0.4554)",
            "Geostatic(k0: 0.4554, surfce: Some(3.0))",
            "surfce",
        ),
        (
            "pile_penetration.ron",
            "KineticEnergyRatio(ratio: 1e-10, max_time: 5.0)",
            "KineticEnergyRatio(ratio: 1e-10, max_time: 5.0, ratoi: 1e-3)",
            "ratoi",
        ),
    ];
    for (file, from, to, field) in cases {
        let text = std::fs::read_to_string(common::scene_path(file)).unwrap();
        assert!(text.contains(from), "fixture text '{from}' not in {file}");
        let edited = text.replacen(from, to, 1);
        let line = edited[..edited.find(to).unwrap()].matches('\n').count() + 1;
        let error = Scene::parse(&edited, Path::new("bad.ron"))
            .expect_err(&format!("{file} with '{to}' accepted"));
        assert_error(error, line, field);
    }
}

#[test]
fn unknown_material_names_are_refused() {
    let from = "material: \"bar\"";
    let e = parse_edited(from, "material: \"steel\"");
    assert_error(
        e,
        line_of(from, "material: \"steel\"", "material: \"steel\""),
        "unknown material 'steel'",
    );
}

#[test]
fn bodies_outside_the_grid_are_refused() {
    let from = "max: (1.0, 0.01)";
    let e = parse_edited(from, "max: (1.5, 0.01)");
    assert_error(
        e,
        line_of(from, "max: (1.5, 0.01)", "shape:"),
        "is not inside the grid",
    );
}

#[test]
fn geostatic_stress_needs_gravity_pointing_down() {
    let mut scene = common::load_scene("elastic_column.ron");
    scene.bodies[0].initial_stress = Some(mpdem::scene::InitialStress::Geostatic {
        k0: 0.5,
        surface: None,
    });
    assert!(Simulation::from_scene(&scene).is_ok());
    scene.gravity = DVec2::new(0.0, 9.81);
    let message = common::refusal(&scene);
    assert!(message.contains("gravity pointing down"), "{message}");
}

#[test]
fn non_finite_values_are_refused() {
    let e = parse_edited("at: (0.5, 0.005)", "at: (inf, 0.005)");
    assert_error(
        e,
        line_of("at: (0.5, 0.005)", "at: (inf, 0.005)", "at: (inf"),
        "location must be finite",
    );
    let e = parse_edited(
        "min: (0.0, 0.0), max: (1.0, 0.01)",
        "min: (0.0, NaN), max: (1.0, 0.01)",
    );
    assert!(e.to_string().contains("finite"), "{e}");
}

#[test]
fn a_time_step_above_the_cfl_limit_warns_with_the_limit() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.time.dt = 1e-3;
    scene.output.probe_interval = Some(1e-3);
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.warnings().len(), 1, "{:?}", sim.warnings());
    assert!(
        sim.warnings()[0]
            .message
            .contains("CFL limit h / c = 5.0000e-4 s"),
        "{}",
        sim.warnings()[0]
    );
}

#[test]
fn a_run_of_a_bad_scene_writes_nothing() {
    let (dir, scene) = common::edited_wave_scene("bad", "density: 1000.0", "density: 0.0");
    let out = dir.join("out");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_mpdem"))
        .args([
            "run",
            scene.to_str().unwrap(),
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!status.status.success());
    let stderr = String::from_utf8_lossy(&status.stderr);
    assert!(
        stderr.contains(&format!("{}:", scene.display()))
            && stderr.contains("expected a density from 0.1"),
        "{stderr}"
    );
    assert!(!out.exists(), "output written for a bad scene");
}

#[test]
fn damping_above_one_and_xpic_orders_out_of_range_are_refused() {
    let from = "position_update: Some(PaperEq11b))";
    for (to, expected) in [
        (
            "position_update: Some(PaperEq11b), grid_damping: 1.5)",
            "expected a damping coefficient in [0, 1], got 1.5",
        ),
        (
            "position_update: Some(PaperEq11b), particle_damping: -0.1)",
            "expected a damping coefficient in [0, 1], got -0.1",
        ),
        (
            "position_update: Some(PaperEq11b), xpic_order: Some(0))",
            "expected an XPIC order from 1 to 10, got 0",
        ),
        (
            "position_update: Some(PaperEq11b), xpic_order: Some(11))",
            "expected an XPIC order from 1 to 10, got 11",
        ),
    ] {
        assert_error(parse_edited(from, to), line_of(from, to, to), expected);
    }
}

#[test]
fn names_that_become_file_names_may_not_leave_the_output_folder() {
    let from = "name: Some(\"wave_1d\")";
    for (to, expected) in [
        ("name: Some(\"../../up\")", "starts with '.'"),
        ("name: Some(\"a/b\")", "holds '/'"),
        ("name: Some(\"\")", "got an empty one"),
        ("name: Some(\"C:up\")", "holds ':'"),
        ("name: Some(\"nul.run\")", "is a device on Windows"),
        ("name: Some(\"wave.\")", "ends with '.' or a space"),
    ] {
        assert_error(parse_edited(from, to), line_of(from, to, to), expected);
    }
    // A name taken from the file's stem is checked too.
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron")).unwrap();
    let unnamed = text.replacen(&format!("{from},"), "", 1);
    let e = Scene::parse(&unnamed, Path::new(".hidden.ron")).expect_err("hidden name accepted");
    assert!(
        e.to_string().starts_with(".hidden.ron: ") && e.to_string().contains("give it a `name`"),
        "{e}"
    );
}

#[test]
fn curves_and_probes_may_not_overwrite_other_files() {
    let text = std::fs::read_to_string(common::scene_path("pile_penetration.ron")).unwrap();
    let from = "name: \"qc\"";
    assert!(
        text.contains(from),
        "fixture text '{from}' not in the pile scene"
    );
    for (to, expected) in [
        ("name: \"energy\"", "would overwrite the run's own files"),
        ("name: \"probe_qc\"", "would overwrite the run's own files"),
        ("name: \"Energy\"", "would overwrite the run's own files"),
        ("name: \"../qc\"", "starts with '.'"),
    ] {
        let edited = text.replacen(from, to, 1);
        let e = Scene::parse(&edited, Path::new("bad.ron")).expect_err("curve name accepted");
        let line = edited[..edited.find(to).unwrap()].matches('\n').count() + 1;
        assert_error(e, line, expected);
    }
    let probe = "(name: \"midpoint\", body: \"bar\", at: (0.5, 0.005)),";
    let two = "(name: \"mid point\", body: \"bar\", at: (0.5, 0.005)), (name: \"mid_point\", body: \"bar\", at: (0.5, 0.005)),";
    assert_error(
        parse_edited(probe, two),
        line_of(probe, two, "\"mid_point\""),
        "probes 'mid point' and 'mid_point' would write the same plot files",
    );
}

#[test]
fn a_byte_order_mark_is_ignored() {
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron")).unwrap();
    let with_mark = format!("\u{feff}{text}");
    let scene = Scene::parse(&with_mark, Path::new("mark.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene, Scene::parse(&text, Path::new("mark.ron")).unwrap());
}

#[test]
fn a_point_count_beyond_memory_is_refused_before_the_points_are_made() {
    // 1e-4 m cells of 8 × 8 points on the 1 m × 0.01 m bar: 6.4e7 points
    // (about 32 GB); refused from the bar's extent, without making them.
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron")).unwrap();
    let edited = text
        .replacen("cell_size: 0.005,", "cell_size: 0.0001,", 1)
        .replacen("cells: (200, 2),", "cells: (10000, 100),", 1)
        .replacen("points_per_cell: 2,", "points_per_cell: 8,", 1);
    let e = Scene::parse(&edited, Path::new("bad.ron")).expect_err("6.4e7 points accepted");
    let line = edited[..edited.find("shape:").unwrap()]
        .matches('\n')
        .count()
        + 1;
    assert_error(e, line, "about 6.4");
}

#[test]
fn a_kinetic_energy_ratio_above_one_is_refused() {
    let text = std::fs::read_to_string(common::scene_path("geostatic_column.ron")).unwrap();
    let (from, to) = ("ratio: 1e-10", "ratio: 2.0");
    let edited = text.replacen(from, to, 1);
    let e = Scene::parse(&edited, Path::new("bad.ron")).expect_err("ratio 2 accepted");
    let line = edited[..edited.find(to).unwrap()].matches('\n').count() + 1;
    assert_error(e, line, "expected a ratio in (0, 1], got 2");
    // A scene built in code is checked by the same rule.
    let mut scene = Scene::parse(&text, Path::new("ok.ron")).unwrap();
    scene.stages[0].end = mpdem::scene::StageEnd::KineticEnergyRatio {
        ratio: 0.0,
        max_time: 1.0,
    };
    let refusal = scene.validate().expect_err("ratio 0 accepted").to_string();
    assert!(
        refusal.contains("expected a ratio in (0, 1], got 0"),
        "{refusal}"
    );
}

#[test]
fn a_stage_built_in_code_is_checked_by_the_files_ranges() {
    let scene = common::load_scene("geostatic_column.ron");
    type Setter = fn(&mut mpdem::scene::StageSpec);
    let cases: [(Setter, &str); 3] = [
        (|s| s.pic_fraction = Some(1.5), "pic_fraction: "),
        (|s| s.grid_damping = Some(-1.0), "grid_damping: "),
        (|s| s.particle_damping = Some(1.2), "particle_damping: "),
    ];
    for (set, expected) in cases {
        let mut bad = scene.clone();
        set(&mut bad.stages[0]);
        let refusal = bad.validate().expect_err(expected).to_string();
        assert!(refusal.contains(expected), "{refusal}");
    }
}

#[test]
fn an_end_off_the_time_step_warns_with_the_steps_taken() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.time.end = 1.5e-4;
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.clock().total_steps(), 1);
    assert_eq!(sim.warnings().len(), 1, "{:?}", sim.warnings());
    assert!(
        sim.warnings()[0]
            .message
            .contains("not a multiple of time.dt = 1e-4 s")
            && sim.warnings()[0].message.contains("1, to t = 1e-4 s"),
        "{}",
        sim.warnings()[0]
    );
    // Half a step off a long run is as far from the asked end.
    scene.time.end = 0.20005;
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.warnings().len(), 1, "{:?}", sim.warnings());
    // A multiple of the step, however long, says nothing.
    scene.time.end = 0.2;
    let sim = Simulation::from_scene(&scene).unwrap();
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
}

#[test]
fn a_frame_at_every_step_of_a_long_run_warns_with_the_room_it_takes() {
    // wave_1d: 10 000 steps of 1e-4 s. A frame every step writes 10 001
    // frames of its points, past the ten thousand that draw a warning;
    // every other step, 5 001, draws none.
    let mut scene = common::load_scene("wave_1d.ron");
    scene.output.frame_interval = Some(1e-4);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let bodies = sim.bodies();
    let points: usize = bodies
        .iter()
        .map(|(entity, _)| sim.points(*entity).map_or(0, |p| p.len()))
        .sum();
    let warnings = common::warning_text(sim.warnings());
    assert!(
        warnings.contains(&format!(
            "output: the run writes up to 10001 VTK frames (one every 1 steps), about {:.1} GB for its {points} points",
            10001.0 * points as f64 * 220.0 / 1e9
        )),
        "{warnings}"
    );
    scene.output.frame_interval = Some(2e-4);
    let sim = Simulation::from_scene(&scene).unwrap();
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
}

#[test]
fn output_intervals_off_the_time_step_warn_with_the_steps_taken() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.output.frame_interval = Some(2.5e-4);
    scene.output.probe_interval = Some(1.4e-4);
    let sim = Simulation::from_scene(&scene).unwrap();
    let warnings = common::warning_text(sim.warnings());
    assert!(
        warnings.contains("output.frame_interval = 2.5e-4 s is not a multiple of time.dt = 1e-4 s: frames are written every 3 step(s), 3e-4 s"),
        "{warnings}"
    );
    assert!(
        warnings.contains("output.probe_interval = 1.4e-4 s is not a multiple of time.dt = 1e-4 s: probes and energy are sampled every 1 step(s), 1e-4 s"),
        "{warnings}"
    );
    // Multiples of the step, and the defaults, say nothing.
    scene.output.frame_interval = Some(3e-4);
    scene.output.probe_interval = None;
    let sim = Simulation::from_scene(&scene).unwrap();
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
}

#[test]
fn stages_of_fixed_durations_that_time_end_cuts_are_warned_by_their_steps() {
    // dt = 1e-4 s. Each stage ends on the first step whose elapsed time
    // reaches its duration less half a step: 0.50004 s and 0.49996 s both
    // take 5 000 steps, so two of either take 10 000.
    let mut scene = common::load_scene("wave_1d.ron");
    let cuts = |scene: &Scene| {
        let sim = Simulation::from_scene(scene).unwrap();
        sim.warnings()
            .iter()
            .any(|w| w.message.contains("cuts stage 'second'"))
    };
    for (duration, end, cut) in [(0.50004, 1.0, false), (0.49996, 0.9999, true)] {
        scene.stages = vec![
            mpdem::scene::StageSpec::new("first", mpdem::scene::StageEnd::Duration(duration)),
            mpdem::scene::StageSpec::new("second", mpdem::scene::StageEnd::Duration(duration)),
        ];
        scene.time.end = end;
        assert_eq!(cuts(&scene), cut, "{duration} s twice, end {end} s");
    }
}

#[test]
fn an_initial_stress_the_material_would_replace_is_refused() {
    // Neo-Hookean stress follows F, which starts at I: the geostatic stress
    // would be gone after the first step.
    let mut scene = common::load_scene("column_collapse.ron");
    assert!(scene.bodies[0].initial_stress.is_some());
    scene.materials[0].model =
        mpdem::materials::MaterialModel::NeoHookean(mpdem::materials::NeoHookean {
            youngs_modulus: 2e7,
            poisson_ratio: 0.2,
        });
    let refusal = scene.validate().expect_err("accepted").to_string();
    assert!(
        refusal.contains("computes its stress from the deformation"),
        "{refusal}"
    );
}

#[test]
fn the_affine_transfer_with_the_linear_kernel_is_refused() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.settings.affine_transfer = true;
    scene.settings.shape_function = mpdem::shape_functions::ShapeFunction::Linear;
    let refusal = scene.validate().expect_err("accepted").to_string();
    assert!(refusal.contains("with the Linear kernel"), "{refusal}");
    scene.settings.shape_function = mpdem::shape_functions::ShapeFunction::UGimp;
    assert!(scene.validate().is_ok());
}

#[test]
fn a_probe_far_from_its_body_warns() {
    let mut scene = common::load_scene("wave_1d.ron");
    scene.probes[0].at = DVec2::new(0.5, 0.5);
    let sim = Simulation::from_scene(&scene).unwrap();
    let warnings = common::warning_text(sim.warnings());
    assert!(
        warnings.contains("probe 'midpoint' at [0.5, 0.5] records the nearest point of body 'bar'"),
        "{warnings}"
    );
}

#[test]
fn a_name_used_twice_is_placed_at_its_second_use() {
    // The body "bar" of material "bar" twice: the error points at the
    // second body's name, not at a later "bar" inside the first body.
    let body = "            velocity: Field(x: \"x*(1-x)\", y: \"0\"),\n        ),";
    let two = format!(
        "{body}\n        (\n            name: \"bar\",\n            material: \"bar\",\n            shape: Rectangle(min: (0.0, 0.0), max: (0.5, 0.01)),\n        ),"
    );
    let text = std::fs::read_to_string(common::scene_path("wave_1d.ron")).unwrap();
    let edited = text.replacen(body, &two, 1);
    let second = edited.find("max: (0.5, 0.01)").unwrap();
    let line = edited[..second].matches('\n').count() - 1;
    assert_error(
        parse_edited(body, &two),
        line,
        "body name 'bar' is used twice",
    );
    // Probes likewise, one named like its body.
    let probe = "(name: \"midpoint\", body: \"bar\", at: (0.5, 0.005)),";
    let probes = "(name: \"bar\", body: \"bar\", at: (0.5, 0.005)),\n        (name: \"bar\", body: \"bar\", at: (0.2, 0.005)),";
    let edited = text.replacen(probe, probes, 1);
    let line = edited[..edited.find("at: (0.2, 0.005)").unwrap()]
        .matches('\n')
        .count()
        + 1;
    assert_error(
        parse_edited(probe, probes),
        line,
        "probe name 'bar' is used twice",
    );
}

#[test]
fn a_stage_duration_off_the_time_step_warns_with_the_steps_taken() {
    // 3.2e-4 s at Δt = 2e-4 s: the stage ends on the first step with
    // elapsed ≥ d − Δt/2 = 2.2e-4 s, the second (4e-4 s).
    let mut scene = common::load_scene("geostatic_column.ron");
    assert_eq!(scene.time.dt, 2e-4);
    scene.stages[0].end = mpdem::scene::StageEnd::Duration(3.2e-4);
    scene.stages[1].end = mpdem::scene::StageEnd::Duration(3e-4);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let warnings = common::warning_text(sim.warnings());
    assert!(
        warnings.contains("stage 'geostatic': Duration(3.2e-4) is not a multiple of time.dt = 2e-4 s: the stage takes 2 step(s), 4e-4 s"),
        "{warnings}"
    );
    // 3e-4 s is 1.5 steps: round-off decides, and the warning says so.
    assert!(
        warnings.contains("stage 'surcharge': Duration(3e-4) is not a multiple of time.dt = 2e-4 s: the stage takes 1 or 2 steps (a half-step tie)"),
        "{warnings}"
    );
    sim.run().unwrap();
    let log = sim.world().resource::<mpdem::resources::StageLog>();
    assert_eq!(log.records[0].steps, 2);
    assert!((1..=2).contains(&log.records[1].steps));
}

#[test]
fn an_update_that_feeds_undamped_contact_springs_is_warned_of() {
    use mpdem::resources::{PositionUpdate, UpdateScheme};
    let warnings = |scheme, update, damping| {
        let mut scene = common::load_scene("block_on_ground.ron");
        scene.settings.grid_damping = damping;
        scene.settings.scheme = scheme;
        scene.settings.position_update = update;
        Simulation::from_scene(&scene)
            .unwrap_or_else(|e| panic!("{e}"))
            .warnings()
            .iter()
            .filter(|w| w.field == "settings.position_update")
            .cloned()
            .collect::<Vec<_>>()
    };
    let paper = warnings(UpdateScheme::Usf, Some(PositionUpdate::PaperEq11b), 0.0);
    assert_eq!(paper.len(), 1, "{paper:?}");
    assert!(
        paper[0]
            .message
            .contains("PaperEq11b under Usf feeds undamped DEM contact springs")
            && paper[0].message.contains("RemappedVelocity"),
        "{}",
        paper[0]
    );
    for scheme in [UpdateScheme::Usf, UpdateScheme::Musl] {
        let grid = warnings(scheme, Some(PositionUpdate::NewGridVelocity), 0.0);
        assert_eq!(grid.len(), 1, "{grid:?}");
    }
    // The safe ones, and the same scene damped, are not warned of.
    assert!(warnings(UpdateScheme::Usf, None, 0.0).is_empty());
    assert!(warnings(UpdateScheme::Musl, None, 0.0).is_empty());
    assert!(
        warnings(
            UpdateScheme::Usl,
            Some(PositionUpdate::NewGridVelocity),
            0.0
        )
        .is_empty()
    );
    assert!(warnings(UpdateScheme::Usf, Some(PositionUpdate::PaperEq11b), 0.1).is_empty());
    // Damped, then released undamped by a stage: warned of.
    let mut released = common::load_scene("block_on_ground.ron");
    released.settings.position_update = Some(PositionUpdate::PaperEq11b);
    let mut settle = mpdem::scene::StageSpec::new("settle", mpdem::scene::StageEnd::Duration(0.1));
    settle.grid_damping = Some(0.2);
    let mut free = mpdem::scene::StageSpec::new("free", mpdem::scene::StageEnd::Duration(0.1));
    free.grid_damping = Some(0.0);
    released.stages = vec![settle, free];
    let sim = Simulation::from_scene(&released).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        sim.warnings().iter().any(|w| w
            .message
            .starts_with("settings.position_update: PaperEq11b")),
        "{:?}",
        sim.warnings()
    );
    // Every contact with a normal dashpot: not warned of.
    let mut dashpot = common::load_scene("block_on_ground.ron");
    dashpot.settings.grid_damping = 0.0;
    dashpot.settings.position_update = Some(PositionUpdate::PaperEq11b);
    dashpot.blocks[0].contact.normal_damping = 100.0;
    let sim = Simulation::from_scene(&dashpot).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        !sim.warnings()
            .iter()
            .any(|w| w.field == "settings.position_update"),
        "{:?}",
        sim.warnings()
    );
}

#[test]
fn an_optional_value_written_bare_is_refused_with_the_form_it_takes() {
    let (from, to) = (
        "position_update: Some(PaperEq11b)",
        "position_update: PaperEq11b",
    );
    let error = parse_edited(from, to);
    assert_error(
        error,
        line_of(from, to, to),
        "expected an optional value: Some(...) or None",
    );
}

#[test]
fn a_granular_body_under_the_affine_transfer_with_pure_flip_warns() {
    let mut scene = common::load_scene("stacked_blocks.ron");
    scene.settings.affine_transfer = true;
    // The default granular relaxation damps the granular body: no warning.
    let sim = Simulation::from_scene(&scene).unwrap();
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
    scene.settings.granular_relaxation = None;
    let sim = Simulation::from_scene(&scene).unwrap();
    let warnings = common::warning_text(sim.warnings());
    assert!(
        warnings.contains("settings.affine_transfer under pure FLIP")
            && warnings.contains("body 'column'"),
        "{warnings}"
    );
    // Taylor PIC says nothing; elastic bodies under the same transfer are
    // covered by the shipped toppling scenes, which must not warn.
    scene.settings.pic_fraction = 1.0;
    let sim = Simulation::from_scene(&scene).unwrap();
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
}
