"""The planar 3-RRP's parameters (paper 003's geometry; our example dimensions) and the planar
vector helpers its modules share.

:class:`Planar3RRPParameters` holds the base joints, first-link lengths, platform points and guide
angles of the three limbs and checks them; :meth:`Planar3RRPParameters.from_mapping` reads them from a
catalog file's ``[parameters]`` (the model: :mod:`screwkit.robots.families.planar_3rrp`).

Examples
--------
>>> EXAMPLE_PARAMETERS.link_lengths
array([0.9, 0.9, 0.9])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ....algebra.backend import DEFAULT_RTOL, as_array
from ....exceptions import (
    CatalogError,
    ScrewkitValueError,
)

__all__ = ["EXAMPLE_PARAMETERS", "Planar3RRPParameters"]


_FIELDS = ("base_points", "link_lengths", "platform_points", "guide_angles")
#: Metadata keys a catalog entry passes along with the geometry (checked, not stored).
_METADATA = ("name", "length_unit")
_FIELD_SHAPES = {
    "base_points": (3, 2),
    "link_lengths": (3,),
    "platform_points": (3, 2),
    "guide_angles": (3,),
}


def _perp(v: np.ndarray) -> np.ndarray:
    """``E v`` of Eq. (6): rotate planar vectors ``(..., 2)`` by +90°."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a * b).sum(axis=-1)


def _unit(angle: np.ndarray) -> np.ndarray:
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def _readonly(array: np.ndarray) -> np.ndarray:
    array = np.array(array)
    array.flags.writeable = False
    return array


def _first_index(mask: np.ndarray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(mask)[0])


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False, slots=True)
class Planar3RRPParameters:
    """Geometry of a planar 3-RRP manipulator (paper 003, Fig. 1a).

    Parameters
    ----------
    base_points : array_like, shape (3, 2)
        Actuated joint centres ``M_k = C_1i`` in the base frame.
    link_lengths : array_like, shape (3,)
        Lengths ``l_k = |A_k - M_k|`` of the first links, > 0.
    platform_points : array_like, shape (3, 2)
        A point ``P_k`` of each guide line, in the platform frame (origin = reference point ``C``).
    guide_angles : array_like, shape (3,)
        Directions ``β_k`` of the guides in the platform frame, radians.

    Raises
    ------
    ScrewkitValueError
        If a field has the wrong shape or non-finite values, a link length is not positive, or the
        three guides are parallel (``|sin(β_k - β_1)| <= DEFAULT_RTOL`` for ``k = 2, 3``): such a
        manipulator translates freely along the guides at every pose (paper 003, Sec. 4.2).

    Examples
    --------
    >>> p = Planar3RRPParameters([[0, 0], [1, 0], [0, 1]], [0.5, 0.5, 0.5],
    ...     [[0, 0], [0.1, 0], [0, 0.1]], [0.0, 1.0, 2.0])
    >>> p.length_scale
    0.5
    """

    base_points: np.ndarray
    link_lengths: np.ndarray
    platform_points: np.ndarray
    guide_angles: np.ndarray

    def __post_init__(self) -> None:
        for name in _FIELDS:
            shape = _FIELD_SHAPES[name]
            value = as_array(getattr(self, name), name, shape)
            if value.shape != shape:
                raise ScrewkitValueError(
                    f"Expected `{name}` to have shape {shape}, got {value.shape}."
                )
            object.__setattr__(self, name, _readonly(value))
        if np.any(self.link_lengths <= 0):
            raise ScrewkitValueError(
                f"Expected `link_lengths` to be > 0, got {self.link_lengths.tolist()}."
            )
        spread = np.abs(np.sin(self.guide_angles[1:] - self.guide_angles[0]))
        if np.all(spread <= DEFAULT_RTOL):
            raise ScrewkitValueError(
                "Expected `guide_angles` not all parallel (mod π), got "
                f"{self.guide_angles.tolist()}: the platform would translate freely along the "
                "guides at every pose (paper 003, Sec. 4.2)."
            )

    @property
    def length_scale(self) -> float:
        """Characteristic length: the longest first link, ``max l_k`` (scales tolerances)."""
        return float(self.link_lengths.max())

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> Planar3RRPParameters:
        """Build parameters from a mapping such as a parsed TOML table.

        Parameters
        ----------
        mapping : Mapping
            Exactly the fields ``base_points`` (3 pairs), ``link_lengths`` (3 numbers),
            ``platform_points`` (3 pairs), ``guide_angles`` (3 numbers, radians); optionally the
            metadata ``name`` and ``length_unit`` (non-empty strings, which
            :func:`screwkit.robots.catalog.load_mechanism` passes to every family; not stored here, the
            catalog's :class:`~screwkit.robots.mechanism.Mechanism` keeps them).
        source : str
            Where the mapping comes from (a file name), quoted in error messages.

        Returns
        -------
        Planar3RRPParameters
            The validated parameters.

        Raises
        ------
        CatalogError
            If ``mapping`` is not a mapping, or a field is missing, unknown, not a (nested) list
            of real numbers, or of the wrong length, or a metadata field is not a non-empty string.
        ScrewkitValueError
            If a value is out of range (see the class); the message starts with ``source``.

        Examples
        --------
        >>> p = Planar3RRPParameters.from_mapping({"base_points": [[0, 0], [1, 0], [0, 1]],
        ...     "link_lengths": [0.5, 0.5, 0.5], "platform_points": [[0, 0], [0, 0], [0, 0]],
        ...     "guide_angles": [0, 1, 2]}, source="demo.toml")
        >>> p.link_lengths
        array([0.5, 0.5, 0.5])
        >>> Planar3RRPParameters.from_mapping({"link_lengths": [1, 1, 1]}, source="demo.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: demo.toml: missing field `base_points` ...
        """
        if not isinstance(mapping, Mapping):
            raise CatalogError(
                f"{source}: expected a mapping of the fields {list(_FIELDS)}, "
                f"got {type(mapping).__name__}."
            )
        for name in mapping:
            if name in _METADATA:
                if not isinstance(mapping[name], str) or not mapping[name].strip():
                    raise CatalogError(
                        f"{source}: field `{name}` must be a non-empty string, got {mapping[name]!r}."
                    )
            elif name not in _FIELDS:
                raise CatalogError(
                    f"{source}: unknown field `{name}`; expected only {list(_FIELDS)}."
                )
        values = {}
        for name in _FIELDS:
            if name not in mapping:
                raise CatalogError(
                    f"{source}: missing field `{name}` (expected shape {_FIELD_SHAPES[name]})."
                )
            values[name] = _catalog_field(mapping[name], name, _FIELD_SHAPES[name], source)
        try:
            return cls(**values)
        except ScrewkitValueError as err:
            raise ScrewkitValueError(f"{source}: {err}") from err


