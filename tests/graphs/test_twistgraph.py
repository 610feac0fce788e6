"""Tests of screwkit.graphs.twistgraph: known twist systems, invariants, reduction vs loop closure, errors."""

import json

import networkx as nx
import numpy as np
import pytest
import sympy
from hypothesis import given, settings

from screwkit.algebra import screw as S
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.exceptions import TwistGraphError
from screwkit.graphs.joints import prismatic, revolute, spherical
from screwkit.graphs.loops import fundamental_loops, joint_screws_along, loop_closure_matrix, simple_paths
from screwkit.graphs.reduction import equivalent_twist_graph, platform_twist_system, series_parallel_tree
from screwkit.graphs.twistgraph import (
    add_joint,
    check_twist_graph,
    from_data,
    graph_frame,
    to_data,
    twist_graph,
)

from ..mechanisms import (
    PLANAR_BASE,
    PLANAR_PLATFORM,
    Z,
    gough_stewart,
    gough_stewart_points,
    leg_lines,
    moved,
    planar_3rpr,
    r_4s_leg,
    random_series_parallel,
    rotation_z,
    tsai_3upu,
    unit,
    wheatstone_bridge,
)
from ..strategies import rigid_motions, seeds, unit_factors

METHODS = ["loop_closure", "reduction"]
TRANSLATIONS = ScrewSystem.span(np.hstack([np.zeros((3, 3)), np.eye(3)]))

# paper 002 §4.1 (Fig. 2): a 4S parallelogram m n q p with mn ∥ pq and mp ∥ nq; the arm's hinge
# axis is parallel to mn (paper 002 §4.2: s_1 ∥ s_mn)
M = np.array([1.2, 0.3, 0.1])
HINGE_AXIS = unit([0.0, 1.0, 0.0])
N = M + 0.3 * HINGE_AXIS
ROD = np.array([0.2, -0.3, -0.9])
P, Q = M + ROD, N + ROD
S_MP, S_MN = unit(P - M), unit(N - M)
NORMAL = unit(np.cross(S_MN, S_MP))


def four_s_leg(end="platform"):
    return r_4s_leg(1, [1.0, 0, 0], HINGE_AXIS, M, N, P, Q, end=end)


def paper_4s_twists():
    """T_4S = span(ε01, ε02, ε∞1, ε∞2) as printed in paper 002 §4.1."""
    return ScrewSystem.span(
        [S.line(S_MP, P), S.line(S_MN, N), S.couple(NORMAL), S.couple(np.cross(S_MP, NORMAL))]
    )


def gs_graph(angle=0.3):
    return gough_stewart(*gough_stewart_points(rotation_z(angle), (0.1, -0.05, 1.0)))


# known values ----------------------------------------------------------------------------------
def test_serial_chain_twists_are_the_sum_of_its_joints():
    G = twist_graph("B", "E", [
        ("B", "arm", revolute("R", [0, 0, 1], [0, 0, 0])),
        ("arm", "E", prismatic("P", [1, 0, 0])),
    ])
    expected = ScrewSystem.span([S.line([0, 0, 1], [0, 0, 0]), S.couple([1, 0, 0])])
    for method in METHODS:
        assert platform_twist_system(G, method=method).is_equivalent(expected)


@pytest.mark.parametrize("method", METHODS)
def test_a_rod_between_two_spherical_joints_transmits_only_the_force_along_it(method):
    # paper 002 §4.1: the wrench system of S_m - S_p is span(τ01), τ01 = (s_mp, r_p × s_mp)
    G = twist_graph("B", "E", [("B", "rod", spherical("Sm", M)), ("rod", "E", spherical("Sp", P))])
    twists = platform_twist_system(G, method=method)
    assert twists.order == 5
    assert twists.reciprocal().is_equivalent(ScrewSystem.span([S.line(S_MP, P)]))


@pytest.mark.parametrize("method", METHODS)
def test_4s_parallelogram_twist_system_is_the_printed_4_system(method):
    G = twist_graph("arm1", "platform", four_s_leg()[1:])
    assert platform_twist_system(G, method=method).is_equivalent(paper_4s_twists())


