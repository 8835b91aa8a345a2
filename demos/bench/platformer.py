"""A small platformer game, against pymunk: what a game's step costs.

Run with ``python -m demos.bench platformer`` (``--quick``: the script's first 5 s, fewer
query rounds). The scene is ``demos.platformer_scene``: ground, walls and ledges as segments
and capsules, a 0.8 x 1.6 m player box that never turns, a rope bridge of six planks on seven
hinges, six 1 m crates in a pyramid, a seesaw (a plank on a hinge), a kinematic moving
platform, a ball rolling down a slanted ledge, five coin sensors, and a scripted 20 s of
running, jumping, crossing the bridge and shoving at dt = 1/60 s. pymunk 7 plays the same
scene (``PymunkPlatformer``: the same shapes, masses, moments and materials, a ``PivotJoint``
for the seesaw and for each of the bridge's hinges, a kinematic platform, sensor coins; its
default 10 iterations, sleeping after 0.5 s still as this World's bodies do, and a collision
slop of 1 cm, not its default 10 cm made for pixels) with the same script and rules
(``demos.platformer_scene``'s ``script``, ``toward``, jump impulse and ground test).

**Each step** is timed in two parts: the engine's own step (``World.step``, pymunk's
``Space.step``: what was measured first) and the game's whole step around it (the script's
input, the ground test, one ``segment_query_first`` below the player's feet, the player's
speed and jump, the engine's step, the coins). The engines step one after another in turn
(the order rotated every step, so a burst of load on a shared machine hits them alike), each
by two clocks: the thread's CPU time (the engine's own work, steady whatever else the machine
runs) and the wall clock (what a player sees: a frame is late by the wall clock). The
engines: this World on the numpy path ("World (numpy)"), on the fast path where numba is
installed ("World (fast)"), the same with the soft step (``World(solver="soft")``: "soft
(numpy)", "soft (fast)"), and pymunk. Reported per engine: the time to build the game and
its first step, apart (on the fast path they include loading or compiling numba's kernels,
when the World is made or at its first step, as the engine does it: the report says what
numba did, from its own cache statistics); over the other steps the median, the 99th
percentile and the worst, each as a ratio to pymunk's median, and the share of steps longer
than a 60 fps frame (16.7 ms); the coins each engine's player collected; any warning the
World gave.

**The hinge's cost**: the same scene without the seesaw's hinge (its plank falls flat and
lies on the ground, so the run differs from then on), stepped in the same rounds; the ratio of
the medians, with and without.

**The ground test's cost**: one 13 cm ``segment_query_first`` below the player's feet
(``demos.platformer_scene.feet_segment``: a thin segment from 5 cm above the soles to 8 cm
below, the player and the coins filtered out), against pymunk's ``Space.segment_query_first``
on its twin, both with the player standing on the ground at t = 0; the median over rounds of
many calls (``demos.bench.compare``). The query uses no kernel: one number for both paths.
And the same test in play: made once more after each step of the side-by-side run (the
bodies have moved, so the World's query index is made again, as the game's next test finds
it), each engine's median by CPU time against pymunk's.

No test asserts a time (``tests/test_bench_platformer.py`` checks the scene, the twin's
layout and the table).
"""

from __future__ import annotations

import importlib
import math
import time
import warnings
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from demos import platformer_scene as scene
from demos.bench import compare
from engine import Body
from engine import kernels as engine_kernels

__all__ = [
    "DT",
    "FRAME",
    "ITERATIONS",
    "SLEEP_TIME",
    "SLOP",
    "ISSUE",
    "PymunkPlatformer",
    "make_space",
    "CPU",
    "WALL",
    "PHYSICS",
    "GAME",
    "Run",
    "side_by_side",
    "query_times",
    "cache_counts",
    "table",
    "report",
]

DT = scene.DT  # s
FRAME = 1.0 / 60.0  # s: a 60 fps frame
ITERATIONS = 10  # pymunk's default
SLEEP_TIME = 0.5  # s still before a pymunk body sleeps: this World's default
#: m: pymunk's collision slop, the overlap it allows at rest: its default, 0.1, is for pixels
#: (the player would stand 10 cm deep in the ground, past the ground test's reach)
SLOP = 0.01
#: What was measured first (ms a step: median, worst; pymunk's median in us; the share of steps
#: over a frame), before this scene was in the repository.
ISSUE = {
    "numpy": "18.4 ms median (689x pymunk's 27 us), 68% of steps over a frame, worst 381 ms",
    "fast": "6.6 ms median, worst 101 ms",
}

