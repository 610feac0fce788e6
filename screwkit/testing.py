"""Conformance checks for a mechanism family (:mod:`screwkit.robots.families`): what every family
must satisfy, checked on its catalog robots at sampled poses.

:func:`check_family` runs five checks and returns a :class:`FamilyReport` (one :class:`Check` per
check and robot; :meth:`FamilyReport.raise_if_failed` raises listing the failures):

``closure``
    First-order closure of the inverse kinematics: every row of ``twist_basis`` (the platform's
    nominal twists) lies in the twist system of every limb (the span of its joint screws, its
    closed sub-loops solved by the analysis core) and in the platform's twist system (reciprocal to
    every constraint wrench: the motions the closed chains allow to first order). A wrong row, or
    joint screws that do not follow the configuration, leave it out.
``jacobian``
    ``B⁻¹A`` of the wrench analysis (:attr:`screwkit.robots.posed.PosedMechanism.jacobians`; paper 004
    Eqs. 6-8) equals the derivative of the actuated joints' values by the pose coordinates, taken by
    central differences of the inverse kinematics (the family's ``actuated_values`` hook).
``rank``
    The twist basis has one row per pose coordinate, as many as the joint table's degrees of
    freedom, and full rank.
``reachability``
    The family's ``reachable`` hook agrees with the inverse kinematics accepting or refusing
    (:class:`~screwkit.exceptions.UnreachablePoseError`) poses drawn in and around the workspace.
``branch``
    The inverse kinematics stays on one branch along straight paths from the default pose (the
    actuated values have no isolated jump: no step is more than :data:`JUMP_RATIO` times both its
    neighbours), and the working mode read back from the default pose's geometry
    (:attr:`screwkit.robots.families.WorkingModes.of`) is the documented default.

A check a family cannot take (no ``actuated_values``, no ``reachable``, no ``WorkingModes.of``) is
reported as skipped, with the reason. The page ``docs/families.md`` describes the checks and how a
new family passes them.

Examples
--------
>>> report = check_family("planar_3rrp")
>>> report.passed, [check.name for check in report.checks][:3]
(True, ['closure', 'jacobian', 'rank'])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .exceptions import ScrewkitError, ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from .robots.catalog import list_mechanisms, load_mechanism
from .robots.families import Family, families
from .robots.mechanism import Mechanism

__all__ = [
    "CLOSURE_TOLERANCE",
    "DIFFERENCE_STEP",
    "JACOBIAN_TOLERANCE",
    "JUMP_RATIO",
    "PATH_STEPS",
    "RANK_TOLERANCE",
    "Check",
    "FamilyReport",
    "check_family",
]

#: Largest distance of a nominal twist from a limb's twist system, relative to the twist's size
#: (both made dimensionless by the pose's characteristic length).
CLOSURE_TOLERANCE = 1e-6
#: Central-difference step, relative: radians for angles, times the workspace's size for lengths.
DIFFERENCE_STEP = 1e-5
#: Largest relative difference, row by row, between ``B⁻¹A`` and its finite-difference estimate
#: (the central difference's truncation error is of order ``DIFFERENCE_STEP²``).
JACOBIAN_TOLERANCE = 1e-5
#: Smallest ratio of the twist basis's extreme singular values (dimensionless rows).
RANK_TOLERANCE = 1e-6
#: A path step of the actuated values more than this many times both its neighbours is a branch jump.
JUMP_RATIO = 8.0
#: Steps along each straight path of the ``branch`` check.
PATH_STEPS = 64

Array = np.ndarray


@dataclass(frozen=True)
class Check:
    """One check on one robot.

    Attributes
    ----------
    name : str
        ``"closure"``, ``"jacobian"``, ``"rank"``, ``"reachability"`` or ``"branch"``.
    mechanism : str
        The robot checked (its catalog name).
    status : str
        ``"pass"``, ``"fail"`` or ``"skip"`` (the family lacks what the check needs).
    value : float
        The worst number found (its meaning is in ``detail``; NaN when skipped).
    tolerance : float
        The bound ``value`` is held to.
    detail : str
        What was measured, at how many poses, and where it failed.

    Examples
    --------
    >>> Check("rank", "H4", "pass", 0.3, 1e-6, "smallest σ ratio").passed
    True
    """

    name: str
    mechanism: str
    status: str
    value: float
    tolerance: float
    detail: str

    @property
    def passed(self) -> bool:
        """True unless the check failed (a skipped check does not fail)."""
        return self.status != "fail"

    def __str__(self) -> str:
        return f"{self.mechanism}: {self.name}: {self.status} ({self.detail})"


@dataclass(frozen=True)
class FamilyReport:
    """The checks of :func:`check_family` on one family's robots.

    Attributes
    ----------
    family : str
    checks : tuple of Check

    Examples
    --------
    >>> report = FamilyReport("x", (Check("rank", "X", "fail", 0.0, 1e-6, "rank 2 of 3"),))
    >>> report.passed, [str(c) for c in report.failures]
    (False, ['X: rank: fail (rank 2 of 3)'])
    """

    family: str
    checks: tuple[Check, ...]

    @property
    def passed(self) -> bool:
        """True when no check failed."""
        return all(check.passed for check in self.checks)

    @property
    def failures(self) -> tuple[Check, ...]:
        """The checks that failed."""
        return tuple(check for check in self.checks if not check.passed)

    def raise_if_failed(self) -> None:
        """Raise when a check failed, listing every failure.

        Raises
        ------
        ScrewkitValueError
            Naming the family and each failed check with its numbers.

        Examples
        --------
        >>> FamilyReport("x", (Check("rank", "X", "fail", 0.0, 1e-6, "rank 2 of 3"),)).raise_if_failed()
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: The family 'x' fails 1 check: X: rank: fail (rank 2 of 3).
        """
        if self.failures:
            count = len(self.failures)
            raise ScrewkitValueError(
                f"The family {self.family!r} fails {count} check{'s' if count > 1 else ''}: "
                + "; ".join(str(check) for check in self.failures)
                + "."
            )

    def __str__(self) -> str:
        return "\n".join([f"family {self.family}:"] + [f"  {check}" for check in self.checks])


def check_family(subject: Any, poses: Any = None, *, samples: int = 8, seed: int = 0) -> FamilyReport:
    """Check a family's protocol on its robots (see the module docstring for the five checks).

    Parameters
    ----------
    subject : Mechanism, Family or str
        A robot (a :class:`~screwkit.robots.mechanism.Mechanism`, whose family is checked through
        it), or a family (registered, or its name): then every catalog robot of that family.
    poses : array_like, shape (m, n), optional
        The poses (file units, radians) of a robot given as ``subject``; default: the default pose
        and ``samples`` poses drawn in the reachable workspace.
    samples : int, optional
        Random workspace poses per robot (default 8).
    seed : int, optional
        Seed of the draws.

    Returns
    -------
    FamilyReport
        One :class:`Check` per check and robot.

    Raises
    ------
    ScrewkitTypeError
        If ``subject`` is none of these.
    ScrewkitValueError
        If a family has no robot in the catalog, or a :class:`Family` given is not the registered one
        of its name (register it first), or ``poses`` is given with a family.

    Examples
    --------
    >>> report = check_family(load_mechanism("h4"), samples=2)
    >>> report.passed, len(report.checks)
    (True, 5)
    >>> check_family(3)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitTypeError: Expected `subject` to be a Mechanism, a Family or a ... got int.
    """
    if isinstance(subject, Mechanism):
        mechanisms = [subject]
        name = subject.family
    elif isinstance(subject, Family | str):
        name = subject.name if isinstance(subject, Family) else subject
        if name not in families() or (isinstance(subject, Family) and families()[name] is not subject):
            raise ScrewkitValueError(
                f"Expected `subject` to be a registered family (screwkit.register), got {name!r}."
            )
        if poses is not None:
            raise ScrewkitValueError("Expected `poses` only with a Mechanism `subject`, got a family.")
        mechanisms = [m for m in map(load_mechanism, list_mechanisms()) if m.family == name]
        if not mechanisms:
            raise ScrewkitValueError(f"Expected a catalog robot of the family {name!r}, found none.")
    else:
        raise ScrewkitTypeError(
            f"Expected `subject` to be a Mechanism, a Family or a family name, got {type(subject).__name__}."
        )
    checks: list[Check] = []
    for mechanism in mechanisms:
        rng = np.random.default_rng(seed)
        chosen = (
            np.concatenate([mechanism.default_pose[None], mechanism.random_poses(rng, samples)])
            if poses is None
            else np.asarray(poses, dtype=float).reshape(-1, len(mechanism.pose_names))
        )
        checks += _checks(mechanism, chosen, rng)
    return FamilyReport(name, tuple(checks))


def _checks(mechanism: Mechanism[Any, Any], poses: Array, rng: np.random.Generator) -> list[Check]:
    """The five checks on one robot at ``poses``; a screwkit error raised inside a check fails it."""
    posed = mechanism.at(poses)
    scale = _scales(mechanism)
    runs = {
        "closure": lambda: _closure(mechanism, posed),
        "jacobian": lambda: _jacobian(mechanism, posed, poses, scale),
        "rank": lambda: _rank(mechanism, posed),
        "reachability": lambda: _reachability(mechanism, rng),
        "branch": lambda: _branch(mechanism, poses),
    }
    checks = []
    for name, run in runs.items():
        try:
            checks.append(run())
        except ScrewkitError as error:
            checks.append(Check(name, mechanism.name, "fail", float("nan"), float("nan"), f"raised: {error}"))
    return checks


def _scales(mechanism: Mechanism[Any, Any]) -> Array:
    """Per pose coordinate, its natural size: 1 rad for angles, the workspace's size for lengths."""
    lengths = [
        max(map(abs, mechanism.workspace[n])) for n in mechanism.pose_names if n not in mechanism.angle_names
    ]
    size = max(lengths, default=1.0) or 1.0
    return np.array([1.0 if n in mechanism.angle_names else size for n in mechanism.pose_names])


