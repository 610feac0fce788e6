"""The coordinates of a link's motion, read off its twist system at a mechanism's reference
configuration: names (``x, y, z`` and ``phi`` or ``rx, ry, rz`` along the reference frame's axes,
``t1 …``/``r1 …`` otherwise), kinds and directions (:func:`task_coordinates`).

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> arm = twist_graph("B", "E", [("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0])),
...                              ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))], dof=2)
>>> task_coordinates(KinematicModel(arm), point=[1, 1, 0], rotations=False).names
('x', 'y')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..algebra.rigid_motions import hat
from ..exceptions import ScrewkitValueError
from .kinematic_model import KinematicModel

__all__ = ["COORDINATE_NAMES", "TaskCoordinates", "task_coordinates"]

Array = np.ndarray

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


def _orthonormal_rows(matrix: Array, rtol: float, scale: float | None = None) -> Array:
    """An orthonormal basis of the row space of ``matrix (m, k)``, ``(rank, k)``: the singular values
    above ``rtol`` times ``scale`` (default: the largest singular value; give the scale of the rows
    the matrix was taken from, so that a part of them that is only round-off is rank 0)."""
    if matrix.size == 0:
        return np.zeros((0, matrix.shape[1]))
    _, sigma, vt = np.linalg.svd(matrix, full_matrices=False)
    size = (sigma[0] if sigma.size else 0.0) if scale is None else scale
    rank = int(np.sum(sigma > rtol * max(size, 1e-300)))
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
        translations = _orthonormal_rows(velocity, rtol, scale=1.0)
        names, directions = _named_basis(translations, "t", None)
        return TaskCoordinates(tuple(names), ("translation",) * len(names), directions, link, centre)
    rotation_basis = _orthonormal_rows(omega, rtol, scale=1.0)  # the system's rows are unit
    without_rotation = _null_space(omega.T, rtol)  # combinations of the twists with ω = 0
    translations = _orthonormal_rows((velocity.T @ without_rotation).T, rtol, scale=1.0)
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
