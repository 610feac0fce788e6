"""Condition maps through one lean wrench pass: the same values as the full pass with its views.

The maps' route (:meth:`screwkit.robots.posed.PosedMechanism.diagram_points`: the core without its
per-pose views, keeping only the frames :func:`screwkit.gca.diagram_points.frames_read` names) must
give every diagram point, and so every condition, bit for bit as the route the maps took before: the
whole joint table through :func:`screwkit.core.wrench_systems.analyze_table` with every view, then the
recipes (an independent path through the core: other requests, other frames kept). Catalog families
whose recipes read branch couples (H4, Quattro, Ragnar), constraint lines (Delta), and graph
mechanisms (Tsai's 3-UPU, a 6-UPS: loop closure instead of a closed form); batches longer than the
core's chunk, and H4 poses 1e-12 … 1e-4 from paper 002's Eq. (6) and (7) surfaces, where a rank
decision taken differently would show.
"""

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import quantities as Q
from screwkit.analysis import workspace as W
from screwkit.core.wrench_systems import analyze_table
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.gca import diagram_points as DP
from screwkit.robots import pose_diagram as PD
from screwkit.robots import posed as P

from ..mechanisms import gough_stewart, gough_stewart_points, tsai_3upu
from ..singular_surfaces import near_surface_poses, surface_roots

MECHANISMS = {
    "h4": lambda: sk.load_mechanism("h4"),
    "quattro": lambda: sk.load_mechanism("quattro"),
    "ragnar": lambda: sk.load_mechanism("ragnar"),
    "delta": lambda: sk.load_mechanism("delta"),
    "3-UPU graph": lambda: sk.mechanism(tsai_3upu([0.1, 0.05, 1.0])),
    "6-UPS graph": lambda: sk.mechanism(gough_stewart(*gough_stewart_points())),
}
#: Poses per mechanism: more than one chunk of the core where the kinematics are closed-form.
COUNTS = {"h4": P.CHUNK + 90, "quattro": P.CHUNK + 90, "ragnar": 200, "delta": 40}


def full_pass_points(points, posed):
    """The diagram's points as the maps computed them before: every view, the whole table at once."""
    return DP.batch_diagram_points(points, analyze_table(posed.joints))


def reachable_poses(mechanism, count, seed):
    poses = mechanism.random_poses(np.random.default_rng(seed), 2 * count)
    return poses[mechanism.reachable(poses)][:count]


@pytest.mark.parametrize("name", list(MECHANISMS))
def test_map_points_and_conditions_equal_the_full_pass_bit_for_bit(name):
    mechanism = MECHANISMS[name]()
    diagram, conditions, _, _ = Q.conditions_of(mechanism, {})
    poses = reachable_poses(mechanism, COUNTS.get(name, 30), 11)
    posed = mechanism.at(poses)
    lean, exists = posed.diagram_points(diagram.points)
    full = full_pass_points(diagram.points, mechanism.at(poses))
    assert exists.all()
    for point in diagram.points:
        np.testing.assert_array_equal(lean[point.label], full[point.label])
    for k, condition in enumerate(conditions):
        mapped, ok = W.evaluate(mechanism, poses, f"condition:{k}")
        assert ok.all()
        np.testing.assert_array_equal(mapped, condition.evaluate(full))


def test_h4_conditions_near_the_singular_surfaces_equal_the_full_pass():
    h4 = sk.load_mechanism("h4")
    rng = np.random.default_rng(20261128)
    poses = np.concatenate(
        [near_surface_poses(surface_roots(rng, s, 2)).poses for s in ("constraint", "actuation")]
    )
    diagram, conditions, _, _ = Q.conditions_of(h4, {})
    full = full_pass_points(diagram.points, h4.at(poses))
    for k, condition in enumerate(conditions):
        expected = condition.evaluate(full)
        assert np.abs(expected).min() < 1e-8 * np.median(np.abs(expected))  # the batch reaches the zeros
        np.testing.assert_array_equal(W.evaluate(h4, poses, f"condition:{k}")[0], expected)


def test_a_map_chunk_runs_one_wrench_pass_per_core_chunk(monkeypatch):
    # the recipes find every frame they read in the lean pass: no second pass (gca's analyze_table
    # would run one for a missing frame), one pass per chunk of CHUNK poses
    h4 = sk.load_mechanism("h4")
    diagram, _, _, _ = Q.conditions_of(h4, {})
    calls = []

    def counted(*args, **kwargs):
        calls.append(len(args[0]))
        return analyze_table(*args, **kwargs)

    def refused(*args, **kwargs):
        raise AssertionError("a second wrench pass")

    monkeypatch.setattr(PD, "analyze_table", counted)  # (the batch's diagram points: robots.pose_diagram)
    monkeypatch.setattr(DP, "analyze_table", refused)
    poses = reachable_poses(h4, P.CHUNK + 10, 5)
    h4.at(poses).diagram_points(diagram.points)
    assert calls == [P.CHUNK, 10]


@pytest.mark.parametrize("name", ["h4", "delta"])
def test_frames_read_are_all_the_recipes_need(name):
    # an analysis keeping only those frames gives the points; keeping none, the recipes compute
    # the missing frames again (a lean pass of its own): the same points
    mechanism = MECHANISMS[name]()
    diagram, _, _, _ = Q.conditions_of(mechanism, {})
    table = mechanism.joints(reachable_poses(mechanism, 6, 3))
    full = DP.batch_diagram_points(diagram.points, analyze_table(table))
    kept = analyze_table(table, views=False, kept=lambda top: DP.frames_read(diagram.points, top))
    bare = analyze_table(table, views=False)
    assert set(DP.frames_read(diagram.points, kept.topology)) <= set(kept.frames)
    assert not set(DP.frames_read(diagram.points, bare.topology)) & set(bare.frames)
    for analysis in (kept, bare):
        found = DP.batch_diagram_points(diagram.points, analysis)
        for label, value in full.items():
            np.testing.assert_array_equal(found[label], value)


def test_kept_names_frames_of_the_topology():
    table = sk.load_mechanism("h4").joints([[0, 0, -750, 0]])
    with pytest.raises(ScrewkitValueError, match=r"Expected `kept` to name frames among .*got 'leg7:W'"):
        analyze_table(table, views=False, kept=lambda top: ["leg7:W"])
    with pytest.raises(ScrewkitTypeError, match=r"Expected `kept` to be callable, got list"):
        analyze_table(table, views=False, kept=["constraint"])
