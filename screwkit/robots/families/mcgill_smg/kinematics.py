"""The McGill SMG's inverse kinematics (closed form, every working mode) and forward kinematics
(every assembly, by an eliminant and Newton polishing), vectorised over poses.

Examples
--------
>>> from screwkit.robots.families.mcgill_smg.parameters import McGillParameters
>>> smg = McGillParameters(l0=600.0, l1=100.0, l2=600.0, l3=200.0 * np.sqrt(2), radius=200.0,
...     b4=-50.0, b5=-50.0, proximal_width=80.0, distal_width=60.0)
>>> config = inverse_kinematics(smg, [[0.0, 0.0, -600.0, 0.0]])
>>> config.joint_angles[0, :, 0]  # pan angles: O_I3 and O_II3 lie on the y axis
array([0., 0.])
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ....algebra.backend import as_array
from ....exceptions import DegenerateGeometryError, UnreachablePoseError
from ...two_limb import (
    ForwardSolutions,
    at_reach,
    checked_mode,
    describe_indices,
    wrap_angle,
)
from .configuration import _K, _SIGN, McGillConfiguration, _chain, _configuration, _e, _pan_points
from .parameters import DEFAULT_MODE, LEGS, McGillParameters

__all__ = ["forward_kinematics", "inverse_kinematics"]


#: Relative slack on the reach of a leg (|cos θ_J3| <= 1 + slack): poses built on the boundary
#: (a fully extended leg) must not be refused for a rounding error.
_REACH_SLACK = 1e-12


# --------------------------------------------------------------------------------------------------
# Inverse and forward kinematics
# --------------------------------------------------------------------------------------------------


def inverse_kinematics(
    params: McGillParameters, pose: Any, mode: Any = DEFAULT_MODE
) -> McGillConfiguration:
    """Joint angles of both legs for poses ``(x, y, z, φ)``: Eqs. (1)-(2) solved per leg.

    For leg ``J``: ``O_J3 = P - s(J) R e(φ) - (b4 + b5) k``; the pan angle makes ``O_J3 - O_J0`` lie
    along ``pan_J e(θ_J1)`` (so ``κ_J = pan_J |O_J3 - O_J0|_horizontal``); the tilt and distal
    angles solve the planar two-link problem ``(κ_J - s(J) l1, z - b4 - b5) = l2 (cos θ_J2,
    sin θ_J2) + l3 (cos θ_J23, sin θ_J23)`` with ``sgn sin θ_J3 = elbow_J``; ``θ_J4 = φ - θ_J1``.
    On the pan axis (``κ_J = 0``, a serial singularity) the pan angle is indeterminate: the value
    returned (``atan2`` of signed zeros) is one of infinitely many solutions.

    Parameters
    ----------
    params : McGillParameters
    pose : (..., 4) array_like
        ``(x, y, z, φ)``; lengths in the unit of ``params``, ``φ`` in radians.
    mode : tuple of 4 int, default :data:`DEFAULT_MODE`
        ``(pan_I, elbow_I, pan_II, elbow_II)``, each +1 or -1.

    Returns
    -------
    McGillConfiguration

    Raises
    ------
    UnreachablePoseError
        A leg cannot reach its wrist point ``O_J3`` (the message names the leg and the poses).
    ScrewkitValueError
        Malformed ``pose`` or ``mode``.

    Examples
    --------
    >>> from screwkit.robots.families.mcgill_smg.configuration import leg_pose
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> config = inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0], mode=(1, 1, -1, -1))
    >>> bool(np.allclose(leg_pose(p, "II", config.joint_angles[1]), config.pose))
    True
    >>> inverse_kinematics(p, [0.0, 0.0, -1400.0, 0.0])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.UnreachablePoseError: Leg I cannot reach the pose: ...
    """
    pose = as_array(pose, "pose", (4,))
    signs = np.array(checked_mode(mode, "mode", 4), dtype=float)
    pan, elbow = signs[0::2], signs[1::2]
    x, y, z, phi = np.moveaxis(pose, -1, 0)
    centre = np.stack([x, y, np.zeros_like(x)], axis=-1)[..., None, :]
    target = centre - (_SIGN * params.radius)[:, None] * _e(phi)[..., None, :]
    offset = target - _pan_points(params)
    kappa = pan * np.hypot(offset[..., 0], offset[..., 1])
    theta1 = np.arctan2(-pan * offset[..., 0], pan * offset[..., 1])
    u = kappa - _SIGN * params.l1
    w = np.broadcast_to((z - params.b4 - params.b5)[..., None], u.shape)
    l2, l3 = params.l2, params.l3
    cos3 = (u**2 + w**2 - l2**2 - l3**2) / (2.0 * l2 * l3)
    for index, leg in enumerate(LEGS):
        bad = np.abs(cos3[..., index]) > 1.0 + _REACH_SLACK
        if np.any(bad):
            distance = np.hypot(u[..., index], w[..., index])[bad]
            raise UnreachablePoseError(
                f"Leg {leg} cannot reach the pose: at {describe_indices(bad)} the distance from "
                f"O_{leg}1 to O_{leg}3 is {distance[:3].round(6).tolist()}, expected within "
                f"[|l2 - l3|, l2 + l3] = [{abs(l2 - l3):.6g}, {l2 + l3:.6g}]."
            )
    cos3 = at_reach(cos3, (u**2 + w**2 + l2**2 + l3**2) / (2.0 * l2 * l3))  # a stretched leg exactly
    sin3 = elbow * np.sqrt(1.0 - cos3**2)
    theta3 = np.arctan2(sin3, cos3)
    theta2 = np.arctan2(w, u) - np.arctan2(l3 * sin3, l2 + l3 * cos3)
    theta4 = phi[..., None] - theta1
    angles = wrap_angle(np.stack([theta1, theta2, theta3, theta4], axis=-1))
    return _configuration(params, tuple(int(s) for s in signs), pose, angles)


@functools.cache
def _tan_half_basis() -> np.ndarray:
    """``T[k + 4, j]``: coefficient of ``t^j`` in ``(1 + i t)^(4 + k) (1 - i t)^(4 - k)`` (built on
    first use: importing ``numpy.polynomial`` is not a cost of loading the catalog's families)."""
    basis = np.zeros((9, 9), dtype=complex)
    for k in range(-4, 5):
        product = np.polynomial.polynomial.polymul(
            np.polynomial.polynomial.polypow([1.0, 1.0j], 4 + k),
            np.polynomial.polynomial.polypow([1.0, -1.0j], 4 - k),
        )
        basis[k + 4, : product.size] = product
    return basis


_SAMPLES = 16  # > 2 * 4: exact Fourier coefficients of a degree-4 trigonometric polynomial
#: Candidates closer than this (sum of angle differences, rad) are one assembly.
_SAME_ASSEMBLY = 1e-6
_NEWTON_STEPS = 12
_MAX_ASSEMBLIES = 8  # Bézout bound of the system in (cos, sin) of both distal angles


def _wrists(elbow: np.ndarray, h: np.ndarray, l3: float, psi: np.ndarray) -> np.ndarray:
    """``O_J3`` for distal angles ``ψ_J`` of shape (..., m, 2): shape (..., m, 2, 3)."""
    radial = np.cos(psi)[..., None] * h[..., None, :, :] + np.sin(psi)[..., None] * _K
    return np.asarray(elbow[..., None, :, :] + l3 * radial)


def _eliminant_roots(
    elbow: np.ndarray, h: np.ndarray, l3: float, radius: float
) -> tuple[np.ndarray, np.ndarray]:
    """Roots ``ψ_I`` (..., 8) of the eliminant ``F`` and a mask of the real ones."""
    gap = elbow[..., 0, :] - elbow[..., 1, :]
    horizontal = gap * np.array([1.0, 1.0, 0.0])
    shift = gap[..., 2:3] / l3  # sin ψ_II = sin ψ_I + shift
    grid = 2.0 * np.pi * np.arange(_SAMPLES) / _SAMPLES
    chord = horizontal[..., None, :] + l3 * np.cos(grid)[:, None] * h[..., None, 0, :]
    sin_two = np.sin(grid) + shift
    m = np.sum(chord**2, axis=-1) + l3**2 * (1.0 - sin_two**2) - 4.0 * radius**2
    n = 2.0 * l3 * np.sum(chord * h[..., None, 1, :], axis=-1)
    samples = m**2 - (1.0 - sin_two**2) * n**2  # F(ψ_I) on the grid, (..., 16)
    scale = (np.sum(horizontal**2, axis=-1) + 2.0 * l3**2 + 4.0 * radius**2) ** 2
    degenerate = np.abs(samples).max(axis=-1) <= 1e-12 * scale
    if np.any(degenerate):
        raise DegenerateGeometryError(
            f"The actuated angles at {describe_indices(degenerate)} admit a continuum of "
            "assemblies (the eliminant F(ψ_I) vanishes identically): expected isolated assemblies."
        )
    coefficients = np.fft.fft(samples, axis=-1)[..., np.arange(-4, 5) % _SAMPLES] / _SAMPLES
    psi0 = grid[np.argmax(np.abs(samples), axis=-1)] - np.pi
    shifted = coefficients * np.exp(1j * np.arange(-4, 5) * psi0[..., None])
    poly = np.real(shifted @ _tan_half_basis())  # ascending powers of t, leading term F(ψ0 + π) != 0
    companion = np.zeros((*poly.shape[:-1], 8, 8))
    companion[..., 0, :] = -poly[..., 7::-1] / poly[..., 8:9]
    companion[..., np.arange(1, 8), np.arange(7)] = 1.0
    roots = np.linalg.eigvals(companion)
    real = np.abs(roots.imag) <= 1e-6 * (1.0 + np.abs(roots))
    return psi0[..., None] + 2.0 * np.arctan(roots.real), real


def _polish(
    elbow: np.ndarray, h: np.ndarray, l3: float, radius: float, psi: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on the unsquared equations; returns ``ψ`` and the relative residual."""
    for _ in range(_NEWTON_STEPS):
        bar = np.diff(_wrists(elbow, h, l3, psi), axis=-2)[..., 0, :]  # O_II3 - O_I3
        e_height, e_length = bar[..., 2], bar[..., 0] ** 2 + bar[..., 1] ** 2 - 4.0 * radius**2
        along = np.sum(bar[..., None, :] * h[..., None, :, :], axis=-1)  # (..., m, 2)
        slope = l3 * np.sin(psi) * along  # ∂|bar|²/∂ψ_J = 2 s(J) l3 sin ψ_J (bar · h_J)
        j11, j12 = -l3 * np.cos(psi[..., 0]), l3 * np.cos(psi[..., 1])
        j21, j22 = 2.0 * slope[..., 0], -2.0 * slope[..., 1]
        det = j11 * j22 - j12 * j21
        usable = np.abs(det) > 1e-14 * (l3 * radius) ** 2
        safe = np.where(usable, det, 1.0)
        step = np.stack([j22 * e_height - j12 * e_length, j11 * e_length - j21 * e_height], -1)
        psi = psi - np.where(usable[..., None], step / safe[..., None], 0.0)
    bar = np.diff(_wrists(elbow, h, l3, psi), axis=-2)[..., 0, :]
    residual = np.maximum(
        np.abs(bar[..., 2]) / l3,
        np.abs(bar[..., 0] ** 2 + bar[..., 1] ** 2 - 4.0 * radius**2) / radius**2,
    )
    return psi, residual


def _distinct(
    psi: np.ndarray, valid: np.ndarray, residual: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """One slot per assembly, best candidate kept, valid slots first, at most 8 slots."""
    rank = np.argsort(np.where(valid, residual, np.inf), axis=-1, kind="stable")
    psi = np.take_along_axis(psi, rank[..., None], axis=-2)
    valid = np.take_along_axis(valid, rank, axis=-1)
    apart = np.abs(wrap_angle(psi[..., :, None, :] - psi[..., None, :, :])).sum(axis=-1)
    earlier = np.tril(np.ones((psi.shape[-2],) * 2, dtype=bool), k=-1)
    valid = valid & ~np.any((apart < _SAME_ASSEMBLY) & earlier & valid[..., None, :], axis=-1)
    keep = np.argsort(~valid, axis=-1, kind="stable")[..., :_MAX_ASSEMBLIES]
    return np.take_along_axis(psi, keep[..., None], axis=-2), np.take_along_axis(valid, keep, -1)


def forward_kinematics(
    params: McGillParameters, actuated: Any, *, rtol: float = 1e-8
) -> ForwardSolutions:
    """All assemblies of the moving plate for given actuated angles (paper 001 gives none).

    The actuated angles fix ``O_J2`` and the leg planes; ``O_J3`` lies on the circle of radius
    ``l3`` about ``O_J2`` in the plane of leg ``J``, at angle ``ψ_J = θ_J23``. The plate needs
    equal heights, ``l3 sin ψ_II = l3 sin ψ_I + z_I2 - z_II2``, and ``|O_I3 - O_II3| = 2R``
    horizontally: ``G = M(ψ_I) - cos ψ_II N(ψ_I) = 0``. Eliminating ``cos ψ_II`` gives
    ``F(ψ_I) = M² - (1 - sin² ψ_II) N² = 0``, a trigonometric polynomial of degree 4. Its Fourier
    coefficients come from 16 samples; the substitution ``ψ_I = ψ_0 + 2 arctan t`` with ``ψ_0 + π``
    at the largest sample turns it into a degree-8 polynomial in ``t`` with a well-scaled leading
    coefficient (``F(ψ_0 + π)``), solved by companion-matrix eigenvalues (batched). Real roots
    with both signs of ``cos ψ_II`` are polished by Newton's method on the unsquared equations and
    kept if the relative residual is at most ``rtol``; hence at most 8 assemblies (Bézout).

    Parameters
    ----------
    params : McGillParameters
    actuated : (..., 4) array_like
        ``(θ_I1, θ_I2, θ_II1, θ_II2)`` in radians.
    rtol : float, default 1e-8
        Largest accepted residual, relative: ``|Δz| / l3`` and ``| |O_I3 O_II3|² - 4R² | / R²``.

    Returns
    -------
    ForwardSolutions
        ``poses (..., 8, 4)``, ``passive (..., 8, 4) = (θ_I3, θ_I4, θ_II3, θ_II4)`` and the working
        mode of each assembly; unused slots are invalid.

    Raises
    ------
    DegenerateGeometryError
        ``F`` vanishes identically (all 16 samples at most ``1e-12`` times the scale of ``F``): the
        actuated angles admit a continuum of assemblies (e.g. parallel leg planes, elbows at equal
        height, offset by ``2R`` normal to the planes).

    Notes
    -----
    Two further thresholds are numerical-method internals: a root ``t`` counts as real when
    ``|Im t| <= 1e-6 (1 + |t|)`` (Newton then polishes it), and two polished candidates closer than
    ``1e-6`` rad (sum over both distal angles) are one assembly, so two genuinely distinct
    assemblies that close are reported once (they are then next to a parallel singularity).

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> config = inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0])
    >>> solutions = forward_kinematics(p, config.actuated)
    >>> distance = np.abs(solutions.poses[solutions.valid] - config.pose).max(axis=-1)
    >>> bool(distance.min() < 1e-9)
    True
    """
    actuated = as_array(actuated, "actuated", (4,))
    theta1, theta2 = actuated[..., 0::2], actuated[..., 1::2]
    h = _e(theta1)
    _, elbow, _, _ = _chain(params, theta1, theta2, theta2)
    l3, radius = params.l3, params.radius
    psi_one, real = _eliminant_roots(elbow, h, l3, radius)
    # Both signs of cos ψ_II for every root ψ_I, then Newton's method.
    psi_one, real = np.repeat(psi_one, 2, axis=-1), np.repeat(real, 2, axis=-1)
    shift = (elbow[..., 0, 2:3] - elbow[..., 1, 2:3]) / l3
    sin_two = np.clip(np.sin(psi_one) + shift, -1.0, 1.0)
    psi_two = np.arctan2(sin_two, np.tile([1.0, -1.0], 8) * np.sqrt(1.0 - sin_two**2))
    psi, residual = _polish(elbow, h, l3, radius, np.stack([psi_one, psi_two], axis=-1))
    psi, valid = _distinct(psi, real & (residual <= rtol), residual)
    wrist = _wrists(elbow, h, l3, psi)
    direction = (wrist[..., 1, :] - wrist[..., 0, :]) / (2.0 * radius)
    phi = np.arctan2(-direction[..., 0], direction[..., 1])
    middle = 0.5 * (wrist[..., 0, :] + wrist[..., 1, :])
    poses = np.stack(
        [middle[..., 0], middle[..., 1], middle[..., 2] + params.b4 + params.b5, phi], axis=-1
    )
    t1, t2 = theta1[..., None, :], theta2[..., None, :]
    passive = wrap_angle(np.stack([psi - t2, phi[..., None] - t1], axis=-1))
    kappa = _SIGN * params.l1 + params.l2 * np.cos(t2) + l3 * np.cos(psi)
    modes = np.stack([np.sign(kappa), np.sign(np.sin(passive[..., 0]))], axis=-1)
    return ForwardSolutions(
        poses=poses,
        passive=passive.reshape(*passive.shape[:-2], 4),
        working_modes=modes.reshape(*modes.shape[:-2], 4).astype(int),
        valid=valid,
    )
