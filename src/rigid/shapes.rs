//! Block shapes as the scene writes them, turned into parry shapes.

use crate::math::{DVec2, PolygonError, Real, check_convex_polygon};
use parry2d_f64::mass_properties::MassProperties;
use parry2d_f64::math::Pose;
use parry2d_f64::shape::SharedShape;
use serde::{Deserialize, Serialize};

/// The shape of a rigid block in its own frame (the block's pose places
/// that frame in the world).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum BlockShape {
    /// A rectangle centred on the frame origin.
    Cuboid {
        /// Half width and half height (m), > 0.
        half_extents: DVec2,
    },
    /// A convex polygon (vertices in either order).
    Polygon {
        /// At least three vertices (m).
        vertices: Vec<DVec2>,
    },
    /// A disk centred on the frame origin.
    Ball {
        /// Radius (m), > 0.
        radius: Real,
    },
    /// A convex polygon with rounded corners (a sphero-polygon).
    RoundPolygon {
        /// At least three vertices of the inner polygon (m).
        vertices: Vec<DVec2>,
        /// Rounding radius added all around (m), > 0.
        border_radius: Real,
    },
    /// Convex parts, each placed in the block's frame, for a non-convex block
    /// (a pile is a shaft plus a cone tip).
    Compound {
        /// The parts: shape, offset of its frame (m) and rotation (rad).
        parts: Vec<(BlockShape, DVec2, Real)>,
    },
}

impl BlockShape {
    /// The parry shape, or what is wrong with the description.
    pub fn build(&self) -> Result<SharedShape, BlockShapeError> {
        match self {
            Self::Cuboid { half_extents } => {
                if half_extents.cmpgt(DVec2::ZERO).all() && half_extents.is_finite() {
                    Ok(SharedShape::cuboid(half_extents.x, half_extents.y))
                } else {
                    Err(BlockShapeError::HalfExtents(*half_extents))
                }
            }
            Self::Polygon { vertices } => {
                check_convex(vertices)?;
                SharedShape::convex_polyline(counter_clockwise(vertices))
                    .ok_or(BlockShapeError::Polygon(PolygonError::NoArea))
            }
            Self::Ball { radius } => {
                if radius.is_finite() && *radius > 0.0 {
                    Ok(SharedShape::ball(*radius))
                } else {
                    Err(BlockShapeError::Radius(*radius))
                }
            }
            Self::RoundPolygon {
                vertices,
                border_radius,
            } => {
                check_convex(vertices)?;
                if !(border_radius.is_finite() && *border_radius > 0.0) {
                    return Err(BlockShapeError::BorderRadius(*border_radius));
                }
                SharedShape::round_convex_polyline(counter_clockwise(vertices), *border_radius)
                    .ok_or(BlockShapeError::Polygon(PolygonError::NoArea))
            }
            Self::Compound { parts } => {
                if parts.is_empty() {
                    return Err(BlockShapeError::EmptyCompound);
                }
                let mut built = Vec::with_capacity(parts.len());
                for (k, (shape, offset, angle)) in parts.iter().enumerate() {
                    if matches!(shape, Self::Compound { .. }) {
                        return Err(BlockShapeError::NestedCompound(k));
                    }
                    if !(offset.is_finite() && angle.is_finite()) {
                        return Err(BlockShapeError::PartPlacement(k));
                    }
                    let part = shape.build().map_err(|e| BlockShapeError::Part {
                        part: k,
                        error: Box::new(e),
                    })?;
                    built.push((Pose::new(*offset, *angle), part));
                }
                Ok(SharedShape::compound(built))
            }
        }
    }
}