@pytest.mark.parametrize("method", METHODS)
def test_r_4s_leg_twist_system_and_its_constraint_couple(method):
    # paper 002 §4.2: T_i = span(ε01..ε∞2) with the hinge; W_i = span((0, n_i)) (R ∥ s_mn)
    G = twist_graph("base", "platform", four_s_leg())
    twists = platform_twist_system(G, method=method)
    assert twists.order == 5
    assert twists.reciprocal().is_equivalent(ScrewSystem.span([S.couple(NORMAL)]))


@pytest.mark.parametrize("method", METHODS)
def test_tsai_3upu_platform_only_translates(method):
    assert platform_twist_system(tsai_3upu([0.1, 0.05, 0.8]), method=method).is_equivalent(TRANSLATIONS)


@pytest.mark.parametrize("method", METHODS)
def test_planar_3rpr_platform_moves_in_its_plane(method):
    plane = ScrewSystem.span([S.line(Z, [0, 0, 0]), S.couple([1, 0, 0]), S.couple([0, 1, 0])])
    assert platform_twist_system(planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM), method=method).is_equivalent(plane)


@pytest.mark.parametrize("method", METHODS)
def test_gough_stewart_platform_is_free_and_two_skew_hinges_lock(method):
    assert platform_twist_system(gs_graph(), method=method).order == 6
    G = twist_graph("B", "E", [
        ("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
        ("B", "E", revolute("R2", [0, 1, 0], [1, 0, 0])),
    ])
    assert platform_twist_system(G, method=method).order == 0


def test_locked_legs_leave_the_twists_reciprocal_to_the_leg_lines():
    # 6-UPS with its P joints locked: the platform twists are the reciprocal of the six leg lines,
    # none at a regular pose, one at Fichter's singular pose (platform turned by 90° about z)
    for angle, order in [(0.3, 0), (np.pi / 2, 1)]:
        base, platform = gough_stewart_points(rotation_z(angle))
        G = gough_stewart(base, platform)
        locked = platform_twist_system(G, locked=[f"P{i}" for i in range(1, 7)])
        reciprocal = ScrewSystem.span(leg_lines(base, platform)).reciprocal()
        assert locked.order == order
        assert locked.is_equivalent(reciprocal)


def test_internal_spin_of_a_rod_is_not_a_platform_twist():
    # regression: the rod of an S-S chain spins about its own line; with the spanning-tree path
    # through the hinge "A" that internal motion mapped to a round-off twist counted as a freedom
    G = twist_graph("B", "E", [
        ("B", "E", revolute("A", [0.3, 1, 0.2], [0.5, -0.2, 0.1])),
        ("B", "rod", spherical("S1", [0.1, 0.2, 0.3])),
        ("rod", "E", spherical("S2", [0.9, -0.4, 1.1])),
    ])
    assert platform_twist_system(G).order == 0
    assert platform_twist_system(G, method="reduction").order == 0


def test_graph_frame_of_two_perpendicular_skew_axes():
    # axes z through (d, 0, 0) and y through the origin: the common perpendicular is the x axis
    # from 0 to d; the least-squares point is its midpoint, each axis at distance d / 2
    d = 100.0
    G = twist_graph("B", "E", [
        ("B", "L", revolute("R1", [0, 0, 1], [d, 0, 0])),
        ("L", "E", revolute("R2", [0, 1, 0], [0, 0, 0])),
    ])
    point, length = graph_frame(G)
    np.testing.assert_allclose(point, [d / 2, 0, 0], atol=1e-9)
    assert length == pytest.approx(d / 2, rel=1e-12)
    # only translations: no finite axis, the origin and length 1
    G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 2, 3]))])
    point, length = graph_frame(G)
    np.testing.assert_array_equal(point, 0.0)
    assert length == 1.0


