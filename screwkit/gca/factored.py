"""The factored form of a bracket polynomial (:class:`FactoredForm`) and how it is collected
(:func:`collect_factors`, ``gca.md`` §6.3): equal brackets written alike, common brackets and the
content factored out, pairs of monomials merged into dotted ones, and products of sums split.

Examples
--------
>>> p = BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")
>>> print(collect_factors(p, finite="aceg", infinite="bdfhijk", collinear=["egj"]))
-[gikj][a b d ḟ][c g ḣ j]
"""

from __future__ import annotations

import functools
import itertools
import math
from collections import Counter
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .brackets import Bracket, BracketMonomial, BracketPolynomial, as_labels
from .dotted import DottedMonomial, DottedSum
from .factoring import Polynomial, factor_polynomial
from .notation import DOT_MARKS, format_bracket, format_sum

__all__ = [
    "FactoredForm",
    "collect_factors",
]


class _Interchange:
    """When a finite point may replace another in a bracket without changing its value.

    With weights 1, ``x − y`` is the infinite point of line xy, so ``[x P Q R] = [y P Q R]`` iff
    ``[(x − y) P Q R] = 0``. That holds when P, Q, R are all infinite (four infinite points,
    ``gca.md`` §5.1: the H4's [eikj] = [gikj]) or when the direction of xy is one of P, Q, R
    (a declared collinear triple x, y, u with u infinite). Replacements are symmetric, so equal
    brackets form classes; :meth:`canonical` writes every bracket as its class's largest member.
    """

    def __init__(self, finite: Any, infinite: Any, collinear: Any) -> None:
        self.finite = as_labels(finite, "finite")
        self.infinite = as_labels(infinite, "infinite")
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
            x, y, u = as_labels(triple, f"collinear[{i}]", 3)
            if x not in self.finite or y not in self.finite or u not in self.infinite:
                raise ScrewkitValueError(
                    f"Expected `collinear[{i}]` to be (finite, finite, infinite) labels as "
                    f"declared in `finite` and `infinite`, got {(x, y, u)}."
                )
            self.directions.setdefault(frozenset((x, y)), set()).add(u)
        self._reach: dict[tuple[str, ...], dict[tuple[str, ...], tuple[str, ...]]] = {}

    def _allowed(self, x: str, y: str, rest: Sequence[str]) -> bool:
        """``[x rest] = [y rest]`` (class docstring), for ``rest`` not all infinite."""
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
                at_infinity = all(label in self.infinite for label in rest)  # any y will do
                for y in self.finite:
                    if y in current or not (at_infinity or self._allowed(x, y, rest)):
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


def _transpositions(
    item: DottedMonomial,
) -> Iterator[tuple[tuple[tuple[int, int], tuple[int, int]], DottedMonomial]]:
    """``(places, item with x and y exchanged)`` for undotted letters x ≠ y in different brackets,
    at ``places`` (bracket, slot); :func:`_dotted` dots them, and its expansion is ``item − second``
    exactly (the dotted one is built only for an exchange that pairs up)."""
    if _next_kind(item) > len(DOT_MARKS):
        return
    places = [(b, s) for b, row in enumerate(item.dots) for s, k in enumerate(row) if not k]
    for (b1, s1), (b2, s2) in itertools.combinations(places, 2):
        x, y = item.brackets[b1][s1], item.brackets[b2][s2]
        if b1 == b2 or x == y:
            continue
        labels = [list(b) for b in item.brackets]
        labels[b1][s1], labels[b2][s2] = y, x
        yield ((b1, s1), (b2, s2)), DottedMonomial(labels, item.dots, item.coefficient)


def _next_kind(item: DottedMonomial) -> int:
    """The dot kind a new pair of ``item`` takes (one more than its last)."""
    return max((k for row in item.dots for k in row), default=0) + 1


def _dotted(item: DottedMonomial, places: tuple[tuple[int, int], tuple[int, int]]) -> DottedMonomial:
    """``item`` with the letters at ``places`` dotted by a new kind (:func:`_transpositions`)."""
    dots = [list(d) for d in item.dots]
    kind = _next_kind(item)
    for b, s in places:
        dots[b][s] = kind
    return DottedMonomial(item.brackets, dots, item.coefficient)


