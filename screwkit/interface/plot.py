"""Drawings over the pose space with matplotlib: index maps, verdict maps, singularity surfaces.

matplotlib is an optional dependency (the extra ``plot``: ``pip install "screwkit[plot]"``); it is
imported through :mod:`screwkit.interface._matplotlib`, and ``import screwkit`` never imports this
module. Without matplotlib, ``import screwkit.interface.plot`` raises
:class:`~screwkit.exceptions.MissingDependencyError` naming the extra. The drawings of one
configuration (its wrench diagram and its twist graph) are in :mod:`screwkit.interface.plot_diagrams`.

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
  :attr:`screwkit.core.verdicts.SingularityReport.codes`, bit 1 constraint, 2 actuation, 4 serial, or
  the verdict strings).

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> from types import SimpleNamespace
>>> codes = np.array([[0, 0, 2], [0, 4, 2]])     # regular, serial, actuation
>>> m = SimpleNamespace(quantity="verdict", x_name="x", x_values=np.arange(3.0), y_name="y",
...                     y_values=np.arange(2.0), values=codes, reachable=np.ones(codes.shape, bool), fixed={})
>>> ax = plot_verdicts(m)
>>> [t.get_text() for t in ax.get_legend().get_texts()]
['regular', 'actuation singularity', 'serial singularity']
"""

from __future__ import annotations

import dataclasses
from collections.abc import Collection, Iterable
from pathlib import Path
from typing import Any

import numpy as np

from ..analysis.quantities import display
from ..core.verdicts import LABELS
from ..exceptions import ScrewkitError, ScrewkitTypeError, ScrewkitValueError
from ._matplotlib import (
    BoundaryNorm,
    Figure,
    Line2D,
    ListedColormap,
    MaxNLocator,
    Patch,
    Poly3DCollection,
    TwoSlopeNorm,
    new_axes,
    to_rgba,
)

__all__ = [
    "DIVERGING_CMAP",
    "KIND_COLOURS",
    "SEQUENTIAL_CMAP",
    "SURFACE_COLOURS",
    "UNREACHABLE_COLOUR",
    "VERDICT_COLOURS",
    "plot_map",
    "plot_singularity_surfaces",
    "plot_verdicts",
    "save_map_png",
]

Array = np.ndarray

#: Colour of each kind of singularity locus.
KIND_COLOURS = {"constraint": "tab:red", "actuation": "tab:blue", "serial": "tab:green", "reach": "black"}
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
#: The colour maps of :func:`plot_map`: sequential for a quantity of one sign, diverging (centred at 0)
#: for a signed one (:attr:`screwkit.analysis.quantities.QuantityDisplay.signed`).
SEQUENTIAL_CMAP, DIVERGING_CMAP = "viridis", "RdBu_r"
#: Colours of the surfaces of :func:`plot_singularity_surfaces`, in turn.
SURFACE_COLOURS = ("tab:orange", "tab:purple", "tab:green", "tab:red", "tab:brown", "tab:pink")


def _verdict_name(code: int) -> str:
    names = [name for bit, name in enumerate(LABELS) if code >> bit & 1]
    return " + ".join(names) + " singularity" if names else "regular"



# maps --------------------------------------------------------------------------------------------
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


def _units_of_map(workspace_map: Any) -> tuple[str, int]:
    """The map's length unit (the unit of a coordinate that is not an angle) and its number of angle
    coordinates (``units``: one entry per pose coordinate); ``("", 0)`` without units."""
    units = getattr(workspace_map, "units", None) or {}
    if not isinstance(units, dict):
        return "", 0
    lengths = [str(u) for u in units.values() if u not in ("rad", "deg")]
    return (lengths[0] if lengths else ""), sum(u in ("rad", "deg") for u in units.values())


def _same_scale(ax: Any, workspace_map: Any, degrees: Collection[str]) -> None:
    """Equal scale on both axes when both are lengths in the same unit (a spatial slice)."""
    x_unit = _unit_of(workspace_map, str(workspace_map.x_name), degrees)
    y_unit = _unit_of(workspace_map, str(workspace_map.y_name), degrees)
    if x_unit and x_unit == y_unit and x_unit not in ("rad", "deg"):
        ax.set_aspect("equal", adjustable="box")


def _legend_outside(ax: Any, handles: list[Any] | None = None) -> None:
    """The legend below the axes, off the data."""
    chosen = handles if handles is not None else ax.get_legend_handles_labels()[0]
    if chosen:
        ax.legend(
            handles=chosen, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize=7, frameon=False
        )


