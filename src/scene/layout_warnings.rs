//! Warnings about where the bodies start: layouts that are valid but that
//! a run will not survive, or will start with a jolt the user did not mean.

use crate::components::MaterialPoints;
use crate::math::{DVec2, Real};
use crate::resources::{BodyPairLaw, Grid};
use crate::scene::Scene;
use crate::warning::{Warning, WarningKind};
use std::collections::HashMap;

/// How close (in cells) a body's points' domains may come to an open grid
/// edge before it counts as touching: round-off of a body placed on the
/// edge, far below any distance a user means.
const TOUCH: Real = 1e-6;

/// Smallest overlap of two contact disks, as a fraction of their radii's
/// sum, that counts: bodies placed exactly touching overlap by round-off
/// (1e-17 m seen), which is no overlap the user made.
const ROUND_OFF_OVERLAP: Real = 1e-9;

/// A warning for each body whose points' domains touch an open (`Free`)
/// grid edge that gravity does not pull it away from: nothing holds the
/// body there, and the run stops if its points' shape functions reach past
/// the edge (a body resting on the grid's bottom edge under gravity does so
/// at its second step). `grid` has the edges the run starts with (the
/// first stage may set them), `gravity` is the starting gravity, `bodies`
/// are (name, points) in scene order.
pub fn free_edge_warnings(
    grid: &Grid,
    gravity: DVec2,
    bodies: &[(&str, &MaterialPoints)],
) -> Vec<Warning> {
    let touch = TOUCH * grid.cell_size;
    let mut warnings = Vec::new();
    for (name, points) in bodies {
        let (low, high) = points.position.iter().zip(&points.half_size).fold(
            (DVec2::INFINITY, DVec2::NEG_INFINITY),
            |(low, high), (x, h)| (low.min(*x - *h), high.max(*x + *h)),
        );
        for edge in grid.edges_around(low, high) {
            // Gravity against the outward normal pulls the body off the edge.
            let pulled_off = gravity.dot(edge.outward) < 0.0;
            if !edge.condition.is_wall() && edge.gap <= touch && !pulled_off {
                let (edge, at) = (edge.name, edge.at);
                warnings.push(Warning::new(WarningKind::Layout, format!("bodies[\"{name}\"]"), format!(
                    "body '{name}' touches the grid's {edge} edge {at}, which is Free (the default, unless grid.edges or the first stage's edges set it): nothing holds the body there, and the run stops if a point's shape functions reach past the edge; give it a wall (Slip or Fixed) or extend the grid"
                )));
            }
        }
    }
    warnings
}

/// A warning for each pair of bodies under a contact law whose points'
/// contact disks overlap at the start: the law's springs then push the
/// bodies apart at once, with a force the user did not set up (k_n δ per
/// pair, δ up to the disks' diameter). `bodies` are (name, points) in
/// scene order, `laws` the scene's body pairs with a law.
pub fn body_overlap_warnings(
    bodies: &[(&str, &MaterialPoints)],
    laws: &[BodyPairLaw],
) -> Vec<Warning> {
    let mut warnings = Vec::new();
    for law in laws {
        let (a, b) = (&bodies[law.a as usize], &bodies[law.b as usize]);
        let (pairs, deepest) = overlapping_disks(a.1, b.1);
        if pairs > 0 {
            warnings.push(Warning::new(WarningKind::Layout, "body_contacts", format!(
                "bodies '{}' and '{}' overlap at the start: {pairs} pairs of their points' contact disks overlap, the deepest by {deepest:.3e} m; their contact law pushes them apart at once: move them apart by at least that",
                a.0, b.0
            )));
        }
    }
    warnings
}

/// A warning for each body's constraint region that holds no node of the
/// grid (outside it, or between two nodes): it constrains nothing.
pub fn empty_region_warnings(scene: &Scene) -> Vec<Warning> {
    let grid = scene.grid.grid();
    let h = grid.cell_size;
    let cells = [grid.cells[0] as Real, grid.cells[1] as Real];
    let tolerance = 1e-9;
    let mut warnings = Vec::new();
    for body in &scene.bodies {
        for (k, region) in body.constraints.iter().enumerate() {
            let (lo, hi) = (
                (region.min - grid.origin) / h,
                (region.max - grid.origin) / h,
            );
            let holds = |axis: usize| {
                let first = (lo[axis] - tolerance).ceil().max(0.0);
                let last = (hi[axis] + tolerance).floor().min(cells[axis]);
                first <= last
            };
            if !(holds(0) && holds(1)) {
                warnings.push(Warning::new(
                    WarningKind::Layout,
                    format!("bodies[\"{}\"].constraints", body.name),
                    format!(
                        "body '{}': constraint region {} ({} to {}) holds no node of the grid, which spans {} to {}: it constrains nothing",
                        body.name,
                        k + 1,
                        region.min,
                        region.max,
                        grid.origin,
                        grid.max()
                    ),
                ));
            }
        }
    }
    warnings
}

