"""Core benchmark: World.step per body-step at 10 to 100,000 bodies, against pymunk, and
the lesson-level Body/Vector step against the same step with pygame's Vector2.

Run with ``python -m engine.bench core``. Targets (issue 2): World at 1,000 bodies at
most 0.5x pymunk's ``Space.step``; the lesson-level step at most 3x the Vector2 loop.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from functools import partial

import numpy as np

from engine import Body, Vector, World
from engine.bench import compare
from engine.forces import Drag, Gravity

__all__ = ["report", "make_world"]

DT = 1.0 / 60.0
G = (0.0, -9.81)


def make_world(n: int, *, seed: int = 0) -> World:
    """A World of ``n`` unit-mass bodies under gravity and drag, stepped by semi-implicit Euler."""
    rng = np.random.default_rng(seed)
    pos, vel = rng.uniform(-10, 10, (n, 2)), rng.uniform(-5, 5, (n, 2))
    world = World(integrator="semi_implicit_euler")
    world.add_all(Body(Vector(*p), Vector(*v), Vector(0, 0)) for p, v in zip(pos, vel, strict=True))
    world.add_force(Gravity(G))
    world.add_force(Drag(0.1))
    return world


def _pymunk_space(n: int) -> Callable[[], object] | None:
    """pymunk's Space.step for n free bodies with gravity and damping, if pymunk is installed."""
    try:
        import pymunk
    except ImportError:
        return None
    space = pymunk.Space()
    space.gravity = G
    space.damping = 0.9  # pymunk's damping is the fraction of velocity kept per second
    for i in range(n):
        body = pymunk.Body(1.0, 1.0)
        body.position = (float(i), 0.0)
        body.velocity = (1.0, 2.0)
        space.add(body)
    return lambda: space.step(DT)


def _vector2_loop(n: int) -> Callable[[], object] | None:
    """The same semi-implicit Euler step on pygame.math.Vector2, in a Python loop."""
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    try:
        from pygame.math import Vector2
    except ImportError:
        return None
    ps = [Vector2(float(i), 0.0) for i in range(n)]
    vs = [Vector2(1.0, 2.0) for _ in range(n)]
    g = Vector2(*G)

    def step() -> None:
        for p, v in zip(ps, vs, strict=True):
            v += g * DT
            p += v * DT

    return step


def _lesson_loop(n: int) -> Callable[[], object]:
    """The lesson-level step: each Body (holding Vectors) steps itself with a prebuilt gravity."""
    bodies = [Body(Vector(float(i), 0.0), Vector(1.0, 2.0), Vector(0.0, 0.0)) for i in range(n)]
    g = Vector(*G)

    def step() -> None:
        for b in bodies:
            b.step(DT, g)

    return step


def report(quick: bool = False) -> str:
    """Run the core benchmark and return its table as text."""
    rounds = 7 if quick else 21
    budget = 2_000 if quick else 20_000  # body-steps per timed call batch
    sizes = (10, 1_000) if quick else (10, 1_000, 100_000)
    candidates: dict[str, tuple[Callable[[], object], int]] = {}
    bodies: dict[str, int] = {}
    for n in sizes:
        world = make_world(n)
        name = f"World.step, {n:,} bodies"
        candidates[name] = (partial(world.step, DT), max(1, budget // n))
        bodies[name] = n
    space = _pymunk_space(1_000)
    if space is not None:
        candidates["pymunk Space.step, 1,000 bodies"] = (space, budget // 1_000)
        bodies["pymunk Space.step, 1,000 bodies"] = 1_000
    lesson, vec2 = _lesson_loop(1_000), _vector2_loop(1_000)
    candidates["lesson Body.step (Vectors), 1,000"] = (lesson, max(1, budget // 10_000))
    bodies["lesson Body.step (Vectors), 1,000"] = 1_000
    if vec2 is not None:
        candidates["pygame Vector2 loop, 1,000"] = (vec2, max(1, budget // 10_000))
        bodies["pygame Vector2 loop, 1,000"] = 1_000
    times = compare(candidates, rounds=rounds)
    per = {name: times[name] / bodies[name] for name in times}

    lines = [
        "core: semi-implicit Euler under gravity and drag, per body-step "
        f"(medians of {rounds} interleaved rounds)"
    ]
    lines += [f"  {name:<36} {t * 1e9:9.1f} ns" for name, t in per.items()]
    if space is not None:
        ratio = per["World.step, 1,000 bodies"] / per["pymunk Space.step, 1,000 bodies"]
        lines.append(f"  World / pymunk at 1,000 bodies:   {ratio:.2f}x  (target <= 0.5x)")
    else:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    if vec2 is not None:
        ratio = per["lesson Body.step (Vectors), 1,000"] / per["pygame Vector2 loop, 1,000"]
        lines.append(f"  lesson Body.step / pygame Vector2: {ratio:.2f}x  (target <= 3x)")
    return "\n".join(lines)
