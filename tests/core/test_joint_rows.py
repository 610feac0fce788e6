"""A model's joint rows as a table writes them (screwkit.core._joint_rows): the scaled frame undone,
each ball's axes orthonormal; the compiled loop and the numpy twin agree bit for bit."""

import importlib.util

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.core._joint_rows import COUPLE_SQUARED_NORM, joint_rows, orthonormal_axes, unscaled_screws

HAS_NUMBA = importlib.util.find_spec("numba") is not None


def _balls(rng, count):
    """``count`` balls' rows ``(count, 3, 6)``: three unit axes through a centre each; some with
    the first axis along x, or the second in the xy plane (the factorization's reflection-free
    cases), some exactly the coordinate axes."""
    directions = rng.normal(size=(count, 3, 3))
    quarter = count // 4
    directions[:quarter, 0, 1:] = 0.0
    directions[quarter : 2 * quarter, 1, 2] = 0.0
    directions[2 * quarter : 2 * quarter + 8] = np.eye(3)
    directions /= np.linalg.norm(directions, axis=-1, keepdims=True)
    centres = rng.normal(size=(count, 1, 3)) * 50.0
    return np.concatenate([directions, np.cross(centres, directions)], axis=-1), centres[:, 0]


def test_a_balls_rows_are_the_given_ones_times_the_inverse_transposed_triangle_of_their_qr():
    # independent computation: numpy's Householder QR of the directions, then R^-T times the rows
    rows, _ = _balls(np.random.default_rng(3), 400)
    triangle = np.linalg.qr(np.swapaxes(rows[..., :3], -1, -2))[1]
    expected = np.linalg.solve(np.swapaxes(triangle, -1, -2), rows)
    conditioning = np.linalg.cond(rows[..., :3])
    well = conditioning < 1e3  # (random axes: a few nearly dependent, where both lose digits)
    assert well.sum() > 350
    np.testing.assert_allclose(orthonormal_axes(rows)[well], expected[well], rtol=0, atol=1e-11 * 50)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(1e-3, 1e3))
def test_ball_rows_orthonormal_through_the_centre_in_any_frame_and_length_unit(seed, unit):
    rng = np.random.default_rng(seed)
    rows, centres = _balls(rng, 16)
    rotation = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    shift = rng.normal(size=3) * 100
    moved_centres = (centres @ rotation.T + shift) * unit
    directions = rows[..., :3] @ rotation.T
    moved = np.concatenate([directions, np.cross(moved_centres[:, None], directions)], axis=-1)
    for given_rows, centre in ((rows, centres), (moved, moved_centres)):
        out = orthonormal_axes(given_rows)
        gram = out[..., :3] @ np.swapaxes(out[..., :3], -1, -2)
        np.testing.assert_allclose(gram, np.broadcast_to(np.eye(3), gram.shape), atol=1e-9)
        scale = 1.0 + np.abs(centre).max()
        np.testing.assert_allclose(out[..., 3:], np.cross(centre[:, None], out[..., :3]), atol=1e-9 * scale)
        for k in range(len(out)):  # the same 3-system: the six rows together still of rank 3
            both = np.vstack([given_rows[k], out[k]]) / np.array([1, 1, 1, scale, scale, scale])
            assert np.linalg.matrix_rank(both, tol=1e-8) == 3


def test_unscaled_screws_undo_the_scaled_frame_and_keep_a_couple():
    point, length = np.array([2.0, -1.0, 3.0]), 4.0
    centre, axis = np.array([1.0, 5.0, -2.0]), np.array([0.0, 0.6, 0.8])
    line = np.concatenate([axis, np.cross(centre, axis)])  # a hinge through the centre
    scaled = np.concatenate([axis, (line[3:] - np.cross(point, axis)) / length])  # by the definition
    couple = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 1.0])  # a slider: no point, its direction as it is
    out = unscaled_screws(np.stack([scaled, couple]), length, point)
    np.testing.assert_allclose(out[0], line, atol=1e-14)
    np.testing.assert_array_equal(out[1], couple)
    tiny = np.array([1e-13, 0.0, 0.0, 0.0, 1.0, 0.0])  # |s|^2 = 1e-26, below COUPLE_SQUARED_NORM: a couple
    assert 1e-26 < COUPLE_SQUARED_NORM
    np.testing.assert_array_equal(unscaled_screws(tiny, length, point), tiny)


@pytest.mark.skipif(not HAS_NUMBA, reason="numba not installed")
def test_joint_rows_compiled_and_numpy_agree_bit_for_bit():
    from screwkit.core import _joint_rows_numba

    rng = np.random.default_rng(11)
    balls, _ = _balls(rng, 2 * 300)
    current = np.concatenate([balls.reshape(300, 6, 6), rng.normal(size=(300, 3, 6))], axis=1)
    current[:, 7, :3] = 0.0  # a couple
    columns = np.array([[0, 1, 2], [3, 4, 5]])
    point, length = np.array([0.3, -2.0, 1.5]), 7.5
    numpy_rows = unscaled_screws(current, length, point)
    numpy_rows[:, columns] = orthonormal_axes(numpy_rows[:, columns])
    compiled = np.empty(current.shape)
    _joint_rows_numba.joint_rows(current, length, point, columns, COUPLE_SQUARED_NORM, compiled)
    np.testing.assert_array_equal(compiled, numpy_rows)
    np.testing.assert_array_equal(joint_rows(current, length, point, columns), numpy_rows)  # (300: compiled)
    assert joint_rows(current[None], length, point, columns).shape == (1, *current.shape)


def test_a_ball_with_dependent_axes_gives_rows_the_table_refuses_on_both_paths():
    from screwkit.exceptions import ScrewkitValueError
    from screwkit.graphs.jointtable import JointSpec, JointTable

    current = np.zeros((1, 3, 6))
    current[0, :, :3] = [[1.0, 0, 0], [1.0, 0, 0], [0, 0, 1.0]]  # two axes along x: no 3-system
    numpy_rows = unscaled_screws(current, 1.0, np.zeros(3))
    numpy_rows[:, [[0, 1, 2]]] = orthonormal_axes(numpy_rows[:, [[0, 1, 2]]])  # (no warning raised)
    assert np.isnan(numpy_rows[0, 1:]).all() and np.isfinite(numpy_rows[0, 0]).all()
    if HAS_NUMBA:
        from screwkit.core import _joint_rows_numba

        compiled = np.empty(current.shape)
        _joint_rows_numba.joint_rows(current, 1.0, np.zeros(3), np.array([[0, 1, 2]]), COUPLE_SQUARED_NORM, compiled)
        np.testing.assert_array_equal(compiled, numpy_rows)
    with pytest.raises(ScrewkitValueError, match="`screws` to hold finite numbers"):  # as a model's joint_table builds it
        JointTable("B", "E", (JointSpec("S", "S", "B", "E", 3, False),), numpy_rows)
