"""A mechanism at a batch of poses: every stage computed once, on demand (docs/architecture.md §1a).

:meth:`screwkit.robots.mechanism.Mechanism.at` returns a frozen :class:`PosedMechanism`. Its stages are
cached properties over the whole batch, each built on the one before:

``configuration`` (the family's inverse kinematics) → ``joints`` (a
:class:`~screwkit.graphs.jointtable.JointTable`) → ``singularities`` (labels, orders, closeness: the inverse
kinematics, joint table and analysis core chunk by chunk, :func:`~screwkit.core.singularity.classify_chunks`,
so that a large batch never holds its whole table) → ``jacobians`` (``A χ̇ = B θ̇`` over the family's
nominal twists) → ``wrench_transmission`` (input/output transmission from the actuation wrenches,
any family: :mod:`screwkit.robots.transmission`). :meth:`PosedMechanism.diagram_points` evaluates a
wrench diagram's points over the batch. The composer hands its results on: maps, loci and paths
(:mod:`screwkit.analysis`), paper 004's indices (:func:`screwkit.papers.paper_004.transmission`) and
the report (:func:`screwkit.interface.report.analyze` of one pose) read them; it calls none of them
(``posed[i].report()`` calls the composer registered in :mod:`screwkit.robots.report_composer`).

Indexing gives a :class:`PosedMechanism` of shape ``()`` (one pose, its row of the batch's joint table):
only there are the per-pose views, its graph, wrench analysis (a batch of one through the same
kernels), verdict, Jacobians, wrench diagram, superbracket (generic samples drawn as one batch), report.

Examples
--------
>>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
>>> posed.shape, posed.singularities.constraint_order.tolist()
((2,), [2, 2])
>>> posed[0].shape, posed[0].singularity.verdict
((), 'regular')
"""

from __future__ import annotations

import functools
import weakref
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.checks import checked_length_scale, checked_rtol
from ..core.jacobian_matrices import Jacobians
from ..core.jacobians import jacobians_from_wrenches
from ..core.singularity import classify_chunks, label_table
from ..core.verdicts import LABELS, SingularityReport
from ..core.wrench_systems import WrenchAnalysis, analyze_table
from ..exceptions import (
    ScrewkitError,
    ScrewkitIndexError,
    ScrewkitValueError,
    UnreachablePoseError,
)
from ..graphs.jointtable import JointTable
from .pose_batch import (
    UNREACHABLE,
    batch_html,
    batch_repr,
    checked_poses,
    joint_table_of,
    one_pose,
    per_pose,
    reachable_part,
    reached_view,
)
from .pose_diagram import (
    diagram_points_over_batch,
    generic_draws,
    pose_diagram_and_sampler,
    pose_superbracket,
)
from .reach import failures_by_index
from .report_composer import report_composer
from .transmission import Transmission, wrench_transmission

__all__ = ["PosedMechanism"]

Array = np.ndarray

#: Poses taken through the inverse kinematics, joint table and analysis core at once.
CHUNK = 512


