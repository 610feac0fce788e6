"""A wrench diagram's points at poses: each recipe (:attr:`~screwkit.gca.diagram.DiagramPoint.key`)
evaluated over a batch at once from the batched core's arrays (:func:`batch_diagram_points`; one
pose, :func:`diagram_points`, is a batch of one); the incidence arithmetic they use is
:mod:`screwkit.gca.diagram_incidence`.

Examples
--------
>>> from screwkit.core.wrench_systems import analyze_table
>>> h4 = load_mechanism("h4")
>>> diagram, _ = h4.wrench_diagram()
>>> found = batch_diagram_points(diagram.points, analyze_table(h4.joints([[0, 0, -750, 0]])))
>>> found["j"]
array([[0., 0., 1., 0.]])
"""

from __future__ import annotations

import functools
from collections.abc import Mapping

import numpy as np

from ..algebra import backend as B
from ..algebra.readable_bases import readable_bases
from ..core import frames as F
from ..core.wrench_systems import WrenchAnalysis, analyze_table
from ..exceptions import DegenerateGeometryError
from ..graphs.jointtable import JointTable
from ..graphs.topology import Topology
from .diagram import INCIDENCE_RTOL, DiagramPoint, axis_key
from .diagram_incidence import (
    _canonical_directions,
    _finite,
    _finite_axes,
    _free,
    _infinite,
    _joint_centres,
    _meet,
    _scaled_axes,
    _units,
)
from .diagram_lines import Line, basis_names, leg_name

__all__ = [
    "batch_diagram_points",
    "diagram_points",
    "frames_read",
]

Array = np.ndarray
ACTUATION = "actuation "  # an actuation line's name: this prefix and its actuated joint


def diagram_points(
    points: tuple[DiagramPoint, ...],
    analysis: WrenchAnalysis,
    *,
    lines: list[Line] | None = None,
) -> dict[str, Array]:
    """Evaluate the points' recipes on an analysis of the same mechanism (at any pose).

    One pose: a batch of one through :func:`batch_diagram_points` (the same arithmetic).

    Parameters
    ----------
    points : tuple of DiagramPoint
        A diagram's points (their recipes).
    analysis : WrenchAnalysis
        One pose of the mechanism.
    lines : list of (name, role, wrench, joints), optional
        The only lines the recipes may use (default: every line of the mechanism).

    Returns
    -------
    dict of str to numpy.ndarray, shape (4,)
        ``{label: point}``, finite points of weight 1, directions unit (a
        ``normals`` point: ``n_a × n_b`` of unit couples, its magnitude kept).

    Raises
    ------
    DegenerateGeometryError
        Naming the point whose recipe has no point at this pose.

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> from screwkit.gca.diagram_recipes import wrench_diagram
    >>> h4 = load_mechanism("h4")
    >>> diagram = wrench_diagram(wrench_analysis(h4.twist_graph()))
    >>> moved = diagram_points(diagram.points, wrench_analysis(h4.twist_graph([50.0, 0, -700.0, 0.3])))
    >>> moved["j"]
    array([0., 0., 1., 0.])
    """
    found = batch_diagram_points(points, analysis, lines=lines)
    for point in points:
        if not np.isfinite(found[point.label]).all():
            raise DegenerateGeometryError(
                f"point {point.label} ({point.description}) does not exist at this pose"
            )
    return {label: value[0] for label, value in found.items()}


