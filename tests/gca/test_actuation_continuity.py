"""The actuation lines' directions (points at infinity of the four-limb and Delta diagrams) carried over
the motion by the limbs' joints (from the rod's arm-side centre to its platform-side centre), so that
the actuation condition is a continuous function of the pose that changes sign only at its zeros
(issue 21, item 2).

A sign fixed by the reference direction alone (flip where the dot product with it turns negative) made
the actuation condition jump at regular poses where an actuation direction got more than 90° away from
its reference direction (the Veloce's ``b``, the Quattro's ``h``: the poses below). The expected
values are the actuation Jacobian's determinant, computed by the core from the actuation wrenches
(``det_A``), independently of the diagram's points: the actuation condition is ``±det A`` with one
sign, a relation these tests check along the motion.
"""

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import quantities as Q
from screwkit.analysis import workspace as W
from screwkit.core.wrench_systems import analyze_table
from screwkit.gca import diagram_points as DP

#: Regular poses where the reference-fixed orientation flipped an actuation direction (a reviewer's
#: bisection), with the direction of the segment it was found on.
FLIPPED = {
    "veloce": [510.3079386544066, -449.2832375908795, -559.7226361523258, -4.48688218046858],
    "quattro": [475.469384583423, -413.61963334357495, -625.6974133533583, 0.4902222563344607],
}
STEP = np.array([1.0, 0.3, -0.2, 0.001])


def actuation_condition(mechanism):
    _, _, labels, _ = Q.conditions_of(mechanism, {})
    return f"condition:{labels.index('actuation')}"


@pytest.mark.parametrize("name", sorted(FLIPPED))
def test_actuation_condition_is_continuous_where_a_direction_turned_past_90_degrees(name):
    mechanism = sk.load_mechanism(name)
    poses = np.array(FLIPPED[name]) + np.array([-1e-6, 1e-6])[:, None] * STEP
    values, ok = W.evaluate(mechanism, poses, actuation_condition(mechanism))
    det_a, _ = W.evaluate(mechanism, poses, "det_A")
    assert ok.all() and np.all(np.abs(det_a) > 0.1)  # a regular pose, far from det A = 0
    np.testing.assert_allclose(values[0], values[1], rtol=1e-5)  # no sign change across it
    sign = np.sign(values[0] * det_a[0])
    np.testing.assert_allclose(values, sign * det_a, rtol=1e-9)


def bisected_jumps(mechanism, condition, low, high, scale, iterations=50):
    """Whether the condition's sign change between two poses is a jump: after bisection, its value
    on either side is still larger than ``1e-8 scale`` (a zero has |value| -> 0)."""
    sign_low = np.sign(W.evaluate(mechanism, low[None], condition)[0][0])
    for _ in range(iterations):
        middle = 0.5 * (low + high)
        if np.sign(W.evaluate(mechanism, middle[None], condition)[0][0]) == sign_low:
            low = middle
        else:
            high = middle
    values = W.evaluate(mechanism, np.array([low, high]), condition)[0]
    return bool(np.abs(values).max() > 1e-8 * scale)


@pytest.mark.parametrize(
    ("name", "segments"), [("h4", 4), ("quattro", 6), ("v4", 6), ("ragnar", 4), ("veloce", 6)]
)
def test_actuation_condition_changes_sign_only_at_its_zeros_on_random_segments(name, segments):
    mechanism = sk.load_mechanism(name)
    condition = actuation_condition(mechanism)
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 1.0, 41)[:, None]
    jumps, followed = 0, 0
    while followed < segments:
        start, end = mechanism.random_poses(rng, 2)
        poses = start + t * (end - start)
        if not mechanism.reachable(poses).all():
            continue
        followed += 1
        values, ok = W.evaluate(mechanism, poses, condition)
        det_a, _ = W.evaluate(mechanism, poses, "det_A")
        assert ok.all()
        # one factor relation along the segment: the value is ± det A with one sign
        sign = np.sign(np.sum(values * det_a))
        np.testing.assert_allclose(values, sign * det_a, rtol=1e-9, atol=1e-12 * np.abs(det_a).max())
        for i in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
            jumps += bisected_jumps(mechanism, condition, poses[i], poses[i + 1], np.median(np.abs(values)))
    assert jumps == 0


@pytest.mark.parametrize("name", ["delta", "h4", "quattro", "ragnar", "v4", "veloce"])
def test_positive_work_rule_orients_as_the_rod_rule_up_to_one_sign(name, monkeypatch):
    # The fallback (w ∘ $_a > 0 on the actuated joint) changes sign only at the limb's serial
    # singularity; where a rod orients the line too, the two agree up to one sign over the motion,
    # which the reference's constant sign absorbs.
    mechanism = sk.load_mechanism(name)
    poses = mechanism.random_poses(np.random.default_rng(3), 60)
    poses = poses[mechanism.reachable(poses)]
    points = mechanism.at(None)[0].diagram.points
    analysis = analyze_table(mechanism.joints(poses))
    by_rods = DP.batch_diagram_points(points, analysis)
    monkeypatch.setattr(DP, "_rods", lambda batch, actuated: [])
    by_work = DP.batch_diagram_points(points, analysis)
    directions = [p.label for p in points if p.key[0] == "direction" and p.key[1].startswith("actuation ")]
    assert len(directions) >= 3 and len(poses) > 20
    for label in directions:
        along = np.einsum("ij,ij->i", by_rods[label], by_work[label])
        assert np.all(np.abs(np.abs(along) - 1.0) < 1e-12) and len(set(np.sign(along))) == 1
