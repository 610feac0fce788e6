"""Speed and memory of the batched H4 verdicts against one batched SVD, and the cost of ``import``.

Run: ``python bench/bench_core.py [--sizes 1000 10000 100000 1000000] [--repeats 21]`` from the
repository root (prints a table; not a test). Every figure is single-threaded: the BLAS/OpenMP
thread counts are set to 1 before numpy is imported, and the rates are this process's CPU time
(``time.process_time``, the best of 3 runs up to 10⁵ poses, one run beyond, the same for the
SVD baseline and for ours), which is the wall time on an idle machine and,
unlike it, is not inflated by other processes on a shared one.

Figures (the issue's targets in brackets):

* ``svd``: one batched ``np.linalg.svd(W, compute_uv=False)`` of the same poses' 6×6 global wrench
  matrices ``W`` (paper 002 Eq. 4: the two constraint couples ``z × s12``, ``z × s34`` and the four
  actuation forces along ``w_i`` through the points where they meet the vertical axes, built here
  vectorised as ``tests/test_h4.paper_wrench_matrix`` does for one pose; building ``W`` is not
  timed), in poses/s;
* ``verdicts``: :func:`verdicts` over the same poses, chunked (``CHUNK`` poses per call), rate and
  the ratio to the SVD's rate [≥ 0.2]. The labels and orders only: the closeness measures are
  computed when asked (:attr:`screwkit.core.wrench_systems.WrenchAnalysis.closeness`), so ``+ closeness``
  gives the rate and ratio of :func:`verdicts` with the report's ``closeness`` asked too;
* memory: ``tracemalloc`` peak of one chunk's :func:`verdicts` / ``CHUNK``, KiB per pose [≤ 3];
* with ``--breakdown``: where a pose's time goes (:func:`breakdown`, 10⁴ poses in the core's own
  chunks of ``screwkit.robots.posed.CHUNK``, CPU time, best of 7);
* import: CPU time (user + sys of the child, ``resource.getrusage(RUSAGE_CHILDREN)`` deltas) of
  ``python -c "import screwkit"`` against ``python -c "import numpy, networkx"`` in fresh
  subprocesses run in turn, each from its bytecode cache (:func:`child_cpu`), min and median over
  the repeats, ratio of the medians [≤ 1.2].
"""

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
              "VECLIB_MAXIMUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ[_name] = "1"

import argparse  # noqa: E402
import resource  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402

import numpy as np  # noqa: E402
from _timing import best_of  # noqa: E402  (bench/ is the script folder)

import screwkit as sk  # noqa: E402
from screwkit.core import _closing, _program, _wrench_pass, wrench_systems  # noqa: E402
from screwkit.robots import posed  # noqa: E402
from screwkit.robots.families.four_limb.joints import PAPER_002_LEGS  # noqa: E402
from screwkit.robots.families.four_limb.kinematics import reachable  # noqa: E402

CHUNK = 10_000


def verdicts(h4, poses):
    """The batched verdicts of the H4 at ``poses`` (n, 4): IK, joint table and the analysis core
    (chunked inside), through the one composer."""
    return h4.at(poses).singularities


def verdicts_and_closeness(h4, poses):
    """:func:`verdicts` with the closeness measures (two 6×6 SVDs a pose) asked as well."""
    report = verdicts(h4, poses)
    return report, report.closeness