def batch_diagram_points(
    points: tuple[DiagramPoint, ...],
    analysis: WrenchAnalysis,
    *,
    lines: list[Line] | None = None,
) -> dict[str, Array]:
    """The points' recipes at every pose of a batched analysis, as arrays over the batch.

    Each recipe is evaluated over the leading axis at once from the batched core's arrays: the
    actuation wrenches, the joint screws, the series-parallel nodes' twist frames (the branches'
    constraint couples), the reference point. A constraint line of a leg is an element of its
    readable basis (:meth:`screwkit.algebra.screwsystem.ScrewSystem.readable_basis`), taken over the
    batch (:func:`screwkit.algebra.readable_bases.readable_bases`), and only for the points that use one.

    Parameters
    ----------
    points : tuple of DiagramPoint
        A diagram's points (their recipes).
    analysis : WrenchAnalysis
        Of shape ``(n,)`` (or one pose, taken as a batch of one), e.g.
        :func:`screwkit.core.wrench_systems.analyze_table` of a family's joint table; one without
        its views should keep the frames the recipes read (``kept``: :func:`frames_read`), else
        they are computed again (those frames only).
    lines : list of (name, role, wrench, joints), optional
        At one pose: the only lines the recipes may use (default: every line of the mechanism).

    Returns
    -------
    dict of str to numpy.ndarray, shape (n, 4)
        ``{label: points}``, finite points of weight 1, directions unit (a ``normals`` point:
        ``n_a × n_b`` of unit couples, its magnitude kept); a row of NaN where the recipe has no
        point at that pose.

    Examples
    --------
    >>> from screwkit.core.wrench_systems import analyze_table
    >>> h4 = load_mechanism("h4")
    >>> diagram, _ = h4.wrench_diagram()
    >>> table = h4.joints([[0, 0, -750, 0], [50, 0, -700, 0.3]])
    >>> found = batch_diagram_points(diagram.points, analyze_table(table))
    >>> found["j"]
    array([[0., 0., 1., 0.],
           [0., 0., 1., 0.]])
    """
    batch = _Batch.create(analysis, lines, points)
    cache: dict[tuple[str, ...], Array] = {}
    return {point.label: _carried(_recipe(point.key, batch, cache), point) for point in points}


def _joint_carried(key: tuple[str, ...]) -> bool:
    """Whether a recipe's point at infinity is oriented by the mechanism's joints over the motion
    (then carried times its constant :attr:`DiagramPoint.sign`): a ``normals`` point
    (:func:`_branch_pair`) and an actuation line's direction (:func:`_actuation_sides`).

    Parameters
    ----------
    key : tuple of str
        A recipe (:attr:`DiagramPoint.key`).

    Returns
    -------
    bool

    Examples
    --------
    >>> _joint_carried(("direction", "actuation A1")), _joint_carried(("axis", "A1"))
    (True, False)
    """
    return key[0] == "normals" or (key[0] == "direction" and key[1].startswith(ACTUATION))


def _carried(value: Array, point: DiagramPoint) -> Array:
    """A point's values with the orientation fixed at the reference configuration: a point the
    joints orient (:func:`_joint_carried`) times its constant :attr:`DiagramPoint.sign` (a flip per
    pose would lose the sign of its value), another point at infinity by its
    :attr:`DiagramPoint.orientation` (:func:`_oriented`)."""
    if _joint_carried(point.key):
        return point.sign * value + 0.0
    return _oriented(value, point.orientation)


def _oriented(value: Array, orientation: tuple[float, ...] | None) -> Array:
    """Points at infinity ``(n, 4)`` with the sign making a non-negative dot product with the
    reference direction (:attr:`DiagramPoint.orientation`), unchanged without one."""
    if orientation is None:
        return value
    with np.errstate(invalid="ignore"):
        flip = value[:, :3] @ np.asarray(orientation, dtype=float) < 0
    return np.where(flip[:, None], -value, value) + 0.0


