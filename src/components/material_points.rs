//! The material points of one body as struct-of-arrays columns.

use crate::geometry::Geometry;
use crate::materials::ConstitutiveModel;
use crate::math::{DMat2, DVec2, Real, SymTensor};
use bevy_ecs::prelude::Component;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Points per chunk of the reductions over a body's points: fixed, not
/// derived from the thread count, so that results do not depend on it.
const CHUNK_POINTS: usize = 1024;

/// The initial state of one point, used to fill the columns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewPoint {
    /// Position (m).
    pub position: DVec2,
    /// Velocity (m/s).
    pub velocity: DVec2,
    /// Volume (m³ per metre of thickness; per radian in axisymmetry).
    pub volume: Real,
    /// Mass (kg per metre of thickness; per radian in axisymmetry).
    pub mass: Real,
    /// Half-size of the point's GIMP domain along x and y (m).
    pub half_size: DVec2,
    /// Initial Cauchy stress (Pa, tension positive).
    pub stress: SymTensor,
    /// Radius of the point's DEM disk (m).
    pub contact_radius: Real,
}

/// Energies of a set of points (J/m), see [`MaterialPoints::energies`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PointEnergies {
    /// Σ ½ m |V|².
    pub kinetic: Real,
    /// Σ w(σ) V.
    pub strain: Real,
    /// −Σ m g · (x − X): gravity's potential relative to the initial positions.
    pub gravity: Real,
    /// Σ of the points' inelastic work (what their material dissipated).
    pub inelastic: Real,
}

impl std::ops::Add for PointEnergies {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            kinetic: self.kinetic + o.kinetic,
            strain: self.strain + o.strain,
            gravity: self.gravity + o.gravity,
            inelastic: self.inelastic + o.inelastic,
        }
    }
}

/// The largest distance any point of the body moved in the last
/// grid-to-particle update (m). The contact broad phase adds it up to know
/// when a point may have left a neighbour list's margin.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepTravel(pub Real);

/// Energy that damping and the velocity update's PIC (or XPIC) part have
/// taken from the body since the start of the run (J/m), for the energy
/// balance ([`crate::resources::EnergySample::damped`]): every step,
/// Σ ½ m_p (|V_p + a*_p Δt|² − |V_p^{n+1}|²), a*_p Δt = Σ_i S_ip (v*_i − v_i^n)
/// the point's change under the nodal velocities v*_i found without grid
/// damping: what the update took against the undamped pure FLIP update
/// (grid and particle damping, the PIC fraction, XPIC's smoothing), before
/// a point the update carried through a wall is put back on it (the
/// velocity component then removed is the grid boundary's work, not
/// counted). Taken at the points, it counts what reaches the body: grid
/// damping also slows nodes that carry almost no mass, whose work would
/// count energy no point ever had.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DampedEnergy(pub Real);

