"""Single-pose and batched verdicts agree everywhere, also near the H4's singular surfaces (issue 8).

The single-pose answer is ``sk.classify(graph)`` of each pose's twist graph; the batched answer is
``h4.at(poses).singularities`` over the same poses (the batched inverse kinematics, the joint
table, the analysis core in chunks).
They must be **identical**: labels, constraint order, global order and serial flags exactly,
closeness values within 1e-12 absolute.

The pose set (built once per module): generic poses of the catalog workspace, the roots of the
constraint, actuation and serial surfaces of :mod:`tests.singular_surfaces`, and poses at relative
distances 1e-12 … 1e-4 on both sides of each root (only inside the reach for the serial surface).

The *correct* verdict is checked independently where it is clear-cut (margins ``CONSTRAINT_MARGIN``, ``ACTUATION_MARGIN``):

* **constraint**: the H4's constraint system is spanned by the two horizontal couples
  ``z × s12`` and ``z × s34`` of its compound legs (paper 002 Eq. 3; checked in
  ``test_h4.test_structure_at_fifty_random_poses``), so the constraint closeness (σ2/σ1 of the two
  unit couples) is ``sqrt((1 − |c|) / (1 + |c|))`` with ``c`` the cosine of the angle between them:
  a closed form, evaluated with mpmath at 50 digits from the configuration's ``u_i`` and ``w_i``
  (the plane normals ``n_i = u_i × w_i``). It vanishes exactly where Eq. (6) does. Where it is
  ≥ ``CONSTRAINT_MARGIN · rtol`` the constraint system has its full order 2; where it is
  ≤ ``rtol / CONSTRAINT_MARGIN`` (at the roots of Eq. 6) it has order 1. The closed form assumes
  no limb is serially singular, so the serial family's poses are left out.
* **actuation**: σ6/σ1 at 50 digits (``mpmath.svd_r``) of the paper's six wrenches
  (``test_h4.paper_wrench_matrix``: two constraint couples, four actuation forces), about the end
  effector's point with moments over the rod length and each row normalised. This frame is not the
  library's (its reference point and length come from ``twistgraph.axes_frame``), so the two
  measures differ by a bounded factor (``test_actuation_truth_measure_tracks_the_library_s``
  bounds it); with the margin, ≥ ``ACTUATION_MARGIN · rtol`` means global order 6 and ≤
  ``rtol / ACTUATION_MARGIN`` means global order 5.

The full parity test makes 10,060 single-pose calls. Before the one core (issue 8) the two paths
disagreed in every field near the surfaces: at the constraint surface (d = 1e-6, 1e-7) the
single-pose path said "constraint" where the 50-digit truth says regular; at the actuation
surface (d = 1e-8) and at the reach edge serial flags, orders and closeness differed. Now a single
pose is a batch of one through the same kernels (:func:`screwkit.core.wrench_systems.analyze_table`).
"""

import os
from collections import Counter

import mpmath
import numpy as np
import pytest

import screwkit as sk
from screwkit.robots.families.four_limb.joints import PAPER_002_LEGS

from ..robots.test_h4 import paper_wrench_matrix
from ..singular_surfaces import (
    DISTANCES,
    H4,
    NearSurfacePoses,
    all_near_surface_poses,
    conditions,
    reachable,
)

RTOL = 1e-9  # the default of classify and classify_poses (backend.DEFAULT_RTOL)
CLOSENESS_ATOL = 1e-12
CONSTRAINT_MARGIN = 1e2  # the closed form is exact and frame-free
ACTUATION_MARGIN = 1e3  # our frame is not the library's (a factor < 10 between them, tested below)
KEYS = ("constraint", "actuation", "serial")


# the pose set ------------------------------------------------------------------------------------
def pose_set(seed, generic, roots_per_surface, distances=DISTANCES):
    """Generic workspace poses, surface roots (distance 0) and near-surface poses, as one set."""
    rng = np.random.default_rng(seed)
    near, roots = all_near_surface_poses(rng, roots_per_surface, distances=distances)
    at_roots = [
        NearSurfacePoses(r.poses, np.full(len(r.poses), s), np.arange(len(r.poses)), np.zeros(len(r.poses)),
                         np.zeros(len(r.poses)), np.zeros(len(r.poses)))
        for s, r in roots.items()
    ]
    poses = H4.random_poses(rng, 2 * generic)
    poses = poses[reachable(H4.parameters, poses)][:generic]
    nan = np.full(len(poses), np.nan)
    workspace = NearSurfacePoses(poses, np.full(len(poses), "generic"), np.zeros(len(poses), int), nan, nan, nan)
    return NearSurfacePoses.concatenate([workspace, *at_roots, near])