def _display_of(name: str) -> Any:
    """The quantity's display (:func:`screwkit.analysis.quantities.display`), or None for a name
    screwkit does not know (a map made elsewhere): then drawn under its own name, unsigned."""
    try:
        return display(name)
    except ScrewkitError:
        return None


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
    cmap: str | None = None,
) -> Any:
    """Isocontours of a map's quantity over its grid, with singularity loci overlaid.

    The style of paper 004, Figs. 8–13 (LTI isocontours over the workspace at a fixed orientation),
    with the loci of its Figs. 14–16 drawn on top, one colour per kind (:data:`KIND_COLOURS`).
    Unreachable grid points (``~reachable``) and non-finite values are left blank, on a grey
    background. The colour bar names the quantity by its symbol, words and unit
    (:func:`screwkit.analysis.quantities.display`: ``η`` for the LTI, ``det A`` with its length
    power); a signed quantity (``det_A``, ``det_B``, ``condition:K``) gets a diverging colour map
    centred at zero and its zero level drawn bold; a slice over two lengths of one unit is drawn at
    equal scale; the legend of the loci sits below the axes.

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
    cmap : str, optional
        Default: :data:`DIVERGING_CMAP` for a signed quantity, else :data:`SEQUENTIAL_CMAP`.

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
    >>> lti = plot_map(SimpleNamespace(**{**vars(m), "quantity": "lti"}))
    >>> lti.get_title(), lti.figure.axes[-1].get_ylabel()
    ('$\\\\eta$, local transmission index at z = -800', '$\\\\eta$, local transmission index (dimensionless)')
    """
    ax = new_axes(ax)
    x, y, reachable, x_label, y_label = _grid(workspace_map, degrees)
    values = np.asarray(workspace_map.values, dtype=float)
    shown = np.ma.masked_where(~reachable | ~np.isfinite(values), values)
    if shown.count() == 0:
        raise ScrewkitValueError(
            f"Expected `workspace_map` to have a finite value at a reachable grid point, got none "
            f"(quantity {workspace_map.quantity!r})."
        )
    ax.set_facecolor(UNREACHABLE_COLOUR)
    info = _display_of(str(workspace_map.quantity))
    signed = info is not None and info.signed
    length_unit, angle_count = _units_of_map(workspace_map)
    label = str(workspace_map.quantity) if info is None else info.axis_label(length_unit, angle_count)
    name = str(workspace_map.quantity) if info is None else f"{info.symbol}, {info.label}"
    chosen: Any = levels if isinstance(levels, int) else np.asarray(list(levels), dtype=float)
    norm = None
    if signed:  # centred at zero: equal colour steps either side of the zero level
        bound = float(np.max(np.abs(shown)))
        norm = TwoSlopeNorm(0.0, -bound, bound) if bound > 0 else None
        if isinstance(chosen, int) and bound > 0:  # levels over the data, zero among them when crossed
            chosen = MaxNLocator(chosen, symmetric=False).tick_values(float(shown.min()), float(shown.max()))
    colours = cmap or (DIVERGING_CMAP if signed else SEQUENTIAL_CMAP)
    if filled:
        fill = ax.contourf(x, y, shown, levels=chosen, cmap=colours, norm=norm, extend="both")
        ax.figure.colorbar(fill, ax=ax, label=label)  # ax's, not pyplot's current
        chosen = fill.levels
    lines = ax.contour(x, y, shown, levels=chosen, colors="black", linewidths=0.6)
    ax.clabel(lines, fmt="%.3g", fontsize=7)
    if signed and shown.min() < 0 < shown.max():
        ax.contour(x, y, shown, levels=[0.0], colors="black", linewidths=2.0)
        ax.plot([], [], color="black", linewidth=2.0, label=f"{info.symbol} = 0")
    _draw_loci(ax, workspace_map, loci, degrees)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    _same_scale(ax, workspace_map, degrees)
    ax.set_title(_title(workspace_map, name, degrees), fontsize=10)
    _legend_outside(ax)
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
        4 serial; :attr:`screwkit.core.verdicts.SingularityReport.codes`) or the verdict strings;
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
    ax = new_axes(ax)
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
    _legend_outside(ax, handles + ax.get_legend_handles_labels()[0])
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    _same_scale(ax, workspace_map, degrees)
    # a map of one category says so (no scale of one colour)
    what = f"every reachable grid pose {_verdict_name(present[0])}" if len(present) == 1 else "verdicts"
    ax.set_title(_title(workspace_map, what, degrees), fontsize=10)
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
    surfaces: Iterable[Any],
    *,
    ax: Any = None,
    wireframe: int = 16,
    alpha: float = 0.85,
    length_unit: str = "mm",
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
    length_unit : str, default "mm"
        The unit of the triangles' coordinates, on the axes (the mechanism's: mm for paper 004's robots).

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
    >>> from screwkit.papers.paper_004_surfaces import actuation_singularity_surface
    >>> from screwkit.papers.paper_004_table4 import TABLE_4_CONE
    >>> quattro = load_mechanism("quattro")
    >>> pair = [actuation_singularity_surface(quattro, angle, TABLE_4_CONE, grid=10)
    ...         for angle in (np.pi / 2, -np.pi / 2)]
    >>> ax = plot_singularity_surfaces(pair)
    >>> [text.get_text() for text in ax.get_legend().get_texts()]
    ['φ = +90°', 'φ = -90°', 'workspace']
    """
    ax = new_axes(ax, three_d=True)
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
        labeller(f"{name} ({length_unit})" if length_unit else name)
    ax.set_title(f"{robot}: actuation singularity loci", fontsize=10)
    ax.legend(handles=handles, loc="upper left", fontsize=8)
    return ax


def save_map_png(workspace_map: Any, path: str | Path) -> Path:
    """Draw a map (:func:`plot_verdicts` for a ``"verdict"`` map, else :func:`plot_map`'s
    isocontours; angles stored in radians drawn in degrees) with its loci over it, and write it
    as a PNG.

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
    >>> m = grid_map(load_mechanism("h4"), "verdict", x=("z", -900, -600, 3), y=("phi", -0.2, 0.2, 3))
    >>> save_map_png(m, pathlib.Path(tempfile.mkdtemp()) / "m.png").stat().st_size > 0
    True
    """
    target = Path(path)
    in_radians = tuple(n for n, unit in workspace_map.units.items() if unit == "rad")  # drawn in degrees
    figure = Figure(figsize=(7, 5.5))
    ax = figure.subplots()
    if workspace_map.quantity == "verdict":  # the plot takes codes 0..7; out of reach is the mask's to say
        drawn = dataclasses.replace(
            workspace_map, values=np.where(workspace_map.reachable, workspace_map.values, 0)
        )
        plot_verdicts(drawn, ax=ax, degrees=in_radians, loci=workspace_map.loci)
    else:
        plot_map(workspace_map, ax=ax, degrees=in_radians, loci=workspace_map.loci)
    figure.savefig(target, dpi=120, bbox_inches="tight")
    return target
