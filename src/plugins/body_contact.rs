//! Contacts between bodies (section 3.3) and the body pairs' record,
//! `body_contacts.csv`.

use super::records::refill;
use super::{MpmPlugin, PluginSetup, placed_bodies};
use crate::checkpoint::{Checkpointed, TimeRecord};
use crate::components::bodies_in_scene_order;
use crate::io::csv::{CsvSeries, field, time};
use crate::math::Real;
use crate::resources::{
    BodyContacts, BodyPairContact, BodyPairLaw, BodyPairLog, BodyPairSample, PairSummary,
    UpdateScheme,
};
use crate::scene::{Scene, SceneError, body_contact_stability_warnings, body_overlap_warnings};
use crate::systems::{ContactStep, DiagnosticsStep, compute_body_contacts, record_body_pairs};
use bevy_ecs::prelude::*;
use std::io::Write;

/// Body–body contact and its record.
pub struct BodyContactPlugin;

impl MpmPlugin for BodyContactPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        let scene = setup.scene;
        let laws = body_pair_laws(scene);
        let bodies = bodies_in_scene_order(setup.world);
        let warnings = layout_warnings(scene, setup.world, &bodies, &laws);
        setup.warn_all(warnings);
        let samples = setup.samples_in_run();
        let world = &mut *setup.world;
        // The first sample, at the start, has no contacts yet.
        let mut log = BodyPairLog {
            samples: Vec::with_capacity(samples * laws.len()),
        };
        log.samples.extend(laws.iter().map(|l| BodyPairSample {
            time: 0.0,
            a: l.a,
            b: l.b,
            summary: PairSummary::default(),
        }));
        world.insert_resource(log);
        world.insert_resource(BodyContacts {
            laws,
            ..Default::default()
        });
        setup.keep_checkpointed::<BodyContacts>("body contacts");
        if scene.body_contacts.is_empty() {
            setup.keep_checkpointed::<BodyPairLog>("body pairs");
        } else {
            setup.record::<BodyPairLog>("body pairs", "body_contacts.csv");
        }
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems((
            compute_body_contacts.in_set(ContactStep::Bodies),
            record_body_pairs.in_set(DiagnosticsStep::BodyPairs),
        ));
    }
}

/// This step's and the last step's contacts (the tangential springs carry
/// over from one to the next); the laws are the scene's.
impl Checkpointed for BodyContacts {
    type Stored = [Vec<BodyPairContact>; 2];

    fn stored(&self) -> Self::Stored {
        [self.current.clone(), self.previous.clone()]
    }

    fn restore(&mut self, [current, previous]: Self::Stored) {
        self.current = current;
        self.previous = previous;
    }
}

impl Checkpointed for BodyPairLog {
    type Stored = Vec<BodyPairSample>;

    fn stored(&self) -> Self::Stored {
        self.samples.clone()
    }

    fn restore(&mut self, samples: Self::Stored) {
        refill(&mut self.samples, samples);
    }
}

impl TimeRecord for BodyPairLog {
    fn forget_from(&mut self, time: Real) {
        self.samples.retain(|s| s.time < time);
    }
}

/// The contact law of every pair of bodies (a < b), expanded from the
/// scene's laws between bodies or groups, sorted by pair.
fn body_pair_laws(scene: &Scene) -> Vec<BodyPairLaw> {
    let mut laws: Vec<BodyPairLaw> = Vec::new();
    for spec in &scene.body_contacts {
        let members = |name: &str| scene.contact_members(name).unwrap_or_default();
        for i in members(&spec.between.0) {
            for j in members(&spec.between.1) {
                laws.push(BodyPairLaw {
                    a: i.min(j) as u32,
                    b: i.max(j) as u32,
                    law: spec.law,
                });
            }
        }
    }
    laws.sort_unstable_by_key(|l| (l.a, l.b));
    laws
}

/// Warnings about where the bodies start: overlapping under a contact
/// law, and body contact springs the time step cannot follow.
fn layout_warnings(
    scene: &Scene,
    world: &World,
    bodies: &[Entity],
    laws: &[BodyPairLaw],
) -> Vec<crate::warning::Warning> {
    let placed = placed_bodies(scene, world, bodies);
    let mut warnings = body_overlap_warnings(&placed, laws);
    warnings.extend(body_contact_stability_warnings(
        scene.time.dt,
        &placed,
        laws,
    ));
    warnings
}

/// `body_contacts.csv`: one row per pair of bodies with a law and sample
/// time, columns time, body_a, body_b, force_x, force_y (on body_a, N/m),
/// contacts (point pairs), half_width, pressure_half_width and
/// initial_pressure_half_width (m, see [`crate::resources::PairSummary`]).
/// `time` is the end of the step whose contacts (found from the positions
/// at its start) are summed, like the other records.
impl CsvSeries for BodyPairLog {
    const HEADER: &'static str = "time,body_a,body_b,force_x,force_y,contacts,half_width,pressure_half_width,initial_pressure_half_width";

    fn rows(&self) -> usize {
        self.samples.len()
    }

    fn write_row(&self, k: usize, bodies: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let s = &self.samples[k];
        let name = |i: u32| field(bodies.get(i as usize).map_or("?", String::as_str));
        let p = &s.summary;
        writeln!(
            out,
            "{},{},{},{:e},{:e},{},{:e},{:e},{:e}",
            time(s.time),
            name(s.a),
            name(s.b),
            p.force.x,
            p.force.y,
            p.contacts,
            p.half_width,
            p.pressure_half_width,
            p.initial_pressure_half_width
        )
    }
}
