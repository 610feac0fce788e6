"""Wrench diagrams: the global wrench system as six projective lines through twelve labelled points.

Paper 002 §5.1 builds the H4's diagram by hand (Fig. 4c): each actuation force is a finite line,
given by the point where it meets a known axis and its point at infinity; each constraint couple is
a line at infinity, given by two infinite points chosen to expose structure (the direction common to
two parallelogram planes, the direction of the vertical axes shared by both couples). This module
makes the same choices automatically, from a :class:`~screwkit.core.wrench_systems.WrenchAnalysis`:

* **lines**: the actuation wrenches grouped by compound leg (the legs in the order of their
  names), then a *line basis* of the mechanism's constraint system ``W^c`` taken from the compound
  legs' own constraint lines (paper 002 Eqs. 3–4): a leg line is kept when it raises the rank, so
  legs whose constraint systems overlap (an overconstrained mechanism, a planar one) give one line
  per dimension of ``W^c``, each named after the leg it comes from;
* **points on a finite line**: joint centres on it, where it meets the axis of a one-freedom joint
  of its compound leg (the joint nearest the platform first), else its point nearest the reference
  point; and its point at infinity (shared with a joint axis parallel to it);
* **points on a line at infinity** (a couple ``(0; m)``): the direction common to the constraint
  couples of two parallel branches inside its compound leg (e.g. ``n1 × n4``), then the most shared
  of: joint-axis directions lying on it, directions of the diagram's finite lines, and the points
  where it meets the other couple lines (``m × m'``);
* **labels** ``a, b, c, …`` in line order, a shared point keeping its first label.

Each line and each point is a *recipe* with a meaning (a line's name, ``DiagramPoint.key``). The
recipes are chosen at a *generic* configuration of the mechanism (:func:`generic_reference`:
random workspace poses of a catalog robot, or configurations reached by moving any twist graph
along its own mobility, :mod:`screwkit.core.motion`) and evaluated at the pose (:func:`diagram_at`), so
what is decided (which lines, which shared points) never depends on a special pose: where two
lines coincide at the pose (the H4's two constraint couples at a constraint singularity) both are
still there, and the factor that vanishes is valued. The same recipes at further generic
configurations give the samples on which structural zeros are decided (gca.md §6). Where a recipe
has no value at the pose (a limb at a serial singularity, a leg whose constraint system changes
order), ``degenerate`` says so (gca.md §7); where the mechanism has no diagram at all (a global
wrench system of order below 6 everywhere, a constraint system not spanned by lines), the reasons
found at generic configurations say so, as properties of the mechanism.

Examples
--------
>>> from screwkit.robots.catalog import load_mechanism
>>> from screwkit.core.wrenches import wrench_analysis
>>> diagram = wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
>>> diagram.line_text()
'[ab, cd, ef, gh, ij, kj]'
"""

from __future__ import annotations

import itertools
import string
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..algebra import backend as B
from ..algebra import projective as P
from ..algebra import screw as S
from ..algebra.incidence import point_on_line
from ..algebra.ranks import screw_rank
from ..algebra.screwsystem import ScrewSystem
from ..algebra.screwvalue import Screw
from ..core import _frames as F
from ..core.wrench_systems import WrenchAnalysis, analyze_table
from ..core.wrenches import wrench_analysis
from ..exceptions import (
    DegenerateGeometryError,
    ScrewkitError,
    ScrewkitTypeError,
    ScrewkitValueError,
)
from ..graphs.jointtable import JointTable
from ..graphs.reduction import SeriesParallelNode
from ..graphs.topology import Topology
from . import Simplification, simplify_superbracket

if TYPE_CHECKING:  # conditions are sympy expressions: that module (and sympy) loads on first use
    from .conditions import Condition

__all__ = [
    "DiagramPoint",
    "ReplaySampler",
    "SuperbracketAnalysis",
    "WrenchDiagram",
    "batch_diagram_points",
    "diagram_at",
    "diagram_points",
    "generic_reference",
    "graph_diagram",
    "graph_sampler",
    "superbracket_analysis",
    "wrench_diagram",
]

Array = np.ndarray
#: Relative tolerance of the incidence decisions made while choosing points.
INCIDENCE_RTOL = 1e-7
#: A condition vanishes at the pose when its value there is at most this times its median size on
#: the generic samples (:attr:`SuperbracketAnalysis.vanishing`).
VANISHING_RTOL = 1e-7
#: Recipes that give finite points (every other recipe gives a point at infinity).
FINITE_KINDS = ("meet", "foot", "centre")


@dataclass(frozen=True)
class DiagramPoint:
    """A labelled point of a wrench diagram and the recipe that defines it.

    Attributes
    ----------
    label : str
    key : tuple
        The recipe: ``("meet", line, joint)``, ``("direction", line)``, ``("axis", joint)``,
        ``("normals", branch, branch)`` or ``("foot", line)``.
    at_infinity : bool
    description : str
    """

    label: str
    key: tuple[str, ...]
    at_infinity: bool
    description: str


