"""Exact proofs at random integer configurations (Schwartz–Zippel): that a bracket polynomial is a
constant times a vector form (:func:`prove_proportional`), or a constant times the superbracket
of six lines (:func:`is_superbracket`), by exact integer evaluation of both sides, with no symbolic
expansion (a general Gough–Stewart factor takes a second, not minutes).

Examples
--------
>>> import sympy
>>> from screwkit.gca import Bracket, BracketPolynomial
>>> from screwkit.gca.vector_forms import VectorCross, VectorDot
>>> i, k, j = sympy.symbols("i k j")
>>> kinds = PointKinds("g", "ijk")
>>> prove_proportional(BracketPolynomial([Bracket("gikj")]), VectorDot(VectorCross(i, k), j), kinds)
Fraction(-1, 1)
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence
from fractions import Fraction

import numpy as np
import sympy

from ..algebra import projective as P
from ..exceptions import ScrewkitValueError
from .brackets import BracketPolynomial
from .vector_forms import PointKinds, form_value

__all__ = [
    "PROOF_CHECKS",
    "PROOF_RANGE",
    "is_irreducible_in_points",
    "is_superbracket",
    "prove_proportional",
    "random_configuration",
]

#: Coordinates of the random configurations are integers in [−PROOF_RANGE, PROOF_RANGE].
PROOF_RANGE = 2**31
#: Configurations that must agree after the one that fixes the constant.
PROOF_CHECKS = 2


def _exact_det4(rows: Sequence[Sequence[int]]) -> int:
    """Determinant of a 4×4 integer matrix (Laplace along the first two rows), exact."""
    (a, b, c, d) = rows
    total = 0
    for (i, j), (k, m), sign in P.LAPLACE:
        total += sign * (a[i] * b[j] - a[j] * b[i]) * (c[k] * d[m] - c[m] * d[k])
    return total


def _exact_value(poly: BracketPolynomial, points: Mapping[str, tuple[int, ...]]) -> Fraction:
    cache: dict[tuple[str, ...], int] = {}
    total = Fraction(0)
    for monomial in poly.terms:
        coefficient, keys = monomial.canonical
        value = coefficient
        for key in keys:
            if key not in cache:
                cache[key] = _exact_det4([points[x] for x in key])
            value *= cache[key]
        total += value
    return total


def random_configuration(
    labels: Sequence[str], types: PointKinds, rng: random.Random
) -> dict[str, tuple[int, ...]]:
    """A random integer configuration: coordinates in [−PROOF_RANGE, PROOF_RANGE], weight 1 for
    finite points and 0 for infinite ones.

    Parameters
    ----------
    labels : sequence of str
    types : PointKinds
        Which labels are infinite.
    rng : random.Random

    Returns
    -------
    dict of str to tuple of int
        ``{label: (x, y, z, w)}``.

    Examples
    --------
    >>> points = random_configuration("ab", PointKinds("a", "b"), random.Random(0))
    >>> points["a"][3], points["b"][3]
    (1, 0)
    """
    return {
        x: (
            *(rng.randint(-PROOF_RANGE, PROOF_RANGE) for _ in range(3)),
            0 if x in types.infinite else 1,
        )
        for x in labels
    }


def prove_proportional(
    poly: BracketPolynomial, expr: sympy.Expr | None, types: PointKinds, seed: int = 0
) -> Fraction:
    """The exact constant c with ``poly = c × expr`` for finite points of weight 1 (0 if ``expr``
    is None and ``poly`` vanishes identically), proved by exact evaluation.

    Both sides are polynomials in the coordinates of total degree at most ``3 × (brackets per
    monomial)``. One random integer configuration fixes c, :data:`PROOF_CHECKS` more must give
    ``poly = c × expr`` exactly. If ``poly − c·expr`` were not the zero polynomial, a configuration
    with coordinates drawn uniformly from ``2·PROOF_RANGE + 1`` integers would be a root with
    probability at most ``degree / (2·PROOF_RANGE + 1)`` (Schwartz–Zippel lemma; J. T. Schwartz,
    J. ACM 27, 1980, Lemma 1), below 1e-17 for the two checks here. This replaces the symbolic
    expansion in coordinates, which took minutes for a general 6-6 Gough–Stewart factor.

    Parameters
    ----------
    poly : BracketPolynomial
    expr : sympy.Expr or None
        A vector form (:mod:`screwkit.gca.vector_forms`), None for the zero form.
    types : PointKinds
        The finite and infinite labels.
    seed : int, default 0
        Seed of the random configurations.

    Returns
    -------
    fractions.Fraction
        The constant c.

    Raises
    ------
    ScrewkitValueError
        If ``poly`` is not a constant times ``expr``.

    Examples
    --------
    >>> from screwkit.gca.vector_forms import VectorCross, VectorDiff, VectorDot
    >>> a, b, c, d = sympy.symbols("a b c d")
    >>> coplanar = VectorDot(VectorCross(VectorDiff(b, a), VectorDiff(c, a)), VectorDiff(d, a))
    >>> prove_proportional(BracketPolynomial.parse("[abcd]"), coplanar, PointKinds("abcd", ""))
    Fraction(-1, 1)
    """
    labels = sorted(set(poly.labels) | ({s.name for s in expr.free_symbols} if expr is not None else set()))
    rng = random.Random(seed)
    constant: Fraction | None = None
    checks = 0
    for _ in range(PROOF_CHECKS + 20):
        points = random_configuration(labels, types, rng)
        exact = _exact_value(poly, points)
        if expr is None:
            form = Fraction(0)
            constant = Fraction(0)
        else:
            vectors = {x: p[:3] for x, p in points.items()}
            form = Fraction(form_value(expr, vectors, Fraction))
        if constant is None:
            if form == 0:  # on the form's zero set by chance: draw again (probability ~0)
                if exact != 0:
                    break
                continue
            constant = exact / form
            if constant == 0:
                break
            continue
        if exact != constant * form:
            break
        checks += 1
        if checks == PROOF_CHECKS:
            return constant
    raise ScrewkitValueError(
        f"Expected the vector form {expr} to be proportional to {poly}, got different ratios at "
        f"exact random configurations."
    )


def _exact_det(matrix: list[list[int]]) -> int:
    """Determinant of a square integer matrix, exact (Bareiss' fraction-free elimination)."""
    m = [row[:] for row in matrix]
    n, sign, previous = len(m), 1, 1
    for k in range(n - 1):
        if m[k][k] == 0:
            swap = next((i for i in range(k + 1, n) if m[i][k] != 0), None)
            if swap is None:
                return 0
            m[k], m[swap], sign = m[swap], m[k], -sign
        for i in range(k + 1, n):
            for j in range(k + 1, n):
                m[i][j] = (m[i][j] * m[k][k] - m[i][k] * m[k][j]) // previous
        previous = m[k][k]
    return sign * m[n - 1][n - 1]


def _plucker(p: Sequence[int], q: Sequence[int]) -> list[int]:
    """``L(p, q) = (p_w q − q_w p ; p × q)`` (``gca.md`` §1), exact."""
    direction = [p[3] * q[i] - q[3] * p[i] for i in range(3)]
    moment = [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]
    return direction + moment


def is_superbracket(poly: BracketPolynomial, lines: Sequence[tuple[str, ...]], types: PointKinds) -> bool:
    """Whether ``poly`` is a non-zero constant times the 6×6 determinant of ``lines``' Plücker
    vectors, proved as in :func:`prove_proportional` (exact values at random integer points).

    Parameters
    ----------
    poly : BracketPolynomial
    lines : sequence of pairs of labels
        Six lines.
    types : PointKinds
        The finite and infinite labels.

    Returns
    -------
    bool

    Examples
    --------
    >>> from screwkit.gca import superbracket_expansion
    >>> lines = ["ab", "cd", "ef", "gh", "ij", "kl"]
    >>> is_superbracket(superbracket_expansion(lines), lines, PointKinds("abcdefghijkl", ""))
    True
    """
    if len(lines) != 6 or set(poly.labels) != {x for line in lines for x in line}:
        return False
    rng = random.Random(1)
    ratio = None
    for _ in range(PROOF_CHECKS + 1):
        points = random_configuration(sorted(poly.labels), types, rng)
        det = _exact_det([_plucker(points[p], points[q]) for p, q in lines])
        value = _exact_value(poly, points)
        if det == 0 or value == 0:
            return False
        if ratio is None:
            ratio = value / det
        elif value != ratio * det:
            return False
    return True



#: The prime of :func:`is_irreducible_in_points`' modular arithmetic (products of two residues fit in
#: 64 bits).
_PRIME = 2_147_483_647
#: Coordinates of its configurations: integers in [−50, 50], so that every 4×4 bracket (at most
#: 4!·50³ in size) is exact in floating point before it is reduced modulo the prime.
_SPLIT_RANGE = 50


def _residues(poly: BracketPolynomial, points: Mapping[str, np.ndarray]) -> np.ndarray:
    """``poly`` modulo :data:`_PRIME` on a batch of integer configurations ``{label: (n, 4)}``."""
    brackets: dict[tuple[str, ...], np.ndarray] = {}
    total = np.zeros(len(next(iter(points.values()))), dtype=np.int64)
    for monomial in poly.terms:
        coefficient, keys = monomial.canonical
        scale = coefficient.numerator * pow(coefficient.denominator, -1, _PRIME) % _PRIME
        value = np.full_like(total, scale)
        for key in keys:
            if key not in brackets:
                rows = np.stack([points[x] for x in key], axis=1).astype(float)
                brackets[key] = np.rint(np.linalg.det(rows)).astype(np.int64) % _PRIME
            value = value * brackets[key] % _PRIME
        total = (total + value) % _PRIME
    return total


def is_irreducible_in_points(poly: BracketPolynomial, types: PointKinds, seed: int = 0) -> bool:
    """Whether ``poly`` is proved irreducible as a polynomial in the coordinates of its points.

    A bracket polynomial has degree at most 1 in each point's coordinates, and degrees add under
    products, so a factorization ``poly = g·h`` splits the points into two groups S, S' (g in the
    points of S, h in those of S'). Then ``f(x_S, x_S') f(y_S, y_S') = f(x_S, y_S') f(y_S, x_S')``
    for any two configurations x, y. One pair of integer configurations at which this fails
    (modulo a prime: a non-zero residue is a non-zero integer) refutes every factorization along
    that split; refuting all ``2^(n−1) − 1`` splits proves irreducibility, over any field. The
    points are free (no incidence of a diagram is imposed).

    Parameters
    ----------
    poly : BracketPolynomial
    types : PointKinds
        The finite and infinite labels.
    seed : int, default 0

    Returns
    -------
    bool
        True when proved; False when some split is not refuted in three tries (the polynomial
        then factors along it, or the configurations were unlucky), when it has fewer than two
        points, or when a monomial does not use every point exactly once (not attempted).

    Examples
    --------
    >>> from screwkit.gca import superbracket_expansion
    >>> lines = ["ab", "cd", "ef", "gh", "ij", "kl"]
    >>> is_irreducible_in_points(superbracket_expansion(lines), PointKinds("abcdefghijkl", ""))
    True
    >>> free = PointKinds("abcdefgh", "")
    >>> is_irreducible_in_points(BracketPolynomial.parse("[abcd][efgh]"), free)
    False
    >>> is_irreducible_in_points(BracketPolynomial.parse("[abcd][efgh] - [abce][dfgh]"), free)
    True
    """
    labels = sorted(poly.labels)
    if len(labels) < 2 or any(sorted(x for b in m.brackets for x in b.labels) != labels for m in poly.terms):
        return False  # only a polynomial linear in every one of its points (the superbracket's form)
    rng = np.random.default_rng(seed)
    # split k: the labels whose bit is set take x, the others y; the last label always takes y
    splits = np.arange(1, 2 ** (len(labels) - 1))
    takes_x = (splits[:, None] >> np.arange(len(labels))) & 1 == 1
    for _ in range(3):
        x, y = ({z: _random_point(rng, z in types.infinite) for z in labels} for _ in range(2))
        mixed, swapped = (
            {z: np.where(mask[:, k, None], first[z], second[z]) for k, z in enumerate(labels)}
            for mask, first, second in ((takes_x, x, y), (takes_x, y, x))
        )
        plain = _residues(poly, {z: np.stack([x[z], y[z]]) for z in labels})
        refuted = (plain[0] * plain[1] - _residues(poly, mixed) * _residues(poly, swapped)) % _PRIME != 0
        if plain[0] and plain[1] and refuted.all():
            return True
    return False


def _random_point(rng: np.random.Generator, infinite: bool) -> np.ndarray:
    return np.r_[rng.integers(-_SPLIT_RANGE, _SPLIT_RANGE + 1, size=3), 0 if infinite else 1]
