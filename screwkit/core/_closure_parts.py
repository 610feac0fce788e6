"""Parts of the loop-closure continuation (:mod:`screwkit.core.loop_closure`; private): a rigid
displacement's loop residual, the pinned model's blocks as the compiled corrector reads them, and the
bookkeeping of the continuation's states and Jacobians over a batch."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra.rigid_motions import rotation_log
from .kinematic_model import KinematicModel, KinematicState

__all__ = [
    "assembled",
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
    pairs = [(state.offsets, other.offsets)]
    if state.stacked is not None and other.stacked is not None:  # (the dicts view these arrays)
        state.stacked[0][rows], state.stacked[1][rows] = other.stacked
    else:
        pairs += [(state.links, other.links), (state.motions, other.motions)]
    for mine, theirs in pairs:
        for key, value in mine.items():
            value[rows] = theirs[key]


def viewed_state(
    theta: Array,
    offsets: dict[str, Array],
    links: Array,
    current: Array,
    motions: Array,
    like: KinematicState,
) -> KinematicState:
    """A state whose link and joint dicts view the arrays ``links (B, links, 4, 4)`` and ``motions (B,
    joints, 4, 4)``, their keys in the order of ``like``'s (that of its own stacked arrays)."""
    return KinematicState(
        theta,
        offsets,
        {key: links[:, i] for i, key in enumerate(like.links)},
        current,
        {key: motions[:, j] for j, key in enumerate(like.motions)},
        (links, motions),
    )


def assembled(count: int, parts: list[tuple[Any, KinematicState]]) -> KinematicState | None:
    """One state of ``count`` poses from ``parts`` of ``(rows, state)``: each part's poses written at its
    rows (an index or a slice; together they cover every pose), once (None for no part)."""
    if not parts:
        return None
    like = parts[0][1]
    if len(parts) == 1 and len(like.theta) == count:  # (one part of every pose: itself)
        return like

    def empty(array: Array) -> Array:
        return np.empty((count, *array.shape[1:]), dtype=array.dtype)

    offsets = {key: empty(value) for key, value in like.offsets.items()}
    if all(state.stacked is not None for _, state in parts):
        links, motions = like.stacked  # type: ignore[misc]
        theta, current = empty(like.theta), empty(like.current)
        state = viewed_state(theta, offsets, empty(links), current, empty(motions), like)
    else:
        by_link = {key: empty(value) for key, value in like.links.items()}
        by_joint = {key: empty(value) for key, value in like.motions.items()}
        state = KinematicState(empty(like.theta), offsets, by_link, empty(like.current), by_joint)
    for rows, part in parts:
        replace_rows(state, rows, part)
    return state
