"""One pose's report from the posed mechanism (posed[i].report()): the report sk.analyze(posed[i])
gives, for a catalog robot and for graph mechanisms (loop closure) alike, composed by the interface
through the composer `import screwkit` registers (screwkit.robots.report_composer); a batch and a pose
out of reach are refused with their reason."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from screwkit.robots.report_composer import register_report_composer, report_composer

from ..mechanisms import planar_3rpr

RPR_BASE = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0, 0.0]])
RPR_PLATFORM = np.array([[0.4, 0.3, 0.0], [0.7, 0.35, 0.0], [0.55, 0.55, 0.0]])


def _same_report(mine, theirs):
    assert mine.verdict.to_dict() == theirs.verdict.to_dict()
    np.testing.assert_array_equal(mine.pose, theirs.pose)
    if theirs.superbracket is None:
        assert mine.superbracket is None and mine.superbracket_note == theirs.superbracket_note
    else:
        text = theirs.superbracket.simplification.factored.to_dict()["text"]
        assert mine.superbracket.simplification.factored.to_dict()["text"] == text
    assert str(mine) == str(theirs)


def test_the_report_of_a_catalog_pose_is_analyzes():
    posed = sk.load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
    mine = posed[1].report()
    _same_report(mine, sk.analyze(posed[1]))
    # paper 002's factored superbracket of the H4 at a regular pose (tests/robots/test_h4.py)
    assert mine.superbracket.simplification.factored.to_dict()["text"] == "-[gikj][a b d ḟ][c g ḣ j]"
    assert mine.verdict.verdict == "regular" and mine.pose.tolist() == [30.0, -20.0, -750.0, 0.3]


def test_the_report_of_a_graph_mechanisms_pose_is_analyzes():
    h4 = sk.mechanism(sk.load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])
    posed = h4.at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
    mine = posed[1].report()
    _same_report(mine, sk.analyze(posed[1]))
    assert mine.superbracket.simplification.factored.to_dict()["text"] == "-[gikj][a b d ḟ][c g ḣ j]"
    assert mine.jacobians is not None and mine.jacobians.type == "regular"
    rpr = sk.mechanism(planar_3rpr(RPR_BASE, RPR_PLATFORM))
    moved = rpr.at(rpr.reference_pose + np.array([[0.0, 0.0, 0.0], [0.02, -0.01, 0.05]]))
    stages = []
    mine = moved[1].report(superbracket=False, progress=stages.append)
    _same_report(mine, sk.analyze(moved[1], superbracket=False))
    assert stages[0] == "wrench systems" and mine.pose.tolist() == moved.poses[1].tolist()


def test_a_batch_is_refused_naming_the_index():
    posed = sk.load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
    with pytest.raises(ScrewkitValueError, match=r"^Expected one pose .*\(index the batch: posed\[i\]\).*\(2,\)\.$"):
        posed.report()
    with pytest.raises(ScrewkitTypeError, match="superbracket"):
        posed[0].report(superbracket="yes")
    with pytest.raises(ScrewkitTypeError, match="progress"):
        posed[0].report(progress=3)


@pytest.mark.parametrize("name", ["v4", "h4 graph"])
def test_a_pose_out_of_reach_is_refused_with_its_reason(name):
    if name == "v4":
        robot, reason = sk.load_mechanism("v4"), "Eq. 3 has no real root"
    else:
        robot = sk.mechanism(sk.load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])
        reason = "do not close"
    posed = robot.at([[0, 0, -750, 0], [0, 0, -3000, 0]])
    stages = []
    with pytest.raises(UnreachablePoseError, match=f"out of reach.*{reason}"):
        posed[1].report(progress=stages.append)
    assert stages == []  # refused before any stage starts


def test_the_composer_is_registered_by_import_screwkit_and_checked():
    composer = report_composer()
    assert composer(sk.load_mechanism("v4").at()[0], superbracket=False, progress=None).verdict.verdict == "regular"
    with pytest.raises(ScrewkitTypeError, match=r"Expected `composer` to be callable, got int"):
        register_report_composer(3)
    assert report_composer() is composer
