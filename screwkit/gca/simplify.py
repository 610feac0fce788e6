"""Simplification of a superbracket (``gca.md`` §6): collecting factors and dotted pairs
(:func:`collect_factors`), the numeric check of every stage against the 6×6 determinant
(:func:`check_proportional`), and the whole chain (:func:`simplify_superbracket`).
"""

from __future__ import annotations

import functools
import itertools
import math
from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any, Protocol

import numpy as np

from ..algebra import backend as B
from ..algebra import projective as P
from ..algebra.backend import checked_rtol
from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from .brackets import Bracket, BracketMonomial, BracketPolynomial, _labels
from .dotted import DottedMonomial, DottedSum
from .expansion import OrderingSearch, _best_ordering, _lines, superbracket_expansion
from .notation import DOT_MARKS, format_bracket, format_sum
from .zeros import Sampler, _check_positive_int, _draw, _drop_zero_monomials, _drop_zero_subsums

__all__ = [
    "FactoredForm",
    "Proportionality",
    "Simplification",
    "check_proportional",
    "collect_factors",
    "simplify_superbracket",
]


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


Monomial = tuple[tuple[str, ...], ...]
Polynomial = dict[Monomial, Fraction]


def _leading(poly: Polynomial) -> Monomial:
    """The leading monomial in lex order (monomials are sorted tuples of variables; compared from
    their largest variable down, which is lex order of exponent vectors for equal degrees)."""
    return max(poly, key=lambda m: m[::-1])


def _quotient_monomial(monomial: Monomial, divisor: Monomial) -> Monomial | None:
    rest = Counter(monomial)
    rest.subtract(divisor)
    if any(count < 0 for count in rest.values()):
        return None
    return tuple(sorted(rest.elements()))


def _divide(poly: Polynomial, divisor: Polynomial) -> Polynomial | None:
    """``poly / divisor`` if the division is exact, else None (multivariate long division)."""
    remainder, quotient = dict(poly), Counter[Monomial]()
    lead = _leading(divisor)
    while remainder:
        top = _leading(remainder)
        q = _quotient_monomial(top, lead)
        if q is None:
            return None
        c = remainder[top] / divisor[lead]
        quotient[q] += c  # type: ignore[assignment]
        for m, cm in divisor.items():
            key = tuple(sorted(q + m))
            value = remainder.get(key, Fraction(0)) - c * cm
            if value:
                remainder[key] = value
            else:
                remainder.pop(key, None)
    return {m: Fraction(c) for m, c in quotient.items() if c}


def _primitive(poly: Polynomial) -> tuple[Fraction, Polynomial]:
    """``(content, primitive part)``, the primitive part's leading coefficient positive."""
    values = list(poly.values())
    content = Fraction(
        math.gcd(*(v.numerator for v in values)), math.lcm(*(v.denominator for v in values))
    )
    if poly[_leading(poly)] < 0:
        content = -content
    return content, {m: c / content for m, c in poly.items()}


def _split(poly: Polynomial) -> list[Polynomial]:
    """Factors of a homogeneous polynomial in bracket variables, found as linear factors.

    A bracket monomial of the 24-term expansion has three brackets, so a product of non-constant
    sums has a factor of degree 1 in the brackets. For each bracket ``b`` of the first monomial
    ``m``, the candidate linear factor collects the monomials ``(m / b)·b'``; it is accepted only if
    it divides ``poly`` exactly (long division over the rationals), then the quotient is split
    again. Factors that exist only modulo the syzygies among brackets are not found here (the
    ordering search exposes them, ``gca.md`` §6.4).
    """
    first = min(poly)
    if len(poly) < 2 or len(first) < 2:
        return [poly]
    for variable in sorted(set(first)):
        cofactor = _quotient_monomial(first, (variable,))
        assert cofactor is not None
        linear: Polynomial = {}
        for m, c in poly.items():
            q = _quotient_monomial(m, cofactor)
            if q is not None and len(q) == 1:
                linear[q] = c
        if len(linear) < 2:
            continue
        quotient = _divide(poly, linear)
        if quotient is not None:
            return [linear, *_split(quotient)]
    return [poly]


#: Largest number of distinct brackets for which sympy's multivariate factoring is tried on a factor
#: that :func:`_split` cannot split (it takes ~0.1 s there, seconds for 30 brackets).
SYMPY_FACTOR_MAX_BRACKETS = 12


def _derivative(poly: Polynomial, variable: tuple[str, ...]) -> Polynomial:
    """``∂poly/∂variable`` of a polynomial of degree at most 1 in ``variable``."""
    out: Polynomial = {}
    for m, c in poly.items():
        if variable in m:
            k = m.index(variable)
            out[m[:k] + m[k + 1 :]] = c
    return out


def _product(a: Polynomial, b: Polynomial) -> Polynomial:
    out: dict[Monomial, Fraction] = {}
    for ma, ca in a.items():
        for mb, cb in b.items():
            key = tuple(sorted(ma + mb))
            out[key] = out.get(key, Fraction(0)) + ca * cb
    return {m: c for m, c in out.items() if c}


