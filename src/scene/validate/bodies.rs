//! The bodies: their materials, points and initial state.

use super::{Locator, nth_name, quoted};
use crate::math::Real;
use crate::rules;
use crate::scene::{
    BodySpec, InitialStress, InitialVelocity, ListedPoint, Scene, SceneError, Shape, VelocityField,
};
use std::collections::BTreeSet;

/// Largest points-per-cell count: 8 × 8 = 64 points per cell is already far
/// beyond what MPM accuracy gains from; larger counts are almost surely typos.
const MAX_POINTS_PER_CELL: u32 = 8;

/// Most material points a scene may have: a point takes about 500 bytes
/// (its columns, its stencil, its place in the scatter order), so 2e7
/// points take 10 GB, beyond what a 2D run on one machine can use; such
/// counts come from a cell size or `points_per_cell` typed wrong.
const MAX_POINTS: u128 = 20_000_000;

/// Largest body acceleration (m/s²): 10⁴ times what pushes the Hertz disks
/// together (10⁸ m/s² on millimetre disks); beyond it a value is a slip.
const MAX_BODY_ACCELERATION: Real = 1e12;

impl Scene {
    /// The bodies against the grid and the materials; returns their names.
    pub(super) fn check_bodies<'s>(
        &'s self,
        v: &Locator,
        material_names: &BTreeSet<&'s str>,
    ) -> Result<BTreeSet<&'s str>, SceneError> {
        if self.bodies.is_empty() && self.blocks.is_empty() {
            let message = "the scene has nothing to simulate: expected a body in `bodies` or a block in `blocks`";
            return Err(v.invalid(&["bodies"], message.into()));
        }
        let mut body_names = BTreeSet::new();
        let mut total_points: Real = 0.0;
        for (k, b) in self.bodies.iter().enumerate() {
            let fail = v.entry("bodies", "body", &b.name);
            if !body_names.insert(b.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("bodies", k),
                    format!("body name '{}' is used twice", b.name),
                ));
            }
            if let Some(load) = b.acceleration
                && !(load.value.is_finite()
                    && load.value.length() <= MAX_BODY_ACCELERATION
                    && load.ramp_time.is_finite()
                    && load.ramp_time >= 0.0)
            {
                return Err(fail(
                    "acceleration",
                    format!(
                        "acceleration must be finite and at most {MAX_BODY_ACCELERATION:e} m/s², with ramp_time ≥ 0, got ({}, {}) over {} s",
                        rules::shown(load.value.x),
                        rules::shown(load.value.y),
                        rules::shown(load.ramp_time)
                    ),
                ));
            }
            if !material_names.contains(b.material.as_str()) {
                return Err(fail(
                    "material",
                    format!(
                        "unknown material '{}'; expected one of {:?}",
                        b.material, material_names
                    ),
                ));
            }
            if !(1..=MAX_POINTS_PER_CELL).contains(&b.points_per_cell) {
                return Err(fail(
                    "points_per_cell",
                    format!(
                        "points_per_cell must be 1 to {MAX_POINTS_PER_CELL}, got {}",
                        b.points_per_cell
                    ),
                ));
            }
            b.shape.check().map_err(|e| fail("shape", e.to_string()))?;
            let points = self.check_body_points(v, b, total_points)?;
            total_points += points.len() as Real;
            self.check_body_initial_state(v, b, &points)?;
        }

        if let Some(r) = contact_radius_error(self) {
            return Err(v.invalid(&["bodies", &quoted(&r.0), "contact_radius"], r.1));
        }
        Ok(body_names)
    }

    /// A body's points, made from its shape: within the cap on the scene's
    /// points (`total_points` made before it), inside the grid less the
    /// kernel's margin, a listed point's domain no larger than a cell, and
    /// at least one.
    pub(super) fn check_body_points(
        &self,
        v: &Locator,
        b: &BodySpec,
        total_points: Real,
    ) -> Result<Vec<ListedPoint>, SceneError> {
        let grid = &self.grid;
        let (grid_min, grid_max) = (grid.origin, grid.max());
        let margin = self.settings.shape_function.required_margin_cells() * grid.cell_size;
        let fail = v.entry("bodies", "body", &b.name);
        // Estimated from the shape before its points are made.
        let estimate = b
            .shape
            .point_estimate(grid.cell_size / Real::from(b.points_per_cell));
        if total_points + estimate > MAX_POINTS as Real {
            return Err(fail(
                "shape",
                format!(
                    "about {estimate:.3e} points at {} per cell of {} m{}: more than the {MAX_POINTS} a scene may hold",
                    b.points_per_cell,
                    grid.cell_size,
                    if total_points > 0.0 {
                        format!(
                            ", {:.3e} with the bodies before it",
                            total_points + estimate
                        )
                    } else {
                        String::new()
                    }
                ),
            ));
        }
        let points = b
            .shape
            .points(grid.origin, grid.cell_size, b.points_per_cell);
        let spacing = grid.cell_size / Real::from(b.points_per_cell);
        // A listed point's whole domain must be inside (a lattice's
        // points are inside their outline by construction), and no
        // larger than a cell: uGIMP's three-node stencil needs l ≤ h / 2.
        if let Shape::Points { file, .. } = &b.shape {
            let cell = grid.cell_size * grid.cell_size;
            if let Some((p, volume)) = points
                .iter()
                .map(|p| (p, p.domain(spacing).0))
                .find(|&(_, volume)| volume > cell)
            {
                return Err(fail(
                    "shape",
                    format!(
                        "the point at {} in '{file}'{} has volume {volume}, more than a cell ({cell}): its domain would reach beyond the nodes next to it",
                        p.position,
                        p.at_line(),
                    ),
                ));
            }
        }
        let (lo, hi) = b.shape.extent(spacing);
        let (inner_min, inner_max) = (grid_min + margin, grid_max - margin);
        if lo.cmplt(inner_min).any() || hi.cmpgt(inner_max).any() {
            // For a point list, the first point past the edge and its line.
            let outside = points.iter().find(|p| {
                let half = p.domain(spacing).1;
                (p.position - half).cmplt(inner_min).any()
                    || (p.position + half).cmpgt(inner_max).any()
            });
            let which = match (&b.shape, outside) {
                (Shape::Points { file, .. }, Some(p)) => format!(
                    ": the point at {} in '{file}'{} reaches past it",
                    p.position,
                    p.at_line()
                ),
                _ => String::new(),
            };
            return Err(fail(
                "shape",
                format!(
                    "it reaches from {lo} to {hi}, so it is not inside the grid (from {grid_min} to {grid_max}{}){which}",
                    if margin > 0.0 {
                        format!(", less a margin of {margin} m that the B-spline needs")
                    } else {
                        String::new()
                    }
                ),
            ));
        }
        if points.is_empty() {
            return Err(fail(
                "shape",
                "it has no point: its shape is smaller than the point spacing".into(),
            ));
        }
        Ok(points)
    }

    /// A body's initial velocity field (defined at every point), initial
    /// stress and region constraints.
    pub(super) fn check_body_initial_state(
        &self,
        v: &Locator,
        b: &BodySpec,
        points: &[ListedPoint],
    ) -> Result<(), SceneError> {
        let fail = v.entry("bodies", "body", &b.name);
        if let InitialVelocity::Constant(velocity) = b.velocity {
            rules::speed(velocity.length())
                .map_err(|e| fail("velocity", format!("velocity: {e}")))?;
        }
        if let InitialVelocity::Field { x, y } = &b.velocity {
            let field = VelocityField::parse(x, y).map_err(|e| fail("velocity", e.to_string()))?;
            for p in points {
                let velocity = field
                    .at(p.position)
                    .map_err(|e| fail("velocity", e.to_string()))?;
                rules::speed(velocity.length()).map_err(|e| {
                    let (x, y) = (
                        rules::shown_rounded(p.position.x),
                        rules::shown_rounded(p.position.y),
                    );
                    fail("velocity", format!("velocity at ({x}, {y}): {e}"))
                })?;
            }
        }
        if let Some(InitialStress::Geostatic { k0, surface }) = &b.initial_stress {
            rules::earth_pressure_coefficient(*k0)
                .map_err(|e| fail("initial_stress", format!("k0: {e}")))?;
            if surface.is_some_and(|s| !s.is_finite()) {
                let message = "the geostatic surface must be finite".to_string();
                return Err(fail("initial_stress", message));
            }
            if self.gravity.y.is_nan() || self.gravity.y >= 0.0 {
                let message = format!(
                    "geostatic stress needs gravity pointing down (g_y < 0), got {}",
                    self.gravity
                );
                return Err(fail("initial_stress", message));
            }
            // These models compute the stress from the deformation (F,
            // or the density), so the first step would replace it.
            let from_deformation = self
                .materials
                .iter()
                .any(|m| m.name == b.material && m.model.as_model().stress_from_deformation());
            if from_deformation {
                let message = format!(
                    "material '{}' computes its stress from the deformation (NeoHookean from F, NewtonianFluid from the density), so an initial stress would be lost at the first step; let the body settle under gravity in a stage instead",
                    b.material
                );
                return Err(fail("initial_stress", message));
            }
        }
        for c in &b.constraints {
            if !(c.min.is_finite() && c.max.is_finite()) || c.min.cmpgt(c.max).any() {
                return Err(fail(
                    "constraints",
                    format!(
                        "constraint region needs finite min ≤ max, got {} and {}",
                        c.min, c.max
                    ),
                ));
            }
            if !(c.fix_x || c.fix_y) {
                return Err(fail(
                    "constraints",
                    "a constraint region fixes nothing: set fix_x, fix_y or both to true".into(),
                ));
            }
        }
        Ok(())
    }
}

/// The first body whose contact radius is given but not positive, or
/// wider than the grid (a disk that reaches every point of every body is a
/// unit typed wrong): its name and the message.
fn contact_radius_error(scene: &Scene) -> Option<(String, String)> {
    let (w, h) = (
        scene.grid.cells.0 as Real * scene.grid.cell_size,
        scene.grid.cells.1 as Real * scene.grid.cell_size,
    );
    let widest = w.max(h);
    scene.bodies.iter().find_map(|b| {
        let r = b.contact_radius?;
        let problem = match rules::positive(r) {
            Err(e) => e.to_string(),
            Ok(r) if r > widest => format!(
                "{} m is wider than the grid ({} m by {} m); a point's contact disk is about half its spacing",
                rules::shown(r),
                rules::shown(w),
                rules::shown(h)
            ),
            Ok(_) => return None,
        };
        Some((
            b.name.clone(),
            format!("body '{}': contact_radius: {problem}", b.name),
        ))
    })
}
