//! The time step and the run's length.

use super::Locator;
use crate::math::Real;
use crate::rules;
use crate::scene::{MAX_SAMPLES, MAX_STEPS, Scene, SceneError, whole_steps};

impl Scene {
    /// The time step and end, and the steps and samples they make.
    pub(super) fn check_time(&self, v: &Locator) -> Result<(), SceneError> {
        rules::positive(self.time.dt).map_err(|e| v.field(&["time", "dt"], e))?;
        rules::positive(self.time.end).map_err(|e| v.field(&["time", "end"], e))?;
        if self.time.dt > self.time.end {
            return Err(v.invalid(
                &["time", "dt"],
                format!(
                    "time.dt ({}) is longer than time.end ({})",
                    self.time.dt, self.time.end
                ),
            ));
        }
        let cap = self.time.max_steps.unwrap_or(MAX_STEPS);
        let steps = self.time.end / self.time.dt;
        if steps > cap as Real {
            return Err(v.invalid(
                &["time", "dt"],
                format!(
                    "time: end / dt = {:e} / {:e} gives {steps:.3e} steps, more than the cap of {cap} (time.max_steps; default {MAX_STEPS}): check dt and end, or name a larger time.max_steps",
                    self.time.end, self.time.dt
                ),
            ));
        }
        // The rows the records keep, as the spawn reserves them: a row per
        // sample for the energies, and one per probe, block, compound part
        // and pair of bodies under a law.
        let samples = (steps.round()
            / whole_steps(
                self.output.probe_interval_or_default(self.time.end),
                self.time.dt,
            ) as Real)
            + 2.0;
        let parts: usize = self
            .blocks
            .iter()
            .map(|b| match &b.shape {
                crate::rigid::BlockShape::Compound { parts } => parts.len(),
                _ => 0,
            })
            .sum();
        let members = |name: &str| self.contact_members(name).map_or(0, |m| m.len());
        let pairs: usize = self
            .body_contacts
            .iter()
            .map(|c| members(&c.between.0) * members(&c.between.1))
            .sum();
        let series = 1 + self.probes.len() + self.blocks.len() + parts + pairs;
        let rows = samples * series as Real;
        if rows > MAX_SAMPLES as Real {
            return Err(v.field(&["output", "probe_interval"], format!("{:e} s over time.end = {} s gives {samples:.3e} samples of {series} records (energies, probes, blocks and their parts, body pairs), {rows:.3e} rows, more than the {MAX_SAMPLES} a run keeps in memory: sample less often",
                    self.output.probe_interval_or_default(self.time.end),
                    self.time.end
                ),
            ));
        }
        Ok(())
    }
}
