"""The mechanism catalog: catalog entries (a robot of a family in :mod:`screwkit.robots.families`, its
parameters, default pose, workspace and published facts), read from the TOML files shipped in the
top-level ``mechanisms/`` folder or from a mapping into a :class:`~screwkit.robots.mechanism.Mechanism`.

**Catalog entries** (``kind = "family"``, shipped in the top-level ``mechanisms/`` folder): a robot of a
parametric family in :mod:`screwkit.robots.families`::

    [mechanism]
    kind = "family"
    name = "H4"
    family = "four_limb"
    length_unit = "mm"
    sources = ["paper 004 ...", "paper 002 ..."]

    [parameters.rod_length]          # one table per parameter
    value = 800.0
    unit = "mm"
    source = "paper 004, §5"

    [pose]                           # the default pose: lengths in length_unit, angle in degrees
    x = 0.0
    y = 0.0
    z = -750.0
    phi_deg = 0.0

    [workspace]                      # the operational workspace, [low, high] per coordinate,
                                     # reachable_fraction = 0.79 if only part of the box is reachable
    x = [-350.0, 350.0]
    ...

    [[expected]]                     # published facts, checked by tests/robots/test_catalog.py
    fact = "platform_twist_order"
    value = 4
    source = "paper 002, §4.2"

The files' reading, units and field checks: :mod:`screwkit.robots.toml_fields`; snapshot files (any
mechanism at one configuration): :mod:`screwkit.robots.snapshot`.

Examples
--------
>>> h4 = load_mechanism("h4")
>>> h4.name, h4.family, h4.length_unit
('H4', 'four_limb', 'mm')
>>> "h4" in list_mechanisms()
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..exceptions import (
    CatalogError,
    ScrewkitError,
    ScrewkitTypeError,
)
from .families import families
from .toml_fields import (
    _check_keys,
    _coordinate,
    _error,
    _length_unit,
    _name,
    _number,
    _parameter_value,
    _string,
    _strings,
    _table,
    _vector,
    file_kind,
    load_toml,
)

if TYPE_CHECKING:
    pass
from .mechanism import Mechanism

__all__ = ["list_mechanisms", "load_mechanism", "mechanism_from_mapping", "unknown_mechanism"]


def _package_file(name: str) -> Path:
    return Path(str(resources.files("screwkit.mechanisms").joinpath(f"{name}.toml")))


def list_mechanisms() -> list[str]:
    """Names of the catalog entries shipped with the package.

    Returns
    -------
    list of str
        The names, sorted.

    Examples
    --------
    >>> "h4" in list_mechanisms()
    True
    """
    folder = resources.files("screwkit.mechanisms")
    return sorted(p.name[: -len(".toml")] for p in folder.iterdir() if p.name.endswith(".toml"))


def load_mechanism(name_or_path: str | Path) -> Mechanism:
    """Load a catalog entry by name (``"h4"``) or from a ``.toml`` path.

    Parameters
    ----------
    name_or_path : str or pathlib.Path
        A catalog name (case-insensitive) or the path of a catalog file.

    Returns
    -------
    Mechanism
        The catalog entry.

    Raises
    ------
    CatalogError
        For an unknown name, an unreadable file, or a malformed entry (naming file and field).

    Examples
    --------
    >>> load_mechanism("h5")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: unknown mechanism 'h5': expected one of [...] or a path to a .toml file.
    """
    if not isinstance(name_or_path, str | Path):
        raise ScrewkitTypeError(
            "Expected a catalog name or a .toml path (str or pathlib.Path), got "
            f"{type(name_or_path).__name__}."
        )
    text = str(name_or_path)
    if text.endswith(".toml"):
        path = Path(text)
    elif text.lower() in list_mechanisms():
        path = _package_file(text.lower())
    else:
        raise CatalogError(unknown_mechanism(text))
    return mechanism_from_mapping(load_toml(path), source=str(path))


def unknown_mechanism(name: str) -> str:
    """The message for a name that is neither a catalog entry nor a ``.toml`` path, with the closest
    entry when there is one.

    Parameters
    ----------
    name : str
        The name given.

    Returns
    -------
    str
        The error message (the catalog's names, and the closest one).

    Examples
    --------
    >>> unknown_mechanism("quatro")  # doctest: +ELLIPSIS
    "unknown mechanism 'quatro' (did you mean 'quattro'?): expected one of [...] or a path to a .toml file."
    """
    import difflib

    close = difflib.get_close_matches(name.lower(), list_mechanisms(), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    return f"unknown mechanism {name!r}{hint}: expected one of {list_mechanisms()} or a path to a .toml file."


def mechanism_from_mapping(data: Mapping[str, Any], *, source: str = "<mapping>") -> Mechanism:
    """Build a :class:`Mechanism` from parsed catalog TOML (see the module docstring).

    Parameters
    ----------
    data : mapping
        A parsed catalog file (``[mechanism]``, ``[parameters]``, ``[pose]``, ``[workspace]``,
        ``[[expected]]``).
    source : str, optional
        Where the data come from, named in every error.

    Returns
    -------
    Mechanism
        The catalog entry; its family is looked up in :func:`screwkit.robots.families.families`.

    Examples
    --------
    >>> mechanism_from_mapping({"mechanism": {"kind": "family", "name": "X", "family": "nope"}})
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: <mapping>: [mechanism]: field `family`: expected one of ...
    """
    if not isinstance(data, Mapping):
        raise CatalogError(f"{source}: expected a mapping of TOML tables, got {type(data).__name__}.")
    kind = file_kind(data)  # first: a file of another kind fails on its kind, not on a field it has
    if kind == "snapshot":
        message = "expected 'family' here, got 'snapshot'; a snapshot file loads with load_snapshot"
        raise _error(source, "[mechanism]", f"field `kind`: {message}.")
    if kind not in ("family", None):
        expected = "'family' (a catalog entry) or 'snapshot' (a snapshot file)"
        raise _error(source, "[mechanism]", f"field `kind`: expected {expected}, got {kind!r}.")
    _check_keys(data, ("mechanism", "parameters", "pose", "workspace", "expected"), source, "top level")
    header = _table(data, "mechanism", source)
    _check_keys(
        header, ("kind", "name", "family", "length_unit", "sources", "description"), source, "[mechanism]"
    )
    name = _name(header, "name", source, "[mechanism]")
    family_name = _string(header, "family", source, "[mechanism]")
    known = families()
    if family_name not in known:
        raise _error(
            source, "[mechanism]", f"field `family`: expected one of {sorted(known)}, got {family_name!r}."
        )
    family = known[family_name]
    length_unit = _length_unit(header, source)
    if "description" in header:
        _string(header, "description", source, "[mechanism]")
    sources = _strings(header, "sources", source, "[mechanism]")
    raw_parameters = _table(data, "parameters", source)
    values: dict[str, Any] = {"name": name, "length_unit": length_unit}
    documented: dict[str, dict[str, Any]] = {}
    for key, entry in raw_parameters.items():
        where = f"[parameters.{key}]"
        if not isinstance(entry, dict) or "value" not in entry:
            raise _error(source, where, f"expected a table with `value`, `unit` and `source`, got {entry!r}.")
        _check_keys(entry, ("value", "unit", "source", "note"), source, where)
        for required in ("unit", "source"):
            _string(entry, required, source, where)
        if "note" in entry:
            _string(entry, "note", source, where)
        values[key] = _parameter_value(
            entry["value"], entry["unit"], family.parameter_kinds.get(key), length_unit, source, where
        )
        documented[key] = dict(entry)
    try:
        parameters = family.parameters(values, source=f"{source}: [parameters]")
    except CatalogError:
        raise
    except KeyError as err:  # a family that reads a field without checking it is there
        if not err.args or err.args[0] in values:
            raise
        raise CatalogError(
            f"{source}: [parameters]: missing field `{err.args[0]}` (read by the family {family.name!r})."
        ) from err
    except ScrewkitError as err:
        text = str(err)  # a family's message may already name the file and table
        prefix = f"{source}: [parameters]"
        raise CatalogError(text if text.startswith(prefix) else f"{prefix}: {text}") from err
    keys = [f"{c}_deg" if c in family.angle_names else c for c in family.pose_names]
    pose_table = _table(data, "pose", source)
    _check_keys(pose_table, keys, source, "[pose]")
    pose = []
    for coordinate, key in zip(family.pose_names, keys, strict=True):
        if key not in pose_table:
            raise _error(source, "[pose]", f"field `{key}`: missing.")
        number = _coordinate(pose_table[key], coordinate in family.angle_names, source, "[pose]", key)
        pose.append(math.radians(number) if coordinate in family.angle_names else number)
    workspace_table = _table(data, "workspace", source)
    _check_keys(workspace_table, [*keys, "reachable_fraction"], source, "[workspace]")
    workspace = {}
    for coordinate, key in zip(family.pose_names, keys, strict=True):
        angle = coordinate in family.angle_names
        low, high = _vector(workspace_table, key, source, "[workspace]", length=2)
        low, high = (_coordinate(v, angle, source, "[workspace]", key) for v in (low, high))
        if not low < high:
            raise _error(source, "[workspace]", f"field `{key}`: expected low < high, got [{low}, {high}].")
        convert = math.radians if angle else float
        workspace[coordinate] = (convert(low), convert(high))
    fraction = _number(
        workspace_table.get("reachable_fraction", 1.0), source, "[workspace]", "reachable_fraction"
    )
    if not 0.0 < fraction <= 1.0:
        raise _error(
            source, "[workspace]", f"field `reachable_fraction`: expected a number in (0, 1], got {fraction}."
        )
    expected = data.get("expected", [])
    if not isinstance(expected, list) or not all(isinstance(e, dict) for e in expected):
        raise _error(source, "[[expected]]", f"expected an array of tables, got {type(expected).__name__}.")
    for index, fact in enumerate(expected):
        where = f"[[expected]] #{index + 1}"
        fields = ("fact", "value", "source", "note", "tolerance", "region", "not_reproduced")
        _check_keys(fact, fields, source, where)
        _string(fact, "fact", source, where)
        _string(fact, "source", source, where)
        if "value" not in fact:
            raise _error(source, where, "field `value`: missing.")
        for key in ("note", "region"):
            if key in fact:
                _string(fact, key, source, where)
        if "tolerance" in fact and not _number(fact["tolerance"], source, where, "tolerance") >= 0:
            raise _error(
                source, where, f"field `tolerance`: expected a number >= 0, got {fact['tolerance']!r}."
            )
        if "not_reproduced" in fact and not isinstance(fact["not_reproduced"], dict):
            raise _error(
                source, where, f"field `not_reproduced`: expected a table, got {fact['not_reproduced']!r}."
            )
    return Mechanism(
        name=name,
        family=family_name,
        length_unit=length_unit,
        source=source,
        sources=tuple(sources),
        parameters=parameters,
        parameter_sources=documented,
        default_pose=np.array(pose),
        workspace=workspace,
        expected=tuple(expected),
        reachable_fraction=fraction,
    )
