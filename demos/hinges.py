"""Hinges: a rod that swings as a shorter pendulum, a chain of planks, a car driven by motors.

    python -m demos hinges                    # frames: out/hinges/rod/, chain/, car/
    python -m demos hinges --scene car --window

Bodies that turn held at points of their own (``Hinge``, ``engine.dynamics.joints``), solved with
every joint at once as RATTLE on positions and angles (``engine.exact.joint_solver``), under
g = 9.81 m/s^2 in a World with ``integrator="auto"``. Everything in the motion is drawn by
``engine.render.draw_world``: each hinge's point a small ring, a rod's line from anchor to
anchor. Lengths in m, times in s, angles from straight down, counter-clockwise positive.

* ``rod``: a uniform rod (a Body with ``shape=Polygon.box(L, w)``, L = 1 m, w = 0.04 m,
  1 kg) on a Hinge at its end to ``world.static_body``, let go level (90 degrees), beside a
  point bob on a ``Rod`` of 2L/3 to a fixed point, let go level too, in the same World. A rod
  hinged at its end is a physical pendulum of equivalent length
  L_eq = I_pivot / (m L / 2) = 2L/3 + w^2 / (6 L), so the two swing together: theta(t) of both
  is plotted (the bob's wide and green, the rod's blue on it), with the rod's exact period,
  T = 4 sqrt(L_eq / g) K(sin 45 deg) = 1.9337 s (K by the arithmetic-geometric mean), marked
  at every whole period. The rod's width makes its period longer than the bob's by
  w^2 / (8 L^2) = 2e-4 of it: half a degree apart by 8 s, the curves lie on each other.
  Measured over the 8 s at dt = 1/240 s (between crossings of the bottom, interpolated in
  their step; the header shows them): the rod's period 1.93367 s, 2.9e-5 short of its exact
  one, the bob's 1.93326 s, 3.7e-5 short of its own; the hinge holds the rod's end at the
  origin to 1e-16 m.
* ``chain``: 20 planks of 0.2 by 0.05 m (0.1 kg each), each hinged to the next at their ends
  and the first to the world, let go level at dt = 1/480 s: the chain falls, folds and whips
  round. The planks share a ``Filter`` group, so they pass through each other: the ideal
  chain of hinges. Beside it the force on the top hinge (N; up to 439 N for a step at a
  whip, past the plot's top) and, on a log scale, the widest gap of any hinge (the distance
  between the two points a hinge holds together): at most 1.4e-15 m over the 4 s (the issue
  asks 1e-4 m), the round-off of coordinates near 1 m.
* ``car``: a box chassis (1.6 by 0.3 m, 1 kg) on two disc wheels (r = 0.3 m, 1 kg each),
  each on a Hinge at its axle with a motor (``motor_speed`` -8 rad/s, clockwise: forward up
  the slope; ``max_torque`` 2 N m), on a 15 degree slope (a ``Segment`` with friction 1),
  from rest at dt = 1/120 s. Rolling without slipping, the closed form is
  a = (2 T / r - M g sin(theta)) / (M + 2 I / r^2) = 1.43 m/s^2 until the motors' speed,
  v = 8 rad/s * r = 2.4 m/s, is reached (at 1.68 s). The plot puts the chassis's velocity up
  the slope, as the World gives it, over the closed form's: they agree to 4e-14 m/s (a
  wheel's contact with the ground takes part in the joints' solve, so the motors drive the
  wheels on friction). Its positions follow too: what the motors and friction do to the
  speeds acts on the positions through the step as a force does (a dt^2 / 2), so by 4 s it
  has climbed the closed form's distance to 1.2e-5 m (the header shows both; the error is
  the step at which the motors reach their speed).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import pygame

from demos.bench.pendulum import period
from demos.bounce import dashed, draw_text
from demos.cli import Demo
from demos.stability import fitting
from engine import Body, Filter, Hinge, Polygon, Rod, Segment, Vector, World
from engine.forces import Gravity
from engine.render import (
    EXACT,
    GRID,
    INK,
    MUTED,
    PAPER,
    POSITION,
    Camera,
    Plot,
    Scene,
    draw_disc,
    font,
    marks,
)
from engine.render.world_view import BODY, draw_world

__all__ = [
    "DEMO",
    "G",
    "ROD_LENGTH",
    "ROD_WIDTH",
    "POINT_PIVOT",
    "PLANKS",
    "PLANK",
    "SLOPE",
    "WHEEL_RADIUS",
    "MOTOR_SPEED",
    "MAX_TORQUE",
    "Pendulums",
    "PlankChain",
    "Car",
    "RodScene",
    "ChainScene",
    "CarScene",
    "angle_from_down",
    "equivalent_length",
]

G = 9.81  # m/s^2
# The rod and the point pendulum.
ROD_DT = 1.0 / 240.0  # s
ROD_LENGTH = 1.0  # m
ROD_WIDTH = 0.04  # m
ROD_MASS = 1.0  # kg
THETA0 = math.pi / 2  # rad: both let go level
POINT_PIVOT = (2.0, 0.0)  # m: the point pendulum's fixed point (the rod's hinge is at 0, 0)
BOB_RADIUS = 0.05  # m (drawn; it does not turn, so it swings as a point)
# The chain.
CHAIN_DT = 1.0 / 480.0  # s
PLANKS = 20
PLANK = 0.2  # m, each plank's length
PLANK_WIDTH = 0.05  # m
PLANK_MASS = 0.1  # kg
# The car.
CAR_DT = 1.0 / 120.0  # s
SLOPE = math.radians(15.0)  # rad
SLOPE_LENGTH = 11.0  # m
START = 1.0  # m along the slope: where the rear wheel touches it
WHEEL_RADIUS = 0.3  # m
WHEEL_MASS = 1.0  # kg
AXLES = 1.2  # m between the wheels' centres
CHASSIS = (1.6, 0.3)  # m: the box's length and height
CHASSIS_MASS = 1.0  # kg
RIDE = 0.25  # m: the chassis's centre above the axles
MOTOR_SPEED = -8.0  # rad/s: clockwise, which rolls the car up a slope rising to the right
MAX_TORQUE = 2.0  # N m, each motor

#: The point pendulum's colour (the rod is draw_world's blue).
BOB = POSITION
CLOSED = EXACT  #: the closed form's curves

Color = tuple[int, int, int]


def angle_from_down(pos: Vector, pivot: Vector) -> float:
    """The angle (rad, -pi to pi) of ``pos`` about ``pivot`` from straight down,
    counter-clockwise: theta with pos = pivot + d (sin theta, -cos theta)."""
    d = pos - pivot
    return math.atan2(d.x, -d.y)


def equivalent_length(length: float = ROD_LENGTH, width: float = ROD_WIDTH) -> float:
    """The length (m) of the point pendulum with the period of a uniform ``length`` by
    ``width`` box hinged at the middle of an end: I_pivot / (m d), d = length / 2, with
    I_pivot = m (length^2 + width^2) / 12 + m d^2; 2 length / 3 + width^2 / (6 length)."""
    d = length / 2
    return ((length**2 + width**2) / 12 + d * d) / d


def _world() -> World:
    # The exact models, asked for: each scene is a lesson's closed form (a period, a car's
    # speed up a slope) that its joints hold to rounding.
    world = World(integrator="auto", solver="exact")
    world.add_force(Gravity((0.0, -G)))
    return world


class Crossings:
    """The times (s) a body's x passes its pivot's leftward, below it, each interpolated
    linearly within its step: once a period for a pendulum let go to the right."""

    def __init__(self, pivot_x: float) -> None:
        self.pivot_x = pivot_x
        self.times: list[float] = []

    def update(self, x0: float, x1: float, y1: float, t0: float, t1: float) -> None:
        a, b = x0 - self.pivot_x, x1 - self.pivot_x
        if a > 0.0 >= b and y1 < 0.0:
            self.times.append(t0 + (t1 - t0) * a / (a - b))

    def period(self) -> float | None:
        """The mean period (s) between the first and last crossing, or None before two."""
        c = self.times
        return (c[-1] - c[0]) / (len(c) - 1) if len(c) >= 2 else None


class PendulumSample(NamedTuple):
    """Both pendulums at one moment: time (s) and each one's angle from down (degrees)."""

    t: float
    rod: float
    point: float


