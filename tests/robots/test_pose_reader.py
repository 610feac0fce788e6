"""The one reader of pose arguments (screwkit.robots.pose_reader): a string, a boolean or NaN inside a
pose is refused by every pose-taking entry point of a catalog robot and of a graph mechanism, naming
the argument, what was expected and what was got (before, ``twist_graph(["30", 0, -750, 0])`` and
``[True, ...]`` were accepted, a string pose raised numpy's ValueError, and a graph mechanism's NaN
pose named the loop closure's internal ``targets``)."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis.workspace import evaluate
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError

from ..mechanisms import gough_stewart, gough_stewart_points

H4 = sk.load_mechanism("h4")
GRAPH = sk.mechanism(gough_stewart(*gough_stewart_points()))


def _pose_with(robot, value):
    """The reference pose as a list with its first coordinate replaced by ``value``."""
    return [value, *np.asarray(robot.reference_pose, dtype=float)[1:].tolist()]


@pytest.mark.parametrize("robot", [H4, GRAPH], ids=["catalog", "graph"])
@pytest.mark.parametrize(
    ("call", "argument"),
    [
        (lambda robot, pose: robot.twist_graph(pose), "pose"),
        (lambda robot, pose: robot.jacobians(pose), "pose"),
        (lambda robot, pose: robot.configuration(pose), "pose"),
        (lambda robot, pose: robot.joints(pose), "pose"),
        (lambda robot, pose: robot.at([pose]), "poses"),
        (lambda robot, pose: robot.reachable(np.array([pose], dtype=object)), "poses"),
        (lambda robot, pose: robot.unreachable_reasons(np.array([pose], dtype=object)), "poses"),
        (lambda robot, pose: evaluate(robot, [pose], "verdict"), "poses"),
        (lambda robot, pose: sk.check_path(robot, pose, robot.reference_pose), "start"),
    ],
)
@pytest.mark.parametrize(
    ("value", "got"),
    [("30", r"got (strings: \[+|str )'30'"), (True, "got bool True"), (None, "got None")],
    ids=["string", "bool", "none"],
)
def test_a_non_numeric_coordinate_is_refused_naming_the_argument(robot, call, argument, value, got):
    with pytest.raises(ScrewkitTypeError, match=rf"Expected `{argument}` to be an array of real numbers, {got}"):
        call(robot, _pose_with(robot, value))


@pytest.mark.parametrize("robot", [H4, GRAPH], ids=["catalog", "graph"])
def test_a_string_pose_is_refused_not_a_numpy_error(robot):
    with pytest.raises(ScrewkitTypeError, match=r"Expected `pose` to be numeric, got the string 'abc'\.$"):
        robot.twist_graph("abc")
    with pytest.raises(ScrewkitTypeError, match=r"Expected `poses` to be numeric, got the string 'abc'\.$"):
        robot.at("abc")


@pytest.mark.parametrize(
    "call",
    [
        lambda robot, poses: robot.reachable(poses),
        lambda robot, poses: robot.unreachable_reasons(poses),
        lambda robot, poses: robot.configuration(poses),
        lambda robot, poses: robot.at(poses),
        lambda robot, poses: evaluate(robot, poses, "verdict"),
    ],
)
def test_a_graph_mechanisms_nan_pose_names_poses_not_targets(call):
    poses = np.array([_pose_with(GRAPH, np.nan)])
    with pytest.raises(ScrewkitValueError, match=r"Expected `poses?` to hold finite numbers, got NaN or infinity"):
        call(GRAPH, poses)


def test_a_wrong_number_of_coordinates_names_them():
    with pytest.raises(ScrewkitValueError, match=r"Expected `poses` to have shape \(\.\.\., 6\), got \(2, 5\) "
                       r"\(coordinates x, y, z, rx, ry, rz\)\.$"):
        GRAPH.at(np.zeros((2, 5)))
    with pytest.raises(ScrewkitValueError, match=r"Expected `pose` to have shape \(4,\), got \(2, 4\) "
                       r"\(one pose of coordinates x, y, z, phi\)\.$"):
        H4.twist_graph(np.zeros((2, 4)))


def test_a_displacement_with_a_string_is_refused():
    shift = np.eye(4).tolist()
    shift[0][3] = "5"
    with pytest.raises(ScrewkitTypeError, match=r"Expected `poses` to be an array of real numbers, got strings"):
        GRAPH.at([shift])


def test_numbers_of_any_numeric_type_are_read_as_before():
    pose = np.asarray(H4.reference_pose, dtype=np.float32)
    assert H4.at([pose]).verdicts.tolist() == ["regular"]
    assert H4.twist_graph([0, 0, -750, 0]).graph["dof"] == 4
