"""The mechanism catalog and snapshot files (TOML), read with :mod:`tomllib`.

Two kinds of file, told apart by ``[mechanism] kind``:

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

    [[expected]]                     # published facts, checked by tests/test_catalog.py
    fact = "platform_twist_order"
    value = 4
    source = "paper 002, §4.2"

**Snapshots** (``kind = "snapshot"``): any mechanism at one configuration, joint by joint::

    [mechanism]
    kind = "snapshot"
    name = "my robot"
    base = "ground"
    platform = "plate"
    dof = 3                          # optional: default, the number of actuated joints
    length_unit = "m"

    [[joints]]
    name = "A1"
    type = "R"                       # R, P, H, C, U, S, Pa
    parent = "ground"
    child = "leg1"
    axis = [0.0, 0.0, 1.0]
    point = [0.0, 0.0, 0.0]
    actuated = true

Joint fields by type: R ``axis, point``; P ``direction``; H ``axis, point, pitch``; C ``axis,
point``; U ``first_axis, second_axis, center``; S ``center``; Pa ``hinge_axis, rod_direction``;
every type takes ``actuated`` (default false). File text is only ever parsed as TOML data: it never
reaches ``eval`` or ``sympify``. Every error names the file, the joint or table, and the field.

Examples
--------
>>> h4 = load_mechanism("h4")
>>> h4.name, h4.family, h4.length_unit
('H4', 'four_limb', 'mm')
>>> sorted(list_mechanisms())[:1]
['h4']
"""

from __future__ import annotations

import codecs
import inspect
import math
import os
import stat
import unicodedata
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import networkx as nx
import numpy as np

from ..algebra.backend import is_dof
from ..exceptions import (
    CatalogError,
    ScrewkitError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
    UnreachablePoseError,
)
from ..graphs import joints as J
from ..graphs.joints import JointTable
from ..graphs.twistgraph import add_joint, check_twist_graph
from .families import Family, families

if TYPE_CHECKING:
    from ..core.jacobians import WrenchJacobians

__all__ = [
    "LENGTH_UNITS",
    "MAX_ANGLE_DEGREES",
    "MAX_ANGLE_RADIANS",
    "MAX_COORDINATE",
    "MAX_FAR_OVER_SPREAD",
    "MAX_FILE_BYTES",
    "MAX_JOINTS",
    "MAX_LOOPS",
    "MAX_REJECTION_ROUNDS",
    "Mechanism",
    "check_dof",
    "degrees_to_radians",
    "file_kind",
    "list_mechanisms",
    "load_mechanism",
    "load_snapshot",
    "load_toml",
    "mechanism_from_mapping",
    "snapshot_from_mapping",
    "unknown_mechanism",
]

Array = np.ndarray


