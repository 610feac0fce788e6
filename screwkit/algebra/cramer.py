"""Cramer's rule, primitive parts and exact quotients: division-free arithmetic on polynomials.

A null-space vector of a ``k × (k+1)`` block is its signed maximal minors (Cramer's rule), computed
by Laplace expansion along the rows with each smaller minor computed once (:func:`signed_minors`):
no division, so the same code is exact on integers, fractions and polynomials. A polynomial vector
is then divided by the greatest common divisor of its entries (:func:`primitive`), which keeps its
projective class. :mod:`screwkit.algebra.symbolic` builds its generic bases with them.

Examples
--------
>>> list(signed_minors([[1, 2, 3]], [0, 1], 1))  # the null vector of [1 2]
[2, -1]
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator, Sequence
from fractions import Fraction
from typing import Any

__all__ = ["primitive", "quotient", "signed_minors"]


def primitive(vector: list[Any]) -> list[Any]:
    """A vector of polynomials (one ring, integer coefficients) divided by the greatest common
    divisor of its entries, the first non-zero entry's leading coefficient made positive; the
    projective class is unchanged.

    Parameters
    ----------
    vector : list of PolyElement
        Polynomials of one ring with integer coefficients.

    Returns
    -------
    list of PolyElement
        The primitive vector.

    Examples
    --------
    >>> from sympy.polys.rings import ring
    >>> from sympy.polys.domains import ZZ
    >>> R, x, y = ring("x y", ZZ)
    >>> primitive([-2 * x * y - 2 * x, 4 * x, R.zero])
    [y + 1, -2, 0]
    """
    nonzero = [p for p in vector if p]
    if not nonzero:
        return list(vector)
    ordered = sorted(nonzero, key=len)  # the smallest first: the gcd shrinks fastest
    common = ordered[0]
    for entry in ordered[1:]:
        if common.is_ground:  # only an integer content is left to find
            common = common.ring.ground_new(math.gcd(*(int(p.content()) for p in nonzero)))
            break
        common = common.gcd(entry)
    if nonzero[0].LC * common.LC < 0:
        common = -common
    return [p.exquo(common) if p else p for p in vector]


def signed_minors(matrix: list[list[Any]], columns: Sequence[int], one: Any) -> Iterator[Any]:
    """Signed maximal minors of a ``k × (k+1)`` submatrix: entry ``c`` is ``(−1)^c`` times the
    determinant without column ``columns[c]`` (a vector of its null space, Cramer's rule).

    Laplace expansion along the rows with each smaller minor computed once (division free,
    so exact on polynomials and on numbers alike).

    Parameters
    ----------
    matrix : list of list
        ``k`` rows (numbers or polynomials).
    columns : sequence of int
        The ``k + 1`` columns of the submatrix.
    one : int or PolyElement
        The unit of the entries' ring.

    Yields
    ------
    int or PolyElement
        The signed minor of each column, in order.

    Examples
    --------
    >>> list(signed_minors([[1, 2, 3]], [0, 1], 1))  # (2, -1): null vector of [1 2]
    [2, -1]
    """
    k = len(matrix)

    @functools.cache
    def minor(depth: int, chosen: tuple[int, ...]) -> Any:
        if depth < 0:
            return one
        total = one - one
        for position, column in enumerate(chosen):
            entry = matrix[depth][column]
            if entry:
                term = entry * minor(depth - 1, chosen[:position] + chosen[position + 1 :])
                total = total + term if (depth + position) % 2 == 0 else total - term
        return total

    for c in range(len(columns)):
        value = minor(k - 1, tuple(columns[:c]) + tuple(columns[c + 1 :]))
        yield value if c % 2 == 0 else -value


def quotient(numerator: Any, denominator: Any) -> Any:
    """``numerator / denominator``, exact (an int when it is one) unless a float is involved.

    Parameters
    ----------
    numerator, denominator : int, Fraction or mpmath.mpf
        The operands.

    Returns
    -------
    int, Fraction or mpmath.mpf
        The quotient.

    Examples
    --------
    >>> quotient(6, 3), quotient(1, 2)
    (2, Fraction(1, 2))
    """
    if isinstance(numerator, int | Fraction) and isinstance(denominator, int | Fraction):
        quotient = (
            Fraction(numerator, denominator)
            if isinstance(numerator, int) and isinstance(denominator, int)
            else Fraction(numerator) / denominator
        )
        return int(quotient) if quotient.denominator == 1 else quotient
    return numerator / denominator