/// Every point of one body, one column per field. All columns have the same
/// length; index p is the same point in every column. Points keep their
/// order for the whole run, so an index identifies a point.
#[derive(Component, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MaterialPoints {
    /// Current position x_p.
    pub position: Vec<DVec2>,
    /// Initial position, for displacements.
    pub initial_position: Vec<DVec2>,
    /// Velocity V_p.
    pub velocity: Vec<DVec2>,
    /// Mass m_p (constant).
    pub mass: Vec<Real>,
    /// Initial volume V_p⁰.
    pub initial_volume: Vec<Real>,
    /// Current volume V_p = det(F) V_p⁰ (in axisymmetry det(F) F_θθ V_p⁰,
    /// F_θθ = exp(ε_θθ) from the strain's zz component).
    pub volume: Vec<Real>,
    /// In-plane deformation gradient F (F_zz = 1 in plane strain).
    pub deformation_gradient: Vec<DMat2>,
    /// For a point that had a contact in the last step, the gradient
    /// L = Σ_i u_i ⊗ G_ip of the nodal velocity u that moved it (per
    /// `PositionUpdate`, written by G2P): the material's motion about the
    /// point; zero for the others. Contacts take the motion of the
    /// material at the contact point relative to the point's centre as
    /// L (x_c − x_p), so a rolling body does not drag its friction springs
    /// (a new contact of a point that had none takes V_p only).
    pub velocity_gradient: Vec<DMat2>,
    /// With `Settings::affine_transfer`, C_p = Σ_i v_i^{n+1} ⊗ G_ip, the
    /// gradient at the point of the nodal velocity of the last G2P, which
    /// the next P2G carries to the nodes; zero without it.
    pub affine_gradient: Vec<DMat2>,
    /// Cauchy stress σ_p.
    pub stress: Vec<SymTensor>,
    /// Accumulated small strain ∫ D dt (logarithmic for straight paths).
    pub strain: Vec<SymTensor>,
    /// Energy the point's material has dissipated since the start (J/m;
    /// per radian in axisymmetry): the plastic and viscous work its model
    /// returned each step (per unit volume) times its volume after the step.
    pub inelastic_work: Vec<Real>,
    /// Equivalent plastic strain since the start, Σ √(2/3 Δe_p : Δe_p)
    /// over the steps, Δe_p the deviator of a step's plastic strain
    /// increment (zero for models without plastic strain).
    pub plastic_strain: Vec<Real>,
    /// External force applied by the user or a system (N/m); not reset by the
    /// engine. Gravity is not included here.
    pub external_force: Vec<DVec2>,
    /// Half-size of the GIMP domain (undeformed).
    pub half_size: Vec<DVec2>,
    /// Radius of the DEM disk the point is for contacts (section 3.1).
    pub contact_radius: Vec<Real>,
    /// Sum of this step's contact forces on the point (N/m), written by
    /// the contact systems and reset by them each step.
    pub contact_force: Vec<DVec2>,
}