def wrench_matrices(h4, poses):
    """The paper's six wrenches (rows) at every pose, ``(n, 6, 6)`` (paper 002 Eq. 4)."""
    cfg = h4.configuration(poses)
    z = np.array([0.0, 0.0, 1.0])
    normals = np.cross(cfg.u, cfg.w)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    leg = {k: v - 1 for k, v in PAPER_002_LEGS.items()}
    s12 = np.cross(normals[:, leg["l1"]], normals[:, leg["l2"]])
    s34 = np.cross(normals[:, leg["l3"]], normals[:, leg["l4"]])
    rows = [np.concatenate([np.zeros_like(s), np.cross(z, s)], axis=-1) for s in (s12, s34)]
    axis_of = {1: 0, 4: 0, 2: 1, 3: 1}  # limb -> the vertical axis (Z_I, Z_II) its force meets
    for paper_leg in ("l1", "l2", "l3", "l4"):
        limb = PAPER_002_LEGS[paper_leg] - 1
        point = cfg.platform_joint_points[:, axis_of[limb + 1]]
        n = normals[:, limb]
        t = np.einsum("ni,ni->n", n, cfg.b[:, limb] - point) / n[:, 2]
        point = point + t[:, None] * z
        direction = cfg.w[:, limb]
        rows.append(np.concatenate([direction, np.cross(point, direction)], axis=-1))
    return np.stack(rows, axis=-2)


def workspace_poses(h4, count, seed=0):
    rng = np.random.default_rng(seed)
    chosen = []
    while sum(len(c) for c in chosen) < count:
        poses = h4.random_poses(rng, min(count, 10**6) + 1000)
        chosen.append(poses[reachable(h4.parameters, poses)])
    return np.concatenate(chosen)[:count]


def chunked(function, poses):
    for begin in range(0, len(poses), CHUNK):
        function(poses[begin : begin + CHUNK])


def breakdown(h4, poses, repeats=7):
    """CPU µs per pose of each stage of :func:`verdicts` over ``poses``, in the core's chunks: the
    inverse kinematics, the joint table, the analysis core (``wrench_systems.analyze_table``) and inside
    it the reference frame with the unit scaled screws (``reference_frame.scaled_frame``), the compiled
    program of series-parallel frames (``_program.run_program``) and the closing pass (global span,
    closeness triangles, user-frame rows: ``_closing.closing``), the rest of the core (limb
    systems, leg residuals, compound-leg checks, numpy glue) and of :func:`verdicts` (copying the
    chunks' results into the batch's arrays, the report). The inner stages are timed by wrapping
    those functions for the run (the wrappers' own cost is in the figures)."""
    protocol, chunk = h4.family_protocol, posed.CHUNK
    wrapped = {
        "frame": (_wrench_pass, "scaled_frame"),
        "program": (_program, "run_program"),
        "closing": (_closing, "closing"),
    }
    spent = dict.fromkeys(["ik", "joints", "core", "whole", *wrapped], 0.0)

    def timed(label, function):
        def run(*args, **kwargs):
            start = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[label] += time.process_time() - start
        return run

    originals = {label: getattr(module, name) for label, (module, name) in wrapped.items()}
    best = dict.fromkeys(spent, float("inf"))
    for _ in range(repeats):  # each figure the best of the repeats
        for key in spent:
            spent[key] = 0.0
        timed("whole", verdicts)(h4, poses)
        try:
            for label, (module, name) in wrapped.items():
                setattr(module, name, timed(label, originals[label]))
            for begin in range(0, len(poses), chunk):
                part = poses[begin : begin + chunk]
                configuration = timed("ik", h4.configuration)(part)
                table = timed("joints", protocol.joint_table)(configuration)
                timed("core", wrench_systems.analyze_table)(table, views=False)
        finally:
            for label, (module, name) in wrapped.items():
                setattr(module, name, originals[label])
        best = {key: min(best[key], spent[key]) for key in spent}
    per_pose = {key: value / len(poses) * 1e6 for key, value in best.items()}
    per_pose["core, other"] = per_pose["core"] - per_pose["frame"] - per_pose["program"] - per_pose["closing"]
    per_pose["verdicts, other"] = per_pose["whole"] - per_pose["ik"] - per_pose["joints"] - per_pose["core"]
    return per_pose


