//! PNG plots with `plotters`: line charts of time series and of curves against their references,
//! and coloured snapshots of material points.
//!
//! Text is rendered with the DejaVu Sans font embedded by the `dejavu` crate (registered once with
//! plotters' `ab_glyph` text backend), so plots look the same on every machine and need no system
//! fonts. Every function writes a PNG file and requires the path to end in `.png`.

use crate::math::{DVec2, Real};
use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Font family name the embedded DejaVu Sans is registered under.
const FONT: &str = "sans-serif";
/// Width of the snapshot image in pixels.
const SNAPSHOT_WIDTH: u32 = 1000;
/// Height of the snapshot's title band in pixels.
const TITLE_HEIGHT: u32 = 50;
/// Width of the snapshot's colour bar band in pixels.
const COLORBAR_WIDTH: u32 = 150;
/// Margin around the snapshot chart in pixels.
const CHART_MARGIN: u32 = 10;
/// Height of the snapshot's x axis label area in pixels.
const X_LABEL_AREA: u32 = 50;
/// Width of the snapshot's y axis label area in pixels.
const Y_LABEL_AREA: u32 = 80;

/// Viridis colour map sampled at 9 evenly spaced points from 0 to 1.
const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 81, 139),
    (44, 113, 142),
    (33, 144, 141),
    (39, 173, 129),
    (92, 200, 99),
    (170, 220, 50),
    (253, 231, 37),
];

/// Colour of points whose value is not finite.
const NAN_COLOR: RGBColor = RGBColor(160, 160, 160);

/// Distinct series colours (Tableau 10, then black), reused cyclically.
const SERIES_COLORS: [RGBColor; 11] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 0),
];

/// One named curve of (x, y) samples.
pub struct Series<'a> {
    /// Legend entry; an empty name leaves the curve out of the legend.
    pub name: &'a str,
    /// Samples in drawing order; samples with a non-finite coordinate are skipped.
    pub points: &'a [(Real, Real)],
}

/// Line chart with title, axis labels, legend and automatic ranges (padded 5%, with a sensible
/// range for a constant series or a single point), 900x600 pixels, white background, distinct
/// colours per series.
///
/// Fails with `InvalidInput` if `path` does not end in `.png`, or with the error of rendering or
/// writing the image.
pub fn plot_series(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> std::io::Result<()> {
    check_png_path(path)?;
    register_font()?;
    let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
    draw_series_chart(&root, title, x_label, y_label, series)
        .and_then(|()| root.present())
        .map_err(std::io::Error::other)
}

/// One curve of [`plot_lines`].
pub struct Line<'a> {
    /// Legend entry, wrapped to the legend's width; an empty name leaves the curve out of the
    /// legend.
    pub name: &'a str,
    /// Samples in drawing order; a sample with a non-finite coordinate breaks the line.
    pub points: &'a [(Real, Real)],
    /// Index of its colour among the series colours of [`plot_series`] (Tableau 10, then black
    /// at 10), taken cyclically.
    pub color: usize,
    /// Dashed instead of solid.
    pub dashed: bool,
}

/// Line chart of `size` pixels (width, height) with solid and dashed curves of chosen colours:
/// title, axis labels, automatic ranges as [`plot_series`], and the legend in a column right of
/// the chart (three tenths of the width, names wrapped), where it covers no curve.
///
/// Fails with `InvalidInput` if `path` does not end in `.png`, or with the error of rendering or
/// writing the image.
pub fn plot_lines(
    path: &Path,
    size: (u32, u32),
    title: &str,
    x_label: &str,
    y_label: &str,
    lines: &[Line],
) -> std::io::Result<()> {
    check_png_path(path)?;
    register_font()?;
    let root = BitMapBackend::new(path, size).into_drawing_area();
    draw_lines_chart(&root, title, x_label, y_label, lines)
        .and_then(|()| root.present())
        .map_err(std::io::Error::other)
}

