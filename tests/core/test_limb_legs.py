"""A leg of six freedoms whose actuated joint is one of its members (a UPS leg) gets its twists and
wrenches from its limb's frames (screwkit.core._program.ProgramBuilder._limb_leg): the same systems
as the generic span of all its screws and its reciprocal, checked against that path here."""

import importlib.util

import numpy as np
import pytest
from hypothesis import given, settings

import screwkit as sk
from screwkit.algebra import compiled as C
from screwkit.algebra import reference_frame as RF
from screwkit.core import _program as PR
from screwkit.core._wrench_pass import canonical
from screwkit.core.wrench_systems import analyze_table
from screwkit.graphs.joints import prismatic, spherical, universal
from screwkit.graphs.jointtable import JointTable
from screwkit.graphs.topology import topology
from screwkit.graphs.twistgraph import twist_graph
from screwkit.robots.catalog import load_mechanism

from ..mechanisms import GS_BASE, Z, gough_stewart, gough_stewart_points, moved, tsai_3upu, unit
from ..strategies import rigid_motions, unit_factors

FIELDS = (
    "platform_order", "constraint_order", "global_order", "serial", "transmissions", "actuation_rows",
    "branch_rows", "reference_point",
)


def _both_ways(function):
    """``function()`` with the program as built, and with the generic program (no leg's frames
    taken from its limb's)."""
    shortcut = function()
    original = PR.ProgramBuilder._limb_leg
    PR.frame_program.cache_clear()
    try:
        PR.ProgramBuilder._limb_leg = lambda self, index: None
        generic = function()
    finally:
        PR.ProgramBuilder._limb_leg = original
        PR.frame_program.cache_clear()
    return shortcut, generic


def _analyses(table, views):
    return _both_ways(lambda: analyze_table(table, views=views))


def _same_span(first, second, order):
    """Orthonormal rows ``(..., 6, 6)`` of the same ``order`` span the same space (their projectors)."""
    mask = np.arange(6) < np.asarray(order)[..., None]
    a, b = np.where(mask[..., None], first, 0.0), np.where(mask[..., None], second, 0.0)
    gap = np.swapaxes(a, -1, -2) @ a - np.swapaxes(b, -1, -2) @ b
    return float(np.abs(gap).max(initial=0.0))


def _leg_twist_frames(analysis):
    top = analysis.topology
    legs = [f"leg{k}:T" for k in range(len(top.legs))]
    nodes = [f"node{i}" for i in top.legs]
    return legs + nodes


def test_a_ups_legs_frames_come_from_its_limb_and_a_3upu_legs_do_not():
    table = JointTable.from_graph(gough_stewart(*gough_stewart_points()))
    top = topology(table.base, table.platform, table.specs)
    builder = PR.ProgramBuilder(top)
    assert [builder._limb_leg(i) is not None for i in top.legs] == [True] * 6
    program = PR.frame_program(top, tuple(("wrenches", i) for i in top.legs))
    spans = [int(count) for code, _, _, count in program.ops if code == 0]  # SPAN ops: sources each
    contracts = sum(1 for code, *_ in program.ops if code == 4)
    assert contracts == 6 and 3 not in spans  # no span of a leg's three joints' screws
    upu = JointTable.from_graph(tsai_3upu([0.1, 0.0, 1.0]))  # legs of five freedoms: generic
    top = topology(upu.base, upu.platform, upu.specs)
    assert all(PR.ProgramBuilder(top)._limb_leg(i) is None for i in top.legs)


@pytest.mark.parametrize("views", [False, True])
def test_the_gough_stewart_analysis_equals_the_generic_paths(views):
    robot = sk.mechanism(gough_stewart(*gough_stewart_points()))
    rng = np.random.default_rng(7)
    count = 2000 if not views else 200
    poses = np.column_stack(
        [rng.uniform(-0.25, 0.25, (count, 2)), rng.uniform(0.8, 1.2, count), rng.uniform(-0.3, 0.3, (count, 3))]
    )
    table = robot.at(poses[robot.reachable(poses)]).joints
    assert len(table) > 0.95 * count
    shortcut, generic = _analyses(table, views)
    for name in FIELDS:  # bit for bit: the legs have no wrench at these poses, either way
        np.testing.assert_array_equal(getattr(shortcut, name), getattr(generic, name), err_msg=name)
    for name in shortcut.closeness_factors:
        np.testing.assert_array_equal(shortcut.closeness_factors[name], generic.closeness_factors[name])
    spans = _leg_twist_frames(shortcut) if views else []
    for name, (rows, order) in generic.frames.items():
        np.testing.assert_array_equal(shortcut.frames[name][1], order, err_msg=name)
        if name in spans:  # another basis of the same twist system (all of it)
            assert _same_span(shortcut.frames[name][0], rows, order) < 1e-12, name
        else:
            np.testing.assert_array_equal(shortcut.frames[name][0], rows, err_msg=name)


