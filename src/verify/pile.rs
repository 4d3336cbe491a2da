//! Paper section 4.3: a rigid pile with a cone tip driven at 0.1 m/s into
//! Mohr–Coulomb sand after a geostatic stage and a 150 kPa surcharge; the
//! cone resistance q_c = f_c / R against z / R. Also the same scene as a
//! body of revolution (`settings.geometry: Axisymmetric`), the geometry of
//! Susila and Hryciw's finite elements, where q_c is the tip's force over
//! its area.

use super::{Check, Context, Curve, Figure, Measured, VerifyError};
use crate::Simulation;
use crate::io::csv::write_curve;
use crate::io::plot::{Series, plot_series};
use crate::math::Real;
use crate::resources::{BlockLog, Geometry, Settings, StageEndReason, StageLog};
use std::path::Path;

/// Radius of the scene's pile (m).
pub const RADIUS: Real = 0.4;

/// (time, z / R, q_c) for every block sample of the penetration (third)
/// stage: z the pile's travel since the stage began, q_c = f_c / R in plane
/// strain (f_c the vertical reaction on the cone, the pile's part 1, of the
/// half model), in axisymmetry the cone's whole force over its area,
/// 2π f_c / (π R²) = 2 f_c / R² (f_c per radian).
pub fn cone_resistance(sim: &Simulation, radius: Real) -> Result<ConeCurve, VerifyError> {
    let world = sim.world();
    let per_force = match world.resource::<Settings>().geometry {
        Geometry::PlaneStrain => 1.0 / radius,
        Geometry::Axisymmetric => 2.0 / (radius * radius),
    };
    let log = world.resource::<BlockLog>();
    let start = world
        .resource::<StageLog>()
        .records
        .get(1)
        .ok_or_else(|| VerifyError::Measurement("the surcharge stage never ended".into()))?
        .end;
    let origin = log
        .samples
        .iter()
        .find(|s| s.time >= start)
        .ok_or_else(|| VerifyError::Measurement("no sample of the penetration stage".into()))?
        .origin;
    Ok(log
        .samples
        .iter()
        .filter(|s| s.time >= start)
        .filter_map(|s| {
            let cone = log.parts.iter().find(|p| p.time == s.time && p.part == 1)?;
            Some((
                s.time,
                (origin.y - s.origin.y) / radius,
                cone.force.y * per_force,
            ))
        })
        .collect())
}

/// (time, z / R, q_c) samples, as [`cone_resistance`] gives them.
pub type ConeCurve = Vec<(Real, Real, Real)>;

/// Mean q_c of the samples with `from ≤ z/R < to`, if any.
pub fn mean_between(curve: &[(Real, Real, Real)], from: Real, to: Real) -> Option<Real> {
    let inside: Vec<Real> = curve
        .iter()
        .filter(|(_, z, _)| (from..to).contains(z))
        .map(|(_, _, q)| *q)
        .collect();
    (!inside.is_empty()).then(|| inside.iter().sum::<Real>() / inside.len() as Real)
}

/// The published plateau, 4–6 MPa (Susila and Hryciw: about 5 MPa).
const PLATEAU: (Real, Real) = (4e6, 6e6);

/// The full scene (about 8 minutes on 2 cores); q_c is written to
/// `OUT/pile_penetration/qc.csv` and plotted to `qc.png`.
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let (plateau, mut checks, figure) = measure(ctx, "pile_penetration", "mpdem, half model")?;
    checks.insert(
        1,
        Check::judged(
            "mean q_c = f_c / R over z/R ≥ 6 (f_c on the half model's cone)",
            format!("{:.2} MPa", plateau / 1e6),
            "4–6 MPa (Susila and Hryciw: about 5 MPa)",
            (PLATEAU.0..=PLATEAU.1).contains(&plateau),
        )
        .because("the plateau the paper compares with, Susila and Hryciw's about 5 MPa"),
    );
    checks.push(Check::reported(
        "the same over z/R ≥ 6 read as the whole cone's 2 f_c / R",
        format!("{:.2} MPa", 2.0 * plateau / 1e6),
        "4–6 MPa, if the paper's f_c is the whole cone's",
    ));
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}

/// The same pile as a body of revolution (`pile_penetration_axisymmetric`,
/// about 4.5 minutes on 2 cores), the geometry of Susila and Hryciw's finite
/// elements: q_c = 2 f_c / R² is compared with their plateau, reported (the
/// judged target is the paper's plane-strain scene's).
pub fn run_axisymmetric(ctx: &Context) -> Result<Measured, VerifyError> {
    let name = "pile_penetration_axisymmetric";
    let (plateau, mut checks, figure) = measure(ctx, name, "mpdem, axisymmetric")?;
    checks.insert(
        1,
        Check::reported(
            "mean q_c = 2 f_c / R² over z/R ≥ 6 (the cone's whole force over its area)",
            format!("{:.2} MPa", plateau / 1e6),
            "4–6 MPa (Susila and Hryciw's axisymmetric finite elements: about 5 MPa)",
        ),
    );
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}

