//! The 2D Hertz problem (paper section 4.4.2): two elastic disks pressed
//! together by opposite ramped body forces, on separate layers, meeting
//! only through the disk–disk DEM contact.

mod common;

use mpdem::io::plot::{Series, SeriesStyle, plot_series};
use mpdem::materials::{MaterialModel, NeoHookean};
use mpdem::prelude::*;
use mpdem::resources::BodyPairLog;
use mpdem::scene::Shape;
use std::path::Path;

/// Disk radius (m), Young's modulus (Pa) and Poisson's ratio of the scene.
const RADIUS: Real = 0.01;
const YOUNGS_MODULUS: Real = 9.4e10;
const POISSON_RATIO: Real = 0.07;

/// The loads where F(a) is compared: those at which Hertz gives a contact
/// between 0.2 R and 0.3 R wide. Below, the flat faces that the lattice of
/// points gives each disk at its poles (about √(R s) wide for a point
/// spacing s: 0.11 R at the finest resolution, 0.22 R at the coarsest)
/// decide the contact, and F rises at a fixed a as on a flat punch; the
/// load ends at 0.3 R.
fn in_window(force: Real) -> bool {
    (hertz_force(0.2 * RADIUS)..=hertz_force(0.3 * RADIUS)).contains(&force)
}

/// The 2D Hertz law, eq. 21: F = π E* a² / (4 R*), E* = E / (2 (1 − ν²)),
/// R* = R / 2 for two equal disks (N/m).
fn hertz_force(a: Real) -> Real {
    let e_star = YOUNGS_MODULUS / (2.0 * (1.0 - POISSON_RATIO * POISSON_RATIO));
    let r_star = 0.5 * RADIUS;
    std::f64::consts::PI * e_star * a * a / (4.0 * r_star)
}

/// One of the paper's runs: cell R / `cells_per_radius`, `points_per_cell`
/// along each direction, the line of centres turned by `angle` degrees;
/// with `neo_hookean` the disks are Neo-Hookean instead of the scene's
/// linear elastic (Jaumann) material with the same E and ν.
#[derive(Clone, Copy, Debug)]
struct Resolution {
    cells_per_radius: u32,
    points_per_cell: u32,
    angle: Real,
    neo_hookean: bool,
}

impl Resolution {
    fn label(&self) -> String {
        format!(
            "cell R/{}, {} pt/cell{}{}",
            self.cells_per_radius,
            self.points_per_cell * self.points_per_cell,
            if self.angle == 0.0 {
                String::new()
            } else {
                format!(", turned {}°", self.angle)
            },
            if self.neo_hookean {
                ", Neo-Hookean"
            } else {
                ""
            }
        )
    }

    /// `scenes/hertz_disks.ron` at this resolution and angle.
    fn scene(&self) -> Scene {
        let mut scene = common::load_scene("hertz_disks.ron");
        if self.neo_hookean {
            scene.materials[0].model = MaterialModel::NeoHookean(NeoHookean {
                youngs_modulus: YOUNGS_MODULUS,
                poisson_ratio: POISSON_RATIO,
            });
        }
        let h = RADIUS / Real::from(self.cells_per_radius);
        scene.grid.cell_size = h;
        let n = (0.05 / h).round() as usize;
        scene.grid.cells = (n, n);
        let along = DVec2::from_angle(self.angle.to_radians());
        for (body, side) in scene.bodies.iter_mut().zip([-1.0, 1.0]) {
            body.points_per_cell = self.points_per_cell;
            body.shape = Shape::Disk {
                center: side * RADIUS * along,
                radius: RADIUS,
            };
            let load = body.acceleration.as_mut().expect("a ramped body force");
            load.value = -side * load.value.length() * along;
        }
        scene
    }
}

/// The recorded (a, F) pairs of a run, a from the spread of the contact
/// forces, the last sample's force, and the body force applied to the left
/// disk at the end of the ramp.
struct LoadingCurve {
    samples: Vec<(Real, Real)>,
    final_force: DVec2,
    applied: DVec2,
}

fn load_to_the_end(resolution: Resolution) -> LoadingCurve {
    let scene = resolution.scene();
    let mut sim = common::run_scene(&scene);
    let disk_mass: Real = sim.points_of("left").expect("left").mass.iter().sum();
    let applied = disk_mass * scene.bodies[0].acceleration.expect("load").value;
    let log = sim.world().resource::<BodyPairLog>();
    let samples = log
        .samples
        .iter()
        .filter(|s| s.summary.contacts > 0)
        .map(|s| (s.summary.pressure_half_width, s.summary.force.length()))
        .collect();
    let final_force = log.samples.last().expect("samples").summary.force;
    LoadingCurve {
        samples,
        final_force,
        applied,
    }
}

