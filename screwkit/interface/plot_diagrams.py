"""Drawings of one configuration with matplotlib: its wrench diagram in 3-D and its twist graph.

matplotlib is an optional dependency, imported through :mod:`screwkit.interface._matplotlib`
(without it, importing this module raises :class:`~screwkit.exceptions.MissingDependencyError`
naming the extra ``plot``); the drawings over the pose space are in :mod:`screwkit.interface.plot`.
Each function draws into the axes it is given (``ax=``) or into a new figure, and returns the axes;
the objects drawn are read by their attributes only (duck typing):

* :func:`plot_wrench_diagram`: a :class:`~screwkit.gca.diagram.WrenchDiagram` in 3-D: finite points as
  labelled dots, points at infinity as labelled arrows (directions) from the centre of the finite
  points, each finite line through its two points, and each line at infinity (a pure couple) as a
  dashed circle of the plane spanned by its two directions: the limit of ever larger circles of a
  plane is that plane's line at infinity (gca.md §1), so the circle stands for it;
* :func:`plot_wrench_diagram_schematic`: the same diagram as a schematic projective view in the
  style of paper 002's Fig. 4c: finite points as labelled dots seen along the direction they spread
  least in (``z`` kept upwards), the border circle standing for the plane at infinity, each point
  at infinity a labelled open dot on the border in its direction, each line drawn through its two
  points (to the border towards its point at infinity), each line at infinity as a dashed arc of
  the border between its two points;
* :func:`plot_twist_graph`: a twist graph (:mod:`screwkit.graphs.twistgraph`), links layered by their
  distance from the base, one arrow per joint (``u → v``), actuated joints bold, virtual joints
  (an equivalent twist graph's, paper 002 Fig. 3) dashed.

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> from screwkit.interface.plot_diagrams import plot_twist_graph
>>> ax = plot_twist_graph(load_mechanism("h4").twist_graph())
>>> len(ax.patches)                      # one arrow per joint of the H4
22
"""

from __future__ import annotations

from collections import deque
from typing import Any

import numpy as np

from ..exceptions import DegenerateGeometryError, ScrewkitValueError
from ..graphs.twistgraph import check_twist_graph
from ._matplotlib import FancyArrowPatch, new_axes

__all__ = ["plot_twist_graph", "plot_wrench_diagram", "plot_wrench_diagram_schematic"]

Array = np.ndarray


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


def _points(diagram: Any) -> tuple[dict[str, Array], dict[str, Array]]:
    """The diagram's finite points (3-D) and points at infinity (unit directions), every point of a
    line present (else the reasons the diagram is degenerate here)."""
    coordinates = {k: np.asarray(v, dtype=float) for k, v in diagram.coordinates.items()}
    missing = sorted({label for line in diagram.lines for label in line} - set(coordinates))
    if missing:
        raise ScrewkitValueError(
            f"Expected coordinates for every point of the diagram, got none for {', '.join(missing)}: "
            + ("; ".join(diagram.degenerate) or "no reason given")
        )
    finite = {k: v[:3] / v[3] for k, v in coordinates.items() if v[3] != 0}
    infinite = {k: _unit(v[:3]) for k, v in coordinates.items() if v[3] == 0}
    return finite, infinite


def _line_styles(diagram: Any) -> list[dict[str, Any]]:
    """One colour per line (the default cycle); actuation solid, constraint dash-dotted."""
    palette = [f"C{k}" for k in range(10)]
    return [
        {
            "color": palette[index % len(palette)],
            "linestyle": "-" if role == "actuation" else "-.",
            "label": f"{p}{q}: {name}",
        }
        for index, ((p, q), name, role) in enumerate(
            zip(diagram.lines, diagram.line_names, diagram.roles, strict=True)
        )
    ]


def _coincident(diagram: Any, finite: dict[str, Array], infinite: dict[str, Array]) -> dict[int, int]:
    """Lines that are the same line as an earlier one (index -> earlier index): drawn offset, else one
    would hide the other. Two lines coincide when the four points are collinear (projective rank 2)."""

    def homogeneous(label: str) -> Array:
        return np.append(finite[label], 1.0) if label in finite else np.append(infinite[label], 0.0)

    scale = max((float(np.linalg.norm(p)) for p in finite.values()), default=1.0) or 1.0
    same: dict[int, int] = {}
    for later, line in enumerate(diagram.lines):
        for earlier in range(later):
            rows = np.array([homogeneous(x) for x in (*diagram.lines[earlier], *line)])
            rows[:, 3] *= scale  # weights in the points' length scale
            singular = np.linalg.svd(rows / np.linalg.norm(rows, axis=1, keepdims=True), compute_uv=False)
            if singular[2] < 1e-9:
                same[later] = earlier
                break
    return same