def single_answers(poses, actuated, *, same_configuration=True):
    """One ``sk.classify(graph)`` call per pose. With ``same_configuration`` the graph is the batch's
    own configuration of that pose (``H4.joints(poses).graph(i)``); else ``H4.twist_graph(pose)``
    solves the inverse kinematics again for the pose alone."""
    labels, corder, gorder, serial = [], [], [], []
    closeness = {key: [] for key in KEYS}
    table = H4.joints(poses) if same_configuration else None
    for i, pose in enumerate(poses):
        graph = table.graph(i) if table is not None else H4.twist_graph(pose)
        report = sk.classify(graph)
        labels.append(report.labels)
        corder.append(report.constraint_order)
        gorder.append(report.global_order)
        flagged = {s.actuated_joint for s in report.serial}
        serial.append([name in flagged for name in actuated])
        for key in KEYS:
            closeness[key].append(report.closeness[key])
    return {
        "labels": labels, "constraint_order": np.array(corder), "global_order": np.array(gorder),
        "serial": np.array(serial), "closeness": {k: np.array(v) for k, v in closeness.items()},
    }


def batch_answers(poses):
    report = H4.at(poses).singularities  # the whole batch, chunked inside
    return {
        "labels": report.labels.tolist(),
        "constraint_order": report.constraint_order,
        "global_order": report.global_order,
        "serial": report.serial_flags,
        "closeness": {k: report.closeness[k] for k in KEYS},
        "actuated_joints": report.actuated_joints,
    }


def mismatches(field, single, batch):
    """Indices where the two answers differ in ``field``."""
    if field == "labels":
        return np.array([a != b for a, b in zip(single["labels"], batch["labels"], strict=True)])
    if field == "serial":
        return (single["serial"] != batch["serial"]).any(axis=1)
    if field.startswith("closeness"):
        key = field.split(":")[1]
        return ~(np.abs(single["closeness"][key] - batch["closeness"][key]) <= CLOSENESS_ATOL)
    return single[field] != batch[field]


def where(poses, mask):
    """'surface d=… side=…: count' per group of poses in ``mask``: the reproducer in a failure."""
    groups = Counter(zip(poses.surface[mask], poses.distance[mask], poses.side[mask], strict=True))
    return "; ".join(f"{s} d={d:.0e} side={side:+.0f}: {n}" for (s, d, side), n in sorted(groups.items()))


def check_parity(field, poses, single, batch):
    bad = mismatches(field, single, batch)
    first = np.flatnonzero(bad)[:3]
    examples = [
        (poses.poses[i].tolist(), single["labels"][i], batch["labels"][i],
         {k: (single["closeness"][k][i], batch["closeness"][k][i]) for k in KEYS})
        for i in first
    ]
    assert not bad.any(), f"{field}: {bad.sum()} of {len(bad)} poses differ ({where(poses, bad)}); e.g. {examples}"


# independent truth (50 digits) -------------------------------------------------------------------
def _mp_cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _mp_unit(a):
    size = mpmath.sqrt(sum(x * x for x in a))
    return [x / size for x in a]


def constraint_closeness_50_digits(poses):
    """σ2/σ1 of the two unit constraint couples z × s12, z × s34, from u_i, w_i at 50 digits."""
    config = H4.configuration(poses)
    values = []
    with mpmath.workdps(50):
        z = [mpmath.mpf(0), mpmath.mpf(0), mpmath.mpf(1)]
        for u, w in zip(config.u, config.w, strict=True):
            n = [_mp_cross([mpmath.mpf(x) for x in u[i]], [mpmath.mpf(x) for x in w[i]]) for i in range(4)]
            leg = {k: n[v - 1] for k, v in PAPER_002_LEGS.items()}
            m1 = _mp_unit(_mp_cross(z, _mp_cross(leg["l1"], leg["l2"])))
            m2 = _mp_unit(_mp_cross(z, _mp_cross(leg["l3"], leg["l4"])))
            c = abs(sum(a * b for a, b in zip(m1, m2, strict=True)))
            values.append(float(mpmath.sqrt((1 - c) / (1 + c))))
    return np.array(values)


