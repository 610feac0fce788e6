"""Brackets, the 24-term superbracket expansion and its simplification (Grassmann–Cayley algebra).

Conventions (``gca.md`` §1, the *reference convention*): a projective point is
``(x, y, z, w)`` with the weight last, finite ``(r, 1)``, infinite ``(d, 0)``. The bracket
``[pqrs]`` is the determinant of the 4×4 matrix whose rows are p, q, r, s. The line through p and
q has the Plücker vector (ray order, direction first) ``L(p, q) = (p_w q − q_w p ; p × q)``, the
seed paper's zero-pitch wrench ``(s, r × s)`` (paper 002, §5.1). The superbracket
``[ab, cd, ef, gh, ij, kl]`` is the determinant of the 6×6 matrix whose rows are
``L(a, b), …, L(k, l)`` (White 2005, "Grassmann–Cayley algebra and robotics applications";
paper 002, §5.2). In this convention it equals the 24-term bracket
polynomial of ``gca.md`` §2.1 with constant exactly +1 (:func:`superbracket_expansion`).

The module has three layers:

* exact bracket algebra: :class:`Bracket`, :class:`BracketMonomial`, :class:`BracketPolynomial`
  (integer or rational coefficients, canonical forms, evaluation on numeric batches or exact sympy
  points), and the dotted notation of McMillan & White (1991), :class:`DottedMonomial` and
  :class:`DottedSum` (``gca.md`` §3);
* the superbracket: :func:`superbracket` (the 6×6 determinant, always the ground truth),
  :func:`superbracket_expansion` and :func:`superbracket_grouped`;
* the simplification procedure of ``gca.md`` §6, each step checked numerically on configurations
  drawn from a *sampler* (a callable ``rng -> {label: point (4,)}`` whose configurations satisfy
  the mechanism's incidences): :func:`structural_zeros`, :func:`drop_zero_subsums`,
  :func:`best_ordering`, :func:`collect_factors`, :func:`check_proportional`, and the whole chain
  :func:`simplify_superbracket`.

Labels are short strings: a letter followed by letters or digits (``"a"``, ``"r1"``). A bracket may
be written ``"gikj"`` (single letters) or ``"r1 r2 r3 r4"`` (separated by spaces).

Notes
-----
Checked against the sources (tests/test_gca.py):

* The 24-term formula of ``gca.md`` §2.1 equals the 6×6 determinant exactly (a proof on all
  369 600 balanced basis configurations, see the test's docstring); the constants of §2.3 hold.
* ``gca.md`` §3 divides the alternation by ``∏_b k_b!`` with ``k_b`` the dotted positions in bracket
  b; with several dot kinds in one bracket the divisor must be taken per bracket *and* kind
  (``[e f ġ ï][ḣ j̈ k l]`` has four terms, not one).
* Paper 002, Eq. (5): the printed second line ``[gikj][abdf][cghj]`` lost the dots of
  ``[gikj][a b d ḟ][c g ḣ j]``; the undotted product is not proportional to the superbracket. In
  the reference convention the superbracket of ``[ab, cd, ef, gh, ij, kj]`` is
  ``−[gikj][a b d ḟ][c g ḣ j]`` (the paper states it "up to a scalar multiple").
* ``gca.md`` §6.4: with the H4's incidences (a, c, j and e, g, j collinear) the ordering
  ``[ab, ij, cd, kj, ef, gh]`` leaves 9 non-zero template monomials that combine into 5, and the
  counts over the 46 080 orderings range from 4 to 18 (the paper's order gives 5, so it is not
  the best); the quoted 13 (like terms not combined) and 5…20 hold only if they are ignored.

References
----------
.. [1] N. L. White, "Grassmann–Cayley algebra and robotics applications", Handbook of Geometric
   Computing, Part VIII, pp. 629–656, Springer, 2005.
.. [2] T. McMillan and N. L. White, "The dotted straightening algorithm", Journal of Symbolic
   Computation 11, pp. 471–482, 1991.
.. [3] S. Amine, D. Kanaan, S. Caro, P. Wenger, "Singularity analysis of lower-mobility parallel
   robots with an articulated nacelle", ARK 2010 (paper 002), §5, Eqs. (5)–(7).

Examples
--------
>>> from screwkit.gca import Bracket, BracketPolynomial
>>> Bracket("gikj") * Bracket("abdf") - Bracket("abdh") * Bracket("cgfj")
BracketPolynomial('[gikj][abdf] - [abdh][cgfj]')
>>> Bracket("bacd") == -Bracket("abcd")
True
"""

from __future__ import annotations

import functools
import itertools
import math
import re
import unicodedata
from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from . import _backend as B
from . import projective as P
from .exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError

if TYPE_CHECKING:
    import sympy

__all__ = [
    "Bracket",
    "BracketMonomial",
    "BracketPolynomial",
    "DottedMonomial",
    "DottedSum",
    "FactoredForm",
    "OrderingSearch",
    "Proportionality",
    "Simplification",
    "best_ordering",
    "check_proportional",
    "collect_factors",
    "drop_zero_subsums",
    "simplify_superbracket",
    "structural_zeros",
    "superbracket",
    "superbracket_expansion",
    "superbracket_grouped",
]

#: A sampler draws one configuration satisfying a mechanism's incidences: ``rng -> {label: (4,)}``.
Sampler = Callable[[np.random.Generator], Mapping[str, Any]]

_LABEL = re.compile(r"[A-Za-z][A-Za-z0-9]*\Z")
#: Combining marks of the dot kinds 1..4 (dot, diaeresis, three dots, four dots) and their LaTeX.
_MARKS = ("\u0307", "\u0308", "\u20db", "\u20dc")
_LATEX_DOTS = (r"\dot", r"\ddot", r"\dddot", r"\ddddot")


# --------------------------------------------------------------------------------------------------
# Labels, signs, coefficients
# --------------------------------------------------------------------------------------------------


def _check_label(label: Any, name: str) -> str:
    if not isinstance(label, str):
        raise ScrewkitTypeError(
            f"Expected `{name}` to be a label string, got {type(label).__name__} {label!r}."
        )
    if not _LABEL.match(label):
        raise ScrewkitValueError(
            f"Expected `{name}` to be a label (a letter followed by letters or digits), "
            f"got {label!r}."
        )
    return label


def _labels(value: Any, name: str, count: int | None = None) -> tuple[str, ...]:
    """Labels from ``"abcd"`` (single letters), ``"r1 r2 r3 r4"`` or a sequence of strings."""
    if isinstance(value, Bracket):
        items: list[Any] = list(value.labels)
    elif isinstance(value, str):
        items = value.split() if any(ch.isspace() for ch in value) else list(value)
    elif isinstance(value, Sequence):
        items = list(value)
    else:
        raise ScrewkitTypeError(
            f"Expected `{name}` to be a string or a sequence of labels, "
            f"got {type(value).__name__} {value!r}."
        )
    labels = tuple(_check_label(item, f"{name}[{i}]") for i, item in enumerate(items))
    if count is not None and len(labels) != count:
        raise ScrewkitValueError(
            f"Expected `{name}` to hold {count} labels, got {len(labels)}: {labels}."
        )
    return labels


@functools.lru_cache(maxsize=1 << 16)
def _bracket_labels(value: str | tuple[str, ...]) -> tuple[str, ...]:
    """Validated labels of a bracket (cached: brackets are built very often while simplifying)."""
    return _labels(value, "labels", 4)


@functools.lru_cache(maxsize=1 << 16)
def _sort_sign(items: tuple[Any, ...]) -> int:
    """Sign of the permutation that sorts ``items``; 0 if an item repeats."""
    if len(set(items)) < len(items):
        return 0
    inversions = sum(
        1 for i in range(len(items)) for j in range(i + 1, len(items)) if items[i] > items[j]
    )
    return -1 if inversions % 2 else 1


def _coefficient(value: Any, name: str) -> Fraction:
    if isinstance(value, bool | np.bool_):
        raise ScrewkitTypeError(f"Expected `{name}` to be an integer or a fraction, got {value!r}.")
    exact = B.exact_fraction(value)
    if exact is not None:
        return exact
    raise ScrewkitTypeError(
        f"Expected `{name}` to be an integer or a fraction (coefficients are exact), "
        f"got {type(value).__name__} {value!r}."
    )


def _is_scalar(value: Any) -> bool:
    return B.exact_fraction(value) is not None


def _format_magnitude(value: Fraction, *, latex: bool, alone: bool) -> str:
    """A non-negative coefficient as a prefix ('' for 1) or, for a bare number, the number."""
    if value == 1 and not alone:
        return ""
    if value.denominator == 1:
        text = str(value.numerator)
    elif latex:
        text = rf"\tfrac{{{value.numerator}}}{{{value.denominator}}}"
    else:
        text = str(value)
    return text if alone else text + " "


def _format_bracket(labels: Sequence[str], dots: Sequence[int], *, latex: bool) -> str:
    single = all(len(label) == 1 for label in labels)
    if latex:
        parts = [
            f"{_LATEX_DOTS[kind - 1]}{{{label}}}" if kind else label
            for label, kind in zip(labels, dots, strict=True)
        ]
        return "[" + ("" if single else r"\,").join(parts) + "]"
    parts = [
        label + (_MARKS[kind - 1] if kind else "") for label, kind in zip(labels, dots, strict=True)
    ]
    text = "[" + ("" if single and not any(dots) else " ").join(parts) + "]"
    return unicodedata.normalize("NFC", text)  # precomposed letters (ḟ, ï) where Unicode has them


def _format_sum(terms: Sequence[tuple[Fraction, str]], *, latex: bool) -> str:
    """Join ``(coefficient, body)`` pairs as ``a - 2 b + c``; an empty sum is '0'."""
    if not terms:
        return "0"
    pieces = []
    for i, (coefficient, body) in enumerate(terms):
        magnitude = abs(coefficient)
        text = _format_magnitude(magnitude, latex=latex, alone=not body) + body
        if i == 0:
            pieces.append(("-" if coefficient < 0 else "") + text)
        else:
            pieces.append((" - " if coefficient < 0 else " + ") + text)
    return "".join(pieces)


