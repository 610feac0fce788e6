"""Writing twist graphs out: snapshot TOML files, Graphviz DOT and JSON (the twist graph layer, §5).

:func:`save_snapshot` writes any numeric twist graph (a catalog robot at a pose, an equivalent graph,
a graph built in Python) as a snapshot file that :func:`screwkit.load_snapshot` reads back to the
same joint screws (floats are written with ``repr``, which round-trips exactly). :func:`graph_dot`
draws the graph's structure for Graphviz; :func:`graph_json` is :func:`screwkit.graphs.twistgraph.to_data`
as text. The snapshot format is the one documented in :mod:`screwkit.robots.snapshot`.

Joints are written from the data they were built from (``Joint.geometry``). A joint without it (a
joint of a family's joint table, a virtual joint of an equivalent graph, a ``Joint`` made from raw
screws) is written from its screws, in the Plücker conventions of :mod:`screwkit.algebra.screw`: a zero-pitch
screw ``(w; p × w)`` as an ``R`` joint through the axis point nearest the origin ``p = w × v / |w|²``;
a pitch-``h`` screw ``(w; p × w + h w)`` as ``H`` with ``h = w·v / w·w``; ``(0; v)`` as ``P`` (so a
parallelogram ``Pa`` without its hinge and rod directions is written as the ``P`` joint of the same
twist); ``S`` and ``U`` by their axes and the point common to them (``p × w = v`` stacked, least
squares, refused if the lines do not meet); ``C`` by its rotation axis. Such joints read back with
the same screws to rounding (a few ulps), those written from their geometry bit for bit.

Examples
--------
>>> import screwkit as sk
>>> graph = sk.twist_graph("ground", "slider", [
...     ("ground", "slider", sk.prismatic("P1", [1.0, 0.0, 0.0], actuated=True))])
>>> print(snapshot_text(graph))  # doctest: +NORMALIZE_WHITESPACE
# screwkit snapshot (written by screwkit.interface.export.save_snapshot)
[mechanism]
kind = "snapshot"
name = "twist graph"
base = "ground"
platform = "slider"
<BLANKLINE>
[[joints]]
name = "P1"
type = "P"
parent = "ground"
child = "slider"
actuated = true
direction = [1.0, 0.0, 0.0]
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..core.line_search import LINE_RTOL
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from ..graphs.joints import JOINT_FIELDS, Joint
from ..graphs.twistgraph import check_twist_graph, to_data

__all__ = ["graph_dot", "graph_json", "save_snapshot", "snapshot_text"]



def _toml_string(text: str) -> str:
    # A TOML basic string: JSON's escapes are TOML's for every character JSON escapes.
    return json.dumps(text, ensure_ascii=False)


def _toml_float(value: float, where: str) -> str:
    if not math.isfinite(value):
        raise ScrewkitValueError(f"{where}: expected finite numbers to write a snapshot, got {value!r}.")
    return repr(float(value))


def _toml_value(value: Any, where: str) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, int | np.integer):
        return str(int(value))
    if isinstance(value, list | tuple | np.ndarray):
        return "[" + ", ".join(_toml_float(float(v), where) for v in value) + "]"
    return _toml_float(float(value), where)


def _link_name(link: Any, where: str) -> str:
    if not isinstance(link, str | int) or isinstance(link, bool):
        raise ScrewkitTypeError(
            f"{where}: expected link names that are strings or integers to write a snapshot, "
            f"got {type(link).__name__} {link!r}."
        )
    return str(link)


def _common_point(name: str, rows: np.ndarray) -> np.ndarray:
    """The point on every zero-pitch line ``(w; p × w)`` of ``rows``: ``p × w = v`` stacked, least
    squares (one line: the point nearest the origin, ``w × v / |w|²``)."""
    matrix = np.concatenate([np.cross(np.eye(3), w).T for w in rows[:, :3]])  # p ↦ p × w, one per row
    point, *_ = np.linalg.lstsq(matrix, rows[:, 3:].reshape(-1), rcond=None)
    residual = float(np.linalg.norm(matrix @ point - rows[:, 3:].reshape(-1)))
    if residual > LINE_RTOL * float(np.linalg.norm(rows[:, 3:]) + np.linalg.norm(point) + 1e-300):
        raise ScrewkitValueError(
            f"Joint {name!r}: expected axes through one point to write its centre, got axes that miss "
            f"each other by {residual:.3g} (relative {residual / float(np.linalg.norm(rows[:, 3:])):.3g})."
        )
    return point


def _unit(vector: np.ndarray) -> list[float]:
    return (vector / np.linalg.norm(vector)).tolist()


def _screw_geometry(joint: Joint) -> tuple[str, dict[str, Any]]:
    """A joint's snapshot type and fields read off its screws (the module docstring)."""
    rows = joint.screws
    if joint.type in ("U", "S"):
        point = _common_point(joint.name, rows).tolist()
        if joint.type == "S":
            return "S", {"center": point}
        return "U", {"first_axis": _unit(rows[0, :3]), "second_axis": _unit(rows[1, :3]), "center": point}
    if joint.type == "C":
        return "C", {"axis": _unit(rows[0, :3]), "point": _common_point(joint.name, rows[:1]).tolist()}
    w, v = rows[0, :3], rows[0, 3:]
    ww = float(w @ w)
    if ww <= (B.DEFAULT_RTOL * float(np.linalg.norm(v))) ** 2:
        # a translation: P (a parallelogram Pa keeps only its translation in a twist, so it is written
        # as the P joint with the same twist; its hinge and rods are not in the screw)
        return "P", {"direction": _unit(v)}
    pitch = float(w @ v) / ww
    axis, point = _unit(w), (np.cross(w, v) / ww).tolist()
    if abs(pitch) * math.sqrt(ww) <= B.DEFAULT_RTOL * float(np.linalg.norm(v) + math.sqrt(ww)):
        return "R", {"axis": axis, "point": point}
    return "H", {"axis": axis, "point": point, "pitch": pitch}


