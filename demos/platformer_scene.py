"""A small platformer, built from the README's pieces: the scene the issue "Games at C speed"
measures, shared by ``demos.bench.platformer`` (which times it beside pymunk's twin) and
``tests/test_bench_platformer.py``.

The level (metres, y up, g = 9.81 m/s^2, dt = 1/60 s), 30 m wide between two walls:

* static geometry, all ``Segment`` colliders: the ground (a thin segment at y = 0), two walls
  and three ledges (capsules: segments with a radius), one of them slanted;
* the player: a 0.8 x 1.6 m box of 4 kg that never turns (``fixed_rotation=True``), no
  friction (the game sets its horizontal speed every step, so it neither sticks to walls nor
  drags on the ground);
* six 1 m crates of 2 kg in a pyramid (3, 2, 1), friction 0.6, that turn;
* a seesaw: a 4 x 0.2 m plank of 5 kg on a ``Hinge`` to the world at its middle, 0.6 m up;
* a moving platform: a kinematic 2.5 x 0.3 m box the game moves left and right at 1.5 m/s;
* a ball (r 0.3 m, 1 kg) that rolls down the slanted ledge and off it;
* a rope bridge from the first ledge's end, 2.6 m over the floor before the crates: six
  0.45 x 0.12 m planks of 2 kg joined end to end by ``Hinge``s at the corners of their tops
  (the outer two to ``world.static_body``), hanging 0.32 m at its middle;
* five coins: ``Circle`` sensors, each taken out of the World when the player touches it.

The input is a script, ``script(t) -> (run, jump)``: run in [-1, 1] (the stick), jump (the
button held). ``Platformer.step(dt)`` does what a game's fixed step does: read the input,
test for ground with one short ``segment_query_first`` below the player's feet (13 cm,
``GROUND_PROBE``), set the player's horizontal velocity (toward the stick's, changing by at
most ``RUN_ACCEL`` dt, plus the platform's when standing on it), give a jump impulse on a
press while on the ground, step the World, then collect the coins whose sensors reported the
player (``on_contact(coin, begin=...)``).

The geometry is data (``GROUND``, ``WALLS``, ``LEDGES``, ``CRATES``, ``BRIDGE_ENDS``, ``COINS``,
...), so that pymunk's twin in ``demos.bench.platformer`` is built from the same numbers.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from engine import (
    Body,
    Circle,
    ContactEvent,
    Filter,
    Hinge,
    Polygon,
    QueryHit,
    Segment,
    Vector,
    World,
)
from engine.forces import Gravity

__all__ = [
    "DT",
    "SECONDS",
    "G",
    "WIDTH",
    "GROUND",
    "WALLS",
    "LEDGES",
    "STATIC",
    "PLAYER_SIZE",
    "PLAYER_MASS",
    "PLAYER_START",
    "RUN_SPEED",
    "JUMP_SPEED",
    "GROUND_PROBE",
    "PROBE_INSET",
    "PROBE_RADIUS",
    "RUN_ACCEL",
    "FEET_FILTER",
    "CRATE",
    "CRATE_MASS",
    "CRATES",
    "SEESAW_PIVOT",
    "SEESAW_SIZE",
    "SEESAW_MASS",
    "PLATFORM_START",
    "PLATFORM_SIZE",
    "PLATFORM_SPEED",
    "PLATFORM_PERIOD",
    "PLATFORM_PHASE",
    "BALL_START",
    "BALL_RADIUS",
    "BALL_MASS",
    "BRIDGE_ENDS",
    "BRIDGE_PLANKS",
    "BRIDGE_PLANK",
    "BRIDGE_MASS",
    "BRIDGE_BIT",
    "BRIDGE_FILTER",
    "bridge_deck",
    "bridge_planks",
    "add_bridge",
    "COINS",
    "COIN_RADIUS",
    "PLAYER_BIT",
    "COIN_BIT",
    "SCRIPT",
    "script",
    "feet_segment",
    "toward",
    "platform_velocity",
    "Platformer",
    "build",
]

DT = 1.0 / 60.0  # s: the game's fixed step
SECONDS = 20.0  # s: the script's length
G = 9.81  # m/s^2
WIDTH = 30.0  # m: between the walls' axes

#: Static segments: (a, b, radius) in metres. The ground is a thin segment at y = 0.
GROUND: tuple[tuple[float, float], tuple[float, float], float] = ((0.0, 0.0), (WIDTH, 0.0), 0.0)
#: The walls: capsules 0.25 m thick on each side of their axes x = 0 and x = WIDTH.
WALLS: tuple[tuple[tuple[float, float], tuple[float, float], float], ...] = (
    ((0.0, 0.0), (0.0, 10.0), 0.25),
    ((WIDTH, 0.0), (WIDTH, 10.0), 0.25),
)
#: The ledges: capsules of radius 0.1; the last is slanted (the ball rolls down it).
LEDGES: tuple[tuple[tuple[float, float], tuple[float, float], float], ...] = (
    ((4.5, 2.0), (7.5, 2.0), 0.1),
    ((0.25, 4.0), (3.0, 4.0), 0.1),
    ((24.5, 6.5), (28.5, 4.5), 0.1),
)
#: Every static segment, in the order they are added (ground, walls, ledges).
STATIC = (GROUND, *WALLS, *LEDGES)

PLAYER_SIZE = (0.8, 1.6)  # m: width, height
PLAYER_MASS = 4.0  # kg
PLAYER_START = (1.0, 0.8)  # m: standing on the ground
RUN_SPEED = 5.0  # m/s at full stick
#: m/s^2: how fast the player's horizontal speed may change toward the stick's (its legs'
#: grip: it can shove a crate, not fling one)
RUN_ACCEL = 25.0
JUMP_SPEED = 7.5  # m/s: the jump impulse is PLAYER_MASS * JUMP_SPEED
#: m: the ground test, a segment GROUND_PROBE long straight down below the player's centre,
#: from PROBE_INSET above the soles (inside the player, which its filter leaves out): it finds
#: ground up to 8 cm below the soles. A thin ray (PROBE_RADIUS 0), not a swept disc: pymunk's
#: segment queries with a radius miss shapes whose bounding box the bare segment does not
#: touch (Chipmunk2D issue 138), and both engines run the same test.
GROUND_PROBE = 0.13
PROBE_INSET = 0.05
PROBE_RADIUS = 0.0

CRATE = 1.0  # m: a crate's side
CRATE_MASS = 2.0  # kg
#: The pyramid's crates, bottom row first, each 1 cm from its neighbours.
CRATES: tuple[tuple[float, float], ...] = (
    (13.0, 0.5),
    (14.01, 0.5),
    (15.02, 0.5),
    (13.505, 1.5),
    (14.515, 1.5),
    (14.01, 2.5),
)
CRATE_FRICTION = 0.6

SEESAW_PIVOT = (19.0, 0.6)  # m: the hinge, at the plank's middle
SEESAW_SIZE = (4.0, 0.2)  # m
SEESAW_MASS = 5.0  # kg

PLATFORM_START = (27.5, 1.6)  # m: the moving platform's centre at t = 0
PLATFORM_SIZE = (2.5, 0.3)  # m
PLATFORM_SPEED = 1.5  # m/s
PLATFORM_PERIOD = 6.0  # s: right for half of it, then left
#: s: where in its period the platform is at t = 0 (at its right end, x 27.5, turning left;
#: it turns at x 23 and 27.5)
PLATFORM_PHASE = 3.0

BALL_START = (25.0, 6.71)  # m: on the slanted ledge's top end
BALL_RADIUS = 0.3  # m
BALL_MASS = 1.0  # kg

#: The rope bridge: planks joined end to end by hinges at the corners of their tops (its deck
#: one unbroken line, bent at the hinges), the outer ones hinged to two points of the world at
#: one height (m): just past the first ledge's right end, level with its top, and 2.6 m to the
#: right, over the floor before the crates.
BRIDGE_ENDS: tuple[tuple[float, float], tuple[float, float]] = ((7.7, 2.1), (10.3, 2.1))
BRIDGE_PLANKS = 6
#: m: a plank's length and thickness: 6 x 0.45 = 2.7 m of deck over the 2.6 m span, which
#: hangs 0.32 m at its middle
BRIDGE_PLANK = (0.45, 0.12)
BRIDGE_MASS = 2.0  # kg a plank

#: The coins' centres (m): sensors of radius COIN_RADIUS on the script's path.
COINS: tuple[tuple[float, float], ...] = (
    (2.0, 1.0),
    (6.0, 3.0),
    (8.9, 2.9),
    (18.0, 2.6),
    (27.5, 3.2),
)
COIN_RADIUS = 0.3  # m

#: Filter categories: the player, and the coins (the ground test sees neither).
PLAYER_BIT = 0b01
COIN_BIT = 0b10
#: The bridge's planks: they do not collide with each other (they meet at their hinges).
BRIDGE_BIT = 0b100
BRIDGE_FILTER = Filter(categories=BRIDGE_BIT, mask=0xFFFFFFFF & ~BRIDGE_BIT)
#: What the ground test sees: everything but the player and the coins.
FEET_FILTER = Filter(categories=0xFFFFFFFF, mask=0xFFFFFFFF & ~(PLAYER_BIT | COIN_BIT))

#: The input, as (until t (s), run, jump): each row holds from the end of the one before.
SCRIPT: tuple[tuple[float, float, bool], ...] = (
    (0.3, 0.0, False),  # stand
    (0.5, 1.0, False),  # run right, through the first coin
    (0.6, 1.0, True),  # jump onto the first ledge (the second coin on the way)
    (1.25, 1.0, False),
    (2.0, 0.0, False),  # land on it
    (5.2, 0.4, False),  # walk off its end onto the bridge, across it (the third coin), off it
    (7.0, 1.0, False),  # shove the pyramid along the ground
    (7.1, 0.6, True),  # jump onto the crates
    (8.5, 0.6, False),  # across them (the fourth coin, over the seesaw)
    (9.5, 1.0, False),  # down the seesaw to the ground
    (9.6, 0.0, False),
    (9.7, 0.3, True),  # jump after the moving platform
    (10.0, 0.3, False),
    (10.5, 0.8, False),  # onto it
    (11.8, 0.0, False),  # ride it right
    (11.9, 0.0, True),  # jump on it at its far end (the fifth coin)
    (14.3, 0.0, False),  # ride it back
    (14.4, -1.0, True),  # jump off it, left
    (19.4, -1.0, False),  # over the crates, run back left under the bridge to the left wall
    (19.5, 0.0, False),
    (19.6, 0.0, True),  # a last jump
    (SECONDS, 0.0, False),
)


def script(t: float) -> tuple[float, bool]:
    """The input at time ``t`` (s): (run in [-1, 1], jump held); nothing after the script."""
    for until, run, jump in SCRIPT:
        if t < until - 1e-9:
            return run, jump
    return 0.0, False


def platform_velocity(t: float) -> float:
    """The moving platform's horizontal velocity (m/s) over the step starting at ``t``:
    right for the first half of each period, left for the second."""
    phase = math.fmod(t + PLATFORM_PHASE + 1e-9, PLATFORM_PERIOD)
    return PLATFORM_SPEED if phase < PLATFORM_PERIOD / 2 else -PLATFORM_SPEED


def bridge_deck() -> list[tuple[float, float]]:
    """The bridge's deck as built (m): the BRIDGE_PLANKS + 1 hinges, left to right, from one of
    BRIDGE_ENDS to the other, a plank's length apart.

    It hangs as a chain of planks at rest does: the hinges pull each plank with the same
    horizontal part H all along, and the vertical part grows by one plank's weight w from one
    hinge to the next; a plank's moments about its middle balance when its slope is the mean
    of the vertical pulls at its ends over H (over H + w t / 2l, the hinges being at its top,
    t / 2 off its middle: l, t its length and thickness), so the slopes grow by one step c
    from plank to plank: tan(angle_k) = c (k - (n - 1) / 2), with c the one that spans the
    ends (found by bisection). The exact solver finds the bridge so built at rest (to 0.1 mm);
    the soft step's hinges give under its pull by millimetres."""
    (x0, y0), (x1, _) = BRIDGE_ENDS
    span, n, length = x1 - x0, BRIDGE_PLANKS, BRIDGE_PLANK[0]
    if n * length <= span:
        raise ValueError(f"the planks ({n} x {length} m) must be longer than the span {span} m")

    def angles(c: float) -> list[float]:
        return [math.atan(c * (k - (n - 1) / 2)) for k in range(n)]

    def reach(c: float) -> float:
        return length * sum(math.cos(a) for a in angles(c))

    low, high = 0.0, 1.0
    while reach(high) > span:
        high *= 2.0
    for _ in range(100):
        mid = (low + high) / 2
        low, high = (mid, high) if reach(mid) > span else (low, mid)
    points = [(x0, y0)]
    for a in angles((low + high) / 2):
        x, y = points[-1]
        points.append((x + length * math.cos(a), y + length * math.sin(a)))
    return points