class Pendulums:
    """A rod on a Hinge at its end and a point on a Rod of 2L/3, in one World, both let go
    level to the right of their pivots. A Steppable: ``history`` holds a sample at the start
    and after every step, ``rod_crossings`` and ``point_crossings`` each one's passes of the
    bottom."""

    def __init__(self) -> None:
        self.world = _world()
        shape = Polygon.box(ROD_LENGTH, ROD_WIDTH)
        self.rod = self.world.add(
            Body(Vector(ROD_LENGTH / 2, 0.0), shape=shape, mass=ROD_MASS)
        )  # fmt: skip
        self.hinge = self.world.add_link(Hinge(self.rod, self.world.static_body, (0.0, 0.0)))
        px, py = POINT_PIVOT
        self.pivot = Vector(px, py)
        length = 2.0 * ROD_LENGTH / 3.0
        self.bob = self.world.add(
            Body(Vector(px + length, py), mass=1.0, radius=BOB_RADIUS, fixed_rotation=True)
        )
        self.link = self.world.add_link(Rod(self.bob, POINT_PIVOT))
        self.rod_crossings = Crossings(0.0)
        self.point_crossings = Crossings(px)
        self.history: list[PendulumSample] = [self.sample()]

    @property
    def t(self) -> float:
        return self.world.t

    def angles(self) -> tuple[float, float]:
        """The rod's angle (its centre about the hinge) and the bob's, from down (rad)."""
        return (
            angle_from_down(self.rod.pos, Vector(0.0, 0.0)),
            angle_from_down(self.bob.pos, self.pivot),
        )

    def sample(self) -> PendulumSample:
        rod, point = self.angles()
        return PendulumSample(self.world.t, math.degrees(rod), math.degrees(point))

    def step(self, dt: float) -> None:
        t0, r0, b0 = self.world.t, self.rod.pos.x, self.bob.pos.x
        self.world.step(dt)
        t1, r, b = self.world.t, self.rod.pos, self.bob.pos
        self.rod_crossings.update(r0, r.x, r.y, t0, t1)
        self.point_crossings.update(b0, b.x, b.y, t0, t1)
        self.history.append(self.sample())

    def snapshot(self) -> tuple[Any, ...]:
        return (
            self.world.snapshot(),
            tuple(self.history),
            tuple(self.rod_crossings.times),
            tuple(self.point_crossings.times),
        )

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, history, rod, point = snapshot
        self.world.restore(world)
        self.history = list(history)
        self.rod_crossings.times, self.point_crossings.times = list(rod), list(point)


