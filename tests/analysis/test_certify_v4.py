"""Certification of the V4 (paper 004's H4 base with a nacelle articulated about j): the constraint
condition derived from the limbs' couples, checked against an independent model written here (its own
inverse kinematics by circle-sphere intersection, the end effector's constraint couples by a rank
computation, det A from paper 004's Eq. 7), against the core, and against paper 002's Eq. (6).

Why not paper 002's Eq. (6) with e = j: sub-platform I (limbs 1, 4) is held by the couples
n_i = w_i x u_i and may turn about s_I = n_1 x n_4; with R_I (axis j) the branch holds the end
effector by the couple c_I = s_I x j. Since u_4 = -j, n_4 . j = 0 and c_I = (n_1 . j) n_4: Eq. (6),
j . (s_I x s_II), factors as (n_1 . j)(n_2 . j) j . (n_4 x n_3). Where n_1 . j = w_1z vanishes (rod 1
horizontal) Eq. (6) changes sign although nothing is singular: n_1 is then normal to j too, and the
branch holds the end effector by two couples instead of one. The V4's condition is j . (n_4 x n_3).
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis.enclosures import FourLimbModel
from tests.analysis.certify_checks import assert_same_facts, in_metres, zeros_along

V4 = sk.load_mechanism("v4")
J = np.array([0.0, 1.0, 0.0])
ETA = (2 * np.arange(1, 5) - 1) * np.pi / 4
SIGMA = np.array([1.0, -1.0, -1.0, 1.0])  # sgn(cos eta_i)
TAU = np.array([1.0, 1.0, -1.0, -1.0])  # sgn(sin eta_i)
AXES = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]])  # alpha = 0, beta = 90 deg


def geometry(pose, scale=1.0):
    """Platform points, elbows and unit rods of the V4 at one pose (paper 004, Sec. 5 dimensions in mm
    times ``scale``; Table 1's V4 row as corrected in mechanisms/v4.toml), elbows by intersecting the
    arm's circle with the rod's sphere, in the branch h_i < 0 (w_i . (u_i x v_i) < 0). None out of reach."""
    big_r, arm, rod, small_r, offset = (v * scale for v in (275.0, 375.0, 800.0, 80.0, 70.0))
    p, phi = np.asarray(pose[:3], dtype=float), float(pose[3])
    bar = np.array([np.cos(phi), 0.0, -np.sin(phi)])  # R_y(phi) i
    c = p + SIGMA[:, None] * small_r * bar + TAU[:, None] * offset * J
    a = big_r * np.stack([np.cos(ETA), np.sin(ETA), np.zeros(4)], -1)
    rods = []
    for i in range(4):
        u = AXES[i]
        height = (c[i] - a[i]) @ u
        centre = c[i] - height * u  # the sphere |x - c| = l cut by the arm's plane
        radius2 = rod**2 - height**2
        d = np.linalg.norm(centre - a[i])
        along = (d**2 + arm**2 - radius2) / (2 * d)
        if radius2 < 0 or arm**2 - along**2 < 0:
            return None
        e1 = (centre - a[i]) / d
        e2 = np.cross(u, e1)
        for side in (1.0, -1.0):
            elbow = a[i] + along * e1 + side * np.sqrt(arm**2 - along**2) * e2
            w = (c[i] - elbow) / rod
            if w @ np.cross(u, (elbow - a[i]) / arm) < 0:
                rods.append(w)
                break
    return c, np.array(rods), phi, small_r


def couples(pose, scale=1.0):
    """The end effector's constraint couples from branch I (limbs 1, 4, joint R_I) and II (limbs 2, 3,
    R_II): each branch's twists are the sub-platform's (reciprocal to its limbs' couples n_i = w_i x u_i)
    and R_I's; the branch's wrenches are their reciprocal (null space, SVD). Returns the two couples'
    unit moments (a branch of rank 2 gives its first)."""
    _, w, phi, small_r = geometry(pose, scale)
    p = np.asarray(pose[:3], dtype=float)
    bar = np.array([np.cos(phi), 0.0, -np.sin(phi)])
    out = []
    for limbs, point in (((0, 3), p + small_r * bar), ((1, 2), p - small_r * bar)):
        rows = np.array([np.concatenate([np.cross(w[i], AXES[i]), np.zeros(3)]) for i in limbs])  # omega . n = 0
        sub = np.linalg.svd(rows)[2][2:]  # the sub-platform's twists (omega; v)
        twists = np.vstack([sub, np.concatenate([J, np.cross(point, J)])])
        # wrench (f; m) reciprocal to every twist: omega . m + v . f = 0
        swapped = np.hstack([twists[:, 3:], twists[:, :3]])
        _, values, vt = np.linalg.svd(swapped)
        rank = int(np.sum(values > 1e-10 * values[0]))
        wrench = vt[rank]
        assert np.linalg.norm(wrench[:3]) < 1e-9  # a couple
        out.append(wrench[3:] / np.linalg.norm(wrench[3:]))
    return out


def independent_closeness(pose):
    """|sin| of the angle between the two branches' couples (0: the constraint wrenches dependent)."""
    one, two = couples(pose)
    return float(np.linalg.norm(np.cross(one, two)))


def weighted_closeness(pose, taper=0.1):
    """The core's constraint closeness written out: each branch's couple c (unit) weighed by its limbs'
    couples' span (n_a, n_b unit, singular values s_1 >= s_2 on directions v_1, v_2, weights
    min(1, s_i / (taper s_1))): g = 1 / |(c . v_i / weight_i)_i|; then sigma_2 / sigma_1 of the two
    weighed couples stacked."""
    _, w, _, _ = geometry(pose)
    rows = []
    for c, limbs in zip(couples(pose), ((0, 3), (1, 2)), strict=True):
        normals = np.array([np.cross(w[i], AXES[i]) for i in limbs])
        normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        _, values, directions = np.linalg.svd(normals)
        weights = np.minimum(1.0, values / (taper * values[0]))
        rows.append(c / np.linalg.norm(directions[:2] @ c / weights))
    values = np.linalg.svd(np.array(rows), compute_uv=False)
    return values[1] / values[0]


def det_a(pose):
    """det A, rows [w_i, r w_i . s_i] with s_i = sigma_i dR_y(phi) i/dphi (paper 004, Eq. 7, Table 1)."""
    _, w, phi, small_r = geometry(pose)
    s = np.array([-np.sin(phi), 0.0, -np.cos(phi)])
    return np.linalg.det(np.hstack([w, (small_r * SIGMA * (w @ s))[:, None]]))


def test_core_constraint_closeness_is_the_independent_couples_angle_and_eq6_is_not_the_condition():
    rng = np.random.default_rng(1)
    lo, hi = np.array([-900.0, -900.0, -1100.0, -1.5]), np.array([900.0, 900.0, -200.0, 1.5])
    poses = lo + rng.uniform(size=(7000, 4)) * (hi - lo)
    poses = poses[V4.reachable(poses)][:2000]
    assert len(poses) == 2000
    closeness = V4.at(poses).singularities.closeness["constraint"]
    # the core's closeness is tan(theta/2), theta the angle between the independent couples (<= 90 deg),
    # where the limbs under each couple's sub-platform are far from dependent; where two of them come
    # within a tenth (core _leg_weights.TAPER) the branch's couple is weighed by their span (7 % of these
    # poses, at most 0.2 % lower): written out in weighted_closeness, equal at every pose
    cosines = np.array([abs(np.dot(*couples(pose))) for pose in poses])
    half_angle = np.sqrt((1 - cosines) / (1 + cosines))
    assert np.mean(np.abs(closeness - half_angle) <= 1e-9) > 0.9
    np.testing.assert_allclose(closeness, [weighted_closeness(pose) for pose in poses], rtol=0, atol=1e-9)
    # the enclosed function vanishes with them: its sign is the sign of j . (n_4 x n_3)
    values = FourLimbModel.of(V4).values(poses)["constraint"]
    rods = V4.configuration(poses).w
    normals = np.cross(rods, AXES)
    np.testing.assert_allclose(values, np.cross(normals[:, 3], normals[:, 2]) @ J, rtol=1e-12, atol=1e-12)
    unit = np.abs(values) / np.linalg.norm(normals[:, 3], axis=-1) / np.linalg.norm(normals[:, 2], axis=-1)
    np.testing.assert_allclose(unit, np.sqrt(1 - cosines**2), atol=1e-9)
    # paper 002's Eq. (6) with e = j changes sign across rod 1 horizontal, where the core and the
    # independent couples read regular (the previous refusal's example pose, moved along x)
    line = np.array([503.5, -492.0, -352.0, 0.2]) + np.linspace(0.0, 40.0, 401)[:, None] * [1.0, 0.0, 0.0, 0.0]
    rods = V4.configuration(line).w
    normals = np.cross(rods, AXES)
    eq6 = np.cross(np.cross(normals[:, 0], normals[:, 3]), np.cross(normals[:, 1], normals[:, 2])) @ J
    (k,) = np.flatnonzero(np.diff(np.sign(eq6)))
    assert abs(rods[k, 0, 2]) < 1e-3  # w_1z: Eq. (6)'s factor n_1 . j
    # regular: one couple per branch at an angle of 14 deg (0.24 rad) apart (rod 1 is not quite
    # horizontal; where it is, branch I adds a second couple normal to j, which the core's rank
    # tolerance already counts here: its closeness reads 0.78)
    assert independent_closeness(line[k]) > 0.2 and V4.at(line[k : k + 2]).singularities.closeness["constraint"].min() > 0.7
    assert np.all(np.sign(FourLimbModel.of(V4).values(line)["constraint"]) == 1)


def test_independent_constraint_singularities_lie_in_no_free_box_and_witnesses_vanish():
    region = {"x": (-200.0, 200.0), "y": (450.0, 750.0), "z": -250.0, "phi": 0.0}
    certificate = sk.certify(V4, region, resolution=2.0)
    free = [b for b in certificate.boxes if b.status == "free"]
    found = 0
    for y in np.linspace(570.0, 610.0, 9):  # the independent singular set: zeros of |sin| along x
        line = np.stack([np.linspace(-200.0, 200.0, 201), np.full(201, y), np.full(201, -250.0), np.zeros(201)], -1)
        for zero in zeros_along(lambda pose: independent_closeness(pose) if geometry(pose) else None, line):
            found += 1
            assert not any(b.bounds["x"][0] <= zero[0] <= b.bounds["x"][1] and b.bounds["y"][0] <= y <= b.bounds["y"][1]
                           for b in free)
    assert found >= 12
    witnesses = [b.witness for b in certificate.boxes if b.status == "singular" and b.witness.label == "constraint"]
    assert len(witnesses) > 100
    for w in witnesses[::10]:
        assert independent_closeness([w.pose["x"], w.pose["y"], w.pose["z"], w.pose["phi"]]) < 1e-6


def test_random_poses_in_free_boxes_are_regular_by_independent_ranks():
    rng = np.random.default_rng(5)
    for region in ({"x": (-650.0, 650.0), "y": (-650.0, 650.0), "z": -750.0, "phi": 0.0},
                   {"x": (-200.0, 200.0), "y": (450.0, 750.0), "z": -250.0, "phi": 0.0}):
        certificate = sk.certify(V4, region, resolution=8.0)
        free = [b for b in certificate.boxes if b.status == "free"]
        assert len(free) > 50
        for box in free[:: max(len(free) // 40, 1)]:
            lo = np.array([box.bounds[n][0] for n in "xy"])
            hi = np.array([box.bounds[n][1] for n in "xy"])
            for xy in lo + rng.uniform(0, 1, (3, 2)) * (hi - lo):
                pose = [xy[0], xy[1], region["z"], 0.0]
                assert geometry(pose) is not None  # reachable
                one, two = couples(pose)
                assert np.linalg.matrix_rank(np.vstack([one, two]), tol=1e-9) == 2
                assert abs(det_a(pose)) > 1e-9


def test_actuation_witnesses_make_the_independent_det_a_vanish():
    certificate = sk.certify(V4, {"x": (-650.0, 650.0), "y": (-650.0, 650.0), "z": -750.0, "phi": 0.3},
                             resolution=5.0)
    witnesses = [b.witness for b in certificate.boxes if b.status == "singular" and b.witness.label == "actuation"]
    assert len(witnesses) > 50
    scale = abs(det_a([0.0, 0.0, -750.0, 0.3]))
    for w in witnesses[::10]:
        assert abs(det_a([w.pose[n] for n in ("x", "y", "z", "phi")])) < 1e-7 * scale


METRES = in_metres(V4)


@settings(max_examples=4, deadline=None)
@given(x=st.floats(-200.0, 150.0), y=st.floats(520.0, 580.0), phi=st.floats(-0.3, 0.3))
def test_certificate_is_invariant_under_the_length_unit(x, y, phi):
    region = {"x": (x, x + 50.0), "y": (y, y + 50.0), "z": -250.0, "phi": phi}
    in_mm = sk.certify(V4, region, resolution=4.0)
    in_m = sk.certify(METRES, {"x": (x / 1e3, (x + 50.0) / 1e3), "y": (y / 1e3, (y + 50.0) / 1e3), "z": -0.25,
                               "phi": phi}, resolution=4e-3)
    assert_same_facts(in_mm, in_m)
