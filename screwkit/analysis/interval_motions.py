"""Rigid motions, screws and determinants over interval enclosures, for the loop-closure enclosure
(:mod:`screwkit.analysis.loop_closure_enclosure`).

Scalars are :class:`~screwkit.analysis.intervals.Enclosure` or None, None standing for an *exact*
zero (a structural zero: the planar mechanisms' out-of-plane components stay None through every
product, so their loop equations are read off exactly). A constant is a pair ``(lo, hi)`` of floats
(None for an exact zero), made into an enclosure of a batch's shape by :func:`lifted`.

* :func:`rodrigues`: ``exp([r]×) = I + f₁(s) [r]× + f₂(s) [r]×²``, ``s = |r|²``, with
  ``f₁ = sin √s / √s = Σ (-s)^k / (2k + 1)!`` and ``f₂ = (1 - cos √s)/s = Σ (-s)^k / (2k + 2)!``
  (Murray, Li & Sastry, *A Mathematical Introduction to Robotic Manipulation*, 1994, Eq. 2.14),
  summed to ``N <=`` :data:`SERIES_TERMS` terms (the fewest whose remainder bound is below 1e-18
  over the batch) by Horner's rule in interval arithmetic plus the alternating series' remainder,
  bounded by its first omitted term (its terms decrease from there on while
  ``s < (2N + 4)(2N + 5)``): no division by an angle that may vanish. One rotation coordinate
  about an axis is turned by its cosine and sine instead.
* :func:`screw_exponential`: ``exp(ŝ θ)`` of a unit screw ``(ω; v)``,
  ``(I + sin θ K + (1 - cos θ) K², θ ω (ω·v) - sin θ K (ω × v) - (1 - cos θ) K² (ω × v))`` with
  ``K = [ω]×``, and ``(I, v θ)`` for a slider (Murray, Li & Sastry 1994, Eqs. 2.14 and 2.36).
* :func:`adjoint`: ``(R ω; R v + p × R ω)`` (Murray, Li & Sastry 1994, Eq. 2.58).
* :func:`determinant` and :func:`cofactors` by Laplace expansion along the rows, every minor of the
  rows above computed once (``n 2ⁿ⁻¹`` products for an ``n × n`` determinant, no division: no
  interval Gaussian elimination).

Examples
--------
>>> r = [Enclosure(np.array([0.0]), np.array([0.0])), None, Enclosure(np.array([0.3]), np.array([0.3]))]
>>> rotation = rodrigues(r)
>>> bool(abs(rotation[0][0].lo[0] - np.cos(0.3)) < 1e-14), float(rotation[2][2].lo[0])
(True, 1.0)
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from .intervals import Enclosure
from .limb_enclosures import _cross, _dot, _mul, _sub, _sum

__all__ = [
    "SERIES_TERMS",
    "adjoint",
    "applied",
    "cofactors",
    "compose",
    "constant_of",
    "determinant",
    "exponential_constants",
    "identity",
    "lifted",
    "rodrigues",
    "screw_exponential",
    "subtract",
    "transposed_product",
]

Scalar = Enclosure | None
Vector = list[Enclosure | None]
Matrix = list[list[Enclosure | None]]
Constant = tuple[Any, Any] | None

#: Terms of the series of ``f₁`` and ``f₂`` in :func:`rodrigues`.
SERIES_TERMS = 14


def constant_of(enclosure: Scalar) -> Constant:
    """The ``(lo, hi)`` of a one-box enclosure (None for an exact zero).

    Parameters
    ----------
    enclosure : Enclosure or None
        Of one box.

    Returns
    -------
    tuple of float, or None

    Examples
    --------
    >>> constant_of(Enclosure(np.array([1.0]), np.array([2.0])))
    (1.0, 2.0)
    """
    if enclosure is None:
        return None
    return float(enclosure.lo[0]), float(enclosure.hi[0])


def lifted(value: Any, batch: Any) -> Scalar:
    """A constant ``(lo, hi)`` or a values-only enclosure as a *fixed* enclosure of ``batch`` boxes:
    no gradient arrays, a zero gradient wherever it meets an enclosure that has one.

    Parameters
    ----------
    value : tuple of float or of arrays (g,), Enclosure or None
        Arrays: one constant per member of a group.
    batch : int or numpy.ndarray of int
        The number of boxes, or each box's member (the index into the arrays).

    Returns
    -------
    Enclosure or None

    Examples
    --------
    >>> c = lifted((1.0, 1.0), 2)
    >>> c.lo.tolist(), c.fixed
    ([1.0, 1.0], True)
    """
    if value is None:
        return None
    members = np.zeros(batch, dtype=int) if np.ndim(batch) == 0 else np.asarray(batch)
    if isinstance(value, Enclosure):
        lo, hi = np.broadcast_to(value.lo, members.shape), np.broadcast_to(value.hi, members.shape)
    else:  # one constant, or one per member
        lo = np.atleast_1d(np.asarray(value[0], float))[members if np.ndim(value[0]) else 0 * members]
        hi = np.atleast_1d(np.asarray(value[1], float))[members if np.ndim(value[1]) else 0 * members]
    return Enclosure(lo, hi, fixed=True)  # a zero gradient wherever it meets one


def identity(like: Enclosure) -> Matrix:
    """The 3 × 3 identity in the shape of ``like``: exact ones, exact zeros (None).

    Parameters
    ----------
    like : Enclosure

    Returns
    -------
    list of 3 lists of 3 Enclosure or None

    Examples
    --------
    >>> eye = identity(Enclosure(np.zeros(2), np.ones(2)))
    >>> eye[0][0].lo.tolist(), eye[0][1]
    ([1.0, 1.0], None)
    """
    ones = np.ones_like(like.lo)
    one = Enclosure(ones, ones, fixed=True)
    return [[one if i == j else None for j in range(3)] for i in range(3)]


def _negated(x: Scalar) -> Scalar:
    return None if x is None else -x


def _hat(w: Vector) -> Matrix:
    return [[None, _negated(w[2]), w[1]], [w[2], None, _negated(w[0])], [_negated(w[1]), w[0], None]]


def _product(a: Matrix, b: Matrix) -> Matrix:
    return [[_sum(*(_mul(a[i][k], b[k][j]) for k in range(3))) for j in range(3)] for i in range(3)]


def _apply(a: Matrix, v: Vector) -> Vector:
    return [_sum(*(_mul(a[i][k], v[k]) for k in range(3))) for i in range(3)]


def _terms(top: float) -> int:
    """The fewest terms (at most :data:`SERIES_TERMS`) whose remainder bound is below 1e-18 for
    ``s <= top``."""
    for n in range(2, SERIES_TERMS):
        if top ** (n + 1) / math.factorial(2 * n + 3) < 1e-18:
            return n
    return SERIES_TERMS


def _series(s: Enclosure, first: int) -> Enclosure:
    """``Σ_k (-s)^k / (2k + first)!`` for ``s >= 0`` (``first`` 1 or 2), with its remainder."""
    top_all = float(np.max(s.hi)) if len(s.hi) else 0.0
    n = _terms(top_all) if np.isfinite(top_all) else SERIES_TERMS
    acc: Enclosure | None = None
    for k in range(n, -1, -1):
        coefficient = (-1.0) ** k / math.factorial(2 * k + first)
        term = Enclosure.constant(coefficient, s, relative=2.0**-50)
        acc = term if acc is None else acc * s + term
    assert acc is not None
    top = np.maximum(s.hi, 0.0)
    with np.errstate(over="ignore"):
        bound = np.nextafter(top ** (n + 1) / math.factorial(2 * n + 2 + first), np.inf) * (1.0 + 2.0**-40)
    bound = np.where(top < (2 * n + 4) * (2 * n + 5), bound, np.inf)
    return acc + Enclosure(
        -bound,
        bound,
        None if s.glo is None else np.zeros_like(s.glo),
        None if s.glo is None else np.zeros_like(s.glo),
    )


def _identity_plus(*terms: Matrix) -> Matrix:
    """``I + Σ terms``, the diagonal's 1 exact."""
    like = next(x for t in terms for row in t for x in row if x is not None)
    one = Enclosure.constant(1.0, like)
    return [[_sum(one if i == j else None, *(t[i][j] for t in terms)) for j in range(3)] for i in range(3)]


