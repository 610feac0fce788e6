"""Certification of the Veloce (paper 004's screw-pair platform with u_3 = -u_1, u_4 = -u_2), and the
rank computation that settles its constraint condition.

Paper 002's Eq. (6) applied to the Veloce's sub-platforms factors: the couples n_1 = w_1 x u_1 and
n_3 = w_3 x u_3 are both normal to u_1, so s_I = n_1 x n_3 = lambda_I u_1 with
lambda_I = (n_1 x n_3).u_1, and Eq. (6) = lambda_I lambda_II (u_1 x u_2).k. The question was whether the
zeros of lambda_I are constraint singularities (the derivation: sub-platform I then held by one couple,
paper 002 Sec. 5.3 case (c)) although the core's constraint closeness reads 1 on sampled poses.
Settled here from the joint screws, independently of screwkit's wrench code: each limb's twist system
(its actuated revolute joint and its parallelogram of four spherical joints, the intersection of the two
rods' chains), each sub-platform's (the intersection of its limbs'), each branch's (with the helical or
revolute joint about k), the constraint wrench system of the end effector as the span of the branches'
reciprocals (null spaces under the reciprocal product), and its order. At a pose built so that
lambda_I = 0 the order drops from 2 to 1: the zeros are constraint singular, the derivation holds and the
core's verdict agrees, and its constraint closeness falls linearly to 0 at them (it once read 1.0 at 1e-3
mm from one: each leg's orthonormal frame kept a unit couple up to the drop; the closeness now also reads
how independent the sub-platform's limbs' couples are).
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis.enclosures import FourLimbModel
from tests.analysis.certify_checks import (
    ScrewPairGeometry,
    assert_same_facts,
    in_metres,
    intersection,
    order,
    reciprocal,
    revolute,
)

VELOCE = sk.load_mechanism("veloce")
MODEL = ScrewPairGeometry(VELOCE, [0.0, 0.0, -750.0, 0.0])
K, AXES, RISE, WIDTH = MODEL.K, MODEL.axes, MODEL.rise, VELOCE.parameters.parallelogram_width
METRE = 1e-3  # the screw computations in metres (moments and forces of one size)

# lambda_I = 0 by construction: p = 400 sqrt(3) u_1 - 300 k, phi = 0. Both arms of sub-platform I lie in
# the vertical plane normal to u_1 (a_1 = -a_3 = 275 e_r, e_r = (i + j)/sqrt 2); with sin theta = -0.8,
# cos theta = 0.6 the elbows are b_1 = -b_3 = 500 e_r - 300 k, at the platform's height, and
# c_1 - b_1 = 400 sqrt(3) u_1 - 400 e_r (|.| = 800 = l), c_3 - b_3 = 400 sqrt(3) u_1 + 400 e_r: the
# rods' projections on that plane are antiparallel, so n_1 = n_3 = k/2 and lambda_I = 0.
BUILT = np.array([200 * np.sqrt(6), -200 * np.sqrt(6), -300.0, 0.0])


def systems(pose):
    """From the joint screws: (sub-platform twist orders, branch twist orders, end effector's constraint
    order)."""
    c, elbows, _ = MODEL.solve(pose)
    c, elbows = c * METRE, elbows * METRE
    half = 0.5 * WIDTH * METRE
    limbs = []
    for i in range(4):
        u = AXES[i]
        m, n, p, q = elbows[i] - half * u, elbows[i] + half * u, c[i] - half * u, c[i] + half * u
        spherical = [revolute(e, point) for point in (m, p) for e in np.eye(3)]
        rod_one = np.array(spherical)
        rod_two = np.array([revolute(e, point) for point in (n, q) for e in np.eye(3)])
        parallelogram = intersection(rod_one, rod_two)
        limbs.append(np.vstack([revolute(u, MODEL.a_points[i] * METRE), parallelogram]))
    centre = np.asarray(pose[:3], dtype=float) * METRE
    joints = (
        np.concatenate([K, np.cross(centre + RISE * METRE * pose[3] * K, K) - RISE * METRE * K]),  # helical
        revolute(K, centre),
    )
    subplatforms = [intersection(limbs[a], limbs[b]) for a, b in ((0, 2), (1, 3))]
    branches = [np.vstack([sub, joint]) for sub, joint in zip(subplatforms, joints, strict=True)]
    constraint = np.vstack([reciprocal(branch) for branch in branches])
    return [order(s) for s in subplatforms], [order(b) for b in branches], order(constraint)


def lambdas(pose):
    """(n_1 x n_3).u_1 and (n_2 x n_4).u_2 on the independent model."""
    _, w = MODEL.geometry(pose)
    n = np.cross(w, AXES)
    return float(np.cross(n[0], n[2]) @ AXES[0]), float(np.cross(n[1], n[3]) @ AXES[1])


def zero_of_lambda_one(low, high):
    """lambda_I = 0 on the segment [low, high] (a sign change), by 200 bisection steps."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    sign = np.sign(lambdas(low)[0])
    assert sign * np.sign(lambdas(high)[0]) < 0
    for _ in range(200):
        middle = 0.5 * (low + high)
        if np.sign(lambdas(middle)[0]) == sign:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


