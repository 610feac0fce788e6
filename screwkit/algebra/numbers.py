"""Refusing what is not a number before numpy reads it as one: the boundary of every numeric input.

numpy reads ``None`` as NaN, the string ``'1'`` as 1.0 and ``True`` as 1.0; :func:`numbers_only`
refuses each by name, so :func:`screwkit.algebra.backend.as_array` (which every public function
calls on its array arguments) says what was given rather than "got NaN".

Examples
--------
>>> numbers_only(None, "coords")
Traceback (most recent call last):
...
screwkit.exceptions.ScrewkitTypeError: Expected `coords` to be an array of numbers, got None.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError

__all__ = ["numbers_only"]


def numbers_only(value: Any, name: str) -> Any:
    """``value`` itself, or as an array, if it holds numbers; refuses None, strings, booleans and
    complex numbers by name (numpy would read None as NaN, ``'1'`` as 1.0 and ``True`` as 1.0).

    Parameters
    ----------
    value : object
        A number, a sequence of numbers, an array.
    name : str
        The argument's name, used in the message.

    Returns
    -------
    object
        ``value`` (a number or a numeric array), or ``numpy.asarray(value)``.

    Raises
    ------
    ScrewkitTypeError
        Naming the argument, the expected and what was got (with its flat index in the array).

    Examples
    --------
    >>> numbers_only([1, 2.5], "point")
    array([1. , 2.5])
    >>> numbers_only([1, True], "point")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitTypeError: Expected `point` to be ..., got bool True at flat index 1.
    """
    if value is None:
        raise ScrewkitTypeError(f"Expected `{name}` to be an array of numbers, got None.")
    if isinstance(value, bool | np.bool_):
        raise ScrewkitTypeError(f"Expected `{name}` to be an array of numbers, got the boolean {value!r}.")
    if isinstance(value, int | float) or (isinstance(value, np.ndarray) and value.dtype.kind in "fiu"):
        return value  # the common cases, checked without a copy
    raw = np.asarray(value)  # a ragged list raises ValueError: the caller's message
    if raw.dtype.kind not in "fiuO":
        what = {"b": "booleans", "U": "strings", "S": "strings", "c": "complex numbers"}.get(
            raw.dtype.kind, f"dtype {raw.dtype}"
        )
        raise ScrewkitTypeError(
            f"Expected `{name}` to be an array of real numbers, got {what}: {_excerpt(raw)}."
        )
    if raw.dtype.kind == "O" or isinstance(value, list | tuple):  # numpy reads [True, 2.0] as [1.0, 2.0]
        items = raw if raw.dtype.kind == "O" else np.array(value, dtype=object)
        for index, item in enumerate(items.flat):
            if item is None or isinstance(item, str | bytes | bool | np.bool_ | complex):
                got = "None" if item is None else f"{type(item).__name__} {item!r}"
                raise ScrewkitTypeError(
                    f"Expected `{name}` to be an array of real numbers, got {got} at flat index {index}."
                )
    return raw


def _excerpt(array: np.ndarray) -> str:
    text = repr(array.tolist())
    return text if len(text) <= 80 else text[:77] + "..."
