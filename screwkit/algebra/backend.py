"""The only module where numeric and symbolic code differ.

Every other module writes one kernel with ``+ - * @``, :func:`numpy.cross`, :func:`numpy.concatenate`
and indexing, which numpy supports both for ``float64`` arrays and for ``object`` arrays of sympy
expressions. What those operators cannot do (input validation and promotion, norms, determinants,
ranks, null spaces, zero tests and degeneracy decisions, quotients with an infinite branch, the
floating-point range scalings, simplification) lives here, each with a numeric and a symbolic
branch (design.md §4): a numeric decision uses a relative tolerance, a symbolic one decides
identically (generically; :func:`is_exactly_zero`). Elsewhere :func:`is_symbolic` only refuses
symbolic input on a numeric-only path (a snapshot, the batched core), sends a symbolic twist graph
to the generic analysis, or passes the branch to a constructor here (``zeros(..., symbolic=...)``).

Rank decisions
--------------
A screw ``(s; s0)`` mixes a dimensionless direction and a moment with the unit of length. Before any
rank decision the moment half is divided by a characteristic length ``length_scale`` and every row is
normalised to unit length (row scaling does not change a rank). The rank is then the number of
singular values above ``rtol`` times the largest one. With ``length_scale`` given in the same unit as
the coordinates, the answer is the same in millimetres and in metres. When ``length_scale`` is None
it is taken from the data: the largest ``|s0| / |s|`` over rows whose direction is not round-off
(``|s| > 1e-9 |s0|``; a length in the data's own unit), or 1 if every row is a couple.

Examples
--------
>>> import numpy as np
>>> from screwkit.algebra import backend as B
>>> B.screw_rank(np.array([[0, 0, 1, 0, 0, 0], [0, 0, 2, 0, 0, 0]]))
1
>>> import sympy
>>> B.is_symbolic(np.array([sympy.Symbol("x"), 1], dtype=object))
True
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np

from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "DEFAULT_RTOL",
    "as_array",
    "as_arrays",
    "characteristic_length",
    "check_rotation",
    "checked_length_scale",
    "cross",
    "det",
    "direction_scaled",
    "dot",
    "exact_fraction",
    "float_lists",
    "from_fraction",
    "infinity",
    "is_dof",
    "is_exactly_zero",
    "is_infinite",
    "is_symbolic",
    "is_zero",
    "matrix_nullspace",
    "norm",
    "ones_like",
    "plain",
    "promote",
    "ratio",
    "scale_moments",
    "screw_image_of_nullspace",
    "screw_nullspace",
    "screw_rank",
    "screw_singular_values",
    "simplify",
    "sqrt",
    "sympy_module",
    "to_sympy",
    "unit_directions",
    "unit_screws",
    "vanishes",
    "where_zero",
    "zero_vectors",
    "zeros",
    "zeros_like",
]

#: Default relative tolerance of every rank and zero decision (documented in each public function).
DEFAULT_RTOL = 1e-9

Array = np.ndarray

if TYPE_CHECKING:
    import sympy


def sympy_module() -> Any:
    """The :mod:`sympy` module, imported on first use: ``import screwkit`` does not import sympy.

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

    Examples
    --------
    >>> infinity(symbolic=True), infinity(symbolic=False)
    (oo, inf)
    """
    return sympy_module().oo if symbolic else math.inf


def is_infinite(value: Any) -> bool:
    """True for ``math.inf``, ``-math.inf``, ``sympy.oo`` or ``-sympy.oo`` (a scalar).

    Examples
    --------
    >>> import sympy
    >>> is_infinite(sympy.oo), is_infinite(float("inf")), is_infinite(sympy.Symbol("h")), is_infinite(2.0)
    (True, True, False, False)
    """
    if is_symbolic(value):
        return bool(value.is_infinite)
    return bool(np.isinf(value))


def is_exactly_zero(value: Any) -> bool:
    """Exact zero test of a scalar: ``value == 0`` for numbers, ``simplify(value) == 0`` for sympy.

    Unlike :func:`is_zero`, a symbolic value that depends on symbols is *generically* decided
    (``x`` is not zero) rather than refused; no tolerance is involved.

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

    A numeric vector is first scaled by a power of two (exact; :func:`direction_scaled`), so that a
    vector whose squared length underflows (a 1e-170 axis) or overflows still gets its unit vector
    (for other vectors the same bits as dividing by the norm). A symbolic direction stays
    polynomial (no ``sqrt``): its length is a generic non-zero factor, and every use of a direction
    in a screw system is projective in it.

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


