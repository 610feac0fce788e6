"""Parts of the loop-closure continuation (:mod:`screwkit.core.loop_closure`; private): a rigid
displacement's loop residual, the pinned model's blocks as the compiled corrector reads them, and the
bookkeeping of the continuation's states and Jacobians over a batch."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra.rigid_motions import rotation_log
from .kinematic_model import KinematicModel, KinematicState

__all__ = [
    "concatenated",
    "kernel_blocks",
    "pose_residual",
    "pose_residual_inverse",
    "replace_rows",
    "rows_replaced",
]

Array = np.ndarray


def rows_replaced(array: Array, rows: Array, other: Array, index: Array) -> Array:
    """A copy of ``array`` whose rows ``rows`` (bool) are ``other``'s rows ``index``."""
    out = array.copy()
    out[rows] = other[index]
    return out


def pose_residual(moved: Array) -> Array:
    """A displacement's loop residual: rotation vector, then translation ``(B, 6)``."""
    return np.concatenate([rotation_log(moved[:, :3, :3]), moved[:, :3, 3]], axis=1)


def pose_residual_inverse(moved: Array, forward: Array) -> Array:
    """Minus its inverse's, ``(φ, Rᵀ p)``, from its own (``forward``)."""
    back = np.einsum("bji,bj->bi", moved[:, :3, :3], moved[:, :3, 3])
    return np.concatenate([forward[:, :3], back], axis=1)


def kernel_blocks(pinned: KinematicModel) -> tuple[Array, ...]:
    """The blocks of a pinned model for :func:`screwkit.core._newton_numba.pinned_newton`: per block its
    loops, per column of it the loops (local, ascending) that hold the column and their signs."""
    block_ptr: list[int] = [0]
    column_ptr: list[int] = [0]
    entry_ptr: list[int] = [0]
    block_loops: list[int] = []
    column_index: list[int] = []
    entry_loop: list[int] = []
    entry_sign: list[float] = []
    for rows, columns in pinned.blocks:
        loops = rows[::6] // 6
        block_loops.extend(loops)
        block_ptr.append(len(block_loops))
        for column in columns:
            column_index.append(column)
            for local, loop in enumerate(loops):
                if pinned.incidence[loop, column] != 0.0:
                    entry_loop.append(local)
                    entry_sign.append(pinned.incidence[loop, column])
            entry_ptr.append(len(entry_loop))
        column_ptr.append(len(column_index))
    whole = (block_ptr, block_loops, column_ptr, column_index, entry_ptr, entry_loop)
    return (*(np.array(part, dtype=np.int64) for part in whole), np.array(entry_sign, dtype=float))


def replace_rows(state: KinematicState, rows: Array, other: KinematicState) -> None:
    """``state``'s rows ``rows`` set to ``other``'s, in place."""
    state.theta[rows] = other.theta
    state.current[rows] = other.current
    pairs = ((state.offsets, other.offsets), (state.links, other.links), (state.motions, other.motions))
    for mine, theirs in pairs:
        for key, value in mine.items():
            value[rows] = theirs[key]


def concatenated(states: list[KinematicState]) -> KinematicState | None:
    """The states of consecutive chunks as one (None for no chunk)."""
    if len(states) <= 1:
        return states[0] if states else None

    def joined(parts: list[dict[Any, Array]]) -> dict[Any, Array]:
        return {key: np.concatenate([part[key] for part in parts]) for key in parts[0]}

    return KinematicState(
        np.concatenate([state.theta for state in states]),
        joined([state.offsets for state in states]),
        joined([state.links for state in states]),
        np.concatenate([state.current for state in states]),
        joined([state.motions for state in states]),
    )
