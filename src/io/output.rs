//! The output folder of a run: VTK frames, the ParaView collections and the
//! CSV series during the run; PNG plots at the end.

use super::animation::{Animation, FrameColumns};
use super::csv::{self, CsvRecord};
use super::figure::{Figure, FigureContext};
use super::manifest::{OutputManifest, SceneOrigin};
use super::plot::{Series, plot_points, plot_series};
use super::vtk::{
    PointFrame, read_collection, write_collection, write_outlines, write_point_frame,
};
use crate::components::{BlockId, BlockOutline, BodyIndex, MaterialPoints, Pose};
use crate::files::{located, partial_path};
use crate::math::{DVec2, Real};
use crate::resources::{BlockLog, Grid};
use crate::scene::{CurveSpec, Scene};
use crate::simulation::Simulation;
use bevy_ecs::entity::Entity;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes a run's results into one folder:
/// * `vtk/points_NNNNN.vtu` every frame interval and `points.pvd` (open this in ParaView);
/// * with rigid blocks, their outlines: `vtk/blocks_NNNNN.vtu` and `blocks.pvd`, and `blocks.csv`;
/// * `probes.csv`, `energy.csv`, with stages `stages.csv`, and with body
///   contact laws `body_contacts.csv`, appended to as the run records each
///   sample (each sample's rows in one write), so that a run killed at any
///   point keeps its series up to there;
/// * `snapshot.png` (final state coloured by displacement magnitude),
///   `energy.png` and `probe_<name>_{velocity,displacement,stress}.png`;
/// * `outputs.txt`, the list of these files ([`OutputManifest`]): a new run
///   into the folder first removes the files an earlier run listed (not
///   the checkpoint, which this writer does not write).
///
/// Every other file is written under a temporary name and renamed, so a
/// run that fails while writing (a full disk) leaves no half-written file;
/// errors name the file.
pub struct RunOutput {
    folder: Folder,
    frame_every: u64,
    frames: Vec<(Real, String)>,
    block_frames: Vec<(Real, String)>,
    buffers: FrameBuffers,
    /// Reaction–displacement curves to write at the end, each with the
    /// frame origin its block is placed at (where its displacement counts
    /// from; the block's first sample comes a probe interval later).
    curves: Vec<(CurveSpec, DVec2)>,
    /// The CSV series, appended to as the run records them.
    series: Vec<SeriesFile>,
    /// The bodies' names in scene order, for the series that name them.
    bodies: Vec<String>,
    /// The frames of `animation.gif`, if the scene asks for it.
    animation: Option<Animation>,
    /// The run's name, for the animation's titles.
    name: String,
}

/// One CSV series open for appending.
struct SeriesFile {
    record: CsvRecord,
    path: PathBuf,
    /// Rows written so far.
    written: usize,
    /// The file's length after them (bytes).
    length: u64,
    file: File,
    /// The rows of one append, written to the file in one call (so that a
    /// killed run is unlikely to leave a part of a row).
    rows: Vec<u8>,
}

impl SeriesFile {
    /// Appends the rows recorded since the last call. An append that fails
    /// (a full disk) is cut off the file, so that it ends with a whole row.
    fn append(&mut self, world: &bevy_ecs::world::World, bodies: &[String]) -> std::io::Result<()> {
        let Self {
            record,
            path,
            written,
            length,
            file,
            rows: buffer,
        } = self;
        let series = (record.series)(world);
        let mut append = || -> std::io::Result<()> {
            let rows = series.rows();
            if rows <= *written {
                return Ok(());
            }
            buffer.clear();
            for k in *written..rows {
                series.write_row(k, bodies, buffer)?;
            }
            if let Err(e) = file.write_all(buffer) {
                // The write's own error is the one to report.
                let _ = file.set_len(*length);
                return Err(e);
            }
            *written = rows;
            *length += buffer.len() as u64;
            Ok(())
        };
        append().map_err(|e| located(path, e))
    }
}

/// The output folder and the list of the files written into it.
struct Folder {
    dir: PathBuf,
    manifest: OutputManifest,
}

