"""A sum of single brackets that is one bracket of combined points: ``[a b (c − d) (e − f)]``.

Brackets are multilinear and alternating in their four points (``gca.md`` §1), so a factor such as
``[abce] − [abcf] − [abde] + [abdf]`` (a 3-UPU's actuation factor) is the single bracket
``[a b (c − d) (e − f)]``. A difference of two finite points (weight 1 each) is the point at
infinity in the direction of the line through them, so with ``a, b`` finite the factor vanishes
exactly when the direction of line ``ab`` is parallel to the plane spanned by the directions of
lines ``cd`` and ``ef``: the three leg directions are parallel to one plane.

Method: a sum ``Σ c_T [T]`` of single brackets is the linear functional of the 4-vector
``ω = Σ c_T e_T`` of the exterior algebra over the formal labels; it is one bracket
``[s₁ s₂ s₃ s₄]`` of combined points exactly when ω is decomposable, ``ω = λ s₁∧s₂∧s₃∧s₄``, and then
the contractions of ω by the 3-vectors span the 4-dimensional space ⟨s₁, …, s₄⟩ (the support of a
decomposable multivector; Marcus, *Finite Dimensional Multilinear Algebra* II, 1975, §4.1, Thm 1.3).
The slots are that space's reduced row-echelon basis (exact rationals), so they read as single
labels and differences; the candidate is then checked by expanding it back (exact arithmetic).

Examples
--------
>>> from screwkit.gca import BracketPolynomial
>>> from screwkit.gca.vector_forms import PointKinds
>>> found = combined_bracket(BracketPolynomial.parse("[abce] - [abcf] - [abde] + [abdf]"))
>>> [str(slot) for slot in found.slots], found.coefficient
(['a', 'b', 'c - d', 'e - f'], Fraction(1, 1))
>>> form, statement = combined_bracket_form(found, PointKinds("abcdef", ""))
>>> print(form)
((b − a) × (c − d))·(e − f)
>>> statement
'the directions of lines ab, cd and ef are parallel to one plane'
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction

import sympy

from .brackets import BracketMonomial, BracketPolynomial
from .notation import join_labels
from .vector_forms import PointKinds, VectorCross, VectorDiff, VectorDot

__all__ = ["CombinedBracket", "CombinedPoint", "combined_bracket", "combined_bracket_form"]


@dataclass(frozen=True)
class CombinedPoint:
    """A linear combination ``Σ c_x x`` of labelled points (one slot of a combined bracket).

    Attributes
    ----------
    terms : tuple of (str, Fraction)
        The labels and their coefficients, in the labels' order.

    Examples
    --------
    >>> str(CombinedPoint((("c", Fraction(1)), ("d", Fraction(-1)))))
    'c - d'
    """

    terms: tuple[tuple[str, Fraction], ...]

    def __str__(self) -> str:
        text = ""
        for label, coefficient in self.terms:
            size = abs(coefficient)
            written = label if size == 1 else f"{size} {label}"
            text += (written if coefficient > 0 else f"-{written}") if not text else (
                f" + {written}" if coefficient > 0 else f" - {written}"
            )
        return text


@dataclass(frozen=True)
class CombinedBracket:
    """``coefficient × [s₁ s₂ s₃ s₄]`` with each slot a :class:`CombinedPoint`.

    Attributes
    ----------
    slots : tuple of CombinedPoint
        Four slots.
    coefficient : Fraction
        The factor λ: the polynomial equals ``λ [s₁ s₂ s₃ s₄]`` expanded.
    """

    slots: tuple[CombinedPoint, ...]
    coefficient: Fraction


def _contraction_rows(weights: dict[tuple[str, ...], Fraction], labels: list[str]) -> list[list[Fraction]]:
    """The contractions ``ι(e_i∧e_j∧e_k) ω`` as coefficient rows over ``labels``."""
    rows = []
    for triple in itertools.combinations(labels, 3):
        row = []
        for label in labels:
            if label in triple:
                row.append(Fraction(0))
                continue
            four = (*triple, label)
            ordered = tuple(sorted(four))
            inversions = sum(a > b for i, a in enumerate(four) for b in four[i + 1 :])
            row.append(weights.get(ordered, Fraction(0)) * (-1) ** inversions)
        if any(row):
            rows.append(row)
    return rows


def combined_bracket(polynomial: BracketPolynomial) -> CombinedBracket | None:
    """The polynomial as one bracket of combined points, or None when it is not one.

    Parameters
    ----------
    polynomial : BracketPolynomial
        A sum of single brackets (a term with two brackets or more gives None).

    Returns
    -------
    CombinedBracket or None
        None also for a single bracket (nothing to combine) and for the zero polynomial.

    Examples
    --------
    >>> combined_bracket(BracketPolynomial.parse("[abcd][efgh]")) is None
    True
    >>> found = combined_bracket(BracketPolynomial.parse("[abce] + [abde]"))
    >>> [str(s) for s in found.slots]
    ['a', 'b', 'c + d', 'e']
    """
    terms = list(polynomial)
    if len(terms) < 2 or any(len(term.brackets) != 1 for term in terms):
        return None
    weights: dict[tuple[str, ...], Fraction] = {}
    for term in terms:
        bracket = term.brackets[0]
        weights[bracket.sorted_labels] = weights.get(bracket.sorted_labels, Fraction(0)) + (
            term.coefficient * bracket.sign
        )
    labels = sorted({x for key in weights for x in key})
    rows = _contraction_rows(weights, labels)
    matrix = sympy.Matrix([[sympy.Rational(v.numerator, v.denominator) for v in row] for row in rows])
    reduced, pivots = matrix.rref()
    if len(pivots) != 4:
        return None
    slots = tuple(
        CombinedPoint(
            tuple(
                (label, Fraction(int(value.p), int(value.q)))
                for label, value in zip(labels, reduced.row(k), strict=True)
                if value != 0
            )
        )
        for k in range(4)
    )
    unit = BracketPolynomial(  # [s1 s2 s3 s4] expanded by multilinearity
        BracketMonomial([tuple(label for label, _ in chosen)], _product(c for _, c in chosen))
        for chosen in itertools.product(*(slot.terms for slot in slots))
        if len({label for label, _ in chosen}) == 4
    )
    reference = next(iter(unit))
    key = reference.brackets[0].sorted_labels
    match = next((t for t in terms if t.brackets[0].sorted_labels == key), None)
    if match is None:
        return None
    coefficient = (match.coefficient * match.brackets[0].sign) / (
        reference.coefficient * reference.brackets[0].sign
    )
    scaled = BracketPolynomial(BracketMonomial(t.brackets, t.coefficient * coefficient) for t in unit)
    if scaled != polynomial:
        return None
    return CombinedBracket(slots, coefficient)


def _product(values: Iterable[Fraction]) -> Fraction:
    total = Fraction(1)
    for value in values:
        total *= value
    return total


def combined_bracket_form(found: CombinedBracket, types: PointKinds) -> tuple[sympy.Expr, str] | None:
    """Vector form and statement of a combined bracket whose slots are labels and differences.

    A slot ``x − y`` of two finite points is the point at infinity in the direction of line
    ``xy``; of two points at infinity, the direction ``x − y``. Slots of other shapes (sums, a finite
    minus an infinite point, three labels) give None: the generic statement is kept for them.

    Parameters
    ----------
    found : CombinedBracket
        From :func:`combined_bracket`.
    types : PointKinds
        The finite and infinite labels.

    Returns
    -------
    (sympy.Expr, str) or None
        The vector form (zero exactly when the factor is) and the statement.

    Examples
    --------
    >>> found = combined_bracket(BracketPolynomial.parse("[abce] - [abcf] - [abde] + [abdf]"))
    >>> combined_bracket_form(found, PointKinds("bcdef", "a"))[1]
    'the direction a, the direction of line cd and the direction of line ef are parallel to one plane'
    """
    finite: list[tuple[sympy.Expr, str]] = []
    infinite: list[tuple[sympy.Expr, str]] = []
    for slot in found.slots:
        if len(slot.terms) == 1:
            label = slot.terms[0][0]
            (finite if label in types.finite else infinite).append((sympy.Symbol(label), label))
            continue
        if len(slot.terms) != 2 or sorted(c for _, c in slot.terms) != [-1, 1]:
            return None
        kinds = {label in types.finite for label, _ in slot.terms}
        if len(kinds) != 1:
            return None
        (x, cx), (y, _) = slot.terms
        plus, minus = (x, y) if cx == 1 else (y, x)
        vector = VectorDiff(sympy.Symbol(plus), sympy.Symbol(minus))
        name = f"line {x}{y}" if kinds == {True} else f"{plus} − {minus}"
        infinite.append((vector, name))
    return _statement(finite, infinite)


def _statement(
    finite: Sequence[tuple[sympy.Expr, str]], infinite: Sequence[tuple[sympy.Expr, str]]
) -> tuple[sympy.Expr, str] | None:
    """The bracket of finite points and directions in words (``gca.md`` §5.1's table)."""

    def direction(name: str) -> str:
        return f"the direction of {name}" if name.startswith("line ") else f"the direction {name}"

    if len(finite) == 2:
        (p, p_name), (q, q_name) = finite
        along = VectorDiff(q, p)
        names = [f"line {p_name}{q_name}", *(n for _, n in infinite)]
        u, w = (v for v, _ in infinite)
        return VectorDot(VectorCross(along, u), w), _parallel(names, direction)
    if len(finite) == 1:
        u, w, z = (v for v, _ in infinite)
        return VectorDot(VectorCross(u, w), z), _parallel([n for _, n in infinite], direction)
    if len(finite) == 3:
        (p, pn), (q, qn), (r, rn) = finite
        (u, un), = infinite
        form = VectorDot(VectorCross(VectorDiff(q, p), VectorDiff(r, p)), u)
        return form, f"{direction(un)} is parallel to plane {join_labels([pn, qn, rn])}"
    return None


def _parallel(names: Sequence[str], direction: Callable[[str], str]) -> str:
    lines = [n[len("line ") :] for n in names if n.startswith("line ")]
    if len(lines) == len(names):
        return f"the directions of lines {', '.join(lines[:-1])} and {lines[-1]} are parallel to one plane"
    described = [direction(n) for n in names]
    return f"{', '.join(described[:-1])} and {described[-1]} are parallel to one plane"
