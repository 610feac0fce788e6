"""The compiled kernel of paper 004's indices (screwkit.papers._lti_numba): its cosine and sine against
the maths library, its fallback for angles beyond the reduction's range against the numpy path, and
calls from several threads at once. ``bench/bench_indices.py`` measures its speed and checks that the
compiler turned its pose loop into packed (SIMD) instructions (a fresh compile, ~10 s: not here).

The parity of the whole kernel with the numpy path over the five robots is checked in
``tests/papers/test_paper_004.py`` (``test_numba_and_numpy_paths_agree``).
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from screwkit.papers import paper_004 as P4
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics

kernels = pytest.importorskip("screwkit.papers._lti_numba")
numba = pytest.importorskip("numba")


@numba.njit
def _cos_sin_many(angles):
    cosines, sines = np.empty(angles.size), np.empty(angles.size)
    for i in range(angles.size):
        cosines[i], sines[i] = kernels.cos_sin(angles[i])
    return cosines, sines


def test_cos_sin_agree_with_the_maths_library_to_a_rounding_unit():
    rng = np.random.default_rng(1)
    limit = kernels.REDUCTION_LIMIT
    turns = rng.integers(-(2**19), 2**19, 20_000)
    angles = np.concatenate([
        np.linspace(-20.0, 20.0, 40_001),
        rng.uniform(-limit, limit, 40_000),
        turns * (np.pi / 2),  # r ~ 0 after the reduction: its worst case
        turns * (np.pi / 2) + 1e-9,
        turns * (np.pi / 4),  # r ~ ±π/4: the polynomials' edge
        [0.0, -0.0, 1e-300, -1e-300, limit, -limit],
    ])
    cosines, sines = _cos_sin_many(angles)
    expected_cos = np.array([math.cos(a) for a in angles])
    expected_sin = np.array([math.sin(a) for a in angles])
    eps = np.finfo(float).eps
    assert np.max(np.abs(cosines - expected_cos)) <= eps
    assert np.max(np.abs(sines - expected_sin)) <= eps


def test_angles_beyond_the_reduction_range_use_the_library():
    quattro = load_mechanism("quattro")  # an articulated platform: φ enters through cos φ, sin φ only
    params, mode = quattro.parameters, (-1, -1, -1, -1)
    base = np.array([[50.0, -30.0, -800.0, 0.3], [0.0, 0.0, -750.0, -0.2], [120.0, 80.0, -900.0, 0.5]])
    far = base.copy()
    far[:, 3] += np.array([1e6, -1e7, 1e12]) * 2 * np.pi  # whole turns: the same poses
    mixed = np.concatenate([base, far])
    fast = kernels.transmission(mixed, *P4._kernel_arguments(params, mode))
    # the reference: the family's inverse kinematics and paper 004's closed forms (angles beyond the
    # catalog's bound, which mechanism.at refuses, reach the kernel only through this private door)
    plain = P4.transmission_indices(inverse_kinematics(params, mixed, working_mode=mode))
    assert np.all(np.abs(far[:, 3]) > kernels.REDUCTION_LIMIT) and fast[2].all()
    np.testing.assert_allclose(fast[0], plain.input, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast[1], plain.output, rtol=0, atol=1e-12)
    # the far poses are the near ones turned whole turns (to the rounding of φ itself: ~1e-4 rad at 6e12)
    np.testing.assert_allclose(fast[0][3:5], fast[0][:2], rtol=0, atol=1e-9)


def test_threads_share_the_kernel():
    # the kernel releases the GIL (the Dask path runs chunks in threads): calls side by side give
    # what calls one after the other give
    h4 = load_mechanism("h4")
    low, high = zip(*(h4.workspace[c] for c in h4.pose_names), strict=True)
    chunks = [np.random.default_rng(seed).uniform(low, high, size=(20_000, 4)) for seed in range(4)]
    packed = P4._kernel_arguments(h4.parameters, (-1, -1, -1, -1))
    serial = [kernels.transmission(chunk, *packed) for chunk in chunks]
    with ThreadPoolExecutor(4) as pool:
        threaded = list(pool.map(lambda chunk: kernels.transmission(chunk, *packed), chunks))
    for one, other in zip(serial, threaded, strict=True):
        for a, b in zip(one, other, strict=True):
            np.testing.assert_array_equal(a, b)
