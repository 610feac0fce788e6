"""Which poses a mechanism reaches, why the others are out of reach, and random reachable poses
(what :class:`~screwkit.robots.mechanism.Mechanism`'s ``reachable``, ``unreachable_reasons`` and
``random_poses`` do).

Examples
--------
>>> v4 = load_mechanism("v4")
>>> reachable_poses(v4, np.array([[0, 0, -750, 0], [0, 0, -3000, 0]]), {}).tolist()
[True, False]
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError

__all__ = [
    "MAX_REJECTION_ROUNDS",
    "failures_by_index",
    "random_reachable_poses",
    "reachable_poses",
    "unreachable_reasons",
]

Array = np.ndarray

#: Rounds of redrawing in :func:`random_reachable_poses` before a mostly unreachable workspace is refused.
MAX_REJECTION_ROUNDS = 50


def reachable_poses(robot: Any, poses: Array, options: dict[str, Any]) -> Array:
    """Which poses ``(m, n)`` (API units) the inverse kinematics accepts, ``(m,)`` bool: the family's
    vectorised ``reachable`` hook when it has one and no option changes the inverse kinematics'
    domain, else one batch call of the inverse kinematics, halved where a batch is refused.

    Parameters
    ----------
    robot : Mechanism
    poses : numpy.ndarray, shape (m, n)
    options : dict
        Inverse-kinematics options (a working mode).

    Returns
    -------
    numpy.ndarray of bool, shape (m,)

    Examples
    --------
    >>> reachable_poses(load_mechanism("h4"), np.zeros((0, 4)), {}).shape
    (0,)
    """
    names = tuple(robot.pose_names)
    shape = np.shape(poses)
    if len(shape) != 2 or shape[1] != len(names):
        raise ScrewkitValueError(
            f"Expected `poses` of shape (m, {len(names)}) (coordinates {', '.join(names)}; one pose as "
            f"[pose]), got shape {shape}."
        )
    if len(poses) == 0:
        return np.zeros(0, dtype=bool)
    protocol = robot.family_protocol  # its reach test holds in every working mode
    test, modes = protocol.reachable, protocol.working_modes
    if test is not None and set(options) <= ({modes.option} if modes is not None else set()):
        return np.asarray(test(robot.parameters, poses), dtype=bool).reshape(len(poses))
    return _reachable_by_halving(robot, poses, options)


def _reachable_by_halving(robot: Any, poses: Array, options: dict[str, Any]) -> Array:
    """:func:`reachable_poses` by the inverse kinematics alone."""
    try:
        robot.configuration(poses, **options)
        return np.ones(len(poses), dtype=bool)
    except UnreachablePoseError:
        if len(poses) == 1:
            return np.zeros(1, dtype=bool)
    half = len(poses) // 2
    halves = (poses[:half], poses[half:])
    return np.concatenate([_reachable_by_halving(robot, part, options) for part in halves])


def unreachable_reasons(robot: Any, poses: Array, options: dict[str, Any]) -> Array:
    """Why each pose ``(m, n)`` is out of reach (an empty string where it is reachable): the family
    parameters' own ``unreachable_reasons(poses)`` when they have one (a graph mechanism's
    continuation, :meth:`screwkit.robots.graph_kinematics.GraphKinematics.unreachable_reasons`), else
    the inverse kinematics' message for that pose.

    Parameters
    ----------
    robot : Mechanism
    poses : numpy.ndarray, shape (m, n)
    options : dict
        Inverse-kinematics options (a working mode).

    Returns
    -------
    numpy.ndarray of str, shape (m,)

    Examples
    --------
    >>> unreachable_reasons(load_mechanism("h4"), np.array([[0, 0, -750, 0]]), {}).tolist()
    ['']
    """
    own = getattr(robot.parameters, "unreachable_reasons", None)
    if callable(own) and not options:
        return np.asarray(own(np.asarray(poses, dtype=float)), dtype=object)
    out = np.full(len(poses), "", dtype=object)
    for index in np.flatnonzero(~reachable_poses(robot, poses, options)):
        try:
            robot.configuration(poses[index], **options)
        except UnreachablePoseError as error:
            out[index] = str(error)
    return out


def failures_by_index(robot: Any, poses: Array, options: dict[str, Any]) -> dict[tuple[int, ...], str]:
    """Why each unreachable pose of a batch ``(..., n)`` is out of reach, by batch index.

    Parameters
    ----------
    robot : Mechanism
    poses : numpy.ndarray, shape (..., n)
    options : dict
        Inverse-kinematics options (a working mode).

    Returns
    -------
    dict
        Batch index → reason (only the unreachable poses).

    Examples
    --------
    >>> list(failures_by_index(load_mechanism("v4"), np.array([[0, 0, -750, 0], [0, 0, -3000, 0]]), {}))
    [(1,)]
    """
    shape = poses.shape[:-1]
    reasons = unreachable_reasons(robot, poses.reshape(-1, poses.shape[-1]), options)
    return {
        tuple(int(i) for i in np.unravel_index(k, shape)) if shape else (): str(reasons[k])
        for k in np.flatnonzero(reasons != "")
    }


def random_reachable_poses(robot: Any, rng: np.random.Generator, count: int) -> Array:
    """Poses drawn uniformly in the reachable part of the workspace box (rejection), ``(count, n)``.

    Parameters
    ----------
    robot : Mechanism
    rng : numpy.random.Generator
    count : int
        In ``0..10**7``.

    Returns
    -------
    numpy.ndarray, shape (count, n)

    Raises
    ------
    ScrewkitTypeError
        If ``rng`` is not a numpy Generator.
    ScrewkitValueError
        If ``count`` is out of range.
    CatalogError
        If fewer than 1 draw in :data:`MAX_REJECTION_ROUNDS` is reachable (the file's workspace box
        is mostly out of reach).

    Examples
    --------
    >>> random_reachable_poses(load_mechanism("h4"), np.random.default_rng(0), 2).shape
    (2, 4)
    """
    if not isinstance(rng, np.random.Generator):
        raise ScrewkitTypeError(f"Expected `rng` to be a numpy.random.Generator, got {type(rng).__name__}.")
    if isinstance(count, bool) or not isinstance(count, int | np.integer) or not 0 <= count <= 10**7:
        raise ScrewkitValueError(f"Expected `count` to be an integer in 0..10**7, got {count!r}.")
    low, high = zip(*(robot.workspace[c] for c in robot.pose_names), strict=True)
    kept = np.empty((0, len(low)))
    for _ in range(MAX_REJECTION_ROUNDS):
        if len(kept) >= count:
            return kept[:count]
        draws = rng.uniform(low, high, size=(count - len(kept), len(low)))
        kept = np.concatenate([kept, draws[reachable_poses(robot, draws, {})]])
    if len(kept) >= count:
        return kept[:count]
    raise CatalogError(
        f"{robot.source}: [workspace]: only {len(kept)} of the poses drawn in {MAX_REJECTION_ROUNDS} "
        f"rounds are reachable, {count} wanted: the workspace box is mostly out of reach."
    )
