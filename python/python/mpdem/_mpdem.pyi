"""Type stubs of mpdem's native module (re-exported by ``mpdem``)."""

from __future__ import annotations

import os
import pathlib
from typing import Any, Callable, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, os.PathLike[str]]

class SceneError(ValueError):
    """A scene that cannot be read or is not valid."""

    message: str
    """What is wrong and what was expected."""
    file: Optional[str]
    """The scene file, when the scene came from one."""
    line: Optional[int]
    """The line (1-based), when known."""
    column: Optional[int]
    """The column (1-based, in characters), when known."""
    key_path: Optional[str]
    """For a scene built from a dict: the keys leading to the value, e.g.
    ``materials[0].model.DruckerPrager.friction_angle``."""

class NumericalFailure(RuntimeError):
    """The numerics broke down during a step."""

    message: str
    """The engine's message: where, which field, what is wrong."""
    step: int
    """The step being computed (1-based). Set by ``Simulation``'s stepping
    only: a failure in ``mpdem.run`` names its step in ``message``."""
    time: float
    """The time at the start of that step (s); as ``step``."""

class RunError(RuntimeError):
    """A run that could not start or finish writing its output folder."""

    message: str

class SceneWarning(UserWarning):
    """A warning the engine raises about a scene or a run."""

class Scene:
    """A scene that has passed the engine's validation."""

    @staticmethod
    def from_file(path: _Path) -> Scene:
        """Reads, parses and validates a RON scene file."""
    @staticmethod
    def from_ron(text: str, folder: Optional[_Path] = None) -> Scene:
        """Parses and validates RON scene text; point lists' files are read
        relative to ``folder`` (default: the current folder)."""
    @staticmethod
    def from_dict(d: dict[str, Any], folder: Optional[_Path] = None) -> Scene:
        """Builds and validates a scene from a dict laid out as ``to_dict``
        gives it; errors carry the key path."""
    def to_dict(self) -> dict[str, Any]:
        """The scene as a dict: structs are dicts, tuples lists, an enum
        variant with fields a one-key dict, one without its name."""
    def to_ron(self) -> str:
        """The scene as RON text that ``from_ron`` and the CLI read back."""
    def get(self, key_path: str) -> Any:
        """The value at ``key_path``, e.g. ``"materials[0].density"`` or
        ``"materials[sand].model.DruckerPrager.friction_angle"``; a path
        that leads nowhere raises ``KeyError``, one that does not parse
        ``ValueError``."""
    def set(self, key_path: str, value: Any) -> None:
        """Sets the value at ``key_path`` and validates again. A value the
        scene refuses raises ``SceneError`` naming its key path, a path that
        leads nowhere ``KeyError``; either way the scene is unchanged."""
    @property
    def name(self) -> str:
        """The scene's name."""
    @property
    def file(self) -> Optional[pathlib.Path]:
        """The scene's file, if it came from one."""
    @property
    def warnings(self) -> list[str]:
        """Warnings about spellings of earlier releases."""
    def __eq__(self, other: object) -> bool:
        """Whether ``other`` is a scene with every field equal."""
    def __reduce__(self) -> tuple[Any, tuple[dict[str, Any], pathlib.Path]]:
        """Pickling and ``copy`` go through ``to_dict`` and ``from_dict``."""

class Body:
    """A snapshot of one body's points between steps (copies, SI units)."""

    name: str
    position: npt.NDArray[np.float64]
    """Position (m), N x 2."""
    displacement: npt.NDArray[np.float64]
    """Displacement from the initial position (m), N x 2."""
    velocity: npt.NDArray[np.float64]
    """Velocity (m/s), N x 2."""
    stress: npt.NDArray[np.float64]
    """Cauchy stress (Pa, tension positive), N x 4: xx, yy, xy, zz."""
    strain: npt.NDArray[np.float64]
    """Accumulated strain, N x 4: xx, yy, xy, zz."""
    deformation_gradient: npt.NDArray[np.float64]
    """In-plane deformation gradient, N x 2 x 2."""
    volume: npt.NDArray[np.float64]
    """Current volume (m^3 per metre), N."""
    initial_volume: npt.NDArray[np.float64]
    """Initial volume (m^3 per metre), N."""
    mass: npt.NDArray[np.float64]
    """Mass (kg per metre), N."""
    inelastic_work: npt.NDArray[np.float64]
    """Plastic and viscous work dissipated since the start (J per metre), N."""
    plastic_strain: npt.NDArray[np.float64]
    """Equivalent plastic strain since the start, N."""
    external_force: npt.NDArray[np.float64]
    """External force set on the points (N per metre), N x 2."""
    contact_force: npt.NDArray[np.float64]
    """Contact forces on the points in the last step (N per metre), N x 2."""
    point_fields: dict[str, npt.NDArray[np.float64]]
    """The plugins' scalar point fields, by name."""
    def __len__(self) -> int: ...

