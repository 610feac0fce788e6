"""Workspace maps: a quantity over a 2-D slice of the pose space, through the posed mechanism in chunks.

Every pose goes through :meth:`screwkit.robots.mechanism.Mechanism.at` (the posed mechanism: inverse
kinematics → joint table → wrench systems → verdicts, closeness, Jacobians), in chunks of the
batch axis, so a map of 10⁶ poses runs in bounded memory. Chunks can run on a Dask distributed
cluster (optional extra ``dask``): pass ``client=``; the results are identical to the in-process run.
The quantities are :mod:`screwkit.analysis.quantities`'; the singular curves and surfaces of a slice
are :mod:`screwkit.analysis.loci`', a straight path's check :mod:`screwkit.analysis.paths`'. A map
is data: :func:`screwkit.interface.plot.save_map_png` draws it.

Units
-----
Poses here are in the API's units (docs/architecture.md §3): lengths in the catalog file's length unit, angles
in **radians**, as everywhere in the Python API; pass ``angles="deg"`` to give ranges, fixed
coordinates and paths in degrees (as in the TOML files and on the command line, which passes it). A
pose is a dict ``{name: value}`` over :attr:`~screwkit.robots.mechanism.Mechanism.pose_names` (missing
coordinates take the default pose) or an array in that order.

Float maps hold NaN where a pose is out of reach, always together with ``reachable`` False.

Examples
--------
>>> h4 = load_mechanism("h4")
>>> m = grid_map(h4, "verdict", x=("z", -1000, -550, 4), y=("phi", -45, 45, 3), angles="deg")
>>> m.values.shape, int(m.maximum), bool(m.reachable.all())
((3, 4), 0, True)
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from ..robots.pose_reader import pose_array
from . import quantities as Q
from .poses import CHUNK, _as_dict, _check_client, _check_mechanism, _options, _Slice, _units, reached_batch

__all__ = ["CHUNK", "WorkspaceMap", "evaluate", "grid_map", "sweep"]

Array = np.ndarray


def evaluate(
    mechanism: Any, poses: Any, quantity: str, *, mode: Any = None, rtol: float | None = None
) -> tuple[Array, Array]:
    """One quantity at poses ``(m, n)`` in **API units** (radians), and which poses are reachable.

    The core (:meth:`~screwkit.robots.mechanism.Mechanism.at`) runs once over the reachable poses.

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like, shape (m, n)
    quantity : str
        See :data:`screwkit.analysis.quantities.QUANTITIES`.
    mode : mapping or sequence, optional
        As in :func:`grid_map`.
    rtol : float, optional

    Returns
    -------
    values : numpy.ndarray, shape (m,)
        int64 codes (``-1`` out of reach) for ``"verdict"``, else float (NaN out of reach).
    reachable : numpy.ndarray of bool, shape (m,)

    Examples
    --------
    >>> evaluate(load_mechanism("h4"), [[0, 0, -750, 0], [0, 0, -5000, 0]], "verdict")
    (array([ 0, -1]), array([ True, False]))
    """
    _check_mechanism(mechanism)
    name = Q.quantity(quantity)
    array = pose_array(mechanism, poses).reshape(-1, len(mechanism.pose_names))
    options = _options(mechanism, mode)
    ok = np.array(mechanism.reachable(array, **options), dtype=bool)  # (narrowed by reached_batch)
    integer = name == "verdict"
    out = np.full(len(array), -1 if integer else np.nan, dtype=np.int64 if integer else float)
    posed = reached_batch(mechanism, array, ok, rtol, options)
    if posed is not None:
        out[ok] = Q.values(posed, name)
    return out, ok


def _run_chunks(
    function: Callable[..., tuple[Array, ...]],
    jobs: Sequence[tuple[Any, Array, tuple[Any, ...]]],
    chunk: int | None,
    client: Any,
    progress: Any,
) -> list[tuple[Array, ...]]:
    """``function(mechanism, poses[chunk], *args)`` (a tuple of arrays along the chunk) over chunks
    of each job's batch, in process or on a Dask client (every chunk of every job submitted at
    once), with an optional progress line; per job, each array's parts joined in order."""
    size = CHUNK if chunk is None else chunk
    if isinstance(size, bool) or not isinstance(size, int | np.integer) or size < 1:
        raise ScrewkitValueError(f"Expected `chunk` to be a positive integer, got {chunk!r}.")
    _check_client(client)
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
        out.append(tuple(np.concatenate([p[n] for p in parts]) for n in range(len(parts[0]))))
    return out


