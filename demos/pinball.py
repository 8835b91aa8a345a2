"""Pinball: two flippers on hinges, three bumpers, two slingshots and a plunger, on the engine's
public API.

A ball rolls down a table tilted by 6.5 degrees (gravity along it is g sin(6.5 degrees) =
111 cm/s^2). The player keeps it in play with two flippers; a ball that falls between them
(or past them) drops into the drain, and the next of the three balls is put on the plunger.
Points come from what the ball touches, read from the World's contact events: a bumper 100,
a slingshot 10, a rollover lane at the top 50.

Every piece is the engine's public API, and the game writes no collision code of its own:

* the walls, the lane guides, the top arch and the top lanes are ``Segment`` colliders
  (capsules); the bumpers are ``Circle`` colliders and the slingshots capsules;
* each flipper is a dynamic body with a ``Polygon`` shape (a tapered bat drawn from its
  pivot), its centre of gravity at the pivot (a flipper's shaft and crank weigh it there; a
  uniform bat's would be 3.6 cm along it), held to the table by a ``Hinge`` to
  ``world.static_body`` with
  ``limits`` (rest and up, 55 degrees apart) and a motor: ``hinge.motor_speed`` is set to
  +/- FLIP_SPEED each step, up while the key is held and down when it is let go, with at
  most FLIP_TORQUE (so the bat is at the top five steps, 42 ms, after the key is pressed);
* the drain and the rollover lanes are sensors (``Segment(..., sensor=True)``): they push
  nothing and report the ball entering them;
* the plunger sends the ball up the shooter lane with an impulse (``ball.apply_impulse``) of
  the strength the key was held for.

**Bumpers and slingshots kick.** A real pop bumper or slingshot is a switch and a solenoid:
touched, it fires and throws the ball off at about the same speed whatever the touch. So the
game kicks with an impulse from the contact event (``event.normal``: away from the bumper),
the ball leaving at least KICK cm/s along it, added to an ordinary bounce (restitution
0.6). It is not a restitution above 1 (pymunk's way) for two reasons, said in full in the
README's section on this game: a restitution e > 1 gives a ball that barely touches a bumper
next to nothing (e times nearly nothing), where the solenoid throws it hard; and in the
engine a bounce made while the ball also touches a flipper is solved by the soft step of a
pile, which takes energy out by design (``engine.exact.pile.dissipative``), so e > 1 would kick
off a lone bumper but be cut back beside a flipper: two rules for one bumper.

The game is a Scene like every other demo (the model is ``demos/breakout.py``): what it steps
is :class:`PinballGame`, which speaks :class:`engine.Steppable`, so each fixed step of 1/120 s
reads the controls, drives the flippers, steps the World and applies the rules, whatever the
frame rate, and a game saved mid-run resumes exactly.

    python -m demos pinball --window     # play: shift or arrow keys (or mouse buttons) flip,
                                         # Down or Enter pulls the plunger, let go to shoot
    python -m demos pinball              # headless: an autopilot plays, frames to out/pinball/

Units: centimetres, grams and seconds (a real table's size: 50 cm across the playfield, the
ball 2.7 cm across and 80 g). The frames show the ball's path since the last frame was saved
as a trail.
"""

from __future__ import annotations

import argparse
import copy
import math
from collections import deque
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import pygame

from demos.cli import Demo
from demos.games import run_game
from engine import Body, Circle, ContactEvent, Filter, Hinge, Polygon, Segment, Vector, World
from engine.forces import Gravity
from engine.render import Camera, Scene, draw_disc, draw_text, font
from engine.world import WorldSnapshot

