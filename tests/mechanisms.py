"""Twist graphs of textbook parallel mechanisms, built from explicit points and axes (test helpers).

Every builder takes world-frame geometry (points and axes in the caller's unit) and returns a
checked twist graph; the poses that make them singular are constructed in the tests from hand
derivations. :func:`moved` applies a rigid motion and a change of length unit to any twist graph.
"""

import itertools

import networkx as nx
import numpy as np

from screwkit.algebra import screw as S
from screwkit.graphs.joints import Joint, cylindrical, helical, prismatic, revolute, spherical, universal
from screwkit.graphs.twistgraph import twist_graph

Z = np.array([0.0, 0.0, 1.0])


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def rotation_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_about(axis, angle):
    """Rodrigues: the rotation by ``angle`` about the unit ``axis``."""
    k = unit(axis)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * cross + (1 - np.cos(angle)) * cross @ cross


def circle_points(radius, angles, z=0.0):
    return np.array([[radius * np.cos(a), radius * np.sin(a), z] for a in angles])


# Gough-Stewart 6-UPS ----------------------------------------------------------------------------
#: Base and platform anchor points of a 6-6 Gough-Stewart platform (pairs of points on circles).
GS_BASE = circle_points(1.0, np.deg2rad([-10, 10, 110, 130, 230, 250]))
GS_PLATFORM = circle_points(0.5, np.deg2rad([-50, 50, 70, 170, 190, 290]))


def gough_stewart_points(rotation=None, position=(0.0, 0.0, 1.0), base=GS_BASE, platform=GS_PLATFORM):
    """World positions of the base and platform anchors at a pose (platform frame: rotation, position)."""
    rotation = np.eye(3) if rotation is None else np.asarray(rotation, dtype=float)
    return np.asarray(base, dtype=float), np.asarray(position, dtype=float) + platform @ rotation.T


def gough_stewart(base_points, platform_points):
    """6-UPS with actuated prismatic legs: U (base) - P - S (platform) in each leg i = 1..6.

    The first U axis is fixed in the base (horizontal, tangent to the base circle), the second is
    perpendicular to it and to the leg.
    """
    joints = []
    for i, (a, c) in enumerate(zip(base_points, platform_points, strict=True), start=1):
        leg = unit(c - a)
        first = unit(np.cross(Z, a)) if np.linalg.norm(np.cross(Z, a)) > 0 else np.array([1.0, 0, 0])
        second = unit(np.cross(leg, first))
        joints += [
            ("base", f"lower{i}", universal(f"U{i}", first, second, a)),
            (f"lower{i}", f"upper{i}", prismatic(f"P{i}", leg, actuated=True)),
            (f"upper{i}", "platform", spherical(f"S{i}", c)),
        ]
    return twist_graph("base", "platform", joints)


def leg_lines(base_points, platform_points):
    """The six leg lines (s; a × s), unit directions: the Plücker rows of the Jacobian."""
    return np.array([S.line(unit(c - a), a) for a, c in zip(base_points, platform_points, strict=True)])


# Tsai's 3-UPU translational manipulator ---------------------------------------------------------
UPU_ANGLES = np.deg2rad([90.0, 210.0, 330.0])


def tsai_3upu(position, base_radius=1.0, platform_radius=0.5, angles=UPU_ANGLES):
    """Tsai's 3-UPU: in each leg the two inner R axes are parallel, and so are the two outer ones.

    Leg i: base U at ``A_i`` (outer axis ``u_i`` horizontal, tangent to the base circle; inner axis
    ``w_i = u_i × d_i`` normalised, ``d_i`` the leg direction), actuated P along ``d_i``, platform
    U at ``C_i`` (inner axis ``w_i``, outer axis ``u_i``). The platform only translates.
    """
    position = np.asarray(position, dtype=float)
    joints = []
    for i, angle in enumerate(angles, start=1):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        a, c = base_radius * radial, position + platform_radius * radial
        u = np.cross(Z, radial)
        d = unit(c - a)
        w = unit(np.cross(u, d))
        joints += [
            ("base", f"lower{i}", universal(f"Ub{i}", u, w, a)),
            (f"lower{i}", f"upper{i}", prismatic(f"P{i}", d, actuated=True)),
            (f"upper{i}", "platform", universal(f"Up{i}", w, u, c)),
        ]
    return twist_graph("base", "platform", joints)


def tsai_constraint_couples(position, base_radius=1.0, platform_radius=0.5, angles=UPU_ANGLES):
    """The couple (0; u_i × w_i) each leg applies (normal to both U axes), rows (3, 6)."""
    rows = []
    for angle in angles:
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        d = unit(np.asarray(position) + platform_radius * radial - base_radius * radial)
        u = np.cross(Z, radial)
        rows.append(S.couple(unit(np.cross(u, unit(np.cross(u, d))))))
    return np.array(rows)


