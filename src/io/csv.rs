//! CSV time series: probes, energies, blocks, body pairs and stages.

use crate::math::Real;
use crate::resources::{BlockLog, BodyPairLog, EnergyLog, Probes, StageLog};
use bevy_ecs::prelude::{Resource, World};
use std::borrow::Cow;
use std::io::Write;
use std::path::Path;

/// A name as one CSV field (RFC 4180): quoted, with its quotes doubled,
/// when it holds a comma, a quote or a line break, so that a probe named
/// "top, left" stays one column.
fn field(name: &str) -> Cow<'_, str> {
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
pub(crate) fn time(t: Real) -> String {
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

/// `probes.csv`: one row per probe and sample time, columns probe, time,
/// x, y, ux, uy, vx, vy, sxx, syy, sxy, szz (SI, stress tension-positive).
impl CsvSeries for Probes {
    const HEADER: &'static str = "probe,time,x,y,ux,uy,vx,vy,sxx,syy,sxy,szz";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        let name = field(&self.probes[s.probe].name);
        let [sxx, syy, sxy, szz] = s.stress.to_array();
        writeln!(
            out,
            "{name},{},{:e},{:e},{:e},{:e},{:e},{:e},{sxx:e},{syy:e},{sxy:e},{szz:e}",
            time(s.time),
            s.position.x,
            s.position.y,
            s.displacement.x,
            s.displacement.y,
            s.velocity.x,
            s.velocity.y
        )
    }
}

/// `energy.csv`: time, kinetic, strain, contact, total, gravity,
/// inelastic, loads, blocks, dissipated, damped, balance (J per metre of
/// thickness). `total` sums the kinetic, strain and contact (the point
/// contacts' springs) energies, conserved by free elastic bodies;
/// `balance` adds gravity's potential, what the materials dissipated, minus
/// the work of the surface loads and of the blocks, what the contacts
/// dissipated and what damping and the PIC part took (see
/// [`crate::resources::EnergySample::balance`] for what it still leaves
/// out).
impl CsvSeries for EnergyLog {
    const HEADER: &'static str = "time,kinetic,strain,contact,total,gravity,inelastic,loads,blocks,dissipated,damped,balance";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        writeln!(
            out,
            "{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            time(s.time),
            // + 0.0 writes a minus zero (a work negated) as 0.
            s.kinetic + 0.0,
            s.strain + 0.0,
            s.contact + 0.0,
            s.total() + 0.0,
            s.gravity + 0.0,
            s.inelastic + 0.0,
            s.loads + 0.0,
            s.blocks + 0.0,
            s.dissipated + 0.0,
            s.damped + 0.0,
            s.balance() + 0.0
        )
    }
}

/// `body_contacts.csv`: one row per pair of bodies with a law and sample
/// time, columns time, body_a, body_b, force_x, force_y (on body_a, N/m),
/// contacts (point pairs), half_width, pressure_half_width and
/// initial_pressure_half_width (m, see [`crate::resources::PairSummary`]).
/// `time` is the end of the step whose contacts (found from the positions
/// at its start) are summed, like the other records.
impl CsvSeries for BodyPairLog {
    const HEADER: &'static str = "time,body_a,body_b,force_x,force_y,contacts,half_width,pressure_half_width,initial_pressure_half_width";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, bodies: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        let name = |i: u32| field(bodies.get(i as usize).map_or("?", String::as_str));
        let p = &s.summary;
        writeln!(
            out,
            "{},{},{},{:e},{:e},{},{:e},{:e},{:e}",
            time(s.time),
            name(s.a),
            name(s.b),
            p.force.x,
            p.force.y,
            p.contacts,
            p.half_width,
            p.pressure_half_width,
            p.initial_pressure_half_width
        )
    }
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

/// `stages.csv`: one row per finished stage, columns stage (index), name,
/// start, end (s), steps, reason (`duration`, `condition`, `max_time` or
/// `scene_end`).
impl CsvSeries for StageLog {
    const HEADER: &'static str = "stage,name,start,end,steps,reason";

    fn rows(&self) -> usize {
        self.records.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let r = &self.records[k];
        writeln!(
            out,
            "{},{},{},{},{},{}",
            r.index,
            field(&r.name),
            time(r.start),
            time(r.end),
            r.steps,
            r.reason.label()
        )
    }
}

/// `blocks.csv`: one row per block and sample time, columns block, time,
/// fx, fy, torque (the points' reaction on the block), x, y, angle (frame
/// origin, rad), vx, vy, omega (centre of mass).
impl CsvSeries for BlockLog {
    const HEADER: &'static str = "block,time,fx,fy,torque,x,y,angle,vx,vy,omega";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        let name = field(self.names.get(s.block as usize).map_or("?", String::as_str));
        writeln!(
            out,
            "{name},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            time(s.time),
            s.force.x,
            s.force.y,
            s.torque,
            s.origin.x,
            s.origin.y,
            s.angle,
            s.velocity.x,
            s.velocity.y,
            s.angular
        )
    }
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
