"""The four-limb family's joint table and nominal twists (the family protocol's ``joints`` and
``twist_basis``).

Each limb is modelled as paper 002 models the H4 (§4.1, Fig. 2): an actuated revolute joint and a
parallelogram with explicit spherical joints at its four corners; the sub-platforms join the end
effector by ``R_I`` and ``R_II``.

Examples
--------
>>> config = load_mechanism("h4").configuration()
>>> joints(config).dof, twist_basis(config).shape
(4, (4, 6))
"""

from __future__ import annotations

import numpy as np

from ....algebra import screw as S
from ....algebra.backend import cross
from ....core.jacobians import schoenflies_basis
from ....graphs.jointtable import JointSpec, JointTable
from .configuration import FourLimbConfiguration, _require

__all__ = [
    "PAPER_002_LEGS",
    "SUBPLATFORMS",
    "actuated_values",
    "application_points",
    "joints",
    "parallelogram_legs",
    "twist_basis",
    "working_mode_of",
]


#: Paper 002's H4 legs l1..l4 as paper 004's limbs (1-based): (1, 4, 2, 3).
PAPER_002_LEGS = {"l1": 1, "l2": 4, "l3": 2, "l4": 3}
#: Names of the sub-platform links and of the joints joining them to the end effector.
SUBPLATFORMS = (("b_I", "R_I"), ("b_II", "R_II"))


def joints(config: FourLimbConfiguration) -> JointTable:
    """The joints of the physical mechanism with their screws over the whole batch of poses.

    Each limb is modelled as paper 002 models the H4's (§4.1, Fig. 2): ``R–(4S)``, an actuated
    revolute joint ``A<i>`` (axis ``u_i`` through ``A_i``) and a parallelogram of two rods with
    **explicit spherical joints** at its four corners ``m, n`` (on the arm) and ``p, q`` (on the
    sub-platform). The closed 4S loops are *not* typed in as virtual chains: the equivalent twist
    graph derives them (:func:`screwkit.graphs.reduction.equivalent_twist_graph`). The sub-platforms
    ``b_I`` and ``b_II`` join the end effector by joints ``R_I`` and ``R_II`` (revolute, or helical
    for the screw-pair platforms) on the axes of :class:`FourLimbConfiguration`.

    Parameters
    ----------
    config : FourLimbConfiguration
        From :func:`~screwkit.robots.families.four_limb.kinematics.inverse_kinematics` (any batch shape
        ``...``).

    Returns
    -------
    JointTable
        Links ``base``, ``arm<i>``, ``rod<i>a``, ``rod<i>b``, ``b_I``, ``b_II``, ``end_effector``;
        joints, in the order of their names, ``A<i>`` (actuated R), ``R_I``, ``R_II``, ``S<i>m``,
        ``S<i>n``, ``S<i>p``, ``S<i>q`` (S); ``dof = 4``; screws ``(..., rows, 6)``.

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`FourLimbConfiguration`.

    Examples
    --------
    >>> from screwkit.robots.families.four_limb.kinematics import inverse_kinematics
    >>> from screwkit.robots.families.four_limb.parameters import FourLimbParameters
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> table = joints(inverse_kinematics(h4, np.zeros((5, 4)) + [0, 0, -700, 0]))
    >>> len(table.specs), table.specs[6].name, table.joint_screws("S1m").shape
    (22, 'S1m', (5, 3, 6))
    >>> G = table.graph(1)
    >>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"], sorted(G.successors("b_I"))
    (16, 22, 4, ['end_effector'])
    """
    _require(config, FourLimbConfiguration, "config")
    limb_platform = {}
    for (link, _), limbs in zip(SUBPLATFORMS, config.subplatform_limbs, strict=True):
        for limb in limbs:
            limb_platform[limb] = link
    axis = config.platform_joint_axis
    middle = []  # R_I, R_II: between the actuated joints and the spheres in the order of the names
    for k, (link, name) in enumerate(SUBPLATFORMS):
        point, pitch = config.platform_joint_points[..., k, :], config.platform_joint_pitches[k]
        screw = (
            S.helical_twist(axis, point, pitch)
            if pitch
            else np.concatenate([np.broadcast_to(axis, point.shape), cross(point, axis)], axis=-1)
        )
        middle.append((JointSpec(name, "H" if pitch else "R", link, "end_effector", 1, False), screw))
    screws, specs = parallelogram_legs(
        config.batch_shape,
        config.a,
        config.u,
        config.elbow_corners,
        config.platform_corners,
        [limb_platform[limb] for limb in range(4)],
        middle,
    )
    return JointTable("base", "end_effector", tuple(specs), screws, dof=4, mobility=4)


