//! Contact laws for particular pairs with a block (`block_contacts`): a
//! block–block pair and a body–block pair take the scene's law for them
//! instead of the one their own laws give, checked on a slope where the
//! friction decides between sliding and sticking.

use mpdem::prelude::*;

/// Gravity tilted by 20°: the floor is a slope of tan 20° = 0.364, above
/// μ = 0.16 and below μ = 0.6.
const TILT_DEG: Real = 20.0;

fn gravity() -> String {
    let (s, c) = TILT_DEG.to_radians().sin_cos();
    format!("({:e}, {:e})", 9.81 * s, -9.81 * c)
}

/// A dynamic box on a fixed floor, each with its own friction, and
/// `pair` as the scene's `block_contacts`.
fn box_on_floor(pair: &str) -> Scene {
    Scene::parse(&format!(
        r#"Scene(
    grid: (cell_size: 0.05, cells: (40, 10)),
    time: (dt: 1e-4, end: 0.3),
    gravity: {g},
    materials: [],
    bodies: [],
    blocks: [
        (name: "floor", shape: Cuboid(half_extents: (1.0, 0.05)), position: (1.0, 0.05), motion: Fixed,
         contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.16, normal_damping: 100.0)),
        (name: "box", shape: Cuboid(half_extents: (0.05, 0.05)), position: (0.5, 0.15),
         motion: Dynamic(density: 500.0),
         contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.6, normal_damping: 100.0)),
    ],
    block_contacts: [{pair}],
)"#,
        g = gravity()
        ),
        "pair_laws.ron".as_ref(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// How far block 1 moved along x.
fn block_travel(scene: &Scene) -> Real {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    let log = sim.world().resource::<mpdem::resources::BlockLog>();
    let box_samples: Vec<_> = log.samples.iter().filter(|s| s.block == 1).collect();
    box_samples.last().unwrap().origin.x - box_samples[0].origin.x
}

#[test]
fn a_block_pair_takes_its_own_law() {
    // Without a law for the pair it takes the smaller friction, 0.16, and
    // slides: s = ½ g (sin θ − μ cos θ) t² = 84.6 mm in 0.3 s (the springs'
    // give and the time the box takes to settle on them aside: within 10%).
    let (s, c) = TILT_DEG.to_radians().sin_cos();
    let expected = 0.5 * 9.81 * (s - 0.16 * c) * 0.3 * 0.3;
    let slid = block_travel(&box_on_floor(""));
    assert!(
        (slid / expected - 1.0).abs() < 0.10,
        "slid {slid} m against {expected} m"
    );
    // With μ = 0.6 for the pair it holds (the springs' creep only).
    let held = block_travel(&box_on_floor(
        r#"(between: ("box", "floor"), law: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.6, normal_damping: 100.0))"#,
    ));
    assert!(held.abs() < 1e-3, "held box moved {held} m");
}

/// An elastic pad on a fixed floor whose own friction is 0.16, with `pair`
/// as the scene's `block_contacts`.
fn pad_on_floor(pair: &str) -> Scene {
    Scene::parse(&format!(
        r#"Scene(
    grid: (cell_size: 0.02, cells: (50, 10)),
    time: (dt: 5e-5, end: 0.2),
    gravity: {g},
    settings: (grid_damping: 0.05),
    materials: [(name: "pad", density: 2000.0, model: LinearElastic((youngs_modulus: 1e7, poisson_ratio: 0.3)))],
    bodies: [(name: "pad", material: "pad", shape: Rectangle(min: (0.3, 0.1), max: (0.5, 0.16)), points_per_cell: 2)],
    blocks: [
        (name: "floor", shape: Cuboid(half_extents: (0.5, 0.05)), position: (0.5, 0.05), motion: Fixed,
         contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.16, normal_damping: 5.0)),
    ],
    block_contacts: [{pair}],
)"#,
        g = gravity()
        ),
        "pair_laws.ron".as_ref(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The pad's mean displacement along x.
fn pad_travel(scene: &Scene) -> Real {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    sim.run().unwrap_or_else(|e| panic!("{e}"));
    let points = sim.points_of("pad").unwrap();
    (0..points.len())
        .map(|p| points.displacement(p).x)
        .sum::<Real>()
        / points.len() as Real
}

#[test]
fn a_body_block_pair_takes_its_own_law() {
    // The floor's own μ = 0.16 lets the pad slide (≈ 37.6 mm in 0.2 s as a
    // rigid block; the pad is elastic, so only an order is asked).
    let slid = pad_travel(&pad_on_floor(""));
    // μ = 0.6 for the pair holds it.
    let held = pad_travel(&pad_on_floor(
        r#"(between: ("floor", "pad"), law: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.6, normal_damping: 5.0))"#,
    ));
    assert!(slid > 0.02, "the pad slid only {slid} m");
    assert!(
        held.abs() < 0.1 * slid,
        "the held pad moved {held} m (free: {slid} m)"
    );
}

#[test]
fn bad_pair_laws_are_refused() {
    let law = "law: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.6)";
    for (pair, expected) in [
        (
            format!(r#"(between: ("box", "roof"), {law})"#),
            "unknown block or body 'roof'",
        ),
        (
            format!(r#"(between: ("box", "box"), {law})"#),
            "does not contact itself",
        ),
        (
            format!(r#"(between: ("box", "floor"), {law}), (between: ("floor", "box"), {law})"#),
            "two laws",
        ),
    ] {
        let text = format!(
            r#"Scene(
    grid: (cell_size: 0.05, cells: (40, 10)),
    time: (dt: 1e-4, end: 0.3),
    materials: [],
    bodies: [],
    blocks: [
        (name: "floor", shape: Cuboid(half_extents: (1.0, 0.05)), position: (1.0, 0.05), motion: Fixed,
         contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.16)),
        (name: "box", shape: Cuboid(half_extents: (0.05, 0.05)), position: (0.5, 0.15),
         motion: Dynamic(density: 500.0),
         contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.6)),
    ],
    block_contacts: [{pair}],
)"#
        );
        let message = match Scene::parse(&text, "pair_laws.ron".as_ref()) {
            Ok(_) => panic!("accepted: {pair}"),
            Err(e) => e.to_string(),
        };
        assert!(message.contains(expected), "{message}");
    }
}

#[test]
fn a_name_both_a_block_and_a_body_is_refused_in_a_pair() {
    let law = "law: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.6)";
    let text = format!(
        r#"Scene(
    grid: (cell_size: 0.02, cells: (50, 10)),
    time: (dt: 5e-5, end: 0.2),
    materials: [(name: "pad", density: 2000.0, model: LinearElastic((youngs_modulus: 1e7, poisson_ratio: 0.3)))],
    bodies: [(name: "pad", material: "pad", shape: Rectangle(min: (0.3, 0.1), max: (0.5, 0.16)), points_per_cell: 2)],
    blocks: [
        (name: "pad", shape: Cuboid(half_extents: (0.5, 0.05)), position: (0.5, 0.05), motion: Fixed,
         contact: (normal_stiffness: 1e7, tangential_stiffness: 1e7, friction: 0.16)),
    ],
    block_contacts: [(between: ("pad", "pad"), {law})],
)"#
    );
    let message = match Scene::parse(&text, "pair_laws.ron".as_ref()) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(message.contains("names a block and a body"), "{message}");
}
