"""The superbracket: the 6×6 determinant of six joins (:func:`superbracket`, the ground truth), its
24-term bracket expansion (:func:`superbracket_expansion`) and grouped dotted form
(:func:`superbracket_grouped`), and the exhaustive search over the 46 080 orderings of its lines for
the fewest surviving monomials (:func:`best_ordering`, ``gca.md`` §6.4).
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..algebra import projective as P
from ..algebra.checks import checked_rtol
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .brackets import BracketPolynomial, as_labels
from .dotted import DottedSum
from .labelled_points import point_arrays, scalar_result
from .zeros import Sampler, draw_samples, drop_structural_zeros, vanishing_brackets

__all__ = [
    "OrderingSearch",
    "best_ordering",
    "checked_lines",
    "search_orderings",
    "superbracket",
    "superbracket_expansion",
    "superbracket_grouped",
]


# --------------------------------------------------------------------------------------------------
# The superbracket
# --------------------------------------------------------------------------------------------------

_SLOTS = "abcdefghijkl"

# gca.md §2.1: [ab,cd,ef,gh,ij,kl] in the reference convention (constant +1). Each monomial is a
# standard Young tableau, so the form is unique; tests/gca/test_expansion.py proves it against the 6×6 det.
_EXPANSION = BracketPolynomial.parse(
    """
    +[abcd][efgi][hjkl] -[abcd][efgj][hikl] -[abcd][efhi][gjkl] +[abcd][efhj][gikl]
    -[abce][dfgh][ijkl] +[abce][dghi][fjkl] -[abce][dghj][fikl]
    +[abcf][degh][ijkl] -[abcf][dghi][ejkl] +[abcf][dghj][eikl]
    -[abcg][defi][hjkl] +[abcg][defj][hikl] +[abch][defi][gjkl] -[abch][defj][gikl]
    +[abde][cfgh][ijkl] -[abde][cghi][fjkl] +[abde][cghj][fikl]
    -[abdf][cegh][ijkl] +[abdf][cghi][ejkl] -[abdf][cghj][eikl]
    +[abdg][cefi][hjkl] -[abdg][cefj][hikl] -[abdh][cefi][gjkl] +[abdh][cefj][gikl]
    """
)

# gca.md §2.2 in dotted notation: [abcd]·Alt{g↔h,i↔j}[efgi][hjkl]
# + Alt{c↔d,g↔h,i↔j}[abdg][cefi][hjkl]
# + Alt{c↔d,e↔f}[abde]([cfgh][ijkl] − [cghi][fjkl] + [cghj][fikl]).
_GROUPED = DottedSum.parse(
    "[abcd][e f g\u0307 i\u0308][h\u0307 j\u0308 k l]"
    " + [a b d\u0307 g\u0308][c\u0307 e f i\u20db][h\u0308 j\u20db k l]"
    " + [a b d\u0307 e\u0308][c\u0307 f\u0308 g h][i j k l]"
    " - [a b d\u0307 e\u0308][c\u0307 g h i][f\u0308 j k l]"
    " + [a b d\u0307 e\u0308][c\u0307 g h j][f\u0308 i k l]"
)


def checked_lines(lines: Any) -> tuple[tuple[str, str], ...]:
    """Validate six lines given as 2-tuples of labels (or two-letter strings).

    Parameters
    ----------
    lines : sequence of six pairs of labels

    Returns
    -------
    tuple of six (str, str)

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError
        For anything but six lines of two labels.

    Examples
    --------
    >>> checked_lines(["ab", "cd", "ef", "gh", "ij", ("k", "l")])[-1]
    ('k', 'l')
    """
    if isinstance(lines, str) or not isinstance(lines, Sequence):
        raise ScrewkitTypeError(
            f"Expected `lines` to be a sequence of six pairs of labels, got {type(lines).__name__}."
        )
    if len(lines) != 6:
        raise ScrewkitValueError(f"Expected `lines` to hold 6 lines, got {len(lines)}.")
    out = []
    for i, line in enumerate(lines):
        p, q = as_labels(line, f"lines[{i}]", 2)
        out.append((p, q))
    return tuple(out)


def superbracket_expansion(lines: Sequence[Sequence[str] | str]) -> BracketPolynomial:
    """The 24-monomial bracket expansion of the superbracket ``[ab, cd, ef, gh, ij, kl]``.

    The formula of ``gca.md`` §2.1 (constant exactly +1 in the reference convention), with the
    slots a…l replaced by the labels of ``lines``. Repeated labels (e.g. the H4's ``j`` on two
    lines, paper 002 §5.1) make some monomials structurally zero; they are dropped and like terms
    are combined, so fewer than 24 monomials may remain.

    Parameters
    ----------
    lines : sequence of six pairs of labels
        E.g. ``[("a", "b"), ("c", "d"), …]`` or ``["ab", "cd", …]``.

    Returns
    -------
    BracketPolynomial

    See Also
    --------
    superbracket : the 6×6 determinant (ground truth).
    superbracket_grouped : the same sum in dotted notation.

    Examples
    --------
    >>> p = superbracket_expansion(["ab", "cd", "ef", "gh", "ij", "kl"])
    >>> len(p), str(p.terms[0])
    (24, '[abcd][efgi][hjkl]')
    >>> len(superbracket_expansion(["ab", "cd", "ef", "gh", "ij", "kj"]))  # H4: j twice
    10
    """
    slots = [label for line in checked_lines(lines) for label in line]
    return _EXPANSION.relabel(dict(zip(_SLOTS, slots, strict=True)))


def superbracket_grouped(lines: Sequence[Sequence[str] | str]) -> DottedSum:
    """The superbracket as five dotted monomials (``gca.md`` §2.2), same 24 terms.

    ``[abcd][e f ġ ï][ḣ j̈ k l] + [a b ḋ g̈][ċ e f i⃛][ḧ j⃛ k l]
    + [a b ḋ ë]([ċ f̈ g h][i j k l] − [ċ g h i][f̈ j k l] + [ċ g h j][f̈ i k l])``,
    with the slots replaced by the labels of ``lines``.

    Parameters
    ----------
    lines : sequence of six pairs of labels

    Returns
    -------
    DottedSum

    Examples
    --------
    >>> g = superbracket_grouped(["ab", "cd", "ef", "gh", "ij", "kl"])
    >>> print(g.terms[0])
    [abcd][e f ġ ï][ḣ j̈ k l]
    >>> g.expand() == superbracket_expansion(["ab", "cd", "ef", "gh", "ij", "kl"])
    True
    """
    slots = [label for line in checked_lines(lines) for label in line]
    return _GROUPED.relabel(dict(zip(_SLOTS, slots, strict=True)))


def superbracket(points: Mapping[str, Any], lines: Sequence[Sequence[str] | str]) -> Any:
    """The superbracket: determinant of the six Plücker rows ``L(p, q)`` (``gca.md`` §1).

    This is the ground truth that every expansion and simplification is checked against.

    Parameters
    ----------
    points : mapping of str to array_like, shape (..., 4)
        Homogeneous points ``(x, y, z, w)``; numeric batches broadcast. Sympy points give an exact
        (expanded) determinant and must not be batched.
    lines : sequence of six pairs of labels

    Returns
    -------
    float, numpy.ndarray or sympy.Expr

    Examples
    --------
    >>> e = np.eye(4)
    >>> pts = {"o": e[3], "x": e[0], "y": e[1], "z": e[2]}
    >>> # forces along the axes through the origin and couples about them: det = +1 here
    >>> float(superbracket(pts, ["ox", "oy", "oz", "yz", "zx", "xy"]))
    1.0
    """
    pairs = checked_lines(lines)
    arrays = point_arrays(points, [label for line in pairs for label in line])
    matrix = np.stack([P.join_unchecked(arrays[p], arrays[q]) for p, q in pairs], axis=-2)
    if B.is_symbolic(matrix) and matrix.ndim != 2:
        raise ScrewkitValueError(
            f"Expected sympy `points` to be single points of shape (4,), got batch shape "
            f"{matrix.shape[:-2]}."
        )
    return scalar_result(B.det(matrix))


# --------------------------------------------------------------------------------------------------
# Exhaustive ordering search (gca.md §6.4)
# --------------------------------------------------------------------------------------------------


@functools.cache
def _line_orders() -> tuple[np.ndarray, np.ndarray]:
    """The 6! line permutations (720, 6), in ``itertools`` order, and the 2^6 flips (64, 6)."""
    perms = np.array(list(itertools.permutations(range(6))))
    flips = np.array(list(itertools.product((0, 1), repeat=6)))
    return perms, flips


def _ordering(index: int) -> tuple[np.ndarray, int]:
    """Ordering ``index`` (of the 6!·2^6 = 46 080) as its slot -> caller position map (12,) and its
    sign.

    Ordering ``64 π + f`` (``π`` a permutation in ``itertools`` order, ``f`` a flip) puts the
    caller's line ``π[k]`` in place ``k``, its points swapped if ``f[k]``; the identity comes first.
    Its superbracket is ``sgn(π)·(-1)^Σf`` times the caller's (swapping two rows or negating one row
    of the 6×6 matrix flips the sign).
    """
    perms, flips = _line_orders()
    perm, flip = perms[index // len(flips)], flips[index % len(flips)]
    slot_positions = np.stack([2 * perm + flip, 2 * perm + 1 - flip], axis=-1).reshape(12)
    inversions = sum(int(perm[i] > perm[j]) for i, j in itertools.combinations(range(6), 2))
    return slot_positions, (-1) ** (inversions + int(flip.sum()))


@functools.cache
def _permutation_brackets() -> np.ndarray:
    """The caller positions of each bracket of the 24 template monomials (gca.md §2.1) under each of
    the 720 line permutations without flips, coded as one index into the 12^4 ordered 4-tuples,
    ``(3, 720, 24)``.

    Ordering ``(π, 0)`` puts caller position ``2 π[k] + bit`` in slot ``2k + bit``, so a bracket's
    code ``Σ_s 12^(3-s) position_s`` is linear in ``π``: ``π @ weights + offsets``.
    """
    slots = np.array([[[_SLOTS.index(x) for x in b.labels] for b in m.brackets] for m in _EXPANSION])
    line, bit = slots.transpose(1, 0, 2) // 2, slots.transpose(1, 0, 2) % 2  # (3, 24, 4)
    place = 12 ** np.arange(3, -1, -1)
    weights = np.zeros((6, 3, 24), dtype=np.int64)
    for k in range(6):
        weights[k] = (2 * place * (line == k)).sum(axis=-1)
    perms, _ = _line_orders()
    codes = np.einsum("pk,kbm->bpm", perms, weights) + (bit * place).sum(axis=-1)[:, None, :]
    return np.ascontiguousarray(codes, dtype=np.intp)


#: The signs of the 24 template monomials.
_TEMPLATE_SIGNS = np.array([int(m.coefficient) for m in _EXPANSION], dtype=np.int32)


def _ordering_counts(positions: Sequence[str], zero: Mapping[tuple[str, ...], bool]) -> np.ndarray:
    """Number of surviving monomials (after combining like terms) per line permutation, (720,).

    The count does not depend on the flips: exchanging the two points of any line maps the 24
    template monomials of gca.md §2.1 onto themselves with every coefficient negated (the expansion
    stays in standard form; the superbracket changes sign as a join does), a property of the template
    that ``tests/gca/test_expansion.py`` checks exactly, monomial by monomial. So the polynomial of ordering
    ``(π, f)`` is ``±`` that of ``(π, 0)``, the same monomials surviving and combining: the 720
    permutations are scored: ordering ``64 π + f`` (:func:`_ordering`) has the count of ``π``.
    """
    unique = sorted(set(positions))
    quads = list(itertools.combinations(range(len(unique)), 4))
    quad_id = np.zeros((len(unique),) * 4, dtype=np.int32)
    for i, quad in enumerate(quads):
        quad_id[quad] = i
    alive = np.array([not zero[tuple(unique[i] for i in quad)] for quad in quads] or [False])
    # Every ordered 4-tuple of caller positions, coded as ±(id of its label set + 1): the sign of
    # sorting its labels, 0 if a label repeats or the bracket is structurally zero.
    label_of = np.array([unique.index(label) for label in positions])
    tuples = label_of[np.indices((12,) * 4).reshape(4, -1).T]  # (12^4, 4)
    pairs = list(itertools.combinations(range(4), 2))
    inversions = sum((tuples[:, i] > tuples[:, j]).astype(int) for i, j in pairs)
    distinct = np.all([tuples[:, i] != tuples[:, j] for i, j in pairs], axis=0)
    ids = quad_id[tuple(np.sort(tuples, axis=1).T)]
    code = np.where(distinct & alive[ids], (1 - 2 * (inversions % 2)) * (ids + 1), 0)
    return _survivor_counts(code[_permutation_brackets()], len(quads) + 1)


def _survivor_counts(codes: np.ndarray, n: int) -> np.ndarray:
    """Surviving monomials per ordering from the codes ``(3, orderings, 24)`` of the three brackets of
    each template monomial (:func:`_ordering_counts`; ``n`` - 1 label sets)."""
    first, second, third = codes.reshape(3, -1, codes.shape[-1])
    coefficients = _TEMPLATE_SIGNS * np.sign(first) * np.sign(second) * np.sign(third)
    # Only monomials without a zero bracket can survive. One is identified within its ordering by
    # the sorted triple of its label sets (low, middle, high); like terms share it.
    row, column = np.nonzero(coefficients)
    first, second, third = np.abs(first[row, column]), np.abs(second[row, column]), np.abs(third[row, column])
    low = np.minimum(np.minimum(first, second), third)
    high = np.maximum(np.maximum(first, second), third)
    keys = ((row.astype(np.int64) * n + low) * n + (first + second + third - low - high)) * n + high
    order = np.argsort(keys, kind="stable")
    keys, values = keys[order], coefficients[row, column][order]
    starts = np.ones(keys.shape, dtype=bool)
    starts[1:] = keys[1:] != keys[:-1]
    totals = np.add.reduceat(values, np.flatnonzero(starts)) if len(keys) else values
    return np.bincount(row[order][starts], weights=totals != 0, minlength=len(coefficients)).astype(int)


@dataclass(frozen=True, slots=True)
class OrderingSearch:
    """Result of :func:`best_ordering`.

    Attributes
    ----------
    lines : tuple of six (str, str)
        The best ordering of the lines and of the points in each line.
    sign : int
        ``superbracket(lines) == sign * superbracket(caller's lines)``.
    polynomial : BracketPolynomial
        The expansion in this ordering without its structurally zero monomials.
    caller_count : int
        Surviving monomials in the caller's own ordering.
    histogram : tuple of (int, int)
        ``(number of surviving monomials, number of orderings)`` over all 46 080 orderings.
    """

    lines: tuple[tuple[str, str], ...]
    sign: int
    polynomial: BracketPolynomial
    caller_count: int
    histogram: tuple[tuple[int, int], ...]

    @property
    def count(self) -> int:
        """Number of surviving monomials in the best ordering."""
        return len(self.polynomial)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary.

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
        return {
            "lines": [list(line) for line in self.lines],
            "sign": self.sign,
            "count": self.count,
            "polynomial": str(self.polynomial),
            "caller_count": self.caller_count,
            "histogram": [list(pair) for pair in self.histogram],
        }

    def __str__(self) -> str:
        lines = ", ".join(p + q if len(p + q) == 2 else f"{p} {q}" for p, q in self.lines)
        spread = ", ".join(f"{c}: {n}" for c, n in self.histogram)
        return (
            f"[{lines}] (sign {self.sign:+d}): {self.count} monomials "
            f"(caller's order: {self.caller_count}; counts over all orderings {{{spread}}})"
        )


def search_orderings(
    pairs: tuple[tuple[str, str], ...], samples: Mapping[str, np.ndarray], rtol: float
) -> OrderingSearch:
    """:func:`best_ordering` on samples already drawn.

    Parameters
    ----------
    pairs : tuple of six (str, str)
        Checked lines (:func:`checked_lines`).
    samples : mapping of str to numpy.ndarray, shape (n_samples, 4)
        Stacked samples (:func:`screwkit.gca.zeros.draw_samples`).
    rtol : float
        Relative zero threshold of a bracket.

    Returns
    -------
    OrderingSearch

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> samples = {x: rng.normal(size=(5, 4)) for x in "abcdefghijkl"}
    >>> search_orderings(checked_lines(["ab", "cd", "ef", "gh", "ij", "kl"]), samples, 1e-9).count
    24
    """
    positions = [label for line in pairs for label in line]
    quads = list(itertools.combinations(sorted(set(positions)), 4))
    zero = vanishing_brackets(samples, quads, rtol)
    counts = _ordering_counts(positions, zero)  # per permutation, the same for its 64 flips
    flips = len(_line_orders()[1])
    # ties: the first, so the caller's order wins if it is optimal
    slot_positions, sign = _ordering(flips * int(np.argmin(counts)))
    chosen = tuple((positions[slot_positions[2 * k]], positions[slot_positions[2 * k + 1]]) for k in range(6))
    polynomial = drop_structural_zeros(superbracket_expansion(chosen), samples, rtol)
    values, tallies = np.unique(counts, return_counts=True)
    return OrderingSearch(
        lines=chosen,
        sign=sign,
        polynomial=polynomial,
        caller_count=int(counts[0]),
        histogram=tuple((int(v), flips * int(t)) for v, t in zip(values, tallies, strict=True)),
    )


def best_ordering(
    lines: Sequence[Sequence[str] | str],
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rtol: float = 1e-9,
    rng: np.random.Generator | int = 0,
) -> OrderingSearch:
    """Exhaustive search over the 6!·2^6 = 46 080 orderings for the fewest surviving monomials.

    The brackets of all 4-subsets of the labels are evaluated once on the samples to find the
    structurally zero ones (as in :func:`~screwkit.gca.zeros.structural_zeros`); then every ordering is
    scored at once
    with numpy: the 24 template monomials are mapped through each ordering, monomials with a zero
    bracket are dropped and like terms are combined (``gca.md`` §6.4). Ties go to the earliest
    ordering, the caller's own first.

    Parameters
    ----------
    lines : sequence of six pairs of labels
    sampler : callable
        ``rng -> {label: point (4,)}`` (see :func:`~screwkit.gca.zeros.structural_zeros`).
    n_samples : int, default 20
    rtol : float, default 1e-9
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    OrderingSearch

    Examples
    --------
    >>> def generic(rng):
    ...     return {x: rng.normal(size=4) for x in "abcdefghijkl"}
    >>> result = best_ordering(["ab", "cd", "ef", "gh", "ij", "kl"], generic)
    >>> result.count, result.histogram  # nothing vanishes: 24 in every ordering
    (24, ((24, 46080),))
    """
    pairs = checked_lines(lines)
    labels = [label for line in pairs for label in line]
    samples = draw_samples(sampler, n_samples, np.random.default_rng(rng), labels)
    return search_orderings(pairs, samples, checked_rtol(rtol))