def ratio(numerator: Any, denominator: Any) -> Any:
    """``numerator / denominator`` elementwise, infinity where the denominator is exactly zero.

    Numeric: float64 (a float for scalars); symbolic: simplified quotients or ``sympy.oo``, decided
    by :func:`is_exactly_zero`.

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


def sqrt(value: Any) -> Any:
    """Square root: :func:`numpy.sqrt`, or ``sympy.sqrt`` elementwise when symbolic.

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


def direction_scaled(s: Array, s0: Array) -> tuple[Array, Array]:
    """Numeric ``(s, s0)`` times a power of two (exact) per screw so that ``|s|`` lies in [0.5, 2):
    ``s·s`` then neither underflows (a 1e-170 axis) nor overflows. Symbolic values are returned as
    they are (exact arithmetic has no range). Quotients homogeneous in ``(s, s0)`` (pitch, axis
    point) are unchanged.

    Examples
    --------
    >>> direction_scaled(np.array([0.0, 0, 8.0]), np.array([1.0, 0, 0]))
    (array([0. , 0. , 0.5]), array([0.0625, 0.    , 0.    ]))
    """
    if is_symbolic(s, s0):
        return s, s0
    shift = _binary_exponents(s)
    return np.ldexp(s, -shift), np.ldexp(s0, -shift)


def _binary_exponents(vectors: Array) -> Array:
    """The binary exponent of each vector's largest component (last axis kept; 0 for a zero vector):
    ``vector · 2^-exponent`` has its largest component in [0.5, 1)."""
    largest = np.max(np.abs(vectors), axis=-1, keepdims=True)
    return np.frexp(np.where(largest > 0, largest, 1.0))[1]


def unit_screws(screws: Array, length_scale: float) -> Array:
    """Numeric screws ``(..., 6)`` with the moment divided by ``length_scale`` and scaled to unit
    length, for tolerance decisions; symbolic screws unchanged (their decisions are exact).

    Raises
    ------
    DegenerateGeometryError
        For a zero screw (numeric, or identically zero).
    ScrewkitValueError
        For a length scale that is not a positive finite number (in either branch).

    Examples
    --------
    >>> unit_screws(np.array([0.0, 0, 2, 0, 0, 4]), 2.0)
    array([0.        , 0.        , 0.70710678, 0.        , 0.        , 0.70710678])
    """
    checked_length_scale(length_scale)
    if is_symbolic(screws):
        if np.any(zero_vectors(screws)):
            raise DegenerateGeometryError("Expected non-zero screws, got the zero screw.")
        return screws
    scaled = np.array(screws, dtype=float)
    scaled[..., 3:] /= length_scale
    largest = np.max(np.abs(scaled), axis=-1, keepdims=True)
    if np.any(largest == 0):
        raise DegenerateGeometryError("Expected non-zero screws, got the zero screw.")
    scaled = np.ldexp(scaled, -np.frexp(largest)[1])  # exact: the norm neither underflows nor overflows
    return scaled / np.linalg.norm(scaled, axis=-1, keepdims=True)


