"""Certification of mechanisms built as twist graphs (screwkit.analysis.loop_closure_enclosure: the
Krawczyk operator on each limb's loop equations, the actuation wrenches' determinant): a planar
3-RPR and a 6-UPS Gough-Stewart platform, whose answers are computed here independently (closed-form
inverse kinematics: the legs run from A_i to the moved platform points; actuation singular iff the
leg lines are dependent, a 3 x 3 determinant of planar lines, resp. the 6 x 6 determinant of the
six legs' Plücker lines), and what is not covered refused by name."""

from __future__ import annotations

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis.krawczyk import implicit_rates, krawczyk
from screwkit.analysis.loop_closure_enclosure import LoopClosureModel
from screwkit.graphs.joints import spherical
from tests.mechanisms import gough_stewart, gough_stewart_points, leg_lines, planar_3rpr, rotation_about, unit

BASE = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.8, 0.0]])
PLATFORM = np.array([[0.4, 0.3, 0.0], [0.6, 0.3, 0.0], [0.5, 0.5, 0.0]])
RPR = sk.mechanism(planar_3rpr(BASE, PLATFORM))
GOUGH = sk.mechanism(gough_stewart(*gough_stewart_points()))
RPR_REGION = {"x": (0.45, 0.55), "y": (0.32, 0.42), "phi": 0.0}


def rpr_lines(x, y, phi):
    """Hand derivation: the platform point C_i moves to (x, y) + R(φ)(C_i - G), G the centroid of the
    C_i (the mechanism's coordinates: the platform joints' centroid, φ about z); leg i is the line
    through A_i along C_i - A_i, planar line coordinates (d, A × d)."""
    turn = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    ends = np.array([x, y]) + (PLATFORM[:, :2] - PLATFORM[:, :2].mean(axis=0)) @ turn.T
    d = ends - BASE[:, :2]
    d = d / np.linalg.norm(d, axis=1, keepdims=True)
    return np.column_stack([d, BASE[:, 0] * d[:, 1] - BASE[:, 1] * d[:, 0]])


def rpr_det(x, y, phi=0.0):
    return float(np.linalg.det(rpr_lines(x, y, phi)))


def gough_det(z, rz, x=0.0, y=0.0, rx=0.0, ry=0.0):
    """Hand derivation: leg i runs from a_i to p + R(r)(c_i - c̄) (r the rotation vector, Rodrigues);
    the determinant of the six unit leg lines (s; a × s)."""
    r = np.array([rx, ry, rz])
    angle = np.linalg.norm(r)
    turn = np.eye(3) if angle == 0 else rotation_about(r / angle, angle)
    base, platform = gough_stewart_points()
    ends = np.array([x, y, z]) + (platform - platform.mean(axis=0)) @ turn.T
    return float(np.linalg.det(leg_lines(base, ends)))


def bisect(function, low, high, steps=60):
    f_low = function(low)
    for _ in range(steps):
        middle = 0.5 * (low + high)
        if np.sign(function(middle)) == np.sign(f_low):
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


@pytest.fixture(scope="module")
def rpr_certificate():
    return sk.certify(RPR, RPR_REGION, resolution=0.01)


def test_rpr_singular_curve_lies_in_no_free_box(rpr_certificate):
    # along rows y = const the independent determinant changes sign once (at x = 0.5 by symmetry:
    # the legs 1 and 2 mirror each other, leg 3 lies on x = 0.5, so the three meet there)
    curve = []
    for y in np.linspace(0.321, 0.419, 15):
        xs = np.linspace(0.45, 0.55, 201)
        dets = np.array([rpr_det(x, y) for x in xs])
        for i in np.flatnonzero(np.sign(dets[1:]) != np.sign(dets[:-1])):
            curve.append((bisect(lambda x, y=y: rpr_det(x, y), xs[i], xs[i + 1]), y))
    assert len(curve) >= 15 and all(abs(x - 0.5) < 1e-9 for x, _ in curve)
    for x, y in curve:
        holding = [
            b
            for b in rpr_certificate.boxes
            if b.bounds["x"][0] <= x <= b.bounds["x"][1] and b.bounds["y"][0] <= y <= b.bounds["y"][1]
        ]
        assert holding and all(b.status != "free" for b in holding)
    assert rpr_certificate.fractions["free"] > 0.5


