"""A fuzzer of the twist-graph API (issue 24): random joints (every kind, axes and points from
round integers to 1e6 away, zero and parallel axes), random topologies (serial, parallel limbs,
nested loops, disconnected pieces, self-loops, multi-edges), random actuation, random ``dof`` and
link names of every accepted and refused kind. Building the graph and every call to ``classify``,
``wrench_analysis`` and ``analyze`` ends in an answer or a ScrewkitError: never another exception,
a NaN, a numpy warning (errors in this suite) or a hang (each call is bounded in time by SIGALRM).

Derandomized (the same examples every run), a few seconds in all.
"""

import dataclasses
import itertools
import math
import signal
from contextlib import contextmanager

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.core.verdicts import SingularityReport
from screwkit.core.wrench_systems import WrenchAnalysis
from screwkit.exceptions import ScrewkitError

FUZZ = settings(max_examples=80, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck), database=None)
#: The longest any one call may take: far above the slowest answer here (a second), far below a hang.
CALL_SECONDS = 20

small_ints = st.integers(-2, 2)
scales = st.sampled_from([1e-3, 1.0, 1.0, 1.0, 25.4, 1e3])
unit_floats = st.floats(0.05, 1).flatmap(lambda x: st.sampled_from([x, -x]))
vectors = st.one_of(
    st.lists(small_ints, min_size=3, max_size=3).filter(any),  # round numbers: parallel axes happen
    st.tuples(unit_floats, unit_floats, unit_floats, scales).map(lambda v: [c * v[3] for c in v[:3]]),
    st.sampled_from([[0, 0, 1], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 0]]),  # and a zero one
)
points = st.one_of(vectors, st.tuples(vectors, st.sampled_from([1e3, 1e6])).map(lambda v: [c * v[1] + 1 for c in v[0]]))


@st.composite
def joints(draw, name):
    """One joint of a random kind; its constructor may refuse it (a zero axis): then a ScrewkitError."""
    kind = draw(st.sampled_from(["R", "R", "R", "P", "P", "H", "C", "U", "S", "S", "Pa", "virtual"]))
    actuated = draw(st.integers(0, 5)) == 0
    if kind == "R":
        return lambda: sk.revolute(name, draw(vectors), draw(points), actuated=actuated)
    if kind == "P":
        return lambda: sk.prismatic(name, draw(vectors), actuated=actuated)
    if kind == "H":
        return lambda: sk.helical(name, draw(vectors), draw(points), draw(st.sampled_from([0.0, 0.5, -2.0, 1e-9])), actuated=actuated)
    if kind == "C":
        return lambda: sk.cylindrical(name, draw(vectors), draw(points))
    if kind == "U":
        return lambda: sk.universal(name, draw(vectors), draw(vectors), draw(points))
    if kind == "S":
        return lambda: sk.spherical(name, draw(points))
    if kind == "Pa":
        return lambda: sk.parallelogram(name, draw(vectors), draw(vectors), actuated=actuated)
    return lambda: sk.virtual(name, [*draw(vectors), *draw(vectors)])


link_styles = st.sampled_from([lambda i: f"L{i}", lambda i: i, lambda i: ("link", i)])


@st.composite
def topologies(draw):
    """(base, platform, [(parent, child)]): a serial chain, parallel limbs or nested loops, with
    random extras (a disconnected piece, a self-loop, a multi-edge, a chord between any links)."""
    name = draw(link_styles)
    base, platform = name(0), name(1)
    counter = iter(range(2, 10**6))
    edges = []

    def chain(start, end, length):
        links = [start, *(name(next(counter)) for _ in range(length - 1)), end]
        edges.extend(itertools.pairwise(links))
        return links

    shape = draw(st.sampled_from(["serial", "parallel", "nested"]))
    if shape == "serial":
        chain(base, platform, draw(st.integers(1, 5)))
    else:
        for _ in range(draw(st.integers(2, 3))):
            links = chain(base, platform, draw(st.integers(1, 3)))
            if shape == "nested" and len(links) >= 3 and draw(st.booleans()):
                chain(links[0], links[1], draw(st.integers(1, 2)))  # a loop inside the limb
                chain(links[1], links[2], 2)
    extras = draw(
        st.lists(st.sampled_from(["disconnected", "self-loop", "multi-edge", "chord", "swap", "bad name"]), max_size=1)
    )
    everything = sorted({x for edge in edges for x in edge}, key=repr)
    for extra in extras:
        if extra == "disconnected":
            edges.append((name(next(counter)), name(next(counter))))
        elif extra == "self-loop":
            link = draw(st.sampled_from(everything))
            edges.append((link, link))
        elif extra == "multi-edge":
            edges.append(draw(st.sampled_from(edges)))
        elif extra == "bad name":  # not a link name: refused by name, not by networkx
            edges.append((draw(st.sampled_from(everything)), draw(st.sampled_from([None, ["x"], True, math.nan, {}]))))
        elif extra == "chord":
            edges.append((draw(st.sampled_from(everything)), draw(st.sampled_from(everything))))
        else:
            platform = draw(st.sampled_from([base, *everything]))  # the platform anywhere, even the base
    if draw(st.booleans()):
        edges = draw(st.permutations(edges))
    return base, platform, edges


