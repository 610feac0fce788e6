"""Bracket algebra: :class:`Bracket`, :class:`BracketMonomial`, :class:`BracketPolynomial` (exact
rational coefficients, canonical forms) and their evaluation on points, batched floats or exact sympy
(the bracket itself is :func:`screwkit.algebra.projective.bracket`).

Examples
--------
>>> Bracket("bacd") == -Bracket("abcd")
True
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

from ..algebra import backend as B
from ..algebra import projective as P
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .labelled_points import point_arrays, scalar_result
from .notation import (
    check_label,
    exact_coefficient,
    format_bracket,
    format_sum,
    is_exact_scalar,
    parse_terms,
    renamed_label,
    sort_sign,
)

if TYPE_CHECKING:
    import sympy

__all__ = [
    "Bracket",
    "BracketMonomial",
    "BracketPolynomial",
    "as_labels",
    "as_monomial",
]


def as_labels(value: Any, name: str, count: int | None = None) -> tuple[str, ...]:
    """Labels from ``"abcd"`` (single letters), ``"r1 r2 r3 r4"`` or a sequence of strings.

    Parameters
    ----------
    value : str, sequence of str or Bracket
    name : str
        The argument's name, for the messages.
    count : int, optional
        The number of labels required.

    Returns
    -------
    tuple of str

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError
        For a value that is not labels, or not ``count`` of them.

    Examples
    --------
    >>> as_labels("gikj", "labels"), as_labels("r1 r2", "line", 2)
    (('g', 'i', 'k', 'j'), ('r1', 'r2'))
    """
    if isinstance(value, Bracket):
        items: list[Any] = list(value.labels)
    elif isinstance(value, str):
        items = value.split() if any(ch.isspace() for ch in value) else list(value)
    elif isinstance(value, Sequence):
        items = list(value)
    else:
        raise ScrewkitTypeError(
            f"Expected `{name}` to be a string or a sequence of labels, "
            f"got {type(value).__name__} {value!r}."
        )
    labels = tuple(check_label(item, f"{name}[{i}]") for i, item in enumerate(items))
    if count is not None and len(labels) != count:
        raise ScrewkitValueError(
            f"Expected `{name}` to hold {count} labels, got {len(labels)}: {labels}."
        )
    return labels


@functools.lru_cache(maxsize=1 << 16)
def _sorted(labels: tuple[str, ...]) -> tuple[str, ...]:
    """A bracket's labels sorted (cached with :func:`_bracket_labels`: brackets recur while simplifying)."""
    return tuple(sorted(labels))


@functools.lru_cache(maxsize=1 << 16)
def _bracket_labels(value: str | tuple[str, ...]) -> tuple[str, ...]:
    """Validated labels of a bracket (cached: brackets are built very often while simplifying)."""
    return as_labels(value, "labels", 4)


def as_monomial(value: Any) -> BracketMonomial | None:
    """A bracket, a monomial or an exact number as a :class:`BracketMonomial`.

    Parameters
    ----------
    value : object

    Returns
    -------
    BracketMonomial or None
        None for any other value.

    Examples
    --------
    >>> print(as_monomial(Bracket("abcd"))), as_monomial(0.5)
    [abcd]
    (None, None)
    """
    if isinstance(value, BracketMonomial):
        return value
    if isinstance(value, Bracket):
        return BracketMonomial((value,))
    if is_exact_scalar(value):
        return BracketMonomial((), exact_coefficient(value, "coefficient"))
    return None


def _as_polynomial(value: Any) -> BracketPolynomial | None:
    if isinstance(value, BracketPolynomial):
        return value
    monomial = as_monomial(value)
    return None if monomial is None else BracketPolynomial((monomial,))


def _operand(value: Any) -> BracketPolynomial | None:
    """The other operand of + - * as a polynomial; floats are refused (coefficients are exact)."""
    if isinstance(value, float | np.floating):
        exact_coefficient(value, "coefficient")  # raises ScrewkitTypeError naming the float
    return _as_polynomial(value)


