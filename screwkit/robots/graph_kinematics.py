"""Loop-closure kinematics of a twist graph as a family: the parameters, configurations and the four
functions a :class:`~screwkit.robots.families.Family` needs, for any mechanism.

:class:`GraphKinematics` holds a graph's product-of-exponentials model
(:class:`~screwkit.core.kinematic_model.KinematicModel`) and the coordinates of a link
(:func:`~screwkit.core.task_coordinates.task_coordinates`): the position of a point of it along the
translation directions of its motion at the reference — ``x, y, z`` along the base frame's axes — and
its rotation vector along the rotation directions (``phi`` for one rotation, ``rx, ry, rz`` for more),
0 at the reference. Its inverse kinematics is :func:`~screwkit.core.loop_closure.close_loops`
continued from the reference configuration, so each pose stays in the working and assembly mode of
the reference; :meth:`GraphKinematics.forward` does the same from actuated-joint values.

When the coordinates fix the link's whole pose over the motion (the mechanism has no parasitic
motion: a Schoenflies, translational, planar or spherical motion generator), the inverse kinematics
also holds the directions the coordinates leave out at their reference values, so the continuation
cannot slip into another assembly mode at a constraint singularity (a Quattro's tilted plate); this
is decided once by moving the mechanism a little in every coordinate (:data:`PURE_MOTION_STEP`) and
checking the link's whole pose.

:func:`kinematics_of` gives the same kinematics for a catalog robot, from its twist graph at its
default pose (its forward kinematics, and the check of its closed-form inverse kinematics).

Examples
--------
>>> h4 = kinematics_of(load_mechanism("h4"))
>>> h4.coordinates.names, h4.complete
(('x', 'y', 'z', 'phi'), True)
>>> h4.solve(np.array([[30.0, -20.0, -750.0, 0.3]])).reached.tolist()
[True]
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass, field
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..core.kinematic_model import KinematicModel, KinematicState
from ..core.kinematic_tasks import JointTask, PoseTask
from ..core.loop_closure import FINAL_TOLERANCE, ClosedConfigurations, close_loops
from ..core.task_coordinates import TaskCoordinates, task_coordinates
from ..exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from ..graphs.jointtable import JointTable
from ..graphs.twistgraph import check_twist_graph, graph_frame
from ._solved_poses import SolvedPoses, identities, pose_keys
from .families import Family
from .point_task import with_task_point

__all__ = [
    "MAX_CACHED_POSES",
    "PURE_MOTION_STEP",
    "GraphConfiguration",
    "GraphKinematics",
    "graph_family",
    "graph_kinematics",
    "kinematics_of",
]

Array = np.ndarray

#: Solved poses remembered per mechanism (a map asks which poses are reachable, then analyses them).
MAX_CACHED_POSES = 16384
#: The small motion (characteristic lengths, radians) in each coordinate that decides whether the
#: coordinates fix the platform's whole pose.
PURE_MOTION_STEP = 0.2


@dataclass(frozen=True, eq=False)
class GraphKinematics:
    """A twist graph's loop-closure kinematics with its coordinates: the family's parameters.

    Attributes
    ----------
    graph : networkx.MultiDiGraph
        The reference configuration.
    model : KinematicModel
    coordinates : TaskCoordinates
    complete : bool
        True when the coordinates fix the measured link's whole pose over the motion.
    angle_offsets : numpy.ndarray, shape (n,)
        Added to the rotation coordinates (a catalog robot's default angles; zeros for a graph).
    reference : JointTable
        The graph's joint table (names, types, actuation, dof).
    point_task : bool
        True when the coordinates are a point's alone (``rotations=False``): the analysis measures the
        point (:func:`screwkit.robots.point_task.with_task_point`).
    """

    graph: nx.MultiDiGraph = field(repr=False)
    model: KinematicModel = field(repr=False)
    coordinates: TaskCoordinates
    complete: bool
    angle_offsets: Array
    reference: JointTable = field(repr=False)
    point_task: bool = False
    _cache: SolvedPoses = field(default_factory=lambda: SolvedPoses(MAX_CACHED_POSES), repr=False)

    @functools.cached_property
    def task(self) -> PoseTask:
        """The coordinates as equations of the joint values."""
        return PoseTask(self.model, self.coordinates, complete=self.complete)

    @property
    def actuated(self) -> tuple[str, ...]:
        """The actuated joints, in name order (the order of :meth:`forward`'s values)."""
        return tuple(sorted(spec.name for spec in self.reference.specs if spec.actuated))

    def _targets(self, poses: Array) -> Array:
        rotation = ~self.task.translation[: len(self.coordinates.names)]
        return self.task.scaled_targets(poses - np.where(rotation, self.angle_offsets, 0.0))

    def solve(self, poses: Array) -> ClosedConfigurations:
        """The configurations at poses ``(m, n)`` (coordinates, graph unit and radians), those asked
        before read from a cache of :data:`MAX_CACHED_POSES` poses.

        Parameters
        ----------
        poses : numpy.ndarray, shape (m, n)

        Returns
        -------
        ClosedConfigurations

        Examples
        --------
        >>> h4 = kinematics_of(load_mechanism("h4"))
        >>> h4.solve(np.array([[0, 0, -750, 0.1], [0, 0, -3000, 0]])).reached.tolist()
        [True, False]
        """
        keys = pose_keys(poses)
        cache = self._cache
        slots = cache.rows(keys)
        known, missing = np.flatnonzero(slots >= 0), np.flatnonzero(slots < 0)
        spherical = [key for key, kind in self.model.types.items() if kind == "S"]
        if not known.size:  # every pose new: the continuation's own arrays
            solved = close_loops(self.model, self.task, self._targets(poses))
            given = solved.offsets
            offsets = {key: given[key] if key in given else identities(len(poses)) for key in spherical}
            closed = dataclasses.replace(solved, offsets=offsets)
        else:
            theta = np.empty((len(poses), self.model.size))
            offsets = {key: np.empty((len(poses), 4, 4)) for key in spherical}
            theta[known] = cache.theta[slots[known]]
            for key, value in offsets.items():
                value[known] = cache.offsets[key][slots[known]]
            reached = np.ones(len(poses), dtype=bool)
            residual = np.zeros(len(poses))
            reasons = np.full(len(poses), "", dtype=object)
            if not missing.size:
                state = cache.recent_state(keys)
                return ClosedConfigurations(theta, offsets, reached, residual, reasons, state)
            solved = close_loops(self.model, self.task, self._targets(poses[missing]))
            theta[missing] = solved.theta
            for key, value in offsets.items():
                value[missing] = solved.offsets.get(key, np.eye(4))
            reached[missing], residual[missing] = solved.reached, solved.residual
            reasons[missing] = solved.reasons
            closed = ClosedConfigurations(theta, offsets, reached, residual, reasons)
        fresh = missing[solved.reached]
        if fresh.size == len(poses):  # (every row: no copy before the cache's own)
            cache.add(keys, closed.theta, offsets)
        else:
            rows = {key: value[fresh] for key, value in offsets.items()}
            cache.add([keys[i] for i in fresh], closed.theta[fresh], rows)
        if solved.state is not None:
            asked = keys if missing.size == len(poses) else [keys[i] for i in missing]
            cache.recent = (dict(zip(asked, range(missing.size), strict=True)), solved.state)
        return closed

    def unreachable_reasons(self, poses: Array) -> Array:
        """Why each pose ``(m, n)`` is out of reach (empty where it is reached).

        Parameters
        ----------
        poses : numpy.ndarray, shape (m, n)

        Returns
        -------
        numpy.ndarray of str, shape (m,)

        Examples
        --------
        >>> kinematics_of(load_mechanism("h4")).unreachable_reasons(np.array([[0, 0, -750, 0.0]])).tolist()
        ['']
        """
        return self.solve(poses).reasons

    def remember(self, poses: Array, closed: ClosedConfigurations) -> None:
        """Add solved configurations (e.g. of the forward kinematics) to the cache.

        Parameters
        ----------
        poses : numpy.ndarray, shape (m, n)
            Their coordinates.
        closed : ClosedConfigurations
            Their configurations (only the reached ones are kept).

        Examples
        --------
        >>> h4 = kinematics_of(load_mechanism("h4"))
        >>> closed = h4.solve(np.array([[0, 0, -750, 0.1]]))
        >>> h4.remember(np.array([[0, 0, -750, 0.1]]), closed)
        """
        keys = pose_keys(poses)
        rows = np.flatnonzero(closed.reached)
        offsets = {
            key: closed.offsets.get(key, np.broadcast_to(np.eye(4), (len(closed.theta), 4, 4)))[rows]
            for key, kind in self.model.types.items()
            if kind == "S"
        }
        self._cache.add([keys[i] for i in rows], closed.theta[rows], offsets)

    def forward(self, values: Array) -> tuple[Array, ClosedConfigurations]:
        """Platform coordinates and configurations at actuated-joint displacements ``(m, k)``.

        Parameters
        ----------
        values : numpy.ndarray, shape (m, k)
            Displacements from the reference of :attr:`actuated` (radians, graph lengths).

        Returns
        -------
        poses : numpy.ndarray, shape (m, n)
            The coordinates (rotations in ``(−π, π]`` about the offsets; NaN where not reached).
        closed : ClosedConfigurations

        Examples
        --------
        >>> h4 = kinematics_of(load_mechanism("h4"))
        >>> poses, closed = h4.forward(np.zeros((1, 4)))
        >>> poses.round(9).tolist()
        [[0.0, 0.0, -750.0, 0.0]]
        """
        task = JointTask(self.model, self.actuated)
        closed = close_loops(self.model, task, task.scaled_targets(values))
        state = self.model.state(closed.theta, closed.offsets)
        poses = self.task.unscaled(self.task.values(state))
        rotation = ~self.task.translation[: len(self.coordinates.names)]
        poses = poses + np.where(rotation, self.angle_offsets, 0.0)
        poses[~closed.reached] = np.nan
        self.remember(poses[closed.reached], _subset(closed, closed.reached))
        return poses, closed

    def twist_basis(self, state: KinematicState) -> Array:
        """The measured link's twists per unit rate of each coordinate, ``(B, n, 6)`` (graph frame).

        The joint rates closing the loops with that coordinate's rate 1 and the others' (and, for a
        complete task, the left-out directions') 0, minimum-norm (internal motions at rest), carried
        to the link along its tree path. When the task fixes the link's whole pose, its rates say
        the twist alone (:meth:`~screwkit.core.kinematic_tasks.PoseTask.twist_rates`, inverted): the
        same twists wherever the loops let the link move so, and the coordinates' own directions at
        a pose where they do not.

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, n, 6)

        Examples
        --------
        >>> h4 = kinematics_of(load_mechanism("h4"))
        >>> closed = h4.solve(np.array([[0, 0, -750, 0.0]]))
        >>> h4.twist_basis(h4.model.state(closed.theta, closed.offsets))[0, 3, :3].round(9) + 0.0
        array([0., 0., 1.])
        """
        model, task = self.model, self.task
        count = len(self.coordinates.names)
        unit = np.where(task.translation[:count], 1.0 / model.length, 1.0)
        if task.fixes_pose:  # the task's rates say the link's twist: (B, 6, 6) inverted, no loop needed
            twists = np.swapaxes(np.linalg.inv(task.twist_rates(state))[..., :count] * unit, -1, -2)
            return self._unscaled_twists(twists)
        loops, rows = model.loop_jacobian(state), task.jacobian(state)
        jacobian = np.concatenate([loops, rows], axis=1)
        rates = np.zeros((jacobian.shape[1], count))
        rates[loops.shape[1] + np.arange(count), np.arange(count)] = unit
        # the minimum-norm joint rates by the pseudo-inverse (singular values below 1e-12 of the
        # largest dropped: the dependent loop equations of an overconstrained mechanism)
        left, sigma, right = np.linalg.svd(jacobian, full_matrices=False)
        inverse = np.where(sigma > 1e-12 * sigma[:, :1], 1.0 / np.where(sigma > 0, sigma, 1.0), 0.0)
        joint_rates = np.swapaxes(right, -1, -2) @ (inverse[..., None] * (np.swapaxes(left, -1, -2) @ rates))
        return self._unscaled_twists(
            np.swapaxes(model.link_jacobian(state, self.coordinates.link) @ joint_rates, -1, -2)
        )

    def _unscaled_twists(self, twists: Array) -> Array:
        model = self.model
        omega = twists[..., :3]  # (B, n, 3); the velocity at the scaled origin back in graph lengths
        return np.concatenate([omega, twists[..., 3:] * model.length + np.cross(model.point, omega)], axis=-1)


def _subset(closed: ClosedConfigurations, rows: Array) -> ClosedConfigurations:
    return ClosedConfigurations(
        closed.theta[rows],
        {k: v[rows] for k, v in closed.offsets.items()},
        closed.reached[rows],
        closed.residual[rows],
        closed.reasons[rows],
    )


@dataclass(frozen=True)
class GraphConfiguration:
    """Configurations of a graph mechanism over a batch: the family's configuration type.

    Attributes
    ----------
    kinematics : GraphKinematics
    state : KinematicState
        Flat over the batch.
    shape : tuple of int
        The batch shape.
    """

    kinematics: GraphKinematics
    state: KinematicState
    shape: tuple[int, ...]


def _inverse_kinematics(kinematics: GraphKinematics, poses: Any) -> GraphConfiguration:
    array = np.asarray(poses, dtype=float)
    shape = array.shape[:-1]
    flat = array.reshape(-1, array.shape[-1])
    closed = kinematics.solve(flat)
    if not np.all(closed.reached):
        first = int(np.flatnonzero(~closed.reached)[0])
        index = np.unravel_index(first, shape) if shape else ()
        raise UnreachablePoseError(
            f"Pose {tuple(int(i) for i in index)} = {flat[first].tolist()} is out of reach: "
            f"{closed.reasons[first]}."
        )
    state = closed.state if closed.state is not None else kinematics.model.state(closed.theta, closed.offsets)
    return GraphConfiguration(kinematics, state, shape)


def _joints(configuration: GraphConfiguration) -> JointTable:
    kinematics, shape = configuration.kinematics, configuration.shape
    table = kinematics.model.joint_table(configuration.state, kinematics.reference, shape)
    if not kinematics.point_task:
        return table
    link, point = kinematics.coordinates.link, kinematics.coordinates.point
    moved = kinematics.model.displacement(configuration.state, link)
    points = (moved[:, :3, :3] @ point + moved[:, :3, 3]).reshape(*shape, 3)
    return with_task_point(table, link, points, len(kinematics.coordinates.names))


def _twist_basis(configuration: GraphConfiguration) -> Array:
    basis = configuration.kinematics.twist_basis(configuration.state)
    return basis.reshape(*configuration.shape, *basis.shape[-2:])


def _actuated_values(configuration: GraphConfiguration) -> Array:
    """The actuated joints' values (radians, graph lengths; from the reference), name order."""
    kinematics = configuration.kinematics
    model = kinematics.model
    columns = [model.joints[name][2][0] for name in kinematics.actuated]
    values = configuration.state.theta[:, columns]
    sliding = np.array([np.linalg.norm(model.columns[c].row[:3]) < 1e-12 for c in columns], dtype=bool)
    values = np.where(sliding, values * model.length, values)
    return values.reshape(*configuration.shape, len(columns))


def _reachable(kinematics: GraphKinematics, poses: Array) -> Array:
    array = np.asarray(poses, dtype=float)
    return kinematics.solve(array.reshape(-1, array.shape[-1])).reached.reshape(array.shape[:-1])


def _no_catalog_parameters(mapping: Any, *, source: str) -> Any:
    raise ScrewkitValueError(
        f"{source}: a graph mechanism has no catalog parameters; build it with screwkit.mechanism(graph)."
    )


def graph_family(coordinates: TaskCoordinates) -> Family[GraphKinematics, GraphConfiguration]:
    """The family of a graph mechanism with these coordinates (its pose names).

    Parameters
    ----------
    coordinates : TaskCoordinates

    Returns
    -------
    Family
        Named ``"loop_closure"``; its parameters are a :class:`GraphKinematics`.

    Examples
    --------
    >>> graph_family(kinematics_of(load_mechanism("h4")).coordinates).angle_names
    ('phi',)
    """
    return Family(
        name="loop_closure",
        parameters=_no_catalog_parameters,
        inverse_kinematics=_inverse_kinematics,
        joints=_joints,
        twist_basis=_twist_basis,
        pose_names=coordinates.names,
        angle_names=coordinates.angle_names,
        reachable=_reachable,
        actuated_values=_actuated_values,
    )


def _checked_graph(graph: Any) -> nx.MultiDiGraph:
    check_twist_graph(graph)
    for _, _, key, joint in graph.edges(keys=True, data="joint"):
        if B.is_symbolic(joint.screws):
            raise ScrewkitTypeError(
                "Expected a numeric twist graph for loop-closure kinematics, got symbolic screws in "
                f"joint {key!r}."
            )
        if joint.virtual:
            raise ScrewkitValueError(
                f"Expected the physical joints of a mechanism, got the virtual joint {key!r} (an equivalent "
                "chain holds only at one configuration): give the graph before equivalent_twist_graph."
            )
    return graph


def _is_complete(model: KinematicModel, coordinates: TaskCoordinates) -> bool:
    """Whether the coordinates fix the link's whole pose: moving each coordinate by
    :data:`PURE_MOTION_STEP` leaves the left-out directions at their reference values."""
    if len(coordinates.names) == 6:
        return True
    free = PoseTask(model, coordinates)
    held = PoseTask(model, coordinates, complete=True)
    count = len(coordinates.names)
    steps = np.concatenate([np.eye(count), -np.eye(count)]) * PURE_MOTION_STEP
    start = free.values(model.state(np.zeros((1, model.size))))
    closed = close_loops(model, free, start + steps)
    if not np.all(closed.reached):
        return False
    values = held.values(model.state(closed.theta, closed.offsets))
    reference = held.scaled_targets(free.unscaled(start))
    return bool(
        np.max(np.abs(held.difference(values, reference)[:, count:]), initial=0.0) < 1e3 * FINAL_TOLERANCE
    )


def graph_kinematics(
    graph: nx.MultiDiGraph,
    *,
    link: Any = None,
    point: Any = None,
    rotations: bool = True,
    angle_offsets: Any = None,
) -> GraphKinematics:
    """The loop-closure kinematics of a twist graph with the coordinates of a link.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A numeric twist graph of physical joints at its reference configuration.
    link : hashable, optional
        The measured link (default: the platform).
    point : array_like, shape (3,), optional
        The measured point (default: the centroid of the link's joint points).
    rotations : bool, default True
        False: only the point's position.
    angle_offsets : array_like, shape (n,), optional
        Added to the rotation coordinates (default 0).

    Returns
    -------
    GraphKinematics

    Raises
    ------
    ScrewkitValueError
        If the link does not move, or the graph has virtual joints.

    Examples
    --------
    >>> graph_kinematics(load_mechanism("h4").twist_graph()).coordinates.names
    ('x', 'y', 'z', 'phi')
    """
    model = KinematicModel(_checked_graph(graph))
    coordinates = task_coordinates(model, link=link, point=point, rotations=rotations)
    offsets = np.zeros(len(coordinates.names)) if angle_offsets is None else np.asarray(angle_offsets, float)
    complete = rotations and _is_complete(model, coordinates)
    reference = JointTable.from_graph(graph)
    if rotations and reference.dof is None:  # the platform's freedoms: as many as its coordinates
        reference = dataclasses.replace(reference, dof=len(coordinates.names))
    return GraphKinematics(graph, model, coordinates, complete, offsets, reference, not rotations)


_KINEMATICS: dict[int, tuple[Any, GraphKinematics]] = {}


def kinematics_of(robot: Any) -> GraphKinematics:
    """A mechanism's loop-closure kinematics: a graph mechanism's own, or a catalog robot's from its
    twist graph at the default pose (coordinates named and offset as its pose coordinates).

    Parameters
    ----------
    robot : Mechanism

    Returns
    -------
    GraphKinematics

    Raises
    ------
    ScrewkitValueError
        If the catalog robot's graph gives other coordinates than its pose coordinates.

    Examples
    --------
    >>> kinematics_of(load_mechanism("planar_3rrp")).coordinates.names
    ('x', 'y', 'phi')
    """
    if isinstance(robot.parameters, GraphKinematics):
        return robot.parameters
    known = _KINEMATICS.get(id(robot))
    if known is not None and known[0] is robot:
        return known[1]
    names = robot.pose_names
    pose = np.asarray(robot.default_pose, dtype=float)
    point = np.array([pose[names.index(a)] if a in names else 0.0 for a in ("x", "y", "z")])
    graph = robot.twist_graph()
    if "z" not in names:  # a planar robot: its point in the plane of its motion
        point[2] = graph_frame(graph)[0][2]
    offsets = np.array([pose[i] if n in robot.angle_names else 0.0 for i, n in enumerate(names)])
    kinematics = graph_kinematics(graph, point=point, angle_offsets=offsets)
    if kinematics.coordinates.names != names:
        raise ScrewkitValueError(
            f"Expected the loop-closure coordinates of {robot.name} to be its pose coordinates {names}, "
            f"got {kinematics.coordinates.names}."
        )
    _KINEMATICS.clear()  # one catalog robot at a time: its model is rebuilt when another is asked
    _KINEMATICS[id(robot)] = (robot, kinematics)
    return kinematics