# lambda_I = 0 away from the symmetric plane, where det A is not 0: solved along x at y = -545.2 mm,
# z = -226.3 mm, phi = -1.8 rad (a sign change between x = 300 and 500 mm), near x = 398.5 mm
SOLVED = zero_of_lambda_one([300.0, -545.2, -226.3, -1.8], [500.0, -545.2, -226.3, -1.8])


def test_built_pose_makes_the_factor_vanish_and_the_constraint_order_drop():
    assert abs(lambdas(BUILT)[0]) < 1e-12 and abs(lambdas(BUILT)[1]) > 0.1
    subplatforms, branches, constraint = systems(BUILT)
    # sub-platform I held by one couple (a 5-system); its branch, with the helical joint, spans all 6
    # twists and exerts nothing: the end effector keeps one couple, it gains a freedom
    assert subplatforms == [5, 4] and branches == [6, 5] and constraint == 1
    assert systems(BUILT + np.array([10.0, 0.0, 0.0, 0.0])) == ([4, 4], [5, 5], 2)
    assert VELOCE.at(BUILT[None]).codes[0] & 1  # the core's verdict: constraint


def test_solved_generic_zero_is_constraint_singular_only():
    assert abs(lambdas(SOLVED)[0]) < 1e-12 and 398.0 < SOLVED[0] < 399.0
    assert abs(MODEL.det_a(SOLVED)) > 0.05  # not an actuation singularity there
    assert systems(SOLVED) == ([5, 4], [6, 5], 1)
    assert systems(SOLVED + np.array([1.0, 0.0, 0.0, 0.0]))[2] == 2
    assert VELOCE.at(SOLVED[None]).codes[0] == 1  # the core: constraint, nothing else


def test_core_constraint_closeness_falls_linearly_to_the_constraint_singularity():
    # the closeness reads the gap of sub-platform I's span of its limbs' couples (core branch_gap):
    # proportional to the distance from the zero of lambda_I (a simple zero), 1 -> 1e-3 mm
    offsets = np.array([1e-3, 1e-2, 1e-1, 1.0])
    near = SOLVED + offsets[:, None] * np.array([1.0, 0.0, 0.0, 0.0])
    assert all(systems(pose)[2] == 2 for pose in near)  # regular at every one of them
    closeness = VELOCE.at(near).singularities.closeness["constraint"]
    assert closeness[0] < 1e-4
    np.testing.assert_allclose(closeness[:-1] / closeness[1:], 0.1, rtol=0.05)  # linear in the distance


def test_map_loci_find_the_constraint_surface_of_the_slice():
    # a sampled map once drew only the actuation locus here; each constraint point found lies on
    # lambda_I = 0 of the independent model (a sign change of lambda_I across 0.5 mm in x)
    found = sk.loci(VELOCE, x=("x", 300, 560, 60), y=("z", -300, -200, 30), fixed={"y": -545.2, "phi": -1.8})
    (constraint,) = [locus for locus in found if locus.kind == "constraint"]
    assert len(constraint.points) > 20
    for x, z in constraint.points:
        below, above = (lambdas([x + dx, -545.2, z, -1.8])[0] for dx in (-0.5, 0.5))
        assert below * above < 0


