"""The fields as NumPy arrays: shapes, units, the blocks, the recorded
series, and velocities and forces set from Python."""

from __future__ import annotations

import numpy as np
import pytest

import mpdem
from conftest import shipped

RHO, G, H, NU = 2000.0, 9.81, 1.0, 0.3  # scenes/elastic_column.ron


@pytest.fixture(scope="module")
def settled_column():
    """The elastic column settled under gravity (its scene says by 0.6 s)."""
    sim = mpdem.Simulation(shipped("elastic_column"))
    sim.run_until(0.6)
    return sim


def test_arrays_have_one_row_per_point_and_the_documented_columns(settled_column):
    body = settled_column.body("column")
    n = len(body)
    assert settled_column.bodies == ["column"]
    assert n == 8 * 40 * 4
    for name in ["position", "displacement", "velocity", "external_force", "contact_force"]:
        assert getattr(body, name).shape == (n, 2), name
    assert body.stress.shape == (n, 4)
    assert body.strain.shape == (n, 4)
    assert body.deformation_gradient.shape == (n, 2, 2)
    for name in ["volume", "initial_volume", "mass", "inelastic_work"]:
        assert getattr(body, name).shape == (n,), name
    assert all(a.dtype == np.float64 for a in [body.position, body.stress, body.mass])
    assert body.point_fields == {}


def test_masses_and_volumes_are_in_si_units(settled_column):
    body = settled_column.body("column")
    # 0.2 m x 1.0 m of 2000 kg/m3, per metre of thickness.
    assert body.mass.sum() == pytest.approx(RHO * 0.2 * 1.0, rel=1e-12)
    assert body.initial_volume.sum() == pytest.approx(0.2, rel=1e-12)
    # V = det(F) V0.
    det = np.linalg.det(body.deformation_gradient)
    np.testing.assert_allclose(body.volume, det * body.initial_volume, rtol=1e-12)


def test_stresses_are_the_geostatic_ones_in_pascal(settled_column):
    body = settled_column.body("column")
    y0 = body.position[:, 1] - body.displacement[:, 1]
    inside = (y0 > 0.1) & (y0 < 0.9)
    expected_yy = -RHO * G * (H - y0[inside])
    # Linear shape functions give a uniform strain per cell: a point reads
    # its cell centre's stress, off by up to rho g h / 2 (h = 0.025 m).
    tolerance = RHO * G * 0.025 / 2 + 0.01 * RHO * G * H
    np.testing.assert_allclose(body.stress[inside, 1], expected_yy, atol=tolerance)
    # Uniaxial strain: sigma_xx / sigma_yy = nu / (1 - nu), and sigma_zz alike.
    ratio = body.stress[inside, 0].sum() / body.stress[inside, 1].sum()
    assert ratio == pytest.approx(NU / (1 - NU), rel=0.02)
    assert np.abs(body.stress[:, 3]).max() > 0.0
    # Settled: velocities of micrometres per second.
    assert np.abs(body.velocity).max() < 1e-4


def test_snapshots_are_copies(settled_column):
    body = settled_column.body("column")
    body.position[:] = 0.0
    assert np.abs(settled_column.body("column").position).max() > 0.0


def free_square() -> mpdem.Scene:
    """A free elastic square without gravity or walls, built as a dict."""
    return mpdem.Scene.from_dict(
        {
            "name": "free_square",
            "grid": {"origin": [0.0, 0.0], "cell_size": 0.1, "cells": [20, 20]},
            "time": {"dt": 1e-4, "end": 0.01},
            "gravity": [0.0, 0.0],
            # Linear shape functions keep a uniformly accelerated body
            # exactly stress-free (uGIMP leaves a stress of 1e-3 Pa).
            "settings": {"shape_function": "Linear"},
            "materials": [
                {
                    "name": "rubber",
                    "density": 1000.0,
                    "model": {"LinearElastic": {"youngs_modulus": 1e6, "poisson_ratio": 0.3}},
                }
            ],
            "bodies": [
                {
                    "name": "square",
                    "material": "rubber",
                    "shape": {"Rectangle": {"min": [0.8, 0.8], "max": [1.2, 1.2]}},
                }
            ],
        }
    )


def test_an_external_force_accelerates_a_free_body_as_newton_says():
    sim = mpdem.Simulation(free_square(), threads=1)
    body = sim.body("square")
    a = np.array([2.0, -1.0])  # m/s2
    sim.set_external_force("square", body.mass[:, None] * a)
    sim.step(50)
    after = sim.body("square")
    np.testing.assert_allclose(after.velocity, np.tile(a * sim.time, (len(after), 1)), rtol=1e-9)
    np.testing.assert_allclose(after.external_force, body.mass[:, None] * a)
    np.testing.assert_allclose(after.stress, 0.0, atol=1e-6)


