"""Speed of the family protocol's conformance checks and of the Delta's batched analysis.

Run: python bench/bench_families.py  (prints figures for the docs; not a test). The Delta is read from
this checkout's mechanisms/ folder (an editable install may map the catalog elsewhere).
"""

from pathlib import Path

import numpy as np
from _timing import best_of

from screwkit.robots.catalog import list_mechanisms, load_mechanism
from screwkit.testing import check_family

DELTA = Path(__file__).resolve().parents[1] / "mechanisms" / "delta.toml"


def main():
    robots = {robot.name: robot for robot in [*map(load_mechanism, list_mechanisms()), load_mechanism(DELTA)]}
    for robot in robots.values():
        seconds = best_of(3, lambda robot=robot: check_family(robot, samples=8))
        print(f"check_family, {robot.name:<13} (9 poses, 5 checks): {seconds:.3f} s")
    for robot in (load_mechanism(DELTA), load_mechanism("h4")):
        poses = robot.random_poses(np.random.default_rng(0), 10_000)
        ik = best_of(3, lambda robot=robot, poses=poses: robot.configuration(poses))
        verdicts = best_of(3, lambda robot=robot, poses=poses: robot.at(poses).verdicts)
        print(
            f"{robot.name:<5} 10,000 poses: IK {10_000 / ik:,.0f} poses/s, "
            f"IK + joints + verdicts {10_000 / verdicts:,.0f} poses/s"
        )


if __name__ == "__main__":
    main()