def _multilinear_irreducible(poly: Polynomial) -> bool:
    """True if ``poly`` is multilinear (degree ≤ 1 in each variable) and irreducible over the
    rationals; False says nothing (sympy decides then).

    Derivation: if a multilinear ``p = f g`` then ``deg_x p = deg_x f + deg_x g ≤ 1``, so the
    factors have disjoint variables. For ``x`` in ``f`` and ``y`` in ``g``,
    ``p ∂²p/∂x∂y = f g f_x g_y = ∂p/∂x ∂p/∂y``. Conversely, inside one irreducible factor ``h`` (``p = h r``,
    ``r`` free of ``x, y``), write ``h = a x y + b x + c y + d``: ``p p_xy − p_x p_y = r² (a d − b c)``,
    and ``a d = b c`` would give ``a h = (a x + c)(a y + b)`` (or, for ``a = 0``, ``b c = 0``: ``h``
    free of ``x`` or ``y``), each factor missing ``x`` or ``y``, so not divisible by the prime ``h``:
    a contradiction. Hence ``x, y`` share an irreducible factor iff ``p p_xy ≠ p_x p_y`` (the pairwise
    test of Shpilka & Volkovich, read-once polynomial identity testing, STOC 2008), and ``p`` is
    irreducible iff the graph of those pairs on its variables is connected. Exact arithmetic over
    the rationals throughout.
    """
    if any(len(set(m)) != len(m) for m in poly):
        return False
    variables = sorted({v for m in poly for v in m})
    reached, frontier = {variables[0]}, [variables[0]]
    while frontier:
        x = frontier.pop()
        p_x = _derivative(poly, x)
        for y in variables:
            if y in reached:
                continue
            if _product(poly, _derivative(p_x, y)) != _product(p_x, _derivative(poly, y)):
                reached.add(y)
                frontier.append(y)
    return len(reached) == len(variables)


def _sympy_factors(poly: Polynomial) -> list[Polynomial]:
    """Irreducible factors over the rationals (sympy ``factor_list``), repeated by multiplicity;
    brackets are independent variables there, so a factorisation found is exact. A multilinear
    polynomial proved irreducible exactly (:func:`_multilinear_irreducible`) is returned as it is
    without calling sympy."""
    variables = sorted({v for m in poly for v in m})
    if len(poly) < 3 or len(variables) > SYMPY_FACTOR_MAX_BRACKETS or _multilinear_irreducible(poly):
        return [poly]
    sympy = B.sympy_module()
    symbols = sympy.symbols(f"x0:{len(variables)}")
    index = {v: s for v, s in zip(variables, symbols, strict=True)}
    expr = sympy.Add(
        *(
            sympy.Rational(c.numerator, c.denominator) * sympy.Mul(*(index[v] for v in m))
            for m, c in poly.items()
        )
    )
    content, factors = sympy.factor_list(expr, *symbols)
    if len(factors) == 1 and factors[0][1] == 1:
        return [poly]
    found: list[Polynomial] = [{(): Fraction(int(content.p), int(content.q))}]
    for factor, multiplicity in factors:
        terms = sympy.Poly(factor, *symbols).terms()
        converted = {
            tuple(v for v, e in zip(variables, exponents, strict=True) for _ in range(e)): Fraction(
                int(c.p), int(c.q)
            )
            for exponents, c in terms
        }
        found += [converted] * multiplicity
    return found


def _factor_polynomial(poly: BracketPolynomial) -> tuple[Fraction, list[tuple[Polynomial, int]]]:
    """``poly = content × ∏ factor**multiplicity`` (primitive factors, each listed once)."""
    content = Fraction(1)
    found: list[tuple[Polynomial, int]] = []
    for factor in (f for part in _split(dict(poly._canonical())) for f in _sympy_factors(part)):
        if set(factor) == {()}:
            content *= factor[()]
            continue
        scale, primitive = _primitive(factor)
        content *= scale
        for k, (known, multiplicity) in enumerate(found):
            if known == primitive:
                found[k] = (known, multiplicity + 1)
                break
        else:
            found.append((primitive, 1))
    return content, found


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

    @property
    def factors(self) -> tuple[Bracket | DottedSum, ...]:
        """The distinct non-constant factors: each common bracket, then the rest unless it is 1
        (or its parts, when it splits); see :attr:`multiplicities`.

        A rest made of one undotted monomial is split into its brackets.
        """
        return tuple(factor for factor, _ in self._powers())

    @property
    def multiplicities(self) -> tuple[int, ...]:
        """How often each of :attr:`factors` divides the form (2 for a squared factor)."""
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
            "parts": [[str(part), multiplicity] for part, multiplicity in self.parts],
            "substitutions": [[str(old), str(new)] for old, new in self.substitutions],
        }

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """Value on points (through :meth:`expand`)."""
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
        """LaTeX of the factored form."""
        return self._text(latex=True)


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
    split_content, split = _factor_polynomial(
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
    constant = B.median(a[nonzero] / b[nonzero])
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
    rtol, check = checked_rtol(rtol), checked_rtol(check_rtol, "check_rtol")
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
