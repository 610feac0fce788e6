"""Generic bases of symbolic screws: ranks, null spaces and reciprocal systems.

The generic rank of a matrix of polynomial screws is the number of rows that raise the rank at the
generic point (:mod:`screwkit.algebra.symbolic`: Schwartz–Zippel, exact arithmetic). Bases are built
**from the chosen generators**, null spaces by Cramer's rule on the non-zero minor picked at the
point: each vector's entries are maximal minors of the pivot rows
(:func:`screwkit.algebra.cramer.signed_minors`), polynomial when the screws are, then divided by
their common factor (:func:`screwkit.algebra.cramer.primitive`). :mod:`screwkit.algebra.ranks`
delegates its symbolic branch here; the generic analysis builds its systems with
:func:`reciprocal_within`.

Examples
--------
>>> import numpy as np, sympy
>>> x = sympy.Symbol("x")
>>> rows = np.array([[1, x, 0, 0, 0, 0], [x, x**2, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]], dtype=object)
>>> independent_rows(rows), generic_rank(rows)
([0, 2], 2)
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

from .cramer import primitive, quotient, signed_minors
from .symbolic import (
    GenericPoint,
    GenericRows,
    _echelon,
    _evaluate,
    _generator_values,
    _precision,
    _sympy,
    generic_point,
)

__all__ = ["MAX_CRAMER", "generic_rank", "independent_rows", "nullspace", "reciprocal_within"]

Array = np.ndarray

#: Largest pivot block solved by Cramer's rule (screw systems need at most 6).
MAX_CRAMER = 6
_SWAP = [3, 4, 5, 0, 1, 2]


def independent_rows(rows: Any, point: GenericPoint | None = None) -> list[int]:
    """Indices of the rows (``(k, n)`` object array) that raise the generic rank, in order.

    Parameters
    ----------
    rows : array_like, shape (k, n)
        Sympy expressions (or numbers).
    point : GenericPoint, optional
        The point of evaluation (default: :func:`generic_point` of the rows).

    Returns
    -------
    list of int

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
    generic = GenericRows.from_exprs(array, point)
    with generic.precision():
        return generic.independent()


def generic_rank(rows: Any, point: GenericPoint | None = None) -> int:
    """The generic rank of a ``(k, n)`` object array (see the module docstring).

    Parameters
    ----------
    rows : array_like, shape (k, n)
        Sympy expressions (or numbers).
    point : GenericPoint, optional
        The point of evaluation (default: :func:`generic_point` of the rows).

    Returns
    -------
    int

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> generic_rank(np.array([[1, x], [1, 1]], dtype=object))
    2
    """
    return len(independent_rows(rows, point))


def _kernel(
    polys: list[list[Any]], values: list[list[Any]], width: int, zero: Any
) -> tuple[list[list[Any]], list[list[Any]]]:
    """A generic basis of ``{x : matrix @ x = 0}`` (polynomials and their values), unreduced."""
    rows, _ = _echelon(values)
    columns = _echelon([list(c) for c in zip(*[values[r] for r in rows], strict=True)])[0] if rows else []
    free = [c for c in range(width) if c not in columns]
    block_polys = [polys[r] for r in rows]
    block_values = [values[r] for r in rows]
    vectors, vector_values = [], []
    for f in free:
        chosen = sorted([*columns, f])
        vector, vector_value = [zero] * width, [0] * width
        polys_minors = signed_minors(block_polys, chosen, zero + 1)
        for c, p, v in zip(chosen, polys_minors, signed_minors(block_values, chosen, 1), strict=True):
            vector[c], vector_value[c] = p, v
        vectors.append(vector)
        vector_values.append(vector_value)
    return vectors, vector_values


def _primitive_rows(
    polys: list[list[Any]], values: list[list[Any]], width: int, ring: Any, point: GenericPoint
) -> GenericRows:
    """Rows made :func:`primitive`, their values divided by the common factor's value (read off the
    entry with the fewest terms). At a point that is not rational the values of derived rows carry
    round-off (a polynomial that is identically zero may have a tiny value), so there the reduced
    polynomials are evaluated again instead, in 60 digits."""
    generators = _generator_values(ring, point)
    exact = all(isinstance(g, int | Fraction) for g in generators)
    out_polys, out_values = [], []
    for row, row_values in zip(polys, values, strict=True):
        reduced = primitive(row)
        if not exact:
            with _precision(exact):
                row_values = [_evaluate(p, generators) if p else 0 for p in reduced]
        else:
            candidates = [j for j, v in enumerate(row_values) if reduced[j] and v != 0]
            if candidates:
                j = min(candidates, key=lambda j: len(reduced[j]))
                factor = quotient(row_values[j], _evaluate(reduced[j], generators))  # common factor's value
                row_values = [quotient(v, factor) for v in row_values]
        out_polys.append(reduced)
        out_values.append(row_values)
    return GenericRows(out_polys, out_values, width, ring, exact)


