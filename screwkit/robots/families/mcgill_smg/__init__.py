"""The McGill Schönflies-motion generator: two RΠΠR limbs on a bar-shaped moving plate.

Source: paper 001 (Angeles, Caro, Khan, Morozov, "Kinetostatic design of an innovative
Schönflies-motion generator", Proc. IMechE C 220(7), 2006) (docs/papers.md). Equation, table and figure
numbers refer to it.
The family's modules: :mod:`~screwkit.robots.families.mcgill_smg.parameters`,
:mod:`~screwkit.robots.families.mcgill_smg.configuration` (the legs' geometry),
:mod:`~screwkit.robots.families.mcgill_smg.kinematics` (inverse and forward) and
:mod:`~screwkit.robots.families.mcgill_smg.joints`; this module declares the
:class:`~screwkit.robots.families.Family`.

The model
---------
Frame: origin midway between the feet ``O_I0``, ``O_II0`` of the two pan axes, ``k`` up, as in
Eqs. (1)-(2). Leg ``J`` has the sign ``s(J) = +1, -1`` for ``J = I, II`` (Eq. 13) and

* ``O_J0 = -s(J) (l0/2) j`` on the vertical pan axis (actuated angle ``θ_J1``);
* ``e(θ) = (-sin θ, cos θ, 0)``, the horizontal direction of the leg's vertical plane, and
  ``f_J = e(θ_J1) × k = (cos θ_J1, sin θ_J1, 0)``, the normal of that plane;
* ``O_J1 = O_J0 + s(J) l1 e(θ_J1)``: the horizontal offset ``a_J1``;
* ``O_J2 = O_J1 + l2 (cos θ_J2 e + sin θ_J2 k)``: the proximal parallelogram (actuated tilt
  ``θ_J2`` about ``f_J``);
* ``O_J3 = O_J2 + l3 (cos θ_J23 e + sin θ_J23 k)``, ``θ_J23 = θ_J2 + θ_J3``: the distal
  parallelogram (passive ``θ_J3``);
* ``O_J4 = O_J3 + b4 k`` on the vertical wrist axis (passive ``θ_J4``, ``φ = θ_J1 + θ_J4``,
  Eqs. 1d, 2d) and ``P = O_J4 + s(J) R e(φ) + b5 k``.

This reproduces Eqs. (1a)-(2d) term by term (``tests/robots/test_families_mcgill_smg.py`` checks it). The
moving plate is the bar ``O_I4 O_II4`` of length ``2R`` with ``P`` at its middle.

Our choices where the paper is silent (Table 1 and Sec. 6 give only ``R = 200 mm``,
``l2 = 600 mm``, ``l3 = √2 R``):

* ``a4 = 0`` (``O_J4`` straight above or below ``O_J3``) and ``a5 = R``. A parallelogram keeps the
  orientation of its input link, so any horizontal offset along ``e(θ_J1)`` after the pan joint
  commutes with the parallelograms and is absorbed in ``l1``; only ``b4 + b5`` enters Eqs. (1)-(2).
* ``l0``, ``l1``, ``b4``, ``b5`` are parameters without published values.
* The parallelograms' short sides are vertical, of lengths ``proximal_width`` and
  ``distal_width``: corners ``O_J1, O_J1 + w k, O_J2 + w k, O_J2`` (proximal) and
  ``O_J2, O_J2 + w k, O_J3 + w k, O_J3`` (distal), revolute axes along ``f_J``. They do not enter
  the kinematics or ``A``, ``B``; they matter for the twist graph of the physical mechanism (a
  parallelogram whose long links are vertical is flat: all four axes in one plane).

Working modes. The inverse kinematics of each leg has two pan branches and two elbow branches. A
working mode is ``(pan_I, elbow_I, pan_II, elbow_II)``, signs with ``pan_J = sgn κ_J``, where the
horizontal projection of ``O_J3 - O_J0`` is ``κ_J e(θ_J1)`` (``κ_J = s(J) l1 + l2 cos θ_J2 +
l3 cos θ_J23``), and ``elbow_J = sgn sin θ_J3``. Beware Eq. (2)'s convention: leg II's tilt is
measured from ``+e(θ_II1)`` while its offset points along ``-e(θ_II1)``, so the posture that is the
mirror image of leg I (both offsets toward the other leg) has ``pan = (+1, -1)`` and *opposite*
elbow signs. :data:`~screwkit.robots.families.mcgill_smg.parameters.DEFAULT_MODE` ``(1, 1, -1, -1)`` is that
mirror-symmetric posture with both
elbows away from the other leg. Mode ``(1, 1, -1, 1)`` makes the two legs translates of each other,
which is a parallel singularity (Eq. 24) whenever ``P`` lies midway between the pan axes with
``φ = 0``.

Where paper 001 is garbled or wrong
-----------------------------------
Table 1 puts the origin of ``F`` at ``O_I0`` (so does the ``+ l0 j`` of Eq. 3b) while Eqs. (1)-(2)
put it midway; we follow Eqs. (1)-(2). Paper 001's Jacobians ``A``, ``B`` (Eqs. 16-19), the factors
of their singularities and what the paper gets wrong about them (the printed block shapes of
Eq. 17a, Figs. 7a-7b, Eq. 22) are a paper analysis, not the robot model: they live in
``tests/paper_001.py`` beside the tests that check them. The mechanism's own Jacobians and labels
come from the analysis core (:meth:`screwkit.robots.mechanism.Mechanism.at`).

Examples
--------
>>> from screwkit.core.singularity import classify_table
>>> smg = FAMILY.parameters({"l0": 600.0, "l1": 100.0, "l2": 600.0, "l3": 200.0 * np.sqrt(2),
...     "radius": 200.0, "b4": -50.0, "b5": -50.0, "proximal_width": 80.0, "distal_width": 60.0})
>>> config = FAMILY.inverse_kinematics(smg, [[0.0, 0.0, -600.0, 0.0]])
>>> config.joint_angles[0, :, 0]  # pan angles: O_I3 and O_II3 lie on the y axis
array([0., 0.])
>>> classify_table(FAMILY.joints(config)).verdict.tolist()
['regular']
"""

