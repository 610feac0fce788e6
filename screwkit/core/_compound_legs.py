"""Compound legs whose actuators share a link, analysed as a whole where a limb's own wrench fails (private).

A compound leg is a branch of the root of the series-parallel tree (the H4's ``L_I = l12 − R_I``,
:attr:`screwkit.graphs.topology.Topology.legs`). Where its actuators share a link (the H4's
nacelle) a limb's actuation wrench from its own chain can fail although the pose is regular;
:func:`compound_legs` then takes the wrench that loads that actuator alone from the leg's locked
wrench system (the why, the method and the evidence: its docstring). The leg residuals
(:func:`leg_residuals`, :func:`apart_from_legs`) measure a wrench against its leg's constraint
system, for that decision and for the actuation closeness.

Examples
--------
>>> from screwkit.graphs.jointtable import JointTable
>>> from screwkit.graphs.topology import topology
>>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[[0, 0, 1.0, 0, 0, 0]]], True)])
>>> coupled_limbs(topology(table.base, table.platform, table.specs))  # one limb, no partner
[]
"""

from __future__ import annotations

import itertools
from typing import NamedTuple

import numpy as np

from ..graphs.topology import Topology
from . import _limbs as LK
from . import _residuals as R
from . import frames as F
from ._program import Evaluation, Frame
from .line_search import nearest_lines

__all__ = [
    "COMPOUND_LINE_REACH",
    "COMPOUND_RTOL",
    "LockedLegs",
    "apart_from_legs",
    "branch_part",
    "compound_legs",
    "coupled_limbs",
    "leg_of",
    "leg_path",
    "leg_residuals",
]

Array = np.ndarray


#: A limb with partners whose own actuation wrench (unit, scaled) lies this close to its compound
#: leg's constraint system has its leg analysed as a whole (:func:`compound_legs`).
COMPOUND_RTOL = 1e-6

#: A compound leg's actuation wrench (unit, scaled) is drawn as a line only if the constraint
#: wrench that makes it one is at most this large: where none of moderate size exists (the H4's
#: ``W_1`` at ``n1·z = 0``, whose pitch no multiple of ``C_n1`` changes), the root found is
#: round-off divided by round-off, and the "line" would be the constraint couple itself.
COMPOUND_LINE_REACH = 1e3



class LockedLegs(NamedTuple):
    """Where compound legs were analysed as a whole (:func:`compound_legs`), each such leg's
    ``W_locked`` there: rows ``(m, 6 q, 6)``, orthonormal, zero beyond each leg's order."""

    where: Array
    rows: Array

    def add_to(self, global_frame: Frame, constraint: Frame, rows: Array, rtol: float) -> None:
        """The global system ``W^c + Σ_L W_L,locked`` at those poses (in place; one rank rule).

        Parameters
        ----------
        global_frame : tuple of numpy.ndarray
            The global frame over the batch, changed in place.
        constraint : tuple of numpy.ndarray
            The constraint frame.
        rows : numpy.ndarray, shape (..., n, 6)
            The limbs' wrench rows.
        rtol : float
        """
        where = self.where
        frame = F.span(np.concatenate([constraint[0][where], rows[where], self.rows], axis=-2), rtol)
        global_frame[0][where], global_frame[1][where] = frame


def coupled_limbs(top: Topology) -> list[int]:
    """The limbs with partners in a compound leg (none in a network).

    Parameters
    ----------
    top : Topology

    Returns
    -------
    list of int
    """
    return [] if top.network else [k for k, plan in enumerate(top.limbs) if plan.partners]


def leg_residuals(top: Topology, rows: Array, legs: Array) -> Array | None:
    """Wrench rows ``(..., n, 6)`` of the limbs with partners (:func:`coupled_limbs`) less their part in
    their compound leg's constraint system (``legs (..., L, 6, 6)``, the legs' wrench frames),
    ``(..., m, 6)`` (not renormalised; None without such limbs): what :func:`compound_legs` and
    :func:`apart_from_legs` measure.

    Parameters
    ----------
    top : Topology
    rows : numpy.ndarray, shape (..., n, 6)
    legs : numpy.ndarray, shape (..., L, 6, 6)

    Returns
    -------
    numpy.ndarray, shape (..., m, 6), or None
    """
    coupled = coupled_limbs(top)
    if not coupled:
        return None
    return R.residuals_against(rows[..., coupled, :], legs, np.array([leg_of(top, k) for k in coupled]))


