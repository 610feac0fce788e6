"""Drawings with matplotlib: index maps, verdict maps, wrench diagrams in 3-D, twist graphs.

matplotlib is an optional dependency (the extra ``plot``: ``pip install "screwkit[plot]"``); it is
imported by this module, and ``import screwkit`` never imports this module. Without matplotlib,
``import screwkit.interface.plot`` raises :class:`~screwkit.exceptions.MissingDependencyError` naming the
extra.

Every function draws into the axes it is given (``ax=``) or into a new figure, and returns the axes.
The objects drawn are read by their attributes only (duck typing), so anything with the same
attributes works:

* :func:`plot_map`: a map of a scalar quantity over a grid of two pose coordinates, drawn as
  isocontours (the style of paper 004, Figs. 8–13: the LTI over the workspace at a fixed
  orientation) with singularity loci overlaid (Figs. 14–16 show such loci). The map has
  ``quantity``, ``x_name``, ``x_values (nx,)``, ``y_name``, ``y_values (ny,)``, ``values (ny, nx)``,
  ``reachable (ny, nx)`` and ``fixed`` (the other pose coordinates); a locus has ``kind``
  (``"constraint"``, ``"actuation"``, ``"serial"``), ``factor``, ``x_name``, ``y_name`` and
  ``points (m, 2)``;
* :func:`plot_singularity_surfaces`: singularity loci as surfaces in the 3-D workspace, inside the
  workspace drawn as a blue wireframe (paper 004, Figs. 14-16: the actuation singularity loci of the
  Quattro, H4 and V4 at two rotations ``±φ`` each). A surface has ``triangles (m, 3, 3)``, ``phi``,
  ``robot`` and ``region`` (with ``lower``, ``upper``, ``name`` and ``boundary(count)``), as
  :func:`screwkit.papers.paper_004_surfaces.actuation_singularity_surface` returns;
* :func:`plot_verdicts`: the same grid coloured by verdict (``values`` are the codes of
  :attr:`screwkit.core.singularity.SingularityReport.codes`, bit 1 constraint, 2 actuation, 4 serial, or
  the verdict strings);
* :func:`plot_wrench_diagram`: a :class:`~screwkit.gca.diagram.WrenchDiagram` in 3-D: finite points as
  labelled dots, points at infinity as labelled arrows (directions) from the centre of the finite
  points, each finite line through its two points, and each line at infinity (a pure couple) as a
  dashed circle of the plane spanned by its two directions: the limit of ever larger circles of a
  plane is that plane's line at infinity (gca.md §1), so the circle stands for it;
* :func:`plot_twist_graph`: a twist graph (:mod:`screwkit.graphs.twistgraph`), links layered by their
  distance from the base, one arrow per joint (``u → v``), actuated joints bold, virtual joints
  (an equivalent twist graph's, paper 002 Fig. 3) dashed.

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> from screwkit.robots.catalog import load_mechanism
>>> from screwkit.interface.plot import plot_twist_graph
>>> ax = plot_twist_graph(load_mechanism("h4").twist_graph())
>>> len(ax.patches)                      # one arrow per joint of the H4
22
"""

from __future__ import annotations

import dataclasses
from collections import deque
from collections.abc import Collection, Iterable
from pathlib import Path
from typing import Any

import numpy as np

from ..exceptions import (
    DegenerateGeometryError,
    MissingDependencyError,
    ScrewkitTypeError,
    ScrewkitValueError,
)

try:
    import matplotlib.pyplot as plt
    from matplotlib.colors import BoundaryNorm, ListedColormap, to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import FancyArrowPatch, Patch
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
except ImportError as err:  # pragma: no cover - exercised in a subprocess without matplotlib
    raise MissingDependencyError(
        "screwkit.interface.plot needs matplotlib, which is not installed: install the optional extra `plot` "
        '(pip install "screwkit[plot]").'
    ) from err

from ..core.singularity import LABELS
from ..graphs.twistgraph import check_twist_graph

__all__ = [
    "KIND_COLOURS",
    "SURFACE_COLOURS",
    "UNREACHABLE_COLOUR",
    "VERDICT_COLOURS",
    "plot_map",
    "plot_singularity_surfaces",
    "plot_twist_graph",
    "plot_verdicts",
    "plot_wrench_diagram",
    "save_map_png",
]

Array = np.ndarray

