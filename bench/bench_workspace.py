"""Speed and memory of workspace maps against the core they run through (screwkit.analysis.workspace).

Run: ``python bench/bench_workspace.py [--side 1000] [--chunk 4096] [--repeats 5] [--conditions-only]``
from the repository root (prints a table; not a test). Single-threaded BLAS.

Figures (rates in poses per second of this process's CPU time, since the machine is shared; the
first section the median of ``--repeats`` rounds, each round timing every compared function once in
turn so that a change of load weighs on all alike, the load average printed before and after; the
other sections best of ``--repeats``):

* ``condition maps vs the core`` (issue 21: a condition map at ≥ 0.5× the core's rate): per
  mechanism, the core on the map's reachable poses (``m.at(poses).singularities``), the verdict
  map and a ``"condition:1"`` map (:func:`screwkit.analysis.workspace.grid_map`, loci off), and the
  ratios condition map / core and condition map / verdict map. The H4 and the Quattro on
  100 × 100 grids (z × phi at x = y = 0), the Delta on 20 × 20 (x × z at y = 0), the H4 as a graph
  mechanism (:func:`screwkit.mechanism`, kinematics by loop closure) on 30 × 30, Tsai's 3-UPU as a
  graph mechanism on 30 × 30 (x × z at y = 0). Measured on
  2026-11-28 (5 rounds; load 2.9–3.6 on 2 cores shared by seven sessions), condition map / core,
  before → after: H4 0.33× → **0.59×**, Quattro 0.31× → **0.59×**, H4 graph 0.58× → **0.76×**,
  Delta 0.004× → 0.005×. Before, each chunk went through the core with every per-pose view and
  the joint table was built whole then sliced; now the core runs without its views, keeping only
  the frames the diagram's recipes read, the joint table is built chunk by chunk as for the
  verdicts, and a joint's axis is computed once per chunk. What is left: the
  recipes' numpy arithmetic over each 512-pose chunk (~2.9 ms of ~8 ms a chunk: the meets of
  actuation lines with joint axes ~1.2 ms, the branches' constraint couples ~1.1 ms), against
  ~4.3 ms for the wrench pass itself. The Delta and the 3-UPU read their legs' constraint lines,
  each leg's readable basis (:meth:`screwkit.algebra.screwsystem.ScrewSystem.readable_basis`,
  ~0.8 ms a system), taken pose by pose before, over the batch now
  (:func:`screwkit.algebra.readable_bases.readable_bases`), and a map no longer evaluates the
  default pose through the core's one-pose path before its poses (~3 ms a map): measured the same
  day (load 0.4–4.9; the same bench on the commit before, then on this one, 5 rounds each), Delta
  0.004–0.005× → **0.52–0.59×** (~400 → 56,000–73,000 poses/s), 3-UPU graph 0.013× → **0.60–0.61×**
  (~450 → ~24,000 poses/s); at load 0.6 the H4 0.61× → 0.62–0.65×, the H4 graph 0.76× → 0.80×;
* ``core``: ``h4.at(poses).singularities`` over 10,000 poses of the catalog box, chunked by the
  core itself (:func:`screwkit.core.singularity.classify_chunks`), poses/s;
* ``verdict map``, ``closeness map``: :func:`screwkit.analysis.workspace.grid_map` of ``"verdict"`` and
  ``"closeness"`` over a 100 × 100 grid of the same box (z × phi at x = y = 0, plus
  reachability), without and with the slice's loci (the maps' default), poses/s and the ratios to
  ``core`` and to the verdict map without loci;
* ``condition:0 / :1 map``: the same grid for the superbracket's two factors (paper 002 Eqs. 6, 7):
  the diagram's points over each chunk from the batched core and the factors' vector forms on them
  (the superbracket factored once before timing), poses/s and the ratio to ``core``;
* ``one pose at a time``: the same condition through the per-pose route the maps used before
  (``condition.evaluate(diagram_points(diagram.points, posed[i].analysis))``), on 200 poses;
* ``large maps``: a ``condition-side²`` map of ``"condition:1"`` (default 300 × 300 = 90,000 poses)
  and a ``side × side`` verdict map (default 1000 × 1000 = 10⁶ poses) in chunks of ``--chunk``
  poses: wall time, poses/s of CPU time, and the process's peak resident memory (``ru_maxrss``)
  before and after each, which the chunks bound (the map's own arrays are 9 bytes per pose);
* ``path``: :func:`screwkit.analysis.paths.check_path` of a 200-sample path across paper 002's actuation
  surface (the first crossing refined to ~1e-16 in the path parameter), seconds;
* ``loci``: :func:`screwkit.analysis.loci.loci` of a 30 × 30 slice through all three surfaces, seconds.
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import resource  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

# this checkout's screwkit (not an installed one) and the tests' mechanisms
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402
from _timing import best_of, interleaved_medians  # noqa: E402  (bench/ is the script folder)

import screwkit as sk  # noqa: E402
from screwkit import workspace as W  # noqa: E402
from screwkit.analysis.quantities import conditions_of  # noqa: E402
from screwkit.gca.diagram_points import diagram_points  # noqa: E402
from tests.mechanisms import tsai_3upu  # noqa: E402


def poses_of(posed):
    return [posed[i] for i in range(len(posed))]


def h4_graph():
    return sk.mechanism(sk.load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])


def tsai_graph():
    return sk.mechanism(tsai_3upu([0.1, 0.05, 1.0]))


#: The condition maps compared with the core: name, mechanism, the grid's x and y axes (degrees for
#: angles) and its fixed coordinates.
CONDITION_MAPS = (
    ("H4", lambda: sk.load_mechanism("h4"), ("z", -1000, -550, 100), ("phi", -45, 45, 100), {"x": 0, "y": 0}),
    ("Quattro", lambda: sk.load_mechanism("quattro"), ("z", -975, -475, 100), ("phi", -45, 45, 100),
     {"x": 0, "y": 0}),
    ("Delta", lambda: sk.load_mechanism("delta"), ("x", -300, 300, 20), ("z", -1150, -850, 20), {"y": 0}),
    ("H4 graph", h4_graph, ("z", -800, -700, 30), ("phi", -20, 20, 30), {"x": 0, "y": 0}),
    ("3-UPU graph", tsai_graph, ("x", -0.2, 0.2, 30), ("z", 0.8, 1.1, 30), {"y": 0}),
)


def grid_poses(mechanism, x, y, fixed):
    """A map's grid in API units (radians), flattened: ``x`` and ``y`` as ``(name, low, high, count)``."""
    names = list(mechanism.pose_names)
    xs, ys = np.meshgrid(np.linspace(*x[1:3], x[3]), np.linspace(*y[1:3], y[3]))
    poses = np.zeros((*xs.shape, len(names)))
    for name, value in {**fixed, x[0]: xs, y[0]: ys}.items():
        poses[..., names.index(name)] = np.radians(value) if name in mechanism.angle_names else value
    return poses.reshape(-1, len(names))


