"""Condition maps (``"condition:K"``) evaluated over the batch: against paper 002 and a 6×6 determinant.

Expected values come from paper 002's Eq. (6) and Eq. (7) and the paper's six wrenches (Eq. 4),
computed in tests/robots/test_h4.py from the parallelograms' plane normals and the limbs' kinematics,
independently of the code under test; the near-zero poses come from root searches on those
equations (tests/singular_surfaces.py). The single-pose evaluation (a batch of one through the same
code) must give each batched value.
"""

import json

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import quantities as Q
from screwkit.analysis import workspace as W
from screwkit.core.wrench_systems import analyze_table
from screwkit.exceptions import DegenerateGeometryError
from screwkit.gca.condition_patterns import bracket_polynomial
from screwkit.gca.diagram_points import batch_diagram_points, diagram_points
from screwkit.interface.cli import main

from ..robots.test_h4 import case_b_pose, paper_002_conditions, paper_wrench_matrix
from ..singular_surfaces import near_surface_poses, surface_roots

H4_MECHANISM = sk.load_mechanism("h4")
#: The first poses of the fixture are random catalog poses: their median sets the typical size.
GENERIC = 60


def typical(values):
    """The median size of ``values`` over the generic poses (the scale of their round-off)."""
    return np.median(np.abs(values[:GENERIC]))


def assert_equal_up_to_one_sign(values, expected, **tolerances):
    """``values == ±expected`` with one sign for every pose: a condition carried continuously over
    the motion (paper 002's Eq. 6 changes sign only at its zeros, and so must the condition)."""
    sign = np.sign(np.sum(values * expected))
    np.testing.assert_allclose(values, sign * expected, **tolerances)


@pytest.fixture(scope="module")
def h4_poses():
    """Random catalog poses and poses at 1e-12 … 1e-4 (relative) on both sides of roots of
    Eq. (6) and of Eq. (7)."""
    rng = np.random.default_rng(20261121)
    near = [near_surface_poses(surface_roots(rng, s, 2)).poses for s in ("constraint", "actuation")]
    return np.concatenate([H4_MECHANISM.random_poses(rng, GENERIC), *near])


def test_condition_maps_are_paper_002_equations_6_and_7_near_their_zeros(h4_poses):
    first, ok_first = W.evaluate(H4_MECHANISM, h4_poses, "condition:0")
    second, ok_second = W.evaluate(H4_MECHANISM, h4_poses, "condition:1")
    assert ok_first.all() and ok_second.all()
    eq6, eq7, _, _ = paper_002_conditions(H4_MECHANISM.configuration(h4_poses))
    assert np.abs(eq6).min() < 1e-10 * typical(eq6)  # the batch reaches each zero
    assert np.abs(eq7).min() < 1e-10 * typical(eq7)
    # [gikj] = (i × k)·j with i, k the points s12 = n1 × n2, s34 = n3 × n4 of unit plane normals, each
    # oriented by its parallelogram over the motion: paper 002 Eq. (6) itself; the actuation factor is
    # Eq. (7) itself (unit actuation directions): equal with one sign over all poses (continuous, a
    # sign change only at the zeros), to round-off of the equations' own size (1e-12 of their typical
    # value) at the zeros
    for value, equation in ((first, eq6), (second, eq7)):
        assert_equal_up_to_one_sign(value, equation, rtol=1e-9, atol=1e-12 * typical(equation))


def test_condition_product_is_the_six_by_six_determinant_of_the_wrench_lines(h4_poses):
    # the superbracket -[gikj][a b d ḟ][c g ḣ j] is the 6×6 determinant of the diagram's lines,
    # which are the paper's six wrenches (Eq. 4), the couples (0; z × s12), (0; z × s34) included
    first, _ = W.evaluate(H4_MECHANISM, h4_poses, "condition:0")
    second, _ = W.evaluate(H4_MECHANISM, h4_poses, "condition:1")
    configurations = [H4_MECHANISM.configuration(pose) for pose in h4_poses]
    six = np.array([np.linalg.det(paper_wrench_matrix(cfg)) for cfg in configurations])
    assert_equal_up_to_one_sign(first * second, six, rtol=1e-9, atol=1e-12 * typical(six))


