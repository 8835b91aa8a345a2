"""Benchmarks: speed measured side by side in one run and reported as ratios.

``python -m engine.bench`` runs every topic; ``python -m engine.bench core --quick``
runs one, briefly. Each topic is a module here with ``report(quick) -> str``. No test
asserts a time: machines are shared and noisy, so the numbers that matter are ratios
of things measured in the same run, round by round, as medians.
"""

from __future__ import annotations

import statistics
import timeit
from collections.abc import Callable

__all__ = ["TOPICS", "compare"]

#: Topic name -> module under engine.bench, in the order they run.
TOPICS: dict[str, str] = {
    "core": "engine.bench.core",
    "particles": "engine.bench.particles",
    "render": "engine.bench.render",
    "throughput": "engine.bench.throughput",
}


def compare(
    candidates: dict[str, tuple[Callable[[], object], int]], *, rounds: int
) -> dict[str, float]:
    """Median seconds per call of each candidate ``name -> (fn, calls per round)``.

    Each round times every candidate once, so a burst of load on a shared machine hits
    all of them alike instead of one; the median over ``rounds`` rounds then ignores the
    rounds a burst spoiled.
    """
    samples: dict[str, list[float]] = {name: [] for name in candidates}
    for fn, _ in candidates.values():
        fn()  # warm up: first-call costs (allocation, caches) are not the steady state
    for _ in range(rounds):
        for name, (fn, number) in candidates.items():
            samples[name].append(timeit.timeit(fn, number=number) / number)
    return {name: statistics.median(times) for name, times in samples.items()}
