"""Zero tests, numeric and symbolic: when a value, a vector or a product counts as zero.

A numeric decision is relative (:func:`vanishes`: a value against the products of its factors'
sizes; :func:`zero_vectors`: exactly zero or underflowing) or absolute where the caller names the
tolerance (:func:`is_zero`); a symbolic one decides identically, generically
(:func:`is_exactly_zero`: exactly at a random point of the symbols' space,
:mod:`screwkit.algebra.symbolic`). Part of the numeric/symbolic backend
(:mod:`screwkit.algebra.backend`).

Examples
--------
>>> zero_vectors(np.array([[0.0, 0, 0], [1.0, 0, 0]]))
array([ True, False])
>>> import sympy
>>> x = sympy.Symbol("x")
>>> is_exactly_zero(sympy.sin(x) ** 2 + sympy.cos(x) ** 2 - 1)
True
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .backend import dot, is_symbolic, sympy_module

__all__ = [
    "is_exactly_zero",
    "is_zero",
    "norm",
    "ratio",
    "unit_directions",
    "vanishes",
    "where_zero",
    "zero_vectors",
]

Array = np.ndarray


def _binary_exponents(vectors: Array) -> Array:
    """The binary exponent of each vector's largest component (last axis kept; 0 for a zero vector):
    ``vector · 2^-exponent`` has its largest component in [0.5, 1)."""
    largest = np.max(np.abs(vectors), axis=-1, keepdims=True)
    return np.frexp(np.where(largest > 0, largest, 1.0))[1]


def is_exactly_zero(value: Any) -> bool:
    """Exact zero test of a scalar: ``value == 0`` for numbers, ``simplify(value) == 0`` for sympy.

    Unlike :func:`is_zero`, a symbolic value that depends on symbols is *generically* decided
    (``x`` is not zero) rather than refused; no tolerance is involved.

    Parameters
    ----------
    value : object
        A number or a sympy expression.

    Returns
    -------
    bool

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> is_exactly_zero(sympy.sin(x) ** 2 + sympy.cos(x) ** 2 - 1), is_exactly_zero(x), is_exactly_zero(0.0)
    (True, False, True)
    """
    if is_symbolic(value):
        return _identically_zero(value)
    return bool(value == 0)


def _identically_zero(expr: Any) -> bool:
    """A sympy scalar is identically zero.

    A non-zero *exact* value at the symbols' random integer point (:mod:`screwkit.algebra.symbolic`)
    proves it is not, without simplifying: the common case costs one substitution. Otherwise
    ``expand`` decides polynomials and ``simplify`` the rest (trigonometric identities).
    """
    sp = sympy_module()
    if expr == 0:
        return True
    if expr.free_symbols:
        from . import symbolic

        try:
            value = symbolic.generic_point(np.array([expr], dtype=object)).value(expr, remember=False)
        except ScrewkitValueError:  # not real at the point: decided below
            value = None
        if isinstance(value, int | Fraction) and value != 0:
            return False
    return bool(sp.expand(expr) == 0 or sp.simplify(expr) == 0)


def zero_vectors(values: Array) -> Array:
    """Where vectors over the last axis are zero: exactly for numbers, identically for sympy.

    Parameters
    ----------
    values : numpy.ndarray, shape (..., n)

    Returns
    -------
    numpy.ndarray of bool, shape (...) (a numpy bool for one vector)

    Examples
    --------
    >>> zero_vectors(np.array([[0.0, 0.0], [0.0, 1e-300]]))
    array([ True, False])
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> zero_vectors(np.array([[x - x, (x + 1) ** 2 - x**2 - 2 * x - 1], [x, 0]], dtype=object))
    array([ True, False])
    """
    if is_symbolic(values):
        rows = values.reshape(-1, values.shape[-1])
        zero = [all(is_exactly_zero(v) for v in row) for row in rows]
        return np.array(zero, dtype=bool).reshape(values.shape[:-1])[()]
    return np.all(np.asarray(values) == 0, axis=-1)


def vanishes(values: Array, *factors: Array, rtol: float) -> Array:
    """Where vectors vanish relative to the vectors they were computed from.

    Numeric: ``|values| <= rtol · ∏ |factor|`` (Euclidean norms over the last axis), so that the
    decision does not change when a factor is scaled (a unit change, a longer direction).
    Symbolic: every component is identically zero (:func:`zero_vectors`); a symbolic value is
    generic, so no tolerance applies.

    Parameters
    ----------
    values : numpy.ndarray, shape (..., n)
        E.g. a cross product, a join or a meet.
    *factors : numpy.ndarray, shape (..., m)
        The inputs ``values`` is linear in (the product of their norms bounds ``|values|``).
    rtol : float

    Returns
    -------
    numpy.ndarray of bool, shape (...) (a numpy bool for one vector)

    Examples
    --------
    >>> a, b = np.array([1.0, 0, 0]), np.array([1.0, 1e-12, 0])
    >>> vanishes(np.cross(a, b), a, b, rtol=1e-9), vanishes(np.cross(a, 1e3 * b), a, 1e3 * b, rtol=1e-9)
    (np.True_, np.True_)
    >>> import sympy
    >>> from screwkit.algebra.backend import cross
    >>> t = sympy.Symbol("t")
    >>> vanishes(cross(np.array([t, 0, 0], dtype=object), np.array([1, t, 0], dtype=object)), rtol=1e-9)
    np.False_
    """
    if is_symbolic(values):
        return zero_vectors(values)
    reference = np.prod([_norms(f) for f in factors], axis=0) if factors else 1.0
    return _norms(values) <= rtol * reference


def _norms(vectors: Array) -> Array:
    """Euclidean norms over the last axis: :func:`numpy.linalg.norm`'s, except where its squares
    overflow or underflow (``|s·m| = 1e180`` of a line, a 1e-170 helix's ``s·m``): those vectors
    are taken times a power of two first (:func:`_binary_exponents`; exact).

    Examples
    --------
    >>> _norms(np.array([[3e200, 4e200], [3e-200, 4e-200], [3.0, 4.0]]))
    array([5.e+200, 5.e-200, 5.e+000])
    """
    with np.errstate(over="ignore"):  # an overflowed square is recomputed below
        norms = np.linalg.norm(vectors, axis=-1)
    # a norm in (1e-145, 1e145): no square overflowed, and those that underflowed are below its ulp
    kept = (norms > 1e-145) & (norms < 1e145)
    if np.all(kept):  # the common case, numpy's norms as they are
        return norms
    risky = ~kept
    shift = _binary_exponents(vectors)
    return np.where(risky, np.ldexp(np.linalg.norm(np.ldexp(vectors, -shift), axis=-1), shift[..., 0]), norms)


def unit_directions(vectors: Array) -> Array:
    """Numeric vectors ``(..., 3)`` scaled to unit length; symbolic vectors unchanged.

    A numeric vector is first scaled by a power of two (exact;
    :func:`~screwkit.algebra.ranks.direction_scaled`), so that a
    vector whose squared length underflows (a 1e-170 axis) or overflows still gets its unit vector
    (for other vectors the same bits as dividing by the norm). A symbolic direction stays
    polynomial (no ``sqrt``): its length is a generic non-zero factor, and every use of a direction
    in a screw system is projective in it.

    Parameters
    ----------
    vectors : numpy.ndarray, shape (..., 3)
        The vectors.

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> unit_directions(np.array([3.0, 0, 4]))
    array([0.6, 0. , 0.8])
    >>> unit_directions(np.array([3e-170, 0, 4e-170]))
    array([0.6, 0. , 0.8])
    >>> import sympy
    >>> unit_directions(np.array([sympy.Symbol("a"), 0, 1], dtype=object))
    array([a, 0, 1], dtype=object)
    """
    if is_symbolic(vectors):
        return vectors
    scaled = np.ldexp(vectors, -_binary_exponents(vectors))
    return scaled / np.linalg.norm(scaled, axis=-1, keepdims=True)


def norm(a: Array) -> Array:
    """Euclidean norm over the last axis (``sympy.sqrt`` of the sum of squares when symbolic).

    Parameters
    ----------
    a : numpy.ndarray, shape (..., n)
        Float or sympy-object vectors.

    Returns
    -------
    numpy.ndarray, shape (...)

    Examples
    --------
    >>> norm(np.array([3.0, 4.0]))
    np.float64(5.0)
    """
    if a.dtype == object:
        sp = sympy_module()
        squares = dot(a, a)
        if isinstance(squares, np.ndarray):
            return np.vectorize(lambda v: sp.sqrt(v), otypes=[object])(squares)
        return sp.sqrt(squares)
    return _norms(a)


def is_zero(value: Any, *, atol: float) -> Any:
    """Decide whether a value is zero: ``|value| <= atol`` numerically, exactly when symbolic.

    Parameters
    ----------
    value : float, array or sympy expression
    atol : float
        Absolute tolerance of the numeric branch (ignored by the symbolic branch).

    Returns
    -------
    bool or numpy.ndarray of bool

    Raises
    ------
    ScrewkitValueError
        If a symbolic value cannot be decided (it depends on free symbols): substitute values.

    Examples
    --------
    >>> is_zero(1e-12, atol=1e-9)
    True
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> is_zero((x + 1) ** 2 - x**2 - 2 * x - 1, atol=0)
    True
    """
    if isinstance(value, np.ndarray) and value.dtype == object:
        return np.vectorize(lambda v: is_zero(v, atol=atol), otypes=[bool])(value)
    if is_symbolic(value):
        reduced = sympy_module().simplify(value)
        if reduced == 0:
            return True
        if reduced.free_symbols:
            raise ScrewkitValueError(
                f"Cannot decide whether {reduced} is zero: it depends on "
                f"{sorted(map(str, reduced.free_symbols))}; substitute values first."
            )
        return bool(abs(complex(reduced)) == 0)
    result = np.abs(value) <= atol
    return bool(result) if np.ndim(result) == 0 else result


def ratio(numerator: Any, denominator: Any) -> Any:
    """``numerator / denominator`` elementwise, infinity where the denominator is exactly zero.

    Numeric: float64 (a float for scalars); symbolic: simplified quotients or ``sympy.oo``, decided
    by :func:`is_exactly_zero`.

    Parameters
    ----------
    numerator, denominator : object
        Floats, sympy expressions or arrays of them (broadcast together).

    Returns
    -------
    object
        The quotients (a float for float scalars).

    Examples
    --------
    >>> ratio(np.array([1.0, 2.0]), np.array([4.0, 0.0]))
    array([0.25,  inf])
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> ratio(x**2, x), ratio(x, x - x)
    (x, oo)
    """
    if is_symbolic(numerator, denominator):
        sp = sympy_module()

        def one(n: Any, d: Any) -> Any:
            return sp.oo if is_exactly_zero(d) else sp.simplify(n / d)

        if np.ndim(denominator) == 0 and np.ndim(numerator) == 0:
            return one(numerator, denominator)
        return np.vectorize(one, otypes=[object])(numerator, denominator)
    safe = np.where(denominator != 0, denominator, 1.0)
    result = np.where(denominator != 0, numerator / safe, math.inf)
    return float(result) if np.ndim(result) == 0 else result


def where_zero(test: Any, if_zero: Any, otherwise: Any) -> Any:
    """``if_zero`` where ``test`` is exactly zero, else ``otherwise``, elementwise.

    Numeric: :func:`numpy.where` (a float for scalars); symbolic: decided by :func:`is_exactly_zero`.

    Parameters
    ----------
    test : object
        The values tested.
    if_zero, otherwise : object
        The values taken where ``test`` is, or is not, exactly zero.

    Returns
    -------
    object
        The chosen values (a float for float scalars).

    Examples
    --------
    >>> where_zero(np.array([0.0, 2.0]), np.array([5.0, 5.0]), np.array([2.0, 2.0]))
    array([5., 2.])
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> where_zero(x - x, 1, x)
    1
    """
    if is_symbolic(test, if_zero, otherwise):
        if np.ndim(test) == 0:
            return if_zero if is_exactly_zero(test) else otherwise
        return np.vectorize(lambda t, a, b: a if is_exactly_zero(t) else b, otypes=[object])(
            test, if_zero, otherwise
        )
    result = np.where(test == 0, if_zero, otherwise)
    return float(result) if np.ndim(result) == 0 else result
