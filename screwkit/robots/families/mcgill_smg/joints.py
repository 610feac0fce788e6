"""The McGill SMG's joint table (the 20 physical joints) and nominal twists (the family protocol's
``joints`` and ``twist_basis``).

Examples
--------
>>> config = load_mechanism("mcgill_smg").configuration()
>>> len(joints(config).specs), twist_basis(config).shape
(20, (4, 6))
"""

from __future__ import annotations

import numpy as np

from ....core.jacobians import schoenflies_basis
from ....graphs.jointtable import JointTable
from ...two_limb import (
    joint_row,
)
from .configuration import McGillConfiguration
from .parameters import LEGS

__all__ = ["joints", "twist_basis"]


# --------------------------------------------------------------------------------------------------
# The family protocol: joints and twist basis (screwkit.robots.families)
# --------------------------------------------------------------------------------------------------


def joints(config: McGillConfiguration) -> JointTable:
    """The 20 physical joints of the McGill SMG over the batch of ``config`` (docs/architecture.md §1a, §5).

    Each leg is the R-Π-Π-R chain of paper 001 (Sec. 3) with each Π joint modelled by its four
    revolute joints; nothing is reduced, so each leg keeps two closed loops, which
    :func:`screwkit.graphs.reduction.equivalent_twist_graph` reduces to virtual translations. Per leg
    ``J``: ``J.pan`` (``base`` → ``J.carrier``, axis ``k`` through ``O_J0``, actuated), the
    proximal parallelogram ``J.proximal.a`` (``J.carrier`` → ``J.proximal_a`` at ``O_J1``,
    actuated tilt), ``J.proximal.b`` (``J.carrier`` → ``J.proximal_b`` at ``O_J1 + w k``),
    ``J.proximal.c`` (``J.proximal_a`` → ``J.elbow`` at ``O_J2``), ``J.proximal.d``
    (``J.proximal_b`` → ``J.elbow`` at ``O_J2 + w k``), all along ``f_J``; the distal parallelogram
    ``J.distal.a``-``d`` likewise from ``J.elbow`` to ``J.wrist`` (corners ``O_J2``,
    ``O_J2 + w k``, ``O_J3``, ``O_J3 + w k``); and ``J.wrist`` (``J.wrist`` → ``platform``, axis
    ``k`` through ``O_J4``). Links: ``base``, per leg ``J.carrier``, ``J.proximal_a``,
    ``J.proximal_b``, ``J.elbow``, ``J.distal_a``, ``J.distal_b``, ``J.wrist``, and ``platform``
    (16); five independent loops; ``dof = 4``.

    Unlike the Π joint of Eqs. (6)-(19), which always translates, a physical parallelogram whose
    long links lie along its short sides (here: vertical long links, see the module docstring) is
    *flat*: its four axes are coplanar and the twist graph lets its coupler turn too. Alone, in
    one leg, that changes no label (the other leg still supplies both horizontal couples); with
    both distal links vertical and parallel leg planes (Fig. 8a) the twist graph reports a
    constraint singularity (the plate gains a rotation about ``f_J``) where ``A`` is
    rank-deficient; with short sides tilted from the vertical it reports an actuation singularity
    (``tests/robots/test_two_limb_catalog.py``).

    Parameters
    ----------
    config : McGillConfiguration

    Returns
    -------
    JointTable
        Screws ``(..., 20, 6)`` over the batch of ``config``; ``table.graph(index)`` is the twist
        graph of one pose.

    Examples
    --------
    >>> from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
    >>> from screwkit.robots.families.mcgill_smg.parameters import McGillParameters
    >>> from screwkit.graphs.reduction import platform_twist_system
    >>> p = McGillParameters(1000, 450, 600, 282.843, 200, -50, -50, 80, 60)
    >>> table = joints(inverse_kinematics(p, [[0.0, 0.0, -800.0, 0.0], [10.0, 0.0, -800.0, 0.1]]))
    >>> table.batch_shape, [s.name for s in table.specs if s.actuated]
    ((2,), ['I.pan', 'I.proximal.a', 'II.pan', 'II.proximal.a'])
    >>> G = table.graph(0)
    >>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"]
    (16, 20, 4)
    >>> platform_twist_system(G).order, platform_twist_system(G, method="reduction").order
    (4, 4)
    """
    rows = []
    for index, leg in enumerate(LEGS):
        k = config.pan_axis[..., index, :]
        f = config.tilt_axis[..., index, :]
        rows.append(joint_row("base", f"{leg}.carrier", f"{leg}.pan", "R",
                              config.pan_point[..., index, :], k, actuated=True))
        for part, start, end, width, first, last in (
            ("proximal", config.shoulder, config.elbow, config.params.proximal_width,
             f"{leg}.carrier", f"{leg}.elbow"),
            ("distal", config.elbow, config.wrist, config.params.distal_width,
             f"{leg}.elbow", f"{leg}.wrist"),
        ):
            lower, upper = start[..., index, :], end[..., index, :]
            corners = (
                ("a", first, f"{leg}.{part}_a", lower),
                ("b", first, f"{leg}.{part}_b", lower + width * k),
                ("c", f"{leg}.{part}_a", last, upper),
                ("d", f"{leg}.{part}_b", last, upper + width * k),
            )
            for tag, parent, child, point in corners:
                rows.append(joint_row(parent, child, f"{leg}.{part}.{tag}", "R", point, f,
                                      actuated=(part, tag) == ("proximal", "a")))
        rows.append(joint_row(f"{leg}.wrist", "platform", f"{leg}.wrist", "R",
                              config.wrist_joint[..., index, :], k))
    return JointTable.from_rows("base", "platform", rows, dof=4, mobility=4)


def twist_basis(config: McGillConfiguration) -> np.ndarray:
    """The moving plate's nominal twists over the batch: a Schoenflies basis (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1``, ``ż = 1`` and ``φ̇ = 1`` with the pose ``(x, y, z, φ)``: the three
    translations and the rotation about the vertical axis ``k`` (the wrist axes' direction) through
    the operation point ``P`` (:func:`screwkit.core.jacobians.schoenflies_basis`). They are the columns
    of ``A`` in :func:`screwkit.core.jacobians.jacobians_from_wrenches`; paper 001's twist is
    ``t = (φ̇, ṗ/L)`` (Eq. 17b), the same motion in other coordinates.

    Parameters
    ----------
    config : McGillConfiguration

    Returns
    -------
    numpy.ndarray, shape (..., 4, 6)

    Examples
    --------
    >>> from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
    >>> from screwkit.robots.families.mcgill_smg.parameters import McGillParameters
    >>> p = McGillParameters(1000, 450, 600, 282.843, 200, -50, -50, 80, 60)
    >>> twist_basis(inverse_kinematics(p, [10.0, 0.0, -800.0, 0.0]))[3]  # about k through P
    array([  0.,   0.,   1.,   0., -10.,   0.])
    """
    return schoenflies_basis(config.platform_point, config.pan_axis[..., 0, :])
