"""Stepping from Python: time, steps, the state hash, callbacks, Ctrl-C,
the GIL and numerical failures."""

from __future__ import annotations

import os
import signal
import subprocess
import threading
import time

import pytest

import mpdem
from conftest import shipped


def test_steps_advance_the_clock_by_whole_time_steps():
    sim = mpdem.Simulation(shipped("wave_1d"), threads=1)
    assert (sim.step_count, sim.time) == (0, 0.0)
    sim.step()
    sim.step(9)
    assert sim.step_count == 10
    assert sim.time == pytest.approx(10 * sim.dt, rel=1e-12)
    assert sim.run_until(0.002) is True
    assert sim.step_count == 20
    assert not sim.finished


def test_run_goes_to_the_scene_end():
    sim = mpdem.Simulation(shipped("wave_1d", end=0.003))
    sim.run()
    assert sim.finished and sim.step_count == 30
    sim.step(5)  # nothing left to run
    assert sim.step_count == 30


def test_the_state_hash_does_not_depend_on_threads_or_on_how_the_steps_are_taken():
    one = mpdem.Simulation(shipped("wave_1d"), threads=1)
    one.run_until(0.002)
    two = mpdem.Simulation(shipped("wave_1d"), threads=2)
    for _ in range(20):
        two.step()
    assert len(one.state_hash()) == 16
    int(one.state_hash(), 16)
    assert one.state_hash() == two.state_hash()


@pytest.mark.parametrize("name,end", [("wave_1d", 0.02), ("sliding_45", 0.02), ("two_rings", 2e-5)])
def test_the_state_hash_is_the_one_the_cli_prints(name, end, cli, tmp_path):
    scene = shipped(name, end=end)
    path = tmp_path / f"{name}.ron"
    path.write_text(scene.to_ron())
    printed = subprocess.run(
        [str(cli), "run", str(path), "--out", str(tmp_path / "cli"), "--quiet"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    cli_hash = printed.split("state hash ")[1].split(";")[0]
    sim = mpdem.Simulation(mpdem.Scene.from_file(path))
    sim.run()
    assert sim.state_hash() == cli_hash
    summary = mpdem.run(mpdem.Scene.from_file(path), out=tmp_path / "py", threads=1)
    assert summary.state_hash == cli_hash


def test_a_callback_runs_every_interval_and_stops_the_run():
    sim = mpdem.Simulation(shipped("wave_1d"))
    seen = []

    def watch(s):
        seen.append(round(s.time, 9))
        return s.time >= 0.003 - 1e-12

    assert sim.run_until(0.01, every=0.001, callback=watch) is False
    assert seen == [0.001, 0.002, 0.003]
    assert sim.step_count == 30
    # Without `every`, after each step.
    count = []
    sim.run_until(0.0035, callback=lambda s: count.append(s.step_count))
    assert count == [31, 32, 33, 34, 35]


def test_a_callback_error_propagates():
    sim = mpdem.Simulation(shipped("wave_1d"))

    def fail(_):
        raise RuntimeError("from the callback")

    with pytest.raises(RuntimeError, match="from the callback"):
        sim.run_until(0.01, callback=fail)
    assert sim.step_count == 1


def test_ctrl_c_stops_between_steps_with_keyboard_interrupt(ctrl_c_raises):
    sim = mpdem.Simulation(shipped("wave_1d"))
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run()
    timer.join()
    stopped = sim.step_count
    assert 0 < stopped < 10_000
    # The state is a whole step's: the run carries on.
    sim.step(3)
    assert sim.step_count == stopped + 3


def test_steps_release_the_gil():
    sim = mpdem.Simulation(shipped("two_rings"), threads=1)
    sim.step()  # first step's set-up
    counted = [0]
    done = threading.Event()

    def count():
        while not done.is_set():
            counted[0] += 1

    thread = threading.Thread(target=count)
    thread.start()
    before = counted[0]
    started = time.perf_counter()
    while time.perf_counter() - started < 0.2:
        sim.step(20)
    elapsed = time.perf_counter() - started
    during = counted[0] - before
    done.set()
    thread.join()
    # A thread that holds the GIL for a step starves the counter for the
    # whole step; released, the counter runs alongside (millions a second).
    assert during > 20_000 * elapsed


def test_a_numerical_failure_raises_with_the_engine_message():
    scene = shipped("elastic_column")
    scene.set("time.dt", 2e-2)  # forty times the stability limit
    with pytest.warns(mpdem.SceneWarning):
        sim = mpdem.Simulation(scene)
    with pytest.raises(mpdem.NumericalFailure) as caught:
        sim.run()
    err = caught.value
    assert str(err).startswith("numerical failure at step")
    assert err.step >= 1 and err.time >= 0.0
    assert err.message in str(err)


def test_threads_must_be_one_to_the_most():
    with pytest.raises(ValueError, match="at least 1"):
        mpdem.Simulation(shipped("wave_1d"), threads=0)
    with pytest.raises(ValueError, match="at most 1024, got 100000"):
        mpdem.Simulation(shipped("wave_1d"), threads=100_000)
    with pytest.raises(ValueError, match="at most 1024"):
        mpdem.run(shipped("wave_1d"), threads=5000)


def test_a_failed_simulation_refuses_further_steps():
    scene = shipped("elastic_column")
    scene.set("time.dt", 2e-2)
    with pytest.warns(mpdem.SceneWarning):
        sim = mpdem.Simulation(scene)
    with pytest.raises(mpdem.NumericalFailure):
        sim.run()
    failed_at = sim.step_count
    with pytest.raises(mpdem.NumericalFailure, match="failed before"):
        sim.step()
    assert sim.step_count == failed_at


def test_two_threads_stepping_at_once_get_a_runtime_error_not_a_panic():
    sim = mpdem.Simulation(shipped("two_rings"), threads=1)
    caught = []

    def step(n):
        try:
            sim.step(n)
        except BaseException as e:  # a PanicException is a BaseException
            caught.append(e)

    long_run = threading.Thread(target=step, args=(3000,))
    long_run.start()
    time.sleep(0.1)
    for _ in range(20):
        step(1)
    long_run.join()
    # Whichever thread finds the simulation held gets a RuntimeError.
    assert caught, "the two threads never met"
    assert all(type(e) is RuntimeError and "borrowed" in str(e) for e in caught), caught
