//! Layouts that are valid but not what was meant draw warnings a program
//! can match by kind and field: a dynamic block placed overlapping another
//! block (at the start, or added by a stage), and a constraint region that
//! holds no node of the grid.

mod common;

use mpdem::prelude::*;
use mpdem::resources::StageLog;

/// A body resting low, a fixed ground under it and a block `stone` at
/// `stone_y` with `motion`, added by the second stage if `later`; the
/// body's constraint region given by `region`.
fn scene(stone_y: f64, motion: &str, later: bool, region: &str) -> Scene {
    let stages = if later {
        r#"stages: [
            (name: "settle", end: Duration(0.002)),
            (name: "drop", end: Duration(0.002), add_blocks: ["stone"]),
        ],"#
    } else {
        ""
    };
    let text = format!(
        r#"Scene(
    grid: (origin: (0.0, 0.0), cell_size: 0.1, cells: (10, 10)),
    time: (dt: 1e-4, end: 0.004),
    materials: [(name: "elastic", density: 1000.0, model: LinearElastic((youngs_modulus: 1e5, poisson_ratio: 0.2)))],
    bodies: [(name: "block", material: "elastic", shape: Rectangle(min: (0.1, 0.3), max: (0.3, 0.5)),
              constraints: [{region}])],
    blocks: [
        (name: "ground", shape: Cuboid(half_extents: (0.5, 0.1)), position: (0.5, 0.1), motion: Fixed,
         contact: (normal_stiffness: 1e6, tangential_stiffness: 1e6, friction: 0.3)),
        (name: "stone", shape: Cuboid(half_extents: (0.05, 0.05)), position: (0.7, {stone_y}), motion: {motion},
         contact: (normal_stiffness: 1e6, tangential_stiffness: 1e6, friction: 0.3), present: {present}),
    ],
    {stages}
)"#,
        present = !later
    );
    Scene::parse(&text, "placement.ron".as_ref()).unwrap_or_else(|e| panic!("{e}"))
}

const HOLDING: &str = "(min: (0.0, 0.0), max: (1.0, 0.05), fix_y: true)";

fn overlaps(warnings: &[Warning]) -> Vec<&Warning> {
    warnings
        .iter()
        .filter(|w| w.kind == WarningKind::Layout && w.field == r#"blocks["stone"].position"#)
        .collect()
}

#[test]
fn a_dynamic_block_placed_in_another_warns_and_fixed_blocks_may_overlap() {
    // The stone's bottom 0.15, the ground's top 0.2: 0.05 m into it.
    let sim = Simulation::from_scene(&scene(0.2, "Dynamic(density: 2500.0)", false, HOLDING))
        .unwrap_or_else(|e| panic!("{e}"));
    let found = overlaps(sim.warnings());
    assert_eq!(found.len(), 1, "{:?}", sim.warnings());
    assert!(
        found[0]
            .message
            .contains("overlaps block 'ground' by 5.000e-2 m"),
        "{}",
        found[0]
    );
    // Resting on it, or both fixed: no warning.
    for (y, motion) in [(0.25, "Dynamic(density: 2500.0)"), (0.2, "Fixed")] {
        let sim = Simulation::from_scene(&scene(y, motion, false, HOLDING)).unwrap();
        assert!(overlaps(sim.warnings()).is_empty(), "{:?}", sim.warnings());
    }
}

#[test]
fn a_stage_adding_a_dynamic_block_in_another_warns() {
    let mut sim = Simulation::from_scene(&scene(0.2, "Dynamic(density: 2500.0)", true, HOLDING))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(overlaps(sim.warnings()).is_empty());
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    let log = sim.world().resource::<StageLog>();
    assert_eq!(overlaps(&log.warnings).len(), 1, "{:?}", log.warnings);
}

#[test]
fn a_constraint_region_holding_no_node_warns() {
    let field = r#"bodies["block"].constraints"#;
    let outside = "(min: (2.0, 2.0), max: (3.0, 3.0), fix_x: true)";
    let between = "(min: (0.02, 0.0), max: (0.08, 1.0), fix_x: true)";
    for region in [outside, between] {
        let sim = Simulation::from_scene(&scene(0.25, "Fixed", false, region)).unwrap();
        let found: Vec<_> = sim.warnings().iter().filter(|w| w.field == field).collect();
        assert_eq!(found.len(), 1, "{region}: {:?}", sim.warnings());
        assert_eq!(found[0].kind, WarningKind::Layout);
    }
    let sim = Simulation::from_scene(&scene(0.25, "Fixed", false, HOLDING)).unwrap();
    assert!(!sim.warnings().iter().any(|w| w.field == field));
}
