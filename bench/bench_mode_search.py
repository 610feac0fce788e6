"""Cost of the global operation-mode search (screwkit.core.mode_search.find_operation_modes).

Run: ``python bench/bench_mode_search.py [--repeats 3]`` from the repository root (prints a table;
not a test). Single-threaded BLAS; seconds of this process's CPU time per call, best of
``--repeats``. Per mechanism: the whole search (12 configurations reached from the reference and 24
random assemblies), the same without random assemblies (``assemblies=0``: what the report paid
before the search), the modes found and how many assemblies closed; then ``sk.analyze`` of Tsai's
3-UPU graph without the superbracket, which runs the search.
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # tests.mechanisms

from _timing import best_of  # noqa: E402  (bench/ is the script folder)

import screwkit as sk  # noqa: E402
from screwkit.core.mode_search import find_operation_modes  # noqa: E402
from tests.mechanisms import gough_stewart, gough_stewart_points, tsai_3upu  # noqa: E402


def cpu_time(call, repeats):
    """The least CPU time of ``repeats`` calls (seconds)."""
    return best_of(repeats, call, clock=time.process_time)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    graphs = {
        "3-UPU above its base": tsai_3upu((0.1, 0.05, 0.8)),
        "3-UPU in its base plane": tsai_3upu((0.1, 0.05, 0.0)),
        "6-UPS (graph)": gough_stewart(*gough_stewart_points()),
        **{name: sk.load_mechanism(name).twist_graph()
           for name in ("planar_3rrp", "delta", "h4", "mcgill_smg")},
    }
    find_operation_modes(graphs["3-UPU above its base"])  # imports and kernels warmed
    print(f"load average {os.getloadavg()[0]:.1f}")
    print(f"{'mechanism':26s} {'search':>9s} {'no assembly':>12s}  closed  modes")
    for name, graph in graphs.items():
        found = find_operation_modes(graph)
        whole = cpu_time(lambda graph=graph: find_operation_modes(graph), args.repeats)
        local = cpu_time(lambda graph=graph: find_operation_modes(graph, assemblies=0), args.repeats)
        print(f"{name:26s} {whole * 1e3:6.1f} ms {local * 1e3:9.1f} ms  {found.closed:2d}/{found.assemblies}"
              f"   {', '.join(found.names())}")
    graph = tsai_3upu((0.1, 0.05, 0.8))
    graph.graph["dof"] = 3
    report = cpu_time(lambda: sk.analyze(graph, superbracket=False), args.repeats)
    print(f"{'analyze 3-UPU graph (no superbracket)':40s} {report * 1e3:8.1f} ms")


if __name__ == "__main__":
    main()
