"""Batched labels: parity with the single-pose analysis, at regular and singular poses; errors."""

import dataclasses
import gc
import weakref

import numpy as np
import pytest

import screwkit as sk
from screwkit.core.singularity import classify, classify_chunks, classify_poses, classify_table
from screwkit.core.wrench_systems import analyze_table
from screwkit.exceptions import ScrewkitValueError, UnreachablePoseError
from screwkit.robots.families.four_limb.joints import joints
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics
from screwkit.robots.posed import CHUNK

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


# the posed batch: IK, joint table and core chunk by chunk (issue 8) ------------------------------
def h4_poses(rng, count):
    mechanism = sk.load_mechanism("h4")
    return mechanism, random_poses(rng, count)


def test_posed_chunks_match_the_whole_table(rng):
    mechanism, poses = h4_poses(rng, 2 * CHUNK + 37)  # two full chunks and a short one
    posed = mechanism.at(poses)
    chunked = posed.singularities
    assert "joints" not in posed.__dict__ and "configuration" not in posed.__dict__
    whole = classify_table(mechanism.joints(poses))  # one IK over the batch, then the core
    np.testing.assert_array_equal(chunked.codes, whole.codes)
    for name in ("constraint_order", "global_order", "serial_flags"):
        np.testing.assert_array_equal(getattr(chunked, name), getattr(whole, name))
    for key in ("constraint", "actuation", "serial"):
        np.testing.assert_array_equal(chunked.closeness[key], whole.closeness[key])
    np.testing.assert_array_equal(chunked.analysis.actuation_rows, whole.analysis.actuation_rows)
    for key, (rows, order) in whole.analysis.frames.items():
        np.testing.assert_array_equal(chunked.analysis.frames[key][0], rows)
        np.testing.assert_array_equal(chunked.analysis.frames[key][1], order)


def test_posed_chunks_ask_for_the_table_only_for_a_view(rng):
    mechanism, poses = h4_poses(rng, 5)
    posed = mechanism.at(poses)
    report = posed.singularities
    assert set(report.analysis.frames) == {"platform", *(f"limb{k}:passive" for k in range(4))}
    one = report[3]
    assert "joints" not in posed.__dict__
    assert one.uncontrolled_twists.shape == (0, 6)  # a view: the table is computed now
    assert report.analysis.table is posed.joints
    full = analyze_table(mechanism.joints(poses))[3]
    for key in ("global", "uncontrolled", "constraint"):
        np.testing.assert_array_equal(one.analysis.frames[key][0], full.frames[key][0])
        assert one.analysis.frames[key][1] == full.frames[key][1]


def test_a_posed_batch_and_its_report_hold_no_reference_cycle(rng):
    # a map's chunks are freed when they are done, not when the cyclic GC next runs (with a cycle
    # a 300 x 300 verdict map held ~2 KB per pose of finished chunks at its peak)
    mechanism, poses = h4_poses(rng, 5)
    posed = mechanism.at(poses)
    report = posed.singularities
    alive = weakref.ref(posed)
    gc.disable()
    try:
        del posed
        assert alive() is None
    finally:
        gc.enable()
    table = report.analysis.table  # asked by a view after the batch is gone: computed again
    np.testing.assert_array_equal(table.screws, mechanism.joints(poses).screws)


def test_posed_chunks_name_the_unreachable_pose_of_the_whole_batch(rng):
    mechanism, poses = h4_poses(rng, CHUNK + 10)
    poses[CHUNK + 3] = [0.0, 0.0, -2000.0, 0.0]
    with pytest.raises(UnreachablePoseError) as whole:
        mechanism.configuration(poses)
    with pytest.raises(UnreachablePoseError) as chunked:
        _ = mechanism.at(poses).singularities
    assert str(chunked.value).startswith(str(whole.value).rstrip("."))  # and where the per-pose views are
    assert f"{CHUNK + 3}" in str(chunked.value) and "posed.verdicts" in str(chunked.value)


def test_error_chunks_of_the_wrong_size():
    table = sk.load_mechanism("h4").joints(np.array([[0.0, 0.0, -750.0, 0.0]] * 3))
    with pytest.raises(ScrewkitValueError, match=r"Expected chunks of 4 configurations in all, got 3\."):
        classify_chunks([table], table, (4,))