#: The tilt of the table (degrees) and the pull of gravity down it (cm/s^2).
TILT = 6.5
GRAVITY = 981.0 * math.sin(math.radians(TILT))
DT = 1.0 / 120.0
#: The table's lengths are centimetres: the World is told so (``length_units_per_meter``), so
#: that the soft step's slop and speeds are a real table's (the exact models' are their own).
UNITS_PER_METER = 100.0
#: The playfield: x from 0 to WIDTH (cm); the shooter lane runs beside it, from WIDTH to
#: LANE_RIGHT. The straight side walls rise to ARCH_Y, where a half circle closes the top.
WIDTH, LANE_RIGHT, ARCH_Y = 46.5, 50.0, 88.0
ARCH_CENTRE, ARCH_RADIUS = (LANE_RIGHT / 2, ARCH_Y), LANE_RIGHT / 2
#: The shooter lane's wall on the playfield side stops this far up (cm), under the arch.
LANE_WALL_TOP = 80.0
#: The ball: radius (cm), mass (g), restitution and friction (each multiplied by the other
#: side's, pymunk's rule: colliders have 1 and 1).
BALL_RADIUS, BALL_MASS = 1.35, 80.0
BALL_RESTITUTION, BALL_FRICTION = 0.6, 0.3
WALL_RADIUS = 0.3  # every wall is a capsule this thick on each side (cm)
#: The flippers: their pivots (cm), length from pivot to tip centre, the bat's half widths
#: at the pivot and the tip, mass (g); they rest REST degrees below level and swing up SWING.
LEFT_PIVOT, RIGHT_PIVOT = (13.75, 14.0), (WIDTH - 13.75, 14.0)
FLIPPER_LENGTH, FLIPPER_ROOT, FLIPPER_TIP, FLIPPER_MASS = 8.0, 1.2, 0.6, 150.0
REST, SWING = 30.0, 55.0
FLIPPER_RESTITUTION, FLIPPER_FRICTION = 0.5, 0.8
#: The flipper's motor: its speed (rad/s) up and down, and its most torque (g cm^2 / s^2):
#: five steps of 1/120 s from the key to the top.
FLIP_SPEED, FLIP_TORQUE = 40.0, 6.0e6
#: The inlane guides run from the side walls at this height down to just above each pivot.
GUIDE_TOP = 24.0
#: Bumpers: centres and radius (cm). Slingshots: the kicking capsule, from its top to its foot.
BUMPERS = ((15.0, 72.0), (31.5, 72.0), (23.25, 60.0))
BUMPER_RADIUS = 2.6
SLINGS = (((0.6, 33.0), (10.0, 18.2)), ((WIDTH - 0.6, 33.0), (WIDTH - 10.0, 18.2)))
SLING_RADIUS = 0.5
#: The least speed (cm/s) a bumper or slingshot throws the ball off at, along the contact's
#: normal (a solenoid's kick).
BUMPER_KICK, SLING_KICK = 180.0, 140.0
#: Two rollover lanes at the top, between three short posts (x, cm), from LANES_Y up.
LANE_POSTS, LANES_Y, LANES_TOP = (17.0, 23.25, 29.5), 92.0, 98.0
POINTS = {"bumper": 100, "sling": 10, "lane": 50}
BALLS = 3
#: The drain: a sensor capsule across the bottom (cm), thicker than a step's travel.
DRAIN_Y, DRAIN_RADIUS = 3.0, 1.5
#: The plunger: the ball rests on it at this height in the shooter lane; the launch speed
#: (cm/s) grows from PLUNGE_MIN to PLUNGE_MAX over PULL_TIME s of pulling.
PLUNGER_Y, PLUNGE_MIN, PLUNGE_MAX, PULL_TIME = 4.0, 200.0, 330.0, 1.0
#: The trail: the ball's path over this many seconds is drawn behind it.
TRAIL_SECONDS = 0.5

BACKGROUND, WALL_COLOUR, INK = (18, 22, 40), (170, 176, 200), (236, 236, 244)
BALL_COLOUR, FLIPPER_COLOUR, DRAIN_COLOUR = (235, 235, 245), (255, 190, 60), (90, 30, 40)
BUMPER_COLOUR, LIT_COLOUR, SLING_COLOUR = (220, 70, 110), (255, 240, 120), (80, 200, 255)
TRAIL_COLOUR, LANE_COLOUR, PLUNGER_COLOUR = (120, 230, 160), (60, 70, 110), (200, 120, 255)
SLING_BODY = (40, 60, 90)
#: How long a game in a window may last (s) when no --seconds is given: until it is closed.
WINDOW_SECONDS = 24 * 3600.0
#: A headless run without --seconds stops this long after the game ends, or at MAX_SECONDS.
AFTER_END, MAX_SECONDS = 1.5, 300.0
#: How long a bumper or slingshot stays lit after a kick (s), for the picture.
LIT = 0.15

#: Collision categories: the flippers meet only the ball (the table's colliders never touch
#: them, nor cost a contact test).
BALL_BIT, FLIPPER_BIT, TABLE_BIT = 0b001, 0b010, 0b100
TABLE_FILTER = Filter(categories=TABLE_BIT)


