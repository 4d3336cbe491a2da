//! Property-based fuzzing of the scene format: a shipped scene with one
//! value pushed to an extreme, one name made hostile, or one line dropped
//! or repeated. Each mutant is parsed and, if accepted, built and stepped a
//! few times on a thread with a time limit: no panic, no hang, and no
//! non-finite state or energy after a step that reported no failure.
//!
//! `PROPTEST_CASES` sets the number of mutants (50 000 by default, about a
//! minute on 2 cores); a long run is `PROPTEST_CASES=1000000 cargo test --release --test
//! fuzz_scenes`. proptest keeps the seed of a failure under
//! `proptest-regressions/`, and replays it first on every later run.

mod common;

use mpdem::prelude::*;
use mpdem::resources::EnergyLog;
use proptest::prelude::*;
use std::path::Path;
use std::time::Duration;

/// The scenes mutated: small enough to build and step in milliseconds.
const SCENES: [&str; 6] = [
    "wave_1d.ron",
    "elastic_column.ron",
    "rigid_drop.ron",
    "sliding_45.ron",
    "block_on_ground.ron",
    "toppling_14.ron",
];

/// Values a number is replaced with: zeros, signs, the edges of f64 and
/// u32/u64, non-finite values.
const EXTREMES: [&str; 14] = [
    "0",
    "-0.0",
    "-1",
    "1e-300",
    "1e300",
    "NaN",
    "inf",
    "-inf",
    "4294967295",
    "18446744073709551615",
    "1e20",
    "1e-20",
    "0.5",
    "-1e6",
];

/// Names a string literal is replaced with.
const HOSTILE: [&str; 8] = [
    "",
    " ",
    "a\\nb",
    "\\u{1b}[31mred",
    "../escape",
    "a/b",
    "CON",
    "xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx",
];

/// Steps taken of an accepted mutant.
const STEPS: usize = 20;

/// Longest a mutant may take to parse, build and step (a hang otherwise).
const TIME_LIMIT: Duration = Duration::from_secs(60);

/// Most points and grid nodes of a mutant that is stepped: a mutant that
/// asks for more (a cell size pushed to 1e-20, say) is refused by the
/// scene's caps only past 2e7 points, too many for this test's budget.
const MOST_POINTS: Real = 2e5;

/// One mutation of a scene's text.
#[derive(Clone, Debug)]
enum Mutation {
    /// The `k`-th number (modulo their count) replaced by `EXTREMES[v]`.
    Number(usize, usize),
    /// The `k`-th string literal replaced by `HOSTILE[v]`.
    Name(usize, usize),
    /// The `k`-th line dropped.
    DropLine(usize),
    /// The `k`-th line repeated.
    RepeatLine(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..EXTREMES.len()).prop_map(|(k, v)| Mutation::Number(k, v)),
        2 => (any::<usize>(), 0..HOSTILE.len()).prop_map(|(k, v)| Mutation::Name(k, v)),
        1 => any::<usize>().prop_map(Mutation::DropLine),
        1 => any::<usize>().prop_map(Mutation::RepeatLine),
    ]
}

/// The byte ranges of the numbers outside comments and strings.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let (mut k, mut in_string) = (0, false);
    while k < bytes.len() {
        let c = bytes[k];
        if in_string {
            if c == b'\\' {
                k += 1;
            } else if c == b'"' {
                in_string = false;
            }
        } else if c == b'"' {
            in_string = true;
        } else if c == b'/' && bytes.get(k + 1) == Some(&b'/') {
            while k < bytes.len() && bytes[k] != b'\n' {
                k += 1;
            }
        } else if (c.is_ascii_digit() || c == b'-')
            && !(k > 0 && (bytes[k - 1].is_ascii_alphanumeric() || bytes[k - 1] == b'_'))
        {
            let start = k;
            k += 1;
            while k < bytes.len()
                && (bytes[k].is_ascii_digit()
                    || matches!(bytes[k], b'.' | b'e' | b'E')
                    || (matches!(bytes[k], b'-' | b'+') && matches!(bytes[k - 1], b'e' | b'E')))
            {
                k += 1;
            }
            if bytes[start..k].iter().any(u8::is_ascii_digit) {
                spans.push((start, k));
            }
            continue;
        }
        k += 1;
    }
    spans
}

