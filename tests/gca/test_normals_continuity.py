"""The ``normals`` points of the four-limb diagrams (``i = n_a × n_b``, paper 002 §5.1) carried over the
motion with their magnitude and one sign: the constraint factor ``[gikj]`` is paper 002's Eq. (6),
``(s12 × s34)·z`` with ``s12 = n1 × n2`` of unit parallelogram normals, a continuous function that changes
sign only at its zeros.

Expected values are computed here from the limbs' kinematics, independently of screwkit's wrench code:
on the Veloce from the independent model of tests/analysis/certify_checks.py (rods w_i, actuated axes
u_i, n_i = w_i × u_i normalised; sub-platform I carries limbs 1 and 3, II limbs 2 and 4), on the Quattro
from paper 002's equations as tests/robots/test_h4.py writes them. The Veloce's zero of Eq. (6) is
solved by bisection on the independent model (``SOLVED``: lambda_I = (n1 × n3)·u1 = 0, where the rank
computation of test_certify_veloce shows the constraint order dropping from 2 to 1).
"""

import json

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis import quantities as Q
from screwkit.analysis import workspace as W
from screwkit.interface.report import analyze

from ..analysis.certify_checks import in_metres
from ..analysis.test_certify_veloce import AXES, MODEL, SOLVED, VELOCE, K
from ..robots.test_h4 import paper_002_conditions

START, END = np.array([300.0, -545.2, -226.3, -1.8]), np.array([500.0, -545.2, -226.3, -1.8])


def veloce_equation_6(pose):
    """(s_I × s_II)·k with s_I = n1 × n3, s_II = n2 × n4 and n_i = unit(w_i × u_i) (paper 002, Eq. 6)."""
    _, rods = MODEL.geometry(pose)
    n = np.cross(rods, AXES)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return float(np.cross(np.cross(n[0], n[2]), np.cross(n[1], n[3])) @ K)


def constraint_index(mechanism):
    _, conditions, labels, _ = Q.conditions_of(mechanism, {})
    (index,) = [k for k, label in enumerate(labels) if label == "constraint"]
    assert str(conditions[index].factor) == "[gikj]"
    return index


def test_veloce_constraint_factor_is_equation_6_and_changes_sign_only_at_its_zero():
    # x from 300 to 500 mm, the solved zero (near x = 398.5 mm) among the poses
    poses = np.vstack([START + t * (END - START) for t in np.linspace(0.0, 1.0, 81)] + [SOLVED])
    poses = poses[np.argsort(poses[:, 0])]
    values, ok = W.evaluate(VELOCE, poses, f"condition:{constraint_index(VELOCE)}")
    assert ok.all()
    expected = np.array([veloce_equation_6(pose) for pose in poses])
    scale = np.median(np.abs(expected))
    sign = np.sign(np.sum(values * expected))  # one sign over the whole path: continuous
    np.testing.assert_allclose(values, sign * expected, rtol=1e-9, atol=1e-12 * scale)
    at = int(np.flatnonzero(poses[:, 0] == SOLVED[0])[0])
    assert abs(values[at]) < 1e-12 * scale  # ≈ 0 at the zero, relative to its size on the path
    others = np.delete(values, at)
    assert np.abs(others).min() > 1e-4 * scale
    # one sign change, across the zero: before it one sign, after it the other
    assert len(set(np.sign(values[:at]))) == 1 and len(set(np.sign(values[at + 1 :]))) == 1
    assert np.sign(values[at - 1]) == -np.sign(values[at + 1])


def test_veloce_report_names_the_constraint_factor_at_its_singular_pose():
    full = analyze(VELOCE, SOLVED)
    report = full.superbracket
    k = constraint_index(VELOCE)
    assert report.labels[k] == "constraint" and report.vanishing[k] and not report.constant[k]
    assert not any(report.constant)  # "never vanishes" is set for no factor, at the pose or elsewhere
    assert [v for i, v in enumerate(report.vanishing) if i != k] == [False]
    assert abs(report.values[k]) < 1e-9 and abs(report.values[1 - k]) > 1e-3
    assert report.conditions[k].statement.startswith("i, k and j are collinear in the plane at infinity")
    text = str(full)
    assert "constraint singularity when [gikj] = 0  <- vanishes at this pose" in text
    assert "never vanishes" not in text and "constraint singularity (dof 4)" in text  # and the verdict
    printed = json.loads(json.dumps(report.to_dict()))
    condition = printed["conditions"][k]
    assert condition["label"] == "constraint" and condition["vanishes_at_pose"]
    assert condition["never_vanishes"] is False and condition["value_at_pose"] is not None
    latex = report.to_latex()
    assert r"\text{constraint}:\quad [gikj] = 0" in latex and "never" not in latex
    regular = analyze(VELOCE, START).superbracket
    assert not any(regular.constant) and not any(regular.vanishing)