def test_enclosed_functions_are_the_independent_factors_and_det_a():
    rng = np.random.default_rng(5)
    poses = [-800.0, -800.0, -1100.0, -6.0] + rng.uniform(size=(4000, 4)) * [1600.0, 1600.0, 900.0, 12.0]
    poses = poses[VELOCE.reachable(poses)][:500]
    assert len(poses) == 500
    values = FourLimbModel.of(VELOCE).values(poses)
    independent = np.array([np.prod(lambdas(pose)) for pose in poses])
    assert independent.min() < 0 < independent.max()  # both signs among these reachable poses
    np.testing.assert_allclose(values["constraint"], independent, rtol=1e-9, atol=1e-12)
    det_a = np.array([MODEL.det_a(pose) for pose in poses])
    np.testing.assert_allclose(values["actuation"], det_a, rtol=1e-9, atol=1e-12 * np.abs(det_a).max())
    np.testing.assert_allclose(values["actuation"], VELOCE.at(poses).jacobians.det_A, rtol=1e-9,
                               atol=1e-12 * np.abs(det_a).max())  # the core's det A


def test_slice_with_the_constraint_surface_certified_and_located():
    region = {"x": (300.0, 560.0), "y": -545.2, "z": (-300.0, -200.0), "phi": -1.8}
    certificate = sk.certify(VELOCE, region, resolution=2.0)
    statuses = {b.status for b in certificate.boxes}
    assert {"free", "singular"} <= statuses and certificate.fractions["free"] > 0.9
    witnesses = [b.witness for b in certificate.boxes if b.witness is not None]
    constraint = [w for w in witnesses if w.label == "constraint"]
    assert len(constraint) > 20 and constraint[0].factor == "[gikj]"
    for w in constraint[::5]:
        pose = [w.pose[n] for n in VELOCE.pose_names]
        assert min(abs(v) for v in lambdas(pose)) < 1e-6
    for w in (w for w in witnesses if w.label == "actuation"):
        assert abs(MODEL.det_a([w.pose[n] for n in VELOCE.pose_names])) < 1e-6
    free = [b for b in certificate.boxes if b.status == "free"]
    for z in np.linspace(-290.0, -210.0, 5):  # the independent surface lambda_I = 0 in this slice
        zero = zero_of_lambda_one([300.0, -545.2, z, -1.8], [500.0, -545.2, z, -1.8])
        assert not any(b.bounds["x"][0] <= zero[0] <= b.bounds["x"][1]
                       and b.bounds["z"][0] <= z <= b.bounds["z"][1] for b in free)


def test_catalog_workspace_slice_is_free_of_constraint_and_actuation_singularities():
    # paper 004, Sec. 5.3: the Veloce's operational workspace is free of singularity. At z = -750 mm,
    # phi = 0 the certificate meets only the reach boundary (serial) inside the catalog's x, y box
    certificate = sk.certify(VELOCE, {"x": (-650.0, 650.0), "y": (-650.0, 650.0), "z": -750.0, "phi": 0.0},
                             resolution=10.0)
    assert {b.witness.label for b in certificate.boxes if b.witness is not None} == {"serial"}
    assert certificate.fractions["free"] > 0.8


@settings(max_examples=3, deadline=None)
@given(x=st.floats(300.0, 420.0), z=st.floats(-300.0, -240.0))
def test_certificate_is_invariant_under_the_length_unit(x, z):
    region = {"x": (x, x + 60.0), "y": -545.2, "z": (z, z + 40.0), "phi": -1.8}
    in_mm = sk.certify(VELOCE, region, resolution=4.0)
    in_m = sk.certify(in_metres(VELOCE), {"x": (x / 1e3, (x + 60.0) / 1e3), "y": -0.5452,
                                           "z": (z / 1e3, (z + 40.0) / 1e3), "phi": -1.8}, resolution=4e-3)
    assert_same_facts(in_mm, in_m, names=("x", "z"))


def test_certified_path_encloses_the_solved_constraint_crossing():
    start, end = np.array([300.0, -545.2, -226.3, -1.8]), np.array([500.0, -545.2, -226.3, -1.8])
    check = sk.check_path(VELOCE, start, end, certify=True)
    constraint = [c for c in check.crossings if c.kind == "constraint"]
    assert len(constraint) == 1 and not check.certified_free
    low, high = constraint[0].enclosure
    assert low <= (SOLVED[0] - 300.0) / 200.0 <= high and high - low < 1e-5
    for crossing in (c for c in check.crossings if c.kind == "actuation"):  # det A changes sign there
        t_low, t_high = crossing.enclosure
        assert MODEL.det_a(start + t_low * (end - start)) * MODEL.det_a(start + t_high * (end - start)) <= 0