class _Batch:
    """What the recipes read over a batch of ``n`` poses (one pose: a batch of one)."""

    def __init__(
        self,
        analysis: WrenchAnalysis,
        frames: Mapping[str, tuple[Array, Array]],
        given: dict[str, Array] | None,
    ) -> None:
        one = analysis.single
        self.topology = analysis.topology
        self.rtol = float(analysis.rtol)
        self.table = analysis.table[None] if one else analysis.table
        self.frames = frames
        self.reference_point = np.asarray(analysis.reference_point, dtype=float).reshape(-1, 3)
        self.length_scale = np.asarray(analysis.length_scale, dtype=float).reshape(-1)
        self.count = len(self.length_scale)
        self.given = given
        self.bases: dict[str, tuple[Array, Array]] = {}
        self.lines: dict[str, Array] = {}
        self.axes: dict[str, tuple[Array, Array, Array, Array]] = {}
        self.centres: dict[str, Array] = {}
        rows = np.asarray(analysis.actuation_rows, dtype=float).reshape(self.count, -1, 6)
        serial = np.asarray(analysis.serial, dtype=bool).reshape(self.count, -1)
        self.actuation = {
            f"{ACTUATION}{plan.actuated_joint}": np.where(serial[:, k, None], np.nan, rows[:, k])
            for k, plan in enumerate(self.topology.limbs)
        }

    @classmethod
    def create(
        cls, analysis: WrenchAnalysis, lines: list[Line] | None, points: tuple[DiagramPoint, ...]
    ) -> _Batch:
        frames: Mapping[str, tuple[Array, Array]] = analysis.frames
        if analysis.single:
            frames = {k: (rows[None], np.asarray(order)[None]) for k, (rows, order) in frames.items()}
        missing = [key for key in frames_read(points, analysis.topology) if key not in frames]
        if missing:  # analysed without them (the core's lean pass): the same kernels again, those only
            table = analysis.table[None] if analysis.single else analysis.table
            frames = {**frames, **_frames_kept(table, analysis, missing)}
        given = None if lines is None else {name: np.asarray(w, dtype=float)[None] for name, _, w, _ in lines}
        return cls(analysis, frames, given)

    def nan(self, width: int) -> Array:
        return np.full((self.count, width), np.nan)

    def wrench(self, name: str) -> Array:
        """A line of the mechanism by name, ``(n, 6)``; NaN where it is not one line."""
        if self.given is not None:
            return self.given.get(name, self.nan(6))
        if name in self.actuation:
            return self.actuation[name]
        return self._constraint_line(name)

    def _constraint_line(self, name: str) -> Array:
        """A constraint line (:func:`screwkit.gca.diagram_lines.select_lines`' names): the element
        of its leg's (or the mechanism's) readable basis at each pose, as the per-pose views give
        it (the same frame conversion, over the batch, without building the views)."""
        source = _constraint_source(self.topology, name)
        if source is None:
            return self.nan(6)
        if name not in self.lines:  # a line may be read by several recipes
            prefix, key = source
            bases, orders = self._readable_bases(key)
            out = self.nan(6)
            for order in np.unique(orders):
                names = basis_names(prefix, int(order))
                if name in names:
                    out[orders == order] = bases[orders == order, names.index(name)]
            self.lines[name] = out
        return self.lines[name]

    def _readable_bases(self, key: str) -> tuple[Array, Array]:
        """The readable basis of a system (a frame) at each pose, ``(n, m, 6)`` (NaN after its
        order), and its orders: what the per-pose views give (:func:`readable_bases`)."""
        if key not in self.bases:
            rows, orders = self.frames[key][0], np.asarray(self.frames[key][1]).astype(int)
            moved = F.from_scaled(rows[:, : orders.max(initial=0)], self.reference_point, self.length_scale)
            found = readable_bases(moved, orders, rtol=self.rtol, length_scale=self.length_scale)
            self.bases[key] = (found, orders)
        return self.bases[key]

    def joint_screws(self, name: str) -> Array:
        """``(n, dof_j, 6)``."""
        return np.asarray(self.table.joint_screws(name), dtype=float)

    def centre(self, name: str) -> Array:
        """:func:`_joint_centres` of a joint over the batch, ``(n, 3)`` (once per joint: the couples'
        sides, the actuation lines' rods and the ``centre`` points read the same joints)."""
        if name not in self.centres:
            self.centres[name] = _joint_centres(self.joint_screws(name))
        return self.centres[name]

    def scaled_axes(self, name: str) -> tuple[Array, Array, Array, Array]:
        """:func:`_scaled_axes` of a joint's first axis over the batch (once per joint: two lines
        may meet it)."""
        if name not in self.axes:
            self.axes[name] = _scaled_axes(self.joint_screws(name)[:, 0], self.length_scale[:, None])
        return self.axes[name]


def _frames_kept(
    table: JointTable, analysis: WrenchAnalysis, keys: list[str]
) -> dict[str, tuple[Array, Array]]:
    """The per-pose frames ``keys`` of an analysis that did not keep them (the same core, lean,
    keeping those)."""
    length = analysis.length_scale  # given back: the same lengths, the same bits
    again = analyze_table(
        table, dof=analysis.dof, rtol=analysis.rtol, length_scale=length, views=False, kept=lambda _: keys
    )
    return {key: again.frames[key] for key in keys}