impl Folder {
    /// Writes the file `relative` (`/`-separated, inside the folder) with
    /// `writer`, given the path to write: lists it, has it written under a
    /// temporary name in the same folder (keeping its extension, which the
    /// PNG writer reads) and renames it into place. On failure the
    /// temporary file is removed and the error names the file.
    fn write_file(
        &mut self,
        relative: &str,
        writer: impl FnOnce(&Path) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        self.manifest.record(relative)?;
        let path = self.dir.join(relative);
        let partial = partial_path(&path);
        let written = writer(&partial).and_then(|()| std::fs::rename(&partial, &path));
        written.map_err(|e| {
            std::fs::remove_file(&partial).ok();
            located(&path, e)
        })
    }
}

/// Concatenated columns of all bodies, reused from frame to frame.
#[derive(Default)]
struct FrameBuffers {
    positions: Vec<DVec2>,
    velocities: Vec<DVec2>,
    displacements: Vec<DVec2>,
    stresses: Vec<[Real; 4]>,
    body: Vec<u32>,
    marker: Real,
    /// Outlines of the rigid blocks in the world, blocks in scene order.
    outlines: Vec<Vec<DVec2>>,
    /// The scene index of each outline's block.
    outline_block: Vec<u32>,
    /// The plugins' scalar fields: name and one value per point.
    fields: Vec<(&'static str, Vec<Real>)>,
}

/// One sample of a reaction–displacement curve: time, scaled displacement,
/// scaled resistance.
type CurveSample = (Real, Real, Real);

impl RunOutput {
    /// Creates the folder (and `vtk/` inside it), removes the files an
    /// earlier run into it listed, and writes frame 0. Frames follow the
    /// `scene`'s frame interval; its curves are written at the end. Returns
    /// the output and how many of the earlier run's files were removed.
    /// `source` is the scene's file, if it has one: the folder's list
    /// names it, or else the scene's name.
    pub fn create(
        dir: &Path,
        scene: &Scene,
        source: Option<&Path>,
        sim: &mut Simulation,
    ) -> std::io::Result<(Self, usize)> {
        let vtk = dir.join("vtk");
        std::fs::create_dir_all(&vtk).map_err(|e| located(&vtk, e))?;
        let origin = SceneOrigin::of(scene, source);
        let (manifest, removed) = OutputManifest::start(dir, Some(&origin))?;
        let frame_every = frame_every(scene, sim);
        let bodies = sim.bodies().into_iter().map(|(_, n)| n).collect();
        let animation = animation(scene, sim, frame_every);
        let mut output = Self {
            folder: Folder {
                dir: dir.to_path_buf(),
                manifest,
            },
            frame_every,
            frames: Vec::new(),
            block_frames: Vec::new(),
            buffers: FrameBuffers::default(),
            curves: placed_curves(scene),
            series: Vec::new(),
            bodies,
            animation,
            name: sim.name().to_owned(),
        };
        for &record in sim.csv_records() {
            let file = output.open_series(record, sim.world(), false)?;
            output.series.push(file);
        }
        output.write_frame(sim)?;
        Ok((output, removed))
    }

