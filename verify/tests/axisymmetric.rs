//! Axisymmetry (`settings.geometry: Axisymmetric`) against Lamé's thick
//! cylinder under internal pressure.

mod common;

use mpdem::prelude::*;
use mpdem::resources::EnergyLog;
use std::path::Path;

/// Inner and outer radius (m), pressure (Pa), Young's modulus (Pa) and
/// Poisson's ratio of the cylinder.
const A: Real = 0.5;
const B: Real = 1.0;
const P: Real = 1e5;
const E: Real = 1e8;
const NU: Real = 0.3;
/// The cylinders' height (m).
const HEIGHT: Real = 0.2;

/// A cylinder `inner` ≤ r ≤ `outer` (inner 0: solid), 0.2 m of its length
/// between two slip walls (so ε_zz = 0), with the grid reaching 0.2 m past
/// it, loaded by the stage traction `load` (a `tractions` entry) and
/// brought to rest by damping (PIC 1.0, particle damping 0.7, as the
/// geostatic stages), with the further `settings` entries given; steel of
/// E, ν.
fn pressed_cylinder(
    name: &str,
    (inner, outer): (Real, Real),
    load: &str,
    settings: &str,
) -> String {
    let cells = ((outer + 0.2) / 0.05).round();
    format!(
        r#"Scene(
    name: Some("{name}"),
    grid: (
        origin: (0.0, 0.0),
        cell_size: 0.05,
        cells: ({cells}, 4),
        edges: (left: Slip, right: Free, bottom: Slip, top: Slip),
    ),
    time: (dt: 5e-5, end: 1.2),
    gravity: (0.0, 0.0),
    settings: (geometry: Axisymmetric, pic_fraction: 1.0, particle_damping: 0.7, {settings}),
    materials: [(name: "steel", density: 1000.0, model: LinearElastic((youngs_modulus: {E:e}, poisson_ratio: {NU})))],
    bodies: [(name: "cylinder", material: "steel", shape: Rectangle(min: ({inner}, 0.0), max: ({outer}, {HEIGHT})), points_per_cell: 2)],
    stages: [(name: "pressure", end: Duration(1.2), tractions: [{load}])],
)"#
    )
}

