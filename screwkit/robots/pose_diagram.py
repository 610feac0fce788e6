"""A posed mechanism's wrench diagram: at one pose, the diagram and the sampler of its points at generic
poses (:meth:`screwkit.robots.posed.PosedMechanism.diagram_and_sampler`; the generic draws the diagram
is chosen at and the first samples of its superbracket go through the analysis core as one batch with
the pose itself, docs/architecture.md §1a), and over a batch, its points
(:meth:`~screwkit.robots.posed.PosedMechanism.diagram_points`).

Examples
--------
>>> diagram, sampler = pose_diagram_and_sampler(load_mechanism("h4").at()[0])
>>> sorted(sampler(np.random.default_rng(0))) == sorted(p.label for p in diagram.points)
True
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from ..core.wrench_systems import WrenchAnalysis, analyze_table
from ..exceptions import ScrewkitError, ScrewkitValueError
from .generic_poses import (
    GENERIC_DRAWS,
    SAMPLES,
    _concatenated,
    _no_sampler,
    _PoseAnalyses,
    _reachable_table,
    _samples,
    generic_samples,
)

__all__ = ["diagram_points_over_batch", "generic_draws", "pose_diagram_and_sampler", "pose_superbracket"]

Array = np.ndarray


def generic_draws(posed: Any) -> tuple[Sequence[WrenchAnalysis], WrenchAnalysis | None, np.random.Generator]:
    """The random workspace poses a wrench diagram is chosen at (:data:`GENERIC_DRAWS`, seed 2026) and
    the first batch of its sampler's (``2 *`` :data:`SAMPLES`, seed 0) through the core as one batch,
    with the pose unless its analysis is already computed (one pass instead of three; a pose's result
    does not depend on the batch it is in, ``tests/robots/test_batch.py``). (61 poses of four limbs
    stay below :data:`screwkit.algebra.compiled.COMPILED_MIN_BATCH`: no numba import.)

    Parameters
    ----------
    posed : PosedMechanism
        One pose (shape ``()``): its analysis, from this batch, is kept on it.

    Returns
    -------
    analyses : sequence of WrenchAnalysis
        The per-pose analyses at the generic draws (those reached).
    samples : WrenchAnalysis or None
        The batch at the samples (None if none is reachable).
    stream : numpy.random.Generator
        The samples' generator, where the next batch is drawn from.

    Examples
    --------
    >>> analyses, samples, _ = generic_draws(load_mechanism("h4").at()[0])
    >>> len(analyses), len(samples)
    (12, 48)
    """
    mechanism, rtol = posed.mechanism, posed.rtol
    own = [] if "analysis" in posed.__dict__ else [posed.joints[None]]  # first: a pose out of reach says so
    stream = np.random.default_rng(0)
    generic = _reachable_table(mechanism, np.random.default_rng(2026), GENERIC_DRAWS)
    sampled = _reachable_table(mechanism, stream, 2 * SAMPLES)
    tables = [*own, *(t for t in (generic, sampled) if t is not None)]
    if not tables:  # the pose analysed already, no random pose reachable
        return [], None, stream
    batch = analyze_table(_concatenated(tables), rtol=rtol, length_scale=posed.length_scale)
    if own:
        posed.__dict__["analysis"] = posed._with_graph(batch[0])
    start = len(own)
    analyses: Sequence[WrenchAnalysis] = []
    if generic is not None:
        analyses = _PoseAnalyses(batch[start : start + len(generic)], generic, mechanism.name)
        start += len(generic)
    return analyses, (None if sampled is None else batch[start:]), stream


def pose_diagram_and_sampler(posed: Any) -> tuple[Any, Callable[[np.random.Generator], dict[str, Array]]]:
    """The wrench diagram at one pose and a sampler of its recipes at generic poses (what
    :meth:`PosedMechanism.diagram_and_sampler <screwkit.robots.posed.PosedMechanism.diagram_and_sampler>`
    returns; its docstring says how they are chosen).

    Parameters
    ----------
    posed : PosedMechanism
        One pose (shape ``()``).

    Returns
    -------
    diagram : WrenchDiagram
    sampler : callable
        ``sampler(rng) -> {label: (4,)}``, the diagram's points at a generic pose.

    Examples
    --------
    >>> diagram, _ = pose_diagram_and_sampler(load_mechanism("h4").at()[0])
    >>> len(diagram.points) > 0
    True
    """
    from ..gca.diagram_placement import ReplaySampler, diagram_at, generic_reference
    from ..gca.diagram_recipes import wrench_diagram

    analyses, first, stream = posed._draws
    reference, reasons = generic_reference(analyses)
    if reference is None:  # a property of the mechanism, found at generic poses: say so
        diagram = wrench_diagram(posed.analysis)
        return replace(diagram, coordinates={}, degenerate=reasons), _no_sampler
    diagram = diagram_at(reference, posed.analysis)
    mechanism, rtol, length = posed.mechanism, posed.rtol, posed.length_scale
    pending = [first]

    def produce(_: np.random.Generator) -> Iterable[dict[str, Array]]:
        # the first batch analysed with the generic draws, the next ones drawn on from its stream
        if pending:
            return _samples(diagram.points, pending.pop(), SAMPLES)
        return generic_samples(mechanism, diagram.points, stream, SAMPLES, rtol, length)

    return diagram, ReplaySampler(produce)


def pose_superbracket(posed: Any) -> Any:
    """The superbracket of one pose's wrench diagram, factored on its generic samples (what
    :attr:`PosedMechanism.superbracket <screwkit.robots.posed.PosedMechanism.superbracket>` is).

    Parameters
    ----------
    posed : PosedMechanism
        One pose (shape ``()``).

    Returns
    -------
    SuperbracketAnalysis or RedundantSuperbracket

    Raises
    ------
    ScrewkitValueError
        If the mechanism has no wrench diagram of six lines (or more) at generic poses.

    Examples
    --------
    >>> pose_superbracket(load_mechanism("h4").at()[0]).simplification.factored.to_dict()["text"]
    '-[gikj][a b d ḟ][c g ḣ j]'
    """
    from ..gca.superbracket_analysis import superbracket_analysis

    diagram, sampler = posed.diagram_and_sampler()
    if sampler is _no_sampler:
        raise ScrewkitValueError(
            f"Expected a wrench diagram of six lines for the superbracket of {posed.mechanism.name}, "
            f"got none: {'; '.join(diagram.degenerate)}."
        )
    return superbracket_analysis(diagram, sampler)


def diagram_points_over_batch(posed: Any, points: tuple[Any, ...]) -> tuple[dict[str, Array], Array]:
    """A wrench diagram's points at every pose of a posed batch, in the core's chunks (what
    :meth:`PosedMechanism.diagram_points <screwkit.robots.posed.PosedMechanism.diagram_points>` returns;
    its docstring says how).

    Parameters
    ----------
    posed : PosedMechanism
    points : tuple of DiagramPoint

    Returns
    -------
    tuple
        The points' values by label ``(..., 4)`` and where all exist ``(...)``, as the method's.

    Raises
    ------
    UnreachablePoseError
        As the method.

    Examples
    --------
    >>> v4 = load_mechanism("v4")
    >>> points = v4.at()[0].diagram.points
    >>> diagram_points_over_batch(v4.at([[0, 0, -750, 0]]), points)[1].tolist()
    [True]
    """
    from ..gca.diagram_points import batch_diagram_points, frames_read

    kept = functools.partial(frames_read, points)
    rtol, length = posed.rtol, posed.length_scale
    try:
        analyses = (
            analyze_table(table, rtol=rtol, length_scale=length, views=False, kept=kept)
            for table in posed._table_chunks()
        )
        parts = [batch_diagram_points(points, analysis) for analysis in analyses]
    except ScrewkitError:
        _ = posed.configuration  # raises the whole batch's message (the failing pose's index)
        raise
    values = {p.label: np.concatenate([part[p.label] for part in parts]) for p in points}
    values = {label: value.reshape(*posed.shape, 4) for label, value in values.items()}
    exists = np.all([np.isfinite(v).all(axis=-1) for v in values.values()], axis=0)
    return values, np.asarray(exists, dtype=bool).reshape(posed.shape)
