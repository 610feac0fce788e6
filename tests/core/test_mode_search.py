"""The global search for operation modes (screwkit.core.mode_search).

Tsai's 3-UPU (tests.mechanisms.tsai_3upu), derived by hand: in leg i the inner U axis w_i is
normal to the base's outer axis u_i and to the platform's, R u_i (R the platform's rotation from the
reference), and the leg C_i − A_i is normal to w_i. So wherever R u_i is not parallel to u_i,

    (p + R c_i − a_i) · (u_i × R u_i) = 0,   i = 1, 2, 3,

three equations on the platform's six coordinates (p its displacement). Their solution sets:

* R = I (or R a half turn about z, which maps every horizontal u_i to −u_i): no equation, p free:
  the platform translates, **3T**;
* R a rotation about z (or a half turn about a horizontal axis): every u_i × R u_i is vertical, the
  equations all say the platform lies in the base plane: x, y and the turn about z, **2T1R**;
* any other R: three linear equations in p with a generically invertible matrix, one p per R: the
  orientation is free and the position follows it, a twist system with no translation, **3R**.

So the linkage has (at least) three kinds of operation mode, not the two of the issue's wording
("3T and 3R"): the planar one is the mode met in the base plane (tests/core/test_mode_transitions.py).
Each configuration the search classifies is checked here by the platform's twists computed from its
joint screws by SVDs written in this file: the rank of their angular parts (rotations) and the
translations they contain (t = order + 3 − rank(twists with the three translations)).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.core.kinematic_model import KinematicModel
from screwkit.core.mode_search import find_operation_modes
from screwkit.core.motion import newton_closure
from screwkit.core.operation_modes import operation_modes
from screwkit.core.wrench_systems import analyze_table
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError, TwistGraphError
from screwkit.graphs.joints import revolute
from screwkit.graphs.jointtable import JointTable
from screwkit.graphs.twistgraph import twist_graph
from screwkit.robots.catalog import load_mechanism
from tests.mechanisms import moved, planar_3rpr, tsai_3upu
from tests.strategies import rigid_motions

SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
TRANSLATIONS = np.hstack([np.zeros((3, 3)), np.eye(3)])


def _null(rows, tol=1e-8):
    _, sigma, vt = np.linalg.svd(rows)
    return vt[int(np.sum(sigma > tol * sigma[0])):]


def platform_kind(table, index, legs, names):
    """(order, translations, rotations' rank) of the platform's twists at one configuration: each
    leg's wrenches are reciprocal to its joint screws, the platform's twists to every leg's."""
    wrenches = []
    for leg in legs:
        screws = np.vstack([table.joint_screws(name.format(leg))[index].reshape(-1, 6) for name in names])
        wrenches.append(_null(screws @ SWAP))
    twists = _null(np.vstack(wrenches) @ SWAP)
    order = len(twists)
    translations = order + 3 - np.linalg.matrix_rank(np.vstack([twists, TRANSLATIONS]), tol=1e-8)
    return order, int(translations), int(np.linalg.matrix_rank(twists[:, :3], tol=1e-8))


UPU_LEGS, UPU_NAMES = (1, 2, 3), ("Ub{}", "P{}", "Up{}")
#: (order, translations, rank of the angular parts) of each motion type, from the derivation above
EXPECTED = {"3T": (3, 3, 0), "2T1R": (3, 2, 1), "3R": (3, 0, 3)}


def joint_centre(table, index, name):
    """The centre of a universal joint: the point nearest both its axes (least squares on p × s = s0
    written out, as for tests/core/test_motion.py's spherical joints)."""
    rows = table.joint_screws(name)[index].reshape(-1, 6)
    system = np.concatenate([np.array([[0, s[2], -s[1]], [-s[2], 0, s[0]], [s[1], -s[0], 0]]) for s in rows[:, :3]])
    return np.linalg.lstsq(system, -np.concatenate(rows[:, 3:]), rcond=None)[0]


def test_3upu_from_a_generic_configuration_finds_its_three_kinds_of_mode():
    found = find_operation_modes(tsai_3upu([0.1, 0.05, 0.8]))
    assert found[0].motion_type == "3T" and found[0].reference
    assert sorted(mode.motion_type for mode in found) == ["2T1R", "3R", "3T", "3T"]
    # the two translational modes (module docstring: R = I, and R a half turn about z) are two
    # components: the platform keeps its orientation in each, so they are told apart by it; the
    # platform's triangle of U centres, read from the joint screws, is the reference's, or turned by π
    turned = next(mode for mode in found if mode.motion_type == "3T" and not mode.reference)
    assert found[0].turn == (0.0, 0.0, 0.0) and turned.name == "3T (turned 180° about (0, 0, 1))"
    reference_side = joint_centre(found.table, 0, "Up2") - joint_centre(found.table, 0, "Up1")
    for mode, sign in ((found[0], 1.0), (turned, -1.0)):
        for index in mode.indices:
            side = joint_centre(found.table, index, "Up2") - joint_centre(found.table, index, "Up1")
            assert np.allclose(side, sign * reference_side, atol=1e-8)
    for mode in found:
        for index in mode.indices:
            assert platform_kind(found.table, index, UPU_LEGS, UPU_NAMES) == EXPECTED[mode.motion_type]
    # the 3R mode's platform is turned: its outer U axes are no longer parallel to the base's
    turned = found.modes[[mode.motion_type for mode in found].index("3R")].indices[0]
    base_axis = found.table.joint_screws("Ub1")[turned][0, :3]
    platform_axis = found.table.joint_screws("Up1")[turned][1, :3]
    assert np.linalg.norm(np.cross(base_axis, platform_axis)) > 1e-3
    assert found.closed <= found.assemblies and found.reached == 12
    assert found.describe().startswith("4 operation modes: 3T (this one), ")
    assert found.describe().endswith("others may exist)")


def test_where_modes_meet_none_is_the_reference_s():
    found = find_operation_modes(tsai_3upu([0.1, 0.05, 0.0]))
    assert sorted(mode.motion_type for mode in found) == ["2T1R", "3R", "3T"]
    assert not any(mode.reference for mode in found)
    assert "(this configuration lies where some meet)" in found.describe()


def test_a_planar_linkage_has_one_mode():
    # every assembly of a linkage whose axes are all parallel to z moves in the plane normal to z
    # (x, y and turns about z): one mode, 2T1R, whatever the assembly
    base = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.8, 1.7, 0.0]]
    platform = [[0.9, 0.7, 0.0], [1.3, 0.6, 0.0], [1.0, 1.1, 0.0]]
    found = find_operation_modes(planar_3rpr(base, platform))
    assert [(mode.motion_type, mode.reference) for mode in found] == [("2T1R", True)]
    assert found.closed > 0
    for index in range(len(found.table)):
        assert platform_kind(found.table, index, (1, 2, 3), ("Ra{}", "P{}", "Rc{}")) == (3, 2, 1)
    assert found.describe().startswith("one operation mode: 2T1R (this one) (found in ")


