"""Loop-closure kinematics of any twist graph: the joint values at given platform poses (inverse
kinematics) or given actuated-joint values (forward kinematics), by continuation from the graph's
reference configuration.

The mechanism's model is :class:`~screwkit.core.kinematic_model.KinematicModel` (product of exponentials
over a spanning tree, one loop-closure equation per joint off it). A *task* adds the equations that
say where the mechanism should be:

* :class:`PoseTask`: the coordinates of a link (the platform by default): the position of a point of
  it along the translation directions of its motion, and its rotation vector along the rotation
  directions (:func:`task_coordinates`: both read off the link's twist system at the reference
  configuration, so a Schoenflies motion gets ``x, y, z, phi``, a planar one ``x, y, phi``, a
  spherical one ``rx, ry, rz``); with ``rotations=False`` only a point of the link (the five-bar's end
  point), whose orientation then stays free;
* :class:`JointTask`: the actuated joints' values (radians, lengths).

:func:`close_loops` then follows the straight path from the start's task values to each target in
steps no longer than :data:`MAX_STEP` (characteristic lengths or radians), closing the loops and the
task at every step by Gauss–Newton iterations with the minimum-norm correction (the Moore–Penrose
step ``Δθ = −Jᵀ (J Jᵀ + λ I)⁻¹ F``, Levenberg's tiny ``λ`` so that the dependent equations of an
overconstrained loop leave it solvable; Nocedal & Wright, *Numerical Optimization*, 2nd ed., 2006,
§10.3), so that each pose stays in the working and assembly mode connected to the start. A pose
whose path leaves the mechanism's reach, runs into a singularity where Newton's method stops
converging, or gives non-finite values is flagged with the reason and the residual — never returned
as a configuration. All poses of a batch move together (arrays with a leading batch axis).

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> arm = twist_graph("B", "E", [
...     ("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0], actuated=True))], dof=2)
>>> model = KinematicModel(arm)
>>> coordinates = task_coordinates(model, point=[1, 1, 0], rotations=False)
>>> coordinates.names
('x', 'y')
>>> task = PoseTask(model, coordinates)
>>> closed = close_loops(model, task, task.scaled_targets(np.array([[-1.0, 1.0]])))
>>> bool(closed.reached[0]), np.degrees(closed.theta[0]).round(6).tolist()  # the elbow as at the start
(True, [90.0, 0.0])
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .kinematic_model import KinematicModel, KinematicState, hat, rotation_log

__all__ = [
    "COORDINATE_NAMES",
    "FINAL_TOLERANCE",
    "MAX_STEP",
    "ClosedConfigurations",
    "JointTask",
    "PoseTask",
    "TaskCoordinates",
    "close_loops",
    "task_coordinates",
]

Array = np.ndarray

#: The longest step of the continuation (characteristic lengths, or radians).
MAX_STEP = 0.25
#: Newton iterations allowed per step.
NEWTON_ITERATIONS = 10
#: The residual (characteristic lengths, radians) at which the Newton iterations of a step on the
#: way stop, and of the last step.
STEP_TOLERANCE = 1e-6
LAST_STEP_TOLERANCE = 1e-12
#: The residual below which a configuration is accepted (characteristic lengths, radians).
FINAL_TOLERANCE = 1e-9
#: A step whose Newton iterations end above this residual has lost the mechanism.
LOST_TOLERANCE = 1e-3
#: The largest Newton correction taken at once (radians, characteristic lengths).
MAX_CORRECTION = 0.5
#: The largest correction Newton's method may make after a step's first (tangent) iteration, in
#: radians or characteristic lengths: beyond it the step may have jumped to another branch of the
#: loop equations (another assembly or working mode), and the pose is taken again in steps
#: :data:`RETRY_REFINEMENT` times shorter.
JUMP_LIMIT = 0.2
#: A spherical joint's angles are folded into its offset once one exceeds this (radians), far from
#: the gimbal lock of its three exponentials at π/2.
RECENTRE_ANGLE = 0.3
#: Poses solved together (bounds the memory of the batched Jacobians).
CHUNK = 1024
#: Refinements of the step tried for the poses the first continuation could not reach.
RETRY_REFINEMENT = 4
#: The most continuation steps taken for one pose.
MAX_STEPS = 2000

_AXES = ("x", "y", "z")
#: Every name :func:`task_coordinates` gives a coordinate.
COORDINATE_NAMES = ("x", "y", "z", "phi", "rx", "ry", "rz", "t1", "t2", "t3", "r1", "r2", "r3")


@dataclass(frozen=True)
class TaskCoordinates:
    """The coordinates of a task: names, kinds and directions, measured on a link.

    Attributes
    ----------
    names : tuple of str
    kinds : tuple of str
        ``"translation"`` or ``"rotation"`` per coordinate.
    directions : numpy.ndarray, shape (n, 3)
        Unit directions in the graph's frame: a translation coordinate is the point's position along
        it, a rotation coordinate the link's rotation vector along it (radians, 0 at the reference).
    link : hashable
        The link measured.
    point : numpy.ndarray, shape (3,)
        The point of the link whose position is measured, at the reference (graph frame and unit).
    """

    names: tuple[str, ...]
    kinds: tuple[str, ...]
    directions: Array
    link: Any
    point: Array

    @property
    def angle_names(self) -> tuple[str, ...]:
        """The rotation coordinates' names."""
        return tuple(n for n, k in zip(self.names, self.kinds, strict=True) if k == "rotation")

    def reference_values(self) -> Array:
        """The coordinates at the reference configuration, ``(n,)`` (translations: the point's position).

        Returns
        -------
        numpy.ndarray, shape (n,)

        Examples
        --------
        >>> c = TaskCoordinates(("x", "phi"), ("translation", "rotation"), np.eye(3)[[0, 2]], "E",
        ...                     np.array([2.0, 1.0, 0.0]))
        >>> c.reference_values().tolist()
        [2.0, 0.0]
        """
        translation = np.array([k == "translation" for k in self.kinds])
        return np.where(translation, self.directions @ self.point, 0.0)


