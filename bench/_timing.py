"""Timing helper shared by the bench scripts (run as ``python bench/NAME.py``)."""

import statistics
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


def interleaved_medians(repeats, functions, clock=time.perf_counter):
    """The median time of each of ``functions`` over ``repeats`` rounds, each round calling every
    function once in turn (so that a change of load on a shared machine weighs on all alike), in
    seconds; with ``clock=time.process_time`` this process's CPU time."""
    times = [[] for _ in functions]
    for _ in range(repeats):
        for function, spent in zip(functions, times, strict=True):
            start = clock()
            function()
            spent.append(clock() - start)
    return [statistics.median(spent) for spent in times]
