"""Singular curves of a 2-D slice and singular surfaces of a 3-D region, refined onto the surfaces.

Along every grid row and column of a slice, ``det A`` and ``det B`` sign changes, closeness minima
(a touching zero has no sign change) and reach edges are refined onto the singular surface
(:mod:`screwkit.analysis.roots`); :func:`loci` gives
the curves of a slice, :func:`surfaces` stacks them over a third coordinate.

Examples
--------
>>> found = loci(load_mechanism("h4"), x=("z", -1000, -550, 6), y=("phi", -45, 45, 5), angles="deg")
>>> [locus.kind for locus in found]  # the catalog's box holds no singular surface at x = y = 0
[]
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .poses import _axis, _check_client, _Slice
from .quantities import KINDS
from .roots import _brackets, _factor, _measure, _refine, _Samples

__all__ = ["LOCUS_KINDS", "Locus", "SingularSurface", "loci", "surfaces"]

Array = np.ndarray


@dataclass(frozen=True, eq=False)
class Locus:
    """Points of one singular surface in a 2-D slice, each refined onto the surface.

    Attributes
    ----------
    kind : str
        ``"constraint"``, ``"actuation"``, ``"serial"`` or ``"reach"`` (the edge of the reachable
        set where no singularity is labelled).
    factor : str or None
        The superbracket factor that vanishes there (None if unknown, and for ``"reach"``).
    x_name, y_name : str
    points : numpy.ndarray, shape (m, 2)
        ``(x, y)`` in user units, sorted by ``x`` then ``y``.
    closeness : numpy.ndarray, shape (m,)
        The kind's closeness at each point (~0; NaN for ``"reach"``).
    """

    kind: str
    factor: str | None
    x_name: str
    y_name: str
    points: Array
    closeness: Array

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "kind": self.kind,
            "factor": self.factor,
            "x_name": self.x_name,
            "y_name": self.y_name,
            "points": self.points.tolist(),
            "closeness": [None if math.isnan(c) else c for c in self.closeness.tolist()],
        }

    def __str__(self) -> str:
        if not len(self.points):
            return f"{self.kind}: no point"
        what = "reach boundary" if self.kind == "reach" else f"{self.kind} singularity"
        factor = f" (factor {self.factor})" if self.factor else ""
        low, high = self.points.min(axis=0), self.points.max(axis=0)
        return (
            f"{what}{factor}: {len(self.points)} points, {self.x_name} in [{low[0]:.6g}, {high[0]:.6g}], "
            f"{self.y_name} in [{low[1]:.6g}, {high[1]:.6g}]"
        )


def loci(
    mechanism: Any,
    *,
    x: Any = None,
    y: Any = None,
    fixed: Any = None,
    mode: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
    client: Any = None,
) -> tuple[Locus, ...]:
    """The singular curves of a 2-D slice: along every grid row and column, det A and det B sign
    changes, closeness minima and reach edges, refined onto the surface (module docstring).

    Parameters
    ----------
    mechanism, x, y, fixed, mode, angles, rtol
        As in :func:`~screwkit.analysis.workspace.grid_map`.
    client : dask.distributed.Client, optional
        Measure the grid and run each refinement step's batch on this cluster (the same loci as
        in process).

    Returns
    -------
    tuple of Locus
        One per kind found, in the order of :data:`LOCUS_KINDS` (constraint, actuation, serial,
        reach).

    Examples
    --------
    >>> found = loci(load_mechanism("h4"), x=("z", -1000, -550, 6), y=("phi", -45, 45, 5), angles="deg")
    >>> [locus.kind for locus in found]  # the catalog's box holds no singular surface at x = y = 0
    []
    """
    grid = _Slice.create(mechanism, x, y, fixed, mode, angles)
    _check_client(client)
    found, _ = _slice_loci(mechanism, grid, rtol, client=client)
    return found


#: The kinds of :class:`Locus`, in order: the three singularity kinds and the reach boundary.
LOCUS_KINDS = (*KINDS, "reach")


def _transposed(samples: _Samples) -> _Samples:
    """The samples of a grid ``(ny, nx)`` read along its columns ``(nx, ny)``."""
    return _Samples(
        samples.ok.T,
        samples.codes.T,
        {k: v.T for k, v in samples.closeness.items()},
        None if samples.det_A is None else samples.det_A.T,
        None if samples.det_B is None else samples.det_B.T,
    )


def _slice_loci(
    mechanism: Any, grid: _Slice, rtol: Any, *, measured: _Samples | None = None, client: Any = None
) -> tuple[tuple[Locus, ...], tuple[str, ...]]:
    """The loci of a slice (the grid measured once, or given as ``measured`` by the map that
    measured it, searched along its rows and columns) and the kinds whose singular set holds every
    reachable pose of the grid (the slice lies inside it)."""
    user = grid.poses()
    scale = grid.scale
    rows = user * scale  # (ny, nx, n): lines along x
    columns = np.swapaxes(rows, 0, 1)  # (nx, ny, n): lines along y
    if measured is None:
        measured = _measure(mechanism, rows, grid.options, rtol, client)
    reachable_codes = measured.codes[measured.ok]
    inside = tuple(
        kind for bit, kind in enumerate(KINDS)
        if reachable_codes.size and bool(np.all(reachable_codes >> bit & 1))
    )
    found: list[tuple[Array, str, float]] = []
    for lines, t, samples in (
        (rows, grid.x_values, measured), (columns, grid.y_values, _transposed(measured))
    ):
        u = (t - t[0]) / (t[-1] - t[0])
        start, stop = lines[:, 0], lines[:, -1]

        def along(which: Array, s: Array, start: Array = start, stop: Array = stop) -> Array:
            return start[which] + s[:, None] * (stop[which] - start[which])

        brackets = _brackets(u, samples)
        refined = _refine(
            mechanism, along, brackets, u, samples, grid.options, rtol, keep_edges=True, client=client
        )
        for root in refined:
            kind = "reach" if root.kind == "unreachable" else root.kind
            found.append((root.pose / scale, kind, root.closeness))
    names = mechanism.pose_names
    ix, iy = names.index(grid.x_name), names.index(grid.y_name)
    out = []
    for kind in LOCUS_KINDS:
        mine = [(p, c) for p, k, c in found if k == kind]
        if not mine:
            continue
        points = np.array([[p[ix], p[iy]] for p, _ in mine])
        closeness = np.array([c for _, c in mine])
        order = np.lexsort((points[:, 1], points[:, 0]))
        points, closeness = points[order], closeness[order]
        keep = np.ones(len(points), dtype=bool)
        keep[1:] = np.any(np.abs(np.diff(points, axis=0)) > 1e-9 * (1 + np.abs(points[1:])), axis=1)
        factor = None
        if kind != "reach":
            closest = np.array([p for p, _ in mine])[np.argsort([c for _, c in mine])]
            factor = _factor(mechanism, closest * scale, kind, grid.options, rtol)
        out.append(Locus(kind, factor, grid.x_name, grid.y_name, points[keep], closeness[keep]))
    return tuple(out), inside


@dataclass(frozen=True, eq=False)
class SingularSurface:
    """One singular surface (one kind of singularity) in a 3-D region of the pose space: points
    refined onto it (:func:`surfaces`) and, where it was triangulated, its triangles (paper 004's
    ``|A| = 0``, :func:`screwkit.papers.paper_004_surfaces.actuation_singularity_surface`).

    Attributes
    ----------
    kind : str
        ``"constraint"``, ``"actuation"`` or ``"serial"``.
    factor : str or None
        The superbracket factor that vanishes there (None if unknown).
    names : tuple of 3 str
        The pose coordinates of the points' columns.
    points : numpy.ndarray, shape (m, 3)
        Points on the surface, user units.
    closeness : numpy.ndarray, shape (m,)
        The kind's closeness at each point (~0; NaN where not measured).
    triangles : numpy.ndarray, shape (t, 3, 3)
        A triangulation of the surface (none: shape ``(0, 3, 3)``).
    fixed : dict of str to float
        The other pose coordinates given by the caller (e.g. ``{"phi": φ}``).
    region : object
        The region searched (a :class:`~screwkit.papers.paper_004_table4.Region`), or None.
    mechanism : str
    """

    kind: str
    factor: str | None
    names: tuple[str, str, str]
    points: Array
    closeness: Array
    triangles: Array = field(default_factory=lambda: np.zeros((0, 3, 3)))
    fixed: dict[str, float] = field(default_factory=dict)
    region: Any = None
    mechanism: str = ""

    @property
    def area(self) -> float:
        """float: The area of the triangles, in the length unit squared (0 without triangles)."""
        edges = self.triangles[:, 1:] - self.triangles[:, :1]
        return float(0.5 * np.sum(np.linalg.norm(np.cross(edges[:, 0], edges[:, 1]), axis=-1)))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "kind": self.kind,
            "factor": self.factor,
            "names": list(self.names),
            "points": self.points.tolist(),
            "closeness": [None if math.isnan(c) else c for c in self.closeness.tolist()],
            "triangles": self.triangles.tolist(),
            "fixed": self.fixed,
            "region": getattr(self.region, "name", self.region),
            "mechanism": self.mechanism,
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
) -> tuple[SingularSurface, ...]:
    """The singular surfaces of a 3-D region: the :func:`loci` of its ``(x, y)`` slices at every
    value of ``z``, stacked (each point refined onto the surface within its slice).

    Parameters
    ----------
    mechanism, x, y, fixed, mode, angles, rtol
        As in :func:`loci`.
    z : tuple (name, low, high, count)
        The third coordinate, one slice per value.

    Returns
    -------
    tuple of SingularSurface
        One per kind found.

    Examples
    --------
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
            if locus.kind == "reach":  # the surfaces are the singular ones
                continue
            column = np.full((len(locus.points), 1), float(value))
            found[locus.kind].append((np.hstack([locus.points, column]), locus.closeness, locus.factor))
    return tuple(
        SingularSurface(
            kind,
            next((factor for _, _, factor in parts if factor is not None), None),
            names,
            np.vstack([p for p, _, _ in parts]),
            np.concatenate([c for _, c, _ in parts]),
            fixed={str(k): float(v) for k, v in given.items()},
            mechanism=mechanism.name,
        )
        for kind, parts in found.items()
        if parts
    )
