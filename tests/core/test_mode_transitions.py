"""Operation modes through a pose (core.mode_transitions) and mobility of an overconstrained linkage.

Expected values are hand derivations from the geometry, checked by rank computations written here:

* Tsai's 3-UPU with its platform in the base plane (z = 0): every leg's inner U axis w_i = u_i × d_i
  is vertical, so each leg is also a planar R-P-R chain with vertical axes, and the mechanism is a
  planar 3-RPR there; it moves in that plane (x, y, rotation about z: 2T1R) as well as translating
  (3T): the two modes meet at every such pose (a constraint singularity that is a C-space
  singularity, the situation of Zlatanov, Bonev & Gosselin 2002). First-order motions there: x, y,
  z and the rotation about z, 4 (each leg's five screws independent, no idle motion).
* Bennett's 4R linkage (Bennett 1903): the Chebychev-Grübler-Kutzbach count 6(4 - 4 - 1) + 4 = -2
  says rigid; with a / sin α = b / sin β its four axes are linearly dependent and it moves with one
  freedom along a finite path (its links keep their common normals: lengths a, b and twists α, β).
"""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from screwkit.core.mobility import generic_mobility
from screwkit.core.mode_transitions import modes_at
from screwkit.core.motion import generic_configurations
from screwkit.exceptions import ScrewkitValueError, TwistGraphError
from tests.mechanisms import UPU_ANGLES, Z, bennett, bennett_axes, bennett_links, moved, tsai_3upu
from tests.strategies import rigid_motions


def leg_screws(graph, leg):
    """The joint screws (rows) of one 3-UPU leg, from the graph's joints."""
    names = (f"Ub{leg}", f"P{leg}", f"Up{leg}")
    rows = [np.atleast_2d(d["joint"].screws) for _, _, d in graph.edges(data=True) if d["joint"].name in names]
    return np.vstack(rows)


def reciprocal_basis(rows):
    """Screws reciprocal to the rows (ω; v)·(f; m) = ω·m + v·f, by an SVD written here."""
    swapped = np.hstack([rows[:, 3:], rows[:, :3]])
    _, sigma, vt = np.linalg.svd(swapped)
    rank = int(np.sum(sigma > 1e-9 * sigma[0]))
    return vt[rank:]


def platform_twists(graph):
    """The 3-UPU platform's twists: reciprocal to every leg's constraint wrenches."""
    wrenches = np.vstack([reciprocal_basis(leg_screws(graph, leg)) for leg in (1, 2, 3)])
    return reciprocal_basis(wrenches)


def test_3upu_in_its_base_plane_lies_where_translation_and_planar_modes_meet():
    result = modes_at(tsai_3upu((0.1, 0.05, 0.0)))
    assert result.meets
    assert result.first_order == 4
    assert sorted(mode.motion_type for mode in result.modes) == ["2T1R", "3T"]
    for mode in result.modes:
        twists = platform_twists(mode.nearby.graph)
        assert twists.shape[0] == mode.mobility == 3
        if mode.motion_type == "3T":  # pure translations: no angular part
            assert np.allclose(twists[:, :3], 0.0, atol=1e-8)
        else:  # plane motion: angular parts along z, no velocity along z
            assert np.allclose(twists[:, :2], 0.0, atol=1e-8) and np.allclose(twists[:, 5], 0.0, atol=1e-8)
            assert np.linalg.matrix_rank(twists[:, 2:3], tol=1e-8) == 1
        # the pose itself, as a configuration of either mode, has a fourth freedom it must not have
        assert mode.at_pose.verdict == "constraint singularity"
    assert "2 operation modes meet" in result.describe()


def test_3upu_above_its_base_has_one_mode():
    result = modes_at(tsai_3upu((0.1, 0.2, 0.6)))
    assert not result.meets and result.first_order == 3
    assert [mode.motion_type for mode in result.modes] == ["3T"]
    assert np.allclose(platform_twists(result.modes[0].nearby.graph)[:, :3], 0.0, atol=1e-8)
    assert result.modes[0].at_pose.verdict == "regular"


def test_four_generic_axes_are_rigid_and_refused():
    graph = bennett(links=bennett_links(bennett=False))
    assert generic_mobility(graph) == 0  # four generic lines: rank 4, rigid as Grübler says
    with pytest.raises(ScrewkitValueError, match="admit no joint motion"):
        modes_at(graph)


def axis_of(row):
    """A revolute twist (u; p × u) as its direction and the point of its axis nearest the origin."""
    return row[:3] / np.linalg.norm(row[:3]), np.cross(row[:3], row[3:]) / np.dot(row[:3], row[:3])


def common_normal(first, second):
    """Length and twist angle between two axes (direction, point)."""
    (u, p), (v, q) = first, second
    normal = np.cross(u, v)
    return abs(np.dot(q - p, normal)) / np.linalg.norm(normal), np.arccos(np.clip(abs(np.dot(u, v)), -1, 1))


def test_bennett_linkage_moves_with_one_freedom():
    axes, closure = bennett_axes(0.9, bennett_links())
    assert np.allclose(closure, np.eye(4), atol=1e-12)  # the builder's loop closes
    graph = bennett()
    assert generic_mobility(graph) == 1
    result = modes_at(graph)
    assert not result.meets and result.modes[0].mobility == 1
    table = generic_configurations(graph, np.random.default_rng(3), 4)
    links = bennett_links()
    for i in range(table.batch_shape[0]):
        rows = {d["joint"].name: np.atleast_2d(d["joint"].screws)[0] for _, _, d in table.graph(i).edges(data=True)}
        moved = [axis_of(rows[f"R{k}"]) for k in (1, 2, 3, 4)]
        for k in range(4):  # rigid links: every common normal kept along the finite motion
            length, twist = common_normal(moved[k], moved[(k + 1) % 4])
            assert length == pytest.approx(links[k][0], abs=1e-8)
            assert twist == pytest.approx(min(links[k][1], np.pi - links[k][1]), abs=1e-8)
        assert not np.allclose(moved[2][0], axes[2][0], atol=1e-3)  # a configuration away from the start