/// Mean of |F − F_Hertz(a)| / F_Hertz(a) over the samples whose load is in
/// the window, and their number.
fn hertz_error(curve: &LoadingCurve) -> (Real, usize) {
    let inside: Vec<Real> = curve
        .samples
        .iter()
        .filter(|(_, f)| in_window(*f))
        .map(|&(a, f)| (f / hertz_force(a) - 1.0).abs())
        .collect();
    (
        inside.iter().sum::<Real>() / inside.len().max(1) as Real,
        inside.len(),
    )
}

#[test]
fn coarse_disks_carry_the_applied_load_along_the_line_of_centres() {
    let resolution = Resolution {
        cells_per_radius: 20,
        points_per_cell: 1,
        angle: 0.0,
        neo_hookean: false,
    };
    let curve = load_to_the_end(resolution);
    let applied = curve.applied;
    let (error, count) = hertz_error(&curve);
    println!(
        "R/20, 1 pt/cell: contact force {:.4e} N/m for an applied {:.4e}; F(a) error {:.1}% over {count} samples",
        curve.final_force.x,
        -applied.x,
        100.0 * error
    );
    // Quasi-static at the end of the ramp: the contact carries the body
    // force of the left disk. 5%: particle damping makes the disks lag the
    // ramp by a little (measured −2% with half this load).
    assert!(
        (curve.final_force.x / -applied.x - 1.0).abs() < 0.05,
        "contact force {} vs applied {}",
        curve.final_force,
        -applied
    );
    // Across the line of centres: frictionless disks pressed along it are
    // in unstable equilibrium against sliding sideways, so round-off grows
    // into a small transverse force (measured 0.5% of F). 2% bounds that
    // and would catch a real asymmetry of the contact.
    println!(
        "force across the line of centres: {:e}",
        curve.final_force.y
    );
    assert!(curve.final_force.y.abs() < 0.02 * curve.final_force.x.abs());
}

/// Mean of F / F_Hertz(a) − 1 over the samples whose load is in each band
/// of Hertz a: below the window (0.15 R to 0.2 R, printed only, to show the
/// trend towards small contacts) and the window's halves (0.2 R to 0.25 R,
/// 0.25 R to 0.3 R), with their numbers: the sign and the growth with load
/// that the mean |error| hides.
fn signed_errors(curve: &LoadingCurve) -> [(Real, usize); 3] {
    let bounds = [0.15, 0.2, 0.25, 0.3].map(|a| hertz_force(a * RADIUS));
    let mut sums = [(0.0, 0); 3];
    for &(a, f) in &curve.samples {
        if let Some(band) = (0..3).find(|&k| (bounds[k]..=bounds[k + 1]).contains(&f)) {
            sums[band].0 += f / hertz_force(a) - 1.0;
            sums[band].1 += 1;
        }
    }
    sums.map(|(sum, count)| (sum / count.max(1) as Real, count))
}