def bridge_planks() -> list[tuple[float, float, float]]:
    """The bridge's planks as built: (x, y, angle) of each (m, rad), left to right, the top of
    each from one hinge of ``bridge_deck`` to the next."""
    deck, half = bridge_deck(), BRIDGE_PLANK[1] / 2
    out = []
    for (xa, ya), (xb, yb) in zip(deck, deck[1:], strict=False):
        a = math.atan2(yb - ya, xb - xa)
        # The middle of the top, then half the thickness down, square to the plank.
        out.append(((xa + xb) / 2 + half * math.sin(a), (ya + yb) / 2 - half * math.cos(a), a))
    return out


def feet_segment(x: float, y: float) -> tuple[Vector, Vector]:
    """The ground test's segment for a player centred at (x, y): from PROBE_INSET above the
    soles, GROUND_PROBE (13 cm) straight down."""
    top = y - PLAYER_SIZE[1] / 2 + PROBE_INSET
    return Vector(x, top), Vector(x, top - GROUND_PROBE)


def toward(vx: float, target: float, dt: float) -> float:
    """The player's horizontal speed (m/s) after a step of ``dt`` toward ``target``, changing
    by at most RUN_ACCEL dt."""
    most = RUN_ACCEL * dt
    return vx + min(max(target - vx, -most), most)


