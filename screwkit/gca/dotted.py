"""Dotted notation of McMillan & White (1991; ``gca.md`` §3): :class:`DottedMonomial` and
:class:`DottedSum`, compact forms of alternating sums of bracket monomials.
"""

from __future__ import annotations

import itertools
import math
from collections import Counter
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .brackets import Bracket, BracketMonomial, BracketPolynomial, as_labels, as_monomial
from .notation import exact_coefficient, format_bracket, format_sum, parse_terms, renamed_label, sort_sign

__all__ = [
    "DottedMonomial",
    "DottedSum",
]


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

    return [(sort_sign(order), order) for order in distribute(tuple(range(sum(groups))), groups)]


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
        labels = tuple(as_labels(b, f"brackets[{i}]", 4) for i, b in enumerate(brackets))
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
        object.__setattr__(self, "coefficient", exact_coefficient(coefficient, "coefficient"))

    @classmethod
    def parse(cls, text: str) -> DottedMonomial:
        """Read one dotted monomial, e.g. ``"-[g i k j][a b d ḟ][c g ḣ j]"``.

        Precomposed characters (``ḟ``, ``ï``) and combining marks are both accepted.

        Parameters
        ----------
        text : str

        Returns
        -------
        DottedMonomial

        Examples
        --------
        >>> DottedMonomial.parse("2[e f ġ ï][ḣ j̈ k l]").dots
        ((0, 0, 1, 2), (1, 2, 0, 0))
        """
        terms = parse_terms(text)
        if len(terms) != 1:
            raise ScrewkitValueError(
                f"Expected `text` to be one dotted monomial, got {len(terms)} terms in {text!r}."
            )
        coefficient, brackets = terms[0]
        return cls([b for b, _ in brackets], [d for _, d in brackets], coefficient)

    @classmethod
    def from_monomial(cls, monomial: BracketMonomial | Bracket) -> DottedMonomial:
        """The monomial with no dots.

        Parameters
        ----------
        monomial : BracketMonomial or Bracket

        Returns
        -------
        DottedMonomial

        Examples
        --------
        >>> print(DottedMonomial.from_monomial(-Bracket("gikj")))
        -[gikj]
        """
        m = as_monomial(monomial)
        if m is None:
            raise ScrewkitTypeError(
                f"Expected `monomial` to be a BracketMonomial or a Bracket, "
                f"got {type(monomial).__name__}."
            )
        return cls([b.labels for b in m.brackets], None, m.coefficient)

    def expand(self) -> BracketPolynomial:
        """The bracket polynomial: signed sum over the shuffles of each dot kind.

        Returns
        -------
        BracketPolynomial

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

        Parameters
        ----------
        mapping : mapping of str to str
            Old label -> new label (checked); labels missing from it stay.

        Returns
        -------
        DottedMonomial

        Examples
        --------
        >>> print(DottedMonomial.parse("[a b ċ d][ė f g h]").relabel({"e": "x"}))
        [a b ċ d][ẋ f g h]
        """
        renamed = [tuple(renamed_label(label, mapping) for label in b) for b in self.brackets]
        return DottedMonomial(renamed, self.dots, self.coefficient)

    def _body(self, *, latex: bool) -> str:
        return "".join(
            format_bracket(b, d, latex=latex)
            for b, d in zip(self.brackets, self.dots, strict=True)
        )

    def __str__(self) -> str:
        return format_sum([(self.coefficient, self._body(latex=False))], latex=False)

    def to_latex(self) -> str:
        """LaTeX, ``\\dot``, ``\\ddot``, ``\\dddot``, ``\\ddddot`` (amsmath) over dotted letters.

        Returns
        -------
        str
        """
        return format_sum([(self.coefficient, self._body(latex=True))], latex=True)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (through :meth:`expand`).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)
            The points by label; batches broadcast against each other.

        Returns
        -------
        float, numpy.ndarray or sympy.Expr
        """
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

        Parameters
        ----------
        text : str

        Returns
        -------
        DottedSum

        Examples
        --------
        >>> print(DottedSum.parse("[abcd][e f ġ ï][ḣ j̈ k l] - 2[a b ċ d][ė f g h]"))
        [abcd][e f ġ ï][ḣ j̈ k l] - 2 [a b ċ d][ė f g h]
        """
        return cls(
            DottedMonomial([b for b, _ in brackets], [d for _, d in brackets], coefficient)
            for coefficient, brackets in parse_terms(text)
        )

    def expand(self) -> BracketPolynomial:
        """Sum of the expansions of the terms.

        Returns
        -------
        BracketPolynomial
        """
        return BracketPolynomial(m for term in self.terms for m in term.expand().terms)

    def relabel(self, mapping: Mapping[str, str]) -> DottedSum:
        """Rename labels simultaneously in every term.

        Parameters
        ----------
        mapping : mapping of str to str
            Old label -> new label (checked); labels missing from it stay.

        Returns
        -------
        DottedSum
        """
        return DottedSum(term.relabel(mapping) for term in self.terms)

    def _pairs(self, *, latex: bool) -> list[tuple[Fraction, str]]:
        return [(t.coefficient, t._body(latex=latex)) for t in self.terms]

    def __str__(self) -> str:
        return format_sum(self._pairs(latex=False), latex=False)

    def to_latex(self) -> str:
        """LaTeX of the sum.

        Returns
        -------
        str
        """
        return format_sum(self._pairs(latex=True), latex=True)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (through :meth:`expand`).

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)
            The points by label; batches broadcast against each other.

        Returns
        -------
        float, numpy.ndarray or sympy.Expr
        """
        return self.expand().evaluate(points)
