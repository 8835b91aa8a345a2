"""The platformer: run, jump, cross a rope bridge, shove crates, ride a moving platform and
collect every coin, on the engine's public API.

The level is the benchmark's scene (``demos/platformer_scene.py``: metres, g = 9.81 m/s^2,
dt = 1/60 s): a player box that never turns, a rope bridge of six planks joined end to end by
``Hinge``s that sags under it, a pyramid of crates to shove, a seesaw on a ``Hinge``, a
kinematic platform moving left and right, a ball rolling down a slanted ledge, and five coins
(``Circle`` sensors that stop sensing once the player has touched them; the third hangs over
the bridge). The game adds two things the benchmark leaves out:

* a one-way ledge (``ONE_WAY``): a ``Segment`` with its own collision type, and a ``pre_solve``
  from ``world.on_collision`` that ignores the contact unless the player is above it and not
  going up, so the player jumps up through it and lands on it;
* a conveyor: the upper-left ledge's ``surface_velocity`` moves along it toward the wall at
  BELT_SPEED; the player (no friction: the game sets its speed) is carried by it as by the
  platform.

The game's step (``PlatformerGame.step``, an :class:`engine.Steppable`): read the controls (the
autopilot or the keys), test for ground (the scene's ``segment_query_first`` below the feet),
set the player's horizontal speed, jump on a press while on the ground, step the World, count
the coins. On ground the player's own speed (relative to what it stands on) moves toward the
stick's by at most RUN_ACCEL dt, and the ground's speed is added to it whole: standing still on
the platform, the player moves with it exactly, through its turns too.

    python -m demos platformer --window   # play: arrows or A/D run, Up, W or space jumps
    python -m demos platformer            # headless: the autopilot collects every coin,
                                          # frames to out/platformer/

The autopilot plays the scene's script (``platformer_scene.script``: onto the first ledge,
across the bridge, the crates shoved, over them) until four coins are taken, then goes for the
last one on its own: it waits beside the platform, jumps onto it as it comes by, steers in the
air over its middle and rides it to the coin at its far end.
"""

from __future__ import annotations

import argparse
import copy
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, NamedTuple

import pygame

from demos import platformer_scene as ps
from demos.cli import Demo
from demos.games import run_game
from engine import Body, ContactEvent, Filter, QueryHit, Segment, Vector
from engine.render import Camera, Scene, draw_text, draw_world
from engine.world import WorldSnapshot

DT = ps.DT
#: Points for a coin.
COIN_POINTS = 100
#: A coin taken: it senses nothing (its mask is empty).
TAKEN = Filter(categories=ps.COIN_BIT, mask=0)
#: The one-way ledge: (a, b, radius) in metres, high over the crates' side of the level, and
#: the collision types of the player and of the ledge.
ONE_WAY: tuple[tuple[float, float], tuple[float, float], float] = ((8.3, 4.0), (10.0, 4.0), 0.1)
PLAYER_TYPE, ONE_WAY_TYPE = 1, 2
#: The conveyor: the upper-left ledge (ps.LEDGES[1]) moves along itself at this speed (m/s,
#: toward the wall).
BELT_SPEED = 1.5
BELT_INDEX = 1 + len(ps.WALLS) + 1  # in ps.STATIC: the ground, the walls, then the ledges
#: The autopilot's stand (m) to wait for the platform, clear of the seesaw's lowered end (at
#: x 20.94: its feet probe must find the ground), and the platform's
#: centre (m) between which it jumps as the platform comes toward its right end.
STAND_X = 21.4
JUMP_WINDOW = (23.2, 24.2)
#: Where under the player (m from its middle) the ground test looks, in turn: the middle
#: first, then 5 cm in from each side.
FEET = (0.0, -(ps.PLAYER_SIZE[0] / 2 - 0.05), ps.PLAYER_SIZE[0] / 2 - 0.05)
#: How long a game in a window may last (s) when no --seconds is given: until it is closed.
WINDOW_SECONDS = 24 * 3600.0
#: A headless run without --seconds stops this long after the last coin, or at MAX_SECONDS.
AFTER_END, MAX_SECONDS = 1.0, 40.0

