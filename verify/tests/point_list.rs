//! Bodies from a point list file (`Shape::Points`, DESIGN.md section 5): the
//! listed points are the body's points, with their volumes; a bad file is
//! refused with the body, the file, its line and what was expected.

mod common;

use mpdem::prelude::*;
use mpdem::scene::{InitialStress, ListedPoint, Shape, Side};
use mpdem::systems::side_points;
use std::path::{Path, PathBuf};

/// The wave scene shortened to 0.05 s (500 steps), its bar read from
/// `points.csv` holding `csv`, in a fresh folder named after `tag`; returns
/// the scene file.
fn listed_wave_scene(tag: &str, csv: &str) -> (common::TempFolder, PathBuf) {
    let (folder, scene) = common::edited_wave_scene(
        tag,
        "shape: Rectangle(min: (0.0, 0.0), max: (1.0, 0.01)),",
        "shape: Points(file: \"points.csv\"),",
    );
    let text = std::fs::read_to_string(&scene).expect("scene");
    std::fs::write(&scene, text.replacen("end: 1.0", "end: 0.05", 1)).expect("scene");
    std::fs::write(folder.join("points.csv"), csv).expect("point list");
    (folder, scene)
}

/// The lattice the wave scene's rectangle gives, as a point list
/// (shortest round-trip decimals, so the positions are exact).
fn lattice_of_the_wave_bar(with_volume: bool) -> String {
    let scene = common::load_scene("wave_1d.ron");
    let grid = &scene.grid;
    let body = &scene.bodies[0];
    let spacing = grid.cell_size / Real::from(body.points_per_cell);
    let mut csv = String::from(if with_volume { "x,y,volume\n" } else { "x,y\n" });
    for p in body
        .shape
        .fill(grid.origin, grid.cell_size, body.points_per_cell)
    {
        if with_volume {
            csv += &format!("{:?},{:?},{:?}\n", p.x, p.y, 0.5 * spacing * spacing);
        } else {
            csv += &format!("{:?},{:?}\n", p.x, p.y);
        }
    }
    csv
}

fn run(path: &Path) -> Simulation {
    let mut sim = Simulation::from_scene_file(path).unwrap_or_else(|e| panic!("{e}"));
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    sim
}

#[test]
fn the_lattice_as_a_point_list_runs_bit_identical_to_the_shape() {
    let (_folder, listed) = listed_wave_scene("listed-lattice", &lattice_of_the_wave_bar(false));
    let mut original = common::load_scene("wave_1d.ron");
    original.time.end = 0.05;
    let mut shape = common::run_scene(&original);
    let mut from_list = run(&listed);
    assert_eq!(
        shape.points_of("bar").unwrap().len(),
        from_list.points_of("bar").unwrap().len()
    );
    assert_eq!(shape.state_hash(), from_list.state_hash());
}

#[test]
fn listed_volumes_set_each_points_mass_and_domain() {
    let (_folder, listed) = listed_wave_scene("listed-volumes", &lattice_of_the_wave_bar(true));
    let scene = Scene::load(&listed).unwrap_or_else(|e| panic!("{e}"));
    let Shape::Points { points, .. } = &scene.bodies[0].shape else {
        panic!("not a point list")
    };
    let volume = points[0].volume.expect("listed volume");
    let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    let bar = sim.points_of("bar").unwrap();
    let density = scene.materials[0].density;
    assert!(bar.volume.iter().all(|&v| v == volume));
    assert!(bar.mass.iter().all(|&m| m == density * volume));
    // The uGIMP domain is a square of the listed area, and the default DEM
    // disk reaches its sides.
    let half = 0.5 * volume.sqrt();
    assert!(bar.half_size.iter().all(|&h| h == DVec2::splat(half)));
    assert!(bar.contact_radius.iter().all(|&r| r == half));
}

/// The geostatic column's soil as a point list filled in code: its lattice
/// with the lattice's volume given explicitly.
fn listed_geostatic_column() -> Scene {
    let mut scene = common::load_scene("geostatic_column.ron");
    let grid = &scene.grid;
    let body = &scene.bodies[0];
    let spacing = grid.cell_size / Real::from(body.points_per_cell);
    let points = body
        .shape
        .fill(grid.origin, grid.cell_size, body.points_per_cell)
        .into_iter()
        .enumerate()
        .map(|(k, position)| ListedPoint {
            position,
            volume: Some(spacing * spacing),
            line: k + 1,
        })
        .collect();
    scene.bodies[0].shape = Shape::Points {
        file: "in code".into(),
        points,
    };
    scene
}

