//! The toppling block's elastic motion by explicit finite elements: a
//! reference independent of the material point method, for the same
//! continuum resting on the same DEM contact disks.
//!
//! The block is meshed with square bilinear (Q4) plane-strain elements,
//! one per material point of the MPM scene (side one point spacing), with
//! 2 × 2 Gauss points and lumped masses, of a Saint Venant–Kirchhoff
//! material (stress from the Green strain, so a rigid rotation leaves it
//! unstrained; at the block's strains, below 1e-3, it is Hooke's law), and
//! integrated by symplectic Euler. Its base carries the MPM scene's contact
//! disks: each at the centre of a bottom element, where the scene's bottom
//! row of points is, of radius half a spacing, moving with its element and
//! pressing on the slope (the line y = 0, gravity turned by the slope
//! angle) by the engine's own contact law (eq. 18, `pair_force`). Its
//! tangential spring is stretched by the material's velocity at the
//! contact point, and its force acts on the material there.
//!
//! One element per point couples each disk to the block as an MPM point
//! couples to its domain. Finer elements would tie each disk to a single
//! node, whose small mass chatters on the stiff springs: at two elements
//! per spacing the block bounces off the slope.

use super::quad4::{gauss_points, local_gradients, shape};
use mpdem::contact::{ContactLaw, pair_force};
use mpdem::materials::{ConstitutiveModel, LinearElastic};
use mpdem::math::{DMat2, DVec2, Real, outer};

/// The block, its material and its disks.
#[derive(Clone, Debug)]
pub struct ElasticBlock {
    /// Width and height (m); the block's lower-left corner is at the origin.
    pub size: DVec2,
    /// Its moduli (the Saint Venant–Kirchhoff law takes λ and μ from them).
    pub material: LinearElastic,
    /// Density (kg/m³).
    pub density: Real,
    /// Gravity in the slope's frame (m/s²).
    pub gravity: DVec2,
    /// The MPM scene's point spacing (m): the disks' spacing and diameter.
    pub point_spacing: Real,
    /// The disks' contact law with the slope.
    pub contact: ContactLaw,
}

/// A material point of the mesh: its element and local coordinates in it.
#[derive(Clone, Copy, Debug)]
struct Place {
    element: usize,
    local: DVec2,
}

/// The mesh and its state.
struct Mesh {
    /// Element size (m).
    h: Real,
    /// Elements along x and y.
    elements: [usize; 2],
    /// Node indices of each element, counter-clockwise from lower-left.
    connectivity: Vec<[usize; 4]>,
    /// Lumped nodal masses (kg/m).
    mass: Vec<Real>,
    /// Current positions.
    x: Vec<DVec2>,
    /// Velocities.
    v: Vec<DVec2>,
}

/// Shape function gradients with respect to the reference position, for
/// square elements of size `h`, at local coordinates `s`.
fn gradients(s: DVec2, h: Real) -> [DVec2; 4] {
    local_gradients(s).map(|g| g * (2.0 / h))
}

impl Mesh {
    fn new(block: &ElasticBlock) -> Self {
        let h = block.point_spacing;
        let elements = [
            (block.size.x / h).round() as usize,
            (block.size.y / h).round() as usize,
        ];
        let rows = elements[1] + 1;
        let node = |i: usize, j: usize| i * rows + j;
        let mut connectivity = Vec::new();
        for i in 0..elements[0] {
            for j in 0..elements[1] {
                connectivity.push([
                    node(i, j),
                    node(i + 1, j),
                    node(i + 1, j + 1),
                    node(i, j + 1),
                ]);
            }
        }
        let x: Vec<DVec2> = (0..=elements[0])
            .flat_map(|i| (0..rows).map(move |j| DVec2::new(i as Real, j as Real) * h))
            .collect();
        let mut mass = vec![0.0; x.len()];
        for nodes in &connectivity {
            for &n in nodes {
                mass[n] += 0.25 * block.density * h * h;
            }
        }
        let v = vec![DVec2::ZERO; x.len()];
        Self {
            h,
            elements,
            connectivity,
            mass,
            x,
            v,
        }
    }