def _constraint_source(top: Topology, name: str) -> tuple[str, str] | None:
    """The system a constraint line's name is read from: its names' prefix and its frame's key
    (a compound leg's ``leg{k}:W``, else the mechanism's ``constraint``); None for other names."""
    legs = () if top.network else range(len(top.legs))
    sources = [(f"constraint of the {leg_name(top, k)}", f"leg{k}:W") for k in legs]
    sources.append(("constraint wrench", "constraint"))
    return next(((prefix, key) for prefix, key in sources if name.startswith(prefix)), None)


def _branches(top: Topology, first: str, second: str) -> tuple[tuple[int, ...], list[str]] | None:
    """The branches (child nodes) of the first parallel node below the root's parallel level that
    holds a branch named ``first`` and one named ``second`` (a branch is named by its first
    actuated joint, else its first joint), with their names; None if there is none."""
    if top.network or top.root is None:
        return None
    actuated = set(top.actuated)

    def name(index: int) -> str:
        joints = top.nodes[index].joints
        return (sorted(j for j in joints if j in actuated) or sorted(joints))[0]

    def nested(index: int, outer: bool) -> list[int]:  # parallel nodes below the first one
        node = top.nodes[index]
        found = [index] if node.kind == "parallel" and not outer else []
        return found + [
            k for child in node.children for k in nested(child, outer and node.kind != "parallel")
        ]

    for index in nested(top.root, True):
        children = top.nodes[index].children
        names = [name(c) for c in children]
        if first in names and second in names:
            return children, names
    return None


def _branches_read(names: list[str], first: str, second: str) -> list[int]:
    """The branches whose constraint couples :func:`_branch_pair` reads, by position: the two
    named and those between them (where a couple between would part them)."""
    a, b = names.index(first), names.index(second)
    return [a, b, *range(a + 1, b)]


def _lines_read(key: tuple[str, ...]) -> list[str]:
    """The names of the mechanism's lines a recipe (:attr:`DiagramPoint.key`) reads (:func:`_recipe`)."""
    kind = key[0]
    if kind in ("meet", "direction", "foot", "free"):
        return [key[1]]
    if kind == "couples":
        return [key[1], key[2]]
    if kind == "perp":
        return [key[1], *_lines_read(key[2:])]
    return []


def frames_read(points: tuple[DiagramPoint, ...], topology: Topology) -> tuple[str, ...]:
    """The per-pose frames of an analysis that the points' recipes read (by their key in
    :attr:`screwkit.core.wrench_systems.WrenchAnalysis.frames`): what a lean pass keeps
    (``kept`` of :func:`screwkit.core.wrench_systems.analyze_table`) so that
    :func:`batch_diagram_points` needs no second pass.

    The constraint lines' systems (a compound leg's ``"leg{k}:W"``, the mechanism's
    ``"constraint"``) and the twist frames ``"node{i}"`` of the branches whose constraint couples
    the ``normals`` recipes cross; actuation lines and joint axes need none.

    Parameters
    ----------
    points : tuple of DiagramPoint
        A diagram's points (their recipes).
    topology : Topology
        The topology the analysis runs on (``analysis.topology``, or the argument ``kept`` is called with).

    Returns
    -------
    tuple of str
        Without repeats, in the order the recipes read them.

    Examples
    --------
    >>> from screwkit.core.wrench_systems import analyze_table
    >>> delta = load_mechanism("delta")
    >>> diagram, _ = delta.wrench_diagram()
    >>> analysis = analyze_table(delta.joints([[0, 0, -800]]), views=False)
    >>> frames_read(diagram.points, analysis.topology)
    ('leg0:W', 'leg1:W', 'leg2:W')
    """
    return _frames_read(points, topology)


@functools.lru_cache(maxsize=64)
def _frames_read(points: tuple[DiagramPoint, ...], topology: Topology) -> tuple[str, ...]:
    """:func:`frames_read`, once per diagram and topology (asked for every chunk of a map)."""
    keys: list[str] = []
    for point in points:
        if point.key[0] == "normals":
            found = _branches(topology, point.key[1], point.key[2])
            if found is not None:
                children, names = found
                keys += [f"node{children[k]}" for k in _branches_read(names, point.key[1], point.key[2])]
        for name in _lines_read(point.key):
            source = _constraint_source(topology, name)
            if source is not None:
                keys.append(source[1])
    return tuple(dict.fromkeys(keys))