impl MaterialPoints {
    /// The smallest box holding every point's position, `None` without
    /// points, unbounded if a position is not finite (min and max are
    /// exact, so the result does not depend on the thread count).
    pub fn bounds(&self) -> Option<(DVec2, DVec2)> {
        // Per chunk, a plain fold without branches (min and max pass a NaN
        // by), then one test of whether every position was finite.
        let unbounded = (DVec2::NEG_INFINITY, DVec2::INFINITY);
        self.position
            .par_chunks(CHUNK_POINTS)
            .map(|chunk| {
                let start = (DVec2::INFINITY, DVec2::NEG_INFINITY, true);
                let (lo, hi, finite) = chunk.iter().fold(start, |(lo, hi, finite), x| {
                    (lo.min(*x), hi.max(*x), finite & x.is_finite())
                });
                if finite { (lo, hi) } else { unbounded }
            })
            .reduce_with(|(lo, hi), (a, b)| (lo.min(a), hi.max(b)))
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether the body has no point.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Appends a point.
    pub fn push(&mut self, p: NewPoint) {
        self.position.push(p.position);
        self.initial_position.push(p.position);
        self.velocity.push(p.velocity);
        self.mass.push(p.mass);
        self.initial_volume.push(p.volume);
        self.volume.push(p.volume);
        self.deformation_gradient.push(DMat2::IDENTITY);
        self.velocity_gradient.push(DMat2::ZERO);
        self.affine_gradient.push(DMat2::ZERO);
        self.stress.push(p.stress);
        self.strain.push(SymTensor::ZERO);
        self.inelastic_work.push(0.0);
        self.plastic_strain.push(0.0);
        self.external_force.push(DVec2::ZERO);
        self.half_size.push(p.half_size);
        self.contact_radius.push(p.contact_radius);
        self.contact_force.push(DVec2::ZERO);
    }

    /// The points at `indices`, in that order, with every column.
    pub fn select(&self, indices: &[usize]) -> Self {
        let Self {
            position,
            initial_position,
            velocity,
            mass,
            initial_volume,
            volume,
            deformation_gradient,
            velocity_gradient,
            affine_gradient,
            stress,
            strain,
            inelastic_work,
            plastic_strain,
            external_force,
            half_size,
            contact_radius,
            contact_force,
        } = self;
        fn pick<T: Copy>(column: &[T], indices: &[usize]) -> Vec<T> {
            indices.iter().map(|&p| column[p]).collect()
        }
        Self {
            position: pick(position, indices),
            initial_position: pick(initial_position, indices),
            velocity: pick(velocity, indices),
            mass: pick(mass, indices),
            initial_volume: pick(initial_volume, indices),
            volume: pick(volume, indices),
            deformation_gradient: pick(deformation_gradient, indices),
            velocity_gradient: pick(velocity_gradient, indices),
            affine_gradient: pick(affine_gradient, indices),
            stress: pick(stress, indices),
            strain: pick(strain, indices),
            inelastic_work: pick(inelastic_work, indices),
            plastic_strain: pick(plastic_strain, indices),
            external_force: pick(external_force, indices),
            half_size: pick(half_size, indices),
            contact_radius: pick(contact_radius, indices),
            contact_force: pick(contact_force, indices),
        }
    }

    /// Appends every point of `other`, with every column.
    pub fn append(&mut self, other: &Self) {
        let Self {
            position,
            initial_position,
            velocity,
            mass,
            initial_volume,
            volume,
            deformation_gradient,
            velocity_gradient,
            affine_gradient,
            stress,
            strain,
            inelastic_work,
            plastic_strain,
            external_force,
            half_size,
            contact_radius,
            contact_force,
        } = other;
        self.position.extend(position);
        self.initial_position.extend(initial_position);
        self.velocity.extend(velocity);
        self.mass.extend(mass);
        self.initial_volume.extend(initial_volume);
        self.volume.extend(volume);
        self.deformation_gradient.extend(deformation_gradient);
        self.velocity_gradient.extend(velocity_gradient);
        self.affine_gradient.extend(affine_gradient);
        self.stress.extend(stress);
        self.strain.extend(strain);
        self.inelastic_work.extend(inelastic_work);
        self.plastic_strain.extend(plastic_strain);
        self.external_force.extend(external_force);
        self.half_size.extend(half_size);
        self.contact_radius.extend(contact_radius);
        self.contact_force.extend(contact_force);
    }

    /// The radius at which point `p`'s hoop terms are taken in axisymmetry:
    /// `hoop_radius` of its position and domain.
    pub fn hoop_radius(&self, p: usize) -> Real {
        hoop_radius(self.position[p], self.half_size[p])
    }

    /// Displacement of point `p` from its initial position.
    pub fn displacement(&self, p: usize) -> DVec2 {
        self.position[p] - self.initial_position[p]
    }

    /// Total mass of the body.
    pub fn total_mass(&self) -> Real {
        self.mass.iter().sum()
    }

    /// Kinetic energy Σ ½ m |V|², stored strain energy Σ w(σ) V, the
    /// change of gravity's potential since the points were placed,
    /// −Σ m g · (x − X), and the inelastic work the materials dissipated
    /// (J/m).
    /// Points are summed in fixed chunks of `CHUNK_POINTS` in parallel and
    /// the chunk sums added in order, so the result never depends on the
    /// thread count.
    /// `chunk_sums` is scratch space, reused so that recording allocates nothing.
    pub fn energies(
        &self,
        model: &dyn ConstitutiveModel,
        gravity: DVec2,
        geometry: Geometry,
        chunk_sums: &mut Vec<PointEnergies>,
    ) -> PointEnergies {
        (0..self.len().div_ceil(CHUNK_POINTS))
            .into_par_iter()
            .map(|c| {
                let range = c * CHUNK_POINTS..((c + 1) * CHUNK_POINTS).min(self.len());
                self.sum_energies(model, gravity, geometry, range)
            })
            .collect_into_vec(chunk_sums);
        chunk_sums
            .iter()
            .fold(PointEnergies::default(), |sum, chunk| sum + *chunk)
    }

    /// The energies of [`Self::energies`] of each group of `groups` (point
    /// indices), summed in order within a group, groups in parallel.
    pub(crate) fn energies_of_groups<'a>(
        &self,
        model: &dyn ConstitutiveModel,
        gravity: DVec2,
        geometry: Geometry,
        groups: impl IndexedParallelIterator<Item = &'a [u32]>,
        sums: &mut Vec<PointEnergies>,
    ) {
        groups
            .map(|group| {
                let points = group.iter().map(|&p| p as usize);
                self.sum_energies(model, gravity, geometry, points)
            })
            .collect_into_vec(sums);
    }

