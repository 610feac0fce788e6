"""Parametric mechanism families: the one protocol every family goes through, and the registry.

A family is four functions and the names of its pose coordinates, generic over its parameter type
``P`` and its configuration type ``C``:

``parameters(mapping, *, source) -> P``
    The family's validated parameters from a catalog file's ``[parameters]`` mapping.
``inverse_kinematics(parameters, poses, **mode) -> C``
    A configuration over poses ``(..., n)`` (batched; ``mode`` picks a working mode).
``joints(configuration) -> JointTable``
    A :class:`~screwkit.graphs.jointtable.JointTable`: the mechanism's structure once, every joint's screws
    over the batch. Everything else (labels, wrench systems, Jacobians, diagrams, reports) comes
    from the analysis core.
``twist_basis(configuration) -> ndarray``
    The platform's nominal twists ``(..., dof, 6)``, one per pose coordinate (the columns of
    ``A`` in :func:`screwkit.core.jacobians.jacobians_from_wrenches`).

Optional knowledge of a family (each a field of :class:`Family`, None or empty when absent; the
page ``docs/families.md`` describes each):

``reachable(parameters, poses)``
    Which poses ``(..., n)`` the inverse kinematics accepts in every working mode, ``(...,)`` bool,
    vectorised (without it, :meth:`screwkit.robots.mechanism.Mechanism.reachable` bisects the batch
    around the refused poses).
``application_points(configuration)``
    Where the actuation wrenches act on the actuated links ``(..., k, 3)``.
``actuated_values(configuration)``
    The actuated joints' values ``(..., k)`` (radians, lengths), in the order of the joint table's
    actuated joints: what :func:`screwkit.testing.check_family` differentiates to check ``B⁻¹A``.
``working_modes``
    A :class:`WorkingModes`: the inverse kinematics' keyword that picks a working mode, its default
    and accepted values, what it means, and optionally how to read it back from a configuration.
``map_axes``
    The two pose coordinates a map spans by default (:func:`screwkit.analysis.workspace.grid_map`);
    default: the first two pose coordinates.
``parameter_kinds``
    What unit each catalog parameter takes (length, angle or number).

The registry is the package itself: every public module (or subpackage) of this package is one
family, named after it, which declares its :class:`Family` as the module attribute ``FAMILY``
(:data:`FAMILY_ATTRIBUTE`). Adding a robot is adding one module here (and its catalog file);
``CONTRIBUTING.md`` has a worked example. A family's module is imported when the family is first
looked up, so that analysing one robot imports one family; :meth:`Registry.pose_names` reads the
literal ``pose_names`` of each ``FAMILY`` declaration without importing the module. Families made at
run time are added with :func:`register`.

Examples
--------
>>> {"four_limb", "planar_3rrp"} <= set(families())
True
>>> families()["planar_3rrp"].pose_names
('x', 'y', 'phi')
"""

from __future__ import annotations

import ast
import functools
import importlib
import importlib.util
import io
import pkgutil
import re
import tokenize
from collections.abc import Callable, Iterator, Mapping, MutableMapping
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

import numpy as np

from ...exceptions import ScrewkitTypeError, ScrewkitValueError
from ...graphs.jointtable import JointTable

__all__ = ["FAMILY_ATTRIBUTE", "Family", "Registry", "WorkingModes", "families", "register"]

#: The module attribute under which a family's module declares its :class:`Family`.
FAMILY_ATTRIBUTE = "FAMILY"

P = TypeVar("P")
C = TypeVar("C")


