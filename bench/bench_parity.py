"""Parity of the single-pose and batched answers on the issue's >= 10,000 H4 poses (not a test run).

Runs ``tests/core/test_parity.py`` with ``SCREWKIT_PARITY=full``: 10,060 poses (generic workspace poses,
the roots of the constraint, actuation and reach-edge surfaces, and poses at relative distances
1e-12 ... 1e-4 on both sides), one ``classify(graph)`` call per pose against ``h4.at(poses)``, and
the verdicts against 50-digit references. Prints pytest's summary and the wall time.

Run: python bench/bench_parity.py
"""

import os
import subprocess
import sys
import time
from pathlib import Path


def main():
    root = Path(__file__).resolve().parent.parent
    start = time.perf_counter()
    result = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests/core/test_parity.py"],
        cwd=root,
        env={**os.environ, "SCREWKIT_PARITY": "full"},
        capture_output=True,
        text=True,
        check=False,
    )
    print(result.stdout.strip().splitlines()[-1])
    print(f"wall time {time.perf_counter() - start:.0f} s")
    return result.returncode


if __name__ == "__main__":
    sys.exit(main())
