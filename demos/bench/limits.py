"""The contact solver's limits: columns and pits, how deep the balls overlap and when they sleep.

Run with ``python -m demos.bench limits`` (``--quick``: three scenes, briefly). Every scene:
balls of radius 0.5 m, restitution 0.5, friction 0.5, under gravity 9.81 m/s^2, dt = 1/60 s,
this engine alone (pymunk has no sleep by default and leaves 20% of r by its slop; see
``demos.bench pit`` for the two side by side). After every step: the deepest overlap of two
balls, or of a ball and a wall or the floor, as a fraction of the radius; a run stops when
every ball sleeps or at its time limit. The table gives, per scene and
``World.contact_iterations``: the deepest overlap at the end (at rest, if asleep), the deepest
at any step (while the balls land), and when the whole scene fell asleep. Scenes with seeds
give the range over the seeds.

Scenes:

* a column of N balls on a floor, centres 2.1 r apart (a gap of 5% of a diameter between
  neighbours), masses alternating 1 and M from the bottom;
* a pit: N balls on the grid of ``demos.bench.pit`` (rows 1.1 m apart, seeded jitter) in a
  box W m wide, equal masses or masses drawn log-uniform from 1 to 1,000;
* the ``ballpit`` demo's 2,000 balls (``demos.ballpit.pit_world``: its grid and its box).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from demos.bench import pit
from engine import Body, Plane, Vector, World
from engine.exact.collisions import deepest_overlap
from engine.forces import Gravity

__all__ = ["Scene", "Result", "SCENES", "QUICK", "run", "measure", "table", "report"]

RADIUS = 0.5
DT = 1.0 / 60.0
G = 9.81


@dataclass(frozen=True)
class Scene:
    """One row of the table: how to build it, for how long to run it, which counts and seeds."""

    label: str
    build: Callable[[int, int], tuple[World, float | None]]  # (iterations, seed) -> (world, W)
    seconds: float
    iterations: tuple[int, ...]
    seeds: tuple[int, ...] = (1,)


@dataclass(frozen=True)
class Result:
    """One run: the deepest overlap / r at the end and over the run (and when), when every
    ball slept (nan: not within the run), the kinetic over potential energy at the end."""

    label: str
    iterations: int
    seed: int
    final: float
    deepest: float
    deepest_at: float
    asleep_at: float
    seconds: float
    ke_pe: float


def column(n: int, heavy: float) -> Callable[[int, int], tuple[World, float | None]]:
    """A column of ``n`` balls on a floor, masses alternating 1 and ``heavy`` from the bottom."""

    def build(iterations: int, seed: int) -> tuple[World, float | None]:
        world = World(integrator="auto")
        world.contact_iterations = iterations
        world.add_force(Gravity((0.0, -G)))
        world.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
        world.add_all(
            Body(
                Vector(0.0, RADIUS + 2.1 * RADIUS * k),
                mass=1.0 if k % 2 == 0 else heavy,
                radius=RADIUS,
                restitution=0.5,
                friction=0.5,
                fixed_rotation=True,  # the pile's solver, as in engine.bench's pit
            )
            for k in range(n)
        )
        return world, None

    return build


def pit_of(
    n: int, width: float, log_masses: bool = False, turning: bool = False
) -> Callable[[int, int], tuple[World, float | None]]:
    """``n`` balls on the bench pit's grid in a box ``width`` m wide; masses equal, or drawn
    log-uniform from 1 to 1,000 (seeded); ``turning``: balls that turn (else they do not)."""

    def build(iterations: int, seed: int) -> tuple[World, float | None]:
        world = pit.make_world(n, iterations, width=width, seed=seed, fixed_rotation=not turning)
        if log_masses:
            masses = 10.0 ** np.random.default_rng(seed).uniform(0.0, 3.0, n)
            for body, m in zip(world.bodies, masses.tolist(), strict=True):
                body.mass = m
        return world, width

    return build


def ballpit_demo(iterations: int, seed: int) -> tuple[World, float | None]:
    """The ``ballpit`` demo's World: 2,000 balls, its grid and its box (40 m wide)."""
    from demos import ballpit

    world, _ = ballpit.pit_world(ballpit.BALLS)
    world.contact_iterations = iterations
    return world, ballpit.WIDTH


