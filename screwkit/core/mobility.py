"""The mobility of a mechanism and the nominal ``dof`` of its analysis, read at generic configurations.

A pose may be singular, so a mechanism's mobility is not read off the analysed pose: it is the
platform's order where the mechanism's *finite* motion takes it (:mod:`screwkit.core.finite_mobility`:
a linkage in line, mobile to first order only, reads 0; a rounded overconstrained linkage moves at
its data precision ``rtol``), or, where that is undecided, the most common order over a few generic
configurations reached by moving the mechanism along its own twists
(:func:`screwkit.core.motion.generic_configurations`, :func:`generic_mobility`). The nominal ``dof``
of every analysis is that mobility, its actuators checked (:func:`resolve_dof`; more actuators than
freedoms is redundant actuation, :mod:`screwkit.core.redundancy`); :func:`settled_dof` checks a
first analysis against it at no cost where the pose is regular with one actuator per freedom.
:func:`generic_analyses` gives the wrench analyses at generic configurations (the structural facts
of wrench diagrams are decided there).

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> planar_2r = twist_graph("B", "E", [
...     ("B", "arm", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("arm", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
>>> generic_mobility(planar_2r)  # one actuator, two freedoms
2
"""

from __future__ import annotations

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.checks import checked_rtol
from ..exceptions import ScrewkitValueError, TwistGraphError
from .finite_mobility import MobilityReading, check_stated_dof, mobility_reading
from .motion import generic_configurations
from .redundancy import generic_driven_freedoms
from .wrench_systems import WrenchAnalysis, analyze_table

__all__ = ["generic_analyses", "generic_mobility", "resolve_dof", "settled_dof"]

Array = np.ndarray


