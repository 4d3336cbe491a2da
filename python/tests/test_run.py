"""`mpdem.run`: the files the CLI writes, its errors and Ctrl-C."""

from __future__ import annotations

import os
import signal
import subprocess
import threading

import pytest

import mpdem
from conftest import shipped

# Files whose bytes depend on the wall clock or the process, not the run.
UNSTABLE = {".mpdem.lock"}


def files_of(folder):
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and p.name not in UNSTABLE
    }


def test_a_run_writes_the_files_the_cli_writes(cli, tmp_path):
    scene = shipped("sliding_45", end=0.05)
    path = tmp_path / "sliding.ron"
    path.write_text(scene.to_ron())
    subprocess.run(
        [str(cli), "run", str(path), "--out", str(tmp_path / "cli"), "--quiet", "--threads", "2"],
        check=True,
        capture_output=True,
    )
    summary = mpdem.run(mpdem.Scene.from_file(path), out=tmp_path / "py", threads=1)
    assert summary.steps == 500 and summary.time == pytest.approx(0.05)
    assert summary.out == tmp_path / "py"
    cli_files, py_files = files_of(tmp_path / "cli"), files_of(tmp_path / "py")
    assert sorted(py_files) == sorted(cli_files)
    assert {"energy.csv", "blocks.csv", "probes.csv", "points.pvd", "snapshot.png"} <= set(py_files)
    different = [name for name in cli_files if cli_files[name] != py_files[name]]
    assert different == []


def test_a_run_refuses_a_folder_holding_a_checkpoint(tmp_path):
    scene = shipped("wave_1d", end=0.002)
    mpdem.run(scene, out=tmp_path / "o", checkpoint_every=0.001)
    assert (tmp_path / "o" / "checkpoint.bin").exists()
    with pytest.raises(mpdem.RunError, match="holds a checkpoint"):
        mpdem.run(scene, out=tmp_path / "o")
    scene.set("time.end", 0.004)
    resumed = mpdem.run(scene, out=tmp_path / "o", resume=True)
    fresh = mpdem.run(scene, out=tmp_path / "fresh")
    assert resumed.state_hash == fresh.state_hash


def test_a_failed_run_raises_numerical_failure_and_keeps_the_results(tmp_path):
    scene = shipped("elastic_column")
    scene.set("time.dt", 2e-2)
    with pytest.warns(mpdem.SceneWarning):
        with pytest.raises(mpdem.NumericalFailure, match="results up to the failure"):
            mpdem.run(scene, out=tmp_path / "o")
    assert (tmp_path / "o" / "energy.csv").exists()


def test_ctrl_c_stops_a_run_with_its_results_and_checkpoint(tmp_path, ctrl_c_raises):
    scene = shipped("elastic_column", end=100.0)  # a million steps: not done in 0.3 s
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        mpdem.run(scene, out=tmp_path / "o", checkpoint_every=10.0)
    timer.join()
    energy = (tmp_path / "o" / "energy.csv").read_text().splitlines()
    assert energy[0].startswith("time,kinetic")
    assert 1 < len(energy) < 100_000
    assert float(energy[-1].split(",")[0]) > 0.0
    # The stop writes a checkpoint, which a resumed run carries on from.
    assert (tmp_path / "o" / "checkpoint.bin").exists()


def test_an_empty_folder_name_is_the_current_folder_with_its_checks(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "precious.txt").write_text("keep")
    with pytest.raises(mpdem.RunError, match="holds files that no mpdem run wrote"):
        mpdem.run(shipped("wave_1d", end=0.001), out="")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["precious.txt"]


def test_resume_and_restart_are_one_or_the_other(tmp_path):
    with pytest.raises(ValueError, match="give one"):
        mpdem.run(shipped("wave_1d", end=0.001), out=tmp_path / "o", resume=True, restart=True)


def test_a_scene_without_a_file_does_not_replace_another_scenes_results(tmp_path):
    first = mpdem.Scene.from_dict(shipped("wave_1d", end=0.001).to_dict())
    mpdem.run(first, out=tmp_path / "o")
    # The same scene (by name) carries on into its own folder.
    mpdem.run(first, out=tmp_path / "o")
    second = mpdem.Scene.from_dict(first.to_dict())
    second.set("name", "other_wave")
    with pytest.raises(mpdem.RunError, match="holds the results of the scene 'wave_1d'"):
        mpdem.run(second, out=tmp_path / "o")
    with pytest.raises(mpdem.RunError, match=r"not of .*wave_1d\.ron"):
        mpdem.run(shipped("wave_1d", end=0.001), out=tmp_path / "o")
    mpdem.run(second, out=tmp_path / "o", overwrite=True)
    listed = (tmp_path / "o" / "outputs.txt").read_text().splitlines()
    assert listed[1] == "# scene without a file: other_wave"
