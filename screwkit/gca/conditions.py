"""Geometric statements and vector forms of bracket factors (``gca.md`` §5, paper 002 §5.3).

Each factor of a factored superbracket (:func:`screwkit.gca.collect_factors`) vanishes exactly on
some singular configurations. :func:`condition` turns one factor into a :class:`Condition`:

* a geometric statement, e.g. "i, k and j are collinear in the plane at infinity" or
  "line fh meets the line where planes abd and cgj intersect" (``gca.md`` §5.1, §5.2);
* a vector form: a sympy expression in named vectors, finite points standing for their position
  vectors (weight 1) and infinite points for their directions, built from the unevaluated
  products :class:`~screwkit.gca.vector_forms.VectorCross`,
  :class:`~screwkit.gca.vector_forms.VectorDot` and the difference
  :class:`~screwkit.gca.vector_forms.VectorDiff`
  (e.g. paper 002 Eq. 6, ``(s12 × s34)·z``, and Eq. 7,
  ``((s1 × s2) × ((r_g − r_c) × z))·(s3 × s4)``);
* the exact constant with ``factor = constant × vector form``, proved at construction by exact
  integer evaluation of both sides at random configurations (Schwartz–Zippel,
  :data:`screwkit.gca.exact_proofs.PROOF_CHECKS`;
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

Any other factor gets the generic form: its expansion with every bracket replaced by its form. The
patterns are :mod:`screwkit.gca.condition_patterns`, the proofs :mod:`screwkit.gca.exact_proofs`,
the vector products and their evaluator :mod:`screwkit.gca.vector_forms`; this module turns
factors into :class:`Condition` values and labels them.

This module is symbolic by nature (its vector forms are sympy expressions), so importing it imports
sympy; :mod:`screwkit.gca.superbracket_analysis` imports it only when conditions are asked for.

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

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import sympy

from ..algebra import backend as B
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .brackets import Bracket
from .condition_patterns import Factor, bracket_polynomial, vector_form
from .dotted import DottedMonomial
from .exact_proofs import prove_proportional
from .factored import FactoredForm
from .notation import join_labels
from .vector_forms import PointKinds, form_value

__all__ = [
    "LABELS",
    "Condition",
    "condition",
    "conditions",
    "given_couples",
    "label",
    "latex",
]


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
        integer configurations (:data:`~screwkit.gca.exact_proofs.PROOF_CHECKS`, Schwartz–Zippel).
    vectors : tuple of str
        The labels the expression uses, sorted.
    multiplicity : int, default 1
        How often the factor divides the superbracket (2 for a squared factor).
    label : str, default ""
        ``"constraint"``, ``"actuation"`` or ``"constraint or actuation"`` when the diagram's lines
        and roles were given (:func:`label`), else empty.
    evidence : str, default ""
        Which lines and roles the factor involves, the reason for ``label``.
    split : tuple of Bracket, default ()
        The brackets whose product the factor is a constant multiple of on the mechanism's sampled
        configurations (:mod:`screwkit.gca.design_factors`), if any: it vanishes where one of them
        does.
    """

    factor: Factor
    statement: str
    expression: sympy.Expr
    constant: sympy.Rational
    vectors: tuple[str, ...]
    multiplicity: int = 1
    label: str = ""
    evidence: str = ""
    split: tuple[Bracket, ...] = ()

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
        value = form_value(self.expression, vectors, float)
        return np.broadcast_to(np.asarray(value, dtype=float), shape)[()]

    def __str__(self) -> str:
        power = f" (multiplicity {self.multiplicity})" if self.multiplicity > 1 else ""
        return f"{self.factor} = 0{power} ⇔ {self.statement} ⇔ {self.expression} = 0"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary.

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
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
            "split_on_mechanism": [str(b) for b in self.split],
        }

    def to_latex(self) -> str:
        """LaTeX of the vector form set to zero, vectors in bold.

        Returns
        -------
        str
        """
        return sympy.latex(self.expression) + " = 0"

    def __repr__(self) -> str:
        label = f"{self.label}: " if self.label else ""
        return f"Condition({label}{self.factor} = 0: {self.statement})"

    def _repr_latex_(self) -> str:
        r"""Jupyter: the factor and its vector form, set to zero, typeset.

        Returns
        -------
        str

        Examples
        --------
        >>> condition(DottedMonomial.parse("[gikj]"), finite="g", infinite="ikj")._repr_latex_()
        '$[gikj] = 0 \\iff - \\left(\\mathbf{i} \\times \\mathbf{k}\\right) \\cdot \\mathbf{j} = 0$'
        """
        head = rf"\text{{{self.label}}}:\quad " if self.label else ""
        return f"${head}{self.factor_latex()} \\iff {self.to_latex()}$"

    def factor_latex(self) -> str:
        """LaTeX of the bracket factor (with its dots and multiplicity) set to zero.

        Returns
        -------
        str
        """
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
    types = PointKinds(finite, infinite)
    polynomial = bracket_polynomial(factor)
    types.split(sorted(_labels_of(factor)))  # every label declared
    expr, statement = vector_form(factor, types, _line_pairs(lines))
    constant = prove_proportional(polynomial, expr, types)
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
        kind: [join_labels(line) for line, r in kinds if r == kind and used & set(line)]
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

    Parameters
    ----------
    factored : FactoredForm
    finite, infinite : str or sequence of str
        The labels of finite points (weight 1) and of infinite points.
    lines : sequence of pairs of labels, optional
        The diagram's lines (statements name them; with ``roles``, the labels).
    roles : sequence of str, optional
        ``"constraint"`` or ``"actuation"`` per line.

    Returns
    -------
    tuple of Condition
        One per distinct factor, in the order of :attr:`FactoredForm.factors`.

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