def _catalog_field(value: Any, name: str, shape: tuple[int, ...], source: str) -> np.ndarray:
    """Check that a catalog value is a nested list of real numbers of the given shape."""

    def fail(got: str) -> CatalogError:
        what = "a list of 3 numbers" if len(shape) == 1 else "a list of 3 [x, y] pairs"
        return CatalogError(f"{source}: field `{name}` must be {what}, got {got}.")

    def check(item: Any, depth: int) -> None:
        if depth == len(shape):
            if isinstance(item, bool) or not isinstance(item, int | float):
                raise fail(f"{type(item).__name__} {item!r} inside {value!r}")
            return
        if not isinstance(item, list | tuple) or len(item) != shape[depth]:
            raise fail(repr(item))
        for sub in item:
            check(sub, depth + 1)

    check(value, 0)
    return np.array(value, dtype=float)


#: Example dimensions (our choice; paper 003 gives none): base joints on a circle of radius 1 at
#: 210°, 330°, 90°; first links 0.9; guides tangent to a circle of radius 0.25 of the platform, the
#: guide of limb ``k`` through ``0.25 u(α_k)`` with direction ``β_k = α_k + 90°``. At the home pose
#: ``(0, 0, 0)`` every limb has ``J_kk = ±sqrt(0.9² - 0.75²) ≈ ±0.4975``.
EXAMPLE_PARAMETERS = Planar3RRPParameters(
    base_points=_unit(np.radians([210.0, 330.0, 90.0])),
    link_lengths=np.full(3, 0.9),
    platform_points=0.25 * _unit(np.radians([210.0, 330.0, 90.0])),
    guide_angles=np.radians([300.0, 60.0, 180.0]),
)
