"""Time the ``dof`` check of a twist graph (issue 11) and print the figures README quotes.

Run: ``python bench/bench_dof_check.py`` from the repository root. Not a test. For each graph: one
``classify`` at a regular pose (the check's free path) and one ``generic_mobility`` (the cost the
check adds where the pose is singular or the actuators are fewer than the freedoms), CPU time, best
of 5 and 3.
"""

import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from _timing import best_of

from screwkit import classify, load_mechanism
from screwkit.core.mobility import generic_mobility
from tests.mechanisms import (
    PLANAR_BASE,
    PLANAR_PLATFORM,
    gough_stewart,
    gough_stewart_points,
    planar_3rpr,
    tsai_3upu,
)
from tests.mechanisms_extra import delta


def main() -> None:
    graphs = {
        "3-RPR": planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM),
        "3-UPU": tsai_3upu([0.1, 0.05, 0.8]),
        "6-6 Gough-Stewart": gough_stewart(*gough_stewart_points()),
        "Delta": delta([0.1, 0.1, -1.5]),
        "H4 graph": load_mechanism("h4").twist_graph(),
    }
    print(f"load average {os.getloadavg()[0]:.1f}")
    for name, graph in graphs.items():
        graph = graph.copy()
        graph.graph.pop("mobility", None)  # measure the computation, not the family's known value
        regular = best_of(5, lambda g=graph: classify(g), clock=time.process_time)
        mobility = best_of(3, lambda g=graph: generic_mobility(g), clock=time.process_time)
        print(f"{name}: classify at a regular pose {regular * 1e3:.1f} ms, "
              f"generic_mobility {mobility * 1e3:.0f} ms")


if __name__ == "__main__":
    main()
