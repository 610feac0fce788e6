"""Time the wrench-diagram search: every catalog robot (generic workspace poses drawn and analysed as
one batch, the diagram chosen there and placed at the default pose) and twist graphs (generic
configurations reached by moving the mechanism and closing its loops, screwkit.core.motion).

Run as ``python bench/bench_diagram.py``.
"""

import numpy as np
from _timing import best_of

from screwkit.core.motion import generic_configurations
from screwkit.core.wrenches import wrench_analysis
from screwkit.gca.diagram_placement import graph_diagram
from screwkit.robots.catalog import load_mechanism

NAMES = ("h4", "v4", "quattro", "veloce", "ragnar", "mcgill_smg", "peppermill", "planar_3rrp")


def main():
    for name in NAMES:
        mechanism = load_mechanism(name)
        diagram, _ = mechanism.wrench_diagram()
        seconds = best_of(3, mechanism.wrench_diagram)
        state = "no diagram" if diagram.degenerate else diagram.line_text()
        print(f"catalog {name:12s} diagram search {seconds * 1e3:7.1f} ms   {state}")
    for name in NAMES[:1] + NAMES[-2:]:
        graph = load_mechanism(name).twist_graph()
        analysis = wrench_analysis(graph)
        seconds = best_of(3, lambda: graph_diagram(analysis))  # noqa: B023
        moving = best_of(3, lambda: generic_configurations(graph, np.random.default_rng(0), 24))  # noqa: B023
        print(
            f"graph   {name:12s} diagram search {seconds * 1e3:7.1f} ms   "
            f"24 generic configurations {moving * 1e3:7.1f} ms"
        )


if __name__ == "__main__":
    main()
