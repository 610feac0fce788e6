"""Four-limb Schönflies-motion generators: Quattro, H4, V4, Veloce, Ragnar.

Source: paper 004 (Wu, Bai, Caro, "A transmission quality index for a class of four-limb parallel
Schönflies motion generators", JMR 10(5), 2018) (docs/papers.md).
All equation and table numbers below refer to that paper; limbs are numbered 1..4 as in it (array
index ``i - 1``). The family's modules: :mod:`~screwkit.robots.families.four_limb.parameters` (Table 3),
:mod:`~screwkit.robots.families.four_limb.configuration`,
:mod:`~screwkit.robots.families.four_limb.kinematics` (Eq. 3, inverse and forward) and
:mod:`~screwkit.robots.families.four_limb.joints` (the joint table and nominal twists); this module
declares the :class:`~screwkit.robots.families.Family`.

The model
---------
Each limb is ``R-R-Π-R-R``: an actuated revolute joint at ``A_i`` (axis ``u_i``), an arm of length
``b`` to the elbow ``B_i``, a parallelogram of length ``l`` to the platform point ``C_i``.

* ``a_i = R [cos η_i, sin η_i, 0]``, ``η_i = (2i - 1)π/4`` (Eq. 1), or explicit points (Ragnar,
  text after Table 4);
* ``u_i = R_z(α_i) i``, ``α_1 = -α_2 = α``, ``α_3 = -α_4 = β`` (Sec. 2), generalised to inclined
  actuated axes ``u_i = F_i i`` with ``F_i = R_z(α_i) R_y(ε_i)``, ``ε_1 = -ε_2 = ε_3 = -ε_4 = ε``
  (``axis_inclination``, 0 for every robot of Table 3; the Ragnar, item 6);
* ``v_i = F_i R_x(θ_i) j``, ``b_i = a_i + b v_i`` (Eq. 2; ``F_i = R_z(α_i)`` when ``ε = 0``);
* ``c_i`` from Table 1 (corrected, see below); ``|c_i - b_i| = l`` (Eq. 3);
* ``w_i = (c_i - b_i)/l``, ``A χ̇ = B θ̇`` with rows ``e_i = [w_i, r w_i·s_i]`` and
  ``B = diag(h_i)``, ``h_i = b w_i·(u_i × v_i)`` (Eqs. 6-8).

Each limb has two inverse-kinematics branches, told apart by the sign of ``h_i``; a *working mode*
is the tuple of the four signs. The paper uses ``h_i < 0`` for every limb (Sec. 3), the default here.

Platforms (Table 1, with ``σ_i = sgn(cos η_i) = (+, -, -, +)``, ``τ_i = sgn(sin η_i) = (+, +, -, -)``)

* ``"articulated_z"`` (Quattro, H4): ``c_i = σ_i r R_z(φ) i + τ_i c j + p``. The ``c_i`` of limbs with
  equal ``σ_i`` differ by a constant vector, so limbs 1, 4 share the translating sub-platform I and
  limbs 2, 3 share sub-platform II. The end effector (the bar ``P_I P_II`` of length ``2r``) turns by
  ``φ`` about ``k``; it is joined to the sub-platforms by revolute joints ``R_I``, ``R_II`` of axis
  ``k`` through ``P_I = p + r R_z(φ) i`` and ``P_II = p - r R_z(φ) i``.
* ``"articulated_y"`` (V4): ``c_i = σ_i r R_y(φ) i + τ_i c j + p`` (Table 1 corrected, item 3
  below), revolute axes along ``j`` through ``P_I = p + r R_y(φ) i`` (limbs 1, 4) and
  ``P_II = p - r R_y(φ) i`` (limbs 2, 3). At ``φ = 0`` the points coincide with the H4's; only the
  axis of rotation differs.
* ``"screw_pair"`` (Veloce, Ragnar): ``c_i = r R_z(γ_i) i + mod(i, 2) (hφ/2π) k + p`` with
  ``γ_i = (2i - 1)π/4`` (Table 3). Limbs 1, 3 share sub-platform I (centre ``p + (hφ/2π) k``), limbs
  2, 4 share sub-platform II (centre ``p``). Modelling choice consistent with Table 1: the end effector
  (position ``p``, angle ``φ``) is joined to sub-platform II by a revolute joint and to sub-platform I by
  a helical joint, both of axis ``k`` through ``p``; the helical joint has pitch ``-h/(2π)`` in the
  screw convention ``(s; r × s + pitch s)`` (the end effector turns by ``+φ`` while sub-platform I
  rises by ``hφ/(2π)`` relative to it).

Parallelograms: the two rods of limb ``i`` join the sphere centres ``m_i = b_i - (d/2) u_i``,
``n_i = b_i + (d/2) u_i`` on the arm to ``p_i = c_i - (d/2) u_i``, ``q_i = c_i + (d/2) u_i`` on the
sub-platform (short sides parallel to the actuated axis, as in paper 002, Sec. 4.2). The width ``d``
is not given by paper 004; it does not enter the kinematics. Its default, 100 mm, is *our choice*.

Where paper 004 is garbled or wrong (each is checked in ``tests/robots/test_families_four_limb.py``)
----------------------------------------------------------------------------------------------------
1. Table 1, ``s_i`` of Quattro/H4/V4, printed ``sgn(cos η_i) r s``: differentiating ``c_i`` gives
   ``∂c_i/∂φ = σ_i r ∂(R(φ) i)/∂φ``; Eq. (4) writes this as ``r s_i`` and calls ``s_i`` a unit
   vector, so the correct entry is ``s_i = σ_i s`` with ``s = ∂(R(φ) i)/∂φ`` (the printed ``r`` is
   spurious). For the Quattro/H4 ``s = R_z(φ) j`` as printed.
2. Table 1, ``s_i`` of the Veloce, printed ``mod(i, 2) hφ/(2π) k``: differentiating gives
   ``∂c_i/∂φ = mod(i, 2) h/(2π) k``, so ``r s_i = mod(i, 2) h/(2π) k`` (no ``φ``; not a unit vector).
3. Table 1, ``c_i`` of the V4, printed ``-sgn(cos η_i) r R_y(φ) i + sgn(cos η_i) c j + p``: the
   second term makes ``C_1 = C_4`` and ``C_2 = C_3`` (two limbs on one point). The row that
   reproduces Table 4's V4 values (``η`` in [0.008, 0.872] at ``φ = 0``, max 0.804 at 45°, with the
   workspace stated in the tests) is ``sgn(cos η_i) r R_y(φ) i + sgn(sin η_i) c j + p``: both the
   leading minus sign and the second ``cos`` are garbles. Over the same workspace the printed row
   gives η in [0, 0.711] at ``φ = 0``, and correcting only one of the two signs gives η_max 0.786
   (first sign) or 0.811 (second), against the paper's 0.872. With the right-handed ``R_y``,
   ``s = ∂(R_y(φ) i)/∂φ = -R_y(φ) k``; Table 1's ``s = R_y(φ) k`` corresponds to measuring ``φ``
   about ``-j``. The indices are even in ``φ``, so Table 4 cannot tell the two apart.

6. Ragnar (text after Table 4): "``u_i`` parallel to the x-z plane" with ``u_i = R_z(α_i) i`` means
   ``u_i = ±i``, i.e. ``α = 0``, ``β = π`` (the arms then point away from the x axis). With these
   horizontal axes all four parallelogram couples ``u_i × w_i`` are normal to ``i``: nothing
   constrains a rotation about ``x`` (a 5-DOF platform) and Table 4's Ragnar values are not
   reproduced (η_max 0.937 against 0.892 over Eq. 19). The real Ragnar (paper 004's ref. [15]) has
   its actuated axes *inclined* out of the base plane, in planes parallel to x-z. ``axis_inclination``
   ``ε`` models this: ``u_i = R_z(α_i) R_y(ε_i) i`` with ``ε_1 = -ε_2 = ε_3 = -ε_4 = ε``, the sign
   pattern that makes the Ragnar (``α = 0``, ``β = π``) symmetric under both mirrors ``x → -x``
   (limbs 1 ↔ 2, 3 ↔ 4) and ``y → -y`` (1 ↔ 4, 2 ↔ 3). Then ``u_1 ∦ u_3`` and ``u_2 ∦ u_4``: each
   sub-platform of the screw pair may only turn about one axis ``n_I`` (``n_II``), and the end
   effector, joined to both by joints of axis ``k``, only about ``span(n_I, k) ∩ span(n_II, k) = k``.
   Paper 004 does not print ``ε``; ``mechanisms/ragnar.toml`` says where its value comes from.

Items 4, 5 and 7 (Table 2, Eqs. 11 and 13, Sec. 5.1) concern the Jacobians and the transmission
indices of Sec. 4, which live in :mod:`screwkit.papers.paper_004` with the rest of that erratum list.

The joint table
---------------
:func:`joints` gives the physical mechanism as paper 002 models the H4 (§4.1, Fig. 2): per limb an
actuated revolute joint and a parallelogram with explicit spherical joints at its four corners; the
sub-platforms join the end effector by ``R_I`` and ``R_II``. :func:`twist_basis` gives the end
effector's nominal (Schoenflies) twists, the columns of the forward Jacobian of
:func:`screwkit.core.jacobians.jacobians_from_wrenches`. Paper 002 numbers the H4's legs differently: its
``b_I`` carries legs ``l1, l2`` and ``b_II`` carries ``l3, l4``, whereas here (Table 1) sub-platform
I carries limbs 1 and 4; paper 002's ``(l1, l2, l3, l4)`` are limbs ``(1, 4, 2, 3)``
(:data:`~screwkit.robots.families.four_limb.joints.PAPER_002_LEGS`).

Examples
--------
>>> FAMILY.pose_names, FAMILY.angle_names
(('x', 'y', 'z', 'phi'), ('phi',))
>>> h4 = FAMILY.parameters({"name": "H4", "platform_kind": "articulated_z", "arm_length": 375.0,
...     "rod_length": 800.0, "alpha": 0.0, "beta": np.pi / 2, "platform_radius": 80.0,
...     "platform_offset": 70.0, "base_radius": 275.0})
>>> bool(np.all(FAMILY.inverse_kinematics(h4, [0.0, 0.0, -700.0, 0.3]).h < 0))
True
"""


