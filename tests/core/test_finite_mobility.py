"""Finite against instantaneous mobility, and mobility at the data's precision (issue 20 item 2).

Expected values are hand derivations:

* planar revolutes about z through points ``(x, 0)`` of one line have planar twists ``(1, 0, -x)``
  (rotation rate, velocity at the origin): n of them span 2 dimensions, so a loop of three has one
  first-order freedom, a loop of four two;
* a triangle with sides 1, 2, 3 (1 + 2 = 3) exists only flat: rigid. A four-bar 1, 1, 2 with ground
  4 (1 + 1 + 2 = 4) likewise; Grübler–Kutzbach counts it 3·(4 − 1) − 2·4 = 1. A parallelogram
  four-bar (1, 3, 1, 3) folded flat is a bifurcation of its parallelogram and antiparallelogram
  branches: it moves, with one freedom, along each;
* Bennett's 4R (Bennett 1903; McCarthy, *Geometric Design of Linkages*, 2000, §9.6): opposite links
  equal (a12 = a34 = a, a23 = a41 = b, the same twists α, β), ``a / sin α = b / sin β``, closed by
  ``tan(θ1/2) tan(θ2/2) = sin((β+α)/2) / sin((β−α)/2)``, θ3 = −θ1, θ4 = −θ2 (checked below on
  the product of Denavit–Hartenberg transforms). A 4R loop in general is rigid (6 − 4 > 0
  equations too many), Bennett's moves with one freedom.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.algebra.rigid_motions import rotation_matrix
from screwkit.core.finite_mobility import check_stated_dof, mobility_reading
from screwkit.core.mobility import generic_mobility
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import ScrewkitValueError, TwistGraphError
from screwkit.graphs.joints import revolute
from screwkit.graphs.twistgraph import twist_graph


def loop(points, axes=None, *, platform="L1", **kwargs):
    """A single loop of revolutes ground → L1 → … → ground through ``points`` (about z by default)."""
    links = ["ground", *(f"L{i}" for i in range(1, len(points))), "ground"]
    axes = [[0, 0, 1]] * len(points) if axes is None else axes
    joints = [(links[i], links[i + 1], revolute(f"J{i + 1}", axes[i], points[i])) for i in range(len(points))]
    return twist_graph("ground", platform, joints, **kwargs)


FLAT_TRIANGLE = [[0, 0, 0], [1, 0, 0], [3, 0, 0]]  # sides 1, 2, 3
FLAT_FOURBAR = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [4, 0, 0]]  # 1, 1, 2 and ground 4
FOLDED_PARALLELOGRAM = [[0, 0, 0], [1, 0, 0], [4, 0, 0], [3, 0, 0]]  # 1, 3, 1 and ground 3
FOURBAR = [[0, 0, 0], [1, 0, 0], [3, 2, 0], [3, 0, 0]]


@pytest.mark.parametrize(
    ("points", "instantaneous", "finite"),
    [(FLAT_TRIANGLE, 1, 0), (FLAT_FOURBAR, 2, 0), (FOLDED_PARALLELOGRAM, 2, 1), (FOURBAR, 1, 1)],
)
def test_planar_linkages_in_line_read_their_finite_mobility(points, instantaneous, finite):
    reading = mobility_reading(loop(points, platform="L2"))
    assert (reading.instantaneous, reading.finite) == (instantaneous, finite)
    assert reading.differs == (instantaneous != finite)
    assert generic_mobility(loop(points, platform="L2")) == finite


def test_a_stated_dof_is_checked_against_the_finite_mobility():
    assert wrench_analysis(loop(FLAT_TRIANGLE), dof=0).dof == 0  # rigid: dof=0 is right
    with pytest.raises(TwistGraphError, match=r"finite mobility, 0 \(instantaneous 1,.*got dof = 1"):
        wrench_analysis(loop(FLAT_TRIANGLE), dof=1)
    with pytest.raises(TwistGraphError, match=r"mobility, 1 \(.*got dof = 0"):  # both 1: one number
        wrench_analysis(loop(FOURBAR), dof=0)


def test_an_undecided_reading_refutes_no_stated_dof():
    reading = mobility_reading(loop(FOURBAR))
    undecided = type(reading)(1, None, 1, 0, 3, 5, 1e-9, "steps did not close")
    check_stated_dof(0, undecided)
    check_stated_dof(3, undecided)
    assert "undecided" in str(undecided)


def _dh(theta, a, alpha):
    """Denavit–Hartenberg ``Rz(θ) Tx(a) Rx(α)`` (no offsets)."""
    c, s, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[c, -s * ca, s * sa, a * c], [s, c * ca, -c * sa, a * s], [0, sa, ca, 0], [0, 0, 0, 1]])


ALPHA, BETA = np.radians(30), np.radians(60)


def bennett_frames(a=1.0, alpha=ALPHA, beta=BETA, theta1=0.7):
    """The four joint frames of a closed Bennett linkage (module docstring), and the closure error."""
    b = a * np.sin(beta) / np.sin(alpha)
    theta2 = 2 * np.arctan(np.sin((beta + alpha) / 2) / np.sin((beta - alpha) / 2) / np.tan(theta1 / 2))
    frames = [np.eye(4)]
    for theta, length, twist in ((theta1, a, alpha), (theta2, b, beta), (-theta1, a, alpha), (-theta2, b, beta)):
        frames.append(frames[-1] @ _dh(theta, length, twist))
    return frames[:4], float(np.abs(frames[4] - np.eye(4)).max())


def bennett(a=1.0, round_to=None, transform=None):
    """Bennett's linkage, each axis given by two points ``a`` apart, rounded to ``round_to`` decimals."""
    frames, _ = bennett_frames(a)
    frames = [(np.eye(4) if transform is None else transform) @ f for f in frames]
    pairs = [(f[:3, 3], f[:3, 3] + a * f[:3, 2]) for f in frames]
    if round_to is not None:
        pairs = [(np.round(p, round_to), np.round(q, round_to)) for p, q in pairs]
    return loop([p for p, _ in pairs], [q - p for p, q in pairs], platform="L2")


