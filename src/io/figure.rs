//! Figures a record draws at the end of a run: line charts declared as
//! data by the record's plugin ([`crate::plugins::PluginSetup::plot`]) and
//! drawn into the output folder by the outputs.

use crate::math::Real;
use crate::scene::Scene;
use bevy_ecs::prelude::{Resource, World};

/// A line chart: its file in the output folder (a `.png` name), its title,
/// axis labels and curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The PNG file's name in the output folder.
    pub file: String,
    /// The title above the chart.
    pub title: String,
    /// The horizontal axis's label.
    pub x_label: String,
    /// The vertical axis's label.
    pub y_label: String,
    /// The curves, each in the legend under its name.
    pub curves: Vec<Curve>,
}

/// One curve of a [`Figure`].
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Legend entry; an empty name leaves the curve out of the legend.
    pub name: String,
    /// Samples in drawing order; non-finite ones are skipped.
    pub points: Vec<(Real, Real)>,
}

impl Curve {
    /// The curve `name` through `points`.
    pub fn new(name: impl Into<String>, points: impl IntoIterator<Item = (Real, Real)>) -> Self {
        Self {
            name: name.into(),
            points: points.into_iter().collect(),
        }
    }
}

/// What a record's figures may need of the run besides the record.
pub struct FigureContext<'a> {
    /// The scene run.
    pub scene: &'a Scene,
    /// The bodies' names in scene order.
    pub bodies: &'a [String],
    /// What extensive quantities are per: `m` (plane strain, per metre of
    /// depth) or `rad` (axisymmetry, per radian).
    pub per: &'a str,
}

/// What gives a record's figures from a world.
type DrawFigures = dyn Fn(&World, &FigureContext) -> Vec<Figure> + Send + Sync;

/// The figures of one record, drawn if its resource is in the world.
pub(crate) struct FigureRecord {
    figures: Box<DrawFigures>,
}

impl FigureRecord {
    /// The figures `draw` makes of the resource `R`.
    pub fn of<R: Resource>(draw: fn(&R, &FigureContext) -> Vec<Figure>) -> Self {
        Self {
            figures: Box::new(move |world, context| {
                world
                    .get_resource::<R>()
                    .map_or_else(Vec::new, |record| draw(record, context))
            }),
        }
    }

    /// The figures of the record in `world`.
    pub fn figures(&self, world: &World, context: &FigureContext) -> Vec<Figure> {
        (self.figures)(world, context)
    }
}
