"""The interpreter of bracket factors: the known patterns of ``gca.md`` §5 turned into a vector form
and a geometric statement (:func:`vector_form`): one bracket by the kinds of its points, two
planes and a line (``[P ẋ][Q ẏ]``), one bracket of combined points (``[a b (c − d)(e − f)]``,
:mod:`~screwkit.gca.combined_brackets`), four planes through one point, the superbracket itself, and
the generic form (the expansion with every bracket replaced by its form) for any other factor.

Examples
--------
>>> from screwkit.gca import DottedMonomial
>>> form, statement = vector_form(DottedMonomial.parse("[a b d ḟ][c g ḣ j]"), PointKinds("acg", "bdfhj"))
>>> print(form)
((b × d) × ((g − c) × j))·(f × h)
>>> statement
'line fh meets the line where planes abd and cgj intersect'
"""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .brackets import Bracket, BracketPolynomial
from .combined_brackets import combined_bracket, combined_bracket_form
from .dotted import DottedMonomial, DottedSum
from .exact_proofs import is_irreducible_in_points, is_superbracket, prove_proportional
from .notation import join_labels
from .vector_forms import PointKinds, VectorCross, VectorDiff, VectorDot, vector_sum

__all__ = [
    "Factor",
    "bracket_polynomial",
    "vector_form",
]

#: A factor of a factored superbracket.
Factor = Bracket | DottedMonomial | DottedSum | BracketPolynomial


def _listing(labels: Sequence[str]) -> str:
    return ", ".join(labels[:-1]) + " and " + labels[-1]


def _bracket_form(labels: Sequence[str], types: PointKinds) -> tuple[sympy.Expr | None, str, int]:
    """Vector form V, statement and sign s with ``[labels] = s·V`` (``gca.md`` §5.1 table).

    The table gives ``[finite…, infinite…] = −V``; another order of the same letters multiplies
    this by the parity of the permutation. V is None when the bracket is always zero.
    """
    finite, infinite = types.split(labels)
    position = {x: i for i, x in enumerate(finite + infinite)}
    order = [position[x] for x in labels]
    inversions = sum(a > b for i, a in enumerate(order) for b in order[i + 1 :])
    sign = 1 if inversions % 2 else -1
    v = {x: sympy.Symbol(x) for x in labels}
    if len(finite) == 4:
        p, q, r, s = (v[x] for x in finite)
        expr = VectorDot(VectorCross(VectorDiff(q, p), VectorDiff(r, p)), VectorDiff(s, p))
        return expr, f"{_listing(finite)} are coplanar", sign
    if len(finite) == 3:
        p, q, r = (v[x] for x in finite)
        expr = VectorDot(VectorCross(VectorDiff(q, p), VectorDiff(r, p)), v[infinite[0]])
        return expr, f"direction {infinite[0]} is parallel to plane {join_labels(finite)}", sign
    if len(finite) == 2:
        p, q = (v[x] for x in finite)
        u, w = (v[x] for x in infinite)
        statement = (
            f"line {join_labels(finite)} is parallel to the plane spanned by directions "
            f"{infinite[0]} and {infinite[1]}"
        )
        return VectorDot(VectorDiff(q, p), VectorCross(u, w)), statement, sign
    if len(finite) == 1:
        u, w, z = (v[x] for x in infinite)
        statement = (
            f"{_listing(infinite)} are collinear in the plane at infinity (the directions "
            f"{', '.join(infinite)} are parallel to one plane)"
        )
        return VectorDot(VectorCross(u, w), z), statement, sign
    return None, f"{_listing(infinite)} are four points at infinity: always coplanar", 0


def _plane(labels: Sequence[str], types: PointKinds) -> tuple[sympy.Expr, str] | None:
    """Normal of the plane through three points and one of its finite points (None at infinity)."""
    finite, infinite = types.split(labels)
    v = {x: sympy.Symbol(x) for x in labels}
    if len(finite) == 3:
        p, q, r = (v[x] for x in finite)
        return VectorCross(VectorDiff(q, p), VectorDiff(r, p)), finite[0]
    if len(finite) == 2:
        p, q = (v[x] for x in finite)
        return VectorCross(VectorDiff(q, p), v[infinite[0]]), finite[0]
    if len(finite) == 1:
        return VectorCross(v[infinite[0]], v[infinite[1]]), finite[0]
    return None


