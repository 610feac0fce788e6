"""Workspace maps, singularity loci and trajectory checks, batched through the one analysis core.

Every pose goes through :meth:`screwkit.robots.catalog.Mechanism.at` (the batched core: inverse
kinematics → joint table → wrench systems → verdicts, closeness, Jacobians), in chunks of the
batch axis, so a map of 10⁶ poses runs in bounded memory. Chunks can run on a Dask distributed
cluster (optional extra ``dask``): pass ``client=``; the results are identical to the in-process run.

Units
-----
Poses here are in the API's units (design.md §3): lengths in the catalog file's length unit, angles
in **radians**, as everywhere in the Python API; pass ``angles="deg"`` to give ranges, fixed
coordinates and paths in degrees (as in the TOML files and on the command line, which passes it). A
pose is a dict ``{name: value}`` over :attr:`~screwkit.robots.catalog.Mechanism.pose_names` (missing
coordinates take the default pose) or an array in that order.

Quantities (:data:`QUANTITIES`)
-------------------------------
``"verdict"``
    The core's code per pose: bit 1 constraint, 2 actuation, 4 serial (0 regular,
    :attr:`screwkit.core.singularity.SingularityReport.codes`); ``-1`` where the pose is out of reach.
``"closeness"``, ``"closeness:constraint"``, ``"closeness:actuation"``, ``"closeness:serial"``
    The core's closeness measures (:mod:`screwkit.core.singularity`), ``"closeness"`` their minimum.
``"det_A"``, ``"det_B"``
    Determinants of the forward and inverse Jacobians ``A χ̇ = B θ̇``
    (:class:`screwkit.core.jacobians.WrenchJacobians`; paper 004 Eq. 6).
``"lti"``, ``"kappa"``, ``"zeta"``
    The local transmission index ``η = min(κ, ζ)`` of paper 004 Eq. (16), its motion index ``κ``
    and force index ``ζ`` (Eq. 15) (:func:`screwkit.analysis.indices.transmission`; four-limb families).
``"condition:K"``
    The vector form of the K-th factor of the superbracket (:mod:`screwkit.gca.conditions`), factored
    once at the default pose and evaluated on the wrench diagram's points over the whole batch
    (:func:`screwkit.gca.diagram_points.batch_diagram_points`, from the batched core); a
    :class:`~screwkit.exceptions.DegenerateGeometryError` names the pose where a point of the
    diagram does not exist (e.g. a limb at a serial singularity has no actuation line).

Float maps hold NaN where a pose is out of reach, always together with ``reachable`` False.

Loci and crossings
------------------
A singular surface is rarely hit by a grid or path sample: a grid's labels miss it. Along each
line of samples (grid rows and columns, or a path) screwkit looks for

* sign changes of ``det A`` (refined by bisection),
* local minima of each closeness measure (refined by golden-section search), and
* the edge of the reachable set (refined by bisection on the inverse kinematics),

then keeps a refined pose when the core labels it singular or one of its closeness measures is
below :data:`ACCEPT` (the kind is the core's label there, else the closest measure). The factor is
the superbracket condition with the smallest value there relative to its value at the default pose.

Examples
--------
>>> from screwkit.robots.catalog import load_mechanism
>>> h4 = load_mechanism("h4")
>>> m = grid_map(h4, "verdict", x=("z", -1000, -550, 4), y=("phi", -45, 45, 3), angles="deg")
>>> m.values.shape, int(m.maximum), bool(m.reachable.all())
((3, 4), 0, True)
>>> check_path(h4, {"z": -800, "phi": 0}, {"z": -700, "phi": 30}, samples=20, angles="deg").singularity_free
True
"""

from __future__ import annotations

import json
import math
import sys
import weakref
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..exceptions import (
    DegenerateGeometryError,
    ScrewkitError,
    ScrewkitTypeError,
    ScrewkitValueError,
)

__all__ = [
    "ACCEPT",
    "QUANTITIES",
    "Crossing",
    "Locus",
    "PathCheck",
    "Surface",
    "WorkspaceMap",
    "check_path",
    "evaluate",
    "grid_map",
    "loci",
    "surfaces",
    "sweep",
]

Array = np.ndarray

#: The quantities a map can show (``"condition:K"`` for any K too).
QUANTITIES = (
    "verdict",
    "closeness",
    "closeness:constraint",
    "closeness:actuation",
    "closeness:serial",
    "det_A",
    "det_B",
    "lti",
    "kappa",
    "zeta",
)
#: A refined pose with a closeness measure below this is a singularity even if the core's rank
#: decision (relative tolerance ``rtol``) did not label it.
ACCEPT = 1e-6
#: Poses analysed at once by default (bounded memory).
CHUNK = 4096
#: The kinds of singularity, by bit of the core's codes.
KINDS = ("constraint", "actuation", "serial")


def verdict_name(code: int) -> str:
    """The words of a ``"verdict"`` map's code (module docstring).

    Examples
    --------
    >>> [verdict_name(c) for c in (-1, 0, 2, 5)]
    ['out of reach', 'regular', 'actuation', 'constraint+serial']
    """
    if code < 0:
        return "out of reach"
    return "+".join(kind for bit, kind in enumerate(KINDS) if code >> bit & 1) or "regular"
#: Refinement stops when a bracket (in the line's parameter, 0..1) is this narrow ...
XTOL = 4e-16
#: ... or after this many steps (each one batch through the core).
MAX_STEPS = 80
#: Poses of one surface tried for its factor (where the diagram's points exist).
_FACTOR_TRIES = 5
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
#: The most poses one map, sweep or surface slice may hold: its grid of poses is built whole (32 bytes
#: a pose, 3.2 GB at the bound), though the analysis runs in chunks (the command line caps at 2e6).
MAX_MAP_POSES = 10**8
#: The most samples a path check takes: they go through the core as one batch (≈ 1 GB at 10⁶).
MAX_PATH_SAMPLES = 10**6


# --------------------------------------------------------------------------------------------------
# Poses and units
# --------------------------------------------------------------------------------------------------


def _options(mode: Any) -> dict[str, Any]:
    """Inverse-kinematics options from ``mode``: None, a mapping of options, or a working mode."""
    if mode is None:
        return {}
    if isinstance(mode, Mapping):
        return dict(mode)
    if isinstance(mode, str | bytes):
        raise ScrewkitTypeError(
            f"Expected `mode` to be None, a mapping of inverse-kinematics options or a working mode "
            f"(a sequence of signs), got {mode!r}."
        )
    return {"working_mode": tuple(mode)}