def _chunk_values(
    mechanism: Any, poses: Array, quantity: str, mode: Any, rtol: Any, loci: bool
) -> tuple[Array, ...]:
    """One chunk of a map (a module-level function, so a Dask worker can run it): ``(values,
    reachable)``, and with ``loci`` the samples the loci search reads, from the same posed batch
    (:func:`screwkit.analysis.roots._measured_chunk`: the grid goes through the core once)."""
    if loci:
        from .roots import _measured_chunk

        return _measured_chunk(mechanism, poses, _options(mechanism, mode), rtol, quantity)
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
    loci : tuple of Locus
        The singular curves and the reach boundary in the slice, found between the grid's nodes
        (:mod:`screwkit.analysis.loci`: sign changes and closeness minima refined onto them), so
        that a singular curve no sample hits is still shown; empty when the map was asked
        without them.
    inside : tuple of str
        The kinds of singularity whose singular set holds every reachable pose of the grid (the
        slice lies inside it).
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
    loci: tuple[Any, ...] = ()
    inside: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for name in ("x_values", "y_values", "values", "reachable"):
            getattr(self, name).flags.writeable = False

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the region, extrema and where they occur, axes, values (None out of reach).

        Returns
        -------
        dict
        """
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
            "loci": [locus.to_dict() for locus in self.loci],
            "inside": list(self.inside),
            **({"codes": {str(c): Q.verdict_name(c) for c in range(-1, 2 ** len(Q.KINDS))}}
               if self.quantity == "verdict" else {}),
        }

    def to_json(self, **kwargs: Any) -> str:
        """:meth:`to_dict` as a JSON string.

        Parameters
        ----------
        **kwargs
            Passed to :func:`json.dumps`.

        Returns
        -------
        str
        """
        return json.dumps(self.to_dict(), **kwargs)

    def save(self, path: str | Path) -> Path:
        """Write ``.npz`` (arrays and the JSON summary) or ``.json`` (a map is data: a ``.png`` is
        drawn by :func:`screwkit.interface.plot.save_map_png`).

        Parameters
        ----------
        path : str or pathlib.Path
            Ending in ``.npz`` or ``.json``.

        Returns
        -------
        pathlib.Path
            The file written.

        Raises
        ------
        ScrewkitValueError
            For another suffix (for ``.png``, naming the function that draws it).

        Examples
        --------
        >>> import tempfile, pathlib
        >>> m = grid_map(load_mechanism("h4"), "verdict", x=("z", -900, -600, 2), y=("phi", -0.1, 0.1, 2))
        >>> m.save(pathlib.Path(tempfile.mkdtemp()) / "m.json").suffix
        '.json'
        """
        target = Path(path)
        suffix = target.suffix.lower()
        if suffix == ".json":
            target.write_text(self.to_json(indent=1))
        elif suffix == ".npz":
            summary = {k: v for k, v in self.to_dict().items() if k not in ("values", "x", "y", "loci")}
            np.savez_compressed(
                target,
                x_values=self.x_values,
                y_values=self.y_values,
                values=self.values,
                reachable=self.reachable,
                loci=np.array(json.dumps([locus.to_dict() for locus in self.loci])),
                summary=np.array(json.dumps(summary)),
            )
        elif suffix == ".png":
            raise ScrewkitValueError(
                f"Expected `path` to end in .npz or .json, got {str(path)!r}: a map is data, "
                "screwkit.interface.plot.save_map_png draws it (pip install 'screwkit[plot]')."
            )
        else:
            raise ScrewkitValueError(f"Expected `path` to end in .npz, .json or .png, got {str(path)!r}.")
        return target


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
    x: Any = None,
    y: Any = None,
    fixed: Any = None,
    mode: Any = None,
    chunk: int | None = None,
    client: Any = None,
    progress: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
    loci: bool = True,
) -> WorkspaceMap:
    """A quantity over a 2-D grid of the pose space, through the core in chunks, with the singular
    loci of the slice found between the grid's nodes.

    Parameters
    ----------
    mechanism : Mechanism
    quantity : str
        See :data:`~screwkit.analysis.quantities.QUANTITIES` (``"detA"``/``"detB"`` and ``"condition"`` =
        ``"condition:0"`` too).
    x, y : tuple (name, low, high, count), optional
        The axes (user units: angles in radians unless ``angles="deg"``); default: the family's
        default map axes (:attr:`screwkit.robots.families.Family.default_map_axes`) over the workspace,
        :data:`~screwkit.analysis.poses.DEFAULT_AXIS_COUNT` values each.
    fixed : dict, optional
        The other coordinates (default: the default pose), e.g. ``{"x": 0.0, "y": 0.0}``.
    mode : mapping or sequence, optional
        Inverse-kinematics options (e.g. ``{"working_mode": (1, 1, 1, 1)}``) or a working mode.
    chunk : int, optional
        Poses per chunk (default :data:`CHUNK`): bounds the memory.
    client : dask.distributed.Client, optional
        Run the chunks (and the loci's refinement batches) on this cluster (results identical to
        the in-process run).
    progress : bool, optional
        Show a progress bar (tqdm if installed); default: on a terminal, for large maps.
    angles : {"deg", "rad"}
    rtol : float, optional
        The core's relative tolerance.
    loci : bool, default True
        Find the singular curves and the reach boundary of the slice (:attr:`WorkspaceMap.loci`):
        the map's chunks also return the samples the search reads (one pass through the core),
        then the refinement's batches run in process or on ``client``.

    Returns
    -------
    WorkspaceMap

    Raises
    ------
    ScrewkitValueError
        For an unknown quantity or coordinate, or a malformed axis.

    Examples
    --------
    >>> m = grid_map(load_mechanism("h4"), "lti", x=("x", -100, 100, 3), y=("y", -100, 100, 3),
    ...              fixed={"z": -750, "phi": 0}, angles="deg")
    >>> print(m.region)
    H4: x in [-100, 100] mm (3 values) x y in [-100, 100] mm (3 values), z = -750 mm, phi = 0 deg
    >>> bool(0 < m.minimum <= m.maximum <= 1)
    True
    """
    _check_flag(loci, "loci")
    name, grid, job = _map_job(mechanism, quantity, x, y, fixed, mode, angles, rtol, loci)
    (columns,) = _run_chunks(_chunk_values, [job], chunk, client, progress)
    return _assembled(mechanism, name, grid, columns, rtol, client)


def _check_flag(value: Any, name: str) -> None:
    if not isinstance(value, bool):
        raise ScrewkitTypeError(f"Expected `{name}` to be True or False, got {value!r}.")


def _map_job(
    mechanism: Any, quantity: Any, x: Any, y: Any, fixed: Any, mode: Any, angles: str, rtol: Any,
    loci: bool,
) -> tuple[str, _Slice, tuple[Any, Array, tuple[Any, ...]]]:
    """A map's quantity, slice and chunk job (its API-unit poses, flattened; with ``loci`` the
    chunks also return the loci's samples)."""
    name = Q.quantity(quantity)
    grid = _Slice.create(mechanism, x, y, fixed, mode, angles)
    if name.startswith("condition:"):  # refuse before the map (factored once per mechanism)
        Q.checked_condition(mechanism, grid.options, int(name.split(":")[1]))
    elif name in Q.CONTRIBUTED:
        Q.values(mechanism.at(None, **grid.options), name)
    user = grid.poses()
    flat = user.reshape(-1, user.shape[-1]) * grid.scale
    return name, grid, (mechanism, flat, (name, grid.options, rtol, loci))


