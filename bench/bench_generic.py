"""Time the generic (symbolic) analysis of families of mechanisms and print the figures.

Run: ``python bench/bench_generic.py [--repeat N]`` from the repository root. Not a test. CPU time
of this process (``time.process_time``), the best and the median of N runs (default 3), each run
on a freshly built graph with the caches cleared; the machine's load is printed beside. The
baseline measured in the same run is the numeric core (``wrench_analysis``) on the H4-like family
at substituted values, so that ratios can be compared across loads.
"""

import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from screwkit.algebra import symbolic
from screwkit.core.generic import generic_analysis
from screwkit.core.wrenches import wrench_analysis
from screwkit.graphs.reduction import platform_twist_system
from tests.core.test_generic import delta_3ruu, four_limb_smg, fully_symbolic_h4, numeric_values


def cpu_times(function, repeat):
    """CPU seconds of ``repeat`` calls (the generic point's cache cleared before each) and the last result."""
    times, result = [], None
    for _ in range(repeat):
        symbolic._point.cache_clear()
        start = time.process_time()
        result = function()
        times.append(time.process_time() - start)
    return times, result


def _with_motion_type(result):
    result.motion_type  # noqa: B018 (the motion type is part of what is timed: decided on the returned basis)
    return result


def report(label, times, result, baseline=None):
    ratio = f"  ({min(times) / baseline:.0f}× the numeric baseline)" if baseline else ""
    print(f"{label}: best {min(times):.2f} s, median {statistics.median(times):.2f} s CPU{ratio}  {result}")


def main() -> None:
    repeat = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 3
    print(f"load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} cores; best/median of {repeat}")
    numeric_h4 = fully_symbolic_h4(numeric_values(np.random.default_rng(1)))
    times, _ = cpu_times(lambda: wrench_analysis(numeric_h4), max(repeat, 5))
    baseline = min(times)
    print(f"baseline: numeric wrench_analysis, H4-like at substituted values: {baseline * 1e3:.1f} ms CPU")
    families = [
        ("Delta-like 3-RUU", delta_3ruu),
        ("four-limb SMG, symbolic positions", four_limb_smg),
        ("H4-like, positions and directions symbolic", fully_symbolic_h4),
    ]
    for label, build in families:
        times, result = cpu_times(lambda build=build: _with_motion_type(generic_analysis(build())), repeat)
        report(f"generic_analysis, {label} ({len(result.symbols)} symbols)", times, repr(result), baseline)
    # (method="loop_closure" over symbols solves a 12 x 15 symbolic system: minutes; not timed)
    times, result = cpu_times(lambda: platform_twist_system(delta_3ruu(), method="reduction").order, repeat)
    report("platform_twist_system(method='reduction'), Delta-like", times, f"order {result}")
    print(f"load average {os.getloadavg()[0]:.2f} (1 min) at the end")


if __name__ == "__main__":
    main()
