"""The cost of the issue-24 hardening: scaling rows by a power of two before a rank decision, and
refusing None, strings and booleans before numpy reads them.

Run: ``python bench/bench_boundary.py`` from the repository root (prints a table; not a test).
CPU time (``time.process_time``), best of 7, single-threaded BLAS.

* ``singular values``: :func:`screwkit.algebra.ranks.screw_singular_values` of a batch of 6×6 screw
  matrices, against the same computation without the power-of-two scaling (the rows normalised by
  their norms as before issue 24, which overflow beyond 1.3e154), in systems per second;
* ``as_array``: :func:`screwkit.algebra.backend.as_array` of one screw given as a list, as a float
  array and a batch of 10⁴ screws as a list of lists, against ``numpy.array(value, dtype=float)``.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import time

import numpy as np
from _timing import best_of  # bench/ is the script folder

from screwkit.algebra.backend import as_array
from screwkit.algebra.ranks import scale_moments, screw_singular_values


def unscaled_singular_values(rows):
    """The singular values as computed before issue 24: moments divided by the length, rows by
    their (overflowing) norms."""
    scaled, _ = scale_moments(rows, 1.0)
    lengths = np.linalg.norm(scaled, axis=-1, keepdims=True)
    return np.linalg.svd(scaled / np.where(lengths > 0, lengths, 1.0), compute_uv=False)


def row(label, ours, base, unit):
    """One line of the table: ours, the baseline and their ratio (a rate or a time per call)."""
    ratio = ours / base if unit == "/s" else base / ours
    print(f"{label:<46} {ours:>14,.1f} {base:>14,.1f} {ratio:>7.2f}")


def main():
    rng = np.random.default_rng(0)
    print(f"{'computation':<46} {'ours':>14} {'baseline':>14} {'ratio':>7}")
    clock = time.process_time
    for count in (1_000, 100_000):
        rows = rng.normal(size=(count, 6, 6))
        ours = best_of(7, lambda rows=rows: screw_singular_values(rows, length_scale=1.0), clock)
        base = best_of(7, lambda rows=rows: unscaled_singular_values(rows), clock)
        row(f"singular values, {count} systems (systems/s)", count / ours, count / base, "/s")
    one, batch = [0.0, 0, 1, 2, -1, 0], rng.normal(size=(10_000, 6)).tolist()
    cases = (
        ("one screw as a list", one),
        ("one screw as an array", np.array(one)),
        ("10^4 screws as lists", batch),
    )
    for label, value in cases:
        ours = best_of(7, lambda value=value: [as_array(value, "screws", (6,)) for _ in range(100)], clock)
        base = best_of(7, lambda value=value: [np.array(value, dtype=float) for _ in range(100)], clock)
        row(f"as_array, {label} (µs per call)", ours * 1e4, base * 1e4, "s")


if __name__ == "__main__":
    main()
