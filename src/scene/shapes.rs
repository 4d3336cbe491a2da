//! Body outlines and the filling of an outline with material points.

use super::point_file::ListedPoint;
use crate::math::{DVec2, PolygonError, Real, check_convex_polygon};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The outline of a body. Points are placed at the sub-cell centres of the
/// grid cells (points_per_cell × points_per_cell per cell) that fall inside,
/// except for `Points`, which lists them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shape {
    /// An axis-aligned rectangle.
    Rectangle {
        /// Lower-left corner (m).
        min: DVec2,
        /// Upper-right corner (m).
        max: DVec2,
    },
    /// A convex polygon, vertices in either winding order.
    Polygon {
        /// At least three vertices (m).
        vertices: Vec<DVec2>,
    },
    /// A full disk.
    Disk {
        /// Centre (m).
        center: DVec2,
        /// Radius (m), > 0.
        radius: Real,
    },
    /// An annulus.
    Ring {
        /// Centre (m).
        center: DVec2,
        /// Inner radius (m), ≥ 0.
        inner_radius: Real,
        /// Outer radius (m), > inner radius.
        outer_radius: Real,
    },
    /// The points listed in a CSV file (see the scene format's point lists), e.g.
    /// `Points(file: "soil.csv")`: a header naming the columns `x`, `y` and
    /// optionally `volume`, then one point per line. Without a volume
    /// column each point gets the lattice's volume, (h / n)²; each point's
    /// uGIMP domain is a square of that area (half-size √V / 2), and its
    /// default DEM disk reaches the square's sides.
    Points {
        /// The file, relative to the scene file's folder.
        file: String,
        /// The points, read from `file` when the scene is loaded
        /// ([`super::Scene::read_point_files`]); a scene built in code may
        /// fill them directly. Not serialized: a written scene names the
        /// file only.
        #[serde(skip)]
        points: Vec<ListedPoint>,
    },
}

