"""Overconstrained linkages built by hand for the mobility tests, exact or with rounded coordinates.

- Bennett's 4R linkage (Bennett 1903, "A new mechanism", Engineering 76; conditions as in McCarthy &
  Soh 2011, *Geometric Design of Linkages*, 2nd ed., §9.5): opposite links equal, ``a12 = a34 = a``,
  ``α12 = α34 = α``, ``a23 = a41 = b``, ``α23 = α41 = β`` with ``a / sin α = b / sin β``; its joint
  angles obey ``θ3 = −θ1``, ``θ4 = −θ2`` and ``tan(θ1/2) tan(θ2/2) = sin((β+α)/2) / sin((β−α)/2)``
  in the Denavit–Hartenberg convention ``Z(θ1) X(a, α) Z(θ2) X(b, β) Z(θ3) X(a, α) Z(θ4) X(b, β) = I``
  (checked numerically by :func:`bennett_loop_error`, independent of screwkit).
- Sarrus' linkage: two chains of three parallel hinges, the chains' axes along x and along y; the
  platform only translates along z (one freedom, a 6R loop that Grübler's count calls rigid).
- A folded planar chain: a closed 4R loop whose links lie on one line, rigid but mobile to first order.

``decimals`` rounds every coordinate given to screwkit, as a design file would; a joint's axis is then
the unit vector between two rounded points on it (as read off a CAD model), so parallel axes are
parallel only to the data's precision.
"""

import numpy as np

from screwkit.graphs.joints import revolute
from screwkit.graphs.twistgraph import twist_graph

BENNETT_A, BENNETT_ALPHA, BENNETT_BETA = 1.0, np.pi / 6, np.pi / 3
BENNETT_B = BENNETT_A * np.sin(BENNETT_BETA) / np.sin(BENNETT_ALPHA)  # a / sin α = b / sin β


def _z(theta):
    c, s = np.cos(theta), np.sin(theta)
    out = np.eye(4)
    out[:2, :2] = [[c, -s], [s, c]]
    return out


def _x(length, twist):
    c, s = np.cos(twist), np.sin(twist)
    out = np.eye(4)
    out[1:3, 1:3] = [[c, -s], [s, c]]
    out[0, 3] = length
    return out


def bennett_angles(theta1, alpha=BENNETT_ALPHA, beta=BENNETT_BETA):
    """The four joint angles of Bennett's linkage at input ``theta1`` (module docstring)."""
    theta2 = 2 * np.arctan(np.sin((beta + alpha) / 2) / np.sin((beta - alpha) / 2) / np.tan(theta1 / 2))
    return np.array([theta1, theta2, -theta1, -theta2])


def bennett_loop_error(angles, a=BENNETT_A, alpha=BENNETT_ALPHA, b=BENNETT_B, beta=BENNETT_BETA):
    """``max |Z X Z X Z X Z X − I|``: 0 when the angles close the loop."""
    t1, t2, t3, t4 = angles
    loop = _z(t1) @ _x(a, alpha) @ _z(t2) @ _x(b, beta) @ _z(t3) @ _x(a, alpha) @ _z(t4) @ _x(b, beta)
    return float(np.abs(loop - np.eye(4)).max())


def _rounded_axis(point, direction, decimals, reach):
    """The axis through ``point`` along ``direction`` as given by two rounded points ``reach`` apart."""
    if decimals is None:
        return np.asarray(direction, float), np.asarray(point, float)
    p, q = np.round(point, decimals), np.round(point + reach * np.asarray(direction), decimals)
    return (q - p) / np.linalg.norm(q - p), p


def _loop_graph(axes_points, first, rest, decimals, reach, actuated):
    """A twist graph of one loop: ``first`` and ``rest`` are the two paths' (parent, child) links."""
    joints = [
        revolute(f"R{i + 1}", *_rounded_axis(p, d, decimals, reach), actuated=(i == 0 and actuated))
        for i, (d, p) in enumerate(axes_points)
    ]
    return twist_graph(
        "ground", "platform", [(*edge, joint) for edge, joint in zip(first + rest, joints, strict=True)]
    )


def bennett(theta1=0.7, *, decimals=None, scale=1.0, actuated=False):
    """Bennett's linkage at input ``theta1``: ground –R1– L1 –R2– platform –R3– L3 –R4– ground."""
    frames = [np.eye(4)]
    angles = bennett_angles(theta1)
    links = [(BENNETT_A, BENNETT_ALPHA), (BENNETT_B, BENNETT_BETA), (BENNETT_A, BENNETT_ALPHA)]
    for theta, (length, twist) in zip(angles[:3], links, strict=True):
        frames.append(frames[-1] @ _z(theta) @ _x(length, twist))
    axes_points = [(f[:3, 2], f[:3, 3] * scale) for f in frames]
    edges = [("ground", "L1"), ("L1", "platform"), ("L3", "platform"), ("ground", "L3")]
    return _loop_graph(axes_points, edges[:2], edges[2:], decimals, 0.5 * scale, actuated)


#: A generic orientation of Sarrus' linkage (so that rounding its coordinates changes its axes).
SARRUS_ROTATION = np.linalg.qr(np.array([[0.3, -1.2, 0.5], [0.8, 0.4, -0.7], [0.2, 0.9, 1.1]]))[0]


def sarrus(*, decimals=None, scale=1.0, actuated=False):
    """Sarrus' linkage, rotated by :data:`SARRUS_ROTATION`: chain A (hinges along x) from ground
    (0, −1, 0) by a knee (0, −1.6, 0.8) to the platform at (0, −1, 1.6); chain B the same in the
    xz plane along y. Links of length 1."""
    x, y = np.eye(3)[:2]
    chain_a = [(x, [0, -1, 0]), (x, [0, -1.6, 0.8]), (x, [0, -1, 1.6])]
    chain_b = [(y, [-1, 0, 1.6]), (y, [-1.6, 0, 0.8]), (y, [-1, 0, 0])]
    axes_points = [
        (SARRUS_ROTATION @ d, SARRUS_ROTATION @ np.array(p, float) * scale) for d, p in chain_a + chain_b
    ]
    edges = [
        ("ground", "A1"),
        ("A1", "A2"),
        ("A2", "platform"),
        ("platform", "B2"),
        ("B2", "B1"),
        ("B1", "ground"),
    ]
    return _loop_graph(axes_points, edges[:3], edges[3:], decimals, 0.5 * scale, actuated)