/// Draws the line chart of [`plot_lines`] on `root`.
fn draw_lines_chart<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    lines: &[Line],
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let (width, _) = root.dim_in_pixel();
    let legend_width = if lines.iter().any(|l| !l.name.is_empty()) {
        width * 3 / 10
    } else {
        0
    };
    let (plot_area, legend_area) = root.split_horizontally(width - legend_width);
    let samples = || {
        lines
            .iter()
            .flat_map(|l| l.points.iter().copied())
            .filter(|(x, y)| x.is_finite() && y.is_finite())
    };
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(title, (FONT, 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(
            padded_range(samples().map(|(x, _)| x)),
            padded_range(samples().map(|(_, y)| y)),
        )?;
    draw_axes(&mut chart, x_label, y_label, 14)?;

    // About 7 pixels a character at the legend's 14-pixel font.
    let columns = (legend_width.saturating_sub(50) / 7).max(10) as usize;
    let mut y = 60;
    for line in lines {
        let color = SERIES_COLORS[line.color % SERIES_COLORS.len()];
        let style = color.stroke_width(2);
        for piece in line
            .points
            .split(|(x, y)| !(x.is_finite() && y.is_finite()))
            .filter(|piece| !piece.is_empty())
        {
            let points = piece.iter().copied();
            if line.dashed {
                chart.draw_series(DashedLineSeries::new(points, 8, 5, style))?;
            } else {
                chart.draw_series(LineSeries::new(points, style))?;
            }
        }
        if line.name.is_empty() {
            continue;
        }
        let key = vec![(8, y), (36, y)];
        if line.dashed {
            legend_area.draw(&DashedPathElement::new(key, 8, 5, style))?;
        } else {
            legend_area.draw(&PathElement::new(key, style))?;
        }
        y = draw_legend_name(&legend_area, line.name, columns, y, 14)?;
    }
    Ok(())
}

/// `text` broken at spaces into lines of at most `columns` characters (a longer word gets a line
/// of its own).
fn wrap(text: &str, columns: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= columns => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Snapshot of material points coloured by `values` with a viridis colour map.
///
/// Each point is a filled square of side `marker_size` (model units, at least 1 pixel) centred at
/// its position. The chart has an equal aspect ratio and covers at least the `view` rectangle
/// (min, max corners in model units), widened along one axis to fill the plot area. A colour bar
/// on the right shows the value range with min/max labels and `value_label`; points with
/// non-finite values are grey, and if all finite values are equal they get the middle colour.
/// `outlines` are closed polylines drawn in black on top (may be empty). Points outside the chart
/// are left out; outlines are not clipped. The image is 1000 pixels wide, its height follows the
/// aspect ratio of `view` plus margins, clamped to [300, 2000] pixels.
///
/// Fails with `InvalidInput` if `path` does not end in `.png`, `positions` and `values` differ in
/// length or `view` is not a finite rectangle of positive size, or with the error of rendering or
/// writing the image.
#[allow(clippy::too_many_arguments)]
pub fn plot_points(
    path: &Path,
    title: &str,
    value_label: &str,
    positions: &[DVec2],
    values: &[Real],
    marker_size: Real,
    view: (DVec2, DVec2),
    outlines: &[Vec<DVec2>],
) -> std::io::Result<()> {
    check_png_path(path)?;
    if positions.len() != values.len() {
        return Err(invalid_input(format!(
            "{} positions but {} values",
            positions.len(),
            values.len()
        )));
    }
    let fitted = FittedView::new(view, marker_size)?;
    register_font()?;
    let snapshot = Snapshot {
        title,
        value_label,
        positions,
        values,
        value_range: finite_range(values.iter().copied()),
        marker_pixels: fitted.marker_pixels,
        x_range: fitted.x_range.clone(),
        y_range: fitted.y_range.clone(),
        outlines,
    };
    let root = BitMapBackend::new(path, (SNAPSHOT_WIDTH, fitted.height)).into_drawing_area();
    draw_snapshot(&root, &snapshot)
        .and_then(|()| root.present())
        .map_err(std::io::Error::other)
}

/// One frame of an animation: its title, and the points with their values
/// and the block outlines at that time.
pub struct AnimationFrame {
    /// The frame's title (the scene and the time).
    pub title: String,
    /// The points' positions (m).
    pub positions: Vec<DVec2>,
    /// Their values.
    pub values: Vec<Real>,
    /// The block outlines.
    pub outlines: Vec<Vec<DVec2>>,
}

/// Writes `frames` as an animated GIF at `path`, `delay_ms` between
/// frames, in the look of [`plot_points`], with one colour scale over all
/// frames so that colours compare across time.
pub fn write_animation(
    path: &Path,
    frames: &[AnimationFrame],
    value_label: &str,
    marker_size: Real,
    view: (DVec2, DVec2),
    delay_ms: u32,
) -> std::io::Result<()> {
    let fitted = FittedView::new(view, marker_size)?;
    register_font()?;
    let value_range = finite_range(frames.iter().flat_map(|f| f.values.iter().copied()));
    let root = BitMapBackend::gif(path, (SNAPSHOT_WIDTH, fitted.height), delay_ms)
        .map_err(std::io::Error::other)?
        .into_drawing_area();
    for frame in frames {
        let snapshot = Snapshot {
            title: &frame.title,
            value_label,
            positions: &frame.positions,
            values: &frame.values,
            value_range,
            marker_pixels: fitted.marker_pixels,
            x_range: fitted.x_range.clone(),
            y_range: fitted.y_range.clone(),
            outlines: &frame.outlines,
        };
        draw_snapshot(&root, &snapshot)
            .and_then(|()| root.present())
            .map_err(std::io::Error::other)?;
    }
    Ok(())
}

/// A view rectangle fitted to a snapshot's plot area: the image's height
/// (the plot area keeps the view's aspect ratio, the view widened along one
/// axis where the height is clamped) and the markers' size in pixels.
struct FittedView {
    height: u32,
    marker_pixels: i32,
    x_range: Range<Real>,
    y_range: Range<Real>,
}

impl FittedView {
    fn new((lo, hi): (DVec2, DVec2), marker_size: Real) -> std::io::Result<Self> {
        let size = hi - lo;
        if !(lo.is_finite() && hi.is_finite() && size.x > 0.0 && size.y > 0.0) {
            return Err(invalid_input(format!(
                "invalid view rectangle {lo} .. {hi}"
            )));
        }
        let chrome_width = COLORBAR_WIDTH + 2 * CHART_MARGIN + Y_LABEL_AREA;
        let chrome_height = TITLE_HEIGHT + 2 * CHART_MARGIN + X_LABEL_AREA;
        let plot_width = Real::from(SNAPSHOT_WIDTH - chrome_width);
        let height =
            (plot_width * size.y / size.x + Real::from(chrome_height)).clamp(300.0, 2000.0) as u32;
        let plot_height = Real::from(height - chrome_height);
        let pixels_per_unit = (plot_width / size.x).min(plot_height / size.y);
        let center = 0.5 * (lo + hi);
        let half = 0.5 * DVec2::new(plot_width, plot_height) / pixels_per_unit;
        Ok(Self {
            height,
            marker_pixels: (marker_size * pixels_per_unit).ceil().clamp(1.0, 2000.0) as i32,
            x_range: center.x - half.x..center.x + half.x,
            y_range: center.y - half.y..center.y + half.y,
        })
    }
}

/// Everything `draw_snapshot` needs, with the view already fitted to the plot area.
struct Snapshot<'a> {
    title: &'a str,
    value_label: &'a str,
    positions: &'a [DVec2],
    values: &'a [Real],
    /// The range the colour scale spans.
    value_range: Option<(Real, Real)>,
    marker_pixels: i32,
    x_range: Range<Real>,
    y_range: Range<Real>,
    outlines: &'a [Vec<DVec2>],
}

/// Result of drawing on a plotters drawing area of backend `DB`.
type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Draws a legend entry's `name` in the legend column `area`, wrapped to
/// `columns` characters, its first line beside the entry's key at height
/// `y`, in a `size`-pixel font; returns the height of the next entry's key.
fn draw_legend_name<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    name: &str,
    columns: usize,
    mut y: i32,
    size: u32,
) -> Result<i32, DrawingAreaErrorKind<DB::ErrorType>> {
    for text in wrap(name, columns) {
        area.draw(&Text::new(
            text,
            (42, y - 8),
            (FONT, size).into_font().color(&BLACK),
        ))?;
        y += size as i32 + 3;
    }
    Ok(y + size as i32 / 2)
}