def _named_basis(basis: Array, prefix: str, single: str | None) -> tuple[list[str], Array]:
    """Names and unit directions for an orthonormal basis ``(k, 3)`` of a subspace of R³: the
    coordinate axes it contains first (``x, y, z`` or ``rx, ry, rz``), then the rest of it numbered
    (``t1 …``, ``r1 …``); one rotation is ``single`` about its axis, pointed along its largest
    component."""
    k = basis.shape[0]
    if k == 0:
        return [], np.zeros((0, 3))
    if k == 1 and single is not None:
        axis = basis[0] * np.sign(basis[0][np.argmax(np.abs(basis[0]))])
        return [single], axis[None]
    projector = basis.T @ basis
    inside = [i for i in range(3) if abs(projector[i, i] - 1.0) < 1e-9]
    names = [("" if prefix == "t" else "r") + _AXES[i] for i in inside]
    directions = [np.eye(3)[i] for i in inside]
    rest = projector - sum((np.outer(d, d) for d in directions), np.zeros((3, 3)))
    values, vectors = np.linalg.eigh(rest)
    for j, column in enumerate(vectors.T[values > 0.5][::-1]):
        column = column * np.sign(column[np.argmax(np.abs(column))])
        names.append(f"{prefix}{j + 1}")
        directions.append(column)
    return names, np.array(directions)


def _orthonormal_rows(matrix: Array, rtol: float) -> Array:
    """An orthonormal basis of the row space of ``matrix (m, k)``, ``(rank, k)``."""
    if matrix.size == 0:
        return np.zeros((0, matrix.shape[1]))
    _, sigma, vt = np.linalg.svd(matrix, full_matrices=False)
    rank = int(np.sum(sigma > rtol * max(sigma[0], 1e-300))) if sigma.size else 0
    return vt[:rank]


def _null_space(matrix: Array, rtol: float) -> Array:
    """An orthonormal basis ``(k, rank')`` of the null space of ``matrix (m, k)``."""
    if matrix.shape[0] == 0:
        return np.eye(matrix.shape[1])
    _, sigma, vt = np.linalg.svd(matrix)
    rank = int(np.sum(sigma > rtol * max(sigma[0], 1.0)))
    return vt[rank:].T


