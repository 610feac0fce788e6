"""Time the generic (symbolic) analysis of families of mechanisms and print the figures.

Run: ``python bench/bench_generic.py [--full]`` from the repository root. Not a test. ``--full``
adds the H4-like family with every position *and* direction symbolic (61 symbols, minutes).
"""

import sys
import time
from pathlib import Path

import sympy

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from screwkit.generic import generic_analysis
from screwkit.joints import revolute, spherical
from screwkit.twistgraph import platform_twist_system, twist_graph
from tests.test_generic import delta_3ruu, four_limb_smg


def fully_symbolic_h4():
    """Four R-(4S) limbs with symbolic base points, axes u_i, elbows, rods d_i, short sides λ_i u_i
    and a symbolic common axis k of R_I, R_II through symbolic points."""

    def vec(name):
        return sympy.symbols(f"{name}x {name}y {name}z")

    joints = []
    for i, sub in zip((1, 2, 3, 4), ("b_I", "b_II", "b_II", "b_I"), strict=True):
        a, u, m, d = vec(f"a{i}"), vec(f"u{i}"), vec(f"m{i}"), vec(f"d{i}")
        side = sympy.Symbol(f"l{i}")
        n = [mj + side * uj for mj, uj in zip(m, u, strict=True)]
        p = [mj + dj for mj, dj in zip(m, d, strict=True)]
        q = [nj + dj for nj, dj in zip(n, d, strict=True)]
        joints += [
            ("base", f"arm{i}", revolute(f"A{i}", u, a, actuated=True)),
            (f"arm{i}", f"rod{i}a", spherical(f"S{i}m", m)),
            (f"rod{i}a", sub, spherical(f"S{i}p", p)),
            (f"arm{i}", f"rod{i}b", spherical(f"S{i}n", n)),
            (f"rod{i}b", sub, spherical(f"S{i}q", q)),
        ]
    joints += [
        ("b_I", "ee", revolute("R_I", vec("k"), vec("r1"))),
        ("b_II", "ee", revolute("R_II", vec("k"), vec("r2"))),
    ]
    return twist_graph("base", "ee", joints, dof=4)


def timed(label, function):
    start = time.perf_counter()
    result = function()
    print(f"{label}: {time.perf_counter() - start:.2f} s  {result}")


def main() -> None:
    families = [
        ("Delta-like 3-RUU (13 symbols)", delta_3ruu),
        ("four-limb SMG, symbolic positions", four_limb_smg),
    ]
    if "--full" in sys.argv:
        families.append(("H4-like, positions and directions symbolic (61 symbols)", fully_symbolic_h4))
    for label, build in families:
        graph = build()
        timed(f"generic_analysis, {label}", lambda graph=graph: repr(generic_analysis(graph)))
    delta = delta_3ruu()
    # (method="loop_closure" over symbols solves a 12 x 15 symbolic system: minutes; not timed)
    timed(
        "platform_twist_system(method='reduction'), Delta-like",
        lambda: platform_twist_system(delta, method="reduction").order,
    )


if __name__ == "__main__":
    main()
