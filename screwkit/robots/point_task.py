"""A point task: what a mechanism's actuators must control is the velocity of one point of a link.

A planar five-bar's end point, a Delta's tool tip taken as a point: the user controls the point's
position and leaves the link's orientation free. The analysis then measures the task, not the link:
:func:`with_task_point` hangs a *task link* on the measured link by a spherical joint at the point
(three rotations through it, not actuated), and makes it the platform, with ``free = 3``
(:attr:`JointTable.free <screwkit.graphs.jointtable.JointTable.free>`). The task link's twists are
the link's plus every rotation about the point, so

* its constraint wrenches are the forces through the point that no motion of the point works against
  (the directions the point cannot move in);
* each limb's actuation wrench lies among the forces through the point (the limb's passive wrench
  system with the spherical joint in every limb), and its serial singularity is where its actuator
  cannot move the *point*;
* the global wrench system ``W^c + W^a`` spans at most the three forces through the point, so an
  actuation singularity is ``order(W^c + W^a) < 6 − free = 3``
  (:mod:`screwkit.core.verdicts`), and the Jacobians' twist basis is one twist per freedom of the point
  (``A_jk = w_j ∘ t_k = f_j · e_k``: the force directions; :mod:`screwkit.core.jacobians`).

For the planar five-bar with its end point ``C`` as the task this gives the classic Jacobians of
``A ẋ = B θ̇`` (Gosselin & Angeles, IEEE Trans. Robot. Autom. 6(3), 1990, the five-bar example;
Liu, Wang & Pritschow, "Kinematics, singularity and workspace of planar 5R symmetrical parallel
mechanisms", Mech. Mach. Theory 41(2), 2006): row ``i`` of ``A`` the unit direction ``u_i`` of
distal link ``i`` (from its elbow ``B_i`` to ``C``) and ``B_ii = ((B_i − A_i) × u_i)·z``. Either leg
stretched or folded (``A_i``, ``B_i``, ``C`` in line) is a serial singularity, the same kind for both
legs; the distal links in line (``u_1 ∥ u_2``) an actuation singularity
(``tests/robots/test_point_task.py`` checks both against these formulas).

Examples
--------
>>> from screwkit.graphs.jointtable import JointTable
>>> slider = ("B", "E", "P", "P", [[[0, 0, 0, 1.0, 0, 0]]], True)
>>> task = with_task_point(JointTable.from_rows("B", "E", [slider]), "E", np.array([[1.0, 2.0, 0.0]]), 1)
>>> task.platform, task.dof, task.free, task.joint_screws(TASK_JOINT)[0, 2].tolist()
('task point', 4, 3, [0.0, 0.0, 1.0, 2.0, -1.0, 0.0])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from ..graphs.jointtable import JointSpec, JointTable

__all__ = ["TASK_JOINT", "TASK_LINK", "with_task_point"]

Array = np.ndarray

#: The task link and its spherical joint, added by :func:`with_task_point`.
TASK_LINK = "task point"
TASK_JOINT = "task point S"


def with_task_point(table: JointTable, link: Any, points: Array, freedoms: int) -> JointTable:
    """The joint table with a task link on a spherical joint at a point of ``link`` as its platform.

    Parameters
    ----------
    table : JointTable
        The mechanism's joints over a batch.
    link : hashable
        The link the point is fixed in.
    points : numpy.ndarray, shape (..., 3)
        The point at each configuration of the batch (the table's length unit).
    freedoms : int
        The point's freedoms (its coordinates): the task link has ``freedoms + 3``.

    Returns
    -------
    JointTable
        Platform :data:`TASK_LINK`, ``dof = freedoms + 3``, ``free = 3``.

    Raises
    ------
    ScrewkitValueError
        If the mechanism already has a link or joint of those names, or ``link`` is none of its links.

    Examples
    --------
    A slider along ``x`` with its point ``(1, 2, 0)`` as the task: one freedom of the point, three free
    rotations about it.

    >>> slider = ("B", "E", "P", "P", [[[0, 0, 0, 1.0, 0, 0]]], True)
    >>> task = with_task_point(JointTable.from_rows("B", "E", [slider]), "E", [[1.0, 2.0, 0.0]], 1)
    >>> [spec.name for spec in task.specs], task.batch_shape
    (['P', 'task point S'], (1,))
    """
    links = {spec.parent for spec in table.specs} | {spec.child for spec in table.specs}
    if link not in links:
        raise ScrewkitValueError(f"Expected the task's link to be a link of the mechanism, got {link!r}.")
    if TASK_LINK in links or TASK_JOINT in {spec.name for spec in table.specs}:
        raise ScrewkitValueError(
            f"Expected no link {TASK_LINK!r} nor joint {TASK_JOINT!r} in a mechanism with a point task "
            "(the names of its task link and joint): rename them."
        )
    centre = np.broadcast_to(np.asarray(points, dtype=float), (*table.batch_shape, 3))
    axes = np.broadcast_to(np.eye(3), (*table.batch_shape, 3, 3))
    rotations = np.concatenate([axes, np.cross(centre[..., None, :], axes)], axis=-1)  # (s; p × s)
    screws = np.concatenate([table.screws, rotations], axis=-2)
    spec = JointSpec(TASK_JOINT, "S", link, TASK_LINK, 3, False)
    return JointTable(
        table.base, TASK_LINK, (*table.specs, spec), screws, freedoms + 3, table.anchor, None, 3
    )