def task_coordinates(
    model: KinematicModel,
    *,
    link: Any = None,
    point: Any = None,
    rotations: bool = True,
    rtol: float = 1e-9,
) -> TaskCoordinates:
    """The coordinates of a link's motion, read off its twist system at the reference configuration.

    The link's twists are those its tree path gives for the joint rates the loops allow (the null
    space of the loop-closure Jacobian). Their angular parts span the rotation directions; the
    twists without one span the translation directions (a helical freedom has a rotation and no
    translation coordinate). Coordinates along the reference frame's axes are named ``x, y, z``
    (translations) and ``rx, ry, rz`` (rotations, or ``phi`` when there is one rotation, about its
    axis); other directions ``t1, t2`` and ``r1, r2`` (their directions in ``.directions``).

    Parameters
    ----------
    model : KinematicModel
    link : hashable, optional
        Default: the platform.
    point : array_like, shape (3,), optional
        The point of the link measured, in the graph's frame at the reference; default: the
        centroid of the points of the joints on the link (their own points when they were built
        with one, else their axes' points nearest the mechanism's reference point).
    rotations : bool, default True
        False: only the point's position (a point task; the link's orientation stays free).
    rtol : float, default 1e-9
        Relative tolerance of the rank decisions.

    Returns
    -------
    TaskCoordinates

    Raises
    ------
    ScrewkitValueError
        If the link does not move, or names no link of the graph.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> scara = twist_graph("B", "E", [("B", "L1", revolute("R1", [0, 0, 1], [0, 0, 0])),
    ...                                ("L1", "L2", revolute("R2", [0, 0, 1], [1, 0, 0])),
    ...                                ("L2", "L3", prismatic("P", [0, 0, 1])),
    ...                                ("L3", "E", revolute("R3", [0, 0, 1], [1, 1, 0]))], dof=4)
    >>> task_coordinates(KinematicModel(scara)).names
    ('x', 'y', 'z', 'phi')
    """
    link = model.platform if link is None else link
    if link not in model.paths:
        raise ScrewkitValueError(f"Expected `link` to name a link of the graph, got {link!r}.")
    if point is None:
        point = _joint_centroid(model, link)
    centre = np.asarray(point, dtype=float).reshape(3)
    state = model.state(np.zeros((1, model.size)))
    allowed = _null_space(model.loop_jacobian(state)[0], rtol)
    twists = (model.link_jacobian(state, link)[0] @ allowed).T  # (m, 6), scaled frame
    system = _orthonormal_rows(twists, rtol)
    if system.shape[0] == 0:
        raise ScrewkitValueError(f"Expected a link that moves, got {link!r}, which the loops hold fixed.")
    local = model.to_scaled_points(centre)
    omega, velocity = system[:, :3], system[:, 3:] + np.cross(system[:, :3], -local)  # v + ω × (−c)
    # velocities of the point: v(c) = v + ω × c
    if not rotations:
        translations = _orthonormal_rows(velocity, rtol)
        names, directions = _named_basis(translations, "t", None)
        return TaskCoordinates(tuple(names), ("translation",) * len(names), directions, link, centre)
    rotation_basis = _orthonormal_rows(omega, rtol)
    without_rotation = _null_space(omega.T, rtol)  # combinations of the twists with ω = 0
    translations = _orthonormal_rows((velocity.T @ without_rotation).T, rtol)
    t_names, t_directions = _named_basis(translations, "t", None)
    r_names, r_directions = _named_basis(rotation_basis, "r", "phi")
    kinds = ("translation",) * len(t_names) + ("rotation",) * len(r_names)
    directions = np.concatenate([t_directions, r_directions]).reshape(-1, 3)
    return TaskCoordinates(tuple(t_names + r_names), kinds, directions, link, centre)