def _dimensionless(twists: Array, length: Any) -> Array:
    """Twists ``(..., 6)`` with their moment part divided by ``length`` (broadcast over the batch)."""
    length = np.asarray(length, dtype=float)
    return np.concatenate([twists[..., :3], twists[..., 3:] / length[..., None, None]], axis=-1)


def _closure(mechanism: Mechanism[Any, Any], posed: Any) -> Check:
    """Every nominal twist in every limb's twist system."""
    worst, where = 0.0, ""
    for index in range(len(posed)):
        one = posed[index]
        analysis = one.analysis
        length = float(np.asarray(analysis.length_scale))
        basis = _dimensionless(np.asarray(one.twist_basis, dtype=float), length)
        systems = [("the platform", analysis.platform_twists)] + [
            (f"limb {limb.actuated_joint}", limb.twist_system) for limb in analysis.limbs
        ]
        for label, twists in systems:
            system = _dimensionless(np.asarray(twists.basis, dtype=float).reshape(-1, 6), length)
            frame, *_ = np.linalg.svd(system.T, full_matrices=False)  # orthonormal columns
            residual = basis - (basis @ frame) @ frame.T
            gap = float(np.max(np.linalg.norm(residual, axis=-1) / np.linalg.norm(basis, axis=-1)))
            if gap > worst:
                worst, where = gap, f"pose {index}, {label}"
    status = "pass" if worst <= CLOSURE_TOLERANCE else "fail"
    detail = f"largest relative distance of a nominal twist from a twist system {worst:.3g}"
    return Check(
        "closure",
        mechanism.name,
        status,
        worst,
        CLOSURE_TOLERANCE,
        detail + (f" at {where}" if status == "fail" else f" over {len(posed)} poses"),
    )


