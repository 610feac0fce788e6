"""Wrench diagrams: the global wrench system as six projective lines through twelve labelled points.

Paper 002 §5.1 builds the H4's diagram by hand (Fig. 4c): each actuation force is a finite line,
given by the point where it meets a known axis and its point at infinity; each constraint couple is
a line at infinity, given by two infinite points chosen to expose structure (the direction common to
two parallelogram planes, the direction of the vertical axes shared by both couples). This module
makes the same choices automatically, from a :class:`~screwkit.wrenches.WrenchAnalysis`:

* **lines**: the actuation wrenches grouped by compound leg (the legs in the order of their first
  actuated joint), then the compound legs' constraint wrenches (paper 002 Eq. 4);
* **points on a finite line**: where it meets the axis of a one-freedom joint of its compound leg
  (the joint nearest the platform first), and its point at infinity;
* **points on a line at infinity** (a couple ``(0; m)``): the direction common to the constraint
  couples of two parallel branches inside its compound leg (e.g. ``n1 × n4``), then a joint-axis
  direction lying on it, preferring one shared with another couple line (a shared point);
* **labels** ``a, b, c, …`` in line order, a shared point keeping its first label.

Each point is a *recipe* with a meaning (``DiagramPoint.key``): the same recipe evaluated at other
poses of the same mechanism gives the random configurations on which structural zeros are confirmed
(gca.md §6). Where a recipe has no point at this pose (a force parallel to the axis it should meet,
a cross product that vanishes, a compound leg whose constraint system is not one line), the diagram
says so in ``degenerate`` (gca.md §7) and no factorization is claimed for it.

Examples
--------
>>> from screwkit.catalog import load_mechanism
>>> from screwkit.wrenches import wrench_analysis
>>> diagram = wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
>>> diagram.line_text()
'[ab, cd, ef, gh, ij, kj]'
"""

from __future__ import annotations

import itertools
import string
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import projective as P
from . import screw as S
from .conditions import Condition, conditions
from .exceptions import DegenerateGeometryError, ScrewkitValueError
from .gca import Simplification, simplify_superbracket
from .twistgraph import SeriesParallelNode
from .wrenches import WrenchAnalysis

__all__ = [
    "DiagramPoint",
    "SuperbracketAnalysis",
    "WrenchDiagram",
    "diagram_points",
    "superbracket_analysis",
    "wrench_diagram",
]

Array = np.ndarray
#: Relative tolerance of the incidence decisions made while choosing points.
INCIDENCE_RTOL = 1e-7


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

    @property
    def constraint_labels(self) -> frozenset[str]:
        """Labels of the points on constraint lines."""
        return frozenset(
            x for line, role in zip(self.lines, self.roles, strict=True) if role == "constraint" for x in line
        )

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


def _canonical_direction(v: Array) -> Array:
    """A unit direction with a fixed sign (first clearly non-zero component positive)."""
    u = _unit(v)
    k = int(np.argmax(np.abs(u) > 1e-9))
    return -u if u[k] < 0 else u


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
                cross = np.cross(_unit(m1), _unit(m2))
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


def _meet_point(line: Array, screw: Array, length_scale: float) -> Array | None:
    """Where a finite line meets a joint axis, or None when they are skew or parallel."""
    axis = S.line(screw[:3], S.axis(screw)[0])
    if not P.lines_intersect(line, axis, rtol=INCIDENCE_RTOL, length_scale=length_scale):
        return None
    if np.linalg.norm(np.cross(_unit(line[:3]), _unit(axis[:3]))) < INCIDENCE_RTOL:
        return None
    normal = np.cross(line[:3], axis[:3])
    plane = P.plane(np.cross(normal, axis[:3]), S.axis(axis)[0])  # contains the axis, ⟂ the common plane
    point = P.meet_line_plane(line, plane, allow_infinite=True)
    return None if abs(point[3]) < 1e-12 else point / point[3]