impl BlockShape {
    /// Mass properties at `density` of the shape `built` from this
    /// description. Parry leaves the border of a rounded polygon out of its
    /// mass, so rounded polygons (alone or as compound parts) are measured
    /// on their rounded outline instead.
    pub fn mass_properties(&self, built: &SharedShape, density: Real) -> MassProperties {
        match self {
            Self::RoundPolygon {
                vertices,
                border_radius,
            } => MassProperties::from_convex_polygon(
                density,
                &rounded_outline(&counter_clockwise(vertices), *border_radius),
            ),
            Self::Compound { parts } => match built.as_compound() {
                Some(compound) => parts
                    .iter()
                    .zip(compound.shapes())
                    .map(|((part, _, _), (pose, shape))| {
                        part.mass_properties(shape, density).transform_by(pose)
                    })
                    .sum(),
                None => built.mass_properties(density),
            },
            _ => built.mass_properties(density),
        }
    }

    /// Closed outlines of the shape in its frame, for pictures (VTK, PNG):
    /// one per convex part; disks and rounded corners as 32-gons.
    pub fn outline(&self) -> Vec<Vec<DVec2>> {
        const SEGMENTS: usize = 32;
        let circle = |center: DVec2, radius: Real| -> Vec<DVec2> {
            (0..SEGMENTS)
                .map(|k| {
                    center
                        + radius
                            * DVec2::from_angle(
                                k as Real * std::f64::consts::TAU / SEGMENTS as Real,
                            )
                })
                .collect()
        };
        match self {
            Self::Cuboid { half_extents: h } => {
                vec![vec![
                    DVec2::new(-h.x, -h.y),
                    DVec2::new(h.x, -h.y),
                    DVec2::new(h.x, h.y),
                    DVec2::new(-h.x, h.y),
                ]]
            }
            Self::Polygon { vertices } => vec![vertices.clone()],
            Self::Ball { radius } => vec![circle(DVec2::ZERO, *radius)],
            Self::RoundPolygon {
                vertices,
                border_radius,
            } => vec![rounded_outline(
                &counter_clockwise(vertices),
                *border_radius,
            )],
            Self::Compound { parts } => parts
                .iter()
                .flat_map(|(shape, offset, angle)| {
                    let turn = DVec2::from_angle(*angle);
                    shape.outline().into_iter().map(move |line| {
                        line.into_iter().map(|p| *offset + turn.rotate(p)).collect()
                    })
                })
                .collect(),
        }
    }
}

/// The vertices in counter-clockwise order, as parry's convex polygons need
/// them (it takes each face's outward normal to the right of its edge).
fn counter_clockwise(vertices: &[DVec2]) -> Vec<DVec2> {
    let twice_area: Real = (0..vertices.len())
        .map(|k| vertices[k].perp_dot(vertices[(k + 1) % vertices.len()]))
        .sum();
    let mut ordered = vertices.to_vec();
    if twice_area < 0.0 {
        ordered.reverse();
    }
    ordered
}

/// The outline of a convex polygon (counter-clockwise) grown by `radius`:
/// each edge pushed out along its normal, joined by arcs around the
/// vertices (8 segments per arc).
fn rounded_outline(vertices: &[DVec2], radius: Real) -> Vec<DVec2> {
    const ARC_SEGMENTS: usize = 8;
    let n = vertices.len();
    let normal = |k: usize| (vertices[(k + 1) % n] - vertices[k]).normalize().perp() * -1.0;
    let mut outline = Vec::with_capacity(n * (ARC_SEGMENTS + 1));
    for (k, vertex) in vertices.iter().enumerate() {
        let (from, to) = (normal((k + n - 1) % n), normal(k));
        let sweep = from.angle_to(to).rem_euclid(std::f64::consts::TAU);
        for s in 0..=ARC_SEGMENTS {
            let turn = DVec2::from_angle(sweep * s as Real / ARC_SEGMENTS as Real);
            outline.push(*vertex + radius * turn.rotate(from));
        }
    }
    outline
}

/// A convex polygon as [`check_convex_polygon`] wants it; a non-convex one
/// is refused with the advice to build the block from convex parts.
fn check_convex(vertices: &[DVec2]) -> Result<(), BlockShapeError> {
    check_convex_polygon(vertices).map_err(|e| match e {
        PolygonError::NotConvex { .. } => BlockShapeError::NotConvex(e),
        e => BlockShapeError::Polygon(e),
    })
}