impl Shape {
    /// Checks the geometry: finite coordinates, ordered corners, positive
    /// radii, a convex polygon; a point list that has been read, with
    /// finite positions and positive volumes.
    pub fn check(&self) -> Result<(), ShapeError> {
        if let Self::Points { file, points } = self
            && points.is_empty()
        {
            return Err(ShapeError::Unread(file.clone()));
        }
        // Too few vertices have no bounds to speak of: say what is missing.
        if let Self::Polygon { vertices } = self
            && vertices.len() < 3
        {
            check_convex_polygon(vertices)?;
        }
        let (lo, hi) = self.bounds();
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(ShapeError::NotFinite { lo, hi });
        }
        match self {
            Self::Rectangle { min, max } => {
                if !(min.cmplt(*max).all() && min.is_finite() && max.is_finite()) {
                    return Err(ShapeError::Corners {
                        min: *min,
                        max: *max,
                    });
                }
            }
            Self::Polygon { vertices } => check_convex_polygon(vertices)?,
            Self::Disk { radius, .. } => {
                if !(radius.is_finite() && *radius > 0.0) {
                    return Err(ShapeError::Radius(*radius));
                }
            }
            Self::Ring {
                inner_radius,
                outer_radius,
                ..
            } => {
                if !(*inner_radius >= 0.0
                    && outer_radius > inner_radius
                    && outer_radius.is_finite())
                {
                    return Err(ShapeError::Radii {
                        inner: *inner_radius,
                        outer: *outer_radius,
                    });
                }
            }
            Self::Points { file, points } => {
                if let Some(p) = points.iter().find(|p| {
                    !p.position.is_finite() || p.volume.is_some_and(|v| !(v > 0.0 && v.is_finite()))
                }) {
                    return Err(ShapeError::ListedPoint {
                        file: file.clone(),
                        at: p.position,
                        volume: p.volume,
                    });
                }
            }
        }
        Ok(())
    }

    /// About how many points a lattice of spacing `spacing` puts in the
    /// shape, without making them: area / spacing² plus one row along the
    /// outline (perimeter / spacing) and one; a point list's length.
    pub fn point_estimate(&self, spacing: Real) -> Real {
        let (area, perimeter) = match self {
            Self::Rectangle { min, max } => {
                let size = *max - *min;
                (size.x * size.y, 2.0 * (size.x + size.y))
            }
            Self::Polygon { vertices } => {
                let edges =
                    (0..vertices.len()).map(|k| (vertices[k], vertices[(k + 1) % vertices.len()]));
                let twice_area: Real = edges.clone().map(|(a, b)| a.perp_dot(b)).sum();
                (
                    0.5 * twice_area.abs(),
                    edges.map(|(a, b)| a.distance(b)).sum(),
                )
            }
            Self::Disk { radius, .. } => (PI * radius * radius, 2.0 * PI * radius),
            Self::Ring {
                inner_radius,
                outer_radius,
                ..
            } => (
                PI * (outer_radius * outer_radius - inner_radius * inner_radius),
                2.0 * PI * (outer_radius + inner_radius),
            ),
            Self::Points { points, .. } => return points.len() as Real,
        };
        area / (spacing * spacing) + perimeter / spacing + 1.0
    }

    /// Lower-left and upper-right corners of the bounding box.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        match self {
            Self::Rectangle { min, max } => (*min, *max),
            Self::Polygon { vertices } => vertices.iter().fold(
                (
                    DVec2::splat(Real::INFINITY),
                    DVec2::splat(Real::NEG_INFINITY),
                ),
                |(lo, hi), v| (lo.min(*v), hi.max(*v)),
            ),
            Self::Disk { center, radius } => (*center - *radius, *center + *radius),
            Self::Ring {
                center,
                outer_radius,
                ..
            } => (*center - *outer_radius, *center + *outer_radius),
            Self::Points { points, .. } => points.iter().fold(
                (
                    DVec2::splat(Real::INFINITY),
                    DVec2::splat(Real::NEG_INFINITY),
                ),
                |(lo, hi), p| (lo.min(p.position), hi.max(p.position)),
            ),
        }
    }

    /// The box the body's material occupies: the outline's bounds, or for a
    /// point list the box around its points' domains
    /// (`point_file::domain_bounds`, `spacing` h / n for points
    /// without a volume).
    pub fn extent(&self, spacing: Real) -> (DVec2, DVec2) {
        match self {
            Self::Points { points, .. } => super::point_file::domain_bounds(points, spacing),
            _ => self.bounds(),
        }
    }

    /// Whether `p` is inside (boundary included); for a point list, whether
    /// `p` is one of its points.
    pub fn contains(&self, p: DVec2) -> bool {
        match self {
            Self::Rectangle { min, max } => p.cmpge(*min).all() && p.cmple(*max).all(),
            Self::Polygon { vertices } => {
                let sides = (0..vertices.len()).map(|k| {
                    let (a, b) = (vertices[k], vertices[(k + 1) % vertices.len()]);
                    (b - a).perp_dot(p - a)
                });
                let (mut left, mut right) = (false, false);
                for s in sides {
                    left |= s > 0.0;
                    right |= s < 0.0;
                }
                !(left && right)
            }
            Self::Disk { center, radius } => p.distance_squared(*center) <= radius * radius,
            Self::Ring {
                center,
                inner_radius,
                outer_radius,
            } => {
                let r2 = p.distance_squared(*center);
                r2 >= inner_radius * inner_radius && r2 <= outer_radius * outer_radius
            }
            Self::Points { points, .. } => points.iter().any(|q| q.position == p),
        }
    }

    /// The body's points: a point list's, or [`Self::fill`]'s lattice
    /// without volumes (the lattice's (h / n)²).
    pub fn points(&self, origin: DVec2, h: Real, points_per_cell: u32) -> Vec<ListedPoint> {
        match self {
            Self::Points { points, .. } => points.clone(),
            _ => self
                .fill(origin, h, points_per_cell)
                .into_iter()
                .map(|position| ListedPoint {
                    position,
                    volume: None,
                    line: 0,
                })
                .collect(),
        }
    }

    /// Point positions filling the shape: the centres of an n × n split of
    /// every grid cell (grid origin `origin`, cell size `h`) that lie inside;
    /// a point list's positions.
    pub fn fill(&self, origin: DVec2, h: Real, points_per_cell: u32) -> Vec<DVec2> {
        if let Self::Points { points, .. } = self {
            return points.iter().map(|p| p.position).collect();
        }
        let (lo, hi) = self.bounds();
        let n = points_per_cell as Real;
        let first = ((lo - origin) / h).floor();
        let last = ((hi - origin) / h).ceil();
        // The points are stored tile by tile (the scatter's tiles of stencil
        // base nodes), row by row within a tile, so that the scatter visits
        // a body that has not flowed in the order it is stored. A point's
        // base node is floor(s − ½) in cells (every kernel's, away from the
        // grid's edges); it grows with the point's row and column, so each
        // tile holds a run of consecutive point rows and columns.
        let runs = |first: i64, last: i64, tile: usize| {
            let lines: Vec<(i64, u32)> = (first..last)
                .flat_map(|cell| (0..points_per_cell).map(move |sub| (cell, sub)))
                .collect();
            let tile_of = |&(cell, sub): &(i64, u32)| {
                (cell - i64::from(2 * sub + 1 < points_per_cell)).div_euclid(tile as i64)
            };
            let mut runs: Vec<Vec<(i64, u32)>> = Vec::new();
            for pair in lines.chunk_by(|a, b| tile_of(a) == tile_of(b)) {
                runs.push(pair.to_vec());
            }
            runs
        };
        let [tile_x, tile_y] = crate::scatter::TILE_CELLS;
        let (columns, rows) = (
            runs(first.x as i64, last.x as i64, tile_x),
            runs(first.y as i64, last.y as i64, tile_y),
        );
        let mut points = Vec::new();
        for tile_rows in &rows {
            for tile_columns in &columns {
                for &(j, b) in tile_rows {
                    for &(i, a) in tile_columns {
                        let local = DVec2::new((a as Real + 0.5) / n, (b as Real + 0.5) / n);
                        let p = origin + (DVec2::new(i as Real, j as Real) + local) * h;
                        if self.contains(p) {
                            points.push(p);
                        }
                    }
                }
            }
        }
        points
    }
}