def _check_mechanism(mechanism: Any) -> None:
    """Maps and paths run over a catalog mechanism's pose coordinates; a twist graph has none."""
    if not all(hasattr(mechanism, name) for name in ("at", "pose_names", "angle_names", "default_pose")):
        hint = (
            " (a twist graph is one configuration: analyse it with screwkit.analyze or classify)"
            if hasattr(mechanism, "edges")
            else ""
        )
        raise ScrewkitTypeError(
            f"Expected `mechanism` to be a catalog Mechanism (screwkit.load_mechanism), got "
            f"{type(mechanism).__name__}{hint}."
        )


def _angle_factor(angles: str) -> float:
    if angles not in ("deg", "rad"):
        raise ScrewkitValueError(f"Expected `angles` to be 'deg' or 'rad', got {angles!r}.")
    return math.pi / 180.0 if angles == "deg" else 1.0


def _scale(mechanism: Any, angles: str) -> Array:
    """Per pose coordinate: API value = user value × scale (radians for angles)."""
    factor = _angle_factor(angles)
    return np.array([factor if n in mechanism.angle_names else 1.0 for n in mechanism.pose_names])


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
    try:
        array = np.asarray(pose, dtype=float)
    except (TypeError, ValueError) as err:
        raise ScrewkitTypeError(
            f"Expected `{what}` to be a dict over {list(names)} or {len(names)} numbers, got {pose!r}."
        ) from err
    if array.shape != (len(names),):
        raise ScrewkitValueError(
            f"Expected `{what}` to have shape ({len(names)},) ({', '.join(names)}), got {array.shape}."
        )
    if not np.isfinite(array).all():
        raise ScrewkitValueError(f"Expected `{what}` to be finite, got {array.tolist()}.")
    _check_angles(mechanism, dict(zip(names, array, strict=True)), what, angles)
    return array


def _check_angles(mechanism: Any, values: Mapping[str, Any], what: str, angles: str) -> None:
    """Refuse angles beyond the bound of files and the CLI (``catalog.MAX_ANGLE_DEGREES``, or its
    radian form), naming the argument and the coordinate."""
    from ..robots.catalog import MAX_ANGLE_DEGREES, MAX_ANGLE_RADIANS

    bound, unit = (MAX_ANGLE_DEGREES, "degrees") if angles == "deg" else (MAX_ANGLE_RADIANS, "rad")
    for name in mechanism.angle_names:
        if name in values and np.max(np.abs(values[name])) > bound:
            raise ScrewkitValueError(
                f"Expected the angle `{name}` of `{what}` to be at most {bound:g} {unit} in magnitude, "
                f"got {float(np.max(np.abs(values[name]))):g}."
            )


def _as_dict(mechanism: Any, pose: Array) -> dict[str, float]:
    return {n: float(v) for n, v in zip(mechanism.pose_names, pose, strict=True)}


def _quantity(quantity: Any) -> str:
    if not isinstance(quantity, str):
        raise ScrewkitTypeError(f"Expected `quantity` to be a str, got {type(quantity).__name__}.")
    aliases = {"detA": "det_A", "detB": "det_B", "condition": "condition:0"}
    name = aliases.get(quantity, quantity)
    if name in QUANTITIES:
        return name
    index = name[len("condition:") :]
    if name.startswith("condition:") and index.isascii() and index.isdigit():  # not '²' or '١'
        return name
    raise ScrewkitValueError(
        f"Expected `quantity` to be one of {[*QUANTITIES, 'condition:K']}, got {quantity!r}."
    )


# --------------------------------------------------------------------------------------------------
# Evaluating a batch through the core
# --------------------------------------------------------------------------------------------------


#: The transmission indices a map can show, by their field of
#: :class:`screwkit.analysis.indices.TransmissionIndices` (paper 004 Eqs. 15-16).
_INDICES = {"lti": "eta", "kappa": "kappa", "zeta": "zeta"}


def _transmission_index(posed: Any, quantity: str) -> Array:
    """Paper 004's ``η`` (Eq. 16), ``κ`` or ``ζ`` (Eq. 15) over a posed batch: the one place the
    maps take them from (:func:`screwkit.analysis.indices.transmission`, the batched entry point, fused
    and compiled with the ``fast`` extra)."""
    from .indices import FourLimbGeometry, transmission

    if not isinstance(posed.configuration, FourLimbGeometry):
        raise ScrewkitValueError(
            f"Expected a four-limb mechanism for quantity {quantity!r} (paper 004), got family "
            f"{posed.mechanism.family!r}."
        )
    return np.asarray(getattr(transmission(posed), _INDICES[quantity]), dtype=float)


def _condition_values(mechanism: Any, index: int, posed: Any) -> Array:
    """The ``index``-th superbracket condition at every pose of ``posed``, as one batch: the
    diagram's points over the batch (:func:`screwkit.gca.diagram_points.batch_diagram_points`, from the
    batched core) and the condition's vector form on them
    (:meth:`screwkit.gca.conditions.Condition.evaluate`).

    Raises
    ------
    DegenerateGeometryError
        Where a point of the diagram does not exist at a pose (naming the point and the pose).
    """
    diagram, conditions, _, _ = _conditions(mechanism, posed.options)
    if not 0 <= index < len(conditions):
        raise ScrewkitValueError(
            f"Expected `quantity` 'condition:K' with K in 0..{len(conditions) - 1} (the superbracket's "
            f"factors at the default pose), got K = {index}."
        )
    points, exists = _diagram_points(diagram, posed)
    if not exists.all():
        i = int(np.argmin(exists))
        point = next(p for p in diagram.points if not np.isfinite(points[p.label][i]).all())
        raise DegenerateGeometryError(
            f"Expected every point of the wrench diagram to exist for {posed.mechanism.name!r}'s "
            f"conditions, got point {point.label} ({point.description}) missing at the pose "
            f"{np.asarray(posed.poses[i]).tolist()} (API units)."
        )
    return np.asarray(conditions[index].evaluate(points), dtype=float).reshape(len(posed))


def _diagram_points(diagram: Any, posed: Any) -> tuple[dict[str, Array], Array]:
    """The diagram's points ``{label: (n, 4)}`` at every pose of a posed batch ``(n,)`` and where
    all of them exist ``(n,)``: the batched core with the per-pose frames the recipes read, in
    the core's own chunks (:data:`screwkit.robots.posed.CHUNK` poses), so that only the points are kept."""
    from ..core.wrench_systems import analyze_table
    from ..gca.diagram_points import batch_diagram_points
    from ..robots.posed import CHUNK as CORE_CHUNK

    table, rtol, length = posed.joints, posed.rtol, posed.length_scale
    parts = [
        batch_diagram_points(
            diagram.points, analyze_table(table[start : start + CORE_CHUNK], rtol=rtol, length_scale=length)
        )
        for start in range(0, len(posed), CORE_CHUNK)
    ]
    points = {p.label: np.concatenate([part[p.label] for part in parts]) for p in diagram.points}
    exists = np.all([np.isfinite(v).all(axis=-1) for v in points.values()], axis=0)
    return points, np.asarray(exists, dtype=bool).reshape(len(posed))