# --------------------------------------------------------------------------------------------------
# Parsing '[abcd][e f ġ ï] - 2[...]'
# --------------------------------------------------------------------------------------------------

_TERM = re.compile(
    r"\s*(?P<sign>[+-]?)\s*(?P<coefficient>\d+(?:/\d+)?)?\s*\*?\s*"
    r"(?P<brackets>(?:\[[^\[\]]*\]\s*)*)"
)
_BRACKET = re.compile(r"\[([^\[\]]*)\]")

ParsedTerm = tuple[Fraction, list[tuple[tuple[str, ...], tuple[int, ...]]]]


def _parse_bracket(content: str, text: str) -> tuple[tuple[str, ...], tuple[int, ...]]:
    tokens = content.split() if any(ch.isspace() for ch in content) else None
    if tokens is None:  # single letters, each possibly followed by one combining mark
        tokens = []
        for ch in content:
            if ch in _MARKS and tokens:
                tokens[-1] += ch
            else:
                tokens.append(ch)
    labels, kinds = [], []
    for token in tokens:
        base = token.rstrip("".join(_MARKS))
        marks = token[len(base) :]
        if len(marks) > 1 or not _LABEL.match(base):
            raise ScrewkitValueError(
                f"Expected `text` to hold brackets of labels with at most one dot each, "
                f"got the entry {token!r} in {text!r}."
            )
        labels.append(base)
        kinds.append(_MARKS.index(marks) + 1 if marks else 0)
    if len(labels) != 4:
        raise ScrewkitValueError(
            f"Expected `text` to hold brackets of 4 labels, got [{content}] in {text!r}."
        )
    return tuple(labels), tuple(kinds)


def _parse(text: Any) -> list[ParsedTerm]:
    """Parse a sum of (dotted) bracket monomials with integer or rational coefficients."""
    if not isinstance(text, str):
        raise ScrewkitTypeError(f"Expected `text` to be a string, got {type(text).__name__}.")
    normalized = unicodedata.normalize("NFD", text).replace("\u2212", "-")
    terms: list[ParsedTerm] = []
    position = 0
    while position < len(normalized) and normalized[position:].strip():
        match = _TERM.match(normalized, position)
        assert match is not None  # every part of _TERM is optional
        empty = not match["coefficient"] and not match["brackets"]
        if empty or (terms and not match["sign"]):
            raise ScrewkitValueError(
                f'Expected `text` to be a sum of bracket monomials like "[abcd][efgh] - '
                f'2[abce][dfgh]", got {text!r} (cannot read it from position {position}).'
            )
        coefficient = Fraction(match["coefficient"] or 1)
        if match["sign"] == "-":
            coefficient = -coefficient
        brackets = [
            _parse_bracket(content, text) for content in _BRACKET.findall(match["brackets"])
        ]
        terms.append((coefficient, brackets))
        position = match.end()
    return terms


# --------------------------------------------------------------------------------------------------
# Points for evaluation (brackets and joins are screwkit.projective's kernels)
# --------------------------------------------------------------------------------------------------


def _point_arrays(
    points: Any, labels: Iterable[str], *, symbolic: bool | None = None
) -> dict[str, np.ndarray]:
    """Validate ``points`` (a mapping label -> (..., 4)), promote them together and broadcast."""
    if not isinstance(points, Mapping):
        raise ScrewkitTypeError(
            f"Expected `points` to be a mapping from labels to points of shape (..., 4), "
            f"got {type(points).__name__}."
        )
    wanted = sorted(set(labels))
    missing = [label for label in wanted if label not in points]
    if missing:
        raise ScrewkitValueError(
            f"Expected `points` to give a point for every label {wanted}, missing {missing}."
        )
    arrays = [
        B.as_array(points[label], f"points[{label!r}]", (4,), symbolic=symbolic) for label in wanted
    ]
    arrays = list(B.promote(*arrays))
    try:
        batch = np.broadcast_shapes(*(a.shape[:-1] for a in arrays))
    except ValueError as err:
        shapes = {label: a.shape for label, a in zip(wanted, arrays, strict=True)}
        raise ScrewkitValueError(
            f"Expected the batch shapes of `points` to broadcast, got {shapes}."
        ) from err
    return {label: np.broadcast_to(a, (*batch, 4)) for label, a in zip(wanted, arrays, strict=True)}


def _scalar(value: Any) -> Any:
    """A 0-d result as a scalar (numpy float or sympy expression), batches as arrays."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value[()]
    return value


# --------------------------------------------------------------------------------------------------
# The bracket algebra
# --------------------------------------------------------------------------------------------------


def _as_monomial(value: Any) -> BracketMonomial | None:
    if isinstance(value, BracketMonomial):
        return value
    if isinstance(value, Bracket):
        return BracketMonomial((value,))
    if _is_scalar(value):
        return BracketMonomial((), _coefficient(value, "coefficient"))
    return None


def _as_polynomial(value: Any) -> BracketPolynomial | None:
    if isinstance(value, BracketPolynomial):
        return value
    monomial = _as_monomial(value)
    return None if monomial is None else BracketPolynomial((monomial,))


def _operand(value: Any) -> BracketPolynomial | None:
    """The other operand of + - * as a polynomial; floats are refused (coefficients are exact)."""
    if isinstance(value, float | np.floating):
        _coefficient(value, "coefficient")  # raises ScrewkitTypeError naming the float
    return _as_polynomial(value)


class _Algebra:
    """Ring operations, equality and hashing shared by brackets, monomials and polynomials.

    Equality compares canonical forms (sorted labels, signed coefficients, like terms combined),
    so a bracket, the monomial 1·bracket and the one-term polynomial are equal and hash alike.
    """

    __slots__ = ()

    def _polynomial(self) -> BracketPolynomial:
        polynomial = _as_polynomial(self)
        assert polynomial is not None
        return polynomial

    def __eq__(self, other: object) -> bool:
        right = None if isinstance(other, float | np.floating) else _as_polynomial(other)
        if right is None:
            return NotImplemented
        return self._polynomial()._canonical() == right._canonical()

    def __hash__(self) -> int:
        return hash(frozenset(self._polynomial()._canonical().items()))

    def __add__(self, other: Any) -> BracketPolynomial:
        right = _operand(other)
        if right is None:
            return NotImplemented
        return BracketPolynomial(self._polynomial().terms + right.terms)

    __radd__ = __add__

    def __neg__(self) -> Any:
        return self * -1

    def __sub__(self, other: Any) -> BracketPolynomial:
        right = _operand(other)
        if right is None:
            return NotImplemented
        return self + right * -1

    def __rsub__(self, other: Any) -> BracketPolynomial:
        left = _operand(other)
        if left is None:
            return NotImplemented
        return left + self * -1

    def __mul__(self, other: Any) -> Any:
        right = _operand(other)
        if right is None:
            return NotImplemented
        left_monomial, right_monomial = _as_monomial(self), _as_monomial(other)
        if left_monomial is not None and right_monomial is not None:
            return left_monomial._times(right_monomial)
        return BracketPolynomial(a._times(b) for a in self._polynomial().terms for b in right.terms)

    __rmul__ = __mul__

    def to_sympy(self, points: Mapping[str, Any]) -> sympy.Expr:
        """Exact value as one sympy expression (floats become rationals), unexpanded.

        Examples
        --------
        >>> import sympy
        >>> t = sympy.Symbol("t")
        >>> pts = {"a": [0, 0, 0, 1], "b": [t, 0, 0, 1], "c": [0, 1, 0, 1], "d": [0, 0, 1, 1]}
        >>> sympy.expand(Bracket("abcd").to_sympy(pts))
        -t
        """
        polynomial = self._polynomial()
        arrays = _point_arrays(points, polynomial.labels, symbolic=True)
        if any(a.ndim > 1 for a in arrays.values()):
            raise ScrewkitValueError(
                "Expected `points` to be single points of shape (4,) for to_sympy, got batches "
                f"{ {label: a.shape for label, a in arrays.items()} }."
            )
        return B.sympy_module().Add(*polynomial._term_values(arrays))


@dataclass(frozen=True, eq=False, slots=True, init=False)
class Bracket(_Algebra):
    """The bracket ``[pqrs]`` of four labelled projective points (``gca.md`` §1, §5.1).

    Its value is the determinant of the 4×4 matrix whose rows are the points ``(x, y, z, w)``.
    The labels are kept in the order given (for printing); the *canonical form* is the sorted labels
    and the sign of the sorting permutation, and equality compares canonical forms, so
    ``[bacd] == -[abcd]``. A repeated label makes the bracket structurally zero.

    Parameters
    ----------
    labels : str or sequence of str
        Four labels: ``"gikj"``, ``"r1 r2 r3 r4"`` or ``("g", "i", "k", "j")``.

    Examples
    --------
    >>> b = Bracket("gikj")
    >>> str(b), b.sorted_labels, b.sign
    ('[gikj]', ('g', 'i', 'j', 'k'), -1)
    >>> Bracket("aabc").is_structurally_zero
    True
    >>> import numpy as np
    >>> points = {"g": [0, 0, 0, 1], "i": [1, 0, 0, 0], "k": [0, 1, 0, 0], "j": [0, 0, 1, 0]}
    >>> float(b.evaluate(points))  # [p u v w] = -det(u, v, w), gca.md §5.1
    -1.0
    """

    labels: tuple[str, ...]

    def __init__(self, labels: str | Sequence[str]) -> None:
        hashable = isinstance(labels, str | tuple)
        checked = _bracket_labels(labels) if hashable else _labels(labels, "labels", 4)
        object.__setattr__(self, "labels", checked)

    @property
    def sign(self) -> int:
        """Sign of the permutation sorting the labels (0 if a label repeats)."""
        return _sort_sign(self.labels)

    @property
    def sorted_labels(self) -> tuple[str, ...]:
        """The labels in sorted order (the canonical bracket is ``sign * [sorted_labels]``)."""
        return tuple(sorted(self.labels))

    @property
    def is_structurally_zero(self) -> bool:
        """True if a label repeats: the bracket vanishes whatever the points."""
        return self.sign == 0

    def __str__(self) -> str:
        return _format_bracket(self.labels, (0,) * 4, latex=False)

    def to_latex(self) -> str:
        """LaTeX of the bracket, e.g. ``[gikj]``.

        Examples
        --------
        >>> Bracket("r1 r2 r3 r4").to_latex()
        '[r1\\\\,r2\\\\,r3\\\\,r4]'
        """
        return _format_bracket(self.labels, (0,) * 4, latex=True)

    def relabel(self, mapping: Mapping[str, str]) -> Bracket:
        """Rename labels simultaneously; labels missing from ``mapping`` stay.

        Examples
        --------
        >>> str(Bracket("abcd").relabel({"a": "b", "b": "a"}))
        '[bacd]'
        """
        return Bracket(tuple(_relabel(label, mapping) for label in self.labels))

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """The determinant, batched over the points' leading axes (or exact if they are sympy).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)
            The points by label; batches broadcast against each other.

        Returns
        -------
        float, numpy.ndarray or sympy.Expr
        """
        arrays = _point_arrays(points, self.labels)
        return _scalar(P.bracket_unchecked(*(arrays[label] for label in self.labels)))


def _relabel(label: str, mapping: Mapping[str, str]) -> str:
    return _check_label(mapping[label], f"mapping[{label!r}]") if label in mapping else label


@dataclass(frozen=True, eq=False, slots=True, init=False)
class BracketMonomial(_Algebra):
    """A product ``coefficient × [..][..]…`` of brackets with an exact rational coefficient.

    Parameters
    ----------
    brackets : iterable of Bracket or label strings
        The factors, kept in the order given for printing.
    coefficient : int or fraction, default 1

    Examples
    --------
    >>> m = BracketMonomial(["abdf", "cghj"], -2)
    >>> str(m), m == -2 * Bracket("cghj") * Bracket("abdf")
    ('-2 [abdf][cghj]', True)
    """

    coefficient: Fraction
    brackets: tuple[Bracket, ...]
    _key: tuple[Fraction, tuple[tuple[str, ...], ...]] = field(repr=False)

    def __init__(
        self, brackets: Iterable[Bracket | str | Sequence[str]] = (), coefficient: Any = 1
    ) -> None:
        factors = tuple(b if isinstance(b, Bracket) else Bracket(b) for b in brackets)
        value = _coefficient(coefficient, "coefficient")
        object.__setattr__(self, "coefficient", value)
        object.__setattr__(self, "brackets", factors)
        canonical = value * math.prod(b.sign for b in factors)
        keys = tuple(sorted(b.sorted_labels for b in factors)) if canonical else ()
        object.__setattr__(self, "_key", (canonical, keys))

    @property
    def canonical(self) -> tuple[Fraction, tuple[tuple[str, ...], ...]]:
        """``(signed coefficient, sorted tuple of sorted bracket labels)``; ``(0, ())`` if zero."""
        return self._key

    @property
    def labels(self) -> tuple[str, ...]:
        """The distinct labels, sorted."""
        return tuple(sorted({label for b in self.brackets for label in b.labels}))

    def _times(self, other: BracketMonomial) -> BracketMonomial:
        return BracketMonomial(self.brackets + other.brackets, self.coefficient * other.coefficient)

    def __str__(self) -> str:
        return _format_sum([(self.coefficient, self._body(latex=False))], latex=False)

    def _body(self, *, latex: bool) -> str:
        return "".join(_format_bracket(b.labels, (0,) * 4, latex=latex) for b in self.brackets)

    def to_latex(self) -> str:
        """LaTeX, e.g. ``-2 [abdf][cghj]``."""
        return _format_sum([(self.coefficient, self._body(latex=True))], latex=True)

    def relabel(self, mapping: Mapping[str, str]) -> BracketMonomial:
        """Rename labels simultaneously (see :meth:`Bracket.relabel`)."""
        return BracketMonomial((b.relabel(mapping) for b in self.brackets), self.coefficient)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (see :meth:`Bracket.evaluate`)."""
        return BracketPolynomial((self,)).evaluate(points)