def _actuated_order(mechanism: Mechanism[Any, Any], jacobian_joints: Sequence[str]) -> list[int]:
    """Where each of the Jacobians' actuated joints is in the joint table's actuated order."""
    table = mechanism.joints()
    names = [spec.name for spec in table.specs if spec.actuated]
    return [names.index(name) for name in jacobian_joints]


def _values(mechanism: Mechanism[Any, Any], poses: Array) -> Array:
    """The actuated values at ``poses`` by the family's hook."""
    hook = mechanism.family_protocol.actuated_values
    assert hook is not None
    return np.asarray(hook(mechanism.configuration(poses)), dtype=float)


def _angle_rows(mechanism: Mechanism[Any, Any], order: Sequence[int]) -> Array:
    """True for the actuated values that are angles (revolute joints), in ``order``."""
    specs = [spec for spec in mechanism.joints().specs if spec.actuated]
    return np.array([specs[k].type in ("R", "H") for k in order])


def _jacobian(mechanism: Mechanism[Any, Any], posed: Any, poses: Array, scale: Array) -> Check:
    """``B⁻¹A`` against central differences of the inverse kinematics."""
    if mechanism.family_protocol.actuated_values is None:
        return Check(
            "jacobian",
            mechanism.name,
            "skip",
            float("nan"),
            JACOBIAN_TOLERANCE,
            "the family has no actuated_values hook",
        )
    jacobians = posed.jacobians
    order = _actuated_order(mechanism, jacobians.actuated_joints)
    regular = np.asarray(jacobians.type) == "regular"
    n = len(mechanism.pose_names)
    steps = DIFFERENCE_STEP * scale
    shifted = poses[regular][:, None, :] + np.eye(n) * steps  # (m, n, n): pose + h_k e_k
    back = poses[regular][:, None, :] - np.eye(n) * steps
    ahead, behind = _values(mechanism, shifted)[..., order], _values(mechanism, back)[..., order]
    change = ahead - behind
    angles = _angle_rows(mechanism, order)
    change[..., angles] = (change[..., angles] + np.pi) % (2 * np.pi) - np.pi
    estimate = np.swapaxes(change, -1, -2) / (2 * DIFFERENCE_STEP)  # (m, k, n), columns per unit scale
    exact = np.linalg.solve(jacobians.B[regular], jacobians.A[regular]) * scale
    gap = np.linalg.norm(estimate - exact, axis=-1) / np.maximum(np.linalg.norm(exact, axis=-1), 1e-300)
    worst = float(gap.max(initial=0.0))
    status = "pass" if worst <= JACOBIAN_TOLERANCE else "fail"
    detail = f"largest relative row difference of B⁻¹A from central differences {worst:.3g}"
    if status == "fail":
        pose, row = np.unravel_index(int(np.argmax(gap)), gap.shape)
        detail += f" (joint {jacobians.actuated_joints[row]} at pose {int(np.flatnonzero(regular)[pose])})"
    else:
        detail += f" over {int(regular.sum())} regular poses"
    return Check("jacobian", mechanism.name, status, worst, JACOBIAN_TOLERANCE, detail)