#: Per mechanism (held weakly: a cache entry dies with its mechanism) and options: the factored
#: superbracket's diagram, conditions, labels and values at the default pose.
_CONDITIONS: weakref.WeakKeyDictionary[Any, dict[tuple[Any, ...], Any]] = weakref.WeakKeyDictionary()


def _conditions(
    mechanism: Any, options: Mapping[str, Any]
) -> tuple[Any, tuple[Any, ...], tuple[str, ...], Array]:
    """The wrench diagram, superbracket conditions, their labels and their values at the default
    pose (factored once per mechanism and mode)."""
    from ..gca.superbracket_analysis import superbracket_analysis

    key = tuple(sorted((k, repr(v)) for k, v in options.items()))
    cache = _CONDITIONS.setdefault(mechanism, {})
    if key not in cache:
        pose = mechanism.at(None, **options)[0]
        diagram, sampler = pose.diagram_and_sampler()
        if diagram.degenerate:
            raise ScrewkitValueError(
                f"Expected a wrench diagram to factor for the conditions, got a degenerate one: "
                f"{'; '.join(diagram.degenerate)}."
            )
        result = superbracket_analysis(diagram, sampler)
        cache[key] = (diagram, result.conditions, result.labels, np.array(result.values, dtype=float))
    return cache[key]


def _values(posed: Any, quantity: str) -> Array:
    """One quantity over a posed batch of reachable poses."""
    if quantity == "verdict":
        return np.asarray(posed.codes, dtype=np.int64)
    if quantity == "closeness":
        return np.min(np.stack([np.asarray(posed.closeness[k], dtype=float) for k in KINDS]), axis=0)
    if quantity.startswith("closeness:"):
        return np.asarray(posed.closeness[quantity.split(":")[1]], dtype=float)
    if quantity in ("det_A", "det_B"):
        return np.asarray(getattr(posed.jacobians, quantity), dtype=float)
    if quantity in _INDICES:
        return _transmission_index(posed, quantity)
    return _condition_values(posed.mechanism, int(quantity.split(":")[1]), posed)


def evaluate(
    mechanism: Any, poses: Any, quantity: str, *, mode: Any = None, rtol: float | None = None
) -> tuple[Array, Array]:
    """One quantity at poses ``(m, n)`` in **API units** (radians), and which poses are reachable.

    The core (:meth:`~screwkit.robots.catalog.Mechanism.at`) runs once over the reachable poses.

    Returns
    -------
    values : numpy.ndarray, shape (m,)
        int64 codes (``-1`` out of reach) for ``"verdict"``, else float (NaN out of reach).
    reachable : numpy.ndarray of bool, shape (m,)

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> evaluate(load_mechanism("h4"), [[0, 0, -750, 0], [0, 0, -5000, 0]], "verdict")
    (array([ 0, -1]), array([ True, False]))
    """
    _check_mechanism(mechanism)
    name = _quantity(quantity)
    array = np.asarray(poses, dtype=float).reshape(-1, len(mechanism.pose_names))
    options = _options(mode)
    ok = mechanism.reachable(array, **options)
    integer = name == "verdict"
    out = np.full(len(array), -1 if integer else np.nan, dtype=np.int64 if integer else float)
    if ok.any():
        out[ok] = _values(mechanism.at(array[ok], rtol=rtol, **options), name)
    return out, ok


def _run_chunks(
    function: Callable[..., tuple[Array, Array]],
    jobs: Sequence[tuple[Any, Array, tuple[Any, ...]]],
    chunk: int | None,
    client: Any,
    progress: Any,
) -> list[tuple[Array, Array]]:
    """``function(mechanism, poses[chunk], *args)`` over chunks of each job's batch, in process or
    on a Dask client (every chunk of every job submitted at once), with an optional progress line;
    per job, the parts joined in order."""
    size = CHUNK if chunk is None else chunk
    if isinstance(size, bool) or not isinstance(size, int | np.integer) or size < 1:
        raise ScrewkitValueError(f"Expected `chunk` to be a positive integer, got {chunk!r}.")
    if client is not None and not (hasattr(client, "submit") and hasattr(client, "gather")):
        raise ScrewkitTypeError(
            f"Expected `client` to be a dask.distributed Client, got {type(client).__name__}."
        )
    tasks = [
        (job, mechanism, poses[i : i + size], args)
        for job, (mechanism, poses, args) in enumerate(jobs)
        for i in range(0, len(poses), size)
    ]
    bar = _Progress(sum(len(poses) for _, poses, _ in jobs), progress)
    if client is not None:
        futures = [client.submit(function, m, piece, *args, pure=False) for _, m, piece, args in tasks]
        results = []
        for (_, _, piece, _), future in zip(tasks, futures, strict=True):
            results.append(future.result())
            bar.update(len(piece))
    else:
        results = []
        for _, m, piece, args in tasks:
            results.append(function(m, piece, *args))
            bar.update(len(piece))
    bar.close()
    out = []
    for job in range(len(jobs)):
        parts = [r for (owner, _, _, _), r in zip(tasks, results, strict=True) if owner == job]
        out.append((np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])))
    return out


def _chunk_values(mechanism: Any, poses: Array, quantity: str, mode: Any, rtol: Any) -> tuple[Array, Array]:
    """One chunk of a map (a module-level function, so a Dask worker can run it)."""
    return evaluate(mechanism, poses, quantity, mode=mode, rtol=rtol)


