"""Speed of certification of the planar 3-RRP (closed form) and of mechanisms built as twist graphs
(screwkit.analysis.loop_closure_enclosure: the Krawczyk operator on the loop equations).

Run: ``python bench/bench_certify_krawczyk.py [--repeats 1]`` from the repository root (prints a
table; not a test). Single-threaded BLAS. CPU time of this process, best of ``--repeats``.

* ``3-RRP``: :func:`screwkit.analysis.certify.certify` of the catalog 3-RRP's slice x, y in
  [-0.3, 0.3] m at phi = 0.8 rad to 0.6 mm (1/1000 of its width), against a 200 x 200 ``verdict``
  map of the same slice (without loci);
* ``3-RPR graph``: a planar 3-RPR given as a twist graph (``screwkit.mechanism``), the slice
  x in [0.4, 0.6], y in [0.27, 0.47] at phi = 0 to 1/100 of its width, against a 50 x 50 ``verdict``
  map (continuation per pose);
* ``6-UPS graph``: a Gough-Stewart platform as a twist graph: the line rz in [1.55, 1.59] rad at
  z = 1 to 0.002 rad (the quarter-turn singularity), the slice z in [0.99, 1.01], rz in [1.56, 1.58]
  to 0.004, and the box x, y in [-0.01, 0.01] at z = 1 near the reference (proved free at once);
* ``Krawczyk``: boxes of the 6-UPS (half-width 0.002 in all six coordinates about random poses near
  the reference) proved per second, kinematics and the actuation determinant included.
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from _timing import best_of  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import screwkit as sk  # noqa: E402
from screwkit.analysis.certify import certify  # noqa: E402
from screwkit.analysis.intervals import Enclosure  # noqa: E402
from screwkit.analysis.loop_closure_enclosure import LoopClosureModel  # noqa: E402
from screwkit.analysis.workspace import grid_map  # noqa: E402
from tests.mechanisms import gough_stewart, gough_stewart_points, planar_3rpr  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    clock = time.process_time
    print(f"load average {os.getloadavg()[0]:.2f}")

    rrp = sk.load_mechanism("planar_3rrp")
    region = {"x": (-0.3, 0.3), "y": (-0.3, 0.3), "phi": 0.8}
    found: dict = {}

    def rrp_proof() -> object:
        found["rrp"] = certify(rrp, region, resolution=0.0006)
        return found["rrp"]

    sampled = best_of(
        args.repeats,
        lambda: grid_map(rrp, "verdict", x=("x", -0.3, 0.3, 200), y=("y", -0.3, 0.3, 200), fixed={"phi": 0.8},
                         loci=False),
        clock,
    )
    proof = best_of(args.repeats, rrp_proof, clock)
    print(f"3-RRP slice: map 200x200 {sampled:.2f} s, certify to 1/1000 {proof:.2f} s "
          f"({proof / sampled:.1f}x; {found['rrp'].evaluated} boxes: {found['rrp'].totals})")

    base = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.8, 0.0]])
    platform = np.array([[0.4, 0.3, 0.0], [0.6, 0.3, 0.0], [0.5, 0.5, 0.0]])
    rpr = sk.mechanism(planar_3rpr(base, platform))

    def rpr_proof() -> object:
        found["rpr"] = certify(rpr, {"x": (0.4, 0.6), "y": (0.27, 0.47), "phi": 0.0}, resolution=0.002)
        return found["rpr"]

    sampled = best_of(
        args.repeats,
        lambda: grid_map(rpr, "verdict", x=("x", 0.4, 0.6, 50), y=("y", 0.27, 0.47, 50), fixed={"phi": 0.0},
                         loci=False),
        clock,
    )
    proof = best_of(args.repeats, rpr_proof, clock)
    print(f"3-RPR graph slice: map 50x50 {sampled:.2f} s, certify to 1/100 {proof:.2f} s "
          f"({found['rpr'].evaluated} boxes: {found['rpr'].totals})")

    gough = sk.mechanism(gough_stewart(*gough_stewart_points()))
    for label, region, resolution in (
        ("line rz in [1.55, 1.59] at z = 1", {"z": 1.0, "rz": (1.55, 1.59)}, 0.002),
        ("slice z in [0.99, 1.01], rz in [1.56, 1.58]", {"z": (0.99, 1.01), "rz": (1.56, 1.58)}, 0.004),
        ("box x, y in [-0.01, 0.01] at z = 1", {"x": (-0.01, 0.01), "y": (-0.01, 0.01), "z": 1.0}, 0.005),
    ):

        def gough_proof(region: dict = region, resolution: float = resolution) -> object:
            found["gough"] = certify(gough, region, resolution=resolution)
            return found["gough"]

        seconds = best_of(args.repeats, gough_proof, clock)
        done = found["gough"]
        print(f"6-UPS graph {label}: {seconds:.2f} s ({done.evaluated} boxes: {done.totals})")

    model = LoopClosureModel.of(gough)
    centres = gough.default_pose + np.random.default_rng(0).uniform(-0.02, 0.02, (256, 6))

    def boxes() -> object:
        model._memo.clear()
        return model.evaluate(Enclosure.variables(centres - 0.002, centres + 0.002, gradient=False))

    seconds = best_of(args.repeats, boxes, clock)
    values = model.evaluate(Enclosure.variables(centres - 0.002, centres + 0.002, gradient=False))
    proved = float(np.mean(values["actuation"].excludes_zero()))
    print(f"Krawczyk: 6-UPS boxes of half-width 0.002: {len(centres) / seconds:,.0f} boxes/s "
          f"({proved:.0%} proved free)")


if __name__ == "__main__":
    main()
