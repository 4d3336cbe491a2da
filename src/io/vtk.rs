//! ParaView output: VTK XML unstructured grids (`.vtu`) and ParaView collections (`.pvd`).
//!
//! The `.vtu` files are written with `vtkio` as VTK XML files (format version 1.0,
//! `byte_order="LittleEndian"`, `header_type="UInt64"`) in which every `DataArray` is stored inline
//! as uncompressed base64 binary (`format="binary"`), the standard encoding that VTK's own writers
//! produce and that ParaView reads natively. Coordinates and floating point arrays are `Float64`.
//! The 2D model lives in the plane z = 0.
//!
//! A `.pvd` collection ties a series of `.vtu` files to simulation times so ParaView plays the
//! series with the right time values.

use crate::math::{DVec2, Real};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, IOBuffer,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

/// One output frame of all material points (all bodies concatenated), columns of equal length.
pub struct PointFrame<'a> {
    /// Current position of each point (m).
    pub positions: &'a [DVec2],
    /// Velocity of each point (m/s).
    pub velocities: &'a [DVec2],
    /// Displacement of each point from its initial position (m).
    pub displacements: &'a [DVec2],
    /// Cauchy stress per point as [xx, yy, xy, zz] (Pa, tension positive).
    pub stresses: &'a [[Real; 4]],
    /// Index of the body each point belongs to (scene order).
    pub body: &'a [u32],
    /// The plugins' scalar fields: name and one value per point.
    pub fields: &'a [(&'static str, Vec<Real>)],
}

/// The names of the point data arrays every frame has.
pub(crate) const FRAME_FIELDS: [&str; 4] = ["velocity", "displacement", "stress", "body"];

/// A scalar field a plugin adds to the points of the VTK frames: its name,
/// and what appends one value per point of a body (its entity) to a column.
#[derive(Clone, Copy)]
pub(crate) struct PointFieldRecord {
    pub name: &'static str,
    pub fill: fn(&bevy_ecs::world::World, bevy_ecs::entity::Entity, &mut Vec<Real>),
}

/// Writes the frame as a VTK XML UnstructuredGrid (`.vtu`) of `VTK_VERTEX` cells, one per point.
///
/// Point data arrays: `"velocity"` and `"displacement"` (3 components, z = 0), `"stress"` (the
/// full symmetric 3x3 tensor as 9 components `[xx, xy, 0, xy, yy, 0, 0, 0, zz]`, so ParaView treats
/// it as a tensor), `"body"` (UInt32 scalar) and the plugins' scalar fields. Points are 3D with z = 0. Arrays are inline base64
/// binary (see the module docs).
///
/// Fails with `InvalidInput` if the columns of `frame` differ in length, or with the I/O error of
/// creating or writing the file.
pub fn write_point_frame(path: &Path, frame: &PointFrame) -> std::io::Result<()> {
    let n = frame.positions.len();
    let lengths: Vec<usize> = [
        frame.velocities.len(),
        frame.displacements.len(),
        frame.stresses.len(),
        frame.body.len(),
    ]
    .into_iter()
    .chain(frame.fields.iter().map(|(_, values)| values.len()))
    .collect();
    if lengths.iter().any(|&len| len != n) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("point frame columns differ in length: {n} positions, others {lengths:?}"),
        ));
    }
    let stress: Vec<Real> = frame
        .stresses
        .iter()
        .flat_map(|&[xx, yy, xy, zz]| [xx, xy, 0.0, xy, yy, 0.0, 0.0, 0.0, zz])
        .collect();
    let mut point_data = vec![
        Attribute::DataArray(DataArray::vectors("velocity").with_data(xyz(frame.velocities))),
        Attribute::DataArray(
            DataArray::vectors("displacement").with_data(xyz(frame.displacements)),
        ),
        Attribute::DataArray(DataArray::tensors("stress").with_data(stress)),
        Attribute::DataArray(DataArray::scalars("body", 1).with_data(frame.body.to_vec())),
    ];
    point_data.extend(frame.fields.iter().map(|(name, values)| {
        Attribute::DataArray(DataArray::scalars(*name, 1).with_data(values.clone()))
    }));
    let cells = Cells {
        cell_verts: VertexNumbers::XML {
            connectivity: (0..n as u64).collect(),
            offsets: (1..=n as u64).collect(),
        },
        types: vec![CellType::Vertex; n],
    };
    write_unstructured_grid(path, frame.positions, cells, point_data, Vec::new())
}