/// The hollow cylinder a ≤ r ≤ b pressed from inside by P, under the
/// update `scheme` (a `settings` entry). Under USF the points move with
/// the remapped velocity: under eq. 11b's update the damped points'
/// displacements drift 1.4% from the strain the stress follows (measured;
/// the stresses are the same either way).
fn thick_cylinder(scheme: &str) -> String {
    pressed_cylinder(
        "thick_cylinder",
        (A, B),
        &format!(r#"(body: "cylinder", side: Left, traction: ({P:e}, 0.0))"#),
        scheme,
    )
}

/// Lamé's solution at radius r: (σ_rr, σ_θθ, u_r) for ε_zz = 0.
fn lame(r: Real) -> (Real, Real, Real) {
    let a_coef = P * A * A / (B * B - A * A);
    let b_coef = a_coef * B * B;
    let radial = (1.0 + NU) / E * ((1.0 - 2.0 * NU) * a_coef * r + b_coef / r);
    (a_coef - b_coef / (r * r), a_coef + b_coef / (r * r), radial)
}

/// How far a run is from Lamé, as fractions of P (stresses) and of
/// u_r(a) (displacement).
#[derive(Debug)]
struct LameErrors {
    /// Largest |σ_rr − Lamé| of a column of cells' mean over its points.
    radial: Real,
    /// Largest |σ_θθ − Lamé| of a column of cells' mean over its points.
    hoop: Real,
    /// Largest |σ_rr − Lamé| or |σ_θθ − Lamé| at a point.
    at_a_point: Real,
    /// Largest |u_r − Lamé| at a point.
    displacement: Real,
    /// |W / W_Lamé − 1|, W the pressure's work per radian (`energy.csv`'s
    /// −loads), W_Lamé = P a h u_r(a) on the bore's a h per radian.
    work: Real,
    /// |2 U / W_Lamé − 1|, U the strain energy at the end: a linear body
    /// loaded from rest stores half the work.
    stored: Real,
}

impl LameErrors {
    /// The cells' means within 1% of P, each point within 12% of P (the
    /// points of a cell alternate about their mean), displacements within
    /// 1% (see the test of the USF run for what was measured).
    fn assert_within_tolerances(&self) {
        assert!(self.radial < 0.01, "{self:?}");
        assert!(self.hoop < 0.01, "{self:?}");
        assert!(self.at_a_point < 0.12, "{self:?}");
        assert!(self.displacement < 0.01, "{self:?}");
        // The work and the stored energy as the displacement, within 1%.
        // (The balance is not asserted here: under PIC 1.0 with particle
        // damping 0.7 the `damped` column takes 3% of W more than W − U,
        // the damping's own accounting error, see tests/energy_balance.rs.)
        assert!(self.work < 0.01, "{self:?}");
        assert!(self.stored < 0.01, "{self:?}");
    }
}

/// Runs the cylinder and compares every point with Lamé at its first
/// radius, and each column of cells' mean stress with Lamé's mean there.
fn lame_errors(scheme: &str) -> LameErrors {
    let scene = Scene::parse(&thick_cylinder(scheme), Path::new("thick_cylinder.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut sim = common::run_scene(&scene);
    let points = sim.points_of("cylinder").expect("cylinder").clone();
    let u_inner = lame(A).2;
    let mut columns = vec![[0.0; 5]; 10];
    let mut errors = LameErrors {
        radial: 0.0,
        hoop: 0.0,
        at_a_point: 0.0,
        displacement: 0.0,
        work: 0.0,
        stored: 0.0,
    };
    for p in 0..points.len() {
        let r = points.initial_position[p].x;
        let (rr, tt, u) = lame(r);
        let s = points.stress[p];
        let column = &mut columns[((r - A) / 0.05) as usize];
        for (sum, value) in column.iter_mut().zip([s.xx, s.zz, rr, tt, 1.0]) {
            *sum += value;
        }
        let worst = (s.xx - rr).abs().max((s.zz - tt).abs()) / P;
        errors.at_a_point = errors.at_a_point.max(worst);
        errors.displacement = errors
            .displacement
            .max((points.displacement(p).x - u).abs() / u_inner);
    }
    for [rr, tt, lame_rr, lame_tt, n] in columns {
        errors.radial = errors.radial.max((rr - lame_rr).abs() / n / P);
        errors.hoop = errors.hoop.max((tt - lame_tt).abs() / n / P);
    }
    let lame_work = P * A * HEIGHT * u_inner;
    let energy = &sim.world().resource::<EnergyLog>().samples;
    let last = energy.last().expect("samples");
    errors.work = (-last.loads / lame_work - 1.0).abs();
    errors.stored = (2.0 * last.strain / lame_work - 1.0).abs();
    println!("{scheme}: {errors:?}");
    errors
}

#[test]
fn a_thick_cylinder_under_internal_pressure_follows_lame() {
    let errors = lame_errors("scheme: Usf, position_update: Some(RemappedVelocity)");
    // 10 cells across the wall, 2 × 2 points per cell: the hoop stress runs
    // from 1.67 p at the bore to 0.67 p outside and σ_rr from −p to 0.
    // Measured: the cells' means within 0.5% of p, the points alternating
    // about them by up to ±5% (σ_θθ) and ±10% (σ_rr, the innermost cell,
    // whose inner edge, the bore, carries the load), displacements within
    // 0.3%.
    errors.assert_within_tolerances();
}

#[test]
fn under_usl_the_thick_cylinder_follows_lame_too() {
    // USL updates the stress after G2P has moved the points: the hoop
    // stretch is then taken at x^{n+1}. The same tolerances, with the
    // strain rate from the nodal solve's velocity and from the remapped
    // one (MUSL, whose hoop rate reads the remapped radial velocity). The
    // case is quasi-static, so it cannot tell the two velocities apart:
    // for MUSL it checks that the branch runs and settles where Lamé says.
    lame_errors("scheme: Usl, position_update: Some(NewGridVelocity)").assert_within_tolerances();
    lame_errors("scheme: Musl").assert_within_tolerances();
}

#[test]
fn a_solid_cylinder_pressed_from_outside_is_evenly_stressed_to_its_axis() {
    // r ≤ 0.5 m pressed from outside by P: σ_rr = σ_θθ = −P and
    // σ_zz = −2νP everywhere, u_r = −(1+ν)(1−2ν) P r / E, up to the axis.
    let text = pressed_cylinder(
        "solid_cylinder",
        (0.0, 0.5),
        &format!(
            r#"(body: "cylinder", side: Right, traction: ({:e}, 0.0))"#,
            -P
        ),
        "scheme: Usf, position_update: Some(RemappedVelocity)",
    );
    let scene =
        Scene::parse(&text, Path::new("solid_cylinder.ron")).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = common::run_scene(&scene);
    let points = sim.points_of("cylinder").expect("cylinder").clone();
    let (mut stress, mut displacement): (Real, Real) = (0.0, 0.0);
    for p in 0..points.len() {
        let s = points.stress[p];
        for (got, exact) in [(s.xx, -P), (s.zz, -P), (s.yy, -2.0 * NU * P)] {
            stress = stress.max((got - exact).abs() / P);
        }
        let r = points.initial_position[p].x;
        let exact = -(1.0 + NU) * (1.0 - 2.0 * NU) * P * r / E;
        let scale = (1.0 + NU) * (1.0 - 2.0 * NU) * P * 0.5 / E;
        displacement = displacement.max((points.displacement(p).x - exact).abs() / scale);
    }
    println!(
        "solid cylinder: worst stress {:.3}% of p, worst u_r {:.3}% of u_r(b)",
        100.0 * stress,
        100.0 * displacement
    );
    // A uniform state: the points next to the axis, where σ_θθ / r and
    // v_r / r are largest, must hold it as well as the rest.
    assert!(stress < 0.01, "{stress}");
    assert!(displacement < 0.01, "{displacement}");
}

/// A solid cylinder r ≤ 0.5 m, 0.5 m tall, standing under gravity on a
/// smooth fixed rigid floor, settled by damping. Poisson's ratio 0: then
/// σ_zz = −ρ g (h − z) with no radial strain is the exact solution and the
/// base stays flat (with ν > 0 the free column's base would curve, by
/// ν ρ g r² / 2E).
const COLUMN_ON_FLOOR: &str = r#"Scene(
    name: Some("column_on_floor"),
    grid: (
        origin: (0.0, 0.0),
        cell_size: 0.05,
        cells: (14, 16),
        edges: (left: Slip, right: Free, bottom: Fixed, top: Free),
    ),
    time: (dt: 1e-4, end: 1.0),
    gravity: (0.0, -9.81),
    settings: (geometry: Axisymmetric, pic_fraction: 1.0, particle_damping: 0.7, scheme: Usf, position_update: Some(RemappedVelocity)),
    materials: [(name: "stone", density: 1000.0, model: LinearElastic((youngs_modulus: 1e7, poisson_ratio: 0.0)))],
    bodies: [(name: "column", material: "stone", shape: Rectangle(min: (0.0, 0.15), max: (0.5, 0.65)), points_per_cell: 2)],
    blocks: [(
        name: "floor",
        shape: Cuboid(half_extents: (0.35, 0.05)),
        position: (0.35, 0.1),
        motion: Fixed,
        contact: (normal_stiffness: 1e6, tangential_stiffness: 1e6, friction: 0.0),
    )],
)"#;

#[test]
fn a_column_on_a_rigid_floor_weighs_its_weight_and_sinks_evenly() {
    let scene = Scene::parse(COLUMN_ON_FLOOR, Path::new("column_on_floor.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut sim = common::run_scene(&scene);
    // Per radian: ρ g h b² / 2.
    let weight = 1000.0 * 9.81 * 0.5 * 0.5 * 0.5 / 2.0;
    let reaction = sim
        .world()
        .resource::<mpdem::resources::BlockLog>()
        .samples
        .last()
        .expect("a block sample")
        .force
        .y;
    let points = sim.points_of("column").expect("column").clone();
    let sinking: Vec<(Real, Real)> = (0..points.len())
        .filter(|&p| points.initial_position[p].y < 0.17)
        .map(|p| (points.initial_position[p].x, -points.displacement(p).y))
        .collect();
    assert_eq!(
        sinking.len(),
        20,
        "the bottom row: 2 points per cell over 10 cells"
    );
    let mean = sinking.iter().map(|s| s.1).sum::<Real>() / sinking.len() as Real;
    let spread = sinking
        .iter()
        .map(|s| (s.1 - mean).abs() / mean)
        .fold(0.0, Real::max);
    println!(
        "column on floor: reaction {:.2} N/rad against the weight {weight:.2} N/rad; bottom row sinks {:.3e} m, each within {:.2}% of that",
        -reaction,
        mean,
        100.0 * spread
    );
    // At rest the floor carries the weight (this holds whatever the
    // springs, so it checks the masses per radian); the springs (per
    // radian, k_n r) hold the base ring at r by f ∝ r, so it sinks as far
    // as the middle: ρ g h (a spacing w) / k_n = 1.2e-4 m. With per-metre
    // springs on the per-radian masses the bottom row's sinking spreads by
    // 91% of its mean (measured, the scaling removed).
    assert!(
        (-reaction / weight - 1.0).abs() < 0.005,
        "{reaction} vs {weight}"
    );
    assert!(spread < 0.05, "{sinking:?}");
}

#[test]
fn what_a_body_of_revolution_cannot_have_is_refused_with_its_line() {
    let stage =
        |entry: &str| format!(r#"stages: [(name: "s", end: Duration(0.1), {entry})], blocks: [("#);
    // (text, its replacement, the refusal's words, whether plane strain
    // takes the edited scene)
    let cases: [(String, String, &str, bool); 11] = [
        (
            "origin: (0.0, 0.0)".into(),
            "origin: (-0.1, 0.0)".into(),
            "grid.origin.x must be 0",
            true,
        ),
        (
            "left: Slip".into(),
            "left: Free".into(),
            "grid.edges.left must be Slip",
            true,
        ),
        (
            "settings: (geometry: Axisymmetric, ".into(),
            "settings: (geometry: Axisymmetric, shape_function: QuadraticBSpline, ".into(),
            "QuadraticBSpline needs a cell",
            false,
        ),
        (
            "gravity: (0.0, -9.81)".into(),
            "gravity: (1.0, -9.81)".into(),
            "gravity must lie along the axis",
            true,
        ),
        (
            "points_per_cell: 2)]".into(),
            "points_per_cell: 2, acceleration: Some((value: (1.0, 0.0))))]".into(),
            "acceleration must lie along the axis",
            true,
        ),
        (
            "motion: Fixed".into(),
            "motion: Dynamic(density: 1000.0)".into(),
            "dynamic blocks are not available",
            true,
        ),
        (
            "motion: Fixed".into(),
            "motion: Kinematic((linear: (0.1, 0.0), angular: 0.0))".into(),
            "must move along the axis",
            true,
        ),
        (
            "motion: Fixed".into(),
            "motion: Kinematic((linear: (0.0, -0.1), angular: 1.0))".into(),
            "must move along the axis",
            true,
        ),
        (
            "position: (0.35, 0.1)".into(),
            "position: (0.3, 0.1)".into(),
            "across the axis",
            true,
        ),
        (
            "blocks: [(".into(),
            stage("gravity: Some((1.0, -9.81))"),
            "gravity must lie along the axis",
            true,
        ),
        (
            "blocks: [(".into(),
            stage("edges: Some((left: Free))"),
            "cannot be made Free",
            true,
        ),
    ];
    for (from, to, expected, _) in &cases {
        assert!(COLUMN_ON_FLOOR.contains(from.as_str()), "{from}");
        let edited = COLUMN_ON_FLOOR.replacen(from.as_str(), to, 1);
        let message = Scene::parse(&edited, Path::new("column.ron"))
            .expect_err("refused")
            .to_string();
        let line = edited
            .lines()
            .position(|l| l.contains(to.as_str()))
            .expect("edited line")
            + 1;
        assert!(message.contains(expected), "{to}: {message}");
        assert!(
            message.contains(&format!("column.ron:{line}:")),
            "{to}: {message}"
        );
    }
    // Edges left out (all Free): the refusal points at the grid.
    let edgeless = COLUMN_ON_FLOOR.replacen(
        "        edges: (left: Slip, right: Free, bottom: Fixed, top: Free),\n",
        "",
        1,
    );
    assert_ne!(edgeless, COLUMN_ON_FLOOR);
    let message = Scene::parse(&edgeless, Path::new("column.ron"))
        .expect_err("refused")
        .to_string();
    assert!(
        message.contains("column.ron:3:") && message.contains("grid.edges.left must be Slip"),
        "{message}"
    );
    // The same scene in plane strain takes them (but for the B-spline,
    // which needs its cell of margin there too).
    for (from, to, _, plane) in &cases {
        if !plane {
            continue;
        }
        let edited = COLUMN_ON_FLOOR
            .replacen("geometry: Axisymmetric, ", "", 1)
            .replacen(from.as_str(), to, 1);
        Scene::parse(&edited, Path::new("column.ron")).unwrap_or_else(|e| panic!("{to}: {e}"));
    }
}

#[test]
fn an_axisymmetric_run_is_the_same_on_one_and_two_threads() {
    // Cells halved and 3 × 3 points per cell: 3 600 points, several
    // parallel tasks per loop.
    let finer = COLUMN_ON_FLOOR
        .replacen("cell_size: 0.05", "cell_size: 0.025", 1)
        .replacen("cells: (14, 16)", "cells: (28, 32)", 1)
        .replacen("points_per_cell: 2", "points_per_cell: 3", 1);
    let scene =
        Scene::parse(&finer, Path::new("column_on_floor.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.bodies[0].points_per_cell, 3);
    let hash = |threads| {
        common::with_threads(threads, || {
            let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
            for _ in 0..200 {
                sim.step().unwrap_or_else(|e| panic!("{e}"));
            }
            sim.state_hash()
        })
    };
    assert_eq!(hash(1), hash(2));
}

/// A solid cylinder r ≤ 1 m between slip walls expanding as v_r = a r
/// (a = 0.01 1/s) for `steps` of 1e-5 s, with `affine` transfer or not.
fn uniform_expansion(affine: bool, steps: u32) -> MaterialPoints {
    let scene = format!(
        r#"Scene(
    grid: (origin: (0.0, 0.0), cell_size: 0.05, cells: (24, 4), edges: (left: Slip, right: Free, bottom: Slip, top: Slip)),
    time: (dt: 1e-5, steps: {steps}),
    gravity: (0.0, 0.0),
    settings: (geometry: Axisymmetric, affine_transfer: {affine}),
    materials: [(name: "m", density: 1000.0, model: LinearElastic((youngs_modulus: 1e7, poisson_ratio: 0.25)))],
    bodies: [(name: "cylinder", material: "m", shape: Rectangle(min: (0.0, 0.0), max: (1.0, 0.2)), points_per_cell: 2, velocity: Field(x: "0.01 * x", y: "0"))],
)"#
    );
    let scene = Scene::parse(&scene, Path::new("expansion.ron")).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = common::run_scene(&scene);
    sim.points_of("cylinder").expect("cylinder").clone()
}

/// The largest |σ/σ_exact − 1| of σ_rr and σ_θθ over the points inside
/// r < 0.6 m, σ_exact = 2(λ + μ) a t: the uniform expansion's stress,
/// which the unloading from the free surface r = 1 (at c = 110 m/s) has
/// not reached by t = 2e-3 s. Also the largest at r < 0.1 m (two cells).
fn expansion_errors(points: &MaterialPoints, time: Real) -> (Real, Real) {
    let (e, nu) = (1e7, 0.25);
    let (lambda, mu) = (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    );
    let exact = 2.0 * (lambda + mu) * 0.01 * time;
    let worst_below = |radius: Real| {
        (0..points.len())
            .filter(|&p| points.position[p].x < radius)
            .flat_map(|p| [points.stress[p].xx, points.stress[p].zz])
            .map(|s| (s / exact - 1.0).abs())
            .fold(0.0, Real::max)
    };
    (worst_below(0.6), worst_below(0.1))
}

#[test]
fn a_uniform_expansion_strains_evenly_up_to_the_axis_with_the_affine_transfer() {
    // v_r = a r gives D_rr = D_θθ = a, uniform stress and no acceleration
    // inside. Mapped with the masses per radian, which grow with r, the
    // nodes near the axis take a velocity leaning outwards: after one step
    // (C_p = 0, eq. 8c) the first node has 1.19 a h and the first cell's
    // stress is 19% too high (asserted: over 10% within two cells); the affine transfer carries each point's
    // velocity gradient and maps the linear field exactly, whatever the
    // weights.
    let first = expansion_errors(&uniform_expansion(false, 1), 1e-5);
    let affine = expansion_errors(&uniform_expansion(true, 200), 2e-3);
    println!(
        "uniform expansion: eq. 8c, one step: worst {:.2}% (first two cells {:.2}%); affine, 200 steps: worst {:.3}% (first two cells {:.3}%)",
        100.0 * first.0,
        100.0 * first.1,
        100.0 * affine.0,
        100.0 * affine.1
    );
    assert!(
        first.1 > 0.1,
        "the near-axis bias of eq. 8c is gone: {first:?}"
    );
    assert!(affine.0 < 0.01, "{affine:?}");
}

#[test]
fn a_left_traction_on_the_axis_is_warned_of_and_one_off_it_loads() {
    // Whether the stage's start warns of the traction, and the largest
    // radial speed after 20 steps (ν = 0 and a smooth floor: only the
    // traction moves the points sideways).
    let with_left = |shape: &str| {
        let text = COLUMN_ON_FLOOR
            .replacen("Rectangle(min: (0.0, 0.15), max: (0.5, 0.65))", shape, 1)
            .replacen(
                "blocks: [(",
                r#"stages: [(name: "s", end: Duration(0.01), tractions: [(body: "column", side: Left, traction: (1e3, 0.0))])], blocks: [("#,
                1,
            );
        let scene = Scene::parse(&text, Path::new("column.ron")).unwrap_or_else(|e| panic!("{e}"));
        let mut sim = Simulation::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
        let warned = sim
            .warnings()
            .iter()
            .any(|w| w.message.contains("lies on the axis"));
        for _ in 0..20 {
            sim.step().unwrap_or_else(|e| panic!("{e}"));
        }
        let points = sim.points_of("column").expect("column");
        let sideways = points
            .velocity
            .iter()
            .map(|v| v.x.abs())
            .fold(0.0, Real::max);
        (warned, sideways)
    };
    // A ring off the axis is loaded.
    let (warned, ring) = with_left("Rectangle(min: (0.2, 0.15), max: (0.5, 0.65))");
    assert!(!warned && ring > 0.0, "{ring}");
    // The column reaches the axis: its Left side has no area there (what
    // moves sideways is rounding: 1e-11 m/s against the ring's 4e-3).
    let (warned, sideways) = with_left("Rectangle(min: (0.0, 0.15), max: (0.5, 0.65))");
    assert!(
        warned && sideways < 1e-6 * ring,
        "{sideways} against {ring}"
    );
    // Starting 0.01 m off the axis its points still fill the cells from
    // the axis: warned too.
    assert!(with_left("Rectangle(min: (0.01, 0.15), max: (0.5, 0.65))").0);
    // A triangle with one corner on it is loaded (a rule on the outline
    // would refuse it).
    let (warned, triangle) = with_left("Polygon(vertices: [(0.0, 0.4), (0.5, 0.15), (0.5, 0.65)])");
    assert!(
        !warned && triangle > 1e-3 * ring,
        "{triangle} against {ring}"
    );
}

/// The uniform expansion v_r = a r left free for 0.05 s (FLIP, no
/// damping) in `model`: its outer surface unloads it and the cylinder
/// breathes, the kinetic and the strain energy trading places (period
/// about 14 ms at E = 1e7 Pa). Returns the largest change of their sum and
/// the least kinetic energy, as fractions of the start.
fn breathing(model: &str, a: Real) -> (Real, Real) {
    breathing_under(model, a, "")
}

/// [`breathing`] with more `settings` (RON fields, each followed by a
/// comma).
fn breathing_under(model: &str, a: Real, settings: &str) -> (Real, Real) {
    let scene = format!(
        r#"Scene(
    grid: (origin: (0.0, 0.0), cell_size: 0.05, cells: (24, 4), edges: (left: Slip, right: Free, bottom: Slip, top: Slip)),
    time: (dt: 1e-5, end: 0.05),
    gravity: (0.0, 0.0),
    materials: [(name: "m", density: 1000.0, model: {model})],
    settings: ({settings} geometry: Axisymmetric),
    bodies: [(name: "cylinder", material: "m", shape: Rectangle(min: (0.0, 0.0), max: (1.0, 0.2)), points_per_cell: 2, velocity: Field(x: "{a} * x", y: "0"))],
)"#
    );
    let scene = Scene::parse(&scene, Path::new("breathing.ron")).unwrap_or_else(|e| panic!("{e}"));
    let sim = common::run_scene(&scene);
    let samples = &sim
        .world()
        .resource::<mpdem::resources::EnergyLog>()
        .samples;
    let start = samples[0].total();
    let drift = samples
        .iter()
        .map(|s| (s.total() / start - 1.0).abs())
        .fold(0.0, Real::max);
    let least_kinetic = samples
        .iter()
        .map(|s| s.kinetic)
        .fold(Real::INFINITY, Real::min);
    println!(
        "breathing cylinder, {model}, a = {a}, settings ({settings}): energy {start:.4e} J/rad, largest change {:.3}%, kinetic energy down to {:.1}% of the start",
        100.0 * drift,
        100.0 * least_kinetic / samples[0].kinetic
    );
    (drift, least_kinetic / samples[0].kinetic)
}

#[test]
fn a_breathing_cylinder_keeps_its_energy() {
    // Nothing takes or gives energy, so the sum must stay, up to the
    // scheme's error: within 1% (measured 0.12% for both over three and a
    // half periods; weighting the nodal velocities by m_p / r_p, tried and
    // reverted, lost a few percent in a reviewer's 1D model of such a
    // cylinder). The Neo-Hookean one breathes at a = 5 1/s, with strains
    // of a few percent: its stored energy reads the hoop stretch F_θθ and
    // must change by the work of its stress, hoop part included (with
    // F_θθ = r / R from the points' positions it drifted 0.9%; with F_θθ = 1
    // in its stress or its energy, 400% or 78%, measured then). The fluid's
    // pressure reads J = det F F_θθ (measured 0.10%). (The linear solid is left
    // at a small amplitude: its Jaumann rate has no stored energy at finite
    // strain, and at a = 5 its complementary energy drifts 1.5%.)
    for (model, a) in [
        (
            "LinearElastic((youngs_modulus: 1e7, poisson_ratio: 0.25))",
            0.01,
        ),
        (
            "NeoHookean((youngs_modulus: 1e7, poisson_ratio: 0.25))",
            5.0,
        ),
        (
            "NewtonianFluid((bulk_modulus: 1e6, gamma: 7.0, viscosity: 0.0))",
            1.0,
        ),
    ] {
        let (drift, least_kinetic) = breathing(model, a);
        // It breathes: its kinetic energy turns into strain and back.
        assert!(least_kinetic < 0.2, "{model}: {least_kinetic}");
        assert!(drift < 0.01, "{model}: {drift}");
    }
}

#[test]
fn under_musl_a_breathing_cylinder_keeps_its_energy() {
    // The Neo-Hookean cylinder of `a_breathing_cylinder_keeps_its_energy`
    // under MUSL, whose strain and hoop rates read the remapped velocity:
    // the same 1% (measured 0.115%, as 0.12% under USF).
    let model = "NeoHookean((youngs_modulus: 1e7, poisson_ratio: 0.25))";
    let (drift, least_kinetic) = breathing_under(model, 5.0, "scheme: Musl,");
    assert!(least_kinetic < 0.2, "{least_kinetic}");
    assert!(drift < 0.01, "{drift}");
}

#[test]
fn a_rigid_punchs_stiffness_converges_to_the_finite_elements_at_first_order() {
    // scenes/axisymmetric_punch.ron at twice its cell (a/5) and at its own
    // (a/10), against finite elements of the same cylinder extrapolated to
    // a zero element: the rigid edge makes both converge at first order, so
    // each run is stiffer than the reference and halving the cell halves
    // the excess (ratio held to 0.4–0.6).
    use mpdem_verify::punch;
    let base = Scene::load(&common::scene_path("axisymmetric_punch.ron")).expect("scene");
    let reference = {
        let elements = punch::finite_elements();
        punch::extrapolated(elements[0], elements[1])
    };
    let excess = |factor: Real| {
        let mut sim = Simulation::from_scene(&mpdem_verify::at_cell(&base, factor)).expect("build");
        sim.run().expect("run");
        punch::stiffness(&sim).expect("stiffness") / punch::sneddon() / reference - 1.0
    };
    let (coarse, fine) = (excess(2.0), excess(1.0));
    println!("excess over the finite elements: a/5 {coarse:+.4}, a/10 {fine:+.4}");
    assert!(coarse > 0.0 && fine > 0.0, "{coarse} {fine}");
    assert!(
        (0.4..0.6).contains(&(fine / coarse)),
        "ratio {}",
        fine / coarse
    );
}

#[test]
#[ignore = "the full punch case at three cells: under a minute on 2 cores"]
fn full_axisymmetric_punch_converges_to_the_finite_elements() {
    common::verify_case("axisymmetric_punch");
}