/// What is wrong with a block's shape.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BlockShapeError {
    /// A cuboid's half extents are not positive.
    #[error("cuboid half_extents must be > 0, got {0}")]
    HalfExtents(DVec2),
    /// A ball's radius is not positive.
    #[error("ball radius must be > 0, got {0}")]
    Radius(Real),
    /// A rounded polygon's border radius is not positive.
    #[error("border_radius must be > 0, got {0}")]
    BorderRadius(Real),
    /// The polygon is degenerate.
    #[error(transparent)]
    Polygon(PolygonError),
    /// The polygon is not convex.
    #[error("{0}: split it into convex parts with a Compound")]
    NotConvex(PolygonError),
    /// A compound without parts.
    #[error("a compound needs at least one part")]
    EmptyCompound,
    /// A compound inside a compound.
    #[error("part {0}: a compound cannot contain a compound")]
    NestedCompound(usize),
    /// A part's offset or angle is not finite.
    #[error("part {0}: its offset and angle must be finite")]
    PartPlacement(usize),
    /// A part is wrong.
    #[error("part {part}: {error}")]
    Part {
        /// The part's index.
        part: usize,
        /// What is wrong with it.
        error: Box<BlockShapeError>,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_build_and_non_convex_polygons_are_refused() {
        let square = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        assert!(
            BlockShape::Polygon {
                vertices: square.clone()
            }
            .build()
            .is_ok()
        );
        let dart = vec![
            DVec2::ZERO,
            DVec2::new(2.0, 0.0),
            DVec2::new(1.0, 0.3),
            DVec2::new(1.0, 2.0),
        ];
        let e = BlockShape::Polygon { vertices: dart }
            .build()
            .err()
            .unwrap();
        assert!(matches!(e, BlockShapeError::NotConvex(_)), "{e}");
        assert!(e.to_string().contains("Compound"), "{e}");
        let pile = BlockShape::Compound {
            parts: vec![
                (
                    BlockShape::Cuboid {
                        half_extents: DVec2::new(0.4, 3.0),
                    },
                    DVec2::new(0.0, 3.0),
                    0.0,
                ),
                (
                    BlockShape::Polygon {
                        vertices: vec![
                            DVec2::new(-0.4, 0.0),
                            DVec2::new(0.0, -0.7),
                            DVec2::new(0.4, 0.0),
                        ],
                    },
                    DVec2::ZERO,
                    0.0,
                ),
            ],
        };
        let shape = pile.build().unwrap();
        let props = shape.mass_properties(1.0);
        assert!((props.mass() - (0.8 * 6.0 + 0.5 * 0.8 * 0.7)).abs() < 1e-9);
    }

    #[test]
    fn clockwise_polygons_and_rounded_masses() {
        // A clockwise square gives the same solid as the counter-clockwise one.
        let ccw = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let cw: Vec<DVec2> = ccw.iter().rev().copied().collect();
        let a = BlockShape::Polygon {
            vertices: ccw.clone(),
        }
        .build()
        .unwrap();
        let b = BlockShape::Polygon { vertices: cw }.build().unwrap();
        let inside = parry2d_f64::math::Pose::IDENTITY;
        for shape in [&a, &b] {
            assert!(shape.contains_point(&inside, DVec2::splat(0.5)));
            assert!(!shape.contains_point(&inside, DVec2::splat(1.5)));
        }
        // Rounded unit square, r = 0.1: area 1 + 4 r + π r² (polygonal arcs
        // of 8 segments lose (1 − sin(π/8)/(π/8)) of the corner area).
        let round = BlockShape::RoundPolygon {
            vertices: ccw,
            border_radius: 0.1,
        };
        let mass = round.mass_properties(&round.build().unwrap(), 1.0).mass();
        let exact = 1.0 + 0.4 + std::f64::consts::PI * 0.01;
        assert!((mass / exact - 1.0).abs() < 2e-3, "{mass} vs {exact}");
    }
}