@dataclass
class Platformer:
    """The scene's World and its bodies, stepped as a game steps: ``step(dt)``.

    ``planks`` and ``bridge_hinges``: the rope bridge's, left to right (``add_bridge``);
    ``collected``: the coins' indices (into ``COINS``) in the order the player took them;
    ``jumps``: the times (s) of the jumps given; ``landings``: the times the ground test
    turned true again after being false.
    """

    world: World
    player: Body
    crates: list[Body]
    seesaw: Body
    hinge: Hinge | None
    platform: Body
    ball: Body
    coins: list[Circle]
    ground: list[Segment]
    planks: list[Body]
    bridge_hinges: list[Hinge]
    collected: list[int] = field(default_factory=list)
    jumps: list[float] = field(default_factory=list)
    landings: list[float] = field(default_factory=list)
    _touched: list[int] = field(default_factory=list)
    _held: bool = False
    _was_grounded: bool = True

    def __post_init__(self) -> None:
        for index, coin in enumerate(self.coins):
            self.world.on_contact(coin, begin=self._coin_handler(index))

    def _coin_handler(self, index: int) -> Callable[[ContactEvent], None]:
        def begin(event: ContactEvent) -> None:
            if event.body is self.player:
                self._touched.append(index)

        return begin

    @property
    def t(self) -> float:
        """The World's time (s)."""
        return self.world.t

    def feet(self) -> tuple[Vector, Vector]:
        """The ground test's segment, from and to (``feet_segment``)."""
        p = self.player.pos
        return feet_segment(p.x, p.y)

    def ground_hit(self) -> QueryHit | None:
        """What is under the player's feet (a Body or a collider), or None in the air."""
        start, end = self.feet()
        return self.world.segment_query_first(start, end, PROBE_RADIUS, FEET_FILTER)

    def on_ground(self) -> bool:
        """Whether the player stands on something (the ground test)."""
        return self.ground_hit() is not None

    def step(self, dt: float = DT) -> None:
        """One fixed step of the game: ``control`` (input, ground test, the player's speed and
        jump, the platform), the World's step, ``collect`` (the coins)."""
        self.control(dt)
        self.physics(dt)
        self.collect()

    def control(self, dt: float = DT) -> None:
        """The game's input before the World's step: the platform's velocity, the ground test,
        the player's horizontal velocity and a jump impulse."""
        t = self.world.t
        run, jump = script(t)
        self.platform.vel = Vector(platform_velocity(t), 0.0)
        hit = self.ground_hit()
        grounded = hit is not None
        if grounded and not self._was_grounded:
            self.landings.append(t)
        self._was_grounded = grounded
        carry = 0.0
        if hit is not None and isinstance(hit.shape, Body) and hit.shape.kinematic:
            carry = hit.shape.vel.x
        player = self.player
        vel = player.vel
        player.vel = Vector(toward(vel.x, run * RUN_SPEED + carry, dt), vel.y)
        if jump and not self._held and grounded:
            player.apply_impulse(Vector(0.0, PLAYER_MASS * JUMP_SPEED))
            self.jumps.append(t)
            self._was_grounded = False
        self._held = jump

    def physics(self, dt: float = DT) -> None:
        """The World's step."""
        self.world.step(dt)

    def take_touched(self) -> list[int]:
        """The coins (indices into ``COINS``) whose sensors reported the player since the last
        call, in order (a coin touched twice is listed twice); the list is emptied."""
        touched, self._touched = self._touched, []
        return touched

    def collect(self) -> None:
        """After the World's step: each coin whose sensor reported the player is counted (once)
        and taken out of the World."""
        for index in self.take_touched():
            if index not in self.collected:
                self.collected.append(index)
                self.world.remove_collider(self.coins[index])


