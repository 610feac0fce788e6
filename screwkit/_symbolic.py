"""Generic (symbolic) screw-system kernels, private: :mod:`screwkit._backend` delegates here.

A screw whose coordinates hold sympy symbols stands for a whole family of screws. Its systems'
*generic* orders (the orders for all values of the symbols but a proper algebraic subset) are
decided by evaluating the screws at one random point of the symbols' space, exactly:

* **Schwartz–Zippel** (Schwartz, *J. ACM* 27, 1980, Lemma 1; Zippel, *EUROSAM* 1979): a non-zero
  polynomial of total degree ``d`` vanishes at a point drawn uniformly from ``S^n`` with
  probability at most ``d / |S|``. A minor of a matrix of polynomial screws is such a polynomial,
  so the rank seen at a random point is the generic rank, and a non-zero minor there is a generic
  pivot, with probability at least ``1 − d / |S|``. Here ``|S| = 2⁶²`` (:data:`SAMPLE_RANGE`).
* **Exact arithmetic**: the symbols get random rationals; ``sin x`` and ``cos x`` get the rational
  point ``(2t/(1+t²), (1−t²)/(1+t²))`` of the unit circle (``t`` random; after
  :func:`sympy.expand_trig`). Since ``x`` and ``(cos x, sin x)`` are algebraically independent,
  the generic rank over the cylinder ``c² + s² = 1`` is the generic rank in ``x``. The elimination
  then runs on :class:`fractions.Fraction` with no rounding. An entry that does not become rational
  (a square root of a symbol, say) is evaluated with 60 significant digits instead and a pivot is
  then a value above ``1e-40`` relative to its row (:data:`FLOAT_RTOL`); :attr:`GenericPoint.exact`
  says which happened.

Bases are then built **from the chosen generators** (no symbolic rank decision at all) and null
spaces by Cramer's rule on a non-zero minor picked at the point: each vector's entries are
determinants of a small matrix (``adj`` of the pivot block), polynomial when the screws are, then
divided by their common factor (:func:`primitive`).

Examples
--------
>>> import numpy as np, sympy
>>> x = sympy.Symbol("x")
>>> rows = np.array([[1, x, 0, 0, 0, 0], [x, x**2, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]], dtype=object)
>>> independent_rows(rows)
[0, 2]
"""

from __future__ import annotations

import functools
import random
from fractions import Fraction
from typing import Any

import numpy as np

__all__ = [
    "FLOAT_RTOL",
    "MAX_CRAMER",
    "SAMPLE_RANGE",
    "GenericPoint",
    "generic_point",
    "generic_rank",
    "independent_rows",
    "nullspace",
    "primitive",
    "reciprocal_within",
]

Array = np.ndarray

#: Random values are drawn from ``{1, ..., 2⁶²} / 2⁶²``-spaced rationals (Schwartz–Zippel's ``|S|``).
SAMPLE_RANGE = 2**62
#: Relative pivot threshold when an entry could not be evaluated exactly (60-digit arithmetic).
FLOAT_RTOL = 1e-40
#: Largest pivot block solved by Cramer's rule (screw systems need at most 6).
MAX_CRAMER = 6
_DIGITS = 60
_SEED = 20261123
_SWAP = [3, 4, 5, 0, 1, 2]


def _sympy() -> Any:
    import sympy

    return sympy


