"""Timing helper shared by the bench scripts (run as ``python bench/NAME.py``)."""

import time


def best_of(repeats, function):
    """The shortest wall time of ``repeats`` calls of ``function()``, in seconds."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)