    /// The energies of `points`, summed in their order.
    fn sum_energies(
        &self,
        model: &dyn ConstitutiveModel,
        gravity: DVec2,
        geometry: Geometry,
        points: impl Iterator<Item = usize>,
    ) -> PointEnergies {
        // F_zz: 1 in plane strain, the hoop stretch exp(ε_θθ) in
        // axisymmetry (as the stress update takes it).
        let f_zz = |p: usize| match geometry {
            Geometry::PlaneStrain => 1.0,
            Geometry::Axisymmetric => self.strain[p].zz.exp(),
        };
        points.fold(PointEnergies::default(), |sum, p| PointEnergies {
            kinetic: sum.kinetic + 0.5 * self.mass[p] * self.velocity[p].length_squared(),
            strain: sum.strain
                + model.stored_energy_density(
                    &self.stress[p],
                    &self.deformation_gradient[p],
                    f_zz(p),
                ) * self.volume[p],
            gravity: sum.gravity - self.mass[p] * gravity.dot(self.displacement(p)),
            inelastic: sum.inelastic + self.inelastic_work[p],
        })
    }

    /// Total linear momentum Σ m_p V_p.
    pub fn momentum(&self) -> DVec2 {
        self.mass
            .iter()
            .zip(&self.velocity)
            .map(|(m, v)| *m * *v)
            .sum()
    }
}

/// The radius r at which a point at `position` with domain half-size
/// `half_size` takes its hoop terms (σ_θθ / r, v_r / r) in axisymmetry:
/// its centre's, but at least a quarter of its domain's width from the
/// axis. The grid holds the axis's radial velocity at zero, so the
/// interpolated velocity of a point near the axis shrinks with r and
/// never carries it there; only a wall's clamp (a point whose PIC/FLIP
/// velocity would cross the axis is put on it) brings a centre closer,
/// and the floor keeps its hoop terms finite.
#[inline]
pub fn hoop_radius(position: DVec2, half_size: DVec2) -> Real {
    position.x.max(0.5 * half_size.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box is exact around finite points, spans more than one chunk,
    /// and is unbounded as soon as one position is not finite.
    #[test]
    fn bounds_hold_every_point_or_none() {
        let mut points = MaterialPoints::default();
        assert_eq!(points.bounds(), None);
        let n = 3 * CHUNK_POINTS + 7;
        points.position = (0..n)
            .map(|k| DVec2::new((k as Real * 0.37).sin(), k as Real * 1e-3 - 1.0))
            .collect();
        let lo = points
            .position
            .iter()
            .fold(DVec2::INFINITY, |a, x| a.min(*x));
        let hi = points
            .position
            .iter()
            .fold(DVec2::NEG_INFINITY, |a, x| a.max(*x));
        assert_eq!(points.bounds(), Some((lo, hi)));
        for broken in [Real::NAN, Real::INFINITY] {
            let mut bad = points.clone();
            bad.position[2 * CHUNK_POINTS + 3].y = broken;
            assert_eq!(
                bad.bounds(),
                Some((DVec2::NEG_INFINITY, DVec2::INFINITY)),
                "{broken}"
            );
        }
    }
}
