"""Cost of the operation-mode test at one pose (screwkit.core.mode_transitions.modes_at).

Run: ``python bench/bench_mode_transitions.py [--repeats 3]`` from the repository root (prints a
table; not a test). Single-threaded BLAS; seconds of this process's CPU time per call, best of
``--repeats``: Tsai's 3-UPU where its translational and planar modes meet (z = 0) and above its base
(z = 0.6), the H4 catalog robot's twist graph, and ``sk.analyze`` of the 3-UPU graph without the
superbracket (which now includes the test).
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # tests.mechanisms

import screwkit as sk  # noqa: E402
from screwkit.core.mode_transitions import modes_at  # noqa: E402
from tests.mechanisms import tsai_3upu  # noqa: E402


def best(call, repeats):
    """The least CPU time of ``repeats`` calls (seconds)."""
    times = []
    for _ in range(repeats):
        start = time.process_time()
        call()
        times.append(time.process_time() - start)
    return min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    meeting, above = tsai_3upu((0.1, 0.05, 0.0)), tsai_3upu((0.1, 0.05, 0.6))
    h4 = sk.load_mechanism("h4").twist_graph()
    modes_at(meeting)  # imports and kernels warmed
    print(f"load average {os.getloadavg()[0]:.1f}")
    for name, call in [
        ("modes_at 3-UPU, modes meet", lambda: modes_at(meeting)),
        ("modes_at 3-UPU, one mode", lambda: modes_at(above)),
        ("modes_at H4 graph", lambda: modes_at(h4)),
        ("analyze 3-UPU graph (no superbracket)", lambda: sk.analyze(meeting, superbracket=False)),
    ]:
        print(f"{name:40s} {best(call, args.repeats) * 1e3:8.1f} ms")


if __name__ == "__main__":
    main()