    /// The element holding reference position `at` (the nearest one for a
    /// position just outside the block) and the local coordinates there.
    fn place(&self, at: DVec2) -> Place {
        let cell =
            |value: Real, count: usize| ((value / self.h).floor().max(0.0) as usize).min(count - 1);
        let (i, j) = (cell(at.x, self.elements[0]), cell(at.y, self.elements[1]));
        let corner = DVec2::new(i as Real, j as Real) * self.h;
        Place {
            element: i * self.elements[1] + j,
            local: (at - corner) * (2.0 / self.h) - DVec2::ONE,
        }
    }

    /// Interpolates a nodal field at a place.
    fn at(&self, field: &[DVec2], place: Place) -> DVec2 {
        let nodes = self.connectivity[place.element];
        shape(place.local)
            .iter()
            .zip(nodes)
            .map(|(w, n)| *w * field[n])
            .sum()
    }

    /// The deformation gradient at a place.
    fn deformation_gradient(&self, place: Place) -> DMat2 {
        let nodes = self.connectivity[place.element];
        gradients(place.local, self.h)
            .iter()
            .zip(nodes)
            .fold(DMat2::ZERO, |f, (g, n)| f + outer(self.x[n], *g))
    }

    /// Adds −∫ P ∇N_a dV of every element to `force` (2 × 2 Gauss points,
    /// P = F S the first Piola–Kirchhoff stress, S = λ tr(E) I + 2μ E in
    /// plane strain, λ and μ those of `material`).
    fn add_internal_forces(&self, material: &LinearElastic, force: &mut [DVec2]) {
        let (lambda, mu) = (material.lame_lambda(), material.shear_modulus());
        let weight = 0.25 * self.h * self.h;
        let points = gauss_points().map(|s| gradients(s, self.h));
        for nodes in &self.connectivity {
            for g in &points {
                let f = nodes
                    .iter()
                    .zip(g)
                    .fold(DMat2::ZERO, |f, (&n, gn)| f + outer(self.x[n], *gn));
                let green = 0.5 * (f.transpose() * f - DMat2::IDENTITY);
                let trace = green.x_axis.x + green.y_axis.y;
                let second = 2.0 * mu * green + DMat2::from_diagonal(DVec2::splat(lambda * trace));
                let first = f * second;
                for (&n, gn) in nodes.iter().zip(g) {
                    force[n] -= weight * (first * *gn);
                }
            }
        }
    }
}

/// The contact disks on the block's base and their tangential springs.
struct Disks {
    /// Each disk's centre in the reference configuration and its place.
    centres: Vec<(DVec2, Place)>,
    /// Radius (m).
    radius: Real,
    /// Each disk's tangential spring force; zero out of contact.
    springs: Vec<DVec2>,
}

impl Disks {
    /// One disk per point of the bottom row, at `spacing`.
    fn new(mesh: &Mesh, width: Real, spacing: Real) -> Self {
        let centres: Vec<(DVec2, Place)> = (0..(width / spacing).round() as usize)
            .map(|k| {
                let centre = DVec2::new((k as Real + 0.5) * spacing, 0.5 * spacing);
                (centre, mesh.place(centre))
            })
            .collect();
        let springs = vec![DVec2::ZERO; centres.len()];
        Self {
            centres,
            radius: 0.5 * spacing,
            springs,
        }
    }