def _scaled_matrix(c: Enclosure, m: Matrix) -> Matrix:
    return [[_mul(c, x) for x in row] for row in m]


def rodrigues(r: Vector) -> Matrix:
    """``exp([r]×)`` of rotation vectors over a batch (module docstring).

    Parameters
    ----------
    r : list of 3 Enclosure or None
        At least one not None.

    Returns
    -------
    list of 3 lists of 3 Enclosure or None

    Examples
    --------
    >>> r = [None, None, Enclosure(np.array([0.5]), np.array([0.5]))]
    >>> m = rodrigues(r)
    >>> bool(m[0][0].lo[0] <= np.cos(0.5) <= m[0][0].hi[0]), m[0][2] is None
    (True, True)
    """
    present = [i for i, x in enumerate(r) if x is not None]
    if len(present) == 1:  # about one axis: its cosine and sine, the rest exact
        axis = present[0]
        cos, sin = r[axis].cos_sin()  # type: ignore[union-attr]
        one = Enclosure.constant(1.0, cos)
        after, last = (axis + 1) % 3, (axis + 2) % 3
        out: Matrix = [[None] * 3 for _ in range(3)]
        out[axis][axis], out[after][after], out[last][last] = one, cos, cos
        out[last][after], out[after][last] = sin, -sin
        return out
    s = _sum(*(None if x is None else x.square() for x in r))
    assert s is not None
    k = _hat(r)
    return _identity_plus(_scaled_matrix(_series(s, 1), k), _scaled_matrix(_series(s, 2), _product(k, k)))