def actuation_closeness_50_digits(poses):
    """σ6/σ1 of the paper's six unit wrenches about the end effector, moments over the rod length."""
    values = []
    length = H4.parameters.rod_length
    for pose in poses:
        rows = paper_wrench_matrix(H4.configuration(pose))
        with mpmath.workdps(50):
            point = [mpmath.mpf(x) for x in pose[:3]]
            scaled = []
            for row in rows:
                force = [mpmath.mpf(x) for x in row[:3]]
                moment = [mpmath.mpf(x) for x in row[3:]]
                about = _mp_cross(force, point)  # m_P = m_O − P × f = m_O + f × P
                scaled.append(_mp_unit(force + [(m + a) / length for m, a in zip(moment, about, strict=True)]))
            sigma = mpmath.svd_r(mpmath.matrix(scaled), compute_uv=False)
            values.append(float(sigma[5] / sigma[0]))
    return np.array(values)


# fixtures ----------------------------------------------------------------------------------------
#: ``SCREWKIT_PARITY=full`` runs the issue's ≥ 10,000 poses (``python bench/bench_parity.py``, a few
#: minutes); the default suite runs the same construction on ~2,000 poses.
FULL = os.environ.get("SCREWKIT_PARITY") == "full"


@pytest.fixture(scope="module")
def full_poses():
    if FULL:
        poses = pose_set(20261121, generic=4300, roots_per_surface=120)
        assert len(poses) >= 10_000
    else:
        poses = pose_set(20261121, generic=800, roots_per_surface=25)
        assert len(poses) >= 2_000
    return poses


@pytest.fixture(scope="module")
def full_batch(full_poses):
    return batch_answers(full_poses.poses)


@pytest.fixture(scope="module")
def full_single(full_poses, full_batch):
    return single_answers(full_poses.poses, full_batch["actuated_joints"])


@pytest.fixture(scope="module")
def full_single_own_ik(full_poses, full_batch):
    return single_answers(full_poses.poses, full_batch["actuated_joints"], same_configuration=False)


@pytest.fixture(scope="module")
def truth(full_poses):
    """The 50-digit measures; actuation not at the serial family's poses (a limb's force degenerates)."""
    constraint = constraint_closeness_50_digits(full_poses.poses)
    actuation = np.full(len(full_poses), np.nan)
    chosen = full_poses.surface != "serial"
    actuation[chosen] = actuation_closeness_50_digits(full_poses.poses[chosen])
    return {"constraint": constraint, "actuation": actuation}


@pytest.fixture(scope="module")
def fast_poses():
    # the distances at which both paths agree today (≥ 1e-5); without the serial roots, where the
    # closeness measures differ today (the full test reports them)
    poses = pose_set(7, generic=252, roots_per_surface=4, distances=np.array([1e-5, 1e-4]))
    return poses.select(~((poses.surface == "serial") & (poses.distance == 0)))


@pytest.fixture(scope="module")
def fast_answers(fast_poses):
    batch = batch_answers(fast_poses.poses)
    return single_answers(fast_poses.poses, batch["actuated_joints"]), batch


# parity ------------------------------------------------------------------------------------------
FIELDS = ["labels", "constraint_order", "global_order", "serial", *(f"closeness:{k}" for k in KEYS)]


@pytest.mark.parametrize("field", FIELDS)
def test_single_and_batched_answers_are_identical(field, full_poses, full_single, full_batch):
    check_parity(field, full_poses, full_single, full_batch)


@pytest.mark.parametrize("field", ["labels", "constraint_order", "global_order", "serial"])
def test_verdicts_are_identical_when_each_pose_solves_its_own_inverse_kinematics(
    field, full_poses, full_single_own_ik, full_batch
):
    """The user's single-pose route, ``classify(h4.twist_graph(pose))``, solves the IK for one pose.
    At the reach edge (a fold: joint angles go as the square root of the distance) the IK of one
    pose and of a batch differ in the last bits (numpy's vectorised transcendental functions), and
    the fold amplifies that to ~1e-9 in the closeness measures; the verdicts stay identical."""
    check_parity(field, full_poses, full_single_own_ik, full_batch)