def build(kernels: str | None = None, *, hinge: bool = True, solver: str = "exact") -> Platformer:
    """The scene in a new World on the path ``kernels`` (None: the default; "numpy", "fast")
    with the ``solver`` ("exact" or "soft": ``World``'s).
    ``hinge=False``: the same scene without the seesaw's hinge (its plank falls and lies on
    the ground), to measure what the hinge costs."""
    world = World(integrator="auto", kernels=kernels, solver=solver)
    world.add_force(Gravity((0.0, -G)))
    ground = [world.add_collider(Segment(a, b, r)) for a, b, r in STATIC]
    w, h = PLAYER_SIZE
    player = world.add(
        Body(Vector(*PLAYER_START), shape=Polygon.box(w, h), mass=PLAYER_MASS,
             restitution=0.0, friction=0.0, fixed_rotation=True,
             filter=Filter(categories=PLAYER_BIT))
    )  # fmt: skip
    crates = [
        world.add(
            Body(
                Vector(x, y),
                shape=Polygon.box(CRATE, CRATE),
                mass=CRATE_MASS,
                restitution=0.0,
                friction=CRATE_FRICTION,
            )
        )  # fmt: skip
        for x, y in CRATES
    ]
    seesaw = world.add(
        Body(Vector(*SEESAW_PIVOT), shape=Polygon.box(*SEESAW_SIZE), mass=SEESAW_MASS,
             restitution=0.0, friction=CRATE_FRICTION)
    )  # fmt: skip
    joint = world.add_link(Hinge(seesaw, world.static_body, SEESAW_PIVOT)) if hinge else None
    platform = world.add(
        Body(Vector(*PLATFORM_START), Vector(platform_velocity(0.0), 0.0),
             shape=Polygon.box(*PLATFORM_SIZE), kinematic=True, restitution=0.0,
             friction=CRATE_FRICTION)
    )  # fmt: skip
    ball = world.add(
        Body(Vector(*BALL_START), radius=BALL_RADIUS, mass=BALL_MASS, restitution=0.2,
             friction=CRATE_FRICTION)
    )  # fmt: skip
    coins = [
        world.add_collider(Circle(c, COIN_RADIUS, sensor=True, filter=Filter(categories=COIN_BIT)))
        for c in COINS
    ]
    planks, bridge_hinges = add_bridge(world)
    return Platformer(
        world, player, crates, seesaw, joint, platform, ball, coins, ground, planks, bridge_hinges
    )


def add_bridge(world: World) -> tuple[list[Body], list[Hinge]]:
    """The rope bridge in ``world``: BRIDGE_PLANKS planks (``bridge_planks``) and a ``Hinge`` at
    each point of ``bridge_deck``: between two planks, or the first or last plank and
    ``world.static_body``. Returns the planks and the hinges, left to right."""
    planks = [
        world.add(
            Body(
                Vector(x, y),
                angle=angle,
                shape=Polygon.box(*BRIDGE_PLANK),
                mass=BRIDGE_MASS,
                restitution=0.0,
                friction=CRATE_FRICTION,
                filter=BRIDGE_FILTER,
            )
        )
        for x, y, angle in bridge_planks()
    ]
    ends = [world.static_body, *planks, world.static_body]
    hinges = [
        world.add_link(Hinge(b, a, point) if a is world.static_body else Hinge(a, b, point))
        for a, b, point in zip(ends[:-1], ends[1:], bridge_deck(), strict=True)
    ]
    return planks, hinges
