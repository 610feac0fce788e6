"""The planar 3-RRP's joint table and nominal twists (the family protocol's ``joints`` and
``twist_basis``), its links and joints named by paper 003's labels.

Examples
--------
>>> from screwkit.robots.families.planar_3rrp.configuration import Planar3RRPConfiguration
>>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
>>> config = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
>>> len(joints(config).specs), twist_basis(config).shape
(9, (3, 6))
"""

from __future__ import annotations

import numpy as np

from ....algebra import screw as S
from ....graphs.jointtable import JointTable
from .configuration import Planar3RRPConfiguration, _check_config

__all__ = ["JOINT_PAIRS", "LINK_NAMES", "joints", "twist_basis"]


#: Link names by the paper's label (Fig. 1b): ``LINK_NAMES[label - 1]``.
LINK_NAMES = (
    "base",
    "limb1_link1",
    "limb1_link2",
    "limb2_link1",
    "limb2_link2",
    "limb3_link1",
    "limb3_link2",
    "platform",
)

#: The joints as pairs of paper labels, per limb from base to platform: actuated R, passive R, P.
JOINT_PAIRS = (
    ((1, 2), (2, 3), (3, 8)),
    ((1, 4), (4, 5), (5, 8)),
    ((1, 6), (6, 7), (7, 8)),
)


# --------------------------------------------------------------------------------------------------
# The joint table and the nominal twists (the family protocol, screwkit.robots.families)
# --------------------------------------------------------------------------------------------------

_AXIS_Z = np.array([0.0, 0.0, 1.0])


def _in_space(planar: np.ndarray) -> np.ndarray:
    """Planar points or directions ``(..., 2)`` in the plane ``z = 0`` of space, ``(..., 3)``."""
    return np.concatenate([planar, np.zeros((*planar.shape[:-1], 1))], axis=-1)


def joints(config: Planar3RRPConfiguration) -> JointTable:
    """The joints of the physical mechanism over the batch (docs/architecture.md §1a, §5).

    Links are :data:`LINK_NAMES`; per limb ``k`` (:data:`JOINT_PAIRS`, base to platform) the joints
    are ``limb{k}_R1`` (actuated revolute, axis ``z`` through ``M_k``: the screw ``(z; M_k × z)``),
    ``limb{k}_R2`` (revolute, axis ``z`` through the elbow ``A_k``) and ``limb{k}_P`` (prismatic
    along the guide, the infinite-pitch screw ``(0; b_k)``). The mechanism lies in the plane
    ``z = 0``; its nominal mobility is ``dof = 3`` (planar motions). The table's ``anchor`` is the
    mean of the six revolute centres, a point of that plane that moves with the mechanism (it fixes
    the reference point along ``z``, where the parallel axes do not;
    :func:`screwkit.graphs.twistgraph.graph_frame`).

    Parameters
    ----------
    config : Planar3RRPConfiguration
        Any batch shape ``...``.

    Returns
    -------
    JointTable
        Base ``"base"``, platform ``"platform"``, nine joints (three loops), ``dof = 3``; screws
        ``(..., 9, 6)``.

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`Planar3RRPConfiguration`.

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> from screwkit.core.singularity import classify
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> table = joints(c)
    >>> [(spec.name, spec.type, spec.actuated) for spec in table.specs[:3]]
    [('limb1_R1', 'R', True), ('limb1_R2', 'R', False), ('limb1_P', 'P', False)]
    >>> table.joint_screws("limb1_R1")  # axis z through M_1
    array([[ 0.       ,  0.       ,  1.       , -0.5      ,  0.8660254,  0.       ]])
    >>> G = table.graph()
    >>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"], classify(G).labels
    (8, 9, 3, ())
    """
    config = _check_config(config)
    base, elbow = _in_space(config.base_points), _in_space(config.elbow_points)
    screws = {
        "R1": S.revolute_twist(_AXIS_Z, base),
        "R2": S.revolute_twist(_AXIS_Z, elbow),
        "P": S.prismatic_twist(_in_space(config.guide_directions)),
    }
    rows = [
        (LINK_NAMES[parent - 1], LINK_NAMES[child - 1], f"limb{k + 1}_{label}", label[0],
         screws[label][..., k, None, :], label == "R1")
        for k, pairs in enumerate(JOINT_PAIRS)
        for label, (parent, child) in zip(("R1", "R2", "P"), pairs, strict=True)
    ]
    anchor = np.concatenate([base, elbow], axis=-2).mean(axis=-2)
    return JointTable.from_rows(LINK_NAMES[0], LINK_NAMES[-1], rows, dof=3, anchor=anchor, mobility=3)


def twist_basis(config: Planar3RRPConfiguration) -> np.ndarray:
    """The platform's nominal (planar) twists over the batch, embedded in space (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1`` and ``φ̇ = 1`` (the pose order ``(x, y, φ)``): the translations
    ``(0; i)``, ``(0; j)`` and the rotation ``(k; C × k)`` about the axis ``z`` through the platform
    point ``C = (x, y, 0)``. They are the columns of ``A`` in
    :func:`screwkit.core.jacobians.jacobians_from_wrenches`. Paper 003's twist ``t = (ω, ẋ, ẏ)`` (Eq. 3)
    lists the same rates with the angular rate first.

    Parameters
    ----------
    config : Planar3RRPConfiguration
        Any batch shape ``...``.

    Returns
    -------
    numpy.ndarray, shape (..., 3, 6)

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`Planar3RRPConfiguration`.

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> twist_basis(Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.05, -0.03, 0.1]))
    array([[ 0.  ,  0.  ,  0.  ,  1.  ,  0.  ,  0.  ],
           [ 0.  ,  0.  ,  0.  ,  0.  ,  1.  ,  0.  ],
           [ 0.  ,  0.  ,  1.  , -0.03, -0.05,  0.  ]])
    """
    config = _check_config(config)
    x, y = np.moveaxis(config.platform_point, -1, 0)
    rows = np.zeros((*x.shape, 3, 6))
    rows[..., 0, 3] = rows[..., 1, 4] = rows[..., 2, 2] = 1.0
    rows[..., 2, 3], rows[..., 2, 4] = y, -x  # C × k = (y, -x, 0)
    return rows
