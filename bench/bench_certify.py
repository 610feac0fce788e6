"""Speed of certification (screwkit.analysis.certify) against sampled maps of the same slice.

Run: ``python bench/bench_certify.py [--repeats 1]`` from the repository root (prints a table; not a
test). Single-threaded BLAS. Times are this process's CPU time (the machine is shared), best of
``--repeats``.

* ``map 200x200``: :func:`screwkit.analysis.workspace.grid_map` ``"verdict"`` over the Quattro's slice
  x, y in [-400, 400] mm at z = -750 mm (phi = 0 and 90 deg), without and with its loci;
* ``certify 1/1000``: :func:`screwkit.analysis.certify.certify` of the same slice to a resolution of
  0.8 mm (1/1000 of its width), and its ratio to the map without loci (the issue's target: <= 10x);
* ``certify 3-D``: the box x, y in [-400, 400], z in [-900, -600] at phi = 0 and 45 deg, to 1/100
  of each width (seconds, boxes);
* ``Delta``: certify the Delta's slice x in [900, 1200], y in [-60, 60] at z = -1000 mm (the rods'
  coplanarity near x = 1143.5 mm) to 0.3 mm, and its workspace box to 1/100 of each width (seconds,
  boxes);
* ``conditions``: the closed-form conditions (the four reach functions, det A, paper 002's Eq. 6;
  inverse kinematics included) at 100,000 poses, in floats
  (:meth:`~screwkit.analysis.enclosures.FourLimbModel.values`, the issue's target: >= 2x) and as
  double intervals at points, against one batched numpy SVD of 6 x 6 matrices of the same count
  (the wrench matrices' shape; poses/s, ratio);
* ``Veloce``, ``McGill SMG``, ``Peppermill``: a slice through a singular surface, the catalog's workspace
  (4-D, or the Veloce's inner box x, y in [-400, 400], z in [-900, -600] at every phi in [-2 pi, 2 pi])
  (seconds, boxes) and the conditions in floats at 100,000 reachable poses against the same SVD.
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from _timing import best_of  # noqa: E402

import screwkit as sk  # noqa: E402
from screwkit.analysis.certify import certify  # noqa: E402
from screwkit.analysis.enclosures import FourLimbModel, model_of  # noqa: E402
from screwkit.analysis.intervals import Enclosure  # noqa: E402
from screwkit.analysis.workspace import grid_map  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    quattro = sk.load_mechanism("quattro")
    clock = time.process_time
    print(f"load average {os.getloadavg()[0]:.2f}")
    for phi in (0.0, 90.0):
        fixed = {"z": -750.0, "phi": phi}
        axes = {"x": ("x", -400, 400, 200), "y": ("y", -400, 400, 200)}
        region = {"x": (-400, 400), "y": (-400, 400), **fixed}

        def sampled(loci: bool, fixed: dict = fixed, axes: dict = axes) -> object:
            return grid_map(quattro, "verdict", fixed=fixed, angles="deg", loci=loci, **axes)

        def proof(region: dict = region) -> object:
            return certify(quattro, region, resolution=0.8, angles="deg")

        plain = best_of(args.repeats, lambda: sampled(False), clock)
        with_loci = best_of(args.repeats, lambda: sampled(True), clock)
        result = proof()
        proved = best_of(args.repeats, proof, clock)
        print(f"phi = {phi:g} deg: map 200x200 {plain:.2f} s (with loci {with_loci:.2f} s); certify 1/1000 "
              f"{proved:.2f} s = {proved / plain:.1f}x the map ({result.evaluated} boxes; "
              + ", ".join(f"{k} {v:.2%}" for k, v in result.fractions.items()) + ")")
    for phi in (0.0, 45.0):
        region = {"x": (-400, 400), "y": (-400, 400), "z": (-900, -600), "phi": phi}
        start = clock()
        result = certify(quattro, region, resolution={"x": 8, "y": 8, "z": 3}, angles="deg")
        print(f"certify 3-D (x, y, z at phi = {phi:g} deg, 1/100): {clock() - start:.1f} s, "
              f"{result.evaluated} boxes; " + ", ".join(f"{k} {v:.2%}" for k, v in result.fractions.items()))
    delta = sk.load_mechanism("delta")
    for region, resolution in (
        ({"x": (900, 1200), "y": (-60, 60), "z": -1000}, 0.3),
        ({"x": (-300, 300), "y": (-300, 300), "z": (-1150, -850)}, {"x": 6, "y": 6, "z": 3}),
    ):
        start = clock()
        result = certify(delta, region, resolution=resolution)
        print(f"Delta {region}: {clock() - start:.2f} s, {result.evaluated} boxes; "
              + ", ".join(f"{k} {v:.2%}" for k, v in result.fractions.items()))
    model = FourLimbModel.of(quattro)
    count = 100_000
    poses = np.asarray(quattro.random_poses(np.random.default_rng(0), count))
    points = Enclosure.variables(poses, poses, gradient=False)
    floats = best_of(3, lambda: model.values(poses), clock)
    intervals = best_of(3, lambda: model.evaluate(points), clock)
    matrices = np.random.default_rng(1).normal(size=(count, 6, 6))
    svd = best_of(3, lambda: np.linalg.svd(matrices, compute_uv=False), clock)
    print(f"batched 6x6 SVD {count / svd:,.0f} poses/s; conditions at poses (kinematics included) in "
          f"floats {count / floats:,.0f} poses/s (ratio {svd / floats:.2f}), as intervals "
          f"{count / intervals:,.0f} poses/s (ratio {svd / intervals:.2f})")
    coverage(clock, svd / count)


#: Per family: a slice through a singular surface and a box of its workspace, with resolutions.
COVERAGE = {
    "veloce": (({"x": (300, 560), "y": -545.2, "z": (-300, -200), "phi": -1.8}, 1.0),
               ({"x": (-400, 400), "y": (-400, 400), "z": (-900, -600), "phi": (-2 * np.pi, 2 * np.pi)},
                {"x": 20, "y": 20, "z": 20, "phi": 0.5})),
    "mcgill_smg": (({"x": (-300, 300), "y": (-300, 300), "z": -800, "phi": 0.3}, 2.0),
                   ({"x": (-100, 100), "y": (-150, 150), "z": (-850, -750), "phi": (-np.pi / 4, np.pi / 4)},
                    {"x": 10, "y": 10, "z": 10, "phi": 0.05})),
    "peppermill": (({"x": 30, "y": (-600, 600), "z": (-700, 0), "phi": 0.5}, 2.0),
                   ({"x": (-150, 150), "y": (-150, 150), "z": (-500, -400), "phi": (-2 * np.pi, 2 * np.pi)},
                    {"x": 10, "y": 10, "z": 10, "phi": 0.1})),
}


def coverage(clock: object, svd_per_pose: float) -> None:
    """The Veloce, the McGill SMG and the Peppermill (module docstring)."""
    for name, cases in COVERAGE.items():
        mechanism = sk.load_mechanism(name)
        for region, resolution in cases:
            start = clock()  # type: ignore[operator]
            result = certify(mechanism, region, resolution=resolution)
            labels = sorted({b.witness.label for b in result.boxes if b.witness is not None})
            print(f"{mechanism.name} {region}: {clock() - start:.2f} s, {result.evaluated} boxes; "  # type: ignore[operator]
                  + ", ".join(f"{k} {v:.2%}" for k, v in result.fractions.items()) + f"; met {labels}")
        box = cases[1][0]
        low = np.array([box[n][0] for n in mechanism.pose_names])
        high = np.array([box[n][1] for n in mechanism.pose_names])
        poses = low + np.random.default_rng(2).uniform(size=(100_000, 4)) * (high - low)
        model = model_of(mechanism)
        floats = best_of(3, lambda model=model, poses=poses: model.values(poses), clock)
        print(f"{mechanism.name} conditions in floats {len(poses) / floats:,.0f} poses/s "
              f"(ratio to the 6x6 SVD {svd_per_pose * len(poses) / floats:.2f})")


if __name__ == "__main__":
    main()
