"""Family facts of the Delta catalog entry, evaluated by tests/robots/test_catalog.py from the robot's
own geometry (tests/delta_geometry.py), not from screwkit.robots.families.delta.

``FACTS = {fact name: check(mechanism, fact) -> (got, expected)}``.
"""

from __future__ import annotations

import numpy as np

from .delta_geometry import coplanar_root_on_x, rod_determinant


def check_actuation_singular_where_the_rods_are_coplanar(mechanism, fact):
    """The stated point ``(x, 0, z)`` is, within ``tolerance``, where the rods' directions become
    dependent on that line, and the twist graph labels it an actuation singularity (regular 5 mm
    either side)."""
    value = fact["value"]
    root = coplanar_root_on_x(mechanism, value["z"])
    near = root + np.array([[0.0, 0.0, 0.0], [-5.0, 0.0, 0.0], [5.0, 0.0, 0.0]])
    verdicts = mechanism.at(near, rtol=1e-6).verdicts.tolist()
    assert abs(rod_determinant(mechanism, root[None])[0]) < 1e-9
    got = (abs(root[0] - value["x"]) <= fact["tolerance"], verdicts)
    return got, (True, ["actuation singularity", "regular", "regular"])


FACTS = {
    "actuation_singular_where_the_rods_are_coplanar": check_actuation_singular_where_the_rods_are_coplanar,
}
