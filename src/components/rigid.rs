//! Components of a rigid block (DESIGN.md section 2).

use crate::contact::ContactLaw;
use crate::math::{DVec2, Real};
use bevy_ecs::prelude::{Component, Entity};
use parry2d_f64::shape::SharedShape;
use serde::{Deserialize, Serialize};

/// The block's name from the scene and its position in the scene's list of
/// blocks (the order of every loop whose results meet across blocks).
#[derive(Component, Clone, Debug, PartialEq, Eq)]
pub struct BlockId {
    /// Unique name.
    pub name: String,
    /// Index in the scene's `blocks`.
    pub index: u32,
}

/// The block's geometry in its own frame.
#[derive(Component, Clone)]
pub struct RigidShape(pub SharedShape);

/// Closed outlines of the block in its frame, for pictures.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct BlockOutline(pub Vec<Vec<DVec2>>);

impl BlockOutline {
    /// The outlines placed in the world at `pose`.
    pub fn in_world(&self, pose: &Pose) -> impl Iterator<Item = Vec<DVec2>> + '_ {
        let pose = *pose;
        self.0
            .iter()
            .map(move |line| line.iter().map(|p| pose.origin + pose.rotate(*p)).collect())
    }
}

/// Where the block's frame is: origin (m) and rotation (rad, counter-clockwise).
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position of the frame origin.
    pub origin: DVec2,
    /// Rotation of the frame.
    pub angle: Real,
}

impl Pose {
    /// The parry pose.
    pub fn to_parry(&self) -> parry2d_f64::math::Pose {
        parry2d_f64::math::Pose::new(self.origin, self.angle)
    }

    /// A vector of the block's frame expressed in the world.
    pub fn rotate(&self, v: DVec2) -> DVec2 {
        DVec2::from_angle(self.angle).rotate(v)
    }

    /// A world position in the block's frame.
    pub fn to_block(&self, x: DVec2) -> DVec2 {
        DVec2::from_angle(-self.angle).rotate(x - self.origin)
    }

    /// A position of the block's frame in the world.
    pub fn to_world(&self, local: DVec2) -> DVec2 {
        self.origin + self.rotate(local)
    }
}

/// Velocity of the block: of its centre of mass, and its spin (rad/s).
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigidVelocity {
    /// Velocity of the centre of mass (m/s).
    pub linear: DVec2,
    /// Angular velocity (rad/s, counter-clockwise).
    #[serde(default)]
    pub angular: Real,
}

/// How the block moves.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum RigidMotion {
    /// Never moves (ground, walls).
    Fixed,
    /// Moves with its prescribed `RigidVelocity`, whatever the forces.
    Kinematic,
    /// Moves under the reactions, gravity and block contacts.
    Dynamic,
}

/// Mass properties, from a density and the shape or given.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct RigidMass {
    /// Mass (kg per metre of thickness).
    pub mass: Real,
    /// Moment of inertia about the centre of mass (kg m² per metre).
    pub inertia: Real,
    /// Centre of mass in the block's frame (m).
    pub local_center: DVec2,
}

impl RigidMass {
    /// The centre of mass in the world for the block at `pose`.
    pub fn center(&self, pose: &Pose) -> DVec2 {
        pose.origin + pose.rotate(self.local_center)
    }
}

/// The DEM laws of the block's contacts with material points: its own,
/// and those the scene gives for its contacts with particular bodies.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct BlockContactLaw {
    /// The block's own law (its `contact`).
    pub own: ContactLaw,
    /// The laws with particular bodies (`block_contacts`).
    pub bodies: Vec<(Entity, ContactLaw)>,
}

impl BlockContactLaw {
    /// The law of the block's contacts with the points of `body`.
    pub fn with_body(&self, body: Entity) -> &ContactLaw {
        self.bodies
            .iter()
            .find(|(b, _)| *b == body)
            .map_or(&self.own, |(_, law)| law)
    }
}

/// The points near the block: candidate contacts, rebuilt every
/// `iter_period` steps (Algorithm 1, l. 5–8) or earlier when a point could
/// have travelled further than the margin since the last rebuild.
#[derive(Component, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NeighbourList {
    /// (body entity, point index) pairs, in scene order of bodies then point order.
    pub points: Vec<(Entity, u32)>,
    /// Largest distance any point may have moved since the rebuild (m).
    pub travel: Real,
    /// Steps since the last rebuild.
    pub age: u32,
    /// Rebuilds forced early by the travel guard.
    pub early_rebuilds: u64,
}

/// A contact of this step between the block and a point, with its force.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointContact {
    /// The body.
    pub body: Entity,
    /// The point's index in its body.
    pub point: u32,
    /// Force on the point (N/m; per radian in axisymmetry); the block
    /// receives the opposite.
    pub force: DVec2,
    /// Tangential spring force, carried to the next step.
    pub tangential: DVec2,
    /// Contact point (m).
    pub at: DVec2,
    /// The contact point in the block's frame, to follow the block's
    /// surface through the step (m).
    pub at_on_block: DVec2,
    /// The point's position when the contact was found (m).
    pub from: DVec2,
    /// Energy stored in the contact's springs (J/m; per radian in
    /// axisymmetry): the normal spring's (½ k_n δ², or k_n ∫A for the
    /// overlap-area measure) plus the tangential spring's.
    pub potential: Real,
    /// Energy stored in the tangential spring, |f_t|² / (2 k_t) with the
    /// k_t the force was found with (J/m; per radian in axisymmetry).
    pub tangential_potential: Real,
    /// Half the change of the tangential force at this step, f_t − f_t
    /// of the step before, times the relative motion over the step before
    /// that the change was taken from (J/m; zero for a new contact):
    /// added to `ContactWork`'s force-times-motion, it makes the work of
    /// the tangential force the trapezoidal rule's, ½ (f_t,old + f_t,new)
    /// · Δu, which a sticking spring's energy change matches exactly; so
    /// only sliding and the springs of ended contacts count as dissipated.
    pub spring_work_correction: Real,
}

impl PointContact {
    /// The arm from the point's centre to the contact point, x_c − x_p.
    pub fn arm(&self) -> DVec2 {
        self.at - self.from
    }
}

/// This step's contacts of the block, in neighbour-list order, and last
/// step's (for the tangential history, kept per (block, point) pair while in
/// contact and dropped on separation).
#[derive(Component, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BlockContacts {
    /// Contacts of this step.
    pub current: Vec<PointContact>,
    /// Contacts of the previous step, sorted by (body, point).
    pub previous: Vec<PointContact>,
}

/// Force the points exert on each part of the block this step (one entry
/// for a single shape; for a compound, each contact goes to the part its
/// contact point is nearest), e.g. a pile's cone tip apart from its shaft.
#[derive(Component, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PartReactions(pub Vec<DVec2>);

/// Force and torque (about the centre of mass) the points exert on the block
/// this step, summed in contact order.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Reaction {
    /// Force (N/m).
    pub force: DVec2,
    /// Torque (N m/m).
    pub torque: Real,
}