def _branch_pair(batch: _Batch, first: str, second: str) -> Array:
    """``n(first) × n(second)`` over the batch (the ``normals`` recipe of
    :mod:`screwkit.gca.diagram_recipes`), NaN where the two branches are not consecutive single
    constraint couples of one parallel node there.

    A branch's constraint couple is the reciprocal of its twist system (the core's frame kernel
    ``reciprocal``) where that has order 1 and infinite pitch; its moment's direction ``n`` is
    frame- and unit-free, taken unit and oriented by the branch's joints (:func:`_couple_sides`).
    The cross product keeps its magnitude (the sine of the angle between the two couples): paper
    002's ``s_m^12 = n^1 × n^2`` (Eq. 6), which vanishes where the two couples are parallel (its
    case (c)); a unit direction would not.
    """
    found = _branches(batch.topology, first, second)
    if found is None:
        return batch.nan(3)
    children, names = found
    a, b = names.index(first), names.index(second)
    moments, couple = {}, {}
    for k in _branches_read(names, first, second):
        rows, order = F.reciprocal(*batch.frames[f"node{children[k]}"])  # the core's kernel, scaled frame
        wrench = rows[:, 0]
        moments[k] = _units(wrench[:, 3:])
        size = np.linalg.norm(wrench, axis=-1)
        couple[k] = (order == 1) & (np.linalg.norm(wrench[:, :3], axis=-1) <= B.DEFAULT_RTOL * size)
    between = np.zeros(batch.count, dtype=bool)
    for k in range(a + 1, b):
        between |= couple[k]
    ok = couple[a] & couple[b] & ~between
    n_a, n_b = (_couple_sides(batch, batch.topology.nodes[children[k]].joints, moments[k]) for k in (a, b))
    return np.where(ok[:, None], B.cross(n_a, n_b), np.nan)


def _couple_sides(batch: _Batch, joints: tuple[str, ...], moment: Array) -> Array:
    """A branch's unit couple moments ``(n, 3)`` with a sign that follows the branch's joints over
    the motion: that of the normal ``(c_2 − c_1) × (c_3 − c_1)`` of the plane through the centres of
    its first three joints that have one (spherical, universal: by name), e.g. a parallelogram's
    plane, to which its couple is normal (paper 002 §5.1: ``n^i`` normal to the plane ``Π_i``).
    Where the branch has no such three centres, or their plane's normal is not along the couple
    (|cos| < 1/2), the canonical sign (first clearly non-zero component positive): continuous up
    to sign only."""
    centred = [j for j in sorted(joints) if batch.joint_screws(j).shape[1] >= 2][:3]
    if len(centred) < 3:
        return _canonical_directions(moment)
    c1, c2, c3 = (batch.centre(j) for j in centred)
    normal = B.cross(c2 - c1, c3 - c1)
    along = np.einsum("...i,...i", moment, normal)  # |n| = 1: along² ≥ |normal|² / 4 is |cos| ≥ 1/2
    with np.errstate(invalid="ignore"):
        clear = along**2 >= 0.25 * np.einsum("...i,...i", normal, normal)
        oriented = np.sign(along)[:, None] * moment
    return oriented if clear.all() else np.where(clear[:, None], oriented, _canonical_directions(moment))


def _actuation_sides(batch: _Batch, name: str) -> Array:
    """An actuation line's unit direction ``(n, 3)`` with a sign that follows its limb's joints over
    the motion (NaN where the line is not one, e.g. at the limb's serial singularity).

    Two rules, per pose. Along a rod: where two centred joints of the limb (spherical, universal)
    joined by one link (the first's child the second's parent, e.g. a parallelogram's rod or a
    Delta's distal rod) have centres on a line parallel to the wrench, the direction from the first
    centre to the second (the rod's length is constant, so this never vanishes). Else: the sign
    making the wrench do positive work on its actuated joint's twist, the reciprocal product
    ``w ∘ $_a = f·v + m·ω > 0`` (Ball's virtual coefficient, Hunt, *Kinematic Geometry of
    Mechanisms*, §4), which vanishes only where the actuated joint's twist is reciprocal to it,
    the limb's serial singularity.
    """
    wrench = batch.wrench(name)
    joint = name[len(ACTUATION):]
    direction = _units(wrench[:, :3])
    actuated = batch.joint_screws(joint)[:, 0]
    work = np.einsum("...i,...i", wrench[:, :3], actuated[:, 3:]) + np.einsum(
        "...i,...i", wrench[:, 3:], actuated[:, :3]
    )
    with np.errstate(invalid="ignore"):
        side = np.sign(work)
        found = np.zeros(len(side), dtype=bool)  # (the first rod along the line decides: a
        for first, second in _rods(batch, joint):  # parallelogram's two rods agree)
            rod = batch.centre(second) - batch.centre(first)
            along = np.einsum("...i,...i", rod, direction)
            parallel = np.linalg.norm(B.cross(_units(rod), direction), axis=-1) <= INCIDENCE_RTOL
            decides = parallel & (along != 0) & ~found
            side, found = np.where(decides, np.sign(along), side), found | decides
            if found.all():
                break
    return np.where((side != 0)[:, None], side[:, None] * direction, np.nan)


