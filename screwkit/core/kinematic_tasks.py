"""The equations a task adds to a mechanism's loop closure: the coordinates of a link
(:class:`PoseTask`) or the values of some joints (:class:`JointTask`), with their Jacobians in the
joint variables (the link's twist carried to its point, and the rotation vector's rate through the
inverse of the left Jacobian of SO(3)).

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> from screwkit.core.task_coordinates import task_coordinates
>>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
>>> JointTask(model, ["P"]).values(model.state(np.array([[0.25]]))).tolist()
[[0.25]]
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ..algebra.rigid_motions import hat, rotation_log, rotation_matrix
from ..exceptions import ScrewkitValueError
from .kinematic_model import KinematicModel, KinematicState
from .task_coordinates import TaskCoordinates

__all__ = ["JointTask", "PoseTask"]

Array = np.ndarray


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
    """The coordinates of a link (:func:`~screwkit.core.task_coordinates.task_coordinates`) as
    equations of the joint values.

    Parameters
    ----------
    model : KinematicModel
    coordinates : TaskCoordinates

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.task_coordinates import task_coordinates
    >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
    >>> task = PoseTask(model, task_coordinates(model, point=[0, 0, 0]))
    >>> task.values(model.state(np.array([[2.0]]))).tolist()  # x of the point (2 char. lengths)
    [[2.0]]
    """

    def __init__(self, model: KinematicModel, coordinates: TaskCoordinates, *, complete: bool = False):
        self.model = model
        #: What a solver prepares once for this task (:func:`~screwkit.core.loop_closure.close_loops`
        #: keeps its system of equations here, built on the first call).
        self.prepared: dict[str, Any] = {}
        self.coordinates = coordinates
        translation = np.array([k == "translation" for k in coordinates.kinds], dtype=bool)
        directions = coordinates.directions.reshape(-1, 3)
        if complete:  # the directions the coordinates leave out, held at their reference values
            extra_t = _complement(directions[translation])
            extra_r = _complement(directions[~translation])
            directions = np.concatenate([directions, extra_t, extra_r])
            held = [np.ones(len(extra_t), bool), np.zeros(len(extra_r), bool)]
            translation = np.concatenate([translation, *held])
        self.directions = directions
        self.translation = translation
        self.local = model.to_scaled_points(coordinates.point)
        moves, turns = directions[translation], directions[~translation]
        #: True when the task's values fix the link's whole pose (three independent translation
        #: directions and three rotation directions): :meth:`displacement` then gives it.
        self.fixes_pose = bool(
            len(moves) == 3 == len(turns)
            and np.linalg.matrix_rank(moves) == 3 == np.linalg.matrix_rank(turns)
        )

    def displacement(self, values: Array) -> Array:
        """The link's displacement ``(B, 4, 4)`` (scaled frame) at which the task takes ``values``
        ``(B, 6)``, for a task that :attr:`fixes_pose`: the rotation ``exp([φ]×)`` of the rotation
        vector ``φ`` and the translation that puts the task's point at its position.

        Parameters
        ----------
        values : numpy.ndarray, shape (B, 6)
            The task's scaled values.

        Returns
        -------
        numpy.ndarray, shape (B, 4, 4)

        Raises
        ------
        ScrewkitValueError
            If the task does not fix the link's pose.

        Examples
        --------
        >>> from screwkit.core.task_coordinates import task_coordinates
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> hinge = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [2, 0, 0]))]))
        >>> held = PoseTask(hinge, task_coordinates(hinge, point=[1, 0, 0]), complete=True)
        >>> turned = hinge.state(np.array([[0.7]]))  # about the hinge at x = 2
        >>> bool(np.allclose(held.displacement(held.values(turned)), turned.links["E"]))
        True
        """
        if not self.fixes_pose:
            raise ScrewkitValueError(
                "Expected a task that fixes the link's whole pose, got the coordinates "
                f"{self.coordinates.names}."
            )
        values = np.asarray(values, dtype=float)
        position = values[:, self.translation] @ self._inverses[0].T
        vector = values[:, ~self.translation] @ self._inverses[1].T
        angle = np.linalg.norm(vector, axis=1)
        axis = np.where(angle[:, None] > 0, vector / np.where(angle > 0, angle, 1.0)[:, None], 0.0)
        out = np.zeros((len(values), 4, 4))
        out[:, :3, :3] = rotation_matrix(axis, angle)
        out[:, :3, 3] = position - out[:, :3, :3] @ self.local
        out[:, 3, 3] = 1.0
        return out

    @functools.cached_property
    def _inverses(self) -> tuple[Array, Array]:
        """The inverses of the translation and of the rotation directions (rows), for :meth:`displacement`."""
        directions = self.directions
        return np.linalg.inv(directions[self.translation]), np.linalg.inv(directions[~self.translation])

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
        >>> from screwkit.core.task_coordinates import task_coordinates
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
        >>> from screwkit.core.task_coordinates import task_coordinates
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
        >>> from screwkit.core.task_coordinates import task_coordinates
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
        >>> from screwkit.core.task_coordinates import task_coordinates
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
        >>> from screwkit.core.task_coordinates import task_coordinates
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> task = PoseTask(model, task_coordinates(model, point=[1, 0, 0]))
        >>> task.coordinates.names, task.jacobian(model.state(np.zeros((1, 1))))[0, :, 0].tolist()
        (('phi',), [1.0])
        """
        twist = self.model.link_jacobian(state, self.coordinates.link)  # (B, 6, columns)
        return self.twist_rates(state) @ twist

    def twist_rates(self, state: KinematicState) -> Array:
        """The task's rates per unit twist of its link, ``(B, m, 6)``: the point's velocity
        ``v + ω × p`` along the translation directions, the rotation vector's rate ``J_l(φ)⁻¹ ω``
        along the rotation directions (twists ``(ω; v)`` spatial, scaled frame).

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, m, 6)

        Examples
        --------
        >>> from screwkit.core.task_coordinates import task_coordinates
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> crank = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> point = PoseTask(crank, task_coordinates(crank, point=[1, 0, 0], rotations=False))
        >>> point.coordinates.names, point.twist_rates(crank.state(np.zeros((1, 1))))[0, -1].tolist()
        (('y',), [0.0, 0.0, 1.0, 0.0, 1.0, 0.0])
        """
        g = state.links[self.coordinates.link]
        position = np.einsum("bij,j->bi", g[:, :3, :3], self.local) + g[:, :3, 3]
        log_rate = _left_jacobian_inverse(rotation_log(g[:, :3, :3]))  # per unit ω
        moved = np.concatenate([-hat(position), np.broadcast_to(np.eye(3), (*position.shape, 3))], axis=-1)
        turned = np.concatenate([log_rate, np.zeros_like(log_rate)], axis=-1)
        return np.where(
            self.translation[None, :, None],
            np.einsum("nk,bkc->bnc", self.directions, moved),
            np.einsum("nk,bkc->bnc", self.directions, turned),
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
        #: What a solver prepares once for this task (as :attr:`PoseTask.prepared`).
        self.prepared: dict[str, Any] = {}
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