class Controls(NamedTuple):
    """What the player does this step: hold the left flipper, the right, the plunger."""

    left: bool = False
    right: bool = False
    pull: bool = False


#: A player: given the game, its controls for this step.
Player = Callable[["PinballGame"], Controls]


@dataclass
class Score:
    """Where the game stands."""

    points: int = 0
    balls: int = BALLS  # balls left, the one in play included
    bumpers: int = 0  # kicks of each kind
    slings: int = 0
    lanes: int = 0

    @property
    def over(self) -> bool:
        """Whether the game has ended: every ball drained."""
        return self.balls == 0


@dataclass(frozen=True)
class PinballSnapshot:
    """Everything a game needs to resume: see :meth:`PinballGame.snapshot`."""

    world: WorldSnapshot
    rng: Mapping[str, Any]
    score: Score
    pulled: float  # how long the plunger has been pulled (s)
    on_plunger: bool
    lit: tuple[tuple[int, float], ...]
    trail: tuple[tuple[float, float], ...]
    memory: Mapping[str, Any]  # the autopilot's


def flipper_shape(side: int) -> Polygon:
    """A tapered bat from its pivot (the origin of its frame, the flipper's centre of gravity)
    to its tip: along +x for the left flipper (side -1), along -x for the right (side +1)."""
    length, root, tip = FLIPPER_LENGTH, FLIPPER_ROOT, FLIPPER_TIP
    d = -side  # +1: the bat points right
    return Polygon([(0.0, -root), (d * length, -tip), (d * length, tip), (0.0, root)])


def arch(segments: int = 12) -> list[tuple[float, float]]:
    """The top of the table: a half circle from the right wall over to the left one."""
    cx, cy = ARCH_CENTRE
    return [
        (cx + ARCH_RADIUS * math.cos(math.pi * k / segments),
         cy + ARCH_RADIUS * math.sin(math.pi * k / segments))
        for k in range(segments + 1)
    ]  # fmt: skip


class Table(NamedTuple):
    """A table built in a World: its pieces, by kind."""

    walls: list[Segment]
    bumpers: list[Circle]
    slings: list[Segment]
    lanes: list[Segment]  # the rollover sensors
    drain: Segment
    flippers: list[Body]  # left, right
    hinges: list[Hinge]


def guide_end(side: int) -> tuple[float, float]:
    """Where the inlane guide of ``side`` (-1 left, +1 right) ends, just above its pivot."""
    pivot = LEFT_PIVOT if side < 0 else RIGHT_PIVOT
    return (pivot[0] + side * 1.35, pivot[1] + 2.0)


def guide_y(x: float) -> float:
    """The height of the inlane guide's line at ``x`` (cm), on either side."""
    side = -1 if x < WIDTH / 2 else 1
    wall_x, (end_x, end_y) = (0.0 if side < 0 else WIDTH), guide_end(side)
    return GUIDE_TOP + (end_y - GUIDE_TOP) * (x - wall_x) / (end_x - wall_x)


