//! Pile penetration (paper section 4.3): stages, a compound kinematic
//! block, Mohr–Coulomb soil and the cone-resistance curve.

mod common;

use mpdem::prelude::*;
use mpdem::resources::{StageEndReason, StageLog};
use mpdem_verify::pile::{RADIUS, cone_resistance, mean_between};

/// The pile scene at a reduced size: cells of 0.16 m (1,500 points), the
/// pile driven to 2R, the step doubled (still within the CFL and contact
/// limits at this cell size).
fn reduced_scene(depth_over_radius: Real) -> Scene {
    let mut scene = common::load_scene("pile_penetration.ron");
    scene.grid.cell_size = 0.16;
    scene.grid.cells = (50, 35);
    scene.time.dt = 2e-4;
    scene.stages[2].end = mpdem::scene::StageEnd::Duration(depth_over_radius * 0.4 / 0.1);
    scene.output.frame_interval = None;
    scene
}

#[test]
fn reduced_pile_penetrates_stably_through_its_stages() {
    let scene = reduced_scene(2.0);
    let sim = common::run_scene(&scene);
    let log = sim.world().resource::<StageLog>();
    let reasons: Vec<_> = log.records.iter().map(|r| r.reason).collect();
    assert_eq!(
        reasons,
        [
            StageEndReason::Condition,
            StageEndReason::Condition,
            StageEndReason::Duration
        ],
        "{:?}",
        log.warnings
    );
    let curve = cone_resistance(&sim, RADIUS).unwrap_or_else(|e| panic!("{e}"));
    let at = |z: Real| mean_between(&curve, z - 0.25, z + 0.25).unwrap_or(Real::NAN);
    let (q1, q2) = (at(1.0), at(1.75));
    println!(
        "reduced pile: q_c = {:.3} MPa at z/R = 1, {:.3} MPa at z/R = 1.75",
        q1 / 1e6,
        q2 / 1e6
    );
    // The cone pushes the soil (positive resistance) and the resistance
    // grows with depth, as the confining stress does. The full scenes'
    // cone resistance is judged by `mpdem verify pile_penetration_axisymmetric`.
    assert!(q1 > 0.0 && q2 > q1, "q_c {q1} then {q2}");
}

#[test]
fn reduced_axisymmetric_pile_meets_more_resistance_than_the_plane_one() {
    // The same reduced scene as a body of revolution: the cone then pushes
    // the sand aside in every direction around it, as a spherical cavity
    // expands, where the plane-strain wedge pushes it aside as a
    // cylindrical one; Vesić's (1972) limit pressures for this sand are
    // 12.9 p₀ against 6.9 p₀. q_c = 2 f_c / R² against f_c / R.
    let q_at = |file: &str| {
        let mut scene = reduced_scene(2.0);
        scene.settings.geometry = common::load_scene(file).settings.geometry;
        let sim = common::run_scene(&scene);
        let curve = cone_resistance(&sim, RADIUS).unwrap_or_else(|e| panic!("{e}"));
        mean_between(&curve, 1.5, 2.0).unwrap_or(Real::NAN)
    };
    let plane = q_at("pile_penetration.ron");
    let axisymmetric = q_at("pile_penetration_axisymmetric.ron");
    println!(
        "reduced pile, q_c over z/R 1.5–2: plane strain {:.3} MPa, axisymmetric {:.3} MPa",
        plane / 1e6,
        axisymmetric / 1e6
    );
    // Measured 1.82 times here (1.64 / 0.90 MPa) and 1.70 times over
    // z/R 4–8 at full size;
    // a fifth more is asked, well clear of both a plane result (1.0) and
    // of the noise between runs of nearby settings (a few percent), and
    // at most 2.5 times: an engine that ran the plane model and only read
    // the force as axisymmetric (2 f_c / R² against f_c / R) would give 5.
    let ratio = axisymmetric / plane;
    assert!(
        (1.2..2.5).contains(&ratio),
        "{axisymmetric} against {plane}"
    );
}

#[test]
#[ignore = "the full pile scene at two cells: about 15 minutes on 2 cores"]
fn full_plane_pile_converges_in_the_cell() {
    // Its q_c (f_c / R) is reported, not judged: Susila and Hryciw's
    // 4–6 MPa comes from an axisymmetric geometry. The stages at both
    // cells and the convergence (the mean over z/R 4–8 within 5% from h to
    // h/2) are judged; the curves go to out/verify/pile_penetration/.
    common::verify_case("pile_penetration");
}

#[test]
#[ignore = "the full axisymmetric pile scene at two cells: about 15 minutes on 2 cores"]
fn full_axisymmetric_pile_runs_through_its_stages_at_two_cells() {
    // Its convergence in the cell and its q_c (2 f_c / R²) over z/R 4–8,
    // extrapolated to a zero cell, against Susila and Hryciw's 4–6 MPa are
    // judged in the report (`mpdem verify pile_penetration_axisymmetric`),
    // where they are missed; this test holds the runs themselves: every
    // stage of both cells ends as planned.
    let case = mpdem_verify::case("pile_penetration_axisymmetric").expect("case");
    let root = common::repository_root();
    let quiet = |_: mpdem_verify::RunEvent| {};
    let ctx = mpdem_verify::Context::new(&root.join("scenes"), &root.join("out/verify"), &quiet);
    let report = mpdem_verify::CaseReport::run(case, &ctx);
    print!("{report}");
    let stages: Vec<_> = report
        .checks()
        .iter()
        .filter(|c| c.quantity.contains("stages:"))
        .collect();
    assert_eq!(stages.len(), 2, "a stage check per cell");
    assert!(
        stages
            .iter()
            .all(|c| c.verdict == mpdem_verify::Verdict::Met),
        "a stage did not end as planned"
    );
}
