//! Contact groups: bodies that share one grid layer act as one continuum.

mod common;

use mpdem::prelude::*;
use mpdem::resources::BodyContacts;
use mpdem::scene::{BodyContactSpec, Shape};

/// The elastic column settling under gravity, as one body or split at
/// y = 0.5 m (a cell boundary, so the points are the same) into a lower and
/// an upper body, in one contact group when `group` is given.
fn column(split: bool, group: Option<&str>) -> Scene {
    let mut scene = common::load_scene("elastic_column.ron");
    scene.time.end = 0.2;
    scene.probes.clear();
    if split {
        let mut upper = scene.bodies[0].clone();
        let lower = &mut scene.bodies[0];
        lower.name = "lower".into();
        lower.shape = Shape::Rectangle {
            min: DVec2::new(0.0, 0.0),
            max: DVec2::new(0.2, 0.5),
        };
        upper.name = "upper".into();
        upper.shape = Shape::Rectangle {
            min: DVec2::new(0.0, 0.5),
            max: DVec2::new(0.2, 1.0),
        };
        scene.bodies.push(upper);
        for body in &mut scene.bodies {
            body.group = group.map(str::to_owned);
        }
    }
    scene
}

/// The lowest point of a body.
fn bottom(sim: &mut Simulation, name: &str) -> Real {
    sim.points_of(name)
        .expect("body")
        .position
        .iter()
        .map(|x| x.y)
        .fold(Real::INFINITY, Real::min)
}

#[test]
fn a_body_split_within_one_group_moves_as_the_whole_body() {
    // At the defaults (USF with remapped positions: the remapped velocity
    // is summed over the group), under MUSL (whose stress update reads that
    // sum) and with the paper's USF and eq. 11b.
    split_column_matches_the_whole(|_| {});
    split_column_matches_the_whole(|settings| {
        settings.scheme = mpdem::resources::UpdateScheme::Musl;
    });
    split_column_matches_the_whole(|settings| {
        settings.scheme = mpdem::resources::UpdateScheme::Usf;
        settings.position_update = Some(mpdem::resources::PositionUpdate::PaperEq11b);
    });
}

/// Runs the column whole and split in one group with `settings` changed,
/// and asserts that every point moves and is stressed alike.
fn split_column_matches_the_whole(change: impl Fn(&mut mpdem::resources::Settings)) {
    let (mut whole, mut split) = (column(false, None), column(true, Some("column")));
    change(&mut whole.settings);
    change(&mut split.settings);
    let mut whole = common::run_scene(&whole);
    let mut split = common::run_scene(&split);
    let reference = whole.points_of("column").expect("column").clone();
    let scale = reference
        .stress
        .iter()
        .map(|s| s.yy.abs())
        .fold(0.0, Real::max);
    let (mut position_gap, mut stress_gap, mut matched) = (0.0 as Real, 0.0 as Real, 0);
    for name in ["lower", "upper"] {
        let part = split.points_of(name).expect("part");
        for (p, x0) in part.initial_position.iter().enumerate() {
            let q = reference
                .initial_position
                .iter()
                .position(|y| y == x0)
                .expect("the same point in the whole column");
            position_gap = position_gap.max(part.position[p].distance(reference.position[q]));
            let d = part.stress[p].to_array();
            let r = reference.stress[q].to_array();
            for k in 0..4 {
                stress_gap = stress_gap.max((d[k] - r[k]).abs() / scale);
            }
            matched += 1;
        }
    }
    println!(
        "{matched} points: position gap {position_gap:e} m, stress gap {stress_gap:e} of the base stress"
    );
    assert_eq!(matched, reference.len());
    // The split only changes the order of the sums at the nodes (each body
    // scatters, then the group's layers are added): round-off, far below
    // the 0.1 mm the column settles.
    assert!(position_gap < 1e-10, "position gap {position_gap:e}");
    assert!(stress_gap < 1e-8, "stress gap {stress_gap:e}");
}

#[test]
fn without_a_group_the_upper_body_falls_through_the_lower_one() {
    let mut grouped = common::run_scene(&column(true, Some("column")));
    let mut apart = common::run_scene(&column(true, None));
    let (held, fell) = (bottom(&mut grouped, "upper"), bottom(&mut apart, "upper"));
    println!("upper body's lowest point after 0.2 s: {held:.4} m in a group, {fell:.4} m apart");
    // Apart, the upper half falls freely: ½ (1 − α_g) g t² = 0.157 m in
    // 0.2 s (the scene's grid damping α_g = 0.2 takes a fifth of the
    // unbalanced force). In the group it settles by a fraction of a mm.
    assert!(held > 0.5 - 0.01, "in a group it rests on the lower half");
    assert!(fell < 0.5 - 0.1, "apart it falls through");
}

/// Two bodies in group "pair" and a third body, with a law between "pair"
/// and "third" (or the given sides).
fn grouped_scene(between: (&str, &str)) -> Scene {
    let mut scene = column(true, Some("pair"));
    let mut third = scene.bodies[0].clone();
    third.name = "third".into();
    third.group = None;
    third.shape = Shape::Rectangle {
        min: DVec2::new(0.0, 1.0),
        max: DVec2::new(0.2, 1.1),
    };
    scene.bodies.push(third);
    scene.body_contacts = vec![BodyContactSpec {
        between: (between.0.into(), between.1.into()),
        law: mpdem::contact::ContactLaw {
            normal_stiffness: 1e7,
            tangential_stiffness: 1e7,
            friction: 0.3,
            normal_damping: 0.0,
        },
    }];
    scene
}

#[test]
fn a_law_naming_a_group_holds_for_each_of_its_bodies() {
    let sim = Simulation::from_scene(&grouped_scene(("third", "pair"))).expect("scene");
    let pairs: Vec<(u32, u32)> = sim
        .world()
        .resource::<BodyContacts>()
        .laws
        .iter()
        .map(|l| (l.a, l.b))
        .collect();
    assert_eq!(pairs, [(0, 2), (1, 2)]);
}

#[test]
fn bad_contact_groups_are_refused() {
    let message = |scene: &Scene| scene.validate().expect_err("refused").to_string();
    let within = message(&grouped_scene(("lower", "pair")));
    assert!(within.contains("shares its layer"), "{within}");
    let unknown = message(&grouped_scene(("third", "nobody")));
    assert!(
        unknown.contains("unknown body or group 'nobody'"),
        "{unknown}"
    );
    let mut named_like_a_body = grouped_scene(("third", "pair"));
    named_like_a_body.bodies[2].group = Some("lower".into());
    let clash = message(&named_like_a_body);
    assert!(clash.contains("has the name of a body"), "{clash}");
    let mut with_xpic = column(true, Some("column"));
    with_xpic.settings.xpic_order = Some(2);
    let xpic = message(&with_xpic);
    assert!(
        xpic.contains("XPIC is not available with contact groups"),
        "{xpic}"
    );
}