@dataclass(frozen=True)
class WorkingModes:
    """A family's working modes: how its inverse kinematics is told which branch to take.

    A working mode is a tuple of ``size`` signs (one per limb for the families shipped here), passed
    to the inverse kinematics as the keyword ``option``; the sign ``values`` each entry may take,
    the ``default`` the inverse kinematics uses when none is given, and ``meaning``, the documented
    geometric reading of the default (what :func:`screwkit.testing.check_family` checks through
    ``of``).

    Attributes
    ----------
    option : str
        The inverse kinematics' keyword argument, e.g. ``"working_mode"``.
    default : tuple of int
        The mode used when none is given.
    meaning : str
        What the signs mean, in a sentence (e.g. ``"sign of h_i (paper 004, Eq. 8); -1: elbows out"``).
    values : tuple of int, optional
        The values each entry may take (default ``(-1, 1)``).
    of : callable or None, optional
        ``of(configuration) -> (..., size) int``: the mode a configuration is in, read from its
        geometry (not from the keyword the inverse kinematics was given), or None.

    Examples
    --------
    >>> modes = families()["four_limb"].working_modes
    >>> modes.option, modes.default
    ('working_mode', (-1, -1, -1, -1))
    >>> modes.options((1, 1, 1, 1))
    {'working_mode': (1, 1, 1, 1)}
    """

    option: str
    default: tuple[int, ...]
    meaning: str
    values: tuple[int, ...] = (-1, 1)
    of: Callable[[Any], np.ndarray] | None = None

    def options(self, mode: Any) -> dict[str, tuple[int, ...]]:
        """The inverse-kinematics keyword arguments that select ``mode``.

        Parameters
        ----------
        mode : sequence of int
            A working mode: ``len(default)`` entries among :attr:`values`.

        Returns
        -------
        dict
            ``{option: mode}``.

        Raises
        ------
        ScrewkitValueError
            If ``mode`` is not ``len(default)`` entries among :attr:`values`.

        Examples
        --------
        >>> families()["planar_3rrp"].working_modes.options([1, -1, 1])
        {'working_mode': (1, -1, 1)}
        >>> families()["planar_3rrp"].working_modes.options([1, 0, 1])
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected `mode` to be 3 values among (-1, 1) ...
        """
        values = tuple(mode) if isinstance(mode, list | tuple | np.ndarray) else None
        if values is None or len(values) != len(self.default) or not all(
            v in self.values for v in values
        ):
            raise ScrewkitValueError(
                f"Expected `mode` to be {len(self.default)} values among {self.values} ({self.meaning}), "
                f"got {mode!r}."
            )
        return {self.option: tuple(int(v) for v in values)}


@dataclass(frozen=True)
class Family(Generic[P, C]):
    """A mechanism family over parameters ``P`` and configurations ``C``: the protocol of the
    module docstring.

    Attributes
    ----------
    name : str
        The family's name (its module's name for a family shipped in this package).
    parameters : callable
        ``parameters(mapping, *, source) -> P``.
    inverse_kinematics : callable
        ``inverse_kinematics(parameters, poses, **mode) -> C``.
    joints : callable
        ``joints(configuration) -> JointTable``.
    twist_basis : callable
        ``twist_basis(configuration) -> ndarray (..., dof, 6)``.
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
    actuated_values : callable or None
        ``actuated_values(configuration) -> (..., k)``, the actuated joints' values in the order of
        the joint table's actuated joints (angles in radians, lengths in the file's unit).
    working_modes : WorkingModes or None
        The inverse kinematics' working-mode option, its default and meaning (None: one mode).
    map_axes : tuple of two str, or None
        The pose coordinates a map spans by default (None: the first two; see :attr:`default_map_axes`).

    Examples
    --------
    >>> families()["four_limb"].angle_names
    ('phi',)
    """

    name: str
    parameters: Callable[..., P]
    inverse_kinematics: Callable[..., C]
    joints: Callable[[C], JointTable]
    twist_basis: Callable[[C], np.ndarray]
    pose_names: tuple[str, ...]
    angle_names: tuple[str, ...]
    parameter_kinds: Mapping[str, str] = field(default_factory=dict)
    reachable: Callable[[P, np.ndarray], np.ndarray] | None = None
    application_points: Callable[[C], np.ndarray] | None = None
    actuated_values: Callable[[C], np.ndarray] | None = None
    working_modes: WorkingModes | None = None
    map_axes: tuple[str, str] | None = None

    @property
    def default_map_axes(self) -> tuple[str, str]:
        """The two pose coordinates a map spans by default: :attr:`map_axes`, else the first two pose
        coordinates (the only one of a one-coordinate family, twice: a map needs two families of
        more coordinates).

        Returns
        -------
        tuple of two str

        Examples
        --------
        >>> families()["four_limb"].default_map_axes
        ('z', 'phi')
        """
        if self.map_axes is not None:
            return self.map_axes
        names = self.pose_names
        return (names[0], names[1 if len(names) > 1 else 0])

    def mode_options(self, mode: Any) -> dict[str, Any]:
        """Inverse-kinematics options from ``mode``: None (no option), a mapping of options (as
        given), or a working mode (the keyword of :attr:`working_modes`).

        Parameters
        ----------
        mode : None, mapping or sequence of int

        Returns
        -------
        dict
            Keyword arguments for the inverse kinematics.

        Raises
        ------
        ScrewkitTypeError
            If ``mode`` is a string, or a working mode of a family that has none.
        ScrewkitValueError
            If the working mode is malformed (:meth:`WorkingModes.options`).

        Examples
        --------
        >>> families()["mcgill_smg"].mode_options((1, 1, -1, -1))
        {'mode': (1, 1, -1, -1)}
        >>> families()["four_limb"].mode_options(None)
        {}
        """
        if mode is None:
            return {}
        if isinstance(mode, Mapping):
            return dict(mode)
        if isinstance(mode, str | bytes) or self.working_modes is None:
            raise ScrewkitTypeError(
                f"Expected `mode` to be None, a mapping of inverse-kinematics options or a working mode "
                f"of the family {self.name!r} "
                f"({'it has none' if self.working_modes is None else self.working_modes.meaning}), "
                f"got {mode!r}."
            )
        return self.working_modes.options(mode)

    def joint_table(self, configuration: C) -> JointTable:
        """``joints(configuration)``, checked to be a :class:`~screwkit.graphs.jointtable.JointTable`
        (what the analysis core reads; a family's mistake is named here, not inside the core).

        Parameters
        ----------
        configuration : C
            A configuration made by the family's inverse kinematics.

        Returns
        -------
        JointTable
            The family's joint table at that configuration.

        Raises
        ------
        ScrewkitTypeError
            If the family's ``joints`` returns something else.

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


_DECLARATION = re.compile(rf"^{FAMILY_ATTRIBUTE}\b[^=\n]*=", re.M)


def _shipped() -> list[str]:
    """The names of this package's public modules and subpackages (the shipped families), in the
    order of the package's search path (alphabetical within a folder)."""
    return [info.name for info in pkgutil.iter_modules(__path__) if not info.name.startswith("_")]


