//! CSV time series: how a record is written as a CSV file (the records
//! themselves write their rows, each in its plugin's file), and the
//! reaction–displacement curves.

use crate::math::Real;
use bevy_ecs::prelude::{Resource, World};
use std::borrow::Cow;
use std::io::Write;
use std::path::Path;

/// A name as one CSV field (RFC 4180): quoted, with its quotes doubled,
/// when it holds a comma, a quote or a line break, so that a probe named
/// "top, left" stays one column.
pub fn field(name: &str) -> Cow<'_, str> {
    if name.contains([',', '"', '\n', '\r']) {
        Cow::Owned(format!("\"{}\"", name.replace('"', "\"\"")))
    } else {
        Cow::Borrowed(name)
    }
}

/// A time (s) as the series write it: to 12 significant digits, with
/// trailing zeros dropped, so that the time of step n, n Δt in floating
/// point, reads `1e-5` rather than `9.999999999999999e-6`. (The other
/// columns keep every digit.)
pub fn time(t: Real) -> String {
    let written = format!("{t:.11e}");
    match written.split_once('e') {
        Some((mantissa, exponent)) => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exponent}")
        }
        None => written,
    }
}

/// A record the outputs write as CSV, one row per sample: written whole
/// ([`write_series`]) or appended to as the run records it
/// (by the run's output folder).
pub trait CsvSeries {
    /// The header line (without its line break).
    const HEADER: &'static str;

    /// How many rows the record holds.
    fn rows(&self) -> usize;

    /// Writes row `k` (with its line break); `bodies` are the bodies' names
    /// in scene order.
    fn write_row(&self, k: usize, bodies: &[String], out: &mut dyn Write) -> std::io::Result<()>;
}

/// A [`CsvSeries`] behind a reference, whatever its type.
pub(crate) trait SeriesRows {
    /// The header line.
    fn header(&self) -> &'static str;
    /// How many rows the record holds.
    fn rows(&self) -> usize;
    /// Writes row `k`.
    fn write_row(&self, k: usize, bodies: &[String], out: &mut dyn Write) -> std::io::Result<()>;
}

impl<S: CsvSeries> SeriesRows for S {
    fn header(&self) -> &'static str {
        S::HEADER
    }
    fn rows(&self) -> usize {
        CsvSeries::rows(self)
    }
    fn write_row(&self, k: usize, bodies: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        CsvSeries::write_row(self, k, bodies, out)
    }
}

/// A record in the world that the outputs write as a CSV file.
#[derive(Clone, Copy)]
pub(crate) struct CsvRecord {
    /// The file's name in the output folder.
    pub file: &'static str,
    /// The record in a world.
    pub series: for<'w> fn(&'w World) -> &'w dyn SeriesRows,
}

impl CsvRecord {
    /// The resource `R`, written as `file`.
    pub fn of<R: Resource + CsvSeries>(file: &'static str) -> Self {
        Self {
            file,
            series: series_of::<R>,
        }
    }
}

fn series_of<R: Resource + CsvSeries>(world: &World) -> &dyn SeriesRows {
    world.resource::<R>()
}

/// Writes the whole `series` to `path`.
pub fn write_series<S: CsvSeries>(
    path: &Path,
    series: &S,
    bodies: &[String],
) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "{}", S::HEADER)?;
    for k in 0..series.rows() {
        series.write_row(k, bodies, &mut out)?;
    }
    out.flush()
}

/// Writes a reaction–displacement curve: `time,displacement,resistance`.
pub fn write_curve(path: &Path, rows: &[(Real, Real, Real)]) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "time,displacement,resistance")?;
    for (t, d, f) in rows {
        writeln!(out, "{},{d:e},{f:e}", time(*t))?;
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    #[test]
    fn times_keep_twelve_digits_and_drop_trailing_zeros() {
        assert_eq!(super::time(100.0 * 1e-7), "1e-5");
        assert_eq!(super::time(0.0), "0e0");
        assert_eq!(super::time(1.5), "1.5e0");
        assert_eq!(super::time(0.123456789012345), "1.23456789012e-1");
    }

    #[test]
    fn names_with_commas_or_quotes_stay_one_field() {
        assert_eq!(super::field("top"), "top");
        assert_eq!(super::field("top, left"), "\"top, left\"");
        assert_eq!(super::field("the \"pile\""), "\"the \"\"pile\"\"\"");
    }
}