def screw_exponential(
    constants: dict[str, Any], theta: Enclosure, members: Any = None
) -> tuple[Matrix, Vector]:
    """``exp(ŝ θ)`` from a screw's constants (:func:`exponential_constants`) over a batch.

    Parameters
    ----------
    constants : dict
        ``"K"``, ``"K2"``, ``"c0"``, ``"b1"``, ``"b2"`` (a rotation) or ``"v"`` (a slider).
    theta : Enclosure
    members : numpy.ndarray of int, optional
        Each box's member, for constants given per member (:func:`lifted`).

    Returns
    -------
    rotation : list of lists of Enclosure or None
    translation : list of Enclosure or None

    Examples
    --------
    >>> w = [None, None, Enclosure(np.array([1.0]), np.array([1.0]))]
    >>> v = [None, Enclosure(np.array([-1.0]), np.array([-1.0])), None]   # the z axis through x = 1
    >>> theta = Enclosure(np.array([np.pi / 2]), np.array([np.pi / 2]))
    >>> _, p = screw_exponential(exponential_constants(w, v), theta)
    >>> [round(float(e.lo[0]), 12) for e in p[:2]]                          # the origin turns to (1, -1)
    [1.0, -1.0]
    """
    batch = len(theta.lo) if members is None else members
    if "v" in constants:
        return identity(theta), [_mul(theta, lifted(c, batch)) for c in constants["v"]]
    cos, sin = theta.cos_sin()
    versine = cos * -1.0 + 1.0

    def lift(m: Any) -> Any:
        if isinstance(m, list):
            return [lift(x) for x in m]
        return lifted(m, batch)

    rotation = _identity_plus(
        _scaled_matrix(sin, lift(constants["K"])), _scaled_matrix(versine, lift(constants["K2"]))
    )
    translation = [
        _sum(
            _mul(theta, lifted(c0, batch)),
            _mul(sin, lifted(b1, batch)),
            _mul(versine, lifted(b2, batch)),
        )
        for c0, b1, b2 in zip(constants["c0"], constants["b1"], constants["b2"], strict=True)
    ]
    return rotation, translation


def exponential_constants(w: Vector, v: Vector) -> dict[str, Any]:
    """The constants of ``exp(ŝ θ)`` (:func:`screw_exponential`) of a unit screw ``(ω; v)`` given by
    one-box enclosures, computed in interval arithmetic.

    Parameters
    ----------
    w, v : list of 3 Enclosure or None
        ``ω`` all None for a slider.

    Returns
    -------
    dict
        ``(lo, hi)`` constants (None: exact zero).

    Examples
    --------
    >>> one = Enclosure(np.array([1.0]), np.array([1.0]))
    >>> exponential_constants([None] * 3, [one, None, None])["v"]
    [(1.0, 1.0), None, None]
    """
    if all(x is None for x in w):
        return {"v": [constant_of(x) for x in v]}
    k = _hat(w)
    k2 = _product(k, k)
    moment = _cross(w, v)
    along = _dot(w, v)
    return {
        "K": [[constant_of(x) for x in row] for row in k],
        "K2": [[constant_of(x) for x in row] for row in k2],
        "c0": [constant_of(_mul(x, along)) for x in w],
        "b1": [constant_of(_negated(x)) for x in _apply(k, moment)],
        "b2": [constant_of(_negated(x)) for x in _apply(k2, moment)],
    }


def compose(a: tuple[Matrix, Vector] | None, b: tuple[Matrix, Vector]) -> tuple[Matrix, Vector]:
    """``a b`` of rigid displacements ``(R, p)`` (None: the identity).

    Parameters
    ----------
    a : tuple or None
    b : tuple

    Returns
    -------
    tuple of rotation and translation

    Examples
    --------
    >>> one = Enclosure(np.array([1.0]), np.array([1.0]))
    >>> eye = identity(one)
    >>> _, p = compose((eye, [one, None, None]), (eye, [None, one, None]))
    >>> [None if x is None else float(x.lo[0]) for x in p]
    [1.0, 1.0, None]
    """
    if a is None:
        return b
    return _product(a[0], b[0]), [_sum(x, y) for x, y in zip(_apply(a[0], b[1]), a[1], strict=True)]