/// Registers the embedded DejaVu Sans as the plotters font family [`FONT`], once per process.
fn register_font() -> std::io::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let registered = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular()).is_ok()
    });
    if registered {
        Ok(())
    } else {
        Err(std::io::Error::other(
            "cannot load the embedded DejaVu Sans font",
        ))
    }
}

/// Checks that `path` names a PNG file (the bitmap encoder picks the format from the extension).
fn check_png_path(path: &Path) -> std::io::Result<()> {
    match path.extension().and_then(|ext| ext.to_str()) {
        Some(ext) if ext.eq_ignore_ascii_case("png") => Ok(()),
        _ => Err(invalid_input(format!(
            "{} does not end in .png",
            path.display()
        ))),
    }
}

/// An `InvalidInput` I/O error with the given message.
fn invalid_input(message: String) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidInput, message)
}

/// Draws the line chart of [`plot_series`] on `root`.
fn draw_series_chart<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    // The legend gets a column of its own, right of the chart, so that it
    // never covers a curve: wide enough for the longest name, at most three
    // tenths of the image, and names longer than that wrapped.
    let (width, _) = root.dim_in_pixel();
    let longest = series.iter().map(|s| s.name.chars().count()).max();
    let legend_width = match longest {
        None | Some(0) => 0,
        Some(chars) => (LEGEND_KEY_WIDTH + LEGEND_CHAR_WIDTH * chars as u32)
            .clamp(LEGEND_WIDTH, width * 3 / 10),
    };
    let columns = (legend_width.saturating_sub(LEGEND_KEY_WIDTH) / LEGEND_CHAR_WIDTH) as usize;
    let (plot_area, legend_area) = root.split_horizontally(width - legend_width);
    let samples = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|(x, y)| x.is_finite() && y.is_finite())
    };
    let x_range = padded_range(samples().map(|(x, _)| x));
    let y_range = padded_range(samples().map(|(_, y)| y));
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(title, (FONT, 26))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(x_range, y_range)?;
    draw_axes(&mut chart, x_label, y_label, 15)?;

    let mut y = 70;
    for (index, s) in series.iter().enumerate() {
        let color = SERIES_COLORS[index % SERIES_COLORS.len()];
        let points = s
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite());
        chart.draw_series(LineSeries::new(points, color.stroke_width(2)))?;
        if !s.name.is_empty() {
            legend_area.draw(&PathElement::new(
                vec![(10, y), (34, y)],
                color.stroke_width(2),
            ))?;
            y = draw_legend_name(&legend_area, s.name, columns.max(10), y, 15)?;
        }
    }
    Ok(())
}