@pytest.mark.parametrize("name", sk.list_mechanisms())
def test_a_pose_gets_the_same_bits_alone_and_in_a_batch(name):
    # the report analyses its pose with the diagram's generic draws as one batch: every number of
    # the pose must be the one a batch of one gives (the core sums each pose's rows in one order,
    # whatever the batch's shape: joint tables reordered by name are made contiguous)
    mechanism = sk.load_mechanism(name)
    poses = mechanism.random_poses(np.random.default_rng(3), 5)
    alone, batch = analyze_table(mechanism.joints(poses[2:3])), analyze_table(mechanism.joints(poses))
    for field in ("reference_point", "length_scale", "actuation_rows", "branch_rows", "transmissions"):
        np.testing.assert_array_equal(np.asarray(getattr(alone, field))[0], np.asarray(getattr(batch, field))[2])
    for key, (rows, order) in alone.frames.items():
        np.testing.assert_array_equal(rows[0], batch.frames[key][0][2], err_msg=key)
        assert order[0] == batch.frames[key][1][2]
    for key, values in alone.closeness.items():
        assert values[0] == batch.closeness[key][2], key


def test_a_posed_batch_iterates_over_its_poses_in_c_order(rng):
    h4 = sk.load_mechanism("h4")
    poses = np.vstack([random_poses(rng, 5), singular_pose(0)])
    posed = h4.at(poses)
    assert [pose.singularity.verdict for pose in posed] == list(posed.verdicts)
    assert [pose.shape for pose in posed] == [()] * 6
    np.testing.assert_array_equal([pose.twist_basis for pose in posed], posed.twist_basis)
    grid = h4.at(poses.reshape(2, 3, 4))  # every pose of a grid, row by row (np.ndindex)
    assert [tuple(pose.poses) for pose in grid] == [tuple(p) for p in poses]
    with pytest.raises(IndexError, match=r"shape \(6,\), got 6 \(out of range\)"):
        posed[6]


def test_a_pose_gives_its_diagram_and_superbracket_as_the_report_does():
    pose = sk.load_mechanism("h4").at([0.0, 0.0, -800.0, 0.1])[0]
    report = sk.analyze(pose)
    assert str(pose.diagram) == str(report.diagram)
    factored = pose.superbracket.simplification.factored.to_dict()["text"]
    assert factored == report.superbracket.simplification.factored.to_dict()["text"]


def test_error_a_pose_without_a_superbracket_says_why(monkeypatch):
    # no catalog robot lacks a diagram: give the pose one with the reasons a generic pose would find
    # (no diagram at generic poses: no sampler; a diagram degenerate only at the pose is factored)
    from screwkit.robots.generic_poses import _no_sampler

    pose = sk.load_mechanism("planar_3rrp").at()[0]
    diagram, _ = pose.diagram_and_sampler()
    degenerate = dataclasses.replace(diagram, degenerate=("limb I: a constraint couple, not a line",))
    monkeypatch.setattr(type(pose), "diagram_and_sampler", lambda self: (degenerate, _no_sampler))
    with pytest.raises(ScrewkitValueError, match=r"Expected a wrench diagram of six lines for the superbracket "
                       r"of Planar 3-RRP, got none: limb I: a constraint couple, not a line\."):
        _ = pose.superbracket


@pytest.mark.parametrize("pose", [np.zeros((0, 4)), [[30, -20, -750, 0.3], [0, 0, -800, 0.1]]])
def test_error_analyze_takes_one_pose(pose):
    with pytest.raises(ScrewkitValueError, match=r"Expected `pose` to be one pose of shape \(4,\) \(x, y, z, phi\), "
                       r"got shape \(\d, 4\); for many poses use mechanism.at\(poses\)"):
        sk.analyze("h4", pose, superbracket=False)


def test_analyze_takes_one_pose_of_a_batch():
    posed = sk.load_mechanism("h4").at([[0.0, 0.0, -750.0, 0.0], [30.0, -20.0, -750.0, 0.3]], rtol=1e-8)
    report = sk.analyze(posed[1], superbracket=False)
    assert report.pose.tolist() == [30.0, -20.0, -750.0, 0.3]
    assert report.to_dict() == sk.analyze("h4", [30.0, -20.0, -750.0, 0.3], rtol=1e-8, superbracket=False).to_dict()
    with pytest.raises(ScrewkitValueError, match=r"Expected no `pose`, `rtol` or `length_scale` with a posed mechanism .*got pose, rtol\."):
        sk.analyze(posed[0], [0.0, 0.0, -750.0, 0.0], rtol=1e-9)
    with pytest.raises(ScrewkitValueError, match=r"Expected one pose of a posed mechanism \(index the batch: posed\[i\]\), "
                       r"got a batch of shape \(2,\)\."):
        sk.analyze(posed, superbracket=False)
