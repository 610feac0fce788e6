"""numba kernel of :func:`screwkit.papers.paper_004.transmission` (private; imported on the first call).

One loop over a flat batch of poses does, pose by pose, paper 004's inverse kinematics (Eq. 3) and the
indices ``κ``, ``ζ`` (Eq. 15), without building a configuration, without a branch and without a call
to the maths library, so that the compiler turns it into SIMD code over several poses at once
(``bench/bench_indices.py`` checks the machine code for packed instructions). The numpy path (the
family's configuration, then :func:`screwkit.papers.paper_004.transmission_indices`) is the reference; the
tests check that the two agree to round-off.

Per limb (limb ``i`` of paper 004; ``d_i = c_i - a_i``, ``F_i j``, ``F_i k`` as in
:func:`screwkit.robots.families.four_limb.kinematics.inverse_kinematics`): Eq. (3),
``|d_i - b v_i|² = l²`` with
``v_i = cos θ_i F_i j + sin θ_i F_i k`` (Eq. 2), is ``P_i cos θ_i + Q_i sin θ_i = K_i`` with
``P_i = d_i·F_i j``, ``Q_i = d_i·F_i k``, ``K_i = (‖d_i‖² + b² - l²) / (2b)``. With ``ρ_i² = P_i² + Q_i²``
and ``R_i = √(ρ_i² - K_i²)`` (= ``ρ_i sin δ_i``; real iff the limb reaches) the root of working mode
``m_i`` (the sign of ``h_i``, Eq. 8) has

* ``ρ_i² cos θ_i = P_i K_i + m_i Q_i R_i`` and ``ρ_i² sin θ_i = Q_i K_i - m_i P_i R_i``: no ``atan2``
  or ``acos``; and so ``l ρ_i² w_i = ρ_i² d_i - b (ρ_i² v_i)`` (``w_i = (c_i - b_i)/l``, Eq. 4) with no
  division: ``ζ`` below is unchanged when a ``w_i`` is scaled by a positive number;
* ``w_i·(u_i × v_i) = (d_i - b v_i)·(u_i × v_i) / l = d_i·(u_i × v_i) / l`` (``v_i ⟂ u_i × v_i``)
  ``= (Q_i cos θ_i - P_i sin θ_i) / l = m_i R_i / l``, so ``|cos μ_i| = R_i / l`` (Eq. 11) and
  ``κ = min_i R_i / l`` (Eq. 15): one square root per limb, the same one the inverse kinematics needs
  (it also gives ``h_i = b m_i R_i / l`` of Eq. 8, whose sign is ``m_i`` as the working mode says);
* ``ζ = |(w_I × w_II)·s| / ‖w_I × w_II‖`` (Eqs. 13, 15) from the four scaled ``w_i``: one more
  square root and one division per pose.

Lengths are taken in units of ``l`` (the caller divides the geometry by ``l`` once, the kernel the
position), so every product stays of order one whatever the length unit; ``κ`` and ``ζ`` are ratios.

The platform angle's cosine and sine come from fdlibm's kernels (Sun Microsystems, 1993:
``__kernel_sin``/``__kernel_cos`` of ``k_sin.c``/``k_cos.c``, degree-13 and -14 polynomials on
``[-π/4, π/4]`` with error below 2⁻⁵⁸ relative) after a Cody–Waite reduction by ``π/2`` in three
33-bit parts (fdlibm's ``e_rem_pio2.c`` constants; each product ``n·(π/2)_k`` is exact for
``|n| < 2²⁰``): written out here so that they vectorise, where ``math.cos`` is a scalar library call
(about 19 ns of the previous 65 ns per pose). Beyond ``|φ| = REDUCTION_LIMIT`` (the three parts lose
exactness) the few such poses are recomputed with ``math.cos``/``math.sin``. One thread, no ``parallel``: it
releases the GIL (``nogil``), so the Dask path's threads (:mod:`screwkit.analysis.workspace`) run chunks side
by side, and nothing in it is shared between calls. Compiled with
``error_model="numpy"`` (no Python division checks: every division is guarded by a select) and
only the ``contract`` fast-math flag (fused multiply-adds); no reassociation, which would undo the
Cody–Waite reduction and fdlibm's compensated cosine.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..robots.two_limb import REACH_ULPS

Array = np.ndarray
EPS = float(np.finfo(float).eps)

_FLAGS = {"contract"}

# The constants below and the polynomial kernels of cos_sin are taken from fdlibm, whose notice
# is preserved as its licence asks:
#   Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
#   Developed at SunSoft, a Sun Microsystems, Inc. business.
#   Permission to use, copy, modify, and distribute this software is freely granted, provided that
#   this notice is preserved.
# fdlibm e_rem_pio2.c: 2/π, and π/2 in three parts of 33 significant bits
_INVERSE_HALF_PI = 6.36619772367581382433e-01
_HALF_PI_1 = 1.57079632673412561417e00
_HALF_PI_2 = 6.07710050630396597660e-11
_HALF_PI_3 = 2.02226624871116645580e-21
#: |φ| (radians) up to which the reduction above is exact to a rounding unit (2¹⁹ π/2 ≈ 8.2e5).
REDUCTION_LIMIT = 2.0**19 * (math.pi / 2.0)
# fdlibm k_sin.c, k_cos.c
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


@njit(cache=True, error_model="numpy", fastmath=_FLAGS, inline="always")
def cos_sin(angle: float) -> tuple[float, float]:  # pragma: no cover - compiled
    """``cos φ``, ``sin φ`` for ``|φ| ≤ REDUCTION_LIMIT``, branch-free (fdlibm, module docstring)."""
    quadrant = math.floor(angle * _INVERSE_HALF_PI + 0.5)
    r = ((angle - quadrant * _HALF_PI_1) - quadrant * _HALF_PI_2) - quadrant * _HALF_PI_3
    z = r * r
    sine = r + z * r * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    half_z = 0.5 * z
    w = 1.0 - half_z
    tail = z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    cosine = w + (((1.0 - w) - half_z) + tail)
    q = int(quadrant) & 3  # φ = r + q π/2 (mod 2π)
    swapped = (q & 1) == 1
    c = sine if swapped else cosine
    s = cosine if swapped else sine
    c = -c if (q == 1 or q == 2) else c
    s = -s if q >= 2 else s
    return c, s


@njit(cache=True, error_model="numpy", fastmath=_FLAGS, inline="always")
def _limb(  # pragma: no cover - compiled
    x: float, y: float, z: float, c: float, s: float, phi: float, g: tuple, arm: float, offset: float,
    half_inverse_arm: float,
) -> tuple[float, float, float, float, bool]:
    """``l ρ² w`` (three components), ``R / l = |cos μ|`` and whether the limb reaches (docstring)."""
    d0 = x + g[0] + c * g[3] + s * g[6] + phi * g[9]  # d_i = c_i - a_i (Table 1)
    d1 = y + g[1] + c * g[4] + s * g[7] + phi * g[10]
    d2 = z + g[2] + c * g[5] + s * g[8] + phi * g[11]
    big_p = d0 * g[12] + d1 * g[13] + d2 * g[14]  # d_i·F_i j
    big_q = d0 * g[15] + d1 * g[16] + d2 * g[17]  # d_i·F_i k
    big_k = (d0 * d0 + d1 * d1 + d2 * d2 + offset) * half_inverse_arm  # Eq. (3)
    rho_squared = big_p * big_p + big_q * big_q
    slack = rho_squared - big_k * big_k  # ρ² sin² δ
    # at_reach's band (families._two_limb, README "Tolerance policy"): within REACH_ULPS rounding units
    # of its reach, ρ - |K| ≈ slack / 2|K|, a limb is at its reach (R = 0), not out of it
    band = 2.0 * abs(big_k) * REACH_ULPS * EPS * abs(big_k * arm + 1.0) / arm
    reach = rho_squared > 0.0 and slack >= -band
    root = math.sqrt(slack) if slack > band else 0.0  # R_i = |w_i·(u_i × v_i)| (l = 1)
    signed = g[18] * root  # m_i R_i
    along_j = big_p * big_k + big_q * signed  # ρ² cos θ_i
    along_k = big_q * big_k - big_p * signed  # ρ² sin θ_i
    w0 = rho_squared * d0 - arm * (along_j * g[12] + along_k * g[15])  # ρ² (d_i - b v_i)
    w1 = rho_squared * d1 - arm * (along_j * g[13] + along_k * g[16])
    w2 = rho_squared * d2 - arm * (along_j * g[14] + along_k * g[17])
    return w0, w1, w2, root, reach


@njit(cache=True, error_model="numpy", fastmath=_FLAGS, inline="always")
def _pose(  # pragma: no cover - compiled
    x: float, y: float, z: float, phi: float, c: float, s: float,
    limbs: tuple, platform: tuple, arm: float, offset: float,
) -> tuple[float, float, bool]:
    """``κ``, ``ζ``, reachable at one pose (lengths in units of ``l``; unreachable: 0, 0, False)."""
    half = 0.5 / arm  # loop-invariant: hoisted by the compiler
    a0, a1, a2, ra, oka = _limb(x, y, z, c, s, phi, limbs[0], arm, offset, half)  # sub-platform I
    b0, b1, b2, rb, okb = _limb(x, y, z, c, s, phi, limbs[1], arm, offset, half)
    c0, c1, c2, rc, okc = _limb(x, y, z, c, s, phi, limbs[2], arm, offset, half)  # sub-platform II
    e0, e1, e2, re, oke = _limb(x, y, z, c, s, phi, limbs[3], arm, offset, half)
    f0, f1, f2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0  # w_I
    h0, h1, h2 = c1 * e2 - c2 * e1, c2 * e0 - c0 * e2, c0 * e1 - c1 * e0  # w_II
    n0, n1, n2 = f1 * h2 - f2 * h1, f2 * h0 - f0 * h2, f0 * h1 - f1 * h0  # w_I × w_II
    s0 = c * platform[0] + s * platform[3] + platform[6]  # s (Tables 1-2)
    s1 = c * platform[1] + s * platform[4] + platform[7]
    s2 = c * platform[2] + s * platform[5] + platform[8]
    squared = n0 * n0 + n1 * n1 + n2 * n2
    cosine = abs(n0 * s0 + n1 * s1 + n2 * s2) / math.sqrt(squared if squared > 0.0 else 1.0)
    reach = oka and okb and okc and oke
    kappa = min(1.0, min(min(ra, rb), min(rc, re))) if reach else 0.0  # Eq. (15)
    zeta = min(1.0, cosine) if (reach and squared > 0.0) else 0.0  # 0 where w_I × w_II = 0 (|A| = 0)
    return kappa, zeta, reach


@njit(cache=True, error_model="numpy", fastmath=_FLAGS, nogil=True)
def transmission(  # pragma: no cover - compiled
    poses: Array, limbs: tuple, platform: tuple, arm: float, offset: float, scale: float
) -> tuple[Array, Array, Array]:
    """``poses (n, 4)`` → ``κ (n,)``, ``ζ (n,)``, reachable ``(n,)`` (unreachable: κ = ζ = 0).

    ``limbs``: four tuples of 19 floats, sub-platform I's two limbs then II's, each ``d_i - (x, y, z)``
    as ``g[0:3] + cos φ g[3:6] + sin φ g[6:9] + φ g[9:12]``, then ``F_i j``, ``F_i k`` and ``m_i``;
    ``platform``: ``s = cos φ p[0:3] + sin φ p[3:6] + p[6:9]``; ``arm``: ``b``, ``offset``:
    ``b² - l²``, both in units of ``l`` like ``g``; ``scale``: ``1/l`` for the positions.
    """
    n = poses.shape[0]
    flat = poses.reshape(4 * n)  # constant stride 4 between poses, which the vectoriser can load
    kappa = np.empty(n)
    zeta = np.empty(n)
    ok = np.empty(n, dtype=np.bool_)
    far = 0
    for p in range(n):  # vectorised: no branch, no call
        x, y, z, phi = flat[4 * p] * scale, flat[4 * p + 1] * scale, flat[4 * p + 2] * scale, flat[4 * p + 3]
        c, s = cos_sin(phi)
        kappa[p], zeta[p], ok[p] = _pose(x, y, z, phi, c, s, limbs, platform, arm, offset)
        far += abs(phi) > REDUCTION_LIMIT
    if far:  # the rare angles beyond the reduction's range: the library's cos and sin
        for p in range(n):
            phi = flat[4 * p + 3]
            if abs(phi) > REDUCTION_LIMIT:
                x, y, z = flat[4 * p] * scale, flat[4 * p + 1] * scale, flat[4 * p + 2] * scale
                kappa[p], zeta[p], ok[p] = _pose(
                    x, y, z, phi, math.cos(phi), math.sin(phi), limbs, platform, arm, offset
                )
    return kappa, zeta, ok
