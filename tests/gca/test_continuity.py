"""The superbracket's conditions are continuous over the motion (issue 21 item 2): the points at
infinity of the wrench diagram are carried with the orientation of the reference configuration, so a
condition changes sign only through its zeros. On main, the H4's ``condition:1`` jumped from about
+70.8 to −70.7 between x = 112.5 and 120 mm (y = 0, z = −750 mm, φ = 0) where det A is smooth: the
directions' signs were fixed by their first non-zero component, which crosses zero there."""

import numpy as np
import pytest

from screwkit.analysis.quantities import conditions_of
from screwkit.robots.catalog import load_mechanism

STEPS = np.linspace(-1.0, 1.0, 61)[:, None]


def values_along(name, direction):
    mechanism = load_mechanism(name)
    posed = mechanism.at(mechanism.default_pose + STEPS * np.asarray(direction, dtype=float))
    diagram, conditions, _, _ = conditions_of(mechanism, posed.options)
    points, exists = posed.diagram_points(diagram.points)
    assert exists.all()
    return posed, [np.asarray(c.evaluate(points), dtype=float) for c in conditions]


@pytest.mark.parametrize(
    ("name", "direction"),
    [
        ("h4", [300.0, 0, 0, 0]),
        ("h4", [200.0, 150.0, 0, 0.5]),
        ("v4", [300.0, 0, 0, 0]),
        ("mcgill_smg", [150.0, -200.0, 100.0, -0.7]),
        ("peppermill", [200.0, 150.0, 0, 0.5]),
    ],
)
def test_conditions_change_sign_only_through_zero(name, direction):
    posed, values = values_along(name, direction)
    det_a = posed.jacobians.det_A
    for value in values:
        size = np.median(np.abs(value))
        # a sign change between neighbours passes near zero: no jump from +v to −v
        changes = np.flatnonzero(np.sign(value[1:]) * np.sign(value[:-1]) < 0)
        for i in changes:
            assert min(abs(value[i]), abs(value[i + 1])) <= 0.2 * size, (i, value[i], value[i + 1])
        # and a step without a zero is small: the values are a continuous function of the pose
        steps = np.abs(np.diff(value))
        assert steps.max() <= 0.2 * np.abs(value).max()
    if not np.any(np.sign(det_a[1:]) * np.sign(det_a[:-1]) < 0):  # det A keeps its sign: so does the
        # product of the conditions (the superbracket, up to factors that never vanish)
        product = np.prod(values, axis=0)
        assert np.all(np.sign(product) == np.sign(product[0]))


def test_the_h4_case_of_the_issue():
    posed, values = values_along("h4", [300.0, 0, 0, 0])
    x = posed.poses[:, 0]
    near = (x >= 100) & (x <= 130)
    assert np.all(values[1][near] < 0) and np.ptp(values[1][near]) < 1.0
    assert np.all(np.sign(posed.jacobians.det_A[near]) == np.sign(posed.jacobians.det_A[near][0]))