SKY, INK = (24, 28, 44), (236, 236, 244)
PLAYER_COLOUR, CRATE_COLOUR, COIN_COLOUR = (255, 120, 40), (170, 110, 60), (255, 215, 0)
PLATFORM_COLOUR, SEESAW_COLOUR, BALL_COLOUR = (90, 200, 120), (150, 150, 190), (220, 60, 80)
PLANK_COLOUR = (215, 170, 100)  # the bridge's: a lighter wood than the crates'
GROUND_COLOUR, BELT_COLOUR, ONE_WAY_COLOUR = (120, 126, 150), (80, 170, 230), (200, 160, 255)


class Controls(NamedTuple):
    """What the player does this step: the stick (-1 left to 1 right) and the jump button."""

    run: float = 0.0
    jump: bool = False


#: A player: given the game, its controls for this step.
Player = Callable[["PlatformerGame"], Controls]


@dataclass
class Score:
    """Where the game stands: the coins taken (indices into ps.COINS, in order) and points."""

    coins: list[int] = field(default_factory=list)

    @property
    def points(self) -> int:
        """COIN_POINTS a coin."""
        return COIN_POINTS * len(self.coins)

    @property
    def over(self) -> bool:
        """Whether every coin is taken."""
        return len(self.coins) == len(ps.COINS)


@dataclass(frozen=True)
class PlatformerSnapshot:
    """Everything a game needs to resume: see :meth:`PlatformerGame.snapshot`."""

    world: WorldSnapshot
    collected: tuple[int, ...]
    held: bool
    carry: float
    memory: dict[str, Any]