#: Colour of each kind of singularity locus.
KIND_COLOURS = {"constraint": "tab:red", "actuation": "tab:blue", "serial": "tab:green"}
#: Colour of each verdict code (bit 1 constraint, 2 actuation, 4 serial; 0 regular).
VERDICT_COLOURS = (
    "#f2f2f2",  # regular
    "tab:red",  # constraint
    "tab:blue",  # actuation
    "tab:purple",  # constraint + actuation (never together in screwkit's labels; kept for codes)
    "tab:green",  # serial
    "tab:olive",  # constraint + serial
    "tab:cyan",  # actuation + serial
    "black",  # all three
)
#: Colour of the axes' background: where a map has no value (unreachable poses).
UNREACHABLE_COLOUR = "0.75"
#: Colours of the surfaces of :func:`plot_singularity_surfaces`, in turn.
SURFACE_COLOURS = ("tab:orange", "tab:purple", "tab:green", "tab:red", "tab:brown", "tab:pink")


def _verdict_name(code: int) -> str:
    names = [name for bit, name in enumerate(LABELS) if code >> bit & 1]
    return " + ".join(names) + " singularity" if names else "regular"


# maps --------------------------------------------------------------------------------------------
def _new_axes(ax: Any, three_d: bool = False) -> Any:
    if ax is None:
        if three_d:
            return plt.figure(figsize=(7, 7)).add_subplot(projection="3d")
        return plt.subplots(figsize=(7, 5.5))[1]
    if three_d and getattr(ax, "name", "") != "3d":
        raise ScrewkitTypeError(
            f"Expected `ax` to be 3-D axes (projection='3d'), got {type(ax).__name__} "
            f"with projection {getattr(ax, 'name', '?')!r}."
        )
    return ax


def _grid(workspace_map: Any, degrees: Collection[str]) -> tuple[Array, Array, Array, str, str]:
    """(x, y, reachable mask, x label, y label) of a map, checked; angles named in ``degrees`` in degrees."""
    try:
        x = np.array(workspace_map.x_values, dtype=float)  # copies: converted to degrees below
        y = np.array(workspace_map.y_values, dtype=float)
        shape = np.shape(workspace_map.values)
        reachable = np.asarray(workspace_map.reachable, dtype=bool)
        names = (str(workspace_map.x_name), str(workspace_map.y_name))
    except AttributeError as err:
        raise ScrewkitTypeError(
            "Expected `workspace_map` to have x_name, x_values, y_name, y_values, values and reachable "
            f"(a screwkit.analysis.workspace.WorkspaceMap), got {type(workspace_map).__name__}: {err}."
        ) from err
    if x.ndim != 1 or y.ndim != 1 or shape != (y.size, x.size):
        raise ScrewkitValueError(
            "Expected `workspace_map.values` to have shape (len(y_values), len(x_values)) = "
            f"({y.size}, {x.size}), got {shape}."
        )
    if reachable.shape != shape:
        raise ScrewkitValueError(
            f"Expected `workspace_map.reachable` to have the shape of its values {shape}, "
            f"got {reachable.shape}."
        )
    labels = []
    for name, values in zip(names, (x, y), strict=True):
        if name in degrees:
            values[...] = np.degrees(values)
        unit = _unit_of(workspace_map, name, degrees)
        labels.append(f"{name} ({unit})" if unit else name)
    return x, y, reachable, labels[0], labels[1]


def _unit_of(workspace_map: Any, name: str, degrees: Collection[str]) -> str:
    """The unit a coordinate is drawn in: "deg" if converted, else the map's ``units`` entry (if any)."""
    if name in degrees:
        return "deg"
    units = getattr(workspace_map, "units", None) or {}
    return str(units.get(name, "")) if isinstance(units, dict) else ""


def _title(workspace_map: Any, what: str, degrees: Collection[str]) -> str:
    fixed = dict(getattr(workspace_map, "fixed", {}) or {})
    parts = []
    for name, value in fixed.items():
        unit = _unit_of(workspace_map, name, degrees)
        shown = np.degrees(value) if name in degrees else value
        parts.append(f"{name} = {shown:.4g}" + (f" {unit}" if unit else ""))
    return what + (f" at {', '.join(parts)}" if parts else "")


