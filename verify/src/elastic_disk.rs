//! The Hertz disks by explicit finite elements: a reference independent of
//! the material point method and of the DEM contact, for disks of the same
//! material law under the same load.
//!
//! Two equal frictionless disks pressed together by opposite body forces
//! touch on their plane of symmetry, which stays straight: each disk
//! presses on it as on a frictionless rigid wall. So one disk is modelled,
//! its centre at (−R, 0), against the wall x = 0.
//!
//! The mesh is the square [−1, 1]² of (2n)² bilinear (Q4) elements mapped
//! onto the disk by blending the square into the circle,
//! (u, v) ↦ R (u, v) (1 − s + s² / |(u, v)|), s = max(|u|, |v|): the nodes
//! of the square's boundary land on the circle, so the disk's outline is
//! smooth to the mesh's resolution (no lattice facets), and near the pole
//! where the disk touches the elements are nearly square, of side R/n.
//!
//! The formulation is updated Lagrangian: at each of an element's 2 × 2
//! Gauss points the step's velocity gradient goes to the scene's own
//! constitutive model (`update_stress`, the law of the material points),
//! and the nodal forces are −∫ σ ∇N dv over the current configuration.
//! Masses are lumped (∫ ρ N dV); time stepping is symplectic Euler, with
//! local damping of the nodal forces to keep the loading quasi-static. The
//! wall is a kinematic constraint: a node that would cross it stops on it,
//! and the force that stops it is its contact reaction. F is the sum of the
//! reactions and a the half-width from their spread, 2 √(Σ|r|(y − ȳ)²/Σ|r|),
//! as the engine measures it between material points, over the nodes'
//! current positions and over their initial ones.

use super::quad4::{gauss_points, local_gradients, shape};
use mpdem::materials::{MaterialModel, PointStep};
use mpdem::math::{DMat2, DVec2, Real, SymTensor, local_damping, outer, rate_of_deformation, spin};
use rayon::prelude::*;

/// One disk pressed by a ramped body force on the frictionless wall x = 0.
#[derive(Clone, Debug)]
pub struct ElasticDisk {
    /// Radius (m).
    pub radius: Real,
    /// Material law.
    pub material: MaterialModel,
    /// Density (kg/m³).
    pub density: Real,
    /// Body force per unit mass towards the wall at the end of the ramp (m/s²).
    pub acceleration: Real,
    /// Time over which the body force grows linearly from zero (s).
    pub ramp_time: Real,
    /// Time the loading runs to (s).
    pub end_time: Real,
    /// Local damping coefficient of the nodal forces (0 to 1).
    pub damping: Real,
    /// Elements along the radius at the pole, n.
    pub divisions: usize,
    /// Geometrically linear: gradients and forces taken on the initial
    /// configuration, no spin, and F = I + ∇u; with a linear elastic law
    /// this is the small-strain theory that Hertz's law comes from. The
    /// contact with the wall still follows the nodes' current positions.
    pub small_strain: bool,
}

/// Shape function gradients with respect to position at one Gauss point,
/// and the Jacobian's determinant (its area weight).
type GaussGradients = ([DVec2; 4], Real);

/// State at one Gauss point: Cauchy stress and deformation gradient.
#[derive(Clone, Copy, Debug)]
struct GaussState {
    stress: SymTensor,
    deformation: DMat2,
}

/// The mesh and its state.
struct Mesh {
    /// Node indices of each element, counter-clockwise.
    connectivity: Vec<[usize; 4]>,
    /// Lumped nodal masses (kg/m).
    mass: Vec<Real>,
    /// Initial node positions.
    x_initial: Vec<DVec2>,
    /// Current node positions.
    x: Vec<DVec2>,
    /// Node velocities.
    v: Vec<DVec2>,
    /// Each element's shape function gradients and area weight at its Gauss
    /// points, on the configuration last measured.
    gradients: Vec<[GaussGradients; 4]>,
    /// The state of each element's Gauss points.
    gauss: Vec<[GaussState; 4]>,
}

/// Shape function gradients with respect to position, in the configuration
/// `x` of an element's nodes, at local coordinates `s`, and the Jacobian's
/// determinant (the Gauss point's area weight).
fn spatial_gradients(x: &[DVec2; 4], s: DVec2) -> GaussGradients {
    let local = local_gradients(s);
    let jacobian = x
        .iter()
        .zip(&local)
        .fold(DMat2::ZERO, |j, (x, g)| j + outer(*x, *g));
    let inverse_transpose = jacobian.inverse().transpose();
    (local.map(|g| inverse_transpose * g), jacobian.determinant())
}

