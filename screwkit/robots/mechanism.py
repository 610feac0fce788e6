"""A catalog mechanism: a family (:mod:`screwkit.robots.families`) with its parameters, default pose,
workspace and expected facts, and what it gives at a pose or a batch of poses (the configuration,
the joint table, the twist graph, and :meth:`Mechanism.at`, the posed mechanism of
:mod:`screwkit.robots.posed`). Catalog entries are read by :mod:`screwkit.robots.catalog`.

Examples
--------
>>> h4 = load_mechanism("h4")
>>> isinstance(h4, Mechanism), h4.pose_names
(True, ('x', 'y', 'z', 'phi'))
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import networkx as nx
import numpy as np

from ..exceptions import (
    ScrewkitTypeError,
)
from ..graphs.jointtable import JointTable
from .angles import pose_text
from .families import Family, families
from .graph_kinematics import kinematics_of
from .pose_conversions import displacements_as_coordinates, forward_posed
from .pose_reader import check_pose_range, pose_array, read_poses
from .reach import random_reachable_poses, reachable_poses, unreachable_reasons

if TYPE_CHECKING:
    from ..core.jacobian_matrices import Jacobians

__all__ = ["Mechanism"]


#: The family's parameter and configuration types (:class:`~screwkit.robots.families.Family`).
P = TypeVar("P")
C = TypeVar("C")


Array = np.ndarray


@dataclass(frozen=True, eq=False)
class Mechanism(Generic[P, C]):
    """A catalog robot: a family, its parameters, default pose, workspace and expected facts;
    generic, as its :class:`~screwkit.robots.families.Family`, over the family's parameter type ``P``
    and configuration type ``C``.

    Attributes
    ----------
    name, family, length_unit : str
    source : str
        The file it was read from.
    sources : tuple of str
        The papers the entry comes from.
    parameters : P
        The family's validated parameter dataclass.
    parameter_sources : dict
        ``{parameter: {"value", "unit", "source"}}`` as written in the file.
    default_pose : numpy.ndarray
        In the file's length unit and **radians** (the file stores degrees).
    workspace : dict
        ``{coordinate: (low, high)}``, angles in radians.
    reachable_fraction : float
        The share of the workspace box the inverse kinematics reaches (``[workspace]
        reachable_fraction``, default 1: every pose). Below 1 the box is a bounding box:
        :meth:`random_poses` draws in its reachable part only, the maps of :mod:`screwkit.analysis.workspace`
        mask the rest as unreachable (checked by ``tests/robots/test_catalog.py`` against the IK).
    expected : tuple of dict
        The ``[[expected]]`` facts.
    """

    name: str
    family: str
    length_unit: str
    source: str
    sources: tuple[str, ...]
    parameters: P
    parameter_sources: dict[str, dict[str, Any]]
    default_pose: Array
    workspace: dict[str, tuple[float, float]]
    expected: tuple[dict[str, Any], ...] = field(default=())
    reachable_fraction: float = 1.0
    protocol: Family[P, C] | None = field(default=None, repr=False)

    def __repr__(self) -> str:
        """One line: name, family, the pose coordinates and their units, the default pose, the file.

        Returns
        -------
        str

        Examples
        --------
        >>> print(repr(load_mechanism("h4")).replace(", default", ",\\n    default"))
        Mechanism('H4', family four_limb, pose (x, y, z, phi) in mm and rad,
            default x = 0 mm, y = 0 mm, z = -750 mm, phi = 0 deg; h4.toml)
        """
        default = pose_text(self.default_pose, self.pose_names, self.angle_names, self.length_unit)
        units = self.length_unit + (" and rad" if self.angle_names else "")
        return (
            f"Mechanism({self.name!r}, family {self.family}, pose ({', '.join(self.pose_names)}) in {units}, "
            f"default {default}; {Path(self.source).name})"
        )

    @property
    def family_protocol(self) -> Family[P, C]:
        """The family's four functions (:mod:`screwkit.robots.families`): its own ``protocol`` when
        it has one (a graph mechanism, :func:`screwkit.robots.graph_mechanism.mechanism`), else the
        registered family's."""
        return self.protocol if self.protocol is not None else families()[self.family]

    @property
    def coordinates(self) -> tuple[str, ...]:
        """The pose coordinates' names (:attr:`pose_names`)."""
        return self.pose_names

    @property
    def reference_pose(self) -> Array:
        """The reference (default) pose in the coordinates, graph or file unit and radians."""
        return np.asarray(self.default_pose, dtype=float)

    @property
    def actuated(self) -> tuple[str, ...]:
        """The actuated joints in the order :meth:`forward` takes their values (name order, as the
        analysis core and the Jacobians' rows)."""
        return kinematics_of(self).actuated

    def forward(
        self, values: Any, *, rtol: float | None = None, length_scale: float | None = None
    ) -> Any:
        """The mechanism at actuated-joint displacements (forward kinematics by loop closure, continued
        from the reference configuration: the assembly mode connected to it).

        Parameters
        ----------
        values : array_like, shape (..., k)
            Displacements of :attr:`actuated` from the reference configuration (radians; lengths in
            the graph's or file's unit).
        rtol, length_scale : float, optional
            As in :meth:`at`.

        Returns
        -------
        PosedMechanism
            Its ``poses`` are the platform coordinates reached (rotations in ``(−π, π]`` about the
            reference's; NaN where the continuation could not reach the values:
            ``reachable`` False and the reason in ``failures``).

        Raises
        ------
        ScrewkitValueError
            If ``values`` does not have one value per actuated joint or is not finite.

        Examples
        --------
        >>> h4 = load_mechanism("h4")
        >>> posed = h4.forward(np.zeros((1, 4)))
        >>> posed.poses.round(9).tolist(), posed.verdicts.tolist()
        ([[0.0, 0.0, -750.0, 0.0]], ['regular'])
        """
        return forward_posed(self, values, rtol=rtol, length_scale=length_scale)

    def unreachable_reasons(self, poses: Array, **options: Any) -> Array:
        """Why each pose ``(m, n)`` is out of reach (an empty string where it is reachable).

        Parameters
        ----------
        poses : numpy.ndarray, shape (m, n)
            In the file's length unit and radians.
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        numpy.ndarray of str, shape (m,)

        Examples
        --------
        >>> load_mechanism("v4").unreachable_reasons(np.array([[0, 0, -750, 0], [0, 0, -3000, 0]]))[1][:30]
        'Pose (x, y, z, phi) = (0, 0, -'
        """
        return unreachable_reasons(self, pose_array(self, poses), options)

    @property
    def pose_names(self) -> tuple[str, ...]:
        """Names of the pose coordinates, e.g. ``('x', 'y', 'z', 'phi')``."""
        return self.family_protocol.pose_names

    @property
    def angle_names(self) -> tuple[str, ...]:
        """The pose coordinates that are angles (radians in the API, degrees in files and the CLI)."""
        return self.family_protocol.angle_names

    def configuration(self, pose: Any = None, *, angles: str = "rad", **options: Any) -> C:
        """The family's configuration (inverse kinematics) at a pose or a batch ``(..., n)``
        (default: the default pose).

        Parameters
        ----------
        pose : array_like, shape (..., n), optional
            In the file's length unit and radians; default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        object
            The family's configuration over the batch (its type is the family's ``C``).

        Examples
        --------
        >>> load_mechanism("h4").configuration().theta.shape
        (4,)
        """
        pose = read_poses(self, pose, "pose", angles=angles)
        chosen = self.default_pose if pose is None else pose
        self._check_options(options)
        return self.family_protocol.inverse_kinematics(self.parameters, chosen, **options)

    def _check_options(self, options: Mapping[str, Any]) -> None:
        """Refuse inverse-kinematics options the family's solver does not take (naming those it does)."""
        if not options:  # nothing to refuse (and no signature to read, chunk after chunk)
            return
        solve = self.family_protocol.inverse_kinematics
        accepted = [
            p.name
            for p in list(inspect.signature(solve).parameters.values())[2:]
            if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)
        ]
        unknown = sorted(set(options) - set(accepted))
        if unknown:
            raise ScrewkitTypeError(
                f"Expected inverse-kinematics options of the {self.family} family among {accepted}, "
                f"got {unknown}."
            )

    def joints(self, pose: Any = None, *, angles: str = "rad", **options: Any) -> JointTable:
        """The joint table at a pose or a batch of poses (the input of the analysis core).

        Parameters
        ----------
        pose : array_like, shape (..., n), optional
            In the file's length unit and radians; default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        JointTable
            Every joint's screws over the batch of poses.

        Examples
        --------
        >>> table = load_mechanism("h4").joints(np.zeros((3, 4)) + [0, 0, -750, 0])
        >>> table.batch_shape, len(table.specs)
        ((3,), 22)
        """
        return self.family_protocol.joint_table(self.configuration(pose, angles=angles, **options))

    def at(
        self,
        poses: Any = None,
        *,
        angles: str = "rad",
        rtol: float | None = None,
        length_scale: float | None = None,
        **options: Any,
    ) -> Any:
        """The mechanism at a batch of poses: a frozen :class:`~screwkit.robots.posed.PosedMechanism` whose
        stages (IK, joints, wrench systems, verdicts, Jacobians) are computed once, on demand.

        Parameters
        ----------
        poses : array_like, shape (..., n) or (..., 4, 4), optional
            Coordinates in the file's length unit and ``angles``, or rigid displacements of the
            platform relative to the reference configuration in the base frame, rotating about the
            platform point (a 2-D ``(4, 4)`` array is four poses of a four-coordinate robot: give one
            displacement as ``(1, 4, 4)``); default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the poses' angle coordinates (:mod:`screwkit.robots.angles`; beyond a turn in
            radians, an :class:`~screwkit.robots.angles.AngleUnitWarning`).
        rtol : float, optional
            Relative tolerance of every rank decision (default 1e-9).
        length_scale : float, optional
            The characteristic length of the rank decisions, in the file's length unit; default:
            derived from each pose's screws (:func:`~screwkit.core.wrench_systems.analyze_table`).
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        PosedMechanism
            The mechanism at ``poses``; its stages are computed on first use.

        Examples
        --------
        >>> posed = load_mechanism("h4").at([[0, 0, -750, 0], [50, 20, -800, 0.3]])
        >>> posed.verdicts.tolist()
        ['regular', 'regular']
        >>> load_mechanism("h4").at([0, 0, -750, 45], angles="deg").poses.round(4).tolist()
        [[0.0, 0.0, -750.0, 0.7854]]
        >>> print(posed[1].singularity)  # doctest: +ELLIPSIS
        regular (dof 4): constraint order 2/2, global order 6/6
          closeness (0 at a singularity): constraint 0.968, actuation ...
        """
        from .posed import PosedMechanism

        self._check_options(options)
        coordinates = displacements_as_coordinates(self, poses)  # 4×4 displacements carry no angle unit
        poses = read_poses(self, coordinates, angles=angles if coordinates is poses else "rad")
        return PosedMechanism.create(self, poses, rtol=rtol, length_scale=length_scale, options=options)

    def check_pose_range(self, poses: Any, argument: str = "poses") -> None:
        """Refuse pose coordinates and angles beyond their bounds
        (:func:`screwkit.robots.pose_reader.check_pose_range`).

        Parameters
        ----------
        poses : array_like or None
            In the file's length unit and radians.
        argument : str, optional
            Named by the message.

        Raises
        ------
        ScrewkitValueError
            Beyond a bound.

        Examples
        --------
        >>> load_mechanism("h4").check_pose_range([[0, 0, -750, 0], [0, 0, 1e101, 0]])  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected pose coordinates up to 1e+100 in size ... got 1e+101.
        """
        check_pose_range(self, poses, argument)

    def random_poses(self, rng: np.random.Generator, count: int) -> Array:
        """Poses drawn uniformly in the *reachable* part of the operational workspace (radians),
        ``(count, n)``: draws whose inverse kinematics has no solution are drawn again (rejection keeps
        the distribution uniform; the first ``count`` draws are returned when all are reachable).

        Parameters
        ----------
        rng : numpy.random.Generator
            The source of randomness.
        count : int
            How many poses.

        Returns
        -------
        numpy.ndarray, shape (count, n)
            Reachable poses of the workspace box, in the file's length unit and radians.

        Raises
        ------
        ScrewkitValueError
            If ``count`` is not a non-negative integer, or fewer than 1 draw in
            :data:`~screwkit.robots.reach.MAX_REJECTION_ROUNDS` is reachable (the workspace box is
            mostly out of reach).

        Examples
        --------
        >>> poses = load_mechanism("h4").random_poses(np.random.default_rng(0), 3)
        >>> poses.shape
        (3, 4)
        """
        return random_reachable_poses(self, rng, count)

    def reachable(self, poses: Array, **options: Any) -> Array:
        """Which poses ``(m, n)`` (API units) the inverse kinematics accepts, ``(m,)`` bool.

        The family's vectorised ``reachable(parameters, poses)`` (:class:`~screwkit.robots.families.Family`)
        when it has one and no option changes the inverse kinematics' domain (the four-limb
        family: every working mode reaches the same poses), else one batch call of
        :meth:`configuration`, halved where a batch is refused
        (:class:`~screwkit.exceptions.UnreachablePoseError`).

        Parameters
        ----------
        poses : numpy.ndarray, shape (m, n)
            In the file's length unit and radians.
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        numpy.ndarray of bool, shape (m,)
            True where the inverse kinematics accepts the pose.

        Examples
        --------
        >>> load_mechanism("v4").reachable(np.array([[0, 0, -750, 0], [0, 0, -3000, 0]]))
        array([ True, False])
        """
        return reachable_poses(self, pose_array(self, poses), options)

    def wrench_diagram(
        self, pose: Any = None, *, angles: str = "rad"
    ) -> tuple[Any, Callable[[np.random.Generator], dict[str, Array]]]:
        """The wrench diagram at a pose, and a sampler of its recipes at random workspace poses
        (:meth:`screwkit.robots.posed.PosedMechanism.diagram_and_sampler`).

        Parameters
        ----------
        pose : array_like, shape (n,), optional
            In the file's length unit and radians; default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).

        Returns
        -------
        tuple
            The :class:`~screwkit.gca.diagram.WrenchDiagram` at the pose, and ``sample(rng)``, which gives the
            diagram's point recipes at a random workspace pose.

        Examples
        --------
        >>> diagram, sampler = load_mechanism("h4").wrench_diagram()
        >>> sorted(sampler(np.random.default_rng(1)))[:3]
        ['a', 'b', 'c']
        """
        return self._one(pose, {}, angles).diagram_and_sampler()

    @property
    def operation_modes(self) -> Any:
        """The operation modes found from the default pose, its own first (an `OperationModes` search).

        Returns
        -------
        OperationModes

        Examples
        --------
        >>> [mode.motion_type for mode in load_mechanism("planar_3rrp").operation_modes]
        ['2T1R']
        """
        from ..core.mode_search import find_operation_modes
        return find_operation_modes(self.twist_graph())

    def twist_graph(self, pose: Any = None, *, angles: str = "rad", **options: Any) -> nx.MultiDiGraph:
        """The twist graph of the physical mechanism at one pose (default: the default pose).

        Parameters
        ----------
        pose : array_like, shape (n,), optional
            In the file's length unit and radians; default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        networkx.MultiDiGraph
            The twist graph of the physical mechanism at that pose.

        Examples
        --------
        >>> load_mechanism("h4").twist_graph().graph["dof"]
        4
        """
        return self._one(pose, options, angles).graph

    def twist_basis(self, pose: Any = None, *, angles: str = "rad", **options: Any) -> Array:
        """The platform's nominal twists at a pose (default: the default pose), rows ``(dof, 6)``.

        One twist per pose coordinate, in the order of :attr:`pose_names` (unit rate of that
        coordinate, user frame): for the Schönflies-motion generators the three translations and
        the rotation about the end effector's own axis through its reference point, for the planar
        3-RRP the translations ``x``, ``y`` and the rotation about ``z`` through the platform point.
        ``options`` go to :meth:`configuration` (e.g. a working mode).

        Parameters
        ----------
        pose : array_like, shape (n,), optional
            In the file's length unit and radians; default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        numpy.ndarray, shape (dof, 6)
            One nominal twist per pose coordinate.

        Examples
        --------
        >>> load_mechanism("v4").twist_basis()[3]  # the V4's end effector turns about j
        array([  0.,   1.,   0., 750.,   0.,   0.])
        """
        return self._one(pose, options, angles).twist_basis

    def jacobians(self, pose: Any = None, *, angles: str = "rad", **options: Any) -> Jacobians:
        """Forward and inverse Jacobians ``A χ̇ = B θ̇`` from the wrench systems at a pose.

        :func:`screwkit.core.jacobians.jacobians_from_wrenches` of the wrench analysis over
        :meth:`twist_basis` (so ``χ̇`` are the rates of the pose coordinates), with its
        Gosselin–Angeles type and closeness measures. ``options`` go to :meth:`configuration`.

        Parameters
        ----------
        pose : array_like, shape (n,), optional
            In the file's length unit and radians; default: the default pose.
        angles : {"rad", "deg"}, default "rad"
            The unit of the pose's angle coordinates (:mod:`screwkit.robots.angles`).
        **options
            Passed to the inverse kinematics (a working mode).

        Returns
        -------
        Jacobians
            ``A`` and ``B`` of ``A χ̇ = B θ̇`` at that pose, with their type.

        Raises
        ------
        ScrewkitError
            If the pose is out of reach (naming the limb), or the basis is refused at this pose
            (:func:`~screwkit.core.jacobians.jacobians_from_wrenches`).

        Examples
        --------
        >>> jac = load_mechanism("planar_3rrp").jacobians()
        >>> jac.type, jac.A.shape, jac.actuated_joints
        ('regular', (3, 3), ('limb1_R1', 'limb2_R1', 'limb3_R1'))
        """
        return self._one(pose, options, angles).jacobians

    def _one(self, pose: Any, options: dict[str, Any], angles: str) -> Any:
        """One pose through the composer (:meth:`at`)."""
        chosen = None if pose is None else pose_array(self, pose, "pose", one=True)
        return self.at(chosen, angles=angles, **options)[0]
