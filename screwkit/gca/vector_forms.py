"""Vector forms: sympy expressions in named vectors for the conditions of bracket factors
(``gca.md`` §5), their printing (plain and LaTeX) and their value.

Finite points stand for their position vectors (weight 1) and infinite points for their directions;
the products are the unevaluated :class:`VectorCross`, :class:`VectorDot` and the difference
:class:`VectorDiff`, so a form prints in the order written (paper 002 Eq. 6, ``(s12 × s34)·z``).
:class:`PointKinds` holds which labels are finite and which infinite; :func:`form_value` evaluates
a form on exact or float coordinates (batches broadcast).

This module is symbolic by nature (its vector products subclass ``sympy.Function``), so importing
it imports sympy.

Examples
--------
>>> i, k, j = sympy.symbols("i k j")
>>> form = VectorDot(VectorCross(i, k), j)
>>> print(form), form_value(form, {"i": (1, 0, 0), "k": (0, 1, 0), "j": (0, 0, 2)}, float)
(i × k)·j
(None, 2)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from fractions import Fraction
from typing import Any

import sympy

from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "PointKinds",
    "VectorCross",
    "VectorDiff",
    "VectorDot",
    "form_value",
    "vector_sum",
]


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


def vector_sum(terms: Sequence[sympy.Expr]) -> sympy.Expr:
    """``sympy.Add(*terms)`` of the vector forms' products, without ``Add.flatten`` when the non-zero
    terms are products ``c·s`` of distinct ``s`` (nothing to collect): their sum is then those terms
    in sympy's canonical order (``Add.flatten``'s own result for them; the first ``Add.flatten`` of a
    process imports ``sympy.tensor.tensor``, 25–90 ms of a command-line analysis). Any other sum
    (like terms, numbers, nested sums, fewer than two terms) goes through ``sympy.Add``.

    Parameters
    ----------
    terms : sequence of sympy.Expr
        Products of the vector forms (numbers times :class:`VectorDot` and the like).

    Returns
    -------
    sympy.Expr
        ``sympy.Add(*terms)``, the same arguments in the same order.

    Examples
    --------
    >>> i, k, j = sympy.symbols("i k j")
    >>> terms = [2 * VectorDot(i, k), -VectorDot(k, j), sympy.Integer(0)]
    >>> print(vector_sum(terms))
    2*i·k - k·j
    >>> vector_sum(terms) == sympy.Add(*terms)
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


def form_value(expr: sympy.Basic, vectors: Mapping[str, Any], number: Callable[[Any], Any]) -> Any:
    """Value of a vector form: each symbol becomes the 3-tuple ``vectors[name]`` (components may
    be Python integers, fractions or numpy arrays; only ``+ − ×`` are used), sympy numbers go
    through ``number`` (``fractions.Fraction`` for exact values, ``float`` for numbers).

    Parameters
    ----------
    expr : sympy.Basic
        A vector form (symbols, :class:`VectorDiff`, :class:`VectorCross`, :class:`VectorDot`,
        sums, products and rational numbers).
    vectors : mapping of str to 3-tuple
        The vector of each symbol by name.
    number : callable
        Converts the form's rational numbers (``fractions.Fraction`` or ``float``).

    Returns
    -------
    object
        A scalar (or a 3-tuple for a vector-valued part) of the components' type.

    Raises
    ------
    ScrewkitValueError
        For a part that is not a vector form.

    Examples
    --------
    >>> from fractions import Fraction
    >>> g, c = sympy.symbols("g c")
    >>> form_value(2 * VectorDot(VectorDiff(g, c), g), {"g": (1, 2, 0), "c": (1, 0, 0)}, Fraction)
    Fraction(8, 1)
    """
    if isinstance(expr, sympy.Symbol):
        return vectors[expr.name]
    if isinstance(expr, VectorDiff | VectorCross | VectorDot):
        a, b = (form_value(arg, vectors, number) for arg in expr.args)
        if isinstance(expr, VectorDiff):
            return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
        if isinstance(expr, VectorCross):
            return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    if isinstance(expr, sympy.Add):
        values = [form_value(arg, vectors, number) for arg in expr.args]
        total = values[0]
        for value in values[1:]:
            total = total + value
        return total
    if isinstance(expr, sympy.Mul):
        product = number(1)
        for arg in expr.args:
            product = product * form_value(arg, vectors, number)
        return product
    if isinstance(expr, sympy.Rational):
        return number(Fraction(int(expr.p), int(expr.q)))
    raise ScrewkitValueError(f"Expected a vector form of named vectors, got the part {expr!r}.")


class PointKinds:
    """Declared finite and infinite labels (finite points stand for positions, infinite ones for
    directions).

    Parameters
    ----------
    finite, infinite : str or sequence of str
        The labels of each kind (``"acg"``, ``"r1 r2"`` or a sequence of label strings); disjoint.

    Attributes
    ----------
    finite, infinite : frozenset of str

    Examples
    --------
    >>> kinds = PointKinds("acg", "bdf")
    >>> kinds.split(["a", "b", "c"])
    (['a', 'c'], ['b'])
    """

    def __init__(self, finite: Any, infinite: Any) -> None:
        self.finite = _label_set(finite, "finite")
        self.infinite = _label_set(infinite, "infinite")
        both = sorted(self.finite & self.infinite)
        if both:
            raise ScrewkitValueError(
                f"Expected `finite` and `infinite` to be disjoint, got {both} in both."
            )

    def split(self, labels: Sequence[str]) -> tuple[list[str], list[str]]:
        """The finite and the infinite labels among ``labels``, each in the order given.

        Parameters
        ----------
        labels : sequence of str

        Returns
        -------
        finite, infinite : list of str

        Raises
        ------
        ScrewkitValueError
            If a label is declared as neither kind.
        """
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