def plot_wrench_diagram(
    diagram: Any, *, ax: Any = None, radius: float | None = None, length_unit: str = ""
) -> Any:
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
    length_unit : str, optional
        The unit of the coordinates, on the axes (e.g. ``"mm"``).

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D
        One line per diagram line (label ``"ab: actuation A1"``, one colour each; actuation lines
        solid, finite constraint lines dash-dotted, lines at infinity dashed circles), one text per
        point, one arrow per point at infinity. A line that coincides with an earlier one is drawn
        offset by 2 % of the radius, its label saying so, so that neither hides the other.

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
    >>> diagram, _ = load_mechanism("h4").wrench_diagram()
    >>> ax = plot_wrench_diagram(diagram)
    >>> [line.get_label() for line in ax.lines][-2:]
    ['ij: constraint of the leg through A1, A4', 'kj: constraint of the leg through A2, A3']
    """
    ax = new_axes(ax, three_d=True)
    finite, infinite = _points(diagram)
    same = _coincident(diagram, finite, infinite)
    centre = np.mean(list(finite.values()), axis=0) if finite else np.zeros(3)
    if radius is None:
        spread = max((float(np.linalg.norm(p - centre)) for p in finite.values()), default=0.0)
        radius = 1.25 * spread if spread > 0 else 1.0
    elif not radius > 0:
        raise ScrewkitValueError(f"Expected `radius` > 0, got {radius!r}.")
    styles = _line_styles(diagram)
    for index, ((p, q), name, style) in enumerate(
        zip(diagram.lines, diagram.line_names, styles, strict=True)
    ):
        shift = np.zeros(3)
        if index in same:
            p0, q0 = diagram.lines[same[index]]
            style = {**style, "label": style["label"] + f" (the line {p0}{q0}; drawn offset)"}
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
        if index in same:  # offset across the line so that both stay visible
            across = np.cross(direction, [0.0, 0.0, 1.0])
            if np.linalg.norm(across) < 1e-9 * np.linalg.norm(direction):
                across = np.cross(direction, [1.0, 0.0, 0.0])
            shift = 0.02 * radius * _unit(across)
        ax.plot(*(_chord(start, direction, centre, radius) + shift).T, **style)
    for label, point in finite.items():
        ax.scatter(*point, color="black", s=12)
        ax.text(*point, f" {label}", fontsize=9)
    for label, direction in infinite.items():
        ax.quiver(*centre, *(radius * direction), color="0.45", arrow_length_ratio=0.08, linewidth=0.8)
        ax.text(*(centre + 1.08 * radius * direction), f"{label}∞", fontsize=9, color="0.3")
    ax.view_init(*_clearest_view([np.array(line.get_data_3d()).T for line in ax.lines]))
    ax.set_xlim(centre[0] - radius, centre[0] + radius)
    ax.set_ylim(centre[1] - radius, centre[1] + radius)
    ax.set_zlim(centre[2] - radius, centre[2] + radius)
    ax.set_box_aspect((1, 1, 1))
    unit = f" ({length_unit})" if length_unit else ""
    ax.set_xlabel("x" + unit)
    ax.set_ylabel("y" + unit)
    ax.set_zlabel("z" + unit)
    ax.set_title(f"wrench diagram {diagram.line_text()}")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, frameon=False)
    return ax


#: The 3-D views tried for a wrench diagram, (elevation, azimuth) in degrees; matplotlib's default first.
VIEWS_3D = tuple((elev, azim) for elev in (30, 20, 45) for azim in (-60, -30, -120, -150, 30, 60, 120, 150))


def _resampled(path: Array, count: int) -> Array:
    """``count`` points evenly spaced along a polyline ``(m, 3)`` (its vertices' order)."""
    steps = np.linalg.norm(np.diff(path, axis=0), axis=1)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    places = np.linspace(0.0, along[-1], count)
    return np.column_stack([np.interp(places, along, path[:, k]) for k in range(3)])


#: Below this clearance (a fraction of the drawing's size) a line counts as nearly hidden in a view.
CLEAR_VIEW = 0.05


def _clearest_view(paths: list[Array]) -> tuple[float, float]:
    """The view of :data:`VIEWS_3D` in which the drawn lines are farthest from hiding one another: for
    each pair of paths, the largest distance of one's projected points from the other's projected
    polyline; the default view if the least of these over the pairs is at least :data:`CLEAR_VIEW`,
    else the view maximising it."""
    if len(paths) < 2:
        return VIEWS_3D[0]

    def hidden(a: Array, b: Array) -> float:
        gaps = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=-1).min(axis=1)
        return float(gaps.max())

    span = max(float(np.ptp(np.concatenate(paths), axis=0).max()), 1e-12)
    sampled = [_resampled(p, 40) for p in paths]
    best, best_score = VIEWS_3D[0], -1.0
    for elev, azim in VIEWS_3D:  # the default view unless a line is nearly hidden in it
        e, a = np.radians(elev), np.radians(azim)
        right = np.array([-np.sin(a), np.cos(a), 0.0])
        up = np.array([-np.sin(e) * np.cos(a), -np.sin(e) * np.sin(a), np.cos(e)])
        flat = [np.c_[p @ right, p @ up] / span for p in sampled]
        score = min(min(hidden(p, q), hidden(q, p)) for k, p in enumerate(flat) for q in flat[k + 1 :])
        if (elev, azim) == VIEWS_3D[0] and score >= CLEAR_VIEW:
            return VIEWS_3D[0]
        if score > best_score + 1e-3:
            best, best_score = (elev, azim), score
    return best