class _Progress:
    """tqdm when installed, else one line on stderr rewritten in place; silent unless asked
    (``progress=True``) or, for ``None``, when stderr is a terminal and the map is large."""

    def __init__(self, total: int, progress: Any) -> None:
        show = progress if progress is not None else (sys.stderr.isatty() and total >= 20 * CHUNK)
        self.total, self.done, self.bar, self.show = total, 0, None, bool(show)
        if self.show:
            try:
                from tqdm import tqdm

                self.bar = tqdm(total=total, unit="pose", file=sys.stderr)
            except ImportError:
                self.bar = None

    def update(self, count: int) -> None:
        self.done += count
        if self.bar is not None:
            self.bar.update(count)
        elif self.show:
            print(f"\r{self.done}/{self.total} poses", end="", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.show:
            print(file=sys.stderr)


# --------------------------------------------------------------------------------------------------
# Maps
# --------------------------------------------------------------------------------------------------


def _axis(mechanism: Any, axis: Any, what: str, angles: str) -> tuple[str, Array]:
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
        _angle_factor(angles)
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
        return cls(mechanism, x_name, x_values, y_name, y_values, rest, angles, _options(mode))

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


@dataclass(frozen=True, eq=False)
class WorkspaceMap:
    """A quantity over a 2-D slice of the pose space.

    Attributes
    ----------
    quantity : str
    x_name : str
    x_values : numpy.ndarray, shape (nx,)
    y_name : str
    y_values : numpy.ndarray, shape (ny,)
    values : numpy.ndarray, shape (ny, nx)
        Float, or int codes for ``"verdict"`` (module docstring); NaN / -1 where out of reach.
    reachable : numpy.ndarray of bool, shape (ny, nx)
    fixed : dict
        The other pose coordinates.
    region : str
        The slice in words, with units.
    minimum, maximum : float or int
        Over the reachable poses (NaN if none).
    argmin, argmax : dict
        The full poses where they occur (empty if none).
    units : dict
        Per pose coordinate.
    mechanism : str
    meaning : str
        What a ``"condition:K"`` map shows: the factor of the superbracket, its label and its
        vector form (empty for the other quantities).
    """

    quantity: str
    x_name: str
    x_values: Array
    y_name: str
    y_values: Array
    values: Array
    reachable: Array
    fixed: dict[str, float]
    region: str
    minimum: Any
    maximum: Any
    argmin: dict[str, float]
    argmax: dict[str, float]
    units: dict[str, str] = field(default_factory=dict)
    mechanism: str = ""
    meaning: str = ""

    def __post_init__(self) -> None:
        for name in ("x_values", "y_values", "values", "reachable"):
            getattr(self, name).flags.writeable = False

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the region, extrema and where they occur, axes, values (None out of reach)."""
        values = self.values.astype(object)
        values[~self.reachable] = None
        return {
            "mechanism": self.mechanism,
            "quantity": self.quantity,
            "region": self.region,
            "units": self.units,
            "fixed": self.fixed,
            "minimum": _plain(self.minimum),
            "maximum": _plain(self.maximum),
            "argmin": self.argmin,
            "argmax": self.argmax,
            "reachable_fraction": float(self.reachable.mean()),
            "x": {"name": self.x_name, "values": self.x_values.tolist()},
            "y": {"name": self.y_name, "values": self.y_values.tolist()},
            "values": [[_plain(v) for v in row] for row in values],
            **({"meaning": self.meaning} if self.meaning else {}),
            **({"codes": {str(c): verdict_name(c) for c in range(-1, 2 ** len(KINDS))}}
               if self.quantity == "verdict" else {}),
        }

    def to_json(self, **kwargs: Any) -> str:
        """:meth:`to_dict` as a JSON string."""
        return json.dumps(self.to_dict(), **kwargs)

    def save(self, path: str | Path) -> Path:
        """Write ``.npz`` (arrays and the JSON summary), ``.json`` or ``.png`` (needs matplotlib
        and :mod:`screwkit.interface.plot`).

        Raises
        ------
        ScrewkitValueError
            For another suffix, or ``.png`` without matplotlib.
        """
        target = Path(path)
        suffix = target.suffix.lower()
        if suffix == ".json":
            target.write_text(self.to_json(indent=1))
        elif suffix == ".npz":
            summary = {k: v for k, v in self.to_dict().items() if k not in ("values", "x", "y")}
            np.savez_compressed(
                target,
                x_values=self.x_values,
                y_values=self.y_values,
                values=self.values,
                reachable=self.reachable,
                summary=np.array(json.dumps(summary)),
            )
        elif suffix == ".png":
            _save_png(self, target)
        else:
            raise ScrewkitValueError(f"Expected `path` to end in .npz, .json or .png, got {str(path)!r}.")
        return target


def _save_png(wmap: WorkspaceMap, target: Path) -> None:
    """Draw with :mod:`screwkit.interface.plot` (verdict colours, or isocontours) and write a PNG."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from ..interface import plot
    except (ImportError, ScrewkitError) as err:
        raise ScrewkitValueError(
            f"Expected matplotlib and screwkit.interface.plot to write {str(target)!r} (pip install "
            f"'screwkit[plot]'); got: {err}. Save .npz or .json instead."
        ) from err
    in_radians = tuple(n for n, unit in wmap.units.items() if unit == "rad")  # drawn in degrees
    if wmap.quantity == "verdict":  # the plot takes codes 0..7; out of reach is the mask's to say
        drawn = replace(wmap, values=np.where(wmap.reachable, wmap.values, 0))
        ax = plot.plot_verdicts(drawn, degrees=in_radians)
    else:
        ax = plot.plot_map(wmap, degrees=in_radians)
    ax.figure.savefig(target, dpi=120, bbox_inches="tight")
    plt.close(ax.figure)


def _plain(value: Any) -> Any:
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def grid_map(
    mechanism: Any,
    quantity: str,
    *,
    x: Any = ("z", -1000.0, -550.0, 50),
    y: Any = ("phi", -math.pi / 4, math.pi / 4, 50),
    fixed: Any = None,
    mode: Any = None,
    chunk: int | None = None,
    client: Any = None,
    progress: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
) -> WorkspaceMap:
    """A quantity over a 2-D grid of the pose space, through the core in chunks.

    Parameters
    ----------
    mechanism : Mechanism
    quantity : str
        See :data:`QUANTITIES` (``"detA"``/``"detB"`` and ``"condition"`` = ``"condition:0"`` too).
    x, y : tuple (name, low, high, count)
        The axes (user units: angles in radians unless ``angles="deg"``).
    fixed : dict, optional
        The other coordinates (default: the default pose), e.g. ``{"x": 0.0, "y": 0.0}``.
    mode : mapping or sequence, optional
        Inverse-kinematics options (e.g. ``{"working_mode": (1, 1, 1, 1)}``) or a working mode.
    chunk : int, optional
        Poses per chunk (default :data:`CHUNK`): bounds the memory.
    client : dask.distributed.Client, optional
        Run the chunks on this cluster (results identical to the in-process run).
    progress : bool, optional
        Show a progress bar (tqdm if installed); default: on a terminal, for large maps.
    angles : {"deg", "rad"}
    rtol : float, optional
        The core's relative tolerance.

    Returns
    -------
    WorkspaceMap

    Raises
    ------
    ScrewkitValueError
        For an unknown quantity or coordinate, or a malformed axis.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> m = grid_map(load_mechanism("h4"), "lti", x=("x", -100, 100, 3), y=("y", -100, 100, 3),
    ...              fixed={"z": -750, "phi": 0}, angles="deg")
    >>> print(m.region)
    H4: x in [-100, 100] mm (3 values) x y in [-100, 100] mm (3 values), z = -750 mm, phi = 0 deg
    >>> bool(0 < m.minimum <= m.maximum <= 1)
    True
    """
    name, grid, job = _map_job(mechanism, quantity, x, y, fixed, mode, angles, rtol)
    ((values, ok),) = _run_chunks(_chunk_values, [job], chunk, client, progress)
    return _assembled(mechanism, name, grid, values, ok)


def _map_job(
    mechanism: Any, quantity: Any, x: Any, y: Any, fixed: Any, mode: Any, angles: str, rtol: Any
) -> tuple[str, _Slice, tuple[Any, Array, tuple[Any, ...]]]:
    """A map's quantity, slice and chunk job (its API-unit poses, flattened)."""
    name = _quantity(quantity)
    grid = _Slice.create(mechanism, x, y, fixed, mode, angles)
    if name in _INDICES or name.startswith("condition:"):  # refuse before the map, not in its chunks
        _values(mechanism.at(None, **grid.options), name)
    user = grid.poses()
    flat = user.reshape(-1, user.shape[-1]) * grid.scale
    return name, grid, (mechanism, flat, (name, grid.options, rtol))


def _assembled(mechanism: Any, name: str, grid: _Slice, values: Array, ok: Array) -> WorkspaceMap:
    """The map from its flat values: extrema over the reachable poses and where they occur."""
    user = grid.poses()
    shape = user.shape[:2]
    values, ok = values.reshape(shape), ok.reshape(shape)
    minimum = maximum = float("nan")
    argmin: dict[str, float] = {}
    argmax: dict[str, float] = {}
    floating = values.dtype.kind == "f"
    candidates = ok & np.isfinite(values) if floating else ok
    if candidates.any():
        masked_low = np.where(candidates, values, np.inf if floating else np.iinfo(np.int64).max)
        masked_high = np.where(candidates, values, -np.inf if floating else -2)
        low = np.unravel_index(np.argmin(masked_low), shape)
        high = np.unravel_index(np.argmax(masked_high), shape)
        minimum, maximum = values[low].item(), values[high].item()
        argmin, argmax = _as_dict(mechanism, user[low]), _as_dict(mechanism, user[high])
    return WorkspaceMap(
        name,
        grid.x_name,
        grid.x_values,
        grid.y_name,
        grid.y_values,
        values,
        ok,
        grid.fixed,
        grid.region,
        minimum,
        maximum,
        argmin,
        argmax,
        _units(mechanism, grid.angles),
        mechanism.name,
        _meaning(mechanism, name, grid.options),
    )


def _meaning(mechanism: Any, name: str, options: Mapping[str, Any]) -> str:
    """What a ``condition:K`` map shows (its factor, label and vector form); empty otherwise."""
    if not name.startswith("condition:"):
        return ""
    _, conditions, labels, _ = _conditions(mechanism, options)
    index = int(name.split(":")[1])
    return f"{labels[index]} factor {conditions[index].factor} (vector form {conditions[index].expression})"


def sweep(
    mechanisms: Sequence[Any],
    quantity: str,
    *,
    x: Any = ("z", -1000.0, -550.0, 50),
    y: Any = ("phi", -math.pi / 4, math.pi / 4, 50),
    fixed: Any = None,
    mode: Any = None,
    chunk: int | None = None,
    client: Any = None,
    progress: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
) -> tuple[WorkspaceMap, ...]:
    """A parameter sweep: the same map for each mechanism (e.g. a family's parameters varied with
    :func:`screwkit.robots.catalog.mechanism_from_mapping`), every chunk of every map submitted at once
    when a Dask ``client`` is given.

    Parameters are those of :func:`grid_map`.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> maps = sweep([load_mechanism("h4"), load_mechanism("quattro")], "lti",
    ...              x=("z", -900, -600, 3), y=("phi", -20, 20, 2), angles="deg")
    >>> [m.mechanism for m in maps]
    ['H4', 'Quattro']
    """
    if isinstance(mechanisms, str) or not isinstance(mechanisms, Sequence) or not mechanisms:
        raise ScrewkitTypeError(
            f"Expected `mechanisms` to be a non-empty sequence of mechanisms, got {mechanisms!r}."
        )
    prepared = [_map_job(m, quantity, x, y, fixed, mode, angles, rtol) for m in mechanisms]
    results = _run_chunks(_chunk_values, [job for _, _, job in prepared], chunk, client, progress)
    return tuple(
        _assembled(mechanism, name, grid, values, ok)
        for mechanism, (name, grid, _), (values, ok) in zip(mechanisms, prepared, results, strict=True)
    )


# --------------------------------------------------------------------------------------------------
# Roots along lines of samples: one search for paths and loci
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Samples:
    """What the core says along lines of samples ``(L, n_t)``."""

    ok: Array
    codes: Array
    closeness: dict[str, Array]
    det_A: Array | None


def _measure(mechanism: Any, poses: Array, options: dict[str, Any], rtol: Any) -> _Samples:
    """Codes, closeness and det A at API-unit poses ``(..., n)`` (NaN / -1 where out of reach)."""
    shape = poses.shape[:-1]
    flat = poses.reshape(-1, poses.shape[-1])
    ok = mechanism.reachable(flat, **options)
    codes = np.full(len(flat), -1, dtype=np.int64)
    closeness = {k: np.full(len(flat), np.nan) for k in KINDS}
    det_a: Array | None = np.full(len(flat), np.nan)
    if ok.any():
        posed = mechanism.at(flat[ok], rtol=rtol, **options)
        if ok.sum() <= CHUNK:  # det A needs the joint table too: build it once (a bounded batch)
            _ = posed.joints
        codes[ok] = posed.codes
        for k in KINDS:
            closeness[k][ok] = posed.closeness[k]
        try:
            det_a[ok] = posed.jacobians.det_A  # type: ignore[index]
        except ScrewkitError:  # no square forward Jacobian for this mechanism: no sign to follow
            det_a = None
    return _Samples(
        ok.reshape(shape),
        codes.reshape(shape),
        {k: v.reshape(shape) for k, v in closeness.items()},
        None if det_a is None else det_a.reshape(shape),
    )


@dataclass(frozen=True)
class _Root:
    """A refined pose on line ``line`` at parameter ``t`` (between the line's samples)."""

    line: int
    t: float
    pose: Array
    kind: str
    closeness: float


def _brackets(t: Array, samples: _Samples) -> list[tuple[int, float, float, str]]:
    """``(line, t_low, t_high, method)`` intervals holding a candidate root, from each line's
    samples: det A sign changes, closeness minima, reach edges and samples labelled singular."""
    out = []
    ok = samples.ok
    both = ok[:, :-1] & ok[:, 1:]
    if samples.det_A is not None:
        with np.errstate(invalid="ignore"):
            change = both & (np.sign(samples.det_A[:, :-1]) != np.sign(samples.det_A[:, 1:]))
        for line, i in zip(*np.nonzero(change), strict=True):
            out.append((int(line), float(t[i]), float(t[i + 1]), "det_A"))
    for kind in KINDS:
        c = np.where(ok, samples.closeness[kind], np.inf)
        left = np.concatenate([np.full((len(c), 1), np.inf), c[:, :-1]], axis=1)
        right = np.concatenate([c[:, 1:], np.full((len(c), 1), np.inf)], axis=1)
        minimum = ok & (c <= left) & (c <= right) & ((c < left) | (c < right))
        for line, i in zip(*np.nonzero(minimum), strict=True):
            low, high = max(i - 1, 0), min(i + 1, len(t) - 1)
            out.append((int(line), float(t[low]), float(t[high]), "min:" + kind))
    edge = ok[:, :-1] != ok[:, 1:]
    for line, i in zip(*np.nonzero(edge), strict=True):
        out.append((int(line), float(t[i]), float(t[i + 1]), "edge"))
    singular = ok & (samples.codes > 0)
    for line, i in zip(*np.nonzero(singular), strict=True):
        out.append((int(line), float(t[i]), float(t[i]), "sample"))
    return out


def _refine(
    mechanism: Any,
    along: Callable[[Array, Array], Array],
    brackets: list[tuple[int, float, float, str]],
    options: dict[str, Any],
    rtol: Any,
    *,
    keep_edges: bool = False,
) -> list[_Root]:
    """Refine every bracket at once and keep the roots the core labels singular or whose closeness
    is below :data:`ACCEPT` (and, with ``keep_edges``, the reach edges that are no singularity, as
    kind ``"unreachable"``).

    ``along(lines, t)`` gives API-unit poses ``(m, n)`` on lines ``lines`` at parameters ``t``.
    Each step is one batch through the core, for all brackets: false position (Illinois) on det A
    for its sign changes, bisection on reachability for reach edges, and for closeness minima a
    golden-section search whose steps are replaced by the apex of the ``|s (t − t₀)|`` fit through
    the bracket when that lands inside (a closeness measure vanishes like the distance to a simple
    root, design of :mod:`screwkit.core.singularity`). Stops when every bracket is narrower than
    :data:`XTOL` or after :data:`MAX_STEPS` steps.
    """
    if not brackets:
        return []
    lines = np.array([b[0] for b in brackets])
    method = np.array([b[3] for b in brackets])
    kind_index = np.array([KINDS.index(m[4:]) if m.startswith("min:") else 0 for m in method])
    is_det, is_edge = method == "det_A", method == "edge"
    is_min = np.char.startswith(method.astype(str), "min:")
    everyone = np.arange(len(brackets))

    def score(t: Array, which: Array = everyone) -> Array:
        """Per bracket ``which``: det A, ±1 reachability, or its kind's closeness (inf out of reach)."""
        s = _measure(mechanism, along(lines[which], t[which]), options, rtol)
        det = np.zeros(len(which)) if s.det_A is None else np.nan_to_num(s.det_A)
        closeness = np.stack([s.closeness[k] for k in KINDS], axis=-1)[
            np.arange(len(which)), kind_index[which]
        ]
        values = np.where(is_edge[which], np.where(s.ok, 1.0, -1.0), np.where(s.ok, closeness, np.inf))
        out = np.full(len(t), np.nan)
        out[which] = np.where(is_det[which], det, values)
        return out

    a = np.array([b[1] for b in brackets])
    b = np.array([b[2] for b in brackets])
    fa, fb = score(a), score(b)
    m = 0.5 * (a + b)
    fm = score(m)
    side = np.zeros(len(a))  # Illinois: which end was kept last
    for step in range(MAX_STEPS):
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            left, right = (fm - fa) / (m - a), (fb - fm) / (b - m)
            steep = np.nan_to_num(np.maximum(-left, right), nan=np.inf)
            illinois = (a * fb - b * fa) / (fb - fa)
            # a minimum that cannot reach ACCEPT unless the slope doubles within the bracket: no root
            smooth = is_min & (fm - 2.0 * steep * (b - a) > ACCEPT)  # inf - inf: not smooth
        done = ((b - a) <= XTOL) | (is_min & (fm == 0.0)) | smooth
        if done.all():
            break
        # the next point of each bracket
        illinois = np.where(is_det & (illinois > a) & (illinois < b), illinois, 0.5 * (a + b))
        with np.errstate(invalid="ignore", divide="ignore"):
            apex = np.where(-left >= right, m + fm / steep, m - fm / steep)
        golden = np.where(m - a > b - m, m - (1 - _GOLDEN) * (m - a), m + (1 - _GOLDEN) * (b - m))
        use_apex = (
            (step % 3 != 2) & np.isfinite(apex) & (apex > a) & (apex < b) & (np.abs(apex - m) > XTOL / 4)
        )
        trial = np.where(is_det, illinois, np.where(is_edge, 0.5 * (a + b), np.where(use_apex, apex, golden)))
        f = score(trial, np.nonzero(~done)[0])
        # sign brackets: keep the end whose sign differs from the trial's
        same_as_a = np.sign(f) == np.sign(fa)
        new_a = np.where(same_as_a, trial, a)
        new_b = np.where(same_as_a, b, trial)
        new_fa = np.where(same_as_a, f, np.where(is_det & (side == -1), 0.5 * fa, fa))
        new_fb = np.where(same_as_a, np.where(is_det & (side == 1), 0.5 * fb, fb), f)
        new_side = np.where(same_as_a, 1.0, -1.0)
        # minimum brackets: a <= m <= b with f(m) <= f(a), f(b)
        better = f < fm
        above = trial > m
        min_a = np.where(better, np.where(above, m, a), np.where(above, a, trial))
        min_b = np.where(better, np.where(above, b, m), np.where(above, trial, b))
        min_fa = np.where(better, np.where(above, fm, fa), np.where(above, fa, f))
        min_fb = np.where(better, np.where(above, fb, fm), np.where(above, f, fb))
        min_m, min_fm = np.where(better, trial, m), np.where(better, f, fm)
        sign = is_det | is_edge
        keep = done  # a converged bracket stays as it is
        a = np.where(keep, a, np.where(sign, new_a, min_a))
        b = np.where(keep, b, np.where(sign, new_b, min_b))
        fa = np.where(keep, fa, np.where(sign, new_fa, min_fa))
        fb = np.where(keep, fb, np.where(sign, new_fb, min_fb))
        m = np.where(keep | sign, m, min_m)
        fm = np.where(keep | sign, fm, min_fm)
        side = np.where(keep, side, new_side)
    # the refined parameter: an edge's reachable end, det A's end of smaller |det A|, the minimum
    t = np.where(
        is_edge,
        np.where(fa > 0, a, b),
        np.where(is_det, np.where(np.abs(fa) <= np.abs(fb), a, b), m),
    )
    t = np.where(method == "sample", a, t)
    final = _measure(mechanism, along(lines, t), options, rtol)
    poses = along(lines, t)
    roots = []
    for k in range(len(brackets)):
        if not final.ok[k]:
            continue
        measures = {kind: float(final.closeness[kind][k]) for kind in KINDS}
        code = int(final.codes[k])
        labelled = [kind for bit, kind in enumerate(KINDS) if code >> bit & 1]
        smallest = min(measures, key=measures.__getitem__)
        if labelled or measures[smallest] < ACCEPT:
            kind = labelled[0] if labelled else smallest
            roots.append(_Root(int(lines[k]), float(t[k]), poses[k], kind, measures[kind]))
        elif keep_edges and method[k] == "edge":
            roots.append(_Root(int(lines[k]), float(t[k]), poses[k], "unreachable", math.nan))
    return roots


def _factor(mechanism: Any, poses: Array, kind: str, options: dict[str, Any], rtol: Any) -> str | None:
    """The superbracket condition vanishing at API-unit poses ``(k, n)`` of one surface: at the
    first of them (up to :data:`_FACTOR_TRIES`, evaluated as one batch) where the diagram's points
    exist, the condition of that kind with the smallest value relative to its value at the default
    pose. None for a serial singularity (a limb's, not the superbracket's) or when the conditions
    cannot be had for this mechanism."""
    if kind not in ("constraint", "actuation"):
        return None
    try:
        diagram, conditions, labels, reference = _conditions(mechanism, options)
    except ScrewkitError:
        return None
    candidates = [i for i, label in enumerate(labels) if label == kind and reference[i] != 0]
    tries = np.asarray(poses[:_FACTOR_TRIES], dtype=float)
    tries = tries[mechanism.reachable(tries, **options)]
    if not candidates or not len(tries):
        return None
    points, exists = _diagram_points(diagram, mechanism.at(tries, rtol=rtol, **options))
    if not exists.any():
        return None
    first = int(np.argmax(exists))
    at = {label: value[first] for label, value in points.items()}
    ratios = [abs(float(conditions[i].evaluate(at)) / reference[i]) for i in candidates]
    return str(conditions[candidates[int(np.argmin(ratios))]].factor)


# --------------------------------------------------------------------------------------------------
# Loci
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Locus:
    """Points of one singular surface in a 2-D slice, each refined onto the surface.

    Attributes
    ----------
    kind : str
        ``"constraint"``, ``"actuation"`` or ``"serial"``.
    factor : str or None
        The superbracket factor that vanishes there (None if unknown).
    x_name, y_name : str
    points : numpy.ndarray, shape (m, 2)
        ``(x, y)`` in user units, sorted by ``x`` then ``y``.
    closeness : numpy.ndarray, shape (m,)
        The kind's closeness at each point (~0).
    """

    kind: str
    factor: str | None
    x_name: str
    y_name: str
    points: Array
    closeness: Array

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {
            "kind": self.kind,
            "factor": self.factor,
            "x_name": self.x_name,
            "y_name": self.y_name,
            "points": self.points.tolist(),
            "closeness": self.closeness.tolist(),
        }


def loci(
    mechanism: Any,
    *,
    x: Any = ("z", -1000.0, -550.0, 50),
    y: Any = ("phi", -math.pi / 4, math.pi / 4, 50),
    fixed: Any = None,
    mode: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
) -> tuple[Locus, ...]:
    """The singular curves of a 2-D slice: along every grid row and column, det A sign changes,
    closeness minima and reach edges, refined onto the surface (module docstring).

    Parameters
    ----------
    mechanism, x, y, fixed, mode, angles, rtol
        As in :func:`grid_map`.

    Returns
    -------
    tuple of Locus
        One per kind found, in the order constraint, actuation, serial.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> found = loci(load_mechanism("h4"), x=("z", -1000, -550, 6), y=("phi", -45, 45, 5), angles="deg")
    >>> [locus.kind for locus in found]  # the catalog's box holds no singular surface at x = y = 0
    []
    """
    grid = _Slice.create(mechanism, x, y, fixed, mode, angles)
    user = grid.poses()
    scale = grid.scale
    rows = user * scale  # (ny, nx, n): lines along x
    columns = np.swapaxes(rows, 0, 1)  # (nx, ny, n): lines along y
    found: list[tuple[Array, str, float]] = []
    for lines, t in ((rows, grid.x_values), (columns, grid.y_values)):
        samples = _measure(mechanism, lines, grid.options, rtol)
        u = (t - t[0]) / (t[-1] - t[0])
        start, stop = lines[:, 0], lines[:, -1]

        def along(which: Array, s: Array, start: Array = start, stop: Array = stop) -> Array:
            return start[which] + s[:, None] * (stop[which] - start[which])

        for root in _refine(mechanism, along, _brackets(u, samples), grid.options, rtol):
            found.append((root.pose / scale, root.kind, root.closeness))
    names = mechanism.pose_names
    ix, iy = names.index(grid.x_name), names.index(grid.y_name)
    out = []
    for kind in KINDS:
        mine = [(p, c) for p, k, c in found if k == kind]
        if not mine:
            continue
        points = np.array([[p[ix], p[iy]] for p, _ in mine])
        closeness = np.array([c for _, c in mine])
        order = np.lexsort((points[:, 1], points[:, 0]))
        points, closeness = points[order], closeness[order]
        keep = np.ones(len(points), dtype=bool)
        keep[1:] = np.any(np.abs(np.diff(points, axis=0)) > 1e-9 * (1 + np.abs(points[1:])), axis=1)
        closest = np.array([p for p, _ in mine])[np.argsort([c for _, c in mine])]
        factor = _factor(mechanism, closest * scale, kind, grid.options, rtol)
        out.append(Locus(kind, factor, grid.x_name, grid.y_name, points[keep], closeness[keep]))
    return tuple(out)


@dataclass(frozen=True, eq=False)
class Surface:
    """Points of one singular surface in a 3-D region, each refined onto the surface.

    Attributes
    ----------
    kind : str
    factor : str or None
    names : tuple of 3 str
        The coordinates of the points' columns.
    points : numpy.ndarray, shape (m, 3)
        User units.
    closeness : numpy.ndarray, shape (m,)
    """

    kind: str
    factor: str | None
    names: tuple[str, str, str]
    points: Array
    closeness: Array

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {
            "kind": self.kind,
            "factor": self.factor,
            "names": list(self.names),
            "points": self.points.tolist(),
            "closeness": self.closeness.tolist(),
        }


def surfaces(
    mechanism: Any,
    *,
    x: Any = ("z", -1000.0, -550.0, 20),
    y: Any = ("phi", -math.pi / 4, math.pi / 4, 20),
    z: Any = ("x", -350.0, 350.0, 5),
    fixed: Any = None,
    mode: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
) -> tuple[Surface, ...]:
    """The singular surfaces of a 3-D region: the :func:`loci` of its ``(x, y)`` slices at every
    value of ``z``, stacked (each point refined onto the surface within its slice).

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> surfaces(load_mechanism("h4"), x=("z", -1000, -550, 4), y=("phi", -45, 45, 3), z=("x", -50, 50, 2),
    ...          angles="deg")
    ()
    """
    z_name, z_values = _axis(mechanism, z, "z", angles)
    if fixed is not None and not isinstance(fixed, Mapping):
        raise ScrewkitTypeError(f"Expected `fixed` to be a dict, got {type(fixed).__name__}.")
    given = dict(fixed or {})
    if z_name in given:
        raise ScrewkitValueError(f"Expected `fixed` not to set the region's axes, got [{z_name!r}].")
    found: dict[str, list[tuple[Array, Array, str | None]]] = {kind: [] for kind in KINDS}
    names: tuple[str, str, str] = (str(x[0]), str(y[0]), z_name)
    for value in z_values:
        for locus in loci(
            mechanism, x=x, y=y, fixed={**given, z_name: float(value)}, mode=mode, angles=angles, rtol=rtol
        ):
            column = np.full((len(locus.points), 1), float(value))
            found[locus.kind].append((np.hstack([locus.points, column]), locus.closeness, locus.factor))
    return tuple(
        Surface(
            kind,
            next((factor for _, _, factor in parts if factor is not None), None),
            names,
            np.vstack([p for p, _, _ in parts]),
            np.concatenate([c for _, c, _ in parts]),
        )
        for kind, parts in found.items()
        if parts
    )


# --------------------------------------------------------------------------------------------------
# Paths
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Crossing:
    """The first singularity met along a path.

    Attributes
    ----------
    parameter : float
        In [0, 1] along the straight segment from start to end (pose coordinates).
    pose : dict
        User units.
    kind : str
        ``"constraint"``, ``"actuation"``, ``"serial"``, or ``"unreachable"`` (the path leaves
        the workspace where no singularity is labelled).
    factor : str or None
    closeness : float
        The kind's closeness there (~0).
    """

    parameter: float
    pose: dict[str, float]
    kind: str
    factor: str | None
    closeness: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {
            "parameter": self.parameter,
            "pose": self.pose,
            "kind": self.kind,
            "factor": self.factor,
            "closeness": _plain(self.closeness),
        }


@dataclass(frozen=True)
class PathCheck:
    """The verdict on a straight path in pose space.

    Attributes
    ----------
    singularity_free : bool
    crossing : Crossing or None
        The first crossing (None when singularity-free).
    start, end : dict
        User units.
    samples : int
    """

    singularity_free: bool
    crossing: Crossing | None
    start: dict[str, float]
    end: dict[str, float]
    samples: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {
            "singularity_free": self.singularity_free,
            "crossing": None if self.crossing is None else self.crossing.to_dict(),
            "start": self.start,
            "end": self.end,
            "samples": self.samples,
        }

    def __str__(self) -> str:
        if self.crossing is None:
            return f"singularity-free ({self.samples} samples, refined)"
        c = self.crossing
        pose = ", ".join(f"{k} = {v:.6g}" for k, v in c.pose.items())
        factor = f", factor {c.factor}" if c.factor else ""
        # an unreachable pose has no closeness (NaN): say so rather than print "nan"
        closeness = f", closeness {c.closeness:.3g}" if math.isfinite(c.closeness) else ""
        where = "the path starts out of reach" if c.kind == "unreachable" and c.parameter == 0 else ""
        text = f"{c.kind} crossing at t = {c.parameter:.9g} ({pose}){factor}{closeness}"
        return f"{text}: {where}" if where else text


def check_path(
    mechanism: Any,
    start: Any,
    end: Any,
    *,
    samples: int = 200,
    mode: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
) -> PathCheck:
    """Check the straight path ``start → end`` (pose coordinates) for singularities.

    ``samples`` poses along it go through the core as one batch; det A sign changes, closeness
    minima, the reach edge and singular samples are refined (module docstring) and the first
    root is the crossing.

    Parameters
    ----------
    mechanism : Mechanism
    start, end : dict or array_like
        User units (angles in radians unless ``angles="deg"``); a dict's missing coordinates take
        the default pose.
    samples : int, default 200
    mode, angles, rtol
        As in :func:`grid_map`.

    Returns
    -------
    PathCheck

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> check = check_path(load_mechanism("h4"), {"z": -750}, {"z": -5000}, samples=20)
    >>> check.crossing.kind, round(check.crossing.parameter, 4)  # the arms and rods line up
    ('serial', 0.0964)
    """
    _check_mechanism(mechanism)
    if (
        isinstance(samples, bool)
        or not isinstance(samples, int | np.integer)
        or not 2 <= samples <= MAX_PATH_SAMPLES
    ):
        raise ScrewkitValueError(
            f"Expected `samples` to be an integer in 2..{MAX_PATH_SAMPLES:g}, got {samples!r}."
        )
    scale = _scale(mechanism, angles)
    first, last = _pose(mechanism, start, "start", angles), _pose(mechanism, end, "end", angles)
    options = _options(mode)
    t = np.linspace(0.0, 1.0, int(samples))
    a, b = first * scale, last * scale

    def along(lines: Array, s: Array) -> Array:
        return a + s[:, None] * (b - a)

    measured = _measure(mechanism, (a + t[:, None] * (b - a))[None], options, rtol)
    roots = _refine(mechanism, along, _brackets(t, measured), options, rtol, keep_edges=True)
    if not measured.ok[0, 0]:
        roots.append(_Root(0, 0.0, a, "unreachable", math.nan))
    crossing = None
    if roots:
        root = min(roots, key=lambda r: r.t)
        factor = _factor(mechanism, root.pose[None], root.kind, options, rtol)
        crossing = Crossing(root.t, _as_dict(mechanism, root.pose / scale), root.kind, factor, root.closeness)
    return PathCheck(
        crossing is None, crossing, _as_dict(mechanism, first), _as_dict(mechanism, last), int(samples)
    )
