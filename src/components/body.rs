//! Identity, material and per-body boundary conditions of a deformable body.

use crate::materials::MaterialModel;
use crate::math::{DVec2, Real};
use bevy_ecs::prelude::{Component, Entity, World};
use serde::{Deserialize, Serialize};

/// The body's name from the scene (unique).
#[derive(Component, Clone, Debug, PartialEq, Eq)]
pub struct BodyName(pub String);

/// The body's position in the scene's list of bodies. Every cross-body loop
/// (outputs, energy sums, the state hash) visits bodies in this order, so
/// results never depend on the ECS storage order.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct BodyIndex(pub u32);

/// Fills `order` with `entities` (bodies by `BodyIndex`, blocks by their
/// index) sorted by scene index, reusing its storage: every loop whose
/// results meet across bodies or blocks visits them in this order.
pub fn sort_into_scene_order<K: Ord>(
    order: &mut Vec<(K, Entity)>,
    entities: impl Iterator<Item = (K, Entity)>,
) {
    order.clear();
    order.extend(entities);
    order.sort_unstable();
}

/// Every body entity, in scene order.
pub fn bodies_in_scene_order(world: &mut World) -> Vec<Entity> {
    let mut order = Vec::new();
    let mut query = world.query::<(Entity, &BodyIndex)>();
    sort_into_scene_order(&mut order, query.iter(world).map(|(e, i)| (*i, e)));
    order.into_iter().map(|(_, e)| e).collect()
}

/// The body's material: density and constitutive model.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct Material {
    /// The material's name in the scene.
    pub name: String,
    /// Initial mass density ρ (kg/m³).
    pub density: Real,
    /// The stress update rule.
    pub model: MaterialModel,
}

/// Nodes of this body's layer inside a rectangle have some velocity
/// components held at zero (e.g. the clamped base of a beam, a symmetry line).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionConstraint {
    /// Lower-left corner of the region (m); nodes on its edges are included.
    pub min: DVec2,
    /// Upper-right corner of the region (m).
    pub max: DVec2,
    /// Hold the x velocity at zero.
    #[serde(default)]
    pub fix_x: bool,
    /// Hold the y velocity at zero.
    #[serde(default)]
    pub fix_y: bool,
}

/// The region constraints of one body's layer.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct RegionConstraints(pub Vec<RegionConstraint>);

/// A body force per unit mass on one body, on top of gravity (scene
/// `acceleration`), ramped linearly from zero over `ramp_time` so a load can
/// be applied quasi-statically (e.g. the Hertz disks pushed together).
#[derive(Component, Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyAcceleration {
    /// Full acceleration (m/s²).
    pub value: DVec2,
    /// Time to reach it from zero (s), ≥ 0. Default 0: applied at once.
    #[serde(default, deserialize_with = "crate::rules::de_non_negative")]
    pub ramp_time: Real,
}

impl BodyAcceleration {
    /// The acceleration at `time`: value × min(time / ramp_time, 1).
    pub fn at(&self, time: Real) -> DVec2 {
        if time >= self.ramp_time {
            self.value
        } else {
            self.value * (time / self.ramp_time)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramped_acceleration_grows_linearly_then_holds() {
        let load = BodyAcceleration {
            value: DVec2::new(4.0, -2.0),
            ramp_time: 2.0,
        };
        assert_eq!(load.at(0.0), DVec2::ZERO);
        assert_eq!(load.at(1.0), DVec2::new(2.0, -1.0));
        assert_eq!(load.at(5.0), load.value);
        let at_once = BodyAcceleration {
            ramp_time: 0.0,
            ..load
        };
        assert_eq!(at_once.at(0.0), load.value);
    }
}
