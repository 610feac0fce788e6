"""The whole analysis of a mechanism at a pose, as one report (text and JSON): the CLI's main job.

:func:`analyze` composes the public pipeline (docs/architecture.md §1): twist graph → equivalent graph →
wrench systems → labels at the pose → wrench diagram → superbracket → conditions. The report says
what the mechanism is, which wrenches act on its platform (each as a line: kind, direction, a point,
pitch), the diagram's twelve points in words, the factored superbracket, each factor as a geometric
statement and a vector form with its label, and the verdict with its closeness measures
(:class:`~screwkit.interface.analysis_report.AnalysisReport`, its JSON and its text).

For a catalog mechanism it also gives the Jacobians ``A χ̇ = B θ̇`` built on the same actuation
wrenches (:func:`screwkit.core.jacobians.jacobians_from_wrenches`) over the family's nominal twists at the
pose (:meth:`screwkit.robots.mechanism.Mechanism.twist_basis`, one per pose coordinate), with their
Gosselin–Angeles type (``"inverse"`` goes with the ``serial`` label, ``"direct"`` with
``actuation``; a ``constraint`` singularity, where the platform gains a twist outside the nominal
ones, leaves ``A`` regular), ``det A``, ``det B`` and the two closeness measures. A snapshot has no
family to give its nominal twists: there the Jacobians are None.

Structural zeros of the superbracket are decided on generic configurations, never at the analysed
pose: random poses of the workspace for a catalog mechanism, configurations reached by moving the
mechanism along its own mobility for a snapshot or a graph (:mod:`screwkit.core.motion`). At a singular
pose the factored form is the one of a regular pose, with the vanishing factors valued (~0) there.

Examples
--------
>>> report = analyze("h4")
>>> report.verdict.verdict, report.superbracket.simplification.factored.to_dict()["text"]
('regular', '-[gikj][a b d ḟ][c g ḣ j]')
>>> report.jacobians.type, report.jacobians.actuated_joints
('regular', ('A1', 'A2', 'A3', 'A4'))
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.checks import checked_length_scale, checked_rtol
from ..core.finite_mobility import mobility_reading
from ..core.jacobian_matrices import Jacobians
from ..core.jacobians import jacobians_from_wrenches
from ..core.mode_search import OperationModes, find_operation_modes
from ..core.mode_transitions import ModesAtPose, modes_at
from ..core.verdicts import classify_analysis
from ..core.wrench_systems import WrenchAnalysis
from ..core.wrenches import wrench_analysis
from ..exceptions import ScrewkitError, ScrewkitTypeError, ScrewkitValueError
from ..graphs.reduction import equivalent_twist_graph
from ..robots.angles import angle_factor
from ..robots.catalog import load_mechanism
from ..robots.mechanism import Mechanism
from ..robots.posed import PosedMechanism
from ..robots.snapshot import load_snapshot
from ..robots.toml_fields import file_kind, load_toml
from .analysis_report import AnalysisReport

if TYPE_CHECKING:  # the diagram and GCA stack loads when a report is made, not on `import screwkit`
    from ..gca.diagram import WrenchDiagram

__all__ = ["analyze", "pose_report"]

Array = np.ndarray


def analyze(
    target: Any,
    pose: Any = None,
    *,
    angles: str = "rad",
    rtol: float | None = None,
    length_scale: float | None = None,
    superbracket: bool = True,
    progress: Callable[[str], None] | None = None,
) -> AnalysisReport:
    """Analyse a mechanism at a pose: the one composer the CLI calls.

    Parameters
    ----------
    target : str, pathlib.Path, Mechanism, PosedMechanism or networkx.MultiDiGraph
        A catalog name (``"h4"``), a catalog or snapshot ``.toml`` file, a :class:`Mechanism`, one
        pose of a posed batch (``mechanism.at(poses)[i]``, shape ``()``: its pose, ``rtol`` and
        ``length_scale``),
        or a twist graph built in Python (analysed at its configuration, like a snapshot).
    pose : array_like, optional
        In the mechanism's length unit and radians; default: the catalog's default pose. Not
        accepted for snapshots, graphs and a posed mechanism (their configuration is given).
    angles : {"rad", "deg"}, default "rad"
        The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).
    rtol : float, optional
        Relative tolerance of every rank decision (default 1e-9).
    length_scale : float, optional
        The characteristic length of every rank decision, in the mechanism's length unit
        (moments are divided by it); default: derived from the screws at each configuration
        (:func:`~screwkit.core.wrench_systems.analyze_table`), so that answers follow a change of unit.
    superbracket : bool, default True
        Also expand and factor the superbracket (skip for speed).
    progress : callable, optional
        Called with the name of each stage as it starts (:data:`STAGES`); the command line prints
        them on a terminal, since the superbracket of a general mechanism may take seconds.

    Returns
    -------
    AnalysisReport

    Raises
    ------
    ScrewkitError
        For an unknown mechanism, a malformed file, an unreachable pose (naming the limb), a posed
        batch (index it first).

    Examples
    --------
    >>> analyze("h4", [0.0, 0.0, -750.0, 0.0], superbracket=False).verdict.labels
    ()
    >>> analyze("h4", [0, 0, -750, 45], angles="deg", superbracket=False).pose.round(4).tolist()
    [0.0, 0.0, -750.0, 0.7854]
    >>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
    >>> analyze(posed[1], superbracket=False).pose.tolist()
    [30.0, -20.0, -750.0, 0.3]
    """
    tolerance = B.DEFAULT_RTOL if rtol is None else checked_rtol(rtol)
    length = checked_length_scale(length_scale, allow_none=True)
    angle_factor(angles)  # checks `angles` for every target
    if not isinstance(superbracket, bool | np.bool_):
        raise ScrewkitTypeError(f"Expected `superbracket` to be True or False, got {superbracket!r}.")
    if progress is not None and not callable(progress):
        raise ScrewkitTypeError(f"Expected `progress` to be callable, got {type(progress).__name__}.")
    step = progress or (lambda stage: None)
    if isinstance(target, PosedMechanism):
        if target.shape != ():
            raise ScrewkitValueError(
                "Expected one pose of a posed mechanism (index the batch: posed[i]), got a batch of shape "
                f"{target.shape}."
            )
        options = (("pose", pose), ("rtol", rtol), ("length_scale", length_scale))
        given = [name for name, value in options if value is not None]
        if given:
            raise ScrewkitValueError(
                "Expected no `pose`, `rtol` or `length_scale` with a posed mechanism (it has them: "
                f"mechanism.at(poses, rtol=..., length_scale=...)), got {', '.join(given)}."
            )
        step(STAGES[0])
        return pose_report(target, superbracket=superbracket, progress=step)
    step(STAGES[0])
    if isinstance(target, nx.MultiDiGraph):
        return _graph_report(target, "<graph>", pose, tolerance, length, superbracket, "a twist graph", step)
    if not isinstance(target, str | Path | Mechanism):
        raise ScrewkitTypeError(
            "Expected `target` to be a catalog name, a .toml path, a Mechanism or a twist graph "
            f"(networkx.MultiDiGraph), got {type(target).__name__}."
        )
    text = str(target) if not isinstance(target, Mechanism) else ""
    if text.endswith(".toml") and file_kind(load_toml(text)) == "snapshot":
        snapshot = load_snapshot(text)
        return _graph_report(snapshot, text, pose, tolerance, length, superbracket, "a snapshot", step)
    mechanism = target if isinstance(target, Mechanism) else load_mechanism(target)
    posed = _one_pose(mechanism, pose, angles, tolerance, length)
    return pose_report(posed, superbracket=superbracket, progress=step)


def _one_pose(mechanism: Mechanism, pose: Any, angles: str, rtol: float, length_scale: float | None) -> Any:
    """The mechanism at one pose (a batch is for :meth:`Mechanism.at`: its reports pose by pose)."""
    if pose is None:
        return mechanism.at(angles=angles, rtol=rtol, length_scale=length_scale)[0]
    array = B.as_array(pose, "pose", (len(mechanism.pose_names),), symbolic=False)
    if array.ndim != 1:
        raise ScrewkitValueError(
            f"Expected `pose` to be one pose of shape ({len(mechanism.pose_names)},) "
            f"({', '.join(mechanism.pose_names)}), got shape {array.shape}; for many poses use "
            "mechanism.at(poses) and sk.analyze(posed[i]) of each pose."
        )
    return mechanism.at(array, angles=angles, rtol=rtol, length_scale=length_scale)[0]


#: The stages :func:`analyze` reports to its ``progress`` callback, in order.
STAGES = (
    "wrench systems",
    "wrench diagram (chosen on generic configurations)",
    "superbracket (expansion, factoring, conditions)",
)


def _graph_report(
    graph: nx.MultiDiGraph,
    source: str,
    pose: Any,
    rtol: float,
    length_scale: float | None,
    superbracket: bool,
    what: str,
    progress: Callable[[str], None],
) -> AnalysisReport:
    if pose is not None:
        raise ScrewkitValueError(f"{source}: {what} is one configuration; expected no pose, got {pose!r}.")
    try:  # dof: the mechanism's mobility at generic configurations (screwkit.core.mobility.settled_dof)
        analysis = wrench_analysis(graph, rtol=rtol, length_scale=length_scale)
    except ScrewkitError as err:
        if source.endswith(".toml"):  # name the file
            raise type(err)(f"{source}: {err}") from err
        raise
    if not isinstance(analysis, WrenchAnalysis):
        raise ScrewkitTypeError(
            f"{source}: expected numeric joint screws for a report at a pose, got symbols; "
            "use screwkit.core.generic.generic_analysis for a family's generic answers."
        )
    from ..gca.diagram_placement import graph_diagram

    progress(STAGES[1])
    diagram, sampler = graph_diagram(analysis, length_scale=length_scale)
    jacobians, jacobians_note, transmission, coordinates = _graph_jacobians(
        graph, analysis, rtol, length_scale
    )
    report = _finish(
        graph.graph.get("name", source),
        source,
        graph.graph.get("length_unit", ""),
        None,
        (),
        graph,
        analysis,
        diagram,
        sampler if superbracket else None,
        f"structural zeros confirmed on generic configurations of {what}, reached by moving the mechanism "
        "and closing its loops again (screwkit.core.motion); each stage equals the 6×6 determinant on "
        "fresh ones",
        jacobians,
        jacobians_note,
        progress=progress,
    )
    return dataclasses.replace(
        report, given_length_scale=length_scale, transmission=transmission, pose_names=coordinates,
        mobility=mobility_reading(graph, rtol=rtol, length_scale=length_scale),
        modes_at_pose=_modes_at_pose(graph, rtol, length_scale),
        operation_modes=_operation_modes(graph, rtol),
    )


def _operation_modes(graph: nx.MultiDiGraph, rtol: float) -> OperationModes | None:
    """The operation modes found from a graph's configuration (None where the search cannot run: a
    mechanism that cannot move there)."""
    try:
        return find_operation_modes(graph, rtol=rtol)
    except ScrewkitError:
        return None


def _modes_at_pose(graph: nx.MultiDiGraph, rtol: float, length_scale: float | None) -> ModesAtPose | None:
    """The operation modes through a graph's configuration (None where the test cannot run: a mechanism
    that cannot move there, or loops Newton's method does not close again)."""
    try:
        return modes_at(graph, rtol=rtol, length_scale=length_scale)
    except ScrewkitError:
        return None


