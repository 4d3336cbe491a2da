//! The bodies' points and the blocks' states as NumPy arrays.

use bevy_ecs::entity::Entity;
use mpdem::Simulation;
use mpdem::components::{BlockId, MaterialPoints, Pose, Reaction, RigidVelocity};
use mpdem::math::{DVec2, Real};
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyReadonlyArray2};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A snapshot of one body's points, taken between steps: one row per point,
/// in the body's fixed order, SI units, plane strain per metre of
/// thickness (per radian in axisymmetry). The arrays are copies: changing
/// them does not change the simulation (use `Simulation.set_velocity` and
/// `set_external_force`).
#[pyclass(module = "mpdem", frozen, get_all)]
pub struct Body {
    /// The body's name.
    name: String,
    /// Position x_p (m), N × 2.
    position: Py<PyAny>,
    /// Displacement from the initial position (m), N × 2.
    displacement: Py<PyAny>,
    /// Velocity V_p (m/s), N × 2.
    velocity: Py<PyAny>,
    /// Cauchy stress σ_p (Pa, tension positive), N × 4: xx, yy, xy, zz.
    stress: Py<PyAny>,
    /// Accumulated strain ∫ D dt, N × 4: xx, yy, xy, zz (zz is the hoop
    /// strain in axisymmetry, zero in plane strain).
    strain: Py<PyAny>,
    /// In-plane deformation gradient F, N × 2 × 2 (`F[p, i, j]` = ∂x_i/∂X_j).
    deformation_gradient: Py<PyAny>,
    /// Current volume V_p (m³ per metre), N.
    volume: Py<PyAny>,
    /// Initial volume V_p⁰ (m³ per metre), N.
    initial_volume: Py<PyAny>,
    /// Mass m_p (kg per metre), N.
    mass: Py<PyAny>,
    /// Energy the point's material has dissipated since the start in
    /// plastic and viscous work (J per metre), N. The models are perfectly
    /// plastic: this is what their yield has cost.
    inelastic_work: Py<PyAny>,
    /// Equivalent plastic strain since the start, Σ √(2/3 Δe_p : Δe_p) over
    /// the steps (zero for models without plastic strain), N.
    plastic_strain: Py<PyAny>,
    /// External force set on the points (N per metre), N × 2; gravity is
    /// not in it.
    external_force: Py<PyAny>,
    /// The contact forces on the points in the last step (N per metre), N × 2.
    contact_force: Py<PyAny>,
    /// The scalar fields the plugins add to the frames, by name (arrays of N).
    point_fields: Py<PyDict>,
}

#[pymethods]
impl Body {
    /// The number of points.
    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        self.mass.bind(py).len()
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "Body({:?}, points={})",
            self.name,
            self.__len__(py)?
        ))
    }
}

/// The state of a rigid block.
#[pyclass(module = "mpdem", frozen, get_all)]
#[derive(Clone, Debug)]
pub struct Block {
    /// The block's name.
    pub name: String,
    /// Position of the block's frame origin (m): (x, y).
    pub origin: (Real, Real),
    /// Rotation of the block's frame (rad, counter-clockwise).
    pub angle: Real,
    /// Velocity of the centre of mass (m/s): (vx, vy).
    pub velocity: (Real, Real),
    /// Angular velocity (rad/s, counter-clockwise).
    pub angular_velocity: Real,
    /// Force the points exerted on the block in the last step (N per
    /// metre): (fx, fy).
    pub force: (Real, Real),
    /// Their torque about the centre of mass (N m per metre).
    pub torque: Real,
}

#[pymethods]
impl Block {
    fn __repr__(&self) -> String {
        format!(
            "Block({:?}, origin=({:.6e}, {:.6e}), angle={:.6e})",
            self.name, self.origin.0, self.origin.1, self.angle
        )
    }
}

