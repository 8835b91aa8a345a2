"""Ball-pit benchmark: balls piling up in a box, bodies against bodies, against pymunk.

Run with ``python -m demos.bench pit``. The scene of issue "Contacts II": N balls of radius
0.5 m dropped on a grid (rows 1.1 m apart, every other row shifted by half a ball) into a box
40 m wide, gravity 9.81 m/s^2, restitution 0.5, friction 0.5, dt = 1/60 s; pymunk with its
default 10 iterations. Both are timed after 5 s of settling (median step), side by side.
Targets: at most 0.5x pymunk's step at 1,000 balls and 1.0x at 10,000, with the overlap at
rest at most 1% of the radius. Besides the time, the table gives each engine's deepest
overlap, the balls outside the box, the kinetic over the potential energy and, for this
engine, how many balls sleep (a still pile costs nothing until something meets it).
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable
from functools import partial

import numpy as np

from demos.bench import compare
from engine import Body, Box, Vector, World
from engine.collisions import deepest_overlap
from engine.forces import Gravity

__all__ = ["report", "make_world", "make_space", "scene", "DT", "RADIUS", "WIDTH"]

DT = 1.0 / 60.0  # s
RADIUS = 0.5  # m
WIDTH = 40.0  # m
G = 9.81  # m/s^2
SETTLE = 5.0  # s
E, MU = 0.5, 0.5


def scene(n: int, seed: int = 1, *, width: float = WIDTH) -> np.ndarray:
    """Start positions (n, 2): a grid ``width`` - 2 balls wide (38 in the 40 m box), every
    other row shifted by half a ball, with a little seeded jitter so that the columns do not
    stand by symmetry."""
    rng = np.random.default_rng(seed)
    cols = int(width) - 2
    k = np.arange(n)
    row = k // cols
    x = 1.0 + (k % cols) + 0.5 * (row % 2) + rng.uniform(-0.01, 0.01, n)
    y = 1.0 + 1.1 * row
    return np.stack([x, y], axis=1)


def make_world(n: int, iterations: int | None = None, *, width: float = WIDTH) -> World:
    """The pit as a World ("auto": the closed form under gravity), ``width`` m wide."""
    world = World(integrator="auto")
    if iterations is not None:
        world.contact_iterations = iterations
    world.add_force(Gravity((0.0, -G)))
    world.add_collider(Box((0.0, 0.0), (width, 1e4)))  # walls and a floor; the top far away
    world.add_all(
        Body(Vector(*p), Vector(0, 0), Vector(0, 0), radius=RADIUS, restitution=E, friction=MU)
        for p in scene(n, width=width).tolist()
    )
    return world


def make_space(
    n: int, iterations: int = 10, *, width: float = WIDTH, slop: float | None = None
) -> object | None:
    """The pit in pymunk (None without pymunk): the same box, balls and materials.

    ``slop``: pymunk's ``collision_slop`` (m), the overlap it leaves alone; None keeps its
    default, 0.1 (20% of the radius here)."""
    try:
        import pymunk
    except ImportError:
        return None
    space = pymunk.Space()
    space.gravity = (0.0, -G)
    space.iterations = iterations
    if slop is not None:
        space.collision_slop = slop
    for a, b in (((0, 0), (width, 0)), ((0, 0), (0, 1e4)), ((width, 0), (width, 1e4))):
        wall = pymunk.Segment(space.static_body, a, b, 0.0)
        wall.elasticity = wall.friction = 1.0
        space.add(wall)
    for p in scene(n, width=width).tolist():
        body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0.0, RADIUS))
        body.position = p
        ball = pymunk.Circle(body, RADIUS)
        ball.elasticity, ball.friction = E, MU
        space.add(body, ball)
    return space


def measures(x: np.ndarray, v: np.ndarray, width: float = WIDTH) -> tuple[float, int, float]:
    """(deepest overlap / radius, balls outside the box, kinetic / potential energy)."""
    over = deepest_overlap(x, np.full(len(x), RADIUS)) / RADIUS
    out = int(((x[:, 0] < 0) | (x[:, 0] > width) | (x[:, 1] < 0)).sum())
    kinetic = 0.5 * float((v * v).sum())
    potential = G * float((x[:, 1] - RADIUS).sum())
    return over, out, kinetic / potential if potential > 0 else 0.0


def _space_state(space: object) -> tuple[np.ndarray, np.ndarray]:
    bodies = space.bodies  # type: ignore[attr-defined]
    return np.array([b.position for b in bodies]), np.array([b.velocity for b in bodies])


def report(quick: bool = False) -> str:
    """Run the ball-pit benchmark and return its table as text."""
    rounds = 5 if quick else 9
    sizes = [(1_000, 0.5)] if quick else [(100, None), (1_000, 0.5), (10_000, 1.0)]
    lines = ["pit: balls (r 0.5 m, e 0.5, mu 0.5) dropped into a box 40 m wide, dt = 1/60 s"]
    lines.append(f"  (medians of {rounds} interleaved rounds, after {SETTLE:g} s of settling)")
    for n, target in sizes:
        world = make_world(n)
        space = make_space(n)
        settle: dict[str, float] = {"World": 0.0, "pymunk": 0.0}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the bench reports the overlap itself
            for _ in range(round(SETTLE / DT)):
                t = time.perf_counter()
                world.step(DT)
                settle["World"] += time.perf_counter() - t
                if space is not None:
                    t = time.perf_counter()
                    space.step(DT)  # type: ignore[attr-defined]
                    settle["pymunk"] += time.perf_counter() - t
            calls = max(1, 2_000 // n)
            candidates: dict[str, tuple[Callable[[], object], int]] = {
                "World": (partial(world.step, DT), calls)
            }
            if space is not None:
                candidates["pymunk"] = (partial(space.step, DT), calls)  # type: ignore[attr-defined]
            times = compare(candidates, rounds=rounds)
        over, out, ke = measures(world.positions(), world.velocities())
        line = (
            f"  {n:>6,} balls: World {times['World'] * 1e3:7.2f} ms a step, overlap {over:.2%} "
            f"of r, {out} outside, KE/PE {ke:.1e}, {world.sleeping} asleep"
        )
        lines.append(line)
        if space is not None:
            p_over, p_out, p_ke = measures(*_space_state(space))
            ratio = times["World"] / times["pymunk"]
            aim = "" if target is None else f" (target <= {target:g}x)"
            lines.append(
                f"          pymunk {times['pymunk'] * 1e3:6.2f} ms a step, overlap {p_over:.2%} "
                f"of r, {p_out} outside, KE/PE {p_ke:.1e}; World / pymunk {ratio:.2f}x{aim}"
            )
            lines.append(
                f"          settling ({SETTLE:g} s): World {settle['World']:.1f} s, "
                f"pymunk {settle['pymunk']:.1f} s"
            )
    if make_space(1) is None:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    return "\n".join(lines)
