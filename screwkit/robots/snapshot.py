"""Snapshot files: any mechanism at one configuration, joint by joint, read into a twist graph.

**Snapshots** (``kind = "snapshot"``): any mechanism at one configuration, joint by joint::

    [mechanism]
    kind = "snapshot"
    name = "my robot"
    base = "ground"
    platform = "plate"
    dof = 3                          # optional: default, the number of actuated joints
    length_unit = "m"

    [[joints]]
    name = "A1"
    type = "R"                       # R, P, H, C, U, S, Pa
    parent = "ground"
    child = "leg1"
    axis = [0.0, 0.0, 1.0]
    point = [0.0, 0.0, 0.0]
    actuated = true

Joint fields by type: R ``axis, point``; P ``direction``; H ``axis, point, pitch``; C ``axis,
point``; U ``first_axis, second_axis, center``; S ``center``; Pa ``hinge_axis, rod_direction``;
every type takes ``actuated`` (default false). File text is only ever parsed as TOML data: it never
reaches ``eval`` or ``sympify``. Every error names the file, the joint or table, and the field.

Examples
--------
>>> graph = snapshot_from_mapping({
...     "mechanism": {"kind": "snapshot", "name": "one R", "base": "ground", "platform": "arm"},
...     "joints": [{"name": "A", "type": "R", "parent": "ground", "child": "arm",
...                 "axis": [0, 0, 1], "point": [0, 0, 0], "actuated": True}]})
>>> graph.number_of_edges()
1
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import networkx as nx
import numpy as np

from ..algebra.backend import is_dof
from ..exceptions import (
    CatalogError,
    ScrewkitError,
    TwistGraphError,
)
from ..graphs import joints as J
from ..graphs.twistgraph import add_joint, check_twist_graph
from .toml_fields import (
    MAX_COORDINATE,
    _check_keys,
    _direction,
    _error,
    _length_unit,
    _name,
    _number,
    _string,
    _strings,
    _table,
    _vector,
    load_toml,
)

if TYPE_CHECKING:
    pass


__all__ = [
    "MAX_FAR_OVER_SPREAD",
    "MAX_JOINTS",
    "MAX_LOOPS",
    "check_dof",
    "load_snapshot",
    "snapshot_from_mapping",
]


#: How far from the origin a snapshot's joints may lie, in units of their spread (1e7: float64 then
#: keeps about 9 significant digits of the geometry, as the default rtol 1e-9 needs).
MAX_FAR_OVER_SPREAD = 1e7
#: Resource cap: a snapshot with more joints is refused before it is read.
MAX_JOINTS = 500
#: Independent loops (joints - links + 1) a snapshot may close: the report's generic configurations
#: solve all loop closures at once, ~2 s at 16 loops of 6 freedoms each, ~20 s at 23 (superlinear).
MAX_LOOPS = 16
_JOINT_FIELDS = J.JOINT_FIELDS
_COMMON_FIELDS = {"name", "type", "parent", "child", "actuated"}


def _snapshot_joint(entry: Any, index: int, source: str) -> tuple[str, str, J.Joint]:
    where = f"[[joints]] #{index + 1}"
    if not isinstance(entry, dict):
        raise _error(source, where, f"expected a table, got {type(entry).__name__}.")
    name = _name(entry, "name", source, where)
    where = f"joint {name!r}"
    kind = _string(entry, "type", source, where)
    if kind not in _JOINT_FIELDS:
        raise _error(source, where, f"field `type`: expected one of {sorted(_JOINT_FIELDS)}, got {kind!r}.")
    parent = _name(entry, "parent", source, where)
    child = _name(entry, "child", source, where)
    actuated = entry.get("actuated", False)
    if not isinstance(actuated, bool):
        raise _error(source, where, f"field `actuated`: expected true or false, got {actuated!r}.")
    _check_keys(entry, (*_COMMON_FIELDS, *_JOINT_FIELDS[kind]), source, f"{where} ({kind} joint)")
    values: dict[str, Any] = {}
    for key in _JOINT_FIELDS[kind]:
        if key not in entry:
            raise _error(
                source, where, f"field `{key}`: missing (a {kind} joint needs {list(_JOINT_FIELDS[kind])})."
            )
        if key == "pitch":
            values[key] = _number(entry[key], source, where, key)
        elif key in ("point", "center"):
            values[key] = _vector(entry, key, source, where)
        else:  # a direction: only its direction counts, so scale it exactly (a power of two) to size ~1
            values[key] = _direction(_vector(entry, key, source, where))
        if any(abs(v) > MAX_COORDINATE for v in np.ravel(values[key])):
            raise _error(
                source,
                where,
                f"field `{key}`: expected magnitudes up to {MAX_COORDINATE:g}, got {entry[key]!r}.",
            )
    builders: dict[str, Callable[..., J.Joint]] = {
        "R": lambda: J.revolute(name, values["axis"], values["point"], actuated=actuated),
        "P": lambda: J.prismatic(name, values["direction"], actuated=actuated),
        "H": lambda: J.helical(name, values["axis"], values["point"], values["pitch"], actuated=actuated),
        "C": lambda: J.cylindrical(name, values["axis"], values["point"]),
        "U": lambda: J.universal(name, values["first_axis"], values["second_axis"], values["center"]),
        "S": lambda: J.spherical(name, values["center"]),
        "Pa": lambda: J.parallelogram(name, values["hinge_axis"], values["rod_direction"], actuated=actuated),
    }
    if actuated and kind in ("C", "U", "S"):
        raise _error(
            source, where, f"field `actuated`: a {kind} joint has several freedoms and cannot be actuated."
        )
    try:
        return parent, child, builders[kind]()
    except ScrewkitError as err:
        raise _error(source, where, str(err)) from err


def snapshot_from_mapping(data: Mapping[str, Any], *, source: str = "<mapping>") -> nx.MultiDiGraph:
    """Build a twist graph from parsed snapshot TOML (see the module docstring).

    Parameters
    ----------
    data : mapping
        A parsed snapshot file (``[mechanism]`` and ``[[joints]]``).
    source : str, optional
        Where the data come from, named in every error.

    Returns
    -------
    networkx.MultiDiGraph
        The twist graph of the snapshot.

    Examples
    --------
    >>> graph = snapshot_from_mapping({
    ...     "mechanism": {"kind": "snapshot", "name": "slider", "base": "B", "platform": "E"},
    ...     "joints": [{"name": "P1", "type": "P", "parent": "B", "child": "E",
    ...                 "direction": [1.0, 0.0, 0.0], "actuated": True}]})
    >>> graph.graph["name"], graph.number_of_edges()
    ('slider', 1)
    """
    if not isinstance(data, Mapping):
        raise CatalogError(f"{source}: expected a mapping of TOML tables, got {type(data).__name__}.")
    _check_keys(data, ("mechanism", "joints"), source, "top level")
    header = _table(data, "mechanism", source)
    _check_keys(
        header,
        ("kind", "name", "base", "platform", "dof", "length_unit", "description", "sources"),
        source,
        "[mechanism]",
    )
    kind = header.get("kind")
    if kind != "snapshot":
        raise _error(source, "[mechanism]", f"field `kind`: expected 'snapshot', got {kind!r}.")
    name = _name(header, "name", source, "[mechanism]")
    base = _name(header, "base", source, "[mechanism]")
    platform = _name(header, "platform", source, "[mechanism]")
    if "description" in header:
        _string(header, "description", source, "[mechanism]")
    _strings(header, "sources", source, "[mechanism]")
    dof = header.get("dof")
    if dof is not None and not is_dof(dof):
        raise _error(source, "[mechanism]", f"field `dof`: expected an integer in 0..6, got {dof!r}.")
    length_unit = _length_unit(header, source) if "length_unit" in header else ""
    entries = data.get("joints")
    if not isinstance(entries, list) or not entries:
        raise _error(source, "[[joints]]", "expected at least one [[joints]] table, got none.")
    if len(entries) > MAX_JOINTS:
        raise _error(source, "[[joints]]", f"expected at most {MAX_JOINTS} joints, got {len(entries)}.")
    _check_precision(entries, source)
    triples = [_snapshot_joint(entry, i, source) for i, entry in enumerate(entries)]
    links = {base, platform} | {t[0] for t in triples} | {t[1] for t in triples}
    loops = len(triples) - len(links) + 1
    if loops > MAX_LOOPS:
        raise _error(
            source,
            "[[joints]]",
            f"expected at most {MAX_LOOPS} independent loops (joints - links + 1), got {loops} "
            f"({len(triples)} joints between {len(links)} links); split the model or reduce it.",
        )
    try:
        graph = _checked_graph(base, platform, triples, dof)
        check_dof(graph)
    except ScrewkitError as err:
        raise CatalogError(f"{source}: {err}") from err
    graph.graph["name"] = name
    graph.graph["length_unit"] = length_unit
    return graph


def _check_precision(entries: list[Any], source: str) -> None:
    """Refuse joints so far from the origin, for their spread, that float64 keeps fewer than ~9
    significant digits of the geometry (:data:`MAX_FAR_OVER_SPREAD`): the rank decisions (rtol
    1e-9) would judge rounding, not the mechanism."""
    points = np.array(
        [
            entry[key]
            for entry in entries
            if isinstance(entry, dict)
            for key in ("point", "center")
            if isinstance(entry.get(key), list)
            and len(entry[key]) == 3
            and all(isinstance(v, int | float) and not isinstance(v, bool) and abs(v) <= MAX_COORDINATE
                    for v in entry[key])
        ],
        dtype=float,
    ).reshape(-1, 3)
    if len(points) < 2:
        return
    far = float(np.abs(points).max())
    spread = float(np.ptp(points, axis=0).max())
    if spread > 0 and far > MAX_FAR_OVER_SPREAD * spread:
        raise _error(
            source,
            "[[joints]]",
            f"expected joints within {MAX_FAR_OVER_SPREAD:g} times their spread of the origin, got points "
            f"{far:g} from it spanning only {spread:g}: float64 keeps too few digits of the geometry "
            "there; put the origin near the mechanism.",
        )


def check_dof(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> None:
    """Refuse a twist graph with actuated joints and ``dof = 0`` (at load time).

    screwkit analyses mechanisms whose nominal ``dof`` is the platform's mobility at generic
    configurations, with as many actuators as freedoms, fewer (under-actuated) or more (redundantly
    actuated, :mod:`screwkit.core.redundancy`). An actuator on a mechanism stated to have no freedom
    drives nothing, and is refused here without computing the mobility; the rest (``dof`` equal to
    the mobility, the actuators driving it) is checked when the graph is analysed
    (:func:`screwkit.core.mobility.settled_dof`). A graph without ``dof`` or without actuated joints
    passes.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, optional
        The edge attribute that holds the joints.

    Raises
    ------
    TwistGraphError
        Naming the actuated joints.

    Examples
    --------
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.graphs.joints import prismatic
    >>> P = [prismatic(f"P{i}", [1, i, 0], actuated=True) for i in range(2)]
    >>> check_dof(twist_graph("B", "E", [("B", "L", P[0]), ("L", "E", P[1])], dof=0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected no actuated joint with dof = 0 (nothing to drive), got 2:...
    """
    dof = graph.graph.get("dof")
    actuated = sorted(
        str(data[joint_key].name)
        for *_, data in graph.edges(data=True)
        if getattr(data[joint_key], "actuated", False)
    )
    if is_dof(dof) and dof == 0 and actuated:
        raise TwistGraphError(
            f"Expected no actuated joint with dof = 0 (nothing to drive), got {len(actuated)}: "
            f"{', '.join(actuated)}; fix `dof` (the mechanism's mobility) or the `actuated` flags."
        )


def _checked_graph(
    base: str, platform: str, triples: list[tuple[str, str, J.Joint]], dof: int | None
) -> nx.MultiDiGraph:
    graph = nx.MultiDiGraph(base=base, platform=platform)
    if dof is not None:
        graph.graph["dof"] = dof
    nodes = {base, platform} | {t[0] for t in triples} | {t[1] for t in triples}
    graph.add_nodes_from(sorted(nodes))
    for parent, child, joint in triples:
        add_joint(graph, parent, child, joint)
    check_twist_graph(graph)
    return graph


def load_snapshot(path: str | Path) -> nx.MultiDiGraph:
    """Load a snapshot file as a twist graph.

    Parameters
    ----------
    path : str or pathlib.Path
        A snapshot file.

    Returns
    -------
    networkx.MultiDiGraph
        The twist graph of the snapshot.

    Raises
    ------
    CatalogError
        Naming the file, the joint and the field of any problem.

    Examples
    --------
    >>> load_snapshot("/nonexistent.toml")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: /nonexistent.toml: cannot read the file: No such file or directory.
    """
    return snapshot_from_mapping(load_toml(path), source=str(path))