@dataclass(frozen=True, eq=False)
class PosedMechanism:
    """A catalog mechanism at a batch of poses (see the module docstring).

    Attributes
    ----------
    mechanism : Mechanism
    poses : numpy.ndarray, shape (..., n)
        Length unit of the file, radians; read-only. Shape ``(n,)`` for one pose (``posed[i]``).
    rtol : float
    length_scale : float or None
        The characteristic length of the rank decisions in the file's length unit; None: derived
        per pose (:func:`~screwkit.core.wrench_systems.analyze_table`).
    options : dict
        Passed to the inverse kinematics (a working mode).
    """

    mechanism: Any = field(repr=False)
    poses: Array
    rtol: float
    length_scale: float | None = None
    options: dict[str, Any] = field(default_factory=dict, repr=False)
    #: The batch this pose was indexed from and its flat index there (its nominal twists are read
    #: from the batch's), or None.
    _batch: tuple[PosedMechanism, int] | None = field(default=None, repr=False)
    #: Known unreachable poses (index → reason), e.g. from the forward kinematics, or None.
    _failures: dict[tuple[int, ...], str] | None = field(default=None, repr=False)

    @classmethod
    def create(
        cls,
        mechanism: Any,
        poses: Any,
        *,
        rtol: float | None = None,
        length_scale: float | None = None,
        options: Any = None,
        failures: dict[tuple[int, ...], str] | None = None,
    ) -> PosedMechanism:
        """Validate and build (what :meth:`screwkit.robots.mechanism.Mechanism.at` calls).

        Parameters
        ----------
        mechanism : Mechanism
        poses : array_like, shape (..., n), optional
            None: the default pose.
        rtol : float, optional
        length_scale : float, optional
        options : mapping, optional
            Inverse-kinematics options.
        failures : dict, optional
            Poses known to be out of reach (batch index → reason; their coordinates may be NaN).

        Returns
        -------
        PosedMechanism

        Examples
        --------
        >>> PosedMechanism.create(load_mechanism("h4"), [0, 0, -750])  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected `poses` to have shape (..., 4), got (3,) ...
        """
        if failures:  # the unreached poses' NaN coordinates are part of the answer
            missing = np.isnan(np.asarray(poses, dtype=float))
            array = checked_poses(mechanism, np.where(missing, 0.0, poses))
            array[missing.reshape(array.shape)] = np.nan
        else:
            array = checked_poses(mechanism, poses)
        array.flags.writeable = False
        tolerance = B.DEFAULT_RTOL if rtol is None else checked_rtol(rtol)
        length = checked_length_scale(length_scale, allow_none=True)
        return cls(mechanism, array, tolerance, length, dict(options or {}), _failures=failures)

    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape."""
        return self.poses.shape[:-1]

    def __len__(self) -> int:
        if self.shape == ():
            raise TypeError("a posed mechanism of one pose has no length")
        return self.shape[0]

    def _one(self, view: str) -> None:
        """Raise unless this is one pose (shape ``()``): the per-pose views need one."""
        if self.shape != ():
            raise ScrewkitValueError(
                f"PosedMechanism.{view} needs one pose: index the batch (posed[i]) first, "
                f"got shape {self.shape}."
            )

    def __iter__(self) -> Iterator[PosedMechanism]:
        """Every pose of the batch in turn, in C order over :attr:`shape` (for a batch of shape
        ``(n,)``: ``posed[0]``, ..., ``posed[n - 1]``).

        Returns
        -------
        iterator of PosedMechanism
            Each of shape ``()``.

        Raises
        ------
        TypeError
            For one pose (shape ``()``).

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[30, -20, -750, 0.3], [0, 0, -800, 0.1]])
        >>> [pose.singularity.verdict for pose in posed]
        ['regular', 'regular']
        """
        if self.shape == ():
            raise TypeError("a posed mechanism of one pose is not iterable")
        return (self[index] for index in np.ndindex(*self.shape))

    def __repr__(self) -> str:
        """One line: the mechanism, the pose with its units (a batch: its shape), ``rtol``.

        Returns
        -------
        str

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[30, -20, -750, 0.3], [0, 0, -800, 0.1]])
        >>> posed
        PosedMechanism('H4', shape=(2,), rtol=1e-09)
        >>> posed[0]
        PosedMechanism('H4' at x = 30 mm, y = -20 mm, z = -750 mm, phi = 17.19 deg, rtol=1e-09)
        """
        return batch_repr(self)

    def _repr_html_(self) -> str:
        """Jupyter: the poses with their units and each pose's verdict as a table (the first 20 of a
        batch); one pose adds its singularity report.

        Returns
        -------
        str
        """
        return batch_html(self)

    @functools.cached_property
    def failures(self) -> dict[tuple[int, ...], str]:
        """Why each pose not reached is out of reach: batch index → reason (the closed form's condition;
        for a graph mechanism the continuation's: its way left the reach, met a singularity or would
        change working mode, with the residual). Not a proof that the pose lies outside the workspace;
        for a graph mechanism it may depend on the batch (:attr:`reachable`)."""
        if self._failures is not None:
            return dict(self._failures)
        return failures_by_index(self.mechanism, self.poses, self.options)

    @functools.cached_property
    def reachable(self) -> Array:
        """Per pose: whether the inverse kinematics found it in the reference's working and assembly
        mode (the reasons in :attr:`failures`). A graph mechanism's continuation continues a large
        batch's far poses from solved poses of its own, so a pose may be reached in a batch and not
        alone (never the reverse; docs/mechanisms.md, "What `reachable` means")."""
        out = np.ones(self.shape, dtype=bool)
        if self._failures is None:
            flat = self.poses.reshape(-1, self.poses.shape[-1])
            return np.asarray(self.mechanism.reachable(flat, **self.options)).reshape(self.shape)
        for index in self._failures:
            out[index] = False
        return out

    @functools.cached_property
    def configuration(self) -> Any:
        """The family's configuration over the batch (inverse kinematics)."""
        if self._failures:  # known out of reach (e.g. by the forward kinematics): no configuration
            index, reason = next(iter(self._failures.items()))
            where = f"Pose {index}" if index else "The pose"
            raise UnreachablePoseError(f"{where} is out of reach: {reason.rstrip('.')}.")
        try:
            return self.mechanism.configuration(self.poses, **self.options)
        except ScrewkitError:
            if self.poses.shape[:-1] == (1,):  # one pose: the family's own single-pose message
                self.mechanism.configuration(self.poses[0], **self.options)
            raise

    @functools.cached_property
    def joints(self) -> JointTable:
        """The joint table over the batch."""
        return self.mechanism.family_protocol.joint_table(self.configuration)

    @functools.cached_property
    def twist_basis(self) -> Array:
        """The platform's nominal twists ``(..., dof, 6)``, one per pose coordinate (one pose of a
        batch: its row of the batch's)."""
        if self._batch is not None:
            batch, flat = self._batch
            basis = batch.twist_basis
            return basis.reshape(-1, *basis.shape[-2:])[flat]
        return np.asarray(self.mechanism.family_protocol.twist_basis(self.configuration), dtype=float)

    @functools.cached_property
    def singularities(self) -> SingularityReport:
        """Labels, orders and closeness over the batch (the analysis core, in chunks).

        Unless the joint table is already there, each chunk of :data:`CHUNK` poses goes through
        the inverse kinematics, its joint table and the core in turn, so memory stays bounded by
        the chunk and the results; the whole table is computed only if a per-pose view asks. One
        pose (shape ``()``): its :attr:`singularity`. The one whole-batch view that needs every pose
        reached (its wrench systems; else :class:`~screwkit.exceptions.UnreachablePoseError` naming the
        first out of reach): the per-pose views (:attr:`verdicts`, :attr:`codes`, :attr:`closeness`,
        :attr:`redundancy`, :attr:`jacobians`, :attr:`wrench_transmission`) mark a pose out of reach.
        """
        if self.shape == ():
            return self.singularity
        if "joints" in self.__dict__:
            return label_table(  # the family's dof
                self.joints, rtol=self.rtol, length_scale=self.length_scale, chunk=CHUNK
            )
        try:
            # the report's table, asked only by a per-pose view, is this object's (held weakly: a
            # reference cycle would keep every chunk of a map alive until the cyclic GC runs)
            owner = weakref.ref(self)
            source = functools.partial(joint_table_of, owner, self.mechanism, self.poses, self.options)
            return classify_chunks(
                self._table_chunks(), source, self.shape, rtol=self.rtol, length_scale=self.length_scale
            )
        except ScrewkitError:
            try:
                _ = self.configuration  # the whole batch's message (the failing pose's index)
            except UnreachablePoseError as err:
                raise UnreachablePoseError(
                    f"{str(err).rstrip('.')}; the whole batch's singularities need every pose in reach (the "
                    "per-pose views mark it: posed.verdicts, codes, closeness, jacobians)."
                ) from err
            raise

    def _table_chunks(self) -> Iterator[JointTable]:
        """The batch's joint table, flattened, in chunks of :data:`CHUNK` poses: slices of
        :attr:`joints` once computed, else each chunk through the inverse kinematics and the
        family's joints in turn (the whole table never held)."""
        if "joints" in self.__dict__ or self.shape == ():
            table, shape = (self.joints[None], (1,)) if self.shape == () else (self.joints, self.shape)
            count = int(np.prod(shape))
            for start in range(0, count, CHUNK):
                yield table[np.unravel_index(np.arange(start, min(start + CHUNK, count)), shape)]
            return
        if self._failures:
            _ = self.configuration  # names the first pose out of reach
        flat = self.poses.reshape(-1, self.poses.shape[-1])
        protocol, configuration = self.mechanism.family_protocol, self.mechanism.configuration
        for start in range(0, max(len(flat), 1), CHUNK):
            yield protocol.joint_table(configuration(flat[start : start + CHUNK], **self.options))

    @property
    def failures_known(self) -> bool:
        """Whether some poses are known to be out of reach from the start (e.g. by the forward kinematics)."""
        return bool(self._failures)

    @functools.cached_property
    def reached_part(self) -> tuple[Array, PosedMechanism | None] | None:
        """None when every pose is reached, else the flat mask of those that are and the posed mechanism
        at them (:func:`~screwkit.robots.pose_batch.reachable_part`): what the per-pose views read."""
        return reachable_part(self)

    @property
    def verdicts(self) -> Array:
        """``"regular"``, ``"constraint singularity"``, ... per pose (an object array), ``"unreachable"``
        where a pose is out of reach (the reason in :attr:`failures`)."""
        return per_pose(self, lambda p: np.asarray(p.singularities.verdict), UNREACHABLE, object)

    @property
    def codes(self) -> Array:
        """Per pose: bit 1 constraint, 2 actuation, 4 serial (:attr:`SingularityReport.codes`), ``-1`` out
        of reach."""
        return per_pose(self, lambda p: p.singularities.codes, -1, np.int64)

    @property
    def redundancy(self) -> Any:
        """The degree of actuation redundancy per pose, the actuated joints minus the freedoms they drive
        (:attr:`SingularityReport.redundancy <screwkit.core.verdicts.SingularityReport.redundancy>`; an int
        for one pose), ``-1`` out of reach."""
        out = per_pose(self, lambda p: p.singularities.redundancy, -1, np.int64)
        return int(out) if self.shape == () else out

    @property
    def closeness(self) -> dict[str, Array]:
        """The closeness measures per pose (:mod:`screwkit.core.singularity`), NaN out of reach."""
        if self.reached_part is None:
            return self.singularities.closeness
        return {k: per_pose(self, lambda p, k=k: p.singularities.closeness[k], np.nan, float) for k in LABELS}

    @functools.cached_property
    def jacobians(self) -> Jacobians:
        """``A χ̇ = B θ̇`` per pose over the family's nominal twists (one pose: from its :attr:`analysis`).
        A pose out of reach has NaN matrices, closeness and determinants and the type ``"unreachable"``;
        the others get what a batch of the reached poses alone gives
        (:func:`~screwkit.robots.pose_batch.reached_view`)."""
        if self.shape != () and self.reached_part is not None:
            return reached_view(self, "jacobians")
        analysis = self.analysis if self.shape == () else self.singularities.analysis
        return jacobians_from_wrenches(analysis, self.twist_basis, rtol=self.rtol)

    @functools.cached_property
    def wrench_transmission(self) -> Transmission:
        """Input/output transmission per actuated joint and their LTI, from the actuation wrenches and
        the nominal twists, for any family (:func:`screwkit.robots.transmission.wrench_transmission`;
        the input at the points the family's optional ``application_points`` hook gives, e.g. the
        elbows of the four-limb family). NaN at a pose out of reach
        (:func:`~screwkit.robots.pose_batch.reached_view`)."""
        if self.shape != () and self.reached_part is not None:
            return reached_view(self, "wrench_transmission")
        hook = self.mechanism.family_protocol.application_points
        points = None if hook is None else hook(self.configuration)
        return wrench_transmission(self.jacobians, input_points=points)

    def diagram_points(self, points: tuple[Any, ...]) -> tuple[dict[str, Array], Array]:
        """A wrench diagram's points at every pose of the batch, in the core's chunks.

        The joint table goes through the analysis core :data:`CHUNK` poses at a time, lean (as for
        the verdicts, without the per-pose views) keeping only the frames the points' recipes read
        (:func:`screwkit.gca.diagram_points.frames_read`: a few branches' twists, the legs'
        constraint systems), then the recipes over the chunk
        (:func:`screwkit.gca.diagram_points.batch_diagram_points`): one wrench pass, only the points kept.

        Parameters
        ----------
        points : tuple of DiagramPoint
            The points of a wrench diagram (``diagram.points``), each with a ``label``.

        Returns
        -------
        values : dict of str to numpy.ndarray, shape (..., 4)
            Per label, the point's homogeneous coordinates over the batch (its :attr:`shape`; NaN
            where it does not exist); shape ``(4,)`` for one pose.
        exists : numpy.ndarray of bool, shape (...)
            Where every point exists; shape ``()`` for one pose.

        Raises
        ------
        UnreachablePoseError
            Naming the first pose out of reach.

        Examples
        --------
        >>> h4 = load_mechanism("h4")
        >>> diagram = h4.at()[0].diagram
        >>> values, exists = h4.at([[0, 0, -750, 0], [30, -20, -750, 0.3]]).diagram_points(diagram.points)
        >>> len(values) == len(diagram.points), exists.tolist()
        (True, [True, True])
        """
        return diagram_points_over_batch(self, points)

    def __getitem__(self, index: Any) -> PosedMechanism:
        """One pose of the batch: a posed mechanism of shape ``()`` with its row of the joint table.

        Parameters
        ----------
        index : int or tuple of int
            One integer per batch axis.

        Returns
        -------
        PosedMechanism
            Of shape ``()``; its joint table and nominal twists are read from this batch's (computed
            once for the whole batch), not from a new inverse kinematics.

        Raises
        ------
        ScrewkitIndexError
            If the index is out of range, or this is one pose already.
        ScrewkitValueError
            If the index does not pick one pose.

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
        >>> posed[1].shape, posed[1].poses.tolist()
        ((), [30.0, -20.0, -750.0, 0.3])
        """
        if self.shape == ():
            raise ScrewkitIndexError(
                f"Expected a batch to index, got one pose (shape ()) at {self.poses.tolist()}."
            )
        return one_pose(self, index)

    @functools.cached_property
    def graph(self) -> nx.MultiDiGraph:
        """The twist graph of the physical mechanism at this pose (one pose only)."""
        self._one("graph")
        graph = self.joints.graph()
        graph.graph["name"] = self.mechanism.name
        graph.graph["length_unit"] = self.mechanism.length_unit
        return graph

    @functools.cached_property
    def analysis(self) -> WrenchAnalysis:
        """The wrench systems (a batch of one through the core, with the per-pose views; one pose only)."""
        self._one("analysis")
        one = self.joints[None]
        return self._with_graph(analyze_table(one, rtol=self.rtol, length_scale=self.length_scale)[0])

    def _with_graph(self, result: WrenchAnalysis) -> WrenchAnalysis:
        object.__setattr__(result, "graph", self.graph)
        return result

    @functools.cached_property
    def singularity(self) -> SingularityReport:
        """The verdict at this pose (one pose only)."""
        self._one("singularity")
        return SingularityReport(self.analysis)

    @functools.cached_property
    def _draws(self) -> tuple[Sequence[WrenchAnalysis], WrenchAnalysis | None, np.random.Generator]:
        """The generic draws, this pose and the first samples through the core as one batch
        (:func:`~screwkit.robots.pose_diagram.generic_draws`; one pose only)."""
        self._one("diagram_and_sampler()")
        return generic_draws(self)

    def diagram_and_sampler(self) -> tuple[Any, Callable[[np.random.Generator], dict[str, Array]]]:
        """The wrench diagram at this pose and a sampler of its recipes at generic poses (one pose only).

        Which lines make the diagram and which points they share is decided at a generic (random,
        seeded) workspace pose of :data:`~screwkit.robots.generic_poses.GENERIC_DRAWS` drawn as one batch
        (:func:`screwkit.gca.diagram_placement.generic_reference`); the diagram is then placed at this pose
        (:func:`screwkit.gca.diagram_placement.diagram_at`), where lines that coincide still appear. When the
        mechanism has no diagram (e.g. a wrench system not spanned by lines), the reasons found at
        the generic poses are given as ``degenerate``. The sampler
        replays recipes evaluated at random workspace poses, drawn and analysed as one batch
        (:func:`~screwkit.robots.generic_poses.generic_samples`).

        Returns
        -------
        diagram : WrenchDiagram
        sampler : callable
            ``sampler(rng) -> {label: (4,)}``, the diagram's points at a generic pose.

        Raises
        ------
        ScrewkitValueError
            On a batch (index it first).

        Examples
        --------
        >>> diagram, sampler = load_mechanism("h4").at()[0].diagram_and_sampler()
        >>> len(diagram.points) > 0
        True
        """
        return pose_diagram_and_sampler(self)

    @functools.cached_property
    def diagram(self) -> Any:
        """The wrench diagram at this pose (:class:`screwkit.gca.diagram.WrenchDiagram`; the first item
        of :meth:`diagram_and_sampler`; one pose only)."""
        self._one("diagram")
        return self.diagram_and_sampler()[0]

    @functools.cached_property
    def superbracket(self) -> Any:
        """The superbracket of this pose's wrench diagram, expanded, simplified, factored and
        interpreted (:func:`screwkit.gca.superbracket_analysis.superbracket_analysis`; what
        :func:`screwkit.interface.report.analyze` shows; one pose only).

        A redundantly actuated mechanism's diagram has more than six lines: its superbracket is
        then the :class:`~screwkit.gca.redundant_conditions.RedundantSuperbracket` of its six-line
        subsets.

        Raises
        ------
        ScrewkitValueError
            On a batch (index it first), or if the mechanism has no wrench diagram of six lines (or
            more) at generic poses (a diagram that degenerates only at this pose is still factored there).
        """
        self._one("superbracket")
        return pose_superbracket(self)

    def report(self, *, superbracket: bool = True, progress: Callable[[str], None] | None = None) -> Any:
        """The whole analysis of this pose as one report: what ``sk.analyze(posed[i])`` returns
        (:func:`screwkit.interface.report.analyze`), for a catalog robot and for a graph or snapshot
        mechanism (``sk.mechanism(graph).at(poses)[i]``) alike.

        The report is composed by the interface, a layer above this one: the robots may not import it
        (docs/architecture.md §2), so this method calls the composer that ``import screwkit`` registers
        (:mod:`screwkit.robots.report_composer`, dependency inversion): ``analyze`` itself, which checks
        the arguments.

        Parameters
        ----------
        superbracket : bool, default True
            Also expand and factor the superbracket (skip for speed).
        progress : callable, optional
            Called with the name of each stage as it starts (``screwkit.interface.report.STAGES``).

        Returns
        -------
        AnalysisReport

        Raises
        ------
        ScrewkitValueError
            On a batch (index it first: ``posed[i]``).
        UnreachablePoseError
            If this pose is out of reach (with the reason, :attr:`failures`).
        ScrewkitTypeError
            If ``superbracket`` is not a bool or ``progress`` not callable.

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])
        >>> report = posed[1].report(superbracket=False)
        >>> report.verdict.verdict, report.pose.tolist()
        ('regular', [30.0, -20.0, -750.0, 0.3])
        >>> posed.report()  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected one pose of a posed mechanism (index the batch: ...
        """
        if self.shape == ():  # (a batch: refused by the composer, as analyze refuses it)
            _ = self.joints  # a pose out of reach raises its reason here, before any stage starts
        return report_composer()(self, superbracket=superbracket, progress=progress)
