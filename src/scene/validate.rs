//! Consistency checks of a whole scene: ranges, names and geometry.

use super::axisymmetry::axisymmetry_error;
use super::{
    BodySpec, InitialStress, InitialVelocity, ListedPoint, MAX_SAMPLES, MAX_STEPS, MotionSpec,
    PROBE_PLOT_LONGEST_SUFFIX, PROBE_PLOT_PREFIX, RUN_FILE_STEMS, Scene, SceneError, Shape,
    SourceLocation, VelocityField, whole_steps,
};
use crate::components::RigidVelocity;
use crate::contact::ForceApplication;
use crate::materials::MaterialModel;
use crate::math::Real;
use crate::resources::MAX_CONTACT_BODIES;
use crate::rules;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Largest points-per-cell count: 8 × 8 = 64 points per cell is already far
/// beyond what MPM accuracy gains from; larger counts are almost surely typos.
const MAX_POINTS_PER_CELL: u32 = 8;

/// Most material points a scene may have: a point takes about 500 bytes
/// (its columns, its stencil, its place in the scatter order), so 2e7
/// points take 10 GB, beyond what a 2D run on one machine can use; such
/// counts come from a cell size or `points_per_cell` typed wrong.
const MAX_POINTS: u128 = 20_000_000;

/// Most nodes a grid may have: 5e7 nodes make an 4.4 GB layer per body (88
/// bytes a node), beyond what a 2D run on one machine can use; node indices
/// are stored as u32, which this also keeps in range.
const MAX_NODES: u128 = 50_000_000;

/// Where a validation error is: the scene's text and file, if it came from
/// one.
struct Locator<'t> {
    source: Option<(&'t str, &'t Path)>,
}

impl Locator<'_> {
    /// The error `message` at the last of `anchors` found in the text (see
    /// [`SourceLocation::find`]).
    fn invalid(&self, anchors: &[&str], message: String) -> SceneError {
        SceneError::Invalid {
            location: match self.source {
                Some((text, path)) => SourceLocation::find(text, path, anchors),
                None => SourceLocation::default(),
            },
            message,
        }
    }
}

/// A name as the quoted string that anchors its entry.
fn quoted(name: &str) -> String {
    format!("\"{name}\"")
}