impl Mesh {
    fn new(disk: &ElasticDisk) -> Self {
        let n = disk.divisions;
        let side = 2 * n + 1;
        let centre = DVec2::new(-disk.radius, 0.0);
        let x: Vec<DVec2> = (0..side)
            .flat_map(|i| (0..side).map(move |j| (i, j)))
            .map(|(i, j)| {
                let uv = DVec2::new(i as Real, j as Real) / n as Real - DVec2::ONE;
                let s = uv.x.abs().max(uv.y.abs());
                let blend = if s == 0.0 {
                    1.0
                } else {
                    1.0 - s + s * s / uv.length()
                };
                centre + disk.radius * blend * uv
            })
            .collect();
        let index = |i: usize, j: usize| i * side + j;
        let connectivity: Vec<[usize; 4]> = (0..2 * n)
            .flat_map(|i| (0..2 * n).map(move |j| (i, j)))
            .map(|(i, j)| {
                [
                    index(i, j),
                    index(i + 1, j),
                    index(i + 1, j + 1),
                    index(i, j + 1),
                ]
            })
            .collect();
        let rest = GaussState {
            stress: SymTensor::ZERO,
            deformation: DMat2::IDENTITY,
        };
        let mut mesh = Self {
            gauss: vec![[rest; 4]; connectivity.len()],
            gradients: vec![[([DVec2::ZERO; 4], 0.0); 4]; connectivity.len()],
            connectivity,
            mass: vec![0.0; x.len()],
            x_initial: x.clone(),
            v: vec![DVec2::ZERO; x.len()],
            x,
        };
        mesh.measure();
        for (nodes, gradients) in mesh.connectivity.iter().zip(&mesh.gradients) {
            for (s, (_, area)) in gauss_points().into_iter().zip(gradients) {
                for (&n, w) in nodes.iter().zip(shape(s)) {
                    mesh.mass[n] += disk.density * area * w;
                }
            }
        }
        mesh
    }

    /// Measures every element's gradients and area weights on the current
    /// configuration.
    fn measure(&mut self) {
        let x = &self.x;
        self.gradients
            .par_iter_mut()
            .zip(&self.connectivity)
            .for_each(|(gradients, nodes)| {
                let corners = nodes.map(|n| x[n]);
                *gradients = gauss_points().map(|s| spatial_gradients(&corners, s));
            });
    }

    /// The shortest element edge (m).
    fn shortest_edge(&self) -> Real {
        self.connectivity
            .iter()
            .flat_map(|e| (0..4).map(move |k| (e[k], e[(k + 1) % 4])))
            .map(|(a, b)| self.x[a].distance(self.x[b]))
            .fold(Real::INFINITY, Real::min)
    }

    /// Each element's share −∫ σ ∇N_a dv of its nodes' forces, over the
    /// configuration last measured.
    fn element_forces(&self, out: &mut [[DVec2; 4]]) {
        out.par_iter_mut()
            .zip(&self.gradients)
            .zip(&self.gauss)
            .for_each(|((forces, gradients), gauss)| {
                *forces = [DVec2::ZERO; 4];
                for ((gradients, area), state) in gradients.iter().zip(gauss) {
                    for (f, g) in forces.iter_mut().zip(gradients) {
                        *f -= *area * state.stress.dot(*g);
                    }
                }
            });
    }

    /// Advances every Gauss point's stress by the step's velocity gradient,
    /// taken on the configuration last measured (the start of the step, or
    /// the initial one in small strain, then without its spin and with
    /// F = I + ∇u).
    fn update_stresses(&mut self, model: &MaterialModel, small_strain: bool, dt: Real) {
        let model = model.as_model();
        let (x, x_initial, v) = (&self.x, &self.x_initial, &self.v);
        self.gauss
            .par_iter_mut()
            .zip(&self.connectivity)
            .zip(&self.gradients)
            .for_each(|((gauss, nodes), gradients)| {
                for (state, &(gradients, _)) in gauss.iter_mut().zip(gradients) {
                    let l = nodes
                        .iter()
                        .zip(gradients)
                        .fold(DMat2::ZERO, |l, (&n, g)| l + outer(v[n], g));
                    state.deformation = if small_strain {
                        nodes
                            .iter()
                            .zip(gradients)
                            .fold(DMat2::IDENTITY, |f, (&n, g)| {
                                f + outer(x[n] - x_initial[n], g)
                            })
                    } else {
                        (DMat2::IDENTITY + dt * l) * state.deformation
                    };
                    let step = PointStep {
                        d: rate_of_deformation(l),
                        w: if small_strain { 0.0 } else { spin(l) },
                        f: state.deformation,
                        f_zz: 1.0,
                        dt,
                    };
                    model.update_stress(&mut state.stress, &step);
                }
            });
    }
}