def apart_from_legs(top: Topology, rows: Array, residuals: Array | None) -> Array:
    """Unit scaled wrench rows ``(..., n, 6)`` with each limb that has partners less its part in its
    compound leg's constraint system (``residuals``, :func:`leg_residuals` of ``rows``;
    renormalised): the actuation closeness's rows. A limb's own wrench may lie close to that system
    where the leg as a whole transmits well (the H4 near ``n1·z = 0``, :func:`compound_legs`),
    which would fake a near-singularity.

    Parameters
    ----------
    top : Topology
    rows : numpy.ndarray, shape (..., n, 6)
    residuals : numpy.ndarray, shape (..., m, 6), or None

    Returns
    -------
    numpy.ndarray, shape (..., n, 6)
    """
    if residuals is None:
        return rows
    out = rows.copy()
    out[..., coupled_limbs(top), :] = LK.unit_rows(residuals)
    return out


def leg_of(top: Topology, k: int) -> int:
    """The index in :attr:`Topology.legs` of limb ``k``'s compound leg.

    Parameters
    ----------
    top : Topology
    k : int
        A limb.

    Returns
    -------
    int
    """
    return next(i for i, leg in enumerate(top.legs) if leg in top.limbs[k].path)


def compound_legs(
    top: Topology,
    scaled: Array,
    rtol: float,
    leg_wrenches: list[Frame],
    actuated: Array,
    limbs: tuple[Array, Array, Array],
    residuals: Array | None,
) -> tuple[Array, Array, Array, Array, LockedLegs] | None:
    """Compound legs whose actuators share a link, analysed as a whole where a limb's own
    actuation wrench fails: ``serial, wrench, branch, transmissions`` over the batch and the
    quotients (None where no limb's wrench fails). ``limbs``: the limbs' own ``wrench, serial,
    transmissions`` (scaled); ``residuals``: :func:`leg_residuals` of their wrenches.

    **Why.** A limb with *partners* (:attr:`screwkit.graphs.topology.LimbPlan.partners`; the H4's
    ``A1`` and ``A4`` both carry the nacelle ``b_I``, which joins the end effector by ``R_I``) gets
    its actuation wrench from its own chain (``A1``, parallelogram 1, ``R_I``): the wrench reciprocal
    to that chain's passive joints, paper 002's force along the rods through the point where it
    meets ``R_I``'s axis (§4.3). Where parallelogram 1's plane contains the vertical (``n1·z = 0``)
    that line goes to infinity and becomes the couple ``C_n1``, which is also leg I's constraint
    wrench (paper 002 Eq. 3): the chain alone then says "serial" (``A1``'s twist in the span of
    its chain's passive twists) and the global system loses a rank ("actuation"). Yet the pose
    is regular: paper 004 Eq. (12) gives ``|A| = −47.9`` and paper 002 Eq. (7) ``47.9`` at
    ``(300, 300, −473.80 mm, 30°)`` (tests/analysis/test_workspace.py). With the end effector fixed and
    ``A4`` locked, ``b_I`` cannot turn about ``R_I`` (parallelogram 4's couple ``C_n4`` has
    ``n4·z ≠ 0``), so ``A1`` cannot move; with all four arms locked leg I transmits three
    independent wrenches (``C_n1``, ``F_w1 − (m1/n4z) C_n4``, ``F_w4 − (m4/n4z) C_n4``), leg II
    three. What fails is only the chain's assumption that its wrench does no work on the motion
    of the partner ``A4``.

    **The leg as a whole.** For a compound leg ``L`` with ``n_L`` actuators, ``W_free`` is its
    constraint system and ``W_locked`` the reciprocal of its twist system with its actuators
    locked. A wrench ``W`` of ``W_locked`` reaches the base through the leg's branches: split at
    each parallel node into the branches' locked wrench systems (least squares; unique when they
    are independent), the part reaching actuator ``j`` loads it with ``τ_j(W) = branch_j ∘ $_j``,
    and every motion of the leg has ``W ∘ t = Σ_j τ_j(W) θ̇_j`` (virtual work). So:

    * the leg is **serial** (an actuator moves with the platform fixed) iff ``τ`` loses rank on
      ``W_locked / W_free`` (``τ`` vanishes on ``W_free``; that quotient has order
      ``ord W_locked − ord W_free ≤ n_L``); actuator ``k`` is among the serial ones iff no
      wrench of ``W_locked`` loads ``k`` without loading the others: with ``τ`` evaluated on the
      orthonormal rows ``L_i`` of ``W_locked``, ``c_k``, the part of ``k``'s column orthogonal to
      the other actuators' columns, is ``≤ rtol`` (the rule of the limb's ``t⊥``; its
      transmission is then that of ``Σ_i c_k,i L_i``, ``~|c_k|``, continuous up to the
      singularity);
    * otherwise ``W_k = Σ_i c_k,i L_i`` loads ``k`` alone (``τ_k(W_k) = |c_k|²``), so ``B`` of the
      leg stays diagonal, ``B_kk = τ_k(W_k)`` (the branch row, :mod:`screwkit.core.jacobians`); drawn
      as a line where adding a constraint wrench can make it one (:func:`nearest_lines`; at
      ``n1·z = 0`` it cannot: the H4's ``W_1`` has a pitch there);
    * the global system is ``W^c + Σ_L W_L,locked`` (each such leg's ``W_locked`` added; one rank
      rule).

    Evidence (tests/core/test_compound_legs.py): at the H4 pose above the core now says regular; its
    ``det A`` equals paper 004's Eq. (12), its ``B`` paper 004's ``diag(−h_i)`` (Eq. 8), ``B⁻¹A``
    the finite differences of the inverse kinematics, and the six locked-leg wrenches written out
    by hand have rank 6; where both of ``b_I``'s parallelograms are vertical the nacelle spins about
    ``R_I`` with the end effector and ``A4`` fixed, turning ``A1``: a serial singularity of ``A1``
    that paper 004's model, whose sub-platforms do not turn, cannot see (its ``h_1 ≠ 0`` there).

    Generically a limb's own wrench lies in ``W_locked``, outside ``W_free``, and loads no
    partner, so it is kept: the leg is analysed as a whole only at the poses where a limb with
    partners is serial by its chain or its wrench lies within :data:`COMPOUND_RTOL` of ``W_free``,
    and only its failing limbs are replaced.

    Parameters
    ----------
    top : Topology
    scaled : numpy.ndarray, shape (..., rows, 6)
        The unit scaled joint screws.
    rtol : float
    leg_wrenches : list of tuple of numpy.ndarray
        Each compound leg's wrench frame.
    actuated : numpy.ndarray, shape (..., n, 6)
        The actuated twists, scaled.
    limbs : tuple of numpy.ndarray
        The limbs' own ``wrench, serial, transmissions``.
    residuals : numpy.ndarray, shape (..., m, 6), or None
        :func:`leg_residuals` of their wrenches.

    Returns
    -------
    tuple or None
        ``(serial, wrench, branch, transmissions, LockedLegs)`` over the batch, None where no
        limb's wrench fails.
    """
    coupled = coupled_limbs(top)
    if residuals is None:
        return None
    wrench, serial, transmissions = limbs
    failing = np.zeros(serial.shape, dtype=bool)
    failing[..., coupled] = serial[..., coupled] | (np.linalg.norm(residuals, axis=-1) <= COMPOUND_RTOL)
    where = np.asarray(failing.any(axis=-1))
    if not where.any():
        return None
    locked_scaled = scaled[where].copy()
    for plan in top.limbs:
        start = top.columns[plan.index]
        locked_scaled[:, start : start + top.specs[plan.index].dof, :] = 0.0
    locked = Evaluation(top, locked_scaled, rtol)
    twists = actuated[where]
    fixed_serial, fixed_wrench = serial[where], wrench[where]
    fixed_branch, fixed_transmissions = fixed_wrench.copy(), transmissions[where]
    lockeds = []
    for leg in sorted({leg_of(top, k) for k in coupled}):
        members = [k for k in range(len(top.limbs)) if leg_of(top, k) == leg]
        free = (leg_wrenches[leg][0][where], leg_wrenches[leg][1][where])
        leg_locked = locked.wrenches(top.legs[leg])[0]  # (m, 6, 6), zero beyond its order
        lockeds.append(leg_locked)
        paths = {k: leg_path(top, k, leg) for k in members}
        loads = np.stack(  # τ_j(L_i) over the rows L_i of W_locked, (m, 6, n_L)
            [
                np.einsum(
                    "...is,...s->...i",
                    branch_part(top, locked, paths[j], leg_locked, rtol),
                    F.swapped(twists[:, j]),
                )
                for j in members
            ],
            axis=-1,
        )
        for position, k in enumerate(members):
            replace_k = failing[where][:, k]
            if not replace_k.any():
                continue
            others = np.swapaxes(np.delete(loads, position, axis=-1), -1, -2)  # (m, n_L - 1, 6)
            alone = R.residual(loads[:, None, :, position], F.span(others, rtol)[0])[:, 0, :]
            size = np.linalg.norm(alone, axis=-1)
            is_serial = size <= rtol
            direction = LK.unit_rows(np.einsum("...i,...is->...s", alone, leg_locked))
            # a line only if the constraint added stays small
            line = nearest_lines(direction, free[0].__getitem__, free[1])
            near = np.linalg.norm(line - direction, axis=-1) <= COMPOUND_LINE_REACH
            chosen = LK.unit_rows(np.where(near[:, None], line, direction))
            part = branch_part(top, locked, paths[k], chosen[:, None, :], rtol)[:, 0, :]
            product = np.abs(np.einsum("...s,...s->...", part, F.swapped(twists[:, k])))
            new = replace_k & ~is_serial  # a serial actuator keeps its limb's (unused) wrench
            fixed_serial[:, k] = np.where(replace_k, is_serial, fixed_serial[:, k])
            fixed_wrench[:, k] = np.where(new[:, None], chosen, fixed_wrench[:, k])
            fixed_branch[:, k] = np.where(new[:, None], part, fixed_branch[:, k])
            transmission = np.where(  # serial: of the unit c_k·L, whose load is |c_k| (continuous)
                is_serial,
                LK.transmission_index(direction, twists[:, k], size, rtol),
                LK.transmission_index(chosen, twists[:, k], product, rtol),
            )
            fixed_transmissions[:, k] = np.where(replace_k, transmission, fixed_transmissions[:, k])
    serial, wrench, transmissions = serial.copy(), wrench.copy(), transmissions.copy()
    branch = wrench.copy()
    serial[where], wrench[where], branch[where], transmissions[where] = (
        fixed_serial,
        fixed_wrench,
        fixed_branch,
        fixed_transmissions,
    )
    return serial, wrench, branch, transmissions, LockedLegs(where, np.concatenate(lockeds, axis=-2))