def _written_as(item: DottedMonomial, swapped: DottedMonomial, rules: _Interchange) -> list[Bracket]:
    """The brackets of the term of ``swapped``'s expansion that stands for ``item``.

    That is ``swapped``'s own brackets, unless one of them is zero (a letter repeated by the
    exchange): the exchange then pairs ``item`` with another term of the expansion, the one equal to
    ``item`` up to equal brackets and sign (e.g. a 3-RPS whose exchange c ↔ h writes ``[cefc]``).
    """
    if any(k for row in item.dots for k in row) or all(len(set(b)) == 4 for b in swapped.brackets):
        return [Bracket(b) for b in swapped.brackets]
    key = rules.canonical(item.expand())
    for term in swapped.expand().terms:
        if rules.canonical(BracketPolynomial([term])) in (key, -1 * key):
            return list(term.brackets)
    return [Bracket(b) for b in swapped.brackets]


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
    memo: dict[tuple[Any, ...], BracketPolynomial] = {}  # the rescans after a merge reuse these

    def canonical(item: DottedMonomial) -> BracketPolynomial:
        key = (item.brackets, item.dots, item.coefficient)
        if key not in memo:
            memo[key] = rules.canonical(item.expand())
        return memo[key]

    merged = True
    while merged:
        merged = False
        forms = [canonical(item) for item in items]
        negated = {-1 * form: j for j, form in enumerate(forms)}  # B = −(A with x↔y) looked up
        for i, item in enumerate(items):
            for places, swapped in _transpositions(item):
                target = canonical(swapped)
                j = negated.get(target) if target else None
                if j is None or j == i:
                    continue
                dotted = _dotted(item, places)
                if canonical(dotted) != forms[i] + forms[j]:
                    continue
                old = [Bracket(b) for b in items[j].brackets]
                for pair in rules.differences(old, _written_as(items[j], swapped, rules)):
                    if pair not in substitutions:
                        substitutions.append(pair)
                items[i] = dotted
                del items[j]
                merged = True
                break
            if merged:
                break
    return items, substitutions


def _as_bracket_polynomial(poly: Polynomial) -> BracketPolynomial:
    return BracketPolynomial(BracketMonomial(m, c) for m, c in poly.items())


@dataclass(frozen=True, slots=True)
class FactoredForm:
    """``coefficient × common brackets × (a sum of dotted monomials)`` (:func:`collect_factors`).

    Attributes
    ----------
    coefficient : Fraction
        The constant factor (sign and content).
    common : tuple of Bracket
        The brackets common to every monomial (a repeated bracket appears as often as it divides).
    rest : DottedSum
        The remaining sum; its first term has a positive coefficient (unless it splits into
        ``parts``: then ``rest`` is their product exactly and the content is in ``coefficient``).
    substitutions : tuple of (Bracket, Bracket)
        The bracket identities used, ``old = new``: valid for finite points of weight 1 and the
        declared collinear triples (``gca.md`` §5.1). Without them :meth:`expand` reproduces the
        factored polynomial exactly; with them, its value on such configurations.
    parts : tuple of (DottedSum, int)
        When ``rest`` is itself a product of sums: its factors, each once with its multiplicity
        (``rest = ∏ part**multiplicity``); empty when ``rest`` does not split.
    """

    coefficient: Fraction
    common: tuple[Bracket, ...]
    rest: DottedSum
    substitutions: tuple[tuple[Bracket, Bracket], ...] = ()
    parts: tuple[tuple[DottedSum, int], ...] = ()

    def __post_init__(self) -> None:
        # Equal brackets written alike (the first one's order), the signs of the permutations in the
        # coefficient: so ``coefficient × ∏ factor ** multiplicity`` is the form's value (a factor
        # [bacd] merged into [abcd]² would otherwise lose a sign).
        first: dict[tuple[str, ...], Bracket] = {}
        sign = 1

        def alike(bracket: Bracket) -> Bracket:
            nonlocal sign
            known = first.setdefault(bracket.sorted_labels, bracket)
            sign *= bracket.sign * known.sign
            return known

        common = tuple(alike(b) for b in self.common)
        rest = self.rest
        if not self.parts and len(rest.terms) == 1 and not any(any(d) for d in rest.terms[0].dots):
            term = rest.terms[0]
            labels = tuple(alike(Bracket(b)).labels for b in term.brackets)
            rest = DottedSum((DottedMonomial(labels, term.dots, term.coefficient),))
        object.__setattr__(self, "common", common)
        object.__setattr__(self, "rest", rest)
        object.__setattr__(self, "coefficient", sign * self.coefficient)

    @property
    def factors(self) -> tuple[Bracket | DottedSum, ...]:
        """The distinct non-constant factors: each common bracket, then the rest unless it is 1
        (or its parts, when it splits); see :attr:`multiplicities`.

        A rest made of one undotted monomial is split into its brackets.
        """
        return tuple(factor for factor, _ in self._powers())

    @property
    def multiplicities(self) -> tuple[int, ...]:
        """How often each of :attr:`factors` divides the form (2 for a squared factor):
        ``coefficient × ∏ factor ** multiplicity`` is the form's value on any points."""
        return tuple(multiplicity for _, multiplicity in self._powers())

    def _powers(self) -> list[tuple[Bracket | DottedSum, int]]:
        items: list[tuple[Bracket | DottedSum, int]] = [(b, 1) for b in self.common]
        if self.parts:
            items += list(self.parts)
        elif len(self.rest.terms) == 1 and not any(any(d) for d in self.rest.terms[0].dots):
            items += [(Bracket(b), 1) for b in self.rest.terms[0].brackets]
        else:
            items.append((self.rest, 1))
        merged: list[tuple[Bracket | DottedSum, int]] = []
        for factor, multiplicity in items:
            key = factor.sorted_labels if isinstance(factor, Bracket) else None
            for k, (known, count) in enumerate(merged):
                if key is not None and isinstance(known, Bracket) and known.sorted_labels == key:
                    merged[k] = (known, count + multiplicity)
                    break
            else:
                merged.append((factor, multiplicity))
        return merged

    def expand(self) -> BracketPolynomial:
        """The bracket polynomial ``coefficient × common × rest``.

        Returns
        -------
        BracketPolynomial
        """
        return BracketMonomial(self.common, self.coefficient) * self.rest.expand()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (text, LaTeX, parts and substitutions).

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
        return {
            "text": str(self),
            "latex": self.to_latex(),
            "coefficient": str(self.coefficient),
            "common": [str(b) for b in self.common],
            "rest": str(self.rest),
            "parts": [[str(part), multiplicity] for part, multiplicity in self.parts],
            "substitutions": [[str(old), str(new)] for old, new in self.substitutions],
        }

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

    def _text(self, *, latex: bool) -> str:
        if self.coefficient == 0:
            return "0"
        head = "".join(format_bracket(b.labels, (0,) * 4, latex=latex) for b in self.common)
        terms = self.rest.terms
        if self.parts:
            body = head + "".join(_power(part, k, latex=latex) for part, k in self.parts)
        elif len(terms) == 1 and terms[0].coefficient == 1:
            body = head + terms[0]._body(latex=latex)
        else:
            body = head + _power(self.rest, 1, latex=latex)
        return format_sum([(self.coefficient, body)], latex=latex)

    def __str__(self) -> str:
        return self._text(latex=False)

    def to_latex(self) -> str:
        """LaTeX of the factored form.

        Returns
        -------
        str
        """
        return self._text(latex=True)

    def __repr__(self) -> str:
        return f"FactoredForm({str(self)!r})"

    def _repr_latex_(self) -> str:
        """Jupyter: the factored form typeset (:meth:`to_latex` in math mode).

        Returns
        -------
        str

        Examples
        --------
        >>> collect_factors(BracketPolynomial.parse("[gikj][abdf]"))._repr_latex_()
        '$[gikj][abdf]$'
        """
        return f"${self.to_latex()}$"