/// Narrowest legend column right of a line chart (pixels).
const LEGEND_WIDTH: u32 = 150;

/// Room for a legend entry's key before its name (pixels).
const LEGEND_KEY_WIDTH: u32 = 50;

/// About the width of a character of the legend's 15-pixel font (pixels).
const LEGEND_CHAR_WIDTH: u32 = 8;

/// Draws the snapshot of [`plot_points`] on `root`: title band, chart and colour bar.
fn draw_snapshot<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    snapshot: &Snapshot,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let (title_area, body) = root.split_vertically(TITLE_HEIGHT);
    let (width, _) = title_area.dim_in_pixel();
    title_area.draw_text(
        snapshot.title,
        &TextStyle::from((FONT, 24)).pos(Pos::new(HPos::Center, VPos::Center)),
        (width as i32 / 2, TITLE_HEIGHT as i32 / 2),
    )?;
    let (chart_area, colorbar_area) = body.split_horizontally(SNAPSHOT_WIDTH - COLORBAR_WIDTH);

    let mut chart = ChartBuilder::on(&chart_area)
        .margin(CHART_MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(snapshot.x_range.clone(), snapshot.y_range.clone())?;
    let x_span = snapshot.x_range.end - snapshot.x_range.start;
    let y_span = snapshot.y_range.end - snapshot.y_range.start;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x (m)")
        .y_desc("y (m)")
        .x_label_formatter(&|v| tick_label(*v, x_span))
        .y_label_formatter(&|v| tick_label(*v, y_span))
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .draw()?;

    let value_range = snapshot.value_range;
    let (side, x_range, y_range) = (snapshot.marker_pixels, &snapshot.x_range, &snapshot.y_range);
    chart.draw_series(
        snapshot
            .positions
            .iter()
            .zip(snapshot.values)
            .filter(|(p, _)| {
                (x_range.start..=x_range.end).contains(&p.x)
                    && (y_range.start..=y_range.end).contains(&p.y)
            })
            .map(|(p, &value)| {
                let color = if value.is_finite() {
                    viridis(value_range.map_or(0.5, |range| normalize(value, range)))
                } else {
                    NAN_COLOR
                };
                EmptyElement::at((p.x, p.y))
                    + Rectangle::new(
                        [(-side / 2, -side / 2), (side - side / 2, side - side / 2)],
                        color.filled(),
                    )
            }),
    )?;
    chart.draw_series(
        snapshot
            .outlines
            .iter()
            .filter(|outline| outline.len() > 1)
            .map(|outline| {
                let closed = outline.iter().chain(outline.first()).map(|p| (p.x, p.y));
                PathElement::new(closed.collect::<Vec<_>>(), BLACK.stroke_width(2))
            }),
    )?;

    draw_colorbar(&colorbar_area, snapshot.value_label, value_range)
}