def _rods(batch: _Batch, actuated: str) -> list[tuple[str, str]]:
    """The pairs of centred joints (two or more axes) of the actuated joint's limb joined by one
    link, the first's child being the second's parent (base to platform), in table order."""
    limb = next((plan for plan in batch.topology.limbs if plan.actuated_joint == actuated), None)
    if limb is None:
        return []
    specs = {spec.name: spec for spec in batch.table.specs}
    centred = [j for j in limb.joints if batch.joint_screws(j).shape[1] >= 2]
    return [(a, b) for a in centred for b in centred if specs[a].child == specs[b].parent]


def _recipe(key: tuple[str, ...], batch: _Batch, cache: dict[tuple[str, ...], Array]) -> Array:
    """One recipe (:attr:`DiagramPoint.key`) over the batch, ``(n, 4)``, NaN where it has no point."""
    if key in cache:
        return cache[key]
    kind = key[0]
    value: Array
    if kind == "meet":
        value = _meet(batch.wrench(key[1]), batch.scaled_axes(key[2]), batch.length_scale[:, None])
    elif kind == "direction" and _joint_carried(key):
        value = _infinite(_actuation_sides(batch, key[1]))
    elif kind == "direction":
        value = _infinite(_canonical_directions(batch.wrench(key[1])[:, :3]))
    elif kind == "axis":
        name, index = (key[1], "") if key[1] in {s.name for s in batch.table.specs} else axis_key(key[1])
        screw = batch.joint_screws(name)[:, int(index) - 1 if index else 0]
        value = _infinite(_canonical_directions(screw[:, :3]))
    elif kind == "normals":  # oriented and scaled by the branches' couples: no canonical sign, no unit
        value = _infinite(_branch_pair(batch, key[1], key[2]))
    elif kind == "foot":  # nearest the reference point: frame-covariant
        nearest, direction = _finite_axes(batch.wrench(key[1]))
        offset = batch.reference_point - nearest
        along = np.einsum("...i,...i", offset, direction) / np.einsum("...i,...i", direction, direction)
        value = _finite(nearest + direction * along[:, None])
    elif kind == "centre":
        value = _finite(batch.centre(key[1]))
    elif kind == "couples":
        first, second = batch.wrench(key[1])[:, 3:], batch.wrench(key[2])[:, 3:]
        cross = B.cross(_units(first), _units(second))
        # two couple lines that coincide here meet everywhere along it: any point of it will do
        with np.errstate(invalid="ignore"):
            apart = np.linalg.norm(cross, axis=-1) >= INCIDENCE_RTOL
        meet = cross if apart.all() else np.where(apart[:, None], cross, _free(first)[0])
        value = _infinite(_canonical_directions(meet))
    elif kind == "free":
        value = _infinite(_free(batch.wrench(key[1])[:, 3:])[int(key[2]) - 1])
    elif kind == "perp":
        moment = batch.wrench(key[1])[:, 3:]
        cross = B.cross(moment, _units(_recipe(key[2:], batch, cache)[:, :3]))
        with np.errstate(invalid="ignore"):
            small = ~(np.linalg.norm(cross, axis=-1) >= INCIDENCE_RTOL * np.linalg.norm(moment, axis=-1))
        value = np.where(small[:, None], np.nan, _infinite(_canonical_directions(cross)))
    else:
        value = batch.nan(4)
    value = np.where(np.isfinite(value).all(axis=-1, keepdims=True), value, np.nan)
    cache[key] = value
    return value
