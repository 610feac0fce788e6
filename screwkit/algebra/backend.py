"""The numeric/symbolic backend: the only place where numeric and symbolic code differ.

Every other module writes one kernel with ``+ - * @``, :func:`numpy.cross`, :func:`numpy.concatenate`
and indexing, which numpy supports both for ``float64`` arrays and for ``object`` arrays of sympy
expressions. What those operators cannot do has a numeric and a symbolic branch (docs/architecture.md §4), in
four modules of one responsibility each:

* this one: input validation and promotion (:func:`as_array`, :func:`promote`: if any input is
  symbolic, all become exact sympy numbers), exact numbers and infinities, elementwise products,
  determinants, square roots and simplification;
* :mod:`screwkit.algebra.branch_values`: zeros and ones of a branch, JSON-ready values of either;
* :mod:`screwkit.algebra.zero_tests`: zero tests and quotients with an infinite branch (a numeric
  decision uses a relative tolerance, a symbolic one decides identically, generically);
* :mod:`screwkit.algebra.ranks`: ranks and null spaces of screws with their length scale;
* :mod:`screwkit.algebra.checks`: the checked parameters (tolerances, length scales, rotations).

Elsewhere :func:`is_symbolic` only refuses symbolic input on a numeric-only path (a snapshot, the
batched core), sends a symbolic twist graph to the generic analysis, or passes the branch to a
constructor here.

Examples
--------
>>> from screwkit.algebra import backend as B
>>> B.as_array([1, 2, 3], "point", (3,))
array([1., 2., 3.])
>>> import sympy
>>> B.is_symbolic(np.array([sympy.Symbol("x"), 1], dtype=object))
True
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .numbers import numbers_only

__all__ = [
    "DEFAULT_RTOL",
    "as_array",
    "as_arrays",
    "cross",
    "det",
    "dot",
    "exact_fraction",
    "from_fraction",
    "infinity",
    "is_dof",
    "is_infinite",
    "is_symbolic",
    "promote",
    "simplify",
    "sqrt",
    "sympy_module",
    "to_sympy",
]

#: Default relative tolerance of every rank and zero decision (documented in each public function).
DEFAULT_RTOL = 1e-9

Array = np.ndarray

if TYPE_CHECKING:
    import sympy


def sympy_module() -> Any:
    """The :mod:`sympy` module, imported on first use: ``import screwkit`` does not import sympy.

    Returns
    -------
    module
        :mod:`sympy`.

    Examples
    --------
    >>> sympy_module().Integer(2) / 4
    1/2
    """
    import sympy

    return sympy


def is_symbolic(*arrays: Any) -> bool:
    """Return True if any argument is, or contains, a sympy expression.

    Parameters
    ----------
    *arrays : array_like or sympy.Basic
        Anything :func:`as_array` accepts.

    Returns
    -------
    bool

    Examples
    --------
    >>> is_symbolic([1.0, 2.0], 3)
    False
    >>> import sympy
    >>> is_symbolic([sympy.Symbol("t"), 2.0])
    True
    """
    sp = sys.modules.get("sympy")
    if sp is None:  # never imported: no value can be a sympy object
        return False
    for value in arrays:
        if isinstance(value, sp.Basic):
            return True
        if isinstance(value, np.ndarray):
            if value.dtype == object and any(isinstance(v, sp.Basic) for v in value.flat):
                return True
            continue
        if isinstance(value, list | tuple) and is_symbolic(*value):
            return True
        if hasattr(value, "__array__") and is_symbolic(np.asarray(value)):  # e.g. a Screw
            return True
    return False


def to_sympy(value: Any) -> sympy.Expr:
    """Convert one scalar to an exact sympy number or leave an expression alone.

    Floats become the rational of their shortest decimal representation, so ``0.1`` becomes
    ``1/10``; a float never leaks into a symbolic result.

    Parameters
    ----------
    value : object
        A number (int, float, Fraction, numpy scalar) or a sympy expression.

    Returns
    -------
    sympy.Expr

    Examples
    --------
    >>> to_sympy(0.1)
    1/10
    >>> to_sympy(3)
    3
    """
    sp = sympy_module()
    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, bool | np.bool_):
        raise ScrewkitTypeError(f"Expected a number or a sympy expression, got a boolean {value!r}.")
    if isinstance(value, int | np.integer):
        return sp.Integer(int(value))
    if isinstance(value, float | np.floating):
        if not np.isfinite(value):
            raise ScrewkitValueError(f"Expected a finite number, got {value!r}.")
        return sp.Rational(repr(float(value)))
    raise ScrewkitTypeError(f"Expected a number or a sympy expression, got {type(value).__name__} {value!r}.")


def exact_fraction(value: Any) -> Fraction | None:
    """The exact rational of an integer, a :class:`~fractions.Fraction` or a sympy ``Rational``; else None.

    Booleans are not numbers here (None). Deciding needs no sympy import.

    Parameters
    ----------
    value : object
        A scalar.

    Returns
    -------
    fractions.Fraction or None

    Examples
    --------
    >>> import sympy
    >>> exact_fraction(sympy.Rational(3, 4)), exact_fraction(np.int64(2)), exact_fraction(0.5)
    (Fraction(3, 4), Fraction(2, 1), None)
    """
    if isinstance(value, bool | np.bool_):
        return None
    if isinstance(value, int | np.integer):
        return Fraction(int(value))
    if isinstance(value, Fraction):
        return value
    if is_symbolic(value) and value.is_Rational:
        return Fraction(int(value.p), int(value.q))
    return None


def from_fraction(value: Fraction, *, symbolic: bool) -> Any:
    """An exact rational in the chosen branch: a sympy ``Rational``, or a float.

    Parameters
    ----------
    value : fractions.Fraction
        The rational.
    symbolic : bool
        The branch: sympy (True) or float (False).

    Returns
    -------
    sympy.Rational or float

    Examples
    --------
    >>> from fractions import Fraction
    >>> from_fraction(Fraction(1, 4), symbolic=True), from_fraction(Fraction(1, 4), symbolic=False)
    (1/4, 0.25)
    """
    if symbolic:
        return sympy_module().Rational(value.numerator, value.denominator)
    return float(value)


def infinity(*, symbolic: bool) -> Any:
    """Infinity in the chosen branch: ``sympy.oo`` or ``math.inf`` (an infinite pitch).

    Parameters
    ----------
    symbolic : bool
        The branch: sympy (True) or float (False).

    Returns
    -------
    sympy.oo or float

    Examples
    --------
    >>> infinity(symbolic=True), infinity(symbolic=False)
    (oo, inf)
    """
    return sympy_module().oo if symbolic else math.inf


def is_infinite(value: Any) -> bool:
    """True for ``math.inf``, ``-math.inf``, ``sympy.oo`` or ``-sympy.oo`` (a scalar).

    Parameters
    ----------
    value : object
        A scalar (float or sympy).

    Returns
    -------
    bool

    Examples
    --------
    >>> import sympy
    >>> is_infinite(sympy.oo), is_infinite(float("inf")), is_infinite(sympy.Symbol("h")), is_infinite(2.0)
    (True, True, False, False)
    """
    if is_symbolic(value):
        return bool(value.is_infinite)
    return bool(np.isinf(value))


def sqrt(value: Any) -> Any:
    """Square root: :func:`numpy.sqrt`, or ``sympy.sqrt`` elementwise when symbolic.

    Parameters
    ----------
    value : object
        A float, a sympy expression or an array of them.

    Returns
    -------
    object
        The square root, of the same kind.

    Examples
    --------
    >>> import sympy
    >>> sqrt(np.array([4.0])), sqrt(sympy.Symbol("x", positive=True) ** 2)
    (array([2.]), x)
    """
    if is_symbolic(value):
        sp = sympy_module()
        if isinstance(value, np.ndarray):
            return np.vectorize(sp.sqrt, otypes=[object])(value)
        return sp.sqrt(value)
    return np.sqrt(value)


def _describe_shape(shape: tuple[int | None, ...]) -> str:
    parts = ["..."] + ["n" if s is None else str(s) for s in shape]
    return "(" + ", ".join(parts) + ")"


def as_array(
    value: Any,
    name: str,
    shape: tuple[int | None, ...] = (),
    *,
    symbolic: bool | None = None,
) -> Array:
    """Validate an argument and return it as a float64 or sympy-object array.

    Parameters
    ----------
    value : array_like
        The argument: numbers, sequences of numbers, numpy arrays, sympy expressions.
    name : str
        The argument's name, used in error messages.
    shape : tuple of int or None
        The required trailing shape, e.g. ``(6,)`` for screws; None matches any length.
    symbolic : bool or None
        Force the symbolic (True) or numeric (False) branch; None decides from ``value``.

    Returns
    -------
    numpy.ndarray
        A new ``float64`` array, or an ``object`` array of sympy expressions.

    Raises
    ------
    ScrewkitTypeError
        If ``value`` holds something that is not a number.
    ScrewkitValueError
        If the trailing shape is wrong or a number is NaN or infinite.

    Examples
    --------
    >>> as_array([1, 2, 3], "point", (3,))
    array([1., 2., 3.])
    >>> as_array([1, 2], "point", (3,))
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `point` to have shape (..., 3), got (2,).
    """
    if isinstance(value, str | bytes):
        raise ScrewkitTypeError(f"Expected `{name}` to be numeric, got the string {value!r}.")
    want_symbolic = is_symbolic(value) if symbolic is None else symbolic
    if want_symbolic:
        raw = np.array(value, dtype=object)  # ragged input becomes an array of lists: refused below
        flat = [_checked_sympy(v, name) for v in raw.flat]
        array = np.empty(raw.shape, dtype=object)
        for i, v in enumerate(flat):
            array.flat[i] = v
    else:
        try:
            array = np.array(numbers_only(value, name), dtype=float)
        except ScrewkitTypeError:  # None, strings, booleans: refused by name
            raise
        except OverflowError as err:  # a Python integer beyond every float
            raise ScrewkitValueError(
                f"Expected `{name}` to hold finite numbers, got an integer too large for a float ({err})."
            ) from err
        except (ValueError, TypeError) as err:
            raise ScrewkitTypeError(
                f"Expected `{name}` to be an array of numbers, got {type(value).__name__}: {err}."
            ) from err
        if not np.all(np.isfinite(array)):
            raise ScrewkitValueError(
                f"Expected `{name}` to hold finite numbers, got NaN or infinity in {array.tolist()}."
            )
    tail: tuple[int, ...] | None = (
        tuple(array.shape[array.ndim - len(shape) :]) if len(shape) <= array.ndim else None
    )
    if tail is None or any(want is not None and want != got for want, got in zip(shape, tail, strict=True)):
        raise ScrewkitValueError(
            f"Expected `{name}` to have shape {_describe_shape(shape)}, got {array.shape}."
        )
    return array


def _checked_sympy(value: Any, name: str) -> sympy.Expr:
    try:
        expr = to_sympy(value)
    except (ScrewkitTypeError, ScrewkitValueError) as err:
        raise type(err)(f"In `{name}`: {err}") from err
    sp = sympy_module()
    if expr.has(sp.nan, sp.oo, -sp.oo, sp.zoo):
        raise ScrewkitValueError(f"Expected `{name}` to hold finite expressions, got {expr}.")
    if expr.has(sp.I) or expr.is_extended_real is False:  # screws are real (Plücker coordinates)
        raise ScrewkitValueError(f"Expected `{name}` to hold real expressions, got {expr}.")
    return expr


def promote(*arrays: Array) -> tuple[Array, ...]:
    """Bring validated arrays to one branch: all float64, or all sympy-object if any is symbolic.

    Parameters
    ----------
    *arrays : numpy.ndarray
        Arrays already validated (:func:`as_array`).

    Returns
    -------
    tuple of numpy.ndarray
        The arrays in one branch, in order.

    Examples
    --------
    >>> import sympy
    >>> a, b = promote(np.array([1.5]), np.array([sympy.Symbol("x")], dtype=object))
    >>> a.dtype, a[0]
    (dtype('O'), 3/2)
    """
    if any(a.dtype == object for a in arrays):
        out = []
        for a in arrays:
            if a.dtype == object:
                out.append(a)
            else:
                converted = np.empty(a.shape, dtype=object)
                for i, v in enumerate(a.flat):
                    converted.flat[i] = to_sympy(float(v))
                out.append(converted)
        return tuple(out)
    return arrays


def as_arrays(shape: tuple[int | None, ...], *named: tuple[Any, str]) -> tuple[Array, ...]:
    """Validate several ``(value, name)`` arguments of one trailing shape and promote them together.

    Parameters
    ----------
    shape : tuple of int or None
        The trailing shape every value must have (None: any length on that axis).
    *named : tuple of (value, str)
        Each argument and its name (for the error messages).

    Returns
    -------
    tuple of numpy.ndarray
        The arrays, in order, all float64 or all sympy-object (:func:`promote`).

    Examples
    --------
    >>> import sympy
    >>> a, b = as_arrays((3,), ([1, 2, 3], "p"), ([0, sympy.Symbol("t"), 0], "q"))
    >>> a.dtype, b[1]
    (dtype('O'), t)
    """
    return promote(*(as_array(value, name, shape) for value, name in named))


def is_dof(value: Any) -> bool:
    """True for an integer (Python or numpy, not a boolean) from 0 to 6: a mobility.

    Parameters
    ----------
    value : object
        The candidate mobility.

    Returns
    -------
    bool

    Examples
    --------
    >>> is_dof(4), is_dof(np.int64(6)), is_dof(True), is_dof(7)
    (True, True, False, False)
    """
    return bool(
        isinstance(value, int | np.integer) and not isinstance(value, bool | np.bool_) and 0 <= value <= 6
    )


def cross(a: Array, b: Array) -> Array:
    """Cross product over the last axis for float and sympy-object arrays alike.

    ``numpy.cross`` refuses object arrays in numpy 2, so the three components are written out: the
    same products and differences as ``numpy.cross`` (so the same bits for floats), without its
    axis bookkeeping, which dominates for single vectors.

    Parameters
    ----------
    a, b : numpy.ndarray, shape (..., 3)
        Float or sympy-object vectors (broadcast together).

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> cross(np.array([1.0, 0, 0]), np.array([0, 1.0, 0]))
    array([0., 0., 1.])
    """
    a, b = np.asarray(a), np.asarray(b)
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def median(values: Array) -> float:
    """``numpy.median`` of a 1-D float array, the same value (the middle one, or the two middle ones
    added and halved; NaN if any is NaN or the array is empty), without ``numpy.median``'s import of
    ``numpy.ma`` on first use (a noticeable share of a single-pose report's time).

    Examples
    --------
    >>> median(np.array([3.0, 1.0, 2.0, 10.0])), median(np.array([2.0, np.nan]))
    (2.5, nan)
    """
    ordered = np.sort(np.asarray(values, dtype=float).ravel())
    if ordered.size == 0 or np.isnan(ordered[-1]):
        return math.nan
    half = ordered.size // 2
    return float(ordered[half] if ordered.size % 2 else (ordered[half - 1] + ordered[half]) / 2)


def dot(a: Array, b: Array, *, keepdims: bool = False) -> Any:
    """Dot product over the last axis, batched; ``keepdims`` keeps a trailing axis of length 1.

    Parameters
    ----------
    a, b : numpy.ndarray, shape (..., n)
        Float or sympy-object vectors (broadcast together).
    keepdims : bool, default False
        Keep the summed axis with length 1.

    Returns
    -------
    numpy.ndarray or scalar
        The products, shape ``(...)`` (or ``(..., 1)`` with ``keepdims``).

    Examples
    --------
    >>> dot(np.array([1.0, 2, 3]), np.array([4.0, 5, 6]))
    np.float64(32.0)
    >>> dot(np.array([1.0, 2, 3]), np.array([4.0, 5, 6]), keepdims=True)
    array([32.])
    """
    return (a * b).sum(axis=-1, keepdims=keepdims)


def det(matrix: Array) -> Any:
    """Determinant of a square matrix over the last two axes (batched when numeric).

    Parameters
    ----------
    matrix : numpy.ndarray, shape (..., n, n)
        Float (batched) or sympy-object (one matrix) entries.

    Returns
    -------
    float, numpy.ndarray of shape (...), or sympy.Expr

    Examples
    --------
    >>> det(np.eye(3) * 2)
    np.float64(7.999999999999998)
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> det(np.array([[x, 1], [1, x]], dtype=object))
    x**2 - 1
    """
    if matrix.dtype == object:
        if matrix.ndim != 2:
            raise ScrewkitValueError(f"Expected a single symbolic square matrix, got shape {matrix.shape}.")
        sp = sympy_module()
        return sp.expand(sp.Matrix(matrix).det(method="berkowitz"))
    return np.linalg.det(matrix)


def simplify(value: Any) -> Any:
    """Simplify a sympy expression, or each element of an object array; floats pass through.

    Parameters
    ----------
    value : object
        A float, a sympy expression or an array of them.

    Returns
    -------
    object
        The simplified value, of the same kind.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> simplify(sympy.sin(x) ** 2 + sympy.cos(x) ** 2)
    1
    """
    if isinstance(value, np.ndarray) and value.dtype == object:
        return np.vectorize(sympy_module().simplify, otypes=[object])(value)
    if is_symbolic(value):
        return sympy_module().simplify(value)
    return value