# planar 3-RPR and 3-RRR (all revolute axes along z: the mechanism stays in the plane z = const) --
def planar_3rpr(base_points, platform_points):
    """3-RPR: R at ``A_i`` - actuated P along ``A_i C_i`` - R at ``C_i``, all R axes along z."""
    joints = []
    for i, (a, c) in enumerate(zip(base_points, platform_points, strict=True), start=1):
        joints += [
            ("base", f"leg{i}", revolute(f"Ra{i}", Z, a)),
            (f"leg{i}", f"rod{i}", prismatic(f"P{i}", unit(np.subtract(c, a)), actuated=True)),
            (f"rod{i}", "platform", revolute(f"Rc{i}", Z, c)),
        ]
    return twist_graph("base", "platform", joints)


def planar_3rrr(base_points, elbow_points, platform_points):
    """3-RRR: actuated R at ``A_i`` - R at the elbow ``B_i`` - R at ``C_i``, all axes along z."""
    joints = []
    for i, (a, b, c) in enumerate(zip(base_points, elbow_points, platform_points, strict=True), start=1):
        joints += [
            ("base", f"arm{i}", revolute(f"Ra{i}", Z, a, actuated=True)),
            (f"arm{i}", f"forearm{i}", revolute(f"Rb{i}", Z, b)),
            (f"forearm{i}", "platform", revolute(f"Rc{i}", Z, c)),
        ]
    return twist_graph("base", "platform", joints)


PLANAR_BASE = np.array([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [1.5, 3.5, 0.0]])
PLANAR_PLATFORM = np.array([[1.4, 1.1, 0.0], [2.6, 1.3, 0.0], [1.9, 2.2, 0.0]])


# an H4 leg: R - (4S) parallelogram (paper 002 §4.1, Fig. 2) -----------------------------------
def r_4s_leg(index, hinge_point, hinge_axis, m, n, p, q, arm="arm", end="platform"):
    """One R-(4S) leg: actuated R on the base, then S_m - S_p and S_n - S_q from the arm to ``end``."""
    i = index
    return [
        ("base", f"{arm}{i}", revolute(f"A{i}", hinge_axis, hinge_point, actuated=True)),
        (f"{arm}{i}", f"rod{i}a", spherical(f"Sm{i}", m)),
        (f"rod{i}a", end, spherical(f"Sp{i}", p)),
        (f"{arm}{i}", f"rod{i}b", spherical(f"Sn{i}", n)),
        (f"rod{i}b", end, spherical(f"Sq{i}", q)),
    ]


# rigid motions and changes of unit --------------------------------------------------------------
def moved(graph, rotation=None, translation=(0.0, 0.0, 0.0), factor=1.0, joint_key="joint"):
    """The same mechanism moved rigidly, then described in another unit (lengths times ``factor``).

    The rigid motion is the adjoint map (``translation`` in the graph's unit). A change of unit then
    multiplies every moment by ``factor`` (points and pitches are lengths); couples/translations
    ``(0; d)`` keep their unit direction.
    """
    rotation = np.eye(3) if rotation is None else rotation
    result = nx.MultiDiGraph(**graph.graph)
    result.add_nodes_from(graph.nodes(data=True))
    for u, v, key, data in graph.edges(keys=True, data=True):
        joint = data[joint_key]
        rows = S.transform(np.array(joint.screws, dtype=float), rotation, translation)
        rows[:, 3:] *= factor
        rows = S.normalize(rows)
        geometry = {  # the joints' points move with the mechanism (and scale with the unit)
            key: ((rotation @ np.asarray(value) + translation) * factor).tolist()
            for key, value in joint.geometry.items() if key in ("point", "center")
        }
        copy = Joint(joint.name, joint.type, rows, joint.actuated, joint.virtual, geometry)
        result.add_edge(u, v, key=key, **{**data, joint_key: copy})
    return result


# Bennett's overconstrained 4R linkage ---------------------------------------------------------
def dh_transform(theta, length, twist):
    """Denavit-Hartenberg ``Rz(θ) Tx(a) Rx(α)`` (4, 4)."""
    c, s, ca, sa = np.cos(theta), np.sin(theta), np.cos(twist), np.sin(twist)
    return np.array([[c, -s * ca, s * sa, length * c], [s, c * ca, -c * sa, length * s],
                     [0.0, sa, ca, 0.0], [0.0, 0.0, 0.0, 1.0]])


BENNETT_TWISTS = np.deg2rad([40.0, 75.0])


def bennett_links(alpha=BENNETT_TWISTS[0], beta=BENNETT_TWISTS[1], length=1.0, bennett=True):
    """Bennett's link lengths and twists ``[(a, α), (b, β), (a, α), (b, β)]``, with
    ``a / sin α = b / sin β`` (Bennett 1903) unless ``bennett`` is False (then ``b`` is 1.3 times it)."""
    other = length * np.sin(beta) / np.sin(alpha) * (1.0 if bennett else 1.3)
    return [(length, alpha), (other, beta), (length, alpha), (other, beta)]