impl ElasticDisk {
    /// A quarter of the wave's crossing time of the shortest element edge
    /// (at the four corners of the mapped square, where the elements are
    /// nearly triangles): stable at n = 20 to 160 and damping 0 to 0.8.
    fn time_step(&self, mesh: &Mesh) -> Real {
        let wave_speed = (self.material.as_model().p_wave_modulus() / self.density).sqrt();
        0.25 * mesh.shortest_edge() / wave_speed
    }

    /// The loading curve: a sample every `interval` while the disk touches
    /// the wall.
    pub fn loading_curve(&self, interval: Real) -> Vec<WallSample> {
        let mut mesh = Mesh::new(self);
        let dt = self.time_step(&mesh);
        let mut element_forces = vec![[DVec2::ZERO; 4]; mesh.connectivity.len()];
        let mut force = vec![DVec2::ZERO; mesh.x.len()];
        let mut reactions: Vec<Reaction> = Vec::new();
        let mut curve = Vec::new();
        let steps = (self.end_time / dt).ceil() as usize;
        let mut next_sample = interval;
        for step in 1..=steps {
            let t = step as Real * dt;
            let load = self.acceleration * (t / self.ramp_time).min(1.0);
            // Small strain keeps the initial configuration's gradients.
            if !self.small_strain {
                mesh.measure();
            }
            mesh.element_forces(&mut element_forces);
            for (f, m) in force.iter_mut().zip(&mesh.mass) {
                *f = DVec2::new(*m * load, 0.0);
            }
            for (nodes, shares) in mesh.connectivity.iter().zip(&element_forces) {
                for (&n, share) in nodes.iter().zip(shares) {
                    force[n] += *share;
                }
            }
            reactions.clear();
            let Mesh {
                x,
                x_initial,
                v,
                mass,
                ..
            } = &mut mesh;
            let nodes = x.iter_mut().zip(v.iter_mut()).zip(&*x_initial);
            for (((x, v), initial), (f, m)) in nodes.zip(force.iter().zip(&*mass)) {
                *v += local_damping(*f, *v, self.damping) / *m * dt;
                if x.x + dt * v.x > 0.0 {
                    let stopped = -x.x / dt;
                    reactions.push(Reaction {
                        y: x.y,
                        initial_y: initial.y,
                        force: *m * (v.x - stopped) / dt,
                    });
                    v.x = stopped;
                    *x += *v * dt;
                    // On the wall exactly: a node a rounding error off it
                    // would move, and local damping would act on its force.
                    x.x = 0.0;
                } else {
                    *x += *v * dt;
                }
            }
            mesh.update_stresses(&self.material, self.small_strain, dt);
            if t >= next_sample {
                next_sample += interval;
                if let Some(sample) = WallSample::of(&reactions) {
                    curve.push(sample);
                }
            }
        }
        curve
    }
}

/// A node's reaction from the wall: its position across the wall, now and
/// in the initial configuration, and the force (N/m, ≥ 0).
#[derive(Clone, Copy, Debug)]
struct Reaction {
    y: Real,
    initial_y: Real,
    force: Real,
}

/// The wall's reactions at one time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallSample {
    /// Their sum F (N/m).
    pub force: Real,
    /// The contact's half-width from their spread over the nodes' current
    /// positions, 2 √(Σ r (y − ȳ)² / F) (m), as the engine measures it
    /// between material points.
    pub half_width: Real,
    /// The same over the nodes' initial positions (m): the half-width of
    /// small-strain theory, which does not tell the configurations apart.
    pub initial_half_width: Real,
}