def _two_planes(term: DottedMonomial, types: PointKinds) -> tuple[sympy.Expr, str] | None:
    """``[P ẋ][Q ẏ] = (P ∧ Q) ∧ xy`` (``gca.md`` §5.2), or None if ``term`` is not of that form."""
    kinds = {k for row in term.dots for k in row if k}
    if len(term.brackets) != 2 or kinds != {1} or any(row.count(1) != 1 for row in term.dots):
        return None
    rows = list(zip(term.brackets, term.dots, strict=True))
    x, y = (next(b[s] for s in range(4) if d[s]) for b, d in rows)
    planes = [[b[s] for s in range(4) if not d[s]] for b, d in rows]
    first, second = (_plane(labels, types) for labels in planes)
    if first is None or second is None or x == y:
        return None
    (n_p, p0), (n_q, q0) = first, second
    if x in types.infinite and y in types.infinite:
        expr = VectorDot(VectorCross(n_p, n_q), VectorCross(sympy.Symbol(x), sympy.Symbol(y)))
    else:

        def value(normal: sympy.Expr, origin: str, point: str) -> sympy.Expr:
            s = sympy.Symbol(point)
            offset = s if point in types.infinite else VectorDiff(s, sympy.Symbol(origin))
            return VectorDot(normal, offset)

        expr = vector_sum([value(n_p, p0, x) * value(n_q, q0, y), -value(n_p, p0, y) * value(n_q, q0, x)])
    statement = (
        f"line {join_labels([x, y])} meets the line where planes {join_labels(planes[0])} and "
        f"{join_labels(planes[1])} intersect"
    )
    return expr, statement + _refinement(planes, x, y, types)


def _refinement(planes: list[list[str]], x: str, y: str, types: PointKinds) -> str:
    """The same condition in the words of the literature, when the planes allow it.

    * Each plane is a finite point and two directions, and x, y are directions: the plane at
      infinity holds three lines (uv, x y, u'v'), and the condition is their concurrency, i.e. the
      three normals u × v, x × y, u' × v' are parallel to one plane (e.g. three constraint couples
      become dependent; ``gca.md`` §5.2, triangle of infinite lines).
    * The planes share one point o: ``P ∩ Q`` is the line through o that meets the lines P − o
      and Q − o, so the condition is that one line through o meets three lines.
    """
    infinite = [[p for p in plane if p in types.infinite] for plane in planes]
    if x in types.infinite and y in types.infinite and all(len(d) == 2 for d in infinite):
        (u, v), (s, t) = infinite
        return (
            f"; i.e. the lines at infinity {join_labels([u, v])}, {join_labels([x, y])} and "
            f"{join_labels([s, t])} are concurrent (the normals {u} × {v}, {x} × {y} and {s} × {t} "
            "are parallel to one plane)"
        )
    shared = sorted(set(planes[0]) & set(planes[1]))
    if len(shared) == 1:
        (o,) = shared
        first, second = ([p for p in plane if p != o] for plane in planes)
        through = f"parallel to direction {o}" if o in types.infinite else f"through {o}"
        return (
            f"; i.e. a line {through} meets the three lines {join_labels(first)}, {join_labels(second)} and "
            f"{join_labels([x, y])} (if these lie in one plane not containing {o}: they are concurrent)"
        )
    return ""


def bracket_polynomial(factor: Factor) -> BracketPolynomial:
    """The bracket polynomial of a factor (a dotted form expanded).

    Parameters
    ----------
    factor : Bracket, DottedMonomial, DottedSum or BracketPolynomial

    Returns
    -------
    BracketPolynomial

    Raises
    ------
    ScrewkitTypeError
        For any other type.

    Examples
    --------
    >>> print(bracket_polynomial(DottedMonomial.parse("[a b d ḟ][c g ḣ j]")))
    [abdf][cghj] - [abdh][cgfj]
    """
    if isinstance(factor, Bracket):
        return BracketPolynomial([factor])
    if isinstance(factor, DottedMonomial | DottedSum):
        return factor.expand()
    if isinstance(factor, BracketPolynomial):
        return factor
    raise ScrewkitTypeError(
        f"Expected `factor` to be a Bracket, DottedMonomial, DottedSum or BracketPolynomial, "
        f"got {type(factor).__name__}."
    )


def _triples(degrees: dict[str, int], allowed: set[tuple[str, ...]]) -> Any:
    """Ways to write a multiset of labels (label → count) as four triples of distinct labels, each
    triple (sorted) in ``allowed``."""
    remaining = {x: d for x, d in degrees.items() if d}
    if not remaining:
        yield ()
        return
    first = min(remaining)
    others = sorted(x for x in remaining if x != first)
    for pair in itertools.combinations(others, 2):
        if (first, *pair) not in allowed:
            continue
        rest = dict(remaining)
        for x in (first, *pair):
            rest[x] -= 1
        for tail in _triples(rest, allowed):
            yield ((first, *pair), *tail)