def bennett_axes(theta, links):
    """The four joint axes (direction, point) of the loop ``T1 T2 T3 T4 = I``, joint i on the z axis of
    frame i-1, at joint angles ``(θ, φ, -θ, -φ)`` with ``tan(θ/2) tan(φ/2) = sin((β+α)/2) /
    sin((β-α)/2)`` (Bennett's closure, in this DH convention; the tests check the loop closes)."""
    (_, alpha), (_, beta) = links[0], links[1]
    phi = 2.0 * np.arctan(np.sin((beta + alpha) / 2) / (np.sin((beta - alpha) / 2) * np.tan(theta / 2)))
    frame, axes = np.eye(4), []
    for angle, (length, twist) in zip((theta, phi, -theta, -phi), links, strict=True):
        axes.append((frame[:3, 2].copy(), frame[:3, 3].copy()))
        frame = frame @ dh_transform(angle, length, twist)
    return axes, frame


def bennett(theta=0.9, links=None):
    """Bennett's 4R linkage at joint angle ``theta``: ground - L1 - coupler - L3 - ground (with
    ``links`` that break Bennett's condition: four lines of no closed linkage, a rigid 4R)."""
    axes, _ = bennett_axes(theta, bennett_links() if links is None else links)
    links_of = [("ground", "L1"), ("L1", "coupler"), ("coupler", "L3"), ("L3", "ground")]
    return twist_graph("ground", "coupler", [
        (u, v, revolute(f"R{i}", axis, point, actuated=i == 1))
        for i, ((u, v), (axis, point)) in enumerate(zip(links_of, axes, strict=True), start=1)])


# other topologies ------------------------------------------------------------------------------
def wheatstone_bridge():
    """A bridge: base - x, base - y, x - y, x - platform, y - platform (not series-parallel)."""
    return twist_graph(
        "base",
        "platform",
        [
            ("base", "x", revolute("Rbx", [0, 0, 1], [0, 0, 0])),
            ("base", "y", revolute("Rby", [0, 0, 1], [1, 0, 0])),
            ("x", "y", revolute("Rxy", [0, 0, 1], [0.5, 0.5, 0])),
            ("x", "platform", revolute("Rxp", [0, 0, 1], [0, 1, 0])),
            ("y", "platform", revolute("Ryp", [0, 0, 1], [1, 1, 0])),
        ],
    )


def random_joint(rng, name):
    """A joint of a random type (R, P, H, C, U, S) at random geometry."""
    kind = rng.choice(["R", "P", "H", "C", "U", "S"], p=[0.35, 0.2, 0.1, 0.1, 0.15, 0.1])
    axis, point = rng.normal(size=3), rng.uniform(-1, 1, size=3)
    if kind == "R":
        return revolute(name, axis, point)
    if kind == "P":
        return prismatic(name, axis)
    if kind == "H":
        return helical(name, axis, point, rng.uniform(-0.5, 0.5))
    if kind == "C":
        return cylindrical(name, axis, point)
    if kind == "U":
        return universal(name, axis, np.cross(axis, rng.normal(size=3)), point)
    return spherical(name, point)


def random_series_parallel(rng, depth=2):
    """A random series-parallel twist graph between "B" and "E" (joints in random directions)."""
    names, links, triples = iter(range(1, 10_000)), iter(range(1, 10_000)), []

    def build(a, b, level):
        draw = rng.uniform()
        if level == 0 or draw < 0.35:
            joint = random_joint(rng, f"J{next(names)}")
            triples.append((a, b, joint) if rng.uniform() < 0.5 else (b, a, joint))
        elif draw < 0.7:
            chain = [a, *[f"L{next(links)}" for _ in range(rng.integers(1, 3))], b]
            for x, y in itertools.pairwise(chain):
                build(x, y, level - 1)
        else:
            for _ in range(rng.integers(2, 4)):
                middle = f"L{next(links)}"
                build(a, middle, level - 1)
                build(middle, b, level - 1)

    build("B", "E", depth)
    return twist_graph("B", "E", triples)


def bisect_root(function, low, high, *, xtol=1e-15, iterations=200):
    """A root of a continuous function that changes sign on [low, high] (plain bisection)."""
    f_low = function(low)
    assert np.sign(f_low) != np.sign(function(high)), "no sign change on the bracket"
    for _ in range(iterations):
        middle = 0.5 * (low + high)
        f_middle = function(middle)
        if f_middle == 0:
            return middle
        if np.sign(f_middle) == np.sign(f_low):
            low, f_low = middle, f_middle
        else:
            high = middle
        if high - low <= xtol * max(1.0, abs(low)):
            break
    return 0.5 * (low + high)
