"""Rods eliminated from a pinned loop closure (private; :mod:`screwkit.core.loop_closure`).

A *rod* is a binary link between two spherical joints (the distal links of a Delta, an H4, a Quattro,
a Ragnar): whatever the rest of the mechanism does, it imposes one equation, that the distance between
its two balls' centres stays its length, and carries one idle freedom, its spin about its own axis
(Merlet, *Parallel Robots*, 2nd ed., 2006, §3.1 and §4.2.2: an S–S link is a distance constraint, which
is how the Delta's inverse kinematics is solved in closed form). When the task places the platform, a
mechanism whose loops are all closed by rods is solved on the remaining joints alone (the actuated
arms, the platform's own joints) from one equation per rod,

    ``gᵣ(θ) = (|q_b − q_a|² − ℓᵣ²) / (2 ℓᵣ)``,
    ``∂gᵣ/∂θ_c = (q_b − q_a)ᵀ (σ_b,c (v_c + ω_c × q_b) − σ_a,c (v_c + ω_c × q_a)) / ℓᵣ``,

with ``q_a``, ``q_b`` the centres carried by the links at the rod's ends, ``(ω_c; v_c)`` the current screw
of joint variable ``c`` and ``σ`` its sign on each end link's tree path (the velocity of a point ``q`` of
a link is ``v + ω × q``; Murray, Li & Sastry, *A Mathematical Introduction to Robotic Manipulation*, 1994,
Eq. 2.58). The minimum-norm Newton correction, the continuation, its steps and the working-mode check of
every step are the loop closure's, on these equations (an H4 half-platform's block, its two legs, is 4
rods × 3 joint variables against 24 loop equations × 27 variables with the balls' angles). Once a step's
equations are solved each rod is placed back: turned by the least rotation that takes its reference
direction to ``q_b − q_a`` (its spin kept at the reference's), its balls' motions are the relative
displacements of the links they join, written as their offsets with zero angles (the form
:meth:`~screwkit.core.kinematic_model.KinematicModel.recentred` gives); the whole model's loops and task
are then checked as for any mechanism, so a pose is reached only where every loop closes.

The corrector runs compiled, pose by pose, when numba is installed (:mod:`screwkit.core._rod_newton_numba`),
else in numpy over the batch (:meth:`_RodLoops.newton`); the two agree to round-off.

Examples
--------
>>> from screwkit.robots.catalog import load_mechanism
>>> from screwkit.robots.graph_kinematics import kinematics_of
>>> kinematics = kinematics_of(load_mechanism("delta"))
>>> rods = rods_of(kinematics.model.pinned_model(kinematics.task.coordinates.link))
>>> rods.names[:2], rods.ends[0]  # three parallelograms of two rods, each from an arm to the platform
(('rod1a', 'rod1b'), ('platform', 'arm1'))
>>> (rods.lengths * kinematics.model.length).round(9).tolist()  # mm: Williams' l = 1244 mm
[1244.0, 1244.0, 1244.0, 1244.0, 1244.0, 1244.0]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from ..algebra.compiled import compiled_kernels
from ._batched_poe import BatchedProduct, rigid_inverse
from ._closure_systems import MAX_CORRECTION, NEWTON_ITERATIONS, _GroupedBlocks
from .kinematic_model import KinematicModel

__all__ = ["RodLinks", "rods_of"]

Array = np.ndarray

#: The compiled corrector.
KERNELS = "screwkit.core._rod_newton_numba"


@dataclass(frozen=True)
class RodLinks:
    """The rods of a pinned model whose every loop one of them closes (:func:`rods_of`).

    Attributes
    ----------
    names : tuple
        The rod links.
    joints : tuple of tuple of str
        Per rod, its two spherical joints (end ``a``, end ``b``).
    ends : tuple of tuple
        Per rod, the links at its ends ``a`` and ``b``.
    centres : numpy.ndarray, shape (R, 2, 3)
        The balls' centres at the reference configuration (scaled frame).
    lengths : numpy.ndarray, shape (R,)
        The rods' lengths (characteristic lengths).
    """

    names: tuple[Any, ...]
    joints: tuple[tuple[str, str], ...]
    ends: tuple[tuple[Any, Any], ...]
    centres: Array
    lengths: Array


def _ball_centre(model: KinematicModel, key: str) -> Array:
    """The common point of a spherical joint's three rotation axes (scaled frame): the least-squares
    solution of ``p × sᵢ = s0ᵢ``."""
    rows = np.array([model.columns[c].row for c in model.joints[key][2]])
    directions, moments = rows[:, :3], rows[:, 3:]
    cross = np.zeros((len(rows), 3, 3))  # −[sᵢ]× p = s0ᵢ
    cross[:, 0, 1], cross[:, 0, 2], cross[:, 1, 2] = directions[:, 2], -directions[:, 1], directions[:, 0]
    cross[:, 1, 0], cross[:, 2, 0], cross[:, 2, 1] = -directions[:, 2], directions[:, 1], -directions[:, 0]
    centre, *_ = np.linalg.lstsq(cross.reshape(-1, 3), moments.ravel(), rcond=None)
    return centre


def rods_of(model: KinematicModel) -> RodLinks | None:
    """The rods of a pinned model, if they close all its loops (module docstring).

    A rod is a link other than the roots with exactly two joints, both spherical, between two links
    that are not rods; the model qualifies when every loop is closed by one of a rod's two joints,
    each rod closes exactly one (the rod hangs from the tree by the other), no rod joins the base to
    the placed platform or either to itself, and every spherical joint is a rod's.

    Parameters
    ----------
    model : KinematicModel
        A model pinned to its platform (:meth:`~screwkit.core.kinematic_model.KinematicModel.pinned_model`).

    Returns
    -------
    RodLinks or None
        None when the model does not qualify: no rod, a loop that no rod closes (the Gough–Stewart
        platform's legs, a five-bar), a ball elsewhere in a leg.

    Examples
    --------
    See the module docstring.
    """
    incident: dict[Any, list[str]] = {}
    for key, (u, v, _) in model.joints.items():
        incident.setdefault(u, []).append(key)
        incident.setdefault(v, []).append(key)
    rods = {
        link: sorted(keys, key=lambda key: key in model.closing)  # the tree joint first
        for link, keys in incident.items()
        if link not in model.roots and len(keys) == 2 and all(model.types[key] == "S" for key in keys)
    }
    rod_joints = {key for keys in rods.values() for key in keys}
    if not rods or any(key not in rod_joints for key in model.closing):
        return None
    if any(kind == "S" and key not in rod_joints for key, kind in model.types.items()):
        return None  # (another ball's angles would fold into offsets the rods' equations do not carry)
    joints, ends, centres, lengths = [], [], [], []
    for rod, keys in rods.items():
        if sum(key in model.closing for key in keys) != 1:
            return None
        others = []
        for key in keys:
            u, v, _ = model.joints[key]
            others.append(v if u == rod else u)
        if any(other in rods for other in others) or all(other in model.roots for other in others):
            return None  # (a rod between two placed links has no joint variable to solve for)
        pair = np.array([_ball_centre(model, key) for key in keys])
        length = float(np.linalg.norm(pair[1] - pair[0]))
        if not length > 1e-9:
            return None
        joints.append((keys[0], keys[1]))
        ends.append(tuple(others))
        centres.append(pair)
        lengths.append(length)
    return RodLinks(tuple(rods), tuple(joints), tuple(ends), np.array(centres), np.array(lengths))


def _cross(a: Array, b: Array) -> Array:
    """``a × b`` over the last axis (broadcast; numpy's ``cross`` moves axes for every call)."""
    return np.stack(
        [a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1], a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
         a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1,
    )


class _RodLoops(_GroupedBlocks):
    """The pinned loops with their rods replaced by their distance equations (module docstring).

    Its states are the remaining links' displacements ``(B, links, 4, 4)`` and the remaining joint
    variables' current screws ``(B, m, 6)``; its equations one per rod, in blocks of rods sharing joint
    variables (``groups``: rods ``(k, r)``, the model's columns ``(k, c)``, the same as positions among
    the remaining variables ``(k, c)``).
    """

    def __init__(self, model: KinematicModel, task: Any, rods: RodLinks):
        super().__init__(model, task)
        pinned = model.pinned_model(task.coordinates.link)
        self.rods = rods
        rod_columns = {c for pair in rods.joints for key in pair for c in pinned.joints[key][2]}
        self.remaining = np.array([c for c in range(pinned.size) if c not in rod_columns], dtype=np.int64)
        position = {int(c): i for i, c in enumerate(self.remaining)}
        kept = {key: (u, v, [position[c] for c in columns]) for key, (u, v, columns) in pinned.joints.items()
                if key not in {key for pair in rods.joints for key in pair}}
        order = [link for link in pinned.order if link not in rods.names]
        tree = {link: pinned.tree[link] for link in order if link in pinned.tree}
        columns = [pinned.columns[c] for c in self.remaining]
        self.product = BatchedProduct(columns, kept, order, tree, pinned.roots)
        index = self.product.link_index
        self.end_links = np.array([[index[a], index[b]] for a, b in rods.ends], dtype=np.int64)
        self.path_signs = np.ascontiguousarray(  # (R, 2, m): each end link's tree path over the variables
            [[pinned.paths[link][self.remaining] for link in pair] for pair in rods.ends]
        )
        involved = np.any(self.path_signs != 0, axis=1)
        blocks = nx.Graph()
        blocks.add_nodes_from(range(len(rods.names)))
        for column in range(self.remaining.size):
            holders = np.flatnonzero(involved[:, column])
            blocks.add_edges_from((holders[0], other) for other in holders[1:])
        shapes: dict[tuple[int, int], list[tuple[Array, Array]]] = {}
        for part in nx.connected_components(blocks):
            rows = np.array(sorted(part))
            shapes.setdefault((rows.size, int(involved[rows].any(axis=0).sum())), []).append(
                (rows, np.flatnonzero(involved[rows].any(axis=0)))
            )
        self.groups = []
        for parts in shapes.values():
            rows, local = np.array([r for r, _ in parts]), np.array([c for _, c in parts])
            self.groups.append((rows, self.remaining[local], local))
        # each rod's balls, (rod, ball): the offset slot, its links (u, v) and which of them is the rod
        joints = [key for pair in rods.joints for key in pair]
        slot = {key: k for k, key in enumerate(self.spherical)}
        self.joint_slots = np.array([slot[key] for key in joints], dtype=np.int64)
        self.joint_rods = np.repeat(np.arange(len(rods.names)), 2)[:, None]  # (2R, 1), over (u, v)
        ends = [pinned.joints[key][:2] for key in joints]
        owners = [rods.names[rod] for rod in self.joint_rods[:, 0]]
        self.from_rod = np.array(  # (1, 2R, 2, 1, 1)
            [[link == owner for link in pair] for owner, pair in zip(owners, ends, strict=True)]
        )[None, :, :, None, None]
        self.joint_links = np.array([[index.get(link, 0) for link in pair] for pair in ends], dtype=np.int64)
        self.rod_columns = np.array(sorted(rod_columns), dtype=np.int64)
        self._last = np.empty((0, len(rods.names), self.remaining.size))  # (the corrector's last Jacobian)
        self.remaining_model = self.product.kernel_arrays([])  # (not `kernel_model`: the whole model's)

    def state(self, theta: Array, offsets: dict[str, Array], target: Array) -> Any:
        links, _, current = self.product.evaluate(
            np.ascontiguousarray(theta[:, self.remaining]), {}, self.task.displacement(target)
        )
        return links, current

    def _centres(self, links: Array) -> Array:
        """The balls' centres ``(B, R, 2, 3)`` carried by the links at the rods' ends."""
        ends = links[:, self.end_links]  # (B, R, 2, 4, 4)
        return np.einsum("brkij,rkj->brki", ends[..., :3, :3], self.rods.centres) + ends[..., :3, 3]

    def equations(self, state: Any, target: Array) -> tuple[Array, Any]:
        """The rods' residual ``(B, R)`` and, per group, their Jacobians ``(B, k, r, c)``."""
        links, current = state
        centres = self._centres(links)
        gap = centres[:, :, 1] - centres[:, :, 0]
        lengths = self.rods.lengths
        residual = (np.einsum("bri,bri->br", gap, gap) - lengths**2) / (2.0 * lengths)
        blocks = []
        for rows, _, local in self.groups:  # rows, local: (k, r), (k, c)
            screws = current[:, local]  # (B, k, c, 6)
            points = centres[:, rows]  # (B, k, r, 2, 3)
            velocity = screws[:, :, None, None, :, 3:] + _cross(  # (B, k, r, 2, c, 3)
                screws[:, :, None, None, :, :3], points[..., None, :]
            )
            signs = np.take_along_axis(  # (k, r, 2, c)
                self.path_signs[rows], local[:, None, None, :], axis=3
            )
            moved = signs[None, ..., None] * velocity
            blocks.append(
                np.einsum("bkri,bkrci->bkrc", gap[:, rows], moved[:, :, :, 1] - moved[:, :, :, 0])
                / lengths[rows][None, :, :, None]
            )
        return residual, blocks

    def newton(
        self, theta: Array, offsets: Array, target: Array, tolerance: Array, working: Array
    ) -> tuple[Array, Array, Array, Array]:
        """The corrector of :class:`~screwkit.core._closure_systems._LoopsAndTask` on the rods'
        equations, a fresh factorisation at every iteration (the blocks are small), then the rods
        placed back (module docstring); the rods' Jacobian at the final values is kept for the
        working-mode check of the step (:meth:`last_blocks`)."""
        at = np.flatnonzero(working)
        fresh = tolerance.copy()
        fresh[:, 3] = 0.0
        self._last = np.full((len(theta), len(self.rods.names), self.remaining.size), np.nan)
        kernels = compiled_kernels(KERNELS, at.size)
        if kernels is None or at.size == 0:
            sizes, corrected, leading, unfolded = super().newton(theta, offsets, target, fresh, working)
            if at.size:
                state = self.state(theta[at], {}, target[at])
                self._last[at] = self._jacobian(state)
                motions = self._ball_motions(state[0])
        else:
            remaining = np.ascontiguousarray(theta[at][:, self.remaining])
            placed = np.ascontiguousarray(self.task.displacement(target[at]))
            sizes, corrected, leading, motions, self._last[at] = kernels.rod_newton(
                remaining, placed, np.ascontiguousarray(fresh[at]), NEWTON_ITERATIONS, MAX_CORRECTION,
                self.remaining_model, self.end_links, self.rods.centres, self.rods.lengths, self.path_signs,
                self.joint_rods[:, 0], self.from_rod[0, :, :, 0, 0], self.joint_links,
            )
            theta[np.ix_(at, self.remaining)] = remaining
            unfolded = theta[at]
        if at.size:
            offsets[at[:, None], self.joint_slots[None, :]] = motions
            theta[np.ix_(at, self.rod_columns)] = 0.0
        return sizes, corrected, leading, unfolded

    def last_blocks(self, rows: Array) -> list[Array]:
        """The Jacobian blocks (as :meth:`equations` gives them) at the last corrector's final values of
        the poses ``rows`` (integer positions in its batch; NaN for a pose it did not correct)."""
        return [self._last[rows][:, parts[:, :, None], local[:, None, :]] for parts, _, local in self.groups]

    def _jacobian(self, state: tuple[Array, Array]) -> Array:
        """The rods' whole Jacobian ``(B, R, m)`` over the remaining variables (:meth:`equations`' blocks
        put together)."""
        _, blocks = self.equations(state, np.empty(0))
        out = np.zeros((len(state[0]), len(self.rods.names), self.remaining.size))
        for (parts, _, local), block in zip(self.groups, blocks, strict=True):
            out[:, parts[:, :, None], local[:, None, :]] = block
        return out

    def _ball_motions(self, links: Array) -> Array:
        """The balls' motions ``(P, 2R, 4, 4)`` (offsets, their angles zero): each rod turned by the
        least rotation from its reference direction ``u₀`` to its ends' ``u``, about ``k = u₀ × u``
        (Rodrigues' formula ``R = I + sin θ [a]× + (1 − cos θ) [a]×²``, Murray, Li & Sastry 1994, Eq.
        2.14, with ``sin θ a = k`` and ``1 − cos θ = |k|² / (1 + cos θ)``: ``R = I + [k]× + [k]×² / (1 +
        u₀·u)``), a ball's motion the relative rotation of the links it joins (that of ``D_u⁻¹ D_v``)
        about its centre: where the rod's ends are not its length apart (a pose out of reach, Newton
        stopped short) the rod's closing ball then leaves that gap in its loop's residual, which the
        whole model's check reads, instead of a translation no ball can make."""
        centres = self._centres(links)  # (P, R, 2, 3)
        gap = centres[:, :, 1] - centres[:, :, 0]
        direction = gap / np.linalg.norm(gap, axis=-1, keepdims=True)
        reference = (self.rods.centres[:, 1] - self.rods.centres[:, 0]) / self.rods.lengths[:, None]
        axis = _cross(reference[None], direction)
        cosine = np.einsum("ri,bri->br", reference, direction)
        skew = np.zeros((*axis.shape, 3))
        skew[..., 0, 1], skew[..., 0, 2], skew[..., 1, 2] = -axis[..., 2], axis[..., 1], -axis[..., 0]
        skew[..., 1, 0], skew[..., 2, 0], skew[..., 2, 1] = axis[..., 2], -axis[..., 1], axis[..., 0]
        with np.errstate(divide="ignore", invalid="ignore"):  # a rod turned by π: NaN, flagged as such
            rotation = np.eye(3) + skew + skew @ skew / (1.0 + cosine)[..., None, None]
        rods = np.zeros((*rotation.shape[:-2], 4, 4))
        rods[..., :3, :3], rods[..., 3, 3] = rotation, 1.0
        rods[..., :3, 3] = centres[:, :, 0] - np.einsum("brij,rj->bri", rotation, self.rods.centres[:, 0])
        moved = np.where(self.from_rod, rods[:, self.joint_rods], links[:, self.joint_links])
        motions = rigid_inverse(moved[:, :, 0]) @ moved[:, :, 1]  # (P, 2R, 4, 4)
        centres = self.rods.centres.reshape(-1, 3)  # a ball turns about its centre: (R, c − R c)
        motions[..., :3, 3] = centres - np.einsum("bjik,jk->bji", motions[..., :3, :3], centres)
        return motions