def _draw_loci(ax: Any, workspace_map: Any, loci: Iterable[Any], degrees: Collection[str]) -> None:
    axes = (str(workspace_map.x_name), str(workspace_map.y_name))
    for index, locus in enumerate(loci):
        if (str(locus.x_name), str(locus.y_name)) != axes:
            raise ScrewkitValueError(
                f"Expected loci[{index}] over the map's axes {axes}, "
                f"got ({locus.x_name!r}, {locus.y_name!r})."
            )
        points = np.array(locus.points, dtype=float).reshape(-1, 2)
        for k, name in enumerate(axes):
            if name in degrees:
                points[:, k] = np.degrees(points[:, k])
        ax.plot(
            points[:, 0],
            points[:, 1],
            linestyle="none",
            marker=".",
            markersize=3,
            color=KIND_COLOURS.get(str(locus.kind), "black"),
            label=f"{locus.kind} locus" + (f": {locus.factor}" if locus.factor else ""),
        )


def plot_map(
    workspace_map: Any,
    *,
    ax: Any = None,
    levels: int | Iterable[float] = 10,
    loci: Iterable[Any] = (),
    degrees: Collection[str] = (),
    filled: bool = True,
    cmap: str = "viridis",
) -> Any:
    """Isocontours of a map's quantity over its grid, with singularity loci overlaid.

    The style of paper 004, Figs. 8–13 (LTI isocontours over the workspace at a fixed orientation),
    with the loci of its Figs. 14–16 drawn on top, one colour per kind (:data:`KIND_COLOURS`).
    Unreachable grid points (``~reachable``) and non-finite values are left blank, on a grey
    background.

    Parameters
    ----------
    workspace_map : WorkspaceMap
        Attributes ``quantity``, ``x_name``, ``x_values (nx,)``, ``y_name``, ``y_values (ny,)``,
        ``values (ny, nx)``, ``reachable (ny, nx)``, ``fixed`` (see the module docstring), and
        optionally ``units`` (``{name: unit}``, shown on the axes and in the title).
    ax : matplotlib.axes.Axes, optional
        Default: a new figure.
    levels : int or sequence of float, default 10
        The contour levels (as for :func:`matplotlib.pyplot.contour`).
    loci : iterable of Locus
        Each with ``kind``, ``factor``, ``x_name``, ``y_name`` (the map's) and ``points (m, 2)``.
    degrees : collection of str, default ()
        Pose coordinates stored in radians, to draw in degrees (:func:`screwkit.analysis.workspace.grid_map`
        stores angles in degrees unless asked for radians: then pass their names here).
    filled : bool, default True
        Fill between the contour lines (the lines are drawn and labelled either way).
    cmap : str, default "viridis"

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ScrewkitTypeError
        If ``workspace_map`` lacks an attribute.
    ScrewkitValueError
        If the values do not have the grid's shape, no grid point has a finite reachable value, or
        a locus is over other axes.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from types import SimpleNamespace
    >>> x, y = np.linspace(-1, 1, 21), np.linspace(-1, 1, 11)
    >>> values = 1 - np.hypot(*np.meshgrid(x, y)) / 2
    >>> m = SimpleNamespace(quantity="eta", x_name="x", x_values=x, y_name="y", y_values=y,
    ...                     values=values, reachable=np.ones(values.shape, bool), fixed={"z": -800.0})
    >>> ax = plot_map(m, levels=[0.4, 0.6, 0.8])
    >>> ax.get_title()
    'eta at z = -800'
    """
    ax = _new_axes(ax)
    x, y, reachable, x_label, y_label = _grid(workspace_map, degrees)
    values = np.asarray(workspace_map.values, dtype=float)
    shown = np.ma.masked_where(~reachable | ~np.isfinite(values), values)
    if shown.count() == 0:
        raise ScrewkitValueError(
            f"Expected `workspace_map` to have a finite value at a reachable grid point, got none "
            f"(quantity {workspace_map.quantity!r})."
        )
    ax.set_facecolor(UNREACHABLE_COLOUR)
    chosen = levels if isinstance(levels, int) else np.asarray(list(levels), dtype=float)
    if filled:
        fill = ax.contourf(x, y, shown, levels=chosen, cmap=cmap, extend="both")  # values off the levels too
        plt.colorbar(fill, ax=ax, label=str(workspace_map.quantity))
        chosen = fill.levels
    lines = ax.contour(x, y, shown, levels=chosen, colors="black", linewidths=0.7)
    ax.clabel(lines, fmt="%.3g", fontsize=7)
    _draw_loci(ax, workspace_map, loci, degrees)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.set_title(_title(workspace_map, str(workspace_map.quantity), degrees))
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper right", fontsize=7)
    return ax


