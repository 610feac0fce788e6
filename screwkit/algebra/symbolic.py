"""Generic (symbolic) screw-system kernels: :mod:`screwkit.algebra.backend` delegates here.

A screw whose coordinates hold sympy symbols stands for a whole family of screws. Its systems'
*generic* orders (the orders for all values of the symbols but a proper algebraic subset) are
decided by evaluating the screws at one random point of the symbols' space, exactly:

* **Schwartz–Zippel** (Schwartz, *J. ACM* 27, 1980, Lemma 1; Zippel, *EUROSAM* 1979): a non-zero
  polynomial of total degree ``d`` vanishes at a point drawn uniformly from ``S^n`` with
  probability at most ``d / |S|``. A minor of a matrix of polynomial screws is such a polynomial,
  so the rank seen at a random point is the generic rank, and a non-zero minor there is a generic
  pivot, with probability at least ``1 − d / |S|``. Here ``S = {1, ..., 2⁶² − 1}``
  (:data:`SAMPLE_RANGE`): a decision on a minor of degree 100 errs with probability below 10⁻¹⁶.
* **Exact arithmetic**: the symbols get random integers; ``sin x`` and ``cos x`` get the rational
  point ``(2t/(1+t²), (1−t²)/(1+t²))`` of the unit circle (``t`` random). Since ``x`` and
  ``(cos x, sin x)`` are algebraically independent, the generic rank over the cylinder
  ``c² + s² = 1`` is the generic rank in ``x``. The elimination then runs on integers and
  :class:`fractions.Fraction` with no rounding. An entry that does not become rational (a square
  root of a symbol, say) is evaluated with 60 significant digits instead and a pivot is then a
  value above ``1e-40`` relative to its row (:data:`FLOAT_RTOL`); :attr:`GenericRows.exact` says
  which happened.

The expressions are held as sparse polynomials (:class:`sympy.polys.rings.PolyElement`, integer
coefficients) in the entries' generators (the symbols, and any other atom such as ``sin x``), each
paired with its exact **value at the point** (:class:`GenericRows`). Every rank and pivot decision
reads the values only: no polynomial is expanded, simplified or evaluated to decide. Bases are
built from the chosen generators (:mod:`screwkit.algebra.symbolic_bases`: ranks, null spaces and
reciprocal systems by Cramer's rule at the point). Only the returned bases are turned back into
sympy expressions.

Examples
--------
>>> import numpy as np, sympy
>>> x = sympy.Symbol("x")
>>> rows = np.array([[1, x, 0, 0, 0, 0], [x, x**2, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]], dtype=object)
>>> GenericRows.from_exprs(rows, generic_point(rows)).independent()
[0, 2]
"""

from __future__ import annotations

import contextlib
import functools
import math
import random
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError

__all__ = [
    "FLOAT_RTOL",
    "SAMPLE_RANGE",
    "GenericPoint",
    "GenericRows",
    "generic_point",
    "is_zero",
]

Array = np.ndarray

#: Random values are drawn from ``{1, ..., 2⁶² − 1}`` (Schwartz–Zippel's ``S``).
SAMPLE_RANGE = 2**62
#: Relative pivot threshold when an entry could not be evaluated exactly (60-digit arithmetic).
FLOAT_RTOL = 1e-40
_DIGITS = 60
_SEED = 20261123


def _sympy() -> Any:
    import sympy

    return sympy


