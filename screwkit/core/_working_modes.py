"""The working and assembly modes a continuation keeps: the orientation of its equations' Jacobian.

Closing the loops of a mechanism at a pose has several solutions: the working modes of its legs (a
Delta arm's elbow in or out) when the platform is placed, the assembly modes of the whole mechanism
when the actuated joints are. Two solutions of one fold (the two elbows of a leg meet where the leg
is at a serial singularity) have Jacobians ``J = ∂F/∂θ`` whose determinants have opposite signs: along
a path of solutions that determinant changes sign only where it passes through a singularity
(Allgower & Georg, *Introduction to Numerical Continuation Methods*, 2003, §2.1, the orientation of
the solution curve; Gosselin & Angeles, IEEE Trans. Robot. Autom. 6(3), 1990, §III: a serial
singularity is where the leg's Jacobian loses rank). Near a fold the two solutions are close, and a
predictor that extrapolates past the fold lands on the other one with small Newton corrections, which
no bound on the corrections can tell from a regular step.

The equations may have dependent rows (an overconstrained loop) and internal motions (a rod's spin
about its own axis), so ``J`` (``m × n``, rank ``r``, read off the start configurations) is not square.
Its orientation is that of the bordered matrix ``[[J, L], [Nᵀ, 0]]``, with ``L`` and ``N`` orthonormal
bases of its left null space and null space (Allgower & Georg §2.1 borders ``J`` the same way with the
tangent): with ``J = U Σ Vᵀ`` (full SVD, ``L`` and ``N`` the last columns of ``U`` and ``V``) its
determinant's sign is ``sgn det U · sgn det V``, whatever signs the SVD gives its singular pairs
(flipping ``uᵢ`` and ``vᵢ`` together leaves both signs' product), once the null spaces' bases are
oriented continuously from step to step (``sgn det(L_prevᵀ L)`` and ``sgn det(N_prevᵀ N)``). Only the
null spaces are carried, which move with the joints, not the range, which near-singular directions
(a Ragnar's screw pair of small lead) make turn fast.

:class:`Orientations` keeps that sign per pose and per independent block of the equations (each leg
group between the base and a pinned platform, or the whole system) at the last trusted step, and
trusts a new step only where every block kept it. A block's sign is the product of its legs' (two legs
of one block changing mode in the same step would cancel); the steps are short next to the distance
between two legs' singularities.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

import numpy as np

from ..algebra.compiled import compiled_kernels
from ._batched_poe import KERNELS

__all__ = ["Orientations", "unreached_reasons"]

Array = np.ndarray

#: Singular values below this fraction of a block's largest are taken as zero (its rank).
RANK_TOLERANCE = 1e-8
#: A step whose null spaces turned by more than ``arccos(1 / MAX_TURN)`` (60°) from the last trusted
#: step's is taken again in shorter steps: the border must stay transversal to them for the sign to hold.
MAX_TURN = 2.0


def _jacobian_blocks(system: Any, theta: Array, offsets: Array, target: Array) -> list[Array]:
    """The equations' Jacobian at the configurations, as groups of blocks ``(B, k, rows, columns)``
    (a pinned system's screws from the compiled corrector's product of exponentials when compiled)."""
    kernels = compiled_kernels(KERNELS, len(theta)) if hasattr(system, "kernel_model") else None
    if kernels is None:
        state = system.state(theta, system.offsets_of(offsets), target)
        _, jacobian = system.equations(state, target)
        if isinstance(jacobian, np.ndarray):  # one system: one block
            return [jacobian[:, None]]
        return list(jacobian)
    placed = np.ascontiguousarray(system.task.displacement(target))
    screws = kernels.evaluate(
        np.ascontiguousarray(theta), np.ascontiguousarray(offsets), placed, system.kernel_model
    )[2]
    blocks = []
    for _, columns, signs in system.groups:  # as ``equations``: (B, k, l, 6, c) -> (B, k, 6 l, c)
        screw_rows = np.swapaxes(screws[:, columns], -1, -2)[:, :, None]
        jacobian = np.multiply(signs[None, :, :, None, :], screw_rows, order="C")  # (reshaped: a view)
        blocks.append(jacobian.reshape(*jacobian.shape[:2], -1, jacobian.shape[-1]))
    return blocks


def _bordered(block: Array, left: Array, right: Array) -> Array:
    """The bordered matrix ``[[J, L], [Nᵀ, 0]]`` ``(B, k, m + n − r, m + n − r)`` of blocks ``J``."""
    rows, columns = block.shape[-2:]
    out = np.zeros((*block.shape[:-2], rows + right.shape[-1], columns + left.shape[-1]))
    out[..., :rows, :columns] = block
    out[..., :rows, columns:] = left
    out[..., rows:, :columns] = np.swapaxes(right, -1, -2)
    return out


def _orthonormal(basis: Array) -> Array:
    """An orthonormal basis of the span of ``basis (…, p, d)`` with its orientation (QR with the signs
    of ``R``'s diagonal moved into ``Q``)."""
    q, r = np.linalg.qr(basis)
    return q * np.where(np.diagonal(r, axis1=-2, axis2=-1) < 0, -1.0, 1.0)[..., None, :]


def _null_spaces(bordered: Array, rows: int, columns: int) -> tuple[Array, Array, Array]:
    """The left null space ``(…, m, m − r)`` and null space ``(…, n, n − r)`` of the block ``J`` of a
    bordered matrix, oriented as its border ``L``, ``N``: the solutions ``X`` of ``J X + L Y = 0``,
    ``Nᵀ X = I`` (so ``J X = 0`` and ``det(Nᵀ X) > 0``; Allgower & Georg 2003, §2.1, compute the tangent
    the same way) and their transposed twins; and how far they turned from the border ``(…)``: the
    largest length of a column of ``X`` (``1/cos`` of its angle to the border's span)."""
    size = bordered.shape[-1]
    right_size, left_size = size - rows, size - columns  # n − r, m − r
    unit = np.zeros((*bordered.shape[:-2], size, right_size))
    unit[..., rows:, :] = np.eye(right_size)
    right = np.linalg.solve(bordered, unit)[..., :columns, :] if right_size else unit[..., :columns, :]
    unit_left = np.zeros((*bordered.shape[:-2], size, left_size))
    unit_left[..., columns:, :] = np.eye(left_size)
    transposed = np.swapaxes(bordered, -1, -2)
    left = np.linalg.solve(transposed, unit_left)[..., :rows, :] if left_size else unit_left[..., :rows, :]
    turned = np.maximum(
        np.linalg.norm(left, axis=-2).max(axis=-1, initial=1.0),
        np.linalg.norm(right, axis=-2).max(axis=-1, initial=1.0),
    )
    return _orthonormal(left) if left_size else left, _orthonormal(right) if right_size else right, turned


def _carried(block: Array, left: Array, right: Array) -> tuple[Array, Array, Array, Array]:
    """Per block ``J (B, k, m, n)`` bordered by ``L``, ``N``: the sign of the bordered determinant
    ``(B, k)``, the null spaces carried to ``J`` and how far they turned (:func:`_null_spaces`), by the
    compiled LU (:func:`screwkit.core._newton_numba.bordered_orientation`) when compiled."""
    kernels = compiled_kernels(KERNELS, block.shape[0] * block.shape[1])
    if kernels is None or block.shape[0] * block.shape[1] == 0:
        bordered = _bordered(block, left, right)
        new_left, new_right, turned = _null_spaces(bordered, block.shape[-2], block.shape[-1])
        return np.sign(np.linalg.det(bordered)), new_left, new_right, turned
    count = block.shape[0] * block.shape[1]
    flat = [np.ascontiguousarray(array.reshape(count, *array.shape[2:])) for array in (block, left, right)]
    signs, new_left, new_right, turned = kernels.bordered_orientation(*flat)
    shape = block.shape[:2]
    new_left, new_right = new_left.reshape(left.shape), new_right.reshape(right.shape)
    return signs.reshape(shape), new_left, new_right, turned.reshape(shape)


class Orientations:
    """The orientation of each pose's equations, kept from step to step of a continuation.

    Parameters
    ----------
    system : object
        The continuation's equations (``state``, ``equations``, ``offsets_of``, ``model``, and
        ``groups`` of blocks when the platform is pinned; :mod:`screwkit.core.loop_closure`).
    theta, offsets, target : numpy.ndarray
        The start configurations ``(B, n)``, their spherical joints' offsets ``(B, K, 4, 4)``, and
        the task's values there ``(B, k)``.

    Attributes
    ----------
    changed : numpy.ndarray of object, shape (B,)
        Per pose, the joints of the block whose orientation a refused step would have changed ("" if
        none was refused).

    Examples
    --------
    >>> from screwkit.core.loop_closure import KinematicModel, PoseTask, _LoopsAndTask
    >>> from screwkit.core.task_coordinates import task_coordinates
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> hinge = dict(actuated=True)  # a 2R arm of links 2 long, its end point at (2, 2) at the reference
    >>> legs = [("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], **hinge)),
    ...         ("L", "E", revolute("R2", [0, 0, 1], [2, 0, 0], **hinge))]
    >>> model = KinematicModel(twist_graph("B", "E", legs, dof=2))
    >>> task = PoseTask(model, task_coordinates(model, point=[2, 2, 0], rotations=False))
    >>> system = _LoopsAndTask(model, task)
    >>> start = np.zeros((1, 2))  # the reference: the elbow at (2, 0)
    >>> offsets = np.zeros((1, 0, 4, 4))
    >>> modes = Orientations(system, start, offsets, system.task.values(model.state(start)))
    >>> other = np.array([[np.pi / 2, np.pi]])  # the same end point, the elbow at (0, 2)
    >>> modes.kept(system, other, offsets, system.task.values(model.state(other)), np.array([True])).tolist()
    [False]
    >>> modes.changed.tolist()
    ['R1, R2']
    """

    def __init__(self, system: Any, theta: Array, offsets: Array, target: Array):
        same = all(np.all(array == array[:1]) for array in (theta, offsets, target)) and len(theta) > 0
        rows = slice(0, 1) if same else slice(None)  # every pose at the reference configuration: once
        blocks = _jacobian_blocks(system, theta[rows], offsets[rows], target[rows])
        self.ranks, self.signs, self.null_spaces = [], [], []
        for block in blocks:
            u, values, vt = np.linalg.svd(block)
            counts = np.sum(values > RANK_TOLERANCE * values[..., :1], axis=-1)
            rank = int(np.max(counts, initial=0))
            left, right = u[..., rank:], np.swapaxes(vt[..., rank:, :], -1, -2)
            sign = np.sign(np.linalg.det(_bordered(block, left, right)))
            copies = len(theta) if same else 1
            self.ranks.append(rank)
            self.signs.append(np.repeat(sign, copies, axis=0))
            self.null_spaces.append((np.repeat(left, copies, axis=0), np.repeat(right, copies, axis=0)))
        self.names = self._block_names(system, blocks)
        self.changed = np.full(len(theta), "", dtype=object)

    def taken(self, index: Array) -> Orientations:
        """The orientations of the poses ``index`` (an integer array, repeats allowed), as new starts.

        Parameters
        ----------
        index : numpy.ndarray of int, shape (C,)

        Returns
        -------
        Orientations
            Each pose's signs and oriented null spaces copied, none refused yet.

        Examples
        --------
        See :mod:`screwkit.core._seeded_starts`.
        """
        out = copy.copy(self)
        out.signs = [sign[index] for sign in self.signs]
        out.null_spaces = [(left[index], right[index]) for left, right in self.null_spaces]
        out.changed = np.full(len(index), "", dtype=object)
        return out

    @staticmethod
    def _block_names(system: Any, blocks: list[Array]) -> list[list[str]]:
        """Per group, per block, the names of its joints (for a refused step's reason)."""
        owner = {}
        for key, (_, _, columns) in system.model.joints.items():
            for column in columns:
                owner[int(column)] = str(key)
        groups = getattr(system, "groups", None)
        if groups is None:
            return [[", ".join(sorted(set(owner.values())))]]
        return [
            [", ".join(sorted({owner[int(c)] for c in block_columns})) for block_columns in columns]
            for _, columns, _ in groups
        ]

    def kept(
        self,
        system: Any,
        theta: Array,
        offsets: Array,
        target: Array,
        rows: Array,
        blocks: Callable[[Array], list[Array]] | None = None,
    ) -> Array:
        """Whether each of the poses ``rows`` (bool mask) kept every block's orientation since its last
        trusted step; the bases of those that did become their new configuration's, and
        :attr:`changed` names the block of those that did not.

        Parameters
        ----------
        system : object
            As in the constructor.
        theta, offsets, target : numpy.ndarray
            The configurations of all the poses, ``(B, n)``, ``(B, K, 4, 4)`` and ``(B, k)``.
        rows : numpy.ndarray of bool, shape (B,)
            The poses to check.
        blocks : callable, optional
            ``blocks(index)``: the Jacobian blocks at ``theta`` of the poses ``index`` (integer positions),
            when the corrector that left ``theta`` has them (the rods',
            ``screwkit.core._rod_closure._RodLoops.last_blocks``); default: evaluated here.

        Returns
        -------
        numpy.ndarray of bool, shape (B,)
            True where the pose was checked and kept its orientation, or was not checked.

        Examples
        --------
        See :class:`Orientations`.
        """
        kept = np.ones(len(theta), dtype=bool)
        at = np.flatnonzero(rows)
        if at.size == 0:
            return kept
        if blocks is None:
            jacobians = _jacobian_blocks(system, theta[at], offsets[at], target[at])
        else:
            jacobians = blocks(at)
        flipped, updates = [], []
        for block, sign, (left, right) in zip(jacobians, self.signs, self.null_spaces, strict=True):
            signs, new_left, new_right, turned = _carried(block, left[at], right[at])
            # a sign read with a border the null spaces have turned far from is not trusted either
            flipped.append((signs != sign[at]) | ~(turned < MAX_TURN))
            updates.append((new_left, new_right))
        good = ~np.any(np.concatenate(flipped, axis=1), axis=1)
        kept[at] = good
        for (new_left, new_right), (left, right) in zip(updates, self.null_spaces, strict=True):
            left[at[good]], right[at[good]] = new_left[good], new_right[good]  # oriented as before
        for index in np.flatnonzero(~good):
            group = next(g for g, mask in enumerate(flipped) if mask[index].any())
            self.changed[at[index]] = self.names[group][int(np.argmax(flipped[group][index]))]
        return kept


def unreached_reasons(residual: Array, unreached: Array, lost_at: Array, changed: Array) -> Array:
    """Why each pose of a continuation was not reached (empty where it was).

    Parameters
    ----------
    residual : numpy.ndarray, shape (B,)
        The poses' residuals (characteristic lengths, radians; inf where non-finite).
    unreached : numpy.ndarray of bool, shape (B,)
        The poses not reached.
    lost_at : numpy.ndarray, shape (B,)
        The fraction of the way where each was lost (NaN: at the end).
    changed : numpy.ndarray of object, shape (B,)
        The joints whose orientation the last refused step would have changed (:attr:`Orientations.changed`;
        "" for none).

    Returns
    -------
    numpy.ndarray of object (str), shape (B,)

    Examples
    --------
    >>> reasons = unreached_reasons(np.array([0.0, 2e-3, 1e-3]), np.array([False, True, True]),
    ...                             np.array([np.nan, 0.4, 0.6]), np.array(["", "", "A1, S1m"], dtype=object))
    >>> reasons[0], reasons[1][:60]
    ('', 'the loops and the task do not close at 40% of the way from t')
    >>> reasons[2][:80]
    'the continuation would leave its working or assembly mode at 60% of the way from'
    """
    reasons = np.full(len(residual), "", dtype=object)
    for index in np.flatnonzero(unreached):
        where = lost_at[index]
        at = f"{100 * where:.0f}% of the way from the start" if np.isfinite(where) else "the end"
        if changed[index]:
            reasons[index] = (
                f"the continuation would leave its working or assembly mode at {at} (residual "
                f"{residual[index]:.1e}): the Jacobian of joints {changed[index]} changes orientation "
                "there, the way crosses or grazes a singularity of theirs (a leg's serial singularity "
                "when the platform is placed)"
            )
        elif np.isfinite(residual[index]):
            reasons[index] = (
                f"the loops and the task do not close at {at} (residual {residual[index]:.1e} "
                "characteristic lengths): the pose is out of the mechanism's reach, or past a "
                "singularity where the continuation from the reference configuration stops"
            )
        else:
            reasons[index] = "Newton's method gave non-finite joint values on the way to the pose"
    return reasons