class _Algebra:
    """Ring operations, equality and hashing shared by brackets, monomials and polynomials.

    Equality compares canonical forms (sorted labels, signed coefficients, like terms combined),
    so a bracket, the monomial 1·bracket and the one-term polynomial are equal and hash alike.
    """

    __slots__ = ()

    def _polynomial(self) -> BracketPolynomial:
        polynomial = _as_polynomial(self)
        assert polynomial is not None
        return polynomial

    def __eq__(self, other: object) -> bool:
        right = None if isinstance(other, float | np.floating) else _as_polynomial(other)
        if right is None:
            return NotImplemented
        return self._polynomial()._canonical() == right._canonical()

    def __hash__(self) -> int:
        return hash(frozenset(self._polynomial()._canonical().items()))

    def __add__(self, other: Any) -> BracketPolynomial:
        right = _operand(other)
        if right is None:
            return NotImplemented
        return BracketPolynomial(self._polynomial().terms + right.terms)

    __radd__ = __add__

    def __neg__(self) -> Any:
        return self * -1

    def __sub__(self, other: Any) -> BracketPolynomial:
        right = _operand(other)
        if right is None:
            return NotImplemented
        return self + right * -1

    def __rsub__(self, other: Any) -> BracketPolynomial:
        left = _operand(other)
        if left is None:
            return NotImplemented
        return left + self * -1

    def __mul__(self, other: Any) -> Any:
        right = _operand(other)
        if right is None:
            return NotImplemented
        left_monomial, right_monomial = as_monomial(self), as_monomial(other)
        if left_monomial is not None and right_monomial is not None:
            return left_monomial._times(right_monomial)
        return BracketPolynomial(a._times(b) for a in self._polynomial().terms for b in right.terms)

    __rmul__ = __mul__

    def to_sympy(self, points: Mapping[str, Any]) -> sympy.Expr:
        """Exact value as one sympy expression (floats become rationals), unexpanded.

        Parameters
        ----------
        points : mapping of str to array_like, shape (4,)
            Single points (numbers or sympy expressions), by label.

        Returns
        -------
        sympy.Expr

        Examples
        --------
        >>> import sympy
        >>> t = sympy.Symbol("t")
        >>> pts = {"a": [0, 0, 0, 1], "b": [t, 0, 0, 1], "c": [0, 1, 0, 1], "d": [0, 0, 1, 1]}
        >>> sympy.expand(Bracket("abcd").to_sympy(pts))
        -t
        """
        polynomial = self._polynomial()
        arrays = point_arrays(points, polynomial.labels, symbolic=True)
        if any(a.ndim > 1 for a in arrays.values()):
            raise ScrewkitValueError(
                "Expected `points` to be single points of shape (4,) for to_sympy, got batches "
                f"{ {label: a.shape for label, a in arrays.items()} }."
            )
        return B.sympy_module().Add(*polynomial._term_values(arrays))


