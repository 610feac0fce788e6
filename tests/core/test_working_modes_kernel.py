"""The compiled working-mode check (screwkit.core._newton_numba.bordered_orientation) against its numpy
twin in screwkit.core._working_modes (LAPACK's determinant, solves and QR), and the whole check with
and without it on Ragnar continuations that step close to a leg's serial singularity."""

import numpy as np
import pytest

from screwkit.core import _working_modes
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.graph_kinematics import kinematics_of

from .test_loop_closure_working_modes import RAGNAR_POSES_NEAR_A_FOLD

kernels = pytest.importorskip("screwkit.core._newton_numba", reason="numba is not installed (the `fast` extra)")


def _bordered_inputs(rng, count, rows, columns, rank, tilt):
    """Blocks ``J`` of the given rank and borders: their null spaces turned by about ``tilt``."""
    u = np.linalg.qr(rng.normal(size=(count, rows, rows)))[0]
    u[..., 0] *= rng.choice([-1.0, 1.0], (count, 1))  # (Householder's Q alone has one determinant)
    v = np.linalg.qr(rng.normal(size=(count, columns, columns)))[0]
    values = np.zeros((count, rows, columns))
    values[:, np.arange(rank), np.arange(rank)] = rng.uniform(0.05, 3.0, (count, rank))
    block = u @ values @ np.swapaxes(v, 1, 2)
    left = np.linalg.qr(u[..., rank:] + tilt * rng.normal(size=(count, rows, rows - rank)))[0]
    right = np.linalg.qr(v[..., rank:] + tilt * rng.normal(size=(count, columns, columns - rank)))[0]
    return block, left, right


@pytest.mark.parametrize("shape", [(24, 27, 23), (6, 6, 6), (12, 8, 8), (5, 9, 4)])
def test_the_kernel_reads_the_numpy_twins_sign_null_spaces_and_turn(shape):
    rng = np.random.default_rng(sum(shape))
    block, left, right = _bordered_inputs(rng, 200, *shape, tilt=0.3)
    signs, new_left, new_right, turned = kernels.bordered_orientation(block, left, right)
    bordered = _working_modes._bordered(block, left, right)
    expected_left, expected_right, expected_turned = _working_modes._null_spaces(bordered, *shape[:2])
    expected_signs = np.sign(np.linalg.det(bordered))
    assert set(np.unique(expected_signs)) == {-1.0, 1.0}  # both orientations occur in the sample
    np.testing.assert_array_equal(signs, expected_signs)
    for got, expected in ((new_left, expected_left), (new_right, expected_right), (turned, expected_turned)):
        np.testing.assert_allclose(got, expected, rtol=0.0, atol=1e-11)


def test_a_flipped_null_space_or_swapped_rows_flip_the_kernels_sign():
    """Hand-checked parities: negating the border's last column negates the determinant; so does
    swapping two rows of ``J`` together with its left null space's rows."""
    rng = np.random.default_rng(3)
    block, left, right = _bordered_inputs(rng, 50, 24, 27, 23, tilt=0.1)
    signs = kernels.bordered_orientation(block, left, right)[0]
    flipped = right.copy()
    flipped[..., -1] *= -1.0
    assert np.all(kernels.bordered_orientation(block, left, flipped)[0] == -signs)
    swapped = [array[:, [1, 0, *range(2, 24)]] for array in (block, left)]
    assert np.all(kernels.bordered_orientation(swapped[0], swapped[1], right)[0] == -signs)


def test_the_check_flags_the_same_ragnar_poses_with_and_without_numba(monkeypatch):
    """The Ragnar poses of tests/core/test_loop_closure_working_modes.py and 300 random ones, closed with
    the compiled check and with its numpy twin (the corrector compiled in both): the same poses
    reached, the same configurations, the same reasons."""
    poses = np.array(RAGNAR_POSES_NEAR_A_FOLD)
    poses = np.concatenate([poses, load_mechanism("ragnar").random_poses(np.random.default_rng(12), 300)])
    with_kernel = kinematics_of(load_mechanism("ragnar")).solve(poses)
    monkeypatch.setattr(_working_modes, "compiled_kernels", lambda name, size: None)
    with_numpy = kinematics_of(load_mechanism("ragnar")).solve(poses)
    assert 0 < (~with_kernel.reached).sum() < len(poses) - 250  # some refused, most reached
    np.testing.assert_array_equal(with_kernel.reached, with_numpy.reached)
    np.testing.assert_array_equal(with_kernel.reasons, with_numpy.reasons)
    np.testing.assert_allclose(with_kernel.theta, with_numpy.theta, rtol=0.0, atol=1e-12)