def _view(finite: dict[str, Array], tilt: tuple[float, float]) -> tuple[Array, Array, Array]:
    """The centre and the in-plane axes ``(u, v)`` of a schematic view: the plane the finite points
    spread most in (normal: their direction of least spread) turned by ``tilt`` along its two axes, so
    that directions differing only along that normal (a symmetric robot has many) do not fall on one
    border point; ``v`` the world ``z`` projected (robots stand upright)."""
    points = np.array(list(finite.values())) if finite else np.zeros((1, 3))
    centre = points.mean(axis=0)
    spread = points - centre
    normal = np.linalg.svd(spread, full_matrices=True)[2][2] if len(points) > 1 else np.array([0.0, 1.0, 0.0])
    u, v = _upright_axes(normal)
    u, v = _upright_axes(_unit(normal + tilt[0] * u + tilt[1] * v))
    return centre, u, v


def _layout(
    diagram: Any, finite: dict[str, Array], infinite: dict[str, Array], tilt: tuple[float, float]
) -> Any:
    """The schematic's 2-D places: finite points inside the unit disc, points at infinity as angles
    on its border (those along the view at the bottom, listed), each finite line's segment."""
    centre, u, v = _view(finite, tilt)
    flat = {k: np.array([(p - centre) @ u, (p - centre) @ v]) for k, p in finite.items()}
    reach = max((float(np.linalg.norm(p)) for p in flat.values()), default=0.0)
    flat = {k: 0.55 * p / reach if reach > 0 else p for k, p in flat.items()}  # the border has radius 1
    border, along_view = {}, []
    for label, direction in infinite.items():
        seen = np.array([direction @ u, direction @ v])
        if np.linalg.norm(seen) < 1e-6:
            seen = np.array([0.0, -1.0])
            along_view.append(label)
        border[label] = float(np.arctan2(seen[1], seen[0]))
    segments = {}
    for p, q in diagram.lines:
        if p in border and q in border:
            continue
        start, other = (flat[p], q) if p in flat else (flat[q], p)
        if other in flat:  # through both finite points, to the border both ways
            segments[p + q] = _chord2(start, flat[other] - start)
        else:
            segments[p + q] = np.array([start, [np.cos(border[other]), np.sin(border[other])]])
    return flat, border, along_view, segments


def _clearance(layout: Any) -> float:
    """How readable a layout is: the least distance between two points (border points by their
    chord) or between a finite point and a drawn line it is not on."""
    flat, border, _, segments = layout
    places = list(flat.values()) + [np.array([np.cos(a), np.sin(a)]) for a in border.values()]
    gaps = [float(np.linalg.norm(a - b)) for k, a in enumerate(places) for b in places[k + 1 :]]
    for name, (start, end) in segments.items():
        step = end - start
        for label, point in flat.items():
            if label in name or not step.any():
                continue
            t = np.clip((point - start) @ step / (step @ step), 0.0, 1.0)
            gaps.append(float(np.linalg.norm(point - (start + t * step))))
    return min(gaps, default=1.0)


#: The tilts tried for the schematic view (the most readable one is drawn, :func:`_clearance`).
VIEW_TILTS = tuple((a, b) for a in (0.2, 0.35, 0.5, -0.2, -0.35, -0.5) for b in (0.15, 0.3, -0.15, -0.3))


def _upright_axes(normal: Array) -> tuple[Array, Array]:
    """Axes ``(u, v)`` of the plane normal to ``normal``, ``v`` the world ``z`` projected (``y`` when
    ``z`` is along the normal)."""
    up = np.array([0.0, 0.0, 1.0]) - normal[2] * normal
    if np.linalg.norm(up) < 1e-6:
        up = np.array([0.0, 1.0, 0.0]) - normal[1] * normal
    v = _unit(up)
    return _unit(np.cross(v, normal)), v


