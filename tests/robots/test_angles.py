"""The one angle convention: every pose-taking function takes ``angles="rad"|"deg"``, default radians."""

import inspect
import math
import warnings

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import loci, paths, workspace
from screwkit.exceptions import ScrewkitValueError
from screwkit.robots.angles import AngleUnitWarning, poses_in_radians
from screwkit.robots.mechanism import Mechanism

POSE_TAKING = [
    Mechanism.at,
    Mechanism.configuration,
    Mechanism.joints,
    Mechanism.twist_graph,
    Mechanism.twist_basis,
    Mechanism.jacobians,
    Mechanism.wrench_diagram,
    workspace.grid_map,
    workspace.sweep,
    loci.loci,
    loci.surfaces,
    paths.check_path,
    sk.analyze,
]


@pytest.mark.parametrize("function", POSE_TAKING, ids=lambda f: f.__qualname__)
def test_every_pose_taking_function_takes_angles_with_the_same_default(function):
    parameter = inspect.signature(function).parameters["angles"]
    assert parameter.default == "rad" and parameter.kind == parameter.KEYWORD_ONLY


@pytest.fixture(scope="module")
def h4():
    return sk.load_mechanism("h4")


def test_degrees_and_radians_give_the_same_posed_mechanism(h4):
    degrees = np.array([[30, -20, -750, 17], [0, 0, -800, -40]])
    radians = degrees * [1, 1, 1, math.pi / 180]  # by hand: only phi is an angle
    by_degrees, by_radians = h4.at(degrees, angles="deg"), h4.at(radians)
    np.testing.assert_allclose(by_degrees.poses, radians, rtol=1e-15)
    assert by_degrees.verdicts.tolist() == by_radians.verdicts.tolist()
    np.testing.assert_allclose(by_degrees.closeness["actuation"], by_radians.closeness["actuation"])
    one_deg, one_rad = degrees[0], radians[0]
    np.testing.assert_allclose(h4.twist_basis(one_deg, angles="deg"), h4.twist_basis(one_rad))
    np.testing.assert_allclose(h4.jacobians(one_deg, angles="deg").A, h4.jacobians(one_rad).A)
    np.testing.assert_allclose(
        h4.configuration(one_deg, angles="deg").theta, h4.configuration(one_rad).theta
    )
    np.testing.assert_allclose(h4.joints(one_deg, angles="deg").screws, h4.joints(one_rad).screws)
    graph_deg, graph_rad = h4.twist_graph(one_deg, angles="deg"), h4.twist_graph(one_rad)
    assert sorted(graph_deg.edges) == sorted(graph_rad.edges)
    report = sk.analyze(h4, one_deg, angles="deg", superbracket=False)
    np.testing.assert_allclose(report.pose, one_rad)
    assert "phi = 17 deg" in str(report)  # the echo states its unit


def test_a_whole_turn_in_radians_warns_and_names_degrees(h4):
    # the case: 45 meant as degrees, read as 45 rad (2578 deg)
    with pytest.warns(AngleUnitWarning, match=r"`phi` of `poses` is 45 rad .*angles='deg'"):
        h4.at([[0, 0, -750, 45]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        posed = h4.at([[0, 0, -750, 45]], angles="deg")
        h4.at([[0, 0, -750, 2 * math.pi - 1e-9]])  # up to a turn is a plain radian angle
    assert posed.poses[0, 3] == pytest.approx(math.pi / 4)


@pytest.mark.parametrize(
    "call",
    [
        lambda h4: h4.at(angles="grad"),
        lambda h4: h4.joints(angles="degrees"),
        lambda h4: h4.twist_graph(angles=None),
        lambda h4: h4.wrench_diagram(angles="DEG"),
        lambda h4: sk.analyze(h4, angles="turns", superbracket=False),
        lambda h4: workspace.grid_map(h4, "verdict", x=("z", -800, -700, 2), y=("phi", 0, 1, 2), angles="gon"),
    ],
)
def test_other_angle_units_are_refused_naming_the_argument(h4, call):
    with pytest.raises(ScrewkitValueError, match=r"Expected `angles` to be 'deg' or 'rad', got"):
        call(h4)


def test_maps_in_degrees_and_radians_agree(h4):
    by_degrees = workspace.grid_map(
        h4, "closeness:actuation", x=("z", -800, -700, 3), y=("phi", -30, 30, 3), angles="deg"
    )
    by_radians = workspace.grid_map(
        h4, "closeness:actuation", x=("z", -800, -700, 3), y=("phi", -math.pi / 6, math.pi / 6, 3)
    )
    np.testing.assert_allclose(by_degrees.values, by_radians.values)
    assert by_degrees.units["phi"] == "deg" and by_radians.units["phi"] == "rad"


def test_non_poses_pass_through_for_the_callee_to_name():
    names, angles = ("x", "y", "z", "phi"), ("phi",)
    assert poses_in_radians(None, names, angles, "deg") is None
    assert poses_in_radians("text", names, angles, "deg") == "text"
    three = [1.0, 2.0, 3.0]
    assert poses_in_radians(three, names, angles, "deg") is three