def _graph_jacobians(
    graph: nx.MultiDiGraph, analysis: WrenchAnalysis, rtol: float, length_scale: float | None
) -> tuple[Jacobians | None, str, dict[str, Any], tuple[str, ...]]:
    """A graph's Jacobians and transmission at its configuration, over the platform's twists per unit
    rate of its coordinates (loop closure, :mod:`screwkit.robots.graph_kinematics`); None and why
    when the graph is not a mechanism with coordinates there (e.g. a singular configuration)."""
    from ..papers.paper_004_summary import transmission_summary
    from ..robots.graph_mechanism import mechanism

    try:
        robot = mechanism(graph)
        basis = robot.at(rtol=rtol, length_scale=length_scale)[0].twist_basis
        jacobians = jacobians_from_wrenches(analysis, basis, rtol=rtol)
    except ScrewkitError as err:
        note = f"not computed: {err}"
        return None, note, {"wrench": None, "paper_004": None, "note": note}, ()
    note = (
        "rows: the actuation wrenches (unit force, or unit couple, signed so that B_jj >= 0); columns: the "
        f"platform's twists per unit rate of its coordinates ({', '.join(robot.coordinates)}) at this "
        "configuration (loop closure, screwkit.robots.graph_kinematics)"
    )
    return jacobians, note, transmission_summary(robot, robot.reference_pose, jacobians), robot.coordinates


