"""Any twist graph as a mechanism over its whole motion: :func:`mechanism`.

:func:`mechanism` turns a twist graph (or a snapshot file) into a
:class:`~screwkit.robots.mechanism.Mechanism` like the catalog's, whose reference configuration is the
graph's: everything over poses (verdicts, closeness, Jacobians, transmission, maps, loci, paths) then
works for it. Its inverse kinematics is :func:`screwkit.core.loop_closure.close_loops` continued from the
reference configuration, so each pose stays in the working and assembly mode of the reference.

Its coordinates, inverse and forward kinematics are those of
:mod:`screwkit.robots.graph_kinematics`; ``task=(link, point)`` makes the coordinates those of a point
of a link (the five-bar's end point), whose orientation stays free; verdicts and Jacobians then
refer to the point's freedoms (:mod:`screwkit.robots.point_task`).

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> five_bar = twist_graph("ground", "distal1", [
...     ("ground", "proximal1", revolute("A1", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("proximal1", "distal1", revolute("B1", [0, 0, 1], [0, 1, 0])),
...     ("ground", "proximal2", revolute("A2", [0, 0, 1], [1, 0, 0], actuated=True)),
...     ("proximal2", "distal2", revolute("B2", [0, 0, 1], [1, 1, 0])),
...     ("distal2", "distal1", revolute("C", [0, 0, 1], [0.5, 1.8, 0]))], dof=2)
>>> m = mechanism(five_bar, task=("distal1", [0.5, 1.8, 0]))
>>> m.coordinates, m.reference_pose.tolist()
(('x', 'y'), [0.5, 1.8])
>>> posed = m.at([[0.5, 1.8], [0.6, 1.7]])
>>> posed.verdicts.tolist()
['regular', 'regular']
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..core.mobility import resolve_dof
from ..core.motion import moved_configurations
from ..core.redundancy import generic_driven_freedoms
from ..exceptions import ScrewkitTypeError, ScrewkitValueError, TwistGraphError
from ..graphs.twistgraph import check_twist_graph
from .graph_kinematics import GraphKinematics, graph_family, graph_kinematics
from .mechanism import Mechanism

__all__ = ["WORKSPACE_ANGLE", "WORKSPACE_LENGTHS", "mechanism"]

Array = np.ndarray

#: The default workspace box about the reference: ± this many characteristic lengths, ± this angle.
WORKSPACE_LENGTHS = 0.5
WORKSPACE_ANGLE = np.pi / 6


#: Configurations (reached by moving the mechanism, seeded) on which a point task's actuators are checked.
POINT_TASK_SAMPLES = 6
POINT_TASK_SEED = 19


def _rank(matrix: Array) -> int:
    sigma = np.linalg.svd(matrix, compute_uv=False)
    return int(np.sum(sigma > B.DEFAULT_RTOL * max(float(sigma[0]) if sigma.size else 0.0, 1.0)))


def _point_freedoms(loops: Array, velocity: Array, held: list[int]) -> int:
    """The point's freedoms at one configuration with the joint variables ``held`` fixed: the rank of
    its velocities over the joint rates that keep the loops closed (scaled units)."""
    rows = np.vstack([loops, np.eye(loops.shape[1])[held]])
    _, sigma, vt = np.linalg.svd(rows)
    rates = vt[int(np.sum(sigma > B.DEFAULT_RTOL * max(float(sigma[0]), 1.0))):]
    return _rank(velocity @ rates.T) if len(rates) else 0


def _check_point_task_actuation(kinematics: GraphKinematics, freedoms: int) -> None:
    """Refuse a point task's actuated joints that drive none of the point's freedoms, or that together
    leave it moving, at generic configurations (as :func:`~screwkit.core.mobility.resolve_dof` for a
    platform). Read from the joint rates: an actuator drives ``f − f_held`` freedoms, ``f`` the point's
    first-order freedoms with the loops closed and the other actuators held, ``f_held`` those left with
    it held too."""
    model, coordinates = kinematics.model, kinematics.coordinates
    try:
        theta = moved_configurations(model, np.random.default_rng(POINT_TASK_SEED), POINT_TASK_SAMPLES)
    except ScrewkitValueError:  # no generic configuration: the reference's verdicts say what is wrong
        return
    state = model.state(theta)
    g = state.links[coordinates.link]
    centre = g[:, :3, :3] @ model.to_scaled_points(coordinates.point) + g[:, :3, 3]
    twists = model.link_jacobian(state, coordinates.link)  # (B, 6, n): v + ω × c is the point's velocity
    velocity = twists[:, 3:] - np.cross(centre[:, None, :], np.swapaxes(twists[:, :3], 1, 2)).swapaxes(1, 2)
    loops = model.loop_jacobian(state)
    columns = {name: model.joints[name][2] for name in kinematics.actuated}

    def driven(names: list[str], others: tuple[str, ...] = ()) -> int:  # the most common count
        kept = [column for name in others for column in columns[name]]
        held = kept + [column for name in names for column in columns[name]]
        counts = [_point_freedoms(loops[b], velocity[b], kept) - _point_freedoms(loops[b], velocity[b], held)
                  for b in range(len(velocity))]
        return int(np.bincount(counts).argmax())

    # an actuator drives nothing when holding it removes no freedom of the point, whether the others
    # are free or held (either alone misreads: with the others free a 3-RPR's leg removes none of the
    # point's 2 freedoms of the platform's 3; with the others held a duplicated actuator removes none)
    idle = [name for name in kinematics.actuated if driven([name]) == 0
            and driven([name], tuple(other for other in kinematics.actuated if other != name)) == 0]
    if idle:
        raise TwistGraphError(
            f"Expected every `actuated` joint to drive the task point, got {', '.join(idle)} driving none "
            f"of its {freedoms} freedom(s) at generic configurations (held, the point moves as before); "
            "fix the `actuated` flags."
        )
    if len(kinematics.actuated) >= freedoms:
        resolve_dof(None, freedoms, kinematics.actuated, driven=driven(list(kinematics.actuated)))


def _checked_point(value: Any, argument: str) -> Array:
    try:
        point = B.as_array(value, argument, (3,), symbolic=False).astype(float)
    except ScrewkitValueError:
        raise
    except Exception as error:
        raise ScrewkitTypeError(f"Expected `{argument}` to be 3 numbers, got {value!r}.") from error
    if point.shape != (3,) or not np.all(np.isfinite(point)):
        raise ScrewkitValueError(
            f"Expected `{argument}` to be 3 finite numbers, got {np.asarray(value).tolist()}."
        )
    return point


def _default_workspace(kinematics: GraphKinematics, reference: Array) -> dict[str, tuple[float, float]]:
    span = WORKSPACE_LENGTHS * kinematics.model.length
    return {
        name: (float(value - span), float(value + span))
        if kind == "translation"
        else (float(value - WORKSPACE_ANGLE), float(value + WORKSPACE_ANGLE))
        for name, kind, value in zip(
            kinematics.coordinates.names, kinematics.coordinates.kinds, reference, strict=True
        )
    }


def _checked_workspace(workspace: Any, names: tuple[str, ...]) -> dict[str, tuple[float, float]]:
    if not isinstance(workspace, Mapping) or set(workspace) != set(names):
        got = sorted(workspace) if isinstance(workspace, Mapping) else type(workspace).__name__
        raise ScrewkitValueError(
            f"Expected `workspace` to map each coordinate {list(names)} to (low, high), got {got}."
        )
    box = {}
    for name in names:
        try:
            low, high = (float(v) for v in workspace[name])
        except (TypeError, ValueError) as error:
            raise ScrewkitValueError(
                f"Expected `workspace[{name!r}]` to be two numbers (low, high), got {workspace[name]!r}."
            ) from error
        if not (np.isfinite(low) and np.isfinite(high) and low < high):
            raise ScrewkitValueError(
                f"Expected `workspace[{name!r}]` to be finite with low < high, got ({low}, {high})."
            )
        box[name] = (low, high)
    return box


def mechanism(
    graph_or_file: Any,
    *,
    task: Any = None,
    platform_point: Any = None,
    workspace: Any = None,
) -> Mechanism[Any, Any]:
    """Any mechanism as a :class:`~screwkit.robots.mechanism.Mechanism`: a twist graph or snapshot file
    over its whole motion (module docstring), or a catalog robot by name.

    Parameters
    ----------
    graph_or_file : networkx.MultiDiGraph, str, pathlib.Path or Mechanism
        A twist graph at its reference configuration, a snapshot file (TOML), a catalog name, or a
        mechanism (returned as is).
    task : tuple (link, point), optional
        A point fixed in a link, given in the graph's frame at the reference: the coordinates are
        then that point's (the link's orientation stays free). Default: the platform's pose.
    platform_point : array_like, shape (3,), optional
        The platform point whose position the translation coordinates give (default: the centroid of
        the platform's joint points); rotations are about it.
    workspace : mapping, optional
        ``{coordinate: (low, high)}`` for maps and random poses (default: ± half the characteristic
        length and ± 30° about the reference).

    Returns
    -------
    Mechanism
        Its family is ``"loop_closure"``; ``default_pose`` is the reference configuration.

    Raises
    ------
    ScrewkitValueError
        If ``task`` names no link or is not ``(link, point)``, a point is not 3 finite numbers, the
        platform moves with a number of freedoms other than the graph's ``dof`` at the reference, or
        the workspace is malformed.
    ScrewkitTypeError
        If ``graph_or_file`` is none of the above.
    TwistGraphError
        If more actuated joints than the platform's freedoms leave it uncontrolled at generic
        configurations (:func:`screwkit.core.mobility.resolve_dof`); with a point task, if an actuated
        joint drives none of the point's freedoms there, or the actuated joints leave it uncontrolled.

    Examples
    --------
    >>> m = mechanism(load_mechanism("h4").twist_graph())
    >>> m.coordinates, m.family
    (('x', 'y', 'z', 'phi'), 'loop_closure')
    >>> mechanism(load_mechanism("h4").twist_graph(), task="platform")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `task` to be (link, point), got 'platform'.
    """
    from .catalog import list_mechanisms, load_mechanism
    from .snapshot import load_snapshot

    if isinstance(graph_or_file, Mechanism):
        return graph_or_file
    source = "<graph>"
    if isinstance(graph_or_file, str | Path):
        if isinstance(graph_or_file, str) and graph_or_file in list_mechanisms():
            return load_mechanism(graph_or_file)
        source = str(graph_or_file)
        graph = load_snapshot(graph_or_file)
    elif isinstance(graph_or_file, nx.MultiDiGraph):
        graph = graph_or_file
    else:
        raise ScrewkitTypeError(
            "Expected `graph_or_file` to be a twist graph, a snapshot file, a catalog name or a Mechanism, "
            f"got {type(graph_or_file).__name__}."
        )
    check_twist_graph(graph)
    if task is None:
        link, point, rotations = None, platform_point, True
    else:
        if not isinstance(task, tuple | list) or len(task) != 2:
            raise ScrewkitValueError(f"Expected `task` to be (link, point), got {task!r}.")
        link, point, rotations = task[0], _checked_point(task[1], "task point"), False
        if link not in graph:
            raise ScrewkitValueError(f"Expected `task` to name a link of the graph, got {link!r}.")
    if point is not None and task is None:
        point = _checked_point(point, "platform_point")
    kinematics = graph_kinematics(graph, link=link, point=point, rotations=rotations)
    names = kinematics.coordinates.names
    dof = graph.graph.get("dof")
    if dof is not None and len(names) != dof:
        raise ScrewkitValueError(
            f"Expected the {'point' if task is not None else 'platform'} to move with the graph's "
            f"dof = {dof} "
            f"freedoms at the reference configuration, got {len(names)} ({', '.join(names)}): the reference "
            "is singular, or dof is not the mechanism's."
        )
    if task is None and len(kinematics.actuated) > len(names):  # redundant: the actuators must drive it
        driven = generic_driven_freedoms(graph, len(names))
        resolve_dof(None, len(names), kinematics.actuated, driven=driven)
    elif task is not None and kinematics.actuated:
        _check_point_task_actuation(kinematics, len(names))
    reference = kinematics.coordinates.reference_values()
    box = (
        _default_workspace(kinematics, reference)
        if workspace is None
        else _checked_workspace(workspace, names)
    )
    return Mechanism(
        name=str(graph.graph.get("name", "mechanism")),
        family="loop_closure",
        length_unit=str(graph.graph.get("length_unit", "")),
        source=source,
        sources=tuple(graph.graph.get("sources", ())),
        parameters=kinematics,
        parameter_sources={},
        default_pose=reference,
        workspace=box,
        protocol=graph_family(kinematics.coordinates),
    )
