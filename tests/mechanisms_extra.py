"""More test mechanisms as twist graphs (the documented API: ``twist_graph`` and the joint builders).

A Delta robot (three R-(4S) parallelogram legs, pure translation), a general 3-PRS, an octahedral
(3-3) Gough-Stewart platform, a singular pose of the general 6-6 one, and a writer of snapshot TOML
files. Each builder takes the configuration's geometry (positions and angles chosen in the test)
and solves its own closed-form inverse kinematics where the mechanism needs it.
"""

import numpy as np

from screwkit.graphs.joints import prismatic, revolute, spherical
from screwkit.graphs.twistgraph import twist_graph

from . import mechanisms as M

Z = np.array([0.0, 0.0, 1.0])
DELTA_ANGLES = np.deg2rad([90.0, 210.0, 330.0])


def delta(position, *, base_radius=1.0, platform_radius=0.3, arm=1.0, rod=2.0, spacing=0.2):
    """A Delta robot: in leg i an actuated R about the base circle's tangent ``t_i`` at ``A_i``, an
    arm to ``B_i``, and a parallelogram of two rods ``S_m S_p`` and ``S_n S_q`` (``m, n = B_i ± t_i
    spacing / 2``, ``p, q = P_i ± t_i spacing / 2``, ``P_i`` the platform point of the leg).

    The arm angle solves ``|P_i − B_i(β)| = rod`` (``B_i = A_i + arm (cos β e_r − sin β z)``):
    ``ρ cos(β + φ) = (|D|² + arm² − rod²) / (2 arm)`` with ``D = P_i − A_i``, ``ρ = |(D_r, D_z)|``,
    ``φ = atan2(D_z, D_r)``.
    """
    position = np.asarray(position, dtype=float)
    joints = []
    for i, angle in enumerate(DELTA_ANGLES, start=1):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        tangent = np.cross(Z, radial)
        a = base_radius * radial
        p = position + platform_radius * radial
        d = p - a
        d_r, d_z = d @ radial, d @ Z
        k = (d @ d + arm**2 - rod**2) / (2 * arm)
        beta = np.arccos(k / np.hypot(d_r, d_z)) - np.arctan2(d_z, d_r)
        b = a + arm * (np.cos(beta) * radial - np.sin(beta) * Z)
        assert abs(np.linalg.norm(p - b) - rod) < 1e-9  # the leg closes
        half = 0.5 * spacing * tangent
        joints += M.r_4s_leg(i, a, tangent, b + half, b - half, p + half, p - half)
    return twist_graph("base", "platform", joints, dof=3)


def delta_couples(graph):
    """The constraint couple of each Delta leg: ``(0; n_i)``, ``n_i`` normal to its parallelogram
    (spanned by the hinge direction ``m − n`` and the rod ``p − m``), from the joints' centres."""
    centre = {key: np.asarray(j.geometry["center"]) for _, _, key, j in graph.edges(keys=True, data="joint") if j.type == "S"}
    rows = []
    for i in (1, 2, 3):
        normal = np.cross(centre[f"Sm{i}"] - centre[f"Sn{i}"], centre[f"Sp{i}"] - centre[f"Sm{i}"])
        rows.append(np.concatenate([np.zeros(3), M.unit(normal)]))
    return np.array(rows)


def delta_actuation_lines(graph):
    """Each leg's actuation force: along its rods, in the parallelogram's mid-plane (any line of it
    parallel to the rods differs from another by the leg's constraint couple)."""
    centre = {key: np.asarray(j.geometry["center"]) for _, _, key, j in graph.edges(keys=True, data="joint") if j.type == "S"}
    rows = []
    for i in (1, 2, 3):
        middle = 0.5 * (centre[f"Sm{i}"] + centre[f"Sn{i}"])
        direction = M.unit(centre[f"Sp{i}"] - centre[f"Sm{i}"])
        rows.append(np.concatenate([direction, np.cross(middle, direction)]))
    return np.array(rows)


