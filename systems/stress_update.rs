//! Algorithm 1, line 13: strain rate at the points and the constitutive update.

use crate::components::{
    GridLayer, GridNode, Material, MaterialPoints, TransferScratch, hoop_radius,
};
use crate::materials::{ConstitutiveModel, MaterialModel, PointStep};
use crate::math::{DMat2, DVec2, Real, outer, rate_of_deformation, spin};
use crate::parallel::MIN_POINTS_PER_TASK;
use crate::resources::{Clock, Geometry, Settings, UpdateScheme};
use crate::shape_functions::Stencil;
use bevy_ecs::prelude::*;
use rayon::prelude::*;

/// For every point: velocity gradient L_p = Σ_i v_i ⊗ G_ip, deformation
/// gradient F ← (I + L Δt) F, volume V = det(F) V⁰, stress from the body's
/// model with D = sym L and W = skew L, strain ε += D Δt, and the energy
/// the model dissipated (per unit volume, times V^{n+1}) added to the
/// point's inelastic work. In axisymmetry
/// D_zz is the hoop rate ε̇_θθ = Σ_i S_ip v_i,r / r_p (r_p at x^n under
/// USF; under USL and MUSL, which run after G2P, at x^{n+1}), and the volume
/// V = det(F) F_θθ V⁰ with F_θθ = exp(ε_θθ), ε_θθ the hoop strain after
/// the step. USF uses the nodal
/// velocity at the start of the step, USL the updated one, and MUSL the
/// points' new velocities mapped back to the nodes, the field that moves
/// them under `PositionUpdate::RemappedVelocity`; all with the gradients
/// at x^n.
/// The scheme is fixed here, with the order of the sets, when the schedule
/// is built.
///
/// USL with the updated nodal velocity dissipates: the strain follows the
/// whole change of the nodal velocity, but the points keep only what the
/// map to the points and back returns to the next step's nodes (for FLIP
/// M_L⁻¹ M_C, the consistent mass matrix over the lumped one, which keeps
/// smooth modes and damps those the lattice resolves poorly). In a model
/// of one mode of frequency ω that the map keeps a fraction λ of (taking
/// the mode to be one of both the stiffness and the map), a step
/// multiplies its phase-space area by 1 − (1 − λ)(ωΔt)²; MUSL's strain
/// follows what the points keep, and under FLIP without damping the area
/// stays (with a PIC fraction both lose what PIC takes, which the energy
/// balance counts as `damped`).
///
/// Reads: `Clock`, `Settings::geometry`, `GridLayer`,
/// `TransferScratch::stencils` and `remap` (MUSL), `Material`,
/// `MaterialPoints` (in axisymmetry position and half-size).
/// Writes: `MaterialPoints` (deformation gradient, volume, stress, strain,
/// inelastic work).
pub fn update_stress(
    scheme: UpdateScheme,
) -> impl FnMut(Res<Clock>, Res<Settings>, Query<StressUpdateData>) {
    move |clock, settings, mut bodies| {
        let geometry = settings.geometry;
        for (material, mut points, layer, scratch) in &mut bodies {
            let window = layer.window();
            let velocity = match scheme {
                UpdateScheme::Usf => StrainVelocity::Mapped(layer.nodes()),
                UpdateScheme::Usl => StrainVelocity::Updated(layer.nodes()),
                UpdateScheme::Musl => StrainVelocity::Remapped(&scratch.remap.current),
            };
            let step = StrainStep {
                velocity,
                origin: window.start.map(|k| k as u32),
                row_len: window.width(),
                dt: clock.dt,
                geometry,
            };
            match &material.model {
                MaterialModel::LinearElastic(m) => {
                    step.apply(&m.prepared(), &mut points, &scratch.stencils)
                }
                MaterialModel::NeoHookean(m) => step.apply(m, &mut points, &scratch.stencils),
                MaterialModel::MohrCoulomb(m) => {
                    step.apply(&m.prepared(), &mut points, &scratch.stencils)
                }
                MaterialModel::DruckerPrager(m) => {
                    step.apply(&m.prepared(), &mut points, &scratch.stencils)
                }
                MaterialModel::NewtonianFluid(m) => step.apply(m, &mut points, &scratch.stencils),
                MaterialModel::User(m) => step.apply(m, &mut points, &scratch.stencils),
            }
        }
    }
}

/// The components the stress update reads and writes per body.
type StressUpdateData = (
    &'static Material,
    &'static mut MaterialPoints,
    &'static GridLayer,
    &'static TransferScratch,
);