def _collinear_point(p: np.ndarray, q: np.ndarray, finite: bool, t: float) -> np.ndarray | None:
    """A point of line pq with the weight of its kind (1 finite, 0 infinite), or None.

    The point at infinity of a line through one finite and one infinite point is the infinite one
    (a multiple of it: the plane of the three points then degenerates, as for three collinear
    points, e.g. a 3-PRS leg whose rod turns parallel to its R axis)."""
    if not finite and (p[3] == 0) != (q[3] == 0):
        return (1 + t) * (p if p[3] == 0 else q)
    point = p + t * q if p[3] == 0 or q[3] == 0 else p + t * (q - p) if finite else p - q
    if finite:
        return None if point[3] == 0 else point / point[3]
    return point if point[3] == 0 else None


def _plane_triples(
    poly: BracketPolynomial, labels: Sequence[str], types: PointKinds, points: Mapping[str, np.ndarray]
) -> set[tuple[str, ...]]:
    """Triples that may be planes of a four-plane factor: ``det[π₁…π₄]`` vanishes when the three
    points of one of its planes are collinear (the plane degenerates), so a triple is kept only if
    the factor vanishes when its third point is moved onto the line of the other two."""
    scale = abs(float(poly.evaluate(points)))
    triples, batch = [], {x: [] for x in points}  # type: ignore[var-annotated]
    for triple in itertools.combinations(sorted(labels), 3):
        if not set(triple) & types.finite:
            continue
        for p, q, r in itertools.permutations(triple):
            moved = _collinear_point(points[p], points[q], r in types.finite, 0.37)
            if moved is not None:
                triples.append(triple)
                for x, point in points.items():
                    batch[x].append(moved if x == r else point)
                break
    if not triples:
        return set()
    values = np.atleast_1d(poly.evaluate({x: np.array(v) for x, v in batch.items()}))
    return {tuple(t) for t, v in zip(triples, values, strict=True) if abs(v) <= 1e-9 * scale}


def _plane_vector(triple: Sequence[str], points: Mapping[str, np.ndarray]) -> np.ndarray:
    """Coordinates π of the plane through three points, ``π·x = [p q r x]`` (``gca.md`` §5.2)."""
    rows = np.stack([points[x] for x in triple])
    return np.array([(-1) ** (k + 1) * np.linalg.det(np.delete(rows, k, axis=1)) for k in range(4)])


def _four_planes(
    poly: BracketPolynomial, types: PointKinds, lines: Sequence[tuple[str, ...]] | None = None
) -> tuple[sympy.Expr, str] | None:
    """``det[π₁; π₂; π₃; π₄]``, zero iff four planes share a point (``gca.md`` §5.2, four-plane
    pattern; the octahedral Gough–Stewart platform), recognised among the ways of grouping the
    factor's twelve letters into four planes: screened on two random float configurations, the
    candidate is then proved exactly by :func:`prove_proportional`."""
    if any(len(m.brackets) != 3 for m in poly.terms):
        return None
    degrees: dict[str, int] = {}
    for m in poly.terms:
        counts = Counter(x for b in m.brackets for x in b.labels)
        for x, k in counts.items():
            degrees[x] = max(degrees.get(x, 0), k)
    if sum(degrees.values()) != 12:
        return None
    rng = np.random.default_rng(0)
    samples = [
        {x: np.r_[rng.normal(size=3), 0.0 if x in types.infinite else 1.0] for x in degrees}
        for _ in range(2)
    ]
    values = [float(poly.evaluate(points)) for points in samples]
    if not all(values):
        return None
    allowed = _plane_triples(poly, list(degrees), types, samples[0])
    candidates = list(_triples(degrees, allowed))
    if not candidates:
        return None
    triples = sorted({t for c in candidates for t in c})
    index = {t: k for k, t in enumerate(triples)}
    vectors = np.array([[_plane_vector(t, points) for t in triples] for points in samples])
    rows = np.array([[index[t] for t in c] for c in candidates])
    dets = np.linalg.det(vectors[:, rows])  # (2, candidates)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratios = np.array(values)[:, None] / dets
    close = np.isfinite(ratios).all(axis=0) & np.isclose(ratios[0], ratios[1], rtol=1e-8, atol=0)
    for k in np.flatnonzero(close).tolist():
        candidate = candidates[k]
        normals = [_plane(t, types) for t in candidate]
        terms = []
        for i, (normal, origin) in enumerate(normals):  # type: ignore[misc]
            others = [n for j, (n, _) in enumerate(normals) if j != i]  # type: ignore[misc]
            volume = VectorDot(VectorCross(others[0], others[1]), others[2])
            terms.append((-1) ** i * VectorDot(normal, sympy.Symbol(origin)) * volume)
        expr = vector_sum(terms)
        try:
            prove_proportional(poly, expr, types)
        except ScrewkitValueError:
            continue
        names = [join_labels(t) for t in candidate]
        statement = f"planes {_listing(names)} pass through one point (possibly at infinity)"
        return expr, statement + _spanning_lines(candidate, lines or ())
    return None


