"""Certified regions and paths (screwkit.analysis.certify): soundness of the enclosures, the Quattro's
y = 0 constraint singularity at phi = 0, paper 002's H4 surfaces (Eqs. 6-7, computed here by an
independent model) in no free box, certified paths, caps and bad input."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import certify as C
from screwkit.analysis.enclosures import FourLimbModel
from screwkit.analysis.intervals import Enclosure, mean_value
from tests.four_limb_reference import H4, QUATTRO, eq6_constraint, eq7_actuation, geometry

QUATTRO_M = sk.load_mechanism("quattro")
H4_M = sk.load_mechanism("h4")
SLICE = {"x": (-400.0, 400.0), "y": (-400.0, 400.0), "z": -750.0, "phi": 0.0}


def test_interval_operations_contain_every_value():
    # random boxes, random points in them: every operation's enclosure holds the float value at the
    # points (the floats are within an ulp of the exact values, far inside the outward rounding)
    rng = np.random.default_rng(7)
    lo = rng.uniform(-3, 3, (500, 2))
    hi = lo + rng.uniform(0, 2, (500, 2))
    x, y = Enclosure.variables(lo, hi)
    t = rng.uniform(0, 1, (500, 40, 2))
    px, py = (lo[:, None] + t * (hi - lo)[:, None]).transpose(2, 0, 1)
    cases = [
        (x * y - y.square() + x * 3.0, px * py - py**2 + 3 * px),
        ((x.square() + 1.0).sqrt(), np.sqrt(px**2 + 1)),
        ((y.square() + 0.5).reciprocal(), 1 / (py**2 + 0.5)),
        (x.cos_sin()[0] * y.cos_sin()[1], np.cos(px) * np.sin(py)),
    ]
    for enclosure, values in cases:
        assert np.all(enclosure.lo[:, None] <= values) and np.all(values <= enclosure.hi[:, None])
    product = x * y  # d(xy)/dx = y: its enclosure holds [lo_y, hi_y], a few ulps wider at most
    assert product.glo is not None and product.ghi is not None
    assert np.all(product.glo[:, 0] <= lo[:, 1]) and np.all(product.ghi[:, 0] >= hi[:, 1])
    assert np.all(product.ghi[:, 0] - product.glo[:, 0] <= (hi - lo)[:, 1] + 1e-12)


def test_model_enclosures_hold_the_core_and_tighten_quadratically():
    # the mean-value enclosure of det A over boxes around a pose holds the core's det A at points
    # inside; its excess over the range seen at the box's corners falls ~4x when the box halves
    # (quadratic), while the direct interval enclosure stays ~8x wider than the range
    model = FourLimbModel.of(QUATTRO_M)
    rng = np.random.default_rng(3)
    centre = np.array([[120.0, 80.0, -760.0, 0.4]])
    corners = np.array(np.meshgrid(*[[0.0, 1.0]] * 4, indexing="ij")).reshape(4, -1).T
    excess, direct = [], []
    for half in (8.0, 4.0, 2.0, 1.0):
        lo, hi = centre - half * np.array([1, 1, 1, 0.01]), centre + half * np.array([1, 1, 1, 0.01])
        box = model.evaluate(Enclosure.variables(lo, hi))
        mid = model.evaluate(Enclosure.variables(centre, centre, gradient=False))
        radius = np.nextafter((hi - lo) / 2, np.inf)
        enclosure = mean_value(mid["actuation"], box["actuation"], radius)
        points = np.vstack([lo + rng.uniform(0, 1, (50, 4)) * (hi - lo), lo + corners * (hi - lo)])
        det_a = QUATTRO_M.at(points).jacobians.det_A
        assert np.all(enclosure.lo <= det_a) and np.all(det_a <= enclosure.hi)
        seen = det_a.max() - det_a.min()
        excess.append(float(enclosure.hi[0] - enclosure.lo[0] - seen))
        direct.append(float(box["actuation"].hi[0] - box["actuation"].lo[0]) / seen)
    assert all(a / b > 3.5 for a, b in itertools.pairwise(excess))
    assert min(direct) > 4.0


def test_quattro_slice_y_zero_singular_or_undecided_rest_free():
    # paper 004's Sec. 5.3 says this robot has no constraint singularity; the twist graph finds the
    # plane y = 0 at phi = 0 (mirror symmetry y -> -y swapping limbs 1<->4, 2<->3; the catalog's fact
    # constraint_singular_poses). Certified: every box meeting y = 0 is singular or undecided, the rest free.
    result = C.certify(QUATTRO_M, SLICE, resolution=8.0)
    assert not result.capped and result.totals["unreachable"] == 0
    for box in result.boxes:
        y_lo, y_hi = box.bounds["y"]
        if y_lo <= 0.0 <= y_hi:
            assert box.status in ("singular", "undecided")
        else:
            assert box.status == "free", box
    singular = [b for b in result.boxes if b.status == "singular"]
    assert singular and {b.witness.label for b in singular} == {"constraint"}
    assert all(abs(b.witness.pose["y"]) < 1e-6 for b in singular)
    assert result.fractions["free"] > 0.97


def test_free_boxes_hold_only_regular_poses():
    # a slice at phi = 90 deg that crosses actuation and constraint singularities and leaves the reach:
    # poses drawn inside the free boxes (kept 2 % off their edges) are reachable and regular per the core
    result = C.certify(QUATTRO_M, {"x": (-650.0, 650.0), "y": (-650.0, 650.0), "z": -750.0, "phi": 90.0},
                       resolution=20.0, angles="deg")
    assert result.totals["free"] and result.totals["singular"] and result.totals["unreachable"]
    rng = np.random.default_rng(11)
    free = [b for b in result.boxes if b.status == "free"]
    poses = []
    for box in free:
        (x0, x1), (y0, y1) = box.bounds["x"], box.bounds["y"]
        s = rng.uniform(0.02, 0.98, (3, 2))
        for u, v in s:
            poses.append([x0 + u * (x1 - x0), y0 + v * (y1 - y0), -750.0, math.pi / 2])
    poses = np.array(poses)
    assert QUATTRO_M.reachable(poses).all()
    assert np.all(QUATTRO_M.at(poses).codes == 0)


def _zeros_along(function, start, stop, count=24):
    """Sign changes of ``function`` along a segment (count samples), refined by 40 bisections."""
    ts = np.linspace(0.0, 1.0, count)
    values = []
    for t in ts:
        try:
            values.append(function(start + t * (stop - start)))
        except ValueError:  # out of reach
            values.append(np.nan)
    values = np.array(values)
    out = []
    for i in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
        lo, hi, f_lo = ts[i], ts[i + 1], values[i]
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if np.sign(function(start + mid * (stop - start))) == np.sign(f_lo):
                lo = mid
            else:
                hi = mid
        out.append(start + 0.5 * (lo + hi) * (stop - start))
    return out


def test_h4_paper_002_surfaces_lie_in_no_free_box():
    # paper 002, Eq. (6) (constraint) and Eq. (7) (actuation), evaluated on an independent model of the
    # H4 (tests/four_limb_reference.py): their zeros along lines of the (z, phi) slice at x = y = 300
    # fall in boxes that are singular or undecided, never free
    result = C.certify(H4_M, {"x": 300.0, "y": 300.0, "z": (-900.0, -450.0), "phi": (-1.5, 1.5)},
                       resolution={"z": 6.0, "phi": 0.02})
    zeros = []
    for z in (-840.0, -700.0, -520.0, -470.0):
        start, stop = np.array([300.0, 300.0, z, -1.5]), np.array([300.0, 300.0, z, 1.5])
        for equation in (eq6_constraint, eq7_actuation):
            zeros += [(equation, p) for p in _zeros_along(lambda p, e=equation: e(geometry(H4, p)), start, stop)]
    assert {e for e, _ in zeros} == {eq6_constraint, eq7_actuation}
    for equation, pose in zeros:
        holding = [b for b in result.boxes
                   if b.bounds["z"][0] <= pose[2] <= b.bounds["z"][1]
                   and b.bounds["phi"][0] <= pose[3] <= b.bounds["phi"][1]]
        assert holding and all(b.status != "free" for b in holding), (equation.__name__, pose)
    labels = {b.witness.label for b in result.boxes if b.status == "singular"}
    assert {"constraint", "actuation"} <= labels


def test_quattro_witnesses_satisfy_the_independent_conditions():
    # each singular box's witness pose makes the paper's condition of its label vanish on the
    # independent model (relative to its size elsewhere in the box)
    result = C.certify(QUATTRO_M, {"x": (-400.0, 400.0), "y": (-400.0, 400.0), "z": -750.0, "phi": 90.0},
                       resolution=40.0, angles="deg")
    checked = 0
    for box in [b for b in result.boxes if b.status == "singular"][::7]:
        pose = np.array([box.witness.pose[n] for n in ("x", "y", "z", "phi")])
        pose[3] = math.radians(pose[3])
        equation = eq6_constraint if box.witness.label == "constraint" else eq7_actuation
        corner = np.array([box.bounds["x"][0], box.bounds["y"][0], -750.0, math.pi / 2])
        assert abs(equation(geometry(QUATTRO, pose))) < 1e-6 * abs(equation(geometry(QUATTRO, corner))) + 1e-9
        checked += 1
    assert checked >= 3


def test_degrees_and_radians_give_the_same_paving():
    # the same region in degrees and radians: the boxes differ only by the outward rounding of the
    # conversion, so the shares of each status agree closely and the witnesses are the same poses
    in_deg = C.certify(QUATTRO_M, {"x": 150.0, "y": (-100.0, 100.0), "z": -800.0, "phi": (-60.0, 60.0)},
                       resolution={"y": 4.0, "phi": 1.5}, angles="deg")
    in_rad = C.certify(QUATTRO_M, {"x": 150.0, "y": (-100.0, 100.0), "z": -800.0,
                                   "phi": (-math.pi / 3, math.pi / 3)},
                       resolution={"y": 4.0, "phi": math.radians(1.5)})
    assert in_deg.totals["singular"] > 0
    for status in C.STATUSES:
        assert in_deg.fractions[status] == pytest.approx(in_rad.fractions[status], abs=0.01)
    assert in_deg.totals["singular"] == pytest.approx(in_rad.totals["singular"], rel=0.1)
    assert {b.witness.label for b in in_deg.boxes if b.witness} == {
        b.witness.label for b in in_rad.boxes if b.witness}


def test_cap_returns_decided_boxes_and_the_rest_undecided():
    full = C.certify(QUATTRO_M, SLICE, resolution=8.0)
    capped = C.certify(QUATTRO_M, SLICE, resolution=8.0, max_boxes=60)
    assert capped.capped and capped.evaluated <= 60 and capped.totals["undecided"] > 0
    assert sum(capped.totals.values()) < sum(full.totals.values())
    for box in capped.boxes:  # never a false free: a free box never meets y = 0
        if box.status == "free":
            assert not box.bounds["y"][0] <= 0.0 <= box.bounds["y"][1]
    assert math.isclose(sum(capped.fractions.values()), 1.0)


def test_dask_local_cluster_gives_the_same_certificate():
    distributed = pytest.importorskip("distributed")
    region = {"x": (-200.0, 200.0), "y": (-100.0, 100.0), "z": -750.0, "phi": 0.0}
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = C.certify(QUATTRO_M, region, resolution=5.0, client=client)
    local = C.certify(QUATTRO_M, region, resolution=5.0)
    assert remote.to_dict() == local.to_dict()


def test_certified_path_encloses_every_crossing():
    # the diagonal at phi = 90 deg crosses the actuation singularity twice (symmetric by the half-turn
    # R_z(pi), which maps the path onto itself reversed: t <-> 1 - t) and the constraint one at the centre
    check = sk.check_path(QUATTRO_M, {"x": -300, "y": -300, "z": -750, "phi": 90},
                          {"x": 300, "y": 300, "z": -750, "phi": 90}, angles="deg", certify=True)
    assert check.certified_free is False
    kinds = [c.kind for c in check.crossings]
    assert kinds == ["actuation", "constraint", "actuation"]
    for c in check.crossings:
        assert c.enclosure[0] <= c.parameter <= c.enclosure[1] and c.enclosure[1] - c.enclosure[0] < 1e-5
    first, middle, last = check.crossings
    assert first.parameter + last.parameter == pytest.approx(1.0, abs=1e-8)
    assert middle.enclosure[0] <= 0.5 <= middle.enclosure[1]
    free = sk.check_path(QUATTRO_M, {"x": 100, "y": 100, "z": -750, "phi": 0},
                         {"x": 200, "y": 150, "z": -700, "phi": 0}, angles="deg", certify=True)
    assert free.certified_free is True and free.crossings == ()
    assert "certified" in str(free)


def test_path_inside_a_singular_set_is_reported_as_such():
    # y = 0 at phi = 0 lies in the constraint singular set: the path runs inside it, start to end
    check = sk.check_path(QUATTRO_M, {"x": -300, "y": 0, "z": -750, "phi": 0},
                          {"x": 300, "y": 0, "z": -750, "phi": 0}, samples=40)
    assert len(check.crossings) == 1
    run = check.crossing
    assert run.kind == "constraint" and (run.parameter, run.until) == (0.0, 1.0)
    assert "inside the constraint singular set" in str(check)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: C.certify(QUATTRO_M, {"x": (1.0, 1.0)}), r"`region\['x'\]` to be a non-empty range"),
        (lambda: C.certify(QUATTRO_M, {"x": (2.0, 1.0)}), r"`region\['x'\]` to be a non-empty range"),
        (lambda: C.certify(QUATTRO_M, {"x": (0.0, 1.0)}, resolution=0), r"`resolution` > 0"),
        (lambda: C.certify(QUATTRO_M, {"x": (0.0, 1.0)}, kinds=("twist",)), r"`kinds` among"),
        (lambda: C.certify(QUATTRO_M, {"w": (0.0, 1.0)}), r"`region` over the coordinates"),
        (lambda: C.certify(QUATTRO_M, {"x": 0.0}), r"`region` to give at least one range"),
        (lambda: C.certify(QUATTRO_M, {"x": (0.0, 1.0)}, max_boxes=0), r"`max_boxes` to be an integer"),
        (lambda: C.certify(QUATTRO_M, {"x": (0.0, math.inf)}), r"`region\['x'\]\[1\]` to be finite"),
        (lambda: C.certify(sk.mechanism(sk.load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750]),
                           {"x": (0.0, 1.0)}), r"`mechanism` among what"),
        (lambda: C.certify(QUATTRO_M, {"x": (0.0, 1.0)}, resolution={"q": 1}), r"`resolution` over"),
    ],
)
def test_bad_input_is_one_line_naming_the_argument(call, message):
    with pytest.raises(sk.ScrewkitError, match=message) as info:
        call()
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(("mechanism", "params"), [(H4_M, H4), (QUATTRO_M, QUATTRO)])
def test_enclosed_functions_are_paper_002_equations_6_and_7(mechanism, params):
    # at random reachable poses the enclosed constraint function is paper 002's Eq. (6) and det A
    # (paper 004, Eq. 12) is minus Eq. (7), both evaluated on the independent model
    model = FourLimbModel.of(mechanism)
    poses = np.asarray(mechanism.random_poses(np.random.default_rng(5), 12))
    values = model.evaluate(Enclosure.variables(poses, poses, gradient=False))
    for k, pose in enumerate(poses):
        g = geometry(params, pose)
        for name, expected in (("constraint", eq6_constraint(g)), ("actuation", -eq7_actuation(g))):
            e = values[name]
            assert e.lo[k] - 1e-13 * abs(expected) <= expected <= e.hi[k] + 1e-13 * abs(expected)


@pytest.mark.parametrize(("mechanism", "params"), [(H4_M, H4), (QUATTRO_M, QUATTRO)])
def test_float_route_is_paper_002_equations_6_and_7_and_the_core_det_a(mechanism, params):
    # the same closed forms in floats (the fast route): paper 002's Eq. (6), minus Eq. (7) on the
    # independent model, the core's det A, the reach functions' sign the core's reachability, and
    # NaN for the singularity functions out of reach
    model = FourLimbModel.of(mechanism)
    rng = np.random.default_rng(11)
    poses = np.asarray(mechanism.random_poses(rng, 20))
    far = poses[:5] + np.array([0.0, 0.0, -3000.0, 0.0])
    values = model.values(np.vstack([poses, far]))
    for k, pose in enumerate(poses):
        g = geometry(params, pose)
        assert values["constraint"][k] == pytest.approx(eq6_constraint(g), rel=1e-9, abs=1e-9)
        assert values["actuation"][k] == pytest.approx(-eq7_actuation(g), rel=1e-9)
    assert np.allclose(values["actuation"][:20], mechanism.at(poses).jacobians.det_A, rtol=1e-9)
    reach = np.all([values[f"serial:{i}"] >= 0 for i in range(1, 5)], axis=0)
    assert reach.tolist() == mechanism.reachable(np.vstack([poses, far])).tolist() == [True] * 20 + [False] * 5
    assert np.isnan(values["actuation"][20:]).all() and np.isnan(values["constraint"][20:]).all()
    with pytest.raises(sk.ScrewkitValueError, match="`poses`"):
        model.values([[0.0, 0.0, -750.0]])


def test_a_scalar_resolution_applies_to_lengths_and_angles_get_their_default():
    # a length and an angle do not compare: a scalar resolution of 4 mm once also bounded phi's boxes at
    # 4 rad, wider than its whole range, so phi was never split; now the lengths take it and each angle
    # range its default, 1/RESOLUTION_DIVISIONS of its width
    region = {"x": 150.0, "y": (-100.0, 100.0), "z": -800.0, "phi": (-math.pi / 3, math.pi / 3)}
    result = C.certify(QUATTRO_M, region, resolution=4.0, max_boxes=200)
    assert result.resolution == {"y": 4.0, "phi": (2 * math.pi / 3) / C.RESOLUTION_DIVISIONS}
    assert min(b.bounds["phi"][1] - b.bounds["phi"][0] for b in result.boxes) < math.pi / 3
    # ranges of one kind all take the number; a mapping gives each its own
    assert C.certify(QUATTRO_M, {**region, "y": 0.0}, resolution=0.5, max_boxes=5).resolution == {"phi": 0.5}
    given = C.certify(QUATTRO_M, region, resolution={"phi": 0.1}, max_boxes=5).resolution
    assert given == {"y": 200.0 / C.RESOLUTION_DIVISIONS, "phi": 0.1}
