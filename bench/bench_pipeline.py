"""Speed of the whole symbolic pipeline for the H4: diagram, simplified factors, vector forms.

Run: python bench/bench_pipeline.py  (prints figures for the README; not a test). The first run in a
process includes sympy's one-time costs (imports, lambdify); later runs are the interactive figure.
Inside the superbracket stage, the two simplifications `superbracket_analysis` makes (the diagram's
own line order, and the best of the 46,080 orderings with its search) are timed apart.
"""

import time

from screwkit.gca import superbracket_analysis as analysis_module
from screwkit.gca.superbracket_analysis import superbracket_analysis
from screwkit.interface.report import analyze
from screwkit.robots.catalog import load_mechanism

#: Wall seconds of each simplify_superbracket call, by its `search` argument
SIMPLIFICATIONS: dict[bool, list[float]] = {False: [], True: []}


def _timed_simplification(function):
    def wrapper(*args, **kwargs):
        start = time.perf_counter()
        result = function(*args, **kwargs)
        SIMPLIFICATIONS[kwargs.get("search", True)].append(time.perf_counter() - start)
        return result

    return wrapper


def timed(function):
    start = time.perf_counter()
    result = function()
    return time.perf_counter() - start, result


def main():
    analysis_module.simplify_superbracket = _timed_simplification(analysis_module.simplify_superbracket)
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
        print(
            f"        of which the 24-term expansion simplified in the diagram's order "
            f"{1e3 * SIMPLIFICATIONS[False][-1]:.0f} ms / with the 46,080-ordering search "
            f"{1e3 * SIMPLIFICATIONS[True][-1]:.0f} ms"
        )
    report_time, _ = timed(lambda: analyze("h4"))
    print(
        f"whole `screwkit analyze h4` report (graph, wrenches, labels, diagram, factors): {report_time:.3f} s"
    )


if __name__ == "__main__":
    main()