    /// Carries on the folder of a run that `sim` was resumed from (see
    /// [`Simulation::resume`]): the frames its collections list up to the
    /// checkpoint's step are kept, later ones are written again, every
    /// frame interval of the `scene` as for a new run. The extra frame a finished run
    /// writes at its end, off that interval, is dropped too: a run that
    /// never stopped would not have it. A folder without `points.pvd` is
    /// not a run's folder: an error. Returns the output and notes for the
    /// user: when the folder's first frame was written after `checkpoint`
    /// (another run into the folder since then replaced the frames), that
    /// the frames before the checkpoint are not this run's; with an
    /// animation, that it starts where the run resumed.
    pub fn resume(
        dir: &Path,
        scene: &Scene,
        sim: &Simulation,
        checkpoint: &Path,
    ) -> std::io::Result<(Self, Vec<String>)> {
        let clock = sim.clock();
        let frame_every = frame_every(scene, sim);
        let on_interval = clock.step.is_multiple_of(frame_every);
        let kept = |path: &Path| -> std::io::Result<Vec<(Real, String)>> {
            let mut frames = read_collection(path).map_err(|e| located(path, e))?;
            frames.retain(|(time, _)| {
                let before = *time < clock.time - 0.5 * clock.dt;
                before || (on_interval && *time <= clock.time + 0.5 * clock.dt)
            });
            Ok(frames)
        };
        let blocks = dir.join("blocks.pvd");
        let frames = kept(&dir.join("points.pvd"))?;
        // A run resumed from the checkpoint keeps the first frame its own
        // run wrote before it; one written after it is another run's.
        let modified = |path: &Path| std::fs::metadata(path).and_then(|m| m.modified()).ok();
        let first_frame = frames
            .first()
            .and_then(|(_, name)| modified(&dir.join(name)));
        let replaced = first_frame
            .zip(modified(checkpoint))
            .is_some_and(|(frame, written)| frame > written);
        let gaps = replaced.then(|| {
            format!(
                "warning: {}: the frames were written after the checkpoint, by another run into this folder: the frames before t = {:.6e} s are that run's, not this one's (the CSV series, kept in the checkpoint, are whole)",
                dir.join("points.pvd").display(),
                clock.time
            )
        });
        let mut output = Self {
            folder: Folder {
                dir: dir.to_path_buf(),
                manifest: OutputManifest::resume(dir)?,
            },
            frame_every,
            frames,
            block_frames: if blocks.is_file() {
                kept(&blocks)?
            } else {
                Vec::new()
            },
            buffers: FrameBuffers::default(),
            curves: placed_curves(scene),
            series: Vec::new(),
            bodies: scene.bodies.iter().map(|b| b.name.clone()).collect(),
            animation: animation(scene, sim, frame_every),
            name: sim.name().to_owned(),
        };
        // The series as the checkpoint holds them, then appended to.
        for &record in sim.csv_records() {
            let file = output.open_series(record, sim.world(), true)?;
            output.series.push(file);
        }
        let mut notes: Vec<String> = gaps.into_iter().collect();
        if output.animation.is_some() {
            notes.push(format!(
                "note: animation.gif shows the run from t = {:.6e} s, where it resumed; the frames before are in {}",
                clock.time,
                dir.join("vtk").display()
            ));
        }
        Ok((output, notes))
    }

    /// Call after every step: appends the samples recorded in the step to
    /// the CSV series, and writes a frame when one is due.
    pub fn after_step(&mut self, sim: &mut Simulation) -> std::io::Result<()> {
        self.append_series(sim)?;
        if sim.clock().step.is_multiple_of(self.frame_every) {
            self.write_frame(sim)?;
        }
        Ok(())
    }

    /// Opens the CSV file of `record` with what `world` holds of it: a new
    /// file, or for a resumed run (`whole`) the whole record written under
    /// a temporary name and renamed, then opened for appending.
    fn open_series(
        &mut self,
        record: CsvRecord,
        world: &bevy_ecs::world::World,
        whole: bool,
    ) -> std::io::Result<SeriesFile> {
        let path = self.folder.dir.join(record.file);
        let bodies = &self.bodies;
        let series = (record.series)(world);
        let written = if whole {
            self.folder.write_file(record.file, |path| {
                let mut out = BufWriter::new(File::create(path)?);
                writeln!(out, "{}", series.header())?;
                for k in 0..series.rows() {
                    series.write_row(k, bodies, &mut out)?;
                }
                out.flush()
            })?;
            series.rows()
        } else {
            self.folder.manifest.record(record.file)?;
            let mut out = File::create(&path).map_err(|e| located(&path, e))?;
            writeln!(out, "{}", series.header()).map_err(|e| located(&path, e))?;
            0
        };
        let out = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| located(&path, e))?;
        let length = out.metadata().map_err(|e| located(&path, e))?.len();
        let mut file = SeriesFile {
            record,
            path,
            written,
            length,
            file: out,
            rows: Vec::new(),
        };
        file.append(world, bodies)?;
        Ok(file)
    }

