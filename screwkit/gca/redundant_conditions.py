"""The conditions of a redundantly actuated mechanism: the superbrackets of its six-line subsets.

A redundantly actuated mechanism's global wrench system ``W^c + W^a`` is spanned by more than six
lines (the diagram's lines: a line basis of the constraint wrenches ``C`` and every actuation wrench
``W``, :mod:`screwkit.core.redundancy`). Its actuation singularities are where the constraint system
has its nominal order and the lines span fewer than six, i.e. (the rank of a matrix is below 6
exactly when every 6 × 6 minor vanishes) where the superbracket of every six of them vanishes. With
``C`` independent, the minors that keep all of ``C`` are enough: if ``[C; W]`` has rank 6, ``C``
extends to a basis with rows of ``W``, so a minor containing every row of ``C`` is non-zero. These
are also the only subsets whose superbracket is a property of the mechanism: the diagram's constraint
lines are one basis of ``W^c`` among many (another line representative of the same system), and a
subset that drops some of them would depend on that choice. So the conditions are the common zero
set of the superbrackets of the subsets made of all the constraint lines and ``6 − |C|`` actuation
lines (:func:`six_line_subsets`; for a 7-UPS, the seven subsets of six legs). Each subset is a wrench
diagram of six lines, analysed as any other
(``screwkit.gca.superbracket_analysis.superbracket_analysis``, which hands a diagram of more than six
lines to :func:`redundant_superbracket`: expanded, factored, each factor stated and labelled);
subsets whose six lines are dependent at every generic configuration are left out, since they vanish
everywhere and decide nothing. The mechanism is singular where, in each remaining subset, one of its
factors vanishes.

:class:`RedundantSuperbracket` keeps the subsets' analyses and gives their conditions as one list
(:attr:`~RedundantSuperbracket.conditions`, with :attr:`~RedundantSuperbracket.subset_of` saying which
subset each belongs to), in the place of a six-line mechanism's (``report.superbracket.conditions``).

Examples
--------
>>> len(six_line_subsets(("actuation",) * 7))  # a 7-UPS: seven forces, no constraint
7
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..algebra.projective import join_unchecked
from ..exceptions import ScrewkitError, ScrewkitTypeError, ScrewkitValueError
from .diagram import WrenchDiagram, require_instance

__all__ = ["MORE_LINES", "RedundantSuperbracket", "redundant_superbracket", "six_line_subsets"]

Array = np.ndarray

#: Part of the reason :mod:`screwkit.gca.diagram_lines` gives a diagram of more than six lines, which
#: the subsets resolve (kept out of each subset's own reasons).
MORE_LINES = "line generators, not 6"


#: Six lines are dependent on a sample when the smallest singular value of their unit rows (moments over
#: the samples' spread, about their centroid) is at most this times the largest.
DEPENDENT_RTOL = 1e-7


def _dependent_everywhere(lines: tuple[tuple[str, str], ...], samples: list[dict[str, Array]]) -> bool:
    """Whether six lines are dependent on every sample: their superbracket is identically zero on the
    mechanism (decided by ranks, so that the expansion's checks never compare noise with noise)."""
    for sample in samples:
        finite = [p[:3] / p[3] for p in sample.values() if p[3] != 0]
        centre = np.mean(finite, axis=0) if finite else np.zeros(3)
        spread = float(np.sqrt(np.mean(np.sum((np.array(finite) - centre) ** 2, axis=1)))) if finite else 1.0
        spread = spread if spread > 0 else 1.0

        def moved(p: Array, centre: Array = centre) -> Array:
            return np.concatenate([p[:3] - p[3] * centre, p[3:]])

        rows = np.array([join_unchecked(moved(sample[a]), moved(sample[b])) for a, b in lines])
        rows[:, 3:] /= spread
        rows /= np.linalg.norm(rows, axis=1, keepdims=True)
        values = np.linalg.svd(rows, compute_uv=False)
        if values[-1] > DEPENDENT_RTOL * values[0]:
            return False
    return True


def six_line_subsets(roles: tuple[str, ...]) -> tuple[tuple[int, ...], ...]:
    """The six-line subsets that decide the actuation singularities: every constraint line with each
    choice of the remaining ones among the actuation lines (indices, sorted, lexicographic order).

    Parameters
    ----------
    roles : tuple of str
        ``"constraint"`` or ``"actuation"`` per line (:attr:`WrenchDiagram.roles`).

    Returns
    -------
    tuple of tuple of int

    Raises
    ------
    ScrewkitValueError
        More than six constraint lines, or fewer than six lines.

    Examples
    --------
    >>> six_line_subsets(("actuation",) * 3 + ("constraint",) * 4)
    ((0, 1, 3, 4, 5, 6), (0, 2, 3, 4, 5, 6), (1, 2, 3, 4, 5, 6))
    """
    constraint = [i for i, role in enumerate(roles) if role == "constraint"]
    actuation = [i for i, role in enumerate(roles) if role != "constraint"]
    if len(roles) < 6 or len(constraint) > 6:
        raise ScrewkitValueError(
            f"Expected at least six lines, at most six of them constraint lines, got {len(roles)} lines "
            f"with {len(constraint)} constraint lines."
        )
    return tuple(
        tuple(sorted(constraint + list(chosen)))
        for chosen in itertools.combinations(actuation, 6 - len(constraint))
    )


def _subset_diagram(diagram: WrenchDiagram, subset: tuple[int, ...]) -> WrenchDiagram:
    lines = tuple(diagram.lines[i] for i in subset)
    used = {label for line in lines for label in line}
    return replace(
        diagram,
        points=tuple(p for p in diagram.points if p.label in used),
        lines=lines,
        line_names=tuple(diagram.line_names[i] for i in subset),
        roles=tuple(diagram.roles[i] for i in subset),
        coordinates={k: v for k, v in diagram.coordinates.items() if k in used},
        degenerate=tuple(reason for reason in diagram.degenerate if MORE_LINES not in reason),
    )


def _joined(name: str, doc: str) -> Any:
    """A property joining an attribute of every subset's analysis, subset by subset."""

    def joined(self: RedundantSuperbracket) -> tuple[Any, ...]:
        return tuple(item for analysis in self.analyses for item in getattr(analysis, name))

    return property(joined, doc=doc)


@dataclass(frozen=True, eq=False)
class RedundantSuperbracket:
    """The superbrackets of a redundantly actuated mechanism's six-line subsets (module docstring).

    Attributes
    ----------
    diagram : WrenchDiagram
        All the lines (more than six).
    subsets : tuple of tuple of int
        The six-line subsets (indices into ``diagram.lines``) whose superbracket is not identically
        zero on the mechanism.
    analyses : tuple of SuperbracketAnalysis
        Each subset's, in the order of ``subsets``.
    """

    diagram: WrenchDiagram
    subsets: tuple[tuple[int, ...], ...]
    analyses: tuple[Any, ...]

    conditions = _joined("conditions", "Every subset's conditions, subset by subset (:attr:`subset_of`).")
    labels = _joined("labels", "Per condition, its label (as a six-line mechanism's).")
    values = _joined("values", "Per condition, its value at the pose.")
    vanishing = _joined("vanishing", "Per condition, whether it vanishes at the pose.")
    constant = _joined("constant", "Per condition, whether it never vanishes on the mechanism.")
    undefined = _joined("undefined", 'Per condition, why it has no value at the pose, or "".')
    split_at_pose = _joined(
        "split_at_pose", 'Per condition, which brackets of its split vanish at the pose, or "".'
    )

    @property
    def subset_of(self) -> tuple[int, ...]:
        """Per condition, the index of its subset in :attr:`subsets`."""
        return tuple(k for k, analysis in enumerate(self.analyses) for _ in analysis.conditions)

    @property
    def representation(self) -> tuple[str, ...]:
        """Why the diagram's representation does not hold at the pose (beyond having more than six
        lines), as a six-line analysis's ``representation``."""
        return tuple(reason for reason in self.diagram.degenerate if MORE_LINES not in reason)

    @property
    def singular(self) -> bool:
        """True when every subset has a vanishing condition at the pose: the lines span fewer than six.
        Also True when no subset is left: every subset's superbracket is identically zero on the
        mechanism, so its lines span fewer than six everywhere (an architecturally singular design).

        Examples
        --------
        >>> RedundantSuperbracket(None, (), ()).singular
        True
        """
        return all(any(a.vanishing) for a in self.analyses)

    def statement(self) -> str:
        """The mechanism's actuation singularity in words: every subset's superbracket vanishes.

        Returns
        -------
        str

        Examples
        --------
        >>> RedundantSuperbracket(None, (), ()).statement()  # doctest: +ELLIPSIS
        'no six-line subset has a superbracket that is not identically zero: the lines span fewer ...'
        """
        if not self.analyses:
            return (
                "no six-line subset has a superbracket that is not identically zero: the lines span "
                "fewer than six at every configuration (an architecturally singular design)"
            )
        parts = [f"{a.diagram.line_text()} = {a.simplification.factored}" for a in self.analyses]
        constraint = self.diagram.roles.count("constraint")
        return (
            f"redundantly actuated: singular where all {len(parts)} superbrackets of the {constraint} "
            f"constraint lines with {6 - constraint} of the {len(self.diagram.lines) - constraint} "
            "actuation lines vanish at once (the lines span fewer than six): " + "; ".join(parts)
        )

    def to_latex(self) -> str:
        """Each subset's factored superbracket and conditions (a six-line analysis's ``to_latex``), one
        block per subset.

        Returns
        -------
        str
        """
        return "\n".join(analysis.to_latex() for analysis in self.analyses)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: the lines, the statement and each subset's analysis.

        Returns
        -------
        dict
        """
        return {
            "superbracket": self.diagram.line_text(),
            "redundant": True,
            "statement": self.statement(),
            "representation_at_pose": list(self.representation),
            "subsets": [
                {"lines": [int(i) for i in subset], **analysis.to_dict()}
                for subset, analysis in zip(self.subsets, self.analyses, strict=True)
            ],
            "conditions": [
                {**c.to_dict(), "subset": k, "label": label, "vanishes_at_pose": vanishes}
                for c, k, label, vanishes in zip(
                    self.conditions, self.subset_of, self.labels, self.vanishing, strict=True
                )
            ],
        }

    def __repr__(self) -> str:
        return f"RedundantSuperbracket({self.diagram.line_text()}: {len(self.subsets)} six-line subsets)"


def redundant_superbracket(
    diagram: WrenchDiagram,
    sampler: Callable[[np.random.Generator], Mapping[str, Array]],
    analyse: Callable[..., Any],
    *,
    n_samples: int = 6,
    rng: int = 0,
) -> RedundantSuperbracket:
    """Analyse the superbracket of every six-line subset of a diagram of more than six lines.

    The generic configurations are drawn once from ``sampler`` and replayed to every subset, each
    analysed by ``analyse`` (``superbracket_analysis``, ``n_samples`` as there); subsets whose
    superbracket is identically zero on the mechanism are left out (module docstring).

    Parameters
    ----------
    diagram : WrenchDiagram
        More than six lines.
    sampler : callable
        ``rng -> {label: point}``: every line's points at a generic configuration.
    analyse : callable
        ``analyse(diagram, sampler, n_samples=...)``: a six-line diagram's analysis
        (``screwkit.gca.superbracket_analysis.superbracket_analysis``).
    n_samples : int, default 6
    rng : int, default 0

    Returns
    -------
    RedundantSuperbracket

    Raises
    ------
    ScrewkitValueError
        A diagram of six lines or fewer, ``n_samples`` not an integer >= 1, or no generic
        configuration sampled.
    ScrewkitTypeError
        If ``analyse`` is not callable.

    Examples
    --------
    >>> redundant_superbracket(load_mechanism("h4").wrench_diagram()[0], None, None)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected a wrench diagram of more than six lines, got 6: ...
    """
    require_instance(diagram, WrenchDiagram, "diagram")
    if len(diagram.lines) <= 6:
        raise ScrewkitValueError(
            f"Expected a wrench diagram of more than six lines, got {len(diagram.lines)}: "
            "use screwkit.gca.superbracket_analysis.superbracket_analysis."
        )
    if not callable(analyse):
        raise ScrewkitTypeError(f"Expected `analyse` to be callable, got {type(analyse).__name__}.")
    if isinstance(n_samples, bool) or not isinstance(n_samples, int) or n_samples < 1:
        raise ScrewkitValueError(f"Expected `n_samples` to be an integer >= 1, got {n_samples!r}.")
    generator = np.random.default_rng(rng)
    try:
        drawn = [dict(sampler(generator)) for _ in range(2 * n_samples)]
    except (ScrewkitError, StopIteration, KeyError, TypeError) as err:
        raise ScrewkitValueError(
            "Expected generic configurations of the mechanism for its six-line subsets, got none: "
            + ("; ".join(diagram.degenerate) or str(err))
        ) from err
    subsets, analyses = [], []
    for subset in six_line_subsets(diagram.roles):
        part = _subset_diagram(diagram, subset)
        if _dependent_everywhere(part.lines, drawn):  # identically zero on the mechanism
            continue
        labels = {p.label for p in part.points}
        replay = iter([{k: v for k, v in sample.items() if k in labels} for sample in drawn])
        result = analyse(part, lambda _, samples=replay: next(samples), n_samples=n_samples)
        if not len(result.simplification.survivors):  # zero by its expansion: decided there too
            continue
        subsets.append(subset)
        analyses.append(result)
    return RedundantSuperbracket(diagram, tuple(subsets), tuple(analyses))