@dataclass(frozen=True, eq=False, slots=True, init=False)
class Bracket(_Algebra):
    """The bracket ``[pqrs]`` of four labelled projective points (``gca.md`` §1, §5.1).

    Its value is the determinant of the 4×4 matrix whose rows are the points ``(x, y, z, w)``.
    The labels are kept in the order given (for printing); the *canonical form* is the sorted labels
    and the sign of the sorting permutation, and equality compares canonical forms, so
    ``[bacd] == -[abcd]``. A repeated label makes the bracket structurally zero.

    Parameters
    ----------
    labels : str or sequence of str
        Four labels: ``"gikj"``, ``"r1 r2 r3 r4"`` or ``("g", "i", "k", "j")``.

    Examples
    --------
    >>> b = Bracket("gikj")
    >>> str(b), b.sorted_labels, b.sign
    ('[gikj]', ('g', 'i', 'j', 'k'), -1)
    >>> Bracket("aabc").is_structurally_zero
    True
    >>> points = {"g": [0, 0, 0, 1], "i": [1, 0, 0, 0], "k": [0, 1, 0, 0], "j": [0, 0, 1, 0]}
    >>> float(b.evaluate(points))  # [p u v w] = -det(u, v, w), gca.md §5.1
    -1.0
    """

    labels: tuple[str, ...]

    def __init__(self, labels: str | Sequence[str]) -> None:
        hashable = isinstance(labels, str | tuple)
        checked = _bracket_labels(labels) if hashable else as_labels(labels, "labels", 4)
        object.__setattr__(self, "labels", checked)

    @property
    def sign(self) -> int:
        """Sign of the permutation sorting the labels (0 if a label repeats)."""
        return sort_sign(self.labels)

    @property
    def sorted_labels(self) -> tuple[str, ...]:
        """The labels in sorted order (the canonical bracket is ``sign * [sorted_labels]``)."""
        return _sorted(self.labels)

    @property
    def is_structurally_zero(self) -> bool:
        """True if a label repeats: the bracket vanishes whatever the points."""
        return self.sign == 0

    def __str__(self) -> str:
        return format_bracket(self.labels, (0,) * 4, latex=False)

    def to_latex(self) -> str:
        """LaTeX of the bracket, e.g. ``[gikj]``.

        Returns
        -------
        str

        Examples
        --------
        >>> Bracket("r1 r2 r3 r4").to_latex()
        '[r1\\\\,r2\\\\,r3\\\\,r4]'
        """
        return format_bracket(self.labels, (0,) * 4, latex=True)

    def relabel(self, mapping: Mapping[str, str]) -> Bracket:
        """Rename labels simultaneously; labels missing from ``mapping`` stay.

        Parameters
        ----------
        mapping : mapping of str to str
            Old label -> new label (checked); labels missing from it stay.

        Returns
        -------
        Bracket

        Examples
        --------
        >>> str(Bracket("abcd").relabel({"a": "b", "b": "a"}))
        '[bacd]'
        """
        return Bracket(tuple(renamed_label(label, mapping) for label in self.labels))

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """The determinant, batched over the points' leading axes (or exact if they are sympy).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)
            The points by label; batches broadcast against each other.

        Returns
        -------
        float, numpy.ndarray or sympy.Expr
        """
        arrays = point_arrays(points, self.labels)
        return scalar_result(P.bracket_unchecked(*(arrays[label] for label in self.labels)))