def test_the_search_is_seeded():
    first, second = (find_operation_modes(tsai_3upu([0.3, -0.2, 0.5])) for _ in range(2))
    assert first.to_dict() == second.to_dict()
    assert np.array_equal(first.table.screws, second.table.screws)


@settings(max_examples=4, deadline=None)
@given(rigid_motions(), st.sampled_from([1e-3, 1.0, 1000.0]))
def test_same_modes_in_any_frame_and_length_unit(motion, factor):
    rotation, translation = motion
    found = find_operation_modes(moved(tsai_3upu([0.1, 0.05, 0.8]), rotation, translation, factor))
    assert (found[0].motion_type, found[0].reference) == ("3T", True)
    assert sorted(mode.motion_type for mode in found) == ["2T1R", "3R", "3T", "3T"]
    turn = next(mode.turn for mode in found if mode.motion_type == "3T" and not mode.reference)
    assert np.linalg.norm(turn) == pytest.approx(np.pi, abs=1e-6)  # half a turn about the frame's z
    assert abs(np.dot(turn, rotation @ [0.0, 0.0, 1.0])) == pytest.approx(np.pi, abs=1e-6)


def test_without_assemblies_only_the_reference_s_mode_is_reached():
    # three steps of 0.25 from a generic translating configuration stay in the 3T mode
    found = find_operation_modes(tsai_3upu([0.1, 0.05, 0.8]), assemblies=0)
    assert [(mode.motion_type, mode.reference) for mode in found] == [("3T", True)]
    assert found.closed == 0 and "found in 0 random assemblies of 0 and 12 configurations" in found.describe()