def test_bennett_linkage_closes_and_moves_with_one_freedom():
    assert bennett_frames()[1] < 1e-12  # the closure condition, checked independently of screwkit
    reading = mobility_reading(bennett())
    assert (reading.instantaneous, reading.finite, reading.moved) == (1, 1, 8)


@pytest.mark.parametrize(("a", "round_to", "rtol"), [(1.0, 6, 1e-5), (100.0, 2, 1e-3)])
def test_rounded_bennett_is_rigid_at_1e9_and_mobile_at_its_data_precision(a, round_to, rtol):
    # 6 decimals of a unit-size linkage, or 0.01 mm of a 100 mm one: relative errors 5e-7 and 5e-5
    rounded = bennett(a, round_to)
    strict = mobility_reading(rounded)
    assert (strict.instantaneous, strict.finite) == (0, 0)  # rigid to 1e-9: the rounding shows
    loose = mobility_reading(rounded, rtol=rtol)
    assert (loose.instantaneous, loose.finite) == (1, 1)
    assert generic_mobility(rounded, rtol=rtol) == 1
    assert wrench_analysis(rounded, dof=1, rtol=rtol).dof == 1  # the right dof is accepted


@pytest.mark.parametrize("rtol", [0.5, -1e-3])
def test_an_out_of_range_data_precision_is_refused_naming_rtol(rtol):
    with pytest.raises(ScrewkitValueError, match="`rtol`"):
        mobility_reading(loop(FOURBAR), rtol=rtol)


@settings(max_examples=12)  # each example closes two linkages' loops: keep the test to seconds
@given(angle=st.floats(-3.0, 3.0), axis=st.sampled_from([(1, 0, 0), (0, 0, 1), (0.6, 0, 0.8)]),
       shift=st.tuples(*[st.floats(-20.0, 20.0)] * 3), unit=st.sampled_from([1e-3, 1.0, 1e3]))
def test_readings_do_not_depend_on_the_frame_or_the_length_unit(angle, axis, shift, unit):
    g = np.eye(4)
    g[:3, :3] = rotation_matrix(np.asarray(axis, dtype=float), np.asarray(angle))
    g[:3, 3] = shift
    reading = mobility_reading(bennett(a=unit, transform=g))  # every length times `unit`, then moved
    assert (reading.instantaneous, reading.finite) == (1, 1)
    triangle = loop([g[:3, :3] @ p + g[:3, 3] for p in np.asarray(FLAT_TRIANGLE, float) * unit],
                    [g[:3, :3] @ [0, 0, 1]] * 3)
    reading = mobility_reading(triangle)
    assert (reading.instantaneous, reading.finite) == (1, 0)


def test_classify_result_carries_both_mobilities_at_its_rtol():
    from screwkit.core.singularity import classify

    assert (classify(loop(FLAT_TRIANGLE), dof=0).mobility.instantaneous,
            classify(loop(FLAT_TRIANGLE), dof=0).mobility.finite) == (1, 0)
    reading = classify(bennett(1.0, 6), dof=1, rtol=1e-5).mobility  # rounded: mobile at its precision
    assert (reading.instantaneous, reading.finite, reading.rtol) == (1, 1, 1e-5)


def test_steps_newton_cannot_close_leave_the_finite_mobility_undecided(monkeypatch):
    import screwkit.core.finite_mobility as finite_mobility

    # one Newton iteration cannot bring a step of the flat triangle back (it converges only
    # linearly at the singular reference): neither a motion nor isolation is shown
    monkeypatch.setattr(finite_mobility, "NEWTON_ITERATIONS", 1)
    reading = mobility_reading(loop(FLAT_TRIANGLE))
    assert (reading.instantaneous, reading.finite, reading.moved) == (1, None, 0)
    assert "undecided" in str(reading) and "did not close" in reading.why
    check_stated_dof(1, reading)  # refutes nothing