    /// Adds each disk's contact force with the slope (eq. 18 by
    /// `pair_force`) at the material point under its contact point.
    fn add_forces(&mut self, mesh: &Mesh, law: &ContactLaw, dt: Real, force: &mut [DVec2]) {
        for ((reference, place), spring) in self.centres.iter().zip(&mut self.springs) {
            let centre = mesh.at(&mesh.x, *place);
            let depth = self.radius - centre.y;
            if depth <= 0.0 {
                *spring = DVec2::ZERO;
                continue;
            }
            let touching = DVec2::new(centre.x, 0.0);
            let f = mesh.deformation_gradient(*place);
            let contact = mesh.place(*reference + f.inverse() * (touching - centre));
            let velocity = mesh.at(&mesh.v, contact);
            let pair = pair_force(law, depth, DVec2::Y, velocity, *spring, dt);
            *spring = pair.tangential;
            let nodes = mesh.connectivity[contact.element];
            for (w, n) in shape(contact.local).iter().zip(nodes) {
                force[n] += *w * pair.force;
            }
        }
    }
}

impl ElasticBlock {
    /// A fifth of the smaller of the elements' wave limit h/c_p and the
    /// disks' spring limit 2√(m/k_n), m a corner node's mass: symplectic
    /// Euler is stable below both, and halving it moves the 18° scene's
    /// rotations by 3e-4° at most.
    fn time_step(&self) -> Real {
        let p_wave = self.material.p_wave_modulus();
        let h = self.point_spacing;
        let wave = h / (p_wave / self.density).sqrt();
        let node = 0.25 * self.density * h * h;
        let spring = 2.0 * (node / self.contact.normal_stiffness).sqrt();
        0.2 * wave.min(spring)
    }

    /// The rotation ψ (rad, toppling downhill positive) at `times` of the
    /// axis between the material points `top` and `bottom` (reference
    /// positions from the block's lower-left corner), as the MPM scene's
    /// probes measure it.
    pub fn rotations(&self, top: DVec2, bottom: DVec2, times: &[Real]) -> Vec<Real> {
        let mut axis0 = None;
        self.observe(times, |mesh| {
            let (top, bottom) = (mesh.place(top), mesh.place(bottom));
            let axis = mesh.at(&mesh.x, top) - mesh.at(&mesh.x, bottom);
            let axis0 = *axis0.get_or_insert(axis);
            -axis0.perp_dot(axis).atan2(axis0.dot(axis))
        })
    }

    /// The displacement (m) of the block's centre of mass at `times`.
    pub fn centre_displacements(&self, times: &[Real]) -> Vec<DVec2> {
        let mut start = None;
        self.observe(times, |mesh| {
            let total: Real = mesh.mass.iter().sum();
            let moment: DVec2 = mesh.x.iter().zip(&mesh.mass).map(|(x, m)| *m * *x).sum();
            let centre = moment / total;
            centre - *start.get_or_insert(centre)
        })
    }

    /// Integrates the block from rest under gravity applied at once, and
    /// returns `measure` of the mesh at the start and at each of `times`
    /// (the first value, at the start, is dropped).
    fn observe<T>(&self, times: &[Real], mut measure: impl FnMut(&Mesh) -> T) -> Vec<T> {
        let mut mesh = Mesh::new(self);
        let mut disks = Disks::new(&mesh, self.size.x, self.point_spacing);
        measure(&mesh);
        let dt = self.time_step();
        let mut force = vec![DVec2::ZERO; mesh.x.len()];
        let (mut t, mut out) = (0.0, Vec::with_capacity(times.len()));
        for &until in times {
            while t < until - 0.5 * dt {
                for (f, m) in force.iter_mut().zip(&mesh.mass) {
                    *f = *m * self.gravity;
                }
                mesh.add_internal_forces(&self.material, &mut force);
                disks.add_forces(&mesh, &self.contact, dt, &mut force);
                let Mesh { x, v, mass, .. } = &mut mesh;
                for ((x, v), (f, m)) in x.iter_mut().zip(v.iter_mut()).zip(force.iter().zip(&*mass))
                {
                    *v += *f / *m * dt;
                    *x += *v * dt;
                }
                t += dt;
            }
            out.push(measure(&mesh));
        }
        out
    }
}
