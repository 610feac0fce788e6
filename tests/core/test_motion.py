"""Generic configurations of any twist graph (screwkit.core.motion): the loops close again, the mechanism
moved, and the answer follows rigid motions and changes of unit.

The loop-closure checks are independent of the module: a moved Delta must keep its rods' lengths
and its parallelograms (read from the S joints' centres, recovered from their screws here), a
moved four-bar its link lengths.
"""

import numpy as np
import pytest

from screwkit.core.kinematic_model import KinematicModel
from screwkit.core.mobility import generic_analyses
from screwkit.core.motion import generic_configurations, newton_closure, tangent_error
from screwkit.exceptions import ScrewkitValueError
from screwkit.graphs.joints import revolute
from screwkit.graphs.twistgraph import twist_graph

from .. import mechanisms as M
from .. import mechanisms_extra as X


def centre(rows):
    """The common point of three (or two) revolute screws through one point: least squares on
    ``s × r = -s0`` written out here (``s0 = r × s``)."""
    rows = np.asarray(rows)
    system = np.concatenate([np.array([[0, s[2], -s[1]], [-s[2], 0, s[0]], [s[1], -s[0], 0]]) for s in rows[:, :3]])
    return np.linalg.lstsq(system, np.concatenate(rows[:, 3:]), rcond=None)[0]


def test_a_moved_delta_keeps_its_rods_and_parallelograms():
    graph = X.delta([0.1, -0.05, -1.8])
    table = generic_configurations(graph, np.random.default_rng(3), 6)
    assert table.batch_shape[0] >= 5
    start = {name: centre(graph.edges[u, v, name]["joint"].screws) for u, v, name in graph.edges(keys=True) if name.startswith("S")}
    for k in range(table.batch_shape[0]):
        c = {name: centre(table[k].joint_screws(name)) for name in start}
        moved = max(np.linalg.norm(c[name] - start[name]) for name in start)
        assert moved > 1e-2  # it went somewhere
        for i in (1, 2, 3):
            assert np.linalg.norm(c[f"Sp{i}"] - c[f"Sm{i}"]) == pytest.approx(2.0, abs=1e-9)  # the rod length
            assert np.allclose(c[f"Sp{i}"] - c[f"Sm{i}"], c[f"Sq{i}"] - c[f"Sn{i}"], atol=1e-9)  # a parallelogram
            assert np.linalg.norm(c[f"Sm{i}"] - c[f"Sn{i}"]) == pytest.approx(0.2, abs=1e-9)
        platform = [c[f"Sp{i}"] - c[f"Sq{i}"] for i in (1, 2, 3)]
        start_platform = [start[f"Sp{i}"] - start[f"Sq{i}"] for i in (1, 2, 3)]
        assert np.allclose(platform, start_platform, atol=1e-9)  # the platform only translates


def test_generic_analyses_keep_the_mechanisms_generic_orders():
    analyses = generic_analyses(M.planar_3rpr(M.PLANAR_BASE, M.PLANAR_PLATFORM), np.random.default_rng(0), 4)
    assert [(a.platform_order, a.constraint_order, a.global_order) for a in analyses] == [(3, 3, 6)] * len(analyses)


def test_configurations_follow_rigid_motions_and_units():
    graph = X.delta([0.1, -0.05, -1.8])
    rotation, translation, factor = M.rotation_about([1.0, 2.0, 0.5], 0.7), np.array([0.3, -1.0, 2.0]), 1000.0
    plain = generic_configurations(graph, np.random.default_rng(9), 3)
    moved = generic_configurations(M.moved(graph, rotation, translation, factor), np.random.default_rng(9), 3)
    for k in range(3):
        for name in ("Sp1", "Sq2", "A3"):
            expected = np.asarray(plain[k].joint_screws(name))
            if name.startswith("S"):
                expected_centre = (rotation @ centre(expected) + translation) * factor
                assert np.allclose(centre(moved[k].joint_screws(name)), expected_centre, atol=1e-6)
            else:
                axis = np.asarray(moved[k].joint_screws(name))[0, :3]
                assert np.allclose(np.abs(axis), np.abs(rotation @ expected[0, :3]), atol=1e-9)


