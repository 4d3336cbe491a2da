//! Property-based fuzzing of the scene format: a shipped scene with one to
//! four mutations at once: values pushed to extremes, names made hostile,
//! lists emptied or their first entry duplicated, fields dropped or
//! repeated, lines dropped or repeated. Each mutant is parsed and, if
//! accepted, built and stepped a few times on a thread with a time limit:
//! no panic, no hang, and no non-finite state, energy or recorded value
//! after steps that reported no failure.
//!
//! `PROPTEST_CASES` sets the number of mutants (80 000 by default, about two
//! minutes on 2 cores); a long run is `PROPTEST_CASES=1000000 cargo test
//! --release --test fuzz_scenes`. proptest keeps the seed of a failure
//! in `tests/fuzz_scenes.proptest-regressions`, and replays it first on every later run.

mod common;

use mpdem::prelude::*;
use mpdem::resources::EnergyLog;
use proptest::prelude::*;
use std::path::Path;
use std::time::Duration;

/// The scenes mutated: every shipped scene. Those of many points are
/// stepped less (see [`steps_for`]).
const SCENES: [&str; 23] = [
    "axisymmetric_punch.ron",
    "block_on_ground.ron",
    "circular_footing.ron",
    "column_collapse.ron",
    "dam_break.ron",
    "elastic_column.ron",
    "geostatic_column.ron",
    "granular_collapse_bui.ron",
    "granular_slab.ron",
    "hertz_disks.ron",
    "pile_penetration.ron",
    "pile_penetration_axisymmetric.ron",
    "rigid_drop.ron",
    "rigid_tip.ron",
    "sliding_45.ron",
    "stacked_blocks.ron",
    "strip_footing.ron",
    "toppling_14.ron",
    "toppling_16.ron",
    "toppling_18.ron",
    "toppling_20.ron",
    "two_rings.ron",
    "wave_1d.ron",
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

/// Most steps taken of an accepted mutant.
const STEPS: usize = 20;

/// Point-steps an accepted mutant is given: a mutant of many points takes
/// fewer steps (at least [`FEWEST_STEPS`]).
const POINT_STEPS: Real = 2e5;

/// Fewest steps taken of an accepted mutant.
const FEWEST_STEPS: usize = 2;

/// The steps a mutant of `points` points takes.
fn steps_for(points: Real) -> usize {
    ((POINT_STEPS / points.max(1.0)) as usize).clamp(FEWEST_STEPS, STEPS)
}

/// Longest a mutant may take to parse, build and step (a hang otherwise).
const TIME_LIMIT: Duration = Duration::from_secs(60);

/// Most points a mutant that is built and stepped may have: a mutant that
/// asks for more (a cell size pushed to 1e-20, say) is refused by the
/// scene's caps only past 2e7 points, too many for this test's budget; it
/// is parsed and validated only.
const MOST_POINTS: Real = 1e5;

/// Most mutations applied to one scene at once.
const MOST_MUTATIONS: usize = 4;

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
    /// The `k`-th list emptied.
    EmptyList(usize),
    /// The `k`-th list's first entry written twice.
    DuplicateEntry(usize),
    /// The `k`-th field (`name: value`) dropped.
    DropField(usize),
    /// The `k`-th field written twice.
    RepeatField(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..EXTREMES.len()).prop_map(|(k, v)| Mutation::Number(k, v)),
        2 => (any::<usize>(), 0..HOSTILE.len()).prop_map(|(k, v)| Mutation::Name(k, v)),
        1 => any::<usize>().prop_map(Mutation::DropLine),
        1 => any::<usize>().prop_map(Mutation::RepeatLine),
        1 => any::<usize>().prop_map(Mutation::EmptyList),
        1 => any::<usize>().prop_map(Mutation::DuplicateEntry),
        2 => any::<usize>().prop_map(Mutation::DropField),
        1 => any::<usize>().prop_map(Mutation::RepeatField),
    ]
}

/// Per byte of `bytes`, whether it lies outside comments and string
/// literals (the quotes included).
fn code_mask(bytes: &[u8]) -> Vec<bool> {
    let mut code = vec![true; bytes.len()];
    let (mut k, mut in_string) = (0, false);
    while k < bytes.len() {
        let c = bytes[k];
        if in_string {
            code[k] = false;
            if c == b'\\' {
                if let Some(escaped) = code.get_mut(k + 1) {
                    *escaped = false;
                }
                k += 1;
            } else if c == b'"' {
                in_string = false;
            }
        } else if c == b'"' {
            code[k] = false;
            in_string = true;
        } else if c == b'/' && bytes.get(k + 1) == Some(&b'/') {
            while k < bytes.len() && bytes[k] != b'\n' {
                code[k] = false;
                k += 1;
            }
            continue;
        }
        k += 1;
    }
    code
}

/// Where the value that starts at `start` ends: at the first `,` or
/// closing bracket outside the brackets it opens (`code` is `bytes`'
/// [`code_mask`]).
fn value_end(bytes: &[u8], code: &[bool], start: usize) -> usize {
    let mut depth = 0_i32;
    for k in (start..bytes.len()).filter(|&k| code[k]) {
        match bytes[k] {
            b'(' | b'[' => depth += 1,
            b')' | b']' if depth == 0 => return k,
            b')' | b']' => depth -= 1,
            b',' if depth == 0 => return k,
            _ => {}
        }
    }
    bytes.len()
}