    /// Appends the samples recorded since the last call to every series.
    fn append_series(&mut self, sim: &Simulation) -> std::io::Result<()> {
        let world = sim.world();
        for file in &mut self.series {
            file.append(world, &self.bodies)?;
        }
        Ok(())
    }

    /// Writes the last frame (if not yet written, and only if the last step
    /// did not fail: a broken state is never written), the collection, the
    /// CSV files and the plots. Call at the end of a run, also after a failure.
    pub fn finish(&mut self, sim: &mut Simulation, failed: bool) -> std::io::Result<()> {
        let time = sim.clock().time;
        if !failed && self.frames.last().is_none_or(|(t, _)| *t != time) {
            self.write_frame(sim)?;
        }
        self.write_collections()?;
        self.append_series(sim)?;
        // The records' figures, of the plugins that were built.
        let world = sim.world();
        let per = world
            .resource::<crate::resources::Settings>()
            .geometry
            .per();
        if let Some(blocks) = world.get_resource::<BlockLog>() {
            for (curve, start) in &self.curves {
                write_curve(&mut self.folder, curve, *start, blocks, per)?;
            }
        }
        let context = FigureContext {
            scene: sim.scene(),
            bodies: &self.bodies,
            per,
        };
        for record in sim.figure_records() {
            for figure in record.figures(world, &context) {
                self.folder
                    .write_file(&figure.file, |path| draw_figure(path, &figure))?;
            }
        }
        let grid = world.resource::<Grid>();
        self.plot_snapshot(sim.name(), grid)?;
        self.write_animation(grid)
    }

    /// Writes `animation.gif`, with the run's last frame, if the scene
    /// asks for it.
    fn write_animation(&mut self, grid: &Grid) -> std::io::Result<()> {
        let Some(animation) = &mut self.animation else {
            return Ok(());
        };
        if let Some(&(time, _)) = self.frames.last() {
            animation.record_last(&self.buffers.columns(&self.name, time));
        }
        let marker = self.buffers.marker;
        self.folder.write_file("animation.gif", |path| {
            animation.write(path, marker, (grid.origin, grid.max()))
        })
    }

    fn write_frame(&mut self, sim: &mut Simulation) -> std::io::Result<()> {
        self.buffers.fill(sim);
        let b = &self.buffers;
        let frame = PointFrame {
            positions: &b.positions,
            velocities: &b.velocities,
            displacements: &b.displacements,
            stresses: &b.stresses,
            body: &b.body,
            fields: &b.fields,
        };
        let name = format!("vtk/points_{:05}.vtu", self.frames.len());
        self.folder
            .write_file(&name, |path| write_point_frame(path, &frame))?;
        let time = sim.clock().time;
        self.frames.push((time, name));
        if let Some(animation) = &mut self.animation {
            animation.record(&b.columns(&self.name, time));
        }
        if !b.outlines.is_empty() {
            let name = format!("vtk/blocks_{:05}.vtu", self.block_frames.len());
            self.folder.write_file(&name, |path| {
                write_outlines(path, &b.outlines, &b.outline_block)
            })?;
            self.block_frames.push((sim.clock().time, name));
        }
        // The collections list every frame so far, so a stopped run can be
        // opened in ParaView and resumed.
        self.write_collections()
    }

    fn write_collections(&mut self) -> std::io::Result<()> {
        let frames = &self.frames;
        self.folder
            .write_file("points.pvd", |path| write_collection(path, frames))?;
        if !self.block_frames.is_empty() {
            let frames = &self.block_frames;
            self.folder
                .write_file("blocks.pvd", |path| write_collection(path, frames))?;
        }
        Ok(())
    }

    /// The last written frame as a PNG.
    fn plot_snapshot(&mut self, name: &str, grid: &Grid) -> std::io::Result<()> {
        let b = &self.buffers;
        let time = self.frames.last().map_or(0.0, |f| f.0);
        let magnitude: Vec<Real> = b.displacements.iter().map(|u| u.length()).collect();
        self.folder.write_file("snapshot.png", |path| {
            plot_points(
                path,
                &format!("{name} at t = {time:.4} s"),
                "|u| (m)",
                &b.positions,
                &magnitude,
                b.marker,
                (grid.origin, grid.max()),
                &b.outlines,
            )
        })
    }
}