/// The `name` field of entry k of a section (each entry has one), for a
/// name used twice: the place of its second use.
fn nth_name(section: &'static str, k: usize) -> Vec<&'static str> {
    std::iter::once(section)
        .chain(std::iter::repeat_n("name", k + 1))
        .collect()
}

impl Scene {
    /// Validates; `source` (text and path) lets errors point into the file.
    pub(super) fn validate_in(&self, source: Option<(&str, &Path)>) -> Result<(), SceneError> {
        let v = Locator { source };
        self.check_name(&v)?;
        self.check_entry_names(&v)?;
        self.check_grid(&v)?;
        self.check_time(&v)?;
        self.check_settings(&v)?;
        let materials = self.check_materials(&v)?;
        let bodies = self.check_bodies(&v, &materials)?;
        let blocks = self.check_blocks(&v)?;
        self.check_contact(&v)?;
        self.check_probes_and_output(&v, &bodies, &blocks)?;
        self.check_body_contacts(&v, &bodies)?;
        self.check_block_contacts(&v, &bodies, &blocks)?;
        self.check_stages(&v, &bodies, &blocks)?;
        Ok(())
    }

    /// The scene's name, which names the output folder.
    fn check_name(&self, v: &Locator) -> Result<(), SceneError> {
        if let Some(name) = &self.name {
            if name.len() > rules::FILE_NAME_MAX_BYTES {
                return Err(v.invalid(
                    &["name"],
                    format!(
                        "name: {} bytes long, past the {} that file systems allow in a folder's name (the output folder is out/<name>): shorten it",
                        name.len(),
                        rules::FILE_NAME_MAX_BYTES
                    ),
                ));
            }
            rules::file_name(name).map_err(|e| {
                v.invalid(
                    &["name"],
                    format!("name: {e} (the output folder is out/<name>)"),
                )
            })?;
        }
        Ok(())
    }

    /// Every named entry has a name: the messages, the outputs and the
    /// entries that refer to one another go by it.
    fn check_entry_names(&self, v: &Locator) -> Result<(), SceneError> {
        let sections: [(&'static str, Vec<&str>); 5] = [
            (
                "materials",
                self.materials.iter().map(|m| m.name.as_str()).collect(),
            ),
            (
                "bodies",
                self.bodies.iter().map(|b| b.name.as_str()).collect(),
            ),
            (
                "blocks",
                self.blocks.iter().map(|b| b.name.as_str()).collect(),
            ),
            (
                "probes",
                self.probes.iter().map(|p| p.name.as_str()).collect(),
            ),
            (
                "stages",
                self.stages.iter().map(|s| s.name.as_str()).collect(),
            ),
        ];
        for (section, names) in sections {
            if let Some(k) = names.iter().position(|name| name.trim().is_empty()) {
                return Err(v.invalid(
                    &nth_name(section, k),
                    format!("{section}: entry {} has an empty name", k + 1),
                ));
            }
        }
        Ok(())
    }

    /// The grid: its origin, cell size and counts.
    fn check_grid(&self, v: &Locator) -> Result<(), SceneError> {
        let grid = &self.grid;
        rules::positive(grid.cell_size)
            .map_err(|e| v.invalid(&["grid", "cell_size"], format!("grid.cell_size: {e}")))?;
        if !grid.origin.is_finite() {
            return Err(v.invalid(
                &["grid", "origin"],
                format!("grid.origin must be finite, got {}", grid.origin),
            ));
        }
        // In u128 each factor fits, and their product saturates rather than
        // wrap for counts near usize::MAX.
        let nodes = (grid.cells.0 as u128 + 1).saturating_mul(grid.cells.1 as u128 + 1);
        if nodes > MAX_NODES {
            return Err(v.invalid(
                &["grid", "cells"],
                format!(
                    "grid.cells {:?} give more than the {MAX_NODES} nodes a layer may hold",
                    grid.cells
                ),
            ));
        }
        if grid.cells.0 < 2 || grid.cells.1 < 2 {
            return Err(v.invalid(
                &["grid", "cells"],
                format!(
                    "grid.cells must be at least 2 in each direction, got {:?}",
                    grid.cells
                ),
            ));
        }
        Ok(())
    }

    /// The time step and end, and the steps and samples they make.
    fn check_time(&self, v: &Locator) -> Result<(), SceneError> {
        rules::positive(self.time.dt)
            .map_err(|e| v.invalid(&["time", "dt"], format!("time.dt: {e}")))?;
        rules::positive(self.time.end)
            .map_err(|e| v.invalid(&["time", "end"], format!("time.end: {e}")))?;
        if self.time.dt > self.time.end {
            return Err(v.invalid(
                &["time", "dt"],
                format!(
                    "time.dt ({}) is longer than time.end ({})",
                    self.time.dt, self.time.end
                ),
            ));
        }
        let cap = self.time.max_steps.unwrap_or(MAX_STEPS);
        let steps = self.time.end / self.time.dt;
        if steps > cap as Real {
            return Err(v.invalid(
                &["time", "dt"],
                format!(
                    "time: end / dt = {:e} / {:e} gives {steps:.3e} steps, more than the cap of {cap} (time.max_steps; default {MAX_STEPS}): check dt and end, or name a larger time.max_steps",
                    self.time.end, self.time.dt
                ),
            ));
        }
        // The rows the records keep, as the spawn reserves them: a row per
        // sample for the energies, and one per probe, block, compound part
        // and pair of bodies under a law.
        let samples = (steps.round()
            / whole_steps(
                self.output.probe_interval_or_default(self.time.end),
                self.time.dt,
            ) as Real)
            + 2.0;
        let parts: usize = self
            .blocks
            .iter()
            .map(|b| match &b.shape {
                crate::rigid::BlockShape::Compound { parts } => parts.len(),
                _ => 0,
            })
            .sum();
        let members = |name: &str| self.contact_members(name).map_or(0, |m| m.len());
        let pairs: usize = self
            .body_contacts
            .iter()
            .map(|c| members(&c.between.0) * members(&c.between.1))
            .sum();
        let series = 1 + self.probes.len() + self.blocks.len() + parts + pairs;
        let rows = samples * series as Real;
        if rows > MAX_SAMPLES as Real {
            return Err(v.invalid(
                &["output", "probe_interval"],
                format!(
                    "output.probe_interval: {:e} s over time.end = {} s gives {samples:.3e} samples of {series} records (energies, probes, blocks and their parts, body pairs), {rows:.3e} rows, more than the {MAX_SAMPLES} a run keeps in memory: sample less often",
                    self.output.probe_interval_or_default(self.time.end),
                    self.time.end
                ),
            ));
        }
        Ok(())
    }

    /// Gravity and the numerical settings.
    fn check_settings(&self, v: &Locator) -> Result<(), SceneError> {
        if !self.gravity.is_finite() {
            return Err(v.invalid(
                &["gravity"],
                format!("gravity must be finite, got {}", self.gravity),
            ));
        }
        self.settings
            .check()
            .map_err(|e| v.invalid(&["settings"], format!("settings: {e}")))?;
        if let Some((anchors, message)) = axisymmetry_error(self) {
            let anchors: Vec<&str> = anchors.iter().map(String::as_str).collect();
            return Err(v.invalid(&anchors, message));
        }
        if self.settings.xpic_order.is_some() && !self.shared_layers().is_empty() {
            return Err(v.invalid(
                &["settings", "xpic_order"],
                "settings.xpic_order: XPIC is not available with contact groups yet (its projections run per body); use pic_fraction".into(),
            ));
        }
        Ok(())
    }

    /// The materials; returns their names.
    fn check_materials<'s>(&'s self, v: &Locator) -> Result<BTreeSet<&'s str>, SceneError> {
        let mut material_names = BTreeSet::new();
        for (k, m) in self.materials.iter().enumerate() {
            let at = ["materials", &quoted(&m.name)];
            if !material_names.insert(m.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("materials", k),
                    format!("material name '{}' is used twice", m.name),
                ));
            }
            rules::positive(m.density).map_err(|e| {
                v.invalid(
                    &[at[0], at[1], "density"],
                    format!("material '{}': density: {e}", m.name),
                )
            })?;
            m.model
                .check()
                .map_err(|e| v.invalid(&at, format!("material '{}': {e}", m.name)))?;
        }
        Ok(material_names)
    }

    /// The bodies against the grid and the materials; returns their names.
    fn check_bodies<'s>(
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
            let name = quoted(&b.name);
            let fail = |field: &str, message: String| v.invalid(&["bodies", &name, field], message);
            if !body_names.insert(b.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("bodies", k),
                    format!("body name '{}' is used twice", b.name),
                ));
            }
            if let Some(load) = b.acceleration
                && !(load.value.is_finite() && load.ramp_time.is_finite() && load.ramp_time >= 0.0)
            {
                return Err(fail(
                    "acceleration",
                    format!(
                        "body '{}': acceleration must be finite with ramp_time ≥ 0, got {} over {} s",
                        b.name, load.value, load.ramp_time
                    ),
                ));
            }
            if !material_names.contains(b.material.as_str()) {
                return Err(fail(
                    "material",
                    format!(
                        "body '{}': unknown material '{}'; expected one of {:?}",
                        b.name, b.material, material_names
                    ),
                ));
            }
            if !(1..=MAX_POINTS_PER_CELL).contains(&b.points_per_cell) {
                return Err(fail(
                    "points_per_cell",
                    format!(
                        "body '{}': points_per_cell must be 1 to {MAX_POINTS_PER_CELL}, got {}",
                        b.name, b.points_per_cell
                    ),
                ));
            }
            b.shape
                .check()
                .map_err(|e| fail("shape", format!("body '{}': {e}", b.name)))?;
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
    fn check_body_points(
        &self,
        v: &Locator,
        b: &BodySpec,
        total_points: Real,
    ) -> Result<Vec<ListedPoint>, SceneError> {
        let grid = &self.grid;
        let (grid_min, grid_max) = (grid.origin, grid.max());
        let margin = self.settings.shape_function.required_margin_cells() * grid.cell_size;
        let name = quoted(&b.name);
        let fail = |field: &str, message: String| v.invalid(&["bodies", &name, field], message);
        // Estimated from the shape before its points are made.
        let estimate = b
            .shape
            .point_estimate(grid.cell_size / Real::from(b.points_per_cell));
        if total_points + estimate > MAX_POINTS as Real {
            return Err(fail(
                "shape",
                format!(
                    "body '{}': about {estimate:.3e} points at {} per cell of {} m{}: more than the {MAX_POINTS} a scene may hold",
                    b.name,
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
                        "body '{}': the point at {} in '{file}'{} has volume {volume}, more than a cell ({cell}): its domain would reach beyond the nodes next to it",
                        b.name,
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
                    "body '{}' (from {lo} to {hi}) is not inside the grid (from {grid_min} to {grid_max}{}){which}",
                    b.name,
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
                format!(
                    "body '{}' has no point: its shape is smaller than the point spacing",
                    b.name
                ),
            ));
        }
        Ok(points)
    }

    /// A body's initial velocity field (defined at every point), initial
    /// stress and region constraints.
    fn check_body_initial_state(
        &self,
        v: &Locator,
        b: &BodySpec,
        points: &[ListedPoint],
    ) -> Result<(), SceneError> {
        let name = quoted(&b.name);
        let fail = |field: &str, message: String| v.invalid(&["bodies", &name, field], message);
        if let InitialVelocity::Constant(velocity) = b.velocity
            && !velocity.is_finite()
        {
            let message = format!("body '{}': velocity must be finite, got {velocity}", b.name);
            return Err(fail("velocity", message));
        }
        if let InitialVelocity::Field { x, y } = &b.velocity {
            let field = VelocityField::parse(x, y)
                .map_err(|e| fail("velocity", format!("body '{}': {e}", b.name)))?;
            for p in points {
                field
                    .at(p.position)
                    .map_err(|e| fail("velocity", format!("body '{}': {e}", b.name)))?;
            }
        }
        if let Some(InitialStress::Geostatic { k0, surface }) = &b.initial_stress {
            rules::non_negative(*k0)
                .map_err(|e| fail("initial_stress", format!("body '{}': k0: {e}", b.name)))?;
            if surface.is_some_and(|s| !s.is_finite()) {
                let message = format!("body '{}': the geostatic surface must be finite", b.name);
                return Err(fail("initial_stress", message));
            }
            if self.gravity.y.is_nan() || self.gravity.y >= 0.0 {
                let message = format!(
                    "body '{}': geostatic stress needs gravity pointing down (g_y < 0), got {}",
                    b.name, self.gravity
                );
                return Err(fail("initial_stress", message));
            }
            // These models compute the stress from the deformation (F,
            // or the density), so the first step would replace it.
            let from_deformation = self.materials.iter().any(|m| {
                m.name == b.material
                    && matches!(
                        m.model,
                        MaterialModel::NeoHookean(_) | MaterialModel::NewtonianFluid(_)
                    )
            });
            if from_deformation {
                let message = format!(
                    "body '{}': material '{}' computes its stress from the deformation (NeoHookean from F, NewtonianFluid from the density), so an initial stress would be lost at the first step; let the body settle under gravity in a stage instead",
                    b.name, b.material
                );
                return Err(fail("initial_stress", message));
            }
        }
        for c in &b.constraints {
            if !(c.min.is_finite() && c.max.is_finite()) || c.min.cmpgt(c.max).any() {
                return Err(fail(
                    "constraints",
                    format!(
                        "body '{}': constraint region needs finite min ≤ max, got {} and {}",
                        b.name, c.min, c.max
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The rigid blocks; returns their names.
    fn check_blocks<'s>(&'s self, v: &Locator) -> Result<BTreeSet<&'s str>, SceneError> {
        let mut block_names = BTreeSet::new();
        for (k, block) in self.blocks.iter().enumerate() {
            let name = quoted(&block.name);
            let fail = |field: &str, message: String| v.invalid(&["blocks", &name, field], message);
            if !block_names.insert(block.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("blocks", k),
                    format!("block name '{}' is used twice", block.name),
                ));
            }
            block
                .shape
                .build()
                .map_err(|e| fail("shape", format!("block '{}': {e}", block.name)))?;
            if !(block.position.is_finite() && block.angle.is_finite()) {
                return Err(fail(
                    "position",
                    format!("block '{}': position and angle must be finite", block.name),
                ));
            }
            block
                .contact
                .check()
                .map_err(|e| fail("contact", format!("block '{}': {e}", block.name)))?;
            let initial = match &block.motion {
                MotionSpec::Fixed => RigidVelocity::default(),
                MotionSpec::Kinematic(v)
                | MotionSpec::Dynamic { velocity: v, .. }
                | MotionSpec::DynamicWithMass { velocity: v, .. } => *v,
            };
            if !(initial.linear.is_finite() && initial.angular.is_finite()) {
                return Err(fail(
                    "motion",
                    format!("block '{}': velocity must be finite", block.name),
                ));
            }
            if let MotionSpec::DynamicWithMass {
                mass,
                inertia,
                center,
                ..
            } = block.motion
            {
                rules::positive(mass)
                    .map_err(|e| fail("mass", format!("block '{}': mass: {e}", block.name)))?;
                rules::positive(inertia).map_err(|e| {
                    fail("inertia", format!("block '{}': inertia: {e}", block.name))
                })?;
                if !center.is_finite() {
                    return Err(fail(
                        "center",
                        format!("block '{}': center must be finite", block.name),
                    ));
                }
            }
            if let MotionSpec::Dynamic { density, .. } = block.motion {
                rules::positive(density).map_err(|e| {
                    fail("density", format!("block '{}': density: {e}", block.name))
                })?;
            }
        }
        Ok(block_names)
    }

    /// The contact settings.
    fn check_contact(&self, v: &Locator) -> Result<(), SceneError> {
        if self.contact.iter_period == Some(0) {
            return Err(v.invalid(
                &["contact", "iter_period"],
                "contact.iter_period must be at least 1".into(),
            ));
        }
        if let ForceApplication::Traction { points: 0 } = self.contact.force_application {
            let message = "contact.force_application: Traction needs at least 1 point".into();
            return Err(v.invalid(&["contact", "force_application"], message));
        }
        if let Some(margin) = self.contact.margin {
            rules::positive(margin)
                .map_err(|e| v.invalid(&["contact", "margin"], format!("contact.margin: {e}")))?;
        }
        Ok(())
    }

    /// The probes and the output intervals and curves.
    fn check_probes_and_output<'s>(
        &'s self,
        v: &Locator,
        body_names: &BTreeSet<&'s str>,
        block_names: &BTreeSet<&'s str>,
    ) -> Result<(), SceneError> {
        let mut probe_names = BTreeSet::new();
        let mut probe_files = BTreeMap::new();
        for (k, p) in self.probes.iter().enumerate() {
            let at = ["probes", &quoted(&p.name)];
            if !probe_names.insert(p.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("probes", k),
                    format!("probe name '{}' is used twice", p.name),
                ));
            }
            // Compared without case: macOS and Windows file systems ignore it.
            let file = rules::file_safe(&p.name).to_ascii_lowercase();
            if let Some(other) = probe_files.insert(file, p.name.as_str()) {
                return Err(v.invalid(
                    &at,
                    format!(
                        "probes '{other}' and '{}' would write the same plot files ({PROBE_PLOT_PREFIX}{}_*.png): file names keep only letters, digits, '-' and '_'",
                        p.name,
                        rules::file_safe(&p.name)
                    ),
                ));
            }
            let longest = format!(
                "{PROBE_PLOT_PREFIX}{}{PROBE_PLOT_LONGEST_SUFFIX}",
                rules::file_safe(&p.name)
            );
            rules::fits_in_file_name(&longest)
                .map_err(|e| v.invalid(&at, format!("probe '{}': {e}", p.name)))?;
            if !p.at.is_finite() {
                return Err(v.invalid(
                    &[at[0], at[1], "at"],
                    format!("probe '{}': location must be finite, got {}", p.name, p.at),
                ));
            }
            if !body_names.contains(p.body.as_str()) {
                return Err(v.invalid(
                    &[at[0], at[1], "body"],
                    format!(
                        "probe '{}': unknown body '{}'; expected one of {:?}",
                        p.name, p.body, body_names
                    ),
                ));
            }
        }
        for (field, value) in [
            ("frame_interval", self.output.frame_interval),
            ("probe_interval", self.output.probe_interval),
        ] {
            if let Some(value) = value {
                rules::positive(value)
                    .map_err(|e| v.invalid(&["output", field], format!("output.{field}: {e}")))?;
            }
        }

        let mut curve_names = BTreeSet::new();
        for (k, curve) in self.output.curves.iter().enumerate() {
            let at = quoted(&curve.name);
            let fail = |field: &str, message: String| {
                v.invalid(
                    &["output", "curves", &at, field],
                    format!("curve '{}': {message}", curve.name),
                )
            };
            let fail_name = |message: String| {
                v.invalid(
                    &["output", "curves", &at],
                    format!("curve '{}': {message}", curve.name),
                )
            };
            rules::file_name(&curve.name)
                .and_then(|()| rules::fits_in_file_name(&format!("{}.csv", curve.name)))
                .map_err(|e| fail_name(e.to_string()))?;
            // Compared without case: macOS and Windows file systems ignore it.
            let file = curve.name.to_lowercase();
            if !curve_names.insert(file.clone()) {
                return Err(v.invalid(
                    &[&["output"], nth_name("curves", k).as_slice()].concat(),
                    format!(
                        "curve '{}': the name is used twice (names are files: letter case does not tell them apart)",
                        curve.name
                    ),
                ));
            }
            if RUN_FILE_STEMS.contains(&file.as_str()) || file.starts_with(PROBE_PLOT_PREFIX) {
                return Err(fail_name(format!(
                    "the name would overwrite the run's own files ({RUN_FILE_STEMS:?}, {PROBE_PLOT_PREFIX}*); choose another"
                )));
            }
            let Some(block) = self.blocks.iter().find(|b| b.name == curve.block) else {
                return Err(fail(
                    "block",
                    format!(
                        "unknown block '{}'; expected one of {block_names:?}",
                        curve.block
                    ),
                ));
            };
            if let Some(part) = curve.part {
                let parts = match &block.shape {
                    crate::rigid::BlockShape::Compound { parts } => parts.len(),
                    _ => 1,
                };
                if part >= parts {
                    return Err(fail(
                        "part",
                        format!(
                            "block '{}' has {parts} part(s), so part {part} does not exist (parts count from 0)",
                            curve.block
                        ),
                    ));
                }
            }
            if !(curve.direction.is_finite() && curve.direction.length() > 0.0) {
                return Err(fail(
                    "direction",
                    "direction must be a finite, non-zero vector".into(),
                ));
            }
            if !(curve.force_scale.is_finite() && curve.displacement_scale.is_finite()) {
                return Err(fail("force_scale", "scales must be finite".into()));
            }
        }
        Ok(())
    }

    /// The laws of pairs with a block: each names a block and a body, or
    /// two blocks; a pair once; valid laws.
    fn check_block_contacts(
        &self,
        v: &Locator,
        body_names: &BTreeSet<&str>,
        block_names: &BTreeSet<&str>,
    ) -> Result<(), SceneError> {
        let mut pairs = BTreeSet::new();
        for (k, spec) in self.block_contacts.iter().enumerate() {
            let (a, b) = (spec.between.0.as_str(), spec.between.1.as_str());
            let at = |field: &'static str| -> Vec<&str> {
                std::iter::once("block_contacts")
                    .chain(std::iter::repeat_n(field, k + 1))
                    .collect()
            };
            for name in [a, b] {
                if block_names.contains(name) && body_names.contains(name) {
                    return Err(v.invalid(
                        &at("between"),
                        format!(
                            "block_contacts: '{name}' names a block and a body; rename one so that the law's pair is clear"
                        ),
                    ));
                }
                if !block_names.contains(name) && !body_names.contains(name) {
                    return Err(v.invalid(
                        &at("between"),
                        format!(
                            "block_contacts: unknown block or body '{name}'; expected one of the blocks {block_names:?} or bodies {body_names:?}"
                        ),
                    ));
                }
            }
            if !block_names.contains(a) && !block_names.contains(b) {
                return Err(v.invalid(
                    &at("between"),
                    format!(
                        "block_contacts ('{a}', '{b}'): neither is a block; the law between two bodies goes in body_contacts"
                    ),
                ));
            }
            if a == b {
                return Err(v.invalid(
                    &at("between"),
                    format!("block_contacts ('{a}', '{b}'): a block does not contact itself"),
                ));
            }
            if !pairs.insert((a.min(b), a.max(b))) {
                return Err(v.invalid(
                    &at("between"),
                    format!("block_contacts ('{a}', '{b}'): the pair has two laws"),
                ));
            }
            spec.law.check().map_err(|e| {
                v.invalid(&at("law"), format!("block_contacts ('{a}', '{b}'): {e}"))
            })?;
        }
        Ok(())
    }

    /// The body contact laws and contact groups.
    fn check_body_contacts<'s>(
        &'s self,
        v: &Locator,
        body_names: &BTreeSet<&'s str>,
    ) -> Result<(), SceneError> {
        let grid = &self.grid;
        let group_names: BTreeSet<&str> = self
            .bodies
            .iter()
            .filter_map(|b| b.group.as_deref())
            .collect();
        if let Some(b) = self
            .bodies
            .iter()
            .find(|b| b.group.as_deref().is_some_and(|g| body_names.contains(g)))
        {
            return Err(v.invalid(
                &["bodies", &quoted(&b.name), "group"],
                format!(
                    "body '{}': group '{}' has the name of a body; body_contacts could not tell them apart",
                    b.name,
                    b.group.as_deref().unwrap_or_default()
                ),
            ));
        }
        let mut pairs = BTreeSet::new();
        for (k, spec) in self.body_contacts.iter().enumerate() {
            let (a, b) = (&spec.between.0, &spec.between.1);
            // The k-th entry's `between` (and below its `law`).
            let at: Vec<&str> = std::iter::once("body_contacts")
                .chain(std::iter::repeat_n("between", k + 1))
                .collect();
            let members = |name: &str| {
                self.contact_members(name).ok_or_else(|| {
                    v.invalid(
                        &at,
                        format!(
                            "body_contacts: unknown body or group '{name}'; expected one of the bodies {body_names:?} or groups {group_names:?}"
                        ),
                    )
                })
            };
            let (first, second) = (members(a)?, members(b)?);
            let same_layer = |i: usize, j: usize| {
                i == j
                    || self.bodies[i].group.is_some()
                        && self.bodies[i].group == self.bodies[j].group
            };
            for &i in &first {
                for &j in &second {
                    if same_layer(i, j) {
                        return Err(v.invalid(
                            &at,
                            format!(
                                "body_contacts ('{a}', '{b}'): body '{}' would contact '{}', which shares its layer (the same body or contact group): such bodies meet through the grid",
                                self.bodies[i].name, self.bodies[j].name
                            ),
                        ));
                    }
                    if !pairs.insert((i.min(j), i.max(j))) {
                        return Err(v.invalid(
                            &at,
                            format!(
                                "body_contacts ('{a}', '{b}'): the bodies '{}' and '{}' have two laws",
                                self.bodies[i].name, self.bodies[j].name
                            ),
                        ));
                    }
                }
            }
            spec.law.check().map_err(|e| {
                v.invalid(
                    &std::iter::once("body_contacts")
                        .chain(std::iter::repeat_n("law", k + 1))
                        .collect::<Vec<_>>(),
                    format!("body_contacts ('{a}', '{b}'): {e}"),
                )
            })?;
        }
        if !self.body_contacts.is_empty()
            && let Some(b) = self
                .bodies
                .iter()
                .find(|b| b.contact_radius.is_some_and(|r| r > 0.5 * grid.cell_size))
        {
            return Err(v.invalid(
                &["bodies", &quoted(&b.name), "contact_radius"],
                format!(
                    "body '{}': contact_radius {} is more than half a cell ({}): body contacts look for overlapping disks in neighbouring cells only",
                    b.name,
                    b.contact_radius.unwrap_or_default(),
                    0.5 * grid.cell_size
                ),
            ));
        }
        if !self.body_contacts.is_empty() && self.bodies.len() > MAX_CONTACT_BODIES {
            return Err(v.invalid(
                &["body_contacts"],
                format!(
                    "body_contacts: at most {MAX_CONTACT_BODIES} bodies are supported, the scene has {}",
                    self.bodies.len()
                ),
            ));
        }
        Ok(())
    }

    /// The stages.
    fn check_stages<'s>(
        &'s self,
        v: &Locator,
        body_names: &BTreeSet<&'s str>,
        block_names: &BTreeSet<&'s str>,
    ) -> Result<(), SceneError> {
        let mut stage_names = BTreeSet::new();
        let mut present: BTreeSet<&str> = self
            .blocks
            .iter()
            .filter(|b| b.present)
            .map(|b| b.name.as_str())
            .collect();
        for (k, stage) in self.stages.iter().enumerate() {
            let at = quoted(&stage.name);
            let fail = |field: &str, message: String| {
                v.invalid(
                    &["stages", &at, field],
                    format!("stage '{}': {message}", stage.name),
                )
            };
            if !stage_names.insert(stage.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("stages", k),
                    format!("stage '{}': the name is used twice", stage.name),
                ));
            }
            stage
                .end
                .check()
                .map_err(|e| fail("end", format!("end: {e}")))?;
            // The same ranges as the file's parser applies (rules.rs), for
            // stages built in code.
            let ranges = [
                (
                    "pic_fraction",
                    stage.pic_fraction,
                    rules::fraction as fn(Real) -> _,
                ),
                ("grid_damping", stage.grid_damping, rules::damping),
                ("particle_damping", stage.particle_damping, rules::damping),
            ];
            for (field, value, rule) in ranges {
                if let Some(v) = value {
                    rule(v).map_err(|e| fail(field, format!("{field}: {e}")))?;
                }
            }
            if let Some(g) = stage.gravity
                && !g.is_finite()
            {
                return Err(fail("gravity", format!("gravity must be finite, got {g}")));
            }
            let block = |name: &str, field: &str| {
                self.blocks.iter().find(|b| b.name == name).ok_or_else(|| {
                    fail(
                        field,
                        format!("unknown block '{name}'; expected one of {block_names:?}"),
                    )
                })
            };
            // Removals come first, then additions (systems/stages.rs).
            for name in &stage.remove_blocks {
                block(name, "remove_blocks")?;
                if !present.remove(name.as_str()) {
                    return Err(fail(
                        "remove_blocks",
                        format!(
                            "block '{name}' is not there when the stage begins (an earlier stage removed it, or none added it)"
                        ),
                    ));
                }
            }
            for name in &stage.add_blocks {
                if block(name, "add_blocks")?.present {
                    return Err(fail(
                        "add_blocks",
                        format!(
                            "block '{name}' is present from the start; give it `present: false` to add it in a stage"
                        ),
                    ));
                }
                if !present.insert(name.as_str()) {
                    return Err(fail(
                        "add_blocks",
                        format!("block '{name}' is there already: an earlier stage added it"),
                    ));
                }
            }
            for change in &stage.block_velocities {
                let b = block(&change.block, "block_velocities")?;
                if !present.contains(change.block.as_str()) {
                    return Err(fail(
                        "block_velocities",
                        format!(
                            "block '{}' is not there during this stage: add it first",
                            change.block
                        ),
                    ));
                }
                if !matches!(b.motion, MotionSpec::Kinematic(_)) {
                    return Err(fail(
                        "block_velocities",
                        format!(
                            "block '{}' is not Kinematic: only a kinematic block's velocity can be set",
                            change.block
                        ),
                    ));
                }
                if !(change.velocity.linear.is_finite() && change.velocity.angular.is_finite()) {
                    return Err(fail("block_velocities", "velocity must be finite".into()));
                }
            }
            for (k, traction) in stage.tractions.iter().enumerate() {
                if stage.tractions[..k]
                    .iter()
                    .any(|t| t.body == traction.body && t.side == traction.side)
                {
                    return Err(fail(
                        "tractions",
                        format!(
                            "body '{}' is loaded twice on its {:?} side in this stage: one traction per body and side (the last would replace the first)",
                            traction.body, traction.side
                        ),
                    ));
                }
                if !self.bodies.iter().any(|b| b.name == traction.body) {
                    return Err(fail(
                        "tractions",
                        format!(
                            "unknown body '{}'; expected one of {body_names:?}",
                            traction.body
                        ),
                    ));
                }
                if !traction.traction.is_finite() {
                    return Err(fail("tractions", "traction must be finite".into()));
                }
            }
        }
        Ok(())
    }
}

/// The first body whose contact radius is given but not positive: its name
/// and the message.
fn contact_radius_error(scene: &Scene) -> Option<(String, String)> {
    scene.bodies.iter().find_map(|b| {
        let r = b.contact_radius?;
        rules::positive(r).err().map(|e| {
            (
                b.name.clone(),
                format!("body '{}': contact_radius: {e}", b.name),
            )
        })
    })
}