@dataclass(frozen=True, eq=False)
class Mechanism:
    """A catalog robot: a family, its parameters, default pose, workspace and expected facts.

    Attributes
    ----------
    name, family, length_unit : str
    source : str
        The file it was read from.
    sources : tuple of str
        The papers the entry comes from.
    parameters : object
        The family's validated parameter dataclass.
    parameter_sources : dict
        ``{parameter: {"value", "unit", "source"}}`` as written in the file.
    default_pose : numpy.ndarray
        In the file's length unit and **radians** (the file stores degrees).
    workspace : dict
        ``{coordinate: (low, high)}``, angles in radians.
    reachable_fraction : float
        The share of the workspace box the inverse kinematics reaches (``[workspace]
        reachable_fraction``, default 1: every pose). Below 1 the box is a bounding box:
        :meth:`random_poses` draws in its reachable part only, the maps of :mod:`screwkit.analysis.workspace`
        mask the rest as unreachable (checked by ``tests/test_catalog.py`` against the IK).
    expected : tuple of dict
        The ``[[expected]]`` facts.
    """

    name: str
    family: str
    length_unit: str
    source: str
    sources: tuple[str, ...]
    parameters: Any
    parameter_sources: dict[str, dict[str, Any]]
    default_pose: Array
    workspace: dict[str, tuple[float, float]]
    expected: tuple[dict[str, Any], ...] = field(default=())
    reachable_fraction: float = 1.0

    @property
    def family_protocol(self) -> Family[Any, Any]:
        """The family's four functions (:mod:`screwkit.robots.families`)."""
        return families()[self.family]

    @property
    def pose_names(self) -> tuple[str, ...]:
        """Names of the pose coordinates, e.g. ``('x', 'y', 'z', 'phi')``."""
        return self.family_protocol.pose_names

    @property
    def angle_names(self) -> tuple[str, ...]:
        """The pose coordinates that are angles (radians in the API, degrees in files and the CLI)."""
        return self.family_protocol.angle_names

    def configuration(self, pose: Any = None, **options: Any) -> Any:
        """The family's configuration (inverse kinematics) at a pose or a batch ``(..., n)``
        (default: the default pose).

        Examples
        --------
        >>> load_mechanism("h4").configuration().theta.shape
        (4,)
        """
        chosen = self.default_pose if pose is None else pose
        self._check_options(options)
        self.check_pose_range(pose, "pose")
        return self.family_protocol.inverse_kinematics(self.parameters, chosen, **options)

    def _check_options(self, options: Mapping[str, Any]) -> None:
        """Refuse inverse-kinematics options the family's solver does not take (naming those it does)."""
        if not options:  # nothing to refuse (and no signature to read, chunk after chunk)
            return
        solve = self.family_protocol.inverse_kinematics
        accepted = [
            p.name
            for p in list(inspect.signature(solve).parameters.values())[2:]
            if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)
        ]
        unknown = sorted(set(options) - set(accepted))
        if unknown:
            raise ScrewkitTypeError(
                f"Expected inverse-kinematics options of the {self.family} family among {accepted}, "
                f"got {unknown}."
            )

    def joints(self, pose: Any = None, **options: Any) -> JointTable:
        """The joint table at a pose or a batch of poses (the input of the analysis core).

        Examples
        --------
        >>> table = load_mechanism("h4").joints(np.zeros((3, 4)) + [0, 0, -750, 0])
        >>> table.batch_shape, len(table.specs)
        ((3,), 22)
        """
        return self.family_protocol.joint_table(self.configuration(pose, **options))

    def at(
        self,
        poses: Any = None,
        *,
        rtol: float | None = None,
        length_scale: float | None = None,
        **options: Any,
    ) -> Any:
        """The mechanism at a batch of poses: a frozen :class:`~screwkit.robots.posed.PosedMechanism` whose
        stages (IK, joints, wrench systems, verdicts, Jacobians) are computed once, on demand.

        Parameters
        ----------
        poses : array_like, shape (..., n), optional
            In the file's length unit and radians; default: the default pose.
        rtol : float, optional
            Relative tolerance of every rank decision (default 1e-9).
        length_scale : float, optional
            The characteristic length of the rank decisions, in the file's length unit; default:
            derived from each pose's screws (:func:`~screwkit.core.wrenches.analyze_table`).
        **options
            Passed to the inverse kinematics (a working mode).

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [50, 20, -800, 0.3]])
        >>> posed.verdicts.tolist()
        ['regular', 'regular']
        >>> print(posed[1].singularity)  # doctest: +ELLIPSIS
        regular (dof 4): constraint order 2/2, global order 6/6
          closeness (0 at a singularity): constraint 0.968, actuation ...
        """
        from .posed import PosedMechanism

        self._check_options(options)
        self.check_pose_range(poses)
        return PosedMechanism.create(self, poses, rtol=rtol, length_scale=length_scale, options=options)

    def check_pose_range(self, poses: Any, argument: str = "poses") -> None:
        """Refuse pose coordinates beyond :data:`MAX_COORDINATE` and angles beyond
        :data:`MAX_ANGLE_RADIANS` (the radian form of the degrees rule, :data:`MAX_ANGLE_DEGREES`).

        Shapes, types and NaN are left to the callee, which names them; this check only bounds sizes.

        Raises
        ------
        ScrewkitValueError
            Naming the argument, the angle coordinate, the bound and the value.

        Examples
        --------
        >>> load_mechanism("h4").check_pose_range([0, 0, -750, 1e5])  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected the angle `phi` of `poses` to be at most 17453.3 ...
        """
        if poses is None or isinstance(poses, str):
            return
        with np.errstate(all="ignore"):
            try:
                values = np.abs(np.asarray(poses, dtype=float))
            except (TypeError, ValueError):  # not numeric: the callee names it
                return
        size = np.nanmax(values, initial=0.0)
        if np.isfinite(size) and size > MAX_COORDINATE:
            raise ScrewkitValueError(
                f"Expected pose coordinates up to {MAX_COORDINATE:g} in size ({self.length_unit}, "
                f"radians), got {size:g}."
            )
        if values.ndim == 0 or values.shape[-1] != len(self.pose_names):
            return
        for name in self.angle_names:
            angle = np.nanmax(values[..., self.pose_names.index(name)], initial=0.0)
            if np.isfinite(angle) and angle > MAX_ANGLE_RADIANS:
                raise ScrewkitValueError(
                    f"Expected the angle `{name}` of `{argument}` to be at most {MAX_ANGLE_RADIANS:g} rad "
                    f"({MAX_ANGLE_DEGREES:g} degrees) in magnitude (beyond it a double no longer holds the "
                    f"angle to the analysis's precision), got {angle:g} rad."
                )

    def random_poses(self, rng: np.random.Generator, count: int) -> Array:
        """Poses drawn uniformly in the *reachable* part of the operational workspace (radians),
        ``(count, n)``: draws whose inverse kinematics has no solution are drawn again (rejection keeps
        the distribution uniform; the first ``count`` draws are returned when all are reachable).

        Raises
        ------
        ScrewkitValueError
            If ``count`` is not a non-negative integer, or fewer than 1 draw in
            :data:`MAX_REJECTION_ROUNDS` is reachable (the workspace box is mostly out of reach).

        Examples
        --------
        >>> poses = load_mechanism("h4").random_poses(np.random.default_rng(0), 3)
        >>> poses.shape
        (3, 4)
        """
        if not isinstance(rng, np.random.Generator):
            raise ScrewkitTypeError(
                f"Expected `rng` to be a numpy.random.Generator, got {type(rng).__name__}."
            )
        if isinstance(count, bool) or not isinstance(count, int | np.integer) or not 0 <= count <= 10**7:
            raise ScrewkitValueError(f"Expected `count` to be an integer in 0..10**7, got {count!r}.")
        low, high = zip(*(self.workspace[c] for c in self.pose_names), strict=True)
        kept = np.empty((0, len(low)))
        for _ in range(MAX_REJECTION_ROUNDS):
            if len(kept) >= count:
                return kept[:count]
            draws = rng.uniform(low, high, size=(count - len(kept), len(low)))
            kept = np.concatenate([kept, draws[self.reachable(draws)]])
        if len(kept) >= count:
            return kept[:count]
        raise ScrewkitValueError(
            f"{self.source}: [workspace]: only {len(kept)} of the poses drawn in {MAX_REJECTION_ROUNDS} "
            "rounds "
            f"are reachable, {count} wanted: the workspace box is mostly out of reach."
        )

    def reachable(self, poses: Array, **options: Any) -> Array:
        """Which poses ``(m, n)`` (API units) the inverse kinematics accepts, ``(m,)`` bool.

        The family's vectorised ``reachable(parameters, poses)`` (:class:`~screwkit.robots.families.Family`)
        when it has one and no option changes the inverse kinematics' domain (the four-limb
        family: every working mode reaches the same poses), else one batch call of
        :meth:`configuration`, halved where a batch is refused
        (:class:`~screwkit.exceptions.UnreachablePoseError`).

        Examples
        --------
        >>> load_mechanism("v4").reachable(np.array([[0, 0, -750, 0], [0, 0, -3000, 0]]))
        array([ True, False])
        """
        if len(poses) == 0:
            return np.zeros(0, dtype=bool)
        test = self.family_protocol.reachable
        if test is not None and set(options) <= {"working_mode"}:
            return np.asarray(test(self.parameters, poses), dtype=bool).reshape(len(poses))
        return self._reachable_by_halving(poses, options)

    def _reachable_by_halving(self, poses: Array, options: dict[str, Any]) -> Array:
        """:meth:`reachable` by the inverse kinematics alone."""
        try:
            self.configuration(poses, **options)
            return np.ones(len(poses), dtype=bool)
        except UnreachablePoseError:
            if len(poses) == 1:
                return np.zeros(1, dtype=bool)
        half = len(poses) // 2
        halves = (poses[:half], poses[half:])
        return np.concatenate([self._reachable_by_halving(part, options) for part in halves])

    def wrench_diagram(
        self, pose: Any = None
    ) -> tuple[Any, Callable[[np.random.Generator], dict[str, Array]]]:
        """The wrench diagram at a pose, and a sampler of its recipes at random workspace poses
        (:meth:`screwkit.robots.posed.Pose.diagram_and_sampler`).

        Examples
        --------
        >>> diagram, sampler = load_mechanism("h4").wrench_diagram()
        >>> sorted(sampler(np.random.default_rng(1)))[:3]
        ['a', 'b', 'c']
        """
        return self.at(None if pose is None else np.asarray(pose, dtype=float)[None])[0].diagram_and_sampler()

    def twist_graph(self, pose: Any = None, **options: Any) -> nx.MultiDiGraph:
        """The twist graph of the physical mechanism at one pose (default: the default pose).

        Examples
        --------
        >>> load_mechanism("h4").twist_graph().graph["dof"]
        4
        """
        return self._one(pose, options).graph

    def twist_basis(self, pose: Any = None, **options: Any) -> Array:
        """The platform's nominal twists at a pose (default: the default pose), rows ``(dof, 6)``.

        One twist per pose coordinate, in the order of :attr:`pose_names` (unit rate of that
        coordinate, user frame): for the Schönflies-motion generators the three translations and
        the rotation about the end effector's own axis through its reference point, for the planar
        3-RRP the translations ``x``, ``y`` and the rotation about ``z`` through the platform point.
        ``options`` go to :meth:`configuration` (e.g. a working mode).

        Examples
        --------
        >>> load_mechanism("v4").twist_basis()[3]  # the V4's end effector turns about j
        array([  0.,   1.,   0., 750.,   0.,   0.])
        """
        return self._one(pose, options).twist_basis

    def jacobians(self, pose: Any = None, **options: Any) -> WrenchJacobians:
        """Forward and inverse Jacobians ``A χ̇ = B θ̇`` from the wrench systems at a pose.

        :func:`screwkit.core.jacobians.jacobians_from_wrenches` of the wrench analysis over
        :meth:`twist_basis` (so ``χ̇`` are the rates of the pose coordinates), with its
        Gosselin–Angeles type and closeness measures. ``options`` go to :meth:`configuration`.

        Raises
        ------
        ScrewkitError
            If the pose is out of reach (naming the limb), or the basis is refused at this pose
            (:func:`~screwkit.core.jacobians.jacobians_from_wrenches`).

        Examples
        --------
        >>> jac = load_mechanism("planar_3rrp").jacobians()
        >>> jac.type, jac.A.shape, jac.actuated_joints
        ('regular', (3, 3), ('limb1_R1', 'limb2_R1', 'limb3_R1'))
        """
        return self._one(pose, options).jacobians

    def _one(self, pose: Any, options: dict[str, Any]) -> Any:
        """One pose through the composer (:meth:`at`)."""
        chosen = None if pose is None else np.asarray(pose, dtype=float)
        if chosen is not None and chosen.ndim != 1:
            raise ScrewkitValueError(
                f"Expected one pose of shape ({len(self.pose_names)},), got {chosen.shape}; "
                "use at() for batches."
            )
        return self.at(chosen, **options)[0]


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
#: How far from the origin a snapshot's joints may lie, in units of their spread (1e7: float64 then
#: keeps about 9 significant digits of the geometry, as the default rtol 1e-9 needs).
MAX_FAR_OVER_SPREAD = 1e7
#: Rounds of redrawing in :meth:`Mechanism.random_poses` before a mostly unreachable workspace is refused.
MAX_REJECTION_ROUNDS = 50
#: Resource caps: a larger file, or a snapshot with more joints, is refused before it is parsed.
MAX_FILE_BYTES = 1 << 20
MAX_JOINTS = 500
#: Independent loops (joints - links + 1) a snapshot may close: the report's generic configurations
#: solve all loop closures at once, ~2 s at 16 loops of 6 freedoms each, ~20 s at 23 (superlinear).
MAX_LOOPS = 16
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
#: The same bound for the radians of the Python API (:meth:`Mechanism.check_pose_range`).
MAX_ANGLE_RADIANS = math.radians(MAX_ANGLE_DEGREES)