def _joint_centroid(model: KinematicModel, link: Any) -> Array:
    """The centroid of the points of the joints on a link (graph frame): a joint's own point when it was
    built with one, else its axes' point nearest to the mechanism's reference point (finite-pitch
    joints only); the reference point when the link has none."""
    points = []
    for key, (u, v, indices) in model.joints.items():
        if link not in (u, v):
            continue
        if key in model.joint_points:
            points.append(model.to_scaled_points(model.joint_points[key]))
            continue
        rows = np.array([model.columns[i].row for i in indices])
        finite = rows[np.linalg.norm(rows[:, :3], axis=1) > 1e-12]
        if len(finite) == 0:
            continue
        # the point nearest the scaled origin on all the joint's axes (one point for R, U, S)
        matrix = np.concatenate([-hat(r[:3]) for r in finite])
        moment = np.concatenate([r[3:] for r in finite])
        points.append(np.linalg.lstsq(matrix, -moment, rcond=None)[0])
    if not points:
        return model.point.copy()
    return model.point + model.length * np.mean(points, axis=0)


def _complement(directions: Array) -> Array:
    """An orthonormal basis ``(3 − k, 3)`` of the directions orthogonal to ``directions (k, 3)``."""
    if len(directions) == 0:
        return np.eye(3)
    _, _, vt = np.linalg.svd(directions)
    return vt[len(directions):]


def _left_jacobian_inverse(phi: Array) -> Array:
    """``J_l(φ)⁻¹`` with ``d/dt log R = J_l(φ)⁻¹ ω`` for the spatial angular velocity ``ω``
    (Chirikjian, *Stochastic Models, Information Theory, and Lie Groups*, vol. 2, 2012, Eq. 10.86;
    the series ``1/12`` near 0)."""
    angle = np.linalg.norm(phi, axis=-1)
    k = hat(phi)
    with np.errstate(divide="ignore", invalid="ignore"):
        small = angle < 1e-6
        safe = np.where(small, 1.0, angle)
        coefficient = np.where(
            small, 1.0 / 12.0, 1.0 / safe**2 - (1 + np.cos(safe)) / (2 * safe * np.sin(safe))
        )
    return np.eye(3) - 0.5 * k + coefficient[..., None, None] * (k @ k)