class ChainSample(NamedTuple):
    """The chain at one moment: time (s), the top hinge's force over the last step (N) and the
    widest gap of any hinge now (m)."""

    t: float
    force: float
    gap: float


class PlankChain:
    """PLANKS planks of PLANK m hinged end to end, the first to the world at the origin, let
    go level to the right. A Steppable."""

    def __init__(self, planks: int = PLANKS, length: float = PLANK) -> None:
        self.world = _world()
        shape = Polygon.box(length, PLANK_WIDTH)
        # One group: the planks pass through each other (only a hinge's two bodies are kept
        # from colliding by default), so the chain is the ideal one and keeps its energy.
        together = Filter(group=1)
        self.planks = [
            self.world.add(
                Body(Vector(length * (k + 0.5), 0.0), shape=shape, mass=PLANK_MASS, filter=together)
            )
            for k in range(planks)
        ]
        static = self.world.static_body
        ends = [static, *self.planks]
        self.hinges = [
            self.world.add_link(Hinge(ends[k + 1], ends[k], (length * k, 0.0)))
            for k in range(planks)
        ]
        self.dt = 0.0
        self.history: list[ChainSample] = [self.sample()]

    @property
    def t(self) -> float:
        return self.world.t

    def gap(self) -> float:
        """The widest distance between the two points a hinge holds together, now (m)."""
        return max((h.end_a() - h.end_b()).length() for h in self.hinges)

    def sample(self) -> ChainSample:
        force = self.hinges[0].force(self.dt).length() if self.dt > 0.0 else 0.0
        return ChainSample(self.world.t, force, self.gap())

    def step(self, dt: float) -> None:
        self.dt = dt
        self.world.step(dt)
        self.history.append(self.sample())

    def snapshot(self) -> tuple[Any, ...]:
        return self.world.snapshot(), tuple(self.history), self.dt

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, history, self.dt = snapshot
        self.world.restore(world)
        self.history = list(history)


