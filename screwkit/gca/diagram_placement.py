"""Placing a wrench diagram: chosen at generic configurations of the mechanism
(:func:`generic_reference`), placed at the pose of interest (:func:`diagram_at`), sampled at
further generic configurations (:class:`ReplaySampler`, :func:`graph_diagram`,
:func:`graph_sampler`), so that what is decided never depends on a special pose.

Examples
--------
>>> from screwkit.core.wrenches import wrench_analysis
>>> diagram, sampler = graph_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
>>> diagram.line_text()
'[ab, cd, ef, gh, ij, kj]'
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from ..algebra import projective as P
from ..algebra.screwvalue import Screw
from ..core.wrench_systems import WrenchAnalysis
from ..core.wrenches import wrench_analysis
from ..exceptions import DegenerateGeometryError, ScrewkitError, ScrewkitValueError
from .diagram import INCIDENCE_RTOL, DiagramPoint, WrenchDiagram, require_instance
from .diagram_lines import lines_at
from .diagram_points import _joint_carried, batch_diagram_points, diagram_points
from .diagram_recipes import wrench_diagram
from .redundant_conditions import MORE_LINES

__all__ = [
    "REFERENCE_TRIES",
    "ReplaySampler",
    "diagram_at",
    "generic_reference",
    "graph_diagram",
    "graph_sampler",
]

Array = np.ndarray


def diagram_at(reference: WrenchDiagram, analysis: WrenchAnalysis) -> WrenchDiagram:
    """The diagram of ``reference`` (its recipes, labels and lines) at another pose of the mechanism.

    Building a diagram decides which points lines share (parallel axes, concentric joints) at the
    analysed pose; at a special pose a coincidence could pass for structure. Build the reference at
    a generic pose and use this to place it at the pose of interest; where a recipe has no point
    there, or the lines are not the reference's, ``degenerate`` says why.

    Parameters
    ----------
    reference : WrenchDiagram
        A diagram chosen at a generic pose (:func:`generic_reference`).
    analysis : WrenchAnalysis
        One pose of the same mechanism.

    Returns
    -------
    WrenchDiagram
        The reference's points and lines, with this pose's coordinates, and ``degenerate``
        reasons where the representation fails here (the coordinates are then those of the points
        that exist here, evaluated on every line of the mechanism).

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> h4 = load_mechanism("h4")
    >>> generic = wrench_diagram(wrench_analysis(h4.twist_graph([40.0, -60.0, -700.0, 0.3])))
    >>> diagram_at(generic, wrench_analysis(h4.twist_graph())).line_text()
    '[ab, cd, ef, gh, ij, kj]'
    """
    require_instance(reference, WrenchDiagram, "reference")
    require_instance(analysis, WrenchAnalysis, "analysis")
    lines, problems = lines_at(reference.line_names, analysis)
    coordinates: dict[str, Array] = {}
    if not problems:
        try:
            coordinates = diagram_points(reference.points, analysis, lines=lines)
        except DegenerateGeometryError as err:
            problems.append(str(err))
    if problems:  # the points that exist here all the same (the design's conditions use them)
        found = batch_diagram_points(reference.points, analysis)
        coordinates = {k: v[0] for k, v in found.items() if np.isfinite(v[0]).all()}
    else:  # each line is the join of its two points (the recipes keep their incidences)
        scale = float(analysis.length_scale)
        for (first, second), (name, _, wrench, _) in zip(reference.lines, lines, strict=True):
            join = P.join_unchecked(coordinates[first], coordinates[second])
            if np.linalg.norm(join) <= INCIDENCE_RTOL or not Screw(join).is_equivalent(
                Screw(wrench), rtol=1e-6, length_scale=scale
            ):
                problems.append(f"the points {first}, {second} do not give the {name} here")
    return WrenchDiagram(
        reference.points, reference.lines, reference.line_names, reference.roles, coordinates, tuple(problems)
    )


#: Generic configurations whose diagrams are tried before a mechanism is said to have none.
REFERENCE_TRIES = 3


def generic_reference(
    analyses: Sequence[WrenchAnalysis],
) -> tuple[WrenchDiagram | None, tuple[str, ...]]:
    """The diagram of a mechanism at a generic configuration, or why the mechanism has none.

    The lines (a line basis of the wrench system, with the legs they come from) and the points
    they share are chosen at generic configurations, never at the analysed one: the first of
    ``analyses`` (random configurations of the same mechanism) whose diagram holds is returned.
    When none of the first :data:`REFERENCE_TRIES` does, the reasons found at the first are
    properties of the mechanism (a global wrench system of order below 6 everywhere, a constraint
    system not spanned by lines, ...) and are returned with ``None``.

    Parameters
    ----------
    analyses : sequence of WrenchAnalysis
        Single-pose analyses of the mechanism at generic configurations. A diagram whose only
        failure is more than six lines (a redundantly actuated mechanism's) holds: it is analysed by
        its six-line subsets (:mod:`screwkit.gca.redundant_conditions`).

    Returns
    -------
    diagram : WrenchDiagram or None
        The first diagram that holds, None when none of the first :data:`REFERENCE_TRIES` does.
    reasons : tuple of str
        Why the mechanism has no diagram (empty when it has one).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> arm = twist_graph("ground", "hand", [  # two freedoms, one actuator
    ...     ("ground", "link", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("link", "hand", revolute("B", [0, 0, 1], [1, 0, 0]))], dof=2)
    >>> reference, reasons = generic_reference([wrench_analysis(arm)])
    >>> reference is None, reasons[0].split(": ")[1]
    (True, 'the global wrench system has order 5, not 6')
    """
    first: tuple[str, ...] = ()
    for analysis in analyses[:REFERENCE_TRIES]:
        try:
            candidate = wrench_diagram(analysis)
        except ScrewkitError as err:  # e.g. a joint whose centre is not defined
            first = first or (str(err),)
            continue
        more = len(candidate.lines) > 6  # redundant actuation: its six-line subsets
        if not [r for r in candidate.degenerate if not (more and MORE_LINES in r)]:
            # its directions orient the points at infinity from now on
            points = tuple(
                _oriented_at_reference(p, candidate.coordinates[p.label]) for p in candidate.points
            )
            coordinates = {p.label: p.sign * candidate.coordinates[p.label] + 0.0 for p in points}
            return replace(candidate, points=points, coordinates=coordinates), ()
        first = first or candidate.degenerate
    if not analyses:
        return None, ("no generic configuration of the mechanism could be reached to choose its diagram",)
    tried = min(len(analyses), REFERENCE_TRIES)
    return None, tuple(
        f"the mechanism has no wrench diagram (at {tried} generic configurations): {reason}"
        for reason in first
    )


def _oriented_at_reference(point: DiagramPoint, value: Any) -> DiagramPoint:
    """A point with its orientation fixed at the reference configuration, where it is ``value``: a
    point at infinity's direction there (:attr:`DiagramPoint.orientation`), or for one the joints
    orient (a ``normals`` point, an actuation line's direction) the constant sign that makes its
    first clearly non-zero component positive there (:attr:`DiagramPoint.sign`)."""
    if not point.at_infinity:
        return point
    direction = np.asarray(value, dtype=float)[:3]
    if _joint_carried(point.key):
        first = direction[np.argmax(np.abs(direction) > 1e-9 * np.abs(direction).max())]
        return replace(point, sign=-1 if first < 0 else 1)
    return replace(point, orientation=tuple(float(x) for x in direction))


class ReplaySampler:
    """``rng -> {label: point}`` handing out samples produced a batch at a time (the ``rng``
    argument is unused: the samples come from their own seeded stream).

    Parameters
    ----------
    produce : callable
        ``rng -> iterable of {label: point}``: a batch of a diagram's points at generic
        configurations; read one sample at a time, so a lazy producer evaluates only those asked for.

    Examples
    --------
    >>> sampler = ReplaySampler(lambda rng: [{"a": k} for k in range(2)])
    >>> [sampler(None), sampler(None), sampler(None)]
    [{'a': 0}, {'a': 1}, {'a': 0}]
    """

    def __init__(self, produce: Callable[[np.random.Generator], Iterable[dict[str, Array]]]):
        self.produce, self.stream = produce, np.random.default_rng(0)
        self.drawn: Iterator[dict[str, Array]] = iter(())

    def __call__(self, rng: np.random.Generator) -> dict[str, Array]:
        """The next sample (a new batch is produced when the last one is used up).

        Parameters
        ----------
        rng : numpy.random.Generator
            Unused (the samples come from their own seeded stream).

        Returns
        -------
        dict of str to numpy.ndarray, shape (4,)
            The next sample, ``{label: point}``.

        Raises
        ------
        ScrewkitValueError
            If the producer gives no sample.
        """
        sample = next(self.drawn, None)
        if sample is None:
            self.drawn = iter(self.produce(self.stream))
            sample = next(self.drawn, None)
        if sample is None:
            raise ScrewkitValueError("Expected the diagram's sampler to produce a sample, got none.")
        return sample


def graph_diagram(
    analysis: WrenchAnalysis, *, rng: int = 2026, samples: int = 24, length_scale: float | None = None
) -> tuple[WrenchDiagram, Callable[[np.random.Generator], dict[str, Array]] | None]:
    """The wrench diagram of a twist graph's mechanism at its configuration, and a generic sampler.

    Generic configurations come from the mechanism itself: it is moved along its own mobility and
    its loops are closed again (:func:`screwkit.core.motion.generic_configurations`), so a snapshot or
    a graph built in Python is treated like a catalog robot: the diagram is chosen at a generic
    configuration (:func:`generic_reference`) and placed at this one (:func:`diagram_at`); the
    sampler hands out its points at further generic configurations, ``samples`` at a time
    (analysed as one batch), on which structural zeros are decided. A given ``length_scale`` is
    the generic configurations' too (:func:`~screwkit.core.wrench_systems.analyze_table`; default: derived).

    Parameters
    ----------
    analysis : WrenchAnalysis
        The mechanism at the configuration of interest (one pose).
    rng : int, default 2026
        Seed of the generic configurations.
    samples : int, default 24
        Generic configurations analysed at a time for the sampler.
    length_scale : float, optional
        The generic configurations' characteristic length (default: derived).

    Returns
    -------
    diagram : WrenchDiagram
        With the mechanism's reasons in ``degenerate`` when it has no diagram.
    sampler : callable or None
        None when there is no diagram.

    Raises
    ------
    ScrewkitTypeError
        If ``analysis`` is not a :class:`~screwkit.core.wrench_systems.WrenchAnalysis` (build one
        from a twist graph with :func:`~screwkit.core.wrenches.wrench_analysis`).

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> diagram, sampler = graph_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
    >>> diagram.line_text(), len(sampler(np.random.default_rng(0)))
    ('[ab, cd, ef, gh, ij, kj]', 11)
    """
    from ..core.mobility import generic_analyses

    require_instance(analysis, WrenchAnalysis, "analysis")
    graph = analysis.graph
    try:
        analyses = generic_analyses(
            graph, np.random.default_rng(rng), REFERENCE_TRIES, rtol=analysis.rtol, length_scale=length_scale
        )
        reference, reasons = generic_reference(analyses)
    except ScrewkitError as err:
        reference, reasons = None, (f"no generic configuration of the mechanism: {err}",)
    if reference is None:
        return replace(wrench_diagram(analysis), coordinates={}, degenerate=reasons), None
    diagram = diagram_at(reference, analysis)

    def produce(stream: np.random.Generator) -> Iterator[dict[str, Array]]:
        found = 0
        for one in generic_analyses(graph, stream, samples, rtol=analysis.rtol, length_scale=length_scale):
            try:
                sample = diagram_points(diagram.points, one)
            except ScrewkitError:
                continue
            found += 1
            yield sample
        if not found:
            raise ScrewkitValueError(
                f"Expected a generic configuration giving every diagram point, got none of {samples}."
            )

    return diagram, ReplaySampler(produce)


def graph_sampler(
    points: tuple[DiagramPoint, ...],
    build: Callable[[np.random.Generator], Any],
    *,
    attempts: int = 50,
) -> Callable[[np.random.Generator], dict[str, Array]]:
    """A sampler of a diagram's points at random configurations of the same mechanism.

    Parameters
    ----------
    points : tuple of DiagramPoint
        A diagram's points (their recipes).
    build : callable
        ``rng -> twist graph`` of the same mechanism (same joint names) at a random configuration;
        it may raise a :class:`~screwkit.exceptions.ScrewkitError` for configurations it cannot
        build (e.g. out of reach), which are skipped.
    attempts : int, default 50
        Configurations tried before giving up.

    Returns
    -------
    callable
        ``rng -> {label: point}``, for :func:`~screwkit.gca.superbracket_analysis.superbracket_analysis`.

    Raises
    ------
    ScrewkitValueError
        (when called) if no configuration of ``attempts`` gives every point.

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> h4 = load_mechanism("h4")
    >>> diagram = wrench_diagram(wrench_analysis(h4.twist_graph()))
    >>> sampler = graph_sampler(diagram.points, lambda rng: h4.twist_graph(h4.random_poses(rng, 1)[0]))
    >>> len(sampler(np.random.default_rng(0)))
    11
    """

    def sampler(rng: np.random.Generator) -> dict[str, Array]:
        for _ in range(attempts):
            try:
                analysis = wrench_analysis(build(rng))
                assert isinstance(analysis, WrenchAnalysis)  # numeric graphs (a symbolic one is generic)
                return diagram_points(points, analysis)
            except ScrewkitError:
                continue
        raise ScrewkitValueError(
            f"Expected a configuration giving every diagram point, got none in {attempts}."
        )

    return sampler