class GenericPoint:
    """A random point of the symbols' space at which screws are evaluated exactly (see module).

    The point is drawn once per set of symbols from a fixed seed, so answers are reproducible.

    Attributes
    ----------
    values : dict
        ``{symbol: Rational}``, and ``{sin(x): ..., cos(x): ...}`` for the symbols under a
        trigonometric function.
    exact : bool
        False once an entry had to be evaluated in 60-digit floating point.
    """

    def __init__(self, symbols: frozenset[Any]):
        sp = _sympy()
        generator = random.Random(f"{_SEED}:{sorted(map(str, symbols))}")
        self.symbols = symbols
        self.values: dict[Any, Any] = {}
        self.circle: dict[Any, Any] = {}
        for symbol in sorted(symbols, key=str):
            value = sp.Rational(generator.randrange(1, SAMPLE_RANGE), SAMPLE_RANGE)
            if symbol.is_negative or symbol.is_nonpositive:
                value = -value
            self.values[symbol] = value
            t = sp.Rational(generator.randrange(1, SAMPLE_RANGE), SAMPLE_RANGE)
            self.circle[sp.sin(symbol)] = 2 * t / (1 + t**2)
            self.circle[sp.cos(symbol)] = (1 - t**2) / (1 + t**2)
            self.circle[sp.tan(symbol)] = 2 * t / (1 - t**2)
        self.exact = True
        self._cache: dict[Any, Any] = {}

    def value(self, expr: Any) -> Any:
        """The entry at the point: a Fraction, or an mpmath float (``exact`` becomes False)."""
        if isinstance(expr, int | np.integer):
            return Fraction(int(expr))
        if isinstance(expr, Fraction):
            return expr
        if isinstance(expr, float | np.floating):
            return Fraction(repr(float(expr)))
        if expr.is_Rational:
            return Fraction(int(expr.p), int(expr.q))
        if expr in self._cache:
            return self._cache[expr]
        sp = _sympy()
        work = expr
        if work.has(sp.sin, sp.cos, sp.tan):
            work = sp.expand_trig(work).xreplace(self.circle)
        work = work.xreplace(self.values)
        if work.is_Rational:
            result: Any = Fraction(int(work.p), int(work.q))
        else:
            self.exact = False
            result = sp.N(work, _DIGITS)
            if not result.is_real:
                raise ValueError(f"entry {expr} is not real at a generic point")
            import mpmath

            with mpmath.workdps(_DIGITS):
                result = mpmath.mpf(str(result))
        self._cache[expr] = result
        return result

    def matrix(self, rows: Any) -> list[list[Any]]:
        """A 2-D array of expressions evaluated at the point, as nested lists."""
        array = np.asarray(rows, dtype=object)
        numbers = [[self.value(v) for v in row] for row in array.reshape(-1, array.shape[-1])]
        if all(isinstance(v, Fraction) for row in numbers for v in row):
            return numbers
        import mpmath

        with mpmath.workdps(_DIGITS):
            return [
                [mpmath.mpf(v.numerator) / v.denominator if isinstance(v, Fraction) else v for v in row]
                for row in numbers
            ]


@functools.lru_cache(maxsize=32)
def _point(symbols: frozenset[Any]) -> GenericPoint:
    return GenericPoint(symbols)


def generic_point(*arrays: Any) -> GenericPoint:
    """The (cached) random point for the free symbols of some object arrays.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> point = generic_point(np.array([x], dtype=object))
    >>> point.value(x) == point.value(x) and point.exact
    True
    """
    symbols: set[Any] = set()
    for array in arrays:
        for v in np.asarray(array, dtype=object).flat:
            symbols |= getattr(v, "free_symbols", set())
    return _point(frozenset(symbols))


def _is_zero(value: Any, scale: Any) -> bool:
    if isinstance(value, Fraction):
        return value == 0
    return bool(abs(value) <= FLOAT_RTOL * scale)


def _echelon(numbers: list[list[Any]]) -> tuple[list[int], list[int]]:
    """Rows that raise the rank, in order, and a pivot column for each (Gaussian elimination;
    60-digit when the entries are mpmath floats)."""
    if all(isinstance(v, Fraction) for row in numbers for v in row):
        return _echelon_in(numbers)
    import mpmath

    with mpmath.workdps(_DIGITS):
        return _echelon_in(numbers)


def _echelon_in(numbers: list[list[Any]]) -> tuple[list[int], list[int]]:
    reduced: list[tuple[int, list[Any]]] = []  # (pivot column, row with 1 at the pivot)
    rows, columns = [], []
    for index, row in enumerate(numbers):
        work = list(row)
        scale = max((abs(v) for v in work), default=0)
        for column, pivot_row in reduced:
            factor = work[column]
            if factor != 0:
                work = [a - factor * b for a, b in zip(work, pivot_row, strict=True)]
        candidates = [(abs(v), k) for k, v in enumerate(work) if not _is_zero(v, scale)]
        if not candidates:
            continue
        column = max(candidates)[1]
        pivot = work[column]
        reduced.append((column, [v / pivot for v in work]))
        rows.append(index)
        columns.append(column)
    return rows, columns


def independent_rows(rows: Any, point: GenericPoint | None = None) -> list[int]:
    """Indices of the rows (``(k, n)`` object array) that raise the generic rank, in order.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> independent_rows(np.array([[x, 1], [2 * x, 2], [0, 1]], dtype=object))
    [0, 2]
    """
    array = np.asarray(rows, dtype=object)
    if array.size == 0:
        return []
    point = point or generic_point(array)
    return _echelon(point.matrix(array))[0]


def generic_rank(rows: Any, point: GenericPoint | None = None) -> int:
    """The generic rank of a ``(k, n)`` object array (see the module docstring).

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> generic_rank(np.array([[1, x], [1, 1]], dtype=object))
    2
    """
    return len(independent_rows(rows, point))