def test_graph_frame_of_concurrent_axes_is_usable():
    # a spherical wrist R-R-R with axes through c: the length of graph_frame is the RMS distance
    # of the axes from c, i.e. zero, which should fall back to 1; it comes out as ~1e-16, and the
    # ranks decided with it are wrong (the wrist's 3 rotations give a 2-system)
    c = [0.3, 0.7, 0.1]
    G = twist_graph("B", "E", [
        ("B", "L1", revolute("R1", [1, 2, 0], c)),
        ("L1", "L2", revolute("R2", [0, 1, 3], c)),
        ("L2", "E", revolute("R3", [-2, 0.5, 1], c)),
    ])
    assert graph_frame(G)[1] > 1e-9
    assert platform_twist_system(G).order == 3


def test_fundamental_loops_of_known_mechanisms():
    # E - V + 1: 6-UPS 18 joints, 14 links; 3-UPU 9, 8; R-(4S) 5, 5; the bridge 5, 4
    for G, count in [(gs_graph(), 5), (tsai_3upu([0, 0, 1.0]), 2), (twist_graph("base", "platform", four_s_leg()), 1),
                     (wheatstone_bridge(), 2)]:
        loops = fundamental_loops(G)
        assert len(loops) == count == G.number_of_edges() - G.number_of_nodes() + 1
        matrix, columns = loop_closure_matrix(G)
        assert matrix.shape == (6 * count, sum(j.dof for _, _, j in G.edges(data="joint")))
        assert len(columns) == matrix.shape[1]


def test_fundamental_loops_close_and_start_with_their_chord():
    G = gs_graph()
    tree_edges = set()
    for loop in fundamental_loops(G):
        start = loop[0][0] if loop[0][3] == "forward" else loop[0][1]
        current = start
        for u, v, key, direction in loop:
            assert G.has_edge(u, v, key)
            assert current == (u if direction == "forward" else v)
            current = v if direction == "forward" else u
        assert current == start
        tree_edges.update(edge[:3] for edge in loop[1:])
        assert loop[0][:3] not in tree_edges  # the chord is not a tree edge


def test_fundamental_loops_are_independent():
    # networkx's check_independent in spirit: the signed edge-incidence vectors of the loops
    # have full rank
    for G in (gs_graph(), wheatstone_bridge(), tsai_3upu([0.1, 0.2, 0.9])):
        edges = {e: i for i, e in enumerate(G.edges(keys=True))}
        vectors = np.zeros((len(fundamental_loops(G)), len(edges)))
        for row, loop in enumerate(fundamental_loops(G)):
            for u, v, key, direction in loop:
                vectors[row, edges[(u, v, key)]] += 1 if direction == "forward" else -1
        assert np.linalg.matrix_rank(vectors) == len(vectors)


