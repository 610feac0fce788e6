"""The four-limb family's parameters: Table 3 of paper 004 as a validated dataclass.

:class:`FourLimbParameters` holds one robot's geometry (base, arms, parallelograms, platform kind of
Table 1) and checks its types, presence rules and ranges; :meth:`FourLimbParameters.from_mapping`
reads it from a catalog file's ``[parameters]`` (the model: :mod:`screwkit.robots.families.four_limb`).

Examples
--------
>>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375.0,
...     rod_length=800.0, alpha=0.0, beta=3.14159, platform_radius=80.0, platform_offset=70.0,
...     base_radius=275.0)
>>> h4.subplatform_limbs
((0, 3), (1, 2))
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from ....exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError

__all__ = ["DEFAULT_PARALLELOGRAM_WIDTH_MM", "PLATFORM_KINDS", "FourLimbParameters", "is_real"]


#: The platform variants of Table 1 (paper 004).
PLATFORM_KINDS = ("articulated_z", "articulated_y", "screw_pair")

#: Default spacing of the two rods of a parallelogram when ``length_unit == "mm"``. Paper 004 does
#: not give it and the kinematics do not depend on it; 100 mm is our choice.
DEFAULT_PARALLELOGRAM_WIDTH_MM = 100.0


#: Limbs (0-based) on sub-platforms I and II, derived from Table 1 (module docstring).
_SUBPLATFORMS = {
    "articulated_z": ((0, 3), (1, 2)),
    "articulated_y": ((0, 3), (1, 2)),
    "screw_pair": ((0, 2), (1, 3)),
}


_REQUIRED = ("name", "platform_kind", "arm_length", "rod_length", "alpha", "beta", "platform_radius")
_POSITIVE_LENGTHS = (
    "arm_length",
    "rod_length",
    "platform_radius",
    "platform_offset",
    "lead",
    "base_radius",
    "parallelogram_width",
)


def is_real(value: Any) -> bool:
    """Whether a value is a real number (an int or a float, numpy's included; a bool is not).

    Parameters
    ----------
    value : object
        Any value read from a file or passed by a caller.

    Returns
    -------
    bool
        True for a real number.

    Examples
    --------
    >>> is_real(2), is_real(np.float64(0.5)), is_real(True), is_real("1")
    (True, True, False, False)
    """
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_
    )


def _normalised_fields(
    values: Mapping[str, Any],
    source: str,
    structure_error: type[Exception],
    type_error: type[Exception],
) -> dict[str, Any]:
    """Check types, presence rules and ranges; return the fields with floats and tuples."""
    out = dict(values)
    for key in ("name", "platform_kind", "length_unit"):
        if not isinstance(out.get(key), str) or not out[key].strip():
            raise type_error(
                f"{source}: expected field `{key}` to be a non-empty string, got {out.get(key)!r}."
            )
    for key in (*_POSITIVE_LENGTHS, "alpha", "beta", "axis_inclination"):
        value = out.get(key)
        if value is None:
            continue
        if not is_real(value):
            raise type_error(
                f"{source}: expected field `{key}` to be a real number, got "
                f"{type(value).__name__} {value!r}."
            )
        if not math.isfinite(value):
            raise ScrewkitValueError(
                f"{source}: expected field `{key}` to be finite, got {value!r}."
            )
        out[key] = float(value)
        if key in _POSITIVE_LENGTHS and value <= 0:
            raise ScrewkitValueError(
                f"{source}: expected field `{key}` (a length) to be > 0, got {value!r}."
            )
    kind = out["platform_kind"]
    if kind not in PLATFORM_KINDS:
        raise ScrewkitValueError(
            f"{source}: expected field `platform_kind` to be one of {PLATFORM_KINDS}, got {kind!r}."
        )
    needed, unused = ("lead", "platform_offset") if kind == "screw_pair" else ("platform_offset",
                                                                              "lead")
    if out.get(needed) is None:
        raise structure_error(f"{source}: field `{needed}` is required when platform_kind={kind!r}.")
    if out.get(unused) is not None:
        raise structure_error(
            f"{source}: field `{unused}` does not apply when platform_kind={kind!r}; remove it."
        )
    if (out.get("base_radius") is None) == (out.get("base_points") is None):
        raise structure_error(
            f"{source}: give exactly one of `base_radius` (Eq. 1 layout) and `base_points` "
            f"(explicit A_i), got base_radius={out.get('base_radius')!r}, "
            f"base_points={out.get('base_points')!r}."
        )
    if out.get("base_points") is not None:
        out["base_points"] = _base_points(out["base_points"], source, type_error)
    if out.get("parallelogram_width") is None:
        if out["length_unit"] != "mm":
            raise structure_error(
                f"{source}: field `parallelogram_width` has no default for length_unit="
                f"{out['length_unit']!r} (the default {DEFAULT_PARALLELOGRAM_WIDTH_MM} is in mm); "
                "give it explicitly."
            )
        out["parallelogram_width"] = DEFAULT_PARALLELOGRAM_WIDTH_MM
    return out


def _base_points(
    value: Any, source: str, type_error: type[Exception]
) -> tuple[tuple[float, float, float], ...]:
    rows = value if isinstance(value, Sequence) and not isinstance(value, str) else None
    if (
        rows is None
        or len(rows) != 4
        or not all(
            isinstance(row, Sequence) and not isinstance(row, str) and len(row) == 3
            and all(is_real(x) for x in row)
            for row in rows
        )
    ):
        raise type_error(
            f"{source}: expected field `base_points` to be 4 points of 3 real numbers, got {value!r}."
        )
    points = tuple((float(p[0]), float(p[1]), float(p[2])) for p in rows)
    if not all(math.isfinite(x) for p in points for x in p):
        raise ScrewkitValueError(f"{source}: expected field `base_points` to be finite, got {value!r}.")
    return points


@dataclass(frozen=True, slots=True)
class FourLimbParameters:
    """Geometry of one four-limb Schönflies-motion generator (paper 004, Tables 1 and 3, Eq. 1).

    All lengths are in ``length_unit``; angles in radians.

    Parameters
    ----------
    name : str
        Robot name, e.g. ``"H4"``.
    platform_kind : {"articulated_z", "articulated_y", "screw_pair"}
        Table 1 row: Quattro/H4, V4, Veloce (and Ragnar).
    arm_length : float
        ``b``, length of the actuated arm ``A_i B_i``.
    rod_length : float
        ``l``, length of the parallelogram ``B_i C_i``.
    alpha, beta : float
        ``α``, ``β`` of Table 3: ``α_1 = -α_2 = α``, ``α_3 = -α_4 = β``, ``u_i = R_z(α_i) i``.
    axis_inclination : float, optional
        ``ε``: the actuated axes leave the base plane, ``u_i = R_z(α_i) R_y(ε_i) i`` with
        ``ε_1 = -ε_2 = ε_3 = -ε_4 = ε`` (module docstring, item 6). Default 0 (Table 3's robots).
    platform_radius : float
        ``r`` of Table 3.
    platform_offset : float, optional
        ``c`` of Table 3; required for the articulated platforms, refused for the screw pair.
    lead : float, optional
        ``h``, lead of the screw pair (length per turn); required for ``"screw_pair"`` only.
    base_radius : float, optional
        ``R`` of Eq. (1); give this or ``base_points``.
    base_points : tuple of 4 (x, y, z), optional
        Explicit ``a_i`` (Ragnar, text after Table 4).
    parallelogram_width : float, optional
        Spacing of the two rods of each parallelogram (not in paper 004, no effect on kinematics).
        Defaults to :data:`DEFAULT_PARALLELOGRAM_WIDTH_MM` when ``length_unit == "mm"``; required
        otherwise.
    length_unit : str
        Unit of every length and of poses (default ``"mm"``, the paper's unit).

    Raises
    ------
    ScrewkitTypeError
        A field has the wrong type.
    ScrewkitValueError
        A length is not positive, a kind is unknown, or a field is missing or does not apply.

    Examples
    --------
    >>> p = FourLimbParameters(name="Veloce", platform_kind="screw_pair", arm_length=375,
    ...     rod_length=800, alpha=-np.pi / 4, beta=3 * np.pi / 4, platform_radius=100, lead=20,
    ...     base_radius=275)
    >>> p.parallelogram_width, p.subplatform_limbs
    (100.0, ((0, 2), (1, 3)))
    """

    name: str
    platform_kind: str
    arm_length: float
    rod_length: float
    alpha: float
    beta: float
    platform_radius: float
    platform_offset: float | None = None
    lead: float | None = None
    base_radius: float | None = None
    base_points: tuple[tuple[float, float, float], ...] | None = None
    parallelogram_width: float | None = None
    length_unit: str = "mm"
    axis_inclination: float = 0.0

    def __post_init__(self) -> None:
        values = {f.name: getattr(self, f.name) for f in fields(self)}
        checked = _normalised_fields(
            values, "FourLimbParameters", ScrewkitValueError, ScrewkitTypeError
        )
        for key, value in checked.items():
            object.__setattr__(self, key, value)

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> FourLimbParameters:
        """Build parameters from a mapping (e.g. a TOML table), naming ``source`` in every error.

        Keys are the field names of this class; ``alpha`` and ``beta`` are in radians.

        Parameters
        ----------
        mapping : mapping
            The ``[parameters]`` values (and the metadata ``name``, ``length_unit``).
        source : str, optional
            Where the mapping comes from, named in every error.

        Returns
        -------
        FourLimbParameters
            The validated parameters.

        Raises
        ------
        CatalogError
            Unknown, missing or wrongly typed fields.
        ScrewkitValueError
            Values out of range (e.g. a negative length, an unknown ``platform_kind``).

        Examples
        --------
        >>> FourLimbParameters.from_mapping({"name": "H4"}, source="h4.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: h4.toml: missing field(s) ['alpha', 'arm_length', ...
        """
        if not isinstance(mapping, Mapping):
            raise CatalogError(f"{source}: expected a mapping of parameters, got "
                               f"{type(mapping).__name__}.")
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(mapping) - known)
        if unknown:
            raise CatalogError(
                f"{source}: unknown field(s) {unknown}; expected a subset of {sorted(known)}."
            )
        missing = sorted(set(_REQUIRED) - set(mapping))
        if missing:
            raise CatalogError(f"{source}: missing field(s) {missing}.")
        values = {f.name: f.default for f in fields(cls)} | dict(mapping)
        checked = _normalised_fields(values, source, CatalogError, CatalogError)
        return cls(**checked)

    @property
    def subplatform_limbs(self) -> tuple[tuple[int, int], tuple[int, int]]:
        """0-based limb indices carried by sub-platforms I and II (derived from Table 1)."""
        return _SUBPLATFORMS[self.platform_kind]

    @property
    def limb_alphas(self) -> np.ndarray:
        """``α_i = (α, -α, β, -β)`` (Sec. 2), shape (4,)."""
        return np.array([self.alpha, -self.alpha, self.beta, -self.beta])

    @property
    def limb_inclinations(self) -> np.ndarray:
        """``ε_i = (ε, -ε, ε, -ε)`` (module docstring, item 6), shape (4,)."""
        return self.axis_inclination * np.array([1.0, -1.0, 1.0, -1.0])