#[test]
fn a_listed_bodys_geostatic_stress_starts_at_its_highest_domain_edge() {
    let mut scene = listed_geostatic_column();
    scene.stages.clear();
    scene.bodies[0].initial_stress = Some(InitialStress::Geostatic {
        k0: 0.5,
        surface: None,
    });
    let mut listed = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    let mut original = common::load_scene("geostatic_column.ron");
    original.stages.clear();
    original.bodies[0].initial_stress = scene.bodies[0].initial_stress.clone();
    let mut lattice = Simulation::from_scene(&original).unwrap_or_else(|e| panic!("{e}"));
    // The top points' domains end at the rectangle's top, 4 m: the same
    // stresses as the rectangle's, up to the round-off of y + half.
    let listed = listed.points_of("soil").unwrap().stress.clone();
    let lattice = &lattice.points_of("soil").unwrap().stress;
    for (a, b) in listed.iter().zip(lattice) {
        assert!(
            (a.yy - b.yy).abs() <= 1e-9 * b.yy.abs().max(1.0),
            "{a:?} vs {b:?}"
        );
    }
    assert!(lattice.iter().all(|s| s.yy < 0.0));
}

/// The listed geostatic column with its two top rows of points (0.1 m
/// apart) replaced by one row of points twice as wide, 0.2 m.
fn listed_column_with_a_coarse_top() -> Scene {
    let mut scene = listed_geostatic_column();
    let Shape::Points { points, .. } = &mut scene.bodies[0].shape else {
        unreachable!()
    };
    points.retain(|p| p.position.y < 3.8);
    let next = points.len() + 1;
    points.extend((0..5).map(|i| ListedPoint {
        position: DVec2::new(0.1 + 0.2 * Real::from(i), 3.9),
        volume: Some(0.2 * 0.2),
        line: next + i as usize,
    }));
    scene
}

#[test]
fn a_listed_bodys_sides_are_found_whatever_its_points_sizes() {
    let mut sim = Simulation::from_scene(&listed_column_with_a_coarse_top())
        .unwrap_or_else(|e| panic!("{e}"));
    let points = sim.points_of("soil").unwrap().clone();
    let side = |side| -> Vec<(DVec2, Real)> {
        side_points(&points, side)
            .into_iter()
            .map(|(p, width)| (points.initial_position[p as usize], width))
            .collect()
    };
    // The top is the five wide points, each carrying its own 0.2 m.
    let top = side(Side::Top);
    assert_eq!(top.len(), 5, "{top:?}");
    for (k, (x, width)) in top.iter().enumerate() {
        assert!(
            (x.x - (0.1 + 0.2 * k as Real)).abs() < 1e-12 && x.y == 3.9,
            "{x}"
        );
        assert!((width - 0.2).abs() < 1e-12, "{width}");
    }
    // The bottom is the ten narrow points of the lowest row, 0.1 m each;
    // the right side is every row's last point: 38 rows of 0.1 m, then
    // the wide top point's 0.2 m, so the whole 4 m height once.
    let bottom = side(Side::Bottom);
    assert_eq!(bottom.len(), 10);
    assert!(
        bottom
            .iter()
            .all(|(x, w)| (x.y - 0.05).abs() < 1e-12 && (w - 0.1).abs() < 1e-12)
    );
    let right = side(Side::Right);
    let height: Real = right.iter().map(|(_, w)| w).sum();
    assert_eq!(right.len(), 39, "{right:?}");
    assert!((height - 4.0).abs() < 1e-9, "{height}");
}

#[test]
fn a_listed_body_off_the_grids_lattice_has_one_strip_per_column() {
    // The column's points shifted half a spacing (0.05 m), so their
    // domains' edges fall on the grid's lattice: nine columns at x = 0.1,
    // 0.2, ..., 0.9, each loaded once over its own 0.1 m.
    let mut scene = listed_geostatic_column();
    let Shape::Points { points, .. } = &mut scene.bodies[0].shape else {
        unreachable!()
    };
    points.retain(|p| p.position.x < 0.9);
    for p in points.iter_mut() {
        p.position.x += 0.05;
    }
    let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    let points = sim.points_of("soil").unwrap();
    let top = side_points(points, Side::Top);
    assert_eq!(top.len(), 9, "{top:?}");
    for (k, (p, width)) in top.iter().enumerate() {
        let x = points.initial_position[*p as usize];
        assert!((x.x - 0.1 * (k + 1) as Real).abs() < 1e-12, "{x}");
        assert!((width - 0.1).abs() < 1e-12, "{width}");
    }
}

