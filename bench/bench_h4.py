"""Speed of the H4 analysis: one pose at a time (readable screw systems) and batched (vectorized).

Run: python bench/bench_h4.py  (prints figures for the README; not a test).
"""


import numpy as np
from _timing import best_of

from screwkit.core.singularity import classify, classify_table
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.four_limb.joints import joints
from screwkit.robots.families.four_limb.kinematics import reachable


def main():
    h4 = load_mechanism("h4")
    rng = np.random.default_rng(0)
    low, high = zip(*(h4.workspace[c] for c in h4.pose_names), strict=True)
    poses = rng.uniform(low, high, size=(12000, 4))
    poses = poses[reachable(h4.parameters, poses)][:10000]

    single = best_of(3, lambda: classify(h4.twist_graph(poses[0])))
    print(
        f"one pose (IK + twist graph + wrench systems + labels): {single * 1e3:.1f} ms, "
        f"{1 / single:.0f} analyses/s"
    )
    for count in (100, 1000, 10000):
        chosen = poses[:count]

        def run(chosen=chosen):
            return classify_table(h4.joints(chosen))

        seconds = best_of(3, run)
        rate = count / seconds
        print(f"batched, {count:>5} poses (IK + screws + labels): {seconds:.3f} s, {rate:,.0f} poses/s")
    graph_only = best_of(3, lambda: joints(h4.configuration(poses[0])).graph())
    print(f"building one twist graph: {graph_only * 1e3:.2f} ms")


if __name__ == "__main__":
    main()