def plot_wrench_diagram_schematic(diagram: Any, *, ax: Any = None) -> Any:
    """Draw a wrench diagram as a schematic projective view (paper 002, Fig. 4c style; the module
    docstring says what stands for what).

    A schematic, not a metric drawing: the finite points are projected orthographically on the
    plane they spread most in and scaled to the inner part of the disc; a point at infinity sits on
    the border in the direction its projection points (a direction along the view is put at the
    bottom of the border and said so in its label).

    Parameters
    ----------
    diagram : WrenchDiagram
        As for :func:`plot_wrench_diagram`.
    ax : matplotlib.axes.Axes, optional
        2-D axes; default: a new figure.

    Returns
    -------
    matplotlib.axes.Axes
        One line (or border arc) per diagram line, labelled ``"ab: actuation A1"``; one text per point.

    Raises
    ------
    ScrewkitValueError
        If a line's point has no coordinates at this pose.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> diagram, _ = load_mechanism("h4").wrench_diagram()
    >>> ax = plot_wrench_diagram_schematic(diagram)
    >>> [line.get_label() for line in ax.lines][1:3], sorted(t.get_text() for t in ax.texts)[:3]
    (['ab: actuation A1', 'cd: actuation A4'], ['a', 'b', 'c'])
    """
    ax = new_axes(ax)
    finite, infinite = _points(diagram)
    flat, border, along_view, segments = max(
        (_layout(diagram, finite, infinite, tilt) for tilt in VIEW_TILTS), key=_clearance
    )
    drawn_at_infinity: list[tuple[str, str]] = []
    turn = np.linspace(0, 2 * np.pi, 241)
    ax.plot(np.cos(turn), np.sin(turn), color="0.6", linewidth=0.8, label="_the plane at infinity")
    for (p, q), style in zip(diagram.lines, _line_styles(diagram), strict=True):
        if p in border and q in border:  # a line at infinity: an arc outside the border, its own radius
            low, high = sorted((border[p], border[q]))
            if high - low > np.pi:
                low, high = high, low + 2 * np.pi
            level = 1.0 + 0.07 * (1 + sum(1 for a, b in drawn_at_infinity))
            drawn_at_infinity.append((p, q))
            arc = np.linspace(low, high, 60)
            path = np.concatenate(
                [
                    [[np.cos(low), np.sin(low)]],
                    level * np.c_[np.cos(arc), np.sin(arc)],
                    [[np.cos(high), np.sin(high)]],
                ]
            )
            ax.plot(*path.T, **{**style, "linestyle": "--"})
            continue
        ends = segments[p + q]
        ax.plot(*ends.T, **style)
    for label, point in flat.items():
        ax.plot(*point, "o", color="black", markersize=4, label="_" + label)
        ax.annotate(label, point, xytext=(4, 4), textcoords="offset points", fontsize=10)
    together: dict[float, list[str]] = {}  # the same point at infinity under two labels: one mark
    for label, angle in border.items():
        together.setdefault(round(angle % (2 * np.pi), 6), []).append(label)
    for angle, labels in together.items():
        place = np.array([np.cos(angle), np.sin(angle)])
        ax.plot(
            *place, "o", markerfacecolor="white", markeredgecolor="black", markersize=6, label="_" + labels[0]
        )
        text = " = ".join(labels) + (" (along the view)" if set(labels) & set(along_view) else "")
        ax.annotate(
            text,
            place,
            xytext=tuple(17 * place),
            textcoords="offset points",
            ha="center",
            va="center",
            fontsize=10,
            style="italic",
        )
    ax.set_aspect("equal")
    ax.set_xlim(-1.25, 1.25)
    ax.set_ylim(-1.25, 1.25)
    ax.set_axis_off()
    ax.set_title(f"wrench diagram {diagram.line_text()}", fontsize=10)
    note = "schematic: the circle stands for the plane at infinity"
    ax.text(0.0, -1.2, note, ha="center", fontsize=8, color="0.4")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=7, frameon=False)
    return ax


def _chord2(point: Array, direction: Array) -> Array:
    """The two ends, on the unit circle, of the 2-D line through ``point`` along ``direction``."""
    unit = _unit(direction)
    along = float(unit @ point)
    half = np.sqrt(max(along**2 - float(point @ point) + 1.0, 0.0))
    return np.array([point + (-along - half) * unit, point + (-along + half) * unit])


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
    ax = new_axes(ax)
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
