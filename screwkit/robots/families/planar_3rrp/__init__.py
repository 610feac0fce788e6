"""Planar 3-RRP parallel manipulator: the robot model (parameters, kinematics, joint table).

Source: paper 003 (S. Zarkandi, "A study of the instantaneous centers of rotation in
singularities of 3-DOF fully parallel planar manipulators") (docs/papers.md). Equation numbers below are
that paper's. The
paper gives no dimensions; the model is general and
:data:`~screwkit.robots.families.planar_3rrp.parameters.EXAMPLE_PARAMETERS` are *our* choice (see
there). The family's modules: :mod:`~screwkit.robots.families.planar_3rrp.parameters`,
:mod:`~screwkit.robots.families.planar_3rrp.kinematics` (inverse and forward),
:mod:`~screwkit.robots.families.planar_3rrp.configuration` and
:mod:`~screwkit.robots.families.planar_3rrp.joints`; this module declares the
:class:`~screwkit.robots.families.Family`.

The model
---------
Links carry the paper's labels (Fig. 1b): ``1`` base, ``2, 4, 6`` the first (actuated) link of limbs
1, 2, 3, ``3, 5, 7`` their second link, ``8`` the end effector (platform). Limb ``k`` (``k = 1, 2,
3``, first link ``i = 2k``, second link ``j = i + 1``) is

``base --R (actuated, at M_k = C_1i)--> link i --R (elbow A_k = C_ij)--> link j --P (b_k)--> 8``.

The prismatic joint keeps link ``j`` at the platform's orientation (Eq. 7b uses the platform's
``ω`` for link ``j``), so the elbow ``A_k`` slides on a *guide line fixed in the platform*: it
passes through the platform point ``P_k`` and has the direction ``b_k = R(φ) (cos β_k, sin β_k)``.

* pose ``(x, y, φ)``: position of the platform's reference point ``C`` and its orientation;
  twist ``t = (ω, ẋ, ẏ) = (φ̇, ẋ, ẏ)`` in the paper's order (Eq. 3, angular rate first: note
  the different order of the pose);
* joint angle ``θ_k``: the angle of ``M_k A_k`` from the base x axis, ``A_k = M_k + l_k u(θ_k)``;
* closure (our form of Eq. 1): ``f_k = n_k·(A_k - C) - n⁰_k·P_k = 0`` with ``n_k = E b_k``,
  ``E`` the 90° rotation of Eq. (6);
* inverse kinematics: line-circle intersection, ``A_k = Q_k + γ_k b_k``, ``Q_k = C + R(φ) P_k``,
  ``γ_k = -(Q_k - M_k)·b_k + σ_k sqrt(l_k² - h_k²)`` with ``h_k = (Q_k - M_k)·n_k``; the working
  mode ``σ = (σ_1, σ_2, σ_3)`` (each ``±1``) is the sign of ``J_kk``, since
  ``J_kk = σ_k sqrt(l_k² - h_k²)``;
* forward kinematics: with ``θ`` given, the three closure equations are linear in ``C``; they are
  consistent iff ``P cos φ + Q sin φ = S`` (the 2×2 minors of the normals do not depend on
  ``φ``), so there are at most two assembly modes, found in closed form.

Velocities, instant centres and the paper's Jacobians ``J``, ``K`` (Eqs. 4-11) and its singularity
classification (Sec. 4) are paper 003's analysis of this model: they live beside the tests that
check them (``tests/paper_003.py``); the joint table below is what screwkit analyses.

Where paper 003 is wrong about the model (its errata 1-5 on the analysis: ``tests/paper_003.py``)
-------------------------------------------------------------------------------------------------
6. Sec. 4.2, second case (all ``b_i`` parallel): ``b_k`` turn together with the platform, so it
   never happens unless the guides are parallel in the platform, and then it happens at *every*
   pose. Such parameters are rejected (:class:`Planar3RRPParameters`).


The joint table
---------------
:func:`joints` embeds the mechanism in space (plane ``z = 0``): R joints are zero-pitch screws
along ``z`` through their centres, P joints infinite-pitch screws along ``(b_k, 0)``. Its wrench
systems (:mod:`screwkit.core.wrenches`) have a constraint system of order 3 (forces along ``z`` and
couples about horizontal axes, the planarity constraints) and, per limb, an actuation wrench that is
the planar force through the elbow ``A_k`` perpendicular to the guide: the Kennedy line ``L_k``.
The labels of :func:`screwkit.core.singularity.classify` then match paper 003's instant-centre
classification (``tests/paper_003.py``):
inverse (``J_kk = 0``) ↔ ``"serial"`` (that limb's twist system drops to order 2, so the platform
is locked in one direction rather than uncontrolled: ``lost_dof = 1``, the global system stays a
6-system); direct (``L_1, L_2, L_3`` concurrent) ↔ ``"actuation"``; combined ↔ both. The tests
(``tests/robots/test_planar_catalog.py``) check this at poses found by root search.

Examples
--------
>>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
>>> from screwkit.core.singularity import classify_table
>>> config = FAMILY.inverse_kinematics(EXAMPLE_PARAMETERS, [[0.0, 0.0, 0.0], [0.05, -0.03, 0.1]])
>>> np.round(np.degrees(config.joint_angles[0]), 3)
array([ -3.557, 116.443, -123.557])
>>> classify_table(FAMILY.joints(config)).verdict.tolist()
['regular', 'regular']
"""


from __future__ import annotations

import numpy as np

from .. import Family, WorkingModes
from .configuration import Planar3RRPConfiguration
from .joints import joints, twist_basis
from .parameters import Planar3RRPParameters

__all__ = ["FAMILY", "working_mode_of"]


def working_mode_of(config: Planar3RRPConfiguration) -> np.ndarray:
    """The working mode a configuration is in, read from its geometry: ``σ_k`` of
    ``γ_k = -(Q_k - M_k)·b_k + σ_k sqrt(l_k² - h_k²)`` (module docstring) is the sign of
    ``(A_k - M_k)·b_k``, the elbow's side of the foot of the perpendicular from ``M_k`` to the guide.

    Parameters
    ----------
    config : Planar3RRPConfiguration

    Returns
    -------
    numpy.ndarray of int, shape (..., 3)

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> config = FAMILY.inverse_kinematics(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0], (1, -1, 1))
    >>> working_mode_of(config).tolist()
    [1, -1, 1]
    """
    along = np.sum((config.elbow_points - config.base_points) * config.guide_directions, axis=-1)
    return np.sign(along).astype(int)


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[Planar3RRPParameters, Planar3RRPConfiguration] = Family(
    name="planar_3rrp",
    parameters=Planar3RRPParameters.from_mapping,
    inverse_kinematics=Planar3RRPConfiguration.from_pose,
    joints=joints,
    twist_basis=twist_basis,
    pose_names=("x", "y", "phi"),
    angle_names=("phi",),
    parameter_kinds=dict.fromkeys(("base_points", "link_lengths", "platform_points"), "length")
    | {"guide_angles": "angle"},
    actuated_values=lambda config: config.joint_angles,
    working_modes=WorkingModes(
        "working_mode", (1, 1, 1), "σ_k per limb: the side of its guide's foot point the elbow is on",
        of=working_mode_of,
    ),
)
