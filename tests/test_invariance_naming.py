"""Invariance to naming and order (issue 24): relabelling the links and the joints, reversing a
joint's edge together with the sign of its screws (its twists are the child's relative to the
parent: ``v → u`` carries ``-S``), and permuting the order in which the edges are added leave the
verdict, its labels, the orders, the mobility and the factored superbracket conditions unchanged.

The reference is the same graph analysed as given; the transformations change nothing geometric,
so every answer must agree (closeness values to round-off: the rows are stacked in another order).
"""

import dataclasses
import functools

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from tests.test_bad_inputs import tripteron

INVARIANCE = settings(max_examples=30, deadline=None, derandomize=True, database=None)


@functools.cache
def graphs():
    """Twist graphs at regular and singular configurations: every catalog robot at its default
    pose and at a random one, the snapshot example, and a Tripteron-like translator regular and
    stretched (a serial singularity)."""
    rng = np.random.default_rng(24)
    found = []
    for name in sk.list_mechanisms():
        mechanism = sk.load_mechanism(name)
        found.append(mechanism.twist_graph())
        found.append(mechanism.twist_graph(mechanism.random_poses(rng, 1)[0]))
    found.append(sk.load_snapshot("examples/planar_3rpr.toml"))
    found.extend([tripteron(False), tripteron(True)])
    return found


def transformed(graph, link_names, joint_names, reversed_joints, order):
    """The same mechanism: links and joints renamed, some edges reversed with their screws' sign,
    the edges added in another order."""
    edges = list(graph.edges(keys=True, data="joint"))
    base, platform = link_names[graph.graph["base"]], link_names[graph.graph["platform"]]
    copy = nx.MultiDiGraph(**{**graph.graph, "base": base, "platform": platform})
    for index in order:
        parent, child, key, joint = edges[index]
        joint = dataclasses.replace(joint, name=joint_names[key])
        if key in reversed_joints:
            joint = dataclasses.replace(joint, screws=-joint.screws)
            parent, child = child, parent
        copy.add_edge(link_names[parent], link_names[child], key=joint.name, joint=joint)
    return copy


@st.composite
def renamings(draw, graph):
    """Random new link names (strings, integers or tuples), joint names, reversed edges and order."""
    links = list(graph.nodes)
    keys = [key for *_, key in graph.edges(keys=True)]
    style = draw(st.sampled_from([lambda i: f"link {i}", lambda i: i, lambda i: ("l", i)]))
    link_order = draw(st.permutations(range(len(links))))
    joint_order = draw(st.permutations(range(len(keys))))
    link_names = {link: style(link_order[i]) for i, link in enumerate(links)}
    joint_names = {key: f"J{joint_order[i]:02d}" for i, key in enumerate(keys)}
    reversed_joints = set(draw(st.lists(st.sampled_from(keys), unique=True)))
    return link_names, joint_names, reversed_joints, draw(st.permutations(range(len(keys))))


def comparable(report):
    """A report's answers that do not name links or joints (closeness and length apart)."""
    data = report.to_dict()
    closeness, length = data.pop("closeness"), data.pop("length_scale")
    data.pop("uncontrolled_twists")  # a basis: compared by its order, uncontrolled_dof
    return data, closeness, length


@INVARIANCE
@given(data=st.data())
def test_verdicts_orders_and_mobility_do_not_depend_on_names_or_edge_order(data):
    graph = data.draw(st.sampled_from(graphs()))
    renamed = transformed(graph, *data.draw(renamings(graph)))
    expected, closeness, length = comparable(sk.classify(graph))
    got, got_closeness, got_length = comparable(sk.classify(renamed))
    assert got == expected
    assert got_closeness.keys() == closeness.keys()
    for key, value in closeness.items():
        assert got_closeness[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    assert got_length == pytest.approx(length, rel=1e-12)
    analysis, renamed_analysis = sk.wrench_analysis(graph), sk.wrench_analysis(renamed)
    assert renamed_analysis.platform_order == analysis.platform_order
    assert renamed_analysis.constraint_order == analysis.constraint_order


@pytest.mark.parametrize("subject", ["h4", "snapshot"])  # the H4 at its default pose; the 3-RPR snapshot
def test_factored_conditions_do_not_depend_on_names_or_edge_order(subject):
    # by name, not by index: the catalog may grow
    graph = sk.load_mechanism("h4").twist_graph() if subject == "h4" else sk.load_snapshot("examples/planar_3rpr.toml")
    rng = np.random.default_rng(0 if subject == "h4" else 16)
    links, keys = list(graph.nodes), [key for *_, key in graph.edges(keys=True)]
    link_names = {link: f"n{k}" for link, k in zip(links, rng.permutation(len(links)), strict=True)}
    joint_names = {key: f"j{k}" for key, k in zip(keys, rng.permutation(len(keys)), strict=True)}
    reversed_joints = {key for key in keys if rng.random() < 0.5}
    renamed = transformed(graph, link_names, joint_names, reversed_joints, rng.permutation(len(keys)))
    expected = sk.analyze(graph).to_dict()["superbracket"]
    got = sk.analyze(renamed).to_dict()["superbracket"]
    assert expected is not None
    assert got["simplification"]["factored"] == expected["simplification"]["factored"]
    assert [c["statement"] for c in got["conditions"]] == [c["statement"] for c in expected["conditions"]]
