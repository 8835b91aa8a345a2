"""Core benchmark: World.step per body-step at 10 to 100,000 bodies, against pymunk, and
the lesson-level Body/Vector step against the same step with pygame's Vector2.

Run with ``python -m demos.bench core``. Targets (issue 2): World at 1,000 bodies at
most 0.5x pymunk's ``Space.step``; the lesson-level step at most 3x the Vector2 loop.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from functools import partial

import numpy as np

from demos.bench import compare
from engine import Body, Vector, World
from engine.forces import Drag, Gravity

__all__ = [
    "report",
    "make_world",
    "start_state",
    "world_step",
    "pymunk_step",
    "vector2_step",
    "lesson_step",
]

DT = 1.0 / 60.0  # s
G = (0.0, -9.81)  # m/s^2
DRAG = 0.1  # N s/m on unit masses: velocity decays at 0.1 per second
Step = Callable[[], object]


def start_state(n: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Positions (m) and velocities (m/s) of ``n`` bodies, the same for every way of stepping."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-10, 10, (n, 2)), rng.uniform(-5, 5, (n, 2))


def make_world(n: int, *, drag: bool = True) -> World:
    """A World of ``n`` unit-mass bodies under gravity (and drag), by semi-implicit Euler."""
    pos, vel = start_state(n)
    world = World(integrator="semi_implicit_euler")
    world.add_all(Body(Vector(*p), Vector(*v), Vector(0, 0)) for p, v in zip(pos, vel, strict=True))
    world.add_force(Gravity(G))
    if drag:
        world.add_force(Drag(DRAG))
    return world


def world_step(n: int, drag: bool = True) -> Step:
    """One World.step of ``n`` bodies."""
    return partial(make_world(n, drag=drag).step, DT)


def pymunk_step(n: int, drag: bool = True) -> Step | None:
    """pymunk's Space.step for ``n`` free bodies with gravity (and damping), if installed."""
    try:
        import pymunk
    except ImportError:
        return None
    pos, vel = start_state(n)
    space = pymunk.Space()
    space.gravity = G
    if drag:
        # pymunk's damping is the fraction of velocity kept after one second: e^{-k/m}.
        space.damping = math.exp(-DRAG)
    for p, v in zip(pos.tolist(), vel.tolist(), strict=True):
        body = pymunk.Body(1.0, 1.0)
        body.position, body.velocity = p, v
        space.add(body)
    return partial(space.step, DT)


def vector2_step(n: int) -> Step | None:
    """The semi-implicit Euler step under gravity on pygame.math.Vector2, in a Python loop."""
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    try:
        from pygame.math import Vector2
    except ImportError:
        return None
    pos, vel = start_state(n)
    ps = [Vector2(*p) for p in pos.tolist()]
    vs = [Vector2(*v) for v in vel.tolist()]
    g = Vector2(*G)

    def step() -> None:
        for p, v in zip(ps, vs, strict=True):
            v += g * DT
            p += v * DT

    return step


def lesson_step(n: int) -> Step:
    """The lesson-level step: each Body (holding Vectors) steps itself with a prebuilt gravity."""
    pos, vel = start_state(n)
    bodies = [Body(Vector(*p), Vector(*v), Vector(0, 0)) for p, v in zip(pos, vel, strict=True)]
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
        name = f"World.step, {n:,} bodies"
        candidates[name] = (world_step(n), max(1, budget // n))
        bodies[name] = n
    space = pymunk_step(1_000)
    if space is not None:
        candidates["pymunk Space.step, 1,000 bodies"] = (space, budget // 1_000)
        bodies["pymunk Space.step, 1,000 bodies"] = 1_000
    lesson, vec2 = lesson_step(1_000), vector2_step(1_000)
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
