//! A rigid, frictionless flat punch pressed into an elastic cylinder as a
//! body of revolution (`scenes/axisymmetric_punch.ron`), against finite
//! elements of the same cylinder ([`super::punch_elements`]): how the
//! reaction of a rigid block converges with the cell.
//!
//! The punch's stiffness dF/dδ is fitted over the second half of its
//! stroke at the scene's cell (a/10), twice it and half of it. A rigid
//! punch's edge makes the stress singular, so the finite elements and the
//! material points both converge at first order in the cell; the judged
//! check is the engine's stiffness extrapolated to a zero cell from its two
//! finest runs, against the elements' extrapolated the same way.

use super::punch_elements::PunchCylinder;
use super::{Check, Context, Curve, Figure, Measured, VerifyError, percent};
use mpdem::Simulation;
use mpdem::math::Real;
use std::f64::consts::PI;

/// Punch radius a (m), cylinder radius and height (m), Young's modulus
/// (Pa) and Poisson's ratio of the scene.
const PUNCH_RADIUS: Real = 0.4;
const CYLINDER: Real = 2.0;
const YOUNGS_MODULUS: Real = 1.6e7;
const POISSON_RATIO: Real = 0.3;

/// The cells the case runs, as multiples of the scene's (a/10): a/5, a/10
/// and a/20.
const CELL_FACTORS: [Real; 3] = [2.0, 1.0, 0.5];

/// Elements per punch radius of the two finite-element meshes whose
/// first-order extrapolation is the reference.
const ELEMENTS_PER_RADIUS: [usize; 2] = [20, 40];

/// Sneddon's stiffness of a rigid flat punch on an elastic half-space,
/// 2 a E / (1 − ν²) (Sneddon 1946, Proc. Cambridge Phil. Soc. 42, 29): the
/// unit the stiffnesses are given in.
pub fn sneddon() -> Real {
    2.0 * PUNCH_RADIUS * YOUNGS_MODULUS / (1.0 - POISSON_RATIO * POISSON_RATIO)
}

/// The punch's stiffness dF/dδ (N/m, F = 2π f its whole force): the least-
/// squares slope of F against δ over the samples of the stroke's second
/// half.
pub fn stiffness(sim: &Simulation) -> Result<Real, VerifyError> {
    let samples: Vec<(Real, Real)> = super::pressed_block(sim, "punch")?
        .into_iter()
        .map(|(sunk, force)| (sunk, 2.0 * PI * force))
        .collect();
    let stroke = samples.iter().map(|s| s.0).fold(0.0, Real::max);
    let late: Vec<(Real, Real)> = samples
        .into_iter()
        .filter(|s| s.0 >= 0.5 * stroke)
        .collect();
    if late.len() < 3 {
        return Err(VerifyError::Measurement(
            "too few samples of the punch's stroke".into(),
        ));
    }
    let n = late.len() as Real;
    let (mx, my) = late
        .iter()
        .fold((0.0, 0.0), |(x, y), s| (x + s.0 / n, y + s.1 / n));
    let (sxy, sxx) = late.iter().fold((0.0, 0.0), |(xy, xx), s| {
        (xy + (s.0 - mx) * (s.1 - my), xx + (s.0 - mx) * (s.0 - mx))
    });
    Ok(sxy / sxx)
}

/// The finite elements' stiffness over Sneddon's at a/20 and a/40, by
/// elements per radius.
pub fn finite_elements() -> [(Real, Real); 2] {
    let cylinder = PunchCylinder {
        punch_radius: PUNCH_RADIUS,
        radius: CYLINDER,
        height: CYLINDER,
        youngs_modulus: YOUNGS_MODULUS,
        poisson_ratio: POISSON_RATIO,
    };
    ELEMENTS_PER_RADIUS.map(|n| (n as Real, cylinder.stiffness(n) / sneddon()))
}

/// First-order extrapolation to a zero cell from stiffnesses at a cell and
/// at half of it, each (cells per radius, stiffness): 2 K(h/2) − K(h).
pub fn extrapolated(coarse: (Real, Real), fine: (Real, Real)) -> Real {
    2.0 * fine.1 - coarse.1
}

/// The three cells, the finite elements, and the checks.
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let base = ctx.scene("axisymmetric_punch.ron")?;
    let mut engine = Vec::new();
    for factor in CELL_FACTORS {
        let scene = super::at_cell(&base, factor);
        let per_radius = PUNCH_RADIUS / scene.grid.cell_size;
        let run = format!("axisymmetric_punch, cell a/{per_radius:.0}");
        let sim = ctx.run(&run, &scene)?;
        engine.push((per_radius, stiffness(&sim)? / sneddon()));
    }
    let elements = finite_elements();
    let reference = extrapolated(elements[0], elements[1]);
    let limit = extrapolated(engine[1], engine[2]);
    let error = limit / reference - 1.0;
    let excesses: Vec<String> = engine
        .iter()
        .map(|(n, k)| format!("a/{n:.0}: {}", percent(k / reference - 1.0, 1)))
        .collect();
    let order = |coarse: (Real, Real), fine: (Real, Real)| {
        ((coarse.1 - reference) / (fine.1 - reference)).log2()
    };
    let checks = vec![
        Check::judged(
            "stiffness extrapolated to a zero cell, 2 K(a/20) − K(a/10), over Sneddon's 2aE*",
            format!("{limit:.4} ({} from the elements')", percent(error, 2)),
            format!("within 2% of the finite elements' {reference:.4}"),
            error.abs() <= 0.02,
        )
        .because(
            "both converge at first order under the rigid edge; the elements' own \
             extrapolation from a/20 and a/40 is good to about 0.3%",
        ),
        Check::reported(
            "stiffness's excess over the finite elements, by cell",
            excesses.join(", "),
            "first order: halving with the cell",
        ),
        Check::reported(
            "order of convergence from a/5 to a/10 and from a/10 to a/20",
            format!(
                "{:.2}, {:.2}",
                order(engine[0], engine[1]),
                order(engine[1], engine[2])
            ),
            "1",
        ),
        Check::reported(
            "finite elements at a/20 and a/40, over Sneddon's 2aE*",
            format!("{:.4}, {:.4}", elements[0].1, elements[1].1),
            "above 1: the cylinder is 5a wide and deep, not a half-space",
        ),
    ];
    let figure = Figure::new(
        "axisymmetric punch: stiffness against the cell",
        "cell / punch radius",
        "dF/dδ / (2 a E*)",
    )
    .with(Curve::computed(
        "mpdem",
        engine.iter().map(|(n, k)| (1.0 / n, *k)).collect(),
    ))
    .with(Curve::reference(
        "finite elements",
        elements.iter().map(|(n, k)| (1.0 / n, *k)).collect(),
    ))
    .with(Curve::reference(
        "finite elements, extrapolated",
        vec![(0.0, reference), (0.2, reference)],
    ));
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}
