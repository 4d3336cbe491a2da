//! The time step as a bevy schedule: one file per step of Algorithm 1.
//!
//! [`MpmSchedule`] runs the [`MpmSystems`] sets strictly one after the other,
//! on a single-threaded executor (parallelism lives inside the systems, over
//! point and node columns) and with ambiguity detection set to error, so two
//! systems that touch the same data in one set must be ordered explicitly.
//! A user system joins the step with `.in_set(MpmSystems::X)`.

mod body_contact;
mod boundary;
mod contact;
mod contact_transfer;
mod contact_work;
mod diagnostics;
mod grid_reset;
mod grid_to_particle;
mod load_work;
mod loose_points;
mod neighbours;
mod nodal_solve;
mod particle_to_grid;
mod rigid_bodies;
mod stages;
mod stress_update;
mod surface_loads;

pub(crate) use body_contact::compute_body_contacts;
pub(crate) use boundary::rebuild_node_constraints;
pub(crate) use contact::compute_rigid_contacts;
pub(crate) use contact_transfer::transfer_contact_forces;
pub(crate) use contact_work::account_contact_work;
pub(crate) use diagnostics::{
    advance_clock, check_finite, record_blocks, record_body_pairs, record_probes_and_energy,
};
pub(crate) use grid_reset::reset_grid_layers;
pub(crate) use grid_to_particle::grid_to_particle;
pub(crate) use load_work::account_load_work;
pub(crate) use loose_points::check_loose_points;
pub(crate) use neighbours::rebuild_neighbour_lists;
pub(crate) use nodal_solve::solve_nodal_momentum;
pub(crate) use particle_to_grid::particle_to_grid;
pub(crate) use rigid_bodies::move_rigid_blocks;
pub use stages::side_points;
pub(crate) use stages::{advance_stages, dynamic_blocks_in_scene_order, enter_stage};
pub(crate) use stress_update::update_stress;
pub(crate) use surface_loads::apply_surface_loads;

use crate::resources::{StepInterrupt, UpdateScheme};
use bevy_ecs::prelude::*;
use bevy_ecs::schedule::{LogLevel, ScheduleBuildSettings, ScheduleLabel, SingleThreadedExecutor};

/// The label of the MPM step schedule.
#[derive(ScheduleLabel, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MpmSchedule;

/// The sets of one step, in Algorithm 1 order for USF (see [`MpmSystems::order`]).
/// Line numbers refer to Algorithm 1 of the paper.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MpmSystems {
    /// Empty: a hook for user systems at the start of the step.
    First,
    /// Zero every layer's active nodes and set them from the points (l. 2);
    /// from here until `ParticleToGrid`, points must not move.
    GridReset,
    /// Stage events, prescribed motions of blocks, boundary conditions (l. 3).
    Boundary,
    /// Rebuild contact neighbour lists every `iterperiod` steps (l. 5–8).
    Neighbours,
    /// Detect contacts and compute DEM forces (l. 9).
    Contact,
    /// Contact forces to points and nodes, reactions to blocks (l. 10), and
    /// the stages' surface tractions (eq. 7b).
    ContactTransfer,
    /// Mass and momentum to each body's layer (l. 12).
    ParticleToGrid,
    /// Strain rate and constitutive update at the points (l. 13).
    StressUpdate,
    /// Internal + external forces, momentum update, boundary conditions (l. 14–15).
    NodalSolve,
    /// Velocity and position update of the points (l. 16, eq. 11).
    GridToParticle,
    /// Integration of dynamic rigid blocks.
    RigidBodies,
    /// Finiteness check, contact and load work, clock, stages, probes and
    /// energies.
    Diagnostics,
    /// Empty: a hook for user systems at the end of the step.
    Last,
}

