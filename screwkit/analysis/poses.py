"""Poses and units of the maps, loci and paths: pose coordinates in user units, grids of a 2-D slice.

Poses here are in the API's units (docs/architecture.md §3): lengths in the catalog file's length unit, angles
in **radians**, as everywhere in the Python API; ``angles="deg"`` gives ranges, fixed coordinates and
paths in degrees (as in the TOML files and on the command line, which passes it). A pose is a dict
``{name: value}`` over :attr:`~screwkit.robots.mechanism.Mechanism.pose_names` (missing coordinates
take the default pose) or an array in that order. Private to :mod:`screwkit.analysis`: the checks
and the slice its maps (:mod:`screwkit.analysis.workspace`), loci (:mod:`screwkit.analysis.loci`)
and paths (:mod:`screwkit.analysis.paths`) share.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from ..robots.pose_reader import pose_array

__all__ = ["CHUNK", "DEFAULT_AXIS_COUNT", "MAX_MAP_POSES"]

Array = np.ndarray

#: Poses analysed at once by default (bounded memory): the maps' chunks and the loci's batches.
CHUNK = 4096

#: The most poses one map, sweep or surface slice may hold: its grid of poses is built whole (32 bytes
#: a pose, 3.2 GB at the bound), though the analysis runs in chunks (the command line caps at 2e6).
MAX_MAP_POSES = 10**8
#: Values along a map's default axis (:func:`screwkit.analysis.workspace.grid_map` without ``x``/``y``).
DEFAULT_AXIS_COUNT = 50


def _options(mechanism: Any, mode: Any) -> dict[str, Any]:
    """Inverse-kinematics options from ``mode``: None, a mapping of options, or a working mode of the
    mechanism's family (:meth:`screwkit.robots.families.Family.mode_options`)."""
    return dict(mechanism.family_protocol.mode_options(mode))


def _check_mechanism(mechanism: Any) -> None:
    """Maps and paths run over a mechanism's pose coordinates; a twist graph gets them from
    :func:`screwkit.mechanism`."""
    if not all(hasattr(mechanism, name) for name in ("at", "pose_names", "angle_names", "default_pose")):
        hint = (
            " (a twist graph is one configuration: screwkit.mechanism(graph) gives its motion)"
            if hasattr(mechanism, "edges")
            else ""
        )
        raise ScrewkitTypeError(
            f"Expected `mechanism` to be a Mechanism (screwkit.load_mechanism or screwkit.mechanism), got "
            f"{type(mechanism).__name__}{hint}."
        )


def _check_client(client: Any) -> None:
    """``client`` is None or a dask.distributed Client (anything with ``submit`` and ``gather``)."""
    if client is not None and not (hasattr(client, "submit") and hasattr(client, "gather")):
        raise ScrewkitTypeError(
            f"Expected `client` to be a dask.distributed Client, got {type(client).__name__}."
        )


def _scale(mechanism: Any, angles: str) -> Array:
    """Per pose coordinate: API value = user value × scale (radians for angles;
    :func:`screwkit.robots.angles.angle_factor`, the API's one angle convention)."""
    from ..robots.angles import pose_scale

    return pose_scale(mechanism.pose_names, mechanism.angle_names, angles)


def _units(mechanism: Any, angles: str) -> dict[str, str]:
    return {
        n: (angles if n in mechanism.angle_names else mechanism.length_unit) for n in mechanism.pose_names
    }


def _default(mechanism: Any, angles: str) -> Array:
    return np.asarray(mechanism.default_pose, dtype=float) / _scale(mechanism, angles)