def condition_maps_against_the_core(repeats):
    """Issue 21's figure: each condition map's rate against the core's on the same poses."""
    print(f"condition maps vs the core (median of {repeats} interleaved rounds, CPU time), "
          f"load average {os.getloadavg()[0]:.1f}")
    for name, build, x, y, fixed in CONDITION_MAPS:
        mechanism = build()
        conditions_of(mechanism, {})  # the superbracket factored once, outside the timing
        poses = grid_poses(mechanism, x, y, fixed)
        reached = poses[mechanism.reachable(poses)]
        grid = {"x": x, "y": y, "fixed": fixed, "angles": "deg", "loci": False, "progress": False}
        _ = mechanism.at(reached[:2]).singularities  # warm-up (numba, imports)
        core, verdict, condition = interleaved_medians(
            repeats,
            [
                lambda m=mechanism, p=reached: m.at(p).singularities,
                lambda m=mechanism, g=grid: W.grid_map(m, "verdict", **g),
                lambda m=mechanism, g=grid: W.grid_map(m, "condition:1", **g),
            ],
            clock=time.process_time,
        )
        count = len(poses)
        print(
            f"  {name:9s} {x[3]} x {y[3]} ({len(reached)} reached): core {len(reached) / core:7.0f} poses/s, "
            f"verdict map {count / verdict:7.0f}, condition:1 map {count / condition:7.0f} poses/s: "
            f"{core / condition:.3f} x the core, {verdict / condition:.3f} x the verdict map"
        )
    print(f"  load average after: {os.getloadavg()[0]:.1f}")


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--side", type=int, default=1000, help="the large map is side x side poses")
    parser.add_argument("--condition-side", type=int, default=300, help="the large condition map's side")
    parser.add_argument("--chunk", type=int, default=W.CHUNK)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--conditions-only", action="store_true", help="only the condition maps vs the core")
    args = parser.parse_args()
    h4 = sk.load_mechanism("h4")
    _ = h4.at([[0, 0, -750, 0]]).codes  # warm up (numba compile, imports)
    condition_maps_against_the_core(args.repeats)
    if args.conditions_only:
        return

    print(f"load average {os.getloadavg()[0]:.1f} (CPU time of this process; best of {args.repeats})")
    cpu = time.process_time
    conditions_of(h4, {})  # the superbracket factored once, outside the timing
    for quantity, side in (("condition:1", args.condition_side), ("verdict", args.side)):
        before = peak_mib()  # large maps first (then the condition map): a peak hides later ones
        start, start_cpu = time.perf_counter(), cpu()
        big = W.grid_map(
            h4,
            quantity,
            x=("z", -1000, -550, side),
            y=("phi", -45, 45, side),
            fixed={"x": 0, "y": 0},
            chunk=args.chunk,
            progress=False,
            angles="deg",
        )
        seconds, cpu_seconds = time.perf_counter() - start, cpu() - start_cpu
        count = side**2
        print(
            f"{quantity} map, {count:,} poses: {seconds:7.1f} s wall, {count / cpu_seconds:8.0f} poses/s "
            f"(CPU)  peak RSS {before:.0f} -> {peak_mib():.0f} MiB (chunk {args.chunk}); "
            f"range [{big.minimum:.4g}, {big.maximum:.4g}]"
        )

    z, phi = np.meshgrid(np.linspace(-1000, -550, 100), np.radians(np.linspace(-45, 45, 100)))
    poses = np.stack([np.zeros_like(z), np.zeros_like(z), z, phi], axis=-1).reshape(-1, 4)
    core = best_of(args.repeats, lambda: h4.at(poses).singularities, clock=cpu)
    print(f"core, 10,000 poses:          {len(poses) / core:10.0f} poses/s")
    grid = {
        "x": ("z", -1000, -550, 100), "y": ("phi", -45, 45, 100), "fixed": {"x": 0, "y": 0}, "angles": "deg"
    }
    diagram, conditions, _, _ = conditions_of(h4, {})
    plain = best_of(args.repeats, lambda: W.grid_map(h4, "verdict", **grid, loci=False), clock=cpu)
    for quantity in ("verdict", "closeness", "condition:0", "condition:1"):
        rates = []
        for loci in (False, True):
            mapped = best_of(
                args.repeats, lambda q=quantity, f=loci: W.grid_map(h4, q, **grid, loci=f), clock=cpu
            )
            rates.append(
                f"{len(poses) / mapped:7.0f} poses/s ({core / mapped:.2f} x the core, "
                f"{plain / mapped:.2f} x the verdict map without loci)"
            )
        label = f"{quantity} map, 100 x 100:"
        print(f"{label:29s} without loci {rates[0]}; with loci {rates[1]}")
    few = h4.at(poses[:: len(poses) // 200])

    def one_at_a_time():
        factor = conditions[1]
        return [factor.evaluate(diagram_points(diagram.points, pose.analysis)) for pose in poses_of(few)]

    single = best_of(1, one_at_a_time, clock=cpu)
    print(f"condition:1, one pose at a time: {len(few) / single:6.0f} poses/s  (200 poses)")

    start_pose = {"x": 300, "y": 300, "z": -800, "phi": -80}
    end_pose = {"x": 300, "y": 300, "z": -800, "phi": 0}
    checked = sk.check_path(h4, start_pose, end_pose, angles="deg")
    path = best_of(args.repeats, lambda: sk.check_path(h4, start_pose, end_pose, angles="deg"), clock=cpu)
    print(f"path, 200 samples, refined:  {path:8.2f} s  ({checked})")
    slice_ = {
        "x": ("z", -1100, -450, 30), "y": ("phi", -90, 90, 30), "fixed": {"x": 300, "y": 300}, "angles": "deg"
    }
    loci_time = best_of(1, lambda: sk.loci(h4, **slice_), clock=cpu)
    found = sk.loci(h4, **slice_)
    counts = ", ".join(f"{lo.kind} {len(lo.points)}" for lo in found)
    print(f"loci, 30 x 30 slice:         {loci_time:8.2f} s  ({counts})")


if __name__ == "__main__":
    main()
