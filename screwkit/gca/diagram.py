"""Wrench diagrams: the global wrench system as six projective lines through twelve labelled points.

Paper 002 §5.1 builds the H4's diagram by hand (Fig. 4c): each actuation force is a finite line,
given by the point where it meets a known axis and its point at infinity; each constraint couple is
a line at infinity, given by two infinite points chosen to expose structure (the direction common to
two parallelogram planes, the direction of the vertical axes shared by both couples). This module
makes the same choices automatically, from a :class:`~screwkit.core.wrench_systems.WrenchAnalysis`
(this module holds the diagram's values, :class:`WrenchDiagram` and :class:`DiagramPoint`; the
stages that make and use them are the modules named below):

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
recipes are chosen at a *generic* configuration of the mechanism
(:func:`~screwkit.gca.diagram_placement.generic_reference`:
random workspace poses of a catalog robot, or configurations reached by moving any twist graph
along its own mobility, :mod:`screwkit.core.motion`) and evaluated at the pose
(:func:`~screwkit.gca.diagram_placement.diagram_at`), so
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
>>> from screwkit.core.wrenches import wrench_analysis
>>> from screwkit.gca.diagram_recipes import wrench_diagram
>>> diagram = wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph()))
>>> diagram.line_text()
'[ab, cd, ef, gh, ij, kj]'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError

__all__ = [
    "FINITE_KINDS",
    "INCIDENCE_RTOL",
    "DiagramPoint",
    "WrenchDiagram",
    "axis_key",
    "require_instance",
]

Array = np.ndarray
#: Relative tolerance of the incidence decisions made while choosing points.
INCIDENCE_RTOL = 1e-7
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
    orientation : tuple of float, optional
        For a point at infinity: its direction at the diagram's reference configuration
        (:func:`screwkit.gca.diagram_placement.generic_reference`). A direction is a projective
        point, defined up to sign; the diagram's points are carried with the sign that makes a
        positive dot product with this one, so a condition's value is a continuous function of the
        pose and changes sign only at its zeros (where the direction stays within 90° of the
        reference's). None: the sign of the first clearly non-zero component. Not used by a
        ``normals`` point or an actuation line's direction, which the joints orient (see ``sign``).
    sign : int, default 1
        For a ``normals`` point ``n_a × n_b``, carried continuously with its magnitude (each couple
        oriented by its branch's joints), and an actuation line's direction (oriented by its limb's
        joints, :func:`screwkit.gca.diagram_points._actuation_sides`): the constant ±1 it is
        multiplied by, fixed once so that at the reference configuration its first clearly
        non-zero component is positive.
    """

    label: str
    key: tuple[str, ...]
    at_infinity: bool
    description: str
    orientation: tuple[float, ...] | None = field(default=None, compare=False)
    sign: int = field(default=1, compare=False)


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
        ``{label: (x, y, z, w)}`` at this pose, finite points of weight 1, directions unit
        (a ``normals`` point: ``n_a × n_b`` of unit couples, its magnitude kept).
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
        """The superbracket's argument, e.g. ``'[ab, cd, ef, gh, ij, kj]'``.

        Returns
        -------
        str
        """
        return "[" + ", ".join("".join(line) for line in self.lines) + "]"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description.

        Returns
        -------
        dict
            Strings, numbers, lists and dicts only (``json.dumps`` takes it).
        """
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

    def __repr__(self) -> str:
        infinite = f", {len(self.infinite)} at infinity" if self.infinite else ""
        degenerate = f"; degenerate here: {'; '.join(self.degenerate)}" if self.degenerate else ""
        return f"WrenchDiagram({self.line_text()}: {len(self.points)} points{infinite}{degenerate})"

    def __str__(self) -> str:
        rows = [f"wrench diagram {self.line_text()}"]
        for line, name in zip(self.lines, self.line_names, strict=True):
            rows.append(f"  {''.join(line)}: {name}")
        for point in self.points:
            rows.append(f"  {point.label}: {point.description}")
        rows += [f"  degenerate here: {reason}" for reason in self.degenerate]
        return "\n".join(rows)



def axis_key(text: str) -> tuple[str, str]:
    """The joint and axis an ``("axis", text)`` recipe names.

    Parameters
    ----------
    text : str
        ``"R1"`` (a one-freedom joint) or ``"U/1/2"`` (axis 2 of the U joint named ``"U/1"``).

    Returns
    -------
    (str, str)
        The joint's name and the axis number (``""`` for a one-freedom joint).

    Examples
    --------
    >>> axis_key("U/1/2"), axis_key("R1")
    (('U/1', '2'), ('R1', ''))
    """
    name, _, index = text.rpartition("/")
    return (name, index) if index in ("1", "2") and name else (text, "")


def require_instance(value: Any, kind: type, name: str) -> None:
    """Refuse an argument of the wrong type, naming it (the diagram's stages need analysis objects).

    Parameters
    ----------
    value : object
    kind : type
        The expected type.
    name : str
        The argument's name, for the message.

    Returns
    -------
    None

    Raises
    ------
    ScrewkitTypeError
        If ``value`` is not a ``kind``.

    Examples
    --------
    >>> require_instance("h4", WrenchDiagram, "diagram")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitTypeError: Expected `diagram` to be a WrenchDiagram, got str.
    """
    if not isinstance(value, kind):
        raise ScrewkitTypeError(f"Expected `{name}` to be a {kind.__name__}, got {type(value).__name__}.")
