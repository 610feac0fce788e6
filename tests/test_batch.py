"""Batched labels: parity with the single-pose analysis, at regular and singular poses; errors."""

import numpy as np
import pytest

from screwkit.exceptions import ScrewkitValueError
from screwkit.families.four_limb import inverse_kinematics, joints
from screwkit.singularity import classify, classify_poses

from .test_h4 import H4, random_poses, singular_pose


def batch_inputs(poses):
    cfg = inverse_kinematics(H4, poses)
    table = joints(cfg)
    return (
        cfg,
        table.graph((0,) * (poses.ndim - 1)),
        {spec.name: table.joint_screws(spec.name) for spec in table.specs},
    )


def test_batch_matches_single_pose_analysis(rng):
    poses = np.vstack([random_poses(rng, 30), singular_pose(0), singular_pose(1)])
    cfg, graph, screws = batch_inputs(poses)
    batch = classify_poses(graph, screws)
    labels = batch.labels.ravel().tolist()
    for i in range(len(poses)):
        single = classify(joints(cfg).graph((i,)))
        assert labels[i] == single.labels
        assert batch.constraint_order[i] == single.constraint_order
        assert batch.global_order[i] == single.global_order
        for key in ("constraint", "actuation", "serial"):
            assert batch.closeness[key][i] == pytest.approx(single.closeness[key], abs=1e-9)
    assert labels[-2] == ("constraint",) and labels[-1] == ("actuation",)


def test_batch_shape_is_kept(rng):
    poses = random_poses(rng, 12).reshape(3, 4, 4)
    _, graph, screws = batch_inputs(poses)
    report = classify_poses(graph, screws)
    assert report.constraint_order.shape == (3, 4) and report.serial_flags.shape == (3, 4, 4)
    assert report.closeness["actuation"].shape == (3, 4)


def test_error_screws_for_other_joints(rng):
    _, graph, screws = batch_inputs(random_poses(rng, 2))
    screws.pop("A1")
    screws["A9"] = np.zeros((2, 1, 6))
    with pytest.raises(ScrewkitValueError, match=r"got missing \['A1'\] and unknown \['A9'\]"):
        classify_poses(graph, screws)


def test_error_inconsistent_batch(rng):
    _, graph, screws = batch_inputs(random_poses(rng, 3))
    screws["A1"] = screws["A1"][:2]
    with pytest.raises(
        ScrewkitValueError,
        match=r"Expected `screws\['A1'\]` of shape \(3, 1, 6\) with a batch axis, got \(2, 1, 6\)",
    ):
        classify_poses(graph, screws)


def test_error_nan_screws(rng):
    _, graph, screws = batch_inputs(random_poses(rng, 2))
    screws["S1m"] = screws["S1m"].copy()
    screws["S1m"][0, 0, 0] = np.nan
    with pytest.raises(ScrewkitValueError, match=r"Expected `screws\['S1m'\]` to hold finite numbers"):
        classify_poses(graph, screws)
