"""Hypothesis strategies shared by the tests: rigid motions, unit changes, random screws."""

import numpy as np
from hypothesis import strategies as st

finite_floats = st.floats(min_value=-10.0, max_value=10.0, allow_nan=False, allow_infinity=False)


@st.composite
def rotations(draw):
    """A uniformly drawn proper rotation matrix (from a unit quaternion)."""
    q = np.array([draw(st.floats(-1, 1)) for _ in range(4)])
    size = np.linalg.norm(q)
    if size < 1e-3:
        q, size = np.array([1.0, 0, 0, 0]), 1.0
    w, x, y, z = q / size
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


@st.composite
def rigid_motions(draw):
    """(rotation, translation) with a translation of up to 10 length units per axis."""
    return draw(rotations()), np.array([draw(finite_floats) for _ in range(3)])


@st.composite
def far_rigid_motions(draw):
    """(rotation, translation) with the translation 1e3 to 1e4 length units from the origin: a robot of
    about one unit in size some kilometres away (issue 11: labels and diagrams must not depend on where
    the origin is)."""
    direction = np.array([draw(st.floats(-1, 1)) for _ in range(3)])
    size = np.linalg.norm(direction)
    direction = np.array([1.0, 0, 0]) if size < 1e-3 else direction / size
    return draw(rotations()), draw(st.floats(1e3, 1e4)) * direction


#: Changes of length unit: metres to millimetres, to inches, to kilometres, ...
unit_factors = st.sampled_from([1e-3, 0.0254, 0.3048, 1.0, 25.4, 1000.0])

seeds = st.integers(min_value=0, max_value=2**32 - 1)