#[test]
#[ignore = "seven runs, 5 minutes; fails today: the error does not fall monotonically with resolution"]
fn hertz_disks_follow_the_2d_hertz_law_and_converge() {
    // The four resolutions and the turned pair, then two controls
    // that are printed and plotted but not judged: the finest point spacing
    // (R/80) on cells twice as fine with one point per cell, and the finest
    // run with Neo-Hookean disks. They show that the positive bias of the
    // finest run appears at the finest point spacing with 1 point per cell
    // too (cell size and points per cell shift it by a few points), and
    // that it depends on the finite-strain law, i.e. the window's strains
    // (mean contact pressure about 0.1 E) are beyond Hertz's small-strain
    // theory.
    let runs = [
        (20, 1, 0.0, false),
        (20, 2, 0.0, false),
        (40, 1, 0.0, false),
        (40, 2, 0.0, false),
        (40, 2, 45.0, false),
        (80, 1, 0.0, false),
        (40, 2, 0.0, true),
    ]
    .map(
        |(cells_per_radius, points_per_cell, angle, neo_hookean)| Resolution {
            cells_per_radius,
            points_per_cell,
            angle,
            neo_hookean,
        },
    );
    let curves: Vec<LoadingCurve> = runs.iter().map(|r| load_to_the_end(*r)).collect();
    let errors: Vec<(Real, usize)> = curves.iter().map(hertz_error).collect();
    for ((run, (error, count)), curve) in runs.iter().zip(&errors).zip(&curves) {
        let [(below, in_below), (lower, in_lower), (upper, in_upper)] = signed_errors(curve);
        println!(
            "{}: F(a) error {:.1}% over {count} samples; signed {:+.1}% (a 0.2–0.25 R, {in_lower} samples), {:+.1}% (0.25–0.3 R, {in_upper}); below the window {:+.1}% (0.15–0.2 R, {in_below})",
            run.label(),
            100.0 * error,
            100.0 * lower,
            100.0 * upper,
            100.0 * below
        );
    }
    // The turned pair against the unturned finest run: their half-widths at
    // equal load (a grows with the load, F does not always grow with a),
    // squared as F ∝ a², so the difference counts as one in F at equal a.
    let finest = &curves[3].samples;
    assert!(finest.len() >= 2, "the finest run has no loading curve");
    let width_at = |f: Real| {
        let k = finest
            .partition_point(|s| s.1 < f)
            .clamp(1, finest.len() - 1);
        let ((a0, f0), (a1, f1)) = (finest[k - 1], finest[k]);
        a0 + (a1 - a0) * (f - f0) / (f1 - f0)
    };
    let turned: Vec<Real> = curves[4]
        .samples
        .iter()
        .filter(|(_, f)| in_window(*f))
        .map(|&(a, f)| ((a / width_at(f)).powi(2) - 1.0).abs())
        .collect();
    let turned_difference = turned.iter().sum::<Real>() / turned.len().max(1) as Real;
    println!(
        "turned vs unturned at the finest resolution: {:.1}%",
        100.0 * turned_difference
    );
    plot(&runs, &curves);

    for (run, (_, count)) in runs.iter().zip(&errors).take(5) {
        assert!(
            *count >= 5,
            "{}: only {count} samples in the window",
            run.label()
        );
    }
    // The targets: within 10% at the finest resolution, the error
    // falling with resolution, the turned pair within 5% of the unturned.
    assert!(errors[3].0 < 0.10, "finest error {:.3}", errors[3].0);
    assert!(errors[0].0 > errors[1].0.max(errors[2].0));
    assert!(errors[1].0.min(errors[2].0) > errors[3].0);
    assert!(
        turned_difference < 0.05,
        "turned differs by {turned_difference:.3}"
    );
}

/// F against a / R for every run, with the Hertz law, in
/// `out/hertz_disks_study/f_of_a.png`.
fn plot(runs: &[Resolution], curves: &[LoadingCurve]) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("out/hertz_disks_study");
    std::fs::create_dir_all(&dir).expect("output folder");
    let scaled: Vec<Vec<(Real, Real)>> = curves
        .iter()
        .map(|c| c.samples.iter().map(|&(a, f)| (a / RADIUS, f)).collect())
        .collect();
    let analytical: Vec<(Real, Real)> = (0..=40)
        .map(|k| {
            let a = 0.35 * RADIUS * Real::from(k) / 40.0;
            (a / RADIUS, hertz_force(a))
        })
        .collect();
    let labels: Vec<String> = runs.iter().map(Resolution::label).collect();
    let mut series: Vec<Series> = scaled
        .iter()
        .zip(&labels)
        .map(|(points, name)| Series {
            name,
            points,
            style: SeriesStyle::Line,
        })
        .collect();
    series.push(Series {
        name: "Hertz: F = π E* a² / (4 R*)",
        points: &analytical,
        style: SeriesStyle::Line,
    });
    let path = dir.join("f_of_a.png");
    plot_series(
        &path,
        "Two disks pressed together",
        "contact half-width a / R",
        "contact force F (N/m)",
        &series,
    )
    .expect("plot");
    println!("plot: {}", path.display());
}

#[test]
fn a_non_finite_body_acceleration_is_refused() {
    let mut scene = common::load_scene("hertz_disks.ron");
    if let Some(load) = scene.bodies[0].acceleration.as_mut() {
        load.value.x = Real::INFINITY;
    }
    let message = scene.validate().expect_err("refused").to_string();
    assert!(message.contains("acceleration must be finite"), "{message}");
}
