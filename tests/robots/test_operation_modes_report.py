"""Tsai's 3-UPU analysed from where its translational and turning modes meet (its base plane) gets the
superbracket of its translational mode: the one found from a generic translating configuration."""

import numpy as np
import pytest

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


def test_report_says_where_modes_meet_and_lists_the_modes_found():
    # the two modes' motion types are checked against the platform twists' rank in
    # tests/core/test_operation_modes.py; here the report names them
    # where they meet, the modes found by leaving the pose say it, with the verdict in each mode
    # (screwkit.core.mode_transitions), after the modes the search found (screwkit.core.mode_search)
    found, meeting = _mode_lines(0.0)
    assert found.startswith("3 operation modes (this configuration lies where some meet): ")
    assert meeting.startswith("this pose lies where 2 operation modes meet: ")
    assert sorted(meeting.split(": ")[1].split(" and ")) == ["2T1R", "3T"]
    # in one mode, the modes found, this one first; the search's extent said
    (line,) = _mode_lines(0.8)
    assert line.startswith("4 operation modes: 3T (this one), ")
    listed = line.split(": ", 1)[1].split(" (found")[0]
    for name in ("3R", "2T1R", "3T (turned 180° about (0, 0, 1))"):  # the platform half-turned: 3T too
        assert f", {name}" in listed or f" and {name}" in listed
    assert "random assemblies" in line and line.endswith("others may exist)")


def test_report_json_has_the_modes_found():
    graph = tsai_3upu([0.1, 0.05, 0.8])
    graph.graph["dof"] = 3
    data = sk.analyze(graph, superbracket=False).to_dict()["operation_modes"]
    assert (data["modes"][0]["motion_type"], data["modes"][0]["reference"]) == ("3T", True)
    assert sorted(mode["motion_type"] for mode in data["modes"]) == ["2T1R", "3R", "3T", "3T"]
    assert sorted(abs(mode["turn"][2]) for mode in data["modes"] if mode["motion_type"] == "3T") == [0.0, pytest.approx(np.pi)]
    assert data["complete"] is False and data["closed"] <= data["assemblies"]
    assert sk.analyze("h4", superbracket=False).to_dict()["operation_modes"] is None  # a graph's only
