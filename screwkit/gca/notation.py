"""Text layer of the Grassmann–Cayley algebra: labels, signs, exact coefficients, the printed form of
brackets and sums (plain and LaTeX, with the dots of McMillan & White), and parsing of bracket text such as
``"[abcd][e f ġ ï] - 2[...]"``. No numbers are evaluated here.

Examples
--------
>>> format_bracket(("a", "b", "d", "f"), (0, 0, 0, 1), latex=False)
'[a b d ḟ]'
>>> parse_terms("-[abcd][e f ġ h]")[0][0]
Fraction(-1, 1)
"""

from __future__ import annotations

import functools
import re
import unicodedata
from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "DOT_MARKS",
    "ParsedTerm",
    "check_label",
    "exact_coefficient",
    "format_bracket",
    "format_sum",
    "is_exact_scalar",
    "join_labels",
    "parse_terms",
    "renamed_label",
    "sort_sign",
]


_LABEL = re.compile(r"[A-Za-z][A-Za-z0-9]*\Z")
#: Combining marks of the dot kinds 1..4 (dot, diaeresis, three dots, four dots) and their LaTeX.
DOT_MARKS = ("\u0307", "\u0308", "\u20db", "\u20dc")
_LATEX_DOTS = (r"\dot", r"\ddot", r"\dddot", r"\ddddot")


# --------------------------------------------------------------------------------------------------
# Labels, signs, coefficients
# --------------------------------------------------------------------------------------------------


def check_label(label: Any, name: str) -> str:
    """A label (a letter followed by letters or digits), checked.

    Parameters
    ----------
    label : object
        The candidate label.
    name : str
        The argument's name, for the messages.

    Returns
    -------
    str
        ``label`` itself.

    Raises
    ------
    ScrewkitTypeError
        If it is not a string.
    ScrewkitValueError
        If it is not a label.

    Examples
    --------
    >>> check_label("r1", "labels[0]")
    'r1'
    """
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


@functools.lru_cache(maxsize=1 << 16)
def sort_sign(items: tuple[Any, ...]) -> int:
    """Sign of the permutation that sorts ``items``; 0 if an item repeats.

    Parameters
    ----------
    items : tuple
        Comparable items (hashable: the result is cached).

    Returns
    -------
    int
        1, -1 or 0.

    Examples
    --------
    >>> sort_sign(("b", "a", "c")), sort_sign(("a", "a"))
    (-1, 0)
    """
    if len(set(items)) < len(items):
        return 0
    inversions = sum(
        1 for i in range(len(items)) for j in range(i + 1, len(items)) if items[i] > items[j]
    )
    return -1 if inversions % 2 else 1


def exact_coefficient(value: Any, name: str) -> Fraction:
    """An exact coefficient (an integer or a fraction; floats and booleans are refused).

    Parameters
    ----------
    value : int, fractions.Fraction or an exact number
    name : str
        The argument's name, for the message.

    Returns
    -------
    fractions.Fraction

    Raises
    ------
    ScrewkitTypeError
        If ``value`` is not exact.

    Examples
    --------
    >>> exact_coefficient(3, "coefficient")
    Fraction(3, 1)
    """
    if isinstance(value, bool | np.bool_):
        raise ScrewkitTypeError(f"Expected `{name}` to be an integer or a fraction, got {value!r}.")
    exact = B.exact_fraction(value)
    if exact is not None:
        return exact
    raise ScrewkitTypeError(
        f"Expected `{name}` to be an integer or a fraction (coefficients are exact), "
        f"got {type(value).__name__} {value!r}."
    )


def is_exact_scalar(value: Any) -> bool:
    """Whether ``value`` is an exact number (a possible coefficient).

    Parameters
    ----------
    value : object

    Returns
    -------
    bool

    Examples
    --------
    >>> is_exact_scalar(2), is_exact_scalar(0.5)
    (True, False)
    """
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


def format_bracket(labels: Sequence[str], dots: Sequence[int], *, latex: bool) -> str:
    """A bracket as text, its dotted letters marked.

    Parameters
    ----------
    labels : sequence of str
        The four labels, in order.
    dots : sequence of int
        The dot kind of each label, 0 for none, 1..4 for ``˙ ¨ ⃛ ⃜``.
    latex : bool
        LaTeX (``\\dot{f}``) rather than Unicode (``ḟ``).

    Returns
    -------
    str
        Single-letter labels side by side (``[abdf]``), else separated (``[r1 r2 r3 r4]``, or
        ``[a b d ḟ]`` with dots).

    Examples
    --------
    >>> format_bracket("abdf", (0, 0, 0, 1), latex=True)
    '[abd\\\\dot{f}]'
    """
    single = all(len(label) == 1 for label in labels)
    if latex:
        parts = [
            f"{_LATEX_DOTS[kind - 1]}{{{label}}}" if kind else label
            for label, kind in zip(labels, dots, strict=True)
        ]
        return "[" + ("" if single else r"\,").join(parts) + "]"
    parts = [
        label + (DOT_MARKS[kind - 1] if kind else "") for label, kind in zip(labels, dots, strict=True)
    ]
    text = "[" + ("" if single and not any(dots) else " ").join(parts) + "]"
    return unicodedata.normalize("NFC", text)  # precomposed letters (ḟ, ï) where Unicode has them