@pytest.mark.parametrize("field", FIELDS)
def test_single_and_batched_answers_are_identical_fast(field, fast_poses, fast_answers):
    assert len(fast_poses) == 300
    check_parity(field, fast_poses, *fast_answers)


def test_generic_poses_agree(full_poses, full_single, full_batch):
    """Away from the surfaces the two paths already agree in every field (the regression guard)."""
    generic = full_poses.surface == "generic"
    part = full_poses.select(generic)
    pick = {
        "labels": [x for x, g in zip(full_single["labels"], generic, strict=True) if g],
        "constraint_order": full_single["constraint_order"][generic],
        "global_order": full_single["global_order"][generic],
        "serial": full_single["serial"][generic],
        "closeness": {k: v[generic] for k, v in full_single["closeness"].items()},
    }
    other = {
        "labels": [x for x, g in zip(full_batch["labels"], generic, strict=True) if g],
        "constraint_order": full_batch["constraint_order"][generic],
        "global_order": full_batch["global_order"][generic],
        "serial": full_batch["serial"][generic],
        "closeness": {k: v[generic] for k, v in full_batch["closeness"].items()},
    }
    for field in FIELDS:
        check_parity(field, part, pick, other)


# the correct verdict -----------------------------------------------------------------------------
def test_pose_set_straddles_the_surfaces(full_poses):
    """Each near-surface pair lies on opposite sides of its surface (the sign of Eq. 6 or 7)."""
    eq6, eq7 = conditions(full_poses.poses)
    for surface, values in (("constraint", eq6), ("actuation", eq7)):
        mine = (full_poses.surface == surface) & (full_poses.distance > 0)
        signs = np.sign(values[mine]) * full_poses.side[mine]
        roots = full_poses.root[mine]
        for k in np.unique(roots):
            assert len(set(signs[roots == k])) == 1, f"{surface} root {k}: a pose on the wrong side"


def test_constraint_truth_measure_is_the_library_s(full_poses, full_batch, truth):
    """The closed form is the closeness both paths compute (at the generic poses, where they agree)."""
    generic = full_poses.surface == "generic"
    np.testing.assert_allclose(full_batch["closeness"]["constraint"][generic], truth["constraint"][generic],
                               rtol=0, atol=1e-12)


def test_actuation_truth_measure_tracks_the_library_s(full_poses, full_batch, truth):
    """Our frame's σ6/σ1 and the library's differ by less than a factor 10 (so the margin holds)."""
    chosen = ~np.isnan(truth["actuation"]) & (truth["actuation"] > 1e-10)
    ratio = full_batch["closeness"]["actuation"][chosen] / truth["actuation"][chosen]
    assert 0.1 < ratio.min() and ratio.max() < 10.0


def truth_violations(answers, full_poses, truth):
    valid = full_poses.surface != "serial"  # the closed form assumes no serially singular limb
    regular_c = valid & (truth["constraint"] >= CONSTRAINT_MARGIN * RTOL)
    singular_c = valid & (truth["constraint"] <= RTOL / CONSTRAINT_MARGIN)
    regular_a = regular_c & (truth["actuation"] >= ACTUATION_MARGIN * RTOL)
    singular_a = regular_c & (truth["actuation"] <= RTOL / ACTUATION_MARGIN)
    labels = answers["labels"]
    has = {key: np.array([key in x for x in labels]) for key in ("constraint", "actuation")}
    wrong = (
        (regular_c & ((answers["constraint_order"] != 2) | has["constraint"]))
        | (singular_c & ((answers["constraint_order"] != 1) | ~has["constraint"]))
        | (regular_a & ((answers["global_order"] != 6) | has["actuation"]))
        | (singular_a & ((answers["global_order"] != 5) | ~has["actuation"]))
    )
    n = len(full_poses)
    assert regular_c.sum() > n / 2 and regular_a.sum() > 0.4 * n
    assert singular_c.sum() >= n / 100 and singular_a.sum() >= n / 100
    return wrong


def test_batched_verdicts_are_correct(full_poses, full_batch, truth):
    wrong = truth_violations(full_batch, full_poses, truth)
    assert not wrong.any(), f"{wrong.sum()} wrong verdicts: {where(full_poses, wrong)}"


def test_single_pose_verdicts_are_correct(full_poses, full_single, truth):
    wrong = truth_violations(full_single, full_poses, truth)
    assert not wrong.any(), f"{wrong.sum()} wrong verdicts: {where(full_poses, wrong)}"