def pose_report(
    pose: Any, *, superbracket: bool = True, progress: Callable[[str], None] | None = None
) -> AnalysisReport:
    """The report of one pose of a posed mechanism (what :func:`analyze` of ``posed[i]`` returns).

    Parameters
    ----------
    pose : PosedMechanism
        One pose of ``mechanism.at(poses)`` (shape ``()``).
    superbracket : bool
        Also expand and factor the superbracket.
    progress : callable, optional
        Called with the name of each stage as it starts (:data:`STAGES`).

    Returns
    -------
    AnalysisReport

    Examples
    --------
    >>> pose_report(load_mechanism("v4").at()[0], superbracket=False).verdict.verdict
    'regular'
    """
    mechanism = pose.mechanism
    step = progress or (lambda stage: None)
    pose._draws  # noqa: B018 (the wrench systems, with the generic draws and samples as one batch, first
    # so that progress names the stages in order)
    step(STAGES[1])
    diagram, sampler = pose.diagram_and_sampler()
    jacobians: Jacobians | None = None
    try:
        jacobians = pose.jacobians
        jacobians_note = (
            "rows: the actuation wrenches (unit force, or unit couple, signed so that B_jj >= 0); columns: "
            "the platform's nominal twists at the pose, one per pose coordinate "
            "(screwkit.robots.mechanism.Mechanism.twist_basis)"
        )
    except ScrewkitError as err:
        jacobians_note = f"not computed: {err}"
    report = _finish(
        mechanism.name,
        mechanism.source,
        mechanism.length_unit,
        np.asarray(pose.poses),
        mechanism.pose_names,
        pose.graph,
        pose.analysis,
        diagram,
        sampler if superbracket else None,
        "structural zeros confirmed on random poses of the workspace (drawn and analysed as one batch); "
        "each stage equals the 6×6 determinant on fresh poses",
        jacobians,
        jacobians_note,
        progress=step,
    )
    from ..papers.paper_004_summary import transmission_summary

    return dataclasses.replace(
        report,
        transmission=transmission_summary(mechanism, report.pose, jacobians),
        given_length_scale=pose.length_scale,
        angle_names=mechanism.angle_names,
    )


def _finish(
    name: str,
    source: str,
    unit: str,
    pose: Array | None,
    pose_names: tuple[str, ...],
    graph: nx.MultiDiGraph,
    analysis: WrenchAnalysis,
    diagram: WrenchDiagram,
    sampler: Any,
    note: str,
    jacobians: Jacobians | None = None,
    jacobians_note: str = AnalysisReport.jacobians_note,
    *,
    progress: Callable[[str], None],
) -> AnalysisReport:
    result = None
    if sampler is None:  # not asked for, or the mechanism has no diagram (the reasons)
        note = "no factorization: " + "; ".join(diagram.degenerate) if diagram.degenerate else "not computed"
    else:
        try:
            from ..gca.superbracket_analysis import superbracket_analysis

            progress(STAGES[2])
            result = superbracket_analysis(diagram, sampler)
        except ScrewkitError as err:
            note = f"not factored: {err}"
    return AnalysisReport(
        name,
        source,
        unit,
        pose,
        pose_names,
        graph,
        equivalent_twist_graph(graph, tree=analysis.tree),  # the core's decomposition, not a second one
        analysis,
        classify_analysis(analysis),
        diagram,
        result,
        note,
        jacobians,
        jacobians_note,
    )