def child_cpu(codes, repeats):
    """User + sys CPU seconds of fresh ``python -c code`` processes, one list per code (the codes
    run in turn, repeat by repeat, so that load drifting over the run hits each alike).

    Every code runs once first, unmeasured, with bytecode writing allowed: screwkit is then timed
    from its ``__pycache__`` as numpy and networkx are from theirs (``pip install`` compiles them;
    with ``PYTHONDONTWRITEBYTECODE`` set, an editable checkout would be recompiled on every import).
    """
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    for code in codes:
        subprocess.run([sys.executable, "-c", code], check=True, env=env)
    figures = [[] for _ in codes]
    for _ in range(repeats):
        for code, figure in zip(codes, figures, strict=True):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([sys.executable, "-c", code], check=True, env=env)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            figure.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return figures


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[10**3, 10**4, 10**5, 10**6])
    parser.add_argument("--repeats", type=int, default=21, help="import-time subprocesses per command")
    parser.add_argument("--breakdown", action="store_true", help="where a pose's time goes (10^4 poses)")
    args = parser.parse_args(argv)
    h4 = sk.load_mechanism("h4")
    poses = workspace_poses(h4, max(args.sizes))
    verdicts(h4, poses[:100])  # warm caches (template graph, imports) outside the timings

    print(f"H4, poses in the catalog workspace, single-threaded; chunks of {CHUNK:,} poses")
    print(
        f"{'N':>9} | {'svd (poses/s)':>14} | {'verdicts (poses/s)':>18} | {'ratio':>6} | seconds | "
        f"{'+ closeness (poses/s)':>21} | {'ratio':>6}"
    )
    for count in args.sizes:
        chosen = poses[:count]
        matrices = np.concatenate(
            [wrench_matrices(h4, chosen[b : b + CHUNK]) for b in range(0, count, CHUNK)]
        )
        repeats = 3 if count <= 10**5 else 1  # the same for the baseline and for ours
        svd = best_of(
            repeats,
            lambda m=matrices: np.linalg.svd(m, compute_uv=False),
            clock=time.process_time,
        )
        ours = best_of(
            repeats,
            lambda c=chosen: chunked(lambda p: verdicts(h4, p), c),
            clock=time.process_time,
        )
        both = best_of(
            repeats,
            lambda c=chosen: chunked(lambda p: verdicts_and_closeness(h4, p), c),
            clock=time.process_time,
        )
        print(
            f"{count:>9,} | {count / svd:>14,.0f} | {count / ours:>18,.0f} | {svd / ours:>6.4f} | "
            f"{ours:7.2f} | {count / both:>21,.0f} | {svd / both:>6.4f}"
        )

    chunk = poses[:CHUNK]
    tracemalloc.start()
    verdicts(h4, chunk)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    per_pose = peak / len(chunk) / 1024
    print(f"memory: tracemalloc peak of one chunk / {len(chunk):,} poses = {per_pose:.2f} KiB/pose")
    if args.breakdown:
        count = min(10**4, len(poses))
        figures = breakdown(h4, poses[:count])
        print(f"breakdown (CPU µs per pose, {count:,} poses in chunks of {posed.CHUNK}, best of 7):")
        for label in ("whole", "ik", "joints", "core", "frame", "program", "closing", "core, other",
                      "verdicts, other"):
            print(f"  {label:16s} {figures[label]:6.2f}")

    ours, base, bare = child_cpu(["import screwkit", "import numpy, networkx", "pass"], args.repeats)
    print(f"import CPU (user+sys, {args.repeats} fresh processes; min / median):")
    rows = (("import screwkit", ours), ("import numpy, networkx", base), ("python -c pass", bare))
    for label, figures in rows:
        print(f"  {label:24s} {min(figures) * 1e3:7.1f} / {statistics.median(figures) * 1e3:7.1f} ms")
    print(f"  ratio screwkit / (numpy, networkx): min {min(ours) / min(base):.2f}, "
          f"median {statistics.median(ours) / statistics.median(base):.2f}")


if __name__ == "__main__":
    main()
