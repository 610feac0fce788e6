"""What happens when a factor of the superbracket vanishes, decided numerically (:func:`vanishing_kind`).

The global wrench matrix of a mechanism is block structured: its constraint wrenches first, then its
actuation wrenches. When the constraint wrench system contributes its own factor to the determinant
(e.g. Tsai's 3-UPU, whose 6×6 matrix of three leg forces and three couples is block triangular, so
``det = det(s₁, s₂, s₃)·det(m₁, m₂, m₃)``; Tsai 1996, "Kinematics of a three-dof platform with three
extensible limbs"; Zlatanov, Bonev & Gosselin 2002, "Constraint singularities of parallel
mechanisms", for the two kinds), that factor vanishes exactly where the constraint system's order
drops; an actuation factor vanishes where the actuation wrenches become dependent while the
constraint system keeps its order. Which lines a factor's points lie on suggests the kind
(:func:`screwkit.gca.conditions.label`); this module checks it at points of the factor's zero set:
each point of the factor not declared collinear with others is moved, in turn, along a random
direction until the factor vanishes (a real root of the polynomial the factor is along that line,
fitted to its values), and the rank of the diagram's constraint lines is read there. The moved
configuration may leave the mechanism's own incidences (the factorization holds on those), so what
is read is the rank of the constraint lines, a function of their points alone: dropping at every
zero reached, the factor is a constraint factor; kept, the superbracket's zeros it stands for leave
the constraint system of full order, i.e. the actuation wrenches become dependent.

Examples
--------
Three constraint forces through the vertices of a triangle whose sides are the actuation lines:
``[pqru]`` uses points of constraint lines only, yet where it vanishes the constraint forces stay
independent (tests/gca/test_factor_kinds.py):

>>> from screwkit.gca import Bracket, condition
>>> rng = np.random.default_rng(1)
>>> points = {x: np.r_[rng.normal(size=3), 1.0 if x in "pqr" else 0.0] for x in "pqruvw"}
>>> triangle = [("p", "q"), ("q", "r"), ("r", "p"), ("p", "u"), ("q", "v"), ("r", "w")]
>>> factor = condition(Bracket("pqru"), finite="pqr", infinite="uvw")
>>> vanishing_kind(factor, points, triangle, ["actuation"] * 3 + ["constraint"] * 3)[0]
'actuation'
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..exceptions import ScrewkitValueError
from .notation import join_labels

if TYPE_CHECKING:
    from .conditions import Condition

__all__ = [
    "RANK_RTOL",
    "vanishing_kind",
]

Array = np.ndarray
#: A set of unit lines is dependent at a zero of a factor when its smallest singular value is at
#: most this (the points are in units of the diagram's size, so rows are of order one).
RANK_RTOL = 1e-7


def _rows(points: Mapping[str, Array], lines: Sequence[tuple[str, str]]) -> Array:
    """Unit Plücker rows ``(p_w q − q_w p ; p × q)`` (direction, or moment for a line at infinity)."""
    rows = []
    for p, q in lines:
        a, b = np.asarray(points[p], dtype=float), np.asarray(points[q], dtype=float)
        row = np.concatenate([a[3] * b[:3] - b[3] * a[:3], np.cross(a[:3], b[:3])])
        size = np.linalg.norm(row[:3]) or np.linalg.norm(row[3:])
        rows.append(row / size if size > 0 else row)
    return np.array(rows)


def _rank(points: Mapping[str, Array], lines: Sequence[tuple[str, str]]) -> int:
    return int(np.linalg.matrix_rank(_rows(points, lines), tol=RANK_RTOL)) if lines else 0


def _degree(found: Condition, label: str) -> int:
    """The factor's degree in one point: the most times it occurs in a monomial."""
    from .condition_patterns import bracket_polynomial  # symbolic: a Condition has loaded it already

    poly = bracket_polynomial(found.factor)
    return max(sum(label in b.labels for b in m.brackets) for m in poly.terms)


