"""The product of exponentials of a kinematic model over a batch, every joint at once: one
Rodrigues evaluation for all joint screws, the joints' products and the spanning tree level by level
(numpy calls per tree level, none per joint), the current screws by one adjoint map.

The formulas are the model's (:mod:`screwkit.core.kinematic_model`): ``exp(ŝ θ)`` of a unit screw
``(ω; v)`` is ``(R, (I − R)(ω × v) + ω ωᵀ v θ)`` with ``R = I + sin θ K + (1 − cos θ) K²``,
``K = [ω]×`` (Murray, Li & Sastry, *A Mathematical Introduction to Robotic Manipulation*, 1994,
Eqs. 2.14 and 2.36), a slider's ``(I, v θ)``, a Π joint's ``(I, R(a, θ) w − w)``; a screw's current
value is the adjoint map of the displacement before it (Eq. 2.58).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra.compiled import compiled_kernels

Array = np.ndarray

#: The compiled twins of :meth:`BatchedProduct.evaluate` and the continuation's corrector.
KERNELS = "screwkit.core._newton_numba"


def _hat(w: Array) -> Array:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def rigid_inverse(g: Array) -> Array:
    """``g⁻¹ = (Rᵀ, −Rᵀ p)`` of rigid displacements ``(..., 4, 4)``."""
    out = np.zeros_like(g)
    rotation_t = np.swapaxes(g[..., :3, :3], -1, -2)
    out[..., :3, :3] = rotation_t
    out[..., :3, 3] = -(rotation_t @ g[..., :3, 3, None])[..., 0]
    out[..., 3, 3] = 1.0
    return out


def _adjoint(g: Array, rows: Array) -> Array:
    """The adjoint map ``(R s; R s0 + p × R s)`` of displacements ``(..., 4, 4)`` on screws ``(..., 6)``
    (Murray, Li & Sastry 1994, Eq. 2.58)."""
    rotation = np.ascontiguousarray(g[..., :3, :3])  # (einsum is several times faster on contiguous
    out = np.empty(rows.shape)  # operands than on these strided views)
    out[..., :3] = s = np.einsum("bnij,bnj->bni", rotation, np.ascontiguousarray(rows[..., :3]))
    turned = np.einsum("bnij,bnj->bni", rotation, np.ascontiguousarray(rows[..., 3:]))
    out[..., 3:] = turned + _cross(np.ascontiguousarray(g[..., :3, 3]), s)
    return out


def _cross(a: Array, b: Array) -> Array:
    """``a × b`` over the last axis, written out (``np.cross``'s overhead dominates these calls)."""
    a0, a1, a2, b0, b1, b2 = a[..., 0], a[..., 1], a[..., 2], b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


class BatchedProduct:
    """What the model's state needs, precomputed once: per column the coefficients of its
    exponential, per joint its columns, per tree level its links.

    Parameters
    ----------
    columns : list of JointColumn
    joints : dict
        Joint name → ``(parent, child, column indices)``.
    order : list
        The links, each after its tree parent.
    tree : dict
        Link → ``(tree joint reaching it, traversed forward)``.
    roots : list
        The links placed from outside (the base at the identity; a pinned link at given displacements).
    """

    def __init__(self, columns: list[Any], joints: dict[str, Any], order: list[Any], tree: dict, roots: list):
        n = len(columns)
        rotation_k = np.zeros((n, 3, 3))
        coefficients = np.zeros((3, n, 3))  # of the translation: θ, sin θ, 1 − cos θ
        self.rows = np.array([column.row for column in columns]).reshape(n, 6)
        self.hinges = [i for i, column in enumerate(columns) if column.hinge is not None]
        for i, column in enumerate(columns):
            if column.hinge is not None:  # R(a, θ) w − w = (sin θ [a]× + (1 − cos θ) [a]×²) w
                axis = _hat(column.hinge)
                coefficients[1, i], coefficients[2, i] = axis @ column.rod, axis @ axis @ column.rod
                continue
            w, v = column.row[:3], column.row[3:]
            size = float(np.sqrt(w @ w))
            if size < 1e-12:
                coefficients[0, i] = v
                continue
            w, v = w / size, v / size
            axis = _hat(w)
            moment = np.cross(w, v)
            rotation_k[i] = axis
            coefficients[:, i] = [w * (w @ v), -axis @ moment, -axis @ axis @ moment]
        # the upper 3 × 4 block (R | p) of exp(ŝ θ), row by row, per column, from (1, θ, sin θ, 1 − cos θ)
        exponential = np.zeros((n, 4, 3, 4))
        exponential[:, 0, :, :3] = np.eye(3)
        exponential[:, 2, :, :3] = rotation_k
        exponential[:, 3, :, :3] = rotation_k @ rotation_k
        exponential[:, 1:, :, 3] = np.swapaxes(coefficients, 0, 1)
        self.exponential = exponential.reshape(n, 4, 12)
        self.hinge_axes = np.array([columns[i].hinge for i in self.hinges]).reshape(-1, 3)
        self.hinge_rods = np.array([columns[i].rod for i in self.hinges]).reshape(-1, 3)
        names = list(joints)
        self.joint_index = {key: j for j, key in enumerate(names)}
        depth = max((len(joints[key][2]) for key in names), default=0)
        self.positions = []  # per position k within a joint: (joints with a k-th column, those columns)
        for k in range(depth):
            having = [j for j, key in enumerate(names) if len(joints[key][2]) > k]
            self.positions.append((np.array(having), np.array([joints[names[j]][2][k] for j in having])))
        self.rigid = np.array([j for j, key in enumerate(names) if not joints[key][2]], dtype=int)
        self.link_index = {link: i for i, link in enumerate(order)}
        self.roots = [self.link_index[root] for root in roots]
        level = {link: 0 for link in roots}
        for link in order:
            if link not in level:
                key, forward = tree[link]
                u, v, _ = joints[key]
                level[link] = level[u if forward else v] + 1
        self.levels = []  # per tree level: (links, their parents, their tree joints, traversed forward)
        for depth_here in range(1, max(level.values(), default=0) + 1):
            links = [link for link in order if level[link] == depth_here]
            parents, keys, forwards = [], [], []
            for link in links:
                key, forward = tree[link]
                u, v, _ = joints[key]
                parents.append(self.link_index[u if forward else v])
                keys.append(self.joint_index[key])
                forwards.append(forward)
            self.levels.append(
                ([self.link_index[link] for link in links], parents, keys, np.array(forwards, dtype=bool))
            )
        self.column_parent = np.array([self.link_index[column.parent] for column in columns], dtype=int)
        self._kernel_arrays: dict[tuple[str, ...], tuple] = {}
        self.joint_ptr = np.cumsum([0] + [len(joints[key][2]) for key in names]).astype(np.int64)
        self.joint_columns = np.array([c for key in names for c in joints[key][2]], dtype=np.int64)
        self.tree = np.array(  # (child, parent, joint, forward), level by level
            [[c, p, k, f] for children, parents, keys, forwards in self.levels
             for c, p, k, f in zip(children, parents, keys, forwards, strict=True)],
            dtype=np.int64,
        ).reshape(-1, 4)

    def kernel_arrays(self, offset_keys: list[str]) -> tuple:
        """The model's arrays for the compiled :func:`screwkit.core._newton_numba.evaluate`, the
        offsets of the joints ``offset_keys`` stacked in that order."""
        keys = tuple(offset_keys)
        if keys not in self._kernel_arrays:
            slot = np.full(len(self.joint_index), -1, dtype=np.int64)
            for k, key in enumerate(keys):
                slot[self.joint_index[key]] = k
            self._kernel_arrays[keys] = (
                self.exponential, self.rows, np.array(self.hinges, dtype=np.int64), self.hinge_axes,
                self.hinge_rods, self.joint_ptr, self.joint_columns, slot, self.tree,
                np.array(self.roots, dtype=np.int64), self.column_parent.astype(np.int64),
                len(self.link_index),
            )
        return self._kernel_arrays[keys]

    def joint_motions(
        self, theta: Array, offsets: dict[str, Array], *, screws: bool = True
    ) -> tuple[Array, Array]:
        """Joint displacements ``(B, joints, 4, 4)`` and, with ``screws``, every screw carried by its
        joint's motion before it ``(B, n, 6)`` (else the reference screws) at ``theta (B, n)``."""
        count, n = theta.shape
        basis = np.stack([np.ones_like(theta), theta, np.sin(theta), 1.0 - np.cos(theta)], axis=-1)
        steps = np.zeros((count, n, 4, 4))  # (column, batch) matrix products: one BLAS call per column
        upper = np.swapaxes(np.swapaxes(basis, 0, 1) @ self.exponential, 0, 1)
        steps[..., :3, :] = upper.reshape(count, n, 3, 4)
        steps[..., 3, 3] = 1.0
        translation = steps[..., :3, 3]
        rows = np.broadcast_to(self.rows, (count, n, 6)).copy()
        if self.hinges and screws:  # the Π's twist turns with its rods: (0; a × R(a, θ) w)
            rows[:, self.hinges, 3:] = _cross(self.hinge_axes, self.hinge_rods + translation[:, self.hinges])
        having, cols = self.positions[0] if self.positions else (np.zeros(0, int), np.zeros(0, int))
        motions = np.empty((count, len(self.joint_index), 4, 4))
        motions[:, self.rigid] = np.eye(4)  # joints without a screw
        motions[:, having] = steps[:, cols]  # a joint's first screw, where the joint has no offset
        if offsets:  # the offset turns the joint's screws and comes before them
            turned = np.array([self.joint_index[key] for key in offsets])
            first = cols[np.searchsorted(having, turned)]
            stacked = np.stack(list(offsets.values()), axis=1)
            if screws:
                rows[:, first] = _adjoint(stacked, rows[:, first])
            motions[:, turned] = stacked @ steps[:, first]
        for having, cols in self.positions[1:]:  # each further screw carried by the motion before it
            if screws:
                rows[:, cols] = _adjoint(motions[:, having], rows[:, cols])
            motions[:, having] = motions[:, having] @ steps[:, cols]
        return motions, rows

    def evaluate(
        self, theta: Array, offsets: dict[str, Array], pinned: Array | None = None
    ) -> tuple[Array, Array, Array]:
        """Link displacements ``(B, links, 4, 4)`` (order of ``order``), joint displacements
        ``(B, joints, 4, 4)`` and current screws ``(B, n, 6)`` at ``theta (B, n)``; ``pinned`` places
        the second root (``(B, 4, 4)``)."""
        count = theta.shape[0]
        kernels = compiled_kernels(KERNELS, count)
        if kernels is not None:
            keys = list(offsets)
            stacked = np.stack([offsets[key] for key in keys], axis=1) if keys else np.zeros((count, 0, 4, 4))
            return kernels.evaluate(
                np.ascontiguousarray(theta, dtype=float),
                np.ascontiguousarray(stacked, dtype=float),
                np.zeros((1, 4, 4)) if pinned is None else np.ascontiguousarray(pinned, dtype=float),
                self.kernel_arrays(keys),
            )
        return self.evaluate_numpy(theta, offsets, pinned)

    def evaluate_numpy(
        self, theta: Array, offsets: dict[str, Array], pinned: Array | None = None
    ) -> tuple[Array, Array, Array]:
        """:meth:`evaluate` with numpy over the batch (the compiled kernel's twin)."""
        count = theta.shape[0]
        motions, rows = self.joint_motions(theta, offsets)
        links = np.empty((count, len(self.link_index), 4, 4))
        links[:, self.roots[0]] = np.eye(4)
        if len(self.roots) > 1:
            links[:, self.roots[1]] = pinned
        for children, parents, keys, forwards in self.levels:
            moved = motions[:, keys]
            if not forwards.all():
                moved = np.where(forwards[:, None, None], moved, rigid_inverse(moved))
            links[:, children] = links[:, parents] @ moved
        return links, motions, _adjoint(links[:, self.column_parent], rows)
