//! Runs that meet faults and misuse keep their data, and commands never
//! panic: stop signals, a killed run, a damaged checkpoint, closed or full
//! standard output, runaway input, and progress when standard error is a
//! log. (A mistaken rerun over a checkpoint, and a run into another scene
//! file's folder: `cli/tests/cli.rs`.)

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn mpdem() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mpdem"))
}

/// `mpdem run SCENE --quiet --out OUT` with `extra` arguments.
fn run_into(scene: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    mpdem()
        .arg("run")
        .arg(scene)
        .args(["--quiet", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("mpdem runs")
}

/// The wave scene run for 10 s (100 000 steps, tens of seconds) into
/// `out`, checkpointed every 0.01 s, with standard error piped.
fn long_run(tag: &str) -> (common::TempFolder, PathBuf, Child) {
    let (base, scene) = common::edited_wave_scene(tag, "end: 1.0", "end: 10.0");
    let out = base.join("out");
    let child = mpdem()
        .args(["run", scene.to_str().unwrap(), "--quiet"])
        .args(["--checkpoint-every", "0.01", "--out", out.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mpdem runs");
    (base, out, child)
}

/// Waits until `ready` holds (at most a minute).
fn wait_for(ready: impl Fn() -> bool) {
    let started = Instant::now();
    while !ready() {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "not ready after 60 s"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn signal(child: &Child, name: &str) {
    let sent = Command::new("kill")
        .args([&format!("-{name}"), &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
}

/// The data rows of a CSV file, each checked to have the header's columns.
fn csv_rows(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).expect("the series");
    let mut lines = text.lines();
    let columns = lines.next().expect("a header").split(',').count();
    let mut rows = 0;
    for line in lines {
        assert_eq!(line.split(',').count(), columns, "a broken row: {line}");
        rows += 1;
    }
    rows
}

#[cfg(unix)]
#[test]
fn sigterm_and_sighup_stop_a_run_as_ctrl_c_does() {
    for name in ["TERM", "HUP"] {
        let (_base, out, child) = long_run(&format!("signal-{name}"));
        wait_for(|| out.join("checkpoint.bin").is_file());
        signal(&child, name);
        let result = child.wait_with_output().expect("mpdem ends");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(130), "SIG{name}: {stderr}");
        assert!(
            stderr.contains("stopped at step") && stderr.contains("`--resume` carries it on"),
            "SIG{name}: {stderr}"
        );
        assert!(csv_rows(&out.join("energy.csv")) >= 2);
        for file in ["probes.csv", "energy.png", "snapshot.png", "points.pvd"] {
            assert!(out.join(file).is_file(), "SIG{name}: {file} missing");
        }
    }
}

#[cfg(unix)]
#[test]
fn a_killed_run_keeps_its_series_up_to_its_last_sample() {
    let (_base, out, mut child) = long_run("sigkill");
    // The probe interval is end / 1000 = 0.01 s: wait for a few samples.
    wait_for(|| {
        std::fs::read_to_string(out.join("energy.csv")).is_ok_and(|t| t.lines().count() > 5)
    });
    child.kill().expect("SIGKILL");
    child.wait().expect("mpdem ends");
    for file in ["energy.csv", "probes.csv"] {
        let rows = csv_rows(&out.join(file));
        assert!(rows >= 5, "{file}: {rows} rows");
    }
}

#[test]
fn a_damaged_checkpoint_is_refused_and_nothing_is_overwritten() {
    let (base, scene) = common::edited_wave_scene("damaged", "end: 1.0", "end: 0.05");
    let out = base.join("out");
    let run = |extra: &[&str]| run_into(&scene, &out, extra);
    assert!(run(&["--checkpoint-every", "0.02"]).status.success());
    let checkpoint = out.join("checkpoint.bin");
    let mut bytes = std::fs::read(&checkpoint).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x10;
    std::fs::write(&checkpoint, &bytes).unwrap();
    let energy = std::fs::read(out.join("energy.csv")).unwrap();
    let result = run(&["--resume"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("the checkpoint is damaged"), "{stderr}");
    assert_eq!(std::fs::read(&checkpoint).unwrap(), bytes);
    assert_eq!(std::fs::read(out.join("energy.csv")).unwrap(), energy);
}

#[test]
fn a_closed_or_full_standard_output_does_not_panic() {
    let scene = common::scene_path("wave_1d.ron");
    // `mpdem check ... | head -c 0`: the reader is gone before the line.
    let mut child = mpdem()
        .args(["check", scene.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mpdem runs");
    drop(child.stdout.take());
    let result = child.wait_with_output().expect("mpdem ends");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    if Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let result = mpdem()
            .args(["check", scene.to_str().unwrap()])
            .stdout(full)
            .output()
            .expect("mpdem runs");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("cannot write to standard output") && !stderr.contains("panicked"),
            "{stderr}"
        );
    }
}

#[test]
fn a_run_logs_its_progress_when_standard_error_is_not_a_terminal() {
    let (base, scene) = common::edited_wave_scene("log", "end: 1.0", "end: 0.05");
    let result = mpdem()
        .args(["run", scene.to_str().unwrap(), "--out"])
        .arg(base.join("out"))
        .output()
        .expect("mpdem runs");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    // The first line at once, then one every 15 s and the last at the end.
    assert!(
        stderr.contains("step 0/500 t = 0.0000e0 s, elapsed 0:00:00, ETA")
            && stderr.contains("step 500/500 t = 5.0000e-2 s, elapsed"),
        "{stderr}"
    );
}

#[test]
fn runaway_input_is_refused_with_its_size() {
    // 1e12 steps: refused with the count; a larger cap named in the scene
    // lets it through to the run (checked, not run).
    let (_base, scene) =
        common::edited_wave_scene("steps", "dt: 1e-4, end: 1.0", "dt: 1e-12, end: 1.0");
    let result = mpdem()
        .args(["check"])
        .arg(&scene)
        .output()
        .expect("mpdem runs");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("gives 1.000e12 steps, more than the cap of 100000000 (time.max_steps"),
        "{stderr}"
    );
    let (_allowed_base, allowed) = common::edited_wave_scene(
        "steps-allowed",
        "dt: 1e-4, end: 1.0",
        "dt: 1e-6, end: 200.0, max_steps: 300000000",
    );
    let result = mpdem()
        .args(["check"])
        .arg(&allowed)
        .output()
        .expect("mpdem runs");
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    // An endless scene file, a file over a cap set by the variable, and a
    // cap that is not a number (refused, not replaced by the default): each
    // refused with status 1 and the message given.
    let refused_under_cap = |file: &Path, cap: &str, expected: &str| {
        let result = mpdem()
            .arg("check")
            .arg(file)
            .env("MPDEM_MAX_INPUT_BYTES", cap)
            .output()
            .expect("mpdem runs");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
    };
    if Path::new("/dev/zero").exists() {
        refused_under_cap(
            Path::new("/dev/zero"),
            "1000000",
            "/dev/zero: cannot read the scene: larger than the 1000000 bytes",
        );
    }
    let wave = common::scene_path("wave_1d.ron");
    refused_under_cap(
        &wave,
        "100",
        "larger than the 100 bytes an input file may have (MPDEM_MAX_INPUT_BYTES",
    );
    refused_under_cap(
        &wave,
        "1 GiB",
        "MPDEM_MAX_INPUT_BYTES is '1 GiB', not a number of bytes",
    );
    // Every step sampled over 10^7 steps: 10^7 rows of energies and as
    // many of the probe, more than a run keeps.
    let (_rows_base, rows) = common::write_edited(
        "wave_1d.ron",
        "rows",
        "rows.ron",
        &[
            ("dt: 1e-4, end: 1.0", "dt: 1e-7, end: 1.0"),
            ("probe_interval: Some(1e-4)", "probe_interval: Some(1e-7)"),
        ],
    );
    let result = mpdem()
        .args(["check"])
        .arg(&rows)
        .output()
        .expect("mpdem runs");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("1.000e7 samples of 2 records")
            && stderr.contains("more than the 10000000 a run keeps"),
        "{stderr}"
    );
}

#[test]
fn a_restart_that_cannot_open_the_folder_keeps_the_checkpoint() {
    let (base, scene) = common::edited_wave_scene("restart-kept", "end: 1.0", "end: 0.02");
    let out = base.join("out");
    let run = |extra: &[&str]| run_into(&scene, &out, extra);
    assert!(run(&["--checkpoint-every", "0.01"]).status.success());
    let checkpoint = std::fs::read(out.join("checkpoint.bin")).unwrap();
    // A list of outputs that is not mpdem's: the new run refuses the folder.
    std::fs::write(out.join("outputs.txt"), "a user's notes").unwrap();
    let result = run(&["--restart"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("not a list of mpdem's outputs"), "{stderr}");
    assert_eq!(
        std::fs::read(out.join("checkpoint.bin")).unwrap(),
        checkpoint
    );
}

#[test]
fn a_runner_runs_once() {
    use mpdem::runner::{RunError, RunOptions, Runner};
    let mut scene = common::load_scene("wave_1d.ron");
    scene.time.end = 0.001;
    let out = common::TempFolder::new("runs-once");
    let mut runner =
        Runner::new(&scene, None, RunOptions::into_folder(out.to_path_buf())).expect("a runner");
    let stop = std::sync::atomic::AtomicBool::new(false);
    assert!(runner.run(&stop, |_| {}).is_ok());
    assert!(matches!(
        runner.run(&stop, |_| {}),
        Err(RunError::RanAlready)
    ));
}

#[test]
fn a_symbolic_link_in_the_output_folder_is_refused_and_nothing_is_written_through_it() {
    let (base, scene) = common::edited_wave_scene("links", "end: 1.0", "end: 0.01");
    let out = base.join("out");
    assert!(run_into(&scene, &out, &[]).status.success());
    let outside = base.join("outside");
    std::fs::create_dir_all(&outside).unwrap();
    let target = outside.join("kept.txt");
    std::fs::write(&target, "not the run's").unwrap();
    let frame = out.join("vtk/points_00000.vtu");
    // energy.csv, a frame file and vtk/ itself replaced by links out.
    for link in [out.join("energy.csv"), frame.clone(), out.join("vtk")] {
        let moved = base.join("moved");
        if link.is_dir() {
            std::fs::rename(&link, &moved).unwrap();
            std::os::unix::fs::symlink(&outside, &link).unwrap();
        } else {
            std::fs::remove_file(&link).unwrap();
            std::os::unix::fs::symlink(&target, &link).unwrap();
        }
        let rerun = run_into(&scene, &out, &[]);
        let stderr = String::from_utf8_lossy(&rerun.stderr);
        assert_eq!(rerun.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains(&format!("{} is a symbolic link", link.display())),
            "{stderr}"
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "not the run's");
        assert_eq!(std::fs::read_dir(&outside).unwrap().count(), 1);
        std::fs::remove_file(&link).unwrap();
        if moved.exists() {
            std::fs::rename(&moved, &link).unwrap();
        } else {
            std::fs::write(&link, "").unwrap();
        }
    }
}