class PlatformerGame:
    """The game's state and rules on the scene's World (``ps.build(kernels)``).

    ``step(dt)`` is one fixed step of the whole game; ``t`` is the World's time; ``player``
    says what the controls are (by default the autopilot). ``carry`` is the speed (m/s) of
    what the player stood on in the last step (0 in the air).
    """

    def __init__(self, kernels: str | None = None, player: Player | None = None) -> None:
        self.level = ps.build(kernels, solver="soft")
        self.world = self.level.world
        self.player: Player = autopilot if player is None else player
        world, hero = self.world, self.level.player
        hero.collision_type = PLAYER_TYPE
        a, b, r = ONE_WAY
        self.ledge = world.add_collider(Segment(a, b, r, restitution=0.0, colour=ONE_WAY_COLOUR))
        self.ledge.collision_type = ONE_WAY_TYPE
        world.on_collision(PLAYER_TYPE, ONE_WAY_TYPE, pre_solve=one_way)
        self.belt = self.level.ground[BELT_INDEX]
        self.belt.surface_velocity = Vector(-BELT_SPEED, 0.0)
        self._colour()
        self.carry = 0.0
        self._held = False
        #: What the autopilot remembers from step to step.
        self.memory: dict[str, Any] = {}

    def _colour(self) -> None:
        level = self.level
        level.player.colour = PLAYER_COLOUR
        for crate in level.crates:
            crate.colour = CRATE_COLOUR
        level.platform.colour = PLATFORM_COLOUR
        level.seesaw.colour = SEESAW_COLOUR
        level.ball.colour = BALL_COLOUR
        for plank in level.planks:
            plank.colour = PLANK_COLOUR
        for segment in level.ground:
            segment.colour = GROUND_COLOUR
        self.belt.colour = BELT_COLOUR
        for coin in level.coins:
            coin.colour = COIN_COLOUR

    @property
    def t(self) -> float:
        """The game's time (s): the World's."""
        return self.world.t

    @property
    def score(self) -> Score:
        """The coins taken so far."""
        return Score(list(self.level.collected))

    def ground(self) -> QueryHit | None:
        """What the player stands on, or None: the scene's ground test (a ray 13 cm down from
        just above the soles) under the middle of the feet, else under either end of them
        (FEET: a corner of a crate is ground too), less the one-way ledge while the player
        goes up through it."""
        hero = self.level.player
        hit = None
        for dx in FEET:
            start, end = ps.feet_segment(hero.pos.x + dx, hero.pos.y)
            hit = self.world.segment_query_first(start, end, ps.PROBE_RADIUS, ps.FEET_FILTER)
            if hit is not None:
                break
        if hit is not None and hit.shape is self.ledge and hero.vel.y > 0.0:
            return None
        return hit

    def ground_speed(self, hit: QueryHit | None) -> float:
        """The horizontal speed (m/s) of what the player stands on: a kinematic body's, the
        belt's surface, else 0."""
        if hit is None:
            return 0.0
        if isinstance(hit.shape, Body):
            return hit.shape.vel.x if hit.shape.kinematic else 0.0
        return float(hit.shape.surface_velocity.x)

    def step(self, dt: float = DT) -> None:
        """One fixed step of ``dt`` s: controls, the World, the coins."""
        self.control(dt)
        self.world.step(dt)
        self.collect()

    def collect(self) -> None:
        """After the World's step: each coin whose sensor reported the player is counted once
        and senses nothing more (its filter: TAKEN). It stays in the World, unlike the
        benchmark's (``Platformer.collect`` removes it), so that a snapshot taken before it
        restores into the same colliders."""
        for index in self.level.take_touched():
            if index not in self.level.collected:
                self.level.collected.append(index)
                self.level.coins[index].filter = TAKEN

    def control(self, dt: float) -> None:
        """Before the World's step: the platform's velocity, the ground test, the player's
        horizontal speed (its own toward the stick's, plus the ground's) and a jump."""
        level, hero = self.level, self.level.player
        level.platform.vel = Vector(ps.platform_velocity(self.t), 0.0)
        controls = Controls() if self.score.over else self.player(self)
        hit = self.ground()
        vx, vy = hero.vel
        target = controls.run * ps.RUN_SPEED
        if hit is None:
            vx, self.carry = ps.toward(vx, target, dt), 0.0
        else:
            # Relative to what carried it in the last step (feet do not slide), plus this
            # step's speed of what it stands on: standing still it moves with it exactly.
            under = self.ground_speed(hit)
            vx = under + ps.toward(vx - self.carry, target, dt)
            self.carry = under
        hero.vel = Vector(vx, vy)
        if controls.jump and not self._held and hit is not None:
            hero.apply_impulse(Vector(0.0, ps.PLAYER_MASS * ps.JUMP_SPEED))
            level.jumps.append(self.t)
        self._held = controls.jump

    def on_platform(self) -> bool:
        """Whether the player stands on the moving platform."""
        hit = self.ground()
        return hit is not None and hit.shape is self.level.platform

    def snapshot(self) -> PlatformerSnapshot:
        """The World (the taken coins' filters with it), the coins taken, the jump button, the
        carry, the autopilot's memory."""
        return PlatformerSnapshot(
            self.world.snapshot(),
            tuple(self.level.collected),
            self._held,
            self.carry,
            copy.deepcopy(self.memory),
        )

    def restore(self, snapshot: PlatformerSnapshot) -> None:
        """Return to the moment ``snapshot()`` was taken."""
        if not isinstance(snapshot, PlatformerSnapshot):
            raise TypeError(
                f"restore takes a PlatformerSnapshot from PlatformerGame.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        self.world.restore(snapshot.world)
        self.level.collected[:] = snapshot.collected
        self._held, self.carry = snapshot.held, snapshot.carry
        self.memory = copy.deepcopy(snapshot.memory)

    # -- drawing ----------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, camera: Camera, alpha: float) -> None:
        """The level by draw_world in the bodies' colours, the coins filled, the score."""
        surface.fill(SKY)
        taken = self.level.collected
        for index, coin in enumerate(self.level.coins):  # a coin taken is drawn in the sky's
            coin.colour = SKY if index in taken else COIN_COLOUR
        draw_world(surface, self.world, camera, alpha)
        for index, coin in enumerate(self.level.coins):
            if index not in taken:  # filled: draw_world draws a sensor as a ring
                at, r = camera.point(tuple(coin.center)), max(2, round(camera.length(coin.radius)))
                pygame.draw.circle(surface, COIN_COLOUR, at, r)
        score = self.score
        draw_text(surface, f"score {score.points}", (12, 8), size=24, color=INK)
        coins = f"coins {len(score.coins)}/{len(ps.COINS)}"
        draw_text(surface, coins, (surface.get_width() - 12, 8), 24, INK, "topright")


def one_way(contact: ContactEvent) -> bool:
    """The one-way ledge's pre_solve: solid only for a player above it that is not going up
    (``contact.normal`` points from the ledge toward the player)."""
    return contact.normal.y > 0.0 and contact.body.vel.y <= 0.0


# -- the autopilot ----------------------------------------------------------------------------
def _stick(to: float, x: float, reach: float = 0.5) -> float:
    """The stick that runs toward ``to`` from ``x`` (m), full beyond ``reach`` m."""
    return max(-1.0, min(1.0, (to - x) / reach))


def autopilot(game: PlatformerGame) -> Controls:
    """The scene's script until four coins are taken; then to the platform and onto it, and
    a ride to the last coin at its far end."""
    level = game.level
    if len(level.collected) < len(ps.COINS) - 1:
        return Controls(*ps.script(game.t))
    hero, platform = level.player, level.platform
    x, feet = hero.pos.x, hero.pos.y - ps.PLAYER_SIZE[1] / 2
    half, top = ps.PLATFORM_SIZE[0] / 2, platform.pos.y + ps.PLATFORM_SIZE[1] / 2
    hit = game.ground()
    if hit is not None and hit.shape is platform:
        return Controls()  # ride it
    if hit is not None:
        low, high = JUMP_WINDOW
        coming = platform.vel.x > 0.0 and low <= platform.pos.x <= high
        # Standing, not landing: a jump's impulse adds to a fall's speed.
        ready = abs(x - STAND_X) < 0.3 and abs(hero.vel.x) < 1.0 and abs(hero.vel.y) < 0.5
        return Controls(_stick(STAND_X, x), coming and ready)
    # In the air: clear the platform's left end until the feet are over its top, then steer
    # over its middle.
    if feet > top + 0.05:
        return Controls(_stick(platform.pos.x, x))
    return Controls(_stick(min(STAND_X, platform.pos.x - half - 0.45), x))


class Person:
    """The player at the keyboard: Left/Right or A/D run, Up, W or space jumps."""

    def __call__(self, game: PlatformerGame) -> Controls:
        keys = pygame.key.get_pressed()
        run = float(keys[pygame.K_RIGHT] or keys[pygame.K_d])
        run -= float(keys[pygame.K_LEFT] or keys[pygame.K_a])
        jump = keys[pygame.K_UP] or keys[pygame.K_w] or keys[pygame.K_SPACE]
        return Controls(run, bool(jump))


class PlatformerScene(Scene):
    """The game as a scene: steps a :class:`PlatformerGame` and draws it."""

    name = "platformer"
    summary = "a platformer: cross a rope bridge, shove crates, ride the platform, take the coins"
    duration = MAX_SECONDS
    dt = DT
    seed = 1
    world: PlatformerGame

    def __init__(self, person: bool = False, kernels: str | None = None) -> None:
        #: Who plays: a person at the keys (True), or the autopilot.
        self.person = person
        self.kernels = kernels

    def build(self, size: tuple[int, int]) -> None:
        """A new game on a ``size`` px canvas: the level fills it below the score line."""
        view = (-0.5, -0.5, ps.WIDTH + 0.5, 10.5)  # the walls, 10 m high, whole
        self.camera = Camera.fit(view, (4, 36, size[0] - 8, size[1] - 40))
        player = Person() if self.person else None
        self.world = self.game = PlatformerGame(self.kernels, player)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """The level, blended by alpha between steps."""
        self.game.draw(surface, self.camera, alpha)


SIZE = (640, 360)


def play(
    window: bool,
    seconds: float | None = None,
    fps: int = 60,
    size: tuple[int, int] = SIZE,
    out: Path | None = None,
    overwrite: bool = False,
) -> Score:
    """Run the game: in a window with the keys, or headless with the autopilot.

    Headless it writes PNG frames at ``fps`` to ``out`` (default out/platformer), 1/fps s
    apart: for ``seconds`` if given, else until AFTER_END s after the last coin (at most
    MAX_SECONDS).
    """
    scene = PlatformerScene(person=window)
    run_game(
        scene, window, seconds, fps, size, out or Path("out/platformer"), overwrite,
        WINDOW_SECONDS, MAX_SECONDS, AFTER_END,
    )  # fmt: skip
    return replace(scene.game.score)


def _run(args: argparse.Namespace) -> int:
    out = args.out or Path("out/platformer")
    score = play(
        window=args.window,
        seconds=args.seconds,
        fps=args.fps or (60 if args.window else 30),
        size=args.size or SIZE,
        out=out,
        overwrite=args.overwrite,
    )
    where = "" if args.window else f"; frames in {out}/frame_00000.png ..."
    print(f"platformer: {score.points} points, {len(score.coins)}/{len(ps.COINS)} coins{where}")
    return 0


DEMO = Demo(
    name="platformer",
    summary="A small game: cross a rope bridge, shove crates, ride a platform, take every coin",
    run=_run,
    # A game, not scenes: no --scene, no motion diagram, no clip; no dice, so no --seed.
    takes=frozenset({"--fps", "--seconds", "--size", "--out", "--overwrite", "--window"}),
    size=SIZE,
    min_size=(320, 180),
)