@dataclass(frozen=True, eq=False)
class WrenchDiagram:
    """Six wrench lines as pairs of labelled points (see the module docstring).

    Attributes
    ----------
    points : tuple of DiagramPoint
    lines : tuple of six (label, label)
    line_names : tuple of str
        ``"actuation A1"``, ``"constraint of the leg through A1, A4"``, ...
    roles : tuple of str
        ``"actuation"`` or ``"constraint"`` per line.
    coordinates : dict
        ``{label: (x, y, z, w)}`` at this pose, finite points of weight 1, directions unit.
    degenerate : tuple of str
        Why the representation fails at this pose (empty when it holds).
    """

    points: tuple[DiagramPoint, ...]
    lines: tuple[tuple[str, str], ...]
    line_names: tuple[str, ...]
    roles: tuple[str, ...]
    coordinates: dict[str, Array]
    degenerate: tuple[str, ...]

    @property
    def finite(self) -> tuple[str, ...]:
        """Labels of the finite points."""
        return tuple(p.label for p in self.points if not p.at_infinity)

    @property
    def infinite(self) -> tuple[str, ...]:
        """Labels of the points at infinity."""
        return tuple(p.label for p in self.points if p.at_infinity)

    def line_text(self) -> str:
        """The superbracket's argument, e.g. ``'[ab, cd, ef, gh, ij, kj]'``."""
        return "[" + ", ".join("".join(line) for line in self.lines) + "]"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description."""
        return {
            "lines": ["".join(line) for line in self.lines],
            "line_names": list(self.line_names),
            "roles": list(self.roles),
            "points": [
                {
                    "label": p.label,
                    "at_infinity": p.at_infinity,
                    "description": p.description,
                    "coordinates": self.coordinates[p.label].tolist()
                    if p.label in self.coordinates
                    else None,
                }
                for p in self.points
            ],
            "degenerate": list(self.degenerate),
        }

    def __str__(self) -> str:
        rows = [f"wrench diagram {self.line_text()}"]
        for line, name in zip(self.lines, self.line_names, strict=True):
            rows.append(f"  {''.join(line)}: {name}")
        for point in self.points:
            rows.append(f"  {point.label}: {point.description}")
        rows += [f"  degenerate here: {reason}" for reason in self.degenerate]
        return "\n".join(rows)


# building blocks ---------------------------------------------------------------------------------
def _unit(v: Array) -> Array:
    return v / np.linalg.norm(v)


def _legs(analysis: WrenchAnalysis) -> list[tuple[str, tuple[str, ...], Any]]:
    """(name, joints, constraint system) of each compound leg, in the order of their names."""
    legs = [(leg.name, leg.joints, leg.constraint_wrenches) for leg in analysis.compound_legs]
    return sorted(legs, key=lambda item: item[0])


def _branch_normals(analysis: WrenchAnalysis) -> dict[tuple[str, str], tuple[Array, str]]:
    """Directions common to the single-couple constraint systems of parallel branches."""
    tree = analysis.tree
    if tree is None:
        return {}
    found: dict[tuple[str, str], tuple[Array, str]] = {}

    def name(node: SeriesParallelNode) -> str:
        actuated = sorted(
            j for j in node.joints if analysis.graph.edges[_edge(analysis, j)]["joint"].actuated
        )
        return actuated[0] if actuated else sorted(node.joints)[0]

    def visit(node: SeriesParallelNode, top: bool) -> None:
        if node.kind == "parallel" and not top:
            couples = []
            for child in node.children:
                wrenches = child.system.reciprocal()
                if wrenches.order == 1 and S.is_infinite_pitch(
                    wrenches.basis[0], length_scale=analysis.length_scale
                ):
                    couples.append((name(child), wrenches.basis[0, 3:]))
            for (first, m1), (second, m2) in itertools.pairwise(couples):
                cross = B.cross(_unit(m1), _unit(m2))
                found[(first, second)] = (
                    cross,
                    f"n({first}) × n({second}), the direction common to the planes "
                    f"normal to the constraint couples of the branches through "
                    f"{first} and {second}",
                )
        for child in node.children:
            visit(child, top and node.kind != "parallel")

    visit(tree, True)
    return found


def _edge(analysis: WrenchAnalysis, joint: str) -> tuple[Any, Any, str]:
    return next((u, v, k) for u, v, k in analysis.graph.edges(keys=True) if k == joint)


def _single_freedom_axes(analysis: WrenchAnalysis, joints: tuple[str, ...]) -> list[tuple[str, Array]]:
    """Finite-pitch one-freedom joints of a leg as (name, screw), nearest the platform first."""
    platform = analysis.graph.graph["platform"]
    axes = []
    for u, v, key, joint in analysis.graph.edges(keys=True, data="joint"):
        if (
            key in joints
            and joint.dof == 1
            and not joint.actuated
            and not S.is_infinite_pitch(joint.screws[0], length_scale=analysis.length_scale)
        ):
            axes.append((0 if platform in (u, v) else 1, key, joint.screws[0]))
    return [(key, screw) for _, key, screw in sorted(axes, key=lambda item: (item[0], item[1]))]


Line = tuple[str, str, Array, tuple[str, ...]]  # (name, role, wrench, joints of its leg or limb)


def _is_line(wrench: Array, length_scale: float) -> bool:
    """A force (zero pitch) or a couple (infinite pitch): a projective line."""
    return bool(
        S.is_infinite_pitch(wrench, rtol=1e-7, length_scale=length_scale)
        or S.is_zero_pitch(wrench, rtol=1e-7, length_scale=length_scale)
    )


def _candidate_lines(
    analysis: WrenchAnalysis, *, mechanism: bool = True
) -> dict[str, tuple[str, Array | None, tuple[str, ...]]]:
    """Every line a diagram may use, by name, at this pose: ``{name: (role, wrench, joints)}``.

    The actuation wrenches, grouped by compound leg (legs in the order of their names, the limbs of
    a network after them), then each compound leg's constraint lines (its readable basis), then
    (unless ``mechanism`` is False: :func:`_mechanism_lines`, asked for when needed) a readable
    basis of the mechanism's constraint system (for graphs without compound legs). A limb at a
    serial singularity has the wrench None.
    """
    found: dict[str, tuple[str, Array | None, tuple[str, ...]]] = {}
    legs = _legs(analysis)
    limbs = {limb.actuated_joint: limb for limb in analysis.limbs}
    grouped = [name for _, joints, _ in legs for name in sorted(j for j in limbs if j in joints)]
    for name in grouped + [j for j in limbs if j not in grouped]:
        joints = next((joints for _, joints, _ in legs if name in joints), limbs[name].joints)
        found[f"actuation {name}"] = ("actuation", limbs[name].actuation_wrench, joints)
    for leg_name, joints, wrenches in legs:
        basis = wrenches.readable_basis()
        for k, wrench in enumerate(basis):
            suffix = f" ({k + 1})" if len(basis) > 1 else ""
            found[f"constraint of the {leg_name}{suffix}"] = ("constraint", wrench, joints)
    return found | _mechanism_lines(analysis) if mechanism else found


def _mechanism_lines(analysis: WrenchAnalysis) -> dict[str, tuple[str, Array | None, tuple[str, ...]]]:
    """The last candidates of :func:`_candidate_lines`: a readable basis of the mechanism's
    constraint system (a diagram takes them when its legs' lines do not span it)."""
    every_joint = tuple(k for _, _, k in analysis.graph.edges(keys=True))
    return {
        f"constraint wrench {k + 1} of the mechanism": ("constraint", wrench, every_joint)
        for k, wrench in enumerate(analysis.constraint_wrenches.readable_basis())
    }


def _rank(rows: list[Array], analysis: WrenchAnalysis) -> int:
    if not rows:
        return 0
    return int(screw_rank(np.array(rows), rtol=1e-7, length_scale=float(analysis.length_scale)))


def _select_lines(analysis: WrenchAnalysis) -> tuple[list[Line], list[str]]:
    """The six lines of the diagram, chosen at a (generic) configuration, and why there are none.

    Every actuation wrench, then a line basis of the mechanism's constraint system ``W^c`` taken
    from the compound legs' constraint lines in order (a line is kept when it raises the rank: an
    overconstrained mechanism, whose legs' constraint systems overlap, keeps one line per
    dimension of ``W^c``, each named after the leg it comes from; paper 002 Eqs. 3–4), else from a
    readable basis of ``W^c`` itself. The reasons returned describe the mechanism at this
    configuration: at a generic one, they say why it has no diagram at all.
    """
    problems: list[str] = []
    scale = float(analysis.length_scale)
    lines: list[Line] = []
    candidates = _candidate_lines(analysis, mechanism=False)
    for name, (role, wrench, joints) in candidates.items():
        if role != "actuation":
            continue
        if wrench is None:
            problems.append(f"the limb of {name.removeprefix('actuation ')} is at a serial singularity: "
                            "it has no actuation wrench")
        elif not _is_line(wrench, scale):
            problems.append(f"the {name} wrench has pitch {S.pitch(wrench):.4g}: it is not a line")
        else:
            lines.append((name, role, wrench, joints))
    target = int(analysis.constraint_order)
    chosen: list[Line] = []
    for prefix in ("constraint of the ", "constraint wrench "):
        if prefix == "constraint wrench ":
            candidates = _mechanism_lines(analysis)  # the legs' lines do not span W^c
        chosen = []
        for name, (role, wrench, joints) in candidates.items():
            if not name.startswith(prefix) or wrench is None or not _is_line(wrench, scale):
                continue
            if _rank([w for _, _, w, _ in chosen] + [wrench], analysis) > len(chosen):
                chosen.append((name, role, wrench, joints))
            if len(chosen) == target:
                break
        if len(chosen) == target:
            break
    if len(chosen) < target:
        problems.append(
            f"the constraint wrench system (order {target}) is not spanned by lines of its legs: "
            f"only {len(chosen)} independent force or couple lines were found"
        )
    lines += chosen
    if int(analysis.global_order) < 6:
        problems.append(
            f"the global wrench system has order {int(analysis.global_order)}, not 6: with its actuators "
            "locked the platform keeps an uncontrolled twist"
        )
    elif len(lines) != 6 and not problems:
        problems.append(f"the global wrench system has {len(lines)} line generators, not 6")
    return lines, problems


def _lines_at(names: tuple[str, ...], analysis: WrenchAnalysis) -> tuple[list[Line], list[str]]:
    """The lines of a diagram (by name) at another configuration, and what is missing there."""
    candidates = _candidate_lines(analysis, mechanism=any(n.startswith("constraint wrench ") for n in names))
    lines, problems = [], []
    for name in names:
        if name not in candidates:
            problems.append(f"the {name} is not one line here (its leg's constraint system changed order)")
            continue
        role, wrench, joints = candidates[name]
        if wrench is None:
            problems.append(f"the limb of {name.removeprefix('actuation ')} is at a serial singularity here: "
                            "it has no actuation wrench")
            continue
        lines.append((name, role, wrench, joints))
    return lines, problems


def _require(value: Any, kind: type, name: str) -> None:
    """Refuse an argument of the wrong type, naming it (a diagram needs the analysis objects)."""
    if not isinstance(value, kind):
        raise ScrewkitTypeError(f"Expected `{name}` to be a {kind.__name__}, got {type(value).__name__}.")


def wrench_diagram(analysis: WrenchAnalysis) -> WrenchDiagram:
    """Build the wrench diagram of a mechanism at its pose (module docstring).

    Parameters
    ----------
    analysis : WrenchAnalysis

    Returns
    -------
    WrenchDiagram
        With ``degenerate`` reasons where the representation fails at this pose.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> diagram = wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
    >>> [p.description for p in diagram.points][:2]
    ['where the actuation A1 meets the axis of R_I', 'the point at infinity of the actuation A1']
    """
    _require(analysis, WrenchAnalysis, "analysis")
    lines, problems = _select_lines(analysis)
    scale = float(analysis.length_scale)
    normals = _branch_normals(analysis)
    infinite = [S.is_infinite_pitch(w, rtol=1e-7, length_scale=scale) for _, _, w, _ in lines]
    recipes: list[tuple[tuple[str, ...], tuple[str, ...]]] = []
    known: dict[str, Array] = {}  # joint centres, each computed once
    for (name, _, wrench, joints), couple in zip(lines, infinite, strict=True):
        if couple:
            recipes.append(
                _couple_line_recipe(name, wrench, joints, lines, infinite, normals, analysis, recipes)
            )
        else:
            recipes.append(_finite_line_recipe(name, wrench, joints, analysis, recipes, known))
    names = [name for name, _, _, _ in lines]
    roles = [role for _, role, _, _ in lines]
    labels: dict[tuple[str, ...], str] = {}
    aliases: dict[tuple[str, ...], tuple[str, ...]] = {}
    centres = dict(_centres(analysis, tuple(k for _, _, k in analysis.graph.edges(keys=True)), known))
    letters = iter(string.ascii_lowercase)
    for pair in recipes:
        for key in pair:
            if key in labels or key in aliases:
                continue
            twin = next(
                (
                    other
                    for other in labels
                    if key[0] == other[0] == "centre"
                    and np.linalg.norm(centres[key[1]] - centres[other[1]])
                    <= INCIDENCE_RTOL * analysis.length_scale
                ),
                None,
            )
            if twin is not None:
                aliases[key] = twin  # concentric joints (e.g. a 3-2-1 platform's shared sphere centre)
            else:
                labels[key] = next(letters)
    recipes = [(aliases.get(a, a), aliases.get(b, b)) for a, b in recipes]
    points = tuple(
        DiagramPoint(label, key, key[0] not in FINITE_KINDS, _describe(key, normals))
        for key, label in labels.items()
    )
    diagram_lines = tuple((labels[a], labels[b]) for a, b in recipes)
    coordinates: dict[str, Array] = {}
    try:
        coordinates = diagram_points(points, analysis, lines=lines)
    except DegenerateGeometryError as err:
        problems.append(str(err))
    return WrenchDiagram(points, diagram_lines, tuple(names), tuple(roles), coordinates, tuple(problems))


def _all_axes(analysis: WrenchAnalysis) -> list[tuple[str, Array]]:
    """Every structural axis direction: one-freedom joints (``"R1"``) and each axis of a U (``"U1/2"``)."""
    axes = _single_freedom_axes(analysis, tuple(k for _, _, k in analysis.graph.edges(keys=True)))
    for _, _, key, joint in sorted(analysis.graph.edges(keys=True, data="joint"), key=lambda e: str(e[2])):
        if joint.type == "U":
            axes += [(f"{key}/{k + 1}", joint.screws[k]) for k in range(2)]
    return axes


def _distinct_directions(axes: list[tuple[str, Array]]) -> list[tuple[str, Array]]:
    """One joint per axis direction (parallel axes share their point at infinity), in order."""
    kept: list[tuple[str, Array]] = []
    for key, screw in axes:
        if all(
            np.linalg.norm(B.cross(_unit(screw[:3]), _unit(other[:3]))) >= INCIDENCE_RTOL
            for _, other in kept
        ):
            kept.append((key, screw))
    return kept


def _centres(
    analysis: WrenchAnalysis, joints: tuple[str, ...], known: dict[str, Array] | None = None
) -> list[tuple[str, Array]]:
    """(name, centre) of the spherical and universal joints among ``joints`` (``known``: centres
    already computed for this analysis, by name; filled in)."""
    known = {} if known is None else known
    found = []
    for _, _, key, joint in analysis.graph.edges(keys=True, data="joint"):
        if key in joints and joint.type in ("S", "U"):
            if key not in known:
                known[key] = _joint_centre(joint.screws)
            found.append((key, known[key]))
    return sorted(found, key=lambda item: item[0])


def _couple_line_recipe(
    name: str,
    wrench: Array,
    joints: tuple[str, ...],
    lines: list[Line],
    infinite: list[bool],
    normals: Mapping[tuple[str, str], tuple[Array, str]],
    analysis: WrenchAnalysis,
    earlier: list[tuple[tuple[str, ...], tuple[str, ...]]],
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Two points at infinity of a couple line ``(0; m)``: directions normal to ``m``.

    First the direction common to two parallel branches of its own leg (paper 002 §5.1, ``n1 × n4``);
    then, most shared first (the number of the diagram's couple lines through the point, then of
    all its lines, then whether an earlier line already uses it): joint-axis directions (passive,
    then actuated), directions of the diagram's finite lines, and the points where it meets
    another couple line (``m × m'``); with fewer than two of those, a direction normal to ``m``
    and to the one found (``perp``), or two such directions with no structural meaning (``free``).
    """
    moment = _unit(wrench[3:])
    own = [
        ("normals", a, b)
        for (a, b), (d, _) in normals.items()
        if set((a, b)) <= set(joints) and abs(_unit(d) @ moment) < INCIDENCE_RTOL
    ]
    axes = _distinct_directions(_all_axes(analysis) + _actuated_axes(analysis))
    options: list[tuple[tuple[str, ...], Array]] = [(("axis", key), screw[:3]) for key, screw in axes]
    options += [
        (("direction", other), w[:3])
        for (other, _, w, _), inf in zip(lines, infinite, strict=True)
        if not inf
    ]
    position = next(i for i, line in enumerate(lines) if line[0] == name)
    for k, ((other, _, w, _), inf) in enumerate(zip(lines, infinite, strict=True)):
        if inf and k != position:
            pair = (name, other) if position < k else (other, name)
            options.append((("couples", *pair), B.cross(wrench[3:], w[3:])))
    used = {key for pair in earlier for key in pair}

    def through(direction: Array) -> tuple[int, int]:
        """(couple lines, then all lines) of the diagram through the point at infinity ``direction``."""
        d = _unit(direction)
        couples = sum(
            abs(d @ _unit(w[3:])) < INCIDENCE_RTOL
            for (_, _, w, _), inf in zip(lines, infinite, strict=True)
            if inf
        )
        finite = sum(
            np.linalg.norm(B.cross(d, _unit(w[:3]))) < INCIDENCE_RTOL
            for (_, _, w, _), inf in zip(lines, infinite, strict=True)
            if not inf
        )
        return -couples, -(couples + finite)

    on_line = [
        (key, d)
        for key, d in options
        if np.linalg.norm(d) > INCIDENCE_RTOL * max(1.0, float(np.linalg.norm(wrench[3:])))
        and abs(_unit(d) @ moment) < INCIDENCE_RTOL
    ]
    ranked = sorted(
        enumerate(on_line), key=lambda item: (*through(item[1][1]), item[1][0] not in used, item[0])
    )
    chosen: list[tuple[tuple[str, ...], Array | None]] = [(key, None) for key in own]
    directions = [normals[(key[1], key[2])][0] for key in own]
    for _, (key, d) in ranked:
        if all(np.linalg.norm(B.cross(_unit(d), _unit(e))) >= INCIDENCE_RTOL for e in directions):
            chosen.append((key, d))
            directions.append(d)
    keys = [key for key, _ in chosen][:2]
    if len(keys) == 1:
        keys.append(("perp", name, *keys[0]))
    if not keys:
        keys = [("free", name, "1"), ("free", name, "2")]
    return keys[0], keys[1]


def _actuated_axes(analysis: WrenchAnalysis) -> list[tuple[str, Array]]:
    """The axes of actuated one-freedom joints of finite pitch, by name."""
    return sorted(
        (
            (key, joint.screws[0])
            for _, _, key, joint in analysis.graph.edges(keys=True, data="joint")
            if joint.actuated and not S.is_infinite_pitch(joint.screws[0], length_scale=analysis.length_scale)
        ),
        key=lambda item: item[0],
    )


def _finite_line_recipe(
    name: str,
    wrench: Array,
    joints: tuple[str, ...],
    analysis: WrenchAnalysis,
    earlier: list[tuple[tuple[str, ...], tuple[str, ...]]],
    known: dict[str, Array] | None = None,
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Two points of a finite line: joint centres on it (shared ones first), a meet, its direction."""
    used = {key for pair in earlier for key in pair}
    on_line = [
        ("centre", key)
        for key, centre in _centres(analysis, joints, known)
        if point_on_line(
            np.append(centre, 1.0), wrench, rtol=INCIDENCE_RTOL, length_scale=analysis.length_scale
        )
    ]
    on_line.sort(key=lambda key: key not in used)
    meets = [
        ("meet", name, key)
        for key, screw in _single_freedom_axes(analysis, joints)
        if np.isfinite(_meet_points(wrench, screw, np.asarray(analysis.length_scale, dtype=float))).all()
    ]
    direction: tuple[str, ...] = ("direction", name)
    for key, screw in _single_freedom_axes(analysis, tuple(k for _, _, k in analysis.graph.edges(keys=True))):
        if np.linalg.norm(B.cross(_unit(screw[:3]), _unit(wrench[:3]))) < INCIDENCE_RTOL:
            direction = ("axis", key)  # the line is parallel to a joint axis: share that point
            break
    finite = on_line + meets + [("foot", name)]
    if len(on_line) >= 2:
        return on_line[0], on_line[1]
    return finite[0], direction


def diagram_at(reference: WrenchDiagram, analysis: WrenchAnalysis) -> WrenchDiagram:
    """The diagram of ``reference`` (its recipes, labels and lines) at another pose of the mechanism.

    Building a diagram decides which points lines share (parallel axes, concentric joints) at the
    analysed pose; at a special pose a coincidence could pass for structure. Build the reference at
    a generic pose and use this to place it at the pose of interest; where a recipe has no point
    there, or the lines are not the reference's, ``degenerate`` says why.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> h4 = load_mechanism("h4")
    >>> generic = wrench_diagram(wrench_analysis(h4.twist_graph([40.0, -60.0, -700.0, 0.3])))
    >>> diagram_at(generic, wrench_analysis(h4.twist_graph())).line_text()
    '[ab, cd, ef, gh, ij, kj]'
    """
    _require(reference, WrenchDiagram, "reference")
    _require(analysis, WrenchAnalysis, "analysis")
    lines, problems = _lines_at(reference.line_names, analysis)
    coordinates: dict[str, Array] = {}
    if not problems:
        try:
            coordinates = diagram_points(reference.points, analysis, lines=lines)
        except DegenerateGeometryError as err:
            problems.append(str(err))
    if coordinates:  # each line is the join of its two points (the recipes keep their incidences)
        scale = float(analysis.length_scale)
        for (first, second), (name, _, wrench, _) in zip(reference.lines, lines, strict=True):
            join = P.join_unchecked(coordinates[first], coordinates[second])
            if np.linalg.norm(join) <= INCIDENCE_RTOL or not Screw(join).is_equivalent(
                Screw(wrench), rtol=1e-6, length_scale=scale
            ):
                problems.append(f"the points {first}, {second} do not give the {name} here")
    return WrenchDiagram(
        reference.points, reference.lines, reference.line_names, reference.roles, coordinates, tuple(problems)
    )


def _axis_of(text: str) -> tuple[str, str]:
    """``"U/1/2"`` -> ``("U/1", "2")`` (axis 2 of the U joint named ``"U/1"``); ``"R1"`` -> ``("R1", "")``."""
    name, _, index = text.rpartition("/")
    return (name, index) if index in ("1", "2") and name else (text, "")


def _describe(key: tuple[str, ...], normals: Mapping[tuple[str, str], tuple[Array, str]]) -> str:
    kind = key[0]
    if kind == "meet":
        return f"where the {key[1]} meets the axis of {key[2]}"
    if kind == "direction":
        return f"the point at infinity of the {key[1]}"
    if kind == "axis":
        name, index = _axis_of(key[1])
        return f"the point at infinity of the axis of {name}" + (f" (its axis {index})" if index else "")
    if kind == "normals":
        return f"the point at infinity of {normals[(key[1], key[2])][1]}"
    if kind == "foot":
        return f"the point of the {key[1]} nearest the mechanism's reference point"
    if kind == "centre":
        return f"the centre of joint {key[1]}"
    if kind == "couples":
        return f"the point at infinity where the {key[1]} meets the {key[2]}"
    if kind == "perp":
        other = _describe(key[2:], normals).removeprefix("the point at infinity of ")
        return f"the point at infinity normal to the {key[1]}'s moment and to {other}"
    return f"a point at infinity of the {key[1]} (no structural choice)"


def diagram_points(
    points: tuple[DiagramPoint, ...],
    analysis: WrenchAnalysis,
    *,
    lines: list[tuple[str, str, Array, tuple[str, ...]]] | None = None,
) -> dict[str, Array]:
    """Evaluate the points' recipes on an analysis of the same mechanism (at any pose).

    One pose: a batch of one through :func:`batch_diagram_points` (the same arithmetic).

    Raises
    ------
    DegenerateGeometryError
        Naming the point whose recipe has no point at this pose.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.core.wrenches import wrench_analysis
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
    lines: list[tuple[str, str, Array, tuple[str, ...]]] | None = None,
) -> dict[str, Array]:
    """The points' recipes at every pose of a batched analysis, as arrays over the batch.

    Each recipe is evaluated over the leading axis at once from the batched core's arrays: the
    actuation wrenches, the joint screws, the series-parallel nodes' twist frames (the branches'
    constraint couples), the reference point. A constraint line of a leg is an element of its
    readable basis (:meth:`screwkit.algebra.screwsystem.ScrewSystem.readable_basis`), taken pose by pose,
    and only for the points that use one.

    Parameters
    ----------
    points : tuple of DiagramPoint
        A diagram's points (their recipes).
    analysis : WrenchAnalysis
        Of shape ``(n,)`` (or one pose, taken as a batch of one), e.g.
        :func:`screwkit.core.wrench_systems.analyze_table` of a family's joint table.
    lines : list of (name, role, wrench, joints), optional
        At one pose: the only lines the recipes may use (default: every line of the mechanism).

    Returns
    -------
    dict of str to numpy.ndarray, shape (n, 4)
        ``{label: points}``, finite points of weight 1, directions unit; a row of NaN where the
        recipe has no point at that pose.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.core.wrench_systems import analyze_table
    >>> h4 = load_mechanism("h4")
    >>> diagram, _ = h4.wrench_diagram()
    >>> table = h4.joints([[0, 0, -750, 0], [50, 0, -700, 0.3]])
    >>> found = batch_diagram_points(diagram.points, analyze_table(table))
    >>> found["j"]
    array([[0., 0., 1., 0.],
           [0., 0., 1., 0.]])
    """
    batch = _Batch.create(analysis, lines)
    cache: dict[tuple[str, ...], Array] = {}
    return {point.label: _recipe(point.key, batch, cache) for point in points}


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
        self.bases: dict[str, list[Array]] = {}
        rows = np.asarray(analysis.actuation_rows, dtype=float).reshape(self.count, -1, 6)
        serial = np.asarray(analysis.serial, dtype=bool).reshape(self.count, -1)
        self.actuation = {
            f"actuation {plan.actuated_joint}": np.where(serial[:, k, None], np.nan, rows[:, k])
            for k, plan in enumerate(self.topology.limbs)
        }

    @classmethod
    def create(cls, analysis: WrenchAnalysis, lines: list[Line] | None) -> _Batch:
        frames: Mapping[str, tuple[Array, Array]] = analysis.frames
        if "constraint" not in frames:  # analysed without its views: the same kernels again, with them
            table = analysis.table[None] if analysis.single else analysis.table
            frames = _frames_with_views(table, analysis)
        elif analysis.single:
            frames = {k: (rows[None], np.asarray(order)[None]) for k, (rows, order) in frames.items()}
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
        """A constraint line (:func:`_candidate_lines`' names): the element of its leg's (or the
        mechanism's) readable basis at each pose, as the per-pose views give it."""
        sources = [
            (f"constraint of the {_leg_name(self.topology, k)}", f"leg{k}:W")
            for k in range(len(self.topology.legs))
            if not self.topology.network
        ] + [("constraint wrench", "constraint")]
        for prefix, key in sources:
            if not name.startswith(prefix):
                continue
            out = self.nan(6)
            for i, basis in enumerate(self._readable_bases(key)):
                names = _basis_names(prefix, len(basis))
                if name in names:
                    out[i] = basis[names.index(name)]
            return out
        return self.nan(6)

    def _readable_bases(self, key: str) -> list[Array]:
        """The readable basis of a system (a frame) at each pose, as the per-pose views give it."""
        if key not in self.bases:
            rows, orders = self.frames[key]
            self.bases[key] = [
                ScrewSystem.from_independent(
                    F.from_scaled(rows[i, : int(orders[i])], self.reference_point[i], self.length_scale[i]),
                    rtol=self.rtol,
                    length_scale=float(self.length_scale[i]),
                ).readable_basis()
                for i in range(self.count)
            ]
        return self.bases[key]

    def joint_screws(self, name: str) -> Array:
        """``(n, dof_j, 6)``."""
        return np.asarray(self.table.joint_screws(name), dtype=float)


def _frames_with_views(table: JointTable, analysis: WrenchAnalysis) -> dict[str, tuple[Array, Array]]:
    """The per-pose frames of an analysis that kept none (the same core, with its views)."""
    length = analysis.length_scale  # given back: the same lengths, the same bits
    return analyze_table(table, dof=analysis.dof, rtol=analysis.rtol, length_scale=length).frames


def _leg_name(topology: Topology, k: int) -> str:
    """The name of the k-th compound leg (:attr:`screwkit.core.wrench_systems.CompoundLeg.name`)."""
    node = topology.nodes[topology.legs[k]]
    actuated = sorted(j for j in node.joints if j in set(topology.actuated))
    return "leg through " + ", ".join(actuated or sorted(node.joints)[:2])


def _basis_names(prefix: str, count: int) -> list[str]:
    """The names of the lines of a readable basis of ``count`` screws (:func:`_candidate_lines`):
    ``"constraint of the leg through A1, A4"``, ``"… (2)"``; ``"constraint wrench 1 of the mechanism"``."""
    if prefix == "constraint wrench":
        return [f"constraint wrench {k + 1} of the mechanism" for k in range(count)]
    return [prefix + (f" ({k + 1})" if count > 1 else "") for k in range(count)]


def _finite(points: Array) -> Array:
    return np.concatenate([points, np.ones((*points.shape[:-1], 1))], axis=-1)


def _infinite(directions: Array) -> Array:
    return np.concatenate([directions, np.zeros((*directions.shape[:-1], 1))], axis=-1)


def _units(v: Array) -> Array:
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _canonical_directions(v: Array) -> Array:
    """Unit directions ``(..., 3)`` with a fixed sign (first clearly non-zero component positive)."""
    u = _units(v)
    k = np.argmax(np.abs(u) > 1e-9, axis=-1)[..., None]
    return np.where(np.take_along_axis(u, k, axis=-1) < 0, -u, u)


def _free(moment: Array) -> tuple[Array, Array]:
    """Two unit directions ``(..., 3)`` normal to ``moment`` and to each other (the coordinate axis
    least aligned with it first): points of the couple line ``(0; moment)`` with no structural
    meaning."""
    m = _units(moment)
    axis = np.eye(3)[np.argmin(np.nan_to_num(np.abs(m), nan=0.0), axis=-1)]
    first = _units(B.cross(m, axis))
    return first, B.cross(m, first)


def _finite_axes(screws: Array) -> tuple[Array, Array]:
    """:func:`screwkit.algebra.screw.axis` over a batch ``(..., 6)``, NaN where the pitch is infinite
    (``s = 0``) or the screw is missing (NaN)."""
    bad = ~np.isfinite(screws).all(axis=-1) | np.all(screws[..., :3] == 0, axis=-1)
    safe = np.where(bad[..., None], np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]), screws)
    point, direction = S.axis(safe)
    return np.where(bad[..., None], np.nan, point), np.where(bad[..., None], np.nan, direction)


def _axis_lines(screws: Array) -> tuple[Array, Array]:
    """The axes ``(s; r × s)`` of screws ``(..., 6)`` and their points ``r`` nearest the origin."""
    nearest, _ = _finite_axes(screws)
    return np.concatenate([screws[..., :3], B.cross(nearest, screws[..., :3])], axis=-1), nearest


def _meet_plane_through_axis(line: Array, axis: Array, origin: Array) -> tuple[Array, Array]:
    """Where lines ``(..., 6)`` meet the planes that contain the axes ``(..., 6)`` (through their
    points ``origin``) and are normal to the planes of line and axis: ``(n × m − δ s, n·s)``
    (:func:`screwkit.algebra.projective.meet_line_plane`), and where the line lies in that plane instead."""
    normal = B.cross(B.cross(line[..., :3], axis[..., :3]), axis[..., :3])
    plane = np.concatenate([normal, -np.einsum("...i,...i", normal, origin)[..., None]], axis=-1)
    s, m, delta = line[..., :3], line[..., 3:], plane[..., 3:]
    point = np.concatenate(
        [B.cross(normal, m) - delta * s, np.einsum("...i,...i", normal, s)[..., None]], axis=-1
    )
    size = np.linalg.norm(line, axis=-1) * np.linalg.norm(plane, axis=-1)
    with np.errstate(invalid="ignore"):
        in_plane = np.all(normal == 0, axis=-1) | (np.linalg.norm(point, axis=-1) <= B.DEFAULT_RTOL * size)
    return point, in_plane


def _meet_points(line: Array, screw: Array, length_scale: Array) -> Array:
    """Where finite lines ``(..., 6)`` meet joint axes ``(..., 6)``: ``(..., 4)`` of weight 1, NaN
    where they are skew, parallel or meet at infinity.

    The line meets the plane that contains the axis and is normal to the plane of both; they meet
    when ``L ∘ A = 0`` after scaling moments by ``length_scale``
    (:func:`screwkit.algebra.incidence.lines_intersect`).
    """
    axis, origin = _axis_lines(screw)
    length = np.asarray(length_scale, dtype=float)[..., None]

    def scaled(rows: Array) -> Array:
        return _units(np.concatenate([rows[..., :3], rows[..., 3:] / length], axis=-1))

    a, b = scaled(line), scaled(axis)
    product = np.einsum("...i,...i", a[..., :3], b[..., 3:]) + np.einsum("...i,...i", a[..., 3:], b[..., :3])
    cross = B.cross(_units(line[..., :3]), _units(axis[..., :3]))
    parallel = np.linalg.norm(cross, axis=-1) < INCIDENCE_RTOL
    # the meet in lengths divided by length_scale: the test of a line lying in the plane compares
    # the point with a product of two moments, not invariant under a change of unit otherwise (a
    # 1 m mechanism written in picometres lost every meet point)
    line, axis = (np.concatenate([rows[..., :3], rows[..., 3:] / length], axis=-1) for rows in (line, axis))
    point, in_plane = _meet_plane_through_axis(line, axis, origin / length)
    with np.errstate(invalid="ignore"):
        skew = ~(np.abs(product) <= INCIDENCE_RTOL)
        missing = skew | parallel | in_plane | ~(np.abs(point[..., 3]) >= 1e-12)
    with np.errstate(invalid="ignore", divide="ignore"):
        meet = point / point[..., 3:]
    meet = np.concatenate([meet[..., :3] * length, meet[..., 3:]], axis=-1)
    return np.where(missing[..., None], np.nan, meet)


def _joint_centres(screws: Array) -> Array:
    """The common point ``(..., 3)`` of joints' first two axes ``(..., k, 6)`` (a spherical or
    universal joint's centre), NaN where they are parallel (no single point)."""
    first, _ = _axis_lines(screws[..., 0, :])
    second, origin = _axis_lines(screws[..., 1, :])
    point, in_plane = _meet_plane_through_axis(first, second, origin)
    with np.errstate(invalid="ignore"):
        missing = in_plane | (np.abs(point[..., 3]) <= B.DEFAULT_RTOL * np.linalg.norm(point, axis=-1))
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(missing[..., None], np.nan, point[..., :3] / point[..., 3:])


def _joint_centre(screws: Array) -> Array:
    """:func:`_joint_centres` of one joint ``(k, 6)``, raising where its axes give no point."""
    centre = _joint_centres(np.asarray(screws, dtype=float)[None])[0]
    if not np.isfinite(centre).all():
        raise DegenerateGeometryError(
            "Expected the joint's first two axes to meet at one point, got parallel axes."
        )
    return centre


def _branch_pair(batch: _Batch, first: str, second: str) -> Array:
    """``n(first) × n(second)`` over the batch (``_branch_normals``' recipe, NaN where the two
    branches are not consecutive single constraint couples of one parallel node there).

    A branch's constraint couple is the reciprocal of its twist system (the core's frame kernel,
    :func:`screwkit.core._frames.reciprocal`) where that has order 1 and infinite pitch; its moment's
    direction is frame- and unit-free.
    """
    top = batch.topology
    if top.network or top.root is None:
        return batch.nan(3)
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
        if first not in names or second not in names:
            continue
        moments, couple = [], []
        for child in children:
            rows, order = F.reciprocal(*batch.frames[f"node{child}"])  # the core's kernel, scaled frame
            wrench = rows[:, 0]
            moments.append(_units(wrench[:, 3:]))
            size = np.linalg.norm(wrench, axis=-1)
            couple.append((order == 1) & (np.linalg.norm(wrench[:, :3], axis=-1) <= B.DEFAULT_RTOL * size))
        a, b = names.index(first), names.index(second)
        between = np.zeros(batch.count, dtype=bool)
        for k in range(a + 1, b):
            between |= couple[k]
        ok = couple[a] & couple[b] & ~between
        return np.where(ok[:, None], B.cross(moments[a], moments[b]), np.nan)
    return batch.nan(3)


def _recipe(key: tuple[str, ...], batch: _Batch, cache: dict[tuple[str, ...], Array]) -> Array:
    """One recipe (:attr:`DiagramPoint.key`) over the batch, ``(n, 4)``, NaN where it has no point."""
    if key in cache:
        return cache[key]
    kind = key[0]
    value: Array
    if kind == "meet":
        value = _meet_points(batch.wrench(key[1]), batch.joint_screws(key[2])[:, 0], batch.length_scale)
    elif kind == "direction":
        value = _infinite(_canonical_directions(batch.wrench(key[1])[:, :3]))
    elif kind == "axis":
        name, index = (key[1], "") if key[1] in {s.name for s in batch.table.specs} else _axis_of(key[1])
        screw = batch.joint_screws(name)[:, int(index) - 1 if index else 0]
        value = _infinite(_canonical_directions(screw[:, :3]))
    elif kind == "normals":
        direction = _branch_pair(batch, key[1], key[2])
        with np.errstate(invalid="ignore"):
            small = ~(np.linalg.norm(direction, axis=-1) >= INCIDENCE_RTOL)
        value = np.where(small[:, None], np.nan, _infinite(_canonical_directions(direction)))
    elif kind == "foot":  # nearest the reference point: frame-covariant
        nearest, direction = _finite_axes(batch.wrench(key[1]))
        offset = batch.reference_point - nearest
        along = np.einsum("...i,...i", offset, direction) / np.einsum("...i,...i", direction, direction)
        value = _finite(nearest + direction * along[:, None])
    elif kind == "centre":
        value = _finite(_joint_centres(batch.joint_screws(key[1])))
    elif kind == "couples":
        first, second = batch.wrench(key[1])[:, 3:], batch.wrench(key[2])[:, 3:]
        cross = B.cross(_units(first), _units(second))
        # two couple lines that coincide here meet everywhere along it: any point of it will do
        with np.errstate(invalid="ignore"):
            apart = np.linalg.norm(cross, axis=-1) >= INCIDENCE_RTOL
        value = _infinite(_canonical_directions(np.where(apart[:, None], cross, _free(first)[0])))
    elif kind == "free":
        value = _infinite(_free(batch.wrench(key[1])[:, 3:])[int(key[2]) - 1])
    elif kind == "perp":
        moment = batch.wrench(key[1])[:, 3:]
        cross = B.cross(moment, _recipe(key[2:], batch, cache)[:, :3])
        with np.errstate(invalid="ignore"):
            small = ~(np.linalg.norm(cross, axis=-1) >= INCIDENCE_RTOL * np.linalg.norm(moment, axis=-1))
        value = np.where(small[:, None], np.nan, _infinite(_canonical_directions(cross)))
    else:
        value = batch.nan(4)
    value = np.where(np.isfinite(value).all(axis=-1, keepdims=True), value, np.nan)
    cache[key] = value
    return value


#: Generic configurations whose diagrams are tried before a mechanism is said to have none.
REFERENCE_TRIES = 3


def generic_reference(
    analyses: Sequence[WrenchAnalysis],
) -> tuple[WrenchDiagram | None, tuple[str, ...]]:
    """The diagram of a mechanism at a generic configuration, or why the mechanism has none.

    The lines (a line basis of the wrench system, with the legs they come from) and the points
    they share are chosen at generic configurations, never at the analysed one: the first of
    ``analyses`` (random configurations of the same mechanism) whose diagram holds is returned.
    When none of the first :data:`REFERENCE_TRIES` does, the reasons found at the first are
    properties of the mechanism (a global wrench system of order below 6 everywhere, a constraint
    system not spanned by lines, ...) and are returned with ``None``.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> arm = twist_graph("ground", "hand", [  # two freedoms, one actuator
    ...     ("ground", "link", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("link", "hand", revolute("B", [0, 0, 1], [1, 0, 0]))], dof=2)
    >>> reference, reasons = generic_reference([wrench_analysis(arm)])
    >>> reference is None, reasons[0].split(": ")[1]
    (True, 'the global wrench system has order 5, not 6')
    """
    first: tuple[str, ...] = ()
    for analysis in analyses[:REFERENCE_TRIES]:
        try:
            candidate = wrench_diagram(analysis)
        except ScrewkitError as err:  # e.g. a joint whose centre is not defined
            first = first or (str(err),)
            continue
        if not candidate.degenerate:
            return candidate, ()
        first = first or candidate.degenerate
    if not analyses:
        return None, ("no generic configuration of the mechanism could be reached to choose its diagram",)
    tried = min(len(analyses), REFERENCE_TRIES)
    return None, tuple(
        f"the mechanism has no wrench diagram (at {tried} generic configurations): {reason}"
        for reason in first
    )


class ReplaySampler:
    """``rng -> {label: point}`` handing out samples produced a batch at a time (the ``rng``
    argument is unused: the samples come from their own seeded stream).

    Parameters
    ----------
    produce : callable
        ``rng -> iterable of {label: point}``: a batch of a diagram's points at generic
        configurations; read one sample at a time, so a lazy producer evaluates only those asked for.

    Examples
    --------
    >>> sampler = ReplaySampler(lambda rng: [{"a": k} for k in range(2)])
    >>> [sampler(None), sampler(None), sampler(None)]
    [{'a': 0}, {'a': 1}, {'a': 0}]
    """

    def __init__(self, produce: Callable[[np.random.Generator], Iterable[dict[str, Array]]]):
        self.produce, self.stream = produce, np.random.default_rng(0)
        self.drawn: Iterator[dict[str, Array]] = iter(())

    def __call__(self, rng: np.random.Generator) -> dict[str, Array]:
        sample = next(self.drawn, None)
        if sample is None:
            self.drawn = iter(self.produce(self.stream))
            sample = next(self.drawn, None)
        if sample is None:
            raise ScrewkitValueError("Expected the diagram's sampler to produce a sample, got none.")
        return sample


def graph_diagram(
    analysis: WrenchAnalysis, *, rng: int = 2026, samples: int = 24, length_scale: float | None = None
) -> tuple[WrenchDiagram, Callable[[np.random.Generator], dict[str, Array]] | None]:
    """The wrench diagram of a twist graph's mechanism at its configuration, and a generic sampler.

    Generic configurations come from the mechanism itself: it is moved along its own mobility and
    its loops are closed again (:func:`screwkit.core.motion.generic_configurations`), so a snapshot or
    a graph built in Python is treated like a catalog robot: the diagram is chosen at a generic
    configuration (:func:`generic_reference`) and placed at this one (:func:`diagram_at`); the
    sampler hands out its points at further generic configurations, ``samples`` at a time
    (analysed as one batch), on which structural zeros are decided. A given ``length_scale`` is
    the generic configurations' too (:func:`~screwkit.core.wrench_systems.analyze_table`; default: derived).

    Returns
    -------
    diagram : WrenchDiagram
        With the mechanism's reasons in ``degenerate`` when it has no diagram.
    sampler : callable or None
        None when there is no diagram.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> diagram, sampler = graph_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
    >>> diagram.line_text(), len(sampler(np.random.default_rng(0)))
    ('[ab, cd, ef, gh, ij, kj]', 11)
    """
    from ..core.mobility import generic_analyses

    graph = analysis.graph
    try:
        analyses = generic_analyses(
            graph, np.random.default_rng(rng), REFERENCE_TRIES, rtol=analysis.rtol, length_scale=length_scale
        )
        reference, reasons = generic_reference(analyses)
    except ScrewkitError as err:
        reference, reasons = None, (f"no generic configuration of the mechanism: {err}",)
    if reference is None:
        return replace(wrench_diagram(analysis), coordinates={}, degenerate=reasons), None
    diagram = diagram_at(reference, analysis)

    def produce(stream: np.random.Generator) -> Iterator[dict[str, Array]]:
        found = 0
        for one in generic_analyses(graph, stream, samples, rtol=analysis.rtol, length_scale=length_scale):
            try:
                sample = diagram_points(diagram.points, one)
            except ScrewkitError:
                continue
            found += 1
            yield sample
        if not found:
            raise ScrewkitValueError(
                f"Expected a generic configuration giving every diagram point, got none of {samples}."
            )

    return diagram, ReplaySampler(produce)


def graph_sampler(
    points: tuple[DiagramPoint, ...],
    build: Callable[[np.random.Generator], Any],
    *,
    attempts: int = 50,
) -> Callable[[np.random.Generator], dict[str, Array]]:
    """A sampler of a diagram's points at random configurations of the same mechanism.

    Parameters
    ----------
    points : tuple of DiagramPoint
        A diagram's points (their recipes).
    build : callable
        ``rng -> twist graph`` of the same mechanism (same joint names) at a random configuration;
        it may raise a :class:`~screwkit.exceptions.ScrewkitError` for configurations it cannot
        build (e.g. out of reach), which are skipped.
    attempts : int, default 50
        Configurations tried before giving up.

    Returns
    -------
    callable
        ``rng -> {label: point}``, for :func:`superbracket_analysis`.

    Raises
    ------
    ScrewkitValueError
        (when called) if no configuration of ``attempts`` gives every point.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> h4 = load_mechanism("h4")
    >>> diagram = wrench_diagram(wrench_analysis(h4.twist_graph()))
    >>> sampler = graph_sampler(diagram.points, lambda rng: h4.twist_graph(h4.random_poses(rng, 1)[0]))
    >>> len(sampler(np.random.default_rng(0)))
    11
    """

    def sampler(rng: np.random.Generator) -> dict[str, Array]:
        for _ in range(attempts):
            try:
                analysis = wrench_analysis(build(rng))
                assert isinstance(analysis, WrenchAnalysis)  # numeric graphs (a symbolic one is generic)
                return diagram_points(points, analysis)
            except ScrewkitError:
                continue
        raise ScrewkitValueError(
            f"Expected a configuration giving every diagram point, got none in {attempts}."
        )

    return sampler


# the superbracket pipeline -----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SuperbracketAnalysis:
    """The simplified superbracket of a diagram and its factors as labelled conditions.

    Attributes
    ----------
    diagram : WrenchDiagram
    simplification : Simplification
    conditions : tuple of Condition
    labels : tuple of str
        Per condition: ``"constraint"``, ``"actuation"`` or ``"constraint or actuation"``, from the
        roles of the lines whose points its vector form uses (:func:`screwkit.gca.conditions.label`;
        the evidence is in each condition's ``evidence``).
    values : tuple of float
        Each condition's vector form at the diagram's pose.
    collinear : tuple of str
        Triples of labels found collinear on every sample (declared to the factoring step).
    vanishing : tuple of bool
        Per condition: True when it vanishes at the pose, i.e. its value there is at most
        :data:`VANISHING_RTOL` times its median size on the generic samples (a singular pose keeps
        the factored form of a regular one; these factors are the ones that vanish).
    constant : tuple of bool
        Per condition: True when it takes one non-zero magnitude (within :data:`INCIDENCE_RTOL`) on
        every generic sample and at the pose: a structural factor of this mechanism that never vanishes
        (e.g. the planar mechanisms' constraint couples and force, the same lines at every pose),
        reported as such rather than as a singularity condition.
    """

    diagram: WrenchDiagram
    simplification: Simplification
    conditions: tuple[Condition, ...]
    labels: tuple[str, ...]
    values: tuple[float, ...]
    collinear: tuple[str, ...] = ()
    vanishing: tuple[bool, ...] = ()
    constant: tuple[bool, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "superbracket": self.diagram.line_text(),
            "simplification": self.simplification.to_dict(),
            "conditions": [
                {
                    **c.to_dict(),
                    "label": label,
                    "value_at_pose": value,
                    "vanishes_at_pose": vanishes,
                    "never_vanishes": constant,
                }
                for c, label, value, vanishes, constant in zip(
                    self.conditions, self.labels, self.values, self.vanishing, self.constant, strict=True
                )
            ],
        }


def superbracket_analysis(
    diagram: WrenchDiagram,
    sampler: Callable[[np.random.Generator], Mapping[str, Array]],
    *,
    n_samples: int = 6,
    rng: int = 0,
) -> SuperbracketAnalysis:
    """Expand, simplify and factor a diagram's superbracket; interpret and label each factor.

    Two orderings are simplified (gca.md §6): the diagram's own (lines grouped by leg, shared
    points last, as in paper 002 Fig. 4c) and the one with the fewest surviving monomials over all
    46 080; the result is the one whose factored form has the fewest terms (then the fewest
    monomials), i.e. the most factors to interpret. Both are checked stage by stage against the
    6×6 determinant on fresh configurations.

    Parameters
    ----------
    diagram : WrenchDiagram
        A diagram whose representation holds at its pose.
    sampler : callable
        ``rng -> {label: point}``: the diagram's recipes at random poses of the same mechanism
        (:meth:`screwkit.robots.mechanism.Mechanism.wrench_diagram`), on which zeros are confirmed.
    n_samples : int, default 6
        Configurations that decide structural zeros (a bracket polynomial that is not identically
        zero on the incidence variety vanishes at a random configuration with probability 0, so
        one would already decide; six guard against a configuration near a singularity), and as
        many fresh ones for the checks; drawn once and shared by both orderings.
    rng : int, default 0

    Raises
    ------
    ScrewkitValueError
        If the diagram is degenerate at its pose (its reasons are given).

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> diagram, sampler = load_mechanism("h4").wrench_diagram()
    >>> result = superbracket_analysis(diagram, sampler)
    >>> str(result.simplification.factored), result.labels
    ('-[gikj][a b d ḟ][c g ḣ j]', ('constraint', 'actuation'))
    """
    _require(diagram, WrenchDiagram, "diagram")
    if not callable(sampler):
        raise ScrewkitTypeError(f"Expected `sampler` to be callable, got {type(sampler).__name__}.")
    if diagram.degenerate:
        raise ScrewkitValueError(
            "The wrench diagram is degenerate at this pose, so no factorization is claimed: "
            + "; ".join(diagram.degenerate)
        )
    generator = np.random.default_rng(rng)
    drawn = [_centred(sampler(generator)) for _ in range(2 * n_samples)]
    # the zero tests of the expansion compare brackets of homogeneous points (x, 1) with products of
    # their norms, which is not free of the length unit: they get the samples in units of the
    # diagram's own size (one factor for all, diag(1/L, 1/L, 1/L, 1), which multiplies every bracket,
    # hence every monomial of the homogeneous superbracket, by the same L⁻³ and keeps every zero)
    length = _spread(drawn)
    in_lengths = [{k: np.concatenate([p[:3] / length, p[3:]]) for k, p in sample.items()} for sample in drawn]

    def replay() -> Callable[[np.random.Generator], Mapping[str, Array]]:
        iterator = iter(in_lengths)
        return lambda _: next(iterator)

    collinear = _collinear_triples(diagram, drawn)
    candidates = [
        simplify_superbracket(
            diagram.lines,
            replay(),
            finite=diagram.finite,
            infinite=diagram.infinite,
            collinear=collinear,
            n_samples=n_samples,
            search=search,
        )
        for search in (False, True)
    ]
    simplification = min(candidates, key=lambda c: (len(c.factored.rest.terms), len(c.survivors)))
    from .conditions import conditions

    found = conditions(
        simplification.factored,
        finite=diagram.finite,
        infinite=diagram.infinite,
        lines=diagram.lines,
        roles=diagram.roles,
    )
    labels = tuple(c.label for c in found)
    values = tuple(float(c.evaluate(_centred(diagram.coordinates))) for c in found)
    on_samples = [np.array([float(c.evaluate(sample)) for sample in drawn]) for c in found]
    typical = [B.median(np.abs(v)) for v in on_samples]
    vanishing = tuple(abs(v) <= VANISHING_RTOL * size for v, size in zip(values, typical, strict=True))
    # the magnitude: a point at infinity is a direction up to sign, so a structural factor may flip sign
    constant = tuple(
        size > 0
        and bool(np.all(np.abs(np.abs(np.append(sampled, value)) - size) <= INCIDENCE_RTOL * size))
        for sampled, value, size in zip(on_samples, values, typical, strict=True)
    )
    return SuperbracketAnalysis(
        diagram, simplification, found, labels, values, collinear, vanishing, constant
    )


def _centred(points: Mapping[str, Array]) -> dict[str, Array]:
    """The points with the origin moved to the centroid of the finite ones (``(x, w) → (x − w c, w)``,
    points at infinity unchanged). Brackets are 4×4 determinants of homogeneous coordinates, and a
    translation is a unimodular map of them, so every bracket, condition and collinearity keeps its
    value (gca.md §5.1: the values depend on differences of finite points only), while a mechanism
    far from the origin no longer loses digits to the cancellation of large coordinates."""
    finite = [np.asarray(p[:3], dtype=float) / p[3] for p in points.values() if p[3] != 0]
    if not finite:
        return dict(points)
    centre = np.mean(finite, axis=0)
    return {k: np.concatenate([p[:3] - p[3] * centre, p[3:]]) for k, p in points.items()}


def _spread(samples: list[dict[str, Array]]) -> float:
    """The RMS distance of the samples' finite points from their (centred) origin, 1 if none."""
    finite = [p[:3] / p[3] for sample in samples for p in sample.values() if p[3] != 0]
    size = float(np.sqrt(np.mean(np.sum(np.square(finite), axis=-1)))) if finite else 0.0
    return size if np.isfinite(size) and size > 0 else 1.0


def _collinear_triples(diagram: WrenchDiagram, samples: list[dict[str, Array]]) -> tuple[str, ...]:
    """Triples (two finite points, one at infinity) collinear on every sample (e.g. a, c, j in the H4)."""
    found = []
    for first, second in itertools.combinations(diagram.finite, 2):
        for direction in diagram.infinite:
            if all(_parallel(s[second][:3] - s[first][:3], s[direction][:3]) for s in samples):
                found.append(first + second + direction)
    return tuple(found)


def _parallel(u: Array, v: Array) -> bool:
    size = np.linalg.norm(u) * np.linalg.norm(v)
    return bool(size > 0 and np.linalg.norm(B.cross(u, v)) <= INCIDENCE_RTOL * size)
