"""Random workspace poses for a wrench diagram: the generic draws its lines and points are chosen
at, and the generic samples its superbracket is checked on, each drawn and analysed as one batch.

The posed mechanism (:mod:`screwkit.robots.posed`) uses them for one pose's diagram and
superbracket: which lines make the diagram and which points they share is decided at generic poses,
and the superbracket's structural zeros and checks are confirmed at fresh ones (docs/architecture.md
§1a: every quantity over poses through the one batched core).

Examples
--------
>>> h4 = load_mechanism("h4")
>>> diagram, _ = h4.wrench_diagram()
>>> len(generic_samples(h4, diagram.points, np.random.default_rng(0), 2))
2
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any, overload

import numpy as np

from ..algebra import backend as B
from ..core.wrench_systems import WrenchAnalysis, analyze_table
from ..exceptions import ScrewkitError, ScrewkitValueError
from ..graphs.jointtable import JointTable

__all__ = ["GENERIC_DRAWS", "SAMPLES", "SAMPLE_CHUNK", "generic_samples"]

Array = np.ndarray

#: Random workspace poses drawn (in one batch) to find a generic configuration for a diagram (the
#: first few reachable ones are tried: screwkit.gca.diagram_placement.REFERENCE_TRIES).
GENERIC_DRAWS = 12
#: Generic samples of a diagram's points drawn (in one batch) for the superbracket: its structural
#: zeros and its checks take 12 (screwkit.gca.superbracket_analysis.superbracket_analysis).
SAMPLES = 24
#: Poses whose diagram points are evaluated at once when samples are read (the superbracket reads
#: 12: most of a batch of SAMPLES is never evaluated; their constraint lines take a readable basis
#: pose by pose).
SAMPLE_CHUNK = 12


def _reachable_table(mechanism: Any, rng: np.random.Generator, count: int) -> JointTable | None:
    """The joint table at ``count`` random workspace poses, those out of reach dropped (None if
    none is reachable)."""
    poses = mechanism.random_poses(rng, count)
    try:
        return mechanism.joints(poses)
    except ScrewkitError:  # some pose out of reach: keep those the IK accepts one by one
        kept = []
        for pose in poses:
            try:
                mechanism.configuration(pose)
            except ScrewkitError:
                continue
            kept.append(pose)
        return mechanism.joints(np.array(kept)) if kept else None


def _concatenated(tables: Sequence[JointTable]) -> JointTable:
    """Joint tables of one mechanism ``(n_i, ...)`` as one batch ``(Σ n_i, ...)``."""
    first = tables[0]
    anchor = None if first.anchor is None else np.concatenate([t.anchor for t in tables])
    screws = np.concatenate([t.screws for t in tables])
    return JointTable(
        first.base, first.platform, first.specs, screws, first.dof, anchor, first.mobility, first.free
    )


class _PoseAnalyses(Sequence[WrenchAnalysis]):
    """The per-pose views of a batched analysis, each (with its twist graph) built on first read:
    a diagram is chosen on the first few and sampled until enough points are found."""

    def __init__(self, batch: Any, table: JointTable, name: str):
        self._batch, self._table, self._name = batch, table, name
        self._built: dict[int, WrenchAnalysis] = {}

    def __len__(self) -> int:
        return len(self._batch)

    @overload
    def __getitem__(self, index: int) -> WrenchAnalysis: ...

    @overload
    def __getitem__(self, index: slice) -> list[WrenchAnalysis]: ...

    def __getitem__(self, index: int | slice) -> WrenchAnalysis | list[WrenchAnalysis]:
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        if not -len(self) <= index < len(self):
            raise IndexError(index)
        index %= len(self)
        if index not in self._built:
            one = self._batch[index]
            graph = self._table.graph(index)
            graph.graph["name"] = self._name
            object.__setattr__(one, "graph", graph)
            self._built[index] = one
        return self._built[index]


def generic_samples(
    mechanism: Any,
    points: Any,
    rng: np.random.Generator,
    count: int,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> list[dict[str, Array]]:
    """A diagram's points (``{label: (4,)}``) at random workspace poses, analysed and evaluated as
    one batch (:func:`screwkit.gca.diagram_points.batch_diagram_points`).

    Poses where a point does not exist are skipped; at most ``2 * count`` poses are drawn.

    Parameters
    ----------
    mechanism : Mechanism
    points : sequence of DiagramPoint
    rng : numpy.random.Generator
    count : int
        Samples wanted.
    rtol : float
    length_scale : float, optional

    Returns
    -------
    list of dict
        ``{label: (4,)}`` per sample.

    Raises
    ------
    ScrewkitValueError
        If no drawn pose gives every point.

    Examples
    --------
    >>> h4 = load_mechanism("h4")
    >>> diagram, _ = h4.wrench_diagram()
    >>> len(generic_samples(h4, diagram.points, np.random.default_rng(0), 3))
    3
    """
    table = _reachable_table(mechanism, rng, 2 * count)
    analysis = None if table is None else analyze_table(table, rtol=rtol, length_scale=length_scale)
    return list(_samples(points, analysis, count))


def _samples(points: Any, analysis: WrenchAnalysis | None, count: int) -> Iterator[dict[str, Array]]:
    """:func:`generic_samples` from the analysis of the drawn poses (None: none reachable), lazily:
    the points are evaluated :data:`SAMPLE_CHUNK` poses at a time, as far as the samples read."""
    from ..gca.diagram_points import batch_diagram_points

    given, total = 0, 0 if analysis is None else len(analysis)
    for start in range(0, total, SAMPLE_CHUNK):
        assert analysis is not None
        found = batch_diagram_points(points, analysis[start : start + SAMPLE_CHUNK])
        exists = np.all([np.isfinite(v).all(axis=-1) for v in found.values()], axis=0) if found else []
        for i in np.flatnonzero(exists)[: count - given]:
            given += 1
            yield {label: v[i] for label, v in found.items()}
        if given == count:
            return
    if not given:
        raise ScrewkitValueError(
            f"Expected a workspace pose giving every diagram point, got none of {2 * count}."
        )


def _no_sampler(rng: np.random.Generator) -> dict[str, Array]:
    """The sampler of a diagram that has no generic reference: always refuses (never called when
    the diagram is reported degenerate)."""
    raise ScrewkitValueError("no generic pose gives this mechanism a wrench diagram to sample.")