def degrees_to_radians(value: float) -> float:
    """Degrees to radians, whole turns kept (``360`` is ``2π``, not ``0``).

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


def _package_file(name: str) -> Path:
    return Path(str(resources.files("screwkit.mechanisms").joinpath(f"{name}.toml")))


def list_mechanisms() -> list[str]:
    """Names of the catalog entries shipped with the package.

    Examples
    --------
    >>> "h4" in list_mechanisms()
    True
    """
    folder = resources.files("screwkit.mechanisms")
    return sorted(p.name[: -len(".toml")] for p in folder.iterdir() if p.name.endswith(".toml"))


def load_mechanism(name_or_path: str | Path) -> Mechanism:
    """Load a catalog entry by name (``"h4"``) or from a ``.toml`` path.

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

    Examples
    --------
    >>> mechanism_from_mapping({"mechanism": {"kind": "family", "name": "X", "family": "nope"}})
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: <mapping>: [mechanism]: field `family`: expected one of ...
    """
    if not isinstance(data, Mapping):
        raise CatalogError(f"{source}: expected a mapping of TOML tables, got {type(data).__name__}.")
    _check_keys(data, ("mechanism", "parameters", "pose", "workspace", "expected"), source, "top level")
    header = _table(data, "mechanism", source)
    _check_keys(
        header, ("kind", "name", "family", "length_unit", "sources", "description"), source, "[mechanism]"
    )
    kind = header.get("kind", "family")
    if kind != "family":
        raise _error(source, "[mechanism]", f"field `kind`: expected 'family' here, got {kind!r}.")
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


# snapshots ---------------------------------------------------------------------------------------
_JOINT_FIELDS = J.JOINT_FIELDS
_COMMON_FIELDS = {"name", "type", "parent", "child", "actuated"}


def _snapshot_joint(entry: Any, index: int, source: str) -> tuple[str, str, J.Joint]:
    where = f"[[joints]] #{index + 1}"
    if not isinstance(entry, dict):
        raise _error(source, where, f"expected a table, got {type(entry).__name__}.")
    name = _name(entry, "name", source, where)
    where = f"joint {name!r}"
    kind = _string(entry, "type", source, where)
    if kind not in _JOINT_FIELDS:
        raise _error(source, where, f"field `type`: expected one of {sorted(_JOINT_FIELDS)}, got {kind!r}.")
    parent = _name(entry, "parent", source, where)
    child = _name(entry, "child", source, where)
    actuated = entry.get("actuated", False)
    if not isinstance(actuated, bool):
        raise _error(source, where, f"field `actuated`: expected true or false, got {actuated!r}.")
    _check_keys(entry, (*_COMMON_FIELDS, *_JOINT_FIELDS[kind]), source, f"{where} ({kind} joint)")
    values: dict[str, Any] = {}
    for key in _JOINT_FIELDS[kind]:
        if key not in entry:
            raise _error(
                source, where, f"field `{key}`: missing (a {kind} joint needs {list(_JOINT_FIELDS[kind])})."
            )
        if key == "pitch":
            values[key] = _number(entry[key], source, where, key)
        elif key in ("point", "center"):
            values[key] = _vector(entry, key, source, where)
        else:  # a direction: only its direction counts, so scale it exactly (a power of two) to size ~1
            values[key] = _direction(_vector(entry, key, source, where))
        if any(abs(v) > MAX_COORDINATE for v in np.ravel(values[key])):
            raise _error(
                source,
                where,
                f"field `{key}`: expected magnitudes up to {MAX_COORDINATE:g}, got {entry[key]!r}.",
            )
    builders: dict[str, Callable[..., J.Joint]] = {
        "R": lambda: J.revolute(name, values["axis"], values["point"], actuated=actuated),
        "P": lambda: J.prismatic(name, values["direction"], actuated=actuated),
        "H": lambda: J.helical(name, values["axis"], values["point"], values["pitch"], actuated=actuated),
        "C": lambda: J.cylindrical(name, values["axis"], values["point"]),
        "U": lambda: J.universal(name, values["first_axis"], values["second_axis"], values["center"]),
        "S": lambda: J.spherical(name, values["center"]),
        "Pa": lambda: J.parallelogram(name, values["hinge_axis"], values["rod_direction"], actuated=actuated),
    }
    if actuated and kind in ("C", "U", "S"):
        raise _error(
            source, where, f"field `actuated`: a {kind} joint has several freedoms and cannot be actuated."
        )
    try:
        return parent, child, builders[kind]()
    except ScrewkitError as err:
        raise _error(source, where, str(err)) from err


def snapshot_from_mapping(data: Mapping[str, Any], *, source: str = "<mapping>") -> nx.MultiDiGraph:
    """Build a twist graph from parsed snapshot TOML (see the module docstring).

    Examples
    --------
    >>> graph = snapshot_from_mapping({
    ...     "mechanism": {"kind": "snapshot", "name": "slider", "base": "B", "platform": "E"},
    ...     "joints": [{"name": "P1", "type": "P", "parent": "B", "child": "E",
    ...                 "direction": [1.0, 0.0, 0.0], "actuated": True}]})
    >>> graph.graph["name"], graph.number_of_edges()
    ('slider', 1)
    """
    if not isinstance(data, Mapping):
        raise CatalogError(f"{source}: expected a mapping of TOML tables, got {type(data).__name__}.")
    _check_keys(data, ("mechanism", "joints"), source, "top level")
    header = _table(data, "mechanism", source)
    _check_keys(
        header,
        ("kind", "name", "base", "platform", "dof", "length_unit", "description", "sources"),
        source,
        "[mechanism]",
    )
    kind = header.get("kind")
    if kind != "snapshot":
        raise _error(source, "[mechanism]", f"field `kind`: expected 'snapshot', got {kind!r}.")
    name = _name(header, "name", source, "[mechanism]")
    base = _name(header, "base", source, "[mechanism]")
    platform = _name(header, "platform", source, "[mechanism]")
    if "description" in header:
        _string(header, "description", source, "[mechanism]")
    _strings(header, "sources", source, "[mechanism]")
    dof = header.get("dof")
    if dof is not None and not is_dof(dof):
        raise _error(source, "[mechanism]", f"field `dof`: expected an integer in 0..6, got {dof!r}.")
    length_unit = _length_unit(header, source) if "length_unit" in header else ""
    entries = data.get("joints")
    if not isinstance(entries, list) or not entries:
        raise _error(source, "[[joints]]", "expected at least one [[joints]] table, got none.")
    if len(entries) > MAX_JOINTS:
        raise _error(source, "[[joints]]", f"expected at most {MAX_JOINTS} joints, got {len(entries)}.")
    _check_precision(entries, source)
    triples = [_snapshot_joint(entry, i, source) for i, entry in enumerate(entries)]
    links = {base, platform} | {t[0] for t in triples} | {t[1] for t in triples}
    loops = len(triples) - len(links) + 1
    if loops > MAX_LOOPS:
        raise _error(
            source,
            "[[joints]]",
            f"expected at most {MAX_LOOPS} independent loops (joints - links + 1), got {loops} "
            f"({len(triples)} joints between {len(links)} links); split the model or reduce it.",
        )
    try:
        graph = _checked_graph(base, platform, triples, dof)
        check_dof(graph)
    except ScrewkitError as err:
        raise CatalogError(f"{source}: {err}") from err
    graph.graph["name"] = name
    graph.graph["length_unit"] = length_unit
    return graph


def _check_precision(entries: list[Any], source: str) -> None:
    """Refuse joints so far from the origin, for their spread, that float64 keeps fewer than ~9
    significant digits of the geometry (:data:`MAX_FAR_OVER_SPREAD`): the rank decisions (rtol
    1e-9) would judge rounding, not the mechanism."""
    points = np.array(
        [
            entry[key]
            for entry in entries
            if isinstance(entry, dict)
            for key in ("point", "center")
            if isinstance(entry.get(key), list)
            and len(entry[key]) == 3
            and all(isinstance(v, int | float) and not isinstance(v, bool) and abs(v) <= MAX_COORDINATE
                    for v in entry[key])
        ],
        dtype=float,
    ).reshape(-1, 3)
    if len(points) < 2:
        return
    far = float(np.abs(points).max())
    spread = float(np.ptp(points, axis=0).max())
    if spread > 0 and far > MAX_FAR_OVER_SPREAD * spread:
        raise _error(
            source,
            "[[joints]]",
            f"expected joints within {MAX_FAR_OVER_SPREAD:g} times their spread of the origin, got points "
            f"{far:g} from it spanning only {spread:g}: float64 keeps too few digits of the geometry "
            "there; put the origin near the mechanism.",
        )


def check_dof(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> None:
    """Refuse a twist graph whose ``dof`` is below its number of actuators (at load time).

    screwkit analyses non-redundantly actuated mechanisms whose nominal ``dof`` is the platform's
    mobility at generic configurations (:func:`screwkit.core.motion.resolve_dof`). A ``dof`` below the
    number of actuated joints contradicts that whatever the mobility, and is refused here without
    computing it; the rest (``dof`` equal to the mobility, actuators no more than it) is checked when
    the graph is analysed (:func:`screwkit.core.motion.settled_dof`). A graph without ``dof`` or without
    actuated joints passes.

    Raises
    ------
    TwistGraphError
        Naming both numbers.

    Examples
    --------
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.graphs.joints import prismatic
    >>> P = [prismatic(f"P{i}", [1, i, 0], actuated=True) for i in range(2)]
    >>> check_dof(twist_graph("B", "E", [("B", "L", P[0]), ("L", "E", P[1])], dof=1))
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected `dof` to be at least the number of actuated joints (2: ...
    """
    dof = graph.graph.get("dof")
    actuated = sorted(
        str(data[joint_key].name)
        for *_, data in graph.edges(data=True)
        if getattr(data[joint_key], "actuated", False)
    )
    if is_dof(dof) and dof < len(actuated):
        raise TwistGraphError(
            f"Expected `dof` to be at least the number of actuated joints ({len(actuated)}: "
            f"{', '.join(actuated)}), got dof = {dof}; screwkit analyses non-redundantly actuated "
            "mechanisms: fix `dof` (the mechanism's mobility) or the `actuated` flags."
        )


def _checked_graph(
    base: str, platform: str, triples: list[tuple[str, str, J.Joint]], dof: int | None
) -> nx.MultiDiGraph:
    graph = nx.MultiDiGraph(base=base, platform=platform)
    if dof is not None:
        graph.graph["dof"] = dof
    nodes = {base, platform} | {t[0] for t in triples} | {t[1] for t in triples}
    graph.add_nodes_from(sorted(nodes))
    for parent, child, joint in triples:
        add_joint(graph, parent, child, joint)
    check_twist_graph(graph)
    return graph


def load_snapshot(path: str | Path) -> nx.MultiDiGraph:
    """Load a snapshot file as a twist graph.

    Raises
    ------
    CatalogError
        Naming the file, the joint and the field of any problem.

    Examples
    --------
    >>> load_snapshot("/nonexistent.toml")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: /nonexistent.toml: cannot read the file: No such file or directory.
    """
    return snapshot_from_mapping(load_toml(path), source=str(path))