def _power(part: DottedSum, multiplicity: int, *, latex: bool) -> str:
    """One factor of a product: ``(sum)``, ``(sum)²`` / ``\\left(sum\\right)^{2}``."""
    single = len(part.terms) == 1 and part.terms[0].coefficient == 1
    if latex:
        text = part.terms[0]._body(latex=True) if single else rf"\left({part.to_latex()}\right)"
        return text + (f"^{{{multiplicity}}}" if multiplicity > 1 else "")
    text = part.terms[0]._body(latex=False) if single else f"({part})"
    return text + (f"^{multiplicity}" if multiplicity > 1 else "")


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
    4. If the remaining sum is a product of sums in the bracket variables (a linear factor divides
       it exactly, found by long division over the rationals), it is split into its factors, each
       kept once with its multiplicity (:attr:`FactoredForm.parts`) and paired as in step 3.

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
    split_content, split = factor_polynomial(
        BracketPolynomial(m for t in rest for m in t.expand().terms)
    )
    parts: list[tuple[DottedSum, int]] = []
    if len(split) > 1 or (split and split[0][1] > 1):  # a product of sums, or a power: one part per factor
        content = split_content
        for factor, multiplicity in split:
            monomials = [DottedMonomial.from_monomial(m) for m in _as_bracket_polynomial(factor)]
            part, more = _pair_dotted(monomials, rules)
            substitutions += [pair for pair in more if pair not in substitutions]
            if part[0].coefficient < 0:  # print each part with a positive first term
                part = [DottedMonomial(t.brackets, t.dots, -t.coefficient) for t in part]
                content *= (-1) ** multiplicity
            parts.append((DottedSum(part), multiplicity))
    terms = [DottedMonomial(t.brackets, t.dots, t.coefficient / content) for t in paired]
    return FactoredForm(
        content, tuple(common), DottedSum(terms), tuple(substitutions), tuple(parts)
    )