/// The animation the scene asks for, over the frames a run writes every
/// `frame_every` steps.
fn animation(scene: &Scene, sim: &Simulation, frame_every: u64) -> Option<Animation> {
    let field = scene.output.animation?;
    Some(Animation::new(
        field,
        sim.clock().total_steps() / frame_every + 2,
    ))
}

/// Draws `figure` as the PNG `path`.
fn draw_figure(path: &Path, figure: &Figure) -> std::io::Result<()> {
    let series: Vec<Series> = figure
        .curves
        .iter()
        .map(|c| Series {
            name: &c.name,
            points: &c.points,
        })
        .collect();
    plot_series(
        path,
        &figure.title,
        &figure.x_label,
        &figure.y_label,
        &series,
    )
}

/// Steps between frames: the scene's frame interval (its default follows
/// the run's `time.end`) in whole steps, at least one.
pub(crate) fn frame_every(scene: &Scene, sim: &Simulation) -> u64 {
    let clock = sim.clock();
    scene.output.frame_every(clock.end, clock.dt)
}

/// The scene's curves, each with the frame origin its block is placed at.
fn placed_curves(scene: &Scene) -> Vec<(CurveSpec, DVec2)> {
    scene
        .output
        .curves
        .iter()
        .map(|curve| {
            let block = scene.blocks.iter().find(|b| b.name == curve.block);
            (curve.clone(), block.map_or(DVec2::ZERO, |b| b.position))
        })
        .collect()
}

/// Writes `<name>.csv` (`time,displacement,resistance`, scaled) and
/// `<name>.png` for one curve.
fn write_curve(
    folder: &mut Folder,
    curve: &CurveSpec,
    start: DVec2,
    log: &BlockLog,
    per: &str,
) -> std::io::Result<()> {
    let Some(block) = log.names.iter().position(|n| *n == curve.block) else {
        return Ok(());
    };
    let d = curve.direction.normalize_or_zero();
    let samples: Vec<_> = log
        .samples
        .iter()
        .filter(|s| s.block as usize == block)
        .collect();
    if samples.is_empty() {
        return Ok(());
    }
    let force_at = |time: Real, whole: DVec2| match curve.part {
        None => whole,
        Some(k) => log
            .parts
            .iter()
            .find(|p| p.block as usize == block && p.part as usize == k && p.time == time)
            .map_or(DVec2::ZERO, |p| p.force),
    };
    let rows: Vec<CurveSample> = samples
        .iter()
        .map(|s| {
            (
                s.time,
                (s.origin - start).dot(d) * curve.displacement_scale,
                -force_at(s.time, s.force).dot(d) * curve.force_scale,
            )
        })
        .collect();
    folder.write_file(&format!("{}.csv", curve.name), |path| {
        csv::write_curve(path, &rows)
    })?;
    let points: Vec<(Real, Real)> = rows.iter().map(|r| (r.1, r.2)).collect();
    folder.write_file(&format!("{}.png", curve.name), |path| {
        plot_series(
            path,
            &curve.name,
            curve
                .displacement_label
                .as_deref()
                .unwrap_or("displacement (m)"),
            curve
                .force_label
                .clone()
                .unwrap_or_else(|| format!("force (N/{per})"))
                .as_str(),
            &[Series {
                name: "",
                points: &points,
            }],
        )
    })
}

impl FrameBuffers {
    /// The columns of the frame at `time` of the run `name`.
    fn columns<'a>(&'a self, name: &'a str, time: Real) -> FrameColumns<'a> {
        FrameColumns {
            name,
            time,
            positions: &self.positions,
            velocities: &self.velocities,
            displacements: &self.displacements,
            stresses: &self.stresses,
            body: &self.body,
            outlines: &self.outlines,
        }
    }

