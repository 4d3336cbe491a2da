//! Each layer resets and solves only its active nodes, those its points can
//! reach: the results must be those of solving every node, bit for bit.

mod common;

use mpdem::components::NodeRect;
use mpdem::contact::ForceApplication;
use mpdem::prelude::*;
use mpdem::scene::{InitialVelocity, Shape};
use mpdem::shape_functions::ShapeFunction;

/// Makes every node of every layer active and stored, as if there were no
/// active rectangle (runs after the reset and the boundary conditions,
/// before any transfer).
fn activate_the_whole_grid(grid: Res<Grid>, mut layers: Query<&mut GridLayer>) {
    for mut layer in &mut layers {
        layer.expand(NodeRect::whole(grid.nodes()));
    }
}

/// Checks that every stored node outside a layer's active rectangle holds
/// zero, and that the layer stores only the nodes around its active ones.
fn nothing_outside_the_active_nodes(sim: &mut Simulation) {
    let mut layers = sim.world_mut().query::<&GridLayer>();
    for layer in layers.iter(sim.world()) {
        let (window, active) = (layer.window(), layer.active());
        assert!(window.covers(active), "{window:?} misses {active:?}");
        for (k, node) in layer.nodes().iter().enumerate() {
            let at = [
                window.start[0] + k % window.width(),
                window.start[1] + k / window.width(),
            ];
            if !active.contains(at) {
                assert_eq!(
                    *node,
                    Default::default(),
                    "node {at:?} outside the active nodes"
                );
            }
        }
    }
}

/// State hashes after `steps` steps with the active rectangles and with the
/// whole grid active, checking the nodes outside the rectangles each step.
fn hashes(scene: &Scene, steps: usize) -> (u64, u64) {
    let mut active = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        active.step().unwrap_or_else(|e| panic!("{e}"));
        nothing_outside_the_active_nodes(&mut active);
    }
    let mut whole = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    whole
        .add_systems(activate_the_whole_grid.in_set(MpmSystems::Neighbours))
        .unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        whole.step().unwrap_or_else(|e| panic!("{e}"));
    }
    (active.state_hash(), whole.state_hash())
}

#[test]
fn a_block_sliding_with_traction_contact_gives_the_whole_grids_result() {
    // Contact forces written to the nodes of the traction points' cells.
    let mut scene = common::load_scene("sliding_45.ron");
    scene.contact.force_application = ForceApplication::Traction { points: 5 };
    let (active, whole) = hashes(&scene, 300);
    assert_eq!(active, whole);
}

/// The column collapse with one point per cell: a body spreading over the
/// grid.
fn reduced_column_collapse() -> Scene {
    let mut scene = common::load_scene("column_collapse.ron");
    for body in &mut scene.bodies {
        body.points_per_cell = 1;
    }
    scene
}

#[test]
fn a_collapsing_column_with_b_splines_gives_the_whole_grids_result() {
    // The widest stencil (the column moved off the grid's edges, as the
    // B-spline needs a cell of margin).
    let mut scene = reduced_column_collapse();
    scene.settings.shape_function = ShapeFunction::QuadraticBSpline;
    scene.grid.origin = DVec2::splat(-0.028);
    scene.grid.cells = (433, 90);
    let (active, whole) = hashes(&scene, 300);
    assert_eq!(active, whole);
}

#[test]
fn a_collapsing_column_with_xpic_gives_the_whole_grids_result() {
    // XPIC(3)'s smoothing passes run over the active nodes only; the nodes
    // outside keep last steps' values, which no stencil may read.
    let mut scene = reduced_column_collapse();
    scene.settings.xpic_order = Some(3);
    scene.settings.position_update = None;
    let (active, whole) = hashes(&scene, 300);
    assert_eq!(active, whole);
}

#[test]
fn colliding_rings_and_a_contact_group_give_the_whole_grids_result() {
    // Two layers meeting through body contacts.
    let mut rings = common::load_scene("two_rings.ron");
    rings.time.end = 6e-4;
    for body in &mut rings.bodies {
        body.points_per_cell = 1;
        body.contact_radius = None;
    }
    let (active, whole) = hashes(&rings, 450);
    assert_eq!(active, whole);
    // A column split into two bodies of one group: the members share the
    // union of their rectangles.
    let mut column = common::load_scene("elastic_column.ron");
    column.probes.clear();
    let mut upper = column.bodies[0].clone();
    column.bodies[0].shape = Shape::Rectangle {
        min: DVec2::new(0.0, 0.0),
        max: DVec2::new(0.2, 0.5),
    };
    column.bodies[0].name = "lower".into();
    column.bodies[0].group = Some("column".into());
    upper.name = "upper".into();
    upper.shape = Shape::Rectangle {
        min: DVec2::new(0.0, 0.5),
        max: DVec2::new(0.2, 1.0),
    };
    upper.group = Some("column".into());
    column.bodies.push(upper);
    let (active, whole) = hashes(&column, 300);
    assert_eq!(active, whole);
}

#[test]
fn rings_flying_across_the_grid_move_their_stored_nodes_and_give_the_whole_grids_result() {
    // Each layer stores a window around its active nodes, moved when the
    // body leaves it: two rings without a contact law pass through each
    // other at ±300 m/s, 0.19 cells a step, 56 cells in 300 steps.
    let mut rings = common::load_scene("two_rings.ron");
    rings.body_contacts.clear();
    for body in &mut rings.bodies {
        body.points_per_cell = 1;
        body.contact_radius = None;
    }
    rings.bodies[0].velocity = InitialVelocity::Constant(DVec2::new(300.0, 0.0));
    rings.bodies[1].velocity = InitialVelocity::Constant(DVec2::new(-300.0, 0.0));
    let mut sim = Simulation::from_scene(&rings).unwrap_or_else(|e| panic!("{e}"));
    let mut windows = vec![Vec::new(); 2];
    for _ in 0..300 {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
        let mut layers = sim.world_mut().query::<&GridLayer>();
        for (seen, layer) in windows.iter_mut().zip(layers.iter(sim.world())) {
            if seen.last() != Some(&layer.window()) {
                seen.push(layer.window());
            }
        }
    }
    for seen in &windows {
        // The window moves with the ring, and spans its active nodes (its
        // 50 cells plus two of reach each side: at most 56 nodes) and a
        // margin of a quarter of them each side: at most 84 nodes, of the
        // grid's 251 x 126.
        assert!(seen.len() >= 3, "the window moved {} times", seen.len() - 1);
        for window in seen {
            assert!(window.width() <= 84 && window.height() <= 84, "{window:?}");
        }
    }
    let (active, whole) = hashes(&rings, 300);
    assert_eq!(active, whole);
}
