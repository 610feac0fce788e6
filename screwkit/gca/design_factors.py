"""Factors that split on one mechanism's configurations though not in the bracket ring.

The factored superbracket is derived in the bracket ring: brackets are independent variables, and
only the diagram's incidences (repeated points, points at infinity, collinear triples) are used. A
mechanism's configurations may satisfy relations that are no incidence of the diagram, e.g. a
helical joint's pitch or axes fixed perpendicular by design. On them, a factor that the bracket
ring cannot split may be a constant multiple of a product of some of its own brackets; its zero
set on this mechanism is then the union of theirs, each with its own statement.

Example: the Peppermill (paper 000), diagram ``[ab, cd, ef, gh, ib, if]``, with ``i`` the plate's
vertical axis, ``b``, ``f`` the horizontal elbow axes and ``d``, ``h`` the distal links. Its
actuation factor is ``F = [abfd][eghi] − [abfh][ecdi]``. Lines cd and gh are reciprocal to the
plate's helical joints (pitches p₁, p₂ per turn, axis through e along i), so on the mechanism
``[eghi] = −p₂ (i·h)/2π`` and ``[ecdi] = −p₁ (i·d)/2π`` (unit i), while ``[abfd] = −(b × f)·d`` with
``b × f = i``. Hence ``F = (p₂ − p₁)/2π · [abfd][abfh]``, zero exactly where a distal link is horizontal:
paper 000's Eq. (48), ``det A = v₁z v₂z (p₂ − p₁)/2π``.

:func:`split_on_configurations` finds such a product (at most :data:`MAX_BRACKETS` brackets) by
the ratio ``F / product`` being one number on every sampled configuration (relative spread at
most :data:`PROPORTION_RTOL`); this is a numerical check on the mechanism's configurations, not a
proof, and the statement says so.

Examples
--------
>>> from screwkit.gca import BracketPolynomial
>>> rng = np.random.default_rng(0)
>>> samples = []
>>> for _ in range(6):  # a design in which e − a = 2 (d − a): then [abce] = 2 [abcd]
...     p = {x: np.r_[rng.normal(size=3), 1.0] for x in "abcd"}
...     samples.append(p | {"e": 2 * p["d"] - p["a"]})
>>> split = split_on_configurations(BracketPolynomial.parse("[abcd] + [abce]"), samples)
>>> [str(b) for b in split.brackets], round(split.ratio, 9)
(['[abcd]'], 3.0)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .brackets import Bracket, BracketPolynomial

if TYPE_CHECKING:
    from .conditions import Condition

__all__ = [
    "MAX_BRACKETS",
    "PROPORTION_RTOL",
    "DesignSplit",
    "split_on_configurations",
    "with_design_splits",
]

#: The most brackets a product may have.
MAX_BRACKETS = 3
#: The ratio factor / product counts as one number when its spread over the samples is at most this
#: times its median magnitude.
PROPORTION_RTOL = 1e-8


@dataclass(frozen=True, slots=True)
class DesignSplit:
    """A factor equal, on a mechanism's sampled configurations, to a constant times a product.

    Attributes
    ----------
    brackets : tuple of Bracket
        The product's brackets (a repeated one is a power).
    ratio : float
        ``factor / product`` on the samples (its median; the points' scales as sampled).
    n_samples : int
        On how many configurations the ratio was found to be one number.
    """

    brackets: tuple[Bracket, ...]
    ratio: float
    n_samples: int


def _stacked(samples: Sequence[Mapping[str, Any]], labels: set[str]) -> dict[str, np.ndarray]:
    for index, sample in enumerate(samples):
        if not isinstance(sample, Mapping):
            raise ScrewkitTypeError(
                f"Expected `samples[{index}]` to map labels to points, got {type(sample).__name__}."
            )
        missing = sorted(labels - set(sample))
        if missing:
            raise ScrewkitValueError(
                f"Expected `samples[{index}]` to hold the points {', '.join(missing)}, got none for them."
            )
    stacked = {}
    for x in labels:
        try:
            stacked[x] = np.stack([np.asarray(s[x], dtype=float) for s in samples])
        except (TypeError, ValueError):
            stacked[x] = np.zeros(0)
        if stacked[x].shape != (len(samples), 4):
            raise ScrewkitValueError(
                f"Expected `samples` to give point {x!r} as 4 homogeneous numbers in each sample, got "
                f"{[np.shape(s[x]) for s in samples][:3]}."
            )
    return stacked


def split_on_configurations(
    factor: BracketPolynomial, samples: Sequence[Mapping[str, Any]]
) -> DesignSplit | None:
    """The smallest product of the factor's own brackets it is a constant multiple of on the samples.

    Parameters
    ----------
    factor : BracketPolynomial
        A factor of two or more terms (a single monomial is a product already: None).
    samples : sequence of mapping of str to array_like, shape (4,)
        Configurations of one mechanism (its diagram's points), at least three.

    Returns
    -------
    DesignSplit or None
        None when no product of at most :data:`MAX_BRACKETS` of its brackets (each varying on the
        samples, none constant in magnitude) has a ratio to the factor that is one number. Of
        several products of the fewest brackets, the one on the fewest points.

    Raises
    ------
    ScrewkitTypeError
        If ``factor`` is not a BracketPolynomial, or ``samples`` not a sequence of mappings.
    ScrewkitValueError
        If there are fewer than three samples, a sample lacks a label of the factor, or a point is not
        four homogeneous numbers.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> samples = [{x: np.r_[rng.normal(size=3), 1.0] for x in "abcdef"} for _ in range(5)]
    >>> print(split_on_configurations(BracketPolynomial.parse("[abcd][abef] - [abce][abdf]"), samples))
    None
    """
    if not isinstance(factor, BracketPolynomial):
        raise ScrewkitTypeError(f"Expected `factor` to be a BracketPolynomial, got {type(factor).__name__}.")
    if not isinstance(samples, Sequence) or isinstance(samples, str):
        raise ScrewkitTypeError(
            f"Expected `samples` to be a sequence of mappings, got {type(samples).__name__}."
        )
    if len(samples) < 3:
        raise ScrewkitValueError(f"Expected at least three `samples`, got {len(samples)}.")
    if len(factor.terms) < 2:
        return None
    brackets = list({b.sorted_labels: b for m in factor.terms for b in m.brackets}.values())
    points = _stacked(samples, {x for b in brackets for x in b.labels})
    values = np.asarray(factor.evaluate(points), dtype=float)
    size = float(np.median(np.abs(values)))
    if not size > 0:
        return None
    varying = []
    for b in brackets:
        v = np.asarray(b.evaluate(points), dtype=float)
        magnitude = float(np.median(np.abs(v)))
        if magnitude > 0 and np.all(np.abs(v) > 1e-12 * magnitude):
            if np.ptp(np.abs(v)) > PROPORTION_RTOL * magnitude:  # a constant one is no condition
                varying.append((b, v))
    if not varying or not np.all(np.abs(values) > 1e-12 * size):
        return None
    # |factor / product| is one number iff log|factor| − Σ log|bracket| is constant over the samples:
    # with each row centred over the samples, iff the centred logs add up (searched by broadcasting)
    logs = np.log(np.abs(np.array([v for _, v in varying])))
    logs -= logs.mean(axis=1, keepdims=True)
    target = np.log(np.abs(values))
    target -= target.mean()
    for count in range(1, MAX_BRACKETS + 1):
        hits = [
            chosen
            for chosen in _sums_matching(logs, target, count)
            if np.ptp(np.sign(values) * np.prod([np.sign(varying[k][1]) for k in chosen], axis=0)) == 0
        ]
        if hits:  # the product on the fewest points reads simplest (the Peppermill: [abfd][abfh])
            chosen = min(hits, key=lambda c: (len({x for k in c for x in varying[k][0].labels}), c))
            product = np.prod([varying[k][1] for k in chosen], axis=0)
            ratio = float(np.median(values / product))
            return DesignSplit(tuple(varying[k][0] for k in chosen), ratio, len(samples))
    return None


def _sums_matching(logs: np.ndarray, target: np.ndarray, count: int) -> list[tuple[int, ...]]:
    """Index tuples i ≤ j ≤ … (``count`` of them) whose rows of ``logs`` add up to ``target`` within
    :data:`PROPORTION_RTOL` (``logs``: one centred row per bracket, one column per sample)."""
    k = len(logs)
    found: list[tuple[int, ...]] = []
    if count == 1:
        close = np.max(np.abs(logs - target), axis=1) <= PROPORTION_RTOL
        return [(int(i),) for i in np.flatnonzero(close)]
    for first in range(k):  # one broadcast per first index keeps memory at k^(count-1) rows
        rest = target - logs[first]
        if count == 2:
            close = np.max(np.abs(logs[first:] - rest), axis=1) <= PROPORTION_RTOL
            found += [(first, first + int(j)) for j in np.flatnonzero(close)]
        else:
            pairs = logs[first:, None, :] + logs[None, first:, :]
            close = np.max(np.abs(pairs - rest), axis=2) <= PROPORTION_RTOL
            rows, columns = np.nonzero(close)
            pairs_found = zip(rows.tolist(), columns.tolist(), strict=True)
            found += [(first, first + i, first + j) for i, j in pairs_found if i <= j]
    return found


def with_design_splits(
    found: Sequence[Condition],
    samples: Sequence[Mapping[str, Any]],
    finite: Any,
    infinite: Any,
) -> tuple[Condition, ...]:
    """The conditions, each factor that splits on the sampled configurations saying so in words.

    Parameters
    ----------
    found : sequence of Condition
        Conditions of one superbracket (:func:`screwkit.gca.conditions.conditions`).
    samples : sequence of mapping of str to array_like, shape (4,)
        Configurations of the mechanism (at least three).
    finite, infinite : str or sequence of str
        The diagram's finite and infinite labels.

    Returns
    -------
    tuple of Condition
        The same conditions; a split one's statement ends with the product, its vector form and the
        statement of each of its brackets.

    Examples
    --------
    >>> from screwkit.gca.superbracket_analysis import superbracket_analysis
    >>> diagram, sampler = load_mechanism("peppermill").wrench_diagram()
    >>> actuation = superbracket_analysis(diagram, sampler).conditions[1]
    >>> print(actuation.statement.split("; ")[1][:59])
    on this mechanism it is a constant multiple of [abfd][abfh]
    """
    from .condition_patterns import bracket_polynomial
    from .conditions import condition

    out = []
    for c in found:
        polynomial = bracket_polynomial(c.factor)
        split = None if isinstance(c.factor, Bracket) else split_on_configurations(polynomial, samples)
        if split is None:
            out.append(c)
            continue
        parts = [condition(b, finite=finite, infinite=infinite) for b in split.brackets]
        product = "".join(str(b) for b in split.brackets)
        forms = " · ".join(f"({p.expression})" if len(parts) > 1 else str(p.expression) for p in parts)
        where = " or where ".join(dict.fromkeys(p.statement for p in parts))
        statement = (
            f"{c.statement}; on this mechanism it is a constant multiple of {product} (the same ratio "
            f"on all {split.n_samples} sampled configurations: a relation of the design that is no "
            f"incidence of the diagram, checked numerically), i.e. of {forms}, so it vanishes exactly "
            f"where {where}"
        )
        out.append(replace(c, statement=statement, split=split.brackets))
    return tuple(out)
