"""Certification of the Ragnar (paper 004's screw-pair platform, actuated axes inclined): its constraint
condition is paper 002's Eq. (6) with e = k. Why: the helical joint's twist (k; q x k + pitch k) differs
from the revolute one (k; q x k) by a translation, and each branch's twists already hold every
translation (the sub-platform, held by two couples, translates freely), so each branch exerts the couple
c = s x k as with revolute joints. Checked against an independent model written here: its own inverse
kinematics (circle-sphere intersection), each branch's couple as the reciprocal of its twists *with the
helical joint's pitch* (SVD), det A from paper 004's Eq. (7) with Table 1's screw-pair row
differentiated (tests/analysis/certify_checks.py). The Veloce: tests/analysis/test_certify_veloce.py."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis.enclosures import FourLimbModel
from tests.analysis.certify_checks import ScrewPairGeometry, assert_same_facts, in_metres, zeros_along

RAGNAR = sk.load_mechanism("ragnar")
MODEL = ScrewPairGeometry(RAGNAR, [0.0, 0.0, -575.0, 0.0])
K, AXES, RISE = MODEL.K, MODEL.axes, MODEL.rise
geometry, det_a = MODEL.geometry, MODEL.det_a


def couples(pose):
    """Each branch's couple on the end effector: reciprocal (SVD) to the sub-platform's twists and its
    joint's: helical (pitch -h/2pi, through p + (h phi/2pi) k) for I, revolute through p for II."""
    _, w = geometry(pose)
    p, phi = np.asarray(pose[:3], dtype=float), float(pose[3])
    out = []
    for limbs, point, pitch in (((0, 2), p + RISE * phi * K, -RISE), ((1, 3), p, 0.0)):
        rows = np.array([np.concatenate([np.cross(w[i], AXES[i]), np.zeros(3)]) for i in limbs])
        twists = np.vstack([np.linalg.svd(rows)[2][2:], np.concatenate([K, np.cross(point, K) + pitch * K])])
        _, values, vt = np.linalg.svd(np.hstack([twists[:, 3:], twists[:, :3]]))
        wrench = vt[int(np.sum(values > 1e-10 * values[0]))]
        assert np.linalg.norm(wrench[:3]) < 1e-9  # a couple
        out.append(wrench[3:] / np.linalg.norm(wrench[3:]))
    return out


def sin_between(pose):
    return float(np.linalg.norm(np.cross(*couples(pose))))


def test_core_closeness_is_the_independent_couples_angle_and_det_a_agrees():
    rng = np.random.default_rng(2)
    poses = np.vstack([np.asarray(RAGNAR.random_poses(rng, 1000)),
                       [-505.0, -685.0, -940.0, -6.0] + rng.uniform(size=(1500, 4)) * [1010.0, 1370.0, 730.0, 12.0]])
    poses = poses[RAGNAR.reachable(poses)][:2000]
    assert len(poses) == 2000
    cosines = np.array([abs(np.dot(*couples(pose))) for pose in poses])
    closeness = RAGNAR.at(poses).singularities.closeness["constraint"]
    np.testing.assert_allclose(closeness, np.sqrt((1 - cosines) / (1 + cosines)), atol=1e-9)
    values = FourLimbModel.of(RAGNAR).values(poses)
    rods = RAGNAR.configuration(poses).w
    normals = np.cross(rods, AXES)
    c_one = np.cross(np.cross(normals[:, 0], normals[:, 2]), K)
    c_two = np.cross(np.cross(normals[:, 1], normals[:, 3]), K)
    unit = values["constraint"] / np.linalg.norm(c_one, axis=-1) / np.linalg.norm(c_two, axis=-1)
    np.testing.assert_allclose(np.abs(unit), np.sqrt(1 - cosines**2), atol=1e-9)
    independent = np.array([det_a(pose) for pose in poses])
    np.testing.assert_allclose(values["actuation"], independent, rtol=1e-9, atol=1e-12 * np.abs(independent).max())


def test_independent_singular_set_in_no_free_box_witnesses_vanish_free_poses_regular():
    region = {"x": (-505.0, 505.0), "y": (-685.0, 685.0), "z": -575.0, "phi": 0.0}
    certificate = sk.certify(RAGNAR, region, resolution=8.0)
    free = [b for b in certificate.boxes if b.status == "free"]
    witnesses = [b.witness for b in certificate.boxes if b.status == "singular" and b.witness.label == "constraint"]
    assert len(witnesses) > 50 and certificate.fractions["free"] > 0.9
    for w in witnesses[::10]:
        assert sin_between([w.pose["x"], w.pose["y"], w.pose["z"], w.pose["phi"]]) < 1e-6
    found = 0
    for x in np.linspace(-450.0, 450.0, 5):  # the independent singular set: zeros of |sin| along y
        line = np.stack([np.full(275, x), np.linspace(-685.0, 685.0, 275), np.full(275, -575.0), np.zeros(275)], -1)
        for zero in zeros_along(lambda pose: sin_between(pose) if geometry(pose) else None, line):
            found += 1
            assert not any(b.bounds["x"][0] <= x <= b.bounds["x"][1] and b.bounds["y"][0] <= zero[1] <= b.bounds["y"][1]
                           for b in free)
    assert found >= 8  # two curves, near y = -330 and y = +330
    rng = np.random.default_rng(3)
    for box in free[:: max(len(free) // 40, 1)]:
        lo = np.array([box.bounds[n][0] for n in "xy"])
        hi = np.array([box.bounds[n][1] for n in "xy"])
        for xy in lo + rng.uniform(0, 1, (3, 2)) * (hi - lo):
            pose = [xy[0], xy[1], -575.0, 0.0]
            assert geometry(pose) is not None
            assert np.linalg.matrix_rank(np.vstack(couples(pose)), tol=1e-9) == 2 and abs(det_a(pose)) > 1e-9


METRES = in_metres(RAGNAR)


@settings(max_examples=4, deadline=None)
@given(x=st.floats(-450.0, 400.0), y=st.floats(-420.0, 250.0), phi=st.floats(-3.0, 3.0))
def test_certificate_is_invariant_under_the_length_unit(x, y, phi):
    in_mm = sk.certify(RAGNAR, {"x": (x, x + 50.0), "y": (y, y + 100.0), "z": -575.0, "phi": phi}, resolution=4.0)
    in_m = sk.certify(METRES, {"x": (x / 1e3, (x + 50.0) / 1e3), "y": (y / 1e3, (y + 100.0) / 1e3), "z": -0.575,
                               "phi": phi}, resolution=4e-3)
    assert_same_facts(in_mm, in_m)
