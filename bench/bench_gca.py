"""Time diagram → factored, stated, labelled conditions (issue 9, item 5) and print the figures.

Run: ``python bench/bench_gca.py [--repeats 3]`` from the repository root. Not a test.

Two groups:

* the catalog robots: ``Mechanism.wrench_diagram()`` (diagram and sampler) and the 12
  configurations its sampler draws ("sampling"), then
  :func:`screwkit.gca.superbracket_analysis.superbracket_analysis` on those configurations
  ("GCA": ordering search, expansion, zeros, factoring, statements, exact proofs, labels);
* diagrams built from their points (gca level): the H4 of paper 002, Tsai's 3-UPU, the 3-RPS, the
  octahedral 3-3 and a general 6-6 Gough–Stewart: :func:`screwkit.gca.simplify_superbracket` then
  :func:`screwkit.gca.conditions.conditions` with the lines' roles;
* twist graphs of the tests (three to six legs: Tsai's 3-UPU, the 6-UPS Gough–Stewart):
  ``sk.graph_diagram`` (the diagram chosen at generic configurations, reached by moving the
  mechanism, and its sampler) then ``superbracket_analysis``, the whole "diagram → factored, stated
  conditions" of issue 21's speed target (≤ 1 s up to six legs), each factor's kind checked at its
  zeros (:func:`screwkit.gca.factor_kinds.vanishing_kind`).

The first call of a process pays for imports (sympy is imported on the first condition); the
figure reported is the best of the repeats after one warm-up call.
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import best_of

from screwkit.core.wrenches import wrench_analysis
from screwkit.gca import simplify_superbracket
from screwkit.gca.conditions import conditions
from screwkit.gca.diagram_placement import graph_diagram
from screwkit.gca.superbracket_analysis import superbracket_analysis
from screwkit.robots.catalog import list_mechanisms, load_mechanism
from tests.mechanisms import gough_stewart, gough_stewart_points, rotation_about, tsai_3upu

Z = np.array([0.0, 0.0, 1.0])


GRAPHS = {
    "3-UPU (3 legs)": tsai_3upu([0.05, 0.1, 1.0]),
    "6-UPS (6 legs)": gough_stewart(
        *gough_stewart_points(rotation_about([0.2, 1.0, 0.1], 0.1), [0.05, 0.02, 1.0])
    ),
}


def h4_sampler(rng):
    """a, c on the vertical axis Z_I; e, g on Z_II; j = (z, 0); the rest random directions."""
    a, e = np.r_[rng.normal(size=3), 1.0], np.r_[rng.normal(size=3), 1.0]
    points = {"a": a, "c": a + np.r_[rng.normal() * Z, 0.0], "e": e, "j": np.r_[Z, 0.0]}
    points["g"] = e + np.r_[rng.normal() * Z, 0.0]
    points |= {x: np.r_[rng.normal(size=3), 0.0] for x in "bdfhik"}
    return points


def generic_sampler(finite, infinite):
    def sampler(rng):
        out = {x: np.r_[rng.normal(size=3), 1.0] for x in finite}
        return out | {x: np.r_[rng.normal(size=3), 0.0] for x in infinite}

    return sampler


#: name: (lines, finite, infinite, collinear, sampler, number of actuation lines)
GCA_CASES = {
    "H4 (paper 002)": (
        ["ab", "cd", "ef", "gh", "ij", "kj"], "aceg", "bdfhijk", ["acj", "egj"], h4_sampler, 4
    ),
    "3-UPU": (["ab", "cd", "ef", "gh", "ij", "kl"], "ace", "bdfghijkl", [], None, 3),
    "3-RPS": (["ap", "bq", "cr", "pu", "qv", "rw"], "abcpqr", "uvw", [], None, 3),
    "octahedral 3-3": (["ad", "ae", "be", "bf", "cf", "cd"], "abcdef", "", [], None, 6),
    "general 6-6": (["ab", "cd", "ef", "gh", "ij", "kl"], "abcdefghijkl", "", [], None, 6),
}


def gca_chain(lines, finite, infinite, collinear, sampler, n_actuation):
    sampler = sampler or generic_sampler(finite, infinite)
    result = simplify_superbracket(lines, sampler, finite=finite, infinite=infinite, collinear=collinear)
    roles = ["actuation"] * n_actuation + ["constraint"] * (6 - n_actuation)
    found = conditions(result.factored, finite=finite, infinite=infinite, lines=lines, roles=roles)
    return result.factored, found


def catalog_samples(name):
    """The diagram at the default pose and the 12 configurations its sampler draws (rng 0)."""
    diagram, sampler = load_mechanism(name).wrench_diagram()
    if diagram.degenerate:
        return None, []
    rng = np.random.default_rng(0)
    return diagram, [sampler(rng) for _ in range(12)]


def catalog_chain(diagram, drawn):
    """superbracket_analysis on pre-drawn configurations (the sampling is timed apart)."""
    iterator = iter(drawn)
    return superbracket_analysis(diagram, lambda _: next(iterator))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(f"diagram -> factored, stated, labelled conditions; best of {args.repeats} after a warm-up")
    print(f"{'mechanism':16s} | {'seconds':>7} | factored form and labels")
    for name, case in GCA_CASES.items():
        factored, found = gca_chain(*case)
        seconds = best_of(args.repeats, lambda case=case: gca_chain(*case))
        powers = [f"^{c.multiplicity}" if c.multiplicity > 1 else "" for c in found]
        labels = ", ".join(c.label + power for c, power in zip(found, powers, strict=True))
        print(f"{name:16s} | {seconds:7.3f} | {factored}  [{labels}]")
    print(f"\n{'robot':16s} | {'sampling':>8} | {'GCA':>7} | factored form and labels (catalog default pose)")
    for name in list_mechanisms():
        try:
            diagram, drawn = catalog_samples(name)
            if diagram is None:
                print(f"{name:16s} |        - |       - | degenerate diagram at the default pose")
                continue
            result = catalog_chain(diagram, drawn)
        except Exception as err:  # a robot the superbracket does not apply to (reported, not timed)
            print(f"{name:16s} |        - |       - | {type(err).__name__}: {str(err)[:80]}")
            continue
        sampling = best_of(args.repeats, lambda name=name: catalog_samples(name))
        gca = best_of(args.repeats, lambda d=diagram, s=drawn: catalog_chain(d, s))
        labels = ", ".join(result.labels)
        print(f"{name:16s} | {sampling:8.3f} | {gca:7.3f} | {result.simplification.factored}  [{labels}]")
    print(f"\n{'twist graph':16s} | {'diagram':>8} | {'GCA':>7} | factored form and labels")
    for name, graph in GRAPHS.items():
        analysis = wrench_analysis(graph)
        seconds = best_of(args.repeats, lambda a=analysis: graph_diagram(a))
        diagram, sampler = graph_diagram(analysis)
        result = superbracket_analysis(diagram, sampler)
        gca = best_of(args.repeats, lambda d=diagram, s=sampler: superbracket_analysis(d, s))
        powers = [f"^{c.multiplicity}" if c.multiplicity > 1 else "" for c in result.conditions]
        labels = ", ".join(c.label + power for c, power in zip(result.conditions, powers, strict=True))
        print(f"{name:16s} | {seconds:8.3f} | {gca:7.3f} | {result.simplification.factored}  [{labels}]")


if __name__ == "__main__":
    main()