#[test]
fn a_listed_body_with_a_coarse_top_carries_the_surcharge_to_its_base() {
    let mut sim = Simulation::from_scene(&listed_column_with_a_coarse_top())
        .unwrap_or_else(|e| panic!("{e}"));
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    let base = mpdem_verify::base_stress(sim.points_of("soil").unwrap());
    // As for the lattice column (verify/tests/stages.rs): the lowest points carry
    // the stress of the bottom cell's centre, ρ g (H − h/2), plus the
    // 150 kPa surcharge; the geostatic tolerance, 3%.
    let expected = -1620.0 * 9.81 * (4.0 - 0.1) - 150e3;
    println!(
        "listed column, coarse top: base σ_v {base:.1} Pa vs {expected:.1} Pa ({:+.3}%)",
        100.0 * (base / expected - 1.0)
    );
    assert!((base / expected - 1.0).abs() <= 0.03);
}

#[test]
fn a_point_lists_line_numbers_are_not_part_of_the_scene() {
    // A comment added to the file moves the lines, not the points: a
    // checkpoint of the scene still resumes.
    let scene = listed_geostatic_column();
    let mut moved = scene.clone();
    let Shape::Points { points, .. } = &mut moved.bodies[0].shape else {
        unreachable!()
    };
    points.iter_mut().for_each(|p| p.line += 1);
    let folder = common::TempFolder::new("point-list-lines");
    let path = folder.join("checkpoint.bin");
    let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
    sim.step().unwrap_or_else(|e| panic!("{e}"));
    sim.write_checkpoint(&path)
        .unwrap_or_else(|e| panic!("{e}"));
    let resumed = Simulation::resume(&moved, &path);
    let mut resumed = resumed.unwrap_or_else(|e| panic!("the moved scene's resume: {e}"));
    assert_eq!(resumed.state_hash(), sim.state_hash());
}

/// The file line of the first listed point of the scene's first body.
fn points_line(scene: &Scene) -> usize {
    let Shape::Points { points, .. } = &scene.bodies[0].shape else {
        unreachable!()
    };
    points[0].line
}

#[test]
fn a_listed_body_refuses_oversized_or_outlying_domains() {
    let mut scene = listed_geostatic_column();
    scene.stages.clear();
    let Shape::Points { points, .. } = &mut scene.bodies[0].shape else {
        unreachable!()
    };
    // uGIMP's stencil holds domains up to a cell (0.2 m here).
    points[0].volume = Some(0.2 * 0.2 * 1.01);
    let message = common::refusal(&scene);
    assert!(message.contains("more than a cell"), "{message}");
    let line = format!("(line {})", points_line(&scene));
    assert!(message.contains(&line), "{message}");
    // The point (0.05, 0.05) with a domain 0.12 m wide reaches past the
    // grid's left edge at 0.
    let Shape::Points { points, .. } = &mut scene.bodies[0].shape else {
        unreachable!()
    };
    points[0].volume = Some(0.12 * 0.12);
    let message = common::refusal(&scene);
    assert!(message.contains("is not inside the grid"), "{message}");
    let reaching = format!(
        "the point at [0.05, 0.05] in 'in code' (line {})",
        points_line(&scene)
    );
    assert!(message.contains(&reaching), "{message}");
    // A position that is not finite, which only code can give.
    let Shape::Points { points, .. } = &mut scene.bodies[0].shape else {
        unreachable!()
    };
    points[0].volume = None;
    points[1].position.x = Real::NAN;
    let message = common::refusal(&scene);
    assert!(message.contains("positions must be finite"), "{message}");
}

#[test]
fn a_bad_point_list_is_refused_with_the_file_and_line() {
    let (_folder, scene) = listed_wave_scene("listed-bad", "x,y\n0.1,0.005\n0.2,oops\n");
    let message = Scene::load(&scene)
        .expect_err("bad list accepted")
        .to_string();
    let shape_line = std::fs::read_to_string(&scene)
        .unwrap()
        .lines()
        .position(|l| l.contains("Points(file"))
        .unwrap()
        + 1;
    assert!(
        message.contains(&format!("{}:{shape_line}:", scene.display())),
        "not at the body's shape: {message}"
    );
    assert!(
        message.contains("body 'bar'")
            && message.contains("points.csv:3: expected a finite number in column y, got 'oops'"),
        "{message}"
    );

    let (_folder, missing) = listed_wave_scene("listed-missing", "x,y\n0.1,0.005\n");
    std::fs::remove_file(missing.with_file_name("points.csv")).unwrap();
    let message = Scene::load(&missing)
        .expect_err("missing list accepted")
        .to_string();
    assert!(
        message.contains("points.csv: cannot read the point list"),
        "{message}"
    );

    let (_folder, outside) = listed_wave_scene("listed-outside", "x,y\n0.1,0.005\n1.5,0.005\n");
    let message = Scene::load(&outside)
        .expect_err("outside accepted")
        .to_string();
    assert!(message.contains("is not inside the grid"), "{message}");
}
