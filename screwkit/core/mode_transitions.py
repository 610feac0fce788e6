"""Whether a configuration lies where operation modes meet, and the pose analysed in each mode.

A mechanism with several operation modes (Tsai's 3-UPU translates in one and moves in the plane of
its base in another) has configurations that belong to two modes at once: there its loop-closure
equations have more instantaneous solutions than either mode has freedoms (Zlatanov, Bonev &
Gosselin, "Constraint singularities as C-space singularities", ARK 2002: such a pose is a singular
point of the configuration space, where its branches cross). Which modes meet at a pose is read
by leaving it (a local test by moving and re-closing the loops, not a higher-order expansion):

1. the joint motions the loops allow to first order at the pose (the null space of the
   loop-closure matrix of :class:`~screwkit.core.kinematic_model.KinematicModel`);
2. :data:`TRIES` random small steps (:data:`STEP`) in that space, each followed by Newton's method
   on the loop-closure equations (the minimum-norm correction), which brings a step that is not
   tangent to any branch back onto the nearest one;
3. a configuration whose first-order motions may be off by more than :data:`TANGENT_TOL`
   (:func:`~screwkit.core.motion.tangent_error`) is closed further to round-off, and left out if
   still so: Newton's method converges only linearly towards where branches cross, so a step
   between two branches can end closed to 1e-11 but 1e-5 from the transition set, where its
   twists are those of neither mode (Tsai's 3-UPU read a third "mode", 2T1H, pitch -0.016);
4. every configuration kept is classified by its platform's twist system (mobility and motion
   type) and the order of its constraint wrench system: each distinct class is one mode through
   the pose, the most frequently reached first.

Two modes of the same motion type, mobility and constraint order are not told apart, and a mode
reached by none of the random steps is missed (a branch whose tangent directions are a thin subset
of the first-order motions): the answer is what the steps found.

Examples
--------
>>> h4 = load_mechanism("h4").twist_graph()
>>> result = modes_at(h4)
>>> result.meets, [(mode.mobility, mode.motion_type) for mode in result.modes]
(False, [(4, '3T1R')])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitValueError
from ..graphs.jointtable import JointTable
from ..graphs.twistgraph import check_twist_graph
from .kinematic_model import KinematicModel
from .motion import _null_space, _with_free, newton_closure, tangent_error
from .operation_modes import CLOSED_RTOL, _key
from .singularity import SingularityReport, classify
from .wrench_systems import WrenchAnalysis, analyze_table

__all__ = ["ModeAtPose", "ModesAtPose", "modes_at"]

Array = np.ndarray

#: Random steps taken from the pose, and their size (radians or characteristic lengths, largest
#: joint variable): small enough to stay next to the pose, large enough that the modes' ranks differ
#: far above the rank tolerance.
TRIES = 16
STEP = 0.05
#: The seed of those steps (fixed: the same pose always gets the same answer).
SEED = 20261128
#: A configuration is classified only if its first-order motions are within this of the true ones
#: (:func:`~screwkit.core.motion.tangent_error`): a hundredth of the tolerance its motion type is read
#: at. Measured at Tsai's 3-UPU in its base plane (150 frames and units, 2,400 steps): configurations
#: away from the transition set read 1e-13 (median), those Newton left next to it up to 3e-3.
TANGENT_TOL = CLOSED_RTOL / 100
#: Further Gauss–Newton iterations for a configuration above it (quadratic convergence next to a
#: branch: a few suffice; one heading for the transition set stays above and is left out).
POLISH_ITERATIONS = 8


@dataclass(frozen=True)
class ModeAtPose:
    """One operation mode through a pose.

    Attributes
    ----------
    mobility : int
        The platform's freedoms in this mode (the order of its twist system next to the pose).
    motion_type : str
        Its motion type there (e.g. ``"3T"``, ``"2T1R"``, ``"1H"``: a helical freedom's pitch, which
        varies along a mode, left out).
    constraint_order : int
        The order of the constraint wrench system there.
    reached : int
        How many of the random steps landed in this mode.
    nearby : WrenchAnalysis
        The wrench analysis of one configuration of this mode next to the pose.
    at_pose : SingularityReport
        The pose itself analysed as a configuration of this mode (``dof`` = this mode's mobility).
    """

    mobility: int
    motion_type: str
    constraint_order: int
    reached: int
    nearby: WrenchAnalysis
    at_pose: SingularityReport


@dataclass(frozen=True)
class ModesAtPose:
    """The operation modes through one pose (:func:`modes_at`).

    Attributes
    ----------
    modes : tuple of ModeAtPose
        Each mode reached, the most often reached first.
    first_order : int
        The joint motions the loops allow to first order at the pose (the loop-closure matrix's
        nullity): more than any one mode's where modes meet.
    """

    modes: tuple[ModeAtPose, ...]
    first_order: int

    @property
    def meets(self) -> bool:
        """True when the pose lies where two or more operation modes meet.

        Returns
        -------
        bool

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> modes_at(twist_graph("B", "E", [("B", "E", prismatic("P", [0, 0, 1], actuated=True))])).meets
        False
        """
        return len(self.modes) > 1

    def to_dict(self) -> dict[str, Any]:
        """The modes as JSON-ready data.

        Returns
        -------
        dict
            ``meets`` (bool), ``first_order`` and ``modes``: per mode its ``mobility``,
            ``motion_type``, ``constraint_order``, ``reached`` and ``verdict`` (the pose's, in that mode).

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> slider = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
        >>> modes_at(slider).to_dict()["modes"][0]["motion_type"]
        '1T'
        """
        return {
            "meets": self.meets,
            "first_order": self.first_order,
            "modes": [
                {"mobility": m.mobility, "motion_type": m.motion_type, "constraint_order": m.constraint_order,
                 "reached": m.reached, "verdict": m.at_pose.verdict}
                for m in self.modes
            ],
        }

    def lines(self) -> list[str]:
        """The report's lines: :meth:`describe`, then the pose's verdict in each mode where modes meet.

        Returns
        -------
        list of str

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> slider = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
        >>> modes_at(slider).lines()
        ['one operation mode through this pose: 1T']
        """
        out = [self.describe()]
        if self.meets:
            out += [f"  in the {m.motion_type} mode: {str(m.at_pose).splitlines()[0]}"
                    for m in self.modes]
        return out

    def describe(self) -> str:
        """One line: the modes through the pose.

        Returns
        -------
        str

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> slider = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
        >>> modes_at(slider).describe()
        'one operation mode through this pose: 1T'
        """
        types = [mode.motion_type for mode in self.modes]
        if not self.meets:
            return f"one operation mode through this pose: {types[0]}"
        return f"this pose lies where {len(types)} operation modes meet: {' and '.join(types)}"


def modes_at(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> ModesAtPose:
    """The operation modes through the graph's configuration (module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (numbers) at the pose to test.
    joint_key : str, default "joint"
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table` (every rank decision).

    Returns
    -------
    ModesAtPose

    Raises
    ------
    TwistGraphError
        If ``graph`` is not a twist graph with joints under ``joint_key``.
    ScrewkitValueError
        If the loops admit no joint motion at the pose, or no step could be closed again.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> arm = twist_graph("B", "E", [("B", "L", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...                              ("L", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    >>> modes_at(arm).modes[0].mobility
    2
    """
    check_twist_graph(graph, joint_key=joint_key)
    model = KinematicModel(graph, joint_key)
    reference = JointTable.from_graph(graph, joint_key=joint_key)
    null = _null_space(model.loop_jacobian(model.state(np.zeros((1, model.size))))[0])
    if null.shape[1] == 0:
        raise ScrewkitValueError("Expected a pose the mechanism can move from (to find its operation "
                                 "modes), got one whose loops admit no joint motion.")
    direction = np.random.default_rng(SEED).standard_normal((TRIES, null.shape[1])) @ null.T
    theta, residual = newton_closure(
        model, STEP * direction / np.max(np.abs(direction), axis=1, keepdims=True)
    )
    error = tangent_error(model, theta)
    rough = error > TANGENT_TOL
    if np.any(rough):  # step 3: closed further, to round-off
        theta[rough], residual[rough] = newton_closure(model, theta[rough], POLISH_ITERATIONS, tolerance=0.0)
        error[rough] = tangent_error(model, theta[rough])
    closed = (residual < 1e-9) & (error <= TANGENT_TOL)
    if not np.any(closed):
        raise ScrewkitValueError(f"Expected loops that close again after a small step, got none in {TRIES} "
                                 "tries (Newton's method did not converge, or only next to a singular "
                                 "configuration).")
    table = _with_free(model.joint_table(model.state(theta[closed]), reference), reference)
    batch = analyze_table(table, dof=0, rtol=rtol, length_scale=length_scale)
    classes: dict[tuple[int, str, int], list[int]] = {}
    for i in range(len(batch)):
        one = batch[i]
        key = (int(one.platform_order), *_key(one))  # read at the closure's precision, pitch left out
        classes.setdefault(key, []).append(i)
    modes = []
    for (mobility, kind, order), members in sorted(classes.items(), key=lambda item: -len(item[1])):
        at_pose = classify(graph, dof=mobility, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
        assert isinstance(at_pose, SingularityReport)  # a graph of numbers
        modes.append(ModeAtPose(mobility, kind, order, len(members), batch[members[0]], at_pose))
    return ModesAtPose(tuple(modes), int(null.shape[1]))
