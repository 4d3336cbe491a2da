//! The malformed scenes of `cli/tests/bad_input/`, one broken thing each over
//! every section of the scene format and the point files: `mpdem check`
//! and `mpdem run` refuse each with status 1, the message its first line
//! expects (`// expect: ...`) at the file, line and column its second line
//! gives (`// at: LINE:COL`), no panic, and nothing written.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// The corpus folder.
fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_input")
}

/// A malformed scene and what its refusal must say.
struct Case {
    path: PathBuf,
    expect: String,
    at: Option<String>,
}

fn cases() -> Vec<Case> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(corpus())
        .expect("the corpus")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("a scene");
            let mut lines = text.lines();
            let header = |line: Option<&str>, key: &str| {
                line.and_then(|l| l.strip_prefix(key))
                    .unwrap_or_else(|| panic!("{}: no '{key}' line", path.display()))
                    .trim()
                    .to_owned()
            };
            let expect = header(lines.next(), "// expect:");
            let at = header(lines.next(), "// at:");
            Case {
                path,
                expect,
                at: (at != "none").then_some(at),
            }
        })
        .collect()
}

#[test]
fn every_malformed_scene_is_refused_with_where_and_what_and_nothing_written() {
    let cases = cases();
    assert!(cases.len() >= 40, "{} malformed scenes", cases.len());
    let out = common::TempFolder::new("bad-input");
    let mut failures = Vec::new();
    for case in &cases {
        let name = case
            .path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let folder = out.join(&name);
        for args in [
            vec!["check", case.path.to_str().unwrap()],
            vec![
                "run",
                case.path.to_str().unwrap(),
                "--quiet",
                "--out",
                folder.to_str().unwrap(),
            ],
        ] {
            let result = Command::new(env!("CARGO_BIN_EXE_mpdem"))
                .args(&args)
                .output()
                .expect("mpdem runs");
            let stderr = String::from_utf8_lossy(&result.stderr);
            let place = case
                .at
                .as_ref()
                .map(|at| format!("{}:{at}:", case.path.display()));
            let problem = if result.status.code() != Some(1) {
                Some(format!("status {:?}", result.status.code()))
            } else if stderr.contains("panicked") {
                Some("a panic".into())
            } else if !stderr.contains(&case.expect) {
                Some(format!("no '{}'", case.expect))
            } else if place.as_ref().is_some_and(|p| !stderr.contains(p.as_str())) {
                Some(format!("not at {}", place.unwrap()))
            } else if folder.exists() {
                Some("an output folder was written".into())
            } else {
                None
            };
            if let Some(problem) = problem {
                failures.push(format!("{name} ({}): {problem}: {stderr}", args[0]));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