@contextmanager
def time_bound(seconds):
    """Fail the example (not the suite) if the body takes longer than ``seconds``."""

    def hang(signum, frame):
        raise AssertionError(f"a call took longer than {seconds} s")

    previous = signal.signal(signal.SIGALRM, hang)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def no_nan(value, where):
    """Every float reachable in ``value`` (dicts, lists, arrays) is not NaN."""
    if isinstance(value, dict):
        for key, item in value.items():
            no_nan(item, f"{where}[{key!r}]")
    elif isinstance(value, list | tuple):
        for index, item in enumerate(value):
            no_nan(item, f"{where}[{index}]")
    elif isinstance(value, np.ndarray) and value.dtype.kind == "f":
        assert not np.isnan(value).any(), where
    elif isinstance(value, float):
        assert not math.isnan(value), where


def answered(call):
    """The call's answer, or None for a ScrewkitError; any other exception fails the test."""
    try:
        with time_bound(CALL_SECONDS):
            return call()
    except ScrewkitError as err:
        assert str(err).strip(), "a screwkit error without a message"
        return None



#: "regular", or the labels that hold joined in their order, e.g. "actuation + serial singularity".
VERDICTS = {"regular"} | {
    " + ".join(label for label, on in zip(("constraint", "actuation", "serial"), bits, strict=True) if on)
    + " singularity"
    for bits in np.ndindex(2, 2, 2)
    if any(bits)
}


@FUZZ
@given(topology=topologies(), data=st.data())
def test_random_twist_graphs_are_answered_or_refused_cleanly(topology, data):
    base, platform, edges = topology
    triples = []
    for index, (parent, child) in enumerate(edges):
        joint = answered(data.draw(joints(f"J{index}")))
        if joint is not None:
            triples.append((parent, child, joint))
    dof = data.draw(st.one_of(*[st.none()] * 6, st.integers(0, 6), st.sampled_from([7, -1, True, "3", 2.5])))
    graph = answered(lambda: sk.twist_graph(base, platform, triples, dof=dof))
    if graph is None:
        return
    check_the_analyses(graph, data)
    if any(joint.actuated for *_, joint in triples) or dof is not None:
        # the same graph without actuators or dof: a mobility analysis, whatever the mobility
        unactuated = [(u, v, dataclasses.replace(joint, actuated=False)) for u, v, joint in triples]
        check_the_analyses(sk.twist_graph(base, platform, unactuated), data)


def check_the_analyses(graph, data):
    """classify, wrench_analysis and (one graph in six) analyze: an answer or a ScrewkitError each,
    the same answer or refusal from the first two, and the same verdict from analyze."""
    report = answered(lambda: sk.classify(graph))
    if report is not None:
        assert isinstance(report, SingularityReport) and report.verdict in VERDICTS, report
        no_nan(report.to_dict(), "classify")
    analysis = answered(lambda: sk.wrench_analysis(graph))
    if analysis is not None:
        assert isinstance(analysis, WrenchAnalysis)
        no_nan(analysis.closeness, "closeness")
        assert 0 <= analysis.constraint_order <= 6 and 0 <= analysis.global_order <= 6
    assert (report is None) == (analysis is None)  # the same graph is refused by both or by neither
    if report is not None and data.draw(st.integers(0, 5)) == 0:  # analyze is slower: one graph in six
        full = answered(lambda: sk.analyze(graph, superbracket=data.draw(st.integers(0, 2)) == 0))
        if full is not None:
            assert full.verdict.verdict == report.verdict
            no_nan(full.to_dict(), "analyze")