/// Writes closed polylines (e.g., rigid block outlines) as a VTK XML UnstructuredGrid (`.vtu`)
/// with one `VTK_POLY_LINE` cell per outline and a `"block"` cell array (UInt32), `blocks[k]`
/// for outline k (the block's index in the scene, to colour by in ParaView; a compound block has
/// one outline per part).
///
/// Each outline's points are stored once; its cell returns to the first point to close the loop.
/// Empty outlines are skipped. Fails with `InvalidInput` if `blocks` and `outlines` differ in
/// length, or with the I/O error of creating or writing the file.
pub fn write_outlines(path: &Path, outlines: &[Vec<DVec2>], blocks: &[u32]) -> std::io::Result<()> {
    if blocks.len() != outlines.len() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "{} outlines but {} block indices",
                outlines.len(),
                blocks.len()
            ),
        ));
    }
    let mut points = Vec::new();
    let mut connectivity = Vec::new();
    let mut offsets = Vec::new();
    let mut cell_blocks = Vec::new();
    for (outline, &block) in outlines
        .iter()
        .zip(blocks)
        .filter(|(outline, _)| !outline.is_empty())
    {
        cell_blocks.push(block);
        let first = points.len() as u64;
        points.extend_from_slice(outline);
        connectivity.extend(first..points.len() as u64);
        connectivity.push(first);
        offsets.push(connectivity.len() as u64);
    }
    let cells = Cells {
        types: vec![CellType::PolyLine; offsets.len()],
        cell_verts: VertexNumbers::XML {
            connectivity,
            offsets,
        },
    };
    let cell_data = vec![Attribute::DataArray(
        DataArray::scalars("block", 1).with_data(cell_blocks),
    )];
    write_unstructured_grid(path, &points, cells, Vec::new(), cell_data)
}

/// Writes a ParaView collection (`.pvd`) listing `(time, file name relative to the .pvd)` entries,
/// so ParaView plays the series with the right times.
///
/// Times are written in round-trip exact scientific notation. Fails with `InvalidInput` if a time
/// is not finite, or with the I/O error of creating or writing the file. (A run's output folder
/// has it written under a temporary name and renamed, so a run stopped while writing keeps the
/// previous collection, which a resumed run reads.)
pub fn write_collection(path: &Path, entries: &[(Real, String)]) -> std::io::Result<()> {
    if let Some((time, file)) = entries.iter().find(|(time, _)| !time.is_finite()) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("collection entry {file:?} has non-finite time {time}"),
        ));
    }
    let mut out = BufWriter::new(File::create(path)?);
    writeln!(out, r#"<?xml version="1.0"?>"#)?;
    writeln!(out, r#"<VTKFile type="Collection" version="0.1">"#)?;
    writeln!(out, "  <Collection>")?;
    for (time, file) in entries {
        writeln!(
            out,
            r#"    <DataSet timestep="{time:e}" group="" part="0" file="{}"/>"#,
            escape_xml(file)
        )?;
    }
    writeln!(out, "  </Collection>")?;
    writeln!(out, "</VTKFile>")?;
    out.flush()
}

/// Reads back a collection written by [`write_collection`]: its (time,
/// file) entries in order. Only that writer's layout is understood (one
/// `DataSet` element per line).
pub fn read_collection(path: &Path) -> std::io::Result<Vec<(Real, String)>> {
    let text = std::fs::read_to_string(path)?;
    let bad = |line: usize| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("line {}: not a collection entry written by mpdem", line + 1),
        )
    };
    let attribute = |line: &str, name: &str| -> Option<String> {
        let start = line.find(&format!(" {name}=\""))? + name.len() + 3;
        let length = line[start..].find('"')?;
        Some(line[start..start + length].to_owned())
    };
    let mut entries = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if !line.trim_start().starts_with("<DataSet") {
            continue;
        }
        let time = attribute(line, "timestep")
            .and_then(|t| t.parse::<Real>().ok())
            .ok_or_else(|| bad(k))?;
        let file = attribute(line, "file").ok_or_else(|| bad(k))?;
        entries.push((time, unescape_xml(&file)));
    }
    Ok(entries)
}