def format_sum(terms: Sequence[tuple[Fraction, str]], *, latex: bool) -> str:
    """Join ``(coefficient, body)`` pairs as ``a - 2 b + c``; an empty sum is '0'.

    Parameters
    ----------
    terms : sequence of (fractions.Fraction, str)
        Each term's coefficient and printed body (``""`` for a bare number).
    latex : bool
        Fractions as ``\\tfrac`` rather than ``p/q``.

    Returns
    -------
    str

    Examples
    --------
    >>> from fractions import Fraction
    >>> format_sum([(Fraction(1), "[abcd]"), (Fraction(-2), "[abce]")], latex=False)
    '[abcd] - 2 [abce]'
    """
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


def renamed_label(label: str, mapping: Mapping[str, str]) -> str:
    """A label renamed by ``mapping`` (checked), or the label itself when it is not renamed.

    Parameters
    ----------
    label : str
    mapping : mapping of str to str

    Returns
    -------
    str

    Examples
    --------
    >>> renamed_label("a", {"a": "x"}), renamed_label("b", {"a": "x"})
    ('x', 'b')
    """
    return check_label(mapping[label], f"mapping[{label!r}]") if label in mapping else label


def join_labels(labels: Sequence[str]) -> str:
    """Labels as one word: side by side if each is one letter (``abd``), else with spaces.

    Parameters
    ----------
    labels : sequence of str

    Returns
    -------
    str

    Examples
    --------
    >>> join_labels("abd"), join_labels(["r1", "r2"])
    ('abd', 'r1 r2')
    """
    return ("" if all(len(x) == 1 for x in labels) else " ").join(labels)


# --------------------------------------------------------------------------------------------------
# Parsing '[abcd][e f ġ ï] - 2[...]'
# --------------------------------------------------------------------------------------------------

_TERM = re.compile(
    r"\s*(?P<sign>[+-]?)\s*(?P<coefficient>\d+(?:/\d+)?)?\s*\*?\s*"
    r"(?P<brackets>(?:\[[^\[\]]*\]\s*)*)"
)
_BRACKET = re.compile(r"\[([^\[\]]*)\]")

#: A parsed term: its coefficient and, per bracket, its labels and their dot kinds.
ParsedTerm = tuple[Fraction, list[tuple[tuple[str, ...], tuple[int, ...]]]]


def _parse_bracket(content: str, text: str) -> tuple[tuple[str, ...], tuple[int, ...]]:
    tokens = content.split() if any(ch.isspace() for ch in content) else None
    if tokens is None:  # single letters, each possibly followed by one combining mark
        tokens = []
        for ch in content:
            if ch in DOT_MARKS and tokens:
                tokens[-1] += ch
            else:
                tokens.append(ch)
    labels, kinds = [], []
    for token in tokens:
        base = token.rstrip("".join(DOT_MARKS))
        marks = token[len(base) :]
        if len(marks) > 1 or not _LABEL.match(base):
            raise ScrewkitValueError(
                f"Expected `text` to hold brackets of labels with at most one dot each, "
                f"got the entry {token!r} in {text!r}."
            )
        labels.append(base)
        kinds.append(DOT_MARKS.index(marks) + 1 if marks else 0)
    if len(labels) != 4:
        raise ScrewkitValueError(
            f"Expected `text` to hold brackets of 4 labels, got [{content}] in {text!r}."
        )
    return tuple(labels), tuple(kinds)


#: The most digits a coefficient of a parsed bracket polynomial may have (numerator or denominator):
#: far beyond any expansion's, and below Python's limit on converting text to integers.
_MAX_COEFFICIENT_DIGITS = 1000


def _coefficient(digits: str, text: str) -> Fraction:
    """The coefficient ``p`` or ``p/q`` read by :func:`parse_terms`, refused by name when too long
    or with a zero denominator."""
    numerator, _, denominator = digits.partition("/")
    excerpt = text if len(text) <= 60 else text[:57] + "..."
    if max(len(numerator), len(denominator)) > _MAX_COEFFICIENT_DIGITS:
        raise ScrewkitValueError(
            f"Expected `text` to hold coefficients of at most {_MAX_COEFFICIENT_DIGITS} digits, got one of "
            f"{max(len(numerator), len(denominator))} digits in {excerpt!r}."
        )
    if denominator and int(denominator) == 0:
        raise ScrewkitValueError(
            f"Expected `text` to hold coefficients with non-zero denominators, got {digits!r}."
        )
    return Fraction(int(numerator), int(denominator or 1))


def parse_terms(text: Any) -> list[ParsedTerm]:
    """Parse a sum of (dotted) bracket monomials with integer or rational coefficients.

    Parameters
    ----------
    text : str
        E.g. ``"[abdf][cghj] - 1/2 [a b d ḟ][c g ḣ j]"`` (precomposed or combining dots).

    Returns
    -------
    list of ParsedTerm
        ``(coefficient, [(labels, dot kinds), ...])`` per term.

    Raises
    ------
    ScrewkitTypeError
        If ``text`` is not a string.
    ScrewkitValueError
        If it cannot be read (the position is named).

    Examples
    --------
    >>> parse_terms("2[a b ċ d]")
    [(Fraction(2, 1), [(('a', 'b', 'c', 'd'), (0, 0, 1, 0))])]
    """
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
        coefficient = _coefficient(match["coefficient"] or "1", text)
        if match["sign"] == "-":
            coefficient = -coefficient
        brackets = [
            _parse_bracket(content, text) for content in _BRACKET.findall(match["brackets"])
        ]
        terms.append((coefficient, brackets))
        position = match.end()
    return terms