def build_table(world: World) -> Table:
    """Put the table in ``world``: walls, guides, bumpers, slingshots, lanes, drain, flippers.

    Shared by the game and the benchmark (``demos/bench/pinball.py`` builds the same table in
    pymunk from these constants).
    """
    world.add_force(Gravity((0.0, -GRAVITY)))
    walls: list[Segment] = []
    # The outer wall: up the right side of the shooter lane, over the arch, down the left.
    points = [(LANE_RIGHT, 0.0), *arch(), (0.0, GUIDE_TOP)]
    for a, b in zip(points[:-1], points[1:], strict=True):
        walls.append(Segment(a, b, WALL_RADIUS, filter=TABLE_FILTER))
    walls.append(
        Segment((WIDTH, 0.0), (WIDTH, LANE_WALL_TOP), WALL_RADIUS, filter=TABLE_FILTER)
    )  # the lane's wall
    walls.append(
        Segment((WIDTH, PLUNGER_Y), (LANE_RIGHT, PLUNGER_Y), WALL_RADIUS, filter=TABLE_FILTER)
    )  # plunger
    for side in (-1, 1):
        # The inlane guide: from the side wall down toward the pivot, ending just above it.
        wall_x, end = (0.0 if side < 0 else WIDTH), guide_end(side)
        walls.append(Segment((wall_x, GUIDE_TOP), end, WALL_RADIUS, filter=TABLE_FILTER))
    walls.append(
        Segment((0.0, 0.0), (WIDTH, 0.0), WALL_RADIUS, filter=TABLE_FILTER)
    )  # under the drain
    walls.append(Segment((0.0, 0.0), (0.0, GUIDE_TOP), WALL_RADIUS, filter=TABLE_FILTER))
    for x in LANE_POSTS:
        walls.append(Segment((x, LANES_Y), (x, LANES_TOP), WALL_RADIUS, filter=TABLE_FILTER))
    bumpers = [Circle(c, BUMPER_RADIUS, filter=TABLE_FILTER) for c in BUMPERS]
    slings = [Segment(a, b, SLING_RADIUS, filter=TABLE_FILTER) for a, b in SLINGS]
    lanes = [
        Segment(
            ((a + b) / 2, LANES_Y + 1.0),
            ((a + b) / 2, LANES_TOP - 1.0),
            0.8,
            sensor=True,
            filter=TABLE_FILTER,
        )
        for a, b in zip(LANE_POSTS[:-1], LANE_POSTS[1:], strict=True)
    ]
    drain = Segment(
        (DRAIN_RADIUS, DRAIN_Y),
        (WIDTH - DRAIN_RADIUS, DRAIN_Y),
        DRAIN_RADIUS,
        sensor=True,
        filter=TABLE_FILTER,
    )
    for collider in [*walls, *bumpers, *slings, *lanes, drain]:
        world.add_collider(collider)
    assert all(c.filter == TABLE_FILTER for c in [*walls, *bumpers, *slings, *lanes, drain])
    flippers, hinges = [], []
    for side in (-1, 1):
        flipper, hinge = add_flipper(world, side)
        flippers.append(flipper)
        hinges.append(hinge)
    return Table(walls, bumpers, slings, lanes, drain, flippers, hinges)


def add_flipper(world: World, side: int, mass: float = FLIPPER_MASS) -> tuple[Body, Hinge]:
    """The flipper of ``side`` (-1 left, +1 right), at rest, on its hinge with its limits and
    its motor holding it down; it meets the ball only. ``mass`` (g) other than FLIPPER_MASS
    scales the motor's torque with it (the same swing)."""
    pivot = LEFT_PIVOT if side < 0 else RIGHT_PIVOT
    rest = math.radians(REST) * side  # the left bat points down to the right: angle -REST
    only_ball = Filter(categories=FLIPPER_BIT, mask=BALL_BIT)
    flipper = world.add(
        Body(Vector(*pivot), mass=mass, shape=flipper_shape(side), angle=rest,
             center_of_gravity=(0.0, 0.0),  # weighted at its pivot by the shaft and crank
             restitution=FLIPPER_RESTITUTION, friction=FLIPPER_FRICTION, filter=only_ball)
    )  # fmt: skip
    # The joint's angle starts at 0 (at rest); up is counter-clockwise for the left bat.
    swing = math.radians(SWING)
    limits = (0.0, swing) if side < 0 else (-swing, 0.0)
    hinge = world.add_link(
        Hinge(flipper, world.static_body, pivot, limits=limits,
              motor_speed=side * FLIP_SPEED, max_torque=FLIP_TORQUE * mass / FLIPPER_MASS)
    )  # fmt: skip
    return flipper, hinge


def add_ball(world: World, at: tuple[float, float]) -> Body:
    """The ball, at rest at ``at``: it meets the walls and the flippers. It is a bullet
    (``Body.bullet``): on the soft step (``World(solver="soft")``) it is swept against the
    flippers too, and crosses the bat in none of demos.bench.pinball's 1000 throws (140 pass
    it as no bullet); the exact solver (the game's) meets it there at its moment anyway."""
    ball_filter = Filter(categories=BALL_BIT)
    return world.add(
        Body(Vector(*at), mass=BALL_MASS, radius=BALL_RADIUS, restitution=BALL_RESTITUTION,
             friction=BALL_FRICTION, filter=ball_filter, bullet=True)
    )  # fmt: skip


def drive(hinge: Hinge, side: int, up: bool) -> None:
    """Set a flipper's motor: up (counter-clockwise for the left bat) while its key is held."""
    hinge.motor_speed = (-side if up else side) * FLIP_SPEED


