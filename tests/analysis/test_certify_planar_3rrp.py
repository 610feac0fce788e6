"""Certification of the planar 3-RRP (screwkit.analysis.planar_3rrp_enclosure): the direct-singular
curve, computed here from a hand derivation (each elbow on its guide by the line-circle
intersection, the actuation lines L_1 and L_2 intersected, the curve where L_3 passes through that
point), lies in no free box; witnesses make the three independent lines concurrent; poses in free
boxes have three independent actuation lines and reach."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis.planar_3rrp_enclosure import Planar3RRPModel
from tests.analysis.certify_checks import assert_same_facts

RRP = sk.load_mechanism("planar_3rrp")
PHI = 0.8  # the slice: the whole square reachable, a direct-singular curve across it
REGION = {"x": (-0.3, 0.3), "y": (-0.3, 0.3), "phi": PHI}


def actuation_lines(pose, mode=(1, 1, 1)):
    """Hand derivation: the guide of limb k passes through Q = C + R(φ) P_k along b = R(φ) u(β_k);
    its elbow A = Q + t b lies on the circle |A - M_k| = l_k, t² + 2 t (Q - M)·b + |Q - M|² - l² = 0,
    the root of working mode σ_k having (A - M)·b = σ_k √(...); the actuation force acts through A
    along the guide's normal n. Returns the points A (3, 2) and the forces' directions n (3, 2), or
    None out of reach."""
    p = RRP.parameters
    x, y, phi = pose
    turn = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    points, normals = [], []
    for k in range(3):
        q = np.array([x, y]) + turn @ p.platform_points[k]
        b = turn @ np.array([np.cos(p.guide_angles[k]), np.sin(p.guide_angles[k])])
        d = q - p.base_points[k]
        half = d @ b
        discriminant = half**2 - d @ d + p.link_lengths[k] ** 2
        if discriminant < 0:
            return None
        t = -half + mode[k] * np.sqrt(discriminant)
        points.append(q + t * b)
        normals.append(np.array([-b[1], b[0]]))
    return np.array(points), np.array(normals)


def concurrency_gap(pose):
    """The signed distance of L_3 from the intersection of L_1 and L_2 (zero iff concurrent)."""
    found = actuation_lines(pose)
    if found is None:
        return None
    points, directions = found
    # points[0] + s n_0 = points[1] + r n_1
    s, _ = np.linalg.solve(np.column_stack([directions[0], -directions[1]]), points[1] - points[0])
    meet = points[0] + s * directions[0]
    across = np.array([-directions[2][1], directions[2][0]])
    return float((meet - points[2]) @ across)


def singular_curve():
    """Points of the direct-singular curve in the slice: along each of 40 vertical lines x = const,
    the sign changes of the concurrency gap over 400 samples of y, refined by 60 bisections."""
    curve = []
    for x in np.linspace(-0.29, 0.29, 40):
        ys = np.linspace(-0.3, 0.3, 401)
        gaps = np.array([concurrency_gap((x, y, PHI)) for y in ys])
        for i in np.flatnonzero(np.sign(gaps[1:]) != np.sign(gaps[:-1])):
            low, high = ys[i], ys[i + 1]
            for _ in range(60):
                middle = 0.5 * (low + high)
                if np.sign(concurrency_gap((x, middle, PHI))) == np.sign(gaps[i]):
                    low = middle
                else:
                    high = middle
            curve.append((x, 0.5 * (low + high)))
    return np.array(curve)


@pytest.fixture(scope="module")
def certificate():
    return sk.certify(RRP, REGION, resolution=0.004)


def test_the_independent_singular_curve_lies_in_no_free_box(certificate):
    curve = singular_curve()
    assert len(curve) >= 20  # the curve crosses the slice
    for x, y in curve:
        holding = [
            b
            for b in certificate.boxes
            if b.bounds["x"][0] <= x <= b.bounds["x"][1] and b.bounds["y"][0] <= y <= b.bounds["y"][1]
        ]
        assert holding and all(b.status != "free" for b in holding)
    assert certificate.fractions["free"] > 0.9
    assert certificate.totals["unreachable"] == 0  # the whole square is reached at phi = 0.8


def test_witnesses_are_labelled_and_make_the_independent_lines_concurrent(certificate):
    witnesses = [b.witness for b in certificate.boxes if b.status == "singular"]
    assert witnesses and {w.label for w in witnesses} == {"actuation"}
    for w in witnesses:
        assert abs(concurrency_gap((w.pose["x"], w.pose["y"], PHI))) < 1e-7
        assert "concurrent" in w.statement and w.factor is not None
        low, high = (concurrency_gap((b["x"], b["y"], PHI)) for b in w.bracket)
        assert low * high <= 0  # the bracket's ends straddle the independent curve


def test_free_boxes_hold_reachable_poses_with_independent_actuation_lines(certificate):
    rng = np.random.default_rng(3)
    free = [b for b in certificate.boxes if b.status == "free"]
    for box in free[:: max(len(free) // 40, 1)]:
        lo = np.array([box.bounds["x"][0], box.bounds["y"][0]])
        hi = np.array([box.bounds["x"][1], box.bounds["y"][1]])
        for x, y in lo + rng.uniform(0, 1, (3, 2)) * (hi - lo):
            points, normals = actuation_lines((x, y, PHI))
            lines = np.column_stack([normals, points[:, 0] * normals[:, 1] - points[:, 1] * normals[:, 0]])
            assert abs(np.linalg.det(lines)) > 1e-9


def test_float_route_is_the_hand_derivation_and_the_family():
    # the enclosed functions in floats: l² - h² against the family's reach margin, the actuation
    # determinant vanishing with the independent gap (both change sign together along a line)
    from screwkit.robots.families.planar_3rrp.kinematics import reach_margin

    model = Planar3RRPModel.of(RRP)
    rng = np.random.default_rng(1)
    poses = np.column_stack([rng.uniform(-0.3, 0.3, (200, 2)), rng.uniform(-1, 1, 200)])
    values = model.values(poses)
    margin = reach_margin(RRP.parameters, poses) * RRP.parameters.link_lengths**2
    np.testing.assert_allclose(
        np.column_stack([values[f"serial:{k}"] for k in (1, 2, 3)]), margin, atol=1e-14
    )
    line = np.column_stack([np.full(300, 0.1), np.linspace(-0.3, 0.3, 300), np.full(300, PHI)])
    det = model.values(line)["actuation"]
    gaps = np.array([concurrency_gap(p) for p in line])
    assert np.array_equal(np.diff(np.sign(det)) != 0, np.diff(np.sign(gaps)) != 0)


def test_working_mode_and_bad_mode():
    other = sk.certify(
        RRP, {"x": (-0.05, 0.05), "y": (-0.05, 0.05), "phi": 0.0}, mode={"working_mode": (1, -1, 1)}
    )
    assert other.totals["free"] >= 1
    with pytest.raises(sk.ScrewkitValueError, match="working_mode"):
        Planar3RRPModel.of(RRP, {"working_mode": (1, 2, 1)})


def in_millimetres(mechanism):
    """The catalog 3-RRP (lengths in m) with every length in mm."""
    from screwkit.robots.catalog import load_toml, mechanism_from_mapping

    data = load_toml(mechanism.source)
    data["mechanism"]["length_unit"] = "mm"
    for entry in data["parameters"].values():
        if entry["unit"] == "m":
            entry["value"] = (np.asarray(entry["value"], dtype=float) * 1000.0).tolist()
            entry["unit"] = "mm"
    for key in ("x", "y"):
        data["pose"][key] *= 1000.0
        data["workspace"][key] = [v * 1000.0 for v in data["workspace"][key]]
    data.pop("expected", None)
    return mechanism_from_mapping(data, source=f"{mechanism.name} in mm")


RRP_MM = in_millimetres(RRP)


@settings(max_examples=5, deadline=None)
@given(x=st.floats(-0.3, 0.2), y=st.floats(-0.3, 0.2))
def test_certificate_is_invariant_under_the_length_unit(x, y):
    # the same region in m and in mm: the same facts (tests/analysis/certify_checks.assert_same_facts),
    # and every actuation witness (in m) on the independent concurrency curve
    region = {"x": (x, x + 0.1), "y": (y, y + 0.1), "phi": PHI}
    in_m = sk.certify(RRP, region, resolution=0.01)
    in_mm = sk.certify(RRP_MM, {"x": (1e3 * x, 1e3 * (x + 0.1)), "y": (1e3 * y, 1e3 * (y + 0.1)), "phi": PHI},
                       resolution=10.0)
    assert_same_facts(in_mm, in_m)
    for w in (b.witness for b in in_m.boxes if b.witness is not None and b.witness.label == "actuation"):
        assert abs(concurrency_gap((w.pose["x"], w.pose["y"], PHI))) < 1e-7