#: The table's rows.
SCENES: tuple[Scene, ...] = (
    Scene("a column of 10 balls, masses 1 and 1", column(10, 1.0), 10.0, (1, 4, 8)),
    Scene("a column of 10 balls, masses 1 and 100", column(10, 100.0), 10.0, (1, 4, 8)),
    Scene("a column of 10 balls, masses 1 and 10^4", column(10, 1e4), 10.0, (1, 4, 8)),
    Scene("a column of 50 balls, masses 1 and 1", column(50, 1.0), 15.0, (1, 4, 8)),
    Scene("a column of 50 balls, masses 1 and 100", column(50, 100.0), 15.0, (1, 4, 8)),
    Scene("a column of 50 balls, masses 1 and 10^4", column(50, 1e4), 15.0, (1, 4, 8)),
    Scene("a column of 200 balls, equal masses", column(200, 1.0), 15.0, (1, 4, 8)),
    Scene("a 200-ball pit, 12 m wide", pit_of(200, 12.0), 15.0, (1, 2, 4, 8, 16)),
    Scene(
        "a 200-ball pit, 12 m wide, masses 1 to 1,000 (log-uniform)",
        pit_of(200, 12.0, log_masses=True),
        15.0,
        (4, 8, 16),
        (1, 2, 3),
    ),
    Scene("a 400-ball pit, 20 m wide", pit_of(400, 20.0), 15.0, (4,), (1, 2, 3)),
    Scene(
        "the 1,000-ball pit of demos.bench pit, 40 m wide",
        pit_of(1_000, 40.0),
        15.0,
        (4,),
        tuple(range(1, 9)),
    ),
    Scene("the ballpit demo's 2,000 balls", ballpit_demo, 15.0, (4,)),
    Scene("the bench pit with 2,000 balls (53 rows, from 58 m)", pit_of(2_000, 40.0), 15.0, (4,)),
    Scene(
        "the bench pit with 10,000 balls (263 rows, from 290 m)",
        pit_of(10_000, 40.0),
        15.0,
        (4,),
    ),
)
#: The quick run's rows: a short column, a small pit, at the default count.
QUICK: tuple[Scene, ...] = (
    Scene("a column of 10 balls, masses 1 and 100", column(10, 100.0), 5.0, (4,)),
    Scene("a 200-ball pit, 12 m wide", pit_of(200, 12.0), 5.0, (4,)),
)


def _wall_overlap(x: np.ndarray, width: float | None) -> float:
    """The deepest overlap (m) of a ball into the floor (y = 0), and the box's walls if any."""
    deepest = float((RADIUS - x[:, 1]).max())
    if width is not None:
        deepest = max(deepest, float((RADIUS - x[:, 0]).max()))
        deepest = max(deepest, float((x[:, 0] - (width - RADIUS)).max()))
    return max(deepest, 0.0)


def overlap(world: World, width: float | None) -> float:
    """The deepest overlap now of two balls, or of a ball and the floor or a wall, over r."""
    x = world.positions()
    pairs = deepest_overlap(x, np.full(len(x), RADIUS))
    return max(pairs, _wall_overlap(x, width)) / RADIUS


def run(scene: Scene, iterations: int, seed: int) -> Result:
    """Run ``scene`` at ``iterations`` with ``seed`` until every ball sleeps, or its time."""
    world, width = scene.build(iterations, seed)
    n = len(world.bodies)
    steps = round(scene.seconds / DT)
    deepest, deepest_at, asleep_at, now = 0.0, 0.0, math.nan, 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the table reports the overlaps itself
        for i in range(steps):
            world.step(DT)
            now = overlap(world, width)
            if now > deepest:
                deepest, deepest_at = now, (i + 1) * DT
            if world.sleeping == n:
                asleep_at = (i + 1) * DT
                break
    x, v = world.positions(), world.velocities()
    m = np.array([b.mass for b in world.bodies])
    kinetic = 0.5 * float((m * (v * v).sum(axis=1)).sum())
    potential = G * float((m * (x[:, 1] - RADIUS)).sum())
    ke_pe = kinetic / potential if potential > 0 else 0.0
    return Result(
        scene.label, iterations, seed, now, deepest, deepest_at, asleep_at, world.t, ke_pe
    )


def measure(quick: bool = False, scenes: Sequence[Scene] | None = None) -> list[Result]:
    """Every scene of the table (or ``scenes``) at each of its counts and seeds."""
    chosen = scenes if scenes is not None else QUICK if quick else SCENES
    return [run(s, k, seed) for s in chosen for k in s.iterations for seed in s.seeds]


def _span(values: Sequence[float], fmt: Callable[[float], str]) -> str:
    lo, hi = min(values), max(values)
    return fmt(lo) if fmt(lo) == fmt(hi) else f"{fmt(lo)} to {fmt(hi)}"


def _pct(x: float) -> str:
    return f"{x:.2%}" if x < 0.1 else f"{x:.0%}"


def table(results: Sequence[Result]) -> str:
    """One line per scene and count (the range over seeds)."""
    lines = [
        "limits: r 0.5 m, e 0.5, mu 0.5, dt = 1/60 s; overlaps of balls with balls, walls and "
        "floor, as a fraction of r",
        f"  {'scene':<58} {'its':>3}  {'at the end':<17} {'deepest (at s)':<24} asleep",
    ]
    groups: dict[tuple[str, int], list[Result]] = {}
    for r in results:
        groups.setdefault((r.label, r.iterations), []).append(r)
    for (label, k), rs in groups.items():
        asleep = [r.asleep_at for r in rs if math.isfinite(r.asleep_at)]
        if len(asleep) == len(rs):
            sleep = "at " + _span(asleep, lambda s: f"{s:.2f} s")
        else:
            awake = [r for r in rs if not math.isfinite(r.asleep_at)]
            sleep = (
                f"{len(asleep)} of {len(rs)}"
                + (f" (at {_span(asleep, lambda s: f'{s:.2f} s')})" if asleep else "")
                + f"; not by {awake[0].seconds:g} s (KE/PE "
                + _span([r.ke_pe for r in awake], lambda e: f"{e:.0e}")
                + ")"
            )
        final = _span([r.final for r in rs], _pct)
        deep = _span([r.deepest for r in rs], _pct)
        when = _span([r.deepest_at for r in rs], lambda s: f"{s:.2f}")
        lines.append(f"  {label:<58} {k:>3}  {final:<17} {deep + f' ({when})':<24} {sleep}")
    return "\n".join(lines)


def report(quick: bool = False) -> str:
    """Run the scenes and return their table as text."""
    return table(measure(quick))
