"""Time the whole H4 superbracket simplification (paper 002 §5, Fig. 4c) and print the figures.

Run: ``python bench/bench_gca.py`` from the repository root. Not a test.
"""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from screwkit.gca import simplify_superbracket

Z = np.array([0.0, 0.0, 1.0])
H4 = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h"), ("i", "j"), ("k", "j")]
DECLARED = {"finite": "aceg", "infinite": "bdfhijk", "collinear": ["acj", "egj"]}


def h4_sampler(rng: np.random.Generator) -> dict[str, np.ndarray]:
    """a, c on the vertical axis Z_I; e, g on Z_II; j = (z, 0); the rest random directions."""
    a, e = np.r_[rng.normal(size=3), 1.0], np.r_[rng.normal(size=3), 1.0]
    points = {"a": a, "c": a + np.r_[rng.normal() * Z, 0.0], "e": e, "j": np.r_[Z, 0.0]}
    points["g"] = e + np.r_[rng.normal() * Z, 0.0]
    points |= {x: np.r_[rng.normal(size=3), 0.0] for x in "bdfhik"}
    return points


def best_of(repeats: int, **options: object) -> tuple[float, float, str]:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = simplify_superbracket(H4, h4_sampler, **DECLARED, **options)  # type: ignore[arg-type]
        times.append(time.perf_counter() - start)
    return times[0], min(times), str(result.factored)


def main() -> None:
    for label, options in [("paper's order", {"search": False}), ("ordering search", {})]:
        first, best, factored = best_of(5, **options)
        print(f"H4, {label:16s}: first {first * 1e3:7.1f} ms, best of 5 {best * 1e3:7.1f} ms"
              f"  ->  {factored}")


if __name__ == "__main__":
    main()