#: pymunk's collision types: the player, a coin.
_PLAYER, _COIN = 1, 2


class PymunkPlatformer:
    """``demos.platformer_scene``'s scene in a pymunk Space, played by the same script and rules.

    ``bodies``: the player, the crates, the seesaw, the platform, the ball, the bridge's planks
    (the World's order); ``coins``: the coins' shapes (sensors on the static body), in
    ``scene.COINS``' order; ``planks`` and ``bridge_hinges``: the rope bridge, left to right;
    ``collected``, ``jumps``, ``landings`` as ``scene.Platformer``'s.
    """

    def __init__(self, hinge: bool = True) -> None:
        import pymunk

        self.pymunk = pymunk
        self.space = space = pymunk.Space()
        space.gravity = (0.0, -scene.G)
        space.iterations = ITERATIONS
        space.sleep_time_threshold = SLEEP_TIME
        space.collision_slop = SLOP
        static = space.static_body
        for a, b, r in scene.STATIC:
            seg = pymunk.Segment(static, a, b, r)
            seg.elasticity, seg.friction = 1.0, 1.0  # a collider's defaults here
            space.add(seg)

        def box(mass: float, size: tuple[float, float], at: tuple[float, float],
                friction: float, moment: float | None = None,
                angle: float = 0.0) -> Any:  # fmt: skip
            body = pymunk.Body(mass, pymunk.moment_for_box(mass, size) if moment is None
                               else moment)  # fmt: skip
            body.position, body.angle = at, angle
            shape = pymunk.Poly.create_box(body, size, 0.0)
            shape.elasticity, shape.friction = 0.0, friction
            space.add(body, shape)
            return body, shape

        self.player, player_shape = box(
            scene.PLAYER_MASS, scene.PLAYER_SIZE, scene.PLAYER_START, 0.0, math.inf
        )
        player_shape.filter = pymunk.ShapeFilter(categories=scene.PLAYER_BIT)
        player_shape.collision_type = _PLAYER
        self.crates = [
            box(scene.CRATE_MASS, (scene.CRATE, scene.CRATE), c, scene.CRATE_FRICTION)[0]
            for c in scene.CRATES
        ]
        self.seesaw, _ = box(
            scene.SEESAW_MASS, scene.SEESAW_SIZE, scene.SEESAW_PIVOT, scene.CRATE_FRICTION
        )
        self.hinge = None
        if hinge:
            self.hinge = pymunk.PivotJoint(static, self.seesaw, scene.SEESAW_PIVOT)
            space.add(self.hinge)
        self.platform = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        self.platform.position = scene.PLATFORM_START
        self.platform.velocity = (scene.platform_velocity(0.0), 0.0)
        plat = pymunk.Poly.create_box(self.platform, scene.PLATFORM_SIZE, 0.0)
        plat.elasticity, plat.friction = 0.0, scene.CRATE_FRICTION
        space.add(self.platform, plat)
        self.ball = pymunk.Body(
            scene.BALL_MASS, pymunk.moment_for_circle(scene.BALL_MASS, 0.0, scene.BALL_RADIUS)
        )
        self.ball.position = scene.BALL_START
        ball = pymunk.Circle(self.ball, scene.BALL_RADIUS)
        ball.elasticity, ball.friction = 0.2, scene.CRATE_FRICTION
        space.add(self.ball, ball)
        self.coins: list[Any] = []
        for c in scene.COINS:
            coin = pymunk.Circle(static, scene.COIN_RADIUS, c)
            coin.sensor = True
            coin.filter = pymunk.ShapeFilter(categories=scene.COIN_BIT)
            coin.collision_type = _COIN
            space.add(coin)
            self.coins.append(coin)
        # The rope bridge: the same planks, and a PivotJoint where the scene has a Hinge (at
        # each point of its deck), the joined bodies not colliding (a Hinge's default).
        self.planks: list[Any] = []
        plank_filter = pymunk.ShapeFilter(
            categories=scene.BRIDGE_BIT, mask=pymunk.ShapeFilter.ALL_MASKS() ^ scene.BRIDGE_BIT
        )
        for x, y, angle in scene.bridge_planks():
            plank, shape = box(
                scene.BRIDGE_MASS, scene.BRIDGE_PLANK, (x, y), scene.CRATE_FRICTION, angle=angle
            )
            shape.filter = plank_filter
            self.planks.append(plank)
        ends = [static, *self.planks, static]
        self.bridge_hinges: list[Any] = []
        for a, b, point in zip(ends[:-1], ends[1:], scene.bridge_deck(), strict=True):
            pivot = pymunk.PivotJoint(a, b, point)
            pivot.collide_bodies = False
            space.add(pivot)
            self.bridge_hinges.append(pivot)
        self.bodies = [
            self.player,
            *self.crates,
            self.seesaw,
            self.platform,
            self.ball,
            *self.planks,
        ]
        self.feet_filter = pymunk.ShapeFilter(
            mask=pymunk.ShapeFilter.ALL_MASKS() ^ (scene.PLAYER_BIT | scene.COIN_BIT)
        )
        self.t = 0.0
        self.steps = 0
        self.collected: list[int] = []
        self.jumps: list[float] = []
        self.landings: list[float] = []
        self._touched: list[int] = []
        self._held = False
        self._was_grounded = True

        def begin(arbiter: Any, space: Any, data: Any) -> None:
            for shape in arbiter.shapes:
                if shape in self.coins:
                    self._touched.append(self.coins.index(shape))

        space.on_collision(_PLAYER, _COIN, begin=begin)

    def ground_hit(self) -> Any:
        """pymunk's SegmentQueryInfo of what is under the player's feet, or None."""
        x, y = self.player.position
        start, end = scene.feet_segment(x, y)
        return self.space.segment_query_first(
            tuple(start), tuple(end), scene.PROBE_RADIUS, self.feet_filter
        )

    def on_ground(self) -> bool:
        """Whether the player stands on something (the ground test)."""
        return self.ground_hit() is not None

    def step(self, dt: float = DT) -> None:
        """One fixed step of the game, as ``scene.Platformer.step``."""
        self.control(dt)
        self.physics(dt)
        self.collect()

    def control(self, dt: float = DT) -> None:
        """The game's input before the Space's step, as ``scene.Platformer.control``."""
        t = self.t
        run, jump = scene.script(t)
        self.platform.velocity = (scene.platform_velocity(t), 0.0)
        hit = self.ground_hit()
        grounded = hit is not None
        if grounded and not self._was_grounded:
            self.landings.append(t)
        self._was_grounded = grounded
        carry = 0.0
        if hit is not None and hit.shape.body.body_type == self.pymunk.Body.KINEMATIC:
            carry = hit.shape.body.velocity.x
        player = self.player
        vx, vy = player.velocity
        player.velocity = (scene.toward(vx, run * scene.RUN_SPEED + carry, dt), vy)
        if jump and not self._held and grounded:
            player.apply_impulse_at_local_point((0.0, scene.PLAYER_MASS * scene.JUMP_SPEED))
            self.jumps.append(t)
            self._was_grounded = False
        self._held = jump

    def physics(self, dt: float = DT) -> None:
        """The Space's step."""
        self.space.step(dt)
        self.steps += 1
        self.t = self.steps * dt

    def collect(self) -> None:
        """The coins, as ``scene.Platformer.collect``."""
        touched, self._touched = self._touched, []
        for index in touched:
            if index not in self.collected:
                self.collected.append(index)
                self.space.remove(self.coins[index])