class GenericPoint:
    """A random point of the symbols' space at which screws are evaluated exactly (see module).

    The point is drawn once per set of symbols from a fixed seed, so answers are reproducible.

    Attributes
    ----------
    values : dict
        ``{symbol: Integer}`` (negated for a symbol declared negative).
    circle : dict
        ``{sin(x): ..., cos(x): ..., tan(x): ...}``, a rational point of the unit circle for each
        symbol.
    """

    def __init__(self, symbols: frozenset[Any]):
        sp = _sympy()
        generator = random.Random(f"{_SEED}:{sorted(map(str, symbols))}")
        self.symbols = symbols
        self.values: dict[Any, Any] = {}
        self.circle: dict[Any, Any] = {}
        for symbol in sorted(symbols, key=str):
            value = sp.Integer(generator.randrange(1, SAMPLE_RANGE))
            if symbol.is_negative or symbol.is_nonpositive:
                value = -value
            self.values[symbol] = value
            t = sp.Rational(generator.randrange(1, SAMPLE_RANGE), SAMPLE_RANGE)
            self.circle[sp.sin(symbol)] = 2 * t / (1 + t**2)
            self.circle[sp.cos(symbol)] = (1 - t**2) / (1 + t**2)
            self.circle[sp.tan(symbol)] = 2 * t / (1 - t**2)
        self._cache: dict[Any, Any] = {}

    def value(self, expr: Any, *, remember: bool = True) -> Any:
        """An expression at the point: an int or a Fraction, or a 60-digit mpmath float when it is
        not rational there. ``remember=False`` keeps it out of the point's cache (one-off
        decisions, e.g. :func:`screwkit.algebra.zero_tests.is_exactly_zero`, would otherwise grow it without
        bound).

        Parameters
        ----------
        expr : sympy.Expr or int
            The expression.
        remember : bool, default True
            Whether to keep the value in the point's cache.

        Returns
        -------
        int, fractions.Fraction or mpmath.mpf

        Examples
        --------
        >>> import sympy
        >>> x = sympy.Symbol("x")
        >>> point = generic_point(np.array([x], dtype=object))
        >>> point.value(sympy.sin(x) ** 2 + sympy.cos(x) ** 2), point.value(sympy.Rational(1, 2))
        (1, Fraction(1, 2))
        """
        if isinstance(expr, int | np.integer) or expr.is_Integer:
            return int(expr)
        if expr.is_Rational:
            return Fraction(int(expr.p), int(expr.q))
        if expr in self._cache:
            return self._cache[expr]
        sp = _sympy()
        work = expr
        if work.has(sp.sin, sp.cos, sp.tan):
            work = sp.expand_trig(work).xreplace(self.circle)
        work = work.xreplace(self.values)
        if work.is_Integer:
            result: Any = int(work)
        elif work.is_Rational:
            result = Fraction(int(work.p), int(work.q))
        else:
            result = sp.N(work, _DIGITS)
            if not result.is_real:
                raise ScrewkitValueError(
                    f"Expected `rows` to hold screw coordinates that are real for real symbols, got {expr} "
                    "(not real at a generic point)."
                )
            import mpmath

            with mpmath.workdps(_DIGITS):
                result = mpmath.mpf(str(result))
        if remember:
            self._cache[expr] = result
        return result


@functools.lru_cache(maxsize=32)
def _point(symbols: frozenset[Any]) -> GenericPoint:
    return GenericPoint(symbols)


def generic_point(*arrays: Any) -> GenericPoint:
    """The (cached) random point for the free symbols of some object arrays.

    Parameters
    ----------
    *arrays : array_like
        Object arrays of sympy expressions (or numbers).

    Returns
    -------
    GenericPoint

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> point = generic_point(np.array([x], dtype=object))
    >>> point.value(x) == point.value(x) and isinstance(point.value(x), int)
    True
    """
    symbols: set[Any] = set()
    for array in arrays:
        for v in np.asarray(array, dtype=object).flat:
            symbols |= getattr(v, "free_symbols", set())
    return _point(frozenset(symbols))


def _evaluate(poly: Any, values: Sequence[Any]) -> Any:
    """A polynomial (integer coefficients) at the generators' values."""
    total: Any = 0
    for monomial, coefficient in poly.items():
        term: Any = int(coefficient)
        for value, exponent in zip(values, monomial, strict=True):
            if exponent:
                term *= value**exponent
        total += term
    return total


