//! Warnings about durations the run cannot give exactly: a `time.end`, a
//! stage `Duration` or an output interval that is not a whole number of
//! time steps.

use super::{Scene, StageEnd};
use crate::math::Real;
use crate::resources::Clock;
use crate::warning::{Warning, WarningKind};

/// How far, in steps, a duration (`time.end`, a stage's, an output
/// interval) may be from the whole number of steps the run gives it before
/// a warning says so: a millionth of a step, far above the round-off of a
/// duration meant as a multiple of Δt (about 1e-16 of the step count), far
/// below the half step of a tie, whatever the duration's length.
const OFF_STEP_TOLERANCE: Real = 1e-6;

/// Whether `duration` is off the whole number `steps` of steps of `dt`.
fn off_step(duration: Real, dt: Real, steps: u64) -> bool {
    (duration / dt - steps as Real).abs() > OFF_STEP_TOLERANCE
}

/// A number of steps as a person reads it: whole up to a billion, in
/// scientific notation beyond (a stage of 1.8e19 steps, not twenty digits).
fn step_count(steps: u64) -> String {
    if steps < 1_000_000_000 {
        steps.to_string()
    } else {
        format!("{:.3e}", steps as Real)
    }
}

/// `steps` × Δt rounded to 12 significant digits, so that a message says
/// 3e-4 s and not 3.0000000000000003e-4 s.
fn steps_time(steps: u64, dt: Real) -> Real {
    let time = steps as Real * dt;
    format!("{time:.11e}").parse().unwrap_or(time)
}

/// A warning for a `time.end`, for each stage `Duration` and for each
/// output interval the scene gives (shorter than the run), more than
/// [`OFF_STEP_TOLERANCE`] of a step away from the steps the run takes for
/// it, with those steps.
pub fn off_step_warnings(scene: &Scene, clock: &Clock) -> Vec<Warning> {
    let mut warnings = Vec::new();
    let steps = clock.total_steps();
    if off_step(clock.end, clock.dt, steps) {
        warnings.push(Warning::new(WarningKind::OffStep, "time.end", format!(
            "time.end = {:e} s is not a multiple of time.dt = {:e} s: the run takes the nearest whole number of steps, {steps}, to t = {:e} s",
            clock.end,
            clock.dt,
            steps_time(steps, clock.dt)
        )));
    }
    for stage in &scene.stages {
        if let StageEnd::Duration(d) = stage.end {
            let ratio = d / clock.dt;
            let stage_steps = stage.end.most_steps(clock.dt);
            if off_step(d, clock.dt, stage_steps) {
                // At a half-step tie the elapsed time's round-off decides.
                let tie = ratio > 0.5 && (ratio.fract() - 0.5).abs() < 1e-6;
                let takes = if tie {
                    format!(
                        "{stage_steps} or {} steps (a half-step tie)",
                        stage_steps + 1
                    )
                } else {
                    format!(
                        "{} step(s), {:e} s",
                        step_count(stage_steps),
                        steps_time(stage_steps, clock.dt)
                    )
                };
                warnings.push(Warning::new(WarningKind::OffStep, format!("stages[\"{}\"].end", stage.name), format!(
                    "stage '{}': Duration({d:e}) is not a multiple of time.dt = {:e} s: the stage takes {takes}",
                    stage.name, clock.dt
                )));
            }
        }
    }
    // Stages that all run a fixed number of steps: time.end cutting them
    // is certain.
    if scene
        .stages
        .iter()
        .all(|s| matches!(s.end, StageEnd::Duration(_)))
    {
        let all = scene
            .stages
            .iter()
            .fold(0, |n: u64, s| n.saturating_add(s.end.most_steps(clock.dt)));
        let mut start: u64 = 0;
        for stage in &scene.stages {
            let end = start.saturating_add(stage.end.most_steps(clock.dt));
            if end > steps {
                warnings.push(Warning::new(WarningKind::OffStep, "time.end", format!(
                    "time.end = {:e} s cuts stage '{}' ({:e} s to {:e} s) short; the stages take {:e} s in all",
                    clock.end,
                    stage.name,
                    steps_time(start, clock.dt),
                    steps_time(end, clock.dt),
                    steps_time(all, clock.dt)
                )));
                break;
            }
            start = end;
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
        // An interval as long as the run never comes: the first and last
        // states are written all the same.
        let Some(interval) = interval.filter(|i| *i < clock.end) else {
            continue;
        };
        let every = super::whole_steps(interval, clock.dt);
        if off_step(interval, clock.dt, every) {
            warnings.push(Warning::new(WarningKind::OffStep, format!("output.{field}"), format!(
                "output.{field} = {interval:e} s is not a multiple of time.dt = {:e} s: {what} every {every} step(s), {:e} s",
                clock.dt,
                steps_time(every, clock.dt)
            )));
        }
    }
    warnings
}
