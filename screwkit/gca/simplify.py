"""Simplification of a superbracket (``gca.md`` §6), every stage checked against the 6×6
determinant: the numeric check (:func:`check_proportional`) and the whole chain
(:func:`simplify_superbracket`: ordering search, expansion, structural zeros, vanishing subsums,
factoring by :func:`~screwkit.gca.factored.collect_factors`).

Examples
--------
>>> def concurrent(rng):  # six lines through the point o: always singular
...     pts = {x: np.r_[rng.normal(size=3), 1.0] for x in "abcdef"}
...     return {**pts, "o": np.r_[rng.normal(size=3), 1.0]}
>>> str(simplify_superbracket(["oa", "ob", "oc", "od", "oe", "of"], concurrent).factored)
'0'
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any, Protocol

import numpy as np

from ..algebra import backend as B
from ..algebra import projective as P
from ..algebra.checks import checked_rtol
from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from .brackets import BracketPolynomial
from .expansion import OrderingSearch, checked_lines, search_orderings, superbracket_expansion
from .factored import FactoredForm, collect_factors
from .zeros import Sampler, checked_positive_int, draw_samples, drop_structural_zeros, drop_vanishing_subsums

__all__ = [
    "Proportionality",
    "Simplification",
    "check_proportional",
    "simplify_superbracket",
]


class _Evaluable(Protocol):
    def evaluate(self, points: Mapping[str, Any]) -> Any: ...


Expression = _Evaluable | Callable[[Mapping[str, np.ndarray]], Any]


def _values(expr: Any, samples: Mapping[str, np.ndarray], name: str) -> np.ndarray:
    if hasattr(expr, "evaluate"):
        values = expr.evaluate(samples)
    elif callable(expr):
        values = expr(samples)
    else:
        raise ScrewkitTypeError(
            f"Expected `{name}` to have an evaluate(points) method or to be a callable "
            f"points -> values, got {type(expr).__name__}."
        )
    n = next(iter(samples.values())).shape[0]
    values = np.broadcast_to(np.asarray(values, dtype=float), (n,))
    if not np.all(np.isfinite(values)):
        raise ScrewkitValueError(f"Expected `{name}` to give finite values, got {values}.")
    return values


@dataclass(frozen=True, slots=True)
class Proportionality:
    """Result of :func:`check_proportional`: ``a ≈ constant × b`` on the samples.

    Attributes
    ----------
    constant : float
        Median of ``a / b`` over the samples.
    max_deviation : float
        ``max |a − constant·b| / max(|a|, |constant·b|)`` over the samples (0 = exactly
        proportional; round-off gives ~1e-14).
    n_samples : int
    """

    constant: float
    max_deviation: float
    n_samples: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary.

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
        return {
            "constant": self.constant,
            "max_deviation": self.max_deviation,
            "n_samples": self.n_samples,
        }

    def __str__(self) -> str:
        return (
            f"constant {self.constant:.12g}, max relative deviation {self.max_deviation:.2e} "
            f"over {self.n_samples} samples"
        )


def _proportionality(a: np.ndarray, b: np.ndarray, name: str) -> Proportionality:
    nonzero = b != 0
    if not np.any(nonzero):
        raise DegenerateGeometryError(
            f"Expected `{name}` to be non-zero on some sample, got zero on all {b.size} samples."
        )
    constant = B.median(a[nonzero] / b[nonzero])
    scale = np.maximum(np.abs(a), np.abs(constant * b))
    deviation = np.abs(a - constant * b) / np.where(scale > 0, scale, 1.0)
    return Proportionality(constant, float(deviation.max()), int(b.size))


def check_proportional(
    expr_a: Expression,
    expr_b: Expression,
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rng: np.random.Generator | int = 0,
) -> Proportionality:
    """Check numerically that ``expr_a = constant × expr_b`` on sampled configurations.

    The check behind every simplification step (``gca.md`` §6.3): the 6×6 determinant divided by
    the simplified expression must be a constant.

    Parameters
    ----------
    expr_a, expr_b : expression or callable
        Anything with ``evaluate(points)`` (brackets, polynomials, dotted forms, factored forms) or
        a callable ``points -> values`` (e.g. ``lambda p: superbracket(p, lines)``). They are
        evaluated on all samples at once (points of shape (n_samples, 4)).
    sampler : callable
        ``rng -> {label: point (4,)}``.
    n_samples : int, default 20
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    Proportionality

    Raises
    ------
    DegenerateGeometryError
        If ``expr_b`` is zero on every sample.

    Examples
    --------
    >>> def sampler(rng):
    ...     return {x: rng.normal(size=4) for x in "abcd"}
    >>> from screwkit.gca import Bracket
    >>> r = check_proportional(Bracket("bacd"), Bracket("abcd"), sampler)
    >>> r.constant, r.max_deviation < 1e-12
    (-1.0, True)
    """
    samples = draw_samples(sampler, n_samples, np.random.default_rng(rng))
    return _proportionality(
        _values(expr_a, samples, "expr_a"), _values(expr_b, samples, "expr_b"), "expr_b"
    )


@dataclass(frozen=True, slots=True)
class Simplification:
    """Every stage of :func:`simplify_superbracket`, each checked against the 6×6 determinant.

    Attributes
    ----------
    lines : tuple of six (str, str)
        The caller's lines.
    ordering : OrderingSearch or None
        The ordering search, if one was made.
    expansion : BracketPolynomial
        The 24-term expansion in the chosen ordering.
    survivors : BracketPolynomial
        Without its structurally zero monomials.
    reduced : BracketPolynomial
        Without vanishing subsums.
    factored : FactoredForm
        The factored form, its coefficient including the ordering's sign, so that it equals the
        superbracket of the caller's lines on the incidence variety.
    checks : tuple of (str, Proportionality)
        ``superbracket(caller's lines) / stage`` on fresh samples, for each stage: the constant is
        1 and the deviation at round-off level. If the superbracket vanishes on the incidence
        variety (nothing survives), one entry ``"vanishes"`` with constant 0 and, as deviation,
        the largest ``|det|`` relative to its Hadamard bound (the product of the row norms).
    """

    lines: tuple[tuple[str, str], ...]
    ordering: OrderingSearch | None
    expansion: BracketPolynomial
    survivors: BracketPolynomial
    reduced: BracketPolynomial
    factored: FactoredForm
    checks: tuple[tuple[str, Proportionality], ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary of every stage.

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
        return {
            "lines": [list(line) for line in self.lines],
            "ordering": None if self.ordering is None else self.ordering.to_dict(),
            "expansion": str(self.expansion),
            "survivors": str(self.survivors),
            "reduced": str(self.reduced),
            "factored": self.factored.to_dict(),
            "checks": {name: check.to_dict() for name, check in self.checks},
        }

    def __str__(self) -> str:
        lines = [
            f"superbracket = {self.factored}",
            f"monomials: {len(self.expansion)} expanded, {len(self.survivors)} not structurally "
            f"zero, {len(self.reduced)} after vanishing subsums",
        ]
        if self.ordering is not None:
            lines.append(f"ordering: {self.ordering}")
        lines += [f"check {name}: {check}" for name, check in self.checks]
        return "\n".join(lines)


def _check_weights(
    samples: Mapping[str, np.ndarray], finite: Sequence[str], infinite: Sequence[str], rtol: float
) -> None:
    for label in finite:
        if label in samples and not np.allclose(samples[label][:, 3], 1.0, rtol=0, atol=rtol):
            raise ScrewkitValueError(
                f"Expected `sampler` to give the finite point {label!r} weight 1, got weights "
                f"{samples[label][:3, 3]}..."
            )
    for label in infinite:
        if label in samples and np.any(samples[label][:, 3] != 0):
            raise ScrewkitValueError(
                f"Expected `sampler` to give the infinite point {label!r} weight 0, got weights "
                f"{samples[label][:3, 3]}..."
            )


def simplify_superbracket(
    lines: Sequence[Sequence[str] | str],
    sampler: Sampler,
    *,
    finite: Sequence[str] = (),
    infinite: Sequence[str] = (),
    collinear: Sequence[Sequence[str] | str] = (),
    search: bool = True,
    n_samples: int = 20,
    rtol: float = 1e-9,
    check_rtol: float = 1e-6,
    max_terms: int = 16,
    rng: np.random.Generator | int = 0,
) -> Simplification:
    """The simplification procedure of ``gca.md`` §6, every step checked numerically.

    Ordering search (optional, :func:`~screwkit.gca.expansion.best_ordering`), 24-term expansion, structural
    zeros
    (:func:`~screwkit.gca.zeros.structural_zeros`), vanishing subsums
    (:func:`~screwkit.gca.zeros.drop_zero_subsums`), factoring
    (:func:`collect_factors`). The samples used to decide zeros and the fresh samples used for
    the checks come from the same generator but are different draws.

    Parameters
    ----------
    lines : sequence of six pairs of labels
    sampler : callable
        ``rng -> {label: point (4,)}``: finite points with weight exactly 1.
    finite, infinite, collinear
        Declarations passed to :func:`collect_factors` (and checked against the samples' weights).
    search : bool, default True
        Search the 46 080 orderings; False keeps the caller's order.
    n_samples : int, default 20
    rtol : float, default 1e-9
        Relative zero threshold of brackets and subsums.
    check_rtol : float, default 1e-6
        Largest accepted deviation of a stage from the superbracket on fresh samples.
    max_terms : int, default 16
        See :func:`~screwkit.gca.zeros.drop_zero_subsums`.
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    Simplification

    Raises
    ------
    ScrewkitValueError
        If a stage is not equal to the superbracket on the fresh samples (a sampler that does not
        satisfy the declarations), or finite/infinite weights do not match the declarations.

    Examples
    --------
    >>> def concurrent(rng):  # six lines through the point o: always singular
    ...     pts = {x: np.r_[rng.normal(size=3), 1.0] for x in "abcdef"}
    ...     return {**pts, "o": np.r_[rng.normal(size=3), 1.0]}
    >>> result = simplify_superbracket(["oa", "ob", "oc", "od", "oe", "of"], concurrent)
    >>> str(result.factored)
    '0'
    """
    pairs = checked_lines(lines)
    rtol, check = checked_rtol(rtol), checked_rtol(check_rtol, "check_rtol")
    terms = checked_positive_int(max_terms, "max_terms")
    generator = np.random.default_rng(rng)
    labels = [label for line in pairs for label in line]
    samples = draw_samples(sampler, n_samples, generator, labels)
    _check_weights(samples, finite, infinite, rtol)
    ordering = search_orderings(pairs, samples, rtol) if search else None
    chosen, sign = (ordering.lines, ordering.sign) if ordering is not None else (pairs, 1)
    expansion = superbracket_expansion(chosen)
    survivors = drop_structural_zeros(expansion, samples, rtol)
    reduced = drop_vanishing_subsums(survivors, samples, rtol, terms)
    factored = collect_factors(reduced, finite=finite, infinite=infinite, collinear=collinear)
    factored = replace(factored, coefficient=sign * factored.coefficient)

    fresh = draw_samples(sampler, n_samples, generator, labels)
    rows = np.stack([P.join_unchecked(fresh[p], fresh[q]) for p, q in pairs], axis=-2)
    truth = np.linalg.det(rows)
    if reduced.terms:
        stages = {"expansion": expansion, "survivors": survivors, "reduced": reduced}
        checks = [
            (name, _proportionality(truth, sign * _values(stage, fresh, name), name))
            for name, stage in stages.items()
        ]
        checks.append(
            ("factored", _proportionality(truth, _values(factored, fresh, "factored"), "factored"))
        )
    else:  # the superbracket vanishes on the variety: compare it with its Hadamard bound
        relative = np.abs(truth) / np.linalg.norm(rows, axis=-1).prod(axis=-1)
        checks = [("vanishes", Proportionality(0.0, float(relative.max()), len(truth)))]
    for name, result in checks:
        expected = 0.0 if name == "vanishes" else 1.0
        if result.max_deviation > check or abs(result.constant - expected) > check:
            raise ScrewkitValueError(
                f"Expected stage {name!r} to equal the superbracket on fresh samples, got {result}:"
                f" check that `sampler` gives finite points of weight 1 and satisfies the "
                f"declared `collinear` triples."
            )
    return Simplification(pairs, ordering, expansion, survivors, reduced, factored, tuple(checks))
