"""The four-limb family's inverse and forward kinematics (Eq. 3 of paper 004), vectorised.

:func:`inverse_kinematics` is the closed form of one working mode (the signs of ``h_i``, checked by
:func:`checked_working_mode`), :func:`reachable` the vectorised reach test, and
:func:`forward_kinematics` Newton's method from the actuated angles.

Examples
--------
>>> from screwkit.robots.families.four_limb.parameters import FourLimbParameters
>>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375.0,
...     rod_length=800.0, alpha=0.0, beta=np.pi / 2, platform_radius=80.0, platform_offset=70.0,
...     base_radius=275.0)
>>> config = inverse_kinematics(h4, [0.0, 0.0, -700.0, 0.3])
>>> config.theta.shape, config.subplatform_limbs
((4,), ((0, 3), (1, 2)))
>>> bool(np.all(config.h < 0))
True
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from ....algebra.backend import as_array
from ....exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from ...two_limb import at_reach, within_reach
from .configuration import (
    _K,
    BaseFrames,
    FourLimbConfiguration,
    _assemble,
    _Platform,
    _platform,
    _require,
    base_frames,
)
from .parameters import FourLimbParameters, is_real

__all__ = [
    "ForwardKinematicsError",
    "checked_working_mode",
    "forward_kinematics",
    "inverse_kinematics",
    "reachable",
]


_DEFAULT_WORKING_MODE = (-1, -1, -1, -1)


class ForwardKinematicsError(ScrewkitValueError):
    """Newton's method did not reach an assembly of the requested working mode.

    Defined here because :mod:`screwkit.exceptions` has no convergence error (yet).
    """


def checked_working_mode(working_mode: Any) -> tuple[int, int, int, int]:
    """A working mode checked: four signs ``+1`` or ``-1``, one per limb, of ``h_i`` (Eq. 8).

    Parameters
    ----------
    working_mode : sequence of int
        The signs of ``h_1 .. h_4`` (a sequence or an array of 4 values in ``{-1, 1}``).

    Returns
    -------
    tuple of int
        The four signs as Python ints.

    Raises
    ------
    ScrewkitTypeError
        If ``working_mode`` is not a sequence (a string is not).
    ScrewkitValueError
        If it does not hold exactly four signs.

    Examples
    --------
    >>> checked_working_mode(np.array([-1, 1, -1, 1]))
    (-1, 1, -1, 1)
    >>> checked_working_mode((1, 0, 1, 1))
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `working_mode` to be 4 signs ... got (1, 0, 1, 1).
    """
    if isinstance(working_mode, str | bytes) or not isinstance(working_mode, Sequence | np.ndarray):
        raise ScrewkitTypeError(
            f"Expected `working_mode` to be a sequence of 4 signs (+1 or -1) of h_i (paper 004, "
            f"Eq. 8), got {type(working_mode).__name__} {working_mode!r}."
        )
    values = list(np.asarray(working_mode, dtype=object).ravel()) if isinstance(
        working_mode, np.ndarray
    ) else list(working_mode)
    if len(values) != 4 or not all(is_real(x) and x in (-1, 1) for x in values):
        raise ScrewkitValueError(
            "Expected `working_mode` to be 4 signs (+1 or -1) of h_i (paper 004, Eq. 8), got "
            f"{tuple(values)!r}."
        )
    return (int(values[0]), int(values[1]), int(values[2]), int(values[3]))


def _describe_failures(mask: np.ndarray, batch: tuple[int, ...], what: str) -> str:
    """'pose index (3,): limbs 1, 2; ...' for the first few failing entries (mask (..., 4))."""
    entries = np.argwhere(mask.any(axis=-1)) if batch else np.zeros((1, 0), dtype=int)
    parts = []
    for index in entries[:5]:
        limbs = ", ".join(str(i + 1) for i in np.flatnonzero(mask[tuple(index)]))
        where = f"{what} index {tuple(int(i) for i in index)}: " if batch else ""
        parts.append(f"{where}limb(s) {limbs}")
    more = f" (and {len(entries) - 5} more)" if len(entries) > 5 else ""
    return "; ".join(parts) + more


def inverse_kinematics(
    params: FourLimbParameters,
    pose: Any,
    *,
    working_mode: Sequence[int] = _DEFAULT_WORKING_MODE,
) -> FourLimbConfiguration:
    """Closed-form inverse kinematics of Eq. (3) (paper 004), vectorised over the pose batch.

    With ``d_i = c_i - a_i``, Eq. (3) reads ``P_i cos θ_i + Q_i sin θ_i = K_i`` where
    ``P_i = d_i·F_i j``, ``Q_i = d_i·F_i k`` (``F_i = R_z(α_i)`` for horizontal axes, item 6) and
    ``K_i = (|d_i|² + b² - l²)/(2b)``. With
    ``ρ_i = hypot(P_i, Q_i)``, ``ψ_i = atan2(Q_i, P_i)`` and ``δ_i = cos⁻¹(K_i/ρ_i)``, the two roots
    are ``θ_i = ψ_i ∓ δ_i``, and ``h_i = (b ρ_i / l) sin(ψ_i - θ_i)`` (Eq. 8), so
    ``θ_i = ψ_i - m_i δ_i`` is the root with ``sgn(h_i) = m_i``.

    Parameters
    ----------
    params : FourLimbParameters
    pose : array_like, shape (..., 4)
        ``(x, y, z, φ)`` in ``params.length_unit`` and radians.
    working_mode : sequence of 4 int
        Sign (+1 or -1) of each ``h_i``; the paper's choice ``(-1, -1, -1, -1)`` by default.

    Returns
    -------
    FourLimbConfiguration

    Raises
    ------
    UnreachablePoseError
        If ``|K_i| > ρ_i`` for some limb (it cannot reach ``C_i``); names the limbs (paper numbering)
        and, for a batch, the pose indices.
    ScrewkitValueError, ScrewkitTypeError
        For a malformed pose or working mode.

    Examples
    --------
    >>> quattro = FourLimbParameters(name="Quattro", platform_kind="articulated_z",
    ...     arm_length=375, rod_length=800, alpha=-np.pi / 4, beta=3 * np.pi / 4,
    ...     platform_radius=80, platform_offset=70, base_radius=275)
    >>> cfg = inverse_kinematics(quattro, [0, 0, -700, 0])
    >>> np.allclose(np.linalg.norm(cfg.c - cfg.b, axis=-1), 800)
    True
    >>> inverse_kinematics(quattro, [0, 0, -2000, 0])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.UnreachablePoseError: Pose (x, y, z, phi) = (0, 0, -2000, 0 rad = 0 deg) is out ...
    """
    _require(params, FourLimbParameters, "params")
    mode = checked_working_mode(working_mode)
    chi = as_array(pose, "pose", (4,), symbolic=False)
    terms = _ik_terms(params, chi)
    unreachable = ~terms.reachable
    if unreachable.any():
        batch = chi.shape[:-1]
        detail = _describe_failures(unreachable, batch, "pose")
        head = (
            f"{int(unreachable.any(axis=-1).sum())} of {int(np.prod(batch))} poses are"
            if batch
            else "Pose (x, y, z, phi) = ({:g}, {:g}, {:g}, {:g} rad = {:g} deg) is".format(
                *chi.tolist(), math.degrees(float(chi[-1]))
            )
        )
        raise UnreachablePoseError(
            f"{head} out of reach of {params.name} (paper 004 limb numbering; Eq. 3 has no real "
            f"root, |K_i| > hypot(P_i, Q_i)): {detail}."
        )
    psi = np.arctan2(terms.q, terms.p)
    delta = np.arccos(at_reach(terms.k / terms.rho, terms.condition))
    theta = _wrap(psi - np.array(mode, dtype=float) * delta)
    return _assemble(params, chi, theta, mode, terms.platform, terms.base)


class _IKTerms(NamedTuple):
    platform: _Platform
    base: BaseFrames
    p: np.ndarray  # P_i = d_i·F_i j
    q: np.ndarray  # Q_i = d_i·F_i k
    k: np.ndarray  # K_i = (|d_i|² + b² - l²) / (2b)
    rho: np.ndarray  # hypot(P_i, Q_i)
    condition: np.ndarray  # relative size of the rounding error of K_i / ρ_i (at_reach)
    reachable: np.ndarray  # (..., 4) bool


def _ik_terms(params: FourLimbParameters, chi: np.ndarray) -> _IKTerms:
    """Coefficients of ``P_i cos θ_i + Q_i sin θ_i = K_i``, Eq. (3) rewritten (paper 004)."""
    platform = _platform(params, chi)
    base = base_frames(params)
    d = platform.c - base.a
    big_p = np.sum(d * base.j_rot, axis=-1)
    big_q = np.sum(d * base.k_rot, axis=-1)
    big_k = (np.sum(d * d, axis=-1) + params.arm_length**2 - params.rod_length**2) / (
        2.0 * params.arm_length
    )
    rho = np.hypot(big_p, big_q)
    with np.errstate(divide="ignore", invalid="ignore"):
        cosine = big_k / rho
        condition = (big_k * params.arm_length + params.rod_length**2) / (params.arm_length * rho)
    # a limb stretched or folded exactly to its reach may round to |K_i| a few ulps above ρ_i: at its
    # reach (arccos of ±1, a serial singularity), not out of reach (README, "Tolerance policy")
    reachable = (rho > 0.0) & within_reach(np.where(rho > 0.0, cosine, np.inf), condition)
    return _IKTerms(platform, base, big_p, big_q, big_k, rho, condition, reachable)


def reachable(params: FourLimbParameters, pose: Any) -> np.ndarray:
    """Which poses every limb can reach (Eq. 3 has real roots for all four limbs).

    Parameters
    ----------
    params : FourLimbParameters
    pose : array_like, shape (..., 4)

    Returns
    -------
    (...,) ndarray of bool
        True where :func:`inverse_kinematics` succeeds (in every working mode).

    Examples
    --------
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> reachable(h4, [[0, 0, -700, 0], [0, 0, -2000, 0]])
    array([ True, False])
    """
    _require(params, FourLimbParameters, "params")
    chi = as_array(pose, "pose", (4,), symbolic=False)
    return np.all(_ik_terms(params, chi).reachable, axis=-1)


def _wrap(angle: np.ndarray) -> np.ndarray:
    """Angles in ``[-π, π)``."""
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def forward_kinematics(
    params: FourLimbParameters,
    theta: Any,
    *,
    working_mode: Sequence[int] = _DEFAULT_WORKING_MODE,
    initial_pose: Any = None,
    rtol: float = 1e-12,
    max_iterations: int = 50,
) -> FourLimbConfiguration:
    """Numerical forward kinematics: Newton's method on Eq. (3) (paper 004), vectorised.

    The residuals ``F_i = |c_i(χ) - b_i(θ_i)|² - l²`` have the Jacobian ``∂F/∂χ = 2 l A`` (Eqs. 6-8),
    so each step solves ``2 l A Δχ = -F`` (pseudo-inverse, so a singular ``A`` does not abort the
    whole batch), halving the step until ``|F|`` decreases.

    Parameters
    ----------
    params : FourLimbParameters
    theta : array_like, shape (..., 4)
        Actuated angles ``θ_i`` in radians.
    working_mode : sequence of 4 int
        Signs of ``h_i`` the assembly must have (default: the paper's ``h_i < 0``).
    initial_pose : array_like, shape (..., 4), optional
        Starting pose, broadcast against the batch. By default the pose whose four parallelograms
        hang straight down (``w_i = -k`` on average) with ``φ = 0``.
    rtol : float
        Convergence when ``max_i |F_i| / l² <= rtol`` (default 1e-12, i.e. rod lengths right to
        about ``rtol·l/2``).
    max_iterations : int
        Newton iterations before giving up (default 50).

    Returns
    -------
    FourLimbConfiguration
        With ``φ`` wrapped to ``[-π, π)`` for articulated platforms (the screw-pair platform is not
        periodic in ``φ``).

    Raises
    ------
    ForwardKinematicsError
        Naming the batch entries that did not converge or converged to another working mode.

    Examples
    --------
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> pose = np.array([50.0, -20.0, -750.0, 0.4])
    >>> fk = forward_kinematics(h4, inverse_kinematics(h4, pose).theta)
    >>> np.allclose(fk.pose, pose)
    True
    """
    _require(params, FourLimbParameters, "params")
    mode = checked_working_mode(working_mode)
    if not (isinstance(rtol, float | int) and rtol > 0):
        raise ScrewkitValueError(f"Expected `rtol` to be a positive number, got {rtol!r}.")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ScrewkitValueError(
            f"Expected `max_iterations` to be a positive integer, got {max_iterations!r}."
        )
    th = as_array(theta, "theta", (4,), symbolic=False)
    batch = th.shape[:-1]
    base = base_frames(params)
    a, _, j_rot, k_rot = base
    elbows = a + params.arm_length * (
        np.cos(th)[..., None] * j_rot + np.sin(th)[..., None] * k_rot
    )
    if initial_pose is None:
        offsets = _platform(params, np.zeros(4)).c
        start = np.mean(elbows - offsets, axis=-2) - params.rod_length * _K
        chi = np.concatenate([start, np.zeros((*batch, 1))], axis=-1)
    else:
        guess = as_array(initial_pose, "initial_pose", (4,), symbolic=False)
        try:
            chi = np.broadcast_to(guess, (*batch, 4)).copy()
        except ValueError as err:
            raise ScrewkitValueError(
                f"Expected `initial_pose` to broadcast to the batch shape {(*batch, 4)} of "
                f"`theta`, got {guess.shape}."
            ) from err
    scale = params.rod_length**2

    def residual(pose: np.ndarray) -> tuple[np.ndarray, np.ndarray, _Platform]:
        plat = _platform(params, pose)
        d = plat.c - elbows
        return np.sum(d * d, axis=-1) - scale, d, plat

    f, d, plat = residual(chi)
    for _ in range(max_iterations):
        active = np.max(np.abs(f), axis=-1) / scale > rtol
        if not active.any():
            break
        jac = 2.0 * np.concatenate([d, np.sum(d * plat.dc_dphi, axis=-1)[..., None]], axis=-1)
        step = np.where(active[..., None], (np.linalg.pinv(jac) @ f[..., None])[..., 0], 0.0)
        size = np.sum(f * f, axis=-1)
        pending = active.copy()
        fraction = np.ones(batch)
        for _ in range(30):
            trial = chi - fraction[..., None] * step
            f_trial, d_trial, plat_trial = residual(trial)
            better = pending & (np.sum(f_trial * f_trial, axis=-1) < size)
            chi = np.where(better[..., None], trial, chi)
            f = np.where(better[..., None], f_trial, f)
            d = np.where(better[..., None, None], d_trial, d)
            plat = _Platform(*(np.where(_expand(better, new), new, old)
                               for new, old in zip(plat_trial, plat, strict=True)))
            pending &= ~better
            if not pending.any():
                break
            fraction = np.where(pending, 0.5 * fraction, fraction)
    failed = np.max(np.abs(f), axis=-1) / scale > rtol
    if params.platform_kind != "screw_pair":
        chi[..., 3] = _wrap(chi[..., 3])
    config = _assemble(params, chi, _wrap(th), mode, _platform(params, chi), base)
    wrong_mode = ~failed & np.any(np.sign(config.h) != np.array(mode), axis=-1)
    if failed.any() or wrong_mode.any():
        problems = [
            f"{int(mask.sum())} {what}" + (f" (batch indices {_first_indices(mask)})" if batch else "")
            for mask, what in (
                (failed, "did not converge"),
                (wrong_mode, f"converged to an assembly outside working mode {mode}"),
            )
            if mask.any()
        ]
        subject = f"theta={th.tolist()}" if not batch else f"a batch of shape {batch}"
        raise ForwardKinematicsError(
            f"Forward kinematics of {params.name} failed for {subject} (Newton on Eq. 3, "
            f"{max_iterations} iterations, rtol={rtol}): {'; '.join(problems)}. Try an "
            "`initial_pose` near the expected assembly."
        )
    return config


def _first_indices(mask: np.ndarray, count: int = 5) -> str:
    indices = [tuple(int(i) for i in index) for index in np.argwhere(mask)[:count]]
    more = f" and {int(mask.sum()) - count} more" if mask.sum() > count else ""
    return ", ".join(str(i) for i in indices) + more


def _expand(mask: np.ndarray, like: np.ndarray) -> np.ndarray:
    """Reshape a batch mask to broadcast against an array with trailing axes."""
    return mask.reshape(mask.shape + (1,) * (like.ndim - mask.ndim))