def _assembled(
    mechanism: Any, name: str, grid: _Slice, columns: tuple[Array, ...], rtol: Any, client: Any
) -> WorkspaceMap:
    """The map from its chunks' flat columns: extrema over the reachable poses and where they
    occur, and, when the chunks measured the loci's samples too, the slice's loci (refined with the
    core's tolerance ``rtol``, on the Dask ``client`` if given)."""
    from .loci import _slice_loci
    from .roots import _samples

    values, ok = columns[:2]
    user = grid.poses()
    shape = user.shape[:2]
    found: tuple[Any, ...] = ()
    inside: tuple[str, ...] = ()
    if len(columns) > 2:
        measured = _samples(list(columns[1:]), shape)
        found, inside = _slice_loci(mechanism, grid, rtol, measured=measured, client=client)
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
        found,
        inside,
    )


def _meaning(mechanism: Any, name: str, options: Mapping[str, Any]) -> str:
    """What a ``condition:K`` map shows (its factor, label and vector form); empty otherwise."""
    if not name.startswith("condition:"):
        return ""
    _, conditions, labels, _ = Q.conditions_of(mechanism, options)
    index = int(name.split(":")[1])
    return f"{labels[index]} factor {conditions[index].factor} (vector form {conditions[index].expression})"


def sweep(
    mechanisms: Sequence[Any],
    quantity: str,
    *,
    x: Any = None,
    y: Any = None,
    fixed: Any = None,
    mode: Any = None,
    chunk: int | None = None,
    client: Any = None,
    progress: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
    loci: bool = True,
) -> tuple[WorkspaceMap, ...]:
    """A parameter sweep: the same map for each mechanism (e.g. a family's parameters varied with
    :func:`screwkit.robots.catalog.mechanism_from_mapping`), every chunk of every map submitted at once
    when a Dask ``client`` is given.

    Parameters
    ----------
    mechanisms : sequence of Mechanism
        The mechanisms to map, in order (non-empty).
    quantity : str
        See :data:`~screwkit.analysis.quantities.QUANTITIES`, as for :func:`grid_map`.
    x, y : tuple (name, low, high, count)
        The axes, as for :func:`grid_map`.
    fixed : dict, optional
        The other coordinates, as for :func:`grid_map`.
    mode : mapping or sequence, optional
        Inverse-kinematics options, as for :func:`grid_map`.
    chunk : int, optional
        Poses per chunk.
    client : dask.distributed.Client, optional
        Submit every chunk of every map to this cluster at once.
    progress : bool, optional
        Show a progress bar.
    angles : {"deg", "rad"}
    rtol : float, optional
        The core's relative tolerance.
    loci : bool, default True
        Find each map's loci, as for :func:`grid_map`.

    Returns
    -------
    tuple of WorkspaceMap
        One per mechanism, in order.

    Examples
    --------
    >>> maps = sweep([load_mechanism("h4"), load_mechanism("quattro")], "lti",
    ...              x=("z", -900, -600, 3), y=("phi", -20, 20, 2), angles="deg")
    >>> [m.mechanism for m in maps]
    ['H4', 'Quattro']
    """
    if isinstance(mechanisms, str) or not isinstance(mechanisms, Sequence) or not mechanisms:
        raise ScrewkitTypeError(
            f"Expected `mechanisms` to be a non-empty sequence of mechanisms, got {mechanisms!r}."
        )
    _check_flag(loci, "loci")
    prepared = [_map_job(m, quantity, x, y, fixed, mode, angles, rtol, loci) for m in mechanisms]
    results = _run_chunks(_chunk_values, [job for _, _, job in prepared], chunk, client, progress)
    return tuple(
        _assembled(mechanism, name, grid, columns, rtol, client)
        for mechanism, (name, grid, _), columns in zip(mechanisms, prepared, results, strict=True)
    )