def _rank(mechanism: Mechanism[Any, Any], posed: Any) -> Check:
    """One nominal twist per coordinate, as many as the degrees of freedom, independent."""
    basis = np.asarray(posed.twist_basis, dtype=float)
    n, dof = len(mechanism.pose_names), posed.joints.dof
    if basis.shape[-2:] != (n, 6) or n != dof:
        return Check(
            "rank",
            mechanism.name,
            "fail",
            0.0,
            RANK_TOLERANCE,
            f"twist basis rows {basis.shape[-2:]} for {n} pose coordinates and dof {dof}",
        )
    length = np.asarray(posed.jacobians.analysis.length_scale, dtype=float)
    values = np.linalg.svd(_dimensionless(basis, np.broadcast_to(length, basis.shape[:-2])), compute_uv=False)
    worst = float(np.min(values[..., -1] / values[..., 0]))
    status = "pass" if worst > RANK_TOLERANCE else "fail"
    return Check(
        "rank",
        mechanism.name,
        status,
        worst,
        RANK_TOLERANCE,
        f"smallest ratio of the twist basis's extreme singular values {worst:.3g} ({n} rows, dof {dof})",
    )


def _reachability(mechanism: Mechanism[Any, Any], rng: np.random.Generator) -> Check:
    """The ``reachable`` hook against the inverse kinematics, in and around the workspace box."""
    family = mechanism.family_protocol
    if family.reachable is None:
        return Check(
            "reachability",
            mechanism.name,
            "skip",
            float("nan"),
            0.0,
            "the family has no reachable hook (Mechanism.reachable asks the inverse kinematics)",
        )
    low, high = np.array([mechanism.workspace[n] for n in mechanism.pose_names]).T
    centre, half = (low + high) / 2, (high - low) / 2
    draws = centre + half * rng.uniform(
        -1.5, 1.5, size=(48, len(low))
    )  # two thirds in the box per coordinate
    said = np.asarray(family.reachable(mechanism.parameters, draws), dtype=bool)
    accepted = np.zeros(len(draws), dtype=bool)
    for index, pose in enumerate(draws):
        try:
            family.inverse_kinematics(mechanism.parameters, pose)
            accepted[index] = True
        except UnreachablePoseError:
            pass
    wrong = int(np.sum(said != accepted))
    detail = (
        f"{wrong} of {len(draws)} poses where reachable() and the inverse kinematics disagree "
        f"({int(accepted.sum())} accepted)"
    )
    return Check("reachability", mechanism.name, "pass" if wrong == 0 else "fail", float(wrong), 0.0, detail)