def make_space(hinge: bool = True) -> PymunkPlatformer | None:
    """pymunk's twin of the scene, or None where pymunk is not installed."""
    try:
        import pymunk  # noqa: F401
    except ImportError:
        return None
    return PymunkPlatformer(hinge)


def cache_counts() -> tuple[int, int]:
    """(kernels numba loaded from its cache, kernels it compiled) so far in this process,
    summed over the engine's loop kernels (numba's own ``Dispatcher.stats``); (0, 0) without
    numba."""
    if not engine_kernels.available():
        return 0, 0
    for name in engine_kernels.MODULES:
        importlib.import_module(name)
    hits = misses = 0
    for k in engine_kernels.kernels():
        stats = k.fast.stats  # makes the dispatcher if need be; compiles nothing
        hits += sum(stats.cache_hits.values())
        misses += sum(stats.cache_misses.values())
    return hits, misses


#: The clocks each step is timed by: the thread's CPU time (the engine's own work, whatever
#: else the machine runs) and the wall clock (what a player sees).
CPU, WALL = 0, 1
#: The parts of a step timed: the engine's own step (``World.step``, ``Space.step``) and the
#: game's whole step (input and ground test, the engine's step, the coins).
PHYSICS, GAME = "physics", "game"


@dataclass
class Run:
    """One engine's scripted run, each time as (CPU, wall clock) seconds: ``made`` to build
    the game (World or Space, bodies, shapes), ``first`` its first (whole) step, and for every
    later step ``physics`` (n, 2), the engine's own step, and ``game`` (n, 2), the whole game
    step; the coins collected; the World's warnings (message -> count); on the fast path
    numba's cache counts over the build and the first step, ``loaded`` and ``compiled``
    (kernels), and ``later`` (kernels loaded or compiled after the first step, in play);
    ``ground`` (n, 2): a ground test (``ground_hit``) made again after each step, in play,
    where the World's query index is made again for the bodies' new places (empty: not
    timed)."""

    engine: str
    made: tuple[float, float]
    first: tuple[float, float]
    physics: np.ndarray
    game: np.ndarray
    coins: list[int]
    warned: Counter[str] = field(default_factory=Counter)
    loaded: int = 0
    compiled: int = 0
    later: int = 0
    ground: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))

    def times(self, part: str = PHYSICS, clock: int = CPU) -> np.ndarray:
        """Seconds of each step after the first: ``part`` PHYSICS or GAME, by ``clock``."""
        return (self.physics if part == PHYSICS else self.game)[:, clock]

    def median(self, part: str = PHYSICS, clock: int = CPU) -> float:
        return float(np.median(self.times(part, clock)))

    def p99(self, part: str = PHYSICS, clock: int = CPU) -> float:
        return float(np.percentile(self.times(part, clock), 99))

    def worst(self, part: str = PHYSICS, clock: int = CPU) -> float:
        return float(self.times(part, clock).max())

    def over_frame(self, part: str = PHYSICS, clock: int = CPU) -> float:
        """The share of steps (after the first) longer than a 60 fps frame."""
        return float((self.times(part, clock) > FRAME).mean())