/// The pairs of points of `a` and `b` whose contact disks overlap (beyond
/// round-off, [`ROUND_OFF_OVERLAP`]), and the
/// deepest overlap (m): `b`'s points binned in square buckets as wide as
/// the widest disk diameter, so each of `a`'s points looks at the 3 × 3
/// buckets around it.
fn overlapping_disks(a: &MaterialPoints, b: &MaterialPoints) -> (usize, Real) {
    let widest = |p: &MaterialPoints| p.contact_radius.iter().copied().fold(0.0, Real::max);
    let bucket = 2.0 * widest(a).max(widest(b));
    if bucket <= 0.0 || a.is_empty() || b.is_empty() {
        return (0, 0.0);
    }
    let key = |x: DVec2| ((x.x / bucket).floor() as i64, (x.y / bucket).floor() as i64);
    let mut buckets: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (j, x) in b.position.iter().enumerate() {
        buckets.entry(key(*x)).or_default().push(j);
    }
    let (mut pairs, mut deepest) = (0, 0.0);
    for (i, x) in a.position.iter().enumerate() {
        let (kx, ky) = key(*x);
        for (dx, dy) in (-1..=1).flat_map(|dx| (-1..=1).map(move |dy| (dx, dy))) {
            for &j in buckets.get(&(kx + dx, ky + dy)).into_iter().flatten() {
                let reach = a.contact_radius[i] + b.contact_radius[j];
                let overlap = reach - x.distance(b.position[j]);
                if overlap > ROUND_OFF_OVERLAP * reach {
                    pairs += 1;
                    deepest = Real::max(deepest, overlap);
                }
            }
        }
    }
    (pairs, deepest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::NewPoint;
    use crate::contact::ContactLaw;
    use crate::math::SymTensor;
    use crate::resources::EdgeCondition;

    /// A row of `n` points spaced 1 from `start` along x, domains of
    /// half-size ½ and contact disks of radius ½ (touching neighbours).
    fn row(start: DVec2, n: usize) -> MaterialPoints {
        let mut points = MaterialPoints::default();
        for k in 0..n {
            points.push(NewPoint {
                position: start + DVec2::new(k as Real, 0.0),
                velocity: DVec2::ZERO,
                volume: 1.0,
                mass: 1.0,
                half_size: DVec2::splat(0.5),
                stress: SymTensor::ZERO,
                contact_radius: 0.5,
            });
        }
        points
    }

    #[test]
    fn a_body_on_a_free_edge_is_named_with_the_edge_and_one_on_a_wall_is_not() {
        let mut grid = Grid {
            origin: DVec2::ZERO,
            cell_size: 1.0,
            cells: [10, 10],
            edges: Default::default(),
        };
        let down = DVec2::new(0.0, -9.81);
        let resting = row(DVec2::new(2.0, 0.5), 3);
        let lifted = row(DVec2::new(2.0, 0.5 + 1e-3), 3);
        let bodies = [("slab", &resting), ("lifted", &lifted)];
        let warnings = free_edge_warnings(&grid, down, &bodies);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0]
                .message
                .contains("body 'slab' touches the grid's bottom edge y = 0")
        );
        // Hanging from the top edge: gravity pulls it off, unless it points up.
        let hanging = row(DVec2::new(2.0, 9.5), 3);
        assert!(free_edge_warnings(&grid, down, &[("hanging", &hanging)]).is_empty());
        let up = free_edge_warnings(&grid, -down, &[("hanging", &hanging)]);
        assert!(
            up[0]
                .message
                .contains("body 'hanging' touches the grid's top edge y = 10"),
            "{up:?}"
        );
        grid.edges.bottom = EdgeCondition::Slip;
        assert!(free_edge_warnings(&grid, down, &[("slab", &resting)]).is_empty());
    }

    #[test]
    fn overlapping_bodies_under_a_law_are_named_with_their_deepest_overlap() {
        let below = row(DVec2::ZERO, 10);
        // Touching, up to round-off (an overlap of 1e-15).
        let touching = row(DVec2::new(0.0, 1.0 - 1e-15), 10);
        let into = row(DVec2::new(0.25, 0.75), 10);
        let law = |a, b| BodyPairLaw {
            a,
            b,
            law: ContactLaw {
                normal_stiffness: 1.0,
                tangential_stiffness: 1.0,
                friction: 0.0,
                normal_damping: 0.0,
            },
        };
        let bodies = [("below", &below), ("touching", &touching), ("into", &into)];
        let warnings = body_overlap_warnings(&bodies, &[law(0, 1)]);
        assert!(warnings.is_empty(), "disks that only touch: {warnings:?}");
        let warnings = body_overlap_warnings(&bodies, &[law(0, 1), law(0, 2)]);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        // Each point of `into` reaches one of `below`'s, √(0.25² + 0.75²) =
        // 0.791 away (the next is 1.06 away): δ = 1 − 0.791 = 0.209.
        assert!(
            warnings[0]
                .message
                .contains("bodies 'below' and 'into' overlap at the start: 10 pairs")
                && warnings[0].message.contains("2.094e-1 m"),
            "{warnings:?}"
        );
    }
}