@pytest.mark.parametrize("name", ["h4", "mcgill_smg", "peppermill", "planar_3rrp", "ragnar"])
def test_batched_conditions_equal_the_single_pose_evaluation(name, h4_poses):
    mechanism = sk.load_mechanism(name)
    diagram, conditions, _, _ = Q.conditions_of(mechanism, {})
    rng = np.random.default_rng(7)
    poses = h4_poses[::8] if name == "h4" else mechanism.random_poses(rng, 8)
    posed = mechanism.at(poses)
    for k, condition in enumerate(conditions):
        batched, ok = W.evaluate(mechanism, poses, f"condition:{k}")
        assert ok.all()
        single = [condition.evaluate(diagram_points(diagram.points, posed[i].analysis)) for i in range(len(poses))]
        np.testing.assert_allclose(batched, single, rtol=1e-12, atol=0)
        assert np.all(batched != 0)


def test_each_bracket_is_a_batched_four_by_four_determinant(h4_poses):
    # the factor as a bracket polynomial (every bracket a 4×4 determinant over the batch) equals
    # its proved constant times the vector form the maps evaluate
    diagram, conditions, _, _ = Q.conditions_of(H4_MECHANISM, {})
    posed = H4_MECHANISM.at(h4_poses)
    points = batch_diagram_points(diagram.points, analyze_table(posed.joints))
    for condition in conditions:
        polynomial = bracket_polynomial(condition.factor).evaluate(points)
        form = condition.evaluate(points)
        assert polynomial.shape == form.shape == (len(h4_poses),)
        expected = float(condition.constant) * form
        np.testing.assert_allclose(polynomial, expected, rtol=1e-9, atol=1e-12 * typical(polynomial))


def test_condition_map_names_the_missing_point_and_the_pose():
    # paper 002 case (b): the limb of A1 is at a serial singularity, so its actuation line (and
    # the point where it meets the axis of R_I) does not exist there
    poses = np.array([[0.0, 0.0, -750.0, 0.0], case_b_pose()])
    assert H4_MECHANISM.at(poses[1]).codes[0] & 4
    with pytest.raises(DegenerateGeometryError, match=r"point a \(where the actuation A1 meets") as err:
        W.evaluate(H4_MECHANISM, poses, "condition:0")
    assert str(case_b_pose()[0]) in str(err.value) and "missing at the pose" in str(err.value)


def test_cli_condition_map_is_paper_002_equation_6(tmp_path, capsys):
    # across the constraint surface (x = y = 300 mm, phi up to 90°): Eq. (6) changes sign there
    out = tmp_path / "condition.json"
    argv = ["map", "h4", "--quantity", "condition", "--z", "-560", "-470", "--phi", "60", "90",
            "--x", "300", "--y", "300", "--grid", "6", "--out", str(out), "--no-progress"]
    assert main(argv) == 0
    printed = json.loads(out.read_text())
    assert printed["quantity"] == "condition:0"
    z, phi = np.meshgrid(printed["x"]["values"], printed["y"]["values"])
    poses = np.stack([np.full_like(z, 300.0), np.full_like(z, 300.0), z, np.radians(phi)], axis=-1)
    values = np.array(printed["values"], dtype=float)
    reached = np.isfinite(values)
    eq6, _, _, _ = paper_002_conditions(H4_MECHANISM.configuration(poses[reached]))
    assert (eq6 > 0).any() and (eq6 < 0).any()
    assert_equal_up_to_one_sign(values[reached], eq6, rtol=1e-9, atol=1e-12)
    assert "written to" in capsys.readouterr().out