/// Writes one unstructured grid piece with the given points (z = 0), cells and point data.
fn write_unstructured_grid(
    path: &Path,
    points: &[DVec2],
    cells: Cells,
    point_data: Vec<Attribute>,
    cell_data: Vec<Attribute>,
) -> std::io::Result<()> {
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: xyz(points),
            cells,
            data: Attributes {
                point: point_data,
                cell: cell_data,
            },
        }),
    };
    let file = vtkio::xml::VTKFile::try_from(vtk).map_err(std::io::Error::other)?;
    let mut out = BufWriter::new(File::create(path)?);
    if points.is_empty() {
        // vtkio leaves out zero counts, but VTK rejects a Piece without NumberOfPoints.
        let mut xml = Vec::new();
        file.write(&mut xml).map_err(std::io::Error::other)?;
        let xml = String::from_utf8(xml).map_err(std::io::Error::other)?;
        let piece = r#"<Piece NumberOfPoints="0" NumberOfCells="0">"#;
        out.write_all(xml.replacen("<Piece>", piece, 1).as_bytes())?;
    } else {
        file.write(&mut out).map_err(std::io::Error::other)?;
    }
    out.flush()
}

/// Flattens 2D vectors into 3-component (x, y, 0) Float64 data.
fn xyz(vectors: &[DVec2]) -> IOBuffer {
    IOBuffer::F64(vectors.iter().flat_map(|v| [v.x, v.y, 0.0]).collect())
}

/// Escapes the five XML special characters for use in an attribute value.
fn escape_xml(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&apos;"),
            _ => escaped.push(c),
        }
    }
    escaped
}