def _joint_fields(joint: Joint) -> tuple[str, dict[str, Any]]:
    fields = JOINT_FIELDS.get(joint.type)
    if fields is not None and all(key in joint.geometry for key in fields):
        return joint.type, {key: joint.geometry[key] for key in fields}
    if B.is_symbolic(joint.screws):
        raise ScrewkitValueError(
            f"Joint {joint.name!r}: expected numeric screws to write a snapshot, got symbolic ones "
            "(a snapshot is one configuration)."
        )
    return _screw_geometry(joint)


def snapshot_text(graph: nx.MultiDiGraph, *, name: str | None = None, joint_key: str = "joint") -> str:
    """The snapshot TOML text of a numeric twist graph (see the module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (checked with :func:`screwkit.graphs.twistgraph.check_twist_graph`).
    name : str, optional
        The ``[mechanism] name``; default the graph's ``name`` attribute or ``"twist graph"``.
    joint_key : str, default "joint"
        The edge attribute holding each :class:`~screwkit.graphs.joints.Joint`.

    Returns
    -------
    str
        The file's text: a ``[mechanism]`` table (``kind = "snapshot"``, name, base, platform,
        length unit if the graph has one) and one ``[[joints]]`` table per joint.

    Raises
    ------
    TwistGraphError
        If ``graph`` is not a valid twist graph.
    ScrewkitValueError
        For symbolic or non-finite screws, or a joint whose axes do not meet where they must.

    Examples
    --------
    >>> import screwkit as sk
    >>> text = snapshot_text(sk.load_mechanism("planar_3rrp").twist_graph())
    >>> text.count("[[joints]]"), 'kind = "snapshot"' in text
    (9, True)
    """
    check_twist_graph(graph, joint_key=joint_key)
    if name is not None and not isinstance(name, str):
        raise ScrewkitTypeError(f"Expected `name` to be a str, got {type(name).__name__}.")
    title = name if name is not None else str(graph.graph.get("name", "twist graph"))
    lines = [
        "# screwkit snapshot (written by screwkit.interface.export.save_snapshot)",
        "[mechanism]",
        'kind = "snapshot"',
        f"name = {_toml_string(title)}",
        f"base = {_toml_string(_link_name(graph.graph['base'], 'graph attribute `base`'))}",
        f"platform = {_toml_string(_link_name(graph.graph['platform'], 'graph attribute `platform`'))}",
    ]
    if graph.graph.get("dof") is not None:
        lines.append(f"dof = {int(graph.graph['dof'])}")
    if graph.graph.get("length_unit"):
        lines.append(f"length_unit = {_toml_string(str(graph.graph['length_unit']))}")
    names = {_link_name(link, f"link {link!r}") for link in graph.nodes}
    if len(names) != graph.number_of_nodes():
        raise ScrewkitValueError(
            "Expected link names that stay distinct as text to write a snapshot, got links whose "
            f"names collide: {sorted(map(repr, graph.nodes))}."
        )
    for parent, child, joint in sorted(graph.edges(data=joint_key), key=lambda e: e[2].name):
        kind, fields = _joint_fields(joint)
        where = f"joint {joint.name!r}"
        lines += [
            "",
            "[[joints]]",
            f"name = {_toml_string(joint.name)}",
            f'type = "{kind}"',
            f"parent = {_toml_string(_link_name(parent, where))}",
            f"child = {_toml_string(_link_name(child, where))}",
        ]
        if joint.actuated:
            lines.append("actuated = true")
        lines += [f"{key} = {_toml_value(value, where)}" for key, value in fields.items()]
    return "\n".join(lines) + "\n"