def _zero_along(
    found: Condition, sample: Mapping[str, Array], label: str, rng: np.random.Generator
) -> dict[str, Array] | None:
    """``sample`` with point ``label`` moved along a random direction onto the factor's zero set
    (two directions tried: along one the factor may be constant)."""
    degree = _degree(found, label)
    ts = np.linspace(-3.0, 3.0, 4 * degree + 5)
    for direction in rng.normal(size=(2 if degree else 0, 3)):
        step = np.r_[direction, 0.0]
        moved = {**sample, label: sample[label] + ts[:, None] * step}
        values = np.asarray(found.evaluate(moved), dtype=float)
        scale = float(np.max(np.abs(values)))
        if not np.isfinite(scale) or scale == 0:
            continue
        roots = np.roots(np.polyfit(ts, values / scale, degree))
        for t in sorted((r.real for r in roots if abs(r.imag) <= 1e-9 * max(1.0, abs(r))), key=abs):
            point = {**sample, label: sample[label] + t * step}
            if abs(float(found.evaluate(point))) <= 1e-9 * scale:
                return point
    return None


def vanishing_kind(
    found: Condition,
    sample: Mapping[str, Array],
    lines: Sequence[tuple[str, str]],
    roles: Sequence[str],
    *,
    collinear: Sequence[str] = (),
    rng: int = 0,
) -> tuple[str, str]:
    """What happens when a factor vanishes: the constraint system's order drops, or the actuation
    wrenches become dependent (module docstring).

    Parameters
    ----------
    found : Condition
        The factor's condition (:func:`screwkit.gca.conditions.condition`).
    sample : mapping of str to numpy.ndarray, shape (4,)
        A generic configuration of the diagram's points (finite of weight 1, in units of the
        diagram's size; the directions' lengths do not matter).
    lines : sequence of pairs of labels
        The diagram's six lines.
    roles : sequence of str
        ``"constraint"`` or ``"actuation"`` per line.
    collinear : sequence of str, default ()
        Triples declared collinear: their points are not moved (that would break the incidence).
    rng : int, default 0
        Seed of the directions of motion.

    Returns
    -------
    (str, str)
        ``"constraint"`` (the constraint lines lose rank at every zero reached), ``"actuation"`` (they
        keep it at every zero reached: on the mechanism the superbracket vanishes there with the
        constraint system of full order), or ``""`` when no zero was reached or the zeros disagree;
        and the evidence in words.

    Raises
    ------
    ScrewkitValueError
        If ``roles`` does not give one role per line.

    Examples
    --------
    >>> from screwkit.gca import Bracket
    >>> from screwkit.gca.conditions import condition
    >>> lines, roles = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h"), ("g", "i"), ("h", "i")], (
    ...     ["actuation"] * 3 + ["constraint"] * 3)
    >>> rng = np.random.default_rng(0)
    >>> sample = {x: np.r_[rng.normal(size=3), 1.0 if x in "ace" else 0.0] for x in "abcdefghi"}
    >>> legs = condition(Bracket("abdf"), finite="a", infinite="bdf")
    >>> kind, evidence = vanishing_kind(legs, sample, lines, roles)
    >>> kind, evidence.split(": ")[1]
    ('actuation', 'the constraint lines gh, gi, hi keep rank 3, the actuation wrenches are dependent')
    """
    if len(roles) != len(lines):
        raise ScrewkitValueError(
            f"Expected `roles` to give one role per line ({len(lines)}), got {len(roles)}."
        )
    constraint = [line for line, role in zip(lines, roles, strict=True) if role == "constraint"]
    names = ", ".join(join_labels(line) for line in constraint)
    fixed = {x for triple in collinear for x in triple}
    generator = np.random.default_rng(rng)
    # directions of unit length (the same projective points), so a step of order one moves them alike
    sample = {x: p / np.linalg.norm(p[:3]) if p[3] == 0 and np.any(p[:3]) else p for x, p in sample.items()}
    ranks = {}
    for point in [x for x in found.vectors if x not in fixed]:
        zero = _zero_along(found, sample, point, generator)
        if zero is not None:
            ranks[point] = _rank(zero, constraint)
    if not ranks:
        return "", "no zero of the factor was reached by moving one of its points"
    if not constraint:
        return "actuation", f"zeros reached by moving {', '.join(ranks)}; the diagram has no constraint line"
    generic = _rank(sample, constraint)
    where = f"zeros reached by moving {', '.join(ranks)}: the constraint lines {names}"
    if all(k < generic for k in ranks.values()):
        return "constraint", f"{where} drop from rank {generic} to {', '.join(map(str, ranks.values()))}"
    if all(k == generic for k in ranks.values()):
        return "actuation", f"{where} keep rank {generic}, the actuation wrenches are dependent"
    return "", f"{where} drop rank at some zeros, not at others"
