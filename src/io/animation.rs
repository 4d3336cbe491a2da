//! `animation.gif`: the run's frames as an animated GIF, the points
//! coloured by a chosen field, kept in memory while the run goes (at most
//! [`MAX_POINTS`] points per frame and [`MAX_FRAMES`] frames, thinned
//! evenly) and written at the end with one colour scale.

use super::plot::{AnimationFrame, write_animation};
use crate::math::{DVec2, Real};
use crate::scene::AnimatedField;

/// Most points an animation frame keeps: a GIF frame a thousand pixels
/// wide shows no more.
pub(crate) const MAX_POINTS: usize = 20_000;

/// Most frames an animation keeps: twenty seconds at ten frames a second.
pub(crate) const MAX_FRAMES: usize = 200;

/// Time between the GIF's frames (ms).
const DELAY_MS: u32 = 100;

/// The frames of an animation, recorded as the run writes its VTK frames.
pub(crate) struct Animation {
    field: AnimatedField,
    /// Every how many VTK frames one is kept.
    every: usize,
    /// VTK frames seen so far.
    seen: usize,
    frames: Vec<AnimationFrame>,
    /// The time of the last frame kept.
    last_time: Option<Real>,
}

/// One VTK frame's columns, all bodies concatenated.
pub(crate) struct FrameColumns<'a> {
    /// The run's name.
    pub name: &'a str,
    /// The frame's time (s).
    pub time: Real,
    /// The points' positions (m).
    pub positions: &'a [DVec2],
    /// Their velocities (m/s).
    pub velocities: &'a [DVec2],
    /// Their displacements (m).
    pub displacements: &'a [DVec2],
    /// Their stresses, [xx, yy, xy, zz] (Pa).
    pub stresses: &'a [[Real; 4]],
    /// Their bodies' indices.
    pub body: &'a [u32],
    /// The blocks' outlines.
    pub outlines: &'a [Vec<DVec2>],
}

impl Animation {
    /// An animation of `field` over a run that writes about `frames` VTK
    /// frames.
    pub(crate) fn new(field: AnimatedField, frames: u64) -> Self {
        Self {
            field,
            every: (frames as usize).div_ceil(MAX_FRAMES).max(1),
            seen: 0,
            frames: Vec::new(),
            last_time: None,
        }
    }

    /// Keeps the frame if it is one of every `every`.
    pub(crate) fn record(&mut self, columns: &FrameColumns) {
        let due = self.seen.is_multiple_of(self.every);
        self.seen += 1;
        if due {
            self.keep(columns);
        }
    }

    /// Keeps the run's last frame, unless it is kept already.
    pub(crate) fn record_last(&mut self, columns: &FrameColumns) {
        if self.last_time != Some(columns.time) {
            self.keep(columns);
        }
    }

    fn keep(&mut self, columns: &FrameColumns) {
        self.last_time = Some(columns.time);
        let stride = columns.positions.len().div_ceil(MAX_POINTS).max(1);
        let kept = (0..columns.positions.len()).step_by(stride);
        let value = |p: usize| match self.field {
            AnimatedField::Displacement => columns.displacements[p].length(),
            AnimatedField::Velocity => columns.velocities[p].length(),
            AnimatedField::MeanStress => {
                let [xx, yy, _, zz] = columns.stresses[p];
                (xx + yy + zz) / 3.0
            }
            AnimatedField::Body => Real::from(columns.body[p]),
        };
        self.frames.push(AnimationFrame {
            title: format!("{} at t = {:.4e} s", columns.name, columns.time),
            positions: kept.clone().map(|p| columns.positions[p]).collect(),
            values: kept.map(value).collect(),
            outlines: columns.outlines.to_vec(),
        });
    }

    /// Writes the GIF at `path` over `view`, markers `marker_size` wide.
    pub(crate) fn write(
        &self,
        path: &std::path::Path,
        marker_size: Real,
        view: (DVec2, DVec2),
    ) -> std::io::Result<()> {
        write_animation(
            path,
            &self.frames,
            self.field.label(),
            marker_size,
            view,
            DELAY_MS,
        )
    }
}
