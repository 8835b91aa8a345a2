"""Core benchmark: World.step at 10 to 100,000 bodies against pymunk's Space.step and
against Particles.step, and the lesson-level Body/Vector step against pygame's Vector2.

Run with ``python -m demos.bench core``. Targets: World at most 2x pymunk's ``Space.step``
at 10 and 100 bodies (small games: the fixed cost per step decides) and at most 0.5x at
1,000; World at 1,000 bodies at most 1.5x ``Particles.step`` on the same bodies and forces;
the lesson-level step at most 3x the Vector2 loop.
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
from engine.particles import Particles

__all__ = [
    "report",
    "make_world",
    "start_state",
    "world_step",
    "pymunk_step",
    "vector2_step",
    "lesson_step",
    "particles_step",
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


def particles_step(n: int, drag: bool = True) -> Step:
    """One Particles.step of ``n`` sparks with the same state, mass and forces as the World."""
    pos, vel = start_state(n)
    forces = [Gravity(G), Drag(DRAG)] if drag else [Gravity(G)]
    sparks = Particles(n, dt=DT, forces=forces)
    sparks.emit(n, position=pos, velocity=vel, lifetime=math.inf)
    return sparks.step


#: (bodies, World / pymunk target) for each size the report compares.
SIZES = ((10, 2.0), (100, 2.0), (1_000, 0.5), (100_000, 0.5))


def report(quick: bool = False) -> str:
    """Run the core benchmark and return its table as text."""
    rounds = 7 if quick else 21
    budget = 2_000 if quick else 20_000  # body-steps per timed call batch
    sizes = [(n, target) for n, target in SIZES if not quick or n <= 1_000]
    candidates: dict[str, tuple[Callable[[], object], int]] = {}
    bodies: dict[str, int] = {}

    def add(name: str, fn: Step | None, n: int, calls: int) -> None:
        if fn is not None:
            candidates[name] = (fn, max(1, calls))
            bodies[name] = n

    for n, _ in sizes:
        add(f"World.step, {n:,} bodies", world_step(n), n, budget // n)
        add(f"pymunk Space.step, {n:,} bodies", pymunk_step(n), n, budget // n)
    add("Particles.step, 1,000", particles_step(1_000), 1_000, budget // 1_000)
    add("lesson Body.step (Vectors), 1,000", lesson_step(1_000), 1_000, budget // 10_000)
    add("pygame Vector2 loop, 1,000", vector2_step(1_000), 1_000, budget // 10_000)
    times = compare(candidates, rounds=rounds)
    per = {name: times[name] / bodies[name] for name in times}

    lines = [
        f"core: semi-implicit Euler under gravity and drag (medians of {rounds} interleaved rounds)"
    ]
    lines += [
        f"  {name:<36} {times[name] * 1e6:9.2f} us a step {per[name] * 1e9:9.1f} ns a body"
        for name in times
    ]
    for n, target in sizes:
        peer = f"pymunk Space.step, {n:,} bodies"
        if peer in times:
            ratio = times[f"World.step, {n:,} bodies"] / times[peer]
            lines.append(
                f"  World / pymunk at {n:>7,} bodies:   {ratio:.2f}x  (target <= {target:g}x)"
            )
    if "pymunk Space.step, 10 bodies" not in times:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    ratio = times["World.step, 1,000 bodies"] / times["Particles.step, 1,000"]
    lines.append(f"  World / Particles at 1,000 bodies: {ratio:.2f}x  (target <= 1.5x)")
    if "pygame Vector2 loop, 1,000" in times:
        ratio = per["lesson Body.step (Vectors), 1,000"] / per["pygame Vector2 loop, 1,000"]
        lines.append(f"  lesson Body.step / pygame Vector2: {ratio:.2f}x  (target <= 3x)")
    return "\n".join(lines)
