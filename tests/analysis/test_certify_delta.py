"""Certification of the Delta (screwkit.analysis.enclosures.DeltaModel): the rods' coplanarity
(Williams' direct singularity, computed on the independent model of tests/delta_geometry.py) lies
in no free box, poses drawn in free boxes have independent wrenches (a rank computed here from the
independent geometry), witnesses vanish, and what is not covered is refused naming what is missing."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis.delta_enclosure import DeltaModel
from screwkit.analysis.enclosures import model_of
from tests.analysis.certify_checks import in_metres
from tests.delta_geometry import RADIAL, coplanar_root_on_x, dimensions, elbows, rod_determinant

DELTA = sk.load_mechanism("delta")
REGION = {"x": (900.0, 1200.0), "y": (-60.0, 60.0), "z": -1000.0}


def wrench_rank(pose, theta):
    """The rank of the three parallelogram couples (0; w_i × u_i) and the three rod forces
    (w_i; C_i × w_i) at a pose, from the independent geometry (elbows from the arm angles)."""
    _, platform, _, rod = dimensions(DELTA)
    c = pose + platform * RADIAL
    w = (c - elbows(DELTA, theta)) / rod
    axes = np.cross([0.0, 0.0, 1.0], RADIAL)
    couples = np.hstack([np.zeros((3, 3)), np.cross(w, axes)])
    forces = np.hstack([w, np.cross(c, w)])
    matrix = np.vstack([couples, forces])
    return np.linalg.matrix_rank(matrix, tol=1e-9 * np.abs(matrix).max())


def test_rods_coplanar_lie_in_no_free_box_and_witnesses_vanish():
    certificate = sk.certify(DELTA, REGION, resolution=3.0)
    root = coplanar_root_on_x(DELTA, -1000.0)
    assert root is not None and 900 < root[0] < 1200  # the catalog's 1143.5 mm
    for box in certificate.boxes:
        inside = box.bounds["x"][0] <= root[0] <= box.bounds["x"][1] and box.bounds["y"][0] <= 0 <= box.bounds["y"][1]
        if inside:
            assert box.status != "free"
    witnesses = [box.witness for box in certificate.boxes if box.status == "singular"]
    assert witnesses and {w.label for w in witnesses} <= {"actuation", "serial"}
    poses = np.array([[w.pose["x"], w.pose["y"], w.pose["z"]] for w in witnesses if w.label == "actuation"])
    dets = rod_determinant(DELTA, poses)
    assert np.all(np.abs(dets) < 1e-6)
    assert certificate.fractions["free"] > 0.8


def test_random_poses_in_free_boxes_have_independent_wrenches():
    certificate = sk.certify(DELTA, {"x": (-300.0, 300.0), "y": (-300.0, 300.0), "z": (-1150.0, -850.0)},
                             resolution=20.0)
    assert certificate.certified_free  # the catalog's workspace box, proved free at once
    rng = np.random.default_rng(4)
    free = [box for box in certificate.boxes if box.status == "free"]
    for box in free[:20]:
        lo = np.array([box.bounds[n][0] for n in "xyz"])
        hi = np.array([box.bounds[n][1] for n in "xyz"])
        for pose in lo + rng.uniform(0, 1, (5, 3)) * (hi - lo):
            theta = DELTA.configuration(pose[None]).theta[0]
            assert wrench_rank(pose, theta) == 6
    near = sk.certify(DELTA, REGION, resolution=3.0)
    boxes = [box for box in near.boxes if box.status == "free"]
    for box in boxes[:: max(len(boxes) // 30, 1)]:
        pose = np.array([np.mean(box.bounds["x"]), np.mean(box.bounds["y"]), -1000.0])
        theta = DELTA.configuration(pose[None]).theta[0]
        assert wrench_rank(pose, theta) == 6


def test_float_route_is_the_independent_rod_determinant_and_the_core():
    poses = np.asarray(DELTA.random_poses(np.random.default_rng(8), 50))
    values = DeltaModel.of(DELTA).values(poses)
    np.testing.assert_allclose(values["actuation"], rod_determinant(DELTA, poses), rtol=1e-9)
    np.testing.assert_allclose(values["actuation"], DELTA.at(poses).jacobians.det_A, rtol=1e-9)


def test_every_catalog_family_is_covered_and_a_bad_mode_is_refused():
    for name in sk.list_mechanisms():
        assert model_of(sk.load_mechanism(name)) is not None
    with pytest.raises(sk.ScrewkitValueError, match="`mode`"):
        DeltaModel.of(DELTA, {"mode": (1, 1)})


def test_loop_closure_mechanisms_are_refused_naming_the_missing_enclosure():
    # sk.mechanism(graph): kinematics by loop closure; the H4's graph has the parallelograms' loops
    # inside its limbs, which the Krawczyk enclosure does not cover
    robot = sk.mechanism(sk.load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])
    with pytest.raises(sk.ScrewkitValueError, match="not inside one serial limb") as info:
        sk.certify(robot, {robot.pose_names[0]: (-1.0, 1.0)})
    assert "\n" not in str(info.value)


def test_certified_path_encloses_the_independent_coplanarity():
    # along y = 0 at z = -1000 the independent model's rods become coplanar at one x: the certified
    # path has exactly one crossing, actuation, whose enclosure holds that x's path parameter
    root = coplanar_root_on_x(DELTA, -1000.0)
    check = sk.check_path(DELTA, {"x": 1000.0, "y": 0.0, "z": -1000.0}, {"x": 1170.0, "y": 0.0, "z": -1000.0},
                          certify=True)
    (crossing,) = check.crossings
    t = (root[0] - 1000.0) / 170.0
    assert crossing.kind == "actuation" and crossing.enclosure[0] <= t <= crossing.enclosure[1]
    assert crossing.enclosure[1] - crossing.enclosure[0] < 1e-5 and check.certified_free is False
    free = sk.check_path(DELTA, {"x": -300.0, "y": -300.0, "z": -1150.0}, {"x": 300.0, "y": 300.0, "z": -850.0},
                         certify=True)
    assert free.certified_free and not free.crossings


METRES = in_metres(DELTA)


@settings(max_examples=6, deadline=None)
@given(x=st.floats(900.0, 1150.0), y=st.floats(-200.0, 150.0), z=st.floats(-1100.0, -900.0))
def test_certificate_is_invariant_under_the_length_unit(x, y, z):
    # the same region in mm and in m: the same boxes, statuses and witness labels
    region = {"x": (x, x + 40.0), "y": (y, y + 50.0), "z": z}
    in_mm = sk.certify(DELTA, region, resolution=4.0)
    in_m = sk.certify(METRES, {"x": (x / 1e3, (x + 40.0) / 1e3), "y": (y / 1e3, (y + 50.0) / 1e3), "z": z / 1e3},
                      resolution=4e-3)
    assert [b.status for b in in_mm.boxes] == [b.status for b in in_m.boxes]
    for mm, m in zip(in_mm.boxes, in_m.boxes, strict=True):
        assert mm.bounds["x"] == pytest.approx(tuple(1e3 * v for v in m.bounds["x"]), rel=1e-12)
        if mm.witness is not None:
            assert mm.witness.label == m.witness.label
            assert mm.witness.pose["x"] == pytest.approx(1e3 * m.witness.pose["x"], rel=1e-9)