def test_a_velocity_set_from_python_moves_the_body():
    sim = mpdem.Simulation(free_square(), threads=1)
    n = len(sim.body("square"))
    sim.set_velocity("square", [[0.5, 0.0]] * n)
    np.testing.assert_array_equal(sim.body("square").velocity, [[0.5, 0.0]] * n)
    sim.step(100)
    moved = sim.body("square").displacement
    np.testing.assert_allclose(moved[:, 0], 0.5 * sim.time, rtol=1e-9)
    with pytest.raises(ValueError, match=r"shape \(N, 2\)"):
        sim.set_velocity("square", np.zeros((n, 3)))
    with pytest.raises(ValueError, match=r"shape \(%d, 2\)" % n):
        sim.set_velocity("square", np.zeros((n + 1, 2)))
    with pytest.raises(ValueError, match="finite"):
        sim.set_velocity("square", np.full((n, 2), np.nan))
    with pytest.raises(KeyError):
        sim.set_velocity("circle", np.zeros((n, 2)))


def test_a_blocks_state_and_reaction():
    # The slope's top face is y = 0.25 and gravity is turned by 45 degrees:
    # the block presses on it with m g cos 45 along -y and, sliding, drags
    # it along +x with mu = 0.5 times that.
    sim = mpdem.Simulation(shipped("sliding_45"))
    assert sim.blocks == ["slope"]
    sim.run_until(0.1)
    forces = []
    sim.run_until(0.6, callback=lambda s: forces.append(s.block("slope").force))
    slope = sim.block("slope")
    assert slope.velocity == (0.0, 0.0) and slope.angular_velocity == 0.0
    assert slope.origin == (5.5, -0.25) and slope.angle == 0.0
    weight = sim.body("block").mass.sum() * G * np.cos(np.pi / 4)
    # The points' contacts chatter from step to step (up to 4 times the
    # mean); over 5000 steps the mean holds to a few percent.
    fx, fy = np.mean(forces, axis=0)
    assert len(forces) == 5000
    assert -fy == pytest.approx(weight, rel=0.03)
    assert fx == pytest.approx(0.5 * weight, rel=0.03)
    with pytest.raises(KeyError):
        sim.block("ramp")


def test_the_series_have_named_columns():
    sim = mpdem.Simulation(shipped("elastic_column", end=0.05))
    sim.run()
    assert sim.series_names == ["probes", "energy"]
    energy = sim.series("energy")
    assert energy.dtype.names[:3] == ("time", "kinetic", "strain")
    assert len(energy) == 51  # t = 0 and every millisecond
    np.testing.assert_allclose(energy.time, np.arange(51) * 1e-3, atol=1e-12)
    assert (energy.kinetic >= 0).all() and energy.kinetic.max() > 0
    probes = sim.series("probes")
    assert set(probes.probe) == {"base", "top"}
    assert probes.time.dtype == np.float64
    with pytest.raises(KeyError):
        sim.series("nothing")


def test_a_series_as_a_pandas_dataframe():
    pandas = pytest.importorskip("pandas")
    sim = mpdem.Simulation(shipped("elastic_column", end=0.01))
    sim.run()
    frame = sim.dataframe("energy")
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == list(sim.series("energy").dtype.names)


def test_names_stay_strings_in_the_series():
    scene = shipped("elastic_column", end=0.005)
    scene.set("probes[0].name", "1")
    scene.set("probes[1].name", "nan")
    sim = mpdem.Simulation(scene)
    sim.run()
    probes = sim.series("probes")
    assert set(probes.probe) == {"1", "nan"}
    pandas = pytest.importorskip("pandas")
    assert set(sim.dataframe("probes").probe) == {"1", "nan"}


def test_points_rows_must_be_real_pairs():
    sim = mpdem.Simulation(free_square(), threads=1)
    n = len(sim.body("square"))
    for bad in [np.zeros(n), [1.0, 0.0], np.zeros((n, 2, 1))]:
        with pytest.raises(ValueError, match=r"shape \(N, 2\)"):
            sim.set_velocity("square", bad)
    with pytest.raises(TypeError, match="real numbers"):
        sim.set_velocity("square", np.zeros((n, 2), dtype=complex))
    sim.set_velocity("square", np.zeros((n, 2), dtype=np.float32))


def test_plastic_strain_grows_where_a_granular_column_yields():
    sim = mpdem.Simulation(shipped("granular_collapse_bui", end=0.05))
    before = sim.body("column").plastic_strain
    assert before.shape == (len(sim.body("column")),) and (before == 0).all()
    sim.run()
    after = sim.body("column")
    assert after.plastic_strain.min() >= 0.0
    # The toe region shears past yield; plastic work goes with it.
    yielded = after.plastic_strain > 0
    assert yielded.any()
    assert (after.inelastic_work[yielded] > 0).mean() > 0.9
    # An elastic body has none.
    column = mpdem.Simulation(shipped("elastic_column", end=0.01))
    column.run()
    assert (column.body("column").plastic_strain == 0).all()