def parallelogram_legs(
    batch: tuple[int, ...],
    a: np.ndarray,
    u: np.ndarray,
    elbow_corners: np.ndarray,
    platform_corners: np.ndarray,
    platform_links: list[str],
    middle: list[tuple[JointSpec, np.ndarray]],
) -> tuple[np.ndarray, list[JointSpec]]:
    """The joints of ``n`` legs ``R–(4S)`` (paper 002, §4.1, Fig. 2), shared by the families with
    parallelogram legs (this one and :mod:`screwkit.robots.families.delta`): per leg ``i`` an actuated
    revolute joint ``A<i>`` (``base`` → ``arm<i>``, axis ``u_i`` through ``A_i``: the screw
    ``(u_i; a_i × u_i)``) and two rods ``rod<i>a``, ``rod<i>b`` with spherical joints ``S<i>m``,
    ``S<i>n`` on the arm and ``S<i>p``, ``S<i>q`` on the leg's platform link.

    Parameters
    ----------
    batch : tuple of int
        The batch shape.
    a, u : numpy.ndarray, shape (..., n, 3)
        The actuated joints' points and unit axes.
    elbow_corners, platform_corners : numpy.ndarray, shape (..., n, 2, 3)
        The sphere centres ``m, n`` on the arms and ``p, q`` on the platform links.
    platform_links : list of str
        The link each leg's rods end on.
    middle : list of (JointSpec, numpy.ndarray (..., 6))
        Joints whose names sort between ``A<i>`` and ``S<i>...`` (the platform's own joints), with
        their screws.

    Returns
    -------
    screws : numpy.ndarray, shape (..., n + len(middle) + 12 n, 6)
        Read-only, rows in the order of the joints' names (the analysis core's canonical order).
    specs : list of JointSpec

    Examples
    --------
    >>> config = load_mechanism("h4").configuration()
    >>> screws, specs = parallelogram_legs((), config.a, config.u, config.elbow_corners,
    ...     config.platform_corners, ["b_I", "b_II", "b_II", "b_I"], [])
    >>> screws.shape, specs[4].name
    ((52, 6), 'S1m')
    """
    n, m = len(platform_links), len(middle)
    screws = np.empty((*batch, n + m + 4 * n * 3, 6))
    # the revolute twists (u; a × u) written in place: S.revolute_twist's operations without its
    # checks (the axes are unit vectors of the base frames)
    screws[..., :n, :3] = u
    screws[..., :n, 3:] = cross(a, u)
    specs = [JointSpec(f"A{i}", "R", "base", f"arm{i}", 1, True) for i in range(1, n + 1)]
    for k, (spec, screw) in enumerate(middle):
        screws[..., n + k, :] = screw
        specs.append(spec)
    spheres = screws[..., n + m :, :].reshape(*batch, n, 4, 3, 6)  # a view: leg, corner m n p q, axis
    _sphere_twists(elbow_corners, spheres[..., :2, :, :])
    _sphere_twists(platform_corners, spheres[..., 2:, :, :])
    for limb, platform in enumerate(platform_links):
        i = limb + 1
        specs += [
            JointSpec(f"S{i}m", "S", f"arm{i}", f"rod{i}a", 3, False),
            JointSpec(f"S{i}n", "S", f"arm{i}", f"rod{i}b", 3, False),
            JointSpec(f"S{i}p", "S", f"rod{i}a", platform, 3, False),
            JointSpec(f"S{i}q", "S", f"rod{i}b", platform, 3, False),
        ]
    screws.flags.writeable = False  # fresh: the table takes it without a copy
    return screws, specs