@dataclass(frozen=True, eq=False, slots=True, init=False)
class BracketPolynomial(_Algebra):
    """A sum of bracket monomials in canonical form: like terms combined, zero terms dropped.

    Each monomial keeps the letter order in which it first appeared (for printing); equality and
    hashing use canonical forms. Supports ``+``, ``-`` and ``*`` with brackets, monomials,
    polynomials and integers or fractions.

    Parameters
    ----------
    terms : iterable of BracketMonomial or Bracket

    Examples
    --------
    >>> p = BracketPolynomial.parse("[abdf][cghj] - [abdh][cgfj] + [bacd][efgh] + [abcd][hgfe]")
    >>> str(p)
    '[abdf][cghj] - [abdh][cgfj]'
    >>> len(p), p.labels
    (2, ('a', 'b', 'c', 'd', 'f', 'g', 'h', 'j'))
    """

    terms: tuple[BracketMonomial, ...]

    def __init__(self, terms: Iterable[BracketMonomial | Bracket] = ()) -> None:
        merged: dict[tuple[tuple[str, ...], ...], list[Any]] = {}
        for term in terms:
            monomial = _as_monomial(term)
            if monomial is None:
                raise ScrewkitTypeError(
                    f"Expected `terms` to hold bracket monomials, got {type(term).__name__}."
                )
            value, keys = monomial.canonical
            if value == 0:
                continue
            if keys in merged:
                merged[keys][1] += value
            else:
                merged[keys] = [monomial, value]
        kept = []
        for display, total in merged.values():
            if total != 0:
                signs = math.prod(b.sign for b in display.brackets)
                kept.append(BracketMonomial(display.brackets, total * signs))
        object.__setattr__(self, "terms", tuple(kept))

    @classmethod
    def parse(cls, text: str) -> BracketPolynomial:
        """Read ``"[abdf][cghj] - [abdh][cgfj]"`` (integer or ``p/q`` coefficients, no dots).

        Examples
        --------
        >>> BracketPolynomial.parse("1/2 [abcd] - 3[abce][dfgh]")
        BracketPolynomial('1/2 [abcd] - 3 [abce][dfgh]')
        """
        monomials = []
        for coefficient, brackets in _parse(text):
            if any(any(kinds) for _, kinds in brackets):
                raise ScrewkitValueError(
                    f"Expected `text` without dots (use DottedSum.parse for dotted brackets), "
                    f"got {text!r}."
                )
            monomials.append(BracketMonomial((labels for labels, _ in brackets), coefficient))
        return cls(monomials)

    def __len__(self) -> int:
        return len(self.terms)

    def __iter__(self) -> Iterator[BracketMonomial]:
        return iter(self.terms)

    def _canonical(self) -> dict[tuple[tuple[str, ...], ...], Fraction]:
        return {keys: value for value, keys in (m.canonical for m in self.terms)}

    def __repr__(self) -> str:
        return f"BracketPolynomial({str(self)!r})"

    def __str__(self) -> str:
        return _format_sum([(m.coefficient, m._body(latex=False)) for m in self.terms], latex=False)

    def to_latex(self) -> str:
        """LaTeX of the sum.

        Examples
        --------
        >>> BracketPolynomial.parse("[abdf][cghj] - 1/2 [abdh][cgfj]").to_latex()
        '[abdf][cghj] - \\\\tfrac{1}{2} [abdh][cgfj]'
        """
        return _format_sum([(m.coefficient, m._body(latex=True)) for m in self.terms], latex=True)

    @property
    def labels(self) -> tuple[str, ...]:
        """The distinct labels, sorted."""
        return tuple(sorted({label for m in self.terms for label in m.labels}))

    def relabel(self, mapping: Mapping[str, str]) -> BracketPolynomial:
        """Rename labels simultaneously; monomials that become equal are combined.

        Examples
        --------
        >>> str(BracketPolynomial.parse("[abcd] + [abce]").relabel({"e": "d"}))
        '2 [abcd]'
        """
        return BracketPolynomial(m.relabel(mapping) for m in self.terms)

    def _term_values(self, arrays: Mapping[str, np.ndarray]) -> list[Any]:
        """Value of each canonical term (signed coefficient × sorted brackets), brackets cached."""
        cache: dict[tuple[str, ...], Any] = {}
        symbolic = B.is_symbolic(*arrays.values())
        values = []
        for monomial in self.terms:
            coefficient, keys = monomial.canonical
            value: Any = B.from_fraction(coefficient, symbolic=symbolic)
            for key in keys:
                if key not in cache:
                    cache[key] = P.bracket_unchecked(*(arrays[label] for label in key))
                value = value * cache[key]
            values.append(value)
        return values

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points, batched over leading axes (exact if the points are sympy).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)

        Returns
        -------
        float, numpy.ndarray or sympy.Expr

        Examples
        --------
        >>> import numpy as np
        >>> p = BracketPolynomial.parse("[abcd] - 2[abdc]")  # = 3 [abcd]
        >>> pts = {"a": np.eye(4)[0], "b": np.eye(4)[1], "c": np.eye(4)[2], "d": np.eye(4)[3]}
        >>> float(p.evaluate(pts))
        3.0
        """
        arrays = _point_arrays(points, self.labels)
        return _scalar(sum(self._term_values(arrays), start=_zero(arrays)))

def _zero(arrays: Mapping[str, np.ndarray]) -> Any:
    """The additive zero matching the branch (sympy zero or a float 0)."""
    return B.from_fraction(Fraction(0), symbolic=B.is_symbolic(*arrays.values()))


# --------------------------------------------------------------------------------------------------
# Dotted notation (McMillan & White 1991; gca.md §3)
# --------------------------------------------------------------------------------------------------


def _shuffles(groups: Sequence[int]) -> list[tuple[int, tuple[int, ...]]]:
    """Signed shuffles of ``n`` items into consecutive groups of the given sizes.

    Returns ``(sign, order)`` pairs: ``order[i]`` is the item put at position ``i``; items inside a
    group are increasing (one representative per distribution), the sign is the permutation's.
    """

    def distribute(remaining: tuple[int, ...], sizes: Sequence[int]) -> Iterator[tuple[int, ...]]:
        if not sizes:
            yield ()
            return
        for chosen in itertools.combinations(remaining, sizes[0]):
            rest = tuple(i for i in remaining if i not in chosen)
            for tail in distribute(rest, sizes[1:]):
                yield chosen + tail

    return [(_sort_sign(order), order) for order in distribute(tuple(range(sum(groups))), groups)]


@dataclass(frozen=True, slots=True, init=False)
class DottedMonomial:
    """A bracket monomial some of whose letters carry dots (McMillan & White 1991).

    Letters with the same kind of dot are alternated over the positions where they stand: the sum
    over all permutations of those letters, each with its sign, divided by ``∏ k!`` over the
    brackets and dot kinds, ``k`` being the number of positions of that kind in that bracket.
    Equivalently, the signed sum over the *shuffles* (distinct distributions of the dotted letters
    among the brackets); different kinds are alternated independently (``gca.md`` §3). The divisor
    is per bracket *and kind*: ``[e f ġ ï][ḣ j̈ k l]`` has four terms, ``Alt{g↔h, i↔j}``.

    Parameters
    ----------
    brackets : sequence of label strings or sequences of labels
        The brackets, four labels each.
    dots : sequence of sequences of int, optional
        The dot kind of each letter, 0 for none, 1..4 for ``˙ ¨ ⃛ ⃜``; each kind used marks at
        least two letters. Default: no dots.
    coefficient : int or fraction, default 1

    Examples
    --------
    >>> m = DottedMonomial.parse("[a b d ḟ][c g ḣ j]")
    >>> print(m.expand())
    [abdf][cghj] - [abdh][cgfj]
    >>> print(m)
    [a b d ḟ][c g ḣ j]
    >>> print(m.to_latex())
    [abd\\dot{f}][cg\\dot{h}j]
    """

    brackets: tuple[tuple[str, ...], ...]
    dots: tuple[tuple[int, ...], ...]
    coefficient: Fraction

    def __init__(
        self,
        brackets: Iterable[str | Sequence[str] | Bracket],
        dots: Sequence[Sequence[int]] | None = None,
        coefficient: Any = 1,
    ) -> None:
        labels = tuple(_labels(b, f"brackets[{i}]", 4) for i, b in enumerate(brackets))
        kinds = tuple((0,) * 4 for _ in labels) if dots is None else _dots(dots, len(labels))
        counts = Counter(kind for row in kinds for kind in row if kind)
        lonely = sorted(kind for kind, count in counts.items() if count < 2)
        if lonely:
            raise ScrewkitValueError(
                f"Expected each dot kind in `dots` to mark at least two letters, got kinds "
                f"{lonely} on a single letter."
            )
        object.__setattr__(self, "brackets", labels)
        object.__setattr__(self, "dots", kinds)
        object.__setattr__(self, "coefficient", _coefficient(coefficient, "coefficient"))

    @classmethod
    def parse(cls, text: str) -> DottedMonomial:
        """Read one dotted monomial, e.g. ``"-[g i k j][a b d ḟ][c g ḣ j]"``.

        Precomposed characters (``ḟ``, ``ï``) and combining marks are both accepted.

        Examples
        --------
        >>> DottedMonomial.parse("2[e f ġ ï][ḣ j̈ k l]").dots
        ((0, 0, 1, 2), (1, 2, 0, 0))
        """
        terms = _parse(text)
        if len(terms) != 1:
            raise ScrewkitValueError(
                f"Expected `text` to be one dotted monomial, got {len(terms)} terms in {text!r}."
            )
        coefficient, brackets = terms[0]
        return cls([b for b, _ in brackets], [d for _, d in brackets], coefficient)

    @classmethod
    def from_monomial(cls, monomial: BracketMonomial | Bracket) -> DottedMonomial:
        """The monomial with no dots.

        Examples
        --------
        >>> print(DottedMonomial.from_monomial(-Bracket("gikj")))
        -[gikj]
        """
        m = _as_monomial(monomial)
        if m is None:
            raise ScrewkitTypeError(
                f"Expected `monomial` to be a BracketMonomial or a Bracket, "
                f"got {type(monomial).__name__}."
            )
        return cls([b.labels for b in m.brackets], None, m.coefficient)

    def expand(self) -> BracketPolynomial:
        """The bracket polynomial: signed sum over the shuffles of each dot kind.

        Examples
        --------
        >>> print(DottedMonomial.parse("[e f ġ ï][ḣ j̈ k l]").expand())
        [efgi][hjkl] - [efgj][hikl] - [efhi][gjkl] + [efhj][gikl]
        """
        choices = []  # per kind: list of (sign, {(bracket, slot): label})
        for kind in sorted({k for row in self.dots for k in row if k}):
            places = [
                (b, s) for b, row in enumerate(self.dots) for s, k in enumerate(row) if k == kind
            ]
            letters = [self.brackets[b][s] for b, s in places]
            sizes = [n for _, n in sorted(Counter(b for b, _ in places).items())]
            choices.append(
                [
                    (sign, {place: letters[i] for place, i in zip(places, order, strict=True)})
                    for sign, order in _shuffles(sizes)
                ]
            )
        terms = []
        for combination in itertools.product(*choices):
            sign = math.prod(s for s, _ in combination)
            assignment = {place: label for _, part in combination for place, label in part.items()}
            brackets = [
                tuple(assignment.get((b, s), label) for s, label in enumerate(labels))
                for b, labels in enumerate(self.brackets)
            ]
            terms.append(BracketMonomial(brackets, sign * self.coefficient))
        return BracketPolynomial(terms)

    def relabel(self, mapping: Mapping[str, str]) -> DottedMonomial:
        """Rename labels simultaneously, keeping the dots.

        Examples
        --------
        >>> print(DottedMonomial.parse("[a b ċ d][ė f g h]").relabel({"e": "x"}))
        [a b ċ d][ẋ f g h]
        """
        renamed = [tuple(_relabel(label, mapping) for label in b) for b in self.brackets]
        return DottedMonomial(renamed, self.dots, self.coefficient)

    def _body(self, *, latex: bool) -> str:
        return "".join(
            _format_bracket(b, d, latex=latex)
            for b, d in zip(self.brackets, self.dots, strict=True)
        )

    def __str__(self) -> str:
        return _format_sum([(self.coefficient, self._body(latex=False))], latex=False)

    def to_latex(self) -> str:
        """LaTeX, ``\\dot``, ``\\ddot``, ``\\dddot``, ``\\ddddot`` (amsmath) over dotted letters."""
        return _format_sum([(self.coefficient, self._body(latex=True))], latex=True)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (through :meth:`expand`)."""
        return self.expand().evaluate(points)


