"""Finite against instantaneous mobility: does the first-order motion of a mechanism really move it?

The instantaneous (first-order) mobility of a closed mechanism is the null space of its loop-closure
Jacobian; it can exceed the finite one. A triangle whose three links lie in line (side lengths
1 + 2 = 3) is rigid, yet its loop Jacobian has a one-dimensional null space (its three revolute axes
are coplanar and parallel, three planar twists through collinear points span two dimensions); a
four-bar flattened into a line (1 + 1 + 2 = 4) is rigid with two first-order freedoms, though
Grübler–Kutzbach counts one (3·(4 − 1) − 2·4 = 1). Conversely an overconstrained linkage (Bennett's
4R: Bennett 1903; McCarthy, *Geometric Design of Linkages*, 2000, §9.6) moves although the count says
it cannot, and given with rounded coordinates its loop Jacobian has a smallest singular value of the
size of the rounding, not zero.

The test here is a *local dimension test* (in the spirit of Bates, Hauenstein, Peterson & Sommese,
"A numerical local dimension test for points on the solution set of a system of polynomial
equations", SIAM J. Numer. Anal. 47, 2009): step a distance ``h`` along random directions of the
first-order null space and bring the loops back together with Newton's method. On a curve (or any
positive-dimensional set) of configurations through the reference, the corrected point stays about
``h`` away (the correction is ``O(h²)``); at an isolated configuration it falls back to the
reference. Every decision honours ``rtol``, the relative precision of the data: singular values of
the loop Jacobian below ``rtol`` times the largest are zero (in the null space and left out of every
Newton correction, so a linkage rounded to 6 decimals moves at ``rtol = 1e-5``), and a loop counts as
closed when its residual is below ``rtol`` times the step (both in characteristic lengths and
radians). The finite mobility is the platform's order at the configurations reached (where the
mechanism has moved off the reference, a serial or constraint singularity of the reference no
longer counts); 0 when every step fell back.

What it cannot decide, said as "undecided": steps that neither close back at the reference nor away
from it (Newton's method failing, as at a cusp of the configuration set sharper than the step), and
a finite motion of legs' internal freedoms only (a leg spinning about its own axis while the
platform stays put to first order) is read as the platform's order at the moved configurations.

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> flat_triangle = twist_graph("ground", "link", [  # sides 1, 2 and 3: in line, rigid
...     ("ground", "link", revolute("A", [0, 0, 1], [0, 0, 0])),
...     ("link", "other", revolute("B", [0, 0, 1], [1, 0, 0])),
...     ("other", "ground", revolute("C", [0, 0, 1], [3, 0, 0]))])
>>> reading = mobility_reading(flat_triangle)
>>> reading.instantaneous, reading.finite
(1, 0)
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.checks import checked_rtol
from ..exceptions import TwistGraphError
from ..graphs.jointtable import JointTable
from .kinematic_model import KinematicModel
from .wrench_systems import analyze_table

__all__ = ["MobilityReading", "check_stated_dof", "mobility_reading"]

Array = np.ndarray

#: Steps taken from the reference, their length ``h`` (radians, or characteristic lengths), the Newton
#: iterations allowed per step, and the seed of their directions (the same graph, the same answer).
SAMPLES = 8
STEP = 0.05
NEWTON_ITERATIONS = 60
SEED = 20261128
#: A corrected step ``θ`` has moved when ``|θ| > MOVED · h`` and fallen back when ``|θ| < BACK · h``.
MOVED, BACK = 0.5, 0.1
#: The closure residual accepted is ``max(rtol, RESIDUAL_FLOOR) · h``; a joint value beyond
#: ``DIVERGED`` (or not finite) ends that step's Newton iterations unclosed.
RESIDUAL_FLOOR = 1e-11
DIVERGED = 1e3


@dataclass(frozen=True)
class MobilityReading:
    """A mechanism's instantaneous and finite mobility at its reference configuration.

    Attributes
    ----------
    instantaneous : int
        The platform's order at the reference (its first-order freedoms), at ``rtol``.
    finite : int or None
        The platform's freedoms along the mechanism's finite motion through the reference; None when
        undecided.
    joint_freedoms : int
        The first-order freedoms of all joints (the loop Jacobian's null space at ``rtol``).
    moved, fell_back, unclosed : int
        How many of the steps closed away from the reference, closed back at it, did not close.
    rtol : float
        The data precision the decisions used.
    why : str
        One sentence: how ``finite`` was decided, or why it was not.
    """

    instantaneous: int
    finite: int | None
    joint_freedoms: int
    moved: int
    fell_back: int
    unclosed: int
    rtol: float
    why: str

    @property
    def differs(self) -> bool:
        """True when the finite mobility is decided and differs from the instantaneous one."""
        return self.finite is not None and self.finite != self.instantaneous

    def __str__(self) -> str:
        finite = "undecided" if self.finite is None else str(self.finite)
        return f"mobility: instantaneous {self.instantaneous}, finite {finite} ({self.why})"


def _truncated_pinv(jacobian: Array, rtol: float) -> Array:
    """The pseudo-inverses ``(B, n, m)`` of ``(B, m, n)`` matrices, singular values below ``rtol``
    times the largest (and below 1e-14 of it) treated as zero: the data's precision."""
    if jacobian.shape[1] == 0:
        return np.zeros((jacobian.shape[0], jacobian.shape[2], 0))
    return np.linalg.pinv(jacobian, rcond=max(rtol, 1e-14))


def mobility_reading(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> MobilityReading:
    """The instantaneous and finite mobility of the graph's mechanism at its configuration.

    The local dimension test of the module docstring: :data:`SAMPLES` steps of length :data:`STEP`
    along random first-order freedoms, each closed again by Newton's method with the loop Jacobian's
    singular values below ``rtol`` left out; the platform's order read where the steps moved.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (numbers) at the configuration to read.
    joint_key : str, default "joint"
    rtol : float, default 1e-9
        The relative precision of the data (in [0, 0.1]): 1e-9 for exact design data, about 1e-5 for
        coordinates rounded to 6 significant digits, ``0.01 mm / size`` for drawings in millimetres.
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.

    Returns
    -------
    MobilityReading

    Raises
    ------
    ScrewkitValueError, ScrewkitTypeError
        An ``rtol`` outside [0, 0.1] (naming it).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> fourbar = twist_graph("ground", "coupler", [
    ...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0])),
    ...     ("crank", "coupler", revolute("B", [0, 0, 1], [1, 0, 0])),
    ...     ("ground", "rocker", revolute("D", [0, 0, 1], [3, 0, 0])),
    ...     ("rocker", "coupler", revolute("C", [0, 0, 1], [3, 2, 0]))])
    >>> print(mobility_reading(fourbar))  # doctest: +ELLIPSIS
    mobility: instantaneous 1, finite 1 (8 of 8 steps ... moved ...)
    """
    rtol = checked_rtol(rtol)
    model = KinematicModel(graph, joint_key)
    n = model.size
    reference = model.state(np.zeros((1, n)))
    jacobian = model.loop_jacobian(reference)[0]
    if jacobian.shape[0]:
        _, sigma, vt = np.linalg.svd(jacobian)
        null = vt[int(np.sum(sigma > max(rtol, 1e-14) * max(sigma[0], 1.0))):].T
    else:
        null = np.eye(n)
    table = JointTable.from_graph(graph, joint_key=joint_key)
    freedoms = null.shape[1]
    if freedoms == 0:
        instantaneous = _platform_orders(model, reference, table, rtol, length_scale)[0]
        return MobilityReading(instantaneous, 0, 0, 0, 0, 0, rtol,
                               "the loops admit no first-order joint motion")
    directions = np.random.default_rng(SEED).standard_normal((SAMPLES, freedoms)) @ null.T
    start = STEP * directions / np.linalg.norm(directions, axis=1, keepdims=True)
    theta, alive = start.copy(), np.ones(SAMPLES, dtype=bool)  # alive: finite, not diverged
    tolerance = max(rtol, RESIDUAL_FLOOR) * STEP
    for _ in range(NEWTON_ITERATIONS):
        if not np.any(alive):
            break
        state = model.state(theta[alive])
        residual = model.loop_residual(state)
        if residual.shape[1] == 0 or np.max(np.abs(residual)) < tolerance:
            break
        theta[alive] -= np.einsum("bij,bj->bi", _truncated_pinv(model.loop_jacobian(state), rtol), residual)
        alive &= np.all(np.abs(theta) < DIVERGED, axis=1)  # NaN compares False
    closed = np.zeros(SAMPLES, dtype=bool)
    if np.any(alive):
        residual = model.loop_residual(model.state(theta[alive]))
        closed[alive] = (np.max(np.abs(residual), axis=1) if residual.shape[1] else 0.0) < tolerance
    distance = np.linalg.norm(np.where(alive[:, None], theta, 0.0), axis=1) / STEP
    moved, back = closed & (distance > MOVED), closed & (distance < BACK)
    orders = _platform_orders(model, model.state(np.vstack([np.zeros((1, n)), theta[moved]])), table, rtol,
                              length_scale)
    counts = (int(moved.sum()), int(back.sum()), int((~closed).sum()))
    steps = f"{SAMPLES} steps of {STEP} along the {freedoms} first-order joint freedom(s) at rtol {rtol:g}"
    if counts[0]:
        finite: int | None = int(np.bincount(orders[1:]).argmax())
        why = f"{counts[0]} of {steps} moved the mechanism; the platform's order there"
    elif counts[1] == SAMPLES:
        finite, why = 0, f"all {steps} fell back to the reference under Newton's method: it is isolated"
    else:
        finite = None
        between = SAMPLES - sum(counts)
        why = (f"of {steps}, {counts[1]} fell back, {counts[2]} did not close (Newton's method) and "
               f"{between} closed {BACK}-{MOVED} steps away: neither a motion nor an isolated "
               "configuration is shown")
    return MobilityReading(orders[0], finite, freedoms, *counts, rtol, why)


def _platform_orders(
    model: KinematicModel, state: object, table: JointTable, rtol: float, length_scale: float | None
) -> list[int]:
    """The platform's order at every configuration of a state, at ``rtol``."""
    moved = model.joint_table(state, table)  # type: ignore[arg-type]
    analysis = analyze_table(moved, dof=0, rtol=rtol, length_scale=length_scale, views=False)
    return [int(order) for order in np.asarray(analysis.platform_order).ravel()]


def check_stated_dof(stated: int | None, reading: MobilityReading) -> None:
    """Refuse a stated ``dof`` that contradicts the finite mobility (naming both numbers).

    A ``dof`` equal to the finite mobility is accepted even where the instantaneous one differs (a
    rigid linkage in line stated ``dof=0``); an undecided finite mobility refutes nothing.

    Parameters
    ----------
    stated : int or None
        The ``dof`` given; None states nothing.
    reading : MobilityReading
        :func:`mobility_reading` of the mechanism.

    Raises
    ------
    TwistGraphError
        A stated ``dof`` other than a decided finite mobility.

    Examples
    --------
    >>> reading = MobilityReading(1, 0, 1, 0, 8, 0, 1e-9, "all steps fell back")
    >>> check_stated_dof(0, reading)
    >>> check_stated_dof(1, reading)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected `dof` to equal the mechanism's finite mobility, 0 ...
    """
    if stated is None or reading.finite is None or stated == reading.finite:
        return
    raise TwistGraphError(
        f"Expected `dof` to equal the mechanism's finite mobility, {reading.finite} (instantaneous "
        f"{reading.instantaneous}, at rtol {reading.rtol:g}: {reading.why}), got dof = {stated}."
    )