def test_loop_closure_matrix_of_two_parallel_hinges():
    G = twist_graph("B", "E", [
        ("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
        ("B", "E", revolute("R2", [0, 0, 1], [1, 0, 0])),
    ])
    matrix, columns = loop_closure_matrix(G)
    assert [c[2] for c in columns] == ["R1", "R2"]
    # loop: R2 forward, R1 backwards: columns -$1 and +$2
    np.testing.assert_allclose(matrix[:, 0], -S.line([0, 0, 1], [0, 0, 0]), atol=1e-12)
    np.testing.assert_allclose(matrix[:, 1], S.line([0, 0, 1], [1, 0, 0]), atol=1e-12)


def test_joint_screws_along_negates_reversed_edges():
    G = twist_graph("B", "E", [("B", "L", revolute("R", [0, 0, 1], [1, 0, 0])), ("L", "E", prismatic("P", [0, 1, 0]))])
    rows = joint_screws_along(G, [("L", "E", "P", "reverse"), ("B", "L", "R", "forward")])
    np.testing.assert_allclose(rows, [[0, 0, 0, 0, -1, 0], [0, 0, 1, 0, -1, 0]], atol=1e-12)
    assert joint_screws_along(G, []).shape == (0, 6)


def test_simple_paths_are_the_limbs():
    G = gs_graph()
    paths = simple_paths(G)
    assert len(paths) == 6
    assert [edge[2] for edge in paths[0]] == ["U1", "P1", "S1"]
    legs = twist_graph("base", "platform", four_s_leg())
    assert sorted(tuple(e[2] for e in p) for p in simple_paths(legs)) == [("A1", "Sm1", "Sp1"), ("A1", "Sn1", "Sq1")]
    # from the platform back to the base: reversed traversal
    back = simple_paths(legs, "platform", "base")
    assert all(path[0][3] == "reverse" for path in back)


def test_series_parallel_tree_of_an_r_4s_leg():
    tree = series_parallel_tree(twist_graph("base", "platform", four_s_leg()))
    assert (tree.kind, tree.ends, tree.links) == ("series", ("base", "platform"), ("base", "arm1", "platform"))
    hinge, loop = tree.children
    assert (hinge.kind, hinge.edge) == ("joint", ("base", "arm1", "A1"))
    assert (loop.kind, loop.ends, loop.system.order) == ("parallel", ("arm1", "platform"), 4)
    assert loop.system.is_equivalent(paper_4s_twists())
    assert sorted(child.links for child in loop.children) == [
        ("arm1", "rod1a", "platform"), ("arm1", "rod1b", "platform")
    ]


def _check_orientation(node):
    """Children chain from ends[0] to ends[1] (series) or share the ends (parallel)."""
    if node.kind == "series":
        assert node.children[0].ends[0] == node.ends[0]
        assert node.children[-1].ends[1] == node.ends[1]
        for first, second in zip(node.children, node.children[1:], strict=False):
            assert first.ends[1] == second.ends[0]
    if node.kind == "parallel":
        assert all(child.ends == node.ends for child in node.children)
    for child in node.children:
        _check_orientation(child)


def test_series_parallel_tree_children_follow_their_parent_orientation():
    # regression: SeriesParallelNode.reversed kept the children's old orientation
    G = twist_graph("B", "E", [
        ("B", "L1", revolute("J1", [0, 0, 1], [0, 0, 0])),
        ("L2", "E", spherical("J3", [1, 0, 0])),
        ("L1", "L2", spherical("J2", [0, 1, 0])),
        ("L1", "L3", revolute("J4", [1, 0, 0], [0, 0, 1])),
        ("L3", "E", revolute("J5", [0, 1, 0], [1, 1, 0])),
    ])
    _check_orientation(series_parallel_tree(G))


def test_parallel_legs_are_one_parallel_node_with_one_child_per_leg():
    # regression: three legs between base and platform gave parallel(parallel(leg, leg), leg)
    for G, legs in [(tsai_3upu([0.1, 0.05, 0.8]), 3), (gs_graph(), 6)]:
        tree = series_parallel_tree(G)
        assert tree.kind == "parallel" and len(tree.children) == legs
        assert all(child.kind == "series" and len(child.children) == 3 for child in tree.children)
        _check_orientation(tree)



def _shape(node):
    return (node.kind, node.ends, node.links, node.edge, node.joints, node.system.order,
            tuple(_shape(child) for child in node.children))


@pytest.mark.parametrize("name", ["h4", "mcgill_smg", "peppermill", "planar_3rrp"])
def test_series_parallel_tree_is_the_analysis_cores_tree(name):
    # one tree: series_parallel_tree is the core's (WrenchAnalysis.tree), node for node, whatever
    # order the graph lists its joints in
    from screwkit.core.wrenches import wrench_analysis
    from screwkit.robots.catalog import load_mechanism

    graph = load_mechanism(name).twist_graph()
    shuffled = nx.MultiDiGraph(**graph.graph)
    shuffled.add_edges_from(reversed(list(graph.edges(keys=True, data=True))))
    expected = _shape(wrench_analysis(graph).tree)
    assert _shape(series_parallel_tree(graph)) == expected
    assert _shape(series_parallel_tree(shuffled)) == expected


def test_series_parallel_tree_drops_a_dangling_actuated_joint():
    G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0])),
                               ("B", "X", revolute("A", [1, 0, 0], [0, 0, 0], actuated=True))])
    tree = series_parallel_tree(G)
    assert (tree.kind, tree.edge, tree.system.order) == ("joint", ("B", "E", "R"), 1)

