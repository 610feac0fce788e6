"""Text layer of the Grassmann–Cayley algebra: labels, signs, exact coefficients, the printed form of
brackets and sums (plain and LaTeX, with the dots of McMillan & White), and parsing of bracket text such as
``"[abcd][e f ġ ï] - 2[...]"``. No numbers are evaluated here.
"""

from __future__ import annotations

import functools
import re
import unicodedata
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__: list[str] = []


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
