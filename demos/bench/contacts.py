"""Contacts benchmark: balls bouncing in a walled box with slanted segments, against pymunk.

Run with ``python -m demos.bench contacts``. The scene of issue "Contacts I": N balls of
radius 0.1 m (not colliding with each other) in a 40 x 30 m box with 50 slanted 2 m segments
inside, gravity 9.81 m/s^2, dt = 1/120 s. Targets: at most 1.0x pymunk's ``Space.step`` at
1,000 balls and 0.25x at 10,000, with no ball lost. Besides the time, the table counts the
balls outside the box after the timed steps (pymunk's discrete check lets fast balls
through its walls; this engine's swept contacts do not) and the World with no colliders
against the same World of points (radius 0: no contact machinery at all, as the World was
before contacts; target: within 5%).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from functools import partial

import numpy as np

from demos.bench import compare
from engine import Body, Box, Filter, Segment, Vector, World, kernels
from engine.forces import Gravity

__all__ = ["report", "make_world", "make_space", "scene"]

DT = 1.0 / 120.0  # s
SIZE = (40.0, 30.0)  # m
RADIUS = 0.1  # m
SEGMENTS = 50
ONE = Filter(group=1)


def scene(n: int, seed: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(segments (50, 2, 2), positions (n, 2), velocities (n, 2)): one scene for both engines."""
    rng = np.random.default_rng(seed)
    a = rng.uniform((2.0, 2.0), (SIZE[0] - 2.0, SIZE[1] - 2.0), (SEGMENTS, 2))
    angle = rng.uniform(0.0, np.pi, SEGMENTS)
    b = a + 2.0 * np.stack([np.cos(angle), np.sin(angle)], axis=1)
    pos = rng.uniform((1.0, 1.0), (SIZE[0] - 1.0, SIZE[1] - 1.0), (n, 2))
    vel = rng.uniform(-10.0, 10.0, (n, 2))
    return np.stack([a, b], axis=1), pos, vel


def make_world(
    n: int,
    *,
    colliders: bool = True,
    radius: float = RADIUS,
    kernels: str | None = None,
    solver: str = "exact",
) -> World:
    """The scene as a World ("auto": the closed form under gravity) on the path ``kernels``
    (None: the default, engine.kernels); ``radius`` 0 makes the balls points, which never
    collide: a World with no contact machinery at all; ``solver``: the World's."""
    segs, pos, vel = scene(n)
    world = World(integrator="auto", kernels=kernels, solver=solver)
    world.add_force(Gravity((0.0, -9.81)))
    if colliders:
        world.add_collider(Box((0.0, 0.0), SIZE))
        for a, b in segs:
            world.add_collider(Segment(tuple(a), tuple(b)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a ball dropped onto a segment is pushed off it
        world.add_all(
            # One group: the balls do not collide with each other (the targets' scene).
            Body(Vector(*p), Vector(*v), radius=radius, restitution=0.9, friction=0.5, filter=ONE)
            for p, v in zip(pos.tolist(), vel.tolist(), strict=True)
        )
    return world


def make_space(n: int) -> object | None:
    """The scene in pymunk (None without pymunk): the same walls, segments and balls."""
    try:
        import pymunk
    except ImportError:
        return None
    segs, pos, vel = scene(n)
    space = pymunk.Space()
    space.gravity = (0.0, -9.81)
    w, h = SIZE
    walls = [((0, 0), (w, 0)), ((w, 0), (w, h)), ((w, h), (0, h)), ((0, h), (0, 0))]
    for a, b in walls + [(tuple(a), tuple(b)) for a, b in segs.tolist()]:
        shape = pymunk.Segment(space.static_body, a, b, 0.0)
        shape.elasticity = shape.friction = 1.0
        space.add(shape)
    no_pairs = pymunk.ShapeFilter(group=1)  # the balls do not collide with each other
    for p, v in zip(pos.tolist(), vel.tolist(), strict=True):
        body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0.0, RADIUS))
        body.position, body.velocity = p, v
        ball = pymunk.Circle(body, RADIUS)
        ball.elasticity, ball.friction, ball.filter = 0.9, 0.5, no_pairs
        space.add(body, ball)
    return space


def _outside(xy: np.ndarray) -> int:
    w, h = SIZE
    out = (xy[:, 0] < 0) | (xy[:, 0] > w) | (xy[:, 1] < 0) | (xy[:, 1] > h)
    return int(out.sum())


def report(quick: bool = False) -> str:
    """Run the contacts benchmark and return its table as text."""
    rounds = 5 if quick else 11
    sizes = [(1_000, 1.0)] if quick else [(1_000, 1.0), (10_000, 0.25)]
    lines = [f"contacts: balls in a box with {SEGMENTS} segments, dt = 1/120 s"]
    lines.append(f"  (medians of {rounds} interleaved rounds, after 1 s of settling)")
    fast_targets = {1_000: 0.5, 10_000: 0.1}  # the fast path's targets
    kernels.prepare()  # compiled (or loaded from the cache) before the clock starts
    for n, target in sizes:
        worlds = {"World": make_world(n, kernels="numpy")}
        if kernels.available():
            worlds["fast"] = make_world(n, kernels="fast")
        space = make_space(n)
        for _ in range(120):
            for world in worlds.values():
                world.step(DT)
            if space is not None:
                space.step(DT)  # type: ignore[attr-defined]
        calls = max(1, 20_000 // n)
        candidates: dict[str, tuple[Callable[[], object], int]] = {
            name: (partial(world.step, DT), calls) for name, world in worlds.items()
        }
        if space is not None:
            candidates["pymunk"] = (partial(space.step, DT), calls)  # type: ignore[attr-defined]
        times = compare(candidates, rounds=rounds)
        for name, world in worlds.items():
            lost = _outside(world.positions())
            line = f"  {n:>6,} balls: {name:<5} {times[name] * 1e6:8.0f} us a step, {lost} outside"
            if space is not None:
                ratio = times[name] / times["pymunk"]
                aim = target if name == "World" else fast_targets[n]
                line += f"; {name} / pymunk {ratio:.2f}x (target <= {aim:g}x)"
            lines.append(line)
        if space is not None:
            out = _outside(np.array([b.position for b in space.bodies]))  # type: ignore[attr-defined]
            lines.append(f"          pymunk {times['pymunk'] * 1e6:8.0f} us, {out} outside")
        lines.append(f"          capped impacts so far: {worlds['World'].capped}")
        if "fast" in worlds:
            same = np.array_equal(worlds["World"].positions(), worlds["fast"].positions())
            lines.append(f"          both paths at the same state: {same}")
    # No colliders: the same World without contacts costs what a World of points (radius 0:
    # no contact machinery at all, the World before contacts) does, side by side.
    bare = make_world(1_000, colliders=False)
    points = make_world(1_000, colliders=False, radius=0.0)
    times = compare(
        {"no colliders": (partial(bare.step, DT), 20), "points": (partial(points.step, DT), 20)},
        rounds=rounds,
    )
    ratio = times["no colliders"] / times["points"]
    lines.append(
        f"  1,000 balls, no colliders: {times['no colliders'] * 1e6:.1f} us a step against "
        f"{times['points'] * 1e6:.1f} us for the same World of points (radius 0: no contact "
        f"machinery): {ratio:.2f}x (target: within 5%)"
    )
    if make_space(1) is None:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    return "\n".join(lines)