def _declared_pose_names(name: str) -> tuple[str, ...] | None:
    """The literal ``pose_names`` of a shipped family's ``FAMILY = Family(...)`` declaration, read
    from its source without importing it (None when the declaration is not found or not literal)."""
    spec = importlib.util.find_spec(f"{__name__}.{name}")
    if spec is None or spec.origin is None or not spec.has_location:
        return None
    with open(spec.origin, encoding="utf-8") as file:
        text = file.read()
    found = _DECLARATION.search(text)
    if found is None:
        return None
    statement = []  # the one logical line of the declaration
    for token in tokenize.generate_tokens(io.StringIO(text[found.start() :]).readline):
        statement.append(token)
        if token.type == tokenize.NEWLINE:
            break
    value = ast.parse(tokenize.untokenize(statement)).body[0].value  # type: ignore[attr-defined]
    for keyword in getattr(value, "keywords", []):
        if keyword.arg == "pose_names":
            try:
                names = ast.literal_eval(keyword.value)
            except ValueError:
                return None
            return names if isinstance(names, tuple) else None
    return None


def _checked(family: Any) -> Family[Any, Any]:
    """A family, its fields checked (the errors of :func:`register`)."""
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
    for attribute in ("reachable", "application_points", "actuated_values"):  # the optional hooks
        hook = getattr(family, attribute)
        if hook is not None and not callable(hook):
            raise ScrewkitTypeError(
                f"Expected `family.{attribute}` to be callable or None, got {type(hook).__name__}."
            )
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
    _check_modes(family)
    axes = family.map_axes
    if axes is not None and (
        not isinstance(axes, tuple) or len(axes) != 2 or len(set(axes)) != 2
        or not set(axes) <= set(family.pose_names)
    ):
        raise ScrewkitValueError(
            f"Expected `family.map_axes` to be None or two different pose coordinates of "
            f"{family.pose_names}, got {axes!r}."
        )
    return family


def _check_modes(family: Family[Any, Any]) -> None:
    """The checks of :func:`register` on ``family.working_modes``."""
    modes = family.working_modes
    if modes is None:
        return
    if not isinstance(modes, WorkingModes):
        raise ScrewkitTypeError(
            f"Expected `family.working_modes` to be a WorkingModes or None, got {type(modes).__name__}."
        )
    if not isinstance(modes.option, str) or not modes.option.isidentifier():
        raise ScrewkitTypeError(
            f"Expected `family.working_modes.option` to be an identifier, got {modes.option!r}."
        )
    if not isinstance(modes.meaning, str) or not modes.meaning:
        raise ScrewkitTypeError(
            f"Expected `family.working_modes.meaning` to be a sentence, got {modes.meaning!r}."
        )
    if modes.of is not None and not callable(modes.of):
        raise ScrewkitTypeError(
            f"Expected `family.working_modes.of` to be callable or None, got {type(modes.of).__name__}."
        )
    if (
        not isinstance(modes.default, tuple) or not modes.default
        or not isinstance(modes.values, tuple) or not set(modes.default) <= set(modes.values)
    ):
        raise ScrewkitValueError(
            f"Expected `family.working_modes.default` to be a non-empty tuple of values among "
            f"{modes.values!r}, got {modes.default!r}."
        )