class GenericRows:
    """Rows of polynomials in one ring, with their values at a generic point (see the module).

    Parameters
    ----------
    polys : list of list of PolyElement
    values : list of list
        ``values[i][j]`` is ``polys[i][j]`` at the point (int, Fraction or mpmath float).
    width : int
        The number of columns (kept for zero rows).
    ring : sympy.polys.rings.PolyRing
        The polynomials' ring (integer coefficients).
    exact : bool
        True when every generator is rational at the point (else the values are 60-digit floats).

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> rows = np.array([[x, 1], [2 * x, 2]], dtype=object)
    >>> generic = GenericRows.from_exprs(rows, generic_point(rows))
    >>> len(generic), generic.exact, generic.independent()
    (2, True, [0])
    """

    __slots__ = ("_exprs", "exact", "polys", "ring", "values", "width")

    def __init__(self, polys: list[list[Any]], values: list[list[Any]], width: int, ring: Any, exact: bool):
        self.polys, self.values, self.width, self.ring, self.exact = polys, values, width, ring, exact
        self._exprs: Array | None = None

    @classmethod
    def from_exprs(cls, array: Any, point: GenericPoint) -> GenericRows:
        """A ``(k, n)`` object array of expressions as polynomials with integer coefficients (each
        row scaled by the common denominator of its coefficients: the span is unchanged).

        Parameters
        ----------
        array : array_like, shape (k, n)
            Sympy expressions (or numbers).
        point : GenericPoint
            The point of evaluation.

        Returns
        -------
        GenericRows

        Examples
        --------
        >>> import sympy
        >>> x = sympy.Symbol("x")
        >>> rows = np.array([[x / 2, 1], [0, x]], dtype=object)
        >>> GenericRows.from_exprs(rows, generic_point(rows)).exprs().tolist()
        [[x, 2], [0, x]]
        """
        sp = _sympy()
        from sympy.polys.domains import QQ, ZZ
        from sympy.polys.rings import sring

        array = np.asarray(array, dtype=object)
        width = array.shape[-1]
        array = array.reshape(-1, width)
        _, flat = sring([sp.sympify(v) for v in array.flat] or [sp.Integer(0)], domain=QQ)
        ring = flat[0].ring.clone(domain=ZZ)
        polys = []
        for i in range(array.shape[0]):
            row = flat[i * width : (i + 1) * width]
            denominator = math.lcm(*(int(c.denominator) for p in row for c in p.values()))
            polys.append(
                [
                    ring.from_dict(
                        {m: int(c.numerator) * (denominator // int(c.denominator)) for m, c in p.items()}
                    )
                    for p in row
                ]
            )
        generators = _generator_values(ring, point)
        exact = all(isinstance(g, int | Fraction) for g in generators)
        with _precision(exact):
            values = [[_evaluate(p, generators) for p in row] for row in polys]
        return cls(polys, values, width, ring, exact)

    def __len__(self) -> int:
        return len(self.polys)

    def take(self, indices: Sequence[int]) -> GenericRows:
        """The rows at some indices.

        Parameters
        ----------
        indices : sequence of int
            The rows kept, in order.

        Returns
        -------
        GenericRows

        Examples
        --------
        >>> import sympy
        >>> x = sympy.Symbol("x")
        >>> rows = np.array([[x, 1], [1, x]], dtype=object)
        >>> GenericRows.from_exprs(rows, generic_point(rows)).take([1]).exprs().tolist()
        [[1, x]]
        """
        return self._like([self.polys[i] for i in indices], [self.values[i] for i in indices])

    def scaled(self, factor: int) -> GenericRows:
        """Every row times an integer (60-digit values multiplied at 60 digits).

        Parameters
        ----------
        factor : int
            The multiplier.

        Returns
        -------
        GenericRows

        Examples
        --------
        >>> import sympy
        >>> x = sympy.Symbol("x")
        >>> rows = np.array([[x, 1]], dtype=object)
        >>> GenericRows.from_exprs(rows, generic_point(rows)).scaled(3).exprs().tolist()
        [[3*x, 3]]
        """
        with self.precision():
            values = [[factor * v for v in row] for row in self.values]
        return self._like([[factor * p for p in row] for row in self.polys], values)

    def stack(self, *others: GenericRows) -> GenericRows:
        """These rows followed by the others' (one ring).

        Parameters
        ----------
        *others : GenericRows
            Rows of the same ring and width.

        Returns
        -------
        GenericRows
        """
        polys, values = list(self.polys), list(self.values)
        for other in others:
            polys += other.polys
            values += other.values
        return self._like(polys, values)

    def identity(self) -> GenericRows:
        """The unit rows of this width, in this ring.

        Returns
        -------
        GenericRows
            ``width`` unit rows.
        """
        ring, n = self.ring, self.width
        return self._like(
            [[ring.one if i == j else ring.zero for j in range(n)] for i in range(n)],
            [[1 if i == j else 0 for j in range(n)] for i in range(n)],
        )

    def independent(self) -> list[int]:
        """Indices of the rows that raise the generic rank, in order (decided at the point, in the
        values' arithmetic).

        Returns
        -------
        list of int

        Examples
        --------
        >>> import sympy
        >>> x = sympy.Symbol("x")
        >>> rows = np.array([[x, 1], [2 * x, 2], [1, x]], dtype=object)
        >>> GenericRows.from_exprs(rows, generic_point(rows)).independent()
        [0, 2]
        """
        if not self.polys:
            return []
        with self.precision():
            return _echelon(self.values)[0]

    def precision(self) -> contextlib.AbstractContextManager[Any]:
        """The arithmetic context of the values: 60 digits unless they are exact.

        Returns
        -------
        contextlib.AbstractContextManager
            A null context, or :func:`mpmath.workdps` at 60 digits.
        """
        return _precision(self.exact)

    def _like(self, polys: list[list[Any]], values: list[list[Any]]) -> GenericRows:
        return GenericRows(polys, values, self.width, self.ring, self.exact)

    def exprs(self) -> Array:
        """The rows as a ``(k, n)`` object array of sympy expressions (converted once).

        Returns
        -------
        numpy.ndarray, shape (k, n)
            Object array of sympy expressions.
        """
        if self._exprs is None:
            out = np.empty((len(self.polys), self.width), dtype=object)
            for i, row in enumerate(self.polys):
                for j, p in enumerate(row):
                    out[i, j] = p.as_expr()
            self._exprs = out
        return self._exprs


def _precision(exact: bool) -> contextlib.AbstractContextManager[Any]:
    if exact:
        return contextlib.nullcontext()
    import mpmath

    return mpmath.workdps(_DIGITS)


def is_zero(value: Any, scale: Any) -> bool:
    """Whether a value at the generic point is zero: exactly for an int or Fraction, else within
    :data:`FLOAT_RTOL` of ``scale`` (60-digit values carry round-off).

    Parameters
    ----------
    value : int, Fraction or mpmath.mpf
        The value.
    scale : int, Fraction or mpmath.mpf
        The size it is compared with (its row's largest entry).

    Returns
    -------
    bool

    Examples
    --------
    >>> is_zero(Fraction(0), 1), is_zero(1e-50, 1.0), is_zero(1e-30, 1.0)
    (True, True, False)
    """
    if isinstance(value, int | Fraction):
        return value == 0
    return bool(abs(value) <= FLOAT_RTOL * scale)


def _echelon(numbers: list[list[Any]]) -> tuple[list[int], list[int]]:
    """Rows that raise the rank, in order, and a pivot column for each (Gaussian elimination,
    exact on integers and fractions; in the caller's precision when the entries are mpmath floats)."""
    if all(isinstance(v, int | Fraction) for row in numbers for v in row):
        numbers = [[Fraction(v) for v in row] for row in numbers]
    reduced: list[tuple[int, list[Any]]] = []  # (pivot column, row with 1 at the pivot)
    rows, columns = [], []
    for index, row in enumerate(numbers):
        work = list(row)
        scale = max((abs(v) for v in work), default=0)
        for column, pivot_row in reduced:
            factor = work[column]
            if factor != 0:
                work = [a - factor * b for a, b in zip(work, pivot_row, strict=True)]
        candidates = [(abs(v), k) for k, v in enumerate(work) if not is_zero(v, scale)]
        if not candidates:
            continue
        column = max(candidates)[1]
        pivot = work[column]
        reduced.append((column, [v / pivot for v in work]))
        rows.append(index)
        columns.append(column)
    return rows, columns


def _generator_values(ring: Any, point: GenericPoint) -> list[Any]:
    values = [point.value(g) for g in ring.symbols]
    if all(isinstance(v, int | Fraction) for v in values):
        return values
    import mpmath

    with mpmath.workdps(_DIGITS):
        return [
            mpmath.mpf(v.numerator) / v.denominator if isinstance(v, Fraction) else mpmath.mpf(v)
            for v in values
        ]