impl WallSample {
    /// The sample of `reactions`; none without contact.
    fn of(reactions: &[Reaction]) -> Option<Self> {
        let force: Real = reactions.iter().map(|r| r.force).sum();
        if force <= 0.0 {
            return None;
        }
        let half_width = |position: fn(&Reaction) -> Real| {
            let mean = reactions
                .iter()
                .map(|r| r.force * position(r))
                .sum::<Real>()
                / force;
            let variance = reactions
                .iter()
                .map(|r| r.force * (position(r) - mean).powi(2))
                .sum::<Real>()
                / force;
            2.0 * variance.sqrt()
        };
        Some(Self {
            force,
            half_width: half_width(|r| r.y),
            initial_half_width: half_width(|r| r.initial_y),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hertz::line_contact_force;
    use mpdem::materials::LinearElastic;

    /// The Hertz scene's disk, meshed with `divisions` elements per radius.
    fn glass_disk(divisions: usize) -> ElasticDisk {
        ElasticDisk {
            radius: 0.01,
            material: MaterialModel::LinearElastic(LinearElastic {
                youngs_modulus: 9.4e10,
                poisson_ratio: 0.07,
            }),
            density: 2500.0,
            acceleration: 1e8,
            ramp_time: 1e-4,
            end_time: 1e-4,
            damping: 0.5,
            divisions,
            small_strain: false,
        }
    }

    #[test]
    fn the_mesh_outline_lies_on_the_circle_and_the_masses_fill_it() {
        let disk = glass_disk(6);
        let mesh = Mesh::new(&disk);
        let side = 2 * disk.divisions + 1;
        let centre = DVec2::new(-disk.radius, 0.0);
        for i in 0..side {
            for j in 0..side {
                if i == 0 || j == 0 || i == side - 1 || j == side - 1 {
                    let r = mesh.x[i * side + j].distance(centre);
                    assert!(
                        (r / disk.radius - 1.0).abs() < 1e-14,
                        "node ({i}, {j}) at {r}"
                    );
                }
            }
        }
        // The masses fill the inscribed polygon of the outline's 8n nodes,
        // whose sides subtend at most 1/n rad (at the poles): it falls short
        // of the circle by Σ R² Δθ³ / 12 ≤ R² 2π / (12 n²), a fraction
        // 1/(6n²) of its area.
        let mass: Real = mesh.mass.iter().sum();
        let deficit = 1.0 - mass / (disk.density * std::f64::consts::PI * disk.radius.powi(2));
        let bound = 1.0 / (6.0 * (disk.divisions as Real).powi(2));
        assert!(deficit > 0.0 && deficit < bound, "{deficit} vs {bound}");
    }

    #[test]
    fn a_uniform_velocity_gradient_gives_the_models_stress_and_no_interior_forces() {
        let disk = glass_disk(4);
        let mut mesh = Mesh::new(&disk);
        let l = DMat2::from_cols(DVec2::new(-3.0, 1.0), DVec2::new(0.5, 2.0));
        mesh.v = mesh.x.iter().map(|x| l * *x).collect();
        let dt = 1e-4;
        mesh.update_stresses(&disk.material, false, dt);
        let mut expected = SymTensor::ZERO;
        disk.material.as_model().update_stress(
            &mut expected,
            &PointStep {
                d: rate_of_deformation(l),
                w: spin(l),
                f: DMat2::IDENTITY + dt * l,
                f_zz: 1.0,
                dt,
            },
        );
        for state in mesh.gauss.iter().flatten() {
            let difference = state.stress + expected * -1.0;
            assert!(
                difference.contract(&difference).sqrt()
                    < 1e-9 * expected.contract(&expected).sqrt()
            );
        }
        // A uniform stress is in equilibrium: −∫ σ ∇N dv cancels at every
        // interior node, and the outline's forces add up to zero.
        let mut shares = vec![[DVec2::ZERO; 4]; mesh.connectivity.len()];
        mesh.element_forces(&mut shares);
        let mut force = vec![DVec2::ZERO; mesh.x.len()];
        for (nodes, share) in mesh.connectivity.iter().zip(&shares) {
            for (&n, f) in nodes.iter().zip(share) {
                force[n] += *f;
            }
        }
        let side = 2 * disk.divisions + 1;
        let scale = expected.xx.abs() * disk.radius;
        for i in 1..side - 1 {
            for j in 1..side - 1 {
                assert!(
                    force[i * side + j].length() < 1e-9 * scale,
                    "node ({i}, {j})"
                );
            }
        }
        assert!(force.iter().sum::<DVec2>().length() < 1e-9 * scale);
    }

    /// Mean of |F / F_Hertz(a) − 1| over the loads at which Hertz gives
    /// 0.2 R ≤ a ≤ 0.3 R (the Hertz scene's window), for `disk` of linear
    /// elastic modulus E and Poisson's ratio ν, a measured over the nodes'
    /// initial positions and over their current ones.
    fn departures_from_hertz(
        disk: &ElasticDisk,
        youngs_modulus: Real,
        poisson_ratio: Real,
    ) -> [Real; 2] {
        let hertz = |a: Real| line_contact_force(youngs_modulus, poisson_ratio, disk.radius, a);
        let window = hertz(0.2 * disk.radius)..=hertz(0.3 * disk.radius);
        let inside: Vec<WallSample> = disk
            .loading_curve(1e-6)
            .into_iter()
            .filter(|s| window.contains(&s.force))
            .collect();
        assert!(inside.len() >= 10, "{} samples in the window", inside.len());
        let mean = |a: fn(&WallSample) -> Real| {
            inside
                .iter()
                .map(|s| (s.force / hertz(a(s)) - 1.0).abs())
                .sum::<Real>()
                / inside.len() as Real
        };
        [mean(|s| s.initial_half_width), mean(|s| s.half_width)]
    }

    #[test]
    fn in_small_strain_the_disk_follows_hertz_with_the_zone_of_the_undeformed_disk() {
        // Geometrically linear elements at R/20 (R/40 moves these errors by
        // 1.4% at most). Over the nodes' initial positions, which small-strain
        // theory does not tell from the current ones, the disk follows Hertz
        // (measured 3.0% at ν = 0.07, 5.3% at ν = 0.45; Hertz's parabola
        // standing for the circle accounts for up to 3a²/8R² = 3.4% at
        // a = 0.3 R). 7% is the larger of these with a margin; it fails the
        // current positions' 20.2% at ν = 0.07. Over those the zone is
        // narrower by the surface's slide towards its centre, ∝ (1 − 2ν) a/R:
        // 20.2% at ν = 0.07 and 3.3% at ν = 0.45.
        let mut disk = glass_disk(20);
        disk.small_strain = true;
        let modulus = 9.4e10;
        for (poisson_ratio, current) in [(0.07, 0.15..0.30), (0.45, 0.0..0.07)] {
            disk.material = MaterialModel::LinearElastic(LinearElastic {
                youngs_modulus: modulus,
                poisson_ratio,
            });
            let [undeformed, now] = departures_from_hertz(&disk, modulus, poisson_ratio);
            assert!(undeformed < 0.07, "ν = {poisson_ratio}: {undeformed}");
            assert!(current.contains(&now), "ν = {poisson_ratio}: {now}");
        }
    }

    #[test]
    fn a_prestressed_disk_turned_rigidly_keeps_its_stress_turned_with_it() {
        // Jaumann's rate turns the stress with the material: a rigid turn by
        // θ leaves σ' = R σ Rᵀ. Steps of ω dt = 1e-4 keep forward Euler's
        // rotation error below 1e-4 and the chord's dilation (θ² per step)
        // below 1e-5 strain, 0.05% of the prestress; 0.5% bounds both. A
        // velocity gradient built transposed would turn the stress the
        // other way: about 26% off in the shear.
        let disk = glass_disk(4);
        let mut mesh = Mesh::new(&disk);
        let prestress = SymTensor::new(-1e9, 3e8, 4e8, -2e8);
        for state in mesh.gauss.iter_mut().flatten() {
            state.stress = prestress;
        }
        let (centre, step_angle, dt) = (DVec2::new(-disk.radius, 0.0), 1e-4, 1e-6);
        let turn = DVec2::from_angle(step_angle);
        for _ in 0..1000 {
            mesh.measure();
            for (x, v) in mesh.x.iter_mut().zip(mesh.v.iter_mut()) {
                let next = centre + turn.rotate(*x - centre);
                *v = (next - *x) / dt;
                *x = next;
            }
            mesh.update_stresses(&disk.material, false, dt);
        }
        let (c, s) = (0.1_f64.cos(), 0.1_f64.sin());
        let rotation = DMat2::from_cols(DVec2::new(c, s), DVec2::new(-s, c));
        let p = DMat2::from_cols(
            DVec2::new(prestress.xx, prestress.xy),
            DVec2::new(prestress.xy, prestress.yy),
        );
        let expected = rotation * p * rotation.transpose();
        let scale = prestress.xx.abs();
        for state in mesh.gauss.iter().flatten() {
            let got = state.stress;
            let error = (got.xx - expected.x_axis.x)
                .abs()
                .max((got.yy - expected.y_axis.y).abs())
                .max((got.xy - expected.y_axis.x).abs());
            assert!(error < 5e-3 * scale, "{got:?} vs {expected:?}");
        }
    }

    #[test]
    fn the_wall_carries_the_applied_load_at_the_end_of_the_ramp() {
        let disk = glass_disk(10);
        let curve = disk.loading_curve(1e-6);
        let WallSample {
            half_width, force, ..
        } = *curve.last().expect("in contact");
        let mass: Real = Mesh::new(&disk).mass.iter().sum();
        let applied = mass * disk.acceleration;
        // Quasi-static: the wall carries the body force to within the lag
        // of the damped ramp (measured +1.0% at R/80).
        assert!((force / applied - 1.0).abs() < 0.02, "{force} vs {applied}");
        assert!(half_width > 0.1 * disk.radius && half_width < 0.5 * disk.radius);
    }
}