def adjoint(g: tuple[Matrix, Vector] | None, w: Vector, v: Vector) -> Vector:
    """The screw ``(ω; v)`` carried by the displacement ``g``: ``(R ω; R v + p × R ω)``.

    Parameters
    ----------
    g : tuple or None
        None: the identity.
    w, v : list of 3 Enclosure or None

    Returns
    -------
    list of 6 Enclosure or None

    Examples
    --------
    >>> one = Enclosure(np.array([1.0]), np.array([1.0]))
    >>> eye = identity(one)
    >>> s = adjoint((eye, [one, None, None]), [None, None, one], [None] * 3)   # z axis moved to x = 1
    >>> [None if x is None else float(x.lo[0]) for x in s]
    [None, None, 1.0, None, -1.0, None]
    """
    if g is None:
        return [*w, *v]
    turned = _apply(g[0], w)
    return [*turned, *(_sum(x, y) for x, y in zip(_apply(g[0], v), _cross(g[1], turned), strict=True))]


def _minors(rows: list[Vector], columns: int) -> dict[tuple[int, ...], Scalar]:
    """The minors of all the rows over every set of as many columns (Laplace along the last row)."""
    level: dict[tuple[int, ...], Scalar] = {(j,): rows[0][j] for j in range(columns)}
    for r in range(1, len(rows)):
        nxt: dict[tuple[int, ...], Scalar] = {}
        for subset in itertools.combinations(range(columns), r + 1):
            terms = []
            for t, j in enumerate(subset):
                term = _mul(rows[r][j], level[subset[:t] + subset[t + 1 :]])
                terms.append(term if (r + t) % 2 == 0 else _negated(term))
            nxt[subset] = _sum(*terms)
        level = nxt
    return level


def determinant(rows: list[Vector]) -> Scalar:
    """The determinant of a square matrix of enclosures (module docstring).

    Parameters
    ----------
    rows : list of n lists of n Enclosure or None

    Returns
    -------
    Enclosure or None

    Examples
    --------
    >>> e = lambda x: Enclosure(np.array([x]), np.array([x]))
    >>> float(determinant([[e(1.0), e(2.0)], [e(3.0), e(4.0)]]).lo[0])
    -2.0
    """
    return _minors(rows, len(rows))[tuple(range(len(rows)))]


def cofactors(rows: list[Vector]) -> Vector:
    """The vector ``c`` with ``c·t = det[rows; t]`` for ``n - 1`` rows of ``n`` enclosures: it is
    orthogonal to every row (their generalised cross product).

    Parameters
    ----------
    rows : list of n - 1 lists of n Enclosure or None

    Returns
    -------
    list of n Enclosure or None

    Examples
    --------
    >>> e = lambda x: Enclosure(np.array([x]), np.array([x]))
    >>> [float(c.lo[0]) for c in cofactors([[e(1.0), e(0.0), e(0.0)], [e(0.0), e(1.0), e(0.0)]])[2:]]
    [1.0]
    """
    n = len(rows) + 1
    minors = _minors(rows, n)
    out = []
    for i in range(n):
        minor = minors[tuple(j for j in range(n) if j != i)]
        out.append(minor if (n - 1 + i) % 2 == 0 else _negated(minor))
    return out


def transposed_product(a: Matrix, b: Matrix) -> Matrix:
    """``a bᵀ``.

    Parameters
    ----------
    a, b : list of lists of Enclosure or None

    Returns
    -------
    list of lists of Enclosure or None

    Examples
    --------
    >>> one = Enclosure(np.array([1.0]), np.array([1.0]))
    >>> eye = identity(one)
    >>> transposed_product(eye, eye)[0][1] is None
    True
    """
    return [[_sum(*(_mul(a[i][k], b[j][k]) for k in range(3))) for j in range(3)] for i in range(3)]


def applied(a: Matrix, v: Vector) -> Vector:
    """``a v``.

    Parameters
    ----------
    a : list of lists of Enclosure or None
    v : list of Enclosure or None

    Returns
    -------
    list of Enclosure or None
        (exact zeros stay None)

    Examples
    --------
    >>> two = Enclosure(np.array([2.0]), np.array([2.0]))
    >>> applied(identity(two), [None, two, None])[1].lo.tolist()
    [2.0]
    """
    return _apply(a, v)


def subtract(a: Vector, b: Vector) -> Vector:
    """``a - b`` componentwise.

    Parameters
    ----------
    a, b : list of Enclosure or None

    Returns
    -------
    list of Enclosure or None

    Examples
    --------
    >>> one = Enclosure(np.array([1.0]), np.array([1.0]))
    >>> subtract([one, None], [one, one])[1].hi.tolist()
    [-1.0]
    """
    return [_sub(x, y) for x, y in zip(a, b, strict=True)]
