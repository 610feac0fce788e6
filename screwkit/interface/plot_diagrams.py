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

__all__ = ["plot_twist_graph", "plot_wrench_diagram"]

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
    >>> diagram, _ = load_mechanism("h4").wrench_diagram()
    >>> ax = plot_wrench_diagram(diagram)
    >>> [line.get_label() for line in ax.lines][-2:]
    ['ij: constraint of the leg through A1, A4', 'kj: constraint of the leg through A2, A3']
    """
    ax = new_axes(ax, three_d=True)
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
