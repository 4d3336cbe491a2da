"""Material point method with DEM-enriched contact, from Python.

Build a scene (``Scene.from_file``, ``Scene.from_ron``, ``Scene.from_dict``),
step its ``Simulation`` and read every field as NumPy arrays between steps,
or ``run`` it to write exactly the files the ``mpdem run`` command writes.

>>> import mpdem
>>> scene = mpdem.Scene.from_file("scenes/wave_1d.ron")
>>> sim = mpdem.Simulation(scene)
>>> sim.run_until(0.01)
True
>>> sim.body(sim.bodies[0]).stress.shape[1]
4
"""

from __future__ import annotations

import csv
import io
from typing import TYPE_CHECKING, Any

import numpy as np

from ._mpdem import (
    Block,
    Body,
    NumericalFailure,
    RunError,
    RunSummary,
    Scene,
    SceneError,
    SceneWarning,
    __version__,
    run,
)
from ._mpdem import Simulation as _NativeSimulation

if TYPE_CHECKING:
    import numpy.typing as npt
    import pandas

__all__ = [
    "Block",
    "Body",
    "NumericalFailure",
    "RunError",
    "RunSummary",
    "Scene",
    "SceneError",
    "SceneWarning",
    "Simulation",
    "__version__",
    "parse_series",
    "run",
]


class Simulation(_NativeSimulation):
    """A running simulation of a scene: ``Simulation(scene, threads=None)``.

    Steps run with the GIL released on ``threads`` worker threads (default:
    all cores); the results do not depend on the number. Ctrl-C stops a
    stepping call after the step in progress with ``KeyboardInterrupt``; a
    step still running half a second later is cut short, and the
    simulation then takes no further step.
    """

    def set_velocity(self, name: str, velocity: "npt.ArrayLike") -> None:
        """Sets the velocity (m/s) of every point of body ``name``: an N x 2
        array of real numbers, one row per point in the body's order."""
        super().set_velocity(name, _point_rows(velocity))

    def set_external_force(self, name: str, force: "npt.ArrayLike") -> None:
        """Sets the external force (N per metre) on every point of body
        ``name``: an N x 2 array of real numbers, kept until set again
        (gravity is separate)."""
        super().set_external_force(name, _point_rows(force))

    def series(self, name: str) -> np.ndarray:
        """The recorded series ``name`` (see ``series_names``) as a NumPy
        record array with the columns of its CSV file: numbers as float64,
        names (of bodies, probes, blocks) as strings.

        >>> energy = sim.series("energy")          # doctest: +SKIP
        >>> energy["time"], energy["kinetic"]      # doctest: +SKIP
        """
        return parse_series(self.series_csv(name))

    def dataframe(self, name: str) -> "pandas.DataFrame":
        """The recorded series ``name`` as a pandas DataFrame (needs pandas)."""
        import pandas

        table = self.series(name)
        return pandas.DataFrame({column: table[column] for column in table.dtype.names})


def _point_rows(values: "npt.ArrayLike") -> np.ndarray:
    """`values` as a C-ordered float64 array of two columns, or a clear error."""
    array = np.asarray(values)
    if np.iscomplexobj(array) or not (
        np.issubdtype(array.dtype, np.number) or array.dtype == np.bool_
    ):
        raise TypeError(f"expected real numbers, got an array of {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(
            f"expected an array of shape (N, 2), one row per point, got shape {array.shape}"
        )
    return np.ascontiguousarray(array, dtype=np.float64)


# The columns of the series that hold names (of probes, bodies, blocks,
# stages) and reasons: strings, whatever they look like.
_TEXT_COLUMNS = {"probe", "body", "body_a", "body_b", "block", "name", "reason"}


def parse_series(text: str) -> np.ndarray:
    """A series' CSV text (header, then one line per sample) as a NumPy
    record array: names (of probes, bodies, blocks, stages) and reasons as
    strings, every other column as float64."""
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        raise ValueError("a series has at least its header line")
    header, body = rows[0], rows[1:]
    columns: list[Any] = []
    dtypes = []
    for k, name in enumerate(header):
        values = [row[k] for row in body]
        try:
            if name in _TEXT_COLUMNS:
                raise ValueError(name)
            column: Any = np.array([float(v) for v in values], dtype=np.float64)
            dtype: Any = np.float64
        except ValueError:
            width = max((len(v) for v in values), default=1)
            column = np.array(values, dtype=f"U{max(width, 1)}")
            dtype = column.dtype
        columns.append(column)
        dtypes.append((name, dtype))
    table = np.empty(len(body), dtype=dtypes)
    for (name, _), column in zip(dtypes, columns):
        table[name] = column
    return table.view(np.recarray)
