"""Timing helper shared by the bench scripts (run as ``python bench/NAME.py``)."""

import time


def best_of(repeats, function, clock=time.perf_counter):
    """The shortest time of ``repeats`` calls of ``function()``, in seconds: wall time, or with
    ``clock=time.process_time`` this process's CPU time (for single-threaded work on a loaded
    machine: the time the work itself took, not the time it waited)."""
    times = []
    for _ in range(repeats):
        start = clock()
        function()
        times.append(clock() - start)
    return min(times)
