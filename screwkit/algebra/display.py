"""How values are shown to people: numbers without rounding noise, screws as screws, short reprs and
HTML tables for Jupyter.

Display only: nothing here changes a value. A coordinate smaller than :data:`DISPLAY_RTOL` times the
largest coordinate of its screw (or row) is shown as ``0`` (a rank decision of the analysis already
treats it as zero: its default tolerance, 1e-9, is far coarser), so ``5e-18`` left by a cross
product prints as ``0``; the arrays keep their exact floats (``np.asarray(screw)``).

The reprs of screwkit's classes are one line for values (``Screw``, ``ScrewSystem``,
``SingularityReport``, ``Jacobians``) and a few lines for reports; ``str()`` is the full text, and
``_repr_html_`` renders reports in Jupyter with :func:`html_table` and :func:`html_section`.

Examples
--------
>>> screw_text([0, 0, 1, 0.4, -0.5, 5e-18])
'(0, 0, 1; 0.4, -0.5, 0)'
>>> elided(["a", "b", "c", "d", "e"], limit=3)
'a, b, c, … (5 in all)'
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

__all__ = [
    "DISPLAY_RTOL",
    "ScrewArray",
    "clean",
    "elided",
    "html_section",
    "html_table",
    "number_text",
    "screw_text",
]

#: Entries below this fraction of the largest entry of their row are shown as 0 (display only).
DISPLAY_RTOL = 1e-12


def clean(values: Any, rtol: float = DISPLAY_RTOL) -> np.ndarray:
    """A float copy with rounding noise set to zero row by row (the last axis), for display.

    Parameters
    ----------
    values : array_like, shape (..., k)
        Numeric rows (a screw's six coordinates, a matrix's rows).
    rtol : float, optional
        Entries smaller than ``rtol`` times the row's largest magnitude become 0 (as do ``-0.0``).

    Returns
    -------
    numpy.ndarray
        The same shape, float.

    Examples
    --------
    >>> clean([[1.0, 5e-18, -0.0], [0.0, 0.0, 0.0]]).tolist()
    [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
    """
    array = np.array(values, dtype=float)
    if array.ndim == 0:
        return array
    with np.errstate(invalid="ignore"):
        largest = np.nanmax(np.abs(array), axis=-1, keepdims=True, initial=0.0)
        array[np.abs(array) < rtol * largest] = 0.0
    return array + 0.0  # -0.0 + 0.0 is +0.0


def number_text(value: Any, digits: int = 6) -> str:
    """A number to ``digits`` significant digits, ``-0`` shown as ``0``; anything else as ``str``.

    Parameters
    ----------
    value : number or object
        A float, an int, or a symbolic expression (shown by ``str``).
    digits : int, optional
        Significant digits.

    Returns
    -------
    str

    Examples
    --------
    >>> number_text(-0.0), number_text(2 / 3, 3), number_text(float("nan"))
    ('0', '0.667', 'nan')
    """
    if isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool):
        return f"{float(value) + 0.0:.{digits}g}"
    return str(value)


def screw_text(coords: Any, digits: int = 6) -> str:
    """Six screw coordinates as ``(s; s0)``, direction first, rounding noise shown as 0.

    Parameters
    ----------
    coords : array_like, shape (6,)
        Numeric or symbolic coordinates.
    digits : int, optional
        Significant digits of each coordinate.

    Returns
    -------
    str

    Examples
    --------
    >>> screw_text([1, 0, 0, 0, 2.000000000001, -1e-19])
    '(1, 0, 0; 0, 2, 0)'
    """
    array = np.asarray(coords)
    if array.dtype != object:
        array = clean(array)
    parts = [number_text(v, digits) for v in array.reshape(6)]
    return f"({', '.join(parts[:3])}; {', '.join(parts[3:])})"


def elided(items: Iterable[str], limit: int = 4) -> str:
    """Items joined by commas, cut after ``limit`` with the total said.

    Parameters
    ----------
    items : iterable of str
    limit : int, optional
        How many to show.

    Returns
    -------
    str

    Examples
    --------
    >>> elided(["a", "b"])
    'a, b'
    """
    listed = list(items)
    if len(listed) <= limit:
        return ", ".join(listed)
    return ", ".join(listed[:limit]) + f", … ({len(listed)} in all)"


def html_table(header: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    """An HTML table, every cell escaped.

    Parameters
    ----------
    header : sequence of str
        Column titles.
    rows : iterable of sequences
        Cells, shown by ``str``.

    Returns
    -------
    str

    Examples
    --------
    >>> html_table(["x", "y"], [[1, "<a>"]])
    '<table><tr><th>x</th><th>y</th></tr><tr><td>1</td><td>&lt;a&gt;</td></tr></table>'
    """
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(str(cell))}</td>" for cell in row) + "</tr>" for row in rows
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def html_section(title: str, body: str, *, level: int = 4) -> str:
    """A titled section: an escaped heading and ``body`` (HTML, not escaped).

    Parameters
    ----------
    title : str
    body : str
        HTML.
    level : int, optional
        The heading level.

    Returns
    -------
    str

    Examples
    --------
    >>> html_section("verdict", "<p>regular</p>")
    '<h4>verdict</h4><p>regular</p>'
    """
    return f"<h{level}>{html.escape(title)}</h{level}>{body}"


class ScrewArray(np.ndarray):
    """A numpy array of screws ``(..., 6)`` that prints its rows as screws, rounding noise shown as 0.

    Everything else is the plain array (shape, indexing, arithmetic, ``np.asarray`` gives the exact
    floats); arrays whose last axis is not 6 print as numpy does.

    Parameters
    ----------
    rows : array_like, shape (..., 6)

    Examples
    --------
    >>> twists = ScrewArray([[0, 0, 1, 0.4, -0.5, 5e-18]])
    >>> twists
    ScrewArray([(0, 0, 1; 0.4, -0.5, 0)])
    >>> print(twists)
    [(0, 0, 1; 0.4, -0.5, 0)]
    >>> twists.shape, float(twists[0, 5])
    ((1, 6), 5e-18)
    """

    def __new__(cls, rows: Any) -> ScrewArray:
        return np.asarray(rows, dtype=float).view(cls)

    def _screws(self) -> str | None:
        if self.ndim == 0 or self.shape[-1] != 6:
            return None
        return ", ".join(screw_text(row) for row in np.asarray(self).reshape(-1, 6))

    def __repr__(self) -> str:
        screws = self._screws()
        return repr(np.asarray(self)) if screws is None else f"ScrewArray([{screws}])"

    def __str__(self) -> str:
        screws = self._screws()
        return str(np.asarray(self)) if screws is None else f"[{screws}]"