class Block:
    """The state of a rigid block."""

    name: str
    origin: tuple[float, float]
    """Position of the block's frame origin (m)."""
    angle: float
    """Rotation of the frame (rad, counter-clockwise)."""
    velocity: tuple[float, float]
    """Velocity of the centre of mass (m/s)."""
    angular_velocity: float
    """Angular velocity (rad/s, counter-clockwise)."""
    force: tuple[float, float]
    """Force of the points on the block in the last step (N per metre)."""
    torque: float
    """Their torque about the centre of mass (N m per metre)."""

class RunSummary:
    """What a finished run reached."""

    name: str
    steps: int
    time: float
    state_hash: str
    """The final state's hash, as the CLI prints it."""
    elapsed: float
    """Wall time (s)."""
    out: pathlib.Path
    """The output folder."""

class Simulation:
    """A running simulation of a scene."""

    def __init__(self, scene: Scene, threads: Optional[int] = None) -> None:
        """Builds the simulation; the scene's warnings are issued as
        ``SceneWarning``. ``threads`` defaults to all cores; results do not
        depend on it."""
    def step(self, n: int = 1) -> None:
        """Takes ``n`` steps (fewer at the run's end)."""
    def run(self) -> None:
        """Steps to the end of the run."""
    def run_until(
        self,
        t: float,
        every: Optional[float] = None,
        callback: Optional[Callable[[Simulation], Any]] = None,
    ) -> bool:
        """Steps to the step nearest time ``t``, or the run's end, calling
        ``callback(sim)`` every ``every`` seconds (or every step); a true
        return value stops the run. Returns whether ``t`` or the end was
        reached."""
    @property
    def time(self) -> float:
        """Simulated time (s)."""
    @property
    def step_count(self) -> int:
        """Steps taken."""
    @property
    def dt(self) -> float:
        """Time step (s)."""
    @property
    def end_time(self) -> float:
        """The run's end (s)."""
    @property
    def finished(self) -> bool:
        """Whether the run has reached its end."""
    @property
    def name(self) -> str:
        """The scene's name."""
    def state_hash(self) -> str:
        """The state's hash, 16 hexadecimal digits, as the CLI prints it."""
    @property
    def bodies(self) -> list[str]:
        """The bodies' names in scene order."""
    @property
    def blocks(self) -> list[str]:
        """The blocks' names in scene order."""
    def body(self, name: str) -> Body:
        """A snapshot of the body's points."""
    def block(self, name: str) -> Block:
        """The block's state."""
    def set_velocity(self, name: str, velocity: npt.ArrayLike) -> None:
        """Sets every point's velocity (m/s), an N x 2 array."""
    def set_external_force(self, name: str, force: npt.ArrayLike) -> None:
        """Sets every point's external force (N per metre), an N x 2 array."""
    @property
    def series_names(self) -> list[str]:
        """The recorded series' names (``energy``, ``probes``, ...)."""
    def series_csv(self, name: str) -> str:
        """The series as the CSV text its file would hold now."""
    @property
    def warnings(self) -> list[str]:
        """The scene's warnings and those the steps raised."""

def run(
    scene: Scene,
    out: Optional[_Path] = None,
    threads: Optional[int] = None,
    checkpoint_every: Optional[float] = None,
    resume: bool = False,
    restart: bool = False,
    overwrite: bool = False,
) -> RunSummary:
    """Runs the scene to its end, writing into ``out`` (default
    ``out/<scene name>``) exactly the files ``mpdem run`` writes."""
