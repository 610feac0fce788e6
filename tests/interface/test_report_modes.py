"""The report says when its pose lies where operation modes meet (core.mode_transitions).

Tsai's 3-UPU with its platform in the base plane is also a planar 3-RPR there (every inner U axis
vertical: hand derivation in tests/core/test_mode_transitions.py): the translational (3T) and the
planar (2T1R) modes meet. Above the base plane only the translational mode passes.
"""

import screwkit as sk
from tests.mechanisms import tsai_3upu


def test_report_says_the_3upu_in_its_base_plane_lies_where_two_modes_meet():
    report = sk.analyze(tsai_3upu((0.1, 0.05, 0.0)), superbracket=False)
    lines = str(report).splitlines()
    meeting = [line for line in lines if "operation modes meet" in line]
    assert len(meeting) == 1 and "3T" in meeting[0] and "2T1R" in meeting[0]
    per_mode = [line for line in lines if line.startswith("  in the ") and " mode: " in line]
    assert sorted(line.split()[2] for line in per_mode) == ["2T1R", "3T"]
    data = report.to_dict()["modes_at_pose"]
    assert data["meets"] and sorted(m["motion_type"] for m in data["modes"]) == ["2T1R", "3T"]
    assert all(m["verdict"] == "constraint singularity" for m in data["modes"])  # 4 freedoms, 3 wanted


def test_report_above_the_base_plane_has_one_mode_and_no_meeting_line():
    report = sk.analyze(tsai_3upu((0.1, 0.05, 0.6)), superbracket=False)
    assert "operation modes meet" not in str(report)
    data = report.to_dict()["modes_at_pose"]
    assert not data["meets"] and [m["motion_type"] for m in data["modes"]] == ["3T"]
