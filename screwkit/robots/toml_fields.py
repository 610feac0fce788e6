"""Reading the catalog's and the snapshots' TOML files: the file itself (size caps, encoding, parsing
with :mod:`tomllib`), the kind of file, units (lengths as exact fractions of a metre, angles) and the
typed readers of their fields, each error naming the file, the table and the field.

Two kinds of file, told apart by ``[mechanism] kind`` (:func:`file_kind`): catalog entries
(``kind = "family"``, :mod:`screwkit.robots.catalog`) and snapshots (``kind = "snapshot"``,
:mod:`screwkit.robots.snapshot`). File text is only ever parsed as TOML data: it never reaches
``eval`` or ``sympify``.

Examples
--------
>>> file_kind({"mechanism": {"kind": "family"}}), LENGTH_UNITS["mm"]
('family', Fraction(1, 1000))
"""

from __future__ import annotations

import codecs
import math
import os
import stat
import unicodedata
from collections.abc import Callable, Mapping
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..exceptions import (
    CatalogError,
    ScrewkitTypeError,
    ScrewkitValueError,
)

if TYPE_CHECKING:
    pass


__all__ = [
    "ANGLE_UNITS",
    "LENGTH_UNITS",
    "MAX_ANGLE_DEGREES",
    "MAX_ANGLE_RADIANS",
    "MAX_COORDINATE",
    "MAX_FILE_BYTES",
    "NUMBER_UNITS",
    "degrees_to_radians",
    "file_kind",
    "load_toml",
]


def _error(source: str, where: str, message: str) -> CatalogError:
    return CatalogError(f"{source}: {where}: {message}")


#: The length units a file may name, as exact fractions of a metre (conversions are exact up to one
#: rounding of the result).
LENGTH_UNITS: dict[str, Fraction] = {
    "km": Fraction(1000),
    "m": Fraction(1),
    "dm": Fraction(1, 10),
    "cm": Fraction(1, 100),
    "mm": Fraction(1, 1000),
    "um": Fraction(1, 10**6),
    "µm": Fraction(1, 10**6),
    "nm": Fraction(1, 10**9),
    "in": Fraction(254, 10**4),
    "ft": Fraction(3048, 10**4),
}
#: Units of angles and of pure numbers in ``[parameters.*] unit``.
ANGLE_UNITS = ("deg", "rad")
NUMBER_UNITS = ("-", "1")
#: Largest coordinate (point, pitch) a snapshot may give, in its length unit: products of a few
#: coordinates must stay far from overflow in the rank kernels and the superbracket.
MAX_COORDINATE = 1e100
#: Resource cap: a larger file is refused before it is parsed.
MAX_FILE_BYTES = 1 << 20
#: Nesting depth of lists in a parameter value (a ``(4, 3)`` table of points is depth 2).
_MAX_LIST_DEPTH = 3


def _check_keys(table: Mapping[str, Any], known: Any, source: str, where: str) -> None:
    """Refuse keys outside ``known``, naming the closest known key."""
    for key in table:
        if key not in known:
            import difflib

            close = difflib.get_close_matches(str(key), sorted(known), n=1)
            hint = f" (did you mean `{close[0]}`?)" if close else ""
            raise _error(
                source, where, f"unknown field `{key}`{hint}; expected some of {sorted(known)}."
            )


#: The largest angle, in degrees, that files and ``--pose`` take: a double holds an angle up to it to
#: ~1e-11 rad (its ulp), below every tolerance of the analysis; beyond, ``value · π/180`` names some
#: other angle. Angles are not reduced modulo 360°: a screw-pair platform (the Veloce, the Ragnar's
#: φ over ±360°) is in another configuration after a whole turn.
MAX_ANGLE_DEGREES = 1e6
#: The same bound for the radians of the Python API
#: (:meth:`~screwkit.robots.mechanism.Mechanism.check_pose_range`).
MAX_ANGLE_RADIANS = math.radians(MAX_ANGLE_DEGREES)


def degrees_to_radians(value: float) -> float:
    """Degrees to radians, whole turns kept (``360`` is ``2π``, not ``0``).

    Parameters
    ----------
    value : float
        An angle in degrees.

    Returns
    -------
    float
        The angle in radians.

    Raises
    ------
    ScrewkitValueError
        For a magnitude above :data:`MAX_ANGLE_DEGREES`.

    Examples
    --------
    >>> degrees_to_radians(360.0) == 2 * math.pi
    True
    >>> degrees_to_radians(1e20)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected an angle of at most 1e+06 degrees in magnitude ...
    """
    if not abs(value) <= MAX_ANGLE_DEGREES:
        raise ScrewkitValueError(
            f"Expected an angle of at most {MAX_ANGLE_DEGREES:g} degrees in magnitude (beyond it a double "
            f"no longer holds the angle to the analysis's precision), got {value:g}."
        )
    return math.radians(value)