/// Byte offsets `k` outside comments and strings where `wanted(k)` holds.
fn structural(bytes: &[u8], code: &[bool], wanted: impl Fn(usize) -> bool) -> Vec<usize> {
    (0..bytes.len()).filter(|&k| code[k] && wanted(k)).collect()
}

/// The lists' contents: from after each `[` to its `]`.
fn list_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let code = code_mask(bytes);
    structural(bytes, &code, |k| bytes[k] == b'[')
        .into_iter()
        .map(|open| {
            let mut end = value_end(bytes, &code, open + 1);
            while end < bytes.len() && bytes[end] == b',' {
                end = value_end(bytes, &code, end + 1);
            }
            (open + 1, end)
        })
        .collect()
}

/// The fields: from the start of each `name:` to the end of its value.
fn field_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let code = code_mask(bytes);
    structural(bytes, &code, |k| {
        bytes[k] == b':' && k > 0 && bytes[k - 1].is_ascii_alphanumeric()
    })
    .into_iter()
    .map(|colon| {
        let mut start = colon;
        while start > 0 && (bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_') {
            start -= 1;
        }
        (start, value_end(bytes, &code, colon + 1))
    })
    .collect()
}

/// The byte ranges of the numbers outside comments and strings.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let code = code_mask(bytes);
    let mut spans = Vec::new();
    let mut k = 0;
    while k < bytes.len() {
        let c = bytes[k];
        if code[k]
            && (c.is_ascii_digit() || c == b'-')
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
    let pick = |spans: Vec<(usize, usize)>, k: usize| match spans.len() {
        0 => None,
        n => Some(spans[k % n]),
    };
    let replace = |span: Option<(usize, usize)>, with: &str| match span {
        Some((a, b)) => format!("{}{with}{}", &text[..a], &text[b..]),
        None => text.to_string(),
    };
    let lines: Vec<&str> = text.lines().collect();
    match *mutation {
        Mutation::Number(k, v) => replace(pick(number_spans(text), k), EXTREMES[v]),
        Mutation::Name(k, v) => replace(pick(string_spans(text), k), HOSTILE[v]),
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
        Mutation::EmptyList(k) => replace(pick(list_spans(text), k), ""),
        Mutation::DuplicateEntry(k) => match pick(list_spans(text), k) {
            Some((a, _)) => {
                let bytes = text.as_bytes();
                let first = &text[a..value_end(bytes, &code_mask(bytes), a)];
                format!("{}{first},{}", &text[..a], &text[a..])
            }
            None => text.to_string(),
        },
        Mutation::DropField(k) => {
            let span = pick(field_spans(text), k).map(|(a, b)| {
                // The comma after the field goes with it.
                (
                    a,
                    if text.as_bytes().get(b) == Some(&b',') {
                        b + 1
                    } else {
                        b
                    },
                )
            });
            replace(span, "")
        }
        Mutation::RepeatField(k) => match pick(field_spans(text), k) {
            Some((a, b)) => format!("{}{}, {}", &text[..a], &text[a..b], &text[a..]),
            None => text.to_string(),
        },
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
    for _ in 0..steps_for(points) {
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
    // Every recorded series, as its CSV would be written.
    for file in sim.series_files() {
        let csv = sim.series_csv(file).unwrap_or_default();
        if let Some(row) = csv.lines().skip(1).find(|row| {
            row.split(',')
                .any(|cell| cell.parse::<Real>().is_ok_and(|x| !x.is_finite()))
        }) {
            return Err(format!("{file} records a non-finite value: {row}"));
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
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(80_000),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_scenes_never_panic_hang_or_record_non_finite_values(
        scene in 0..SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..=MOST_MUTATIONS),
    ) {
        let path = common::scene_path(SCENES[scene]);
        let text = std::fs::read_to_string(Path::new(&path)).expect("a shipped scene");
        let mutant = mutations.iter().fold(text, |t, m| mutate(&t, m));
        let outcome = check_mutant(mutant.clone());
        prop_assert!(outcome.is_ok(), "{}: {mutations:?}: {}\n{mutant}", SCENES[scene], outcome.unwrap_err());
    }
}

#[test]
fn each_mutation_changes_what_it_names() {
    let text = "S(a: [(n: \"x\", v: 1.5), (n: \"y\", v: 2)], b: (c: 3))";
    let cases = [
        (
            Mutation::Number(0, 4),
            "S(a: [(n: \"x\", v: 1e300), (n: \"y\", v: 2)], b: (c: 3))",
        ),
        (
            Mutation::Name(1, 0),
            "S(a: [(n: \"x\", v: 1.5), (n: \"\", v: 2)], b: (c: 3))",
        ),
        (Mutation::EmptyList(0), "S(a: [], b: (c: 3))"),
        (
            Mutation::DuplicateEntry(0),
            "S(a: [(n: \"x\", v: 1.5),(n: \"x\", v: 1.5), (n: \"y\", v: 2)], b: (c: 3))",
        ),
        (
            Mutation::DropField(2),
            "S(a: [(n: \"x\", ), (n: \"y\", v: 2)], b: (c: 3))",
        ),
        (
            Mutation::DropField(6),
            "S(a: [(n: \"x\", v: 1.5), (n: \"y\", v: 2)], b: ())",
        ),
        (
            Mutation::RepeatField(5),
            "S(a: [(n: \"x\", v: 1.5), (n: \"y\", v: 2)], b: (c: 3), b: (c: 3))",
        ),
    ];
    for (mutation, expected) in cases {
        assert_eq!(mutate(text, &mutation), expected, "{mutation:?}");
    }
}
