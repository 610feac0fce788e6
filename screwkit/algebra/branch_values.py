"""Values of a branch and out of it: zeros and ones, and JSON-ready plain values.

A kernel that builds an array must build it in its inputs' branch (docs/architecture.md §4): float64, or
exact sympy numbers in an object array, so that no float leaks into a symbolic result
(:func:`zeros`, :func:`zeros_like`, :func:`ones_like`). Results leave either branch as plain
JSON-ready values (:func:`plain`, :func:`float_lists`). Part of the numeric/symbolic backend
(:mod:`screwkit.algebra.backend`).

Examples
--------
>>> zeros((2,), symbolic=True).tolist(), plain(0.5)
([0, 0], 0.5)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .backend import is_symbolic, to_sympy

__all__ = ["float_lists", "ones_like", "plain", "zeros", "zeros_like"]

Array = np.ndarray


def plain(value: Any) -> float | str:
    """A JSON-ready scalar: a float for a number, the text of a sympy expression.

    Parameters
    ----------
    value : object
        A number or a sympy expression.

    Returns
    -------
    float or str

    Examples
    --------
    >>> import sympy
    >>> plain(np.float64(2.5)), plain(sympy.Symbol("x") / 2)
    (2.5, 'x/2')
    """
    return str(value) if is_symbolic(value) else float(value)


def float_lists(**values: Any) -> dict[str, Any]:
    """Numeric values as JSON-ready float lists by name; ``{}`` when any value is symbolic.

    Parameters
    ----------
    **values : array_like
        The named values.

    Returns
    -------
    dict of str to list
        Nested float lists by name, or ``{}`` if any value is symbolic.

    Examples
    --------
    >>> import sympy
    >>> float_lists(axis=np.array([0, 0, 1]), pitch=2), float_lists(axis=[sympy.Symbol("a"), 0, 1])
    ({'axis': [0.0, 0.0, 1.0], 'pitch': 2.0}, {})
    """
    if is_symbolic(*values.values()):
        return {}
    return {name: np.asarray(value, dtype=float).tolist() for name, value in values.items()}


def zeros(shape: tuple[int, ...], *, symbolic: bool) -> Array:
    """Zeros of a shape in a branch: float64, or exact sympy zeros in an object array.

    Parameters
    ----------
    shape : tuple of int
        The shape.
    symbolic : bool
        The branch: sympy-object (True) or float64 (False).

    Returns
    -------
    numpy.ndarray

    Examples
    --------
    >>> zeros((2,), symbolic=True)
    array([0, 0], dtype=object)
    """
    if not symbolic:
        return np.zeros(shape)
    out = np.empty(shape, dtype=object)
    out.fill(to_sympy(0))
    return out


def zeros_like(a: Array) -> Array:
    """Zeros of ``a``'s shape in its branch: float64 zeros, or exact sympy zeros in an object array.

    Parameters
    ----------
    a : numpy.ndarray
        Float or sympy-object array.

    Returns
    -------
    numpy.ndarray
        Zeros of ``a``'s shape (float64 or sympy-object).

    Examples
    --------
    >>> import sympy
    >>> zeros_like(np.array([sympy.Symbol("x")], dtype=object))
    array([0], dtype=object)
    """
    return a * 0 if is_symbolic(a) else np.zeros_like(a, dtype=float)


def ones_like(a: Array) -> Array:
    """Ones of ``a``'s shape in its branch: float64 ones, or exact sympy ones in an object array.

    Parameters
    ----------
    a : numpy.ndarray
        Float or sympy-object array.

    Returns
    -------
    numpy.ndarray
        Ones of ``a``'s shape (float64 or sympy-object).

    Examples
    --------
    >>> ones_like(np.zeros(2))
    array([1., 1.])
    """
    return a * 0 + to_sympy(1) if is_symbolic(a) else np.ones_like(a, dtype=float)