def file_kind(data: Mapping[str, Any]) -> Any:
    """``[mechanism] kind`` of parsed TOML: ``"family"`` or ``"snapshot"`` (a file without a kind but
    with ``[[joints]]`` is read as a snapshot, so that its errors speak of snapshots); None otherwise.

    Parameters
    ----------
    data : mapping
        A parsed TOML file.

    Returns
    -------
    str or None
        ``"family"``, ``"snapshot"``, another string the file names, or None.

    Examples
    --------
    >>> file_kind({"mechanism": {"kind": "snapshot"}}), file_kind({"mechanism": 5}), file_kind({"joints": []})
    ('snapshot', None, 'snapshot')
    """
    if not isinstance(data, Mapping):
        return None
    header = data.get("mechanism")
    kind = header.get("kind") if isinstance(header, Mapping) else None
    return "snapshot" if kind is None and "joints" in data else kind


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file as plain data, with errors that name the file.

    Parameters
    ----------
    path : str or pathlib.Path
        The file (at most :data:`MAX_FILE_BYTES`, UTF-8 text).

    Returns
    -------
    dict
        The parsed TOML as plain data.

    Examples
    --------
    >>> load_toml("/nonexistent.toml")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: /nonexistent.toml: cannot read the file: No such file or directory.
    """
    import tomllib  # on first use: not a cost of `import screwkit`

    if not isinstance(path, str | Path):
        raise ScrewkitTypeError(f"Expected `path` to be a str or pathlib.Path, got {type(path).__name__}.")
    name = str(path)
    try:
        mode = os.stat(path).st_mode
        regular = stat.S_ISREG(mode)
        if regular:  # not a pipe (it would block), nor /dev/zero (it never ends)
            with open(path, "rb") as stream:
                raw = stream.read(MAX_FILE_BYTES + 1)
    except OSError as err:
        raise CatalogError(f"{name}: cannot read the file: {err.strerror or err}.") from err
    except ValueError as err:  # e.g. a NUL character in the path
        raise CatalogError(f"{name}: cannot read the file: {err}.") from err
    if not regular:
        got = "a folder" if stat.S_ISDIR(mode) else "a pipe" if stat.S_ISFIFO(mode) else "a device"
        raise CatalogError(f"{name}: cannot read the file: expected a regular file, got {got}.")
    if len(raw) > MAX_FILE_BYTES:
        raise CatalogError(f"{name}: expected a file of at most {MAX_FILE_BYTES} bytes, got a larger one.")
    if raw.startswith(codecs.BOM_UTF8):  # some editors start UTF-8 files with a byte-order mark
        raw = raw[len(codecs.BOM_UTF8) :]
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise CatalogError(
            f"{name}: expected UTF-8 text (TOML), got byte 0x{raw[err.start]:02x} at offset {err.start} "
            "(a binary file, or another encoding such as UTF-16)."
        ) from err
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise CatalogError(f"{name}: not valid TOML: {err}.") from err
    except RecursionError as err:
        raise CatalogError(f"{name}: not valid TOML here: arrays or tables nested too deeply.") from err


def _table(data: Mapping[str, Any], key: str, source: str, where: str = "") -> dict[str, Any]:
    value = data.get(key)
    if not isinstance(value, dict):
        got = "nothing" if value is None else type(value).__name__
        raise _error(source, where or f"[{key}]", f"expected a table [{key}], got {got}.")
    return value


def _string(data: Mapping[str, Any], key: str, source: str, where: str) -> str:
    value = data.get(key)
    if not isinstance(value, str) or not value:
        raise _error(source, where, f"field `{key}`: expected a non-empty string, got {value!r}.")
    return value


def _name(data: Mapping[str, Any], key: str, source: str, where: str) -> str:
    """A name (of the mechanism, a link or a joint): a non-empty string without control characters
    (a tab is allowed): a newline or an escape sequence would garble the text report or the terminal."""
    value = _string(data, key, source, where)
    bad = next((c for c in value if unicodedata.category(c) == "Cc" and c != "\t"), None)
    if bad is not None:
        raise _error(
            source, where, f"field `{key}`: expected a name without control characters, got {value!r} "
            f"(character U+{ord(bad):04X})."
        )
    return value


def _strings(data: Mapping[str, Any], key: str, source: str, where: str) -> list[str]:
    """An optional list of strings (``sources``)."""
    value = data.get(key, [])
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise _error(source, where, f"field `{key}`: expected a list of strings, got {value!r}.")
    return value


def _number(value: Any, source: str, where: str, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _error(source, where, f"field `{key}`: expected a finite number, got {value!r}.")
    if isinstance(value, int) and abs(value) > 10**300:  # a TOML integer may exceed every float
        digits = len(str(abs(value)))
        raise _error(
            source, where, f"field `{key}`: expected a magnitude up to 1e300, got a {digits}-digit integer."
        )
    if not math.isfinite(value):
        raise _error(source, where, f"field `{key}`: expected a finite number, got {value!r}.")
    return float(value)


def _coordinate(value: Any, angle: bool, source: str, where: str, key: str) -> float:
    """A pose coordinate of ``[pose]`` or ``[workspace]``: an angle in degrees up to
    :data:`MAX_ANGLE_DEGREES`, a length up to :data:`MAX_COORDINATE` (squares of larger ones
    overflow in the inverse kinematics)."""
    number = _number(value, source, where, key)
    if angle:
        try:
            degrees_to_radians(number)
        except ScrewkitValueError as err:
            raise _error(source, where, f"field `{key}`: {err}") from err
    elif not abs(number) <= MAX_COORDINATE:
        raise _error(
            source, where, f"field `{key}`: expected a length of at most {MAX_COORDINATE:g} in magnitude, "
            f"got {number:g}."
        )
    return number


def _vector(data: Mapping[str, Any], key: str, source: str, where: str, length: int = 3) -> list[float]:
    value = data.get(key)
    if not isinstance(value, list) or len(value) != length:
        raise _error(source, where, f"field `{key}`: expected a list of {length} numbers, got {value!r}.")
    return [_number(v, source, where, key) for v in value]


def _length_unit(header: Mapping[str, Any], source: str) -> str:
    unit = header.get("length_unit")
    if not isinstance(unit, str) or unit not in LENGTH_UNITS:
        raise _error(
            source, "[mechanism]", f"field `length_unit`: expected one of {list(LENGTH_UNITS)}, got {unit!r}."
        )
    return unit


def _parameter_value(
    value: Any, unit: str, kind: str | None, length_unit: str, source: str, where: str
) -> Any:
    """A parameter's value in the file's length unit and radians, its ``unit`` checked against the
    family's kind of the parameter (``"length"``, ``"angle"``, ``"number"``; None: not declared)."""
    units = {"length": tuple(LENGTH_UNITS), "angle": ANGLE_UNITS, "number": NUMBER_UNITS}
    allowed = units[kind] if kind else (*LENGTH_UNITS, *ANGLE_UNITS, *NUMBER_UNITS)
    if unit not in allowed:
        what = f"a {kind}" if kind else "a parameter"
        raise _error(
            source, where, f"field `unit`: expected one of {list(allowed)} for {what}, got {unit!r}."
        )
    if unit in LENGTH_UNITS:
        factor = LENGTH_UNITS[unit] / LENGTH_UNITS[length_unit]
        return _scaled(value, lambda v: float(Fraction(v) * factor), source, where)
    if unit == "deg":
        return _scaled(value, degrees_to_radians, source, where)
    if unit == "rad":
        return _scaled(value, _radians, source, where)
    return value