def test_veloce_path_crossing_and_locus_carry_the_constraint_factor():
    check = sk.check_path(VELOCE, START, END)
    (constraint,) = [c for c in check.crossings if c.kind == "constraint"]
    assert constraint.factor == "[gikj]"
    assert abs(constraint.parameter - (SOLVED[0] - START[0]) / (END[0] - START[0])) < 1e-3
    found = sk.loci(VELOCE, x=("x", 300, 560, 14), y=("z", -300, -200, 6), fixed={"y": -545.2, "phi": -1.8})
    (locus,) = [locus for locus in found if locus.kind == "constraint"]
    assert locus.factor == "[gikj]" and len(locus.points) > 3
    for x, z in locus.points:  # on the independent Eq. (6)'s zero: a sign change across 1 mm in x
        below, above = (veloce_equation_6([x + dx, -545.2, z, -1.8]) for dx in (-0.5, 0.5))
        assert below * above < 0


def test_quattro_constraint_factor_is_equation_6_with_one_sign_across_a_constraint_crossing():
    quattro = sk.load_mechanism("quattro")
    k = constraint_index(quattro)
    rng = np.random.default_rng(11)
    # a segment between two reachable poses, reachable along its length, across which Eq. (6) changes sign
    t = np.linspace(0.0, 1.0, 61)
    for _ in range(200):
        start, end = quattro.random_poses(rng, 2)
        poses = start + t[:, None] * (end - start)
        if not quattro.reachable(poses).all():
            continue
        eq6 = paper_002_conditions(quattro.configuration(poses))[0]
        if eq6[0] * eq6[-1] < 0:
            break
    else:
        raise AssertionError("no segment across Eq. (6)'s zero among 200 random ones")
    values, ok = W.evaluate(quattro, poses, f"condition:{k}")
    assert ok.all()
    scale = np.median(np.abs(eq6))
    sign = np.sign(np.sum(values * eq6))
    np.testing.assert_allclose(values, sign * eq6, rtol=1e-9, atol=1e-12 * scale)
    # where it changes sign, bisected on Eq. (6): the condition ≈ 0 and the core says constraint there
    change = int(np.flatnonzero(np.sign(eq6[:-1]) != np.sign(eq6[1:]))[0])
    low, high = poses[change], poses[change + 1]
    for _ in range(60):
        middle = 0.5 * (low + high)
        if np.sign(paper_002_conditions(quattro.configuration(middle[None]))[0][0]) == np.sign(eq6[change]):
            low = middle
        else:
            high = middle
    value, _ = W.evaluate(quattro, middle[None], f"condition:{k}")
    assert abs(value[0]) < 1e-9 * scale
    assert quattro.at(middle[None]).codes[0] & 1


@settings(max_examples=4, deadline=None)
@given(t=st.floats(0.0, 1.0))
def test_veloce_constraint_factor_is_free_of_the_length_unit(t):
    # products of sines of angles between couples: the same number in mm and in m
    pose = START + t * (END - START)
    k = constraint_index(VELOCE)
    in_mm, _ = W.evaluate(VELOCE, pose[None], f"condition:{k}")
    in_m, _ = W.evaluate(in_metres(VELOCE), (pose * [1e-3, 1e-3, 1e-3, 1.0])[None], f"condition:{k}")
    np.testing.assert_allclose(in_m, in_mm, rtol=1e-9, atol=1e-12)
    expected = veloce_equation_6(pose)
    assert min(abs(in_mm[0] - expected), abs(in_mm[0] + expected)) <= 1e-9 * abs(expected) + 1e-12
