"""Newton's cradle: five touching balls on a floor, one (or two, or a heavy one) sent in; and
the real cradle, hung on rods.

    python -m demos cradle                    # frames: out/cradle/five/, two/, heavy/, hung/
    python -m demos cradle --scene hung --window
    python -m demos cradle --strobe           # one motion diagram per scene

Five balls of radius 0.5 m and mass 1 kg lie in a row, touching, on a frictionless floor
(a ``Plane`` with friction 0) under gravity; restitution e = 1 (perfectly elastic). The
first ball is pulled back 1 m and sent in at 2 m/s. On the floor the balls move along one
line, which is all the blows need; the ``hung`` scene hangs them on rods, as a real cradle
does.

The engine takes the impacts at their exact moment and in time order: the first ball hits
the second and stops, the second, already touching the third, hits it at the same instant
and stops, and so on down the row, until the last ball leaves with the first one's speed.
Each impact keeps the total momentum p = sum of m v and, with e = 1, the kinetic energy
KE = sum of m v^2 / 2, so both read-outs stay at their first values to rounding.

* ``five``: one ball in at 2 m/s; one ball out at 2 m/s, the other four at rest.
* ``two``: two balls in; two out. (One ball out at twice the speed would keep the momentum,
  but not the energy.)
* ``heavy``: a 3 kg ball in. Each blow sends one ball down the row at 1.5 times the heavy
  ball's speed and leaves the heavy ball half as fast, so the row sends out a train:
  3, 1.5, 0.75 and 0.375 m/s, and the heavy ball follows at 0.125 m/s.
* ``hung``: the real cradle. Each ball hangs on a ``Rod`` of 2 m from a bar (``Rod(ball,
  top, LENGTH)``, ``world.add_link``), so at rest they touch in a row; ball 1 is pulled back
  30 degrees and let go under gravity. It swings down and strikes the row at the bottom
  (about 2.29 m/s, after 0.72 s); ball 5 swings out to 30 degrees, comes back, and ball 1
  leaves again: three blows in the 4 s, back and forth.

The hung cradle steps at dt = 1/240 s: the World takes a step in which a linked ball is
struck again in 16 parts (README: "Links"), so the blow passes down the row to 2e-7 of the
speed here (measured; 4e-7 on the README's 1 m rods). Its read-outs differ from the floor's.
The bars and the momentum are horizontal: p = sum of m v_x is not kept, since the rods pull
sideways as the balls swing (it runs between +2.29 and -2.29 kg m/s, and each blow passes it
from one end ball to the other). What is kept is the energy E = KE + PE, with PE = sum of
m g h from the balls' lowest places: the rods do no work, and the World's closed form with
the rods is RATTLE, so E is kept up to RATTLE's bounded error (under 7e-5 J of 2.63 J
through the swing, vanishing at the turning points) and the blows' own error, which costs
about 1e-6 J a blow (measured over 60 s).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import pygame

from demos.cli import Demo
from engine import Body, Plane, Rod, Vector, World
from engine.forces import Gravity
from engine.render import GRID, INK, MUTED, PAPER, Camera, Scene, draw_text, draw_vector

__all__ = [
    "ANGLE",
    "BALLS",
    "COLOURS",
    "faded",
    "DT",
    "G",
    "HEAVY",
    "HUNG_DT",
    "LENGTH",
    "PULL",
    "RADIUS",
    "ROD",
    "SPEED",
    "Cradle",
    "CradleScene",
    "FiveScene",
    "HeavyScene",
    "HungCradle",
    "HungScene",
    "Sample",
    "TwoScene",
    "cradle_world",
    "hung_world",
    "DEMO",
]

#: Balls in the row, their radius (m), gravity (m/s^2), the physics step (s).
BALLS = 5
RADIUS = 0.5
G = 9.81
DT = 1.0 / 60.0
#: How far the balls sent in are pulled back (m) and their speed (m/s); the heavy ball's mass.
PULL = 1.0
SPEED = 2.0
HEAVY = 3.0
#: The hung cradle: its rods' length (m), how far the first ball is pulled back (degrees), and
#: its step (s). A step in which a linked ball is struck is taken again in 16 parts by the
#: World, so at 1/240 s the blow passes down the row to 2e-7 of the speed (README: "Links").
LENGTH = 2.0
ANGLE = 30.0
HUNG_DT = 1.0 / 240.0
#: Each ball's colour (the Okabe-Ito set): no other drawing uses them, so a test finds each
#: ball by its colour; its velocity bar has the same colour.
COLOURS: tuple[tuple[int, int, int], ...] = (
    (0, 114, 178),
    (213, 94, 0),
    (0, 158, 115),
    (204, 121, 167),
    (230, 159, 0),
)
FLOOR = (70, 70, 78)
#: The hung cradle's rods (the bar is drawn like the floor).
ROD = (104, 98, 90)
MOMENTUM, ENERGY = (40, 90, 160), (150, 60, 40)
#: The floor as shown (m), left to right.
VIEW = (-2.0, 14.0)
#: A velocity arrow is as long as this many seconds of travel.
ARROW_SECONDS = 0.4

Color = tuple[int, int, int]


def cradle_world(sent: int = 1, first_mass: float = 1.0) -> tuple[World, list[Body]]:
    """The cradle's World: gravity, a frictionless floor at y = 0 and BALLS balls on it.

    Ball k rests at x = 2 r k, touching its neighbours; the first ``sent`` balls are pulled
    back PULL metres and move at SPEED m/s toward the others. The first ball has
    ``first_mass`` kg, every other ball 1 kg; all have e = 1 and no friction.
    """
    if not 1 <= sent < BALLS:
        raise ValueError(f"sent must be from 1 to {BALLS - 1} balls, got {sent!r}")
    world = World(integrator="auto")  # gravity alone: the closed form
    world.add_force(Gravity((0.0, -G)))
    world.add_collider(Plane((0.0, 0.0), (0.0, 1.0), friction=0.0))
    balls = [
        world.add(
            Body(
                Vector(2.0 * RADIUS * k - (PULL if k < sent else 0.0), RADIUS),
                Vector(SPEED if k < sent else 0.0, 0.0),
                Vector(0.0, 0.0),
                mass=first_mass if k == 0 else 1.0,
                radius=RADIUS,
                restitution=1.0,
                friction=0.0,
            )
        )
        for k in range(BALLS)
    ]
    return world, balls


class Sample(NamedTuple):
    """The cradle at one moment: time (s), total momentum (kg m/s, along x), kinetic energy
    (J), each ball's velocity along the row (m/s), and the potential energy (J) of the balls'
    heights above their lowest places (0 on the floor; the hung cradle's swing)."""

    t: float
    momentum: float
    energy: float
    velocities: tuple[float, ...]
    potential: float = 0.0

    @property
    def total(self) -> float:
        """Kinetic plus potential energy (J)."""
        return self.energy + self.potential


class Cradle:
    """The cradle's physics and its history: a Steppable (``step(dt)``, ``t``, snapshots).

    ``history`` holds a :class:`Sample` at the start and after every step.
    """

    def __init__(self, sent: int = 1, first_mass: float = 1.0) -> None:
        self.sent, self.first_mass = sent, first_mass
        self.world, self.balls = cradle_world(sent, first_mass)
        self.history: list[Sample] = [self.sample()]

    @property
    def t(self) -> float:
        return self.world.t

    def sample(self) -> Sample:
        """Total momentum and kinetic energy now, summed ball by ball in the row's order."""
        p = ke = 0.0
        for b in self.balls:
            v = b.vel
            p += b.mass * v.x
            ke += 0.5 * b.mass * (v.x * v.x + v.y * v.y)
        return Sample(self.world.t, p, ke, tuple(b.vel.x for b in self.balls))

    def step(self, dt: float) -> None:
        self.world.step(dt)
        self.history.append(self.sample())

    def snapshot(self) -> tuple[Any, ...]:
        return self.world.snapshot(), tuple(self.history)

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, history = snapshot
        self.world.restore(world)
        self.history = list(history)


def hung_world(angle: float = ANGLE) -> tuple[World, list[Body], list[Rod]]:
    """The hung cradle's World: gravity, and BALLS balls hung on rods of LENGTH m from a bar.

    Ball k's rod hangs from (2 r k, 0), so at rest the balls touch in a row at y = -LENGTH.
    The first ball is pulled back ``angle`` degrees (its rod turned away from the row) and let
    go at rest. All balls have 1 kg, e = 1 and no friction.
    """
    if not 0.0 < angle < 180.0:
        raise ValueError(f"angle must be in (0, 180) degrees, got {angle!r}")
    world = World(integrator="auto")  # gravity alone: the closed form, and RATTLE with the rods
    world.add_force(Gravity((0.0, -G)))
    balls, rods = [], []
    for k in range(BALLS):
        top = Vector(2.0 * RADIUS * k, 0.0)
        a = math.radians(angle) if k == 0 else 0.0
        ball = world.add(
            Body(
                top + Vector(-math.sin(a), -math.cos(a)) * LENGTH,
                Vector(0.0, 0.0),
                Vector(0.0, 0.0),
                radius=RADIUS,
                restitution=1.0,
                friction=0.0,
            )
        )
        balls.append(ball)
        rods.append(world.add_link(Rod(ball, top, LENGTH)))
    return world, balls, rods


class HungCradle(Cradle):
    """The hung cradle's physics and history (``rods`` are its links, ball by ball).

    Its samples hold the horizontal momentum and velocities, and the potential energy from
    the balls' lowest places, y = -LENGTH.
    """

    def __init__(self, angle: float = ANGLE) -> None:
        self.sent, self.first_mass, self.angle = 1, 1.0, angle
        self.world, self.balls, self.rods = hung_world(angle)
        self.history = [self.sample()]

    def sample(self) -> Sample:
        p = ke = pe = 0.0
        for b in self.balls:
            v = b.vel
            p += b.mass * v.x
            ke += 0.5 * b.mass * (v.x * v.x + v.y * v.y)
            pe += b.mass * G * (b.pos.y + LENGTH)
        return Sample(self.world.t, p, ke, tuple(b.vel.x for b in self.balls), pe)


# -- drawing --------------------------------------------------------------------------------


def faded(colour: Color, amount: float) -> Color:
    """``colour`` mixed toward white: amount 1 is the colour, 0 white."""
    r, g, b = colour
    return (
        round(255 - (255 - r) * amount),
        round(255 - (255 - g) * amount),
        round(255 - (255 - b) * amount),
    )


def _darker(colour: Color) -> Color:
    """``colour`` darkened, for the arrows: never one of the balls' own colours."""
    r, g, b = colour
    return (round(r * 0.7), round(g * 0.7), round(b * 0.7))


class CradleScene(Scene):
    """The row on its floor, each ball's velocity as a bar, and the total momentum and energy."""

    name = "five"
    summary = "one ball in at 2 m/s: one ball out, at 2 m/s"
    duration = 3.5
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.25
    world: Cradle
    #: How many balls are sent in, and the first ball's mass (kg).
    sent = 1
    first_mass = 1.0
    #: The top of the velocity bars' scale (m/s).
    v_top = 2.5
    #: The title, and the x range (m) the strobe picture shows.
    title = "Newton's cradle: five balls, e = 1, on a frictionless floor"
    view = VIEW

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.cradle = Cradle(self.sent, self.first_mass)
        w, h = size
        s = self.s = h / 360
        self.size = size
        m = self.margin = round(10 * s)
        # The floor and balls across the whole width under two lines of title: wide enough
        # for the furthest ball and the tip of its velocity arrow by the scene's end.
        self.view = (VIEW[0], max(VIEW[1], self.reach()))
        box = (self.view[0], -0.25, self.view[1], 1.45)
        self.camera = Camera.fit(box, (m, 50 * s, w - 2 * m, 90 * s))
        if self.view[1] > VIEW[1]:  # and the arrowhead's 11 px past the tip, and 3 px more
            self.view = (self.view[0], self.view[1] + 14 / self.camera.scale)
            box = (self.view[0], -0.25, self.view[1], 1.45)
            self.camera = Camera.fit(box, (m, 50 * s, w - 2 * m, 90 * s))
        # The bars bottom left, the read-outs bottom right.
        self.bars = pygame.Rect(m, round(158 * s), round(w * 0.46), h - round(158 * s) - m)
        left = self.bars.right + round(14 * s)
        self.readout = pygame.Rect(left, self.bars.top, w - left - m, self.bars.height)
        #: The bars' zero line (px) and scale (px per m/s).
        self.bar_zero = self.bars.bottom - round(22 * s)
        self.bar_scale = (self.bar_zero - self.bars.top - round(40 * s)) / self.v_top

    def reach(self) -> float:
        """The furthest right (m) a ball's edge or its velocity arrow's tip (0.4 s of travel)
        gets within the scene's duration, run ahead on a cradle of its own."""
        cradle = Cradle(self.sent, self.first_mass)
        far = 0.0
        while cradle.t < self.duration + self.dt / 2:
            cradle.step(self.dt)
            for ball in cradle.balls:
                x, v = ball.pos.x, ball.vel.x
                far = max(far, x + RADIUS, x + ARROW_SECONDS * v)
        return far

    def step(self, dt: float) -> None:
        self.cradle.step(dt)

    def _shown(self, t: float) -> Sample:
        """The last sample at or before time t (the read-outs are the state's, not a blend)."""
        history = self.cradle.history
        k = min(len(history) - 1, max(0, int(t / self.dt + 1e-9)))
        return history[k]

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        surface.fill(PAPER)
        self._title(surface, t)
        self._floor(surface)
        sample = self._shown(t)
        for k, ball in enumerate(self.cradle.balls):
            pos = self.cradle.world.position_of(ball, alpha)
            assert isinstance(pos, Vector)  # a 2D World
            self._ball(surface, k, (pos.x, pos.y), COLOURS[k], label=True)
            v = sample.velocities[k]
            if abs(v) > 1e-3:  # its velocity above it: an arrow as long as 0.4 s of travel
                tail = (pos.x, pos.y + 1.6 * RADIUS)
                dark = _darker(COLOURS[k])
                draw_vector(
                    surface, self.camera, tail, (v, 0.0), ARROW_SECONDS, dark, width=3 * self.s
                )
        self._bars(surface, sample.velocities)
        self._readouts(surface, sample)

    def _title(self, surface: pygame.Surface, t: float) -> None:
        s, m = self.s, self.margin
        draw_text(surface, self.title, (m, 6 * s), round(20 * s))
        draw_text(
            surface,
            f"t = {t:4.2f} s",
            (surface.get_width() - m, 6 * s),
            round(20 * s),
            INK,
            "topright",
        )
        draw_text(surface, self.summary, (m, 27 * s), round(16 * s), MUTED)

    def _floor(self, surface: pygame.Surface) -> None:
        cam, s = self.camera, self.s
        left, right = cam.point((self.view[0], 0.0)), cam.point((self.view[1], 0.0))
        pygame.draw.line(surface, FLOOR, left, right, max(2, round(2 * s)))
        # Hatching under the floor, and a tick at each ball's place of rest.
        step = max(6, round(10 * s))
        for x in range(left[0], right[0], step):
            pygame.draw.line(
                surface, GRID, (x, left[1] + 2), (x - step // 2, left[1] + step // 2 + 2)
            )
        for k in range(BALLS):
            px = cam.point((2.0 * RADIUS * k, 0.0))
            pygame.draw.line(surface, MUTED, (px[0], px[1] + 3), (px[0], px[1] + 3 + round(4 * s)))

    def _ball(
        self,
        surface: pygame.Surface,
        k: int,
        pos: tuple[float, float],
        colour: Color,
        label: bool,
    ) -> None:
        cam, s = self.camera, self.s
        centre = cam.point(pos)
        r = round(cam.length(RADIUS))
        pygame.draw.circle(surface, colour, centre, r)
        heavy = k == 0 and self.first_mass != 1.0
        if heavy:
            pygame.draw.circle(surface, INK, centre, r, max(2, round(3 * s)))
        if label:
            draw_text(surface, str(k + 1), centre, round(18 * s), (255, 255, 255), "center")
            if heavy:
                draw_text(  # under the floor, below the ball
                    surface,
                    f"{self.first_mass:g} kg",
                    (centre[0], centre[1] + r + 10 * s),
                    round(15 * s),
                    INK,
                    "midtop",
                )

    def _bar_box(self, surface: pygame.Surface, title: str) -> tuple[float, pygame.Rect]:
        """The velocity bars' white box with its title; (scale s, the box)."""
        s, box = self.s, self.bars
        pygame.draw.rect(surface, (255, 255, 255), box, border_radius=4)
        pygame.draw.rect(surface, GRID, box, 1, border_radius=4)
        draw_text(surface, title, (box.left + 6 * s, box.top + 4 * s), round(16 * s))
        return s, box

    def _bars(self, surface: pygame.Surface, velocities: Sequence[float]) -> None:
        """Each ball's velocity along the row as a bar, with its value, on one scale."""
        s, box = self._bar_box(surface, "velocity of each ball  m/s")
        bottom, scale = self.bar_zero, self.bar_scale
        left = box.left + round(30 * s)
        # Grid lines every 0.5 m/s, numbered every 1 m/s.
        y_tick = 0.0
        while y_tick <= self.v_top + 1e-9:
            py = round(bottom - y_tick * scale)
            pygame.draw.line(surface, GRID, (left, py), (box.right - round(8 * s), py))
            if abs(y_tick - round(y_tick)) < 1e-9:
                draw_text(
                    surface, f"{y_tick:g}", (left - 4 * s, py), round(14 * s), MUTED, "midright"
                )
            y_tick += 0.5
        pygame.draw.line(surface, INK, (left, bottom), (box.right - round(8 * s), bottom))
        slot = (box.right - round(8 * s) - left) / BALLS
        width = round(slot * 0.56)
        for k, v in enumerate(velocities):
            cx = round(left + slot * (k + 0.5))
            height = round(max(-0.3, min(self.v_top, v)) * scale)
            rect = pygame.Rect(cx - width // 2, bottom - max(0, height), width, abs(height))
            if rect.height:
                pygame.draw.rect(surface, COLOURS[k], rect)
            draw_text(
                surface,
                f"{v:.3f}",
                (cx, bottom - max(0, height) - 2 * s),
                round(14 * s),
                INK,
                "midbottom",
            )
            draw_text(
                surface, str(k + 1), (cx, bottom + 3 * s), round(15 * s), COLOURS[k], "midtop"
            )

    def _readouts(self, surface: pygame.Surface, now: Sample) -> None:
        """Total momentum and kinetic energy, and how far each is from its value at t = 0."""
        s, box = self.s, self.readout
        first = self.cradle.history[0]
        x, y = box.left, box.top + round(2 * s)
        big, small = round(19 * s), round(15 * s)
        for name, formula, unit, value, start, colour in (
            ("total momentum", "p = \u03a3 m v", "kg m/s", now.momentum, first.momentum, MOMENTUM),
            ("kinetic energy", "KE = \u03a3 m v\u00b2 / 2", "J", now.energy, first.energy, ENERGY),
        ):
            draw_text(surface, f"{name}:  {formula}", (x, y), small, MUTED)
            y += round(17 * s)
            draw_text(surface, f"{value:.15f} {unit}", (x, y), big, colour)
            y += round(21 * s)
            draw_text(surface, f"change since t = 0:  {value - start:+.1e}", (x, y), small, INK)
            y += round(28 * s)
        draw_text(surface, "kept exactly, to rounding:", (x, y), small, MUTED)
        y += round(16 * s)
        draw_text(surface, "each impact at its moment, in order", (x, y), small, MUTED)

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """A motion diagram with time running down the page: one row for each of ``times``
        (s), each ball drawn there at its place, as wide as it is (squashed in height)."""
        self.build(surface.get_size())
        surface.fill(PAPER)
        s, m = self.s, self.margin
        w, h = surface.get_size()
        draw_text(
            surface,
            f"Newton's cradle ({self.name}): the row every {self.strobe_interval:g} s, "
            "time running down",
            (m, 6 * s),
            round(20 * s),
        )
        draw_text(surface, self.summary, (m, 27 * s), round(16 * s), MUTED)
        # x as in the frames; each row of balls a band of the page, t = 0 at the top.
        left = round(44 * s)
        view = self.view
        cam = Camera.fit((view[0], 0.0, view[1], 1.0), (left, 0, w - left - m, h))
        top, bottom = round(56 * s), h - round(30 * s)
        row = (bottom - top) / max(1, len(times) - 1)
        height = max(3, round(row * 0.7))
        width = round(cam.length(2.0 * RADIUS))
        for j, t in enumerate(times):
            while self.cradle.t < t - 1e-9:
                self.cradle.step(self.dt)
            y = round(top + j * row)
            if abs(t - round(t * 2) / 2) < 1e-9:  # every 0.5 s: a grid line and its time
                pygame.draw.line(surface, GRID, (left, y), (w - m, y))
                draw_text(surface, f"{t:g} s", (left - 6 * s, y), round(14 * s), MUTED, "midright")
            for k, ball in enumerate(self.cradle.balls):
                cx = cam.point((ball.pos.x, 0.0))[0]
                rect = pygame.Rect(0, 0, width, height)
                rect.center = (cx, y)
                pygame.draw.ellipse(surface, COLOURS[k], rect)
        axis = round(bottom + row / 2 + 2 * s)
        pygame.draw.line(surface, FLOOR, (left, axis), (w - m, axis), max(1, round(s)))
        x = math.ceil(view[0])
        while x < view[1] - 1.0:
            px = cam.point((float(x), 0.0))[0]
            pygame.draw.line(surface, FLOOR, (px, axis), (px, axis + round(4 * s)))
            draw_text(surface, f"{x}", (px, axis + 5 * s), round(14 * s), MUTED, "midtop")
            x += 2
        draw_text(surface, "x (m)", (w - m, axis + 5 * s), round(14 * s), MUTED, "topright")


class FiveScene(CradleScene):
    """One ball in at 2 m/s: it stops, and the last ball leaves at 2 m/s."""

    name = "five"
    summary = "one ball in at 2 m/s: one ball out at 2 m/s, four at rest"


class TwoScene(CradleScene):
    """Two balls in at 2 m/s: two balls out at 2 m/s."""

    name = "two"
    summary = "two balls in at 2 m/s: two balls out at 2 m/s, three at rest"
    sent = 2


class HeavyScene(CradleScene):
    """A 3 kg ball in at 2 m/s: the row sends out a train at 3, 1.5, 0.75 and 0.375 m/s."""

    name = "heavy"
    summary = "a 3 kg ball in at 2 m/s: out go 3, 1.5, 0.75, 0.375 m/s; it follows at 0.125"
    first_mass = HEAVY
    v_top = 3.5


class HungScene(CradleScene):
    """The real cradle: the balls hung on rods from a bar, the first let go from 30 degrees.

    The blow goes back and forth: ball 5 swings out, comes back, and ball 1 leaves again.
    The bars and the momentum are horizontal; the energy counts the heights too.
    """

    name = "hung"
    summary = "hung on 2 m rods, ball 1 let go from 30\u00b0: the blow passes back and forth"
    title = "Newton's cradle: five balls, e = 1, hung on rods"
    duration = 4.0
    dt = HUNG_DT
    strobe_interval = 0.1
    view = (-2.0, 6.0)
    #: The world box (x0, y0, x1, y1) the frames show (m): the bar, the rods and the swing,
    #: with room under the balls for their velocity arrows.
    box = (-2.0, -2.95, 6.0, 0.3)

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.cradle = self.hung = HungCradle()
        w, h = size
        s = self.s = h / 360
        self.size = size
        m = self.margin = round(10 * s)
        # The cradle across the whole width under two lines of title, the panels below it.
        top = round(198 * s)
        self.camera = Camera.fit(self.box, (m, 48 * s, w - 2 * m, top - 52 * s))
        self.bars = pygame.Rect(m, top, round(w * 0.46), h - top - m)
        left = self.bars.right + round(14 * s)
        self.readout = pygame.Rect(left, self.bars.top, w - left - m, self.bars.height)
        # The bars go both ways from a zero line midway; each ball's value and number below.
        self.bar_label = self.bars.bottom - round(18 * s)
        self.bar_values = self.bar_label - round(16 * s)
        high, low = self.bars.top + round(26 * s), self.bar_values - round(4 * s)
        self.bar_zero = round((high + low) / 2)
        self.bar_scale = (low - high) / 2 / self.v_top

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        surface.fill(PAPER)
        self._title(surface, t)
        sample = self._shown(t)
        cam, s = self.camera, self.s
        places = []
        for ball in self.hung.balls:
            pos = self.hung.world.position_of(ball, alpha)
            assert isinstance(pos, Vector)  # a 2D World
            places.append((pos.x, pos.y))
        for rod, place in zip(self.hung.rods, places, strict=True):
            top = rod.other
            assert isinstance(top, Vector)  # hung from a fixed point
            pygame.draw.line(surface, ROD, cam.point(top), cam.point(place), max(2, round(2 * s)))
        self._support(surface)  # over the rods' tops
        for k, place in enumerate(places):
            self._ball(surface, k, place, COLOURS[k], label=True)
            v = sample.velocities[k]
            if abs(v) > 1e-3:  # its horizontal velocity under it, as long as 0.4 s of travel
                tail = (place[0], place[1] - 1.6 * RADIUS)
                dark = _darker(COLOURS[k])
                draw_vector(surface, cam, tail, (v, 0.0), ARROW_SECONDS, dark, width=3 * s)
        self._bars(surface, sample.velocities)
        self._readouts(surface, sample)

    def _support(self, surface: pygame.Surface) -> None:
        """The bar the rods hang from, hatched above like the floor below."""
        cam, s = self.camera, self.s
        reach = 2.0 * RADIUS * (BALLS - 1)
        left, right = cam.point((-0.8, 0.0)), cam.point((reach + 0.8, 0.0))
        step = max(6, round(10 * s))
        for x in range(left[0], right[0], step):
            pygame.draw.line(
                surface, GRID, (x, left[1] - 2), (x + step // 2, left[1] - step // 2 - 2)
            )
        pygame.draw.line(surface, FLOOR, left, right, max(3, round(4 * s)))

    def _bars(self, surface: pygame.Surface, velocities: Sequence[float]) -> None:
        """Each ball's horizontal velocity as a bar up (to the right) or down (to the left)."""
        s, box = self._bar_box(surface, "horizontal velocity of each ball  m/s")
        zero, scale = self.bar_zero, self.bar_scale
        left, right = box.left + round(30 * s), box.right - round(8 * s)
        top = int(self.v_top)
        for tick in range(-top, top + 1):  # grid lines every 1 m/s, numbered
            py = round(zero - tick * scale)
            pygame.draw.line(surface, GRID, (left, py), (right, py))
            draw_text(surface, f"{tick:g}", (left - 4 * s, py), round(14 * s), MUTED, "midright")
        pygame.draw.line(surface, INK, (left, zero), (right, zero))
        slot = (right - left) / BALLS
        width = round(slot * 0.56)
        for k, v in enumerate(velocities):
            cx = round(left + slot * (k + 0.5))
            height = round(max(-self.v_top, min(self.v_top, v)) * scale)
            rect = pygame.Rect(cx - width // 2, zero - max(0, height), width, abs(height))
            if rect.height:
                pygame.draw.rect(surface, COLOURS[k], rect)
            shown = round(v, 3) + 0.0  # no "-0.000" for a ball at rest to 1e-11
            draw_text(surface, f"{shown:.3f}", (cx, self.bar_values), round(14 * s), INK, "midtop")
            draw_text(
                surface, str(k + 1), (cx, self.bar_label), round(15 * s), COLOURS[k], "midtop"
            )

    def _readouts(self, surface: pygame.Surface, now: Sample) -> None:
        """The total energy (kept but for RATTLE's bounded error), its kinetic and potential
        parts, and the horizontal momentum (not kept while the rods pull)."""
        s, box = self.s, self.readout
        first = self.hung.history[0]
        x, y = box.left, box.top + round(2 * s)
        big, small = round(19 * s), round(15 * s)
        draw_text(surface, "total energy:  E = KE + PE  (PE = \u03a3 m g h)", (x, y), small, MUTED)
        y += round(17 * s)
        draw_text(surface, f"{now.total:.9f} J", (x, y), big, ENERGY)
        y += round(21 * s)
        draw_text(
            surface, f"KE {now.energy:.3f} J  +  PE {now.potential:.3f} J", (x, y), small, INK
        )
        y += round(16 * s)
        change = now.total - first.total
        draw_text(surface, f"change since t = 0:  {change:+.1e} J", (x, y), small, INK)
        y += round(16 * s)
        draw_text(surface, "kept to RATTLE's bounded error (< 7e-5 J)", (x, y), small, MUTED)
        y += round(21 * s)
        draw_text(surface, "horizontal momentum:  p = \u03a3 m vx", (x, y), small, MUTED)
        y += round(17 * s)
        draw_text(surface, f"{now.momentum:+.6f} kg m/s", (x, y), big, MOMENTUM)
        y += round(21 * s)
        draw_text(surface, "not kept while the rods pull sideways", (x, y), small, MUTED)


DEMO = Demo(
    name="cradle",
    summary="Newton's cradle: one ball in, one out (two in, two out; a heavy ball), on a floor"
    " or hung on rods",
    scenes={"five": FiveScene, "two": TwoScene, "heavy": HeavyScene, "hung": HungScene},
)
