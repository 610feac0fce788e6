"""Speed of the whole symbolic pipeline for the H4: diagram, simplified factors, vector forms.

Run: python bench/bench_pipeline.py  (prints figures for the README; not a test). The first run in a
process includes sympy's one-time costs (imports, lambdify); later runs are the interactive figure.
"""

import time

from screwkit.catalog import load_mechanism
from screwkit.diagram import superbracket_analysis
from screwkit.report import analyze


def timed(function):
    start = time.perf_counter()
    result = function()
    return time.perf_counter() - start, result


def main():
    h4 = load_mechanism("h4")
    for run in ("first", "second", "third"):
        diagram_time, (diagram, sampler) = timed(h4.wrench_diagram)
        pipeline_time, result = timed(
            lambda diagram=diagram, sampler=sampler: superbracket_analysis(diagram, sampler)
        )
        total = diagram_time + pipeline_time
        print(
            f"{run:>6} run: diagram {diagram_time:.3f} s + superbracket, factors, conditions "
            f"{pipeline_time:.3f} s = {total:.3f} s   ({result.simplification.factored})"
        )
    report_time, _ = timed(lambda: analyze("h4"))
    print(
        f"whole `screwkit analyze h4` report (graph, wrenches, labels, diagram, factors): {report_time:.3f} s"
    )


if __name__ == "__main__":
    main()