def leg_path(top: Topology, k: int, leg: int) -> tuple[int, ...]:
    """Limb ``k``'s path from its compound leg's node down to its actuated joint.

    Parameters
    ----------
    top : Topology
    k : int
        A limb.
    leg : int
        Its compound leg.

    Returns
    -------
    tuple of int
        Tree nodes.
    """
    path = top.limbs[k].path
    return path[path.index(top.legs[leg]) :]


def branch_part(
    top: Topology, locked: Evaluation, path: tuple[int, ...], wrenches: Array, rtol: float
) -> Array:
    """The part of wrenches ``(m, k, 6)`` of a leg's locked system that reaches the end of
    ``path``: split at each parallel node into its branches' locked wrench systems (minimum-norm
    least squares), the path's branch kept.

    Parameters
    ----------
    top : Topology
    locked : Evaluation
        The frames with every actuator locked.
    path : tuple of int
        :func:`leg_path`.
    wrenches : numpy.ndarray, shape (m, k, 6)
    rtol : float

    Returns
    -------
    numpy.ndarray, shape (m, k, 6)
    """
    for node_index, child in itertools.pairwise(path):
        node = top.nodes[node_index]
        if node.kind != "parallel":
            continue
        blocks = np.concatenate([locked.wrenches(c)[0] for c in node.children], axis=-2)  # (m, 6p, 6)
        coefficients = np.einsum("...ks,...sr->...kr", wrenches, np.linalg.pinv(blocks, rcond=rtol))
        at = 6 * node.children.index(child)
        wrenches = np.einsum(
            "...kr,...rs->...ks", coefficients[..., at : at + 6], blocks[..., at : at + 6, :]
        )
    return wrenches
