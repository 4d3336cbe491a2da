//! `mpdem run` writes every output; `mpdem check` validates; `mpdem
//! verify` tabulates its cases.

mod common;

use std::process::Command;

fn mpdem(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mpdem"))
        .args(args)
        .output()
        .expect("mpdem runs")
}

/// `mpdem run SCENE --quiet --out OUT` with `extra` arguments.
fn run_into(
    scene: &std::path::Path,
    out: &std::path::Path,
    extra: &[&str],
) -> std::process::Output {
    let mut args = vec![
        "run",
        scene.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    mpdem(&args)
}

#[test]
fn run_writes_csv_vtk_and_png_outputs() {
    // The wave scene shortened to 0.05 s (500 steps) to keep the test fast.
    let (base, scene) = common::edited_wave_scene("short", "end: 1.0", "end: 0.05");
    let out = base.join("out");
    let result = mpdem(&[
        "run",
        scene.to_str().unwrap(),
        "--quiet",
        "--threads",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(stdout.contains("state hash"), "{stdout}");
    for file in [
        "probes.csv",
        "energy.csv",
        "points.pvd",
        "snapshot.png",
        "energy.png",
        "probe_midpoint_velocity.png",
        "probe_midpoint_displacement.png",
        "probe_midpoint_stress.png",
        "vtk/points_00000.vtu",
        "vtk/points_00005.vtu",
    ] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    let probes = std::fs::read_to_string(out.join("probes.csv")).unwrap();
    assert_eq!(
        probes.lines().count(),
        1 + 501,
        "header + one row per step and step 0"
    );
    let pvd = std::fs::read_to_string(out.join("points.pvd")).unwrap();
    assert_eq!(
        pvd.matches("<DataSet").count(),
        6,
        "frames at 0, 0.01, ..., 0.05 s"
    );
}

#[test]
fn check_accepts_every_shipped_scene() {
    for scene in ["wave_1d.ron", "elastic_column.ron"] {
        let path = common::scene_path(scene);
        let result = mpdem(&["check", path.to_str().unwrap()]);
        assert!(
            result.status.success(),
            "{scene}: {}",
            String::from_utf8_lossy(&result.stderr)
        );
        assert!(String::from_utf8_lossy(&result.stdout).contains(": ok"));
    }
    let missing = mpdem(&["check", "no/such/scene.ron"]);
    assert!(!missing.status.success());
    assert!(
        String::from_utf8_lossy(&missing.stderr)
            .contains("no/such/scene.ron: cannot read the scene")
    );
    // Several at once (`mpdem check scenes/*.ron`): each reported, status 1
    // if any is refused.
    let (wave, column) = (
        common::scene_path("wave_1d.ron"),
        common::scene_path("elastic_column.ron"),
    );
    let (wave, column) = (wave.to_str().unwrap(), column.to_str().unwrap());
    let both = mpdem(&["check", wave, column]);
    assert!(both.status.success());
    assert_eq!(
        String::from_utf8_lossy(&both.stdout)
            .matches(": ok")
            .count(),
        2
    );
    let one_bad = mpdem(&["check", wave, "no/such/scene.ron", column]);
    assert_eq!(one_bad.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&one_bad.stdout)
            .matches(": ok")
            .count(),
        2
    );
    assert!(String::from_utf8_lossy(&one_bad.stderr).contains("no/such/scene.ron"));
}

#[test]
fn a_blow_up_stops_the_run_and_writes_no_broken_state() {
    // Ten times the CFL limit: the bar inverts within a few steps.
    let (base, scene) =
        common::edited_wave_scene("blowup", "dt: 1e-4, end: 1.0", "dt: 5e-3, end: 1.0");
    let out = base.join("out");
    let result = mpdem(&[
        "run",
        scene.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("CFL limit"), "{stderr}");
    assert!(
        stderr.contains("numerical failure at step") && stderr.contains("body 'bar', point"),
        "{stderr}"
    );
    for file in ["probes.csv", "energy.csv"] {
        let text = std::fs::read_to_string(out.join(file)).unwrap();
        assert!(
            !text.to_lowercase().contains("nan") && !text.contains("inf"),
            "{file} holds a broken state"
        );
    }
}

/// The state hash `mpdem run` prints.
/// Every file under `dir`, at any depth.
fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).expect("a folder") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            files.extend(walk(&path));
        } else {
            files.push(path);
        }
    }
    files
}

