"""The superbracket of a wrench diagram, analysed: expanded, simplified, factored, each factor
interpreted as a geometric condition and labelled by the roles of the lines it involves
(:func:`superbracket_analysis`, paper 002 §5; ``gca.md`` §5–§6).

Examples
--------
>>> diagram, sampler = load_mechanism("h4").wrench_diagram()
>>> print(superbracket_analysis(diagram, sampler).simplification.factored)
-[gikj][a b d ḟ][c g ḣ j]
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitError, ScrewkitTypeError, ScrewkitValueError
from .diagram import INCIDENCE_RTOL, WrenchDiagram, require_instance
from .redundant_conditions import RedundantSuperbracket, redundant_superbracket
from .simplify import Simplification, simplify_superbracket

if TYPE_CHECKING:  # conditions are sympy expressions: that module (and sympy) loads on first use
    from .conditions import Condition

__all__ = [
    "VANISHING_RTOL",
    "SuperbracketAnalysis",
    "superbracket_analysis",
]

Array = np.ndarray
#: A condition vanishes at the pose when its value there is at most this times its median size on
#: the generic samples (:attr:`SuperbracketAnalysis.vanishing`).
VANISHING_RTOL = 1e-7


@dataclass(frozen=True, eq=False)
class SuperbracketAnalysis:
    """The simplified superbracket of a diagram and its factors as labelled conditions.

    Attributes
    ----------
    diagram : WrenchDiagram
    simplification : Simplification
    conditions : tuple of Condition
    labels : tuple of str
        Per condition: ``"constraint"``, ``"actuation"`` or ``"constraint or actuation"``, from the
        roles of the lines whose points its vector form uses (:func:`screwkit.gca.conditions.label`;
        the evidence is in each condition's ``evidence``).
    values : tuple of float
        Each condition's vector form at the diagram's pose (NaN where one of its points does not
        exist there: :attr:`undefined`).
    collinear : tuple of str
        Triples of labels found collinear on every sample (declared to the factoring step).
    vanishing : tuple of bool
        Per condition: True when it vanishes at the pose, i.e. its value there is at most
        :data:`VANISHING_RTOL` times its median size on the generic samples (a singular pose keeps
        the factored form of a regular one; these factors are the ones that vanish).
    undefined : tuple of str
        Per condition: why it has no value at the pose (a point of the diagram that does not exist
        there, e.g. on a limb at a serial singularity), or "".
    split_at_pose : tuple of str
        Per condition that splits on the mechanism (:attr:`Condition.split
        <screwkit.gca.conditions.Condition.split>`), which of its brackets vanish at the pose, e.g.
        "here [abfd] = 1.4e-10 (vanishes), [abfh] = -0.61" (each relative to its median size on the
        generic samples, as :attr:`vanishing`); "" for the others.
    constant : tuple of bool
        Per condition: True when it takes one non-zero magnitude (within :data:`INCIDENCE_RTOL`) on
        every generic sample and at the pose: a structural factor of this mechanism that never vanishes
        (e.g. the planar mechanisms' constraint couples and force, the same lines at every pose),
        reported as such rather than as a singularity condition. The JSON field
        ``never_vanishes`` of each condition (:meth:`to_dict`), the report's text and the LaTeX
        (:meth:`to_latex`) all say so.
    """

    diagram: WrenchDiagram
    simplification: Simplification
    conditions: tuple[Condition, ...]
    labels: tuple[str, ...]
    values: tuple[float, ...]
    collinear: tuple[str, ...] = ()
    vanishing: tuple[bool, ...] = ()
    constant: tuple[bool, ...] = ()
    undefined: tuple[str, ...] = ()
    split_at_pose: tuple[str, ...] = ()

    @property
    def representation(self) -> tuple[str, ...]:
        """Why the diagram's representation does not hold at the pose (its ``degenerate`` reasons):
        the factored form is still the design's, derived at generic configurations, and every
        condition whose points exist at the pose is evaluated there (:attr:`undefined` says which
        are not). Empty at a pose where the representation holds.

        Returns
        -------
        tuple of str
        """
        return tuple(self.diagram.degenerate)

    def to_latex(self) -> str:
        """The factored superbracket and its conditions as a LaTeX ``align*`` block, the factors
        that never vanish said so (:func:`screwkit.gca.conditions.latex`).

        Returns
        -------
        str

        Examples
        --------
        >>> diagram, sampler = load_mechanism("planar_3rrp").wrench_diagram()
        >>> rows = superbracket_analysis(diagram, sampler).to_latex().splitlines()
        >>> print(rows[2].split("&")[0])
        \\text{never vanishes}:\\quad [hijg] \\neq 0
        """
        from .conditions import latex

        return latex(self.simplification.factored, self.conditions, self.diagram.line_text(), self.constant)

    def __repr__(self) -> str:
        """One line: the superbracket, its factored form and each condition's label.

        Returns
        -------
        str
        """
        pairs = zip(self.conditions, self.labels, strict=True)
        found = ", ".join(f"{label} {c.factor}" for c, label in pairs)
        return (
            f"SuperbracketAnalysis({self.diagram.line_text()} = {self.simplification.factored}"
            f"{'; ' + found if found else ''})"
        )

    def _repr_latex_(self) -> str:
        """Jupyter: the factored superbracket and its labelled conditions as one ``align*`` block
        (:func:`screwkit.gca.conditions.latex`, as ``screwkit analyze --latex``).

        Returns
        -------
        str
        """
        from .conditions import latex

        return latex(self.simplification.factored, self.conditions, self.diagram.line_text())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary.

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
        return {
            "superbracket": self.diagram.line_text(),
            "representation_at_pose": list(self.representation),
            "simplification": self.simplification.to_dict(),
            "conditions": [
                {
                    **c.to_dict(),
                    "label": label,
                    "value_at_pose": None if math.isnan(value) else value,
                    "undefined_at_pose": reason,
                    "vanishes_at_pose": vanishes,
                    "never_vanishes": constant,
                    "split_at_pose": split,
                }
                for c, label, value, vanishes, constant, reason, split in zip(
                    self.conditions,
                    self.labels,
                    self.values,
                    self.vanishing,
                    self.constant,
                    self.undefined,
                    self.split_at_pose or ("",) * len(self.conditions),
                    strict=True,
                )
            ],
        }


def superbracket_analysis(
    diagram: WrenchDiagram,
    sampler: Callable[[np.random.Generator], Mapping[str, Array]],
    *,
    n_samples: int = 6,
    rng: int = 0,
) -> SuperbracketAnalysis | RedundantSuperbracket:
    """Expand, simplify and factor a diagram's superbracket; interpret and label each factor.

    A diagram of more than six lines (a redundantly actuated mechanism's) is analysed by its six-line
    subsets (:func:`screwkit.gca.redundant_conditions.redundant_superbracket`).

    Two orderings are simplified (gca.md §6): the diagram's own (lines grouped by leg, shared
    points last, as in paper 002 Fig. 4c) and the one with the fewest surviving monomials over all
    46 080; the result is the one whose factored form has the fewest terms (then the fewest
    monomials), i.e. the most factors to interpret. Both are checked stage by stage against the
    6×6 determinant on fresh configurations.

    Parameters
    ----------
    diagram : WrenchDiagram
        A diagram of the mechanism at the pose (its representation may fail there: ``degenerate``).
    sampler : callable
        ``rng -> {label: point}``: the diagram's recipes at random poses of the same mechanism
        (:meth:`screwkit.robots.mechanism.Mechanism.wrench_diagram`), on which zeros are confirmed.
    n_samples : int, default 6
        Configurations that decide structural zeros (a bracket polynomial that is not identically
        zero on the incidence variety vanishes at a random configuration with probability 0, so
        one would already decide; six guard against a configuration near a singularity), and as
        many fresh ones for the checks; drawn once and shared by both orderings.
    rng : int, default 0

    Returns
    -------
    SuperbracketAnalysis or RedundantSuperbracket

    Raises
    ------
    ScrewkitValueError
        If the diagram is degenerate at its pose and the sampler gives no generic configuration
        (its reasons are given). A diagram degenerate at its pose alone is factored all the same:
        the factored form is the design's, and the conditions are evaluated where their points
        exist (:attr:`SuperbracketAnalysis.undefined`, :attr:`SuperbracketAnalysis.representation`).

    Examples
    --------
    >>> diagram, sampler = load_mechanism("h4").wrench_diagram()
    >>> result = superbracket_analysis(diagram, sampler)
    >>> str(result.simplification.factored), result.labels
    ('-[gikj][a b d ḟ][c g ḣ j]', ('constraint', 'actuation'))
    """
    require_instance(diagram, WrenchDiagram, "diagram")
    if not callable(sampler):
        raise ScrewkitTypeError(f"Expected `sampler` to be callable, got {type(sampler).__name__}.")
    if isinstance(n_samples, bool) or not isinstance(n_samples, int) or n_samples < 1:
        raise ScrewkitValueError(f"Expected `n_samples` to be an integer >= 1, got {n_samples!r}.")
    if len(diagram.lines) > 6:  # redundant actuation: the six-line subsets
        return redundant_superbracket(diagram, sampler, superbracket_analysis, n_samples=n_samples, rng=rng)
    generator = np.random.default_rng(rng)
    try:  # the factored form is the design's: derived at generic configurations, whatever the pose
        drawn = [_centred(sampler(generator)) for _ in range(2 * n_samples)]
    except (ScrewkitError, StopIteration, KeyError) as err:
        if not diagram.degenerate:
            raise
        raise ScrewkitValueError(
            "The wrench diagram is degenerate at this pose and no generic configuration was sampled, "
            "so no factorization is claimed: " + "; ".join(diagram.degenerate)
        ) from err
    # the zero tests of the expansion compare brackets of homogeneous points (x, 1) with products of
    # their norms, which is not free of the length unit: they get the samples in units of the
    # diagram's own size (one factor for all, diag(1/L, 1/L, 1/L, 1), which multiplies every bracket,
    # hence every monomial of the homogeneous superbracket, by the same L⁻³ and keeps every zero)
    length = _spread(drawn)
    in_lengths = [{k: np.concatenate([p[:3] / length, p[3:]]) for k, p in sample.items()} for sample in drawn]

    def replay() -> Callable[[np.random.Generator], Mapping[str, Array]]:
        iterator = iter(in_lengths)
        return lambda _: next(iterator)

    collinear = _collinear_triples(diagram, drawn)
    candidates = [
        simplify_superbracket(
            diagram.lines,
            replay(),
            finite=diagram.finite,
            infinite=diagram.infinite,
            collinear=collinear,
            n_samples=n_samples,
            search=search,
        )
        for search in (False, True)
    ]
    simplification = min(candidates, key=lambda c: (len(c.factored.rest.terms), len(c.survivors)))
    from .conditions import conditions, given_couples
    from .design_factors import with_design_splits

    found = conditions(
        simplification.factored,
        finite=diagram.finite,
        infinite=diagram.infinite,
        lines=diagram.lines,
        roles=diagram.roles,
    )
    found = _checked_kinds(found, in_lengths[-1], diagram, collinear)
    found = given_couples(found, diagram.lines, diagram.roles, diagram.infinite)
    found = with_design_splits(found, drawn, diagram.finite, diagram.infinite)
    labels = tuple(c.label for c in found)
    at_pose = _centred(diagram.coordinates)  # the points that exist at the pose
    missing = [sorted(set(c.vectors) - set(at_pose)) for c in found]
    values = tuple(
        float(c.evaluate(at_pose)) if not gone else math.nan for c, gone in zip(found, missing, strict=True)
    )
    undefined = tuple(
        f"the diagram has no point {', '.join(gone)} at this pose" if gone else "" for gone in missing
    )
    on_samples = [np.array([float(c.evaluate(sample)) for sample in drawn]) for c in found]
    typical = [B.median(np.abs(v)) for v in on_samples]
    vanishing = tuple(bool(abs(v) <= VANISHING_RTOL * size) for v, size in zip(values, typical, strict=True))
    # the magnitude: a point at infinity is a direction up to sign, so a structural factor may flip sign
    constant = tuple(
        size > 0
        and bool(
            np.all(
                np.abs(np.abs(sampled if math.isnan(value) else np.append(sampled, value)) - size)
                <= INCIDENCE_RTOL * size
            )
        )
        for sampled, value, size in zip(on_samples, values, typical, strict=True)
    )
    split_at_pose = tuple(_split_at_pose(c.split, at_pose, drawn) for c in found)
    return SuperbracketAnalysis(
        diagram, simplification, found, labels, values, collinear, vanishing, constant, undefined,
        split_at_pose,
    )


def _split_at_pose(
    split: tuple[Any, ...], at_pose: Mapping[str, Array], drawn: list[dict[str, Array]]
) -> str:
    """Which brackets of a split factor vanish at the pose, in words ("" if none split it or a point
    is missing there)."""
    if not split or any(x not in at_pose for b in split for x in b.labels):
        return ""
    parts = []
    for bracket in dict.fromkeys(split):
        value = float(bracket.evaluate(at_pose))
        size = B.median(np.abs([float(bracket.evaluate(sample)) for sample in drawn]))
        vanishes = abs(value) <= VANISHING_RTOL * size
        parts.append(f"{bracket} = {value:.6g}" + (" (vanishes)" if vanishes else ""))
    return "here " + ", ".join(parts)


def _checked_kinds(
    found: tuple[Condition, ...],
    sample: Mapping[str, Array],
    diagram: WrenchDiagram,
    collinear: tuple[str, ...],
) -> tuple[Condition, ...]:
    """Each condition labelled by what happens at its zeros
    (:func:`~screwkit.gca.factor_kinds.vanishing_kind`: the constraint lines lose rank, or keep it
    while the actuation wrenches become dependent), the roles' label kept where that does not decide;
    the evidence says both."""
    from dataclasses import replace

    from .factor_kinds import vanishing_kind

    checked = []
    for c in found:
        kind, evidence = vanishing_kind(c, sample, diagram.lines, diagram.roles, collinear=collinear)
        checked.append(replace(c, label=kind or c.label, evidence=f"{c.evidence}; {evidence}"))
    return tuple(checked)


def _centred(points: Mapping[str, Array]) -> dict[str, Array]:
    """The points with the origin moved to the centroid of the finite ones (``(x, w) → (x − w c, w)``,
    points at infinity unchanged). Brackets are 4×4 determinants of homogeneous coordinates, and a
    translation is a unimodular map of them, so every bracket, condition and collinearity keeps its
    value (gca.md §5.1: the values depend on differences of finite points only), while a mechanism
    far from the origin no longer loses digits to the cancellation of large coordinates."""
    finite = [np.asarray(p[:3], dtype=float) / p[3] for p in points.values() if p[3] != 0]
    if not finite:
        return dict(points)
    centre = np.mean(finite, axis=0)
    return {k: np.concatenate([p[:3] - p[3] * centre, p[3:]]) for k, p in points.items()}


def _spread(samples: list[dict[str, Array]]) -> float:
    """The RMS distance of the samples' finite points from their (centred) origin, 1 if none."""
    finite = [p[:3] / p[3] for sample in samples for p in sample.values() if p[3] != 0]
    size = float(np.sqrt(np.mean(np.sum(np.square(finite), axis=-1)))) if finite else 0.0
    return size if np.isfinite(size) and size > 0 else 1.0


def _collinear_triples(diagram: WrenchDiagram, samples: list[dict[str, Array]]) -> tuple[str, ...]:
    """Triples (two finite points, one at infinity) collinear on every sample (e.g. a, c, j in the H4)."""
    found = []
    for first, second in itertools.combinations(diagram.finite, 2):
        for direction in diagram.infinite:
            if all(_parallel(s[second][:3] - s[first][:3], s[direction][:3]) for s in samples):
                found.append(first + second + direction)
    return tuple(found)


def _parallel(u: Array, v: Array) -> bool:
    size = np.linalg.norm(u) * np.linalg.norm(v)
    return bool(size > 0 and np.linalg.norm(B.cross(u, v)) <= INCIDENCE_RTOL * size)
