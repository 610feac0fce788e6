"""Operation modes: Tsai's 3-UPU, translational (3T) above its base, where 3T and a turning mode meet
in its base plane (Zlatanov, Bonev & Gosselin 2002). Each class's motion type is checked against an
independent rank computation from the joint screws (numpy SVDs written here)."""

import numpy as np

import screwkit as sk
from screwkit.core.motion import generic_configurations
from screwkit.core.operation_modes import operation_modes
from screwkit.core.wrench_systems import analyze_table
from screwkit.graphs.jointtable import JointTable
from tests.mechanisms import tsai_3upu, tsai_constraint_couples

SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


def _null(rows, tol=1e-8):
    _, s, vt = np.linalg.svd(rows)
    rank = int(np.sum(s > tol * s[0]))
    return vt[rank:]


def platform_rotations(table, index):
    """Rotations of the platform's twist system at one configuration: each leg's wrenches are
    reciprocal to its joint screws (w·Δt = 0), the platform's twists reciprocal to all legs' wrenches;
    the rotations are the rank of the twists' angular parts."""
    wrenches = []
    for leg in (1, 2, 3):
        screws = np.vstack([table.joint_screws(name)[index].reshape(-1, 6)
                            for name in (f"Ub{leg}", f"P{leg}", f"Up{leg}")])
        wrenches.append(_null(screws @ SWAP))
    twists = _null(np.vstack(wrenches) @ SWAP)
    return len(twists), int(np.linalg.matrix_rank(twists[:, :3], tol=1e-8))


def test_above_the_base_every_configuration_translates():
    table = generic_configurations(tsai_3upu([0.1, 0.05, 0.8]), np.random.default_rng(1), 8)
    modes = operation_modes(analyze_table(table), analyze_table(JointTable.from_graph(tsai_3upu([0.1, 0.05, 0.8]))))
    assert [(mode.motion_type, mode.reference) for mode in modes] == [("3T", True)]
    assert all(platform_rotations(table, i) == (3, 0) for i in range(len(table)))


def test_in_the_base_plane_the_draws_reach_two_modes_and_are_told_apart():
    graph = tsai_3upu([0.1, 0.05, 0.0])
    table = generic_configurations(graph, np.random.default_rng(1), 12, same_mode=False)
    modes = operation_modes(analyze_table(table))
    assert sorted(mode.motion_type for mode in modes) == ["2T1R", "3T"]
    for mode in modes:
        expected = (3, 0) if mode.motion_type == "3T" else (3, 1)
        assert all(platform_rotations(table, i) == expected for i in mode.indices)


def test_generic_configurations_keep_one_mode():
    graph = tsai_3upu([0.1, 0.05, 0.0])
    table = generic_configurations(graph, np.random.default_rng(1), 12)
    rotations = {platform_rotations(table, i) for i in range(len(table))}
    assert len(table) >= 1 and len(rotations) == 1


def test_mode_kept_is_the_reference_s_when_it_has_one():
    # a reference above the base translates: every kept draw translates, even drawn far
    table = generic_configurations(tsai_3upu([0.3, -0.2, 0.5]), np.random.default_rng(5), 12)
    assert len(table) == 12
    assert {platform_rotations(table, i) for i in range(len(table))} == {(3, 0)}


def test_mechanism_lists_its_own_mode_first():
    graph = tsai_3upu([0.1, 0.05, 0.8])
    graph.graph["dof"] = 3
    modes = sk.mechanism(graph).operation_modes
    assert (modes[0].motion_type, modes[0].reference) == ("3T", True)
    # the other modes (3R, 2T1R and the half-turned 3T: tests/core/test_mode_search.py) are found by
    # random assembly
    assert sorted(mode.motion_type for mode in modes[1:]) == ["2T1R", "3R", "3T"]
    # independent: three couples normal to both U axes of each leg, rank 3: no rotation is left
    assert np.linalg.matrix_rank(tsai_constraint_couples([0.1, 0.05, 0.8])[:, 3:]) == 3