def test_rpr_witnesses_are_labelled_and_the_independent_lines_meet_there(rpr_certificate):
    witnesses = [b.witness for b in rpr_certificate.boxes if b.status == "singular"]
    assert witnesses and {w.label for w in witnesses} == {"actuation"}
    for w in witnesses:
        assert abs(rpr_det(w.pose["x"], w.pose["y"])) < 1e-6
        ends = [rpr_det(p["x"], p["y"]) for p in w.bracket]
        assert ends[0] * ends[1] < 0  # certified signs agree with the independent determinant's
        assert "actuation wrenches are dependent" in w.statement


def test_rpr_free_boxes_hold_reachable_regular_poses(rpr_certificate):
    rng = np.random.default_rng(2)
    free = [b for b in rpr_certificate.boxes if b.status == "free"]
    poses = np.array([[rng.uniform(*b.bounds["x"]), rng.uniform(*b.bounds["y"]), 0.0] for b in free])
    assert np.all(RPR.reachable(poses))
    assert all(abs(rpr_det(x, y)) > 1e-6 for x, y, _ in poses)
    signs = {np.sign(rpr_det(x, y)) for x, y, _ in poses}
    assert signs == {-1.0, 1.0}  # free boxes on both sides of the curve


def test_gough_stewart_singular_at_a_quarter_turn_and_free_near_the_reference():
    # rz = π/2 (the platform turned a quarter turn about the vertical): the independent leg-line
    # determinant changes sign there; the certificate's only singular box holds it, with a witness
    root = bisect(lambda rz: gough_det(1.0, rz), 1.55, 1.59)
    assert abs(root - np.pi / 2) < 1e-9
    certificate = sk.certify(GOUGH, {"z": 1.0, "rz": (1.55, 1.59)}, resolution=0.002)
    singular = [b for b in certificate.boxes if b.status == "singular"]
    assert len(singular) == 1 and singular[0].bounds["rz"][0] <= root <= singular[0].bounds["rz"][1]
    assert abs(singular[0].witness.pose["rz"] - root) < 1e-6
    assert abs(gough_det(1.0, singular[0].witness.pose["rz"])) < 1e-6
    assert all(b.status == "free" for b in certificate.boxes if b is not singular[0])
    near = sk.certify(GOUGH, {"x": (-0.01, 0.01), "y": (-0.01, 0.01), "z": 1.0}, resolution=0.005)
    assert near.certified_free


def test_the_krawczyk_operator_proves_a_unique_root_and_refuses_an_empty_box():
    # F(θ, u) = θ² - u on X, U = [2, 2.1]: the root √u ∈ [1.414, 1.45] is proved unique in [1.3, 1.6];
    # [1.5, 1.6] holds no root, and K(X) ⊄ X there
    def operator(lo, hi):
        y = np.array([[0.5 * (lo + hi)]])
        f_y = (y**2 - 2.1, y**2 - 2.0)
        jacobian = (np.array([[[2 * lo]]]), np.array([[[2 * hi]]]))
        return krawczyk(f_y, jacobian, y, (np.array([[lo]]), np.array([[hi]])))

    k_lo, k_hi, proved = operator(1.3, 1.6)
    assert proved[0] and k_lo[0, 0] <= np.sqrt(2.0) and np.sqrt(2.1) <= k_hi[0, 0]
    assert not operator(1.5, 1.6)[2][0]
    # implicit rates: dθ/du = 1/(2θ) over θ ∈ [1.3, 1.6] holds the true rate at the root
    rate_lo, rate_hi = implicit_rates((np.array([[[2.6]]]), np.array([[[3.2]]])), (-np.ones((1, 1, 1)),) * 2)
    assert rate_lo[0, 0, 0] <= 1 / (2 * np.sqrt(2.05)) <= rate_hi[0, 0, 0]


