"""Tsai's 3-UPU analysed from where its translational and turning modes meet (its base plane) gets the
superbracket of its translational mode: the one found from a generic translating configuration."""

import screwkit as sk
from tests.mechanisms import tsai_3upu


def _superbracket_line(z):
    graph = tsai_3upu([0.1, 0.05, z])
    graph.graph["dof"] = 3
    text = str(sk.analyze(graph))
    return next(line for line in text.splitlines() if line.strip().startswith("[ab, cd, ef, gh, gi, hi] ="))


def test_transition_pose_gets_the_translational_mode_s_superbracket():
    at_transition = _superbracket_line(0.0)
    assert at_transition == _superbracket_line(0.8)
    assert not at_transition.rstrip().endswith("= 0")


def _mode_lines(z):
    graph = tsai_3upu([0.1, 0.05, z])
    graph.graph["dof"] = 3
    return [line for line in str(sk.analyze(graph)).splitlines() if "operation modes" in line]


def test_report_says_where_modes_meet_and_is_silent_in_one_mode():
    # the two modes' motion types are checked against the platform twists' rank in
    # tests/core/test_operation_modes.py; here the report names them
    # where they meet, the modes found by leaving the pose say it once, with the verdict in each mode
    # (screwkit.core.mode_transitions); the reached-modes line would repeat it and is left out
    (line,) = _mode_lines(0.0)
    assert line.startswith("this pose lies where 2 operation modes meet: ")
    assert sorted(line.split(": ")[1].split(" and ")) == ["2T1R", "3T"]
    assert _mode_lines(0.8) == []
