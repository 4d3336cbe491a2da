//! A constitutive model defined outside the crate and plugged into a scene
//! built in code: von Mises perfect plasticity on a linear elastic
//! predictor, through the crate's `ElasticPlastic` trait (the elastic
//! trial and the plastic work come with it; the model gives its return).
//! The elastic column of `scenes/elastic_column.ron` is given a yield
//! stress below the deviatoric stress gravity brings to its lower part;
//! the example checks that no point ever leaves the yield surface and that
//! some reach it.
//!
//! Run with `cargo run --release --example custom_model`.

use mpdem::materials::{ElasticPlastic, LinearElastic, MaterialModel, UserModel};
use mpdem::prelude::*;

/// Von Mises perfect plasticity: q = √(3 J₂) ≤ σ_y, with J₂ of the whole
/// deviator (σ_zz, the out-of-plane stress, included).
struct VonMises {
    elastic: LinearElastic,
    /// Yield stress in uniaxial tension σ_y (Pa).
    yield_stress: Real,
}

/// The deviator of `stress` and its mean stress.
fn deviator(stress: SymTensor) -> (SymTensor, Real) {
    let mean = (stress.xx + stress.yy + stress.zz) / 3.0;
    (stress - SymTensor::new(mean, mean, 0.0, mean), mean)
}

/// The von Mises equivalent stress q = √(3/2 s : s).
fn equivalent(stress: SymTensor) -> Real {
    let (s, _) = deviator(stress);
    (1.5 * (s.xx * s.xx + s.yy * s.yy + s.zz * s.zz + 2.0 * s.xy * s.xy)).sqrt()
}

impl ElasticPlastic for VonMises {
    fn elastic(&self) -> LinearElastic {
        self.elastic
    }

    /// The radial return: the deviator scaled back onto the surface, the
    /// mean stress kept.
    fn return_map(&self, trial: SymTensor) -> SymTensor {
        let q = equivalent(trial);
        if q <= self.yield_stress {
            return trial;
        }
        let (s, mean) = deviator(trial);
        s * (self.yield_stress / q) + SymTensor::new(mean, mean, 0.0, mean)
    }
}

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/elastic_column.ron");
    let mut scene = Scene::load(path.as_ref())?;
    let yield_stress = 1.5e3;
    let MaterialModel::LinearElastic(elastic) = scene.materials[0].model else {
        return Err("the column's material is no longer linear elastic".into());
    };
    scene.materials[0].model = MaterialModel::User(UserModel::new(
        "von Mises",
        VonMises {
            elastic,
            yield_stress,
        },
    ));
    scene.time.end = 0.3;
    let mut sim = Simulation::from_scene(&scene)?;
    // The largest q over the run, and how many steps had a point on the
    // surface (a column confined by its walls relaxes towards an isotropic
    // state once it has yielded, so the last step alone tells little).
    let (mut largest, mut steps_yielding): (Real, u64) = (0.0, 0);
    while !sim.clock().finished() {
        sim.step()?;
        let points = sim.points_of("column").ok_or("no column")?;
        let q = points
            .stress
            .iter()
            .map(|s| equivalent(*s))
            .fold(0.0, Real::max);
        largest = largest.max(q);
        if q >= yield_stress * (1.0 - 1e-9) {
            steps_yielding += 1;
        }
    }
    println!(
        "largest q = {largest:.6e} Pa against σ_y = {yield_stress:e} Pa; a point on the surface in {steps_yielding} of {} steps",
        sim.clock().step
    );
    // The return puts q on the surface up to rounding.
    if largest > yield_stress * (1.0 + 1e-9) {
        return Err(format!("a point went outside the yield surface: q = {largest:e} Pa").into());
    }
    if steps_yielding == 0 {
        return Err("no point reached the yield surface: the model was not used".into());
    }
    Ok(())
}