def _dots(dots: Any, count: int) -> tuple[tuple[int, ...], ...]:
    rows = tuple(tuple(row) for row in dots) if isinstance(dots, Sequence) else None
    if rows is None or len(rows) != count or any(len(row) != 4 for row in rows):
        raise ScrewkitValueError(
            f"Expected `dots` to give 4 dot kinds for each of the {count} brackets, got {dots!r}."
        )
    if any(
        not isinstance(k, int) or isinstance(k, bool) or not 0 <= k <= 4 for r in rows for k in r
    ):
        raise ScrewkitValueError(
            f"Expected the dot kinds in `dots` to be integers 0 (none) to 4, got {dots!r}."
        )
    return rows


@dataclass(frozen=True, slots=True, init=False)
class DottedSum:
    """A sum of dotted monomials, e.g. the grouped superbracket of ``gca.md`` §2.2.

    Parameters
    ----------
    terms : iterable of DottedMonomial

    Examples
    --------
    >>> s = DottedSum.parse("[a b d ḟ][c g ḣ j] - [a b c d]")
    >>> len(s.terms), len(s.expand())
    (2, 3)
    """

    terms: tuple[DottedMonomial, ...]

    def __init__(self, terms: Iterable[DottedMonomial]) -> None:
        items = tuple(terms)
        for item in items:
            if not isinstance(item, DottedMonomial):
                raise ScrewkitTypeError(
                    f"Expected `terms` to hold DottedMonomial values, got {type(item).__name__}."
                )
        object.__setattr__(self, "terms", items)

    @classmethod
    def parse(cls, text: str) -> DottedSum:
        """Read a sum of dotted monomials.

        Examples
        --------
        >>> print(DottedSum.parse("[abcd][e f ġ ï][ḣ j̈ k l] - 2[a b ċ d][ė f g h]"))
        [abcd][e f ġ ï][ḣ j̈ k l] - 2 [a b ċ d][ė f g h]
        """
        return cls(
            DottedMonomial([b for b, _ in brackets], [d for _, d in brackets], coefficient)
            for coefficient, brackets in _parse(text)
        )

    def expand(self) -> BracketPolynomial:
        """Sum of the expansions of the terms."""
        return BracketPolynomial(m for term in self.terms for m in term.expand().terms)

    def relabel(self, mapping: Mapping[str, str]) -> DottedSum:
        """Rename labels simultaneously in every term."""
        return DottedSum(term.relabel(mapping) for term in self.terms)

    def _pairs(self, *, latex: bool) -> list[tuple[Fraction, str]]:
        return [(t.coefficient, t._body(latex=latex)) for t in self.terms]

    def __str__(self) -> str:
        return _format_sum(self._pairs(latex=False), latex=False)

    def to_latex(self) -> str:
        """LaTeX of the sum."""
        return _format_sum(self._pairs(latex=True), latex=True)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (through :meth:`expand`)."""
        return self.expand().evaluate(points)


# --------------------------------------------------------------------------------------------------
# The superbracket
# --------------------------------------------------------------------------------------------------

_SLOTS = "abcdefghijkl"

# gca.md §2.1: [ab,cd,ef,gh,ij,kl] in the reference convention (constant +1). Each monomial is a
# standard Young tableau, so the form is unique; tests/test_gca.py proves it against the 6×6 det.
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


def _lines(lines: Any) -> tuple[tuple[str, str], ...]:
    """Validate six lines given as 2-tuples of labels (or two-letter strings)."""
    if isinstance(lines, str) or not isinstance(lines, Sequence):
        raise ScrewkitTypeError(
            f"Expected `lines` to be a sequence of six pairs of labels, got {type(lines).__name__}."
        )
    if len(lines) != 6:
        raise ScrewkitValueError(f"Expected `lines` to hold 6 lines, got {len(lines)}.")
    out = []
    for i, line in enumerate(lines):
        p, q = _labels(line, f"lines[{i}]", 2)
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
    slots = [label for line in _lines(lines) for label in line]
    return _EXPANSION.relabel(dict(zip(_SLOTS, slots, strict=True)))


def superbracket_grouped(lines: Sequence[Sequence[str] | str]) -> DottedSum:
    """The superbracket as five dotted monomials (``gca.md`` §2.2), same 24 terms.

    ``[abcd][e f ġ ï][ḣ j̈ k l] + [a b ḋ g̈][ċ e f i⃛][ḧ j⃛ k l]
    + [a b ḋ ë]([ċ f̈ g h][i j k l] − [ċ g h i][f̈ j k l] + [ċ g h j][f̈ i k l])``,
    with the slots replaced by the labels of ``lines``.

    Examples
    --------
    >>> g = superbracket_grouped(["ab", "cd", "ef", "gh", "ij", "kl"])
    >>> print(g.terms[0])
    [abcd][e f ġ ï][ḣ j̈ k l]
    >>> g.expand() == superbracket_expansion(["ab", "cd", "ef", "gh", "ij", "kl"])
    True
    """
    slots = [label for line in _lines(lines) for label in line]
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
    >>> import numpy as np
    >>> e = np.eye(4)
    >>> pts = {"o": e[3], "x": e[0], "y": e[1], "z": e[2]}
    >>> # forces along the axes through the origin and couples about them: det = +1 here
    >>> float(superbracket(pts, ["ox", "oy", "oz", "yz", "zx", "xy"]))
    1.0
    """
    pairs = _lines(lines)
    arrays = _point_arrays(points, [label for line in pairs for label in line])
    matrix = np.stack([P.join_unchecked(arrays[p], arrays[q]) for p, q in pairs], axis=-2)
    if B.is_symbolic(matrix) and matrix.ndim != 2:
        raise ScrewkitValueError(
            f"Expected sympy `points` to be single points of shape (4,), got batch shape "
            f"{matrix.shape[:-2]}."
        )
    return _scalar(B.det(matrix))