def _branch(mechanism: Mechanism[Any, Any], poses: Array) -> Check:
    """No branch jump along straight paths from the default pose; the documented mode there."""
    family = mechanism.family_protocol
    notes, worst = [], 0.0
    modes = family.working_modes
    failed = False
    if modes is not None and modes.of is not None:
        found = np.asarray(modes.of(mechanism.configuration())).ravel().tolist()
        if found != list(modes.default):
            failed = True
            notes.append(f"working mode at the default pose {tuple(found)}, documented {modes.default}")
        else:
            notes.append(f"documented working mode {modes.default} at the default pose")
    else:
        notes.append("no WorkingModes.of hook: the default pose's mode is not read back")
    if family.actuated_values is None:
        notes.append("no actuated_values hook: continuity not checked")
        return Check(
            "branch", mechanism.name, "fail" if failed else "skip", float("nan"), JUMP_RATIO, "; ".join(notes)
        )
    specs = [spec for spec in mechanism.joints().specs if spec.actuated]
    angles = np.array([spec.type in ("R", "H") for spec in specs])
    t = np.linspace(0.0, 1.0, PATH_STEPS + 1)[:, None]
    start = mechanism.default_pose
    for index, end in enumerate(poses):
        path = start + t * (end - start)
        reach = mechanism.reachable(path)
        if not reach.all():  # the path leaves the workspace: its reachable start only
            path = path[: int(np.argmin(reach))]
        if len(path) < 4:
            continue
        steps = np.diff(_values(mechanism, path), axis=0)
        steps[..., angles] = (steps[..., angles] + np.pi) % (2 * np.pi) - np.pi
        size = np.abs(steps) + 1e-12 * np.abs(steps).max(initial=1.0)
        neighbours = np.maximum(
            np.pad(size[:-1], ((1, 0), (0, 0)), mode="edge"), np.pad(size[1:], ((0, 1), (0, 0)), mode="edge")
        )
        ratio = size / neighbours  # more than JUMP_RATIO times both neighbours: a jump
        if ratio.max() > worst:
            worst = float(ratio.max())
            if worst > JUMP_RATIO:
                failed = True
                step, joint = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
                notes.append(f"jump of {specs[joint].name} at step {step} of the path to pose {index}")
    notes.append(f"largest step ratio to its neighbours {worst:.3g}")
    return Check("branch", mechanism.name, "fail" if failed else "pass", worst, JUMP_RATIO, "; ".join(notes))