def _radians(value: float) -> float:
    """An angle given in radians, refused beyond the radian equivalent of :data:`MAX_ANGLE_DEGREES`
    (as ``1e20`` degrees is)."""
    if not abs(value) <= math.radians(MAX_ANGLE_DEGREES):
        raise ScrewkitValueError(
            f"Expected an angle of at most {math.radians(MAX_ANGLE_DEGREES):.6g} radians "
            f"({MAX_ANGLE_DEGREES:g} degrees) in magnitude, got {value:g}."
        )
    return float(value)


def _scaled(value: Any, convert: Callable[[float], float], source: str, where: str, depth: int = 0) -> Any:
    """``convert`` applied to a number or to every number of a (nested) list."""
    if isinstance(value, list):
        if depth >= _MAX_LIST_DEPTH:
            raise _error(
                source, where, f"field `value`: expected lists nested at most {_MAX_LIST_DEPTH} deep."
            )
        return [_scaled(item, convert, source, where, depth + 1) for item in value]
    try:
        result = convert(_number(value, source, where, "value"))
    except ScrewkitValueError as err:
        if isinstance(err, CatalogError):
            raise
        raise _error(source, where, f"field `value`: {err}") from err
    if not abs(result) <= MAX_COORDINATE:
        raise _error(
            source,
            where,
            f"field `value`: expected a magnitude up to {MAX_COORDINATE:g} in the file's unit, "
            f"got {value!r}.",
        )
    return result


def _direction(vector: list[float]) -> list[float]:
    """A direction scaled by a power of two (exactly) so that its largest component lies in [0.5, 1):
    an axis of length 1e-170 or 1e300 is still an axis (its norm would underflow or overflow)."""
    largest = max(abs(v) for v in vector)
    if largest == 0:
        return vector
    exponent = math.frexp(largest)[1]
    return [math.ldexp(v, -exponent) for v in vector]