/// Draws a vertical viridis colour bar with max/min labels and the rotated `label` beside it,
/// spanning the height of the snapshot's plot area.
fn draw_colorbar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    range: Option<(Real, Real)>,
) -> DrawResult<DB> {
    let (_, height) = area.dim_in_pixel();
    let (top, bottom) = (
        CHART_MARGIN as i32,
        (height - CHART_MARGIN - X_LABEL_AREA) as i32,
    );
    let (left, right) = (10, 40);
    for y in top..bottom {
        let t = Real::from(bottom - 1 - y) / Real::from((bottom - top - 1).max(1));
        area.draw(&Rectangle::new(
            [(left, y), (right, y + 1)],
            viridis(t).filled(),
        ))?;
    }
    area.draw(&Rectangle::new([(left, top), (right, bottom)], BLACK))?;

    let (min_text, max_text) = match range {
        Some((min, max)) => (format_value(min), format_value(max)),
        None => ("n/a".to_string(), "n/a".to_string()),
    };
    let style = |v_pos| TextStyle::from((FONT, 15)).pos(Pos::new(HPos::Left, v_pos));
    area.draw_text(&max_text, &style(VPos::Top), (right + 6, top))?;
    area.draw_text(&min_text, &style(VPos::Bottom), (right + 6, bottom))?;
    area.draw_text(
        label,
        &TextStyle::from((FONT, 17).into_font().transform(FontTransform::Rotate270))
            .pos(Pos::new(HPos::Center, VPos::Center)),
        (COLORBAR_WIDTH as i32 - 20, (top + bottom) / 2),
    )
}