def test_a_four_bar_keeps_its_link_lengths():
    points = {"A": [0, 0, 0], "B": [1, 0, 0], "C": [3, 2, 0], "D": [3, 0, 0]}
    graph = twist_graph("ground", "coupler", [
        ("ground", "crank", revolute("A", [0, 0, 1], points["A"], actuated=True)),
        ("crank", "coupler", revolute("B", [0, 0, 1], points["B"])),
        ("ground", "rocker", revolute("D", [0, 0, 1], points["D"])),
        ("rocker", "coupler", revolute("C", [0, 0, 1], points["C"])),
    ], dof=1)
    table = generic_configurations(graph, np.random.default_rng(1), 4)

    def where(k, name):  # a z axis (0, 0, 1; y, -x, 0) through (x, y)
        row = table[k].joint_screws(name)[0]
        return np.array([-row[4], row[3]])

    for k in range(table.batch_shape[0]):
        assert np.allclose(where(k, "A"), [0, 0]) and np.allclose(where(k, "D"), [3, 0])
        assert np.linalg.norm(where(k, "B") - where(k, "A")) == pytest.approx(1.0, abs=1e-9)
        assert np.linalg.norm(where(k, "C") - where(k, "B")) == pytest.approx(np.hypot(2, 2), abs=1e-9)
        assert np.linalg.norm(where(k, "C") - where(k, "D")) == pytest.approx(2.0, abs=1e-9)
        assert np.linalg.norm(where(k, "B") - [1, 0]) > 1e-3


def test_error_a_structure_that_cannot_move():
    triangle = twist_graph("ground", "top", [
        ("ground", "a", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
        ("a", "top", revolute("R2", [0, 0, 1], [1, 0, 0])),
        ("ground", "top", revolute("R3", [0, 0, 1], [0, 1, 0])),
    ], dof=1)
    with pytest.raises(ScrewkitValueError, match="Expected a mechanism that can move"):
        generic_configurations(triangle, np.random.default_rng(0), 2)


def _null(matrix, tol=1e-9):
    """Orthonormal null-space basis (columns), by an SVD written here."""
    _, sigma, vt = np.linalg.svd(matrix)
    return vt[int(np.sum(sigma > tol * sigma[0])):].T


@pytest.mark.parametrize("angle", [1e-2, 1e-4])
def test_tangent_error_bounds_how_far_the_first_order_motions_turn(angle):
    # Tsai's 3-UPU in its base plane: turned by `angle` about z it is a configuration of its planar
    # mode `angle` (in joint-space terms, the loop-closure matrix's smallest nonzero singular value)
    # from where the planar and translating modes meet. Pushed off it by delta along the direction
    # of that singular value, the loops open by sigma * delta, and the joint rates they allow turn by
    # about delta / sigma (measured here as the sine of the largest principal angle between the null
    # spaces): tangent_error = |F| / sigma^2 must bound that turn, within a small factor
    model = KinematicModel(M.tsai_3upu((0.1, 0.05, 0.0)))
    start = np.zeros((1, model.size))
    state = model.state(start)
    allowed = _null(model.loop_jacobian(state)[0])
    platform = model.link_jacobian(state, "platform")[0] @ allowed  # the platform's twists (scaled)
    about_z = allowed @ np.linalg.lstsq(platform, [0, 0, 1.0, 0, 0, 0], rcond=None)[0]
    turned, residual = newton_closure(model, start + angle * about_z / np.max(np.abs(about_z)), tolerance=0.0)
    assert residual[0] < 1e-15
    _, sigma, vt = np.linalg.svd(model.loop_jacobian(model.state(turned))[0])
    assert sigma[-1] < angle  # next to the transition set
    assert tangent_error(model, turned)[0] < 1e-8  # closed to round-off: far below any rank tolerance
    rates = _null(model.loop_jacobian(model.state(turned))[0])
    for delta in (1e-12, 1e-10, 1e-8):
        off = turned + delta * vt[len(sigma) - 1]  # the normal direction of the smallest sigma
        moved_rates = _null(model.loop_jacobian(model.state(off))[0])
        turn = np.linalg.norm(moved_rates - rates @ (rates.T @ moved_rates), 2)
        error = tangent_error(model, off)[0]
        assert error == pytest.approx(delta / sigma[-1], rel=1e-3)  # |F| = sigma delta
        assert error / 10 < turn <= error


def test_tangent_error_refuses_theta_of_the_wrong_shape():
    model = KinematicModel(M.tsai_3upu((0.1, 0.05, 0.5)))
    with pytest.raises(ScrewkitValueError, match=r"`theta` of shape \(B, 15\)"):
        tangent_error(model, np.zeros(model.size))