def three_prs(rotation, position, *, base_radius=1.0, platform_radius=0.5, drop=0.8, angles=DELTA_ANGLES):
    """A general 3-PRS: actuated vertical P at ``b_i`` (base circle), an R whose axis is horizontal
    and normal to the vertical plane through ``b_i`` and the platform point ``c_i``, at height
    ``c_i·z − drop``, and an S at ``c_i``. The leg planes are taken through the platform points of
    the given pose, so every pose is a configuration of some 3-PRS.

    Returns the graph and the constraint force of each leg (through ``c_i`` along the R axis).
    """
    rotation = np.asarray(rotation, dtype=float)
    joints, forces = [], []
    for i, angle in enumerate(angles, start=1):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        b = base_radius * radial
        c = np.asarray(position, dtype=float) + rotation @ (platform_radius * radial)
        horizontal = (c - b) - ((c - b) @ Z) * Z
        axis = M.unit(np.cross(Z, horizontal))
        s = b + (c[2] - drop) * Z
        joints += [
            ("base", f"slider{i}", prismatic(f"P{i}", Z, actuated=True)),
            (f"slider{i}", f"rod{i}", revolute(f"R{i}", axis, s)),
            (f"rod{i}", "platform", spherical(f"S{i}", c)),
        ]
        forces.append(np.concatenate([axis, np.cross(c, axis)]))
    return twist_graph("base", "platform", joints, dof=3), np.array(forces)


def three_prs_lines(rotation, position, **options):
    """A 3-PRS graph and its six wrench lines written from the geometry: each leg's rod line (its
    actuation force: through the R axis and the S centre) and its constraint force."""
    graph, forces = three_prs(rotation, position, **options)
    joints = {k: j for _, _, k, j in graph.edges(keys=True, data="joint")}
    rods = []
    for i in (1, 2, 3):
        s, c = np.asarray(joints[f"R{i}"].geometry["point"]), np.asarray(joints[f"S{i}"].geometry["center"])
        rods.append(np.concatenate([M.unit(c - s), np.cross(s, M.unit(c - s))]))
    return graph, np.concatenate([rods, forces])


#: The tilt axis, position and R height below the platform of :func:`singular_three_prs_tilt`.
PRS_TILT_AXIS, PRS_POSITION, PRS_DROP = [1.0, 0.3, 0.0], [0.02, 0.03, 1.0], 0.3


def singular_three_prs_tilt():
    """A tilt angle at which the 6×6 determinant of :func:`three_prs_lines` vanishes (bisection
    between a sign change found on a grid)."""

    def det(angle):
        rotation = M.rotation_about(PRS_TILT_AXIS, angle)
        return np.linalg.det(three_prs_lines(rotation, PRS_POSITION, drop=PRS_DROP)[1])

    grid = np.linspace(0.2, 1.0, 33)
    values = [det(a) for a in grid]
    k = next(k for k in range(len(grid) - 1) if values[k] * values[k + 1] < 0)
    return M.bisect_root(det, grid[k], grid[k + 1])


def octahedral_points(rotation=None, position=(0.0, 0.0, 1.0)):
    """An octahedral (3-3) Gough-Stewart: base vertices at 90°, 210°, 330° (radius 1), platform
    vertices at 30°, 150°, 270° (radius 0.5); each base vertex joins the two platform vertices next
    to it. Returns the six legs' base and platform points (repeated vertices)."""
    base = M.circle_points(1.0, np.deg2rad([90.0, 90.0, 210.0, 210.0, 330.0, 330.0]))
    platform = M.circle_points(0.5, np.deg2rad([30.0, 150.0, 150.0, 270.0, 270.0, 30.0]))
    return M.gough_stewart_points(rotation, position, base=base, platform=platform)


def singular_gough_stewart_angle():
    """A rotation about z of the general 6-6 platform (:data:`tests.mechanisms.GS_PLATFORM`) at which
    the 6×6 determinant of its leg lines vanishes: bisection between a sign change found on a grid."""

    def det(angle):
        return np.linalg.det(M.leg_lines(*M.gough_stewart_points(M.rotation_z(angle))))

    grid = np.linspace(-np.pi, -np.pi / 4, 136)
    values = [det(a) for a in grid]
    k = next(k for k in range(len(grid) - 1) if values[k] * values[k + 1] < 0)
    return M.bisect_root(det, grid[k], grid[k + 1])