def _builders(hinge: bool, fast: bool, pymunk: bool) -> dict[str, Callable[[], Any]]:
    """engine name -> a function that builds its game: this World on the numpy path, on the
    fast path where numba is installed and ``fast``, and pymunk's twin where installed and
    ``pymunk``."""
    out: dict[str, Callable[[], Any]] = {"World (numpy)": lambda: scene.build("numpy", hinge=hinge)}
    if fast and engine_kernels.available():
        out["World (fast)"] = lambda: scene.build("fast", hinge=hinge)
    # The same World with the soft step (World(solver="soft"): a game's solver).
    out["soft (numpy)"] = lambda: scene.build("numpy", hinge=hinge, solver="soft")
    if fast and engine_kernels.available():
        out["soft (fast)"] = lambda: scene.build("fast", hinge=hinge, solver="soft")
    if pymunk and make_space() is not None:
        out["pymunk"] = lambda: PymunkPlatformer(hinge)
    return out


def _clocks() -> tuple[float, float]:
    return time.thread_time(), time.perf_counter()


def _since(start: tuple[float, float]) -> tuple[float, float]:
    cpu, wall = _clocks()
    return cpu - start[CPU], wall - start[WALL]


def _step_noting(game: Any, warned: Counter[str]) -> tuple[tuple[float, float], ...]:
    """Step ``game`` once; the (CPU, wall) seconds its engine's step took, the whole step
    took, and a ground test made after it took (the game's own test, once more: what the
    next step's costs, in play; outside the whole step's clocks), the warnings it gave
    counted in ``warned``, outside the clocks."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        start = _clocks()
        game.control(DT)
        before = _clocks()
        game.physics(DT)
        physics = _since(before)
        game.collect()
        whole = _since(start)
        before = _clocks()
        game.ground_hit()
        ground = _since(before)
    warned.update(str(w.message).split(":")[0] for w in caught)
    return physics, whole, ground


def side_by_side(
    seconds: float = scene.SECONDS,
    *,
    without_hinge: bool = True,
    fast: bool = True,
    pymunk: bool = True,
) -> dict[str, Run]:
    """Play the script for ``seconds`` in every engine, one step each in turn, timing each
    step. ``without_hinge``: the same scenes without the seesaw's hinge too, named
    "... no hinge"; ``fast``, ``pymunk``: those engines too, where installed. Returns
    engine -> Run."""
    builders = _builders(True, fast, pymunk)
    if without_hinge:
        builders |= {f"{name}, no hinge": b for name, b in _builders(False, fast, pymunk).items()}
    names = list(builders)
    games: dict[str, Any] = {}
    made: dict[str, tuple[float, float]] = {}
    firsts: dict[str, tuple[float, float]] = {}
    warned: dict[str, Counter[str]] = {name: Counter() for name in names}
    numba_did: dict[str, tuple[int, int]] = {}
    counting = fast and engine_kernels.available()

    def counts() -> tuple[int, int]:
        return cache_counts() if counting else (0, 0)

    for name in names:  # built and stepped once, apart: the fast path's kernels load here
        before = counts()
        start = _clocks()
        games[name] = builders[name]()
        made[name] = _since(start)
        firsts[name] = _step_noting(games[name], warned[name])[1]
        after = counts()
        numba_did[name] = (after[0] - before[0], after[1] - before[1])
    settled = counts()
    steps = round(seconds / DT)
    times = {name: np.empty((3, steps - 1, 2)) for name in names}
    for i in range(steps - 1):
        k = i % len(names)
        for name in names[k:] + names[:k]:
            times[name][:, i] = _step_noting(games[name], warned[name])
    later = sum(counts()) - sum(settled)
    return {
        name: Run(name, made[name], firsts[name], times[name][0], times[name][1],
                  list(games[name].collected), warned[name], *numba_did[name],
                  later if "fast" in name else 0, times[name][2])
        for name in names
    }  # fmt: skip


def alone(seconds: float = 5.0, *, fast: bool = True, pymunk: bool = True) -> dict[str, float]:
    """Each soft engine and pymunk alone: its game built and the script played for ``seconds``
    with nothing stepped between its steps; engine -> the median CPU seconds of its own step.
    (``side_by_side`` steps every engine in turn, so each step starts with the others' code
    and data in the caches: that costs pymunk's small C step most.)"""
    builders = {
        name: b
        for name, b in _builders(True, fast, pymunk).items()
        if name.startswith("soft") or name == "pymunk"
    }
    out: dict[str, float] = {}
    warned: Counter[str] = Counter()
    for name, build in builders.items():
        game = build()
        _step_noting(game, warned)  # (the first step, apart, as side_by_side's)
        steps = [_step_noting(game, warned)[0][CPU] for _ in range(round(seconds / DT) - 1)]
        out[name] = float(np.median(steps))
    return out


#: Where a spawned ball appears (m), and its speed (m/s): up in the air, left of the crates.
SPAWN_AT, SPAWN_VELOCITY = (3.0, 6.0), (2.0, 0.0)


def _spawn(game: Any) -> Callable[[], None]:
    """Add a 0.1 m, 0.2 kg ball to ``game``'s engine (a game spawning a thing in play); return
    how to take it out again."""
    if isinstance(game, PymunkPlatformer):
        pm = game.pymunk
        body = pm.Body(0.2, pm.moment_for_circle(0.2, 0.0, 0.1))
        body.position, body.velocity = SPAWN_AT, SPAWN_VELOCITY
        shape = pm.Circle(body, 0.1)
        game.space.add(body, shape)
        return lambda: game.space.remove(body, shape)
    world = game.world
    ball = world.add(Body(SPAWN_AT, SPAWN_VELOCITY, mass=0.2, radius=0.1))
    return lambda: world.remove(ball)


def _then_steps(
    game: Any, change: Callable[[], Any], spawned: list[float], plain: list[float]
) -> Any:
    """``change()`` and ``game``'s next step, timed together (CPU s, into ``spawned``), then
    five steps more, each timed (into ``plain``); what ``change`` returned."""
    start = _clocks()
    made = change()
    game.step(DT)
    spawned.append(_since(start)[CPU])
    for _ in range(5):
        start = _clocks()
        game.step(DT)
        plain.append(_since(start)[CPU])
    return made


def spawns(rounds: int = 9, *, fast: bool = True, pymunk: bool = True) -> dict[str, float]:
    """Each soft engine and pymunk, its game played 1 s, then ``rounds`` times: a ball added
    and the game's next step, five steps, the ball taken out and the next step, five steps.
    Engine -> the median CPU seconds of (the add and the step after it) over the median of
    the plain steps between (what a game that spawns a thing waits on, in its own steps)."""
    builders = {
        name: b
        for name, b in _builders(True, fast, pymunk).items()
        if name.startswith("soft") or name == "pymunk"
    }
    out: dict[str, float] = {}
    for name, build in builders.items():
        game = build()
        for _ in range(round(1.0 / DT)):
            game.step(DT)
        spawned: list[float] = []
        plain: list[float] = []
        for _ in range(rounds):
            take = _then_steps(game, partial(_spawn, game), spawned, plain)
            _then_steps(game, take, spawned, plain)
        out[name] = float(np.median(spawned) / np.median(plain))
    return out


def query_times(rounds: int = 15) -> dict[str, float]:
    """Median seconds of one ground test (``segment_query_first`` 13 cm below the player's
    feet, the arguments made once) on this World (numpy path: the query uses no kernel) and
    on pymunk's twin (where installed), the player standing on the ground at t = 0."""
    ours = scene.build("numpy")
    start, end = ours.feet()
    world = ours.world

    def world_query() -> object:
        return world.segment_query_first(start, end, scene.PROBE_RADIUS, scene.FEET_FILTER)

    assert world_query() is not None
    candidates: dict[str, tuple[Callable[[], object], int]] = {"World": (world_query, 20)}
    twin = make_space()
    if twin is not None:
        a, b = tuple(start), tuple(end)
        space, feet = twin.space, twin.feet_filter

        def space_query() -> object:
            return space.segment_query_first(a, b, scene.PROBE_RADIUS, feet)

        assert space_query() is not None
        candidates["pymunk"] = (space_query, 2000)
    return compare(candidates, rounds=rounds)


def _ms(seconds: float) -> str:
    return f"{1e3 * seconds:.3f} ms" if seconds < 1e-3 else f"{1e3 * seconds:.1f} ms"


def _x(value: float, peer: float | None) -> str:
    return f"{value / peer:.0f}x" if peer else "-"


def _rows(runs: dict[str, Run], part: str, clock: int, firsts: bool, coins: bool) -> list[str]:
    """One section of the table: each engine's steps' ``part`` by ``clock`` (the build and
    first step too if ``firsts``; the coins if ``coins``), against pymunk's median."""
    peer_run = runs.get("pymunk")
    peer = peer_run.median(part, clock) if peer_run is not None else None
    first = f" {'build':>9} {'1st step':>9}" if firsts else ""
    lines = [
        f"  {'engine':14}{first} {'median':>9} {'p99':>9} {'worst':>9} "
        f"{'x pymunk median: median/p99/worst':>34} {'over 16.7 ms':>12}"
        + (f" {'coins':>7}" if coins else "")
    ]
    for name, r in runs.items():
        if "no hinge" in name:
            continue
        first = f" {_ms(r.made[clock]):>9} {_ms(r.first[clock]):>9}" if firsts else ""
        m, p, w = r.median(part, clock), r.p99(part, clock), r.worst(part, clock)
        ratios = f"{_x(m, peer)} / {_x(p, peer)} / {_x(w, peer)}"
        lines.append(
            f"  {name:14}{first} {_ms(m):>9} {_ms(p):>9} {_ms(w):>9} {ratios:>34} "
            f"{100 * r.over_frame(part, clock):11.1f}%"
            + (f" {len(r.coins):>2} of {len(scene.COINS)}" if coins else "")
        )
    return lines


def table(
    runs: dict[str, Run],
    seconds: float,
    query: dict[str, float],
    apart: dict[str, float] | None = None,
) -> list[str]:
    """The report's lines for ``runs`` (``side_by_side``) over ``seconds`` of the script, the
    ground test's ``query`` times (``query_times``) and each engine's median step played
    ``apart`` (``alone``), if given."""
    lines = [
        f"platformer: the small game (demos.platformer_scene: a rope bridge of "
        f"{scene.BRIDGE_PLANKS} planks on hinges, {len(scene.CRATES)} crates, a seesaw on a "
        f"hinge, a moving platform, a ball, {len(scene.COINS)} coin sensors), its script's "
        f"first {seconds:g} s ({round(seconds / DT)} steps of 1/60 s), "
        f"the engines one step each in turn; pymunk {ITERATIONS} iterations",
        "  the engine's step (World.step, Space.step), CPU time (the engine's own work, "
        "whatever else the machine runs); build and 1st step: the game's, apart",
        *_rows(runs, PHYSICS, CPU, firsts=True, coins=True),
        "  the game's whole step (input and ground test, the engine's step, the coins), CPU time",
        *_rows(runs, GAME, CPU, firsts=False, coins=False),
        "  the game's whole step by the wall clock (what a player of this machine saw, with its "
        "other work)",
        *_rows(runs, GAME, WALL, firsts=True, coins=False),
    ]
    if apart:
        peer = apart.get("pymunk")
        lines.append(
            "  each soft engine alone (the script played with nothing between its steps, so "
            "its own code and data stay in the caches), the engine's median step (CPU): "
            + ", ".join(
                f"{name} {_ms(t)}" + (f" ({t / peer:.0f}x)" if peer and name != "pymunk" else "")
                for name, t in apart.items()
            )
        )
    fast = runs.get("World (fast)")
    if fast is None:
        lines.append("  World (fast): numba is not installed (pip install -e '.[fast]'): skipped")
    else:
        if fast.compiled:
            cache = (
                f"numba's cache was cold: it compiled {fast.compiled} kernel(s) and loaded "
                f"{fast.loaded} from the cache"
            )
        elif fast.loaded:
            cache = f"numba's cache was warm: it loaded all {fast.loaded} kernels from it"
        else:
            cache = "the kernels were in memory already (loaded earlier in this process)"
        lines.append(
            f"  the fast path's build and first step: {cache}; later, in play, "
            f"{fast.later} more loaded or compiled"
        )
    if "pymunk" not in runs:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    lines.append(f"  as measured first: numpy {ISSUE['numpy']}; fast {ISSUE['fast']}")
    hinged = [
        (name, runs[name].median() / runs[f"{name}, no hinge"].median())  # the engine's, CPU
        for name in runs
        if f"{name}, no hinge" in runs
    ]
    if hinged:
        lines.append(
            "  the seesaw's hinge, the engine's median step (CPU) with it over without it "
            "(without, the plank falls and lies on the ground): "
            + ", ".join(f"{n} {x:.2f}x" for n, x in hinged)
        )
    for name, r in runs.items():
        if r.warned:
            said = "; ".join(f"{m} ({n}x)" for m, n in r.warned.most_common(3))
            lines.append(f"  {name} warned: {said}")
    ours, theirs = query["World"], query.get("pymunk")
    lines.append(
        f"  the ground test, one {100 * scene.GROUND_PROBE:.0f} cm segment_query_first "
        f"below the feet, median (wall clock): World {1e6 * ours:.1f} us"
        + (f", pymunk {1e6 * theirs:.2f} us: {ours / theirs:.0f}x" if theirs else "")
        + f"; {100 * ours / FRAME:.2f}% of a 60 fps frame"
    )
    # The same test in play: after each step, where the World's query index is made again.
    played = {
        name: float(np.median(r.ground[:, CPU]))
        for name, r in runs.items()
        if len(r.ground) and "no hinge" not in name
    }
    if played:
        peer = played.get("pymunk")
        lines.append(
            "  the same ground test in play, after each step (the bodies moved: the World's "
            "query index is made again), median (CPU): "
            + ", ".join(
                f"{name} {1e6 * t:.1f} us"
                + (f" ({t / peer:.0f}x)" if peer and name != "pymunk" else "")
                for name, t in played.items()
            )
        )
    return lines


def report(quick: bool = False) -> str:
    """Run the platformer in every engine, and time the ground test; return the text."""
    seconds = 5.0 if quick else scene.SECONDS
    runs = side_by_side(seconds)
    query = query_times(rounds=5 if quick else 15)
    lines = table(runs, seconds, query, alone(seconds))
    spawned = spawns(rounds=5 if quick else 9)
    lines.append(
        "  a ball spawned in play (added, or taken out again, and the game's next step), "
        "over the game's median step (CPU): "
        + ", ".join(f"{name} {x:.1f}x" for name, x in spawned.items())
    )
    return "\n".join(lines)