def test_the_mcgill_smg_analysis_equals_the_generic_paths():
    robot = load_mechanism("mcgill_smg")
    table = robot.at(robot.random_poses(np.random.default_rng(2), 500)).joints
    shortcut, generic = _analyses(table, views=False)
    for name in FIELDS:
        np.testing.assert_array_equal(getattr(shortcut, name), getattr(generic, name), err_msg=name)


def _gough_stewart_with_leg_one_singular(tilt):
    """Leg 1's U axes span a plane holding the leg (its platform centre in the U's plane: the leg
    has a constraint wrench), tilted out of it by ``tilt`` radians."""
    joints = []
    for i, (a, c) in enumerate(zip(GS_BASE, gough_stewart_points()[1], strict=True), start=1):
        leg = unit(c - a)
        first, second = unit(np.cross(Z, a)), unit(np.cross(leg, unit(np.cross(Z, a))))
        if i == 1:
            across = unit(np.cross(leg, Z))
            first, second = unit(leg + across), unit(leg - across + tilt * unit(np.cross(leg, across)))
        joints += [
            ("base", f"lower{i}", universal(f"U{i}", first, second, a)),
            (f"lower{i}", f"upper{i}", prismatic(f"P{i}", leg, actuated=True)),
            (f"upper{i}", "platform", spherical(f"S{i}", c)),
        ]
    return twist_graph("base", "platform", joints)


@pytest.mark.parametrize("tilt", [0.0, 1e-12, 1e-10, 1e-9, 3e-9, 1e-8, 1e-6, 1e-2])
def test_at_and_near_a_legs_singularity_the_ranks_are_the_generic_paths(tilt):
    graph = _gough_stewart_with_leg_one_singular(tilt)
    table = JointTable.from_graph(graph)[None]
    shortcut, generic = _analyses(table, views=True)
    singular = tilt < 2e-9  # the rank rule's threshold (rtol 1e-9) lies between 1e-9 and 3e-9 here
    assert generic.frames["leg0:W"][1].tolist() == [1 if singular else 0]
    for name, (rows, order) in generic.frames.items():
        assert shortcut.frames[name][1].tolist() == order.tolist(), name
        assert _same_span(shortcut.frames[name][0], rows, order) < 1e-12, name  # a line's sign may differ
    for name in ("platform_order", "constraint_order", "global_order", "serial"):
        np.testing.assert_array_equal(getattr(shortcut, name), getattr(generic, name), err_msg=name)
    np.testing.assert_allclose(shortcut.transmissions, generic.transmissions, rtol=1e-12, atol=1e-15)
    verdicts = _both_ways(lambda: sk.classify(graph).verdict)
    assert verdicts[0] == verdicts[1] and (verdicts[0] == "regular") != singular


@pytest.mark.skipif(importlib.util.find_spec("numba") is None, reason="numba is not installed (the `fast` extra)")
def test_the_compiled_and_numpy_programs_agree_bit_for_bit_on_these_legs(monkeypatch):
    from screwkit.core import _frames_numba

    tables = [JointTable.from_graph(_gough_stewart_with_leg_one_singular(t)) for t in (0.0, 1e-9, 3e-9, 1e-2)]
    screws = np.stack([t.screws for t in tables] + [t.screws for t in tables[-1:]])
    table = canonical(JointTable(tables[0].base, tables[0].platform, tables[0].specs, screws))
    top = topology(table.base, table.platform, table.specs)
    centre, length = RF.mechanism_frame(table.screws, table.anchor)
    scaled = RF.unit_scaled(table.screws, centre, length)
    requests = (
        *(("twists", i) for i in range(len(top.nodes))),  # the legs' EXTEND too
        *(("wrenches", i) for i in top.legs),
        *(("passive", tuple(plan.siblings)) for plan in top.limbs),
    )
    program = PR.frame_program(top, requests)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", _frames_numba)
    compiled = PR.run_program(program, scaled, 1e-9, requests)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    stepwise = PR.run_program(program, scaled, 1e-9, requests)
    np.testing.assert_array_equal(compiled[1], stepwise[1])
    np.testing.assert_array_equal(compiled[0], stepwise[0])
    assert compiled[1][:, len(top.nodes)].tolist() == [1, 1, 0, 0, 0]  # leg 1's wrench: at, within, beyond


@settings(max_examples=10, deadline=None)
@given(motion=rigid_motions(), factor=unit_factors)
def test_a_legs_wrench_follows_rigid_motions_and_units(motion, factor):
    for tilt, order in ((0.0, 1), (1e-2, 0)):  # at a leg's singularity (a wrench) and away from it (none)
        graph = moved(_gough_stewart_with_leg_one_singular(tilt), *motion, factor=factor)
        analysis = analyze_table(JointTable.from_graph(graph)[None], views=True)
        assert analysis.frames["leg0:W"][1].tolist() == [order]
        assert analysis.constraint_order.tolist() == [order]
