"""The physical twist graph of a four-limb SMG (H4, Quattro, V4, Veloce, Ragnar) at one pose.

Each limb is modelled as paper 002 models the H4's (§4.1, Fig. 2): ``R–(4S)``, an actuated revolute
joint ``A<i>`` (axis ``u_i`` through ``A_i``) and a parallelogram of two rods with **explicit
spherical joints** at its four corners ``m, n`` (on the arm) and ``p, q`` (on the sub-platform).
The closed 4S loops are *not* typed in as virtual chains: the equivalent twist graph derives them
(:func:`screwkit.twistgraph.equivalent_twist_graph`).

The articulated platform joins the two sub-platforms ``b_I`` and ``b_II`` to the end effector by
joints ``R_I`` and ``R_II`` (revolute, or helical for the screw-pair platforms of the Veloce and
Ragnar) on the axes given by :class:`~screwkit.families.four_limb.FourLimbConfiguration`.

:func:`twist_basis` gives the end effector's nominal (Schoenflies) twists at a pose, the columns of
the forward Jacobian of :func:`screwkit.jacobians.jacobians_from_wrenches`.

Limb numbering follows paper 004 (``A1`` … ``A4``). Paper 002 numbers the H4's legs differently:
its ``b_I`` carries legs ``l1, l2`` and ``b_II`` carries ``l3, l4``, whereas in paper 004's Table 1
the sub-platform of limbs with ``sgn(cos η_i) > 0`` carries limbs 1 and 4. So paper 002's
``(l1, l2, l3, l4)`` are paper 004's limbs ``(1, 4, 2, 3)`` (:data:`PAPER_002_LEGS`).

Examples
--------
>>> import numpy as np
>>> from screwkit.families.four_limb import FourLimbParameters, inverse_kinematics
>>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375, rod_length=800,
...     alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70, base_radius=275)
>>> G = four_limb_twist_graph(inverse_kinematics(h4, [0, 0, -700, 0]))
>>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"]
(16, 22, 4)
"""

from __future__ import annotations

import networkx as nx
import numpy as np

from .. import screw as S
from ..exceptions import ScrewkitValueError
from ..jacobians import schoenflies_basis
from ..joints import Joint
from ..twistgraph import twist_graph
from .four_limb import FourLimbConfiguration

__all__ = ["PAPER_002_LEGS", "SUBPLATFORMS", "four_limb_joints", "four_limb_twist_graph", "twist_basis"]

#: Paper 002's H4 legs l1..l4 as paper 004's limbs (1-based): (1, 4, 2, 3).
PAPER_002_LEGS = {"l1": 1, "l2": 4, "l3": 2, "l4": 3}
#: Names of the sub-platform links and of the joints joining them to the end effector.
SUBPLATFORMS = (("b_I", "R_I"), ("b_II", "R_II"))


def four_limb_joints(config: FourLimbConfiguration) -> list[tuple[str, str, str, str, np.ndarray, bool]]:
    """The joints of the physical mechanism with their screws over the whole batch of poses.

    Returns
    -------
    list of (parent, child, name, type, screws, actuated)
        ``screws`` has shape ``(..., dof, 6)`` over the configuration's batch shape ``...``.

    Examples
    --------
    >>> import numpy as np
    >>> from screwkit.families.four_limb import FourLimbParameters, inverse_kinematics
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> table = four_limb_joints(inverse_kinematics(h4, np.zeros((5, 4)) + [0, 0, -700, 0]))
    >>> len(table), table[1][2], table[1][4].shape
    (22, 'S1m', (5, 3, 6))
    """
    eye = np.eye(3)

    def spheres(centres: np.ndarray) -> np.ndarray:
        return S.revolute_twist(eye, centres[..., None, :])

    limb_platform = {}
    for (link, _), limbs in zip(SUBPLATFORMS, config.subplatform_limbs, strict=True):
        for limb in limbs:
            limb_platform[limb] = link
    table = []
    for limb in range(4):
        i = limb + 1
        arm = f"arm{i}"
        actuated = S.revolute_twist(config.u[..., limb, :], config.a[..., limb, :])[..., None, :]
        table.append(("base", arm, f"A{i}", "R", actuated, True))
        for rod, corner, (first, second) in ((f"rod{i}a", 0, "mp"), (f"rod{i}b", 1, "nq")):
            table.append(
                (arm, rod, f"S{i}{first}", "S", spheres(config.elbow_corners[..., limb, corner, :]), False)
            )
            table.append(
                (
                    rod,
                    limb_platform[limb],
                    f"S{i}{second}",
                    "S",
                    spheres(config.platform_corners[..., limb, corner, :]),
                    False,
                )
            )
    axis = config.platform_joint_axis
    for k, (link, name) in enumerate(SUBPLATFORMS):
        point, pitch = config.platform_joint_points[..., k, :], config.platform_joint_pitches[k]
        screw = S.helical_twist(axis, point, pitch) if pitch else S.revolute_twist(axis, point)
        table.append((link, "end_effector", name, "H" if pitch else "R", screw[..., None, :], False))
    return table