def _codes(values: Any, reachable: Array) -> Array:
    """Verdict codes 0..7 from codes or verdict strings; unreachable cells (any value) become 0."""
    array = np.asarray(values)
    if array.dtype.kind in "iub":
        codes = np.where(reachable, array.astype(int), 0)
    else:
        names = {_verdict_name(code): code for code in range(8)}
        flat = [
            names.get(str(v), -1) if ok else 0 for v, ok in zip(array.ravel(), reachable.ravel(), strict=True)
        ]
        codes = np.array(flat, dtype=int).reshape(array.shape)
        unknown = sorted({str(v) for v in array[codes < 0]})
        if unknown:
            raise ScrewkitValueError(
                f"Expected `workspace_map.values` to be verdict codes or verdicts {sorted(names)}, "
                f"got {unknown[:3]}."
            )
    bad = (codes < 0) | (codes > 7)
    if bad.any():
        raise ScrewkitValueError(
            f"Expected verdict codes in 0..7 (bits: 1 constraint, 2 actuation, 4 serial) where "
            f"reachable, got {sorted(set(codes[bad].tolist()))[:3]}."
        )
    return codes


def plot_verdicts(
    workspace_map: Any,
    *,
    ax: Any = None,
    loci: Iterable[Any] = (),
    degrees: Collection[str] = (),
) -> Any:
    """A map of verdicts: each grid cell coloured by its label (:data:`VERDICT_COLOURS`).

    Parameters
    ----------
    workspace_map : WorkspaceMap
        As for :func:`plot_map`, with ``values`` the verdict codes (bit 1 constraint, 2 actuation,
        4 serial; :attr:`screwkit.core.singularity.SingularityReport.codes`) or the verdict strings;
        unreachable cells may hold anything (e.g. ``-1``).
    ax : matplotlib.axes.Axes, optional
    loci : iterable of Locus
        Drawn on top, as in :func:`plot_map`.
    degrees : collection of str, default ()
        As for :func:`plot_map`.

    Returns
    -------
    matplotlib.axes.Axes
        Its legend names the verdicts present (unreachable cells are left grey).

    Raises
    ------
    ScrewkitValueError
        For values that are neither codes 0..7 nor verdict strings.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from types import SimpleNamespace
    >>> codes = np.zeros((3, 4), int)
    >>> codes[1, :] = 1                      # a row of constraint singularities
    >>> m = SimpleNamespace(quantity="verdict", x_name="x", x_values=np.arange(4.0), y_name="y",
    ...                     y_values=np.arange(3.0), values=codes, reachable=np.ones((3, 4), bool), fixed={})
    >>> [t.get_text() for t in plot_verdicts(m).get_legend().get_texts()]
    ['regular', 'constraint singularity']
    """
    ax = _new_axes(ax)
    x, y, reachable, x_label, y_label = _grid(workspace_map, degrees)
    codes = _codes(workspace_map.values, reachable)
    ax.set_facecolor(UNREACHABLE_COLOUR)
    ax.pcolormesh(
        x,
        y,
        np.ma.masked_where(~reachable, codes),
        cmap=ListedColormap(VERDICT_COLOURS),
        norm=BoundaryNorm(np.arange(-0.5, 8.5), 8),
        shading="nearest",
    )
    present = sorted(set(codes[reachable].tolist()))
    handles = [Patch(facecolor=VERDICT_COLOURS[c], edgecolor="0.3", label=_verdict_name(c)) for c in present]
    _draw_loci(ax, workspace_map, loci, degrees)
    ax.legend(handles=handles + ax.get_legend_handles_labels()[0], loc="upper right", fontsize=7)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.set_title(_title(workspace_map, "verdicts", degrees))
    return ax


# singularity surfaces in 3-D ---------------------------------------------------------------------
def _shaded(colour: str, triangles: Array) -> Array:
    """One RGBA per triangle: ``colour`` darkened by how far the triangle turns from a light above
    and in front (either side lit alike: the surfaces have no outside)."""
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=-1)
    light = np.array([-0.4, -0.5, 0.77]) / np.linalg.norm([-0.4, -0.5, 0.77])
    facing = np.minimum(np.abs(normals @ light) / np.where(lengths > 0, lengths, 1.0), 1.0)
    rgba = np.tile(np.array(to_rgba(colour)), (len(triangles), 1))
    rgba[:, :3] *= (0.45 + 0.55 * facing)[:, None]
    return rgba


