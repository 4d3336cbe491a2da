//! Wall-clock time of each set of the step, for finding where a run's time
//! goes and which parts scale with the threads.

use bevy_ecs::prelude::*;
use mpdem::math::Real;
use mpdem::resources::Settings;
use mpdem::systems::MpmSystems;
use mpdem::{Simulation, StepError};
use std::time::Instant;

/// The seconds spent in each set of the step since the timer was started
/// or last read.
#[derive(Resource, Debug)]
struct SetClock {
    /// The sets in the order the step runs them.
    order: [MpmSystems; 13],
    /// When the set now running began; `None` between steps.
    since: Option<Instant>,
    /// Seconds of `order[k]`, summed over the steps.
    seconds: [Real; 13],
}

/// Adds a timer to `sim`'s step: a mark between each pair of consecutive
/// sets records the time since the last mark. The marks only read the
/// clock, so the run's results do not change. Call it once per simulation.
pub fn start_set_timer(sim: &mut Simulation) -> Result<(), StepError> {
    let order = MpmSystems::order(sim.world().resource::<Settings>().scheme);
    sim.world_mut().insert_resource(SetClock {
        order,
        since: None,
        seconds: [0.0; 13],
    });
    for (k, pair) in order.windows(2).enumerate() {
        // This mark ends set k (none for the first mark of a step, which
        // only starts the clock) and starts set k + 1 (none for the last).
        let (ends, starts) = (k, k + 1);
        let last = starts == order.len() - 1;
        let mark = move |mut clock: ResMut<SetClock>| {
            let now = Instant::now();
            if let Some(since) = clock.since {
                clock.seconds[ends] += (now - since).as_secs_f64();
            }
            clock.since = (!last).then_some(now);
        };
        sim.add_systems(mark.after(pair[0]).before(pair[1]))?;
    }
    Ok(())
}

/// The seconds each set took since the timer started or was last read, in
/// the order the step runs them, and sets them back to zero. The first and
/// last sets, the empty hooks for user systems, are not timed. Empty if
/// [`start_set_timer`] was not called.
pub fn take_set_seconds(sim: &mut Simulation) -> Vec<(MpmSystems, Real)> {
    let Some(mut clock) = sim.world_mut().get_resource_mut::<SetClock>() else {
        return Vec::new();
    };
    let taken = clock.order[1..12]
        .iter()
        .zip(&clock.seconds[1..12])
        .map(|(&set, &s)| (set, s))
        .collect();
    clock.seconds = [0.0; 13];
    taken
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::elastic_block_scene;

    #[test]
    fn the_timer_times_every_set_between_the_hooks_and_changes_nothing() {
        let scene = elastic_block_scene(400);
        let mut plain = Simulation::from_scene(&scene).unwrap();
        let mut timed = Simulation::from_scene(&scene).unwrap();
        assert!(take_set_seconds(&mut timed).is_empty());
        start_set_timer(&mut timed).unwrap();
        let start = Instant::now();
        for _ in 0..5 {
            plain.step().unwrap();
            timed.step().unwrap();
        }
        let wall = start.elapsed().as_secs_f64();
        assert_eq!(plain.state_hash(), timed.state_hash());
        let sets = take_set_seconds(&mut timed);
        let order = MpmSystems::order(scene.settings.scheme);
        assert_eq!(
            sets.iter().map(|(s, _)| *s).collect::<Vec<_>>(),
            order[1..12].to_vec()
        );
        assert!(sets.iter().all(|(_, s)| *s >= 0.0));
        let total: Real = sets.iter().map(|(_, s)| s).sum();
        assert!(total > 0.0 && total <= wall, "{total} s of {wall} s");
        assert!(
            sets.iter()
                .find(|(s, _)| *s == MpmSystems::ParticleToGrid)
                .unwrap()
                .1
                > 0.0
        );
        assert!(take_set_seconds(&mut timed).iter().all(|(_, s)| *s == 0.0));
    }
}