    /// Copies the current state of every body, in scene order.
    fn fill(&mut self, sim: &mut Simulation) {
        self.positions.clear();
        self.velocities.clear();
        self.displacements.clear();
        self.stresses.clear();
        self.body.clear();
        self.marker = Real::INFINITY;
        self.outlines.clear();
        self.outline_block.clear();
        let mut query = sim.world_mut().query::<(&BlockId, &BlockOutline, &Pose)>();
        let mut blocks: Vec<_> = query
            .iter(sim.world())
            .map(|(id, outline, pose)| (id.index, outline.in_world(pose).collect::<Vec<_>>()))
            .collect();
        blocks.sort_by_key(|b| b.0);
        for (block, outlines) in blocks {
            self.outline_block
                .extend(std::iter::repeat_n(block, outlines.len()));
            self.outlines.extend(outlines);
        }
        let bodies: Vec<Entity> = sim.bodies().into_iter().map(|(e, _)| e).collect();
        for &entity in &bodies {
            let world = sim.world();
            let (Some(index), Some(points)) = (
                world.get::<BodyIndex>(entity),
                world.get::<MaterialPoints>(entity),
            ) else {
                continue;
            };
            self.positions.extend_from_slice(&points.position);
            self.velocities.extend_from_slice(&points.velocity);
            self.displacements
                .extend((0..points.len()).map(|p| points.displacement(p)));
            self.stresses
                .extend(points.stress.iter().map(|s| s.to_array()));
            self.body.extend(std::iter::repeat_n(index.0, points.len()));
            self.marker = points
                .half_size
                .iter()
                .fold(self.marker, |m, h| m.min(2.0 * h.x));
        }
        self.fill_point_fields(sim, &bodies);
    }

    /// The plugins' point fields, bodies in scene order. A field that
    /// gives a body another count of values than its points is written
    /// as it is, and the frame's check of its columns refuses it.
    fn fill_point_fields(&mut self, sim: &Simulation, bodies: &[Entity]) {
        let records = sim.point_fields();
        self.fields.resize_with(records.len(), || ("", Vec::new()));
        for (record, (name, values)) in records.iter().zip(&mut self.fields) {
            *name = record.name;
            values.clear();
            for &entity in bodies {
                (record.fill)(sim.world(), entity, values);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::resources::BlockSample;

    /// A punch placed at y = 0.4 and driven down at 0.05 m/s from t = 0:
    /// its first sample, a probe interval in, has moved 0.5 mm already,
    /// and the curve says so (it counted from the first sample before).
    #[test]
    fn a_curve_counts_the_displacement_from_where_its_block_was_placed() {
        let dir = std::env::temp_dir().join(format!("mpdem-curve-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (manifest, _) = OutputManifest::start(&dir, None).unwrap();
        let mut folder = Folder {
            dir: dir.clone(),
            manifest,
        };
        let sample = |time: Real, y: Real| BlockSample {
            block: 0,
            time,
            force: DVec2::new(0.0, 100.0 * time),
            torque: 0.0,
            origin: DVec2::new(0.5, y),
            angle: 0.0,
            velocity: DVec2::new(0.0, -0.05),
            angular: 0.0,
        };
        let log = BlockLog {
            names: vec!["punch".into()],
            samples: vec![sample(0.01, 0.3995), sample(0.02, 0.399)],
            parts: Vec::new(),
        };
        let curve = CurveSpec {
            name: "qc".into(),
            block: "punch".into(),
            part: None,
            direction: DVec2::new(0.0, -1.0),
            force_scale: 1.0,
            displacement_scale: 1.0,
            force_label: None,
            displacement_label: None,
        };
        write_curve(&mut folder, &curve, DVec2::new(0.5, 0.4), &log, "m").unwrap();
        let text = std::fs::read_to_string(dir.join("qc.csv")).unwrap();
        let displacements: Vec<Real> = text
            .lines()
            .skip(1)
            .map(|row| row.split(',').nth(1).unwrap().parse().unwrap())
            .collect();
        assert_eq!(displacements.len(), 2);
        assert!((displacements[0] - 5e-4).abs() < 1e-12, "{text}");
        assert!((displacements[1] - 1e-3).abs() < 1e-12, "{text}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