impl MpmSystems {
    /// The order of the sets for an update scheme: USF as Algorithm 1; USL
    /// and MUSL move the stress update after the grid-to-particle transfer.
    pub fn order(scheme: UpdateScheme) -> [Self; 13] {
        use MpmSystems::*;
        let (middle_a, middle_b, middle_c) = match scheme {
            UpdateScheme::Usf => (StressUpdate, NodalSolve, GridToParticle),
            UpdateScheme::Usl | UpdateScheme::Musl => (NodalSolve, GridToParticle, StressUpdate),
        };
        [
            First,
            GridReset,
            Boundary,
            Neighbours,
            Contact,
            ContactTransfer,
            ParticleToGrid,
            middle_a,
            middle_b,
            middle_c,
            RigidBodies,
            Diagnostics,
            Last,
        ]
    }
}

/// A schedule with the sets chained in the order of `scheme` and the
/// ordered steps inside them; the features' plugins add their systems
/// (see [`crate::plugins`]).
pub(crate) fn build_schedule(scheme: UpdateScheme) -> Schedule {
    let mut schedule = Schedule::new(MpmSchedule);
    schedule.set_executor(SingleThreadedExecutor::new());
    schedule.set_build_settings(ScheduleBuildSettings {
        ambiguity_detection: LogLevel::Error,
        ..Default::default()
    });
    let order = MpmSystems::order(scheme);
    for pair in order.windows(2) {
        schedule.configure_sets(pair[0].before(pair[1]));
    }
    for set in order {
        match set {
            MpmSystems::Diagnostics | MpmSystems::Last => {
                schedule.configure_sets(set.run_if(step_is_whole));
            }
            _ => {
                schedule.configure_sets(set.run_if(step_goes_on));
            }
        }
    }
    schedule.configure_sets(
        (ContactStep::Blocks, ContactStep::Bodies)
            .chain()
            .in_set(MpmSystems::Contact),
    );
    schedule.configure_sets(
        (
            ContactTransferStep::Forces,
            ContactTransferStep::SurfaceLoads,
        )
            .chain()
            .in_set(MpmSystems::ContactTransfer),
    );
    schedule.configure_sets(
        (
            DiagnosticsStep::CheckFinite,
            DiagnosticsStep::ContactWork,
            DiagnosticsStep::LoadWork,
            DiagnosticsStep::Clock,
            DiagnosticsStep::Stages,
            DiagnosticsStep::Energy,
            DiagnosticsStep::Blocks,
            DiagnosticsStep::BodyPairs,
        )
            .chain()
            .in_set(MpmSystems::Diagnostics),
    );
    schedule
}

/// Whether the step goes on into its next set: not once a
/// [`StepInterrupt`] was requested.
fn step_goes_on(interrupt: Option<Res<StepInterrupt>>) -> bool {
    interrupt.is_none_or(|i| i.goes_on())
}

/// Whether the step so far is whole: the diagnostics and the last hook
/// finish every step that reached them, and only those.
fn step_is_whole(interrupt: Option<Res<StepInterrupt>>) -> bool {
    interrupt.is_none_or(|i| !i.cut_short())
}

/// The ordered steps of [`MpmSystems::Contact`].
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactStep {
    /// Point–block contacts (it also resets every point's contact force).
    Blocks,
    /// Body–body contacts.
    Bodies,
}

/// The ordered steps of [`MpmSystems::ContactTransfer`].
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactTransferStep {
    /// Contact forces to the points and nodes.
    Forces,
    /// The stages' surface loads.
    SurfaceLoads,
}

/// The ordered steps of [`MpmSystems::Diagnostics`].
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DiagnosticsStep {
    /// Finiteness of the step's results.
    CheckFinite,
    /// The point contacts' work.
    ContactWork,
    /// The surface loads' work.
    LoadWork,
    /// The clock.
    Clock,
    /// The stages' end conditions, before the records: a sample at a
    /// stage's change shows the state the step ends in, as that step's
    /// frame does, and the step on which the last stage ends the run is
    /// sampled.
    Stages,
    /// Probes and energies.
    Energy,
    /// The blocks' record.
    Blocks,
    /// The body pairs' record.
    BodyPairs,
}