def check_rotation(rotation: Array, name: str = "rotation") -> None:
    """Refuse numeric matrices ``(..., 3, 3)`` that are not proper rotations (``RᵀR = I`` to 1e-9,
    ``det R > 0``). Symbolic matrices are taken as given: their entries may obey relations the
    symbols do not state (``c² + s² = 1`` for ``c``, ``s`` standing for a cosine and a sine), and
    proving trigonometric identities costs up to a second a matrix.

    Raises
    ------
    ScrewkitValueError
        Naming the argument and the determinant.

    Examples
    --------
    >>> import sympy
    >>> c, s = sympy.symbols("c s")
    >>> check_rotation(np.eye(3)), check_rotation(np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]))
    (None, None)
    >>> check_rotation(np.diag([1.0, 1, -1]))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `rotation` to be a proper rotation ..., got det = -1.0.
    """
    if is_symbolic(rotation):
        return
    product = np.swapaxes(rotation, -1, -2) @ rotation
    if not (np.allclose(product, np.eye(3), atol=1e-9) and np.all(np.linalg.det(rotation) > 0)):
        raise ScrewkitValueError(
            f"Expected `{name}` to be a proper rotation matrix (R^T R = I, det R = +1), "
            f"got det = {np.linalg.det(rotation)}."
        )


def plain(value: Any) -> float | str:
    """A JSON-ready scalar: a float for a number, the text of a sympy expression.

    Examples
    --------
    >>> import sympy
    >>> plain(np.float64(2.5)), plain(sympy.Symbol("x") / 2)
    (2.5, 'x/2')
    """
    return str(value) if is_symbolic(value) else float(value)


def float_lists(**values: Any) -> dict[str, Any]:
    """Numeric values as JSON-ready float lists by name; ``{}`` when any value is symbolic.

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

    Examples
    --------
    >>> import sympy
    >>> zeros_like(np.array([sympy.Symbol("x")], dtype=object))
    array([0], dtype=object)
    """
    return a * 0 if is_symbolic(a) else np.zeros_like(a, dtype=float)


