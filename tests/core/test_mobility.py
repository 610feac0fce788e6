"""Mobility honours rtol as the data's precision: overconstrained linkages given with rounded
coordinates (Bennett 1903; Sarrus) are mobile at a loose rtol, rigid at the default; a stated dof
is then accepted; a tolerance out of range is refused naming `rtol`."""

import numpy as np
import pytest

from screwkit.algebra.motion_type import motion_type
from screwkit.core.mobility import generic_mobility
from screwkit.core.singularity import classify
from screwkit.exceptions import ScrewkitError, TwistGraphError
from screwkit.graphs.joints import prismatic, revolute, universal
from screwkit.graphs.twistgraph import twist_graph
from tests.mechanisms import UPU_ANGLES, tsai_3upu
from tests.overconstrained import bennett, bennett_angles, bennett_loop_error, sarrus


@pytest.mark.parametrize("theta1", [0.7, -2.0, 2.5])
def test_the_bennett_closure_relation_closes_the_loop(theta1):
    # McCarthy & Soh 2011 §9.5's input-output relation, checked by multiplying the 4x4 matrices
    assert bennett_loop_error(bennett_angles(theta1)) < 1e-12


@pytest.mark.parametrize("linkage", [bennett, sarrus])
def test_exact_overconstrained_linkages_have_one_freedom(linkage):
    # Grübler–Kutzbach counts 6 (4 − 1) − 4·5 = −2 for Bennett's 4R, 6 (6 − 1) − 6·5 = 0 for
    # Sarrus' 6R: both move with one freedom (Bennett 1903; Sarrus 1853)
    assert [generic_mobility(linkage(), rtol=r) for r in (1e-9, 1e-4)] == [1, 1]


@pytest.mark.parametrize(
    ("linkage", "scale", "decimals", "loose"),
    [
        (bennett, 1.0, 6, 1e-4),  # unit-size links to 6 decimals: axes off by ~1e-6
        (sarrus, 1.0, 6, 1e-4),
        (bennett, 100.0, 2, 1e-3),  # 100 mm links to 0.01 mm: axes off by ~1e-4 (two points 50 mm apart)
        (sarrus, 100.0, 2, 1e-3),
    ],
)
def test_rounded_overconstrained_linkages_are_mobile_at_their_data_precision(linkage, scale, decimals, loose):
    graph = linkage(decimals=decimals, scale=scale)
    # at 1e-9 the rounding is data: the rounded loop is a rigid structure
    assert generic_mobility(graph, rtol=1e-9) == 0
    assert generic_mobility(graph, rtol=loose) == 1
    report = classify(graph, rtol=loose, dof=1)  # the stated dof is the right one: accepted
    assert report.dof == 1
    with pytest.raises(TwistGraphError, match=r"mobility[^,]*, 0 .*dof = 1"):
        classify(graph, dof=1)


def test_a_loose_rtol_does_not_make_a_rigid_loop_mobile():
    # a general spatial 4R loop (Bennett's conditions broken: a / sin α ≠ b / sin β by 30 %) is
    # rigid, far beyond any data precision
    joints = [
        revolute("R1", [0, 0, 1], [0, 0, 0]),
        revolute("R2", [0, 1, 1], [1, 0, 0]),
        revolute("R3", [1, 0, 1], [1.3, 1, 0.2]),
        revolute("R4", [1, 1, 0], [0, 1.1, 0.5]),
    ]
    graph = twist_graph(
        "ground",
        "platform",
        [
            ("ground", "L1", joints[0]),
            ("L1", "platform", joints[1]),
            ("L3", "platform", joints[2]),
            ("ground", "L3", joints[3]),
        ],
    )
    assert generic_mobility(graph, rtol=0.01) == 0


@pytest.mark.parametrize("rtol", [0.5, -1e-3, float("nan"), "1e-4"])
def test_an_out_of_range_data_tolerance_is_one_line_naming_rtol(rtol):
    with pytest.raises(ScrewkitError, match=r"^Expected `rtol` to be a number in \[0, 0\.1\], got") as info:
        generic_mobility(bennett(decimals=6), rtol=rtol)
    assert "\n" not in str(info.value)
    with pytest.raises(ScrewkitError, match=r"`rtol`"):
        classify(bennett(decimals=6), rtol=rtol)


def test_rtol_is_a_precision_in_any_unit():
    # millimetres or metres: the same rounded linkage (6 decimals of metres = 3 decimals of mm)
    metres = bennett(decimals=6)
    millimetres = bennett(decimals=3, scale=1000.0)
    assert [generic_mobility(g, rtol=1e-4) for g in (metres, millimetres)] == [1, 1]


def rounded_tsai_3upu(position, decimals):
    """Tsai's 3-UPU (tests.mechanisms.tsai_3upu) with its platform joints' axes and centres rounded
    to ``decimals`` (the base joints exact): the inner axes are then parallel only to the data's
    precision."""
    joints = []
    for i, angle in enumerate(UPU_ANGLES, start=1):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        a, c = radial, np.asarray(position, float) + 0.5 * radial
        u = np.cross([0.0, 0, 1], radial)
        d = (c - a) / np.linalg.norm(c - a)
        w = np.cross(u, d) / np.linalg.norm(np.cross(u, d))
        joints += [
            ("base", f"lower{i}", universal(f"Ub{i}", u, w, a)),
            (f"lower{i}", f"upper{i}", prismatic(f"P{i}", d, actuated=True)),
            (f"upper{i}", "platform", universal(f"Up{i}", *(np.round(v, decimals) for v in (w, u, c)))),
        ]
    return twist_graph("base", "platform", joints)


def test_a_rounded_3upu_translates_at_its_data_precision():
    # Tsai's 3-UPU translates (each leg's constraint is a couple normal to its two U's parallel inner
    # and outer axes; three such couples leave 3T). Rounded, the inner axes are skew by ~1e-6: at
    # 1e-9 that is a different (rotating) 3-DOF mechanism; at 1e-4 it is Tsai's.
    graph = rounded_tsai_3upu([0.1, 0.05, 0.8], 6)
    exact = classify(tsai_3upu([0.1, 0.05, 0.8]))
    rounded = classify(graph, rtol=1e-4, dof=3)
    assert motion_type(exact.analysis.platform_twists) == "3T"
    assert (rounded.dof, motion_type(rounded.analysis.platform_twists)) == (3, "3T")
    assert motion_type(classify(graph).analysis.platform_twists) != "3T"