def test_to_dict_counts_every_configuration():
    found = find_operation_modes(tsai_3upu([0.1, 0.05, 0.8]))
    data = found.to_dict()
    assert sum(mode["configurations"] for mode in data["modes"]) == found.closed + found.reached
    assert data["complete"] is False


def test_bad_assemblies_and_a_rigid_linkage_are_refused():
    with pytest.raises(ScrewkitValueError, match=r"`assemblies` to be an integer in \[0, 10000\], got -1\."):
        find_operation_modes(tsai_3upu([0.1, 0.05, 0.8]), assemblies=-1)
    with pytest.raises(ScrewkitValueError, match=r"`assemblies` to be an integer in \[0, 10000\], got 2\.5\."):
        find_operation_modes(tsai_3upu([0.1, 0.05, 0.8]), assemblies=2.5)
    triangle = twist_graph("A", "C", [
        ("A", "B", revolute("R1", [0, 0, 1], [0, 0, 0])),
        ("B", "C", revolute("R2", [0, 0, 1], [1, 0, 0])),
        ("C", "A", revolute("R3", [0, 0, 1], [0, 1, 0]))])
    with pytest.raises(ScrewkitValueError, match="can move"):
        find_operation_modes(triangle)


def test_modes_are_reachable_at_the_top_level():
    import screwkit as sk
    from screwkit.core import mode_search, mode_transitions, operation_modes

    assert sk.find_operation_modes is find_operation_modes and sk.OperationModes is mode_search.OperationModes
    assert sk.modes_at is mode_transitions.modes_at and sk.ModesAtPose is mode_transitions.ModesAtPose
    assert sk.OperationMode is operation_modes.OperationMode
    assert {"find_operation_modes", "modes_at", "OperationModes", "OperationMode", "ModesAtPose"} <= set(sk.__all__)


def test_a_configuration_near_a_singular_one_is_no_mode_at_a_loose_rtol():
    # at rtol = 1e-3 one random assembly of the planar 3-RRP lies within 1e-3 of a singular
    # configuration and once read "1T1R"; moved by 0.05 it reads 2T1R: a planar linkage has one mode
    graph = load_mechanism("planar_3rrp").twist_graph()
    for rtol in (1e-9, 1e-5, 1e-3):
        assert find_operation_modes(graph, rtol=rtol).names() == ["2T1R (this one)"]


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ({"rtol": float("nan")}, ScrewkitValueError, r"`rtol` to be a number in \[0, 0.1\], got nan"),
        ({"rtol": "a"}, ScrewkitTypeError, r"`rtol` to be a number"),
        ({"assemblies": 10**8}, ScrewkitValueError, r"`assemblies` to be an integer in \[0, 10000\]"),
        ({"joint_key": "nope"}, TwistGraphError, r"expected attribute 'nope' holding a Joint"),
    ],
)
def test_bad_arguments_are_named(arguments, error, message):
    with pytest.raises(error, match=message):
        find_operation_modes(load_mechanism("planar_3rrp").twist_graph(), **arguments)
    with pytest.raises(TwistGraphError, match=r"Expected a networkx\.MultiDiGraph, got str"):
        find_operation_modes("x")


def smallest_turn(model, theta):
    """(joint motions, smallest singular value of the angular parts of an orthonormal basis of the
    platform's twists) at one configuration: the twists are the platform's link Jacobian over the
    loops' null space (scaled by the model's characteristic length), both by SVDs written here; the
    value is how close the twist system comes to holding a translation (0: it holds one)."""
    state = model.state(theta[None])
    allowed = _null(model.loop_jacobian(state)[0]).T
    twists = model.link_jacobian(state, "platform")[0] @ allowed
    u, sigma, _ = np.linalg.svd(twists)
    basis = u[:, :int(np.sum(sigma > 1e-9 * sigma[0]))]
    return allowed.shape[1], np.linalg.svd(basis[:3], compute_uv=False)[-1]