/// The nodal velocity field the strain rate follows.
#[derive(Clone, Copy)]
enum StrainVelocity<'a> {
    /// USF: v^n, mapped from the points at the start of the step.
    Mapped(&'a [GridNode]),
    /// USL: v^{n+1}, the nodal solve's.
    Updated(&'a [GridNode]),
    /// MUSL: ṽ, the points' new
    /// velocities mapped back to the nodes by G2P
    /// (`TransferScratch::remap.current`, one per stored node).
    Remapped(&'a [DVec2]),
}

/// What the stress update of one body reads from its layer.
struct StrainStep<'a> {
    /// The nodal velocities, laid out as the layer's stored nodes.
    velocity: StrainVelocity<'a>,
    /// The grid node of the first stored node.
    origin: [u32; 2],
    /// Stored nodes per row.
    row_len: usize,
    dt: Real,
    geometry: Geometry,
}

impl StrainStep<'_> {
    fn apply<M: ConstitutiveModel>(
        &self,
        model: &M,
        points: &mut MaterialPoints,
        stencils: &[Stencil],
    ) {
        let MaterialPoints {
            deformation_gradient,
            stress,
            strain,
            inelastic_work,
            plastic_strain,
            volume,
            initial_volume,
            position,
            half_size,
            ..
        } = points;
        let axisymmetric = self.geometry == Geometry::Axisymmetric;
        (
            deformation_gradient.par_iter_mut(),
            stress.par_iter_mut(),
            (
                strain.par_iter_mut(),
                inelastic_work.par_iter_mut(),
                plastic_strain.par_iter_mut(),
            ),
            volume.par_iter_mut(),
            initial_volume.par_iter(),
            stencils.par_iter(),
        )
            .into_par_iter()
            .with_min_len(MIN_POINTS_PER_TASK)
            .enumerate()
            .for_each(
                |(p, (f, sigma, (eps, dissipated, plastic), v, v0, stencil))| {
                    let l = self.velocity_gradient(stencil);
                    *f = (DMat2::IDENTITY + l * self.dt) * *f;
                    let mut d = rate_of_deformation(l);
                    let mut f_zz = 1.0;
                    if axisymmetric {
                        // ε̇_θθ = v_r / r, and F_θθ = exp(ε_θθ) with ε_θθ the
                        // integral of that rate (the hoop strain column), so
                        // the stored energy of a model that reads F_θθ changes
                        // by the work of σ_θθ ε̇_θθ, as the in-plane F does with
                        // the in-plane rate. (The points' r / R moves with their
                        // position update instead: a Neo-Hookean cylinder's
                        // energy drifted 0.9% against 0.1% for the linear one.)
                        let r = hoop_radius(position[p], half_size[p]);
                        d.zz = self.radial_velocity(stencil) / r;
                        f_zz = (eps.zz + d.zz * self.dt).exp();
                        *v = f.determinant() * f_zz * v0;
                    } else {
                        *v = f.determinant() * v0;
                    }
                    let step = PointStep {
                        d,
                        w: spin(l),
                        f: *f,
                        f_zz,
                        dt: self.dt,
                    };
                    if M::dissipates() {
                        let (dissipation, plastic_step) =
                            model.update_stress_and_plastic_strain(sigma, &step);
                        *dissipated += dissipation * *v;
                        *plastic += plastic_step;
                    } else {
                        model.update_stress(sigma, &step);
                    }
                    *eps += d * self.dt;
                },
            );
    }

    /// The radial velocity at the point, Σ_i S_ip v_i,r (axisymmetry).
    #[inline(always)]
    fn radial_velocity(&self, stencil: &Stencil) -> Real {
        self.gather(stencil, 0.0, |u, v, w, _| u + w * v.x)
    }

    /// L_p = Σ_i v_i ⊗ G_ip of the field the strain rate follows.
    #[inline(always)]
    fn velocity_gradient(&self, stencil: &Stencil) -> DMat2 {
        self.gather(stencil, DMat2::ZERO, |l, v, _, g| l + outer(v, g))
    }

    /// Folds `f` over the stencil's nodes with the velocity the strain rate
    /// follows (the match is made once per point, not per node).
    #[inline(always)]
    fn gather<A>(&self, stencil: &Stencil, init: A, f: impl Fn(A, DVec2, Real, DVec2) -> A) -> A {
        let (o, n) = (self.origin, self.row_len);
        match self.velocity {
            StrainVelocity::Mapped(nodes) => {
                stencil.gather(nodes, o, n, init, |a, node, w, g| f(a, node.velocity, w, g))
            }
            StrainVelocity::Updated(nodes) => stencil.gather(nodes, o, n, init, |a, node, w, g| {
                f(a, node.velocity_new, w, g)
            }),
            StrainVelocity::Remapped(v) => {
                stencil.gather(v, o, n, init, |a, v, w, g| f(a, *v, w, g))
            }
        }
    }
}
