//! Time series recorded during a run: probes and energies.

use super::Geometry;
use super::body_contacts::PairSummary;
use crate::components::{
    BlockId, Material, MaterialPoints, PartReactions, PointEnergies, Pose, Reaction, RigidVelocity,
};
use crate::math::{DVec2, Real, SymTensor};
use bevy_ecs::prelude::{Entity, Resource};
use serde::{Deserialize, Serialize};

/// A watched material point.
#[derive(Clone, Debug, PartialEq)]
pub struct Probe {
    /// Name from the scene.
    pub name: String,
    /// The body entity.
    pub body: Entity,
    /// Index of the point in its body (the point nearest the requested location at the start).
    pub point: usize,
}

/// One recorded state of a probe.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProbeSample {
    /// Index of the probe in [`Probes::probes`].
    pub probe: usize,
    /// Simulated time (s).
    pub time: Real,
    /// Position (m).
    pub position: DVec2,
    /// Displacement from the initial position (m).
    pub displacement: DVec2,
    /// Velocity (m/s).
    pub velocity: DVec2,
    /// Cauchy stress (Pa).
    pub stress: SymTensor,
}

impl ProbeSample {
    /// Probe `probe`'s sample at `time`, of point `p` of `points`.
    pub fn of(probe: usize, time: Real, points: &MaterialPoints, p: usize) -> Self {
        Self {
            probe,
            time,
            position: points.position[p],
            displacement: points.displacement(p),
            velocity: points.velocity[p],
            stress: points.stress[p],
        }
    }
}

/// When the records sample the run (`output.probe_interval`): every
/// `every` steps, at step 0 and at the run's last step. Every record
/// samples on these steps, so that a checkpoint's records agree (see
/// `checkpoint::TimeRecord`).
#[derive(Resource, Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampling {
    /// Recording period in steps (≥ 1).
    pub every: u64,
}

impl Sampling {
    /// Whether the step the clock has just taken is sampled: every
    /// `every` steps, and the run's last step (its end, or where its last
    /// stage ended it). Steps taken past the end (`Simulation::step` does
    /// not stop there) keep the interval.
    pub fn due(&self, clock: &crate::resources::Clock) -> bool {
        clock.step.is_multiple_of(self.every.max(1)) || clock.step == clock.total_steps()
    }
}

/// Probes and their samples, recorded when [`Sampling`] says.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct Probes {
    /// The watched points.
    pub probes: Vec<Probe>,
    /// Samples in time order, probes in order within a time.
    pub samples: Vec<ProbeSample>,
}

impl Probes {
    /// Appends one sample per probe at `time`; `points_of` gives a body's points.
    pub fn record<'a>(
        &mut self,
        time: Real,
        points_of: impl Fn(Entity) -> Option<&'a MaterialPoints>,
    ) {
        for (k, probe) in self.probes.iter().enumerate() {
            let Some(points) = points_of(probe.body) else {
                continue;
            };
            self.samples
                .push(ProbeSample::of(k, time, points, probe.point));
        }
    }

    /// The samples of probe `index`, in time order.
    pub fn series(&self, index: usize) -> impl Iterator<Item = &ProbeSample> {
        self.samples.iter().filter(move |s| s.probe == index)
    }
}

/// Energies of all bodies at one time (J per metre of thickness).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EnergySample {
    /// Simulated time (s).
    pub time: Real,
    /// Kinetic energy Σ ½ m_p |V_p|² (J/m).
    pub kinetic: Real,
    /// Stored strain energy Σ w(σ_p) V_p (J/m).
    pub strain: Real,
    /// Potential energy of the point contacts' springs, body–body and
    /// point–block (J/m).
    pub contact: Real,
    /// Gravity's potential relative to the initial positions,
    /// −Σ m_p g · (x_p − X_p) (J/m), with the gravity of the time.
    pub gravity: Real,
    /// Energy the bodies' materials have dissipated since the start (J/m):
    /// plastic work (Mohr–Coulomb, Drucker–Prager) and viscous work (the
    /// fluid), [`crate::components::MaterialPoints::inelastic_work`].
    pub inelastic: Real,
    /// Minus the work the stages' surface tractions have done on the bodies
    /// since the start (J/m; [`crate::resources::LoadWork`]): in plane
    /// strain, a dead load's potential −F · u (in axisymmetry the force per
    /// radian follows the loaded edge's radius).
    pub loads: Real,
    /// Minus the work the blocks have done on the bodies through the point
    /// contacts since the start (J/m; [`crate::resources::ContactWork::block_work`]):
    /// what a kinematic block drives into the bodies, or a dynamic block
    /// gives them (the blocks' own energy is not in the balance).
    pub blocks: Real,
    /// Energy the point contacts' tangential forces have taken from the
    /// bodies since the start and their springs do not hold (J/m): −W_t −
    /// Σ |f_t|²/(2 k_t), W_t their work on the actual relative motion at
    /// the contact points by the trapezoidal rule
    /// ([`crate::resources::ContactWork`]): Coulomb sliding and the springs
    /// of contacts that ended, less a new contact's first stretch (by the
    /// FLIP velocity, before the pair has an actual motion). The normal
    /// dashpot's work (`normal_damping`) is not in it.
    pub dissipated: Real,
    /// Energy grid and particle damping and the PIC (or XPIC) part of the
    /// velocity update have taken from the bodies since the start (J/m;
    /// [`crate::components::DampedEnergy`]).
    pub damped: Real,
}