def _spanning_lines(planes: Sequence[tuple[str, ...]], lines: Sequence[tuple[str, ...]]) -> str:
    """Which of the planes are spanned by two lines of the diagram through a common point (e.g. a
    3-RPS leg's force and constraint force through its sphere centre), in words, or ""."""
    spans = []
    for plane in planes:
        inside = [line for line in lines if set(line) <= set(plane)]
        pairs = [(x, y) for x, y in itertools.combinations(inside, 2) if set(x) | set(y) == set(plane)]
        if pairs:
            x, y = pairs[0]
            spans.append(f"{join_labels(plane)} is the plane of lines {join_labels(x)} and {join_labels(y)}")
    return "; " + ", ".join(spans) if spans else ""


def vector_form(
    factor: Factor, types: PointKinds, lines: Sequence[tuple[str, ...]] | None = None
) -> tuple[sympy.Expr | None, str]:
    """The vector form and the statement of a factor: a known pattern, else the generic form.

    Parameters
    ----------
    factor : Bracket, DottedMonomial, DottedSum or BracketPolynomial
    types : PointKinds
        The finite and infinite labels (every label of the factor declared).
    lines : sequence of pairs of labels, optional
        The diagram's lines: the generic statement names those the factor involves, or says the
        factor is the superbracket itself.

    Returns
    -------
    form : sympy.Expr or None
        None when the factor vanishes identically (four points at infinity).
    statement : str
        When the factor vanishes, in words.

    Examples
    --------
    >>> form, statement = vector_form(Bracket("gikj"), PointKinds("g", "ijk"))
    >>> print(form)
    (i × k)·j
    """
    if isinstance(factor, Bracket):
        expr, statement, _ = _bracket_form(factor.labels, types)
        return expr, statement
    single = factor.terms[0] if isinstance(factor, DottedSum) and len(factor.terms) == 1 else factor
    if isinstance(single, DottedMonomial):
        found = _two_planes(single, types)
        if found is not None:
            return found
    polynomial = bracket_polynomial(factor)
    combined = combined_bracket(polynomial)
    if combined is not None:
        found = combined_bracket_form(combined, types)
        if found is not None:
            return found
    found = _four_planes(polynomial, types, lines)
    if found is not None:
        return found
    products = []
    for monomial in polynomial:
        product = [sympy.Rational(monomial.coefficient.numerator, monomial.coefficient.denominator)]
        for bracket in monomial.brackets:
            expr, _, sign = _bracket_form(bracket.labels, types)
            product += [sympy.Integer(0 if expr is None else sign)] + ([] if expr is None else [expr])
        products.append(sympy.Mul(*product))
    total = vector_sum(products)
    statement = f"the bracket expression {factor} vanishes"
    if lines is not None and is_superbracket(polynomial, lines, types):
        statement = (
            f"the six lines {_listing([join_labels(line) for line in lines])} are linearly dependent "
            "(they belong to one linear line complex): no factor of the superbracket is simpler"
        )
        if is_irreducible_in_points(polynomial, types):
            statement += (
                f" (it is irreducible in the coordinates of its {len(polynomial.labels)} points taken free, "
                "proved exactly: no split of them into two groups factors it); which complex, or which "
                "smaller Grassmann class, is read from the lines at the pose (sk.grassmann_class)"
            )
    elif lines is not None:
        labels = set(polynomial.labels)
        involved = [join_labels(line) for line in lines if labels & set(line)]
        statement += (
            f" (it involves lines {', '.join(involved) or 'none'} through the points "
            f"{', '.join(sorted(labels))})"
        )
    return (total if total != 0 else None), statement
