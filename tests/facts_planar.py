"""Family facts of the planar 3-RRP catalog entry (paper 003), evaluated by tests/robots/test_catalog.py.

``FACTS = {fact name: check(mechanism, fact) -> (got, expected)}``. The twist-graph results are
compared with paper 003's own instant-centre and Jacobian results (``tests/paper_003.py``), which
are computed without screw systems.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from screwkit.algebra import screw as S
from screwkit.core.singularity import classify_table
from screwkit.core.wrenches import wrench_analysis
from screwkit.gca.diagram_points import diagram_points
from screwkit.gca.superbracket_analysis import superbracket_analysis
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.planar_3rrp.configuration import Planar3RRPConfiguration
from screwkit.robots.families.planar_3rrp.joints import joints
from screwkit.robots.families.planar_3rrp.kinematics import WORKING_MODES

from .paper_003 import classify, jacobians

SEED = 20261121


def random_configuration(mechanism, count: int, seed: int = SEED):
    """The configuration at random poses of the workspace box (all reachable: see the TOML)."""
    return mechanism.configuration(mechanism.random_poses(np.random.default_rng(seed), count))


def check_actuation_wrenches_are_kennedy_lines(mechanism, fact):
    """At random workspace poses the actuation wrench of limb k is a zero-pitch line through the
    elbow A_k = C_ij, perpendicular to the guide b_k and in the plane z = 0 (paper 003's t_k)."""
    config = random_configuration(mechanism, 8)
    ok = True
    for index in range(8):
        analysis = wrench_analysis(joints(config).graph((index,)))
        for k, limb in enumerate(analysis.limbs):
            assert limb.actuated_joint == f"limb{k + 1}_R1"
            point, direction = S.axis(limb.actuation_wrench)
            elbow = np.append(config.elbow_points[index, k], 0.0)
            guide = np.append(config.guide_directions[index, k], 0.0)
            ok &= bool(abs(direction @ guide) < 1e-9 and abs(direction[2]) < 1e-9)
            ok &= bool(np.linalg.norm(np.cross(point - elbow, direction)) < 1e-9)
            ok &= bool(abs(S.pitch(limb.actuation_wrench)) < 1e-9)
    return ok, fact["value"]


def check_labels_match_instant_centre_types(mechanism, fact):
    """Over random workspace poses in all eight working modes, the twist-graph labels (vectorized
    :func:`classify_table`) agree with the family's classification: regular <-> no label, inverse
    <-> serial, direct <-> actuation, combined <-> both."""
    poses = mechanism.random_poses(np.random.default_rng(SEED), 40)
    config = Planar3RRPConfiguration.from_pose(mechanism.parameters, poses[:, None, :], WORKING_MODES)
    kinds = classify(config).kind.ravel()
    labels = classify_table(joints(config)).labels.ravel().tolist()
    expected = {
        "regular": (),
        "inverse": ("serial",),
        "direct": ("actuation",),
        "combined": ("actuation", "serial"),
    }
    return all(expected[str(kind)] == label for kind, label in zip(kinds, labels, strict=True)), fact["value"]


@lru_cache(maxsize=2)
def superbracket(source: str):
    """The superbracket analysis of the entry at its default pose (cached: about a second)."""
    mechanism = load_mechanism(source)
    diagram, sampler = mechanism.wrench_diagram()
    return diagram, superbracket_analysis(diagram, sampler)


def condition_values(mechanism, count: int = 12) -> tuple[np.ndarray, np.ndarray]:
    """Each superbracket condition's vector form at random workspace poses, and det K there."""
    diagram, result = superbracket(mechanism.source)
    config = random_configuration(mechanism, count)
    values = []
    for index in range(count):
        points = diagram_points(diagram.points, wrench_analysis(joints(config).graph((index,))))
        values.append([float(c.evaluate(points)) for c in result.conditions])
    det_k = np.linalg.det(jacobians(config)[1])
    return np.array(values), det_k


def check_superbracket_factor_labels(mechanism, fact):
    """The labels of the factors of the simplified superbracket, in order."""
    return list(superbracket(mechanism.source)[1].labels), fact["value"]


def check_superbracket_constraint_factor_never_vanishes(mechanism, fact):
    """The constraint factor (planarity: two horizontal couples and a vertical force) is +-1 on unit
    directions at every pose: a planar mechanism cannot lose its planar constraints."""
    _, result = superbracket(mechanism.source)
    values, _ = condition_values(mechanism)
    column = [i for i, label in enumerate(result.labels) if label == "constraint"]
    return bool(len(column) == 1 and np.allclose(np.abs(values[:, column[0]]), 1.0, atol=1e-12)), fact[
        "value"
    ]


def check_superbracket_actuation_factor_equals_det_k(mechanism, fact):
    """The actuation factor equals +-det K of paper 003, Eq. (11b), which vanishes exactly when the
    three Kennedy lines t_k are concurrent (Sec. 4.2): |factor| = |det K| at random poses."""
    _, result = superbracket(mechanism.source)
    values, det_k = condition_values(mechanism)
    column = [i for i, label in enumerate(result.labels) if label == "actuation"]
    ok = len(column) == 1 and np.allclose(np.abs(values[:, column[0]]), np.abs(det_k), rtol=1e-9, atol=0)
    return bool(ok), fact["value"]


FACTS = {
    "actuation_wrenches_are_kennedy_lines": check_actuation_wrenches_are_kennedy_lines,
    "labels_match_instant_centre_types": check_labels_match_instant_centre_types,
    "superbracket_factor_labels": check_superbracket_factor_labels,
    "superbracket_constraint_factor_never_vanishes": check_superbracket_constraint_factor_never_vanishes,
    "superbracket_actuation_factor_equals_det_K": check_superbracket_actuation_factor_equals_det_k,
}