def _finite(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ScrewkitTypeError(f"Expected `{what}` to be a number, got {type(value).__name__} {value!r}.")
    if not math.isfinite(value):
        raise ScrewkitValueError(f"Expected `{what}` to be finite, got {value!r}.")
    return float(value)


def _pose(mechanism: Any, pose: Any, what: str, angles: str) -> Array:
    """A pose in user units from a dict (missing coordinates: the default pose) or an array."""
    names = mechanism.pose_names
    if isinstance(pose, Mapping):
        unknown = sorted(set(pose) - set(names), key=str)
        if unknown:
            raise ScrewkitValueError(f"Expected the keys of `{what}` among {list(names)}, got {unknown}.")
        out = _default(mechanism, angles)
        for i, name in enumerate(names):
            if name in pose:
                out[i] = _finite(pose[name], f"{what}[{name!r}]")
        _check_angles(mechanism, dict(zip(names, out, strict=True)), what, angles)
        return out
    array = pose_array(mechanism, pose, what, one=True)  # real numbers, finite, one per coordinate
    _check_angles(mechanism, dict(zip(names, array, strict=True)), what, angles)
    return array


def _check_angles(mechanism: Any, values: Mapping[str, Any], what: str, angles: str) -> None:
    """Refuse angles beyond the bound of files and the CLI (``toml_fields.MAX_ANGLE_DEGREES``, or its
    radian form), naming the argument and the coordinate."""
    from ..robots.toml_fields import MAX_ANGLE_DEGREES, MAX_ANGLE_RADIANS

    bound, unit = (MAX_ANGLE_DEGREES, "degrees") if angles == "deg" else (MAX_ANGLE_RADIANS, "rad")
    for name in mechanism.angle_names:
        if name in values and np.max(np.abs(values[name])) > bound:
            raise ScrewkitValueError(
                f"Expected the angle `{name}` of `{what}` to be at most {bound:g} {unit} in magnitude, "
                f"got {float(np.max(np.abs(values[name]))):g}."
            )


def _as_dict(mechanism: Any, pose: Array) -> dict[str, float]:
    return {n: float(v) for n, v in zip(mechanism.pose_names, pose, strict=True)}


def _axis(mechanism: Any, axis: Any, what: str, angles: str) -> tuple[str, Array]:
    if axis is None:  # the family's default map axis, over the workspace, 50 values
        name = mechanism.family_protocol.default_map_axes[0 if what == "x" else 1]
        low, high = np.array(mechanism.workspace[name]) / _scale(mechanism, angles)[
            mechanism.pose_names.index(name)
        ]
        axis = (name, float(low), float(high), DEFAULT_AXIS_COUNT)
    if not isinstance(axis, Sequence) or isinstance(axis, str) or len(axis) != 4:
        raise ScrewkitValueError(f"Expected `{what}` to be (name, low, high, count), got {axis!r}.")
    name, low, high, count = axis
    if name not in mechanism.pose_names:
        raise ScrewkitValueError(
            f"Expected `{what}`'s name among the pose coordinates {list(mechanism.pose_names)}, got {name!r}."
        )
    low, high = _finite(low, f"{what} low"), _finite(high, f"{what} high")
    if isinstance(count, bool) or not isinstance(count, int | np.integer) or not 2 <= count <= MAX_MAP_POSES:
        raise ScrewkitValueError(
            f"Expected `{what}` count to be an integer in 2..{MAX_MAP_POSES:g}, got {count!r}."
        )
    if not low < high:
        raise ScrewkitValueError(f"Expected `{what}` low < high, got {low:g} and {high:g}.")
    _check_angles(mechanism, {name: [low, high]}, what, angles)
    return str(name), np.linspace(low, high, int(count))


@dataclass(frozen=True, eq=False)
class _Slice:
    """A 2-D slice of the pose space (user units): axes, fixed values, and its poses ``(ny, nx, n)``."""

    mechanism: Any
    x_name: str
    x_values: Array
    y_name: str
    y_values: Array
    fixed: dict[str, float]
    angles: str
    options: dict[str, Any]

    @classmethod
    def create(cls, mechanism: Any, x: Any, y: Any, fixed: Any, mode: Any, angles: str) -> _Slice:
        _check_mechanism(mechanism)
        _scale(mechanism, angles)  # checks `angles`
        x_name, x_values = _axis(mechanism, x, "x", angles)
        y_name, y_values = _axis(mechanism, y, "y", angles)
        if len(x_values) * len(y_values) > MAX_MAP_POSES:
            raise ScrewkitValueError(
                f"Expected at most {MAX_MAP_POSES:g} poses in a map (x count times y count), got "
                f"{len(x_values)} x {len(y_values)}; split the map."
            )
        if x_name == y_name:
            raise ScrewkitValueError(
                f"Expected `x` and `y` over different coordinates, got {x_name!r} twice."
            )
        given = {} if fixed is None else fixed
        if not isinstance(given, Mapping):
            raise ScrewkitTypeError(f"Expected `fixed` to be a dict, got {type(given).__name__}.")
        clash = sorted({x_name, y_name} & set(given))
        if clash:
            raise ScrewkitValueError(f"Expected `fixed` not to set the map's axes, got {clash}.")
        base = _pose(mechanism, given, "fixed", angles)
        names = mechanism.pose_names
        rest = {n: float(v) for n, v in zip(names, base, strict=True) if n not in (x_name, y_name)}
        return cls(mechanism, x_name, x_values, y_name, y_values, rest, angles, _options(mechanism, mode))

    def poses(self, x_values: Array | None = None, y_values: Array | None = None) -> Array:
        """User-unit poses on the grid ``(ny, nx, n)``."""
        xs = self.x_values if x_values is None else x_values
        ys = self.y_values if y_values is None else y_values
        names = self.mechanism.pose_names
        out = np.empty((len(ys), len(xs), len(names)))
        for i, name in enumerate(names):
            if name == self.x_name:
                out[..., i] = xs[None, :]
            elif name == self.y_name:
                out[..., i] = ys[:, None]
            else:
                out[..., i] = self.fixed[name]
        return out

    @property
    def scale(self) -> Array:
        return _scale(self.mechanism, self.angles)

    @property
    def region(self) -> str:
        units = _units(self.mechanism, self.angles)
        mode = f"; inverse kinematics {self.options}" if self.options else ""

        def axis(name: str, values: Array) -> str:
            return f"{name} in [{values[0]:g}, {values[-1]:g}] {units[name]} ({len(values)} values)"

        fixed = ", ".join(f"{n} = {v:g} {units[n]}" for n, v in self.fixed.items())
        return (
            f"{self.mechanism.name}: {axis(self.x_name, self.x_values)} x {axis(self.y_name, self.y_values)}"
            f"{', ' + fixed if fixed else ''}{mode}"
        )


def reached_batch(mechanism: Any, poses: Array, ok: Array, rtol: Any, options: dict[str, Any]) -> Any:
    """The mechanism at the poses ``ok`` marks reachable, one posed batch, ``ok`` narrowed in place to
    the poses that batch reaches: a graph mechanism's continuation may reach a pose in a larger batch
    only (through a seed of that batch, docs/mechanisms.md, "What reachable means"), and a map must
    then mark it out of reach, not read the sub-batch's marker as a verdict. None if no pose is left."""
    while ok.any():
        posed = mechanism.at(poses[ok], rtol=rtol, **options)
        again = np.asarray(posed.reachable, dtype=bool).reshape(-1)
        if again.all():
            return posed
        ok[np.flatnonzero(ok)[~again]] = False
    return None