def _sphere_twists(centres: np.ndarray, out: np.ndarray) -> None:
    """The unit rotations about ``x, y, z`` through each of ``centres (..., 3)``, written into
    ``out (..., 3, 6)``: the lines ``(e_k; c × e_k)`` of :func:`screwkit.algebra.screw.revolute_twist`
    written out (no validation needed: the directions are the unit axes)."""
    out[...] = 0.0
    x, y, z = centres[..., 0], centres[..., 1], centres[..., 2]
    for k in range(3):
        out[..., k, k] = 1.0
    out[..., 0, 4], out[..., 0, 5] = z, -y  # c × e_x = (0, z, −y)
    out[..., 1, 3], out[..., 1, 5] = -z, x  # c × e_y = (−z, 0, x)
    out[..., 2, 3], out[..., 2, 4] = y, -x  # c × e_z = (y, −x, 0)


def twist_basis(config: FourLimbConfiguration) -> np.ndarray:
    """The end effector's nominal twists over the batch: a Schoenflies basis (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1``, ``ż = 1`` and ``φ̇ = 1`` with ``χ = (x, y, z, φ)``: the three
    translations and the rotation about the end effector's own axis of rotation,
    ``config.platform_joint_axis`` (``k`` for the Quattro, H4, Veloce and Ragnar, ``j`` for the
    V4) through the end-effector point ``p`` (:func:`screwkit.core.jacobians.schoenflies_basis`). They
    are the columns of ``A`` in :func:`screwkit.core.jacobians.jacobians_from_wrenches`, in paper 004's
    order (Eq. 7a).

    Parameters
    ----------
    config : FourLimbConfiguration
        From :func:`~screwkit.robots.families.four_limb.kinematics.inverse_kinematics` (any batch shape
        ``...``).

    Returns
    -------
    numpy.ndarray, shape (..., 4, 6)

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`FourLimbConfiguration`.

    Examples
    --------
    >>> from screwkit.robots.families.four_limb.kinematics import inverse_kinematics
    >>> from screwkit.robots.families.four_limb.parameters import FourLimbParameters
    >>> v4 = FourLimbParameters(name="V4", platform_kind="articulated_y", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> twist_basis(inverse_kinematics(v4, [[0, 0, -700, 0], [50, 0, -700, 0.2]]))[1, 3]  # about j
    array([  0.,   1.,   0., 700.,   0.,  50.])
    """
    _require(config, FourLimbConfiguration, "config")
    return schoenflies_basis(config.pose[..., :3], config.platform_joint_axis)


def application_points(config: FourLimbConfiguration) -> np.ndarray:
    """Where the actuation wrenches act on the actuated links: the elbows ``B_i`` (Eq. 2), in limb
    order (the family's ``application_points`` hook, :class:`screwkit.robots.families.Family`).

    Parameters
    ----------
    config : FourLimbConfiguration

    Returns
    -------
    numpy.ndarray, shape (..., 4, 3)

    Examples
    --------
    >>> application_points(load_mechanism("h4").configuration()).shape
    (4, 3)
    """
    _require(config, FourLimbConfiguration, "config")
    return np.asarray(config.b)


def actuated_values(config: FourLimbConfiguration) -> np.ndarray:
    """The actuated angles ``θ_i`` (Eq. 2) in the order of the joints ``A1..A4`` (the family's
    ``actuated_values`` hook, :class:`screwkit.robots.families.Family`).

    Parameters
    ----------
    config : FourLimbConfiguration

    Returns
    -------
    numpy.ndarray, shape (..., 4)

    Examples
    --------
    >>> actuated_values(load_mechanism("h4").configuration()).shape
    (4,)
    """
    _require(config, FourLimbConfiguration, "config")
    return np.asarray(config.theta)


def working_mode_of(config: FourLimbConfiguration) -> np.ndarray:
    """The working mode a configuration is in, read from its geometry: the signs of
    ``h_i = b w_i·(u_i × v_i)`` (paper 004, Eq. 8), which change only at a serial singularity of
    limb ``i``. The paper's mode, ``h_i < 0`` for every limb, has the elbows ``B_i`` out, farther
    from the base's centre than the actuated joints ``A_i`` (``tests/test_testing.py``).

    Parameters
    ----------
    config : FourLimbConfiguration

    Returns
    -------
    numpy.ndarray of int, shape (..., 4)

    Examples
    --------
    >>> working_mode_of(load_mechanism("h4").configuration()).tolist()
    [-1, -1, -1, -1]
    """
    _require(config, FourLimbConfiguration, "config")
    return np.sign(config.h).astype(int)
