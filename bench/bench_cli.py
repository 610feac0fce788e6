"""Wall and CPU time of ``screwkit analyze NAME`` for every catalog robot against importing its dependencies.

Run: ``python bench/bench_cli.py [--repeats 5] [--robot NAME ...]`` from the repository root (prints
a table; not a test). Each command runs in a fresh subprocess with ``OPENBLAS_NUM_THREADS=1`` (and
the other thread counts) set and ``PYTHONDONTWRITEBYTECODE`` unset, so both sides read their
bytecode caches (an editable checkout otherwise recompiles screwkit in every process); one
unmeasured run of each command comes first. The repeats are interleaved (reference, then every
robot, ``--repeats`` times), so a change of load on a shared machine hits both sides alike.

The installed command runs :func:`screwkit.interface.cli.console`, which freezes the objects left for the exit
(the collector's passes over numpy's, sympy's and networkx's objects at shutdown, ≈ 0.1–0.15 s, are
skipped); ``--source`` runs ``main`` and exits as Python does, so the two show what that saves. A
console script generated before the entry point became ``screwkit.interface.cli:console`` still calls
``main``: the header then says to reinstall.

Per robot: the minimum and median wall time, the median CPU time (user + system of the child),
and the ratios of the minima and of the medians to those of the reference
``python -c "import numpy, networkx, sympy"`` in the same run. The issue's target is a ratio
≤ 1.5 per robot. The command is the installed console script ``screwkit`` next to this
interpreter if there is one, else ``python -m screwkit``; with ``--source DIR``, the checkout at
``DIR`` run by this interpreter (an editable install's import hook set aside), to compare two
versions in one run. The load average is printed before and after.
"""

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
           "VECLIB_MAXIMUM_THREADS", "BLIS_NUM_THREADS")
REFERENCE = "import numpy, networkx, sympy"


def environment():
    env = os.environ.copy()
    env.update(dict.fromkeys(THREADS, "1"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


#: Runs ``screwkit.interface.cli.main`` from the checkout given as the first argument, ahead of any install
#: (the catalog folder ``mechanisms/`` of the checkout serves as ``screwkit.mechanisms``).
LAUNCHER = (
    "import sys; sys.meta_path[:] = [f for f in sys.meta_path if 'editable' not in repr(f)]; "
    "root = sys.argv.pop(1); sys.path.insert(0, root); import screwkit; screwkit.__path__.append(root); "
    "from screwkit.interface.cli import main; sys.exit(main(sys.argv[1:]))"
)


def command(source=None):
    if source is not None:
        return [sys.executable, "-c", LAUNCHER, str(Path(source).resolve())]
    script = Path(sys.executable).with_name("screwkit")
    if script.exists():
        return [str(script)]
    found = shutil.which("screwkit")
    return [found] if found else [sys.executable, "-m", "screwkit"]


def stale(cli):
    """True if ``cli`` is a console script generated for the old entry point (``main``, not ``console``)."""
    script = Path(cli[0])
    return len(cli) == 1 and script.is_file() and "console" not in script.read_text(errors="replace")


def timed(arguments):
    """(wall, cpu) seconds of one fresh process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(arguments, check=True, env=environment(), stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def load():
    return "load average " + ", ".join(f"{x:.2f}" for x in os.getloadavg())


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--robot", action="append", default=None, metavar="NAME",
                        help="a catalog name; repeat for several (default: every catalog robot)")
    parser.add_argument("--source", default=None, metavar="DIR",
                        help="run the screwkit checkout at DIR instead of the installed command")
    args = parser.parse_args(argv)
    cli = command(args.source)
    listing = subprocess.run([*cli, "list"], check=True, env=environment(), capture_output=True, text=True)
    names = args.robot or [line.split()[0] for line in listing.stdout.splitlines() if line.strip()]
    jobs = {"reference": [sys.executable, "-c", REFERENCE]} | {n: [*cli, "analyze", n] for n in names}
    print(f"command: {' '.join(cli)} analyze NAME; {args.repeats} interleaved fresh processes each, "
          f"single-threaded BLAS; {load()}")
    if stale(cli):
        print("note: this console script calls screwkit.interface.cli:main (generated before the "
              "console entry "
              "point): reinstall (pip install -e .) to time the command as shipped")
    for arguments in jobs.values():  # bytecode caches written, files in the page cache
        timed(arguments)
    runs = {name: [] for name in jobs}
    for _ in range(args.repeats):
        for name, arguments in jobs.items():
            runs[name].append(timed(arguments))

    def summary(name):
        walls, cpus = [w for w, _ in runs[name]], [c for _, c in runs[name]]
        return min(walls), statistics.median(walls), statistics.median(cpus)

    ref_min, ref_median, ref_cpu = summary("reference")
    print(f"reference: python -c '{REFERENCE}'  wall min {ref_min:.3f} s, median {ref_median:.3f} s; "
          f"CPU median {ref_cpu:.3f} s")
    print(f"{'robot':12s} | {'wall min':>8} | {'wall med':>8} | {'CPU med':>7} | {'ratio min':>9} | "
          f"{'ratio med':>9} | {'ratio CPU':>9}")
    for name in names:
        low, median, cpu = summary(name)
        print(f"{name:12s} | {low:8.3f} | {median:8.3f} | {cpu:7.3f} | {low / ref_min:9.2f} | "
              f"{median / ref_median:9.2f} | {cpu / ref_cpu:9.2f}")
    print(load())


if __name__ == "__main__":
    main()