/// Range of the finite samples padded by 5% on each side; a constant sample gets a range around
/// its value and no finite sample gives 0..1.
fn padded_range(samples: impl Iterator<Item = Real>) -> Range<Real> {
    let Some((lo, hi)) = finite_range(samples) else {
        return 0.0..1.0;
    };
    let magnitude = lo.abs().max(hi.abs());
    let pad = if hi - lo > 1e-12 * magnitude {
        0.05 * (hi - lo)
    } else if magnitude > 0.0 {
        0.05 * magnitude
    } else {
        1.0
    };
    lo - pad..hi + pad
}

/// Minimum and maximum of the finite samples, `None` if there is none.
fn finite_range(samples: impl Iterator<Item = Real>) -> Option<(Real, Real)> {
    samples
        .filter(|v| v.is_finite())
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Position of `value` in `(min, max)` as a fraction in [0, 1]; 0.5 for an empty range.
fn normalize(value: Real, (min, max): (Real, Real)) -> Real {
    if max > min {
        ((value - min) / (max - min)).clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// Viridis colour at `t` in [0, 1] (clamped), linearly interpolated between the table entries.
fn viridis(t: Real) -> RGBColor {
    let scaled = t.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as Real;
    let index = (scaled.floor() as usize).min(VIRIDIS.len() - 2);
    let frac = scaled - index as Real;
    let (a, b) = (VIRIDIS[index], VIRIDIS[index + 1]);
    let mix = |a: u8, b: u8| (Real::from(a) + frac * (Real::from(b) - Real::from(a))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Compact label for a colour bar value: plain decimals for moderate magnitudes, otherwise
/// scientific notation, with up to 4 significant digits and no trailing zeros.
fn format_value(value: Real) -> String {
    let magnitude = value.abs();
    if value == 0.0 {
        "0".to_string()
    } else if (1e-2..1e4).contains(&magnitude) {
        let digits = (3 - magnitude.log10().floor() as i32).max(0) as usize;
        trim_fraction_zeros(&format!("{value:.digits$}")).to_string()
    } else {
        let text = format!("{value:.3e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        format!("{}e{exponent}", trim_fraction_zeros(mantissa))
    }
}

/// Removes trailing zeros (and a then trailing point) from a decimal number with a fraction.
fn trim_fraction_zeros(number: &str) -> &str {
    if number.contains('.') {
        number.trim_end_matches('0').trim_end_matches('.')
    } else {
        number
    }
}

/// Draws a line chart's light grid and its labelled axes, ticks labelled
/// by [`tick_label`], in `font` pixels (the axis names two larger).
fn draw_axes<DB: DrawingBackend>(
    chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x_label: &str,
    y_label: &str,
    font: u32,
) -> DrawResult<DB> {
    let (x_range, y_range) = (chart.x_range(), chart.y_range());
    let (x_span, y_span) = (x_range.end - x_range.start, y_range.end - y_range.start);
    chart
        .configure_mesh()
        .light_line_style(RGBColor(238, 238, 238))
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| tick_label(*v, x_span))
        .y_label_formatter(&|v| tick_label(*v, y_span))
        .label_style((FONT, font))
        .axis_desc_style((FONT, font + 2))
        .draw()
}

/// A short label for a tick at `v` on an axis spanning `span`: plain up to
/// four digits, scientific beyond (or below 1e-3), so large values such as
/// 4500000.0 Pa do not crowd the axis. A tick within a billionth of the
/// span of zero is zero (the axis's steps put it at 5.55e-17), and no
/// label reads -0.
fn tick_label(v: Real, span: Real) -> String {
    let v = if v.abs() <= 1e-9 * span.abs() { 0.0 } else { v };
    let a = v.abs();
    if a == 0.0 || (1e-3..1e4).contains(&a) {
        format!("{}", (v * 1e4).round() / 1e4 + 0.0)
    } else {
        format!("{v:.2e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// A fresh folder for one test, removed when dropped.
    fn test_dir(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("mpdem-io-plot-{name}-"))
            .tempdir()
            .unwrap()
    }

    /// Returns (width, height) from the IHDR chunk, after checking the PNG signature.
    fn png_size(path: &Path) -> (u32, u32) {
        let bytes = std::fs::read(path).unwrap();
        assert_eq!(
            &bytes[..8],
            b"\x89PNG\r\n\x1a\n",
            "{} is not a PNG",
            path.display()
        );
        assert_eq!(&bytes[12..16], b"IHDR");
        let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
        (word(16), word(20))
    }

    #[test]
    fn series_chart_is_a_900x600_png() {
        let sine: Vec<(f64, f64)> = (0..100)
            .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
            .collect();
        let measured = [(1.0, 0.5), (2.0, f64::NAN), (3.0, -0.25)];
        let series = [
            Series {
                name: "sin(t)",
                points: &sine,
            },
            Series {
                name: "measured",
                points: &measured,
            },
        ];
        let dir = test_dir("series");
        let path = dir.path().join("energy.png");
        plot_series(&path, "Kinetic energy", "time (s)", "energy (J)", &series).unwrap();
        assert_eq!(png_size(&path), (900, 600));
    }

    #[test]
    fn line_chart_has_the_asked_size_and_wraps_its_legend() {
        let computed: Vec<(f64, f64)> = (0..50).map(|i| (i as f64, (i as f64).sqrt())).collect();
        let reference: Vec<(f64, f64)> = computed.iter().map(|&(x, y)| (x, 1.1 * y)).collect();
        let lines = [
            Line {
                name: "computed",
                points: &computed,
                color: 0,
                dashed: false,
            },
            Line {
                name: "the reference, a name long enough to take two lines of the legend",
                points: &reference,
                color: 0,
                dashed: true,
            },
        ];
        let dir = test_dir("lines");
        let path = dir.path().join("lines.png");
        plot_lines(&path, (800, 500), "Lines", "x (m)", "y (m)", &lines).unwrap();
        assert_eq!(png_size(&path), (800, 500));
        assert_eq!(wrap("a name long enough", 8), ["a name", "long", "enough"]);
    }

    #[test]
    fn degenerate_series_do_not_panic() {
        let dir = test_dir("degenerate_series");
        let constant = [(0.0, 2.0), (1.0, 2.0), (2.0, 2.0)];
        let single = [(5.0, 0.0)];
        let nan = [(f64::NAN, f64::NAN)];
        for (name, points) in [
            ("constant", &constant[..]),
            ("single", &single),
            ("nan", &nan),
            ("empty", &[]),
        ] {
            let path = dir.path().join(format!("{name}.png"));
            let series = [Series { name, points }];
            plot_series(&path, name, "x", "y", &series).unwrap();
            assert_eq!(png_size(&path), (900, 600));
        }
        plot_series(&dir.path().join("none.png"), "no series", "x", "y", &[]).unwrap();
    }

    #[test]
    fn snapshot_size_follows_view_aspect() {
        let dir = test_dir("snapshot");
        let mut positions = Vec::new();
        let mut values = Vec::new();
        for i in 0..40 {
            for j in 0..20 {
                let p = DVec2::new(0.025 + 0.05 * i as f64, 0.025 + 0.05 * j as f64);
                positions.push(p);
                values.push(if i == 5 && j == 5 {
                    f64::NAN
                } else {
                    -1e5 * p.y
                });
            }
        }
        let block = vec![
            DVec2::new(0.8, 1.0),
            DVec2::new(1.2, 1.0),
            DVec2::new(1.2, 1.3),
            DVec2::new(0.8, 1.3),
        ];
        let view = (DVec2::new(0.0, 0.0), DVec2::new(2.0, 1.4));
        let path = dir.path().join("stress.png");
        plot_points(
            &path,
            "Vertical stress, t = 0.1 s",
            "stress yy (Pa)",
            &positions,
            &values,
            0.05,
            view,
            &[block],
        )
        .unwrap();
        let chrome = (
            COLORBAR_WIDTH + 2 * CHART_MARGIN + Y_LABEL_AREA,
            TITLE_HEIGHT + 2 * CHART_MARGIN + X_LABEL_AREA,
        );
        let expected_height = (f64::from(SNAPSHOT_WIDTH - chrome.0) * 0.7) as u32 + chrome.1;
        assert_eq!(png_size(&path), (SNAPSHOT_WIDTH, expected_height));

        // Very tall and very flat views clamp the height; constant and NaN values do not panic.
        let tall = (DVec2::ZERO, DVec2::new(0.1, 10.0));
        plot_points(
            &dir.path().join("tall.png"),
            "tall",
            "v",
            &positions,
            &vec![1.0; 800],
            0.0,
            tall,
            &[],
        )
        .unwrap();
        assert_eq!(
            png_size(&dir.path().join("tall.png")),
            (SNAPSHOT_WIDTH, 2000)
        );
        let flat = (DVec2::ZERO, DVec2::new(100.0, 0.1));
        plot_points(
            &dir.path().join("flat.png"),
            "flat",
            "v",
            &positions,
            &vec![f64::NAN; 800],
            0.05,
            flat,
            &[],
        )
        .unwrap();
        assert_eq!(
            png_size(&dir.path().join("flat.png")),
            (SNAPSHOT_WIDTH, 300)
        );
    }

    #[test]
    fn invalid_inputs_are_errors() {
        let dir = test_dir("invalid");
        let view = (DVec2::ZERO, DVec2::ONE);
        let kind = |result: std::io::Result<()>| result.unwrap_err().kind();
        let invalid = std::io::ErrorKind::InvalidInput;
        assert_eq!(
            kind(plot_points(
                &dir.path().join("a.jpg"),
                "",
                "",
                &[],
                &[],
                1.0,
                view,
                &[]
            )),
            invalid
        );
        assert_eq!(
            kind(plot_points(
                &dir.path().join("b.png"),
                "",
                "",
                &[DVec2::ZERO],
                &[],
                1.0,
                view,
                &[]
            )),
            invalid
        );
        let flat_view = (DVec2::ZERO, DVec2::new(1.0, 0.0));
        assert_eq!(
            kind(plot_points(
                &dir.path().join("c.png"),
                "",
                "",
                &[],
                &[],
                1.0,
                flat_view,
                &[]
            )),
            invalid
        );
        assert_eq!(
            kind(plot_series(&dir.path().join("d.svg"), "", "", "", &[])),
            invalid
        );
    }

    #[test]
    fn viridis_and_labels() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(0.0625), RGBColor(70, 23, 103));
        assert_eq!(format_value(-0.0), "0");
        assert_eq!(format_value(12.5), "12.5");
        assert_eq!(format_value(-2.0e6), "-2e6");
        assert_eq!(format_value(1.23456e-7), "1.235e-7");
        assert_eq!(format_value(0.0123456), "0.01235");
        assert_eq!(format_value(1234.0), "1234");
        let close = |a: Range<f64>, b: Range<f64>| {
            (a.start - b.start).abs() < 1e-12 && (a.end - b.end).abs() < 1e-12
        };
        assert!(close(padded_range([2.0, 2.0].into_iter()), 1.9..2.1));
        assert!(close(padded_range([0.0].into_iter()), -1.0..1.0));
        assert!(close(
            padded_range([1.0, 3.0, f64::NAN].into_iter()),
            0.9..3.1
        ));
        assert!(close(padded_range(std::iter::empty()), 0.0..1.0));
    }

    #[test]
    fn tick_labels_switch_to_scientific_for_large_and_tiny_values() {
        assert_eq!(tick_label(4.5e6, 1e7), "4.50e6");
        assert_eq!(tick_label(0.25, 1.0), "0.25");
        assert_eq!(tick_label(0.0, 1.0), "0");
        assert_eq!(tick_label(-2e-5, 1e-4), "-2.00e-5");
        // A zero tick off by the rounding of the axis's steps, and one
        // that rounds to minus zero.
        assert_eq!(tick_label(5.551115123125783e-17, 0.4), "0");
        assert_eq!(tick_label(-0.0, 1.0), "0");
    }
}