# the equivalent twist graph (paper 002 Fig. 2b, Fig. 3) -----------------------------------------
def test_equivalent_graph_of_an_r_4s_leg_is_r_vr_vr_vp_vp():
    G = twist_graph("base", "platform", four_s_leg())
    E = equivalent_twist_graph(G)
    joints = [j for _, _, j in E.edges(data="joint")]
    assert sorted(j.type for j in joints) == ["R", "vP", "vP", "vR", "vR"]
    assert E.graph["equivalent"] is True and E.graph["base"] == "base"
    virtual = ScrewSystem.span(np.vstack([j.screws for j in joints if j.virtual]))
    assert virtual.is_equivalent(paper_4s_twists())
    # the virtual chain is serial: one path from the arm to the platform through the virtual links
    (path,) = simple_paths(E)
    assert path[0][2] == "A1"
    assert platform_twist_system(E).is_equivalent(platform_twist_system(G))


def test_equivalent_graph_keeps_the_limbs_starting_at_the_base():
    second = [unit([0.1, 1, 0.2]), np.array([-1.2, 0.3, 0.1])]
    m2, n2 = second[1], second[1] + 0.3 * second[0]
    rod2 = np.array([0.3, 0.1, -0.9])
    G = twist_graph("base", "platform", four_s_leg() + r_4s_leg(2, [-1.0, 0, 0], second[0], m2, n2, m2 + rod2, n2 + rod2))
    E = equivalent_twist_graph(G)
    assert {("base", "arm1", "A1"), ("base", "arm2", "A2")} <= set(E.edges(keys=True))
    assert sorted(j.type for _, _, j in E.edges(data="joint")) == ["R", "R"] + ["vP"] * 4 + ["vR"] * 4
    limbs = simple_paths(E)
    assert len(limbs) == 2 and {path[0][2] for path in limbs} == {"A1", "A2"}
    assert platform_twist_system(E).is_equivalent(platform_twist_system(G))


def test_equivalent_graph_keeps_a_rigid_sub_loop():
    # regression: a closed sub-loop whose twist system is {0} had no virtual chain at all, and the
    # platform was left unconnected
    G = twist_graph("B", "E", [
        ("B", "arm", revolute("A", [1, 0, 0], [0, 0, 0], actuated=True)),
        ("arm", "r1", revolute("a1", [0, 1, 0], [0, 0, 0])),
        ("r1", "E", revolute("a2", [0, 0, 1], [1, 2, 0])),
        ("arm", "r2", revolute("b1", [1, 1, 0], [0, 3, 0])),
        ("r2", "E", revolute("b2", [0, 1, 1], [1, 0, 5])),
    ])
    E = equivalent_twist_graph(G)
    check_twist_graph(E)
    assert platform_twist_system(E).is_equivalent(platform_twist_system(G))
    assert platform_twist_system(E).order == 1



@pytest.mark.parametrize("name", ["h4", "ragnar", "mcgill_smg", "peppermill", "planar_3rrp"])
def test_equivalent_graph_from_the_cores_tree_has_the_same_chains(name):
    # the report builds it on the analysis core's tree (WrenchAnalysis.tree, twist systems from the
    # core's frames); series_parallel_tree is the same tree with systems summed and intersected from
    # the graph's screws: the same edges between the same links, joint types and spans; the virtual
    # joints' screws may be another basis of each closed sub-loop's twist system
    from screwkit.robots.catalog import load_mechanism

    mechanism = load_mechanism(name)
    poses = np.concatenate([np.asarray(mechanism.default_pose)[None],
                            mechanism.random_poses(np.random.default_rng(3), 2)])
    for pose in mechanism.at(poses):
        reduced = equivalent_twist_graph(pose.graph)
        from_core = equivalent_twist_graph(pose.graph, tree=pose.analysis.tree)
        assert from_core.graph == reduced.graph and set(from_core.nodes) == set(reduced.nodes)

        def chains(graph):
            found = {}
            for u, v, key, joint in graph.edges(keys=True, data="joint"):
                found.setdefault((u, v) if not joint.virtual else key.split("[")[1], []).append(joint)
            return found

        expected, got = chains(reduced), chains(from_core)
        assert expected.keys() == got.keys()
        for where, joints in expected.items():
            assert sorted(j.type for j in got[where]) == sorted(j.type for j in joints), where
            scale = float(pose.analysis.length_scale)
            span = ScrewSystem.span(np.vstack([j.screws for j in joints]), length_scale=scale)
            assert span.is_equivalent(ScrewSystem.span(np.vstack([j.screws for j in got[where]]),
                                                       length_scale=scale)), where