def sps_leg_platform():
    """A 6-SPS: each leg S - P - S has 7 joint variables (the leg spins about its axis)."""
    base, ends = gough_stewart_points()
    joints = []
    for i, (a, c) in enumerate(zip(base, ends, strict=True), start=1):
        joints += [
            ("base", f"lower{i}", spherical(f"Sa{i}", a)),
            (f"lower{i}", f"upper{i}", sk.prismatic(f"P{i}", unit(c - a), actuated=True)),
            (f"upper{i}", "platform", spherical(f"Sc{i}", c)),
        ]
    return sk.twist_graph("base", "platform", joints)


@pytest.mark.parametrize(
    ("build", "reason"),
    [
        (lambda: sk.mechanism(sk.load_mechanism("h4").twist_graph()), "is not inside one serial limb"),
        (lambda: sk.mechanism(sps_leg_platform()), "an internal motion"),
        (
            lambda: sk.mechanism(planar_3rpr(BASE, PLATFORM), task=("platform", [0.5, 0.4, 0.0])),
            "do not fix the platform's whole pose",
        ),
    ],
    ids=["parallelograms", "spinning legs", "point task"],
)
def test_what_is_not_covered_is_refused_by_name_with_the_reason(build, reason):
    with pytest.raises(sk.ScrewkitValueError, match=reason) as info:
        sk.certify(build(), {"x": (0.0, 0.1)})
    assert "loop-closure mechanisms" in str(info.value) and "\n" not in str(info.value)


def test_loop_closure_models_refuse_a_mode_and_name_their_functions():
    model = LoopClosureModel.of(RPR)
    assert (model.dimension, model.limbs) == (3, 3)
    assert sorted(model.functions()) == ["actuation", "serial:1", "serial:2", "serial:3"]
    with pytest.raises(sk.ScrewkitValueError, match="`mode`"):
        sk.certify(RPR, RPR_REGION, mode={"working_mode": (1, 1, 1)})


def test_certificate_is_invariant_under_a_translation_and_the_length_unit():
    # the same 3-RPR translated by (2, -1, 0) and described in mm: a region mapped alike gives the
    # same facts (the singular line x = 0.5 found with an actuation witness at x' = 1000 (0.5 + 2))
    from tests.mechanisms import moved

    other = sk.mechanism(moved(planar_3rpr(BASE, PLATFORM), None, (2.0, -1.0, 0.0), 1000.0))
    region = {"x": (0.47, 0.53), "y": (0.35, 0.39), "phi": 0.0}
    mapped = {"x": (2470.0, 2530.0), "y": (-650.0, -610.0), "phi": 0.0}
    here = sk.certify(RPR, region, resolution=0.02)
    there = sk.certify(other, mapped, resolution=20.0)
    for certificate, scale, shift in ((here, 1.0, 0.0), (there, 1000.0, 2000.0)):
        witnesses = [b.witness for b in certificate.boxes if b.status == "singular"]
        assert witnesses and {w.label for w in witnesses} == {"actuation"}
        assert all(abs(w.pose["x"] - (0.5 * scale + shift)) < 1e-6 * scale for w in witnesses)
    assert abs(here.fractions["free"] - there.fractions["free"]) <= sum(
        c.fractions[k] for c in (here, there) for k in ("singular", "undecided")
    )


def test_dask_local_cluster_gives_the_same_loop_closure_certificate():
    # each box's proof depends on the box alone (the continuation from the reference at its centre),
    # so a cluster's chunks give the in-process paving, witness for witness
    distributed = pytest.importorskip("dask.distributed")
    region = {"x": (0.47, 0.53), "y": (0.35, 0.39), "phi": 0.0}
    here = sk.certify(RPR, region, resolution=0.02)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        there = sk.certify(RPR, region, resolution=0.02, client=client)
    assert [b.to_dict() for b in here.boxes] == [b.to_dict() for b in there.boxes]
    assert here.totals["singular"] >= 1