# --------------------------------------------------------------------------------------------------
# Sampling and numeric zero tests
# --------------------------------------------------------------------------------------------------


def _check_positive_int(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ScrewkitValueError(f"Expected `{name}` to be a positive integer, got {value!r}.")
    return int(value)


def _check_rtol(rtol: Any, name: str = "rtol") -> float:
    if isinstance(rtol, bool) or not isinstance(rtol, int | float) or not 0 <= rtol < 1:
        raise ScrewkitValueError(f"Expected `{name}` to be a number in [0, 1), got {rtol!r}.")
    return float(rtol)


def _draw(
    sampler: Any, n_samples: int, rng: np.random.Generator, labels: Iterable[str] | None = None
) -> dict[str, np.ndarray]:
    """Draw ``n_samples`` configurations and stack them: label -> (n_samples, 4) float array.

    The Python loop only *draws* configurations (the sampler's contract is one configuration per
    call); every evaluation afterwards is vectorised over the stacked samples.
    """
    if not callable(sampler):
        raise ScrewkitTypeError(
            f"Expected `sampler` to be a callable rng -> {{label: point (4,)}}, "
            f"got {type(sampler).__name__}."
        )
    n = _check_positive_int(n_samples, "n_samples")
    draws = [sampler(rng) for _ in range(n)]
    if not all(isinstance(d, Mapping) for d in draws):
        raise ScrewkitTypeError(
            f"Expected `sampler(rng)` to return a mapping label -> point (4,), "
            f"got {type(draws[0]).__name__}."
        )
    wanted = sorted(draws[0]) if labels is None else sorted(set(labels))
    out = {}
    for label in wanted:
        missing = [i for i, d in enumerate(draws) if label not in d]
        if missing:
            raise ScrewkitValueError(
                f"Expected `sampler(rng)` to give a point for label {label!r}, missing in draw "
                f"{missing[0]} (labels {sorted(draws[missing[0]])})."
            )
        name = f"sampler(rng)[{label!r}]"
        stacked = np.stack([B.as_array(d[label], name, (4,), symbolic=False) for d in draws])
        if stacked.ndim != 2:
            raise ScrewkitValueError(
                f"Expected `{name}` to be one point of shape (4,), got {stacked.shape[1:]}."
            )
        if np.any(np.all(stacked == 0, axis=-1)):
            raise DegenerateGeometryError(
                f"Expected `{name}` to be a projective point, got the zero vector."
            )
        out[label] = stacked
    return out


def _relative_brackets(
    samples: Mapping[str, np.ndarray], quads: Sequence[Sequence[str]]
) -> np.ndarray:
    """``|[pqrs]| / (|p||q||r||s|)`` (≤ 1, Hadamard) for each quad: (n_samples, n_quads)."""
    if not quads:
        return np.zeros((next(iter(samples.values())).shape[0], 0))
    labels = sorted({label for quad in quads for label in quad})
    index = {label: i for i, label in enumerate(labels)}
    stacked = np.stack([samples[label] for label in labels])  # (n_labels, n_samples, 4)
    rows = np.array([[index[label] for label in quad] for quad in quads])  # (n_quads, 4)
    gathered = stacked[rows]  # (n_quads, 4, n_samples, 4)
    values = P.bracket_unchecked(*(gathered[:, i] for i in range(4)))
    norms = np.linalg.norm(gathered, axis=-1).prod(axis=1)
    return (np.abs(values) / norms).T


def _vanishing_quads(
    samples: Mapping[str, np.ndarray], quads: Sequence[tuple[str, ...]], rtol: float
) -> dict[tuple[str, ...], bool]:
    """Whether each bracket (distinct labels) vanishes on every sample (relative to Hadamard)."""
    zero = np.all(_relative_brackets(samples, quads) <= rtol, axis=0)
    return dict(zip(quads, (bool(z) for z in zero), strict=True))


def _drop_zero_monomials(
    poly: BracketPolynomial, samples: Mapping[str, np.ndarray], rtol: float
) -> BracketPolynomial:
    quads = sorted({key for m in poly.terms for key in m.canonical[1]})
    zero = _vanishing_quads(samples, quads, rtol)
    return BracketPolynomial(m for m in poly.terms if not any(zero[k] for k in m.canonical[1]))


def structural_zeros(
    poly: BracketPolynomial,
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rtol: float = 1e-9,
    rng: np.random.Generator | int = 0,
) -> BracketPolynomial:
    """Drop the monomials that vanish on every configuration the sampler draws (``gca.md`` §6.2).

    A bracket is taken as zero on a sample when ``|[pqrs]| <= rtol · |p||q||r||s|`` (the Hadamard
    bound, so the test is independent of units and of the points' scaling); a monomial is dropped
    when one of its brackets is zero on all ``n_samples`` samples. This catches repeated points,
    four infinite points and every incidence the sampler respects (collinear, coplanar points).

    Parameters
    ----------
    poly : BracketPolynomial
    sampler : callable
        ``rng -> {label: point (4,)}``, one random configuration satisfying the incidences.
    n_samples : int, default 20
    rtol : float, default 1e-9
        Relative zero threshold of a bracket (structural zeros are at round-off level, ~1e-16).
    rng : numpy.random.Generator or int, default 0
        The generator passed to ``sampler`` (or its seed).

    Returns
    -------
    BracketPolynomial
        The surviving monomials.

    Examples
    --------
    >>> import numpy as np
    >>> def collinear(rng):  # a, b, c on one line
    ...     a, b = rng.normal(size=4), rng.normal(size=4)
    ...     return {"a": a, "b": b, "c": 2 * a - 3 * b, "d": rng.normal(size=4),
    ...             "e": rng.normal(size=4)}
    >>> str(structural_zeros(BracketPolynomial.parse("[abcd] + [abde]"), collinear))
    '[abde]'
    """
    samples = _draw(sampler, n_samples, np.random.default_rng(rng), poly.labels)
    return _drop_zero_monomials(poly, samples, _check_rtol(rtol))


def _drop_zero_subsums(
    poly: BracketPolynomial, samples: Mapping[str, np.ndarray], rtol: float, max_terms: int
) -> BracketPolynomial:
    k = len(poly)
    if k < 2 or k > max_terms:
        return poly
    arrays = {label: samples[label] for label in poly.labels}
    values = np.stack(poly._term_values(arrays), axis=-1)  # (n_samples, k)
    scale = np.abs(values).sum(axis=-1, keepdims=True)
    drop = (np.arange(2**k)[:, None] >> np.arange(k)) & 1  # (2^k, k): 1 = dropped
    vanishing = np.all(np.abs(values @ drop.T) <= rtol * scale, axis=0)
    best = int(np.argmax(np.where(vanishing, drop.sum(axis=1), -1)))
    return BracketPolynomial(m for m, d in zip(poly.terms, drop[best], strict=True) if not d)


def drop_zero_subsums(
    poly: BracketPolynomial,
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rtol: float = 1e-9,
    max_terms: int = 16,
    rng: np.random.Generator | int = 0,
) -> BracketPolynomial:
    """Drop the largest set of monomials whose *sum* vanishes on every sampled configuration.

    A numeric stand-in for the syzygies of ``gca.md`` §6.3: on the incidence variety some sums of
    non-zero monomials vanish (Grassmann–Plücker relations combined with the incidences). All
    ``2^k`` subsets are scored at once (vectorised); a subset vanishes when its sum is at most
    ``rtol`` times the sum of the monomials' absolute values on every sample. Verify the result
    with :func:`check_proportional`; :func:`simplify_superbracket` does.

    Parameters
    ----------
    poly : BracketPolynomial
    sampler : callable
        ``rng -> {label: point (4,)}`` (see :func:`structural_zeros`).
    n_samples : int, default 20
    rtol : float, default 1e-9
    max_terms : int, default 16
        Polynomials with more monomials are returned unchanged (the search is ``2^k``).
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    BracketPolynomial
        Equal to ``poly`` on the sampled variety, with fewer monomials if a subsum vanishes.

    Examples
    --------
    >>> import numpy as np
    >>> def sampler(rng):  # d = b + c, so [abde] = [abbe] + [abce] = [abce]
    ...     pts = {x: rng.normal(size=4) for x in "abcef"}
    ...     return {**pts, "d": pts["b"] + pts["c"]}
    >>> str(drop_zero_subsums(BracketPolynomial.parse("[abde] - [abce] + [abef]"), sampler))
    '[abef]'
    """
    samples = _draw(sampler, n_samples, np.random.default_rng(rng), poly.labels)
    return _drop_zero_subsums(
        poly, samples, _check_rtol(rtol), _check_positive_int(max_terms, "max_terms")
    )


# --------------------------------------------------------------------------------------------------
# Exhaustive ordering search (gca.md §6.4)
# --------------------------------------------------------------------------------------------------


@functools.cache
def _orderings() -> tuple[np.ndarray, np.ndarray]:
    """All 6!·2^6 orderings as slot -> caller position maps (46080, 12), and their signs.

    Ordering ``(π, f)`` puts the caller's line ``π[k]`` in place ``k``, its points swapped if
    ``f[k]``; the identity comes first. Its superbracket is ``sgn(π)·(-1)^Σf`` times the caller's
    (swapping two rows or negating one row of the 6×6 matrix flips the sign).
    """
    perms = np.array(list(itertools.permutations(range(6))))
    flips = np.array(list(itertools.product((0, 1), repeat=6)))
    first = 2 * perms[:, None, :] + flips[None, :, :]
    second = 2 * perms[:, None, :] + 1 - flips[None, :, :]
    slot_positions = np.stack([first, second], axis=-1).reshape(-1, 12)
    perm_signs = np.array([_sort_sign(tuple(p)) for p in perms])
    signs = (perm_signs[:, None] * (-1) ** flips.sum(axis=1)[None, :]).reshape(-1)
    return slot_positions, signs


@functools.cache
def _ordering_brackets() -> np.ndarray:
    """For every ordering, the caller positions of each bracket of the 24 template monomials
    (gca.md §2.1), coded as one index into the 12^4 ordered 4-tuples: shape (3, 46080, 24)."""
    brackets = [m.brackets for m in _EXPANSION]
    slots = np.array([[[_SLOTS.index(x) for x in b.labels] for b in t] for t in brackets])
    slot_positions = _orderings()[0].astype(np.int16)
    flat = np.zeros((3, len(slot_positions), len(slots)), dtype=np.int16)  # 12^4 < 2^15
    for s in range(4):
        flat = flat * 12 + slot_positions[:, slots[..., s]].transpose(2, 0, 1)
    return flat


def _ordering_counts(positions: Sequence[str], zero: Mapping[tuple[str, ...], bool]) -> np.ndarray:
    """Number of surviving monomials (after combining like terms) for every ordering, (46080,)."""
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

    first, second, third = code.astype(np.int32)[_ordering_brackets()]  # each (46080, 24)
    signs = np.array([int(m.coefficient) for m in _EXPANSION])
    coefficients = signs * np.sign(first) * np.sign(second) * np.sign(third)
    # A monomial is identified by the sorted triple of its label sets: (low, middle, high).
    first, second, third = np.abs(first), np.abs(second), np.abs(third)
    low = np.minimum(np.minimum(first, second), third)
    high = np.maximum(np.maximum(first, second), third)
    n = len(quads) + 1
    keys = (low * n + (first + second + third - low - high)) * n + high
    order = np.argsort(keys, axis=1)
    keys = np.take_along_axis(keys, order, axis=1)
    coefficients = np.take_along_axis(coefficients, order, axis=1)
    starts = np.ones(keys.shape, dtype=bool)
    starts[:, 1:] = keys[:, 1:] != keys[:, :-1]
    group = np.cumsum(starts.ravel()) - 1
    totals = np.bincount(group, weights=coefficients.ravel())
    rows = np.repeat(np.arange(len(keys)), keys.shape[1])[starts.ravel()]
    return np.bincount(rows, weights=totals != 0, minlength=len(keys)).astype(int)


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
        """JSON-ready summary."""
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


def _best_ordering(
    pairs: tuple[tuple[str, str], ...], samples: Mapping[str, np.ndarray], rtol: float
) -> OrderingSearch:
    positions = [label for line in pairs for label in line]
    quads = list(itertools.combinations(sorted(set(positions)), 4))
    zero = _vanishing_quads(samples, quads, rtol)
    counts = _ordering_counts(positions, zero)
    best = int(np.argmin(counts))  # ties: the first, so the caller's order wins if it is optimal
    slot_positions, signs = _orderings()
    chosen = tuple(
        (positions[slot_positions[best, 2 * k]], positions[slot_positions[best, 2 * k + 1]])
        for k in range(6)
    )
    polynomial = _drop_zero_monomials(superbracket_expansion(chosen), samples, rtol)
    values, tallies = np.unique(counts, return_counts=True)
    return OrderingSearch(
        lines=chosen,
        sign=int(signs[best]),
        polynomial=polynomial,
        caller_count=int(counts[0]),
        histogram=tuple((int(v), int(t)) for v, t in zip(values, tallies, strict=True)),
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
    structurally zero ones (as in :func:`structural_zeros`); then every ordering is scored at once
    with numpy: the 24 template monomials are mapped through each ordering, monomials with a zero
    bracket are dropped and like terms are combined (``gca.md`` §6.4). Ties go to the earliest
    ordering, the caller's own first.

    Parameters
    ----------
    lines : sequence of six pairs of labels
    sampler : callable
        ``rng -> {label: point (4,)}`` (see :func:`structural_zeros`).
    n_samples : int, default 20
    rtol : float, default 1e-9
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    OrderingSearch

    Examples
    --------
    >>> import numpy as np
    >>> def generic(rng):
    ...     return {x: rng.normal(size=4) for x in "abcdefghijkl"}
    >>> result = best_ordering(["ab", "cd", "ef", "gh", "ij", "kl"], generic)
    >>> result.count, result.histogram  # nothing vanishes: 24 in every ordering
    (24, ((24, 46080),))
    """
    pairs = _lines(lines)
    labels = [label for line in pairs for label in line]
    samples = _draw(sampler, n_samples, np.random.default_rng(rng), labels)
    return _best_ordering(pairs, samples, _check_rtol(rtol))


# --------------------------------------------------------------------------------------------------
# Collecting factors and dotted pairs
# --------------------------------------------------------------------------------------------------


class _Interchange:
    """When a finite point may replace another in a bracket without changing its value.

    With weights 1, ``x − y`` is the infinite point of line xy, so ``[x P Q R] = [y P Q R]`` iff
    ``[(x − y) P Q R] = 0``. That holds when P, Q, R are all infinite (four infinite points,
    ``gca.md`` §5.1: the H4's [eikj] = [gikj]) or when the direction of xy is one of P, Q, R
    (a declared collinear triple x, y, u with u infinite). Replacements are symmetric, so equal
    brackets form classes; :meth:`canonical` writes every bracket as its class's largest member.
    """

    def __init__(self, finite: Any, infinite: Any, collinear: Any) -> None:
        self.finite = _labels(finite, "finite")
        self.infinite = _labels(infinite, "infinite")
        both = sorted(set(self.finite) & set(self.infinite))
        if both:
            raise ScrewkitValueError(
                f"Expected `finite` and `infinite` to be disjoint, got {both} in both."
            )
        if isinstance(collinear, str) or not isinstance(collinear, Sequence):
            raise ScrewkitTypeError(
                f"Expected `collinear` to be a sequence of triples (finite, finite, infinite), "
                f"got {type(collinear).__name__}."
            )
        self.directions: dict[frozenset[str], set[str]] = {}
        for i, triple in enumerate(collinear):
            x, y, u = _labels(triple, f"collinear[{i}]", 3)
            if x not in self.finite or y not in self.finite or u not in self.infinite:
                raise ScrewkitValueError(
                    f"Expected `collinear[{i}]` to be (finite, finite, infinite) labels as "
                    f"declared in `finite` and `infinite`, got {(x, y, u)}."
                )
            self.directions.setdefault(frozenset((x, y)), set()).add(u)
        self._reach: dict[tuple[str, ...], dict[tuple[str, ...], tuple[str, ...]]] = {}

    def _allowed(self, x: str, y: str, rest: Sequence[str]) -> bool:
        if all(label in self.infinite for label in rest):
            return True
        return bool(self.directions.get(frozenset((x, y)), set()) & set(rest))

    def reachable(self, labels: tuple[str, ...]) -> dict[tuple[str, ...], tuple[str, ...]]:
        """Brackets equal to ``labels`` by in-place replacements: sorted labels -> labels."""
        if labels in self._reach:
            return self._reach[labels]
        found = {tuple(sorted(labels)): labels}
        frontier = [labels]
        while frontier:
            current = frontier.pop()
            for slot, x in enumerate(current):
                if x not in self.finite:
                    continue
                rest = current[:slot] + current[slot + 1 :]
                for y in self.finite:
                    if y in current or not self._allowed(x, y, rest):
                        continue
                    new = (*current[:slot], y, *current[slot + 1 :])
                    if tuple(sorted(new)) not in found:
                        found[tuple(sorted(new))] = new
                        frontier.append(new)
        self._reach[labels] = found
        return found

    def representative(self, labels: tuple[str, ...]) -> tuple[str, ...]:
        """The largest member of the class of ``labels``, written in place (same value)."""
        reachable = self.reachable(labels)
        return reachable[max(reachable)]

    def canonical(self, poly: BracketPolynomial) -> BracketPolynomial:
        """``poly`` with every bracket replaced by the largest member of its class."""
        return BracketPolynomial(
            BracketMonomial(
                [Bracket(self.representative(b.labels)) for b in m.brackets],
                m.coefficient,
            )
            for m in poly.terms
        )

    def differences(
        self, old: Iterable[Bracket], new: Iterable[Bracket]
    ) -> list[tuple[Bracket, Bracket]]:
        """Pairs (old bracket, equal new bracket) where two equal monomials are written apart."""
        unmatched = list(new)
        pairs = []
        for b in old:
            key = sorted(self.representative(b.labels))
            match = next(c for c in unmatched if sorted(self.representative(c.labels)) == key)
            unmatched.remove(match)
            if match.sorted_labels != b.sorted_labels:
                pairs.append((b, match))
        return pairs


def _unify_brackets(
    poly: BracketPolynomial, rules: _Interchange
) -> tuple[BracketPolynomial, list[tuple[Bracket, Bracket]]]:
    """Write equal brackets of ``poly`` alike, so that like terms combine and common factors show.

    Within each class of equal brackets present in ``poly``, the representative is the one that
    occurs in the most monomials (ties: the largest sorted labels); it is written with the letters
    of each occurrence replaced in place, which keeps the value.
    """
    occurrences = Counter(key for m in poly.terms for key in {b.sorted_labels for b in m.brackets})
    substitutions: list[tuple[Bracket, Bracket]] = []
    monomials = []
    for m in poly.terms:
        factors = []
        for b in m.brackets:
            reachable = rules.reachable(b.labels)
            members = [key for key in reachable if key in occurrences]
            new = Bracket(reachable[max(members, key=lambda k: (occurrences[k], k))])
            if new.labels != b.labels and (b, new) not in substitutions:
                substitutions.append((b, new))
            factors.append(new)
        monomials.append(BracketMonomial(factors, m.coefficient))
    return BracketPolynomial(monomials), substitutions


def _transpositions(item: DottedMonomial) -> Iterator[tuple[DottedMonomial, DottedMonomial]]:
    """``(item with x, y dotted by a new kind, item with x and y exchanged)`` for undotted
    letters x ≠ y in different brackets; the first expands to ``item − second`` exactly."""
    kind = max((k for row in item.dots for k in row), default=0) + 1
    if kind > len(_MARKS):
        return
    places = [(b, s) for b, row in enumerate(item.dots) for s, k in enumerate(row) if not k]
    for (b1, s1), (b2, s2) in itertools.combinations(places, 2):
        x, y = item.brackets[b1][s1], item.brackets[b2][s2]
        if b1 == b2 or x == y:
            continue
        labels = [list(b) for b in item.brackets]
        dots = [list(d) for d in item.dots]
        dots[b1][s1] = dots[b2][s2] = kind
        labels[b1][s1], labels[b2][s2] = y, x
        yield (
            DottedMonomial(item.brackets, dots, item.coefficient),
            DottedMonomial(labels, item.dots, item.coefficient),
        )


def _pair_dotted(
    items: list[DottedMonomial], rules: _Interchange
) -> tuple[list[DottedMonomial], list[tuple[Bracket, Bracket]]]:
    """Merge pairs ``A + B`` with ``B = −(A with x↔y)`` into A with x, y dotted, while possible.

    ``B`` is compared with ``−(A with x↔y)`` up to equal brackets (:class:`_Interchange`); the
    brackets written differently are returned as substitutions. Each merge is checked: the
    dotted monomial's expansion equals ``A + B`` up to equal brackets.
    """
    items = list(items)
    substitutions: list[tuple[Bracket, Bracket]] = []
    merged = True
    while merged:
        merged = False
        forms = [rules.canonical(item.expand()) for item in items]
        index = {form: j for j, form in enumerate(forms)}
        for i, item in enumerate(items):
            for dotted, swapped in _transpositions(item):
                target = rules.canonical(swapped.expand())
                j = index.get(-1 * target) if target else None
                if j is None or j == i:
                    continue
                if rules.canonical(dotted.expand()) != forms[i] + forms[j]:
                    continue
                old = [Bracket(b) for b in items[j].brackets]
                for pair in rules.differences(old, [Bracket(b) for b in swapped.brackets]):
                    if pair not in substitutions:
                        substitutions.append(pair)
                items[i] = dotted
                del items[j]
                merged = True
                break
            if merged:
                break
    return items, substitutions


@dataclass(frozen=True, slots=True)
class FactoredForm:
    """``coefficient × common brackets × (a sum of dotted monomials)`` (:func:`collect_factors`).

    Attributes
    ----------
    coefficient : Fraction
        The constant factor (sign and content).
    common : tuple of Bracket
        The brackets common to every monomial.
    rest : DottedSum
        The remaining sum; its first term has a positive coefficient.
    substitutions : tuple of (Bracket, Bracket)
        The bracket identities used, ``old = new``: valid for finite points of weight 1 and the
        declared collinear triples (``gca.md`` §5.1). Without them :meth:`expand` reproduces the
        factored polynomial exactly; with them, its value on such configurations.
    """

    coefficient: Fraction
    common: tuple[Bracket, ...]
    rest: DottedSum
    substitutions: tuple[tuple[Bracket, Bracket], ...] = ()

    @property
    def factors(self) -> tuple[Bracket | DottedSum, ...]:
        """The non-constant factors: each common bracket, then the rest unless it is 1.

        A rest made of one undotted monomial is split into its brackets.
        """
        if len(self.rest.terms) == 1 and not any(any(d) for d in self.rest.terms[0].dots):
            return self.common + tuple(Bracket(b) for b in self.rest.terms[0].brackets)
        return (*self.common, self.rest)

    def expand(self) -> BracketPolynomial:
        """The bracket polynomial ``coefficient × common × rest``."""
        return BracketMonomial(self.common, self.coefficient) * self.rest.expand()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (text, LaTeX, parts and substitutions)."""
        return {
            "text": str(self),
            "latex": self.to_latex(),
            "coefficient": str(self.coefficient),
            "common": [str(b) for b in self.common],
            "rest": str(self.rest),
            "substitutions": [[str(old), str(new)] for old, new in self.substitutions],
        }

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (through :meth:`expand`)."""
        return self.expand().evaluate(points)

    def _text(self, *, latex: bool) -> str:
        if self.coefficient == 0:
            return "0"
        head = "".join(_format_bracket(b.labels, (0,) * 4, latex=latex) for b in self.common)
        terms = self.rest.terms
        if len(terms) == 1 and terms[0].coefficient == 1:
            body = head + terms[0]._body(latex=latex)
        else:
            rest = self.rest.to_latex() if latex else str(self.rest)
            body = head + (r"\left(" + rest + r"\right)" if latex else f"({rest})")
        return _format_sum([(self.coefficient, body)], latex=latex)

    def __str__(self) -> str:
        return self._text(latex=False)

    def to_latex(self) -> str:
        """LaTeX of the factored form."""
        return self._text(latex=True)


def collect_factors(
    poly: BracketPolynomial,
    *,
    finite: Sequence[str] = (),
    infinite: Sequence[str] = (),
    collinear: Sequence[Sequence[str] | str] = (),
) -> FactoredForm:
    """Factor a bracket polynomial: equal brackets, common factors, dotted pairs (``gca.md`` §6.3).

    1. Equal brackets are written alike. With finite points of weight 1, ``[x P Q R] = [y P Q R]``
       for finite x, y when P, Q, R are infinite (a bracket with one finite and three infinite
       points does not depend on the finite point, ``gca.md`` §5.1; the H4's [eikj] = [gikj]), or
       when ``(x, y, u)`` is a declared collinear triple and u is among P, Q, R.
    2. Like terms are combined; brackets common to all monomials and the rational content are
       factored out.
    3. Pairs ``A + B`` with ``B = −(A with x↔y)`` (x, y in different brackets) become one dotted
       monomial, repeatedly (new dot kinds), each merge checked with
       :meth:`DottedMonomial.expand` (exactly, up to the equal brackets of step 1).

    Parameters
    ----------
    poly : BracketPolynomial
    finite, infinite : sequence of str
        Labels of finite points (weight 1 is assumed) and of infinite points (weight 0).
    collinear : sequence of (str, str, str)
        Triples ``(x, y, u)``: finite x, y whose difference is a multiple of the infinite point u
        (u is the direction of line xy).

    Returns
    -------
    FactoredForm
        ``expand()`` equals ``poly`` exactly when no substitution was used, and has the value of
        ``poly`` on every configuration satisfying the declarations otherwise.

    Examples
    --------
    >>> p = BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")
    >>> f = collect_factors(p, finite="aceg", infinite="bdfhijk", collinear=["egj"])
    >>> print(f)
    -[gikj][a b d ḟ][c g ḣ j]
    >>> [f"{old} = {new}" for old, new in f.substitutions]
    ['[eikj] = [gikj]', '[cefj] = [cgfj]']
    """
    rules = _Interchange(finite, infinite, collinear)
    unified, substitutions = _unify_brackets(poly, rules)
    if not unified.terms:
        return FactoredForm(Fraction(0), (), DottedSum(()), tuple(substitutions))
    counts = [Counter(b.sorted_labels for b in m.brackets) for m in unified.terms]
    shared = functools.reduce(lambda a, b: a & b, counts)
    common: list[Bracket] = []
    for b in unified.terms[0].brackets:
        if shared[b.sorted_labels] > sum(c.sorted_labels == b.sorted_labels for c in common):
            common.append(b)
    rest = []
    for m in unified.terms:
        remaining, coefficient = list(m.brackets), m.coefficient
        for c in common:
            k = next(i for i, b in enumerate(remaining) if b.sorted_labels == c.sorted_labels)
            coefficient *= remaining.pop(k).sign * c.sign
        rest.append(DottedMonomial.from_monomial(BracketMonomial(remaining, coefficient)))
    paired, more = _pair_dotted(rest, rules)
    substitutions += [pair for pair in more if pair not in substitutions]
    content = Fraction(
        math.gcd(*(t.coefficient.numerator for t in paired)),
        math.lcm(*(t.coefficient.denominator for t in paired)),
    )
    if paired[0].coefficient < 0:
        content = -content
    terms = [DottedMonomial(t.brackets, t.dots, t.coefficient / content) for t in paired]
    return FactoredForm(content, tuple(common), DottedSum(terms), tuple(substitutions))


# --------------------------------------------------------------------------------------------------
# Numeric verification and the whole procedure
# --------------------------------------------------------------------------------------------------


class _Evaluable(Protocol):
    def evaluate(self, points: Mapping[str, Any]) -> Any: ...


Expression = _Evaluable | Callable[[Mapping[str, np.ndarray]], Any]


def _values(expr: Any, samples: Mapping[str, np.ndarray], name: str) -> np.ndarray:
    if hasattr(expr, "evaluate"):
        values = expr.evaluate(samples)
    elif callable(expr):
        values = expr(samples)
    else:
        raise ScrewkitTypeError(
            f"Expected `{name}` to have an evaluate(points) method or to be a callable "
            f"points -> values, got {type(expr).__name__}."
        )
    n = next(iter(samples.values())).shape[0]
    values = np.broadcast_to(np.asarray(values, dtype=float), (n,))
    if not np.all(np.isfinite(values)):
        raise ScrewkitValueError(f"Expected `{name}` to give finite values, got {values}.")
    return values


@dataclass(frozen=True, slots=True)
class Proportionality:
    """Result of :func:`check_proportional`: ``a ≈ constant × b`` on the samples.

    Attributes
    ----------
    constant : float
        Median of ``a / b`` over the samples.
    max_deviation : float
        ``max |a − constant·b| / max(|a|, |constant·b|)`` over the samples (0 = exactly
        proportional; round-off gives ~1e-14).
    n_samples : int
    """

    constant: float
    max_deviation: float
    n_samples: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "constant": self.constant,
            "max_deviation": self.max_deviation,
            "n_samples": self.n_samples,
        }

    def __str__(self) -> str:
        return (
            f"constant {self.constant:.12g}, max relative deviation {self.max_deviation:.2e} "
            f"over {self.n_samples} samples"
        )


def _proportionality(a: np.ndarray, b: np.ndarray, name: str) -> Proportionality:
    nonzero = b != 0
    if not np.any(nonzero):
        raise DegenerateGeometryError(
            f"Expected `{name}` to be non-zero on some sample, got zero on all {b.size} samples."
        )
    constant = float(np.median(a[nonzero] / b[nonzero]))
    scale = np.maximum(np.abs(a), np.abs(constant * b))
    deviation = np.abs(a - constant * b) / np.where(scale > 0, scale, 1.0)
    return Proportionality(constant, float(deviation.max()), int(b.size))


def check_proportional(
    expr_a: Expression,
    expr_b: Expression,
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rng: np.random.Generator | int = 0,
) -> Proportionality:
    """Check numerically that ``expr_a = constant × expr_b`` on sampled configurations.

    The check behind every simplification step (``gca.md`` §6.3): the 6×6 determinant divided by
    the simplified expression must be a constant.

    Parameters
    ----------
    expr_a, expr_b : expression or callable
        Anything with ``evaluate(points)`` (brackets, polynomials, dotted forms, factored forms) or
        a callable ``points -> values`` (e.g. ``lambda p: superbracket(p, lines)``). They are
        evaluated on all samples at once (points of shape (n_samples, 4)).
    sampler : callable
        ``rng -> {label: point (4,)}``.
    n_samples : int, default 20
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    Proportionality

    Raises
    ------
    DegenerateGeometryError
        If ``expr_b`` is zero on every sample.

    Examples
    --------
    >>> import numpy as np
    >>> def sampler(rng):
    ...     return {x: rng.normal(size=4) for x in "abcd"}
    >>> r = check_proportional(Bracket("bacd"), Bracket("abcd"), sampler)
    >>> r.constant, r.max_deviation < 1e-12
    (-1.0, True)
    """
    samples = _draw(sampler, n_samples, np.random.default_rng(rng))
    return _proportionality(
        _values(expr_a, samples, "expr_a"), _values(expr_b, samples, "expr_b"), "expr_b"
    )


@dataclass(frozen=True, slots=True)
class Simplification:
    """Every stage of :func:`simplify_superbracket`, each checked against the 6×6 determinant.

    Attributes
    ----------
    lines : tuple of six (str, str)
        The caller's lines.
    ordering : OrderingSearch or None
        The ordering search, if one was made.
    expansion : BracketPolynomial
        The 24-term expansion in the chosen ordering.
    survivors : BracketPolynomial
        Without its structurally zero monomials.
    reduced : BracketPolynomial
        Without vanishing subsums.
    factored : FactoredForm
        The factored form, its coefficient including the ordering's sign, so that it equals the
        superbracket of the caller's lines on the incidence variety.
    checks : tuple of (str, Proportionality)
        ``superbracket(caller's lines) / stage`` on fresh samples, for each stage: the constant is
        1 and the deviation at round-off level. If the superbracket vanishes on the incidence
        variety (nothing survives), one entry ``"vanishes"`` with constant 0 and, as deviation,
        the largest ``|det|`` relative to its Hadamard bound (the product of the row norms).
    """

    lines: tuple[tuple[str, str], ...]
    ordering: OrderingSearch | None
    expansion: BracketPolynomial
    survivors: BracketPolynomial
    reduced: BracketPolynomial
    factored: FactoredForm
    checks: tuple[tuple[str, Proportionality], ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary of every stage."""
        return {
            "lines": [list(line) for line in self.lines],
            "ordering": None if self.ordering is None else self.ordering.to_dict(),
            "expansion": str(self.expansion),
            "survivors": str(self.survivors),
            "reduced": str(self.reduced),
            "factored": self.factored.to_dict(),
            "checks": {name: check.to_dict() for name, check in self.checks},
        }

    def __str__(self) -> str:
        lines = [
            f"superbracket = {self.factored}",
            f"monomials: {len(self.expansion)} expanded, {len(self.survivors)} not structurally "
            f"zero, {len(self.reduced)} after vanishing subsums",
        ]
        if self.ordering is not None:
            lines.append(f"ordering: {self.ordering}")
        lines += [f"check {name}: {check}" for name, check in self.checks]
        return "\n".join(lines)


def _check_weights(
    samples: Mapping[str, np.ndarray], finite: Sequence[str], infinite: Sequence[str], rtol: float
) -> None:
    for label in finite:
        if label in samples and not np.allclose(samples[label][:, 3], 1.0, rtol=0, atol=rtol):
            raise ScrewkitValueError(
                f"Expected `sampler` to give the finite point {label!r} weight 1, got weights "
                f"{samples[label][:3, 3]}..."
            )
    for label in infinite:
        if label in samples and np.any(samples[label][:, 3] != 0):
            raise ScrewkitValueError(
                f"Expected `sampler` to give the infinite point {label!r} weight 0, got weights "
                f"{samples[label][:3, 3]}..."
            )


def simplify_superbracket(
    lines: Sequence[Sequence[str] | str],
    sampler: Sampler,
    *,
    finite: Sequence[str] = (),
    infinite: Sequence[str] = (),
    collinear: Sequence[Sequence[str] | str] = (),
    search: bool = True,
    n_samples: int = 20,
    rtol: float = 1e-9,
    check_rtol: float = 1e-6,
    max_terms: int = 16,
    rng: np.random.Generator | int = 0,
) -> Simplification:
    """The simplification procedure of ``gca.md`` §6, every step checked numerically.

    Ordering search (optional, :func:`best_ordering`), 24-term expansion, structural zeros
    (:func:`structural_zeros`), vanishing subsums (:func:`drop_zero_subsums`), factoring
    (:func:`collect_factors`). The samples used to decide zeros and the fresh samples used for
    the checks come from the same generator but are different draws.

    Parameters
    ----------
    lines : sequence of six pairs of labels
    sampler : callable
        ``rng -> {label: point (4,)}``: finite points with weight exactly 1.
    finite, infinite, collinear
        Declarations passed to :func:`collect_factors` (and checked against the samples' weights).
    search : bool, default True
        Search the 46 080 orderings; False keeps the caller's order.
    n_samples : int, default 20
    rtol : float, default 1e-9
        Relative zero threshold of brackets and subsums.
    check_rtol : float, default 1e-6
        Largest accepted deviation of a stage from the superbracket on fresh samples.
    max_terms : int, default 16
        See :func:`drop_zero_subsums`.
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    Simplification

    Raises
    ------
    ScrewkitValueError
        If a stage is not equal to the superbracket on the fresh samples (a sampler that does not
        satisfy the declarations), or finite/infinite weights do not match the declarations.

    Examples
    --------
    >>> import numpy as np
    >>> def concurrent(rng):  # six lines through the point o: always singular
    ...     pts = {x: np.r_[rng.normal(size=3), 1.0] for x in "abcdef"}
    ...     return {**pts, "o": np.r_[rng.normal(size=3), 1.0]}
    >>> result = simplify_superbracket(["oa", "ob", "oc", "od", "oe", "of"], concurrent)
    >>> str(result.factored)
    '0'
    """
    pairs = _lines(lines)
    rtol, check = _check_rtol(rtol), _check_rtol(check_rtol, "check_rtol")
    terms = _check_positive_int(max_terms, "max_terms")
    generator = np.random.default_rng(rng)
    labels = [label for line in pairs for label in line]
    samples = _draw(sampler, n_samples, generator, labels)
    _check_weights(samples, finite, infinite, rtol)
    ordering = _best_ordering(pairs, samples, rtol) if search else None
    chosen, sign = (ordering.lines, ordering.sign) if ordering is not None else (pairs, 1)
    expansion = superbracket_expansion(chosen)
    survivors = _drop_zero_monomials(expansion, samples, rtol)
    reduced = _drop_zero_subsums(survivors, samples, rtol, terms)
    factored = collect_factors(reduced, finite=finite, infinite=infinite, collinear=collinear)
    factored = replace(factored, coefficient=sign * factored.coefficient)

    fresh = _draw(sampler, n_samples, generator, labels)
    rows = np.stack([P.join_unchecked(fresh[p], fresh[q]) for p, q in pairs], axis=-2)
    truth = np.linalg.det(rows)
    if reduced.terms:
        stages = {"expansion": expansion, "survivors": survivors, "reduced": reduced}
        checks = [
            (name, _proportionality(truth, sign * _values(stage, fresh, name), name))
            for name, stage in stages.items()
        ]
        checks.append(
            ("factored", _proportionality(truth, _values(factored, fresh, "factored"), "factored"))
        )
    else:  # the superbracket vanishes on the variety: compare it with its Hadamard bound
        relative = np.abs(truth) / np.linalg.norm(rows, axis=-1).prod(axis=-1)
        checks = [("vanishes", Proportionality(0.0, float(relative.max()), len(truth)))]
    for name, result in checks:
        expected = 0.0 if name == "vanishes" else 1.0
        if result.max_deviation > check or abs(result.constant - expected) > check:
            raise ScrewkitValueError(
                f"Expected stage {name!r} to equal the superbracket on fresh samples, got {result}:"
                f" check that `sampler` gives finite points of weight 1 and satisfies the "
                f"declared `collinear` triples."
            )
    return Simplification(pairs, ordering, expansion, survivors, reduced, factored, tuple(checks))
