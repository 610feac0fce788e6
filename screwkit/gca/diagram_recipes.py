"""Choosing a wrench diagram at a configuration: the point recipes of each line and the labels
(:func:`wrench_diagram`; the rules are in :mod:`screwkit.gca.diagram`'s docstring).

Examples
--------
>>> from screwkit.core.wrenches import wrench_analysis
>>> wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph())).line_text()
'[ab, cd, ef, gh, ij, kj]'
"""

from __future__ import annotations

import itertools
import string
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..algebra import screw as S
from ..algebra.incidence import point_on_line
from ..core.wrench_systems import WrenchAnalysis
from ..exceptions import DegenerateGeometryError
from ..graphs.reduction import SeriesParallelNode
from .diagram import FINITE_KINDS, INCIDENCE_RTOL, DiagramPoint, WrenchDiagram, axis_key, require_instance
from .diagram_incidence import joint_centre, meet_points
from .diagram_lines import Line, select_lines
from .diagram_points import diagram_points

__all__ = [
    "wrench_diagram",
]

Array = np.ndarray


def _unit(v: Array) -> Array:
    return v / np.linalg.norm(v)


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


def wrench_diagram(analysis: WrenchAnalysis) -> WrenchDiagram:
    """Build the wrench diagram of a mechanism at its pose (the rules: :mod:`screwkit.gca.diagram`).

    Parameters
    ----------
    analysis : WrenchAnalysis

    Returns
    -------
    WrenchDiagram
        With ``degenerate`` reasons where the representation fails at this pose.

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> diagram = wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
    >>> [p.description for p in diagram.points][:2]
    ['where the actuation A1 meets the axis of R_I', 'the point at infinity of the actuation A1']
    """
    require_instance(analysis, WrenchAnalysis, "analysis")
    lines, problems = select_lines(analysis)
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
                known[key] = joint_centre(joint.screws)
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
        if np.isfinite(meet_points(wrench, screw, np.asarray(analysis.length_scale, dtype=float))).all()
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



def _describe(key: tuple[str, ...], normals: Mapping[tuple[str, str], tuple[Array, str]]) -> str:
    kind = key[0]
    if kind == "meet":
        return f"where the {key[1]} meets the axis of {key[2]}"
    if kind == "direction":
        return f"the point at infinity of the {key[1]}"
    if kind == "axis":
        name, index = axis_key(key[1])
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