#: Where the ball rests on the plunger.
PLUNGER_REST = ((WIDTH + LANE_RIGHT) / 2, PLUNGER_Y + WALL_RADIUS + BALL_RADIUS)


class PinballGame:
    """The game's state and rules; the physics is an engine World: the ball and two flippers.

    ``step(dt)`` is one fixed step of the whole game (the controls are read, the flippers
    driven, the World steps, the rules apply); ``t`` is the World's time. ``player`` says what
    the controls are; by default the autopilot plays. ``solver``: the World's, the exact
    models by default (the flippers' impacts on the ball at their moment, and their limits
    held to 1e-9 rad); "soft", the game's step, takes a tenth of their time (demos.bench
    pinball), its bats' limits giving about a degree under the motors' torque.
    """

    def __init__(self, seed: int = 1, player: Player | None = None, solver: str = "exact") -> None:
        self.rng = np.random.default_rng(seed)
        self.world = World(integrator="auto", solver=solver, length_units_per_meter=UNITS_PER_METER)
        self.table = build_table(self.world)
        self.ball = add_ball(self.world, PLUNGER_REST)
        self.kinds: dict[Any, str] = {}
        for bumper in self.table.bumpers:
            self.kinds[bumper] = "bumper"
        for sling in self.table.slings:
            self.kinds[sling] = "sling"
        for lane in self.table.lanes:
            self.kinds[lane] = "lane"
        self._hits: list[ContactEvent] = []
        self.world.on_contact(self.ball, begin=self._hits.append)
        self.score = Score()
        self.pulled = 0.0
        self.on_plunger = True
        #: Each bumper or slingshot kicked lately (its index in ``lights``), and when.
        self.lights: list[Any] = [*self.table.bumpers, *self.table.slings]
        self.lit: dict[int, float] = {}
        steps = round(TRAIL_SECONDS / DT)
        self.trail: deque[tuple[float, float]] = deque(maxlen=steps)
        self.player: Player = autopilot if player is None else player
        #: What the autopilot remembers from step to step (when each flip started, its pull).
        self.memory: dict[str, Any] = {}

    @property
    def t(self) -> float:
        """The game's time (s): the World's."""
        return self.world.t

    @property
    def flippers(self) -> list[Body]:
        """The left and the right flipper."""
        return self.table.flippers

    @property
    def hinges(self) -> list[Hinge]:
        """Their hinges."""
        return self.table.hinges

    def step(self, dt: float) -> None:
        """One fixed step of ``dt`` s: controls, flippers, plunger, the World, the rules."""
        controls = Controls() if self.score.over else self.player(self)
        for side, hinge, up in ((-1, self.hinges[0], controls.left),
                                (1, self.hinges[1], controls.right)):  # fmt: skip
            drive(hinge, side, up)
        if self.on_plunger:
            self._plunger(controls.pull, dt)
        self.world.step(dt)
        self.trail.append((self.ball.pos.x, self.ball.pos.y))
        self.update()

    def _plunger(self, pull: bool, dt: float) -> None:
        """Pull while held; on release, shoot the ball up the lane at the speed pulled for."""
        if pull:
            self.pulled = min(self.pulled + dt, PULL_TIME)
            return
        if self.pulled > 0.0:
            speed = PLUNGE_MIN + (PLUNGE_MAX - PLUNGE_MIN) * self.pulled / PULL_TIME
            self.ball.apply_impulse(Vector(0.0, BALL_MASS * speed))
            self.pulled, self.on_plunger = 0.0, False

    def update(self) -> None:
        """Apply the rules to the contacts of the ball that began in the last step."""
        hits, self._hits[:] = list(self._hits), []
        ball = self.ball
        if not self.on_plunger and ball.pos.x > WIDTH and ball.pos.y < PLUNGER_REST[1] + 1.0:
            # A shot too weak to leave the lane rolls back onto the plunger: shoot it again.
            self.on_plunger = ball.vel.length() < 10.0
        for event in hits:
            kind = self.kinds.get(event.collider)
            if kind is not None:
                self.score.points += POINTS[kind]
                if kind == "lane":
                    self.score.lanes += 1
                    continue
                if kind == "bumper":
                    self.score.bumpers += 1
                else:
                    self.score.slings += 1
                self.kick(event, BUMPER_KICK if kind == "bumper" else SLING_KICK)
                self.lit[self.lights.index(event.collider)] = self.t
            elif event.collider is self.table.drain and not self.on_plunger:
                self.score.balls -= 1
                if not self.score.over:
                    self.serve()
                else:
                    self.ball.vel, self.ball.angular_velocity = Vector(0.0, 0.0), 0.0

    def kick(self, event: ContactEvent, speed: float) -> None:
        """A solenoid's kick: the ball leaves along the contact's normal at ``speed`` cm/s at
        least (an impulse, added to the bounce it already made)."""
        along = self.ball.vel.dot(event.normal)
        if along < speed:
            self.ball.apply_impulse(event.normal * (BALL_MASS * (speed - along)))

    def serve(self) -> None:
        """The next ball, at rest on the plunger."""
        self.ball.pos, self.ball.vel = Vector(*PLUNGER_REST), Vector(0.0, 0.0)
        self.ball.angular_velocity = 0.0
        self.on_plunger, self.pulled = True, 0.0
        self.trail.clear()

    def snapshot(self) -> PinballSnapshot:
        """The World, the random generator, the score, the plunger, the lights, the trail."""
        return PinballSnapshot(
            self.world.snapshot(),
            copy.deepcopy(self.rng.bit_generator.state),
            replace(self.score),
            self.pulled,
            self.on_plunger,
            tuple(self.lit.items()),
            tuple(self.trail),
            copy.deepcopy(self.memory),
        )

    def restore(self, snapshot: PinballSnapshot) -> None:
        """Return to the moment ``snapshot()`` was taken."""
        if not isinstance(snapshot, PinballSnapshot):
            raise TypeError(
                f"restore takes a PinballSnapshot from PinballGame.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        self.world.restore(snapshot.world)
        self.rng.bit_generator.state = copy.deepcopy(snapshot.rng)
        self.score, self.pulled = replace(snapshot.score), snapshot.pulled
        self.on_plunger, self.lit = snapshot.on_plunger, dict(snapshot.lit)
        self.trail.clear()
        self.trail.extend(snapshot.trail)
        self.memory = copy.deepcopy(dict(snapshot.memory))
        self._hits.clear()

    # -- drawing ----------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, camera: Camera, alpha: float) -> None:
        """Draw the table, the ball's trail, the ball, the flippers and the score line."""
        surface.fill(BACKGROUND)
        top_left = camera.point((0.0, DRAIN_Y + DRAIN_RADIUS))
        pygame.draw.rect(
            surface,
            DRAIN_COLOUR,
            (*top_left, round(camera.length(WIDTH)), round(camera.length(2 * DRAIN_RADIUS))),
        )
        for lane in self.table.lanes:
            a, b = camera.point(lane.a), camera.point(lane.b)
            pygame.draw.line(surface, LANE_COLOUR, a, b, max(2, round(camera.length(1.6))))
        wide = max(2, round(camera.length(2 * WALL_RADIUS)))
        for wall in self.table.walls:
            pygame.draw.line(surface, WALL_COLOUR, camera.point(wall.a), camera.point(wall.b), wide)
        for k, sling in enumerate(self.table.slings):
            # The slingshot's body: between its kicking face, the side wall and the guide.
            lit = self._lit(len(self.table.bumpers) + k)
            wall_x = 0.0 if sling.a.x < WIDTH / 2 else WIDTH
            body = [sling.a, sling.b, (sling.b.x, guide_y(sling.b.x)), (wall_x, GUIDE_TOP)]
            pygame.draw.polygon(surface, SLING_BODY, [camera.point(p) for p in body])
            thick = max(2, round(camera.length(2 * SLING_RADIUS)))
            colour = LIT_COLOUR if lit else SLING_COLOUR
            pygame.draw.line(surface, colour, camera.point(sling.a), camera.point(sling.b), thick)
        for k, bumper in enumerate(self.table.bumpers):
            colour = LIT_COLOUR if self._lit(k) else BUMPER_COLOUR
            # By the renderer's draw_disc, so the layout test (tests/test_marks.py) sees a
            # label written on a bumper.
            centre = (bumper.center.x, bumper.center.y)
            draw_disc(surface, camera, centre, bumper.radius, None, colour, colour)
            at = camera.point(bumper.center)
            pygame.draw.circle(surface, INK, at, camera.length(bumper.radius) * 0.45)
        # The plunger: a spring under the ball in the shooter lane, shorter as it is pulled.
        pull = self.pulled / PULL_TIME if self.on_plunger else 0.0
        x = (WIDTH + LANE_RIGHT) / 2
        top = camera.point((x, PLUNGER_Y - 2.0 * pull))
        base = camera.point((x, -1.5))
        pygame.draw.line(surface, PLUNGER_COLOUR, top, base, max(2, round(camera.length(1.4))))
        if len(self.trail) > 1:
            points = [camera.point(p) for p in self.trail]
            pygame.draw.lines(surface, TRAIL_COLOUR, False, points, 2)
        for flipper in self.flippers:
            pos = self.world.position_of(flipper, alpha)
            corners = [
                camera.point(pos + Vector(*v).rotate_rad(flipper.angle))
                for v in flipper.shape.vertices
            ]
            pygame.draw.polygon(surface, FLIPPER_COLOUR, corners)
            pygame.draw.circle(surface, INK, camera.point(pos), max(2, camera.length(0.5)))
        ball = Vector.coerce(self.world.position_of(self.ball, alpha), "ball")
        draw_disc(surface, camera, (ball.x, ball.y), BALL_RADIUS, self.ball.angle,
                  BALL_COLOUR, (60, 60, 80))  # fmt: skip
        s = self.score
        draw_text(surface, f"score {s.points}", (12, 8), size=24, color=INK)
        draw_text(surface, f"balls {s.balls}", (surface.get_width() - 12, 8), 24, INK, "topright")
        if s.over:
            self.draw_verdict(surface, camera)

    def draw_verdict(self, surface: pygame.Surface, camera: Camera) -> pygame.Rect:
        """Write "GAME OVER" where nothing of the table is drawn: across the open band
        between the lowest bumper and the slingshots' tops, within the side walls, at 40 px or
        as large as fits there. Returns its box (px)."""
        table = self.table
        low = min(b.center.y - b.radius for b in table.bumpers)
        high = max(max(s.a.y, s.b.y) + s.radius for s in table.slings)
        left, top = camera.point((WALL_RADIUS, low))
        right, bottom = camera.point((WIDTH - WALL_RADIUS, high))
        band = pygame.Rect(left, top, right - left, bottom - top).inflate(-8, -8)
        size = 40
        while size > 10 and not _fits(font(size).size("GAME OVER"), band.size):
            size -= 1
        return draw_text(
            surface, "GAME OVER", band.center, size, INK, "center", background=BACKGROUND
        )

    def _lit(self, k: int) -> bool:
        return k in self.lit and self.t - self.lit[k] < LIT


# -- the autopilot ----------------------------------------------------------------------------
#: The autopilot holds a flipper up this long (s) once it flips, and lets it rest this long
#: before it may flip again; it misses (does not flip when it could) a MISS share of the
#: times, as a person does, so that its games end.
HOLD, REARM, MISS = 0.18, 0.12, 0.3


def _fits(size: tuple[int, int], room: tuple[int, int]) -> bool:
    return size[0] <= room[0] and size[1] <= room[1]


def near_flipper(game: PinballGame, side: int) -> bool:
    """Whether the ball is over the flipper of ``side`` (-1 left, +1 right), within its
    reach, coming down or rolling on it: the moment a player flips."""
    pivot = Vector(*(LEFT_PIVOT if side < 0 else RIGHT_PIVOT))
    rel = game.ball.pos - pivot
    # Along the bat at rest (from its pivot toward its tip) and across it (up is +).
    rest = math.radians(REST)
    along = Vector(-side * math.cos(rest), -math.sin(rest))
    u = rel.dot(along)
    v = rel.dot(Vector(-along.y, along.x) * -side)
    reach = FLIPPER_LENGTH * 0.35 < u < FLIPPER_LENGTH + BALL_RADIUS
    return reach and -BALL_RADIUS < v < 6.0 and game.ball.vel.y < 20.0


def autopilot(game: PinballGame) -> Controls:
    """A fair player: when the ball comes over a flipper's outer part it flips it (or, a
    MISS share of the times, is too late), holds it up for HOLD s and lets it down; it shoots
    each ball with the plunger pulled for a random time. Its dice are the game's ``rng``."""
    memory = game.memory
    if game.on_plunger:
        want = memory.setdefault("pull_for", float(game.rng.uniform(0.3, PULL_TIME)))
        if game.pulled < want:
            return Controls(pull=True)
        memory.pop("pull_for", None)
        return Controls()
    held = []
    for side, name in ((-1, "left"), (1, "right")):
        since = game.t - memory.get(name, -1.0)
        if since >= HOLD + REARM and near_flipper(game, side):
            memory[name], since = game.t, 0.0
            memory[name + " up"] = bool(game.rng.uniform() >= MISS)
        held.append(since < HOLD and memory.get(name + " up", False))
    return Controls(left=held[0], right=held[1])


class Person:
    """The player at the keyboard or mouse: left shift or the left arrow (or the left mouse
    button) for the left flipper, right shift or the right arrow (or the right button) for the
    right one; Down or Enter pulls the plunger, let go to shoot."""

    def __call__(self, game: PinballGame) -> Controls:
        keys = pygame.key.get_pressed()
        buttons = pygame.mouse.get_pressed()
        left = keys[pygame.K_LSHIFT] or keys[pygame.K_LEFT] or buttons[0]
        right = keys[pygame.K_RSHIFT] or keys[pygame.K_RIGHT] or buttons[2]
        pull = keys[pygame.K_DOWN] or keys[pygame.K_RETURN]
        return Controls(bool(left), bool(right), bool(pull))


class PinballScene(Scene):
    """The game as a scene: steps a :class:`PinballGame` and draws it."""

    name = "pinball"
    summary = "pinball: flippers on hinges with motors, bumpers that kick, a drain sensor"
    duration = MAX_SECONDS
    dt = DT
    seed = 1
    min_size = (160, 240)
    world: PinballGame

    def __init__(self, person: bool = False) -> None:
        #: Who plays: a person at the keys or mouse (True), or the autopilot.
        self.person = person

    def build(self, size: tuple[int, int]) -> None:
        """A new game on a ``size`` px canvas: the table fills it below the score line."""
        view = (-1.0, -2.0, LANE_RIGHT + 1.0, ARCH_Y + ARCH_RADIUS + 1.0)
        self.camera = Camera.fit(view, (4, 36, size[0] - 8, size[1] - 40))
        player = Person() if self.person else None
        self.world = self.game = PinballGame(self.seed, player)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """The table, blended by alpha between steps."""
        self.game.draw(surface, self.camera, alpha)


#: The frames' size (px) when no --size is given: the table stands upright.
SIZE = (360, 640)


def play(
    window: bool,
    seconds: float | None = None,
    fps: int = 60,
    size: tuple[int, int] = SIZE,
    seed: int = 1,
    out: Path | None = None,
    overwrite: bool = False,
) -> Score:
    """Run the game: in a window with the keys or mouse, or headless with the autopilot.

    Headless it writes PNG frames at ``fps`` to ``out`` (default out/pinball), 1/fps s
    apart: for ``seconds`` if given, else until AFTER_END s after the game ends (at most
    MAX_SECONDS).
    """
    scene = PinballScene(person=window)
    scene.seed = seed
    run_game(
        scene, window, seconds, fps, size, out or Path("out/pinball"), overwrite,
        WINDOW_SECONDS, MAX_SECONDS, AFTER_END,
    )  # fmt: skip
    return scene.game.score


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.set_defaults(seed=1)


def _run(args: argparse.Namespace) -> int:
    out = args.out or Path("out/pinball")
    score = play(
        window=args.window,
        seconds=args.seconds,
        fps=args.fps or (60 if args.window else 30),
        size=args.size or SIZE,
        seed=args.seed,
        out=out,
        overwrite=args.overwrite,
    )
    where = "" if args.window else f"; frames in {out}/frame_00000.png ..."
    print(
        f"pinball: {score.points} points ({score.bumpers} bumper kicks, {score.slings} "
        f"slingshot kicks, {score.lanes} lanes), {score.balls} balls left{where}"
    )
    return 0


DEMO = Demo(
    name="pinball",
    summary="A small game: two flippers on hinges, bumpers that kick, three balls",
    add_arguments=_add_arguments,
    run=_run,
    # A game, not scenes: no --scene, no motion diagram, no clip (yet).
    takes=frozenset({"--fps", "--seconds", "--size", "--out", "--overwrite", "--window", "--seed"}),
    size=SIZE,
    min_size=(160, 240),
)