fn printed_hash(output: &std::process::Output) -> String {
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let at = stdout.find("state hash ").expect("a state hash") + "state hash ".len();
    stdout[at..at + 16].to_owned()
}

#[test]
fn a_new_run_into_a_folder_removes_the_earlier_runs_files_and_no_others() {
    let (base, long) = common::edited_wave_scene("rerun-long", "end: 1.0", "end: 0.05");
    let (_short_base, short) = common::edited_wave_scene("rerun-short", "end: 1.0", "end: 0.02");
    let out = base.join("out");
    let run = |scene: &std::path::Path, extra: &[&str]| {
        let result = run_into(scene, &out, extra);
        assert!(
            result.status.success(),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
    };
    run(&long, &["--checkpoint-every", "0.01"]);
    assert!(out.join("vtk/points_00005.vtu").is_file());
    let checkpoint = std::fs::read(out.join("checkpoint.bin")).unwrap();
    std::fs::write(out.join("notes.txt"), "the user's").unwrap();
    std::fs::write(out.join("vtk/mine.vtu"), "the user's").unwrap();
    // Refused, nothing touched: the same scene again without --resume (a
    // mistaken rerun would replace the checkpoint with an earlier one), and
    // another scene file into this one's folder.
    let refused = |scene: &std::path::Path, extra: &[&str], expected: &[&str]| {
        let result = run_into(scene, &out, extra);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(1), "{stderr}");
        for text in expected {
            assert!(stderr.contains(text), "'{text}' not in: {stderr}");
        }
        assert_eq!(
            std::fs::read(out.join("checkpoint.bin")).unwrap(),
            checkpoint
        );
        assert!(out.join("vtk/points_00005.vtu").is_file());
    };
    refused(
        &long,
        &["--checkpoint-every", "0.01"],
        &[
            "holds a checkpoint of an earlier run",
            "--resume",
            "--restart",
        ],
    );
    refused(
        &short,
        &["--restart"],
        &[
            "holds the results of",
            "rerun-long",
            "not of",
            "rerun-short",
            "--overwrite",
        ],
    );
    // Asked to: the earlier run's files go, the user's stay.
    run(&short, &["--restart", "--overwrite"]);
    let frames: Vec<String> = std::fs::read_dir(out.join("vtk"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with("points_"))
        .collect();
    assert_eq!(
        frames.len(),
        3,
        "frames at 0, 0.01, 0.02 s only: {frames:?}"
    );
    assert!(!out.join("checkpoint.bin").exists(), "--restart removes it");
    assert!(out.join("notes.txt").is_file() && out.join("vtk/mine.vtu").is_file());
    let listed = std::fs::read_to_string(out.join("outputs.txt")).unwrap();
    assert!(
        listed.lines().any(|l| l == "vtk/points_00002.vtu"),
        "{listed}"
    );
    assert!(!listed.contains("points_00003"), "{listed}");
    // The first run's checkpoint (0.05 s) put back and carried on to
    // 0.07 s: the frames before it are the second run's (0, 0.01, 0.02 s),
    // written after it; a warning says so.
    std::fs::write(out.join("checkpoint.bin"), &checkpoint).unwrap();
    let written = std::fs::metadata(out.join("checkpoint.bin"))
        .and_then(|m| m.modified())
        .unwrap();
    std::fs::File::options()
        .write(true)
        .open(out.join("vtk/points_00000.vtu"))
        .and_then(|f| f.set_modified(written + std::time::Duration::from_secs(60)))
        .unwrap();
    let (_later_base, later) = common::edited_wave_scene("rerun-later", "end: 1.0", "end: 0.07");
    let result = run_into(&later, &out, &["--resume"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    assert!(
        stderr.contains(
            "the frames were written after the checkpoint, by another run into this folder"
        ),
        "{stderr}"
    );
}

#[test]
fn a_run_resumed_from_its_checkpoint_with_a_later_end_gives_the_longer_runs_outputs() {
    // The first run ends at 0.055 s, off the 0.01 s frame interval: its
    // extra last frame is not in the longer run.
    let (base, short) = common::edited_wave_scene("resume-short", "end: 1.0", "end: 0.055");
    let (other, long) = common::edited_wave_scene("resume-long", "end: 1.0", "end: 0.08");
    let (resumed, straight) = (base.join("out"), other.join("out"));
    let run = run_into;
    printed_hash(&run(&short, &resumed, &["--checkpoint-every", "0.02"]));
    assert!(resumed.join("checkpoint.bin").is_file());
    // The folder then holds frames past the checkpoint (0.055 s), as after a
    // run stopped later than its last checkpoint: the resumed run drops
    // them from the collection and writes them again. (The longer scene run
    // over it, the checkpoint put back.) That run's first frame is dated
    // before the checkpoint, as the frames of the run that wrote it are: a
    // resume warns when they were written after it.
    let checkpoint = std::fs::read(resumed.join("checkpoint.bin")).unwrap();
    printed_hash(&run(&long, &resumed, &["--restart", "--overwrite"]));
    std::fs::write(resumed.join("checkpoint.bin"), checkpoint).unwrap();
    let written = std::fs::metadata(resumed.join("checkpoint.bin"))
        .and_then(|m| m.modified())
        .unwrap();
    std::fs::File::options()
        .write(true)
        .open(resumed.join("vtk/points_00000.vtu"))
        .and_then(|f| f.set_modified(written - std::time::Duration::from_secs(60)))
        .unwrap();
    // Not quiet: the progress lines go to the log that standard error is.
    let resumed_run = mpdem(&[
        "run",
        long.to_str().unwrap(),
        "--out",
        resumed.to_str().unwrap(),
        "--resume",
    ]);
    let stderr = String::from_utf8_lossy(&resumed_run.stderr);
    assert!(
        !stderr.contains("written after the checkpoint"),
        "the frames up to the checkpoint are whole: {stderr}"
    );
    // Where it resumed is said first, before the first progress line.
    assert!(
        stderr.starts_with("resuming at step 550 (t = 5.500000e-2 s)")
            && stderr.contains("\nstep 550/800 t = 5.5000e-2 s"),
        "{stderr}"
    );
    // The log says when the stepping is over and the results are written.
    assert!(
        stderr.contains("\nstep 800/800 t = 8.0000e-2 s: writing the results"),
        "{stderr}"
    );
    let resumed_hash = printed_hash(&resumed_run);
    let straight_hash = printed_hash(&run(&long, &straight, &[]));
    assert_eq!(resumed_hash, straight_hash);
    for file in [
        "probes.csv",
        "energy.csv",
        "points.pvd",
        "vtk/points_00003.vtu",
        "vtk/points_00008.vtu",
    ] {
        let read = |dir: &std::path::Path| std::fs::read(dir.join(file)).expect(file);
        assert!(read(&resumed) == read(&straight), "{file} differs");
    }
    // The resumed run, given no interval, kept the checkpoint current: it
    // is at its end (step 800), which the refusal of a checkpoint past a
    // scene's end names. Refusals: that one, no checkpoint in the folder,
    // a checkpoint interval of zero.
    let (_early_base, early) = common::edited_wave_scene("resume-early", "end: 1.0", "end: 0.03");
    let result = run(&early, &resumed, &["--resume"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        !result.status.success()
            && stderr.contains("at step 800 (t = 8.000000e-2 s), where the run has ended (the scene's end is step 300"),
        "{stderr}"
    );
    // The same scene resumed at its own end has nothing to run either: it
    // is refused and leaves every output as it was.
    let outputs = |dir: &std::path::Path| {
        let mut files: Vec<(std::path::PathBuf, Vec<u8>)> = walk(dir)
            .into_iter()
            .filter(|f| !f.ends_with(mpdem::runner::LOCK_FILE))
            .map(|f| (f.clone(), std::fs::read(&f).unwrap()))
            .collect();
        files.sort();
        files
    };
    let before = outputs(&resumed);
    let result = run(&long, &resumed, &["--resume"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        !result.status.success()
            && stderr.contains("nothing to run, and the outputs are left as they are"),
        "{stderr}"
    );
    assert!(
        outputs(&resumed) == before,
        "a refused resumption changed the outputs"
    );
    let empty = base.join("empty");
    let result = run(&long, &empty, &["--resume"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        !result.status.success() && stderr.contains("checkpoint.bin"),
        "{stderr}"
    );
    let result = run(&long, &empty, &["--checkpoint-every", "0"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("the checkpoint interval must be a positive time in seconds, got 0"),
        "{stderr}"
    );
}

#[test]
fn verify_tabulates_a_case_and_fails_when_a_target_is_missed() {
    let listed = mpdem(&["verify", "--list"]);
    let listing = String::from_utf8_lossy(&listed.stdout);
    for case in mpdem_verify::CASES {
        assert!(listing.contains(case.name), "{listing}");
    }

    // The wave case on the shipped scenes: met, and tabulated.
    // Twice the initial velocity the exact solution assumes: the midpoint
    // error is 100%, the case misses its target.
    let base = common::edited_scenes_folder("wave_1d.ron", "verify", &[("x*(1-x)", "2*x*(1-x)")]);
    let out = base.join("out");
    let scenes = common::scene_path("");
    let args = |scenes: &str| {
        [
            "verify",
            "wave_1d",
            "--quiet",
            "--scenes",
            scenes,
            "--out",
            out.to_str().unwrap(),
        ]
        .map(String::from)
    };
    let met = Command::new(env!("CARGO_BIN_EXE_mpdem"))
        .args(args(scenes.to_str().unwrap()))
        .output()
        .expect("mpdem runs");
    let stdout = String::from_utf8_lossy(&met.stdout);
    assert!(met.status.success(), "{stdout}");
    assert!(stdout.contains("2 checks met, 0 missed"), "{stdout}");
    let table = std::fs::read_to_string(out.join("verify.csv")).expect("verify.csv");
    assert_eq!(table.lines().count(), 3, "{table}");
    assert!(
        table
            .lines()
            .all(|l| l.ends_with("\"met\"") || l.starts_with("case,"))
    );

    // The edited wave: the command fails.
    let missed = Command::new(env!("CARGO_BIN_EXE_mpdem"))
        .args(args(base.to_str().unwrap()))
        .output()
        .expect("mpdem runs");
    let stdout = String::from_utf8_lossy(&missed.stdout);
    assert!(!missed.status.success(), "{stdout}");
    assert!(stdout.contains("MISSED"), "{stdout}");
    assert!(
        String::from_utf8_lossy(&missed.stderr).contains("1 check missed its target"),
        "{}",
        String::from_utf8_lossy(&missed.stderr)
    );

    let unknown = mpdem(&["verify", "no_such_case"]);
    assert!(!unknown.status.success());
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("no case 'no_such_case'"));
}

#[cfg(unix)]
#[test]
fn ctrl_c_stops_the_run_after_its_step_and_writes_its_results_and_a_checkpoint() {
    // The wave for 10 s (100 000 steps, about 20 s of running): Ctrl-C
    // arrives once the first checkpoint is written, long before the end.
    let (base, scene) = common::edited_wave_scene("ctrl-c", "end: 1.0", "end: 10.0");
    let out = base.join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_mpdem"))
        .args([
            "run",
            scene.to_str().unwrap(),
            "--quiet",
            "--checkpoint-every",
            "0.01",
        ])
        .args(["--out", out.to_str().unwrap()])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("mpdem runs");
    let started = std::time::Instant::now();
    while !out.join("checkpoint.bin").is_file() {
        assert!(started.elapsed().as_secs() < 60, "no checkpoint after 60 s");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // A second run into the folder meanwhile is refused, and changes nothing.
    let second = run_into(&scene, &out, &["--resume"]);
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert_eq!(second.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("is being written by another run"),
        "{stderr}"
    );
    // Two signals at once (as `timeout` sends them, to the process and to
    // its group) are one request: the run still stops after its step.
    let signal = Command::new("sh")
        .args(["-c", &format!("kill -INT {0}; kill -INT {0}", child.id())])
        .status()
        .expect("kill runs");
    assert!(signal.success());
    let result = child.wait_with_output().expect("mpdem ends");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(130), "{stderr}");
    assert!(
        stderr.contains("stopped at step") && stderr.contains("`--resume` carries it on"),
        "{stderr}"
    );
    // The request is acknowledged once, at once.
    assert_eq!(
        stderr
            .matches("stop requested: the run stops after its step")
            .count(),
        1,
        "{stderr}"
    );
    // The series end where the run stopped, and the checkpoint is there.
    let energy = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    let rows = energy.lines().count() - 1;
    assert!((2..100_001).contains(&rows), "{rows} energy rows");
    for file in ["probes.csv", "snapshot.png", "points.pvd"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
}

#[test]
fn a_folder_holding_files_no_run_wrote_is_refused_unless_overwrite() {
    let (base, scene) = common::edited_wave_scene("foreign", "end: 1.0", "end: 0.01");
    let out = base.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("energy.csv"), "the user's").unwrap();
    let refused = run_into(&scene, &out, &[]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("holds files that no mpdem run wrote") && stderr.contains("--overwrite"),
        "{stderr}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("energy.csv")).unwrap(),
        "the user's"
    );
    let asked = run_into(&scene, &out, &["--overwrite"]);
    assert!(
        asked.status.success(),
        "{}",
        String::from_utf8_lossy(&asked.stderr)
    );
    assert!(out.join("outputs.txt").is_file());
}

#[test]
fn check_and_run_print_a_warning_alike() {
    // An end 1.5 steps past 0.01 s: off the steps, a warning on time.end.
    let (dir, scene) = common::edited_wave_scene("warned", "end: 1.0", "end: 0.01015");
    let check = mpdem(&["check", scene.to_str().unwrap()]);
    assert!(check.status.success());
    let run = run_into(&scene, &dir.join("out"), &[]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let warning_lines = |output: &std::process::Output| {
        String::from_utf8_lossy(&output.stderr)
            .lines()
            .filter(|l| l.starts_with("warning: "))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    let checked = warning_lines(&check);
    assert_eq!(checked.len(), 1, "{checked:?}");
    assert!(
        checked[0].starts_with(&format!("warning: {}: time.end = ", scene.display())),
        "{checked:?}"
    );
    assert_eq!(warning_lines(&run), checked);
}

#[test]
fn a_thread_count_beyond_the_limit_is_refused_at_once() {
    let (base, scene) = common::edited_wave_scene("threads", "end: 1.0", "end: 0.05");
    let out = base.join("out");
    let started = std::time::Instant::now();
    for (threads, expected) in [
        (
            "100000",
            "--threads: the number of threads must be at most 1024, got 100000",
        ),
        ("0", "--threads: the number of threads must be at least 1"),
    ] {
        let result = run_into(&scene, &out, &["--threads", threads]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
        assert!(!out.exists(), "nothing is written");
    }
    // Starting a hundred thousand threads took minutes.
    assert!(started.elapsed().as_secs() < 20);
}

/// Started as a rank of an MPI job of several, the command line built
/// without MPI refuses (rank 0 says why, once for the job) and writes
/// nothing; a job of one is one process.
#[cfg(not(feature = "mpi"))]
#[test]
fn a_rank_of_an_mpi_job_is_refused() {
    let scene = common::scene_path("wave_1d.ron");
    let as_rank = |rank: &str, size: &str| {
        Command::new(env!("CARGO_BIN_EXE_mpdem"))
            .args(["check", scene.to_str().unwrap()])
            .env("OMPI_COMM_WORLD_RANK", rank)
            .env("OMPI_COMM_WORLD_SIZE", size)
            .output()
            .expect("mpdem runs")
    };
    let first = as_rank("0", "4");
    assert_eq!(first.status.code(), Some(1));
    let said = String::from_utf8_lossy(&first.stderr);
    assert!(said.contains("rank 0 of an MPI job of 4"), "{said}");
    assert!(said.contains("built without MPI"), "{said}");
    assert!(said.contains("docs/distributed.md"), "{said}");
    let other = as_rank("3", "4");
    assert_eq!(other.status.code(), Some(1));
    assert!(other.stderr.is_empty());
    let alone = as_rank("0", "1");
    assert_eq!(
        alone.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&alone.stderr)
    );
}