class PoseTask:
    """The coordinates of a link (:func:`task_coordinates`) as equations of the joint values.

    Parameters
    ----------
    model : KinematicModel
    coordinates : TaskCoordinates

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
    >>> task = PoseTask(model, task_coordinates(model, point=[0, 0, 0]))
    >>> task.values(model.state(np.array([[2.0]]))).tolist()  # x of the point (2 char. lengths)
    [[2.0]]
    """

    def __init__(self, model: KinematicModel, coordinates: TaskCoordinates, *, complete: bool = False):
        self.model = model
        self.coordinates = coordinates
        translation = np.array([k == "translation" for k in coordinates.kinds], dtype=bool)
        directions = coordinates.directions.reshape(-1, 3)
        if complete:  # the directions the coordinates leave out, held at their reference values
            extra_t = _complement(directions[translation])
            extra_r = _complement(directions[~translation])
            directions = np.concatenate([directions, extra_t, extra_r])
            translation = np.concatenate([translation, np.ones(len(extra_t), bool), np.zeros(len(extra_r), bool)])
        self.directions = directions
        self.translation = translation
        self.local = model.to_scaled_points(coordinates.point)

    def scaled_targets(self, values: Array) -> Array:
        """Coordinates ``(B, n)`` in the graph's unit → the task's scaled values ``(B, m)`` (with a
        complete task, the left-out directions' reference values appended).

        Parameters
        ----------
        values : numpy.ndarray, shape (B, n)

        Returns
        -------
        numpy.ndarray, shape (B, m)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> task = PoseTask(model, task_coordinates(model, point=[0, 0, 0]))
        >>> bool(np.allclose(task.unscaled(task.scaled_targets(np.array([[3.0]]))), 3.0))
        True
        >>> PoseTask(model, task.coordinates, complete=True).scaled_targets(np.array([[3.0]])).shape
        (1, 6)
        """
        values = np.asarray(values, dtype=float)
        n = len(self.coordinates.names)
        offset = self.directions[:n] @ self.model.point
        scaled = np.where(self.translation[:n], (values - offset) / self.model.length, values)
        held = np.where(self.translation[n:], self.directions[n:] @ self.local, 0.0)
        return np.concatenate([scaled, np.broadcast_to(held, (len(values), len(held)))], axis=1)

    def unscaled(self, values: Array) -> Array:
        """The coordinates ``(B, n)`` in the graph's unit from the task's scaled values ``(B, m)``.

        Parameters
        ----------
        values : numpy.ndarray, shape (B, m)

        Returns
        -------
        numpy.ndarray, shape (B, n)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> PoseTask(model, task_coordinates(model, point=[0, 0, 0])).unscaled(np.zeros((1, 1))).shape
        (1, 1)
        """
        n = len(self.coordinates.names)
        offset = self.directions[:n] @ self.model.point
        return np.where(self.translation[:n], values[:, :n] * self.model.length + offset, values[:, :n])

    def values(self, state: KinematicState) -> Array:
        """The task's scaled values at a state, ``(B, n)``.

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, n)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> task = PoseTask(model, task_coordinates(model, point=[1, 0, 0]))
        >>> task.coordinates.names, task.values(model.state(np.array([[0.5]])))[:, -1].tolist()
        (('phi',), [0.5])
        """
        g = state.links[self.coordinates.link]
        position = np.einsum("bij,j->bi", g[:, :3, :3], self.local) + g[:, :3, 3]
        rotation = rotation_log(g[:, :3, :3])
        return np.where(self.translation, position @ self.directions.T, rotation @ self.directions.T)

    def difference(self, values: Array, targets: Array) -> Array:
        """``values − targets``, rotations wrapped into ``(−π, π]`` (a rotation coordinate is read from
        the link's rotation, which is the same a turn later; the continuation's small steps keep
        track of the turns, so a helical joint can go round more than once).

        Parameters
        ----------
        values, targets : numpy.ndarray, shape (B, n)

        Returns
        -------
        numpy.ndarray, shape (B, n)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> task = PoseTask(model, task_coordinates(model))
        >>> task.difference(np.array([[3.0]]), np.array([[-3.0]])).round(6).tolist()  # 6 rad less a turn
        [[-0.283185]]
        """
        difference = values - targets
        wrapped = difference - 2 * np.pi * np.round(difference / (2 * np.pi))
        return np.where(self.translation, difference, wrapped)

    def jacobian(self, state: KinematicState) -> Array:
        """The Jacobian of :meth:`values` in the joint variables, ``(B, n, columns)``.

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, n, columns)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> task = PoseTask(model, task_coordinates(model, point=[1, 0, 0]))
        >>> task.coordinates.names, task.jacobian(model.state(np.zeros((1, 1))))[0, :, 0].tolist()
        (('phi',), [1.0])
        """
        g = state.links[self.coordinates.link]
        twist = self.model.link_jacobian(state, self.coordinates.link)  # (B, 6, columns)
        omega, velocity = twist[:, :3], twist[:, 3:]
        position = np.einsum("bij,j->bi", g[:, :3, :3], self.local) + g[:, :3, 3]
        point_velocity = velocity - hat(position) @ omega  # v + ω × p
        log_rate = _left_jacobian_inverse(rotation_log(g[:, :3, :3])) @ omega
        directions = self.directions
        return np.where(
            self.translation[None, :, None],
            np.einsum("nk,bkc->bnc", directions, point_velocity),
            np.einsum("nk,bkc->bnc", directions, log_rate),
        )


