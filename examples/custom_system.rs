//! Adding user systems to the step, as a plugin: a horizontal "wind" load
//! that grows with time, applied to every point of the elastic column in
//! the `Boundary` set (before the particle-to-grid transfer picks up
//! external forces), and a report in `Last`.
//!
//! Run with `cargo run --release --example custom_system`.

use mpdem::prelude::*;
use mpdem::resources::UpdateScheme;

/// Wind pressure growth rate, N per metre of thickness per point per second.
const WIND_RATE: Real = 0.5;

/// Sets each point's external force to a load growing linearly in time.
fn wind(clock: Res<Clock>, mut bodies: Query<&mut MaterialPoints>) {
    let load = DVec2::new(WIND_RATE * clock.time, 0.0);
    for mut points in &mut bodies {
        points.external_force.iter_mut().for_each(|f| *f = load);
    }
}

/// Prints the top of the column's sway every 0.1 s.
fn report(clock: Res<Clock>, bodies: Query<(&BodyName, &MaterialPoints)>) {
    if !clock.step.is_multiple_of(1000) {
        return;
    }
    for (name, points) in &bodies {
        let top = (0..points.len())
            .max_by(|&a, &b| points.position[a].y.total_cmp(&points.position[b].y))
            .map_or(0.0, |p| points.displacement(p).x);
        println!(
            "t = {:.2} s: '{}' top moved {top:+.3e} m sideways",
            clock.time, name.0
        );
    }
}

/// The wind and its report, as one feature of the step.
struct WindPlugin;

impl MpmPlugin for WindPlugin {
    fn add_systems(&self, schedule: &mut Schedule, _: UpdateScheme) {
        schedule.add_systems((
            wind.in_set(MpmSystems::Boundary),
            report.in_set(MpmSystems::Last),
        ));
    }
}

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/elastic_column.ron");
    let mut scene = Scene::load(path.as_ref())?;
    // The column's side walls are slip walls: free them so it can sway.
    scene.grid.edges.left = mpdem::resources::EdgeCondition::Free;
    scene.grid.edges.right = mpdem::resources::EdgeCondition::Free;
    scene.grid.origin.x = -0.5;
    scene.grid.cells.0 = 48;
    scene.time.end = 0.5;
    let mut sim = Simulation::from_scene(&scene)?;
    sim.add_plugin(&WindPlugin)?;
    sim.run()?;
    println!("state hash {:016x}", sim.state_hash());
    Ok(())
}
