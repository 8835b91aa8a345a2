"""Benchmark: the particle step at 100,000 sparks against the floor of numpy memory traffic.

The floor is one in-place ``np.add(x, y, out=x)`` where x and y are float64 arrays as large
as the positions and velocities together (4 N numbers each): the least an update of both can
cost in numpy. The step is :meth:`engine.particles.Particles.step` under gravity and a wind
(drag toward the air's velocity), timed side by side with the floor in the same run, in
alternating rounds so that both see the same machine. Target: step / floor <= 1.5.

It also times a whole fireworks frame at 60 fps (two physics steps of 1/120 s and the numpy
drawing of ``demos/fireworks.py`` at 640x360) at two spark counts, fits time = a + b N, and
reports how many sparks fit in 1/60 s.

    python -c "from demos.bench.particles import report; print(report())"
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable

import numpy as np

from engine.forces import Gravity, Wind
from engine.particles import Particles

__all__ = ["report", "step_ratio", "frame_budget"]

SPARKS = 100_000
FRAME = 1.0 / 60.0


def _per_call(fn: Callable[[], object], calls: int) -> float:
    """Seconds per call of ``fn`` over ``calls`` calls."""
    start = time.perf_counter()
    for _ in range(calls):
        fn()
    return (time.perf_counter() - start) / calls


def _sparks(n: int, fast: bool = True) -> Particles:
    rng = np.random.default_rng(0)
    p = Particles(
        n,
        dt=1.0 / 120.0,
        forces=[Gravity((0.0, -9.81)), Wind((2.0, 0.0), 0.006)],
        mass=0.01,
        fast_path=fast,
    )
    p.emit(n, rng.uniform(-30, 30, (n, 2)), rng.normal(0, 8, (n, 2)))  # lifetime inf
    return p


def step_ratio(n: int = SPARKS, rounds: int = 15, calls: int = 50) -> dict[str, float]:
    """Median seconds per step (fast, general path) and per floor add, and their ratios."""
    x = np.random.default_rng(1).random(4 * n)
    y = np.random.default_rng(2).random(4 * n)
    fast, general = _sparks(n), _sparks(n, fast=False)
    assert fast.uses_fast_path and not general.uses_fast_path
    floor_t, fast_t, general_t = [], [], []
    for _ in range(rounds):  # alternate, so that drifts in the machine hit all three alike
        floor_t.append(_per_call(lambda: np.add(x, y, out=x), calls))
        fast_t.append(_per_call(fast.step, calls))
        general_t.append(_per_call(general.step, max(1, calls // 5)))
        x[:] = 0.5  # keep the floor's numbers from growing without bound
    # The ratio is taken round by round (floor and step timed back to back), then the median:
    # a burst of load from another process spoils one round, not the answer.
    return {
        "floor": statistics.median(floor_t),
        "fast": statistics.median(fast_t),
        "general": statistics.median(general_t),
        "fast_ratio": statistics.median(f / b for f, b in zip(fast_t, floor_t, strict=True)),
        "general_ratio": statistics.median(g / b for g, b in zip(general_t, floor_t, strict=True)),
    }


def frame_budget(counts: tuple[int, int] = (2_000, 40_000), frames: int = 20) -> dict[str, float]:
    """Seconds per 60 fps fireworks frame (2 steps + draw) at two spark counts, and the fit."""
    import pygame

    from demos.fireworks import KINDS, FireworksScene
    from engine.render import init_headless

    init_headless()
    surface = pygame.Surface((640, 360))
    times = []
    for n in counts:
        scene = FireworksScene()
        scene.capacity = n + 100
        scene.interval = (1e9, 1e9)  # no launches: time exactly n sparks
        scene.build((640, 360))
        rng = np.random.default_rng(3)
        p = scene.particles
        p.clear()
        stars = [i for i, k in enumerate(KINDS) if k.launch is None and not k.payload]
        p.emit(
            n,
            np.column_stack((rng.uniform(-35, 35, n), rng.uniform(5, 40, n))),
            rng.normal(0, 6, (n, 2)),
            lifetime=1e6,
            kind=rng.choice(stars, n),
        )

        def frame(scene: FireworksScene = scene) -> None:
            scene.step(scene.dt)
            scene.step(scene.dt)
            scene.draw(surface, 0.5)

        frame()
        times.append(min(_per_call(frame, frames // 4) for _ in range(4)))
    (n1, n2), (t1, t2) = counts, times
    per_spark = (t2 - t1) / (n2 - n1)
    fixed = t1 - per_spark * n1
    return {
        "n1": n1,
        "t1": t1,
        "n2": n2,
        "t2": t2,
        "per_spark": per_spark,
        "fixed": fixed,
        "max_sparks": (FRAME - fixed) / per_spark,
    }


def report(quick: bool = False) -> str:
    """Run the particle benchmarks and return a short human-readable report."""
    r = step_ratio(rounds=5 if quick else 15, calls=20 if quick else 50)
    f = frame_budget(frames=8 if quick else 20)
    fast, floor, general = r["fast"], r["floor"], r["general"]
    ratio, general_ratio = r["fast_ratio"], r["general_ratio"]
    verdict = "meets" if ratio <= 1.5 else "MISSES"
    lines = [
        f"particles: step of {SPARKS:,} sparks under gravity and wind (semi-implicit Euler)",
        f"  floor, np.add(x, y, out=x) on 2 x {4 * SPARKS:,} float64: {floor * 1e6:8.1f} us",
        f"  Particles.step, fast path:                    {fast * 1e6:8.1f} us"
        f"  = {ratio:.2f} x floor ({verdict} the 1.5 x target)",
        f"  Particles.step, general path (integrator fn): {general * 1e6:8.1f} us"
        f"  = {general_ratio:.2f} x floor",
        f"  per spark-step: {fast / SPARKS * 1e9:.2f} ns",
        "fireworks frame at 60 fps (2 steps of 1/120 s + numpy drawing at 640x360):",
        f"  {f['n1']:>7,.0f} sparks: {f['t1'] * 1e3:6.2f} ms   {f['n2']:>7,.0f} sparks:"
        f" {f['t2'] * 1e3:6.2f} ms",
        f"  = {f['fixed'] * 1e3:.2f} ms a frame + {f['per_spark'] * 1e9:.0f} ns a spark:"
        f" about {f['max_sparks']:,.0f} sparks stepped and drawn within 1/60 s",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    print(report())