class JointTask:
    """The values of some joint variables (the actuated joints) as the task.

    Parameters
    ----------
    model : KinematicModel
    joints : sequence of str
        One-degree-of-freedom joints, in the order of the targets.

    Raises
    ------
    ScrewkitValueError
        If a name is not a one-degree-of-freedom joint of the model.

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
    >>> JointTask(model, ["P"]).values(model.state(np.array([[0.3]]))).tolist()
    [[0.3]]
    """

    def __init__(self, model: KinematicModel, joints: Any):
        self.model = model
        self.columns = []
        self.sliding = []
        for name in joints:
            if name not in model.joints or len(model.joints[name][2]) != 1:
                raise ScrewkitValueError(
                    f"Expected one-degree-of-freedom joints of the graph, got {name!r}."
                )
            index = model.joints[name][2][0]
            self.columns.append(index)
            column = model.columns[index]
            self.sliding.append(column.hinge is None and np.linalg.norm(column.row[:3]) < 1e-12)
        self.sliding_mask = np.array(self.sliding, dtype=bool)

    def scaled_targets(self, values: Array) -> Array:
        """Joint displacements ``(B, k)`` (radians, graph lengths) → the task's scaled values.

        Parameters
        ----------
        values : numpy.ndarray, shape (B, k)

        Returns
        -------
        numpy.ndarray, shape (B, k)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> bool(np.allclose(JointTask(model, ["P"]).scaled_targets(np.array([[model.length]])), 1.0))
        True
        """
        return np.where(self.sliding_mask, values / self.model.length, values)

    def unscaled(self, values: Array) -> Array:
        """The inverse of :meth:`scaled_targets`.

        Parameters
        ----------
        values : numpy.ndarray, shape (B, k)

        Returns
        -------
        numpy.ndarray, shape (B, k)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> JointTask(model, ["P"]).unscaled(np.zeros((1, 1))).tolist()
        [[0.0]]
        """
        return np.where(self.sliding_mask, values * self.model.length, values)

    def values(self, state: KinematicState) -> Array:
        """The joints' values at a state, ``(B, k)`` (scaled).

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, k)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> JointTask(model, ["P"]).values(model.state(np.zeros((2, 1)))).shape
        (2, 1)
        """
        return state.theta[:, self.columns]

    def difference(self, values: Array, targets: Array) -> Array:
        """``values − targets`` (a joint's value counts its turns).

        Parameters
        ----------
        values, targets : numpy.ndarray, shape (B, k)

        Returns
        -------
        numpy.ndarray, shape (B, k)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> JointTask(model, ["P"]).difference(np.array([[3.0]]), np.array([[-3.0]])).tolist()
        [[6.0]]
        """
        return values - targets

    def jacobian(self, state: KinematicState) -> Array:
        """Unit rows on the joints' columns, ``(B, k, columns)``.

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, k, columns)

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> JointTask(model, ["P"]).jacobian(model.state(np.zeros((1, 1)))).tolist()
        [[[1.0]]]
        """
        rows = np.zeros((state.theta.shape[0], len(self.columns), self.model.size))
        rows[:, np.arange(len(self.columns)), self.columns] = 1.0
        return rows


@dataclass(frozen=True)
class ClosedConfigurations:
    """The continuation's result over a batch.

    Attributes
    ----------
    theta : numpy.ndarray, shape (B, n)
        Joint values (spherical joints' in ``offsets``).
    offsets : dict
        Spherical joint name → rotation offsets ``(B, 4, 4)``.
    reached : numpy.ndarray of bool, shape (B,)
        True where the loops and the task closed to :data:`FINAL_TOLERANCE`.
    residual : numpy.ndarray, shape (B,)
        The largest loop or task residual (characteristic lengths, radians).
    reasons : numpy.ndarray of str, shape (B,)
        Why a pose was not reached (empty where it was).
    """

    theta: Array
    offsets: dict[str, Array]
    reached: Array
    residual: Array
    reasons: Array


def _solve_step(jacobian: Array, residual: Array) -> Array:
    """The minimum-norm Gauss–Newton correction ``−Jᵀ (J Jᵀ + λ I)⁻¹ F`` per pose (module docstring)."""
    gram = jacobian @ np.swapaxes(jacobian, -1, -2)
    damping = 1e-13 * (np.trace(gram, axis1=-2, axis2=-1)[:, None, None] + 1.0)
    multipliers = np.linalg.solve(gram + damping * np.eye(gram.shape[-1]), residual[..., None])[..., 0]
    return -np.einsum("bji,bj->bi", jacobian, multipliers)


def _equations(model: KinematicModel, task: Any, state: KinematicState, target: Array) -> tuple[Array, Array]:
    residual = np.concatenate([model.loop_residual(state), task.difference(task.values(state), target)], axis=1)
    jacobian = np.concatenate([model.loop_jacobian(state), task.jacobian(state)], axis=1)
    return residual, jacobian


