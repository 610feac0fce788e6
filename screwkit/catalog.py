"""The mechanism catalog and snapshot files (TOML), read with :mod:`tomllib`.

Two kinds of file, told apart by ``[mechanism] kind``:

**Catalog entries** (``kind = "family"``, shipped in the top-level ``mechanisms/`` folder): a robot of a
parametric family in :mod:`screwkit.families`::

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

    [workspace]                      # the operational workspace, [low, high] per coordinate
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

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import networkx as nx
import numpy as np

from . import joints as J
from ._backend import is_dof
from .exceptions import CatalogError, ScrewkitError, ScrewkitValueError
from .families import Family, families
from .joints import JointTable
from .twistgraph import add_joint, check_twist_graph

if TYPE_CHECKING:
    from .jacobians import WrenchJacobians

__all__ = [
    "Mechanism",
    "list_mechanisms",
    "load_mechanism",
    "load_snapshot",
    "load_toml",
    "mechanism_from_mapping",
    "snapshot_from_mapping",
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

    @property
    def family_protocol(self) -> Family:
        """The family's four functions (:mod:`screwkit.families`)."""
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
        return self.family_protocol.inverse_kinematics(self.parameters, chosen, **options)

    def joints(self, pose: Any = None, **options: Any) -> JointTable:
        """The joint table at a pose or a batch of poses (the input of the analysis core).

        Examples
        --------
        >>> table = load_mechanism("h4").joints(np.zeros((3, 4)) + [0, 0, -750, 0])
        >>> table.batch_shape, len(table.specs)
        ((3,), 22)
        """
        return self.family_protocol.joints(self.configuration(pose, **options))

    def at(self, poses: Any = None, *, rtol: float | None = None, **options: Any) -> Any:
        """The mechanism at a batch of poses: a frozen :class:`~screwkit.posed.PosedMechanism` whose
        stages (IK, joints, wrench systems, verdicts, Jacobians) are computed once, on demand.

        Parameters
        ----------
        poses : array_like, shape (..., n), optional
            In the file's length unit and radians; default: the default pose.
        rtol : float, optional
            Relative tolerance of every rank decision (default 1e-9).
        **options
            Passed to the inverse kinematics (a working mode).

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [50, 20, -800, 0.3]])
        >>> posed.verdicts.tolist()
        ['regular', 'regular']
        >>> print(posed[1].singularity)
        regular (dof 4): constraint order 2/2, global order 6/6
        """
        from .posed import PosedMechanism

        return PosedMechanism.create(self, poses, rtol=rtol, options=options)

    def random_poses(self, rng: np.random.Generator, count: int) -> Array:
        """Poses drawn uniformly in the operational workspace (radians), ``(count, n)``.

        Examples
        --------
        >>> load_mechanism("h4").random_poses(np.random.default_rng(0), 3).shape
        (3, 4)
        """
        low, high = zip(*(self.workspace[c] for c in self.pose_names), strict=True)
        return rng.uniform(low, high, size=(count, len(low)))

    def wrench_diagram(
        self, pose: Any = None
    ) -> tuple[Any, Callable[[np.random.Generator], dict[str, Array]]]:
        """The wrench diagram at a pose, and a sampler of its recipes at random workspace poses
        (:meth:`screwkit.posed.Pose.diagram_and_sampler`).

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

        :func:`screwkit.jacobians.jacobians_from_wrenches` of the wrench analysis over
        :meth:`twist_basis` (so ``χ̇`` are the rates of the pose coordinates), with its
        Gosselin–Angeles type and closeness measures. ``options`` go to :meth:`configuration`.

        Raises
        ------
        ScrewkitError
            If the pose is out of reach (naming the limb), or the basis is refused at this pose
            (:func:`~screwkit.jacobians.jacobians_from_wrenches`).

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

    name = str(path)
    try:
        with open(path, "rb") as stream:
            return tomllib.load(stream)
    except OSError as err:
        raise CatalogError(f"{name}: cannot read the file: {err.strerror}.") from err
    except tomllib.TOMLDecodeError as err:
        raise CatalogError(f"{name}: not valid TOML: {err}.") from err


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


def _number(value: Any, source: str, where: str, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise _error(source, where, f"field `{key}`: expected a finite number, got {value!r}.")
    return float(value)


def _radians(value: Any, source: str, where: str) -> Any:
    if isinstance(value, list):
        return [_radians(item, source, where) for item in value]
    return math.radians(_number(value, source, where, "value"))


def _vector(data: Mapping[str, Any], key: str, source: str, where: str, length: int = 3) -> list[float]:
    value = data.get(key)
    if not isinstance(value, list) or len(value) != length:
        raise _error(source, where, f"field `{key}`: expected a list of {length} numbers, got {value!r}.")
    return [_number(v, source, where, key) for v in value]


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
    text = str(name_or_path)
    if text.endswith(".toml"):
        path = Path(text)
    elif text.lower() in list_mechanisms():
        path = _package_file(text.lower())
    else:
        raise CatalogError(
            f"unknown mechanism {text!r}: expected one of {list_mechanisms()} or a path to a .toml file."
        )
    return mechanism_from_mapping(load_toml(path), source=str(path))


def mechanism_from_mapping(data: Mapping[str, Any], *, source: str = "<mapping>") -> Mechanism:
    """Build a :class:`Mechanism` from parsed catalog TOML (see the module docstring).

    Examples
    --------
    >>> mechanism_from_mapping({"mechanism": {"kind": "family", "name": "X", "family": "nope"}})
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: <mapping>: [mechanism]: field `family`: expected one of ...
    """
    header = _table(data, "mechanism", source)
    kind = header.get("kind", "family")
    if kind != "family":
        raise _error(source, "[mechanism]", f"field `kind`: expected 'family' here, got {kind!r}.")
    name = _string(header, "name", source, "[mechanism]")
    family_name = _string(header, "family", source, "[mechanism]")
    known = families()
    if family_name not in known:
        raise _error(
            source, "[mechanism]", f"field `family`: expected one of {sorted(known)}, got {family_name!r}."
        )
    family = known[family_name]
    length_unit = _string(header, "length_unit", source, "[mechanism]")
    sources = header.get("sources", [])
    if not isinstance(sources, list) or not all(isinstance(s, str) for s in sources):
        raise _error(source, "[mechanism]", f"field `sources`: expected a list of strings, got {sources!r}.")
    raw_parameters = _table(data, "parameters", source)
    values: dict[str, Any] = {"name": name, "length_unit": length_unit}
    documented: dict[str, dict[str, Any]] = {}
    for key, entry in raw_parameters.items():
        where = f"[parameters.{key}]"
        if not isinstance(entry, dict) or "value" not in entry:
            raise _error(source, where, f"expected a table with `value`, `unit` and `source`, got {entry!r}.")
        for required in ("unit", "source"):
            _string(entry, required, source, where)
        unknown = set(entry) - {"value", "unit", "source", "note"}
        if unknown:
            raise _error(source, where, f"unknown field(s) {sorted(unknown)}.")
        value = entry["value"]
        if entry["unit"] == "deg":  # a number or a (nested) list of numbers, in degrees
            value = _radians(value, source, where)
        values[key] = value
        documented[key] = dict(entry)
    try:
        parameters = family.parameters(values, source=f"{source}: [parameters]")
    except CatalogError:
        raise
    except ScrewkitError as err:
        raise CatalogError(f"{source}: [parameters]: {err}") from err
    pose_table = _table(data, "pose", source)
    pose = []
    for coordinate in family.pose_names:
        key = f"{coordinate}_deg" if coordinate in family.angle_names else coordinate
        if key not in pose_table:
            raise _error(source, "[pose]", f"field `{key}`: missing.")
        number = _number(pose_table[key], source, "[pose]", key)
        pose.append(math.radians(number) if coordinate in family.angle_names else number)
    workspace_table = _table(data, "workspace", source)
    workspace = {}
    for coordinate in family.pose_names:
        key = f"{coordinate}_deg" if coordinate in family.angle_names else coordinate
        low, high = _vector(workspace_table, key, source, "[workspace]", length=2)
        if not low < high:
            raise _error(source, "[workspace]", f"field `{key}`: expected low < high, got [{low}, {high}].")
        convert = math.radians if coordinate in family.angle_names else float
        workspace[coordinate] = (convert(low), convert(high))
    expected = data.get("expected", [])
    if not isinstance(expected, list) or not all(isinstance(e, dict) for e in expected):
        raise _error(source, "[[expected]]", f"expected an array of tables, got {type(expected).__name__}.")
    for index, fact in enumerate(expected):
        where = f"[[expected]] #{index + 1}"
        _string(fact, "fact", source, where)
        _string(fact, "source", source, where)
        if "value" not in fact:
            raise _error(source, where, "field `value`: missing.")
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
    )


# snapshots ---------------------------------------------------------------------------------------
_JOINT_FIELDS: dict[str, tuple[str, ...]] = {
    "R": ("axis", "point"),
    "P": ("direction",),
    "H": ("axis", "point", "pitch"),
    "C": ("axis", "point"),
    "U": ("first_axis", "second_axis", "center"),
    "S": ("center",),
    "Pa": ("hinge_axis", "rod_direction"),
}
_COMMON_FIELDS = {"name", "type", "parent", "child", "actuated"}


def _snapshot_joint(entry: Any, index: int, source: str) -> tuple[str, str, J.Joint]:
    where = f"[[joints]] #{index + 1}"
    if not isinstance(entry, dict):
        raise _error(source, where, f"expected a table, got {type(entry).__name__}.")
    name = _string(entry, "name", source, where)
    where = f"joint {name!r}"
    kind = _string(entry, "type", source, where)
    if kind not in _JOINT_FIELDS:
        raise _error(source, where, f"field `type`: expected one of {sorted(_JOINT_FIELDS)}, got {kind!r}.")
    parent = _string(entry, "parent", source, where)
    child = _string(entry, "child", source, where)
    actuated = entry.get("actuated", False)
    if not isinstance(actuated, bool):
        raise _error(source, where, f"field `actuated`: expected true or false, got {actuated!r}.")
    unknown = set(entry) - _COMMON_FIELDS - set(_JOINT_FIELDS[kind])
    if unknown:
        raise _error(
            source,
            where,
            f"unknown field(s) {sorted(unknown)} for a {kind} joint (expected {list(_JOINT_FIELDS[kind])}).",
        )
    values: dict[str, Any] = {}
    for key in _JOINT_FIELDS[kind]:
        if key not in entry:
            raise _error(
                source, where, f"field `{key}`: missing (a {kind} joint needs {list(_JOINT_FIELDS[kind])})."
            )
        values[key] = (
            _number(entry[key], source, where, key) if key == "pitch" else _vector(entry, key, source, where)
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
    header = _table(data, "mechanism", source)
    kind = header.get("kind")
    if kind != "snapshot":
        raise _error(source, "[mechanism]", f"field `kind`: expected 'snapshot', got {kind!r}.")
    name = _string(header, "name", source, "[mechanism]")
    base = _string(header, "base", source, "[mechanism]")
    platform = _string(header, "platform", source, "[mechanism]")
    dof = header.get("dof")
    if dof is not None and not is_dof(dof):
        raise _error(source, "[mechanism]", f"field `dof`: expected an integer in 0..6, got {dof!r}.")
    entries = data.get("joints")
    if not isinstance(entries, list) or not entries:
        raise _error(source, "[[joints]]", "expected at least one [[joints]] table, got none.")
    triples = [_snapshot_joint(entry, i, source) for i, entry in enumerate(entries)]
    try:
        graph = _checked_graph(base, platform, triples, dof)
    except ScrewkitError as err:
        raise CatalogError(f"{source}: {err}") from err
    graph.graph["name"] = name
    graph.graph["length_unit"] = header.get("length_unit", "")
    return graph


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
