//! A granular collapse run to its end and its deposit measured with the
//! engine's own record of it (`output.fronts`): the toes at 2% and 5% of
//! H0, the farthest point, the spray and the surface.

use super::{Context, VerifyError, largest};
use mpdem::math::Real;
use mpdem::plugins::{DepositLog, FrontLog};
use mpdem::resources::EnergyLog;
use mpdem::scene::Scene;

/// What one run of a collapse measured (lengths in m).
pub struct DepositRun {
    /// The run's label in the checks and figures.
    pub label: String,
    /// L0 and H0: the column's initial length (its point domains' largest
    /// x) and height.
    pub start: (Real, Real),
    /// The final toes where the deposit thins below 2% and 5% of H0.
    pub toes: [Real; 2],
    /// The final farthest point's centre.
    pub farthest: Real,
    /// The final share of the mass beyond the toe at 2%.
    pub spray: Real,
    /// The final surface's highest point above the initial base.
    pub top: Real,
    /// Kinetic energy at the end over its peak.
    pub resting: Real,
    /// Peak kinetic energy (J/m).
    pub peak_kinetic: Real,
    /// (t, ΔL/L0 at the toe at 2%) over the run.
    pub history: Vec<(Real, Real)>,
    /// The final surface: (x, height) per grid column it covers.
    pub surface: Vec<(Real, Real)>,
}

impl DepositRun {
    /// Runs `scene`, whose first body is the column, to its end as the run
    /// `run`, with its fronts recorded.
    pub fn measure(
        ctx: &Context,
        run: &str,
        label: impl Into<String>,
        scene: &Scene,
    ) -> Result<Self, VerifyError> {
        let mut scene = scene.clone();
        scene.output.fronts = true;
        let sim = ctx.run(run, &scene)?;
        let world = sim.world();
        let missing = |what: &str| VerifyError::Measurement(format!("{run}: no {what} recorded"));
        let fronts: Vec<_> = world
            .resource::<FrontLog>()
            .samples
            .iter()
            .filter(|s| s.body == 0)
            .copied()
            .collect();
        let (first, last) = match (fronts.first(), fronts.last()) {
            (Some(first), Some(last)) => (*first, *last),
            _ => return Err(missing("front")),
        };
        let columns = &world.resource::<DepositLog>().columns;
        let of_body = |time: Real| {
            columns
                .iter()
                .filter(move |c| c.body == 0 && c.time == time)
                .map(|c| (c.x, c.height))
        };
        let height0 = largest(of_body(0.0).map(|c| c.1));
        let surface: Vec<_> = of_body(last.time).collect();
        // The toes start at the initial front: the column's right edge.
        let length0 = first.toe_2;
        let energy = &world.resource::<EnergyLog>().samples;
        let peak = largest(energy.iter().map(|s| s.kinetic));
        let resting = energy.last().map_or(Real::NAN, |s| s.kinetic) / peak;
        Ok(Self {
            label: label.into(),
            start: (length0, height0),
            toes: [last.toe_2, last.toe_5],
            farthest: last.farthest,
            spray: last.spray,
            top: largest(surface.iter().map(|c| c.1)),
            resting,
            peak_kinetic: peak,
            history: fronts
                .iter()
                .map(|s| (s.time, (s.toe_2 - length0) / length0))
                .collect(),
            surface,
        })
    }

    /// ΔL/L0 at the toe at 2% of H0.
    pub fn toe_2(&self) -> Real {
        self.run_out(self.toes[0])
    }

    /// ΔL/L0 at the toe at 5% of H0.
    pub fn toe_5(&self) -> Real {
        self.run_out(self.toes[1])
    }

    /// ΔL/L0 at the farthest point.
    pub fn farthest(&self) -> Real {
        self.run_out(self.farthest)
    }

    /// H∞/H0.
    pub fn height(&self) -> Real {
        self.top / self.start.1
    }

    /// ΔL/L0 of a front at `x`.
    fn run_out(&self, x: Real) -> Real {
        (x - self.start.0) / self.start.0
    }

    /// The surface's height at `x`, linear between the columns' centres,
    /// the first column's before it and 0 past the last.
    pub fn height_at(&self, x: Real) -> Real {
        let after = self.surface.partition_point(|c| c.0 < x);
        match (
            after.checked_sub(1).map(|k| self.surface[k]),
            self.surface.get(after),
        ) {
            (None, Some(c)) => c.1,
            (Some(_), None) | (None, None) => 0.0,
            (Some(a), Some(b)) => a.1 + (x - a.0) / (b.0 - a.0) * (b.1 - a.1),
        }
    }
}