fn unescape_xml(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// A fresh folder for one test, removed when dropped.
    fn test_dir(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("mpdem-io-vtk-{name}-"))
            .tempdir()
            .unwrap()
    }

    /// Reads a `.vtu` back with vtkio and returns its single inline piece.
    fn read_piece(path: &Path) -> UnstructuredGridPiece {
        let vtk = Vtk::import(path).unwrap();
        match vtk.data {
            DataSet::UnstructuredGrid { mut pieces, .. } => {
                assert_eq!(pieces.len(), 1);
                pieces.remove(0).into_loaded_piece_data(None).unwrap()
            }
            other => panic!("expected an unstructured grid, got {other:?}"),
        }
    }

    fn point_array<'a>(piece: &'a UnstructuredGridPiece, name: &str) -> &'a DataArray {
        piece
            .data
            .point
            .iter()
            .find_map(|a| match a {
                Attribute::DataArray(array) if array.name == name => Some(array),
                _ => None,
            })
            .unwrap_or_else(|| panic!("missing point array {name}"))
    }

    #[test]
    fn point_frame_round_trips_through_vtkio() {
        let positions = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.5, -2.0),
            DVec2::new(3.0, 0.25),
        ];
        let velocities = [DVec2::new(0.1, 0.2), DVec2::ZERO, DVec2::new(-1.0, 1e-12)];
        let displacements = [DVec2::ZERO, DVec2::new(0.5, 0.5), DVec2::new(1.0, -1.0)];
        let stresses = [[1.0, 2.0, 3.0, 4.0], [-1e6, -2e6, 5e5, -3e6], [0.0; 4]];
        let body = [0, 0, 1];
        let frame = PointFrame {
            positions: &positions,
            velocities: &velocities,
            displacements: &displacements,
            stresses: &stresses,
            body: &body,
            fields: &[("porosity", vec![0.3, 0.35, 0.4])],
        };
        let dir = test_dir("frame");
        let path = dir.path().join("points_0000.vtu");
        write_point_frame(&path, &frame).unwrap();

        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with(r#"<VTKFile type="UnstructuredGrid""#));
        assert!(text.contains(r#"header_type="UInt64""#));

        let piece = read_piece(&path);
        assert_eq!(piece.num_points(), 3);
        assert_eq!(piece.cells.types, vec![CellType::Vertex; 3]);
        let points = piece.points.cast_into::<f64>().unwrap();
        assert_eq!(points, vec![0.0, 0.0, 0.0, 1.5, -2.0, 0.0, 3.0, 0.25, 0.0]);

        let stress = point_array(&piece, "stress");
        assert_eq!(stress.num_comp(), 9);
        let stress = stress.data.cast_into::<f64>().unwrap();
        assert_eq!(
            &stress[9..18],
            &[-1e6, 5e5, 0.0, 5e5, -2e6, 0.0, 0.0, 0.0, -3e6]
        );

        let velocity = point_array(&piece, "velocity")
            .data
            .cast_into::<f64>()
            .unwrap();
        assert_eq!(&velocity[6..9], &[-1.0, 1e-12, 0.0]);
        let porosity = point_array(&piece, "porosity");
        assert_eq!(porosity.num_comp(), 1);
        assert_eq!(
            porosity.data.cast_into::<f64>().unwrap(),
            vec![0.3, 0.35, 0.4]
        );
        let body_read = point_array(&piece, "body");
        assert_eq!(body_read.data, IOBuffer::U32(vec![0, 0, 1]));
    }

    #[test]
    fn mismatched_columns_are_rejected() {
        let positions = [DVec2::ZERO; 2];
        let frame = PointFrame {
            positions: &positions,
            velocities: &positions,
            displacements: &positions,
            stresses: &[[0.0; 4]],
            body: &[0, 0],
            fields: &[],
        };
        let dir = test_dir("mismatch");
        let path = dir.path().join("bad.vtu");
        let err = write_point_frame(&path, &frame).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    }

    #[test]
    fn empty_frame_and_outlines_are_valid_files() {
        let dir = test_dir("empty");
        let frame = PointFrame {
            positions: &[],
            velocities: &[],
            displacements: &[],
            stresses: &[],
            body: &[],
            fields: &[],
        };
        write_point_frame(&dir.path().join("points.vtu"), &frame).unwrap();
        write_outlines(&dir.path().join("outlines.vtu"), &[], &[]).unwrap();
        for name in ["points.vtu", "outlines.vtu"] {
            let path = dir.path().join(name);
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(text.contains(r#"<Piece NumberOfPoints="0" NumberOfCells="0">"#));
            assert_eq!(read_piece(&path).num_points(), 0);
        }
    }

    #[test]
    fn outlines_are_closed_poly_lines() {
        let square = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        let triangle = vec![
            DVec2::new(2.0, 0.0),
            DVec2::new(3.0, 0.0),
            DVec2::new(2.5, 1.0),
        ];
        let dir = test_dir("outlines");
        let path = dir.path().join("blocks_0000.vtu");
        write_outlines(&path, &[square, Vec::new(), triangle], &[3, 4, 5]).unwrap();

        let piece = read_piece(&path);
        let Attribute::DataArray(block) = &piece.data.cell[0] else {
            panic!("no block array: {:?}", piece.data.cell);
        };
        assert_eq!(block.name, "block");
        assert_eq!(block.data, IOBuffer::U32(vec![3, 5]));
        assert_eq!(piece.num_points(), 7);
        assert_eq!(piece.cells.types, vec![CellType::PolyLine; 2]);
        let (connectivity, offsets) = piece.cells.cell_verts.into_xml();
        assert_eq!(connectivity, vec![0, 1, 2, 3, 0, 4, 5, 6, 4]);
        assert_eq!(offsets, vec![5, 9]);
    }

    #[test]
    fn collection_lists_times_and_files() {
        let dir = test_dir("collection");
        let path = dir.path().join("run.pvd");
        let entries = vec![
            (0.0, "frames/points_0000.vtu".to_string()),
            (0.1 + 0.2, "frames/points_0001.vtu".to_string()),
            (1.25e-7, "a&b.vtu".to_string()),
        ];
        write_collection(&path, &entries).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(r#"<VTKFile type="Collection" version="0.1">"#));
        let times: Vec<f64> = text
            .split(r#"timestep=""#)
            .skip(1)
            .map(|rest| rest.split('"').next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(times, vec![0.0, 0.1 + 0.2, 1.25e-7]);
        assert!(text.contains(r#"file="frames/points_0001.vtu""#));
        assert!(text.contains(r#"file="a&amp;b.vtu""#));
        // Read back exactly: times and files.
        assert_eq!(read_collection(&path).unwrap(), entries);

        let bad_path = path.with_file_name("bad.pvd");
        let _ = std::fs::remove_file(&bad_path);
        let bad = write_collection(&bad_path, &[(f64::NAN, "x.vtu".to_string())]).unwrap_err();
        assert_eq!(bad.kind(), std::io::ErrorKind::InvalidInput);
        assert!(!bad_path.exists());
    }
}