# Frames in which a step of modes_at once ended between the two branches: closed to 7e-12 but 1.7e-5
# from the transition set, its twists read "2T1H" (pitch -0.016, and -1.5e-6 in the second frame)
TURNED = np.array([[-0.33528188644529466, -0.42991190899217, 0.8383088972022144],
                   [0.42991190899217, 0.7219509357057997, 0.5421831765558836],
                   [-0.8383088972022144, 0.5421831765558836, -0.057232822151094265]])
TURNED_AGAIN = np.array([[-0.4030964372318595, -0.37306472673008767, 0.8356649878753963],
                         [0.37306472673008767, 0.7668345457936953, 0.5222906174221227],
                         [-0.8356649878753963, 0.5222906174221227, -0.16993098302555465]])


@settings(max_examples=4, deadline=None)
@given(rigid_motions(), st.sampled_from([1.0, 1000.0]))
@example((TURNED, np.zeros(3)), 1.0)
@example((TURNED_AGAIN, np.zeros(3)), 1.0)
def test_modes_at_same_in_any_frame_and_length_unit(motion, factor):
    rotation, translation = motion
    result = modes_at(moved(tsai_3upu((0.1, 0.05, 0.0)), rotation, translation, factor))
    assert result.meets and result.first_order == 4
    assert sorted(mode.motion_type for mode in result.modes) == ["2T1R", "3T"]


def test_a_pitch_of_round_off_is_no_helical_mode():
    # seen in a frame half-turned about a horizontal axis (quaternion (0, 1/32, 1, 0)), one of the 16
    # closed configurations once read "2T1H" (pitch -1.4e-9 against a threshold of 7.9e-10): Newton
    # closes the loops to 1e-9, so the twists carry round-off of that size
    w, x, y, z = np.array([0.0, 1 / 32, 1.0, 0.0]) / np.hypot(1 / 32, 1.0)
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])
    result = modes_at(moved(tsai_3upu((0.1, 0.05, 0.0)), rotation, np.zeros(3), 1.0))
    assert sorted(mode.motion_type for mode in result.modes) == ["2T1R", "3T"]


def test_not_a_twist_graph_is_refused_by_name():
    with pytest.raises(TwistGraphError, match=r"Expected a networkx\.MultiDiGraph, got NoneType"):
        modes_at(None)


def meeting_positions(axis, platform_radius=0.5):
    """Where Tsai's 3-UPU's turning (3R) mode meets its translating one (R = I), approached by turns
    about ``axis``: the positions p solving p · m_i = (1 − ρ) r_i · k, m_i = k − (k · u_i) u_i
    (module docstring of tests/core/test_mode_search.py: (p + R c_i − a_i) · (u_i × R u_i) = 0 with
    R = exp(θ k̂), divided by sin θ, as θ → 0; base radius 1, c_i = ρ r_i)."""
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    rows, values = [], []
    for angle in UPU_ANGLES:
        r = np.array([np.cos(angle), np.sin(angle), 0.0])
        u = np.cross(Z, r)
        rows.append(k - (k @ u) * u)
        values.append((1 - platform_radius) * (r @ k))
    return np.linalg.solve(np.array(rows), values)


def test_which_modes_pass_through_the_3upu_in_its_base_plane():
    # Derivation (the 3-UPU's three kinds of mode: tests/core/test_mode_search.py). The 3T mode
    # (R = I) and the 2T1R mode (R about z, p_z = 0) contain (R = I, p0 = (0.1, 0.05, 0)). The 3R
    # mode reaches R = I only in the limit of its equations divided by sin θ, R = exp(θ k̂):
    #     (p − (1 − ρ) r_i) · (k − (k · u_i) u_i) = 0,   i = 1, 2, 3.
    # At p0 (horizontal, r_i ⊥ u_i) the left side is s_i (k_h · r_i), s_i = p0 · r_i − (1 − ρ) ≠ 0:
    # only k = ±z, the axis of the planar mode itself. Next to it, k = (ε g, 1), p_z = ε q, the
    # equations to first order in ε read q + s_i (g · r_i) = 0: a 3 × 3 system in (q, g) whose
    # matrix [1, s_i r_i] is invertible, so g = 0 (implicit function theorem): the solutions next
    # to (R = I, p0) are those of the planar mode, and the 3R mode does not pass through the pose.
    p0 = np.array([0.1, 0.05, 0.0])
    radial = np.array([[np.cos(a), np.sin(a), 0.0] for a in UPU_ANGLES])
    s = radial @ p0 - 0.5
    assert np.all(np.abs(s) > 0.3)
    matrix = np.column_stack([np.ones(3), s[:, None] * radial[:, :2]])
    assert abs(np.linalg.det(matrix)) > 0.1 * np.prod(np.abs(s))
    assert sorted(mode.motion_type for mode in modes_at(tsai_3upu(p0)).modes) == ["2T1R", "3T"]
    # the control: where the derivation says the 3R mode meets the 3T mode (turns about k), the
    # search finds both, with one more first-order motion (the turn about k)
    for axis in ([1.0, 1.0, 1.0], [0.3, -0.2, 1.0]):
        result = modes_at(tsai_3upu(meeting_positions(axis)))
        assert result.first_order == 4
        assert sorted(mode.motion_type for mode in result.modes) == ["3R", "3T"]
