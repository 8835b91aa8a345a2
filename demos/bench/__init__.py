"""Benchmarks: speed measured side by side in one run and reported as ratios.

``python -m demos.bench`` runs every topic; ``python -m demos.bench core --quick``
runs one, briefly. Each topic is a module here with ``report(quick) -> str``; a topic that
draws pictures (``pit``, ``stack``) takes ``out`` too, the folder it writes them into
(``out/bench``, or ``--out DIR``; files of the same name there are replaced). No test
asserts a time: machines are shared and noisy, so the numbers that matter are ratios
of things measured in the same run, round by round, as medians.

They live under ``demos/``, above both the engine and the demos, because some of them time a
demo (a fireworks frame): nothing under ``engine/`` imports ``demos/``. The tradeoff demo
draws the throughput and solver topics' measurements as charts.
"""

from __future__ import annotations

import statistics
import timeit
from collections.abc import Callable

__all__ = ["TOPICS", "compare"]

#: Topic name -> module under demos.bench, in the order they run.
TOPICS: dict[str, str] = {
    "core": "demos.bench.core",
    "particles": "demos.bench.particles",
    "render": "demos.bench.render",
    "throughput": "demos.bench.throughput",
    "contacts": "demos.bench.contacts",
    "pit": "demos.bench.pit",
    "board": "demos.bench.board",
    "limits": "demos.bench.limits",
    "before": "demos.bench.before",
    "solver": "demos.bench.solver",
    "pendulum": "demos.bench.pendulum",
    "kernels": "demos.bench.kernels",
    "pinball": "demos.bench.pinball",
    "stack": "demos.bench.stack",
    "tumbler": "demos.bench.tumbler",
    "platformer": "demos.bench.platformer",
    "queries": "demos.bench.queries",
    "soft": "demos.bench.soft",
    "lanes": "demos.bench.lanes",
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