def _checked_index(config: FourLimbConfiguration, index: tuple[int, ...]) -> tuple[int, ...]:
    batch = config.pose.shape[:-1]
    index = tuple(index)
    if len(index) != len(batch) or any(not (0 <= i < n) for i, n in zip(index, batch, strict=True)):
        raise ScrewkitValueError(
            f"Expected `index` to pick one pose of the batch of shape {batch}, got {index!r}."
        )
    return index


def four_limb_twist_graph(config: FourLimbConfiguration, index: tuple[int, ...] = ()) -> nx.MultiDiGraph:
    """The twist graph of the physical mechanism at one pose of a configuration.

    Parameters
    ----------
    config : FourLimbConfiguration
        From :func:`~screwkit.families.four_limb.inverse_kinematics`.
    index : tuple of int
        Which pose of a batched configuration (empty for a single pose).

    Returns
    -------
    networkx.MultiDiGraph
        Links ``base``, ``arm<i>``, ``rod<i>a``, ``rod<i>b``, ``b_I``, ``b_II``, ``end_effector``;
        joints ``A<i>`` (actuated R), ``S<i>m``, ``S<i>p``, ``S<i>n``, ``S<i>q`` (S), ``R_I``,
        ``R_II``; ``dof = 4``.

    Raises
    ------
    ScrewkitValueError
        If ``index`` does not pick one pose of the batch.

    Examples
    --------
    >>> import numpy as np
    >>> from screwkit.families.four_limb import FourLimbParameters, inverse_kinematics
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> cfg = inverse_kinematics(h4, [[0, 0, -700, 0], [50, 0, -700, 0.2]])
    >>> sorted(four_limb_twist_graph(cfg, (1,)).successors("b_I"))
    ['end_effector']
    """
    index = _checked_index(config, index)
    joints = [
        (parent, child, Joint(name, kind, screws[index], actuated=actuated))
        for parent, child, name, kind, screws, actuated in four_limb_joints(config)
    ]
    return twist_graph("base", "end_effector", joints, dof=4)


def twist_basis(config: FourLimbConfiguration, index: tuple[int, ...] = ()) -> np.ndarray:
    """The end effector's nominal twists at one pose: a Schoenflies basis (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1``, ``ż = 1`` and ``φ̇ = 1`` with ``χ = (x, y, z, φ)``: the three
    translations and the rotation about the end effector's own axis of rotation,
    ``config.platform_joint_axis`` (``k`` for the Quattro, H4, Veloce and Ragnar, ``j`` for the
    V4) through the end-effector point ``p`` (:func:`screwkit.jacobians.schoenflies_basis`). They
    are the columns of ``A`` in :func:`screwkit.jacobians.jacobians_from_wrenches`, in paper 004's
    order (Eq. 7a).

    Parameters
    ----------
    config : FourLimbConfiguration
        From :func:`~screwkit.families.four_limb.inverse_kinematics`.
    index : tuple of int
        Which pose of a batched configuration (empty for a single pose).

    Returns
    -------
    numpy.ndarray, shape (4, 6)

    Raises
    ------
    ScrewkitValueError
        If ``index`` does not pick one pose of the batch.

    Examples
    --------
    >>> import numpy as np
    >>> from screwkit.families.four_limb import FourLimbParameters, inverse_kinematics
    >>> v4 = FourLimbParameters(name="V4", platform_kind="articulated_y", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> twist_basis(inverse_kinematics(v4, [[0, 0, -700, 0], [50, 0, -700, 0.2]]), (1,))[3]  # about j
    array([  0.,   1.,   0., 700.,   0.,  50.])
    """
    index = _checked_index(config, index)
    return schoenflies_basis(config.pose[index][:3], config.platform_joint_axis[index])
