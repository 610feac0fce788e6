"""An independent model of the four-limb robots with an articulated nacelle (Quattro, H4), written
for the tests from the papers, sharing no code with screwkit's kinematics.

* Inverse kinematics: paper 004, Eq. (1) (base points a_i = R [cos eta_i, sin eta_i, 0],
  eta_i = (2i - 1) pi/4), Table 1 (platform points c_i = sgn(cos eta_i) r R_z(phi) i
  + sgn(sin eta_i) c j + p), Eq. (2)-(3) (the arm b_i = a_i + b F_i R_x(theta_i) j with
  F_i = R_z(alpha_i), alpha_i = (alpha, -alpha, beta, -beta) and |c_i - b_i| = l), solved for
  theta_i by a numeric root search of |c_i - b_i|^2 - l^2 in the working mode h_i < 0 (Eq. 8).
* Paper 002, Eq. (6): the constraint condition (s_I x s_II) . z with s_I = n_1 x n_2 over the
  limbs of sub-platform I (paper 002's limbs 1, 2 are paper 004's 1, 4) and n_i the normal of limb
  i's parallelogram (its rod direction w_i times its actuated axis F_i i).
* Paper 002, Eq. (7): the actuation condition ((w_1 x w_2) x ((r_g - r_c) x z)) . (w_3 x w_4) with
  r_c, r_g points of the sub-platforms' vertical axes (p + r R_z(phi) i and p - r R_z(phi) i).
"""

from __future__ import annotations

import numpy as np

ETA = (2 * np.arange(1, 5) - 1) * np.pi / 4
SGN_COS = np.sign(np.cos(ETA))
SGN_SIN = np.sign(np.sin(ETA))
Z = np.array([0.0, 0.0, 1.0])


def _rod_for(a, ci, fj, b: float, rod: float):
    """Limb rods w (unit) and h for the working mode h < 0: the roots of |c - b(theta)|^2 = l^2 by
    a sign scan of 721 samples refined by 60 bisections."""

    def elbow(theta: float) -> np.ndarray:
        return a + b * (np.cos(theta) * fj + np.sin(theta) * Z)

    def gap(theta: float) -> float:
        return float(np.sum((ci - elbow(theta)) ** 2) - rod * rod)

    grid = np.linspace(-np.pi, np.pi, 721)
    elbows = a + b * (np.cos(grid)[:, None] * fj + np.sin(grid)[:, None] * Z)
    values = np.sum((ci - elbows) ** 2, axis=1) - rod * rod
    for k in np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:])):
        lo, hi = grid[k], grid[k + 1]
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if np.sign(gap(mid)) == np.sign(gap(lo)):
                lo = mid
            else:
                hi = mid
        theta = 0.5 * (lo + hi)
        w = (ci - elbow(theta)) / rod
        # Eq. (8): h_i = b w_i . (u_i x v_i), u_i x v_i = -sin(theta) F_i j + cos(theta) k
        h = b * float(w @ (-np.sin(theta) * fj + np.cos(theta) * Z))
        if h < 0:
            return w, h
    raise ValueError("out of reach")


def geometry(params: dict, pose) -> dict:
    """Rods w_i (unit), axes u_i, h_i, and the platform's points for one pose (x, y, z, phi)."""
    x, y, z, phi = (float(v) for v in pose)
    p = np.array([x, y, z])
    alphas = np.array([params["alpha"], -params["alpha"], params["beta"], -params["beta"]])
    bar = np.array([np.cos(phi), np.sin(phi), 0.0])
    w, u, h = [], [], []
    for i in range(4):
        a = params["R"] * np.array([np.cos(ETA[i]), np.sin(ETA[i]), 0.0])
        ci = SGN_COS[i] * params["r"] * bar + SGN_SIN[i] * params["c"] * np.array([0.0, 1.0, 0.0]) + p
        fj = np.array([-np.sin(alphas[i]), np.cos(alphas[i]), 0.0])
        wi, hi = _rod_for(a, ci, fj, params["b"], params["l"])
        w.append(wi)
        u.append(np.array([np.cos(alphas[i]), np.sin(alphas[i]), 0.0]))
        h.append(hi)
    return {"w": np.array(w), "u": np.array(u), "h": np.array(h), "p": p, "bar": bar, "r": params["r"]}


def eq6_constraint(g: dict) -> float:
    """Paper 002, Eq. (6), with paper 004's limb numbering (sub-platform I: limbs 1, 4)."""
    n = np.cross(g["w"], g["u"])
    s_one, s_two = np.cross(n[0], n[3]), np.cross(n[1], n[2])
    return float(np.cross(s_one, s_two) @ Z)


def eq7_actuation(g: dict) -> float:
    """Paper 002, Eq. (7), with paper 004's limb numbering."""
    w = g["w"]
    r_c = g["p"] + g["r"] * g["bar"]
    r_g = g["p"] - g["r"] * g["bar"]
    return float(np.cross(np.cross(w[0], w[3]), np.cross(r_g - r_c, Z)) @ np.cross(w[1], w[2]))


QUATTRO = {
    "R": 275.0,
    "b": 375.0,
    "l": 800.0,
    "r": 80.0,
    "c": 70.0,
    "alpha": -np.pi / 4,
    "beta": 3 * np.pi / 4,
}
H4 = {"R": 275.0, "b": 375.0, "l": 800.0, "r": 80.0, "c": 70.0, "alpha": 0.0, "beta": np.pi / 2}