/// What is wrong with a body's shape.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShapeError {
    /// A point list not read, or empty.
    #[error("the point list '{0}' has not been read (Scene::read_point_files) or is empty")]
    Unread(String),
    /// Coordinates not finite.
    #[error("shape coordinates must be finite, got bounds {lo} to {hi}")]
    NotFinite {
        /// The lower corner of the bounds.
        lo: DVec2,
        /// The upper corner.
        hi: DVec2,
    },
    /// A rectangle's corners out of order.
    #[error("rectangle needs min < max in x and y, got min {min}, max {max}")]
    Corners {
        /// Its `min`.
        min: DVec2,
        /// Its `max`.
        max: DVec2,
    },
    /// A polygon that is not convex, or degenerate.
    #[error(transparent)]
    Polygon(#[from] PolygonError),
    /// A disk's radius not positive.
    #[error("disk radius must be > 0, got {0}")]
    Radius(Real),
    /// A ring's radii out of order.
    #[error("ring needs 0 ≤ inner_radius < outer_radius, got {inner} and {outer}")]
    Radii {
        /// Its inner radius.
        inner: Real,
        /// Its outer radius.
        outer: Real,
    },
    /// A listed point with a position not finite or a volume not positive.
    #[error(
        "point list '{file}': the point at {at} has volume {volume:?}; positions must be finite and volumes > 0"
    )]
    ListedPoint {
        /// The list's file.
        file: String,
        /// The point's position.
        at: DVec2,
        /// Its volume.
        volume: Option<Real>,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_fill_is_exact() {
        let s = Shape::Rectangle {
            min: DVec2::ZERO,
            max: DVec2::new(1.0, 0.5),
        };
        let pts = s.fill(DVec2::ZERO, 0.1, 2);
        assert_eq!(pts.len(), 10 * 5 * 4);
        assert!((pts[0] - DVec2::splat(0.025)).length() < 1e-15);
    }

    #[test]
    fn ring_and_polygon_membership() {
        let ring = Shape::Ring {
            center: DVec2::ZERO,
            inner_radius: 1.0,
            outer_radius: 2.0,
        };
        assert!(ring.contains(DVec2::new(1.5, 0.0)) && !ring.contains(DVec2::new(0.5, 0.0)));
        let tri = Shape::Polygon {
            vertices: vec![DVec2::ZERO, DVec2::X, DVec2::Y],
        };
        assert!(tri.check().is_ok());
        assert!(tri.contains(DVec2::splat(0.2)) && !tri.contains(DVec2::splat(0.8)));
        let dart = Shape::Polygon {
            vertices: vec![
                DVec2::ZERO,
                DVec2::new(2.0, 0.0),
                DVec2::new(1.0, 0.3),
                DVec2::new(1.0, 2.0),
            ],
        };
        assert!(dart.check().unwrap_err().to_string().contains("not convex"));
    }
}
