//! A user system runs in the set it was put in, and sees the step's data in
//! the state that set implies.

mod common;

use mpdem::components::GridLayer;
use mpdem::prelude::*;

/// What a spy system saw, appended step by step.
#[derive(Resource, Default)]
struct Seen(Vec<(&'static str, u64, Real, Real)>);

/// Records the set's name, the clock step, the layer's total mass and the
/// largest updated nodal speed.
fn spy(label: &'static str) -> impl FnMut(Res<Clock>, Query<&GridLayer>, ResMut<Seen>) {
    move |clock, layers, mut seen| {
        let layer = layers.iter().next().expect("one body");
        let mass: Real = layer.nodes().iter().map(|n| n.mass).sum();
        let speed = layer
            .nodes()
            .iter()
            .map(|n| n.velocity_new.length())
            .fold(0.0, Real::max);
        seen.0.push((label, clock.step, mass, speed));
    }
}

#[test]
fn user_systems_run_where_they_were_put() {
    let mut sim = Simulation::from_scene(&common::load_scene("elastic_column.ron")).unwrap();
    sim.world_mut().init_resource::<Seen>();
    sim.add_systems(spy("first").in_set(MpmSystems::First))
        .unwrap();
    sim.add_systems(spy("after reset").in_set(MpmSystems::Neighbours))
        .unwrap();
    sim.add_systems(spy("stress").in_set(MpmSystems::StressUpdate))
        .unwrap();
    sim.add_systems(spy("last").in_set(MpmSystems::Last))
        .unwrap();
    for _ in 0..3 {
        sim.step().unwrap();
    }
    let seen = &sim.world().resource::<Seen>().0;
    let body_mass = 2000.0 * 0.2 * 1.0;
    let labels: Vec<&str> = seen.iter().map(|s| s.0).collect();
    assert_eq!(labels[..4], ["first", "after reset", "stress", "last"]);
    for step in seen.chunks(4) {
        let [first, reset, stress, last] = [step[0], step[1], step[2], step[3]];
        // First runs before the clock advances, Last after.
        assert_eq!(first.1 + 1, last.1);
        // After GridReset the layer is empty; P2G has filled it by StressUpdate.
        assert_eq!(reset.2, 0.0);
        assert!(
            (stress.2 - body_mass).abs() < 1e-9 * body_mass,
            "mass {}",
            stress.2
        );
        // The momentum update (NodalSolve) comes after StressUpdate in USF.
        assert_eq!(stress.3, 0.0);
        assert!(last.3 > 0.0);
    }
}

#[test]
fn an_ambiguous_user_system_is_refused() {
    let mut sim = Simulation::from_scene(&common::load_scene("elastic_column.ron")).unwrap();
    // Two systems writing the points in one set with no order between them.
    let push = |mut points: Query<&mut MaterialPoints>| {
        for mut p in &mut points {
            p.external_force.iter_mut().for_each(|f| f.x += 1.0);
        }
    };
    let pull = |mut points: Query<&mut MaterialPoints>| {
        for mut p in &mut points {
            p.external_force.iter_mut().for_each(|f| f.x -= 1.0);
        }
    };
    let error = sim.add_systems((
        push.in_set(MpmSystems::Boundary),
        pull.in_set(MpmSystems::Boundary),
    ));
    assert!(
        matches!(error, Err(StepError::Schedule(_))),
        "ambiguity accepted"
    );
}
