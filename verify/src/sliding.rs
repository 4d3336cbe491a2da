//! Paper section 4.2.2: an elastic block sliding down a 45° slope with
//! friction μ = 0.5, against the kinematics of a rigid block.

use super::{
    Check, Context, Curve, Figure, Measured, VerifyError, body, centre_of_mass, mass_weighted_mean,
    percent,
};
use mpdem::components::MaterialPoints;
use mpdem::math::{DVec2, Real};

/// Motion of a body's centre of mass: (displacement, velocity).
pub fn centre_of_mass_motion(points: &MaterialPoints) -> (DVec2, DVec2) {
    let (centre, velocity) = centre_of_mass(points);
    (
        centre - mass_weighted_mean(points, &points.initial_position),
        velocity,
    )
}

/// Steps between two samples of the travel s(t) for the figure.
const SAMPLE_EVERY: u64 = 100;

/// The scene to its end (2 s), with the travel s(t) of the block's centre
/// of mass beside the rigid block's.
pub fn run(ctx: &Context) -> Result<Measured, VerifyError> {
    let scene = ctx.scene("sliding_45.ron")?;
    let run = "sliding_45";
    let mut sim = ctx.start(run, &scene)?;
    let mut travel = Vec::new();
    ctx.advance(run, &mut sim, |sim| {
        let time = sim.clock().time;
        if sim.clock().step.is_multiple_of(SAMPLE_EVERY)
            && let Some(points) = sim.points_of("block")
        {
            travel.push((time, centre_of_mass_motion(points).0.x));
        }
        false
    })?;
    let g: Real = 9.81;
    let theta = std::f64::consts::FRAC_PI_4;
    let a = g * (theta.sin() - 0.5 * theta.cos());
    let t = scene.time.end;
    // The reference is the motion of a rigid block, so the block's centre
    // of mass is compared: a single point's velocity also carries the
    // elastic block's vibration (±1 m/s at the centre point, measured).
    let (u, v) = centre_of_mass_motion(body(&mut sim, "block")?);
    travel.push((sim.clock().time, u.x));
    let rigid = travel.iter().map(|&(t, _)| (t, 0.5 * a * t * t)).collect();
    let figure = Figure::new(
        "Elastic block sliding down a 45° slope, μ = 0.5",
        "time t (s)",
        "travel s of the centre of mass (m)",
    )
    .with(Curve::computed("mpdem", travel))
    .with(Curve::reference("rigid block, s = ½ a t²", rigid));
    let (s_exact, v_exact) = (0.5 * a * t * t, a * t);
    let (s_error, v_error) = (u.x / s_exact - 1.0, v.x / v_exact - 1.0);
    // The targets: 2% on both (no over-damping).
    let checks = vec![
        Check::judged(
            format!("centre of mass travel at {t} s against ½ a t² = {s_exact:.4} m"),
            format!("{:.4} m ({})", u.x, percent(s_error, 2)),
            "within 2%",
            s_error.abs() <= 0.02,
        ),
        Check::judged(
            format!("centre of mass velocity at {t} s against a t = {v_exact:.4} m/s"),
            format!("{:.4} m/s ({})", v.x, percent(v_error, 2)),
            "within 2%",
            v_error.abs() <= 0.02,
        ),
    ];
    Ok(Measured {
        checks,
        figures: vec![figure],
    })
}