def _lines_and_roles(
    analysis: WrenchAnalysis,
) -> tuple[list[tuple[str, str, Array, tuple[str, ...]]], list[str]]:
    """(name, role, wrench, leg joints) of the six lines, and reasons the selection fails."""
    problems: list[str] = []
    lines: list[tuple[str, str, Array, tuple[str, ...]]] = []
    legs = _legs(analysis)
    limbs = {limb.actuated_joint: limb for limb in analysis.limbs}
    for _, joints, _ in legs:
        for name in sorted(j for j in limbs if j in joints):
            wrench = limbs[name].actuation_wrench
            if wrench is None:
                problems.append(f"the limb of {name} is at a serial singularity: it has no actuation wrench")
                continue
            lines.append((f"actuation {name}", "actuation", wrench, joints))
    for leg_name, joints, wrenches in legs:
        if wrenches.order != 1:
            problems.append(
                f"the constraint system of the {leg_name} has order {wrenches.order}, not 1: "
                "its wrench is not one line here"
            )
            continue
        lines.append(
            (f"constraint of the leg through {leg_name}", "constraint", wrenches.readable_basis()[0], joints)
        )
    if not legs:
        for wrench in analysis.constraint_wrenches.readable_basis():
            lines.append(("constraint", "constraint", wrench, tuple(analysis.graph.edges(keys=True))))
    if len(lines) != 6 and not problems:
        problems.append(f"the global wrench system has {len(lines)} generators, not 6")
    for name, _, wrench, _ in lines:
        finite = not S.is_infinite_pitch(wrench, rtol=1e-7, length_scale=analysis.length_scale)
        if finite and not S.is_zero_pitch(wrench, rtol=1e-7, length_scale=analysis.length_scale):
            problems.append(f"the {name} wrench has pitch {S.pitch(wrench):.4g}: it is not a line")
    return lines, problems


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
    >>> from screwkit.catalog import load_mechanism
    >>> from screwkit.wrenches import wrench_analysis
    >>> diagram = wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
    >>> [p.description for p in diagram.points][:2]
    ['where the actuation A1 meets the axis of R_I', 'the point at infinity of the actuation A1']
    """
    lines, problems = _lines_and_roles(analysis)
    normals = _branch_normals(analysis)
    couple_lines = [
        w for _, _, w, _ in lines if S.is_infinite_pitch(w, rtol=1e-7, length_scale=analysis.length_scale)
    ]
    axes_everywhere = _single_freedom_axes(analysis, tuple(k for _, _, k in analysis.graph.edges(keys=True)))
    recipes: list[tuple[tuple[str, ...], tuple[str, ...]]] = []
    names, roles = [], []
    for index, (name, role, wrench, joints) in enumerate(lines):
        line_id = f"L{index + 1}"
        names.append(name)
        roles.append(role)
        if not S.is_infinite_pitch(wrench, rtol=1e-7, length_scale=analysis.length_scale):
            meet = next(
                (
                    ("meet", name, key)
                    for key, screw in _single_freedom_axes(analysis, joints)
                    if _meet_point(wrench, screw, analysis.length_scale) is not None
                ),
                ("foot", name),
            )
            recipes.append((meet, ("direction", name)))
            continue
        moment = _unit(wrench[3:])
        own = [
            ("normals", a, b)
            for (a, b), (d, _) in normals.items()
            if set((a, b)) <= set(joints) and abs(_unit(d) @ moment) < INCIDENCE_RTOL
        ]
        shared = sorted(
            (
                ("axis", key)
                for key, screw in axes_everywhere
                if abs(_unit(screw[:3]) @ moment) < INCIDENCE_RTOL
            ),
            key=lambda k: (
                -sum(
                    abs(_unit(_key_direction(k, analysis)) @ _unit(c[3:])) < INCIDENCE_RTOL
                    for c in couple_lines
                )
            ),
        )
        choice = (own + shared)[:2]
        if len(choice) < 2:
            problems.append(f"line {line_id} ({name}): fewer than two structural points at infinity found")
            recipes.append((("couple", name, "1"), ("couple", name, "2")))
        else:
            recipes.append((choice[0], choice[1]))
    labels: dict[tuple[str, ...], str] = {}
    letters = iter(string.ascii_lowercase)
    for pair in recipes:
        for key in pair:
            if key not in labels:
                labels[key] = next(letters)
    points = tuple(
        DiagramPoint(label, key, key[0] not in ("meet", "foot"), _describe(key, normals))
        for key, label in labels.items()
    )
    diagram_lines = tuple((labels[a], labels[b]) for a, b in recipes)
    coordinates: dict[str, Array] = {}
    try:
        coordinates = diagram_points(points, analysis, lines=lines)
    except DegenerateGeometryError as err:
        problems.append(str(err))
    return WrenchDiagram(points, diagram_lines, tuple(names), tuple(roles), coordinates, tuple(problems))


def _key_direction(key: tuple[str, ...], analysis: WrenchAnalysis) -> Array:
    screw = analysis.graph.edges[_edge(analysis, key[1])]["joint"].screws[0]
    return screw[:3]


def _describe(key: tuple[str, ...], normals: Mapping[tuple[str, str], tuple[Array, str]]) -> str:
    kind = key[0]
    if kind == "meet":
        return f"where the {key[1]} meets the axis of {key[2]}"
    if kind == "direction":
        return f"the point at infinity of the {key[1]}"
    if kind == "axis":
        return f"the point at infinity of the axis of {key[1]}"
    if kind == "normals":
        return f"the point at infinity of {normals[(key[1], key[2])][1]}"
    if kind == "foot":
        return f"the point of the {key[1]} nearest the mechanism's reference point"
    return f"a point at infinity of the {key[1]} (no structural choice)"


def diagram_points(
    points: tuple[DiagramPoint, ...],
    analysis: WrenchAnalysis,
    *,
    lines: list[tuple[str, str, Array, tuple[str, ...]]] | None = None,
) -> dict[str, Array]:
    """Evaluate the points' recipes on an analysis of the same mechanism (at any pose).

    Raises
    ------
    DegenerateGeometryError
        Naming the point whose recipe has no point at this pose.

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> from screwkit.wrenches import wrench_analysis
    >>> h4 = load_mechanism("h4")
    >>> diagram = wrench_diagram(wrench_analysis(h4.twist_graph()))
    >>> moved = diagram_points(diagram.points, wrench_analysis(h4.twist_graph([50.0, 0, -700.0, 0.3])))
    >>> moved["j"]
    array([0., 0., 1., 0.])
    """
    if lines is None:
        lines = _lines_and_roles(analysis)[0]
    by_name = {name: wrench for name, _, wrench, _ in lines}
    normals = _branch_normals(analysis)
    coordinates = {}
    for point in points:
        key, kind = point.key, point.key[0]
        value: Array | None
        if kind == "meet" and key[1] in by_name:
            value = _meet_point(
                by_name[key[1]],
                analysis.graph.edges[_edge(analysis, key[2])]["joint"].screws[0],
                analysis.length_scale,
            )
        elif kind == "direction" and key[1] in by_name:
            value = np.append(_canonical_direction(by_name[key[1]][:3]), 0.0)
        elif kind == "axis":
            value = np.append(_canonical_direction(_key_direction(key, analysis)), 0.0)
        elif kind == "normals" and (key[1], key[2]) in normals:
            direction = normals[(key[1], key[2])][0]
            value = (
                None
                if np.linalg.norm(direction) < INCIDENCE_RTOL
                else np.append(_canonical_direction(direction), 0.0)
            )
        elif kind == "foot" and key[1] in by_name:
            value = np.append(S.axis(by_name[key[1]])[0], 1.0)
        else:
            value = None
        if value is None:
            raise DegenerateGeometryError(
                f"point {point.label} ({point.description}) does not exist at this pose"
            )
        coordinates[point.label] = value
    return coordinates


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
        Per condition: ``"constraint"`` when its factor involves only points of constraint lines
        (paper 002 §5.3, condition 1), else ``"actuation"``.
    values : tuple of float
        Each condition's vector form at the diagram's pose.
    collinear : tuple of str
        Triples of labels found collinear on every sample (declared to the factoring step).
    """

    diagram: WrenchDiagram
    simplification: Simplification
    conditions: tuple[Condition, ...]
    labels: tuple[str, ...]
    values: tuple[float, ...]
    collinear: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "superbracket": self.diagram.line_text(),
            "simplification": self.simplification.to_dict(),
            "conditions": [
                {**c.to_dict(), "label": label, "value_at_pose": value}
                for c, label, value in zip(self.conditions, self.labels, self.values, strict=True)
            ],
        }