def test_the_delta_s_1t2r_class_at_a_loose_rtol_is_its_3r_mode():
    # At rtol 1e-3 the Delta (rods between spherical joints, no joint limits) lists a third class,
    # "1T2R", which no assembly reads at 1e-9. Its configuration is one of the 3R mode: its platform's
    # twists hold no translation (smallest angular singular value 1e-3, far above round-off) but come
    # within 1e-3 of one (the platform turns by 1e-3 per characteristic length in one direction). A
    # path along the loops' motions from it (steps of 0.05, closed again) keeps the loops' nullity
    # (no singular configuration of the configuration space crossed: the same component) and the 3R
    # reading at 1e-9, while the angular part grows and the 1e-3 reading turns to 3R: it is a region of
    # the 3R mode read at a tolerance it cannot be told from 1T2R at, not a mode. Left as found:
    # the search's classes are the readings at the given rtol (docs/operation_modes.md, Limits).
    graph = load_mechanism("delta").twist_graph()
    assert find_operation_modes(graph).names() == ["3T (this one)", "3R"]
    found = find_operation_modes(graph, rtol=1e-3)
    assert found.names() == ["3T (this one)", "3R", "1T2R"]
    start = found.table.graph(found[2].indices[0])
    model = KinematicModel(start)
    theta = np.zeros(model.size)
    joint_motions, turn = smallest_turn(model, theta)
    assert 1e-4 < turn < 2e-3
    direction = np.random.default_rng(2).standard_normal(model.size)
    readings = []
    for _ in range(10):
        allowed = _null(model.loop_jacobian(model.state(theta[None]))[0]).T
        step = allowed @ (allowed.T @ direction)
        closed, residual = newton_closure(model, (theta + 0.05 * step / np.max(np.abs(step)))[None])
        assert residual[0] < 1e-9
        theta = closed[0]
        motions, turn = smallest_turn(model, theta)
        assert motions == joint_motions == 9  # three freedoms and the six rods' spins
        table = model.joint_table(model.state(theta[None]), JointTable.from_graph(start))
        readings.append([operation_modes(analyze_table(table, rtol=rtol))[0].motion_type for rtol in (1e-9, 1e-3)])
    assert readings[0] == ["3R", "1T2R"] and readings[-1] == ["3R", "3R"]
    assert all(at_1e9 == "3R" for at_1e9, _ in readings) and turn > 1e-2


def test_a_loose_rtol_takes_no_unclosed_assembly_as_closed():
    # The Ragnar's data close exactly; of 200 random assemblies Gauss–Newton leaves one at a residual
    # of 0.044 characteristic lengths (a stall, no configuration of the linkage). The data's precision
    # (rtol 0.1) must not make it closed: assemblies are closed at the loop closure's own 1e-9.
    from screwkit.core.mode_search import SEED, random_assemblies

    graph = load_mechanism("ragnar").twist_graph()
    model = KinematicModel(graph)
    rows = random_assemblies(model, np.random.default_rng(SEED), 200)
    residual = np.max(np.abs(model.loop_residual(model.state(rows))), axis=1)
    assert 190 <= len(rows) < 200 and np.all(residual < 1e-9)
    # the search draws the same assemblies at any rtol: it must close the same ones (the McGill SMG's
    # 300 assemblies: 287 close, and rtol 0.1 took 4 more, stalled, as closed)
    smg = load_mechanism("mcgill_smg").twist_graph()
    assert find_operation_modes(smg, rtol=0.1, assemblies=300).closed == find_operation_modes(
        smg, assemblies=300).closed == 287


def test_rounded_data_close_at_the_loop_closure_s_tolerance():
    # Bennett's linkage of 100 mm links given to 0.01 mm (tests/overconstrained.py; mobile at rtol 1e-3
    # only, tests/core/test_mobility.py) is a rigid structure at 1e-9 whose assemblies are exact
    # solutions of its loop equations: Gauss–Newton closes them to round-off
    from tests.overconstrained import bennett as rounded_bennett

    found = find_operation_modes(rounded_bennett(decimals=2, scale=100.0), rtol=1e-3)
    assert found.closed > 0 and len(found) >= 1
