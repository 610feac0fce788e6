"""Forward and inverse Jacobians ``A χ̇ = B θ̇`` from the wrench systems; Gosselin–Angeles types.

Derivation
----------
Let ``t_1 … t_dof`` be a basis of the platform's twists (rows ``(dof, 6)``, e.g.
:func:`schoenflies_basis`) and ``t = Σ_k χ̇_k t_k`` the twist of the platform. Limb ``j`` has the
actuated joint twist ``$_j`` and, from :func:`~screwkit.core.wrenches.wrench_analysis`, an actuation
wrench ``w_j``: reciprocal to every twist the limb allows with its actuator locked (its *passive*
wrench system, paper 002 §4.3). Along the limb the platform's twist is ``t = θ̇_j $_j + t_p`` with
``t_p`` a twist of the locked limb, so ``w_j ∘ t = θ̇_j (w_j ∘ $_j)`` (reciprocal product, conventions
in :mod:`screwkit.algebra.screw`; Joshi & Tsai, "Jacobian analysis of limited-DOF parallel manipulators",
ASME J. Mech. Des. 124(2), 2002). Stacking the limbs,

* ``A_jk = w_j ∘ t_k``  (n_actuated × dof, the *forward* or direct Jacobian),
* ``B = diag(w_j ∘ $_j)`` (n × n, the *inverse* Jacobian),

and ``A χ̇ = B θ̇``, the form of paper 004 Eq. (6). In a compound leg whose actuators share a link
(the H4's ``A1``, ``A4`` on the nacelle ``b_I``), where a limb's own wrench fails the core picks
``w_j`` from the leg as a whole, loading ``A_j`` alone (:func:`screwkit.core.wrench_systems.analyze_table`):
``w_j`` then splits between the leg's parallel branches and ``B_jj`` is the part on ``A_j``'s branch
times ``$_j`` (:attr:`~screwkit.core.wrench_systems.WrenchAnalysis.branch_rows`); ``B`` stays diagonal and its
zeros are the leg's serial singularities. This needs the actuated joint *in series* in
its limb (on no closed loop of the limb), which is checked. Each ``w_j`` is defined up to a factor
(and up to the limb's constraint wrenches, which are reciprocal to every ``t_k``), so ``A`` and
``B`` are defined up to a common diagonal row scaling ``D``; ``A⁻¹B`` is not. Here every ``w_j``
is scaled to a unit force ``|f| = 1`` (a unit moment ``|m| = 1`` if it is a pure couple) and signed
so that ``B_jj ≥ 0``. For the four-limb SMGs of paper 004 this gives exactly ``A_paper = D A``,
``B_paper = D B`` with ``D = diag(sgn h_i) = −I`` in the paper's working mode (its rows
``e_i = [w_iᵀ, r w_iᵀs_i]`` have unit ``w_i``; Eqs. 6–8).

Point tasks and redundant actuation
-----------------------------------
For a point task (:mod:`screwkit.robots.point_task`: the platform a task link on a spherical joint
at the point, ``analysis.free = 3``) the basis has one twist per freedom of the point
(``dof − free`` rows) and every ``w_j`` is a force through the point, so ``A_jk = f_j · e_k``: for the
planar five-bar the rows of ``A`` are the distal links' directions and ``B_jj = ((B_j − A_j) × u_j)·z``
(Gosselin & Angeles 1990). A redundantly actuated mechanism (:mod:`screwkit.core.redundancy`) has
more rows than columns; its direct closeness is below.

Serial singularities (no actuation wrench)
------------------------------------------
Where the actuated twist is reciprocal to the whole passive wrench system of its limb,
:func:`~screwkit.core.wrenches.wrench_analysis` finds no actuation wrench (``Limb.actuation_wrench is
None``). The row of ``A`` is then built on the passive wrench that acts most on the twist basis (the
top singular direction of the passive wrenches' normalised products with the ``t_k``; with a
passive system of order 1, its only wrench, the limit of the actuation wrench), and ``B_jj = 0``
exactly: the limb still constrains the platform (``w_j ∘ t = 0``) but its actuator cannot move it.
Such rows are listed in ``serial_limbs``; nothing is NaN.

Gosselin–Angeles types and their tolerances
-------------------------------------------
Gosselin & Angeles, "Singularity analysis of closed-loop kinematic chains", IEEE Trans. Robot.
Autom. 6(3), 1990; paper 004 §4.2 (type 1: ``|B| = 0``, type 2: ``|A| = 0``). The decisions use
unit-free matrices, in the spirit of :mod:`screwkit.core.verdicts`'s closeness measures:

* ``Â_jk = (w_j ∘ t_k) / (N(w_j) N(t_k) L)`` with ``L`` the mechanism's characteristic length and
  ``N`` the size of :func:`~screwkit.core.wrenches.normalized_reciprocal_product` (``|s|``, or ``|s0|/L``
  for a couple or translation). For a force and a translation it is a cosine, for a force and a
  rotation the mutual moment over ``L``. ``Â`` does not change under rigid motions or changes of
  unit (it does depend on the choice of ``L``, as any conditioning of a dimensionally
  inhomogeneous Jacobian does; the *zero* decision does not).
* closeness ``"direct"`` = σ_dof(Â) / σ_1(Â) (0 if there are fewer actuation rows than ``dof``). For a
  redundantly actuated mechanism (``n > dof`` rows, :mod:`screwkit.core.redundancy`) ``Â`` is
  ``n × dof`` and σ_dof its smallest singular value: 0 exactly where ``rank A < dof``, where the
  platform keeps a twist of the basis with *all* the actuators locked (the redundant robot's actuation
  singularity; Gosselin & Angeles' type 2 for a non-square ``A``). It is the inverse condition number
  of ``Â``, so it does not change when the rows are permuted or the basis rotated orthonormally;
* closeness ``"inverse"`` = min_j ``|B_jj| / (N(w_j) N($_j) L)``, the smallest limb transmission
  (equal to :mod:`screwkit.core.verdicts`'s ``"serial"`` closeness), 0 for a limb in ``serial_limbs``.

A pose is ``"direct"`` (type 2, parallel: ``A`` loses rank, the platform keeps an uncontrolled
twist of the basis with the actuators locked) when the direct closeness is ``≤ rtol``,
``"inverse"`` (type 1, serial) when the inverse closeness is ``≤ rtol``, ``"combined"`` when both,
else ``"regular"``. The default ``rtol`` is the analysis's (1e-9): ``"inverse"`` is then the
decision behind :func:`~screwkit.core.singularity.classify`'s ``"serial"`` label (same measure, same
tolerance), and a rank-deficient ``A`` goes with its ``"actuation"`` label, though the two are
decided on different matrices (``Â`` here, the global wrench system there).

The basis is checked: its rows must be independent (rank ``dof`` at ``rtol``) and lie in the
platform's twist system (relative residual ``≤ basis_rtol``, default 1e-6). The membership check is
skipped at a pose with a limb at a serial singularity, where the platform's instantaneous twist
system has lost the twists that limb can no longer drive.

What ``det A`` sees and what it misses (the H4, papers 002 and 004)
-------------------------------------------------------------------
``A`` only tests the twists of the basis. Complete the Schoenflies basis ``T`` (4 × 6) with two
rotations ``T' = {(i; 0), (j; 0)}`` and stack the mechanism's constraint wrenches ``C`` (2 × 6) on
the actuation wrenches ``W`` (4 × 6). Since ``C ∘ T = 0``, the matrix of reciprocal products is
block triangular::

    [C; W] ∘ [T; T'] = [[0, C ∘ T'], [A, W ∘ T']],   so   det[C; W] = ± det(C ∘ T') · det A

(the sign from ``det[T; T']`` and the swap of the screw halves). For the H4, ``C`` spans the
couples ``(0; z × s12)``, ``(0; z × s34)`` (paper 002 Eq. 3) and ``det(C ∘ T') = (s12 × s34)·z``
is paper 002's Eq. (6); ``det A`` (paper 004 Eq. 12, ``2r (w14 × w23)ᵀs``) is *minus* paper 002's
Eq. (7) identically, because ``(r_g − r_c) × z = 2r s`` for the points ``r_c`` on ``Z_I`` and
``r_g`` on ``Z_II``. With paper 002's normalisation of the six wrenches the global determinant is
``Eq.(6) · det A = −Eq.(6) · Eq.(7)`` (the known ``±Eq.(6)·Eq.(7)`` with its sign fixed):

* ``det A`` (and the ``"direct"`` type) sees the actuation singularities (roots of Eq. 7) and misses
  the constraint singularities (roots of Eq. 6), where the platform gains a twist outside the
  Schoenflies basis: there ``A`` stays regular;
* the 6 × 6 determinant (:mod:`screwkit.core.verdicts`'s global order) sees both kinds and cannot
  tell them apart; the constraint order alone sees Eq. (6).

``tests/core/test_jacobians.py`` keeps the evidence (identities at random poses, labels at the roots).

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> from screwkit.core.wrenches import wrench_analysis
>>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
>>> result = jacobians_from_wrenches(wrench_analysis(G), [[0, 0, 0, 1, 0, 0]])
>>> result.A, result.B, result.type
(array([[1.]]), array([[1.]]), 'regular')
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra import screw as S
from ..algebra.checks import checked_rtol
from ..algebra.ranks import screw_singular_values
from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError, TwistGraphError
from . import frames as F
from .jacobian_matrices import Jacobians, _plain, _safe_divide
from .singularity import classify_poses
from .wrench_systems import WrenchAnalysis

__all__ = ["jacobians_from_wrenches", "jacobians_over_poses", "schoenflies_basis"]

Array = np.ndarray

#: Default tolerance of the twist-basis membership check (module docstring of each function).
DEFAULT_BASIS_RTOL = 1e-6

_SWAP = F.SWAP


# --------------------------------------------------------------------------------------------------
# Kernels (batched over leading axes)
# --------------------------------------------------------------------------------------------------


def schoenflies_basis(point: Any, axis: Any = (0.0, 0.0, 1.0)) -> Array:
    """Unit-rate twists of a Schoenflies motion: three translations and a rotation about ``axis``.

    The rows are the twists of the end effector (user frame, conventions of :mod:`screwkit.algebra.screw`)
    for ``ẋ = 1``, ``ẏ = 1``, ``ż = 1`` and ``φ̇ = 1``: ``(0; i)``, ``(0; j)``, ``(0; k)`` and the
    rotation ``(a; p × a)`` about the axis through ``point`` (the platform's reference point ``p``)
    along ``axis`` ``a``. With ``χ = (x, y, z, φ)`` the platform's twist is ``Σ_k χ̇_k t_k``, the
    column order of paper 004's ``A`` (Eq. 7a).

    Parameters
    ----------
    point : array_like, shape (..., 3)
        A point of the rotation axis (the point whose velocity is ``(ẋ, ẏ, ż)``).
    axis : array_like, shape (..., 3), default (0, 0, 1)
        Direction of the rotation axis; its length is the angular rate per unit ``φ̇``.

    Returns
    -------
    numpy.ndarray, shape (..., 4, 6)

    Raises
    ------
    DegenerateGeometryError
        If ``axis`` is zero.

    Examples
    --------
    >>> schoenflies_basis([100.0, 0.0, -700.0])
    array([[   0.,    0.,    0.,    1.,    0.,    0.],
           [   0.,    0.,    0.,    0.,    1.,    0.],
           [   0.,    0.,    0.,    0.,    0.,    1.],
           [   0.,    0.,    1.,    0., -100.,    0.]])
    """
    p = B.as_array(point, "point", (3,), symbolic=False)
    a = B.as_array(axis, "axis", (3,), symbolic=False)
    if np.any(np.all(a == 0, axis=-1)):
        raise DegenerateGeometryError(f"Expected `axis` to be a non-zero direction, got {a.tolist()}.")
    rotation = S.revolute_twist(a, p)
    batch = rotation.shape[:-1]
    translations = np.concatenate([np.zeros((3, 3)), np.eye(3)], axis=-1)
    return np.concatenate([np.broadcast_to(translations, (*batch, 3, 6)), rotation[..., None, :]], axis=-2)


def _products(first: Array, second: Array) -> Array:
    """Reciprocal products of rows ``(..., n, 6)`` and ``(..., m, 6)``: ``(..., n, m)``."""
    return (first @ _SWAP) @ np.swapaxes(second, -1, -2)


def _size(rows: Array, length: Array, rtol: float) -> Array:
    """``N`` of :func:`~screwkit.core.wrenches.normalized_reciprocal_product`, rows ``(..., k, 6)``."""
    directions = np.linalg.norm(rows[..., :3], axis=-1)
    moments = np.linalg.norm(rows[..., 3:], axis=-1) / length[..., None]
    return np.where(directions > rtol * moments, directions, moments)


def _most_acting(passive: Array, basis: Array, length: Array, rtol: float) -> Array:
    """The unit combination of orthonormal scaled rows ``(..., k, 6)`` acting most on the basis."""
    if passive.shape[-2] == 0:
        return np.zeros((*passive.shape[:-2], 6))
    sizes = _size(basis, length, rtol)[..., None, :]  # scaled basis: N(t) of the user frame / 1
    normalized = _safe_divide(_products(passive, basis), sizes)  # (..., k, dof)
    if normalized.shape[-1] == 0:
        return passive[..., 0, :]
    left = np.linalg.svd(normalized)[0][..., :, 0]  # (..., k)
    return np.einsum("...k,...kj->...j", left, passive)


def _jacobian_arrays(
    wrenches: Array,
    branches: Array,
    twists: Array,
    basis: Array,
    length: Array,
    substituted: Array,
    rtol: float,
) -> dict[str, Array]:
    """A, B, closeness measures and serial flags from chosen wrenches (user frame), batched.

    ``wrenches, branches, twists``: (..., n, 6) (``branches``: the part of each wrench reaching
    its actuated joint, :attr:`~screwkit.core.wrench_systems.WrenchAnalysis.branch_rows`); ``basis``:
    (..., dof, 6); ``length``: (...,); ``substituted``: (..., n) bool, rows built on a passive
    wrench (``B_jj`` set to 0).
    """
    sizes = np.linalg.norm(wrenches[..., :3], axis=-1)
    couples = np.linalg.norm(wrenches[..., 3:], axis=-1)
    is_couple = ~(sizes > rtol * couples / length[..., None])
    scale = np.where(is_couple, couples, sizes)
    wrenches = _safe_divide(wrenches, scale[..., None])
    branches = _safe_divide(branches, scale[..., None])
    forward = _products(wrenches, basis)  # (..., n, dof)
    inverse = np.einsum("...ij,...ij->...i", branches @ _SWAP, twists)  # (..., n)
    w_size, b_size = _size(wrenches, length, rtol), _size(basis, length, rtol)
    hat = _safe_divide(forward, w_size[..., :, None] * b_size[..., None, :] * length[..., None, None])
    transmission = _safe_divide(np.abs(inverse), w_size * _size(twists, length, rtol) * length[..., None])
    transmission = np.where(substituted, 0.0, transmission)
    # signs: B_jj >= 0; for a substituted row, the largest entry of its normalised A row positive
    largest = (
        np.take_along_axis(hat, np.argmax(np.abs(hat), axis=-1)[..., None], axis=-1)[..., 0]
        if (hat.shape[-1])
        else np.ones(hat.shape[:-1])
    )
    sign = np.where(
        substituted | (inverse == 0), np.where(largest < 0, -1.0, 1.0), np.where(inverse < 0, -1.0, 1.0)
    )
    wrenches, forward, hat = wrenches * sign[..., None], forward * sign[..., None], hat * sign[..., None]
    inverse = np.where(substituted, 0.0, inverse * sign)
    n, dof = forward.shape[-2], forward.shape[-1]
    if dof == 0:
        direct = np.ones(forward.shape[:-2])
    elif n < dof:
        direct = np.zeros(forward.shape[:-2])
    else:
        values = np.linalg.svd(hat, compute_uv=False)
        direct = _safe_divide(values[..., dof - 1], values[..., 0])
    inverse_closeness = transmission.min(axis=-1) if n else np.ones(forward.shape[:-2])
    return dict(
        A=forward,
        B=inverse[..., :, None] * np.eye(n),
        wrenches=wrenches,
        direct=direct,
        inverse=inverse_closeness,
        serial=transmission <= rtol,
        transmission=transmission,
    )


def _check_in_series(name: str, edges: list[tuple[Any, Any, str]]) -> None:
    """The actuated joint must be a bridge of its limb (B_jj = w_j ∘ $_j needs it)."""
    graph = nx.MultiGraph()
    graph.add_edges_from((u, v, key) for u, v, key in edges if key != name)
    ends = next((u, v) for u, v, key in edges if key == name)
    if all(node in graph for node in ends) and nx.has_path(graph, *ends):
        raise TwistGraphError(
            f"Expected actuated joint {name!r} to be in series in its limb (on no closed loop of the "
            "limb), got a loop through it; B_jj = w_j ∘ $_j needs it (screwkit.core.jacobians docstring)."
        )



def _where(mask: Array, batch: tuple[int, ...]) -> str:
    if not batch:
        return ""
    indices = [tuple(int(i) for i in index) for index in np.argwhere(mask.reshape(batch))[:3]]
    return f" at batch indices {indices}" + (" and more" if mask.sum() > 3 else "")


def _check_independent(scaled: Array, dof: int, rtol: float, batch: tuple[int, ...] = ()) -> None:
    """The rows of a scaled twist basis ``(..., dof, 6)`` are independent (rank ``dof``)."""
    if not dof:
        return
    values = screw_singular_values(scaled, length_scale=1.0)
    rank = ((values > rtol * values[..., :1]) & (values[..., :1] > 0)).sum(axis=-1)
    if np.any(rank < dof):
        raise ScrewkitValueError(
            f"Expected the {dof} rows of `twist_basis` to be independent twists, got rank "
            f"{int(np.min(rank))}{_where(rank < dof, batch)}."
        )


def _check_inside(
    scaled: Array, span: Array, skip: Any, basis_rtol: float, batch: tuple[int, ...] = ()
) -> None:
    """Scaled basis twists ``(..., dof, 6)`` lie in an orthonormal span ``(..., k, 6)`` (rows may be
    zero), except at the poses ``skip`` (a limb at a serial singularity: there the platform's
    instantaneous twist system has lost the twists that limb can no longer drive)."""
    if not scaled.shape[-2]:
        return
    inside = scaled @ np.swapaxes(span, -1, -2) @ span  # orthogonal projection on the span
    residual = np.linalg.norm(scaled - inside, axis=-1) / np.linalg.norm(scaled, axis=-1)
    worst = np.where(skip, 0.0, residual.max(axis=-1))
    if np.any(worst > basis_rtol):
        raise ScrewkitValueError(
            "Expected `twist_basis` to lie in the platform's twist system, got a twist with a relative "
            f"residual {float(np.max(worst)):.3g} > basis_rtol = {basis_rtol:g} outside it"
            f"{_where(worst > basis_rtol, batch)}."
        )


def jacobians_from_wrenches(
    analysis: WrenchAnalysis,
    twist_basis: Any,
    *,
    rtol: float | None = None,
    basis_rtol: float = DEFAULT_BASIS_RTOL,
) -> Jacobians:
    """Forward and inverse Jacobians from a wrench analysis and a basis of the platform's twists.

    ``A_jk = w_j ∘ t_k`` and ``B = diag(w_j ∘ $_j)`` (module docstring: derivation, the treatment
    of limbs at a serial singularity, the row scaling, the tolerances).

    Parameters
    ----------
    analysis : WrenchAnalysis
        From :func:`~screwkit.core.wrenches.wrench_analysis` (one pose) or
        :func:`~screwkit.core.wrench_systems.analyze_table` (a batch).
    twist_basis : array_like, shape (..., dof, 6)
        Unit-rate twists of the platform, user frame, one per degree of freedom of the analysis
        (e.g. :func:`schoenflies_basis`); they define the columns of ``A`` and the meaning of
        ``χ̇``. For a point task (``analysis.free = 3``) one per freedom of the point: the twists
        giving the point unit velocities (rows ``dof − 3``).
    rtol : float, optional
        Tolerance of the type decisions (closeness ``≤ rtol``); default the analysis's ``rtol``.
    basis_rtol : float, default 1e-6
        The basis is refused if a row, as a unit screw about the reference point with its moment
        over the length, lies farther than this from the platform's twist system (relative
        residual of its orthogonal projection). Looser than ``rtol``: at a pose just above the rank
        tolerance the platform's twist system is only known to about machine epsilon / ``rtol``.

    Returns
    -------
    Jacobians

    Raises
    ------
    ScrewkitTypeError
        If ``analysis`` is not a WrenchAnalysis.
    ScrewkitValueError
        If ``twist_basis`` has the wrong shape, dependent rows or a row outside the platform's
        twist system, or a tolerance is out of range.
    TwistGraphError
        If an actuated joint is not in series in its limb.

    Examples
    --------
    A slider-crank: a crank of length 1 (actuated revolute joint ``A`` at the origin, axis ``z``)
    pushes a slider along ``x`` through a coupler of length 2; the platform is the slider, its
    twist basis the translation ``(0; i)``, so ``A χ̇ = B θ̇`` relates ``ẋ`` to ``θ̇``.

    >>> from screwkit.graphs.joints import prismatic, revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> def slider_crank(theta):
    ...     pin = [np.cos(theta), np.sin(theta), 0.0]
    ...     slider = [pin[0] + np.sqrt(4.0 - pin[1] ** 2), 0.0, 0.0]
    ...     return twist_graph("ground", "slider", [
    ...         ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...         ("crank", "coupler", revolute("R1", [0, 0, 1], pin)),
    ...         ("coupler", "slider", revolute("R2", [0, 0, 1], slider)),
    ...         ("ground", "slider", prismatic("P", [1, 0, 0]))], dof=1)
    >>> result = jacobians_from_wrenches(wrench_analysis(slider_crank(np.pi / 2)), [[0, 0, 0, 1, 0, 0]])
    >>> result.type, result.kinematic_jacobian()  # ẋ = -θ̇ with the crank upright
    ('regular', array([[-1.]]))
    >>> print(jacobians_from_wrenches(wrench_analysis(slider_crank(0.0)), [[0, 0, 0, 1, 0, 0]]))
    inverse singularity (Gosselin-Angeles): A 1x1, B 1x1; closeness direct 1, inverse 0
      serial singularity of the limb of 'A' (B_jj = 0)
    """
    if not isinstance(analysis, WrenchAnalysis):
        raise ScrewkitTypeError(f"Expected `analysis` to be a WrenchAnalysis, got {type(analysis).__name__}.")
    tolerance = analysis.rtol if rtol is None else checked_rtol(rtol, "rtol")
    basis_tolerance = checked_rtol(basis_rtol, "basis_rtol")
    dof, batch = analysis.dof - analysis.free, analysis.shape  # a point task: the point's freedoms
    raw = B.as_array(twist_basis, "twist_basis", (None, 6), symbolic=False)
    if raw.ndim < 2 or raw.shape[-2] != dof:
        raise ScrewkitValueError(
            f"Expected `twist_basis` to have shape (..., {dof}, 6), one twist per degree of freedom of "
            f"the analysis, got {raw.shape}."
        )
    try:
        basis = np.broadcast_to(raw, (*batch, dof, 6))
    except ValueError as err:
        raise ScrewkitValueError(
            f"Expected `twist_basis` to have shape (..., {dof}, 6) broadcastable to the batch shape "
            f"{batch}, got {raw.shape}."
        ) from err
    specs = {spec.name: spec for spec in analysis.table.specs}
    for plan in analysis.topology.limbs:
        _check_in_series(plan.actuated_joint, [(specs[j].parent, specs[j].child, j) for j in plan.joints])
    centre = np.asarray(analysis.reference_point, dtype=float)
    length = np.asarray(analysis.length_scale, dtype=float)
    scaled_basis = F.to_scaled(basis, centre, length)
    _check_independent(scaled_basis, dof, tolerance, batch)
    serial = np.asarray(analysis.serial)
    n = serial.shape[-1]
    rows = np.array(analysis.actuation_rows, dtype=float)
    branches = np.array(analysis.branch_rows, dtype=float)
    for k in range(n):
        if serial[..., k].any():
            passive, _ = analysis.frames[f"limb{k}:passive"]
            chosen = _most_acting(passive, scaled_basis, np.ones(batch), tolerance)
            substitute = F.from_scaled(chosen[..., None, :], centre, length)[..., 0, :]
            rows[..., k, :] = np.where(serial[..., k, None], substitute, rows[..., k, :])
            branches[..., k, :] = np.where(serial[..., k, None], substitute, branches[..., k, :])
    twists = np.asarray(analysis.actuated_twists)
    arrays = _jacobian_arrays(rows, branches, twists, basis, length, serial, tolerance)
    platform_rows, _ = analysis.frames["platform"]
    _check_inside(scaled_basis, platform_rows, np.any(arrays["serial"], axis=-1), basis_tolerance, batch)
    return Jacobians(
        A=arrays["A"],
        B=arrays["B"],
        wrenches=arrays["wrenches"],
        twist_basis=basis,
        actuated_joints=analysis.topology.actuated,
        serial=arrays["serial"],
        closeness={"direct": _plain(arrays["direct"]), "inverse": _plain(arrays["inverse"])},
        rtol=tolerance,
        analysis=analysis,
    )


def jacobians_over_poses(
    graph: nx.MultiDiGraph,
    screws: Mapping[str, Any],
    twist_basis: Any,
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
    basis_rtol: float = DEFAULT_BASIS_RTOL,
) -> Jacobians:
    """:func:`jacobians_from_wrenches` over a batch of poses, vectorized (no loop over poses).

    As :func:`~screwkit.core.singularity.classify_poses`, the graph is a template (topology, names,
    actuated flags) and ``screws`` holds every joint's screws over the batch; the wrenches come from
    the one analysis core (:func:`~screwkit.core.wrench_systems.analyze_table`), so they are those of the
    single-pose path. Where a limb has no actuation wrench (transmission ``≤ rtol``) its row is the
    passive wrench acting most on the basis, with ``B_jj = 0``. Row scaling, signs, closeness
    measures and types as in the module docstring.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph of the mechanism (any pose).
    screws : mapping of joint name to array_like, shape (..., dof_j, 6)
        E.g. :meth:`JointTable.joint_screws <screwkit.graphs.jointtable.JointTable.joint_screws>` of every
        joint of
        :meth:`screwkit.robots.mechanism.Mechanism.joints`.
    twist_basis : array_like, shape (..., dof, 6)
        Broadcast against the batch shape (e.g. :func:`schoenflies_basis` of the poses).
    dof : int, optional
        Nominal mobility; default the graph's ``dof``, else the number of actuated joints.
    rtol : float, default 1e-9
        Rank tolerance of the loop-closure equations and of the type decisions.
    basis_rtol : float, default 1e-6
        Membership check of the basis, as in :func:`jacobians_from_wrenches`.

    Returns
    -------
    Jacobians
        Over the batch.

    Raises
    ------
    ScrewkitValueError
        If the screws do not match the graph, or the basis has the wrong shape, dependent rows or
        a row outside the platform's twist system.
    TwistGraphError
        If ``dof`` is invalid or an actuated joint is not in series in its limb.

    Examples
    --------
    The slider-crank of :func:`jacobians_from_wrenches` at three crank angles at once:

    >>> from screwkit.graphs.joints import prismatic, revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.algebra.screw import revolute_twist
    >>> theta = np.array([0.0, np.pi / 2, np.pi])
    >>> pins = np.stack([np.cos(theta), np.sin(theta), 0 * theta], axis=-1)
    >>> sliders = np.stack([pins[:, 0] + np.sqrt(4 - pins[:, 1] ** 2), 0 * theta, 0 * theta], axis=-1)
    >>> G = twist_graph("ground", "slider", [
    ...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("crank", "coupler", revolute("R1", [0, 0, 1], pins[1])),
    ...     ("coupler", "slider", revolute("R2", [0, 0, 1], sliders[1])),
    ...     ("ground", "slider", prismatic("P", [1, 0, 0]))], dof=1)
    >>> z = [0.0, 0.0, 1.0]
    >>> screws = {"A": np.tile(revolute_twist(z, [0, 0, 0]), (3, 1, 1)),
    ...           "R1": revolute_twist(z, pins)[:, None], "R2": revolute_twist(z, sliders)[:, None],
    ...           "P": np.tile([0, 0, 0, 1.0, 0, 0], (3, 1, 1))}
    >>> result = jacobians_over_poses(G, screws, [[0, 0, 0, 1, 0, 0]])
    >>> result.types
    array(['inverse', 'regular', 'inverse'], dtype='<U8')
    >>> result.B[:, 0, 0] / result.A[:, 0, 0]  # dx/dθ = -sin θ (1 + cos θ / sqrt(4 - sin² θ))
    array([ 0., -1.,  0.])
    """
    tolerance = checked_rtol(rtol, "rtol")
    analysis = classify_poses(graph, screws, dof=dof, rtol=tolerance).analysis
    return jacobians_from_wrenches(analysis, twist_basis, basis_rtol=basis_rtol)
