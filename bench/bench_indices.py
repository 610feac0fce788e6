"""Speed of LTI maps (paper 004's κ, ζ, η over a grid of poses): the fused kernel against numpy.

Run: ``python bench/bench_indices.py [--sizes 100000 1000000] [--repeats 5] [--robots ragnar | all]``
from the repository root (prints a table; not a test). One thread (BLAS/OpenMP threads set to 1; the
numba kernel is a plain loop, SIMD over poses, no ``parallel``); times are the process's CPU time
(``time.process_time``, the shared machine's load inflates wall time), best of the repeats timed
interleaved (one call of each column per round), with the load average printed before and after.

Four timings over the same poses (a grid over the robot's workspace box, all four coordinates
varying), the results checked against the first (``max diff``: the largest difference in κ or ζ;
~1e-13, up to ~1e-11 at poses where ζ is ill-conditioned, ``w_I × w_II`` nearly zero, where any two
evaluations differ by round-off times the condition number):

* ``numpy (straightforward)``: written out here as one would from paper 004 -- the closed-form
  inverse kinematics of Eq. (3) (``θ_i = atan2(Q_i, P_i) - m_i acos(K_i/ρ_i)``), ``v_i``,
  ``w_i = (c_i - b_i)/l``, ``κ = min_i |w_i·(u_i × v_i)|`` (Eqs. 11, 15) and
  ``ζ = |(w_I × w_II)·s| / ‖w_I × w_II‖`` (Eqs. 13, 15), vectorised over the batch;
* ``numpy (screwkit)``: :func:`screwkit.papers.paper_004.transmission` with ``SCREWKIT_NUMBA=0``'s path
  (the family's inverse kinematics, a full configuration, then the indices);
* ``fused kernel``: :mod:`screwkit.papers._lti_numba` alone (compiled once before timing), the part
  :func:`screwkit.papers.paper_004.transmission` runs per pose;
* ``sk.transmission``: the whole public call (argument checks, the kernel, ``η = min(κ, ζ)``, NaN
  where out of reach), what a user's map costs.

The issue's target: the fused kernel ≥ 35× the straightforward numpy implementation (both columns
of ratios are printed). Last, the script says whether the kernel's machine code has packed (SIMD)
square roots, the sign that its pose loop was vectorised (x86 mnemonics).
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
              "VECLIB_MAXIMUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from _timing import best_of  # noqa: E402  (bench/ is the script folder)

from screwkit.papers import paper_004 as I  # noqa: E402
from screwkit.robots.catalog import load_mechanism  # noqa: E402
from screwkit.robots.families.four_limb import configuration as FL  # noqa: E402


def straightforward(params, poses, mode=(-1, -1, -1, -1)):
    """κ, ζ over ``poses (n, 4)`` as written out from paper 004 (module docstring); NaN out of reach."""
    base = FL.base_frames(params)
    x, phi = poses[:, None, :3], poses[:, 3]
    r = params.platform_radius
    if params.platform_kind == "screw_pair":  # Table 1, Veloce row (corrected, four_limb item 2)
        radial = np.stack([np.cos(FL.ETA), np.sin(FL.ETA), np.zeros(4)], axis=-1)
        rise = (FL.ODD_LIMB * params.lead / (2 * np.pi))[:, None] * phi[:, None, None]
        c = r * radial + rise * [0, 0, 1] + x
        s = np.broadcast_to([0.0, 0.0, 1.0], (len(poses), 3))
    else:  # Quattro, H4: R_z(phi); V4: R_y(phi) (item 3)
        cos, sin, zero = np.cos(phi), np.sin(phi), np.zeros_like(phi)
        if params.platform_kind == "articulated_z":
            bar, s = np.stack([cos, sin, zero], -1), np.stack([-sin, cos, zero], -1)
        else:
            bar, s = np.stack([cos, zero, -sin], -1), np.stack([-sin, zero, -cos], -1)
        offsets = (FL.SGN_SIN_ETA * params.platform_offset)[:, None] * [0, 1, 0]
        c = FL.SGN_COS_ETA[:, None] * r * bar[:, None, :] + offsets + x
    d = c - base.a
    big_p, big_q = np.sum(d * base.j_rot, -1), np.sum(d * base.k_rot, -1)
    big_k = (np.sum(d * d, -1) + params.arm_length**2 - params.rod_length**2) / (2 * params.arm_length)
    rho = np.hypot(big_p, big_q)
    with np.errstate(invalid="ignore"):
        theta = np.arctan2(big_q, big_p) - np.array(mode) * np.arccos(big_k / rho)  # Eq. (3)
    v = np.cos(theta)[..., None] * base.j_rot + np.sin(theta)[..., None] * base.k_rot  # Eq. (2)
    u_cross_v = -np.sin(theta)[..., None] * base.j_rot + np.cos(theta)[..., None] * base.k_rot
    w = (c - base.a - params.arm_length * v) / params.rod_length
    kappa = np.min(np.abs(np.sum(w * u_cross_v, -1)), -1)  # Eqs. (11), (15)
    (i1, i2), (j1, j2) = params.subplatform_limbs
    normal = np.cross(np.cross(w[:, i1], w[:, i2]), np.cross(w[:, j1], w[:, j2]))
    zeta = np.abs(np.sum(normal * s, -1)) / np.linalg.norm(normal, axis=-1)  # Eqs. (13), (15)
    return kappa, zeta


def grid(mechanism, count):
    """About ``count`` poses on a grid over the workspace box (x, y, z, phi)."""
    side = max(2, round(count ** 0.25))
    axes = [np.linspace(*mechanism.workspace[c], side) for c in mechanism.pose_names]
    return np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 4)


def packed_square_roots(kernels, packed):
    """Whether the kernel's machine code has packed square roots (``sqrtpd``/``vsqrtpd``: the pose
    loop runs as SIMD code); compiles the kernel's source afresh (numba shows no assembly for cached
    code), with the same options."""
    from numba import njit

    fresh = njit(error_model="numpy", fastmath=kernels._FLAGS)(kernels.transmission.py_func)
    fresh(np.zeros((8, 4)), *packed)
    return "sqrtpd" in "\n".join(fresh.inspect_asm().values())


def timings(mechanism, poses, kernels, packed, repeats):
    """CPU times of the four columns (module docstring), best of ``repeats``, interleaved: each round
    times every column once in turn, so that a change of the machine's load falls on all of them."""
    params, mode = mechanism.parameters, (-1, -1, -1, -1)
    calls = [
        lambda: straightforward(params, poses),
        lambda: I._transmission_numpy(mechanism, poses, mode),
        lambda: kernels.transmission(poses, *packed),
        lambda: I.transmission(mechanism, poses, unreachable="nan"),
    ]
    best = [math.inf] * len(calls)
    for _ in range(repeats):
        best = [min(b, best_of(1, call, time.process_time)) for b, call in zip(best, calls, strict=True)]
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[100_000, 1_000_000])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--robots", nargs="+", default=["ragnar"], help="catalog names, or: all")
    args = parser.parse_args()
    names = ["quattro", "h4", "v4", "veloce", "ragnar"] if args.robots == ["all"] else args.robots
    kernels = I._numba_kernels(max(args.sizes))
    if kernels is None:
        raise SystemExit("numba is not available (install the `fast` extra); nothing to compare")
    print(f"LTI maps (paper 004 Eqs. 3, 11-16), one thread, CPU time of the process, best of "
          f"{args.repeats}; load average {os.getloadavg()[0]:.1f} at the start")
    print(f"{'robot':>8} {'poses':>8} {'reach':>5} | {'numpy (straight)':>16} {'numpy (screwkit)':>16} "
          f"{'fused kernel':>13} {'sk.transmission':>15} | {'kernel vs straight':>18} "
          f"{'call vs straight':>16} {'max diff':>8}")
    for name in names:
        mechanism = load_mechanism(name)
        params, mode = mechanism.parameters, (-1, -1, -1, -1)
        packed = I._kernel_arguments(params, mode)
        kernels.transmission(grid(mechanism, 16), *packed)  # compile (or load the cache) before timing
        for size in args.sizes:
            poses = grid(mechanism, size)
            kappa, zeta, ok = kernels.transmission(poses, *packed)
            ref_kappa, ref_zeta = straightforward(params, poses)
            assert np.array_equal(ok, np.isfinite(ref_kappa)), "reachability differs"
            difference = max(np.max(np.abs(kappa - ref_kappa)[ok]), np.max(np.abs(zeta - ref_zeta)[ok]))
            assert difference < 1e-10, difference  # printed: ~1e-13, ~1e-11 where ζ is ill-conditioned
            plain = I._transmission_numpy(mechanism, poses, mode)
            assert np.allclose(plain[0], kappa, rtol=0, atol=1e-12) and np.array_equal(plain[2], ok)
            times = timings(mechanism, poses, kernels, packed, args.repeats)
            widths = (16, 16, 13, 15)
            rates = "".join(
                f" {len(poses) / t / 1e6:>{w - 4}.2f} M/s" for t, w in zip(times, widths, strict=True)
            )
            print(f"{name:>8} {len(poses):>8} {ok.mean():>5.2f} |{rates} | {times[0] / times[2]:>17.1f}x "
                  f"{times[0] / times[3]:>15.1f}x {difference:>8.0e}")
    simd = packed_square_roots(kernels, I._kernel_arguments(load_mechanism(names[0]).parameters, (-1,) * 4))
    print(f"packed (SIMD) square roots in the kernel's machine code: {'yes' if simd else 'NO'}")
    print(f"load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