/// The body `entity`'s points as a [`Body`].
pub fn body_snapshot(
    py: Python<'_>,
    sim: &Simulation,
    entity: Entity,
    name: &str,
) -> PyResult<Body> {
    let points = sim
        .points(entity)
        .ok_or_else(|| PyKeyError::new_err(format!("body {name:?} has no points")))?;
    let n = points.len();
    let vectors = |v: &[DVec2]| -> PyResult<Py<PyAny>> {
        let flat: Vec<Real> = v.iter().flat_map(|x| [x.x, x.y]).collect();
        Ok(Array2::from_shape_vec((n, 2), flat)
            .map_err(|e| PyValueError::new_err(e.to_string()))?
            .into_pyarray(py)
            .into_any()
            .unbind())
    };
    let scalars =
        |v: Vec<Real>| -> Py<PyAny> { Array1::from_vec(v).into_pyarray(py).into_any().unbind() };
    let tensors = |v: &[mpdem::math::SymTensor]| -> PyResult<Py<PyAny>> {
        let flat: Vec<Real> = v.iter().flat_map(|t| [t.xx, t.yy, t.xy, t.zz]).collect();
        Ok(Array2::from_shape_vec((n, 4), flat)
            .map_err(|e| PyValueError::new_err(e.to_string()))?
            .into_pyarray(py)
            .into_any()
            .unbind())
    };
    let displacement: Vec<DVec2> = (0..n).map(|p| points.displacement(p)).collect();
    let gradients: Vec<Real> = points
        .deformation_gradient
        .iter()
        .flat_map(|f| [f.x_axis.x, f.y_axis.x, f.x_axis.y, f.y_axis.y])
        .collect();
    let point_fields = PyDict::new(py);
    for field in sim.point_field_names() {
        if let Some(values) = sim.point_field(entity, field) {
            point_fields.set_item(field, scalars(values))?;
        }
    }
    Ok(Body {
        name: name.to_owned(),
        position: vectors(&points.position)?,
        displacement: vectors(&displacement)?,
        velocity: vectors(&points.velocity)?,
        stress: tensors(&points.stress)?,
        strain: tensors(&points.strain)?,
        deformation_gradient: Array3::from_shape_vec((n, 2, 2), gradients)
            .map_err(|e| PyValueError::new_err(e.to_string()))?
            .into_pyarray(py)
            .into_any()
            .unbind(),
        volume: scalars(points.volume.clone()),
        initial_volume: scalars(points.initial_volume.clone()),
        mass: scalars(points.mass.clone()),
        inelastic_work: scalars(points.inelastic_work.clone()),
        plastic_strain: scalars(points.plastic_strain.clone()),
        external_force: vectors(&points.external_force)?,
        contact_force: vectors(&points.contact_force)?,
        point_fields: point_fields.unbind(),
    })
}

/// The blocks present now, in scene order.
pub fn block_states(sim: &mut Simulation) -> Vec<Block> {
    let world = sim.world_mut();
    let mut blocks: Vec<(u32, Block)> = world
        .query::<(&BlockId, &Pose, &RigidVelocity, Option<&Reaction>)>()
        .iter(world)
        .map(|(id, pose, velocity, reaction)| {
            let reaction = reaction.copied().unwrap_or_default();
            let block = Block {
                name: id.name.clone(),
                origin: (pose.origin.x, pose.origin.y),
                angle: pose.angle,
                velocity: (velocity.linear.x, velocity.linear.y),
                angular_velocity: velocity.angular,
                force: (reaction.force.x, reaction.force.y),
                torque: reaction.torque,
            };
            (id.index, block)
        })
        .collect();
    blocks.sort_by_key(|(index, _)| *index);
    blocks.into_iter().map(|(_, block)| block).collect()
}

/// Sets the column `column` of body `entity`'s points from an N × 2 array.
pub fn set_point_column(
    sim: &mut Simulation,
    entity: Entity,
    values: &PyReadonlyArray2<'_, f64>,
    column: impl Fn(&mut MaterialPoints) -> &mut Vec<DVec2>,
) -> PyResult<()> {
    let mut points = sim
        .world_mut()
        .get_mut::<MaterialPoints>(entity)
        .ok_or_else(|| PyKeyError::new_err("the body has no points"))?;
    let view = values.as_array();
    let n = points.len();
    if view.shape() != [n, 2] {
        return Err(PyValueError::new_err(format!(
            "expected an array of shape ({n}, 2), one row per point, got {:?}",
            view.shape()
        )));
    }
    if view.iter().any(|v| !v.is_finite()) {
        return Err(PyValueError::new_err("the values must be finite"));
    }
    for (slot, row) in column(&mut points).iter_mut().zip(view.outer_iter()) {
        *slot = DVec2::new(row[0], row[1]);
    }
    Ok(())
}