def primitive(vector: list[Any]) -> list[Any]:
    """A vector of expressions divided by the common factor of its entries (numerators after
    bringing them to one denominator, as polynomials); the projective class is unchanged.

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> primitive([x * y + x, 2 * x, 0])
    [y + 1, 2, 0]
    """
    sp = _sympy()
    pairs = [sp.fraction(sp.together(sp.sympify(v))) for v in vector]
    if not any(num != 0 for num, _ in pairs):
        return [sp.Integer(0)] * len(vector)
    exprs = [*(n for n, _ in pairs), *(d for _, d in pairs)]
    try:
        polys, _ = sp.parallel_poly_from_expr(exprs)
    except sp.PolificationFailed:  # numbers only: polynomials in a dummy generator
        polys, _ = sp.parallel_poly_from_expr(exprs, sp.Dummy("t"))
    numerators, denominators = polys[: len(pairs)], polys[len(pairs) :]
    common = functools.reduce(lambda a, b: a.lcm(b), denominators)
    cleared = [n * common.exquo(d) for n, d in zip(numerators, denominators, strict=True)]
    content = functools.reduce(lambda a, b: a.gcd(b), [c for c in cleared if not c.is_zero])
    out = [c.exquo(content).as_expr() for c in cleared]
    first = next(v for v in out if v != 0)
    if first.could_extract_minus_sign():
        out = [-v for v in out]
    return out


def nullspace(matrix: Any, point: GenericPoint | None = None, *, reduce: bool = True) -> Array:
    """A generic basis of ``{x : matrix @ x = 0}`` (``(m, n)`` object array), as rows.

    Cramer's rule on a pivot block chosen at the random point: for a free column ``f`` the vector
    has ``det(K_RP)`` at ``f`` and ``−det(K_RP with column i replaced by K_Rf)`` at the pivot
    column ``i``. Each vector is then made :func:`primitive` (unless ``reduce`` is False). A pivot
    block larger than :data:`MAX_CRAMER` (a loop-closure matrix) goes to sympy's elimination.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> nullspace(np.array([[1, x, 0]], dtype=object)).tolist()
    [[x, -1, 0], [0, 0, 1]]
    """
    sp = _sympy()
    array = np.asarray(matrix, dtype=object)
    n = array.shape[-1]
    if array.size == 0:
        return np.array(sp.eye(n).tolist(), dtype=object).reshape(n, n)
    point = point or generic_point(array)
    numbers = point.matrix(array)
    rows, _ = _echelon(numbers)
    columns = _echelon([list(c) for c in zip(*[numbers[r] for r in rows], strict=True)])[0]
    if len(rows) > MAX_CRAMER:  # a large system (a loop-closure matrix): sympy's elimination
        vectors = [primitive(list(v)) for v in sp.Matrix(array).nullspace(simplify=True)]
        return np.array(vectors, dtype=object).reshape(len(vectors), n)
    block = sp.Matrix([[array[r, c] for c in columns] for r in rows])
    free = [c for c in range(n) if c not in columns]
    determinant = sp.expand(block.det(method="berkowitz")) if rows else sp.Integer(1)
    vectors = []
    for f in free:
        vector: list[Any] = [sp.Integer(0)] * n
        vector[f] = determinant
        for k, c in enumerate(columns):
            replaced = block.copy()
            replaced[:, k] = sp.Matrix([array[r, f] for r in rows])
            vector[c] = -replaced.det(method="berkowitz")
        vectors.append(primitive(vector) if reduce else vector)
    return np.array(vectors, dtype=object).reshape(len(vectors), n)


def reciprocal_within(basis: Any, others: Any, point: GenericPoint | None = None) -> Array:
    """The screws of ``span(basis)`` reciprocal to every row of ``others`` (generic), as rows.

    With ``basis`` the identity this is the reciprocal system; with ``basis`` a child's wrench
    system and ``others`` its siblings' twists it is the intersection of wrench systems of a
    serial chain (paper 002 Eq. 1), solved on ``order(basis)`` unknowns only.

    Examples
    --------
    >>> import sympy
    >>> z = sympy.Symbol("z")
    >>> line = np.array([[0, 0, 1, z, 0, 0]], dtype=object)          # an axis parallel to z
    >>> reciprocal_within(np.eye(6, dtype=int).astype(object), line).shape
    (5, 6)
    """
    sp = _sympy()
    basis = np.asarray(basis, dtype=object).reshape(-1, 6)
    others = np.asarray(others, dtype=object).reshape(-1, 6)
    if others.shape[0] == 0 or basis.shape[0] == 0:
        return basis.copy()
    products = np.array(
        [[sp.expand(sum(o[_SWAP[j]] * b[j] for j in range(6))) for b in basis] for o in others], dtype=object
    )
    point = point or generic_point(basis, others)
    coefficients = nullspace(products, point, reduce=False)  # the rows are made primitive below
    rows = [
        primitive([sum(c * b[j] for c, b in zip(vector, basis, strict=True)) for j in range(6)])
        for vector in coefficients
    ]
    return np.array(rows, dtype=object).reshape(len(rows), 6)