class CarSample(NamedTuple):
    """The car at the end of a step: time (s); the chassis's velocity along the slope as the
    World gives it (m/s, up the slope positive); how fast the chassis moved up the slope in
    the step (m/s: its distance / dt); and how far it has climbed since the start (m)."""

    t: float
    velocity: float
    speed: float
    climbed: float


class Car:
    """A box chassis on two motor-driven wheels, at rest on the slope at START. A Steppable."""

    def __init__(self) -> None:
        self.world = _world()
        c, s = math.cos(SLOPE), math.sin(SLOPE)
        self.along, self.up = Vector(c, s), Vector(-s, c)
        top = self.along * SLOPE_LENGTH
        self.slope = self.world.add_collider(
            Segment((0.0, 0.0), (top.x, top.y), friction=1.0, restitution=0.0)
        )

        def at(distance: float, height: float) -> Vector:
            return self.along * distance + self.up * height

        self.chassis = self.world.add(
            Body(at(START + AXLES / 2, WHEEL_RADIUS + RIDE), shape=Polygon.box(*CHASSIS),
                 mass=CHASSIS_MASS, angle=SLOPE, friction=0.5, restitution=0.0)
        )  # fmt: skip
        self.wheels = [
            self.world.add(
                Body(
                    at(START + k * AXLES, WHEEL_RADIUS),
                    radius=WHEEL_RADIUS,
                    mass=WHEEL_MASS,
                    friction=1.0,
                    restitution=0.0,
                )
            )
            for k in range(2)
        ]
        self.motors = [
            self.world.add_link(
                Hinge(
                    wheel, self.chassis, wheel.pos, motor_speed=MOTOR_SPEED, max_torque=MAX_TORQUE
                )
            )
            for wheel in self.wheels
        ]
        self.start = self.chassis.pos
        self.history: list[CarSample] = [self.sample()]

    @property
    def t(self) -> float:
        return self.world.t

    def sample(self, before: Vector | None = None, dt: float = 0.0) -> CarSample:
        """The sample after a step of ``dt`` s that began with the chassis at ``before``;
        at rest with no step before it."""
        velocity = self.chassis.vel.dot(self.along)
        climbed = (self.chassis.pos - self.start).dot(self.along)
        if before is None:
            return CarSample(self.world.t, velocity, 0.0, climbed)
        speed = (self.chassis.pos - before).dot(self.along) / dt
        return CarSample(self.world.t, velocity, speed, climbed)

    @staticmethod
    def acceleration() -> float:
        """The closed form's acceleration (m/s^2) up the slope while the motors give their
        max torque, rolling without slipping: a = (2 T / r - M g sin(theta)) / (M + 2 I / r^2),
        M the whole car's mass and I = m r^2 / 2 a wheel's moment."""
        mass = CHASSIS_MASS + 2 * WHEEL_MASS
        moment = WHEEL_MASS * WHEEL_RADIUS**2 / 2
        drive = 2 * MAX_TORQUE / WHEEL_RADIUS - mass * G * math.sin(SLOPE)
        return drive / (mass + 2 * moment / WHEEL_RADIUS**2)

    @classmethod
    def closed_form(cls, t: float) -> float:
        """The closed form's speed (m/s) at ``t`` s: a t, until the motors' speed |w| r."""
        return min(cls.acceleration() * t, abs(MOTOR_SPEED) * WHEEL_RADIUS)

    @classmethod
    def closed_distance(cls, t: float) -> float:
        """How far (m) the closed form's car has climbed at ``t`` s: a t^2 / 2 until the
        knee t1 = |w| r / a, then a t1^2 / 2 + |w| r (t - t1)."""
        a, cruise = cls.acceleration(), abs(MOTOR_SPEED) * WHEEL_RADIUS
        knee = cruise / a
        if t <= knee:
            return 0.5 * a * t * t
        return 0.5 * a * knee * knee + cruise * (t - knee)

    def step(self, dt: float) -> None:
        before = self.chassis.pos
        self.world.step(dt)
        self.history.append(self.sample(before, dt))

    def snapshot(self) -> tuple[Any, ...]:
        return self.world.snapshot(), tuple(self.history)

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, history = snapshot
        self.world.restore(world)
        self.history = list(history)


