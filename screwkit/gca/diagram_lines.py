"""The six lines of a wrench diagram: which wrenches of a mechanism are taken, and their names.

Every actuation wrench (grouped by compound leg, the legs in the order of their names), then a
*line basis* of the mechanism's constraint system ``W^c`` taken from the compound legs' own
constraint lines (paper 002 Eqs. 3–4), else from a readable basis of ``W^c`` itself
(:mod:`screwkit.gca.diagram`). A line is a :data:`Line`: ``(name, role, wrench, joints)``.

Examples
--------
>>> from screwkit.core.wrenches import wrench_analysis
>>> lines, problems = select_lines(wrench_analysis(load_mechanism("h4").twist_graph()))
>>> [name for name, _, _, _ in lines][-2:], problems
(['constraint of the leg through A1, A4', 'constraint of the leg through A2, A3'], [])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra import screw as S
from ..algebra.ranks import screw_rank
from ..core.wrench_systems import WrenchAnalysis
from ..graphs.topology import Topology

__all__ = [
    "Line",
    "basis_names",
    "leg_name",
    "lines_at",
    "select_lines",
]

Array = np.ndarray
#: A line of a diagram: ``(name, role, wrench, joints of its leg or limb)``, role ``"actuation"`` or
#: ``"constraint"``, the wrench ``(6,)`` (None for a limb at a serial singularity).
Line = tuple[str, str, Array, tuple[str, ...]]


def _legs(analysis: WrenchAnalysis) -> list[tuple[str, tuple[str, ...], Any]]:
    """(name, joints, constraint system) of each compound leg, in the order of their names."""
    legs = [(leg.name, leg.joints, leg.constraint_wrenches) for leg in analysis.compound_legs]
    return sorted(legs, key=lambda item: item[0])


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
    for name, joints, wrenches in legs:
        basis = wrenches.readable_basis()
        for line, wrench in zip(basis_names(f"constraint of the {name}", len(basis)), basis, strict=True):
            found[line] = ("constraint", wrench, joints)
    return found | _mechanism_lines(analysis) if mechanism else found


def _mechanism_lines(analysis: WrenchAnalysis) -> dict[str, tuple[str, Array | None, tuple[str, ...]]]:
    """The last candidates of :func:`_candidate_lines`: a readable basis of the mechanism's
    constraint system (a diagram takes them when its legs' lines do not span it)."""
    every_joint = tuple(k for _, _, k in analysis.graph.edges(keys=True))
    basis = analysis.constraint_wrenches.readable_basis()
    return {
        line: ("constraint", wrench, every_joint)
        for line, wrench in zip(basis_names("constraint wrench", len(basis)), basis, strict=True)
    }


def _rank(rows: list[Array], analysis: WrenchAnalysis) -> int:
    if not rows:
        return 0
    return int(screw_rank(np.array(rows), rtol=1e-7, length_scale=float(analysis.length_scale)))


def select_lines(analysis: WrenchAnalysis) -> tuple[list[Line], list[str]]:
    """The six lines of the diagram, chosen at a (generic) configuration, and why there are none.

    Every actuation wrench, then a line basis of the mechanism's constraint system ``W^c`` taken
    from the compound legs' constraint lines in order (a line is kept when it raises the rank: an
    overconstrained mechanism, whose legs' constraint systems overlap, keeps one line per
    dimension of ``W^c``, each named after the leg it comes from; paper 002 Eqs. 3–4), else from a
    readable basis of ``W^c`` itself. The reasons returned describe the mechanism at this
    configuration: at a generic one, they say why it has no diagram at all.

    Parameters
    ----------
    analysis : WrenchAnalysis
        One pose of the mechanism (a generic one, to choose a diagram).

    Returns
    -------
    lines : list of Line
        The lines found, actuation lines first (six when the mechanism has a diagram here).
    problems : list of str
        Why the mechanism has no diagram here (empty when it has one).

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> lines, problems = select_lines(wrench_analysis(load_mechanism("h4").twist_graph()))
    >>> [role for _, role, _, _ in lines], problems
    (['actuation', 'actuation', 'actuation', 'actuation', 'constraint', 'constraint'], [])
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


def lines_at(names: tuple[str, ...], analysis: WrenchAnalysis) -> tuple[list[Line], list[str]]:
    """The lines of a diagram (by name) at another configuration, and what is missing there.

    Parameters
    ----------
    names : tuple of str
        The diagram's line names (:attr:`screwkit.gca.diagram.WrenchDiagram.line_names`).
    analysis : WrenchAnalysis
        One pose of the same mechanism.

    Returns
    -------
    lines : list of Line
        The named lines that exist here, in order.
    problems : list of str
        Why a named line is missing here (a limb at a serial singularity, a leg whose constraint
        system changed order).

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> h4 = load_mechanism("h4")
    >>> lines, problems = lines_at(("actuation A1",), wrench_analysis(h4.twist_graph([0, 0, -700.0, 0.2])))
    >>> lines[0][0], problems
    ('actuation A1', [])
    """
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


def leg_name(topology: Topology, k: int) -> str:
    """The name of the k-th compound leg (:attr:`screwkit.core.wrench_systems.CompoundLeg.name`).

    Parameters
    ----------
    topology : Topology
        The mechanism's topology (series-parallel, with compound legs).
    k : int
        The leg's index in ``topology.legs``.

    Returns
    -------
    str
        ``"leg through"`` and its actuated joints (else its first two joints).

    Examples
    --------
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> leg_name(wrench_analysis(load_mechanism("h4").twist_graph()).topology, 0)
    'leg through A2, A3'
    """
    node = topology.nodes[topology.legs[k]]
    actuated = sorted(j for j in node.joints if j in set(topology.actuated))
    return "leg through " + ", ".join(actuated or sorted(node.joints)[:2])


def basis_names(prefix: str, count: int) -> list[str]:
    """The names of the lines of a readable basis of ``count`` screws.

    Parameters
    ----------
    prefix : str
        ``"constraint of the"`` and a leg's name, or ``"constraint wrench"`` (the mechanism's).
    count : int
        The number of screws in the basis.

    Returns
    -------
    list of str
        ``"constraint of the leg through A1, A4"`` (one screw), ``"… (1)"``, ``"… (2)"`` (several);
        ``"constraint wrench 1 of the mechanism"``, ...

    Examples
    --------
    >>> basis_names("constraint of the leg through A1", 2)
    ['constraint of the leg through A1 (1)', 'constraint of the leg through A1 (2)']
    >>> basis_names("constraint wrench", 1)
    ['constraint wrench 1 of the mechanism']
    """
    if prefix == "constraint wrench":
        return [f"constraint wrench {k + 1} of the mechanism" for k in range(count)]
    return [prefix + (f" ({k + 1})" if count > 1 else "") for k in range(count)]