def ones_like(a: Array) -> Array:
    """Ones of ``a``'s shape in its branch: float64 ones, or exact sympy ones in an object array.

    Examples
    --------
    >>> ones_like(np.zeros(2))
    array([1., 1.])
    """
    return a * 0 + to_sympy(1) if is_symbolic(a) else np.ones_like(a, dtype=float)


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
            array = np.array(value, dtype=float)
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

    Examples
    --------
    >>> import sympy
    >>> a, b = as_arrays((3,), ([1, 2, 3], "p"), ([0, sympy.Symbol("t"), 0], "q"))
    >>> a.dtype, b[1]
    (dtype('O'), t)
    """
    return promote(*(as_array(value, name, shape) for value, name in named))


@overload
def checked_length_scale(value: Any, *, allow_none: Literal[False] = False) -> float: ...


@overload
def checked_length_scale(value: Any, *, allow_none: Literal[True]) -> float | None: ...


def checked_length_scale(value: Any, *, allow_none: bool = False) -> float | None:
    """Validate a characteristic length: a number in [:data:`MIN_LENGTH_SCALE`, 1 /
    :data:`MIN_LENGTH_SCALE`] (or None where a default exists).

    Examples
    --------
    >>> checked_length_scale(2)
    2.0
    >>> checked_length_scale(0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `length_scale` to be a positive ..., got 0.
    """
    if value is None and allow_none:
        return None
    ok = isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)
    if not (ok and np.isfinite(value) and MIN_LENGTH_SCALE <= value <= 1 / MIN_LENGTH_SCALE):
        expected = f"a positive finite number in [{MIN_LENGTH_SCALE:g}, {1 / MIN_LENGTH_SCALE:g}]"
        raise ScrewkitValueError(
            f"Expected `length_scale` to be {expected}{' or None' if allow_none else ''}, got {value!r}."
        )
    return float(value)


#: The smallest characteristic length accepted, and its inverse the largest, in length units:
#: moments are divided by it, and coordinates are at most 1e100 (README, input rules).
MIN_LENGTH_SCALE = 1e-100


def is_dof(value: Any) -> bool:
    """True for an integer (Python or numpy, not a boolean) from 0 to 6: a mobility.

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

    Examples
    --------
    >>> dot(np.array([1.0, 2, 3]), np.array([4.0, 5, 6]))
    np.float64(32.0)
    >>> dot(np.array([1.0, 2, 3]), np.array([4.0, 5, 6]), keepdims=True)
    array([32.])
    """
    return (a * b).sum(axis=-1, keepdims=keepdims)


def norm(a: Array) -> Array:
    """Euclidean norm over the last axis (``sympy.sqrt`` of the sum of squares when symbolic).

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
    return np.linalg.norm(a, axis=-1)


def det(matrix: Array) -> Any:
    """Determinant of a square matrix over the last two axes (batched when numeric).

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


def scale_moments(rows: Array, length_scale: float | None) -> tuple[Array, float]:
    """Divide the moment half of screws ``(..., 6)`` by a characteristic length.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)
    length_scale : float or None
        The characteristic length; None derives it from the data (see the module docstring).

    Returns
    -------
    scaled : numpy.ndarray, shape (..., 6)
    length_scale : float
        The length actually used.

    Examples
    --------
    >>> scale_moments(np.array([[1.0, 0, 0, 0, 0, 500.0]]), None)[1]
    500.0
    """
    if length_scale is None:
        directions = np.linalg.norm(rows[..., :3], axis=-1)
        moments = np.linalg.norm(rows[..., 3:], axis=-1)
        has_direction = directions > DEFAULT_RTOL * moments  # a couple's round-off direction is not one
        ratios = moments[has_direction] / directions[has_direction]
        length = float(ratios.max()) if ratios.size and ratios.max() > 0 else 1.0
    else:
        checked = checked_length_scale(length_scale, allow_none=True)  # its message mentions None
        assert checked is not None  # None took the branch above
        length = checked
    scaled = np.array(rows, dtype=float)
    scaled[..., 3:] /= length
    return scaled, length


def characteristic_length(rows: Array, length_scale: float | None) -> float | None:
    """The length a numeric rank decision on ``rows`` uses (:func:`scale_moments`); symbolic rows
    keep ``length_scale`` as given (their decisions are exact and need none).

    Examples
    --------
    >>> import sympy
    >>> characteristic_length(np.array([[1.0, 0, 0, 0, 0, 500.0]]), None)
    500.0
    >>> characteristic_length(np.array([[sympy.Symbol("a"), 0, 0, 0, 0, 1]], dtype=object), None) is None
    True
    """
    if is_symbolic(rows):
        return length_scale
    return scale_moments(rows, length_scale)[1]


#: The coarsest relative tolerance accepted for a rank or zero decision. Beyond it the decisions
#: of a system and of its reciprocal stop agreeing: at ``rtol = 0.3`` the H4's default pose reads
#: a 3T3R platform and a global wrench system of order 3 (a 4-DOF robot), and coarser values give
#: negative freedom counts; up to 0.1 every catalog robot keeps a consistent 3T1R (2T1R) platform.
MAX_RTOL = 0.1

#: The finest relative tolerance the command line accepts (its analyses are in floats). Below it a
#: rank decision reads round-off as rank: at ``rtol = 0`` the H4's default pose reads a constraint +
#: serial singularity of constraint order 0/2, at 1e-16 a 3R1T platform; at 1e-14 the McGill SMG's
#: verdicts differ from those at the default 1e-9 on 58 of 2,000 random workspace poses, at 1e-13 no
#: catalog robot's do. 1e-12 keeps a factor of 10 from that edge. (The API keeps ``[0, MAX_RTOL]``:
#: ``rtol = 0`` is exact for sympy rows.)
MIN_FLOAT_RTOL = 1e-12


def checked_rtol(value: Any, name: str = "rtol") -> float:
    """A relative tolerance: a real number in ``[0, MAX_RTOL]`` (:data:`MAX_RTOL` = 0.1).

    Examples
    --------
    >>> checked_rtol(1e-6)
    1e-06
    >>> checked_rtol(0.5)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `rtol` to be a number in [0, 0.1], got 0.5.
    """
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ScrewkitTypeError(f"Expected `{name}` to be a number in [0, {MAX_RTOL:g}], got {value!r}.")
    if not 0 <= float(value) <= MAX_RTOL:
        raise ScrewkitValueError(f"Expected `{name}` to be a number in [0, {MAX_RTOL:g}], got {value!r}.")
    return float(value)


def screw_singular_values(rows: Array, *, length_scale: float | None = None) -> Array:
    """Singular values of screws ``(..., k, 6)`` after moment scaling and row normalisation.

    The largest is between 1 and sqrt(k); their ratios are frame-sensitive but unit-invariant.
    Zero rows are kept as zero rows. Batched over leading axes.

    Examples
    --------
    >>> screw_singular_values(np.array([[1.0, 0, 0, 0, 0, 0], [0, 1.0, 0, 0, 0, 0]]))
    array([1., 1.])
    """
    scaled, _ = scale_moments(np.asarray(rows, dtype=float), length_scale)
    lengths = np.linalg.norm(scaled, axis=-1, keepdims=True)
    safe = np.where(lengths > 0, lengths, 1.0)
    return np.linalg.svd(scaled / safe, compute_uv=False)


def screw_rank(rows: Array, *, rtol: float = DEFAULT_RTOL, length_scale: float | None = None) -> Any:
    """Rank of a set of screws ``(..., k, 6)``: numeric at a pose, generic when symbolic.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
    rtol : float, default 1e-9
        Singular values at most ``rtol`` times the largest count as zero.
    length_scale : float or None
        See the module docstring.

    Returns
    -------
    int or numpy.ndarray of int
        Batched over leading axes when numeric. The symbolic rank is the *generic* rank, decided
        exactly at a random rational point (Schwartz–Zippel, :mod:`screwkit.algebra.symbolic`): it says
        nothing about special values of the symbols.

    Examples
    --------
    >>> screw_rank(np.zeros((0, 6)))
    0
    """
    checked_rtol(rtol)
    if rows.dtype == object:
        from . import symbolic

        return symbolic.generic_rank(rows.reshape(-1, rows.shape[-1])) if rows.size else 0
    if rows.shape[-2] == 0:
        return 0 if rows.ndim == 2 else np.zeros(rows.shape[:-2], dtype=int)
    values = screw_singular_values(rows, length_scale=length_scale)
    largest = values[..., :1]
    counted = (values > rtol * largest) & (largest > 0)
    result = counted.sum(axis=-1)
    return int(result) if np.ndim(result) == 0 else result


_SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


def screw_nullspace(
    rows: Array,
    *,
    rtol: float = DEFAULT_RTOL,
    length_scale: float | None = None,
) -> Array:
    """Basis of the screws reciprocal to every row of ``rows`` (shape ``(k, 6)``).

    Parameters
    ----------
    rows : numpy.ndarray, shape (k, 6)
    rtol, length_scale
        As in :func:`screw_rank`.

    Returns
    -------
    numpy.ndarray, shape (6 - rank, 6)
        Numeric rows are an orthonormal basis in scaled coordinates, mapped back to the caller's
        unit; symbolic rows the generic null space (:func:`matrix_nullspace`).

    Examples
    --------
    >>> screw_nullspace(np.array([[0.0, 0, 0, 0, 0, 1]])).shape
    (5, 6)
    """
    checked_rtol(rtol)
    if rows.dtype == object:
        if rows.shape[0] == 0:
            return np.array(sympy_module().eye(6).tolist(), dtype=object)
        return matrix_nullspace(rows @ _SWAP.astype(int), rtol=rtol)
    if rows.shape[0] == 0:
        return np.eye(6)
    scaled, length = scale_moments(rows, length_scale)
    lengths = np.linalg.norm(scaled, axis=-1, keepdims=True)
    scaled = scaled / np.where(lengths > 0, lengths, 1.0)
    basis = matrix_nullspace(scaled @ _SWAP, rtol=rtol)
    # In scaled coordinates x' = (x_s; x_m / L); reciprocity a∘x = L (a'∘x') is preserved.
    basis[:, 3:] *= length
    return basis


def screw_image_of_nullspace(
    mapping: Array, constraints: Array, *, rtol: float, length_scale: float
) -> Array:
    """The screws ``mapping @ x`` for ``x`` in the null space of ``constraints``: e.g. the platform
    twists a loop-closure matrix allows, with ``mapping`` the joint screws along a path to it.

    Parameters
    ----------
    mapping : numpy.ndarray, shape (6, n)
        Screw columns.
    constraints : numpy.ndarray, shape (6 m, n)
        Stacked screw rows (m blocks of 6; m may be 0).
    rtol : float
    length_scale : float
        Moments are divided by it before any numeric decision (module docstring).

    Returns
    -------
    numpy.ndarray, shape (k, 6)
        Numeric: an orthogonal basis of the image in scaled coordinates, moments scaled back. Columns
        are scaled to unit size first, and the image's rank is decided relative to the size of the
        mapping's columns, not to the image itself: internal motions (a rod spinning between two S
        joints) map to round-off, not to a screw. Symbolic: the images of an exact (generic) null
        space basis, not reduced to a basis.

    Examples
    --------
    >>> spin = np.array([[0.0], [0], [1], [0], [0], [0]])  # a free rotation about z, no loop
    >>> screw_image_of_nullspace(spin, np.zeros((0, 1)), rtol=1e-9, length_scale=1.0)
    array([[0., 0., 1., 0., 0., 0.]])
    """
    checked_rtol(rtol)
    n = mapping.shape[1]
    if mapping.dtype == object or constraints.dtype == object:
        rates = (
            matrix_nullspace(constraints, rtol=rtol)
            if constraints.shape[0]
            else np.eye(n, dtype=int) + zeros((n, n), symbolic=True)
        )
        return (mapping @ rates.T).T
    scaled = constraints.copy()
    scaled.reshape(-1, 6, n)[:, 3:, :] /= length_scale
    scaled_mapping = mapping.copy()
    scaled_mapping[3:] /= length_scale
    column_norm = np.linalg.norm(np.vstack([scaled, scaled_mapping]), axis=0)
    scaled = scaled.reshape(-1, n) if scaled.size else np.zeros((0, n))
    column_norm[column_norm == 0] = 1.0
    scaled_mapping = scaled_mapping / column_norm
    rates = matrix_nullspace(scaled / column_norm, rtol=rtol)  # orthonormal, in scaled coordinates
    u, values, _ = np.linalg.svd(scaled_mapping @ rates.T, full_matrices=False)
    keep = values > rtol * np.linalg.norm(scaled_mapping, 2)
    image = (u[:, keep] * values[keep]).T
    image[:, 3:] *= length_scale
    return image


def matrix_nullspace(matrix: Array, *, rtol: float = DEFAULT_RTOL) -> Array:
    """Basis of ``{x : matrix @ x = 0}`` as rows, for any ``(m, n)`` matrix.

    Numeric: the right singular vectors whose singular values are at most ``rtol`` times the
    largest (an orthonormal basis). Symbolic: the generic null space by Cramer's rule on a pivot
    block chosen at an exact random point (:mod:`screwkit.algebra.symbolic`), each vector primitive. The
    caller
    scales rows beforehand if they carry different units (row scaling keeps the null space).

    Examples
    --------
    >>> matrix_nullspace(np.array([[1.0, 1.0]]))
    array([[-0.70710678,  0.70710678]])
    """
    checked_rtol(rtol)
    if matrix.dtype == object:
        from . import symbolic

        return symbolic.nullspace(matrix)
    if matrix.shape[0] == 0:
        return np.eye(matrix.shape[1])
    _, values, vt = np.linalg.svd(matrix)
    rank = int(((values > rtol * values[:1]) & (values[:1] > 0)).sum())
    return vt[rank:].copy()