def save_snapshot(
    graph: nx.MultiDiGraph, path: str | Path, *, name: str | None = None, joint_key: str = "joint"
) -> Path:
    """Write a numeric twist graph as a snapshot file; :func:`screwkit.load_snapshot` reads it back.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A numeric twist graph (checked with :func:`screwkit.graphs.twistgraph.check_twist_graph`).
    path : str or pathlib.Path
        The file to write (replaced if it exists).
    name, joint_key
        As for :func:`snapshot_text`.

    Returns
    -------
    pathlib.Path
        ``path``, written with :func:`snapshot_text`'s text in UTF-8.

    Raises
    ------
    ScrewkitTypeError
        If ``path`` is not a str or a path.
    ScrewkitValueError
        If the file cannot be written, or as :func:`snapshot_text`.

    Examples
    --------
    >>> import tempfile, screwkit as sk
    >>> graph = sk.load_mechanism("h4").twist_graph()
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     again = sk.load_snapshot(save_snapshot(graph, folder + "/h4.toml"))
    >>> again.number_of_edges() == graph.number_of_edges()
    True
    """
    if not isinstance(path, str | Path):
        raise ScrewkitTypeError(f"Expected `path` to be a str or pathlib.Path, got {type(path).__name__}.")
    target = Path(path)
    text = snapshot_text(graph, name=name, joint_key=joint_key)
    try:
        target.write_text(text, encoding="utf-8")
    except OSError as err:
        raise ScrewkitValueError(f"{target}: cannot write the snapshot: {err.strerror}.") from err
    return target


def _dot_id(value: Any) -> str:
    return json.dumps(str(value), ensure_ascii=False)


def graph_dot(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> str:
    """Graphviz DOT text of a twist graph: links as nodes (base and platform boxed), joints as edges
    labelled ``name (type)``, actuated joints bold, virtual joints dashed.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph, numeric or symbolic (checked with
        :func:`screwkit.graphs.twistgraph.check_twist_graph`).
    joint_key : str, default "joint"
        The edge attribute holding each :class:`~screwkit.graphs.joints.Joint`.

    Returns
    -------
    str
        A ``digraph`` named after the graph's ``name`` attribute: links sorted by name, joints
        sorted by name.

    Examples
    --------
    >>> import screwkit as sk
    >>> graph = sk.twist_graph("B", "E", [("B", "E", sk.revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True))])
    >>> print(graph_dot(graph))
    digraph "twist graph" {
      "B" [shape=box];
      "E" [shape=box, peripheries=2];
      "B" -> "E" [label="R1 (R)", style=bold];
    }
    """
    check_twist_graph(graph, joint_key=joint_key)
    base, platform = graph.graph["base"], graph.graph["platform"]
    lines = [f"digraph {_dot_id(graph.graph.get('name', 'twist graph'))} {{"]
    for link in sorted(graph.nodes, key=str):
        shape = " [shape=box, peripheries=2]" if link == platform else " [shape=box]" if link == base else ""
        lines.append(f"  {_dot_id(link)}{shape};")
    for parent, child, joint in sorted(graph.edges(data=joint_key), key=lambda e: e[2].name):
        style = ", style=bold" if joint.actuated else ", style=dashed" if joint.virtual else ""
        label = _dot_id(f"{joint.name} ({joint.type})")
        lines.append(f"  {_dot_id(parent)} -> {_dot_id(child)} [label={label}{style}];")
    return "\n".join(lines) + "\n}"


def graph_json(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> str:
    """JSON text of a twist graph (:func:`screwkit.graphs.twistgraph.to_data`; read back with
    :func:`screwkit.graphs.twistgraph.from_data`).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A numeric twist graph (checked with :func:`screwkit.graphs.twistgraph.check_twist_graph`).
    joint_key : str, default "joint"
        The edge attribute holding each :class:`~screwkit.graphs.joints.Joint`.

    Returns
    -------
    str
        The graph's data, indented by two spaces, non-ASCII characters kept.

    Raises
    ------
    ScrewkitValueError
        For symbolic screws.

    Examples
    --------
    >>> import json, screwkit as sk
    >>> graph = sk.twist_graph("B", "E", [("B", "E", sk.prismatic("P1", [0, 0, 1]))])
    >>> json.loads(graph_json(graph))["edges"][0]["joint"]["type"]
    'P'
    """
    check_twist_graph(graph, joint_key=joint_key)
    if B.is_symbolic(*(joint.screws for _, _, joint in graph.edges(data=joint_key))):
        raise ScrewkitValueError("Expected a numeric twist graph to write JSON, got symbolic screws.")
    return json.dumps(to_data(graph, joint_key=joint_key), indent=2, ensure_ascii=False, default=str)
