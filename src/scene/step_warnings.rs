//! Warnings about durations the run cannot give exactly: a `time.end`, a
//! stage `Duration` or an output interval that is not a whole number of
//! time steps.

use super::{Scene, StageEnd};
use crate::math::Real;
use crate::resources::Clock;

/// How far, as a fraction of itself, a duration (`time.end`, a stage's)
/// may be from the whole number of steps the run gives it before a warning
/// says so: a thousandth, far above the round-off of a duration meant as a
/// multiple of Δt, far below one step of a duration a few steps long.
const OFF_STEP_WARNING: Real = 1e-3;

/// `steps` × Δt rounded to 12 significant digits, so that a message says
/// 3e-4 s and not 3.0000000000000003e-4 s.
fn steps_time(steps: u64, dt: Real) -> Real {
    let time = steps as Real * dt;
    format!("{time:.11e}").parse().unwrap_or(time)
}

/// A warning for a `time.end`, for each stage `Duration` and for each
/// output interval the scene gives, more than [`OFF_STEP_WARNING`] of
/// itself away from the steps the run takes for it, with those steps.
pub fn off_step_warnings(scene: &Scene, clock: &Clock) -> Vec<String> {
    let mut warnings = Vec::new();
    let steps = clock.total_steps();
    if (steps as Real * clock.dt - clock.end).abs() > OFF_STEP_WARNING * clock.end {
        warnings.push(format!(
            "time.end = {:e} s is not a multiple of time.dt = {:e} s: the run takes the nearest whole number of steps, {steps}, to t = {:e} s",
            clock.end,
            clock.dt,
            steps_time(steps, clock.dt)
        ));
    }
    for stage in &scene.stages {
        if let StageEnd::Duration(d) = stage.end {
            // The stage ends on the first step with elapsed ≥ d − Δt/2.
            let ratio = d / clock.dt;
            let stage_steps = (ratio - 0.5 - 1e-9).ceil().max(1.0) as u64;
            if (stage_steps as Real * clock.dt - d).abs() > OFF_STEP_WARNING * d {
                // At a half-step tie the elapsed time's round-off decides.
                let tie = ratio > 0.5 && (ratio.fract() - 0.5).abs() < 1e-6;
                let takes = if tie {
                    format!(
                        "{stage_steps} or {} steps (a half-step tie)",
                        stage_steps + 1
                    )
                } else {
                    format!(
                        "{stage_steps} step(s), {:e} s",
                        steps_time(stage_steps, clock.dt)
                    )
                };
                warnings.push(format!(
                    "stage '{}': Duration({d:e}) is not a multiple of time.dt = {:e} s: the stage takes {takes}",
                    stage.name, clock.dt
                ));
            }
        }
    }
    // Intervals the scene gives; the defaults (a fraction of the end) are
    // rounded as documented.
    let intervals = [
        (
            "frame_interval",
            scene.output.frame_interval,
            "frames are written",
        ),
        (
            "probe_interval",
            scene.output.probe_interval,
            "probes and energy are sampled",
        ),
    ];
    for (field, interval, what) in intervals {
        let Some(interval) = interval else {
            continue;
        };
        let every = super::whole_steps(interval, clock.dt);
        if (every as Real * clock.dt - interval).abs() > OFF_STEP_WARNING * interval {
            warnings.push(format!(
                "output.{field} = {interval:e} s is not a multiple of time.dt = {:e} s: {what} every {every} step(s), {:e} s",
                clock.dt,
                steps_time(every, clock.dt)
            ));
        }
    }
    warnings
}