def plot_singularity_surfaces(
    surfaces: Iterable[Any], *, ax: Any = None, wireframe: int = 16, alpha: float = 0.85
) -> Any:
    """Draw singularity surfaces in the workspace, as paper 004's Figs. 14-16.

    Each surface is a set of triangles in its own colour (:data:`SURFACE_COLOURS` in turn), shaded
    by a light from above; the first surface's region is drawn as a blue wireframe (points of its
    boundary, :meth:`screwkit.papers.paper_004_table4.Region.boundary`), the axes span the region's
    box with equal scales. A surface with no triangle (none in the region) is named in the legend as such.

    Parameters
    ----------
    surfaces : SingularSurface or iterable of SingularSurface
        From :func:`screwkit.papers.paper_004_surfaces.actuation_singularity_surface`, e.g. at
        ``+φ`` and ``-φ``.
    ax : 3-D matplotlib axes, optional
        Default: a new figure with ``projection="3d"``.
    wireframe : int
        Latitudes of the region's wireframe (twice as many meridians); 0 draws none.
    alpha : float
        Opacity of the surfaces.

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D
        One ``Poly3DCollection`` per surface with triangles (its label ``"φ = +75°"``), the
        wireframe, a legend.

    Raises
    ------
    ScrewkitTypeError
        If a surface lacks ``triangles``, ``phi``, ``robot`` or ``region``, or ``ax`` is not 3-D.
    ScrewkitValueError
        If there is no surface, or triangles are not of shape ``(m, 3, 3)``.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import numpy as np
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.papers.paper_004_surfaces import actuation_singularity_surface
    >>> from screwkit.papers.paper_004_table4 import TABLE_4_CONE
    >>> quattro = load_mechanism("quattro")
    >>> pair = [actuation_singularity_surface(quattro, angle, TABLE_4_CONE, grid=10)
    ...         for angle in (np.pi / 2, -np.pi / 2)]
    >>> ax = plot_singularity_surfaces(pair)
    >>> [text.get_text() for text in ax.get_legend().get_texts()]
    ['φ = +90°', 'φ = -90°', 'workspace']
    """
    ax = _new_axes(ax, three_d=True)
    # one surface is drawn as a list of one
    items: list[Any] = [surfaces] if hasattr(surfaces, "triangles") else list(surfaces)
    if not items:
        raise ScrewkitValueError("Expected at least one surface to draw, got none.")
    handles: list[Any] = []
    regions = []
    for index, surface in enumerate(items):
        try:
            triangles = np.asarray(surface.triangles, dtype=float)
            phi, robot = float(surface.fixed["phi"]), str(surface.mechanism)
            regions.append(surface.region)
        except (AttributeError, KeyError, TypeError) as err:
            raise ScrewkitTypeError(
                "Expected each surface to have triangles, fixed (with phi), mechanism and region (a "
                f"screwkit.analysis.loci.SingularSurface), got {type(surface).__name__}: {err}."
            ) from err
        if triangles.ndim != 3 or triangles.shape[1:] != (3, 3):
            raise ScrewkitValueError(
                f"Expected surfaces[{index}].triangles of shape (m, 3, 3), got {triangles.shape}."
            )
        colour = SURFACE_COLOURS[index % len(SURFACE_COLOURS)]
        label = f"φ = {np.degrees(phi):+.4g}°"
        if len(triangles):
            shades = _shaded(colour, triangles)  # edges in the face colour: no seams between triangles
            ax.add_collection3d(
                Poly3DCollection(triangles, facecolors=shades, edgecolors=shades, linewidths=0.3, alpha=alpha,
                                 label=label)
            )
        else:
            label += ": none in the region"
        handles.append(Patch(facecolor=colour, alpha=alpha, label=label))
    first = regions[0]
    lower, upper = np.array(first.lower, dtype=float), np.array(first.upper, dtype=float)
    if wireframe:
        x, y, z = first.boundary(wireframe)
        ax.plot_wireframe(x, y, z, color="tab:blue", linewidth=0.4, alpha=0.45)
        handles.append(Line2D([], [], color="tab:blue", linewidth=0.8, label="workspace"))
    for limits, low, high in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lower, upper, strict=True):
        limits(low, high)
    ax.set_box_aspect(tuple(np.maximum(upper - lower, 1e-9 * np.max(upper - lower))))
    for name, labeller in zip("xyz", (ax.set_xlabel, ax.set_ylabel, ax.set_zlabel), strict=True):
        labeller(name)
    ax.set_title(f"{robot}: actuation singularity loci", fontsize=10)
    ax.legend(handles=handles, loc="upper left", fontsize=8)
    return ax