# saving and loading ----------------------------------------------------------------------------
def test_graph_round_trip_through_json():
    G = gs_graph()
    G.graph["dof"] = 6
    H = from_data(json.loads(json.dumps(to_data(G))))
    assert H.graph == G.graph
    assert sorted(H.edges(keys=True)) == sorted(G.edges(keys=True))
    for u, v, key, joint in G.edges(keys=True, data="joint"):
        loaded = H.edges[u, v, key]["joint"]
        np.testing.assert_array_equal(loaded.screws, joint.screws)
        assert (loaded.type, loaded.actuated, loaded.geometry) == (joint.type, joint.actuated, joint.geometry)
    assert platform_twist_system(H).order == 6
    # the equivalent graph (virtual joints) round-trips too
    E = equivalent_twist_graph(twist_graph("base", "platform", four_s_leg()))
    F = from_data(json.loads(json.dumps(to_data(E))))
    assert sorted(j.type for _, _, j in F.edges(data="joint")) == ["R", "vP", "vP", "vR", "vR"]
    assert all(j.virtual for _, _, j in F.edges(data="joint") if j.type.startswith("v"))


def test_custom_joint_key_is_used_throughout():
    # regression: fundamental_loops checked the graph with the default key "joint"
    G = nx.MultiDiGraph(base="B", platform="E")
    G.add_edge("B", "E", key="R1", j=revolute("R1", [0, 0, 1], [0, 0, 0]))
    G.add_edge("B", "E", key="R2", j=revolute("R2", [0, 0, 1], [0, 0, 0]))
    check_twist_graph(G, joint_key="j")
    assert len(fundamental_loops(G, joint_key="j")) == 1
    for method in METHODS:
        assert platform_twist_system(G, joint_key="j", method=method).order == 1
    assert loop_closure_matrix(G, joint_key="j")[0].shape == (6, 2)


def test_symbolic_loop_closure_matrix_is_exact_and_agrees_with_numeric():
    # regression: numeric joints put floats (0.0, 1.0) into the symbolic matrix
    x = sympy.Symbol("x", real=True)

    def graph(offset):
        return twist_graph("B", "E", [
            ("B", "L", revolute("R1", [0, 0, 1], [offset, 0, 0])),
            ("L", "E", prismatic("P", [1, 0, 0])),
            ("B", "E", revolute("R2", [0, 0, 1], [0, 1, 0])),
            ("B", "M", revolute("R3", [0, 0, 1], [0.5, 0.5, 0])),
            ("M", "E", prismatic("P2", [0, 1, 0])),
        ])

    symbolic, columns = loop_closure_matrix(graph(x))
    assert symbolic.dtype == object
    assert not any(isinstance(v, float) or (isinstance(v, sympy.Basic) and v.has(sympy.Float)) for v in symbolic.flat)
    numeric, numeric_columns = loop_closure_matrix(graph(0.75))
    assert columns == numeric_columns
    substituted = np.array([[float(sympy.sympify(v).subs(x, 0.75)) for v in row] for row in symbolic])
    np.testing.assert_allclose(substituted, numeric, atol=1e-12)
    # generic rank: the symbolic order is the numeric order at a generic value
    assert platform_twist_system(graph(x)).order == platform_twist_system(graph(0.75)).order
    serial = twist_graph("B", "E", [("B", "L", revolute("R1", [0, 0, 1], [x, 0, 0])), ("L", "E", prismatic("P", [1, 0, 0]))])
    assert platform_twist_system(serial).order == 2


