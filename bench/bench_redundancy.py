"""Time redundant actuation and point tasks (issue 20 item 1, issue 21 item 7, issue 19's point task).

Run: ``python bench/bench_redundancy.py`` from the repository root. Not a test. Prints, CPU time:

* the ``dof`` check of a 7-UPS (one ``classify``: the generic mobility and the driven-freedoms run
  that redundant actuation adds) against the 6-UPS of the same six legs;
* verdict maps over 4,000 poses (loop closure, verdicts, closeness) of the planar five-bar with a
  third actuated leg against the two-leg five-bar, and of the five-bar with its end point as the task;
* the conditions of the redundant five-bar (its six-line subsets' superbrackets, one pose).
"""

import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from _timing import best_of

import screwkit as sk
from screwkit.core.singularity import classify
from tests.core.test_redundancy import circle, elbow, five_bar, ups_legs

A1, A2, A3 = np.zeros(3), np.array([1.0, 0, 0]), np.array([0.5, -0.5, 0])


def main() -> None:
    print(f"load average {os.getloadavg()[0]:.1f}")
    rng = np.random.default_rng(7)
    bases = circle(1.0, np.sort(rng.uniform(0, 2 * np.pi, 7)), 0.0)
    tops = circle(0.6, np.sort(rng.uniform(0, 2 * np.pi, 7)), 1.0) + rng.normal(0, 0.05, (7, 3))
    for name, graph in (("7-UPS", ups_legs(bases, tops)), ("6-UPS", ups_legs(bases[:6], tops[:6]))):
        seconds = best_of(3, lambda graph=graph: classify(graph), clock=time.process_time)
        print(f"classify (dof check included) {name}: {seconds * 1e3:.0f} ms")
    c = np.array([0.5, 1.5, 0.0])
    legs = [(A1, elbow(A1, c, 1)), (A2, elbow(A2, c, -1)), (A3, elbow(A3, c, 1))]
    mechanisms = {
        "five-bar, 3 actuated legs": sk.mechanism(five_bar(c, legs)),
        "five-bar, 2 legs": sk.mechanism(five_bar(c, legs[:2])),
        "five-bar, end point as task": sk.mechanism(five_bar(c, legs[:2]), task=("d1", c)),
    }
    for name, m in mechanisms.items():
        span = np.array([0.1, 0.1]) if "task" in name else np.array([0.1, 0.05])
        poses = m.reference_pose + rng.uniform(-1, 1, (4000, 2)) * span
        _ = m.at(m.reference_pose + rng.uniform(-1, 1, (1000, 2)) * span).verdicts  # compiling out

        def verdicts(m=m, poses=poses):
            posed = m.at(poses)
            return posed.verdicts, posed.closeness["actuation"]

        seconds = best_of(1, verdicts, clock=time.process_time)  # once: the kinematics cache the poses
        print(f"map of 4,000 poses, {name}: {4000 / seconds:,.0f} poses/s")
    one = mechanisms["five-bar, 3 actuated legs"].at()[0]
    start = time.process_time()
    result = one.superbracket
    print(f"conditions of the redundant five-bar ({len(result.subsets)} six-line subsets): "
          f"{time.process_time() - start:.2f} s (with the diagram and generic samples)")


if __name__ == "__main__":
    main()