from __future__ import annotations

import numpy as np

from .. import Family, WorkingModes
from .configuration import _SIGN, McGillConfiguration
from .joints import joints, twist_basis
from .kinematics import inverse_kinematics
from .parameters import DEFAULT_MODE, McGillParameters

__all__ = ["FAMILY", "working_mode_of"]


def working_mode_of(config: McGillConfiguration) -> np.ndarray:
    """The working mode ``(pan_I, elbow_I, pan_II, elbow_II)`` a configuration is in, read from its
    joint angles: ``pan_J = sgn κ_J`` with ``κ_J = s(J) l1 + l2 cos θ_J2 + l3 cos(θ_J2 + θ_J3)`` (the
    signed horizontal reach of the two-link problem of
    :func:`~screwkit.robots.families.mcgill_smg.kinematics.inverse_kinematics`) and
    ``elbow_J = sgn sin θ_J3``.

    Parameters
    ----------
    config : McGillConfiguration

    Returns
    -------
    numpy.ndarray of int, shape (..., 4)

    Examples
    --------
    >>> from screwkit.robots.families.mcgill_smg.parameters import McGillParameters
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> working_mode_of(FAMILY.inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0], mode=(1, -1, -1, 1))).tolist()
    [1, -1, -1, 1]
    """
    params, angles = config.params, config.joint_angles
    reach = (
        _SIGN * params.l1
        + params.l2 * np.cos(angles[..., 1])
        + params.l3 * np.cos(angles[..., 1] + angles[..., 2])
    )
    modes = np.stack([np.sign(reach), np.sign(np.sin(angles[..., 2]))], axis=-1)
    return modes.reshape(*modes.shape[:-2], 4).astype(int)


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[McGillParameters, McGillConfiguration] = Family(
    name="mcgill_smg",
    parameters=McGillParameters.from_mapping,
    inverse_kinematics=inverse_kinematics,
    joints=joints,
    twist_basis=twist_basis,
    pose_names=("x", "y", "z", "phi"),
    angle_names=("phi",),
    parameter_kinds=dict.fromkeys(
        ("l0", "l1", "l2", "l3", "radius", "b4", "b5", "proximal_width", "distal_width"), "length"
    ),
    actuated_values=lambda config: config.actuated,
    working_modes=WorkingModes(
        "mode",
        DEFAULT_MODE,
        "(pan_I, elbow_I, pan_II, elbow_II): sgn κ_J and sgn sin θ_J3 per leg",
        of=working_mode_of,
    ),
)
