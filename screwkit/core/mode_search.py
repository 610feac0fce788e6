"""The operation modes of a linkage: its reference's, those reached by moving it, and those found by
assembling it at random.

A mechanism's operation modes are the components of its configuration space on which the platform
keeps one kind of motion (Tsai's 3-UPU translates in one, turns with its position following its
orientation in another, moves in its base plane in a third). Moving the mechanism from its reference
configuration (:func:`~screwkit.core.motion.generic_configurations`) stays in the reference's mode
unless the reference lies where modes meet; the other modes are found here globally:

1. :data:`REACHED` configurations reached by moving the mechanism from its reference (every mode
   kept), so the reference's own mode is always among those found;
2. :data:`ASSEMBLIES` random assemblies: every joint variable drawn at random (angles uniform in
   ``[-π, π]``, slider travels uniform in ``±`` :data:`TRAVEL` characteristic lengths) and the loops
   closed by Gauss–Newton's minimum-norm correction on the loop-closure equations of
   :class:`~screwkit.core.kinematic_model.KinematicModel` (Nocedal & Wright, *Numerical
   Optimization*, 2006, §10.3), which lands each draw on a nearby point of *some* component of the
   configuration space, a generic point of it with probability one;
3. every closed configuration classified by its platform's motion type and the order of its
   constraint wrench system (:func:`~screwkit.core.operation_modes.operation_modes`), each class one
   mode, the reference's first;
4. a class other than the reference's is kept only if a configuration of it, moved by :data:`NEARBY`
   and closed again, still reads it (at a loose ``rtol`` a configuration near a singular one can
   read a class of its own);
5. a mode without rotations keeps its platform's orientation, so configurations of such a class
   whose platforms are turned from each other (by more than :data:`TURN_TOL`) lie in different
   modes: Tsai's 3-UPU translates with its platform as assembled and with it turned half a turn
   about the vertical, two components of its configuration space with one motion type, read "3T"
   and "3T (turned 180° about (0, 0, 1))". Each such mode carries its turn from the reference.

It is a search, not a proof: a mode whose basin of attraction no draw falls in is missed, and two
modes of the same motion type and constraint order read as one, unless they are modes without
rotations whose platforms are turned from each other (step 5).
The joints have no limits here: a slider may run through zero and beyond, and a parallelogram built
of two rods between spherical joints (the catalog's Delta-like robots) may stop being one, a mode the
real robot's joint ranges exclude. The draws are seeded, so the same mechanism always gets the same
answer.

Examples
--------
>>> found = find_operation_modes(load_mechanism("planar_3rrp").twist_graph())
>>> [mode.motion_type for mode in found], found.closed, found.assemblies
(['2T1R'], 24, 24)
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any, overload

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.checks import checked_rtol
from ..algebra.rigid_motions import rotation_log
from ..exceptions import ScrewkitValueError
from ..graphs.jointtable import JointTable
from ..graphs.twistgraph import check_twist_graph
from .kinematic_model import KinematicModel
from .motion import _null_space, _with_free, moved_configurations, newton_closure
from .operation_modes import OperationMode, operation_modes
from .wrench_systems import analyze_table

__all__ = ["OperationModes", "find_operation_modes", "random_assemblies"]

#: Configurations reached by moving the mechanism from its reference, and random assemblies tried.
REACHED = 12
ASSEMBLIES = 24
#: At most this many random assemblies (each a Gauss–Newton run over the whole model).
MAX_ASSEMBLIES = 10_000
#: How far a candidate mode's configurations are moved to check it (largest joint change).
NEARBY = 0.05
#: How many of a candidate mode's configurations are moved to check it (one staying in it suffices).
RECHECKED = 3
#: Two configurations of a mode without rotations whose platforms' orientations differ by more than
#: this (radians; or ten times ``rtol``, if more) lie in different modes (module docstring, step 5).
TURN_TOL = 1e-3
#: The loop-closure residual (characteristic lengths) at which an assembly is closed, whatever the data's
#: precision: Gauss–Newton closes the loops of rounded data too (an overconstrained linkage given rounded
#: is a rigid structure whose configurations are exact solutions of its equations).
CLOSED = 1e-9
#: A slider's random travel, in characteristic lengths either way.
TRAVEL = 2.0
#: Gauss–Newton iterations closing a random assembly (far from the solution set: more than a step
#: of :func:`~screwkit.core.motion.generic_configurations` needs), and the largest change of a joint
#: variable per iteration (radians or characteristic lengths; :func:`~screwkit.core.motion.newton_closure`).
ASSEMBLY_ITERATIONS = 60
ASSEMBLY_STEP = 0.5
#: The seed of the draws (fixed: the same mechanism always gets the same answer).
SEED = 20


@dataclass(frozen=True, eq=False)
class OperationModes(Sequence[OperationMode]):
    """The operation modes found (:func:`find_operation_modes`): a sequence of :class:`OperationMode`.

    Attributes
    ----------
    modes : tuple of OperationMode
        The reference's mode first (marked ``reference``; none is where the reference lies where
        modes meet), then by decreasing number of configurations; each mode's ``indices`` are rows of
        ``table``.
    table : JointTable
        Every configuration classified, batch shape ``(k,)``: those reached from the reference, then
        the random assemblies that closed.
    assemblies : int
        Random assemblies tried.
    closed : int
        Those whose loops closed.
    reached : int
        Configurations reached by moving the mechanism from its reference.
    """

    modes: tuple[OperationMode, ...]
    table: JointTable
    assemblies: int
    closed: int
    reached: int

    @overload
    def __getitem__(self, index: int) -> OperationMode: ...

    @overload
    def __getitem__(self, index: slice) -> Sequence[OperationMode]: ...

    def __getitem__(self, index: int | slice) -> OperationMode | Sequence[OperationMode]:
        return self.modes[index]

    def __len__(self) -> int:
        return len(self.modes)

    def __iter__(self) -> Iterator[OperationMode]:
        return iter(self.modes)

    def names(self) -> list[str]:
        """Each mode's name (:attr:`OperationMode.name`: its motion type, and a translational mode's
        turn from the reference), the reference's marked "(this one)".

        Returns
        -------
        list of str

        Examples
        --------
        >>> find_operation_modes(load_mechanism("delta").twist_graph()).names()  # its rods: 2 S-S each
        ['3T (this one)', '3R']
        """
        return [mode.name + (" (this one)" if mode.reference else "") for mode in self.modes]

    def describe(self) -> str:
        """One line: the modes found, and how (a search: others may exist).

        Returns
        -------
        str

        Examples
        --------
        >>> found = find_operation_modes(load_mechanism("planar_3rrp").twist_graph())
        >>> found.describe().split(" (found")[0]
        'one operation mode: 2T1R (this one)'
        """
        names = self.names()
        listed = names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"
        count = "one operation mode" if len(names) == 1 else f"{len(names)} operation modes"
        meet = "" if self.modes[0].reference else " (this configuration lies where some meet)"
        return (f"{count}{meet}: {listed} (found in {self.closed} random assemblies of {self.assemblies} "
                f"and {self.reached} configurations reached from this one; others may exist)")

    def to_dict(self) -> dict[str, Any]:
        """The modes as JSON-ready data.

        Returns
        -------
        dict
            ``modes`` (per mode its ``motion_type``, ``constraint_order``, ``reference``,
            ``configurations``: how many of those classified fell in it, and ``turn``: a mode without
            rotations' turn from the reference as a rotation vector, radians, else None),
            ``assemblies``, ``closed``, ``reached`` and ``complete`` (always False: a search cannot
            rule other modes out).

        Examples
        --------
        >>> found = find_operation_modes(load_mechanism("planar_3rrp").twist_graph())
        >>> found.to_dict()["modes"]  # doctest: +NORMALIZE_WHITESPACE
        [{'motion_type': '2T1R', 'constraint_order': 3, 'reference': True, 'configurations': 36,
          'turn': None}]
        """
        return {
            "modes": [{"motion_type": mode.motion_type, "constraint_order": mode.constraint_order,
                       "reference": mode.reference, "configurations": len(mode.indices),
                       "turn": None if mode.turn is None else list(mode.turn)}
                      for mode in self.modes],
            "assemblies": self.assemblies,
            "closed": self.closed,
            "reached": self.reached,
            "complete": False,
        }


def random_assemblies(
    model: KinematicModel, rng: np.random.Generator, count: int, tolerance: float = CLOSED
) -> np.ndarray:
    """Joint values of random assemblies whose loops closed (module docstring, step 2).

    Parameters
    ----------
    model : KinematicModel
    rng : numpy.random.Generator
    count : int
        Assemblies tried.
    tolerance : float, default :data:`CLOSED`
        The largest loop-closure residual (characteristic lengths) of an assembly taken as closed:
        the loop closure's own, whatever the data's precision (a loose ``rtol`` would take an
        assembly that Gauss–Newton left short of closing as one: at rtol 0.1, a Ragnar assembly
        at a residual of 0.044 characteristic lengths).

    Returns
    -------
    numpy.ndarray, shape (k, n)
        ``k <= count`` rows, those that closed.

    Examples
    --------
    >>> model = KinematicModel(load_mechanism("planar_3rrp").twist_graph())
    >>> random_assemblies(model, np.random.default_rng(0), 4).shape
    (4, 9)
    """
    if count == 0:
        return np.zeros((0, model.size))
    slider = np.array([not np.any(column.row[:3]) for column in model.columns])
    theta = rng.uniform(-1.0, 1.0, (count, model.size)) * np.where(slider, TRAVEL, np.pi)
    with np.errstate(all="ignore"):  # a draw that runs off is dropped below, not propagated
        theta, residual = newton_closure(model, theta, ASSEMBLY_ITERATIONS, ASSEMBLY_STEP)
    closed = np.isfinite(residual) & (residual < tolerance) & np.all(np.isfinite(theta), axis=1)
    return theta[closed]


def find_operation_modes(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    assemblies: int = ASSEMBLIES,
) -> OperationModes:
    """The operation modes of the graph's mechanism, its reference's first (module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph at its reference configuration.
    joint_key : str, default "joint"
    rtol : float, default 1e-9
        The data's precision (as in :func:`~screwkit.core.motion.generic_configurations`) and the
        rank tolerance of the classification (the motion type at least 1e-6: closed configurations
        carry round-off of the closure's size). A random assembly is closed at the loop closure's
        own :data:`CLOSED`, whatever ``rtol``.
    assemblies : int, default 24
        Random assemblies tried.

    Returns
    -------
    OperationModes

    Raises
    ------
    TwistGraphError
        If ``graph`` is not a twist graph with joints under ``joint_key``.
    ScrewkitValueError
        If ``assemblies`` is not an integer in [0, 10000] or ``rtol`` not in [0, 0.1]; as
        :func:`~screwkit.core.motion.generic_configurations` (a mechanism that cannot move).

    Examples
    --------
    >>> [mode.motion_type for mode in find_operation_modes(load_mechanism("h4").twist_graph())]
    ['3T1R', '1T3R']
    """
    if (isinstance(assemblies, bool) or not isinstance(assemblies, int | np.integer)
            or not 0 <= assemblies <= MAX_ASSEMBLIES):
        raise ScrewkitValueError(
            f"Expected `assemblies` to be an integer in [0, {MAX_ASSEMBLIES}], got {assemblies!r}."
        )
    check_twist_graph(graph, joint_key=joint_key)
    rank_rtol = max(checked_rtol(rtol), B.DEFAULT_RTOL)  # 0 would count round-off as rank
    rng = np.random.default_rng(SEED)
    model = KinematicModel(graph, joint_key)
    reached = moved_configurations(model, rng, REACHED, rank_rtol)
    found = random_assemblies(model, rng, assemblies)
    reference = JointTable.from_graph(graph, joint_key=joint_key)
    theta = np.concatenate([reached, found])
    table, modes = _classified(model, reference, theta, rank_rtol)
    kept = [modes[0]]
    for mode in modes[1:]:  # a class met away from a singular configuration: moved, it stays itself
        members = theta[list(mode.indices[:RECHECKED])]
        moved = _moved_nearby(model, members, rng)
        both = np.concatenate([members, moved])
        again = _classified(model, reference, both, rank_rtol)[1]
        if any(other.motion_type == mode.motion_type and other.constraint_order == mode.constraint_order
               and any(i >= len(members) for i in other.indices) for other in again):
            kept.append(mode)
    if not reference.free:  # a point task's task link has no orientation of its own
        kept = _by_orientation(kept, model, theta, rank_rtol)
    return OperationModes(tuple(kept), table, int(assemblies), len(found), len(reached))


def _by_orientation(
    modes: list[OperationMode], model: KinematicModel, theta: np.ndarray, rtol: float
) -> list[OperationMode]:
    """Each mode without rotations split by its platform's orientation (module docstring, step 5),
    the reference's first, then by decreasing number of configurations."""
    state = model.state(*model.recentred(theta, {}))
    rotations = model.displacement(state, model.platform)[:, :3, :3]
    tolerance = max(TURN_TOL, 10 * rtol)
    out = []
    for mode in modes:
        if any(kind in mode.motion_type for kind in "RH"):
            out.append(mode)
            continue
        groups: list[list[int]] = []  # configurations whose platforms keep one orientation
        for i in mode.indices:
            for group in groups:
                if np.linalg.norm(rotation_log(rotations[group[0]].T @ rotations[i])) < tolerance:
                    group.append(i)
                    break
            else:
                groups.append([i])
        for group in groups:
            turn = rotation_log(rotations[group[0]])
            turned = bool(np.linalg.norm(turn) >= tolerance)
            out.append(OperationMode(mode.motion_type, mode.constraint_order, tuple(group),
                                     mode.reference and not turned,
                                     (float(turn[0]), float(turn[1]), float(turn[2])) if turned
                                     else (0.0, 0.0, 0.0)))
    return sorted(out, key=lambda mode: (not mode.reference, -len(mode.indices), mode.indices[0]))


def _classified(
    model: KinematicModel, reference: JointTable, theta: np.ndarray, rtol: float
) -> tuple[JointTable, list[OperationMode]]:
    """The joint table of closed configurations and their classes (the reference's first)."""
    # spherical joints' angles folded into their offsets: three screws never read at a gimbal lock
    table = _with_free(model.joint_table(model.state(*model.recentred(theta, {})), reference), reference)
    modes = operation_modes(analyze_table(table, rtol=rtol, views=False),
                            analyze_table(reference, rtol=rtol, views=False))
    return table, modes


def _moved_nearby(
    model: KinematicModel, theta: np.ndarray, rng: np.random.Generator
) -> np.ndarray:
    """Each closed configuration moved by :data:`NEARBY` along a random motion of its loops and closed
    again (those that close to :data:`CLOSED`): a configuration that only lies near a singular one
    (within a loose ``rtol``: a planar 3-RRP once read "1T1R" at one random assembly of 24) reads its
    mode once moved."""
    moved = []
    for row in theta:
        null = _null_space(model.loop_jacobian(model.state(row[None]))[0])
        if null.shape[1]:
            direction = null @ rng.standard_normal(null.shape[1])
            moved.append(row + NEARBY * direction / np.max(np.abs(direction)))
    if not moved:
        return np.zeros((0, theta.shape[1]))
    closed, residual = newton_closure(model, np.array(moved))
    return closed[np.isfinite(residual) & (residual < CLOSED)]  # as random_assemblies