# the wrench diagram in 3-D -----------------------------------------------------------------------
def _unit(v: Array) -> Array:
    return v / np.linalg.norm(v)


def _chord(point: Array, direction: Array, centre: Array, radius: float) -> Array:
    """The two ends of the line through ``point`` along ``direction`` on the sphere (centre, radius)."""
    u = _unit(direction)
    offset = point - centre
    along = float(u @ offset)
    half = np.sqrt(max(along**2 - float(offset @ offset) + radius**2, 0.0))
    return np.array([point + (-along - half) * u, point + (-along + half) * u])


def plot_wrench_diagram(diagram: Any, *, ax: Any = None, radius: float | None = None) -> Any:
    """Draw a wrench diagram in 3-D (see the module docstring for what stands for what).

    Parameters
    ----------
    diagram : WrenchDiagram
        Its ``points`` (labels), ``lines`` (pairs of labels), ``line_names``, ``roles`` and
        ``coordinates`` (``{label: (x, y, z, w)}``, directions with ``w = 0``).
    ax : 3-D matplotlib axes, optional
        Default: a new figure with ``projection="3d"``.
    radius : float, optional
        Radius of the sphere, about the centre of the finite points, on which arrows end and lines
        at infinity are drawn; default 1.25 × the largest distance of a finite point from the centre
        (1 if there is none).

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D
        One line per diagram line (label ``"ab: actuation A1"``, one colour each; actuation lines
        solid, finite constraint lines dash-dotted, lines at infinity dashed circles), one text per
        point, one arrow per point at infinity.

    Raises
    ------
    ScrewkitValueError
        If a line's point has no coordinates at this pose (the diagram is degenerate; its reasons
        are given).
    DegenerateGeometryError
        If a line at infinity is given by two parallel directions.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from screwkit.robots.catalog import load_mechanism
    >>> diagram, _ = load_mechanism("h4").wrench_diagram()
    >>> ax = plot_wrench_diagram(diagram)
    >>> [line.get_label() for line in ax.lines][-2:]
    ['ij: constraint of the leg through A1, A4', 'kj: constraint of the leg through A2, A3']
    """
    ax = _new_axes(ax, three_d=True)
    coordinates = {k: np.asarray(v, dtype=float) for k, v in diagram.coordinates.items()}
    missing = sorted({label for line in diagram.lines for label in line} - set(coordinates))
    if missing:
        raise ScrewkitValueError(
            f"Expected coordinates for every point of the diagram, got none for {', '.join(missing)}: "
            + ("; ".join(diagram.degenerate) or "no reason given")
        )
    finite = {k: v[:3] / v[3] for k, v in coordinates.items() if v[3] != 0}
    infinite = {k: _unit(v[:3]) for k, v in coordinates.items() if v[3] == 0}
    centre = np.mean(list(finite.values()), axis=0) if finite else np.zeros(3)
    if radius is None:
        spread = max((float(np.linalg.norm(p - centre)) for p in finite.values()), default=0.0)
        radius = 1.25 * spread if spread > 0 else 1.0
    elif not radius > 0:
        raise ScrewkitValueError(f"Expected `radius` > 0, got {radius!r}.")
    palette = [f"C{k}" for k in range(10)]  # the default colour cycle
    for index, ((p, q), name, role) in enumerate(
        zip(diagram.lines, diagram.line_names, diagram.roles, strict=True)
    ):
        style = {
            "color": palette[index % len(palette)],
            "linestyle": "-" if role == "actuation" else "-.",
            "label": f"{p}{q}: {name}",
        }
        if p in infinite and q in infinite:
            normal = np.cross(infinite[p], infinite[q])
            if np.linalg.norm(normal) < 1e-9:
                raise DegenerateGeometryError(
                    f"line {p}{q} ({name}): its two points at infinity are the same direction"
                )
            first = infinite[p]
            second = _unit(np.cross(_unit(normal), first))
            angle = np.linspace(0, 2 * np.pi, 121)[:, None]
            circle = centre + radius * (np.cos(angle) * first + np.sin(angle) * second)
            ax.plot(*circle.T, **{**style, "linestyle": "--"})
            continue
        start = finite[p] if p in finite else finite[q]
        other = q if p in finite else p
        direction = finite[other] - start if other in finite else infinite[other]
        if np.linalg.norm(direction) == 0:
            raise DegenerateGeometryError(f"line {p}{q} ({name}): its two points coincide")
        ax.plot(*_chord(start, direction, centre, radius).T, **style)
    for label, point in finite.items():
        ax.scatter(*point, color="black", s=12)
        ax.text(*point, f" {label}", fontsize=9)
    for label, direction in infinite.items():
        ax.quiver(*centre, *(radius * direction), color="0.45", arrow_length_ratio=0.08, linewidth=0.8)
        ax.text(*(centre + 1.08 * radius * direction), f"{label}∞", fontsize=9, color="0.3")
    ax.set_xlim(centre[0] - radius, centre[0] + radius)
    ax.set_ylim(centre[1] - radius, centre[1] + radius)
    ax.set_zlim(centre[2] - radius, centre[2] + radius)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(f"wrench diagram {diagram.line_text()}")
    ax.legend(loc="upper left", fontsize=7)
    return ax