impl EnergySample {
    /// The first term that is not finite, by its name in `energy.csv`.
    pub fn first_non_finite(&self) -> Option<&'static str> {
        [
            ("kinetic", self.kinetic),
            ("strain", self.strain),
            ("contact", self.contact),
            ("gravity", self.gravity),
            ("inelastic", self.inelastic),
            ("loads", self.loads),
            ("blocks", self.blocks),
            ("dissipated", self.dissipated),
            ("damped", self.damped),
        ]
        .into_iter()
        .find_map(|(name, value)| (!value.is_finite()).then_some(name))
    }

    /// The energies of `bodies` (in scene order) at `time` under `gravity`
    /// in `geometry` (with what their materials dissipated), without
    /// contacts, loads and damping (`contact`, `loads`, `blocks`,
    /// `dissipated` and `damped` zero); `scratch` is reused
    /// between calls (see [`MaterialPoints::energies`]).
    pub fn of<'a>(
        time: Real,
        bodies: impl Iterator<Item = (&'a MaterialPoints, &'a Material)>,
        gravity: DVec2,
        geometry: Geometry,
        scratch: &mut Vec<PointEnergies>,
    ) -> Self {
        let sum = bodies.fold(PointEnergies::default(), |sum, (points, material)| {
            sum + points.energies(material.model.as_model(), gravity, geometry, scratch)
        });
        Self::of_points(time, sum)
    }

    /// The sample at `time` of the points' energies `sum`, without
    /// contacts, loads and damping (see [`Self::of`]).
    pub fn of_points(time: Real, sum: PointEnergies) -> Self {
        Self {
            time,
            kinetic: sum.kinetic,
            strain: sum.strain,
            contact: 0.0,
            gravity: sum.gravity,
            inelastic: sum.inelastic,
            loads: 0.0,
            blocks: 0.0,
            dissipated: 0.0,
            damped: 0.0,
        }
    }

    /// Kinetic + strain + contact energy (J/m): conserved by a free elastic
    /// system without damping or friction (gravity's potential is not
    /// included).
    pub fn total(&self) -> Real {
        self.kinetic + self.strain + self.contact
    }

    /// Total + gravity's potential + what the materials dissipated + minus
    /// the work of the surface loads and of the blocks + what the contacts
    /// dissipated + what damping and the PIC part took (J/m): constant for
    /// bodies under constant gravity, touching each other and blocks, up to
    /// the MPM scheme's own error (for plastic bodies, that of taking the
    /// plastic work with the stress after the return). It leaves out the
    /// work of the contacts' normal dashpots and of the grid's boundaries,
    /// and the blocks' own energy.
    pub fn balance(&self) -> Real {
        self.total()
            + self.gravity
            + self.inelastic
            + self.loads
            + self.blocks
            + self.dissipated
            + self.damped
    }
}

/// Energy history, recorded when the probes are.
#[derive(Resource, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnergyLog {
    /// Samples in time order.
    pub samples: Vec<EnergySample>,
}

/// One recorded state of a rigid block.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BlockSample {
    /// Index of the block in the scene.
    pub block: u32,
    /// Simulated time (s).
    pub time: Real,
    /// Reaction force of the points on the block (N/m).
    pub force: DVec2,
    /// Reaction torque about the centre of mass (N m/m).
    pub torque: Real,
    /// Frame origin (m).
    pub origin: DVec2,
    /// Rotation (rad).
    pub angle: Real,
    /// Velocity of the centre of mass (m/s).
    pub velocity: DVec2,
    /// Angular velocity (rad/s).
    pub angular: Real,
}

/// Reactions and motion of every block, recorded when the probes are.
#[derive(Resource, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BlockLog {
    /// Block names by scene index.
    pub names: Vec<String>,
    /// Samples in time order, blocks in scene order within a time.
    pub samples: Vec<BlockSample>,
    /// Reactions on the parts of compound blocks, sampled with `samples`.
    pub parts: Vec<BlockPartSample>,
}

impl BlockLog {
    /// Appends a block's reaction, pose and velocity at `time` and, for a
    /// compound block (more than one part), the reactions on its parts.
    pub fn record(
        &mut self,
        time: Real,
        (id, reaction, parts, pose, velocity): (
            &BlockId,
            &Reaction,
            &PartReactions,
            &Pose,
            &RigidVelocity,
        ),
    ) {
        self.samples.push(BlockSample {
            block: id.index,
            time,
            force: reaction.force,
            torque: reaction.torque,
            origin: pose.origin,
            angle: pose.angle,
            velocity: velocity.linear,
            angular: velocity.angular,
        });
        if parts.0.len() > 1 {
            self.parts.extend(
                parts
                    .0
                    .iter()
                    .enumerate()
                    .map(|(k, force)| BlockPartSample {
                        block: id.index,
                        part: k as u32,
                        time,
                        force: *force,
                    }),
            );
        }
    }
}

/// The reaction on one part of a compound block at one time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BlockPartSample {
    /// Index of the block in the scene.
    pub block: u32,
    /// Index of the part in the block's compound.
    pub part: u32,
    /// Simulated time (s).
    pub time: Real,
    /// Force of the points on the part (N/m).
    pub force: DVec2,
}

/// The contacts between two bodies with a contact law at one time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyPairSample {
    /// Simulated time (s).
    pub time: Real,
    /// The lower body index.
    pub a: u32,
    /// The higher body index.
    pub b: u32,
    /// Their contacts summed up.
    pub summary: PairSummary,
}

/// Body–body contact history, every pair with a law, recorded when the
/// probes are.
#[derive(Resource, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BodyPairLog {
    /// Samples in time order, pairs in (a, b) order within a time.
    pub samples: Vec<BodyPairSample>,
}