# -- drawing --------------------------------------------------------------------------------


def _upto(history: Sequence[Any], t: float, dt: float) -> Sequence[Any]:
    """The samples at or before time ``t`` (the plots show the state's history, not a blend)."""
    k = min(len(history) - 1, max(0, int(t / dt + 1e-9)))
    return history[: k + 1]


def _every(samples: Sequence[Any], most: int = 1200) -> Sequence[Any]:
    """At most about ``most`` samples for a curve, evenly spaced, keeping the last."""
    step = max(1, len(samples) // most)
    out = list(samples[::step])
    if samples and out[-1] is not samples[-1]:
        out.append(samples[-1])
    return out


class HingeScene(Scene):
    """What the three scenes share: a header (title, a line of numbers) and the canvas's
    scale ``s`` (1 at 360 px tall)."""

    title = ""
    short_titles: tuple[str, ...] = ()
    min_size = (480, 270)
    s = 1.0

    def header(self, surface: pygame.Surface, t: float, line: str, right: float) -> None:
        """The title and ``line`` at the top left, kept left of ``right`` px."""
        s, m = self.s, round(8 * self.s)
        size = round(18 * s)
        title = fitting([self.title, *self.short_titles], max(12, size), right - m - 4 * s)
        draw_text(surface, title, (m, 4 * s), size)
        draw_text(surface, f"t = {t:5.2f} s   {line}", (m, 25 * s), round(14 * s), MUTED)

    def pivot(self, surface: pygame.Surface, at: tuple[float, float]) -> None:
        """A fixed point: a short hatched bar over it."""
        s = self.s
        x, y = self.camera.point(at)
        half = round(14 * s)
        y -= max(5, round(6 * s))  # just clear of a hinge's ring
        pygame.draw.line(surface, INK, (x - half, y), (x + half, y), max(2, round(2 * s)))
        for k in range(-half, half, max(4, round(6 * s))):
            pygame.draw.line(
                surface, GRID, (x + k, y - 1), (x + k + round(5 * s), y - round(6 * s))
            )


class RodScene(HingeScene):
    """A rod on a hinge beside the point pendulum of 2L/3: both angles against time, the
    exact period marked."""

    name = "rod"
    title = "A rod on a hinge swings as a point on a rod of 2L/3"
    short_titles = ("A rod on a hinge, a point on 2L/3", "Rod on a hinge")
    summary = "a rod on a hinge at its end beside a point pendulum of 2L/3: they swing together"
    duration = 8.0
    dt = ROD_DT
    #: The motion's view (m): left, bottom, right, top.
    view = (-1.1, -1.1, POINT_PIVOT[0] + 0.75, 0.2)
    world: Pendulums

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.pendulums = Pendulums()
        w, h = size
        s = self.s = h / 360
        m = round(8 * s)
        band = round(150 * s)
        top = round(46 * s)
        self.camera = Camera.fit(self.view, (m, top, round(w * 0.8) - 2 * m, band))
        self.exact = period(THETA0, equivalent_length())
        self.exact_point = period(THETA0, 2 * ROD_LENGTH / 3)
        plot_top = top + band + round(4 * s)
        self.theta_plot = Plot(
            (m, plot_top, w - 2 * m, h - plot_top - m),
            t_max=self.duration,
            y_range=(-100.0, 150.0),
            title="\u03b8(t)  degrees",
            t_step=1.0,
            y_step=45.0,
            color=BODY,
            text_scale=s,
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        p, s = self.pendulums, self.s
        w = surface.get_width()
        surface.fill(PAPER)
        rod, point = p.rod_crossings.period(), p.point_crossings.period()
        line = "measured T: rod " + ("..." if rod is None else f"{rod:.5f} s")
        line += ", point " + ("..." if point is None else f"{point:.5f} s")
        self.header(surface, t, line, w)
        self.pivot(surface, (0.0, 0.0))
        self.pivot(surface, POINT_PIVOT)
        draw_world(surface, p.world, self.camera, alpha)
        at = p.world.position_of(p.bob, alpha)
        assert isinstance(at, Vector)
        draw_disc(surface, self.camera, (at.x, at.y), BOB_RADIUS, None, BOB)
        self._legend(surface)
        samples = _every(_upto(p.history, t, self.dt))
        ts = [q.t for q in samples]
        plot = self.theta_plot
        plot.draw_frame(surface)
        a = plot.area
        size = max(12, round(13 * s))
        captions = [
            f"dashed: the rod's exact period, T = 4 sqrt(L_eq/g) K(sin 45\u00b0) = "
            f"{self.exact:.5f} s,  L_eq = 2L/3 + w\u00b2/(6L)",
            f"dashed: the rod's exact period, T = {self.exact:.5f} s",
            f"dashed: T = {self.exact:.5f} s",
        ]
        caption = draw_text(
            surface,
            fitting(captions, size, a.width - 8 * s),
            (a.left + 3 * s, a.top + 2 * s),
            round(13 * s),
            INK,
        )
        k = 1
        while k * self.exact <= self.duration:
            px = float(plot.to_px(k * self.exact, 0.0)[0])
            top = caption.bottom + 2
            dashed(surface, INK, (px, top), (px, a.bottom - 1), dash=5)
            marks.note(surface, "marker", pygame.Rect(round(px), top, 1, a.bottom - top))
            draw_text(
                surface, f"{k}T", (px + 3 * s, a.bottom - 1), round(13 * s), INK, "bottomleft"
            )
            k += 1
        # The point's curve wide and light under the rod's: where they agree, one line with
        # a green edge.
        plot.draw_curve(
            surface, ts, [q.point for q in samples], color=BOB, width=max(4, round(6 * s))
        )
        plot.draw_curve(surface, ts, [q.rod for q in samples], color=BODY)

    def _legend(self, surface: pygame.Surface) -> None:
        s = self.s
        x = round(surface.get_width() * 0.8)
        y = round(60 * s)
        size = round(13 * s)
        rows = [
            ("blue: a rod 1 m by 4 cm", BODY),
            ("on a Hinge at its end", BODY),
            ("green: a point on a", BOB),
            ("Rod of 2L/3 = 0.667 m", BOB),
            ("both let go level", MUTED),
        ]
        for k, (text, colour) in enumerate(rows):
            draw_text(surface, text, (x, y + k * 17 * s), size, colour)


class ChainScene(HingeScene):
    """Twenty planks on hinges, let go level: the top hinge's force and every hinge's gap."""

    name = "chain"
    title = "A chain of 20 planks on hinges"
    short_titles = ("20 planks on hinges",)
    summary = "20 planks hinged end to end, let go level: they whip, every hinge holds"
    duration = 4.0
    dt = CHAIN_DT
    view = (-3.8, -4.0, 4.05, 0.3)
    world: PlankChain
    #: The force plot's range (N).
    force_range = (0.0, 250.0)

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.chain = PlankChain()
        w, h = size
        s = self.s = h / 360
        m = round(8 * s)
        left = round(w * 0.6)
        top = round(46 * s)
        self.camera = Camera.fit(self.view, (m, top, left - 2 * m, h - top - m))
        self.plot_left = left
        half = (h - round(6 * s)) // 2
        common = {"t_max": self.duration, "t_step": 1.0, "text_scale": s}
        self.force_plot = Plot(
            (left, round(4 * s), w - left - m, half - round(2 * s)),
            y_range=self.force_range,
            title="force on the top hinge  N",
            y_step=50.0,
            color=CLOSED,
            **common,  # type: ignore[arg-type]
        )
        self.gap_plot = Plot(
            (left, round(6 * s) + half, w - left - m, half - round(2 * s)),
            y_range=(-17.0, -8.0),
            title="log10 widest hinge gap (m)",
            y_step=2.0,
            color=INK,
            **common,  # type: ignore[arg-type]
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        c, s = self.chain, self.s
        surface.fill(PAPER)
        samples = _upto(c.history, t, self.dt)
        worst = max(q.gap for q in samples)
        force, weight = samples[-1].force, PLANKS * PLANK_MASS * G
        lines = [
            f"widest hinge gap so far {worst:.1e} m;  top hinge {force:.1f} N "
            f"(weight {weight:.1f} N)",
            f"widest hinge gap so far {worst:.1e} m;  top hinge {force:.1f} N",
            f"widest gap {worst:.1e} m",
        ]
        size = max(12, round(14 * s))  # as the header writes it (demos.bounce.draw_text)
        room = self.plot_left - round(8 * s) - font(size).size("t = 10.00 s   ")[0]
        self.header(surface, t, fitting(lines, size, room), self.plot_left)
        self.pivot(surface, (0.0, 0.0))
        draw_world(surface, c.world, self.camera, alpha)
        shown = _every(samples)
        ts = [q.t for q in shown]
        plot = self.force_plot
        plot.draw_frame(surface)
        plot.draw_curve(surface, ts, [q.force for q in shown])
        plot = self.gap_plot
        plot.draw_frame(surface)
        # Where every gap is 0 to the last bit, log10 is -inf: drawn at the panel's floor.
        logs = [math.log10(max(q.gap, 1e-17)) for q in shown]
        plot.draw_curve(surface, ts, logs)
        a = plot.area
        y = float(plot.to_px(0.0, -9.0)[1])
        dashed(surface, CLOSED, (a.left, y), (a.right - 1, y), dash=5)
        draw_text(
            surface,
            "1e-9 m: the tests' bound",
            (a.right - 4 * s, y + 2 * s),
            round(13 * s),
            CLOSED,
            "topright",
        )


class CarScene(HingeScene):
    """A car on motor-driven hinges climbs a 15 degree slope: its speed against the closed
    form's."""

    name = "car"
    title = "A car on motors climbs 15\u00b0"
    short_titles = ("A car on motors",)
    summary = "two wheels on hinges with motors under a box climb 15 deg, against the closed form"
    duration = 4.0
    dt = CAR_DT
    #: Sky over the slope: the plot sits in it, clear of the car as it passes under.
    view = (-0.4, -0.3, SLOPE_LENGTH * math.cos(SLOPE) + 0.4, 4.6)
    world: Car

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.car = Car()
        w, h = size
        s = self.s = h / 360
        m = round(8 * s)
        top = round(46 * s)
        self.camera = Camera.fit(self.view, (m, top, w - 2 * m, h - top - m))
        # The plot in the empty corner over the slope's foot.
        self.speed_plot = Plot(
            (m, top, round(w * 0.47), round(135 * s)),
            t_max=self.duration,
            y_range=(-0.2, 2.7),
            title="velocity up the slope  m/s",
            t_step=1.0,
            y_step=1.0,
            color=BODY,
            text_scale=s,
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        car, s = self.car, self.s
        surface.fill(PAPER)
        samples = _upto(car.history, t, self.dt)
        now = samples[-1]
        cruise = abs(MOTOR_SPEED) * WHEEL_RADIUS
        self.header(
            surface,
            t,
            f"v = {now.velocity:.4f} m/s, closed form {Car.closed_form(now.t):.4f};  "
            f"climbed {now.climbed:.3f} m, closed form {Car.closed_distance(now.t):.3f}",
            surface.get_width(),
        )
        draw_world(surface, car.world, self.camera, alpha)
        shown = _every(samples)
        ts = [q.t for q in shown]
        plot = self.speed_plot
        plot.draw_frame(surface)
        knee = cruise / Car.acceleration()
        # The closed form wide and light under the World's velocity: where they agree, one
        # line with a purple edge.
        plot.draw_curve(
            surface, [0.0, knee, self.duration], [0.0, cruise, cruise], color=CLOSED,
            width=max(4, round(6 * s)), marker=False,
        )  # fmt: skip
        plot.draw_curve(surface, ts, [q.velocity for q in shown])
        a = plot.area
        size = round(13 * s)
        axis = float(plot.to_px(0.0, 0.0)[1])  # the t axis, at 0 m/s: the words sit on it
        draw_text(
            surface,
            f"closed form: a = {Car.acceleration():.2f} m/s\u00b2 to {cruise:.1f} m/s",
            (a.right - 4 * s, axis - 3 * s - 15 * s),
            size,
            CLOSED,
            "bottomright",
        )
        draw_text(
            surface,
            "the World's velocity",
            (a.right - 4 * s, axis - 3 * s),
            size,
            BODY,
            "bottomright",
        )


DEMO = Demo(
    name="hinges",
    summary="Hinges: a rod swinging as a 2L/3 pendulum, a chain of 20 planks, a car on motors",
    scenes={"rod": RodScene, "chain": ChainScene, "car": CarScene},
)
