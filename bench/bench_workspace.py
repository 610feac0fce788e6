"""Speed and memory of workspace maps against the core they run through (screwkit.workspace).

Run: ``python bench/bench_workspace.py [--side 1000] [--chunk 4096] [--repeats 3]`` from the
repository root (prints a table; not a test). Single-threaded BLAS.

Figures:

* ``core``: ``h4.at(poses).codes`` over 10,000 poses of the catalog box, chunked by the core
  itself (:func:`screwkit.singularity.classify_table`), poses/s;
* ``verdict map``: :func:`screwkit.workspace.grid_map` of ``"verdict"`` over a 100 × 100 grid of
  the same box (z × phi at x = y = 0, plus reachability), poses/s and the ratio to ``core``;
* ``large map``: a ``side × side`` verdict map (default 1000 × 1000 = 10⁶ poses) in chunks of
  ``--chunk`` poses: wall time, poses/s, and the process's peak resident memory (``ru_maxrss``)
  before and after it, which the chunks bound (the map's own arrays are 9 bytes per pose);
* ``path``: :func:`screwkit.workspace.check_path` of a 200-sample path across paper 002's actuation
  surface (the first crossing refined to ~1e-16 in the path parameter), seconds;
* ``loci``: :func:`screwkit.workspace.loci` of a 30 × 30 slice through all three surfaces, seconds.
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import resource  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from _timing import best_of  # noqa: E402  (bench/ is the script folder)

import screwkit as sk  # noqa: E402
from screwkit import workspace as W  # noqa: E402


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--side", type=int, default=1000, help="the large map is side x side poses")
    parser.add_argument("--chunk", type=int, default=W.CHUNK)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    h4 = sk.load_mechanism("h4")
    _ = h4.at([[0, 0, -750, 0]]).codes  # warm up (numba compile, imports)

    z, phi = np.meshgrid(np.linspace(-1000, -550, 100), np.radians(np.linspace(-45, 45, 100)))
    poses = np.stack([np.zeros_like(z), np.zeros_like(z), z, phi], axis=-1).reshape(-1, 4)
    core = best_of(args.repeats, lambda: h4.at(poses).codes)
    grid = {"x": ("z", -1000, -550, 100), "y": ("phi", -45, 45, 100), "fixed": {"x": 0, "y": 0}}
    mapped = best_of(args.repeats, lambda: W.grid_map(h4, "verdict", **grid))
    print(f"core, 10,000 poses:          {len(poses) / core:10.0f} poses/s")
    ratio = core / mapped
    print(f"verdict map, 100 x 100:      {len(poses) / mapped:10.0f} poses/s  ({ratio:.2f} x the core)")

    before = peak_mib()
    start = time.perf_counter()
    big = W.grid_map(
        h4,
        "verdict",
        x=("z", -1000, -550, args.side),
        y=("phi", -45, 45, args.side),
        fixed={"x": 0, "y": 0},
        chunk=args.chunk,
        progress=False,
    )
    seconds = time.perf_counter() - start
    count = args.side**2
    print(
        f"verdict map, {count:,} poses:  {seconds:8.1f} s  {count / seconds:10.0f} poses/s  peak RSS "
        f"{before:.0f} -> {peak_mib():.0f} MiB (chunk {args.chunk}); codes {np.unique(big.values).tolist()}"
    )

    start_pose = {"x": 300, "y": 300, "z": -800, "phi": -80}
    end_pose = {"x": 300, "y": 300, "z": -800, "phi": 0}
    path = best_of(1, lambda: W.check_path(h4, start_pose, end_pose))  # first call factors once
    path = best_of(args.repeats, lambda: W.check_path(h4, start_pose, end_pose))
    print(f"path, 200 samples, refined:  {path:8.2f} s  ({W.check_path(h4, start_pose, end_pose)})")
    slice_ = {"x": ("z", -1100, -450, 30), "y": ("phi", -90, 90, 30), "fixed": {"x": 300, "y": 300}}
    loci_time = best_of(1, lambda: W.loci(h4, **slice_))
    found = W.loci(h4, **slice_)
    counts = ", ".join(f"{lo.kind} {len(lo.points)}" for lo in found)
    print(f"loci, 30 x 30 slice:         {loci_time:8.2f} s  ({counts})")


if __name__ == "__main__":
    main()
