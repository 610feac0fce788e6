"""Geometric statements and vector forms of bracket factors (``gca.md`` §5, paper 002 §5.3).

Each factor of a factored superbracket (:func:`screwkit.gca.collect_factors`) vanishes exactly on
some singular configurations. :func:`condition` turns one factor into a :class:`Condition`:

* a geometric statement, e.g. "i, k and j are collinear in the plane at infinity" or
  "line fh meets the line where planes abd and cgj intersect" (``gca.md`` §5.1, §5.2);
* a vector form: a sympy expression in named vectors, finite points standing for their position
  vectors (weight 1) and infinite points for their directions, built from the unevaluated
  products :class:`VectorCross`, :class:`VectorDot` and the difference :class:`VectorDiff`
  (e.g. paper 002 Eq. 6, ``(s12 × s34)·z``, and Eq. 7,
  ``((s1 × s2) × ((r_g − r_c) × z))·(s3 × s4)``);
* the exact constant with ``factor = constant × vector form``, proved at construction by expanding
  both sides in coordinates with sympy (for finite points of weight 1);
* a numeric evaluator compiled once with :func:`sympy.lambdify`, vectorised over batches, and LaTeX.

The vector forms used (reference convention of ``gca.md`` §1; p, q, r, s finite, u, v, w
infinite; the bracket is the constant times the form):

* ``[p q r s]``: ``((q − p) × (r − p))·(s − p)``, "p, q, r and s are coplanar";
* ``[p q r u]``: ``((q − p) × (r − p))·u``, "direction u is parallel to plane pqr";
* ``[p q u v]``: ``(q − p)·(u × v)``, "line pq is parallel to the plane spanned by u and v";
* ``[p u v w]``: ``(u × v)·w``, "u, v and w are collinear in the plane at infinity";
* ``[P ẋ][Q ẏ]`` (planes P, Q, points x, y): ``(n_P × n_Q)·(x × y)`` for infinite x, y,
  else ``φ_P(x) φ_Q(y) − φ_P(y) φ_Q(x)`` with ``φ(x) = n·(x − p0)`` (``n·x`` for infinite x),
  "line xy meets the line where planes P and Q intersect"; plane normals
  ``(q − p) × (r − p)``, ``(q − p) × u``, ``u × v`` (``gca.md`` §5.2).

Any other factor gets the generic form: its expansion with every bracket replaced by its form.

This module is symbolic by nature (its vector forms are sympy expressions, and :class:`VectorDiff`,
:class:`VectorCross`, :class:`VectorDot` subclass ``sympy.Function``), so importing it imports sympy;
:mod:`screwkit.diagram` imports it only when conditions are asked for.

Examples
--------
>>> from screwkit.gca import Bracket
>>> c = condition(Bracket("gikj"), finite="g", infinite="ijk")
>>> print(c.statement)
i, k and j are collinear in the plane at infinity (the directions i, k, j are parallel to one plane)
>>> print(c.expression)
(i × k)·j
>>> c.constant
-1
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy

from . import _backend as B
from .exceptions import ScrewkitTypeError, ScrewkitValueError
from .gca import Bracket, BracketPolynomial, DottedMonomial, DottedSum, FactoredForm

__all__ = [
    "Condition",
    "VectorCross",
    "VectorDiff",
    "VectorDot",
    "condition",
    "conditions",
]


# --------------------------------------------------------------------------------------------------
# Unevaluated vector operations on named vectors
# --------------------------------------------------------------------------------------------------


def _str_arg(printer: Any, arg: sympy.Basic) -> str:
    text = printer._print(arg)
    return f"({text})" if isinstance(arg, sympy.Add | sympy.Mul) else text


def _latex_arg(printer: Any, arg: sympy.Basic) -> str:
    if isinstance(arg, sympy.Symbol):
        return rf"\mathbf{{{arg.name}}}"
    text = printer._print(arg)
    return rf"\left({text}\right)" if isinstance(arg, sympy.Add | sympy.Mul) else text


class VectorDiff(sympy.Function):
    """``a − b`` for named 3-vectors, kept unevaluated so it prints in the order written.

    Examples
    --------
    >>> g, c = sympy.symbols("g c")
    >>> print(VectorDiff(g, c)), sympy.latex(VectorDiff(g, c))
    (g − c)
    (None, '\\\\left(\\\\mathbf{g} - \\\\mathbf{c}\\\\right)')
    """

    nargs = 2

    def _sympystr(self, printer: Any) -> str:
        return f"({_str_arg(printer, self.args[0])} − {_str_arg(printer, self.args[1])})"

    def _latex(self, printer: Any) -> str:
        a, b = (_latex_arg(printer, arg) for arg in self.args)
        return rf"\left({a} - {b}\right)"


class VectorCross(sympy.Function):
    """Unevaluated cross product ``a × b`` of named 3-vectors.

    Examples
    --------
    >>> i, k = sympy.symbols("i k")
    >>> print(VectorCross(i, k))
    (i × k)
    """

    nargs = 2

    def _sympystr(self, printer: Any) -> str:
        return f"({_str_arg(printer, self.args[0])} × {_str_arg(printer, self.args[1])})"

    def _latex(self, printer: Any) -> str:
        a, b = (_latex_arg(printer, arg) for arg in self.args)
        return rf"\left({a} \times {b}\right)"


class VectorDot(sympy.Function):
    """Unevaluated dot product ``a·b`` of named 3-vectors (a scalar).

    Examples
    --------
    >>> i, k, j = sympy.symbols("i k j")
    >>> print(VectorDot(VectorCross(i, k), j)), sympy.latex(VectorDot(VectorCross(i, k), j))
    (i × k)·j
    (None, '\\\\left(\\\\mathbf{i} \\\\times \\\\mathbf{k}\\\\right) \\\\cdot \\\\mathbf{j}')
    """

    nargs = 2

    def _sympystr(self, printer: Any) -> str:
        return f"{_str_arg(printer, self.args[0])}·{_str_arg(printer, self.args[1])}"

    def _latex(self, printer: Any) -> str:
        a, b = (_latex_arg(printer, arg) for arg in self.args)
        return rf"{a} \cdot {b}"


def _components(expr: sympy.Basic, vectors: Mapping[sympy.Symbol, sympy.Matrix]) -> Any:
    """Expand a vector form into coordinates: symbols become the 3-vectors of ``vectors``."""
    if isinstance(expr, sympy.Symbol):
        return vectors[expr]
    if isinstance(expr, VectorDiff | VectorCross | VectorDot):
        a, b = (_components(arg, vectors) for arg in expr.args)
        if isinstance(expr, VectorDiff):
            return a - b
        return a.cross(b) if isinstance(expr, VectorCross) else a.dot(b)
    if isinstance(expr, sympy.Add | sympy.Mul):
        return expr.func(*(_components(arg, vectors) for arg in expr.args))
    return expr


# --------------------------------------------------------------------------------------------------
# Patterns
# --------------------------------------------------------------------------------------------------


def _word(labels: Sequence[str]) -> str:
    return ("" if all(len(x) == 1 for x in labels) else " ").join(labels)


def _listing(labels: Sequence[str]) -> str:
    return ", ".join(labels[:-1]) + " and " + labels[-1]


class _Types:
    """Declared finite and infinite labels."""

    def __init__(self, finite: Any, infinite: Any) -> None:
        self.finite = _label_set(finite, "finite")
        self.infinite = _label_set(infinite, "infinite")
        both = sorted(self.finite & self.infinite)
        if both:
            raise ScrewkitValueError(
                f"Expected `finite` and `infinite` to be disjoint, got {both} in both."
            )

    def split(self, labels: Sequence[str]) -> tuple[list[str], list[str]]:
        undeclared = [x for x in labels if x not in self.finite | self.infinite]
        if undeclared:
            raise ScrewkitValueError(
                f"Expected every label of the factor to be declared in `finite` or `infinite`, "
                f"got {sorted(set(undeclared))} undeclared."
            )
        return [x for x in labels if x in self.finite], [x for x in labels if x in self.infinite]


def _label_set(value: Any, name: str) -> frozenset[str]:
    if isinstance(value, str):
        return frozenset(value.split() if any(ch.isspace() for ch in value) else value)
    if isinstance(value, Sequence) and all(isinstance(x, str) for x in value):
        return frozenset(value)
    raise ScrewkitTypeError(
        f"Expected `{name}` to be a string of labels or a sequence of label strings, "
        f"got {type(value).__name__} {value!r}."
    )


def _bracket_form(labels: Sequence[str], types: _Types) -> tuple[sympy.Expr | None, str, int]:
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
        return expr, f"direction {infinite[0]} is parallel to plane {_word(finite)}", sign
    if len(finite) == 2:
        p, q = (v[x] for x in finite)
        u, w = (v[x] for x in infinite)
        statement = (
            f"line {_word(finite)} is parallel to the plane spanned by directions "
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


def _plane(labels: Sequence[str], types: _Types) -> tuple[sympy.Expr, str] | None:
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


def _two_planes(term: DottedMonomial, types: _Types) -> tuple[sympy.Expr, str] | None:
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

        expr = value(n_p, p0, x) * value(n_q, q0, y) - value(n_p, p0, y) * value(n_q, q0, x)
    statement = (
        f"line {_word([x, y])} meets the line where planes {_word(planes[0])} and "
        f"{_word(planes[1])} intersect"
    )
    return expr, statement


# --------------------------------------------------------------------------------------------------
# Conditions
# --------------------------------------------------------------------------------------------------

Factor = Bracket | DottedMonomial | DottedSum | BracketPolynomial


@dataclass(frozen=True, slots=True)
class Condition:
    """A bracket factor, its geometric statement and its vector form.

    Attributes
    ----------
    factor : Bracket, DottedMonomial, DottedSum or BracketPolynomial
    statement : str
        When the factor vanishes, in words.
    expression : sympy.Expr
        The vector form in named vectors (finite points: positions, infinite: directions).
    constant : sympy.Rational
        ``factor = constant × expression`` for finite points of weight 1 (0 if the factor is
        identically zero, e.g. four points at infinity).
    vectors : tuple of str
        The labels the expression uses, sorted.
    """

    factor: Factor
    statement: str
    expression: sympy.Expr
    constant: sympy.Rational
    vectors: tuple[str, ...]
    _compiled: Callable[..., Any] = field(repr=False, compare=False)

    def evaluate(self, points: Mapping[str, Any]) -> Any:
        """The vector form on points ``(..., 4)`` (their first three coordinates), vectorised.

        Parameters
        ----------
        points : mapping of str to array_like, shape (..., 4)
            Finite points of weight 1 and infinite points; batches broadcast.

        Returns
        -------
        float or numpy.ndarray
        """
        if not isinstance(points, Mapping):
            raise ScrewkitTypeError(
                f"Expected `points` to be a mapping from labels to points of shape (..., 4), "
                f"got {type(points).__name__}."
            )
        missing = [x for x in self.vectors if x not in points]
        if missing:
            raise ScrewkitValueError(
                f"Expected `points` to give a point for every label {list(self.vectors)}, "
                f"missing {missing}."
            )
        arrays = [
            B.as_array(points[x], f"points[{x!r}]", (4,), symbolic=False) for x in self.vectors
        ]
        try:
            arrays = list(np.broadcast_arrays(*arrays))
        except ValueError as err:
            shapes = {x: a.shape for x, a in zip(self.vectors, arrays, strict=True)}
            raise ScrewkitValueError(
                f"Expected the batch shapes of `points` to broadcast, got {shapes}."
            ) from err
        coordinates = [a[..., i] for a in arrays for i in range(3)]
        shape = arrays[0].shape[:-1] if arrays else ()
        return np.broadcast_to(np.asarray(self._compiled(*coordinates), dtype=float), shape)[()]

    def __str__(self) -> str:
        return f"{self.factor} = 0 ⇔ {self.statement} ⇔ {self.expression} = 0"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "factor": str(self.factor),
            "statement": self.statement,
            "vector_form": str(self.expression),
            "latex": self.to_latex(),
            "constant": str(self.constant),
            "vectors": list(self.vectors),
        }

    def to_latex(self) -> str:
        """LaTeX of the vector form set to zero, vectors in bold."""
        return sympy.latex(self.expression) + " = 0"


def condition(factor: Factor, *, finite: Any, infinite: Any) -> Condition:
    """The geometric condition expressed by one bracket factor (``gca.md`` §5).

    Parameters
    ----------
    factor : Bracket, DottedMonomial, DottedSum or BracketPolynomial
        A factor, e.g. from :attr:`screwkit.gca.FactoredForm.factors`.
    finite, infinite : str or sequence of str
        The labels of finite points (weight 1) and of infinite points.

    Returns
    -------
    Condition

    Examples
    --------
    >>> from screwkit.gca import DottedMonomial
    >>> c = condition(DottedMonomial.parse("[a b d ḟ][c g ḣ j]"), finite="acg", infinite="bdfhj")
    >>> c.statement
    'line fh meets the line where planes abd and cgj intersect'
    >>> print(c.expression)  # paper 002 Eq. (7)
    ((b × d) × ((g − c) × j))·(f × h)
    >>> c.constant
    -1
    """
    types = _Types(finite, infinite)
    expr, statement = _form(factor, types)
    labels = sorted(_labels_of(factor))
    vectors = {sympy.Symbol(x): sympy.Matrix(sympy.symbols(f"{x}_x {x}_y {x}_z")) for x in labels}
    points = {
        x: [*vectors[sympy.Symbol(x)], sympy.Integer(0 if x in types.infinite else 1)]
        for x in labels
    }
    polynomial = _polynomial(factor)
    if expr is None:
        expr, constant = sympy.Integer(0), sympy.Integer(0)
    elif sum(24 ** len(m.brackets) for m in polynomial) > MAX_EXPANDED_TERMS:
        constant = _sampled_ratio(polynomial, expr, vectors, points, labels)
    else:
        exact = sympy.expand(polynomial.to_sympy(points))
        ratio = sympy.cancel(exact / sympy.expand(_components(expr, vectors)))
        if not ratio.is_Rational or ratio == 0:
            raise ScrewkitValueError(
                f"Expected the vector form {expr} to be proportional to {factor}, got the ratio "
                f"{ratio}."
            )
        constant = ratio
    used = tuple(sorted(s.name for s in expr.free_symbols))
    arguments = [c for x in used for c in vectors[sympy.Symbol(x)]]
    components = _components(expr, {s: vectors[s] for s in expr.free_symbols})
    compiled = sympy.lambdify(arguments, components, modules="numpy")
    return Condition(factor, statement, expr, constant, used, compiled)


#: Largest expansion (bounded by 24 terms per bracket of every monomial) that :func:`condition` checks
#: symbolically; beyond it (e.g. the 24-term factor of a general Gough-Stewart platform, ~3e5 terms)
#: the expansion would take minutes, so the proportionality is checked exactly at integer points.
MAX_EXPANDED_TERMS = 20_000


def _sampled_ratio(
    polynomial: BracketPolynomial, expr: sympy.Expr, vectors: Any, points: Any, labels: list[str]
) -> sympy.Rational:
    """The constant ``polynomial / expr``, in exact integer arithmetic at five seeded random integer
    points (a polynomial identity that holds at random points holds, Schwartz-Zippel); refuses a
    ratio that is not one constant."""
    rng = np.random.default_rng(2026)
    ratios = set()
    for _ in range(5):
        values = {x: [sympy.Integer(int(v)) for v in rng.integers(-9, 10, 3)] for x in labels}
        at = {c: v for x in labels for c, v in zip(vectors[sympy.Symbol(x)], values[x], strict=True)}
        numeric = {x: [*values[x], points[x][3]] for x in labels}
        form = sympy.Integer(_components(expr, vectors).subs(at))
        if form == 0:
            continue
        ratios.add(sympy.Rational(polynomial.to_sympy(numeric)) / form)
    if len(ratios) != 1 or 0 in ratios:
        raise ScrewkitValueError(
            f"Expected the vector form {expr} to be proportional to the factor, got ratios {sorted(ratios)}."
        )
    return ratios.pop()


def conditions(factored: FactoredForm, *, finite: Any, infinite: Any) -> tuple[Condition, ...]:
    """One :class:`Condition` per factor of a factored superbracket.

    Examples
    --------
    >>> from screwkit.gca import BracketPolynomial, collect_factors
    >>> p = BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")
    >>> f = collect_factors(p, finite="aceg", infinite="bdfhijk", collinear=["egj"])
    >>> [str(c.expression) for c in conditions(f, finite="aceg", infinite="bdfhijk")]
    ['(i × k)·j', '((b × d) × ((g − c) × j))·(f × h)']
    """
    if not isinstance(factored, FactoredForm):
        raise ScrewkitTypeError(
            f"Expected `factored` to be a FactoredForm, got {type(factored).__name__}."
        )
    return tuple(condition(f, finite=finite, infinite=infinite) for f in factored.factors)


def _polynomial(factor: Factor) -> BracketPolynomial:
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


def _labels_of(factor: Factor) -> set[str]:
    return set(_polynomial(factor).labels) | (
        {x for b in factor.brackets for x in b} if isinstance(factor, DottedMonomial) else set()
    )


def _form(factor: Factor, types: _Types) -> tuple[sympy.Expr | None, str]:
    """The vector form and the statement of a factor: a known pattern, else the generic form."""
    if isinstance(factor, Bracket):
        expr, statement, _ = _bracket_form(factor.labels, types)
        return expr, statement
    single = factor.terms[0] if isinstance(factor, DottedSum) and len(factor.terms) == 1 else factor
    if isinstance(single, DottedMonomial):
        found = _two_planes(single, types)
        if found is not None:
            return found
    polynomial = _polynomial(factor)
    total = sympy.Integer(0)
    for monomial in polynomial:
        product = sympy.Rational(monomial.coefficient.numerator, monomial.coefficient.denominator)
        for bracket in monomial.brackets:
            expr, _, sign = _bracket_form(bracket.labels, types)
            product *= 0 if expr is None else sign * expr
        total += product
    return (total if total != 0 else None), f"the bracket expression {factor} vanishes"
