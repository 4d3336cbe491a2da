//! Rigid footings on a weightless, cohesionless Mohr–Coulomb soil with
//! associated flow under a surcharge q, against their exact collapse loads
//! p + q = N_q q: a smooth strip in plane strain (`scenes/strip_footing.ron`;
//! N_q = e^{π tan φ} tan²(π/4 + φ/2), Prandtl 1920, Reissner 1924) and a
//! smooth circle as a body of revolution (`scenes/circular_footing.ron`; N_q
//! by the method of stress characteristics, Cox, Eason and Hopkins 1961).
//! They check the frictional strength and the block contact together, in
//! the limit load a pile's tip resistance rests on, in both geometries.
//!
//! The footing's pressure is averaged over a stretch of its settlement past
//! the collapse, at twice the scene's cell (B/5), at its cell (B/10) and at
//! half of it. The edge of a rigid footing makes the stress singular, so the
//! collapse load converges from above at about first order in the cell; the
//! judged check is the first-order extrapolation of B/10 and B/20 to a zero
//! cell, and the three cells' own order and extrapolation are reported.

use super::stress_characteristics::smooth_footing_nq;
use super::{Check, Context, Curve, Figure, Measured, VerifyError, percent};
use mpdem::Simulation;
use mpdem::geometry::Geometry;
use mpdem::math::Real;
use std::f64::consts::PI;

/// Footing width B (m; the circle's diameter), surcharge q (Pa) and friction
/// angle φ (degrees) of both scenes.
const WIDTH: Real = 1.0;
const SURCHARGE: Real = 150e3;
const FRICTION_ANGLE: Real = 32.0;

/// The two footings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Footing {
    /// A strip in plane strain, as a half model (`scenes/strip_footing.ron`).
    Strip,
    /// A circle as a body of revolution (`scenes/circular_footing.ron`).
    Circle,
}

impl Footing {
    /// The scene's file name.
    pub fn scene_file(self) -> &'static str {
        match self {
            Footing::Strip => "strip_footing.ron",
            Footing::Circle => "circular_footing.ron",
        }
    }

    /// The case's name, which prefixes its runs.
    fn case_name(self) -> &'static str {
        match self {
            Footing::Strip => "strip_footing",
            Footing::Circle => "circular_footing",
        }
    }

    /// The mean pressure under the footing from its vertical reaction f:
    /// f over the half model's half width, or 2 π f / (π a²) = 2 f / a² for
    /// the circle of radius a, f per radian.
    pub fn pressure(self, force: Real) -> Real {
        match self {
            Footing::Strip => force / (0.5 * WIDTH),
            Footing::Circle => 2.0 * force / (0.5 * WIDTH).powi(2),
        }
    }

    /// The exact N_q of the scene's soil (φ = 32°): Prandtl's closed form,
    /// or the method of characteristics for the circle.
    pub fn exact_nq(self) -> Real {
        match self {
            Footing::Strip => prandtl_nq(FRICTION_ANGLE),
            Footing::Circle => smooth_footing_nq(FRICTION_ANGLE, Geometry::Axisymmetric, 60),
        }
    }

    /// The reference's name in the figure.
    fn reference(self) -> &'static str {
        match self {
            Footing::Strip => "Prandtl: N_q",
            Footing::Circle => "characteristics: N_q",
        }
    }
}

/// The settlements s/B over which the pressure is averaged: past the
/// strip's collapse (at about 0.04 at B/10 and B/20), short of the heave's
/// largest; the circle is averaged over the same stretch.
const PLATEAU: (Real, Real) = (0.05, 0.08);

/// Prandtl's bearing capacity factor N_q of a weightless soil.
pub fn prandtl_nq(friction_angle_degrees: Real) -> Real {
    let phi = friction_angle_degrees.to_radians();
    (PI * phi.tan()).exp() * (PI / 4.0 + phi / 2.0).tan().powi(2)
}

/// The footing's settlement over B and (p + q) / q at each sample: the
/// settlement from where the footing stood when first sampled, p its mean
/// pressure ([`Footing::pressure`]).
pub fn pressure_curve(
    sim: &Simulation,
    footing: Footing,
) -> Result<Vec<(Real, Real)>, VerifyError> {
    let samples = super::pressed_block(sim, "footing")?;
    Ok(samples
        .into_iter()
        .map(|(sunk, force)| {
            let pressure = footing.pressure(force);
            (sunk / WIDTH, (pressure + SURCHARGE) / SURCHARGE)
        })
        .collect())
}

/// The mean of (p + q) / q over the settlements s/B 0.05–0.08, past the
/// strip's collapse and short of the heave's largest.
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

/// Richardson's extrapolation at the order the values themselves show: from
/// P at cells 4h, 2h and h, the order n = log2((P_4h − P_2h) / (P_2h − P_h))
/// and the limit P_h − (P_2h − P_h) / (2^n − 1); both NaN when the three do
/// not change monotonically.
pub fn observed_order_limit(coarsest: Real, coarse: Real, fine: Real) -> (Real, Real) {
    let order = ((coarsest - coarse) / (coarse - fine)).log2();
    (order, fine - (coarse - fine) / (order.exp2() - 1.0))
}

/// The strip footing's case.
pub fn run_strip(ctx: &Context) -> Result<Measured, VerifyError> {
    run(ctx, Footing::Strip)
}

/// The circular footing's case.
pub fn run_circle(ctx: &Context) -> Result<Measured, VerifyError> {
    run(ctx, Footing::Circle)
}

/// Both cells of a footing, and the checks.
fn run(ctx: &Context, footing: Footing) -> Result<Measured, VerifyError> {
    let base = ctx.scene(footing.scene_file())?;
    let exact = footing.exact_nq();
    let mut cells = Vec::new();
    let name = footing.case_name();
    let mut figure = Figure::new(
        format!("{}: pressure against settlement", name.replace('_', " ")),
        "s / B",
        "(p + q) / q",
    );
    for factor in [2.0, 1.0, 0.5] {
        let scene = super::at_cell(&base, factor);
        let per_width = WIDTH / scene.grid.cell_size;
        let sim = ctx.run(&format!("{name}, cell B/{per_width:.0}"), &scene)?;
        let curve = pressure_curve(&sim, footing)?;
        cells.push((per_width, plateau(&curve)?));
        figure = figure.with(Curve::computed(
            format!("mpdem, cell B/{per_width:.0}"),
            curve,
        ));
    }
    figure = figure.with(Curve::reference(
        footing.reference(),
        vec![(0.0, exact), (0.1, exact)],
    ));
    let (coarsest, coarse, fine) = (cells[0], cells[1], cells[2]);
    let limit = 2.0 * fine.1 - coarse.1;
    let (observed_order, observed_limit) = observed_order_limit(coarsest.1, coarse.1, fine.1);
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
        Check::reported(
            "the three cells' own order, and their extrapolation at it",
            format!(
                "order {observed_order:.2}: {observed_limit:.2} ({} from N_q)",
                percent(observed_limit / exact - 1.0, 1)
            ),
            "near N_q",
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

    /// The observed order and limit recover P = 10 + 3 h^1.5.
    #[test]
    fn richardson_recovers_a_power_law() {
        let value = |h: Real| 10.0 + 3.0 * h.powf(1.5);
        let (order, limit) = observed_order_limit(value(4.0), value(2.0), value(1.0));
        assert!((order - 1.5).abs() < 1e-12, "{order}");
        assert!((limit - 10.0).abs() < 1e-12, "{limit}");
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
