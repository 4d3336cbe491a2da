//! `mpdem check`: validate scenes without running them.

use crate::console::{say, say_err, say_warning};
use crate::failure::Failure;
use mpdem::Simulation;
use mpdem::resources::Geometry;
use mpdem::scene::Scene;
use std::path::{Path, PathBuf};

/// The arguments of `mpdem check`.
#[derive(clap::Args)]
pub struct CheckArgs {
    /// The RON scene files.
    #[arg(required = true)]
    pub scenes: Vec<PathBuf>,
}

/// Checks every scene, reporting each accepted one as it comes; an error
/// if any is refused: a single scene's refusal, or, of several, each
/// refusal printed and their count.
pub fn check_all(paths: &[PathBuf]) -> Result<(), Failure> {
    let mut refused = Vec::new();
    for path in paths {
        if let Err(failure) = check(path) {
            refused.push(failure);
        }
    }
    match refused.pop() {
        None => Ok(()),
        Some(last) if paths.len() == 1 => Err(last),
        Some(last) => {
            for failure in refused.iter().chain([&last]) {
                say_err(&format!("error: {failure}"));
            }
            Err(Failure::Refused {
                refused: refused.len() + 1,
                checked: paths.len(),
            })
        }
    }
}

fn check(path: &Path) -> Result<(), Failure> {
    let scene = Scene::load(path)?;
    let sim = Simulation::from_scene(&scene)?;
    // Named by file: `check` may be given several scenes.
    for w in sim.warnings() {
        say_warning(path, w);
    }
    let clock = sim.clock();
    let geometry = match scene.settings.geometry {
        Geometry::PlaneStrain => "plane strain",
        Geometry::Axisymmetric => "axisymmetric, per radian",
    };
    say(&format!(
        "{}: ok ({geometry}; bodies: {}, steps: {} of {:e} s)",
        path.display(),
        scene.bodies.len(),
        clock.total_steps(),
        clock.dt
    ))?;
    Ok(())
}