def _continue(
    model: KinematicModel, task: Any, targets: Array, theta: Array, offsets: dict[str, Array],
    start: Array, step_length: float, jump_limit: float,
) -> tuple[Array, dict[str, Array], Array, Array]:
    """One continuation of a chunk, each pose in equal steps of at most ``step_length`` (a pose whose
    way is done rests); returns theta, offsets, the residual at the targets (inf where non-finite)
    and the fraction of the way where each pose was lost (NaN if not)."""
    count = targets.shape[0]
    lost_at = np.full(count, np.nan)
    active = np.ones(count, dtype=bool)
    residual_size = np.zeros(count)
    spherical = np.array(
        [i for key, kind in model.types.items() if kind == "S" for i in model.joints[key][2]], dtype=int
    )
    way = np.max(np.abs(targets - start), axis=1, initial=0.0)
    own = np.clip(np.ceil(way / step_length), 1, MAX_STEPS)
    steps = int(np.max(own, initial=1))
    for step in range(1, steps + 1):
        moving = step <= own
        target = start + (targets - start) * np.minimum(1.0, step / own)[:, None]
        tolerance = np.where(step >= own, LAST_STEP_TOLERANCE, STEP_TOLERANCE)
        corrected = np.zeros(count)  # the corrections after each pose's first iteration
        first = np.ones(count, dtype=bool)
        working = active & moving
        for _ in range(NEWTON_ITERATIONS):  # only the poses not yet within the tolerance
            rows = np.flatnonzero(working)
            if rows.size == 0:
                break
            state = model.state(theta[rows], {k: v[rows] for k, v in offsets.items()})
            residual, jacobian = _equations(model, task, state, target[rows])
            size = np.max(np.abs(residual), axis=1, initial=0.0)
            residual_size[rows] = size
            need = size > tolerance[rows]
            working[rows[~need]] = False
            rows = rows[need]
            if rows.size == 0:
                break
            correction = _solve_step(jacobian[need], residual[need])
            length = np.max(np.abs(correction), axis=1, initial=0.0)
            correction *= np.minimum(1.0, MAX_CORRECTION / np.maximum(length, 1e-300))[:, None]
            theta[rows] += correction
            corrected[rows] += np.where(first[rows], 0.0, np.minimum(length, MAX_CORRECTION))
            first[rows] = False
        bad = ~np.isfinite(residual_size) | ~np.all(np.isfinite(theta), axis=1)
        newly = active & moving & (bad | (residual_size > LOST_TOLERANCE) | (corrected > jump_limit))
        lost_at[newly] = np.minimum(1.0, step / own[newly])
        active &= ~newly
        theta[~np.all(np.isfinite(theta), axis=1)] = 0.0  # frozen and flagged, never propagated
        if spherical.size:  # fold the spherical joints' angles into their offsets before they grow
            turned = np.flatnonzero(np.max(np.abs(theta[:, spherical]), axis=1) > RECENTRE_ANGLE)
            if turned.size:
                sub = {k: v[turned] for k, v in offsets.items()}
                new_theta, new_offsets = model.recentred(model.state(theta[turned], sub))
                theta[turned] = new_theta
                for key, value in new_offsets.items():
                    offsets.setdefault(key, np.tile(np.eye(4), (count, 1, 1)))[turned] = value
    state = model.state(theta, offsets)
    residual, _ = _equations(model, task, state, targets)
    size = np.max(np.abs(residual), axis=1, initial=0.0)
    size[~active] = np.maximum(size[~active], LOST_TOLERANCE)  # a lost pose is never accepted
    return theta, offsets, np.where(np.isfinite(size), size, np.inf), lost_at


