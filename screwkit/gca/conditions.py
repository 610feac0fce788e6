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
* the exact constant with ``factor = constant × vector form``, proved at construction by exact
  integer evaluation of both sides at random configurations (Schwartz–Zippel, :data:`PROOF_CHECKS`;
  no symbolic expansion, so a general Gough–Stewart factor takes a second, not minutes);
* a numeric evaluator (the same small evaluator, vectorised over batches) and LaTeX.

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
:mod:`screwkit.gca.diagram` imports it only when conditions are asked for.

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

import itertools
import random
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import numpy as np
import sympy

from ..algebra import backend as B
from ..algebra import projective as P
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from . import Bracket, BracketPolynomial, DottedMonomial, DottedSum, FactoredForm

__all__ = [
    "Condition",
    "VectorCross",
    "VectorDiff",
    "VectorDot",
    "condition",
    "conditions",
    "label",
    "latex",
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


def _sum(terms: Sequence[sympy.Expr]) -> sympy.Expr:
    """``sympy.Add(*terms)`` of the vector forms' products, without ``Add.flatten`` when the non-zero
    terms are products ``c·s`` of distinct ``s`` (nothing to collect): their sum is then those terms
    in sympy's canonical order (``Add.flatten``'s own result for them; the first ``Add.flatten`` of a
    process imports ``sympy.tensor.tensor``, 25–90 ms of a command-line analysis). Any other sum
    (like terms, numbers, nested sums, fewer than two terms) goes through ``sympy.Add``.

    Examples
    --------
    >>> i, k, j = sympy.symbols("i k j")
    >>> terms = [2 * VectorDot(i, k), -VectorDot(k, j), sympy.Integer(0)]
    >>> print(_sum(terms))
    2*i·k - k·j
    >>> _sum(terms) == sympy.Add(*terms)
    True
    """
    kept = [t for t in terms if t != 0]
    plain = all(isinstance(t, sympy.Mul | VectorDot | sympy.Symbol) and t.is_commutative for t in kept)
    if len(kept) < 2 or not plain or len({t.as_coeff_Mul()[1] for t in kept}) < len(kept):
        return sympy.Add(*terms)
    try:  # sympy's private helpers (1.12–1.14); a sympy without them takes the public path
        from sympy.core.add import _addsort

        build = sympy.Add._exec_constructor_postprocessors
    except (ImportError, AttributeError):
        return sympy.Add(*terms)
    _addsort(kept)
    return build(sympy.Add._from_args(kept, True))


def _form_value(expr: sympy.Basic, vectors: Mapping[str, Any], number: Callable[[Any], Any]) -> Any:
    """Value of a vector form: each symbol becomes the 3-tuple ``vectors[name]`` (components may
    be Python integers, fractions or numpy arrays; only ``+ − ×`` are used), sympy numbers go
    through ``number`` (``fractions.Fraction`` for exact values, ``float`` for numbers)."""
    if isinstance(expr, sympy.Symbol):
        return vectors[expr.name]
    if isinstance(expr, VectorDiff | VectorCross | VectorDot):
        a, b = (_form_value(arg, vectors, number) for arg in expr.args)
        if isinstance(expr, VectorDiff):
            return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
        if isinstance(expr, VectorCross):
            return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    if isinstance(expr, sympy.Add):
        values = [_form_value(arg, vectors, number) for arg in expr.args]
        total = values[0]
        for value in values[1:]:
            total = total + value
        return total
    if isinstance(expr, sympy.Mul):
        product = number(1)
        for arg in expr.args:
            product = product * _form_value(arg, vectors, number)
        return product
    if isinstance(expr, sympy.Rational):
        return number(Fraction(int(expr.p), int(expr.q)))
    raise ScrewkitValueError(f"Expected a vector form of named vectors, got the part {expr!r}.")


# --------------------------------------------------------------------------------------------------
# Exact proofs at random integer configurations (Schwartz–Zippel)
# --------------------------------------------------------------------------------------------------

#: Coordinates of the random configurations are integers in [−PROOF_RANGE, PROOF_RANGE].
PROOF_RANGE = 2**31
#: Configurations that must agree after the one that fixes the constant.
PROOF_CHECKS = 2


def _exact_det4(rows: Sequence[Sequence[int]]) -> int:
    """Determinant of a 4×4 integer matrix (Laplace along the first two rows), exact."""
    (a, b, c, d) = rows
    total = 0
    for (i, j), (k, m), sign in P._LAPLACE:
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


def _random_configuration(
    labels: Sequence[str], types: _Types, rng: random.Random
) -> dict[str, tuple[int, ...]]:
    return {
        x: (
            *(rng.randint(-PROOF_RANGE, PROOF_RANGE) for _ in range(3)),
            0 if x in types.infinite else 1,
        )
        for x in labels
    }


def _prove_proportional(
    poly: BracketPolynomial, expr: sympy.Expr | None, types: _Types, seed: int = 0
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
    """
    labels = sorted(set(poly.labels) | ({s.name for s in expr.free_symbols} if expr is not None else set()))
    rng = random.Random(seed)
    constant: Fraction | None = None
    checks = 0
    for _ in range(PROOF_CHECKS + 20):
        points = _random_configuration(labels, types, rng)
        exact = _exact_value(poly, points)
        if expr is None:
            form = Fraction(0)
            constant = Fraction(0)
        else:
            vectors = {x: p[:3] for x, p in points.items()}
            form = Fraction(_form_value(expr, vectors, Fraction))
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

        expr = _sum([value(n_p, p0, x) * value(n_q, q0, y), -value(n_p, p0, y) * value(n_q, q0, x)])
    statement = (
        f"line {_word([x, y])} meets the line where planes {_word(planes[0])} and "
        f"{_word(planes[1])} intersect"
    )
    return expr, statement + _refinement(planes, x, y, types)


def _refinement(planes: list[list[str]], x: str, y: str, types: _Types) -> str:
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
            f"; i.e. the lines at infinity {_word([u, v])}, {_word([x, y])} and {_word([s, t])} "
            f"are concurrent (the normals {u} × {v}, {x} × {y} and {s} × {t} are parallel to one "
            "plane)"
        )
    shared = sorted(set(planes[0]) & set(planes[1]))
    if len(shared) == 1:
        (o,) = shared
        first, second = ([p for p in plane if p != o] for plane in planes)
        through = f"parallel to direction {o}" if o in types.infinite else f"through {o}"
        return (
            f"; i.e. a line {through} meets the three lines {_word(first)}, {_word(second)} and "
            f"{_word([x, y])} (if these lie in one plane not containing {o}: they are concurrent)"
        )
    return ""


# --------------------------------------------------------------------------------------------------
# Conditions
# --------------------------------------------------------------------------------------------------

Factor = Bracket | DottedMonomial | DottedSum | BracketPolynomial

#: The labels of :func:`label`, and what each means (paper 002 §5.3).
LABELS = ("constraint", "actuation", "constraint or actuation")


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
        identically zero, e.g. four points at infinity), proved by exact evaluation at random
        integer configurations (:data:`PROOF_CHECKS`, Schwartz–Zippel).
    vectors : tuple of str
        The labels the expression uses, sorted.
    multiplicity : int, default 1
        How often the factor divides the superbracket (2 for a squared factor).
    label : str, default ""
        ``"constraint"``, ``"actuation"`` or ``"constraint or actuation"`` when the diagram's lines
        and roles were given (:func:`label`), else empty.
    evidence : str, default ""
        Which lines and roles the factor involves, the reason for ``label``.
    """

    factor: Factor
    statement: str
    expression: sympy.Expr
    constant: sympy.Rational
    vectors: tuple[str, ...]
    multiplicity: int = 1
    label: str = ""
    evidence: str = ""

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
        shape = arrays[0].shape[:-1] if arrays else ()
        vectors = {x: (a[..., 0], a[..., 1], a[..., 2]) for x, a in zip(self.vectors, arrays, strict=True)}
        value = _form_value(self.expression, vectors, float)
        return np.broadcast_to(np.asarray(value, dtype=float), shape)[()]

    def __str__(self) -> str:
        power = f" (multiplicity {self.multiplicity})" if self.multiplicity > 1 else ""
        return f"{self.factor} = 0{power} ⇔ {self.statement} ⇔ {self.expression} = 0"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "factor": str(self.factor),
            "statement": self.statement,
            "vector_form": str(self.expression),
            "latex": self.to_latex(),
            "constant": str(self.constant),
            "vectors": list(self.vectors),
            "multiplicity": self.multiplicity,
            "label": self.label,
            "evidence": self.evidence,
        }

    def to_latex(self) -> str:
        """LaTeX of the vector form set to zero, vectors in bold."""
        return sympy.latex(self.expression) + " = 0"

    def factor_latex(self) -> str:
        """LaTeX of the bracket factor (with its dots and multiplicity) set to zero."""
        text = self.factor.to_latex()
        if self.multiplicity > 1:
            text = rf"\left({text}\right)^{{{self.multiplicity}}}"
        return text + " = 0"


def condition(
    factor: Factor,
    *,
    finite: Any,
    infinite: Any,
    lines: Sequence[Sequence[str]] | None = None,
) -> Condition:
    """The geometric condition expressed by one bracket factor (``gca.md`` §5).

    Parameters
    ----------
    factor : Bracket, DottedMonomial, DottedSum or BracketPolynomial
        A factor, e.g. from :attr:`screwkit.gca.FactoredForm.factors`.
    finite, infinite : str or sequence of str
        The labels of finite points (weight 1) and of infinite points.
    lines : sequence of pairs of labels, optional
        The diagram's lines; the generic statement then names the lines the factor involves.

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
    polynomial = _polynomial(factor)
    types.split(sorted(_labels_of(factor)))  # every label declared
    expr, statement = _form(factor, types, _line_pairs(lines))
    constant = _prove_proportional(polynomial, expr, types)
    if expr is None:
        expr = sympy.Integer(0)
    used = tuple(sorted(s.name for s in expr.free_symbols))
    rational = sympy.Rational(constant.numerator, constant.denominator)
    return Condition(factor, statement, expr, rational, used)


def label(
    vectors: Sequence[str], lines: Sequence[Sequence[str]], roles: Sequence[str]
) -> tuple[str, str]:
    """Label a factor by the roles of the lines whose points its vector form uses.

    A factor whose form uses only points of constraint lines is a function of the constraint
    wrenches alone: ``"constraint"`` (paper 002 §5.3, condition 1, [gikj] in the H4), even if
    some of those points also lie on actuation lines. If one of its points lies only on actuation
    lines it involves the actuation wrenches: ``"actuation"`` (condition 2). If every one of its
    points lies on lines of both kinds (e.g. joint centres both kinds of wrench pass through), it is
    a function of either kind alone and the roles cannot tell: ``"constraint or actuation"``.

    Parameters
    ----------
    vectors : sequence of str
        The labels the factor's vector form uses (:attr:`Condition.vectors`).
    lines : sequence of pairs of labels
    roles : sequence of str
        ``"constraint"`` or ``"actuation"`` per line.

    Returns
    -------
    (str, str)
        The label and its evidence in words.

    Examples
    --------
    >>> lines = ["ab", "cd", "ef", "gh", "ij", "kj"]
    >>> roles = ["actuation"] * 4 + ["constraint"] * 2
    >>> label(["i", "j", "k"], lines, roles)[0]
    'constraint'
    >>> label(["b", "j"], lines, roles)
    ('actuation', 'involves lines ab (actuation), ij, kj (constraint); b lies only on actuation lines')
    """
    pairs = _line_pairs(lines) or []
    if len(roles) != len(pairs) or any(r not in ("constraint", "actuation") for r in roles):
        raise ScrewkitValueError(
            f"Expected `roles` to give 'constraint' or 'actuation' for each of the {len(pairs)} "
            f"lines, got {list(roles)}."
        )
    used = set(vectors)
    kinds = list(zip(pairs, roles, strict=True))
    on = {kind: {x for line, r in kinds if r == kind for x in line} for kind in ("constraint", "actuation")}
    involved = {
        kind: [_word(line) for line, r in kinds if r == kind and used & set(line)]
        for kind in ("actuation", "constraint")
    }
    text = "involves lines " + ", ".join(
        f"{', '.join(names)} ({kind})" for kind, names in involved.items() if names
    ) if any(involved.values()) else "involves no line of the diagram"
    only_actuation = sorted(used & on["actuation"] - on["constraint"])
    shared = sorted(used & on["actuation"] & on["constraint"])
    if only_actuation:
        verb = "lies" if len(only_actuation) == 1 else "lie"
        return "actuation", f"{text}; {', '.join(only_actuation)} {verb} only on actuation lines"
    if shared and used <= on["actuation"]:
        return "constraint or actuation", (
            f"{text}; each of its points, {', '.join(shared)}, lies on constraint and on actuation lines"
        )
    also = f" ({', '.join(shared)} on actuation lines too)" if shared else ""
    return "constraint", f"{text}; its points lie on constraint lines{also}"


def conditions(
    factored: FactoredForm,
    *,
    finite: Any,
    infinite: Any,
    lines: Sequence[Sequence[str]] | None = None,
    roles: Sequence[str] | None = None,
) -> tuple[Condition, ...]:
    """One :class:`Condition` per distinct factor of a factored superbracket, with its multiplicity
    and, when the diagram's ``lines`` and ``roles`` are given, its label (:func:`label`).

    Examples
    --------
    >>> from screwkit.gca import BracketPolynomial, collect_factors
    >>> p = BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")
    >>> f = collect_factors(p, finite="aceg", infinite="bdfhijk", collinear=["egj"])
    >>> [str(c.expression) for c in conditions(f, finite="aceg", infinite="bdfhijk")]
    ['(i × k)·j', '((b × d) × ((g − c) × j))·(f × h)']
    >>> lines, roles = ["ab", "cd", "ef", "gh", "ij", "kj"], ["actuation"] * 4 + ["constraint"] * 2
    >>> [c.label for c in conditions(f, finite="aceg", infinite="bdfhijk", lines=lines, roles=roles)]
    ['constraint', 'actuation']
    """
    if not isinstance(factored, FactoredForm):
        raise ScrewkitTypeError(
            f"Expected `factored` to be a FactoredForm, got {type(factored).__name__}."
        )
    found = []
    for factor, multiplicity in zip(factored.factors, factored.multiplicities, strict=True):
        c = condition(factor, finite=finite, infinite=infinite, lines=lines)
        kind, evidence = ("", "") if roles is None else label(c.vectors, lines or (), roles)
        found.append(replace(c, multiplicity=multiplicity, label=kind, evidence=evidence))
    return tuple(found)


def latex(factored: FactoredForm, found: Sequence[Condition], lines: str = "") -> str:
    """The factored superbracket and its conditions as one LaTeX ``align*`` block (amsmath).

    Parameters
    ----------
    factored : FactoredForm
    found : sequence of Condition
        Its conditions (:func:`conditions`).
    lines : str, default ""
        The superbracket's argument, e.g. ``"[ab, cd, ef, gh, ij, kj]"``, printed on the left.

    Examples
    --------
    >>> from screwkit.gca import BracketPolynomial, collect_factors
    >>> f = collect_factors(BracketPolynomial.parse("[gikj][abdf]"))
    >>> print(latex(f, conditions(f, finite="ag", infinite="bdfijk")))  # doctest: +ELLIPSIS
    \\begin{align*}
     &= [gikj][abdf] \\\\
    [gikj] = 0 &\\iff \\left(\\mathbf{i} \\times \\mathbf{k}\\right) \\cdot \\mathbf{j} = 0 ...
    \\end{align*}
    """
    left = lines.replace(", ", ",\\,")
    rows = [rf"{left} &= {factored.to_latex()}" + " \\\\"]
    for c in found:
        head = rf"\text{{{c.label}}}:\quad " if c.label else ""
        rows.append(
            rf"{head}{c.factor_latex()} &\iff {c.to_latex()} "
            rf"\quad\text{{({_latex_text(c.statement)})}}" + " \\\\"
        )
    return "\\begin{align*}\n" + "\n".join(rows) + "\n\\end{align*}"


def _latex_text(text: str) -> str:
    """Plain words for ``\\text{}``: escape LaTeX specials, spell × and ·."""
    for old, new in (("\\", r"\textbackslash{}"), ("_", r"\_"), ("&", r"\&"), ("%", r"\%"),
                     ("#", r"\#"), ("×", r"$\times$"), ("·", r"$\cdot$"), ("−", "-")):
        text = text.replace(old, new)
    return text


def _line_pairs(lines: Any) -> list[tuple[str, ...]] | None:
    if lines is None:
        return None
    if isinstance(lines, str) or not isinstance(lines, Sequence):
        raise ScrewkitTypeError(
            f"Expected `lines` to be a sequence of pairs of labels, got {type(lines).__name__}."
        )
    pairs = [tuple(line) for line in lines]
    if any(len(line) != 2 or not all(isinstance(x, str) for x in line) for line in pairs):
        raise ScrewkitValueError(f"Expected `lines` to be pairs of labels, got {list(lines)!r}.")
    return pairs


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
    """A point of line pq with the weight of its kind (1 finite, 0 infinite), or None."""
    point = p + t * q if p[3] == 0 or q[3] == 0 else p + t * (q - p) if finite else p - q
    if finite:
        return None if point[3] == 0 else point / point[3]
    return point if point[3] == 0 else None


def _plane_triples(
    poly: BracketPolynomial, labels: Sequence[str], types: _Types, points: Mapping[str, np.ndarray]
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


def _four_planes(poly: BracketPolynomial, types: _Types) -> tuple[sympy.Expr, str] | None:
    """``det[π₁; π₂; π₃; π₄]``, zero iff four planes share a point (``gca.md`` §5.2, four-plane
    pattern; the octahedral Gough–Stewart platform), recognised among the ways of grouping the
    factor's twelve letters into four planes: screened on two random float configurations, the
    candidate is then proved exactly by :func:`_prove_proportional`."""
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
        expr = _sum(terms)
        try:
            _prove_proportional(poly, expr, types)
        except ScrewkitValueError:
            continue
        names = [_word(t) for t in candidate]
        return expr, f"planes {_listing(names)} pass through one point (possibly at infinity)"
    return None


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


def _is_superbracket(poly: BracketPolynomial, lines: Sequence[tuple[str, ...]], types: _Types) -> bool:
    """Whether ``poly`` is a non-zero constant times the 6×6 determinant of ``lines``' Plücker
    vectors, proved as in :func:`_prove_proportional` (exact values at random integer points)."""
    if len(lines) != 6 or set(poly.labels) != {x for line in lines for x in line}:
        return False
    rng = random.Random(1)
    ratio = None
    for _ in range(PROOF_CHECKS + 1):
        points = _random_configuration(sorted(poly.labels), types, rng)
        det = _exact_det([_plucker(points[p], points[q]) for p, q in lines])
        value = _exact_value(poly, points)
        if det == 0 or value == 0:
            return False
        if ratio is None:
            ratio = value / det
        elif value != ratio * det:
            return False
    return True


def _form(
    factor: Factor, types: _Types, lines: Sequence[tuple[str, ...]] | None = None
) -> tuple[sympy.Expr | None, str]:
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
    found = _four_planes(polynomial, types)
    if found is not None:
        return found
    products = []
    for monomial in polynomial:
        product = [sympy.Rational(monomial.coefficient.numerator, monomial.coefficient.denominator)]
        for bracket in monomial.brackets:
            expr, _, sign = _bracket_form(bracket.labels, types)
            product += [sympy.Integer(0 if expr is None else sign)] + ([] if expr is None else [expr])
        products.append(sympy.Mul(*product))
    total = _sum(products)
    statement = f"the bracket expression {factor} vanishes"
    if lines is not None and _is_superbracket(polynomial, lines, types):
        statement = (
            f"the six lines {_listing([_word(line) for line in lines])} are linearly dependent "
            "(they belong to one linear line complex): no factor of the superbracket is simpler"
        )
    elif lines is not None:
        labels = set(polynomial.labels)
        involved = [_word(line) for line in lines if labels & set(line)]
        statement += (
            f" (it involves lines {', '.join(involved) or 'none'} through the points "
            f"{', '.join(sorted(labels))})"
        )
    return (total if total != 0 else None), statement