def generic_analyses(
    graph: nx.MultiDiGraph,
    rng: np.random.Generator,
    count: int,
    *,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> list[WrenchAnalysis]:
    """Wrench analyses of the graph's mechanism at ``count`` generic configurations, as one batch.

    :func:`generic_configurations` analysed by :func:`~screwkit.core.wrench_systems.analyze_table` in one
    call (``rtol``, ``length_scale`` as there); each analysis of one configuration carries its twist
    graph (the graph's ``dof`` and ``name`` kept).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph of the mechanism (numbers), at any pose.
    rng : numpy.random.Generator
        Draws the configurations (:func:`generic_configurations`).
    count : int
        How many configurations.
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.

    Returns
    -------
    list of WrenchAnalysis
        One analysis of one configuration each (shape ``()``), in the order drawn.

    Examples
    --------
    >>> graph = load_mechanism("h4").twist_graph()
    >>> [a.global_order for a in generic_analyses(graph, np.random.default_rng(1), 2)]
    [6, 6]
    """
    table = generic_configurations(graph, rng, count, rtol=max(checked_rtol(rtol), B.DEFAULT_RTOL))
    batch = analyze_table(table, dof=graph.graph.get("dof"), rtol=rtol, length_scale=length_scale)
    out = []
    for i in range(len(batch)):
        one = batch[i]
        moved = table.graph(i)
        moved.graph.update({k: v for k, v in graph.graph.items() if k in ("name", "length_unit")})
        object.__setattr__(one, "graph", moved)
        out.append(one)
    return out


#: Generic configurations the mobility is read from (their most common platform order), and the seed
#: of the random motion that reaches them (fixed: the same graph always gets the same answer).
MOBILITY_SAMPLES = 3
MOBILITY_SEED = 20261124


def generic_mobility(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> int | None:
    """The platform's freedoms along the finite motion of the graph's mechanism.

    The finite mobility of :func:`~screwkit.core.finite_mobility.mobility_reading` (the platform's
    order where small steps along the first-order freedoms, closed again by Newton's method at the
    data precision ``rtol``, move the mechanism: a singular analysed pose does not decide it, a
    stretched limb loses a freedom there, a constraint singularity gains one; 0 when every step falls
    back, as for a linkage in line). Where that is undecided: the most common order of the platform's
    twist system over :data:`MOBILITY_SAMPLES` configurations reached from the graph's own by
    :func:`generic_configurations`, each decided with ``rtol`` and ``length_scale``
    (:func:`~screwkit.core.wrench_systems.analyze_table`); 0 for a mechanism whose loops admit no
    joint motion; None when Newton's method closed no loop.

    ``rtol`` is also the data's precision (docs/data-precision.md): joint rates whose loop-closure singular
    value is at most ``rtol`` times the largest are motions, and loops closed to ``rtol``
    characteristic lengths are closed, so an overconstrained linkage given with rounded coordinates
    (a Bennett linkage to 6 decimals) is mobile at an ``rtol`` above its rounding (1e-4), rigid at
    the default 1e-9. This is the first-order (instantaneous) count moved along: a linkage rigid but
    mobile to first order reads its first-order freedoms here.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph of the mechanism (numbers).
    joint_key : str, default "joint"
    rtol : float, default 1e-9
        Relative tolerance of every decision, and the data's precision (above).
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.

    Returns
    -------
    int or None
        The mobility (0 to 6), None when no loop could be closed.

    Raises
    ------
    ScrewkitValueError
        An ``rtol`` outside [0, 0.1] (naming it).

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic, revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> generic_mobility(twist_graph("B", "E", [("B", "L", prismatic("P1", [1, 0, 0], actuated=True)),
    ...                                         ("L", "E", prismatic("P2", [0, 1, 0]))]))
    2
    >>> fourbar = twist_graph("ground", "coupler", [
    ...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("crank", "coupler", revolute("B", [0, 0, 1], [1, 0, 0])),
    ...     ("ground", "rocker", revolute("D", [0, 0, 1], [3, 0, 0])),
    ...     ("rocker", "coupler", revolute("C", [0, 0, 1], [3, 2, 0]))])
    >>> generic_mobility(fourbar)
    1
    """
    return _finite_or_moved(  # mobility_reading refuses an out-of-range rtol (one line naming it)
        mobility_reading(graph, joint_key=joint_key, rtol=rtol, length_scale=length_scale),
        graph, joint_key, rtol, length_scale,
    )


def _finite_or_moved(
    reading: MobilityReading,
    graph: nx.MultiDiGraph,
    joint_key: str,
    rtol: float,
    length_scale: float | None,
) -> int | None:
    """The reading's finite mobility; where undecided, the generic configurations'
    (:func:`generic_mobility`, their loops closed to ``rtol``, floored at 1e-9)."""
    if reading.finite is not None:
        return reading.finite
    precision = max(rtol, B.DEFAULT_RTOL)
    try:
        table = generic_configurations(graph, np.random.default_rng(MOBILITY_SEED), MOBILITY_SAMPLES,
                                       joint_key=joint_key, rtol=precision)
    except ScrewkitValueError as err:
        if "admit no joint motion" in str(err):
            return 0
        return None
    analysis = analyze_table(table, dof=0, rtol=rtol, length_scale=length_scale, views=False)
    orders = np.asarray(analysis.platform_order).ravel()
    return int(np.bincount(orders).argmax())


def resolve_dof(
    stated: int | None, mobility: int, actuated: tuple[str, ...] | list[str], *, driven: int | None = None
) -> int:
    """The nominal ``dof`` of an analysis: the mechanism's mobility, with its actuators checked.

    screwkit analyses mechanisms whose nominal ``dof`` is the platform's mobility at generic
    configurations. Fewer actuators than ``dof`` is an under-actuated mechanism (uncontrolled
    freedoms: an actuation singularity everywhere, a non-square Jacobian); more is a redundantly
    actuated one (:mod:`screwkit.core.redundancy`); no actuator at all, a mobility analysis.

    Parameters
    ----------
    stated : int or None
        The ``dof`` given (argument or graph attribute); None derives it.
    mobility : int
        :func:`generic_mobility`.
    actuated : sequence of str
        The actuated joints.
    driven : int, optional
        The freedoms the actuators drive at generic configurations
        (:func:`screwkit.core.redundancy.generic_driven_freedoms`); given, at least as many actuators
        as the mobility must drive all of it.

    Returns
    -------
    int
        The mobility (``stated`` when it equals it).

    Raises
    ------
    TwistGraphError
        A stated ``dof`` other than the mobility (naming both numbers and the actuated joints);
        actuated joints on a mechanism that cannot move, or ``actuated`` flags that leave the
        platform uncontrolled at generic configurations (``driven`` below the mobility).

    Examples
    --------
    >>> resolve_dof(None, 3, ["A1", "A2", "A3"]), resolve_dof(2, 2, ["A1"]), resolve_dof(None, 4, [])
    (3, 2, 4)
    >>> resolve_dof(None, 2, ["A1", "A2", "A3"], driven=2)  # redundantly actuated
    2
    >>> resolve_dof(2, 3, ["A1", "A2", "A3"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected `dof` to equal the mechanism's mobility, 3 (...), ...
    >>> resolve_dof(None, 1, ["A1", "A2"], driven=0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected the `actuated` joints to drive the mechanism's 1 ...
    """
    names = f"{len(actuated)} actuated joint(s)" + (f": {', '.join(sorted(actuated))}" if actuated else "")
    if stated is not None and stated != mobility:
        raise TwistGraphError(
            f"Expected `dof` to equal the mechanism's mobility, {mobility} (the platform's freedoms at "
            f"generic configurations, screwkit.core.mobility.generic_mobility), got dof = {stated}; {names}. "
            "A `dof` other than the mobility would label every pose falsely (constraint singularities "
            "for a dof below it, lost freedoms above it): omit `dof` to use the mobility."
        )
    if actuated and mobility == 0:
        raise TwistGraphError(
            f"Expected no `actuated` joint on a mechanism that cannot move (mobility 0 at generic "
            f"configurations), got {names}: an actuator there drives nothing; fix the `actuated` flags."
        )
    if driven is not None and len(actuated) >= mobility > driven:
        raise TwistGraphError(
            f"Expected the `actuated` joints to drive the mechanism's {mobility} freedom(s) at generic "
            f"configurations, got {names} driving {driven} (screwkit.core.redundancy): with them locked "
            "the platform still moves everywhere; fix the `actuated` flags (or the design, singular at "
            "every configuration)."
        )
    return mobility


def _regular_for(analysis: WrenchAnalysis, dof: int) -> bool:
    """True when every pose of the analysis is regular for a nominal ``dof`` equal to its number of
    actuators: the platform has exactly ``dof`` freedoms there (constraint order ``6 - dof``), all
    controlled (global order 6), no limb serially singular. Such a pose confirms ``dof`` on its own
    (its first-order mobility is ``dof``); any other is checked against :func:`generic_mobility`."""
    return bool(
        len(analysis.topology.actuated) == dof > 0
        and np.all(np.asarray(analysis.constraint_order) == 6 - dof)
        and np.all(np.asarray(analysis.global_order) == 6)
        and not np.any(np.asarray(analysis.serial))
    )


def settled_dof(
    graph: nx.MultiDiGraph,
    stated: int | None,
    analysis: WrenchAnalysis,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> int:
    """The nominal ``dof`` the graph's analysis must use (:func:`resolve_dof`), given a first analysis
    with ``stated`` (or, when None, the number of actuators).

    A first analysis that is regular for its ``dof`` confirms it (:func:`_regular_for`: no generic
    configuration needed, the common case costs nothing). Otherwise the mobility is the graph's
    ``mobility`` attribute when it has one (a catalog family's graphs do:
    :attr:`screwkit.graphs.jointtable.JointTable.mobility`), else computed (:func:`generic_mobility`,
    0.03–0.2 s, with the analysis's ``rtol`` as the data precision and the given ``length_scale``;
    where no loop could be closed, the platform's most common order over the analysed poses stands
    in for it). A stated ``dof`` equal to the finite mobility is accepted where the instantaneous one
    differs (a linkage in line, rigid, stated ``dof=0``); one that contradicts a finite motion is
    refused with both numbers (:func:`~screwkit.core.finite_mobility.check_stated_dof`).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        The analysed twist graph (for a batch, its first configuration's).
    stated : int or None
        The ``dof`` given (argument or the graph's or table's attribute); None derives it.
    analysis : WrenchAnalysis
        The first analysis, made with ``stated`` (or the number of actuators).
    joint_key : str, default "joint"
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.

    Returns
    -------
    int
        The nominal ``dof``; when it differs from ``analysis.dof`` the caller analyses again with it.

    Raises
    ------
    TwistGraphError
        A ``dof`` other than the mobility (naming the finite and instantaneous mobility where they
        differ), or actuators that do not drive it (:func:`resolve_dof`).

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> G = twist_graph("B", "E", [("B", "L", prismatic("P1", [1, 0, 0], actuated=True)),
    ...                            ("L", "E", prismatic("P2", [0, 1, 0]))])
    >>> wrench_analysis(G).dof  # under-actuated: one actuator, the mobility 2 (wrench_analysis settles it)
    2
    """
    actuated = analysis.topology.actuated
    if (stated is None or stated == len(actuated)) and _regular_for(analysis, analysis.dof):
        return analysis.dof
    known = graph.graph.get("mobility")  # a catalog family's (JointTable.mobility)
    if known is not None and not B.is_dof(known):
        raise TwistGraphError(f"Expected graph attribute 'mobility' to be an integer in 0..6, got {known!r}.")
    if known is not None:
        mobility: int | None = int(known)
    else:
        reading = mobility_reading(graph, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
        if reading.differs:  # else resolve_dof's message says it all (with the actuated joints)
            check_stated_dof(stated, reading)
        mobility = _finite_or_moved(reading, graph, joint_key, rtol, length_scale)
    if mobility is None:
        mobility = int(np.bincount(np.asarray(analysis.platform_order).ravel()).argmax())
    driven = (  # redundant actuation: the actuators must drive every freedom (screwkit.core.redundancy)
        generic_driven_freedoms(graph, mobility, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
        if len(actuated) > mobility > 0
        else None
    )
    return resolve_dof(stated, mobility, actuated, driven=driven)