from __future__ import annotations

from .. import Family, WorkingModes
from .configuration import FourLimbConfiguration
from .joints import actuated_values, application_points, joints, twist_basis, working_mode_of
from .kinematics import _DEFAULT_WORKING_MODE, inverse_kinematics, reachable
from .parameters import FourLimbParameters

__all__ = ["FAMILY"]


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[FourLimbParameters, FourLimbConfiguration] = Family(
    name="four_limb",
    parameters=FourLimbParameters.from_mapping,
    inverse_kinematics=inverse_kinematics,
    joints=joints,
    twist_basis=twist_basis,
    pose_names=("x", "y", "z", "phi"),
    angle_names=("phi",),
    parameter_kinds=dict.fromkeys(
        ("base_radius", "base_points", "arm_length", "rod_length", "platform_radius", "platform_offset",
         "lead", "parallelogram_width"),
        "length",
    )
    | {"alpha": "angle", "beta": "angle", "platform_kind": "number"},
    reachable=reachable,
    application_points=application_points,
    actuated_values=actuated_values,
    working_modes=WorkingModes(
        "working_mode",
        _DEFAULT_WORKING_MODE,
        "the signs of h_i (paper 004, Eq. 8) per limb; -1, the paper's, has the elbows out",
        of=working_mode_of,
    ),
    map_axes=("z", "phi"),
)