/// The byte ranges of the string literals' contents outside comments.
fn string_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut k = 0;
    while k < bytes.len() {
        match bytes[k] {
            b'/' if bytes.get(k + 1) == Some(&b'/') => {
                while k < bytes.len() && bytes[k] != b'\n' {
                    k += 1;
                }
            }
            b'"' => {
                let start = k + 1;
                k += 1;
                while k < bytes.len() && bytes[k] != b'"' {
                    k += if bytes[k] == b'\\' { 2 } else { 1 };
                }
                spans.push((start, k.min(bytes.len())));
            }
            _ => {}
        }
        k += 1;
    }
    spans
}

fn mutate(text: &str, mutation: &Mutation) -> String {
    let replace = |spans: Vec<(usize, usize)>, k: usize, with: &str| match spans.len() {
        0 => text.to_string(),
        n => {
            let (a, b) = spans[k % n];
            format!("{}{with}{}", &text[..a], &text[b..])
        }
    };
    let lines: Vec<&str> = text.lines().collect();
    match *mutation {
        Mutation::Number(k, v) => replace(number_spans(text), k, EXTREMES[v]),
        Mutation::Name(k, v) => replace(string_spans(text), k, HOSTILE[v]),
        Mutation::DropLine(k) => {
            let drop = k % lines.len();
            let kept: Vec<&str> = (0..lines.len())
                .filter(|&i| i != drop)
                .map(|i| lines[i])
                .collect();
            kept.join("\n")
        }
        Mutation::RepeatLine(k) => {
            let at = k % lines.len();
            let mut out = lines.clone();
            out.insert(at, lines[at]);
            out.join("\n")
        }
    }
}

/// Parses, builds and steps `text`: an error if it panics, or steps
/// without a failure into a non-finite state or energy.
fn try_mutant(text: String) -> Result<(), String> {
    let path = common::scene_path("mutant.ron");
    let Ok(scene) = Scene::parse(&text, &path) else {
        return Ok(());
    };
    let spacing = |b: &mpdem::scene::BodySpec| scene.grid.cell_size / b.points_per_cell as Real;
    let points: Real = scene
        .bodies
        .iter()
        .map(|b| b.shape.point_estimate(spacing(b)))
        .sum();
    if points.is_nan() || points > MOST_POINTS {
        return Ok(());
    }
    let Ok(mut sim) = Simulation::from_scene(&scene) else {
        return Ok(());
    };
    for _ in 0..STEPS {
        if sim.step().is_err() {
            return Ok(());
        }
        for (entity, name) in sim.bodies() {
            let Some(points) = sim.points(entity) else {
                continue;
            };
            let finite = points.position.iter().all(|x| x.is_finite())
                && points.velocity.iter().all(|v| v.is_finite())
                && points.stress.iter().all(|s| s.is_finite());
            if !finite {
                return Err(format!(
                    "body '{name}' is not finite after a step that succeeded"
                ));
            }
        }
        let energy = sim.world().get_resource::<EnergyLog>();
        if let Some(broken) =
            energy.and_then(|e| e.samples.iter().find_map(|s| s.first_non_finite()))
        {
            return Err(format!(
                "energy '{broken}' is not finite after a step that succeeded"
            ));
        }
    }
    Ok(())
}

/// Runs `try_mutant` on a thread: a panic or a time past `TIME_LIMIT` is
/// an error too.
fn check_mutant(text: String) -> Result<(), String> {
    let (done, result) = std::sync::mpsc::channel();
    std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let outcome = std::panic::catch_unwind(|| try_mutant(text));
            let _ = done.send(outcome);
        })
        .expect("a thread");
    match result.recv_timeout(TIME_LIMIT) {
        Ok(Ok(outcome)) => outcome,
        Ok(Err(_)) => Err("panicked".into()),
        Err(_) => Err(format!("not done within {TIME_LIMIT:?}: a hang")),
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(50_000),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_scenes_never_panic_hang_or_record_non_finite_values(
        scene in 0..SCENES.len(),
        mutation in mutation(),
    ) {
        let path = common::scene_path(SCENES[scene]);
        let text = std::fs::read_to_string(Path::new(&path)).expect("a shipped scene");
        let mutant = mutate(&text, &mutation);
        let outcome = check_mutant(mutant.clone());
        prop_assert!(outcome.is_ok(), "{}: {mutation:?}: {}\n{mutant}", SCENES[scene], outcome.unwrap_err());
    }
}