# invariants ------------------------------------------------------------------------------------
@settings(max_examples=30)
@given(seed=seeds)
def test_reduction_and_loop_closure_agree_on_series_parallel_graphs(seed):
    G = random_series_parallel(np.random.default_rng(seed))
    closure = platform_twist_system(G)
    reduction = platform_twist_system(G, method="reduction")
    assert closure.order == reduction.order
    assert closure.is_equivalent(reduction)
    tree = series_parallel_tree(G)
    _check_orientation(tree)
    stack = [tree]
    while stack:  # no parallel node directly under a parallel node (they would have the same ends)
        node = stack.pop()
        assert not (node.kind == "parallel" and any(c.kind == "parallel" for c in node.children))
        stack.extend(node.children)
    assert len(fundamental_loops(G)) == G.number_of_edges() - G.number_of_nodes() + 1
    # the equivalent graph spans the same system (judged with the original mechanism's length)
    length = graph_frame(G)[1]
    E = equivalent_twist_graph(G)
    check_twist_graph(E)
    assert platform_twist_system(E, length_scale=length).is_equivalent(closure)


MECHANISMS = {
    "gough-stewart": gs_graph,
    "3-upu": lambda: tsai_3upu([0.1, 0.05, 0.8]),
    "3-rpr": lambda: planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM),
    "r-4s": lambda: twist_graph("base", "platform", four_s_leg()),
}


@pytest.mark.parametrize("name", sorted(MECHANISMS))
@settings(max_examples=15)
@given(motion=rigid_motions(), factor=unit_factors)
def test_twist_systems_follow_rigid_motions_and_units(name, motion, factor):
    rotation, translation = motion
    G = MECHANISMS[name]()
    H = moved(G, rotation, translation, factor)
    assert len(fundamental_loops(H)) == len(fundamental_loops(G))
    before = platform_twist_system(G)
    expected = S.transform(before.basis, rotation, translation) if before.order else before.basis
    expected = np.hstack([expected[:, :3], factor * expected[:, 3:]])
    for method in METHODS:
        after = platform_twist_system(H, method=method)
        assert after.order == before.order
        assert after.is_equivalent(ScrewSystem.span(expected, length_scale=after.length_scale))
    _, length = graph_frame(H)
    assert length == pytest.approx(factor * graph_frame(G)[1], rel=1e-9)


# errors: one per message -----------------------------------------------------------------------
def R(name, point=(0, 0, 0)):
    return revolute(name, [0, 0, 1], point)


def test_error_joints_must_be_triples():
    with pytest.raises(TwistGraphError, match=r"Expected joints as \(parent, child, Joint\) triples, got \('B', 'E'\)"):
        twist_graph("B", "E", [("B", "E")])


def test_error_edge_attribute_must_be_a_joint_when_added():
    with pytest.raises(TwistGraphError, match="Edge 'B' → 'E': expected a Joint, got str"):
        add_joint(nx.MultiDiGraph(base="B", platform="E"), "B", "E", "R")


def test_error_duplicate_joint_name_when_added():
    with pytest.raises(TwistGraphError, match="Duplicate joint name 'R': joint names must be unique"):
        twist_graph("B", "E", [("B", "L", R("R")), ("L", "E", R("R", (1, 0, 0)))])


def test_error_self_loop_when_added():
    with pytest.raises(TwistGraphError, match="Joint 'R': expected two different links, got 'L' twice"):
        twist_graph("B", "E", [("B", "E", R("A")), ("L", "L", R("R"))])


def test_error_self_loop_in_a_graph_built_directly():
    # regression: check_twist_graph accepted a joint from a link to itself
    G = twist_graph("B", "E", [("B", "E", R("A"))])
    G.add_edge("E", "E", key="R", joint=R("R"))
    with pytest.raises(TwistGraphError, match="Joint 'R': expected two different links, got 'E' twice"):
        check_twist_graph(G)


def test_error_not_a_multidigraph():
    with pytest.raises(TwistGraphError, match=r"Expected a networkx\.MultiDiGraph, got Graph"):
        check_twist_graph(nx.Graph(base="B", platform="E"))


@pytest.mark.parametrize(("role", "meaning"), [("base", "the fixed link"), ("platform", "the end effector")])
def test_error_no_base_or_platform(role, meaning):
    G = twist_graph("B", "E", [("B", "E", R("R"))])
    del G.graph[role]
    with pytest.raises(TwistGraphError, match=f"Expected graph attribute '{role}' naming {meaning}, got none"):
        check_twist_graph(G)