class Registry(MutableMapping[str, Family[Any, Any]]):
    """The families by name: those shipped as modules of this package (each imported when first
    looked up), then those added by :func:`register`.

    The package's search path is read at every listing, so that a module put on it (a folder
    appended to ``screwkit.robots.families.__path__``) is a family from then on. Deleting a shipped
    family forgets its loaded :class:`Family` (it is made again on its next look-up).

    Examples
    --------
    >>> registry = families()
    >>> "four_limb" in registry, "five_bar" in registry
    (True, False)
    """

    def __init__(self) -> None:
        self._loaded: dict[str, Family[Any, Any]] = {}
        self._registered: dict[str, Family[Any, Any]] = {}

    def _load(self, name: str) -> Family[Any, Any]:
        """Import a shipped family's module and check its declaration."""
        module = importlib.import_module(f"{__name__}.{name}")
        family = getattr(module, FAMILY_ATTRIBUTE, None)
        if not isinstance(family, Family):
            raise ScrewkitTypeError(
                f"Expected the module {module.__name__} to declare its family as "
                f"`{FAMILY_ATTRIBUTE} = Family(...)`, got {type(family).__name__}."
            )
        if family.name != name:
            raise ScrewkitValueError(
                f"Expected the family of the module {module.__name__} to be named {name!r}, "
                f"got {family.name!r}."
            )
        self._loaded[name] = _checked(family)
        return family

    def __getitem__(self, name: str) -> Family[Any, Any]:
        if name in self._registered:
            return self._registered[name]
        if name in self._loaded:
            return self._loaded[name]
        if isinstance(name, str) and name in _shipped():
            return self._load(name)
        raise KeyError(name)

    def __setitem__(self, name: str, family: Family[Any, Any]) -> None:
        self._registered[name] = family

    def __delitem__(self, name: str) -> None:
        # a registered family is removed; a shipped one is forgotten (imported again on its next
        # look-up, while its module is on the package's search path)
        found = [known.pop(name) for known in (self._registered, self._loaded) if name in known]
        if not found:
            raise KeyError(name)

    def __iter__(self) -> Iterator[str]:
        shipped = _shipped()
        return iter(shipped + [name for name in self._registered if name not in shipped])

    def __len__(self) -> int:
        return len(list(iter(self)))

    def __contains__(self, name: object) -> bool:
        return name in self._registered or name in self._loaded or name in _shipped()

    def pose_names(self) -> list[str]:
        """Every family's pose coordinates, each once, in order (reading a shipped family's
        declaration rather than importing its module, when the names are written literally).

        Returns
        -------
        list of str
            The coordinate names, in the order the families list them.

        Examples
        --------
        >>> families().pose_names()[:4]
        ['x', 'y', 'z', 'phi']
        """
        names: list[str] = []
        for name in self:
            known = self._registered.get(name) or self._loaded.get(name)
            found = known.pose_names if known is not None else _declared_pose_names(name)
            if found is None:
                found = self[name].pose_names
            names.extend(n for n in found if n not in names)
        return names


@functools.cache
def families() -> Registry:
    """The families a catalog entry can name, by name (each imported on first use; :func:`register`
    adds more).

    Returns
    -------
    Registry
        The one registry, a mutable mapping from names to families.

    Examples
    --------
    >>> families()["mcgill_smg"].pose_names
    ('x', 'y', 'z', 'phi')
    """
    return Registry()


def register(family: Family[P, C]) -> Family[P, C]:
    """Add a family made at run time to :func:`families`, so that catalog entries can name it (and
    return it). A family shipped with screwkit is a module of this package instead.

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
    _checked(family)
    known = families()
    if family.name in known:
        raise ScrewkitValueError(
            f"Expected a new family name, got {family.name!r}, which is already registered "
            f"({', '.join(sorted(known))})."
        )
    known[family.name] = family
    return family