def superbracket_analysis(
    diagram: WrenchDiagram,
    sampler: Callable[[np.random.Generator], Mapping[str, Array]],
    *,
    n_samples: int = 10,
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
        (:meth:`screwkit.catalog.Mechanism.wrench_diagram`), on which zeros are confirmed.
    n_samples : int, default 10
        Configurations that decide structural zeros (a bracket polynomial that is not identically
        zero on the incidence variety vanishes at a random configuration with probability 0), and
        as many fresh ones for the checks; drawn once and shared by both orderings.
    rng : int, default 0

    Raises
    ------
    ScrewkitValueError
        If the diagram is degenerate at its pose (its reasons are given).

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> diagram, sampler = load_mechanism("h4").wrench_diagram()
    >>> result = superbracket_analysis(diagram, sampler)
    >>> str(result.simplification.factored), result.labels
    ('-[gikj][a b d ḟ][c g ḣ j]', ('constraint', 'actuation'))
    """
    if diagram.degenerate:
        raise ScrewkitValueError(
            "The wrench diagram is degenerate at this pose, so no factorization is claimed: "
            + "; ".join(diagram.degenerate)
        )
    generator = np.random.default_rng(rng)
    drawn = [dict(sampler(generator)) for _ in range(2 * n_samples)]

    def replay() -> Callable[[np.random.Generator], Mapping[str, Array]]:
        iterator = iter(drawn)
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
    found = conditions(simplification.factored, finite=diagram.finite, infinite=diagram.infinite)
    constraint = diagram.constraint_labels
    labels = tuple("constraint" if set(c.vectors) <= constraint else "actuation" for c in found)
    values = tuple(float(c.evaluate(diagram.coordinates)) for c in found)
    return SuperbracketAnalysis(diagram, simplification, found, labels, values, collinear)


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
    return bool(size > 0 and np.linalg.norm(np.cross(u, v)) <= INCIDENCE_RTOL * size)