# the twist graph ---------------------------------------------------------------------------------
def _layers(graph: Any) -> dict[Any, tuple[float, float]]:
    """Positions: the distance from the base (undirected) upwards; within a layer, the order of
    the mean position of the neighbours one layer down (one barycentric sweep)."""
    base = graph.graph["base"]
    depth = {base: 0}
    queue = deque([base])
    while queue:
        node = queue.popleft()
        for other in sorted(set(graph.successors(node)) | set(graph.predecessors(node)), key=str):
            if other not in depth:
                depth[other] = depth[node] + 1
                queue.append(other)
    for node in graph.nodes:  # links not connected to the base (a graph check refuses those)
        depth.setdefault(node, max(depth.values()) + 1)
    position: dict[Any, tuple[float, float]] = {}
    for level in range(max(depth.values()) + 1):
        members = [n for n in graph.nodes if depth[n] == level]

        def below(node: Any, level: int = level) -> float:
            near = [
                position[n][0]
                for n in set(graph.successors(node)) | set(graph.predecessors(node))
                if depth[n] == level - 1
            ]
            return float(np.mean(near)) if near else 0.0

        members.sort(key=below)
        for index, node in enumerate(members):
            position[node] = (index - (len(members) - 1) / 2, float(level))
    return position


def plot_twist_graph(
    graph: Any, *, ax: Any = None, joint_key: str = "joint", edge_labels: str | None = "name"
) -> Any:
    """Draw a twist graph: links as labelled boxes, one arrow per joint.

    Links are layered by their distance from the base (base at the bottom); an arrow ``u → v``
    carries the twists of ``v`` relative to ``u`` (:mod:`screwkit.graphs.twistgraph`); parallel joints
    between two links are drawn as arcs. Actuated joints are bold orange, virtual joints (an
    equivalent twist graph, paper 002 Fig. 3) dashed grey.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (checked with :func:`screwkit.graphs.twistgraph.check_twist_graph`).
    ax : matplotlib.axes.Axes, optional
    joint_key : str, default "joint"
        The edge attribute holding the :class:`~screwkit.graphs.joints.Joint`.
    edge_labels : {"name", "type", None}, default "name"
        What to write on each arrow: the joint's name, its type (``R``, ``S``, ``vP``...), or nothing.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax.patches`` holds one arrow per joint; ``ax.texts`` the link names, then the edge labels.

    Raises
    ------
    TwistGraphError
        If ``graph`` is not a valid twist graph.
    ScrewkitValueError
        For an unknown ``edge_labels``.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from screwkit.graphs.joints import prismatic, revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("ground", "slider", [
    ...     ("ground", "arm", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("arm", "slider", prismatic("P1", [1, 0, 0])),
    ... ])
    >>> ax = plot_twist_graph(G)
    >>> [t.get_text() for t in ax.texts]
    ['ground', 'arm', 'slider', 'R1', 'P1']
    """
    if edge_labels not in ("name", "type", None):
        raise ScrewkitValueError(f"Expected `edge_labels` to be 'name', 'type' or None, got {edge_labels!r}.")
    check_twist_graph(graph, joint_key=joint_key)
    ax = _new_axes(ax)
    position = _layers(graph)
    base, platform = graph.graph["base"], graph.graph["platform"]
    for node, (x, y) in position.items():
        colour = "0.35" if node == base else "gold" if node == platform else "white"
        ax.text(
            x,
            y,
            str(node),
            ha="center",
            va="center",
            fontsize=8,
            color="white" if node == base else "black",
            bbox={"boxstyle": "round", "facecolor": colour, "edgecolor": "0.3"},
            zorder=3,
        )
    seen: dict[frozenset[Any], int] = {}
    counts: dict[frozenset[Any], int] = {}
    for u, v in graph.edges():
        counts[frozenset((u, v))] = counts.get(frozenset((u, v)), 0) + 1
    labels = []
    for u, v, key, joint in graph.edges(keys=True, data=joint_key):
        pair = frozenset((u, v))
        index = seen.get(pair, 0)
        seen[pair] = index + 1
        rad = 0.0 if counts[pair] == 1 else 0.3 * (index - (counts[pair] - 1) / 2)
        start, end = np.array(position[u]), np.array(position[v])
        virtual = bool(getattr(joint, "virtual", False))
        actuated = bool(getattr(joint, "actuated", False))
        ax.add_patch(
            FancyArrowPatch(
                tuple(start),
                tuple(end),
                arrowstyle="-|>",
                mutation_scale=10,
                connectionstyle=f"arc3,rad={rad}",
                shrinkA=12,
                shrinkB=12,
                linestyle="--" if virtual else "-",
                linewidth=2.2 if actuated else 1.0,
                color="tab:orange" if actuated else "0.5" if virtual else "0.15",
                zorder=2,
            )
        )
        if edge_labels is not None:
            chord = end - start
            middle = (start + end) / 2 + rad / 2 * np.array([chord[1], -chord[0]])
            labels.append((middle, str(key) if edge_labels == "name" else str(joint.type)))
    for middle, text in labels:
        ax.text(
            *middle,
            text,
            ha="center",
            va="center",
            fontsize=6,
            color="0.1",
            bbox={"boxstyle": "square,pad=0.1", "facecolor": "white", "edgecolor": "none", "alpha": 0.8},
        )
    xs = [p[0] for p in position.values()]
    ys = [p[1] for p in position.values()]
    ax.set_xlim(min(xs) - 0.8, max(xs) + 0.8)
    ax.set_ylim(min(ys) - 0.5, max(ys) + 0.5)
    ax.set_axis_off()
    name = graph.graph.get("name")
    ax.set_title(f"twist graph of {name}" if name else "twist graph")
    return ax