def close_loops(
    model: KinematicModel,
    task: Any,
    targets: Array,
    *,
    start: tuple[Array, dict[str, Array]] | None = None,
) -> ClosedConfigurations:
    """Joint values closing the loops and the task at each target, by continuation (module docstring).

    Parameters
    ----------
    model : KinematicModel
    task : PoseTask or JointTask
    targets : numpy.ndarray, shape (B, k)
        The task's scaled values (``task.scaled_targets``).
    start : tuple, optional
        ``(theta (n,), offsets)`` of a closed configuration to start from (one for the whole batch);
        default: the reference configuration.

    Returns
    -------
    ClosedConfigurations

    Raises
    ------
    ScrewkitValueError
        If ``targets`` is not finite or has the wrong shape.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> arm = twist_graph("B", "E", [
    ...     ("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0], actuated=True))], dof=2)
    >>> model = KinematicModel(arm)
    >>> task = PoseTask(model, task_coordinates(model, point=[1, 1, 0], rotations=False))
    >>> closed = close_loops(model, task, task.scaled_targets(np.array([[3.0, 0.0]])))  # beyond reach
    >>> bool(closed.reached[0]), closed.reasons[0][:38]
    (False, 'the loops and the task do not close at')
    """
    targets = np.asarray(targets, dtype=float)
    if targets.ndim != 2 or not np.all(np.isfinite(targets)):
        raise ScrewkitValueError(f"Expected finite targets of shape (B, k), got shape {targets.shape}.")
    if start is None:
        start_theta, start_offsets = np.zeros(model.size), {}
    else:
        start_theta, start_offsets = start
    out_theta = np.zeros((len(targets), model.size))
    out_offsets: dict[str, list[Array]] = {}
    residual = np.zeros(len(targets))
    reasons = np.full(len(targets), "", dtype=object)
    for begin in range(0, len(targets), CHUNK):
        chunk = slice(begin, begin + CHUNK)
        result = _close_chunk(model, task, targets[chunk], start_theta, start_offsets)
        out_theta[chunk], residual[chunk], reasons[chunk] = result[0], result[2], result[3]
        for key, value in result[1].items():
            out_offsets.setdefault(key, []).append(value)
    reached = residual < FINAL_TOLERANCE
    offsets = {key: np.concatenate(parts) for key, parts in out_offsets.items()}
    return ClosedConfigurations(out_theta, offsets, reached, residual, reasons)


def _close_chunk(
    model: KinematicModel, task: Any, targets: Array, start_theta: Array, start_offsets: dict[str, Array]
) -> tuple[Array, dict[str, Array], Array, Array]:
    count = len(targets)

    def begin(rows: Array) -> tuple[Array, dict[str, Array], Array]:
        theta = np.tile(start_theta, (int(rows.sum()), 1))
        offsets = {k: np.repeat(v[:1] if v.ndim == 3 else v[None], int(rows.sum()), axis=0)
                   for k, v in start_offsets.items()}
        values = task.values(model.state(theta[:1], {k: v[:1] for k, v in offsets.items()}))
        return theta, offsets, np.repeat(values, len(theta), axis=0)

    everything = np.ones(count, dtype=bool)
    theta, offsets, start = begin(everything)
    theta, offsets, residual, lost_at = _continue(model, task, targets, theta, offsets, start, MAX_STEP, JUMP_LIMIT)
    missed = ~(residual < FINAL_TOLERANCE)
    if np.any(missed):  # again, in shorter steps
        retry_theta, retry_offsets, retry_start = begin(missed)
        again = _continue(  # the steps are short: the corrections may be what they need
            model, task, targets[missed], retry_theta, retry_offsets, retry_start,
            MAX_STEP / RETRY_REFINEMENT, math.inf,
        )
        theta[missed] = again[0]
        for key in offsets:
            offsets[key][missed] = again[1][key]
        residual[missed], lost_at[missed] = again[2], again[3]
    reasons = np.full(count, "", dtype=object)
    for index in np.flatnonzero(~(residual < FINAL_TOLERANCE)):
        where = lost_at[index]
        if np.isfinite(residual[index]):
            at = f"{100 * where:.0f}% of the way from the start" if np.isfinite(where) else "the end"
            reasons[index] = (
                f"the loops and the task do not close at {at} (residual {residual[index]:.1e} "
                "characteristic lengths): the pose is out of the mechanism's reach, or past a "
                "singularity where the continuation from the reference configuration stops"
            )
        else:
            reasons[index] = "Newton's method gave non-finite joint values on the way to the pose"
    return theta, offsets, residual, reasons
