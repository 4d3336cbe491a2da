//! Prandtl's strip footing (`scenes/strip_footing.ron`): a smooth rigid
//! strip pressed into a weightless, cohesionless Mohr–Coulomb soil with
//! associated flow under a surcharge q, against the exact collapse load
//! p + q = N_q q, N_q = e^{π tan φ} tan²(π/4 + φ/2) (Prandtl 1920, Reissner
//! 1924). It checks the frictional strength and the block contact together,
//! in the limit load a pile's tip resistance rests on.
//!
//! The footing's pressure is averaged over a stretch of its settlement past
//! the collapse, at the scene's cell (B/10) and at half of it. The edge of a
//! rigid footing makes the stress singular, so the collapse load converges at
//! first order in the cell, from above; the judged check is its first-order
//! extrapolation to a zero cell.

use super::{Check, Context, Curve, Figure, Measured, VerifyError, percent};
use crate::Simulation;
use crate::math::Real;
use std::f64::consts::PI;

/// Footing width B (m), surcharge q (Pa) and friction angle φ (degrees) of
/// the scene.
const WIDTH: Real = 1.0;
const SURCHARGE: Real = 150e3;
const FRICTION_ANGLE: Real = 32.0;

/// The settlements s/B over which the pressure is averaged: past the
/// collapse (at about 0.04 at both cells), short of the heave's largest.
const PLATEAU: (Real, Real) = (0.05, 0.08);

/// Prandtl's bearing capacity factor N_q of a weightless soil.
pub fn prandtl_nq(friction_angle_degrees: Real) -> Real {
    let phi = friction_angle_degrees.to_radians();
    (PI * phi.tan()).exp() * (PI / 4.0 + phi / 2.0).tan().powi(2)
}

/// The footing's settlement over B and (p + q) / q at each sample: the
/// settlement from where the footing stood when first sampled, p its
/// vertical reaction over the half model's half width.
pub fn pressure_curve(sim: &Simulation) -> Result<Vec<(Real, Real)>, VerifyError> {
    let samples = super::pressed_block(sim, "footing")?;
    Ok(samples
        .into_iter()
        .map(|(sunk, force)| {
            let pressure = force / (0.5 * WIDTH);
            (sunk / WIDTH, (pressure + SURCHARGE) / SURCHARGE)
        })
        .collect())
}

/// The mean of (p + q) / q over the settlements of [`PLATEAU`].
pub fn plateau(curve: &[(Real, Real)]) -> Result<Real, VerifyError> {
    let inside: Vec<Real> = curve
        .iter()
        .filter(|(s, _)| (PLATEAU.0..=PLATEAU.1).contains(s))
        .map(|&(_, p)| p)
        .collect();
    if inside.len() < 3 {
        let reached = curve.iter().map(|&(s, _)| s).fold(0.0, Real::max);
        return Err(VerifyError::Measurement(format!(
            "too few samples over s/B {}–{}: the footing settled {reached:.3} B",
            PLATEAU.0, PLATEAU.1
        )));
    }
    Ok(inside.iter().sum::<Real>() / inside.len() as Real)
}

/// Both cells, and the checks.
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let base = ctx.scene("strip_footing.ron")?;
    let exact = prandtl_nq(FRICTION_ANGLE);
    let mut cells = Vec::new();
    let mut figure = Figure::new(
        "strip footing: pressure against settlement",
        "s / B",
        "(p + q) / q",
    );
    for factor in [1.0, 0.5] {
        let scene = super::at_cell(&base, factor);
        let per_width = WIDTH / scene.grid.cell_size;
        let sim = ctx.run(&format!("strip_footing, cell B/{per_width:.0}"), &scene)?;
        let curve = pressure_curve(&sim)?;
        cells.push((per_width, plateau(&curve)?));
        figure = figure.with(Curve::computed(
            format!("mpdem, cell B/{per_width:.0}"),
            curve,
        ));
    }
    figure = figure.with(Curve::reference(
        "Prandtl: N_q",
        vec![(0.0, exact), (0.1, exact)],
    ));
    let (coarse, fine) = (cells[0], cells[1]);
    let limit = 2.0 * fine.1 - coarse.1;
    let error = limit / exact - 1.0;
    let by_cell: Vec<String> = cells
        .iter()
        .map(|(n, p)| format!("B/{n:.0}: {p:.2} ({})", percent(p / exact - 1.0, 1)))
        .collect();
    let checks = vec![
        Check::judged(
            "(p + q) / q over s/B 0.05–0.08, extrapolated to a zero cell",
            format!("{limit:.2} ({} from N_q)", percent(error, 1)),
            format!("within 5% of N_q = {exact:.2}"),
            error.abs() <= 0.05,
        )
        .because(
            "the rigid edge makes the collapse load converge at first order in the cell, \
             from above; 5% is the usual agreement of limit-load benchmarks",
        ),
        Check::reported(
            "(p + q) / q over s/B 0.05–0.08, by cell",
            by_cell.join(", "),
            "above N_q, the excess halving with the cell",
        ),
        Check::reported(
            "order of convergence from B/10 to B/20",
            format!("{:.2}", ((coarse.1 - exact) / (fine.1 - exact)).log2()),
            "1",
        ),
    ];
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// N_q from its closed form against tabulated values (Vesić 1973:
    /// 18.40 at 30°, 23.18 at 32°, 33.30 at 35°).
    #[test]
    fn prandtl_nq_matches_the_tables() {
        for (phi, nq) in [(30.0, 18.40), (32.0, 23.18), (35.0, 33.30)] {
            let computed = prandtl_nq(phi);
            assert!(
                (computed - nq).abs() < 0.01,
                "{phi}: {computed} against {nq}"
            );
        }
    }

    /// The plateau averages the samples inside the window and refuses a
    /// curve that never reaches it.
    #[test]
    fn the_plateau_averages_its_window() {
        let curve: Vec<(Real, Real)> = (0..=100).map(|k| (k as Real * 1e-3, k as Real)).collect();
        let mean = plateau(&curve).unwrap();
        assert!((mean - 65.0).abs() < 1e-9, "{mean}");
        let short = &curve[..40];
        let message = plateau(short).unwrap_err().to_string();
        assert!(message.contains("settled 0.039 B"), "{message}");
    }
}