def save_map_png(workspace_map: Any, path: str | Path) -> Path:
    """Draw a map (:func:`plot_verdicts` for a ``"verdict"`` map, else :func:`plot_map`'s
    isocontours; angles stored in radians drawn in degrees) and write it as a PNG.

    What ``screwkit map ... --out FILE.png`` writes: a map is data
    (:class:`screwkit.analysis.workspace.WorkspaceMap`), drawn here. The figure is drawn off screen
    (a :class:`matplotlib.figure.Figure` of its own: pyplot's backend and figures are left alone).

    Parameters
    ----------
    workspace_map : WorkspaceMap
    path : str or pathlib.Path
        The PNG file to write.

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from screwkit.analysis.workspace import grid_map
    >>> from screwkit.robots.catalog import load_mechanism
    >>> m = grid_map(load_mechanism("h4"), "verdict", x=("z", -900, -600, 3), y=("phi", -0.2, 0.2, 3))
    >>> save_map_png(m, pathlib.Path(tempfile.mkdtemp()) / "m.png").stat().st_size > 0
    True
    """
    from matplotlib.figure import Figure

    target = Path(path)
    in_radians = tuple(n for n, unit in workspace_map.units.items() if unit == "rad")  # drawn in degrees
    figure = Figure(figsize=(7, 5.5))
    ax = figure.subplots()
    if workspace_map.quantity == "verdict":  # the plot takes codes 0..7; out of reach is the mask's to say
        drawn = dataclasses.replace(
            workspace_map, values=np.where(workspace_map.reachable, workspace_map.values, 0)
        )
        plot_verdicts(drawn, ax=ax, degrees=in_radians)
    else:
        plot_map(workspace_map, ax=ax, degrees=in_radians)
    figure.savefig(target, dpi=120, bbox_inches="tight")
    return target
