"""Wall time of ``screwkit analyze NAME`` for every catalog robot against importing its dependencies.

Run: ``python bench/bench_cli.py [--repeats 3]`` from the repository root (prints a table; not a
test). Each command runs in a fresh subprocess with ``OPENBLAS_NUM_THREADS=1`` (and the other
thread counts) set; the figure is the best of the repeats. The reference is
``python -c "import numpy, networkx, sympy"``; the issue's target is a ratio ≤ 1.5 per robot.
The command is the installed console script ``screwkit`` next to this interpreter if there is
one, else ``python -m screwkit``.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
           "VECLIB_MAXIMUM_THREADS", "BLIS_NUM_THREADS")


def environment():
    env = os.environ.copy()
    env.update(dict.fromkeys(THREADS, "1"))
    return env


def command():
    script = Path(sys.executable).with_name("screwkit")
    if script.exists():
        return [str(script)]
    found = shutil.which("screwkit")
    return [found] if found else [sys.executable, "-m", "screwkit"]


def best_wall(arguments, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(arguments, check=True, env=environment(), stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return min(times)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    cli = command()
    listing = subprocess.run([*cli, "list"], check=True, env=environment(), capture_output=True, text=True)
    names = [line.split()[0] for line in listing.stdout.splitlines() if line.strip()]
    reference = best_wall([sys.executable, "-c", "import numpy, networkx, sympy"], args.repeats)
    print(f"command: {' '.join(cli)} analyze NAME; best of {args.repeats}, single-threaded BLAS")
    print(f"reference: python -c 'import numpy, networkx, sympy'  {reference:.3f} s")
    print(f"{'robot':12s} | {'analyze (s)':>11} | ratio")
    for name in names:
        seconds = best_wall([*cli, "analyze", name], args.repeats)
        print(f"{name:12s} | {seconds:>11.3f} | {seconds / reference:5.2f}")


if __name__ == "__main__":
    main()