def given_couples(
    found: Sequence[Condition], lines: Sequence[Sequence[str]], roles: Sequence[str], infinite: Any
) -> tuple[Condition, ...]:
    """The actuation condition given the constraints, in words, where the constraints are two couples
    normal to one direction: the constraint lines are two lines at infinity ``ij``, ``kj`` through a
    common point j (the Schönflies-motion generators' couples, normal to the rotation axis j).

    Where the constraint factors do not vanish the two couples span every couple normal to j, so the
    six lines are dependent exactly when the actuation lines and those couples are: when a twist
    reciprocal to them, i.e. a translation with a rotation about an axis parallel to j (ω ∥ j), does
    no work on any actuation line (paper 002 §5.3; the factor is then proportional to the 4×4
    determinant of the actuation lines on the translations and the rotation about j, checked in
    tests/gca/test_statements.py). A single actuation factor (multiplicity 1) that only had the
    generic statement gets this one; every other condition is returned unchanged.

    Parameters
    ----------
    found : sequence of Condition
        The labelled conditions of one superbracket (:func:`conditions`).
    lines : sequence of pairs of labels
    roles : sequence of str
        ``"constraint"`` or ``"actuation"`` per line.
    infinite : str or sequence of str
        The labels of the points at infinity.

    Returns
    -------
    tuple of Condition

    Examples
    --------
    >>> from screwkit.gca import BracketPolynomial, collect_factors
    >>> ragnar = [(1, "abef", "cdhj"), (-1, "abhf", "cdej"), (1, "abed", "fghj"), (-1, "abeh", "fgdj")]
    >>> text = " ".join(f"{'+-'[s < 0]} [gikj][{p}][{q}]" for s, p, q in ragnar)  # the catalog Ragnar's
    >>> f = collect_factors(BracketPolynomial.parse(text))
    >>> lines = ["ab", "cd", "ef", "gh", "ij", "kj"]
    >>> roles = ["actuation"] * 4 + ["constraint"] * 2
    >>> found = conditions(f, finite="aceg", infinite="bdfhijk", lines=lines, roles=roles)
    >>> print(given_couples(found, lines, roles, "bdfhijk")[1].statement)  # doctest: +NORMALIZE_WHITESPACE
    a translation combined with a rotation about an axis parallel to j does no work on any of the
    actuation lines ab, cd, ef, gh (with the couples normal to j, spanned by ij, kj, they are
    linearly dependent)
    """
    pairs = _line_pairs(lines) or []
    couples = [line for line, role in zip(pairs, roles, strict=True) if role == "constraint"]
    at_infinity = set(infinite)
    common = set.intersection(*(set(line) for line in couples)) if couples else set()
    actuation = [c for c in found if c.label == "actuation"]
    if (
        len(couples) != 2
        or not all(set(line) <= at_infinity for line in couples)
        or len(common) != 1
        or len(actuation) != 1
        or actuation[0].multiplicity != 1
        or not actuation[0].statement.startswith("the bracket expression")
        or any(c.label != "constraint" for c in found if c is not actuation[0])
    ):
        return tuple(found)
    (j,) = common
    driven = [join_labels(line) for line, role in zip(pairs, roles, strict=True) if role == "actuation"]
    statement = (
        f"a translation combined with a rotation about an axis parallel to {j} does no work on any of "
        f"the actuation lines {', '.join(driven)} (with the couples normal to {j}, spanned by "
        f"{', '.join(join_labels(line) for line in couples)}, they are linearly dependent)"
    )
    return tuple(replace(c, statement=statement) if c is actuation[0] else c for c in found)


def latex(
    factored: FactoredForm,
    found: Sequence[Condition],
    lines: str = "",
    never_vanishes: Sequence[bool] | None = None,
) -> str:
    """The factored superbracket and its conditions as one LaTeX ``align*`` block (amsmath).

    Parameters
    ----------
    factored : FactoredForm
    found : sequence of Condition
        Its conditions (:func:`conditions`).
    lines : str, default ""
        The superbracket's argument, e.g. ``"[ab, cd, ef, gh, ij, kj]"``, printed on the left.
    never_vanishes : sequence of bool, optional
        Per condition: True for a factor that does not vanish on the mechanism's workspace
        (:attr:`screwkit.gca.superbracket_analysis.SuperbracketAnalysis.constant`), written
        ``\\text{never vanishes}: factor \\neq 0`` instead of a labelled condition.

    Returns
    -------
    str

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
    flags = [False] * len(found) if never_vanishes is None else list(never_vanishes)
    for c, never in zip(found, flags, strict=True):
        if never:
            rows.append(
                rf"\text{{never vanishes}}:\quad {c.factor_latex().removesuffix(' = 0')} \neq 0 "
                rf"&\iff {sympy.latex(c.expression)} \neq 0" + " \\\\"
            )
            continue
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


def _labels_of(factor: Factor) -> set[str]:
    return set(bracket_polynomial(factor).labels) | (
        {x for b in factor.brackets for x in b} if isinstance(factor, DottedMonomial) else set()
    )


