"""Solved configurations of a graph mechanism remembered by pose
(:class:`~screwkit.robots.graph_kinematics.GraphKinematics`' cache): a map asks which poses of a chunk
are reachable, then analyses them, and the second call reads the first one's configurations.

A pose's key is its coordinates' bytes (:func:`pose_keys`): the same pose asked again, bit for bit,
finds its row; any other pose is solved.

Examples
--------
>>> cache = SolvedPoses(capacity=100)
>>> keys = pose_keys(np.array([[0.0, 1.0], [2.0, 3.0]]))
>>> cache.add(keys, np.zeros((2, 5)), {"S": identities(2)})
>>> cache.rows(pose_keys(np.array([[2.0, 3.0], [4.0, 5.0]]))).tolist()
[1, -1]
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from ..core.kinematic_model import KinematicState

__all__ = ["SolvedPoses", "identities", "pose_keys"]

Array = np.ndarray


def pose_keys(poses: Array) -> list[bytes]:
    """Each pose's coordinates as bytes: ``(m, n)`` → ``m`` keys (one call for the batch).

    Parameters
    ----------
    poses : numpy.ndarray, shape (m, n)

    Returns
    -------
    list of bytes

    Examples
    --------
    >>> len(pose_keys(np.zeros((3, 4)))[0])  # four float64 coordinates
    32
    """
    rows = np.ascontiguousarray(poses, dtype=float)
    whole = rows.view(np.dtype((np.void, rows.dtype.itemsize * rows.shape[1])))  # a pose per item
    return cast(list[bytes], whole.ravel().tolist())


def _rows_of(index: dict[bytes, int], keys: list[bytes]) -> Array:
    """Each key's row in ``index``, -1 where it has none."""
    get = index.get
    return np.fromiter((get(key, -1) for key in keys), dtype=np.int64, count=len(keys))


def identities(count: int) -> Array:
    """``count`` identity displacements (a spherical joint's offsets at rest).

    Parameters
    ----------
    count : int

    Returns
    -------
    numpy.ndarray, shape (count, 4, 4)
        A new array.

    Examples
    --------
    >>> identities(2).shape
    (2, 4, 4)
    """
    return np.broadcast_to(np.eye(4), (count, 4, 4)).copy()


class SolvedPoses:
    """Solved configurations remembered by pose (:func:`pose_keys`): joint values and spherical
    offsets in arrays, a slot per pose, emptied when ``capacity`` would be exceeded; and the last
    continuation's model state (:attr:`recent`, a row per pose) until another pose is remembered: a
    map asks which poses of a chunk are reachable, then analyses them there.

    Parameters
    ----------
    capacity : int
        The most poses remembered.

    Examples
    --------
    >>> cache = SolvedPoses(capacity=100)
    >>> cache.add(pose_keys(np.ones((1, 2))), np.zeros((1, 3)), {})
    >>> cache.used, cache.rows(pose_keys(np.ones((1, 2)))).tolist()
    (1, [0])
    """

    def __init__(self, capacity: int) -> None:
        self.capacity = capacity
        self.slots: dict[bytes, int] = {}
        self.used = 0  # rows written (a pose solved again gets a new row)
        self.theta = np.zeros((0, 0))
        self.offsets: dict[str, Array] = {}
        self.recent: tuple[dict[bytes, int], KinematicState] | None = None

    def __getstate__(self) -> dict[str, Any]:
        """A copy (a Dask worker's) gets the remembered poses, not the last continuation's state."""
        used, offsets = self.used, {key: value[: self.used] for key, value in self.offsets.items()}
        kept = dict(slots=self.slots, used=used, theta=self.theta[:used], offsets=offsets, recent=None)
        return dict(kept, capacity=self.capacity)

    def rows(self, keys: list[bytes]) -> Array:
        """Each pose's row in :attr:`theta`, -1 where it is not remembered.

        Parameters
        ----------
        keys : list of bytes
            From :func:`pose_keys`.

        Returns
        -------
        numpy.ndarray of int, shape (m,)

        Examples
        --------
        >>> SolvedPoses(capacity=100).rows(pose_keys(np.zeros((2, 3)))).tolist()
        [-1, -1]
        """
        if not self.slots:
            return np.full(len(keys), -1, dtype=np.int64)
        return _rows_of(self.slots, keys)

    def recent_state(self, keys: list[bytes]) -> KinematicState | None:
        """The last continuation's state at these poses (all remembered), None if it lacks one.

        Parameters
        ----------
        keys : list of bytes
            The poses' keys (:func:`pose_keys`).

        Returns
        -------
        KinematicState or None
            Its rows in the order of ``keys``.

        Examples
        --------
        >>> SolvedPoses(capacity=100).recent_state(pose_keys(np.zeros((1, 3)))) is None
        True
        """
        if self.recent is None:
            return None
        index, state = self.recent
        found = _rows_of(index, keys)
        if found.size and found.min() < 0:
            return None
        if np.array_equal(found, np.arange(len(state.theta))):
            return state

        def rows(arrays: dict[Any, Array]) -> dict[Any, Array]:
            return {key: value[found] for key, value in arrays.items()}

        theta, current = state.theta[found], state.current[found]  # (no stacked arrays: optional)
        return KinematicState(theta, rows(state.offsets), rows(state.links), current, rows(state.motions))

    def add(self, keys: list[bytes], theta: Array, offsets: dict[str, Array]) -> None:
        """Remember solved configurations (copied).

        Parameters
        ----------
        keys : list of bytes
            Their poses' keys (:func:`pose_keys`).
        theta : numpy.ndarray, shape (k, n)
            Their joint values.
        offsets : dict
            Every spherical joint's offsets, name → ``(k, 4, 4)``.

        Examples
        --------
        >>> cache = SolvedPoses(capacity=100)
        >>> cache.add(pose_keys(np.zeros((2, 1))), np.zeros((2, 3)), {"S": identities(2)})
        >>> cache.used  # (the same pose twice: one key, the later row)
        2
        """
        self.recent = None  # (its poses' rows may now be another solution's)
        if not keys:  # (a batch that reached nothing: nothing to remember, nor columns to size by)
            return
        if self.used + len(keys) > self.capacity:
            self.slots.clear()
            self.used = 0
        used, end = self.used, self.used + len(keys)
        if end > len(self.theta):  # grown by doubling (the rows in use copied)
            size = max(min(2 * end, self.capacity), end, 256)
            self.theta = _grown(self.theta[:used], (size, theta.shape[1]))
            old = self.offsets
            self.offsets = {k: _grown(old.get(k, v[:0])[:used], (size, 4, 4)) for k, v in offsets.items()}
        self.theta[used:end] = theta
        for key, value in offsets.items():
            self.offsets[key][used:end] = value
        self.slots.update(zip(keys, range(used, end), strict=True))
        self.used = end


def _grown(kept: Array, shape: tuple[int, ...]) -> Array:
    out = np.empty(shape)
    out[: len(kept)] = kept.reshape(-1, *shape[1:])  # (an empty start has no columns yet)
    return out