def nullspace(matrix: Any, point: GenericPoint | None = None) -> Array:
    """A generic basis of ``{x : matrix @ x = 0}`` (``(m, n)`` object array), as rows.

    Cramer's rule on a pivot block chosen at the random point: for a free column ``f`` the vector
    holds the signed maximal minors of the pivot rows on the pivot columns and ``f``. Each vector
    is then made :func:`primitive`. A pivot block larger than :data:`MAX_CRAMER` (a loop-closure
    matrix) goes to sympy's elimination.

    Parameters
    ----------
    matrix : array_like, shape (m, n)
        Sympy expressions (or numbers).
    point : GenericPoint, optional
        The point of evaluation (default: :func:`generic_point` of the rows).

    Returns
    -------
    numpy.ndarray, shape (n - rank, n)
        Object array; each row primitive.

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
    rows = GenericRows.from_exprs(array, point)
    with rows.precision():
        large = len(rows.independent()) > MAX_CRAMER
    if large:  # a loop-closure matrix: sympy's elimination, each vector's denominators cleared
        vectors = []
        for vector in sp.Matrix(array).nullspace(simplify=True):
            denominator = sp.lcm([sp.fraction(sp.together(v))[1] for v in vector])
            vectors.append([sp.cancel(v * denominator) for v in vector])
        rows = GenericRows.from_exprs(np.array(vectors, dtype=object).reshape(len(vectors), n), point)
        polys, values = rows.polys, rows.values
    else:
        with rows.precision():
            polys, values = _kernel(rows.polys, rows.values, n, rows.ring.zero)
    with rows.precision():
        kernel = _primitive_rows(polys, values, n, rows.ring, point)
    return kernel.exprs().reshape(len(kernel), n)


def reciprocal_within(basis: GenericRows, others: GenericRows, point: GenericPoint) -> GenericRows:
    """The screws of ``span(basis)`` reciprocal to every row of ``others`` (generic), as rows.

    With ``basis`` the identity this is the reciprocal system; with ``basis`` a child's wrench
    system and ``others`` its siblings' twists it is the intersection of wrench systems of a
    serial chain (paper 002 Eq. 1), solved on ``order(basis)`` unknowns only. The reciprocal
    products are formed as polynomials only for the pivot rows chosen at the point. Call inside
    ``basis.precision()``.

    Parameters
    ----------
    basis : GenericRows
        Rows ``(b, 6)`` spanning the system searched.
    others : GenericRows
        Rows ``(k, 6)`` every result must be reciprocal to.
    point : GenericPoint
        The point of evaluation.

    Returns
    -------
    GenericRows
        A basis of the reciprocal screws of ``span(basis)``, as rows ``(r, 6)``.

    Examples
    --------
    >>> import sympy
    >>> z = sympy.Symbol("z")
    >>> line = np.array([[0, 0, 1, z, 0, 0]], dtype=object)          # an axis parallel to z
    >>> point = generic_point(line)
    >>> others = GenericRows.from_exprs(line, point)
    >>> len(reciprocal_within(others.identity(), others, point))
    5
    """
    if len(others) == 0 or len(basis) == 0:
        return basis
    products = [[sum(o[_SWAP[j]] * b[j] for j in range(6)) for b in basis.values] for o in others.values]
    pivots, _ = _echelon(products)
    zero = basis.ring.zero
    product_polys = [
        [sum((others.polys[i][_SWAP[j]] * b[j] for j in range(6)), zero) for b in basis.polys] for i in pivots
    ]
    # the coefficients' common factor is removed first: it is found on the small minors, not on
    # their combinations of the basis (where it is as large and harder to find)
    coefficients = _primitive_rows(
        *_kernel(product_polys, [products[i] for i in pivots], len(basis), zero),
        len(basis),
        basis.ring,
        point,
    )
    polys = [
        [sum((c * b[j] for c, b in zip(vector, basis.polys, strict=True) if c), zero) for j in range(6)]
        for vector in coefficients.polys
    ]
    values = [
        [sum(c * b[j] for c, b in zip(vector, basis.values, strict=True)) for j in range(6)]
        for vector in coefficients.values
    ]
    return _primitive_rows(polys, values, 6, basis.ring, point)