/// Runs the scene `NAME.ron`, writes its q_c curve to `OUT/NAME/qc.csv`
/// and `qc.png` (the measured line named `label`), checks its stages and
/// reports its profile; returns its mean q_c over z/R ≥ 6 with the checks
/// and the figure of q_c against the published plateau.
fn measure(
    ctx: &Context,
    name: &str,
    label: &str,
) -> Result<(Real, Vec<Check>, Figure), VerifyError> {
    let scene = ctx.scene(&format!("{name}.ron"))?;
    let sim = ctx.run(name, &scene)?;
    let curve = cone_resistance(&sim, RADIUS)?;
    let dir = ctx.out_dir(name)?;
    write_curve(&dir.join("qc.csv"), &curve).map_err(|source| VerifyError::Io {
        path: dir.join("qc.csv"),
        source,
    })?;
    plot(&dir.join("qc.png"), &curve, label)?;

    let reasons: Vec<StageEndReason> = sim
        .world()
        .resource::<StageLog>()
        .records
        .iter()
        .map(|r| r.reason)
        .collect();
    let depth = curve.last().map_or(0.0, |c| c.1);
    let planned = [
        StageEndReason::Condition,
        StageEndReason::Condition,
        StageEndReason::Duration,
    ];
    let mut checks = vec![Check::judged(
        "stages: geostatic and surcharge settle, the pile is driven to 9R",
        format!(
            "{}; z/R = {depth:.2} at the end",
            reasons
                .iter()
                .map(|r| r.label())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        "condition, condition, duration; z/R ≥ 8.9",
        reasons == planned && depth >= 8.9,
    )];
    let profile: Vec<String> = (1..=8)
        .map(|z| {
            let z = Real::from(z);
            mean_between(&curve, z - 0.25, z + 0.25)
                .map_or_else(|| "–".into(), |q| format!("{:.2}", q / 1e6))
        })
        .collect();
    checks.push(Check::reported(
        "q_c (MPa) at z/R = 1, 2, …, 8 (mean over ±0.25)",
        profile.join(" / "),
        "a plateau of about 5 MPa from z/R ≈ 3 (paper Fig. 16)",
    ));
    let plateau = mean_between(&curve, 6.0, Real::INFINITY).unwrap_or(Real::NAN);
    Ok((plateau, checks, figure(&curve, label)))
}

/// q_c (MPa) against z / R, named `label`, beside the published plateau's
/// bounds.
fn figure(curve: &[(Real, Real, Real)], label: &str) -> Figure {
    let end = curve.last().map_or(9.0, |c| c.1);
    let (low, high) = (PLATEAU.0 / 1e6, PLATEAU.1 / 1e6);
    Figure::new(
        "Cone resistance against depth, pile penetration",
        "depth of the tip z / R",
        "cone resistance q_c (MPa)",
    )
    .with(Curve::computed(
        label,
        curve.iter().map(|&(_, z, q)| (z, q / 1e6)).collect(),
    ))
    .with(Curve::reference(
        "published plateau, 4–6 MPa (Susila and Hryciw)",
        vec![
            (0.0, low),
            (end, low),
            (Real::NAN, Real::NAN),
            (0.0, high),
            (end, high),
        ],
    ))
}

/// q_c against z / R with the published band.
fn plot(path: &Path, curve: &[(Real, Real, Real)], label: &str) -> Result<(), VerifyError> {
    let measured: Vec<(Real, Real)> = curve.iter().map(|&(_, z, q)| (z, q)).collect();
    let end = measured.last().map_or(9.0, |p| p.0);
    let low = [(0.0, PLATEAU.0), (end, PLATEAU.0)];
    let high = [(0.0, PLATEAU.1), (end, PLATEAU.1)];
    plot_series(
        path,
        "Cone resistance, pile penetration",
        "z / R",
        "q_c (Pa)",
        &[
            Series {
                name: label,
                points: &measured,
            },
            Series {
                name: "published plateau, 4 and 6 MPa",
                points: &low,
            },
            Series {
                name: "",
                points: &high,
            },
        ],
    )
    .map_err(|source| VerifyError::Io {
        path: path.to_path_buf(),
        source,
    })
}
