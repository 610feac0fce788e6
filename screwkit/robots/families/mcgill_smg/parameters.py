"""The McGill SMG's parameters (Table 1 of paper 001 and our choices) and working modes.

:class:`McGillParameters` holds the lengths of the two legs and the plate and checks them;
:meth:`McGillParameters.from_mapping` reads them from a catalog file's ``[parameters]`` (the model:
:mod:`screwkit.robots.families.mcgill_smg`).

Examples
--------
>>> smg = McGillParameters(l0=600.0, l1=100.0, l2=600.0, l3=282.843, radius=200.0, b4=-50.0,
...     b5=-50.0, proximal_width=80.0, distal_width=60.0)
>>> smg.scaled(0.001).l2, len(WORKING_MODES), DEFAULT_MODE
(0.6, 16, (1, 1, -1, -1))
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ....exceptions import ScrewkitValueError
from ...two_limb import (
    check_parameters,
    parameters_from_mapping,
)

__all__ = ["DEFAULT_MODE", "LEGS", "WORKING_MODES", "McGillParameters"]


#: Leg names, in the order of every leg axis of this module.
LEGS = ("I", "II")
#: The 16 working modes ``(pan_I, elbow_I, pan_II, elbow_II)`` (module docstring).
WORKING_MODES: tuple[tuple[int, ...], ...] = tuple(itertools.product((1, -1), repeat=4))
#: Mirror-symmetric legs, elbows away from each other (module docstring).
DEFAULT_MODE = (1, 1, -1, -1)


@dataclass(frozen=True, slots=True)
class McGillParameters:
    """Dimensions of a McGill SMG (Table 1 of paper 001; lengths in one unit of your choice).

    Parameters
    ----------
    l0 : float
        Distance between the two pan axes (Table 1), >= 0. Not given by the paper.
    l1 : float
        ``‖a_J1‖``, horizontal offset of the tilt axis from the pan axis (Eqs. 1-2), >= 0.
        Not given by the paper.
    l2, l3 : float
        Lengths of the proximal and distal parallelograms, > 0. Sec. 6: ``l2 = 600 mm``,
        ``l3 = √2 R = 282.843 mm``.
    radius : float
        ``R`` of Table 1, half the length of the moving bar, > 0. Sec. 6: 200 mm.
    b4, b5 : float
        Vertical projections of ``a_J4 = O_J3→O_J4`` and ``a_J5 = O_J4→P`` (Table 1), signed.
        Not given by the paper; only ``b4 + b5`` enters the kinematics.
    proximal_width, distal_width : float
        Short (vertical) sides of the two parallelograms, > 0. Our choice; only the joint axes of
        :func:`~screwkit.robots.families.mcgill_smg.joints.joints` depend on them.

    Examples
    --------
    >>> p = McGillParameters.from_mapping({"l0": 600, "l1": 100, "l2": 600, "l3": 282.843,
    ...     "radius": 200, "b4": -50, "b5": -50, "proximal_width": 80, "distal_width": 60})
    >>> p.l2, p.radius
    (600.0, 200.0)
    >>> McGillParameters(600, 100, 600, 282.843, -200, 0, 0, 80, 60)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected parameter `radius` of ... > 0, got -200.
    """

    l0: float
    l1: float
    l2: float
    l3: float
    radius: float
    b4: float
    b5: float
    proximal_width: float
    distal_width: float

    def __post_init__(self) -> None:
        check_parameters(
            self,
            positive=("l2", "l3", "radius", "proximal_width", "distal_width"),
            nonnegative=("l0", "l1"),
            real=("b4", "b5"),
        )

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> McGillParameters:
        """Build parameters from a mapping (e.g. a TOML table), naming ``source`` in every error.

        Parameters
        ----------
        mapping : mapping
            The ``[parameters]`` values (and the metadata ``name``, ``length_unit``).
        source : str, optional
            Where the mapping comes from, named in every error.

        Returns
        -------
        McGillParameters
            The validated parameters.

        Raises
        ------
        CatalogError
            Unknown, missing or non-numeric fields.
        ScrewkitValueError
            Values out of range.

        Examples
        --------
        >>> McGillParameters.from_mapping({"l0": 600}, source="mcgill.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: mcgill.toml: missing field(s) ['l1', 'l2', ...
        """
        return parameters_from_mapping(cls, mapping, source)

    def scaled(self, factor: float) -> McGillParameters:
        """The same robot in another unit of length (every length times ``factor`` > 0).

        Parameters
        ----------
        factor : float
            The ratio of the new unit of length to the old (> 0).

        Returns
        -------
        McGillParameters
            The scaled parameters.

        Examples
        --------
        >>> McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60).scaled(1e-3).l2
        0.6
        """
        if not (isinstance(factor, int | float) and factor > 0):
            raise ScrewkitValueError(f"Expected `factor` to be a number > 0, got {factor!r}.")
        return McGillParameters(
            *(getattr(self, name) * factor for name in self.__dataclass_fields__)
        )
