"""Parametric mechanism families: the one protocol every family goes through (design.md §1a).

A family is four functions and the names of its pose coordinates:

``parameters(mapping, *, source)``
    The family's validated parameters from a catalog file's ``[parameters]`` mapping.
``inverse_kinematics(parameters, poses, **mode)``
    A configuration over poses ``(..., n)`` (batched; ``mode`` picks a working mode).
``joints(configuration)``
    A :class:`~screwkit.graphs.jointtable.JointTable`: the mechanism's structure once, every joint's screws
    over the batch. Everything else (labels, wrench systems, Jacobians, diagrams, reports) comes
    from the analysis core.
``twist_basis(configuration)``
    The platform's nominal twists ``(..., dof, 6)``, one per pose coordinate (the columns of
    ``A`` in :func:`screwkit.core.jacobians.jacobians_from_wrenches`).

Optionally ``reachable(parameters, poses)``: which poses ``(..., n)`` the inverse kinematics
accepts in every working mode, ``(...,)`` bool, vectorised (without it,
:meth:`screwkit.robots.catalog.Mechanism.reachable` bisects the batch around the refused poses).

Adding a robot: write those four functions, wrap them in a :class:`Family` and :func:`register` it
(``CONTRIBUTING.md`` has a worked example); a catalog mapping or file can then name it.

Examples
--------
>>> sorted(families())
['four_limb', 'mcgill_smg', 'peppermill', 'planar_3rrp']
>>> families()["planar_3rrp"].pose_names
('x', 'y', 'phi')
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator, Mapping, MutableMapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...exceptions import ScrewkitTypeError, ScrewkitValueError
from ...graphs.jointtable import JointTable

__all__ = ["Family", "families", "register"]


@dataclass(frozen=True)
class Family:
    """A mechanism family: the protocol of the module docstring.

    Attributes
    ----------
    name : str
    parameters, inverse_kinematics, joints, twist_basis : callable
    pose_names, angle_names : tuple of str
        The pose coordinates, and which of them are angles (degrees in files and on the command
        line, radians in the API).
    parameter_kinds : mapping of str to str
        ``{parameter: "length" | "angle" | "number"}``: what a catalog file's ``unit`` of that
        parameter may be (:mod:`screwkit.robots.catalog` converts lengths to the file's length unit and
        angles to radians, and refuses a unit of the wrong kind); parameters not named here take
        any known unit.
    reachable : callable or None
        ``reachable(parameters, poses) -> (...,) bool``, the optional vectorised reach test.
    application_points : callable or None
        ``application_points(configuration) -> (..., n, 3)``, the optional hook saying where the
        actuation wrenches act on the actuated links, in the order of the actuated joints
        (:func:`screwkit.robots.transmission.wrench_transmission`'s ``input_points``); None: found
        from the joint axes.

    Examples
    --------
    >>> families()["four_limb"].angle_names
    ('phi',)
    """

    name: str
    parameters: Callable[..., Any]
    inverse_kinematics: Callable[..., Any]
    joints: Callable[[Any], JointTable]
    twist_basis: Callable[[Any], np.ndarray]
    pose_names: tuple[str, ...]
    angle_names: tuple[str, ...]
    parameter_kinds: Mapping[str, str] = field(default_factory=dict)
    reachable: Callable[[Any, np.ndarray], np.ndarray] | None = None
    application_points: Callable[[Any], np.ndarray] | None = None

    def joint_table(self, configuration: Any) -> JointTable:
        """``joints(configuration)``, checked to be a :class:`~screwkit.graphs.jointtable.JointTable`
        (what the analysis core reads; a family's mistake is named here, not inside the core).

        Examples
        --------
        >>> import dataclasses
        >>> broken = dataclasses.replace(families()["four_limb"], joints=lambda configuration: "table")
        >>> broken.joint_table(None)
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitTypeError: Expected the family 'four_limb''s joints(configuration) ...
        """
        table = self.joints(configuration)
        if not isinstance(table, JointTable):
            raise ScrewkitTypeError(
                f"Expected the family {self.name!r}'s joints(configuration) to return a JointTable, "
                f"got {type(table).__name__}."
            )
        return table


_SMG = ("x", "y", "z", "phi")
#: The built-in families: their pose coordinates and angles, known before their modules are imported
#: (the command line's ``map`` options name every family's coordinates).
_BUILT_IN = {
    "four_limb": (_SMG, ("phi",)),
    "mcgill_smg": (_SMG, ("phi",)),
    "peppermill": (_SMG, ("phi",)),
    "planar_3rrp": (("x", "y", "phi"), ("phi",)),
}


def _built_in(name: str) -> Family:
    """A built-in family, its module imported now (``analyze h4`` imports the four-limb one only)."""
    pose_names, angle_names = _BUILT_IN[name]
    if name == "four_limb":
        from . import four_limb

        limb_lengths = ("base_radius", "base_points", "arm_length", "rod_length", "platform_radius",
                        "platform_offset", "lead", "parallelogram_width")
        return Family(
            name,
            four_limb.FourLimbParameters.from_mapping,
            four_limb.inverse_kinematics,
            four_limb.joints,
            four_limb.twist_basis,
            pose_names,
            angle_names,
            dict.fromkeys(limb_lengths, "length")
            | {"alpha": "angle", "beta": "angle", "platform_kind": "number"},
            four_limb.reachable,
            four_limb.application_points,
        )
    if name == "mcgill_smg":
        from . import mcgill_smg

        smg_lengths = ("l0", "l1", "l2", "l3", "radius", "b4", "b5", "proximal_width", "distal_width")
        return Family(
            name,
            mcgill_smg.McGillParameters.from_mapping,
            mcgill_smg.inverse_kinematics,
            mcgill_smg.joints,
            mcgill_smg.twist_basis,
            pose_names,
            angle_names,
            dict.fromkeys(smg_lengths, "length"),
        )
    if name == "peppermill":
        from . import peppermill

        return Family(
            name,
            peppermill.PeppermillParameters.from_mapping,
            peppermill.inverse_kinematics,
            peppermill.joints,
            peppermill.twist_basis,
            pose_names,
            angle_names,
            dict.fromkeys(("r1", "r2", "l1", "l2", "b0", "p1", "p2"), "length"),
        )
    from . import planar_3rrp

    planar_lengths = ("base_points", "link_lengths", "platform_points")
    return Family(
        name,
        planar_3rrp.Planar3RRPParameters.from_mapping,
        planar_3rrp.Planar3RRPConfiguration.from_pose,
        planar_3rrp.joints,
        planar_3rrp.twist_basis,
        pose_names,
        angle_names,
        dict.fromkeys(planar_lengths, "length") | {"guide_angles": "angle"},
    )


class _Registry(MutableMapping[str, Family]):
    """The families by name, in registration order; a built-in one is made (its module imported)
    when it is first looked up."""

    def __init__(self) -> None:
        self._families: dict[str, Family | None] = dict.fromkeys(_BUILT_IN)

    def __getitem__(self, name: str) -> Family:
        family = self._families[name]
        if family is None:
            family = self._families[name] = _built_in(name)
        return family

    def __setitem__(self, name: str, family: Family) -> None:
        self._families[name] = family

    def __delitem__(self, name: str) -> None:
        del self._families[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._families)

    def __len__(self) -> int:
        return len(self._families)

    def pose_names(self) -> list[str]:
        """Every family's pose coordinates, each once, in order (without importing a family).

        Examples
        --------
        >>> families().pose_names()
        ['x', 'y', 'z', 'phi']
        """
        names: list[str] = []
        for name, family in self._families.items():
            found = _BUILT_IN[name][0] if family is None else family.pose_names
            names.extend(n for n in found if n not in names)
        return names


@functools.cache
def families() -> _Registry:
    """The families a catalog entry can name, by name (each imported on first use; :func:`register`
    adds more).

    Examples
    --------
    >>> families()["mcgill_smg"].pose_names
    ('x', 'y', 'z', 'phi')
    """
    return _Registry()


def register(family: Family) -> Family:
    """Add a family to :func:`families`, so that catalog entries can name it (and return it).

    Parameters
    ----------
    family : Family
        Its four functions and pose names; ``name`` must be new.

    Returns
    -------
    Family
        The family itself.

    Raises
    ------
    ScrewkitTypeError
        If ``family`` is not a :class:`Family`, or one of its fields has the wrong type.
    ScrewkitValueError
        If a family of that name is already registered, or an angle is not a pose coordinate.

    Examples
    --------
    >>> register(families()["four_limb"])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected a new family name, got 'four_limb', which is ...
    >>> register({"name": "five_bar"})
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitTypeError: Expected `family` to be a screwkit.robots.families.Family, got
    dict.
    """
    if not isinstance(family, Family):
        raise ScrewkitTypeError(
            f"Expected `family` to be a screwkit.robots.families.Family, got {type(family).__name__}."
        )
    if not isinstance(family.name, str) or not family.name.isidentifier():
        raise ScrewkitTypeError(f"Expected `family.name` to be an identifier, got {family.name!r}.")
    for attribute in ("parameters", "inverse_kinematics", "joints", "twist_basis"):
        if not callable(getattr(family, attribute)):
            got = type(getattr(family, attribute)).__name__
            raise ScrewkitTypeError(f"Expected `family.{attribute}` to be callable, got {got}.")
    for attribute in ("pose_names", "angle_names"):
        names = getattr(family, attribute)
        if not isinstance(names, tuple) or not all(isinstance(n, str) for n in names):
            raise ScrewkitTypeError(f"Expected `family.{attribute}` to be a tuple of str, got {names!r}.")
    if family.reachable is not None and not callable(family.reachable):
        got = type(family.reachable).__name__
        raise ScrewkitTypeError(f"Expected `family.reachable` to be callable or None, got {got}.")
    kinds = family.parameter_kinds
    if not isinstance(kinds, Mapping) or not set(kinds.values()) <= {"length", "angle", "number"}:
        raise ScrewkitTypeError(
            "Expected `family.parameter_kinds` to map parameter names to 'length', 'angle' or 'number', "
            f"got {kinds!r}."
        )
    if not family.pose_names or not set(family.angle_names) <= set(family.pose_names):
        raise ScrewkitValueError(
            f"Expected `family.angle_names` to be some of the pose coordinates {family.pose_names}, "
            f"got {family.angle_names}."
        )
    known = families()
    if family.name in known:
        raise ScrewkitValueError(
            f"Expected a new family name, got {family.name!r}, which is already registered "
            f"({', '.join(sorted(known))})."
        )
    known[family.name] = family
    return family