@pytest.mark.parametrize("role", ["base", "platform"])
def test_error_base_or_platform_not_a_node(role):
    G = twist_graph("B", "E", [("B", "E", R("R"))])
    G.graph[role] = "X"
    with pytest.raises(TwistGraphError, match=f"Expected the {role} link 'X' to be a node of the graph, got no such node"):
        check_twist_graph(G)


def test_error_base_equals_platform():
    with pytest.raises(TwistGraphError, match="Expected base and platform to differ, got 'B' for both"):
        twist_graph("B", "B", [("B", "E", R("R"))])


def test_error_edge_attribute_not_a_joint():
    G = nx.MultiDiGraph(base="B", platform="E")
    G.add_edge("B", "E", key="R", joint=np.eye(1, 6))
    with pytest.raises(TwistGraphError, match=r"Edge 'B' → 'E' \(key 'R'\): expected attribute 'joint' holding a Joint, got ndarray"):
        check_twist_graph(G)


def test_error_key_differs_from_the_joint_name():
    G = nx.MultiDiGraph(base="B", platform="E")
    G.add_edge("B", "E", key="other", joint=R("R"))
    with pytest.raises(TwistGraphError, match=r"Edge 'B' → 'E': expected key 'R' \(the joint's name\), got 'other'"):
        check_twist_graph(G)


def test_error_duplicate_joint_names_in_a_graph_built_directly():
    G = nx.MultiDiGraph(base="B", platform="E")
    G.add_edge("B", "L", key="R", joint=R("R"))
    G.add_edge("L", "E", key="R", joint=R("R", (1, 0, 0)))
    with pytest.raises(TwistGraphError, match=r"Duplicate joint name 'R' on edges \('B', 'L'\) and \('L', 'E'\)"):
        check_twist_graph(G)


def test_error_unconnected_link():
    G = twist_graph("B", "E", [("B", "E", R("R"))])
    G.add_edge("X", "Y", key="Q", joint=R("Q"))
    with pytest.raises(TwistGraphError, match=r"Expected every link connected to the base 'B', got unconnected links \['X', 'Y'\]"):
        check_twist_graph(G)


@pytest.mark.parametrize("dof", [7, -1, 2.0, "3"])
def test_error_bad_dof(dof):
    with pytest.raises(TwistGraphError, match=r"Expected graph attribute 'dof' to be an integer in 0\.\.6, got"):
        twist_graph("B", "E", [("B", "E", R("R"))], dof=dof)


def test_error_non_series_parallel_graph_with_reduction():
    G = wheatstone_bridge()
    with pytest.raises(TwistGraphError, match=r"Expected a series-parallel twist graph .*links left: \['base', 'platform', 'x', 'y'\].*use method='loop_closure'"):
        platform_twist_system(G, method="reduction")
    with pytest.raises(TwistGraphError, match="Expected a series-parallel twist graph"):
        equivalent_twist_graph(G)
    # the loop-closure method handles it: the triangle base-x-y of z hinges is rigid, and so is the
    # platform hinged to both x and y (Grübler: 3·3 − 2·5 = −1)
    assert platform_twist_system(G).order == 0


def test_error_unknown_locked_joint():
    with pytest.raises(TwistGraphError, match=r"Expected `locked` to name joints of the graph, got unknown \['X'\]"):
        platform_twist_system(gs_graph(), locked=["P1", "X"])


def test_error_locked_with_reduction():
    with pytest.raises(TwistGraphError, match="Expected no `locked` joints with method='reduction'; use 'loop_closure'"):
        platform_twist_system(gs_graph(), method="reduction", locked=["P1"])


def test_error_unknown_method():
    with pytest.raises(TwistGraphError, match="Expected method 'loop_closure' or 'reduction', got 'svd'"):
        platform_twist_system(gs_graph(), method="svd")  # type: ignore[arg-type]


def test_error_loading_a_graph_that_breaks_the_schema():
    data = to_data(twist_graph("B", "E", [("B", "E", R("R"))]))
    data["graph"]["platform"] = "nowhere"
    with pytest.raises(TwistGraphError, match="Expected the platform link 'nowhere' to be a node"):
        from_data(data)
