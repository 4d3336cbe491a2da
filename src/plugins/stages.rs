//! Stages and their surface loads: entering the first stage, the loads and
//! their work, the stages' end conditions, and their record, `stages.csv`.

use super::{MpmPlugin, PluginSetup};
use crate::checkpoint::Checkpointed;
use crate::components::bodies_in_scene_order;
use crate::io::csv::{CsvSeries, field, time};
use crate::math::Real;
use crate::resources::{
    Clock, LoadWork, StageEndReason, StageLog, StagePlan, StageProgress, UpdateScheme,
};
use crate::scene::SceneError;
use crate::systems::{
    ContactTransferStep, DiagnosticsStep, account_load_work, advance_stages, apply_surface_loads,
    dynamic_blocks_in_scene_order, enter_stage,
};
use bevy_ecs::prelude::*;
use std::io::Write;

/// Stages, surface loads and their record.
pub struct StagesPlugin;

impl MpmPlugin for StagesPlugin {
    fn build(&self, setup: &mut PluginSetup) -> Result<(), SceneError> {
        let scene = setup.scene;
        setup.world.insert_resource(StageLog::default());
        setup.world.insert_resource(LoadWork::default());
        setup.keep_checkpointed::<LoadWork>("load work");
        setup.keep_resource::<StageLog>("stage log");
        if scene.stages.is_empty() {
            return Ok(());
        }
        setup.write_csv::<StageLog>("stages.csv");
        let mut plan = StagePlan {
            stages: scene.stages.clone(),
            absent_blocks: setup.take_absent_blocks(),
            bodies: Vec::new(),
            dynamic_blocks: Vec::new(),
            progress: StageProgress::default(),
        };
        let warnings = enter_stage(setup.world, &mut plan, 0);
        setup.warn_all(warnings);
        setup.world.insert_resource(plan);
        setup.keep_checkpointed::<StagePlan>("stages");
        setup.after_restore(carry_on_the_stages);
        Ok(())
    }

    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems((
            apply_surface_loads.in_set(ContactTransferStep::SurfaceLoads),
            account_load_work.in_set(DiagnosticsStep::LoadWork),
            advance_stages.in_set(DiagnosticsStep::Stages),
        ));
    }
}

/// The work so far; no load is pending between steps.
impl Checkpointed for LoadWork {
    type Stored = Real;

    fn stored(&self) -> Real {
        self.work
    }

    fn restore(&mut self, work: Real) {
        self.work = work;
        self.applied.clear();
    }
}

/// Where the run is in its stages; the stages themselves are the scene's.
impl Checkpointed for StagePlan {
    type Stored = StageProgress;

    fn stored(&self) -> StageProgress {
        self.progress.clone()
    }

    fn restore(&mut self, progress: StageProgress) {
        self.progress = progress;
    }
}

/// Once a checkpoint is restored: the plan's bodies and dynamic blocks are
/// those of the restored world, and a stage the checkpoint's run cut short
/// at its `time.end` goes on if the resumed run ends later.
fn carry_on_the_stages(world: &mut World) {
    let Some(mut plan) = world.remove_resource::<StagePlan>() else {
        return;
    };
    plan.bodies = bodies_in_scene_order(world);
    plan.dynamic_blocks = dynamic_blocks_in_scene_order(world);
    carry_on_a_stage_cut_short(world, &mut plan.progress);
    world.insert_resource(plan);
}

/// A stage still running when the run reached its `time.end` was ended
/// there (`SceneEnd`, with a warning). If the resumed scene ends later, the
/// stage goes on as in a run that was given the later end from the start:
/// that record and its warning are taken back. A plan that finished
/// otherwise stays finished, and the run with it.
fn carry_on_a_stage_cut_short(world: &mut World, progress: &mut StageProgress) {
    if !progress.finished {
        return;
    }
    // The clock holds the checkpoint's step and the resumed scene's end.
    let clock = *world.resource::<Clock>();
    let mut log = world.resource_mut::<StageLog>();
    let cut_short = log
        .records
        .last()
        .is_some_and(|r| r.reason == StageEndReason::SceneEnd);
    if cut_short && !clock.finished() {
        log.records.pop();
        log.warnings.pop();
        progress.finished = false;
    } else {
        world.resource_mut::<Clock>().end = clock.time;
    }
}

/// `stages.csv`: one row per finished stage, columns stage (index), name,
/// start, end (s), steps, reason (`duration`, `condition`, `max_time` or
/// `scene_end`).
impl CsvSeries for StageLog {
    const HEADER: &'static str = "stage,name,start,end,steps,reason";

    fn rows(&self) -> usize {
        self.records.len()
    }

    fn write_row(&self, k: usize, _: &[String], out: &mut dyn Write) -> std::io::Result<()> {
        let r = &self.records[k];
        writeln!(
            out,
            "{},{},{},{},{},{}",
            r.index,
            field(&r.name),
            time(r.start),
            time(r.end),
            r.steps,
            r.reason.label()
        )
    }
}
