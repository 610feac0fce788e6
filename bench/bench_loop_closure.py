"""Speed of loop-closure kinematics against the catalog's closed forms (screwkit.core.loop_closure).

Run: ``python bench/bench_loop_closure.py [--poses 2000] [--side 200] [--repeats 2]`` from the
repository root (prints a table; not a test; ``--side 0`` measures the first ratio only).
Single-threaded BLAS. Rates in poses per second of this process's CPU time (the machine may be
shared; the load average is printed), the two sides of each ratio measured in the same run:

* ``H4 closed form``: ``load_mechanism("h4").at(poses).verdicts`` on ``--poses`` random reachable poses
  (closed-form inverse kinematics, joint table, verdicts);
* ``H4 loop closure``: the same poses and verdicts through ``screwkit.mechanism(h4 twist graph)``
  (loop-closure inverse kinematics continued from the reference configuration; the verdicts are
  checked equal to the closed form's), and the ratio of the rates (the issue's target: >= 0.3). Each
  of ``--repeats`` repeats draws fresh poses (none read from the mechanism's cache of solved poses)
  and times the two sides in turn; the medians are printed. Both mechanisms are built once, outside
  the timing (the graph's build time is printed);
* ``H4 catalog map``: ``grid_map(h4, "verdict")`` over ``--side``² poses (x, y at z = -750 mm), best
  of ``--repeats``;
* ``6-UPS graph map``: ``grid_map`` of a Gough-Stewart platform built as a twist graph over the same
  number of poses (x, y at the reference height), and the ratio to the H4 catalog map (target >= 0.3).

Measured with ``--poses 1000 --side 0 --repeats 5..7`` on a shared 2-core machine (load average
2.6-9): H4 loop closure 6,400-7,800 poses/s against the closed form's 63,600-78,900 (ratio
0.099-0.104; the same bench on the code before the compiled continuation, in the same minutes:
966-1,408 against 66,600-90,700, ratio 0.014-0.017). With ``--side 60 --repeats 5`` (load 3.1), with
the graph verdict path (core/_program.py's UPS legs, robots/graph_kinematics.py's remembered poses and
model states) as well: 6-UPS graph map 12,100 poses/s against the H4 catalog map's 29,300 (ratio
0.41; the compiled continuation alone: 0.354-0.381 at load 2.7-2.9; before both: 4,638 against
28,239, ratio 0.164). See docs/mechanisms.md ("Speed") for what dominates the H4. With the first
step's tangent predictor, steps of 0.35 and retries from the last trusted step (model evaluations per
H4 pose 11.4 -> 8.6), ``--poses 2000 --side 0 --repeats 5`` at load 0.4: 7,523 poses/s against the
closed form's 46,062 (ratio 0.163; the code before, in the same minute: 6,643 against 45,417, 0.146).

With steps on the way stopped by the corrector's contraction (Θ / (1 − Θ) |Δθ| ≤ 1e-3) and simplified
Newton iterations (model evaluations per H4 pose 8.6 -> 7.3, ~8.8 -> ~7.8 µs each), the continuation's
system built once per task, and the graph verdict path's compiled joint table (wp-verdictpath),
``--poses 2000 --side 0 --repeats 5`` at load 5.3-7, the three versions alternated twice in the same
minutes: 9,547-9,754 poses/s against the closed form's 39,482-41,274 (ratio 0.236-0.242); the loop
closure's changes alone 0.195-0.198; b9f8382 0.164-0.172. With ``--side 60 --repeats 3`` (load 7):
the 6-UPS graph map 0.681 of the H4 catalog map (b9f8382 0.585, the same minute).

With the working-mode check of every step (wp-branches) and seeded starts (core/_seeded_starts.py: a
chunk's far poses continued from 1 in 16 of them solved from the reference), ``--poses 2000 --side 60
--repeats 3`` at load 6.2, alternated twice with the code before seeded starts (main f0c0e09): H4 loop
closure 3,972-4,028 poses/s, ratio 0.105-0.109 (before: 3,331-3,438, ratio 0.091-0.096); the 6-UPS graph
map 0.601-0.613 of the H4 catalog map (before: 0.612-0.626; its poses are within one step of the
reference and are not seeded).

With the rods (binary links between two balls) replaced by their distance equations when they close
every loop (core/_rod_closure.py, compiled corrector core/_rod_newton_numba.py), ``--poses 2000 --side 60
--repeats 5`` at load 0.4: H4 loop closure 16,439 poses/s against the closed form's 47,623 (ratio 0.345,
0.336-0.389 per repeat; the code before, the same load: 5,832 against 41,830, 0.139); the 6-UPS graph
map 0.627 of the H4 catalog map (no rods: unchanged).
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # tests.mechanisms, bench._timing

import screwkit as sk  # noqa: E402
from bench._timing import best_of  # noqa: E402
from screwkit.robots.catalog import load_mechanism  # noqa: E402
from tests.mechanisms import gough_stewart, gough_stewart_points  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=2000)
    parser.add_argument("--side", type=int, default=200, help="0: the first ratio only")
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    clock = time.process_time
    print(f"load average {os.getloadavg()[0]:.2f}; {args.poses} poses, maps of {args.side}² poses")

    h4 = load_mechanism("h4")
    rng = np.random.default_rng(0)
    pose_sets = [h4.random_poses(rng, args.poses) for _ in range(args.repeats)]  # fresh poses per repeat
    _ = h4.at(pose_sets[0][:300]).verdicts  # numba compiled before timing
    start = clock()
    graph = sk.mechanism(h4.twist_graph(), platform_point=[0.0, 0.0, -750.0])
    build = clock() - start
    _ = graph.at(h4.random_poses(rng, 300)).verdicts  # (compiled, and the pinned model built once)
    rates_closed, rates_loop = [], []
    for poses in pose_sets:  # the two sides in turn on the same poses; no pose asked twice (no cache)
        start = clock()
        closed_form = h4.at(poses).verdicts
        rates_closed.append(len(poses) / (clock() - start))
        start = clock()
        verdicts = graph.at(poses).verdicts
        rates_loop.append(len(poses) / (clock() - start))
        assert (verdicts == closed_form).all(), "the loop closure's verdicts differ from the closed form's"
    rate_closed, rate_loop = float(np.median(rates_closed)), float(np.median(rates_loop))
    ratios = np.array(rates_loop) / np.array(rates_closed)
    print(f"H4 closed form      {rate_closed:10.0f} poses/s   (median of {args.repeats})")
    print(
        f"H4 loop closure     {rate_loop:10.0f} poses/s   ratio {rate_loop / rate_closed:.3f} "
        f"(per repeat {ratios.min():.3f}-{ratios.max():.3f}; target >= 0.3); the mechanism built once "
        f"in {1e3 * build:.0f} ms"
    )
    if args.side == 0:
        return

    side = args.side
    seconds_h4_map = best_of(
        args.repeats,
        lambda: sk.grid_map(h4, "verdict", x=("x", -200, 200, side), y=("y", -200, 200, side),
                            fixed={"z": -750.0, "phi": 0.0}, progress=False),
        clock=clock,
    )
    gs = gough_stewart(*gough_stewart_points())

    def gs_map():
        robot = sk.mechanism(gs)  # a fresh cache
        return sk.grid_map(robot, "verdict", x=("x", -0.2, 0.2, side), y=("y", -0.2, 0.2, side),
                           fixed={"z": 1.0, "rx": 0.0, "ry": 0.0, "rz": 0.0}, progress=False)

    seconds_gs_map = best_of(args.repeats, gs_map, clock=clock)
    count = side * side
    rate_h4, rate_gs = count / seconds_h4_map, count / seconds_gs_map
    print(f"H4 catalog map      {rate_h4:10.0f} poses/s")
    print(f"6-UPS graph map     {rate_gs:10.0f} poses/s   ratio {rate_gs / rate_h4:.3f} (target >= 0.3)")


if __name__ == "__main__":
    main()
