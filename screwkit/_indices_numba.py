"""numba kernel of :func:`screwkit.indices.transmission` (private; imported on the first call).

One fused loop over a flat batch of poses does, pose by pose, paper 004's inverse kinematics (Eq. 3,
closed form of :func:`screwkit.families.four_limb.inverse_kinematics`) and the indices ``κ``, ``ζ``
(Eq. 15) of :func:`screwkit.indices.transmission_indices`, without building a configuration and
without trigonometric calls per limb: with ``cos ψ = P/ρ``, ``sin ψ = Q/ρ``, ``cos δ = K/ρ`` and
``ρ sin δ = √(ρ² - K²)`` the root ``θ = ψ - m δ`` of the working mode ``m`` has
``cos θ = (P K + m Q √(ρ² - K²)) / ρ²`` and ``sin θ = (Q K - m P √(ρ² - K²)) / ρ²``: one square
root and one division per limb. The numpy path
(the configuration, then :func:`screwkit.indices.transmission_indices`) is the reference; the tests
check that the two agree to round-off. ``cache=True`` stores the compiled code beside this file;
``error_model="numpy"`` drops Python's division checks (every division is by a checked non-zero
length) and ``fastmath`` lets the compiler reorder the few dozen flops per limb (round-off only:
the inputs are finite, checked by the caller).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .families._two_limb import REACH_ULPS

Array = np.ndarray
EPS = float(np.finfo(float).eps)


@njit(cache=True, error_model="numpy", fastmath=True)
def _cross_into(a0: float, a1: float, a2: float, b0: float, b1: float, b2: float, out: Array) -> None:
    out[0] = a1 * b2 - a2 * b1
    out[1] = a2 * b0 - a0 * b2
    out[2] = a0 * b1 - a1 * b0


@njit(cache=True, error_model="numpy", fastmath=True)
def transmission(  # pragma: no cover - compiled
    poses: Array,
    base: Array,
    platform: Array,
    mode: Array,
    kind: int,
    lengths: Array,
    pairs: Array,
) -> tuple[Array, Array, Array]:
    """``poses (n, 4)`` → ``κ (n,)``, ``ζ (n,)``, reachable ``(n,)`` (unreachable: κ = ζ = 0).

    ``base (4, 4, 3)``: per limb ``a_i``, ``F_i j``, ``F_i k``, spare; ``platform (4, 4, 3)``: per
    limb the constant part of ``c_i`` (screw pair: ``r R_z(γ_i) i``; articulated: ``τ_i c j``) in
    slot 0, ``σ_i`` (articulated) or ``mod(i, 2)`` (screw pair) in ``platform[i, 1, 0]``; ``mode``:
    the signs ``m_i``; ``kind``: 0 articulated_z, 1 articulated_y, 2 screw_pair; ``lengths``:
    ``b, l, r, h/(2π)``; ``pairs (2, 2)``: the limbs of sub-platforms I and II.
    """
    n = poses.shape[0]
    kappa = np.zeros(n)
    zeta = np.zeros(n)
    ok = np.zeros(n, dtype=np.bool_)
    arm, rod, radius, rise = lengths[0], lengths[1], lengths[2], lengths[3]
    half_inverse_arm, inverse_rod, lengths_term = 0.5 / arm, 1.0 / rod, arm * arm - rod * rod
    w = np.empty((4, 3))
    first = np.empty(3)
    second = np.empty(3)
    normal = np.empty(3)
    for p in range(n):
        x, y, z, phi = poses[p, 0], poses[p, 1], poses[p, 2], poses[p, 3]
        cphi, sphi = math.cos(phi), math.sin(phi)
        if kind == 0:  # R_z(φ) i and s = R_z(φ) j
            bar0, bar1, bar2 = cphi, sphi, 0.0
            s0, s1, s2 = -sphi, cphi, 0.0
        elif kind == 1:  # R_y(φ) i and s = -R_y(φ) k (four_limb item 3)
            bar0, bar1, bar2 = cphi, 0.0, -sphi
            s0, s1, s2 = -sphi, 0.0, -cphi
        else:
            bar0, bar1, bar2 = 0.0, 0.0, 0.0
            s0, s1, s2 = 0.0, 0.0, 1.0
        reach = True
        smallest = 1.0
        for i in range(4):
            factor = platform[i, 1, 0]
            if kind == 2:
                d0 = platform[i, 0, 0] + x - base[i, 0, 0]
                d1 = platform[i, 0, 1] + y - base[i, 0, 1]
                d2 = platform[i, 0, 2] + z + factor * rise * phi - base[i, 0, 2]
            else:
                d0 = factor * radius * bar0 + platform[i, 0, 0] + x - base[i, 0, 0]
                d1 = factor * radius * bar1 + platform[i, 0, 1] + y - base[i, 0, 1]
                d2 = factor * radius * bar2 + platform[i, 0, 2] + z - base[i, 0, 2]
            big_p = d0 * base[i, 1, 0] + d1 * base[i, 1, 1] + d2 * base[i, 1, 2]  # d_i·F_i j
            big_q = d0 * base[i, 2, 0] + d1 * base[i, 2, 1] + d2 * base[i, 2, 2]  # d_i·F_i k
            big_k = (d0 * d0 + d1 * d1 + d2 * d2 + lengths_term) * half_inverse_arm
            rho_squared = big_p * big_p + big_q * big_q
            slack = rho_squared - big_k * big_k  # ρ² sin² δ
            if not rho_squared > 0.0:
                reach = False
                break
            if slack < 1e-12 * rho_squared:  # near the reach: at_reach's rule (families._two_limb)
                gap = math.sqrt(rho_squared) - abs(big_k)  # ρ (1 - |cos δ|)
                if abs(gap) <= REACH_ULPS * EPS * abs(big_k * arm + rod * rod) / arm:
                    slack = 0.0  # at its reach (stretched or folded), not out of it
                elif gap < 0.0:
                    reach = False
                    break
            root = mode[i] * math.sqrt(slack)  # m ρ sin δ
            inverse = 1.0 / rho_squared
            cos_t = (big_p * big_k + big_q * root) * inverse  # cos(ψ - m δ)
            sin_t = (big_q * big_k - big_p * root) * inverse  # sin(ψ - m δ)
            j0, j1, j2 = base[i, 1, 0], base[i, 1, 1], base[i, 1, 2]
            k0, k1, k2 = base[i, 2, 0], base[i, 2, 1], base[i, 2, 2]
            w0 = (d0 - arm * (cos_t * j0 + sin_t * k0)) * inverse_rod  # (c_i - b_i)/l, v_i (Eq. 2)
            w1 = (d1 - arm * (cos_t * j1 + sin_t * k1)) * inverse_rod
            w2 = (d2 - arm * (cos_t * j2 + sin_t * k2)) * inverse_rod
            w[i, 0], w[i, 1], w[i, 2] = w0, w1, w2
            h_sum = (  # w_i·(u_i × v_i), u_i × v_i = F_i R_x(θ) k
                w0 * (cos_t * k0 - sin_t * j0)
                + w1 * (cos_t * k1 - sin_t * j1)
                + w2 * (cos_t * k2 - sin_t * j2)
            )
            smallest = min(smallest, abs(h_sum))  # |cos μ_i| = |w_i·(u_i × v_i)| (Eq. 11)
        if not reach:
            continue
        ok[p] = True
        kappa[p] = smallest
        i1, i2, j1, j2 = pairs[0, 0], pairs[0, 1], pairs[1, 0], pairs[1, 1]
        _cross_into(w[i1, 0], w[i1, 1], w[i1, 2], w[i2, 0], w[i2, 1], w[i2, 2], first)
        _cross_into(w[j1, 0], w[j1, 1], w[j1, 2], w[j2, 0], w[j2, 1], w[j2, 2], second)
        _cross_into(first[0], first[1], first[2], second[0], second[1], second[2], normal)
        length = math.sqrt(normal[0] ** 2 + normal[1] ** 2 + normal[2] ** 2)
        if length > 0.0:  # Eq. (13) as an acute angle; 0 where w_I × w_II = 0 (|A| = 0)
            zeta[p] = min(1.0, abs(normal[0] * s0 + normal[1] * s1 + normal[2] * s2) / length)
    return kappa, zeta, ok