@dataclass(frozen=True, eq=False, slots=True, init=False)
class BracketMonomial(_Algebra):
    """A product ``coefficient × [..][..]…`` of brackets with an exact rational coefficient.

    Parameters
    ----------
    brackets : iterable of Bracket or label strings
        The factors, kept in the order given for printing.
    coefficient : int or fraction, default 1

    Examples
    --------
    >>> m = BracketMonomial(["abdf", "cghj"], -2)
    >>> str(m), m == -2 * Bracket("cghj") * Bracket("abdf")
    ('-2 [abdf][cghj]', True)
    """

    coefficient: Fraction
    brackets: tuple[Bracket, ...]
    _key: tuple[Fraction, tuple[tuple[str, ...], ...]] = field(repr=False)

    def __init__(
        self, brackets: Iterable[Bracket | str | Sequence[str]] = (), coefficient: Any = 1
    ) -> None:
        factors = tuple(b if isinstance(b, Bracket) else Bracket(b) for b in brackets)
        value = exact_coefficient(coefficient, "coefficient")
        object.__setattr__(self, "coefficient", value)
        object.__setattr__(self, "brackets", factors)
        sign = math.prod(b.sign for b in factors)  # -1, 0 or 1: no rational product needed
        canonical = value if sign == 1 else -value if sign == -1 else Fraction(0)
        keys = tuple(sorted(b.sorted_labels for b in factors)) if canonical else ()
        object.__setattr__(self, "_key", (canonical, keys))

    @property
    def canonical(self) -> tuple[Fraction, tuple[tuple[str, ...], ...]]:
        """``(signed coefficient, sorted tuple of sorted bracket labels)``; ``(0, ())`` if zero."""
        return self._key

    @property
    def labels(self) -> tuple[str, ...]:
        """The distinct labels, sorted."""
        return tuple(sorted({label for b in self.brackets for label in b.labels}))

    def _times(self, other: BracketMonomial) -> BracketMonomial:
        return BracketMonomial(self.brackets + other.brackets, self.coefficient * other.coefficient)

    def __str__(self) -> str:
        return format_sum([(self.coefficient, self._body(latex=False))], latex=False)

    def _body(self, *, latex: bool) -> str:
        return "".join(format_bracket(b.labels, (0,) * 4, latex=latex) for b in self.brackets)

    def to_latex(self) -> str:
        """LaTeX, e.g. ``-2 [abdf][cghj]``.

        Returns
        -------
        str
        """
        return format_sum([(self.coefficient, self._body(latex=True))], latex=True)

    def relabel(self, mapping: Mapping[str, str]) -> BracketMonomial:
        """Rename labels simultaneously (see :meth:`Bracket.relabel`).

        Parameters
        ----------
        mapping : mapping of str to str
            Old label -> new label (checked); labels missing from it stay.

        Returns
        -------
        BracketMonomial
        """
        return BracketMonomial((b.relabel(mapping) for b in self.brackets), self.coefficient)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (see :meth:`Bracket.evaluate`).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)
            The points by label; batches broadcast against each other.

        Returns
        -------
        float, numpy.ndarray or sympy.Expr
        """
        return BracketPolynomial((self,)).evaluate(points)


@dataclass(frozen=True, eq=False, slots=True, init=False)
class BracketPolynomial(_Algebra):
    """A sum of bracket monomials in canonical form: like terms combined, zero terms dropped.

    Each monomial keeps the letter order in which it first appeared (for printing); equality and
    hashing use canonical forms. Supports ``+``, ``-`` and ``*`` with brackets, monomials,
    polynomials and integers or fractions.

    Parameters
    ----------
    terms : iterable of BracketMonomial or Bracket

    Examples
    --------
    >>> p = BracketPolynomial.parse("[abdf][cghj] - [abdh][cgfj] + [bacd][efgh] + [abcd][hgfe]")
    >>> str(p)
    '[abdf][cghj] - [abdh][cgfj]'
    >>> len(p), p.labels
    (2, ('a', 'b', 'c', 'd', 'f', 'g', 'h', 'j'))
    """

    terms: tuple[BracketMonomial, ...]

    def __init__(self, terms: Iterable[BracketMonomial | Bracket] = ()) -> None:
        merged: dict[tuple[tuple[str, ...], ...], list[Any]] = {}
        for term in terms:
            monomial = as_monomial(term)
            if monomial is None:
                raise ScrewkitTypeError(
                    f"Expected `terms` to hold bracket monomials, got {type(term).__name__}."
                )
            value, keys = monomial.canonical
            if value == 0:
                continue
            if keys in merged:
                merged[keys][1] += value
            else:
                merged[keys] = [monomial, value]
        kept = []
        for display, total in merged.values():
            if total != 0:
                signs = math.prod(b.sign for b in display.brackets)
                kept.append(BracketMonomial(display.brackets, total * signs))
        object.__setattr__(self, "terms", tuple(kept))

    @classmethod
    def parse(cls, text: str) -> BracketPolynomial:
        """Read ``"[abdf][cghj] - [abdh][cgfj]"`` (integer or ``p/q`` coefficients, no dots).

        Parameters
        ----------
        text : str

        Returns
        -------
        BracketPolynomial

        Raises
        ------
        ScrewkitValueError
            For text that is not a sum of bracket monomials, or that has dots.

        Examples
        --------
        >>> BracketPolynomial.parse("1/2 [abcd] - 3[abce][dfgh]")
        BracketPolynomial('1/2 [abcd] - 3 [abce][dfgh]')
        """
        monomials = []
        for coefficient, brackets in parse_terms(text):
            if any(any(kinds) for _, kinds in brackets):
                raise ScrewkitValueError(
                    f"Expected `text` without dots (use DottedSum.parse for dotted brackets), "
                    f"got {text!r}."
                )
            monomials.append(BracketMonomial((labels for labels, _ in brackets), coefficient))
        return cls(monomials)

    def __len__(self) -> int:
        return len(self.terms)

    def __iter__(self) -> Iterator[BracketMonomial]:
        return iter(self.terms)

    def _canonical(self) -> dict[tuple[tuple[str, ...], ...], Fraction]:
        return {keys: value for value, keys in (m.canonical for m in self.terms)}

    def __repr__(self) -> str:
        return f"BracketPolynomial({str(self)!r})"

    def __str__(self) -> str:
        return format_sum([(m.coefficient, m._body(latex=False)) for m in self.terms], latex=False)

    def to_latex(self) -> str:
        """LaTeX of the sum.

        Returns
        -------
        str

        Examples
        --------
        >>> BracketPolynomial.parse("[abdf][cghj] - 1/2 [abdh][cgfj]").to_latex()
        '[abdf][cghj] - \\\\tfrac{1}{2} [abdh][cgfj]'
        """
        return format_sum([(m.coefficient, m._body(latex=True)) for m in self.terms], latex=True)

    @property
    def labels(self) -> tuple[str, ...]:
        """The distinct labels, sorted."""
        return tuple(sorted({label for m in self.terms for label in m.labels}))

    def relabel(self, mapping: Mapping[str, str]) -> BracketPolynomial:
        """Rename labels simultaneously; monomials that become equal are combined.

        Parameters
        ----------
        mapping : mapping of str to str
            Old label -> new label (checked); labels missing from it stay.

        Returns
        -------
        BracketPolynomial

        Examples
        --------
        >>> str(BracketPolynomial.parse("[abcd] + [abce]").relabel({"e": "d"}))
        '2 [abcd]'
        """
        return BracketPolynomial(m.relabel(mapping) for m in self.terms)

    def _term_values(self, arrays: Mapping[str, np.ndarray]) -> list[Any]:
        """Value of each canonical term (signed coefficient × sorted brackets), brackets cached."""
        cache: dict[tuple[str, ...], Any] = {}
        symbolic = B.is_symbolic(*arrays.values())
        values = []
        for monomial in self.terms:
            coefficient, keys = monomial.canonical
            value: Any = B.from_fraction(coefficient, symbolic=symbolic)
            for key in keys:
                if key not in cache:
                    cache[key] = P.bracket_unchecked(*(arrays[label] for label in key))
                value = value * cache[key]
            values.append(value)
        return values

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points, batched over leading axes (exact if the points are sympy).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)

        Returns
        -------
        float, numpy.ndarray or sympy.Expr

        Examples
        --------
        >>> p = BracketPolynomial.parse("[abcd] - 2[abdc]")  # = 3 [abcd]
        >>> pts = {"a": np.eye(4)[0], "b": np.eye(4)[1], "c": np.eye(4)[2], "d": np.eye(4)[3]}
        >>> float(p.evaluate(pts))
        3.0
        """
        arrays = point_arrays(points, self.labels)
        return scalar_result(sum(self._term_values(arrays), start=_zero(arrays)))

def _zero(arrays: Mapping[str, np.ndarray]) -> Any:
    """The additive zero matching the branch (sympy zero or a float 0)."""
    return B.from_fraction(Fraction(0), symbolic=B.is_symbolic(*arrays.values()))
