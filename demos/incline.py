"""Incline: a hoop, a disc and a frictionless slider race down a slope; a disc slips on a steep one.

Run with ``python -m demos incline``. Two scenes, each checked against its closed form:

- ``race``: three lanes tilted by 20 degrees, side by side, and on each a body let go from
  rest at the same height: a hoop (``moment=m r^2``), a solid disc (the default moment,
  m r^2 / 2) and a slider (a disc with friction 0: nothing turns it, so it slides as a
  frictionless box would: friction is what would turn a box on a slope). Rolling without slipping,
  a = g sin(theta) / (1 + I / (m r^2)), so a body covers L = 4 m along its lane in
  t = sqrt(2 L / a): the times stand 1 : sqrt(3/2) : sqrt(2) for slider : disc : hoop,
  whatever the masses and radii. Each crossing is timed within its step by solving that
  step's motion at constant acceleration (what the engine's exact method does), and the
  table puts it beside the closed form.
- ``slip``: a disc on a 60 degree slope with mu = 0.25 (it would roll only with
  mu >= tan(theta) / 3 = 0.577): it slides at a = g (sin - mu cos) while friction spins it up
  at 2 mu g cos(theta) / r, so the slip speed v - omega r grows at g (sin - 3 mu cos).

Every disc that turns is drawn with a radius line (``engine.render.draw_disc``), so a roll is
seen: the hoop's and the disc's lines go round, the slider's keeps pointing along +x.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import pygame

from demos.cli import Demo
from demos.cradle import faded
from engine import Body, Segment, Vector, World
from engine.forces import Gravity
from engine.render import (
    EULER,
    INK,
    MUTED,
    PAPER,
    POSITION,
    VELOCITY,
    Camera,
    Plot,
    Scene,
    draw_disc,
    draw_text,
)
from engine.render.draw import Color
from engine.render.world_view import angle_of

__all__ = [
    "DEMO",
    "G",
    "LENGTH",
    "RaceScene",
    "Racer",
    "SlipScene",
    "crossing_time",
    "race_acceleration",
]

G = 9.81  # m/s^2
DT = 1.0 / 120.0  # s
# The race.
RACE_SLOPE = math.radians(20.0)  # rad
RADIUS = 0.25  # m, every racer's
MASS = 1.0  # kg (it cancels: a depends on I / (m r^2) only)
LENGTH = 4.0  # m along the slope, from the start to the finish line
LANE = 11.0  # m, each lane's length past its body's start (the slider covers 10.5 m in 2.5 s)
STAGGER = 2.0  # m: each lane starts this far right of the one before, at the same height
# The slip.
SLIP_SLOPE = math.radians(60.0)  # rad
SLIP_MU = 0.25
SLIP_RADIUS = 0.5  # m
SLIP_LANE = 9.5  # m along the slope (the disc covers 8.2 m in 1.5 s)

SLIDER, DISC, HOOP = POSITION, VELOCITY, EULER  #: the racers' colours


def race_acceleration(ratio: float, slope: float = RACE_SLOPE) -> float:
    """a = g sin(theta) / (1 + I / (m r^2)) (m/s^2): a body rolling without slipping down a
    slope, with ``ratio`` = I / (m r^2) (0 for a frictionless slider, 1/2 a disc, 1 a hoop)."""
    return G * math.sin(slope) / (1.0 + ratio)


def crossing_time(
    t0: float, dt: float, s0: float, v0: float, s1: float, v1: float, at: float
) -> float | None:
    """The time (s) within the step from ``t0`` to ``t0 + dt`` at which a body at ``s0``
    (m, along its path) moving at ``v0`` (m/s), and at ``s1``, ``v1`` after the step, passes
    ``at``: the root of s0 + v0 tau + a tau^2 / 2 = at with a = (v1 - v0) / dt, the step's
    constant acceleration (so exact for the engine's steps); None if it does not pass it."""
    if not s0 < at <= s1:
        return None
    a = (v1 - v0) / dt
    gap = at - s0
    # tau = (-v0 + sqrt(v0^2 + 2 a gap)) / a, written without the cancellation at small a.
    root = math.sqrt(max(v0 * v0 + 2.0 * a * gap, 0.0))
    return t0 + 2.0 * gap / (v0 + root)


@dataclass
class Racer:
    """One body in the race: its name, I / (m r^2) (``ratio``), colour, body, where it
    started and the unit vector down its lane; ``finish`` is when it crossed (s)."""

    name: str
    ratio: float
    colour: tuple[int, int, int]
    body: Body
    start: Vector
    down: Vector
    finish: float | None = None
    #: (distance along the lane (m), speed down it (m/s)) at the last step.
    last: tuple[float, float] = (0.0, 0.0)

    def along(self) -> tuple[float, float]:
        """(distance covered down the lane (m), speed down it (m/s)) now."""
        return (self.body.pos - self.start).dot(self.down), self.body.vel.dot(self.down)

    @property
    def theory(self) -> float:
        """The closed form's time (s) to cover LENGTH from rest: sqrt(2 L / a)."""
        return math.sqrt(2.0 * LENGTH / race_acceleration(self.ratio))


@dataclass
class Race:
    """The race's World, its three lanes and racers, stepped and timed together."""

    world: World = field(default_factory=World)
    racers: list[Racer] = field(default_factory=list)
    lanes: list[tuple[Vector, Vector]] = field(default_factory=list)

    def __post_init__(self) -> None:
        th = RACE_SLOPE
        down = Vector(math.cos(th), -math.sin(th))
        normal = Vector(math.sin(th), math.cos(th))
        self.world.add_force(Gravity((0.0, -G)))
        kinds = [
            ("slider", 0.0, SLIDER, {"friction": 0.0}),
            ("disc", 0.5, DISC, {"friction": 0.5}),
            ("hoop", 1.0, HOOP, {"friction": 0.5, "moment": MASS * RADIUS**2}),
        ]
        for k, (name, ratio, colour, kw) in enumerate(kinds):
            # Lane k passes through (k STAGGER, 0): the bodies start at the same height.
            top = Vector(k * STAGGER, 0.0)
            a, b = top - down * 0.6, top + down * LANE
            self.world.add_collider(Segment(tuple(a), tuple(b)))
            self.lanes.append((a, b))
            start = top + normal * RADIUS
            body = self.world.add(
                Body(start, radius=RADIUS, mass=MASS, restitution=0.0, **kw)  # type: ignore[arg-type]
            )
            self.racers.append(Racer(name, ratio, colour, body, start, down))

    @property
    def t(self) -> float:
        return self.world.t

    def step(self, dt: float) -> None:
        t0 = self.world.t
        self.world.step(dt)
        for r in self.racers:
            s0, v0 = r.last
            s1, v1 = r.last = r.along()
            if r.finish is None:
                r.finish = crossing_time(t0, dt, s0, v0, s1, v1, LENGTH)

    def snapshot(self) -> Any:
        return self.world.snapshot(), [(r.finish, r.last) for r in self.racers]

    def restore(self, snapshot: Any) -> None:
        self.world.restore(snapshot[0])
        for r, (finish, last) in zip(self.racers, snapshot[1], strict=True):
            r.finish, r.last = finish, last


def _hoop(
    surface: pygame.Surface,
    camera: Camera,
    at: tuple[float, float],
    radius: float,
    angle: float | None,
    colour: tuple[int, int, int],
    outline: tuple[int, int, int] = INK,
) -> None:
    """A hoop: a pale disc with a thick rim in ``colour`` and its radius line."""
    draw_disc(surface, camera, at, radius, angle, faded(colour, 0.35), outline)
    r_px = round(radius * camera.scale)
    rim = max(2, round(r_px / 4))
    pygame.draw.circle(surface, colour, camera.point(at), r_px, rim)
    pygame.draw.circle(surface, outline, camera.point(at), r_px, 1)


def _dashed(
    surface: pygame.Surface, colour: tuple[int, int, int], y: int, x0: int, x1: int
) -> None:
    for x in range(x0, x1, 10):
        pygame.draw.line(surface, colour, (x, y), (min(x + 5, x1), y), 1)


class RaceScene(Scene):
    """A hoop, a disc and a frictionless slider let go together on three 20 degree lanes."""

    name = "race"
    summary = "a hoop, a disc and a frictionless slider race 4 m down a 20 degree slope"
    duration = 2.5
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.25
    world: Race

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.race = Race()
        w, h = size
        s = self.s = h / 360
        self.header = round(66 * s)
        m = round(8 * s)
        # The lanes, with room above the bodies for their names.
        drop = LANE * math.sin(RACE_SLOPE)
        view = (-0.7, -drop - 0.2, 2 * STAGGER + LANE * math.cos(RACE_SLOPE) + 0.2, 1.05)
        x0, y0, x1, y1 = view
        scale = min((w - 2 * m) / (x1 - x0), (h - self.header - m) / (y1 - y0))
        # Centred across, set just under the header: the table goes under the lanes' left.
        self.camera = Camera(
            scale, ((w - scale * (x1 - x0)) / 2 - scale * x0, self.header + scale * y1)
        )

    def _bodies(self, surface: pygame.Surface, alpha: float, fade: float = 1.0) -> None:
        world = self.race.world
        for r in self.race.racers:
            p = world.position_of(r.body, alpha)
            assert isinstance(p, Vector)  # a 2D World
            at = (float(p.x), float(p.y))
            colour, outline = faded(r.colour, fade), faded(INK, fade)
            angle = angle_of(world, r.body, alpha)
            if r.name == "hoop":
                _hoop(surface, self.camera, at, RADIUS, angle, colour, outline)
            else:
                draw_disc(surface, self.camera, at, RADIUS, angle, colour, outline)

    def _course(self, surface: pygame.Surface) -> None:
        """The lanes, each racer's name at its lane's top, and the start and finish lines."""
        s, cam = self.s, self.camera
        w = surface.get_width()
        for (a, b), r in zip(self.race.lanes, self.race.racers, strict=True):
            pygame.draw.line(surface, INK, cam.point(tuple(a)), cam.point(tuple(b)), 2)
            # The name above the body's start, clear of the lanes and of the other bodies.
            x, y = cam.point((r.start.x, r.start.y + RADIUS + 0.04))
            draw_text(surface, r.name, (x, y), round(15 * s), r.colour, "midbottom")
        th = RACE_SLOPE
        y_start = RADIUS / math.cos(th)  # the centres' height at the start
        y_finish = y_start - LENGTH * math.sin(th)
        left = cam.point((-0.2, 0.0))[0]
        for y, text in ((y_start, "start"), (y_finish, f"finish: L = {LENGTH:g} m down the slope")):
            py = cam.point((0.0, y))[1]
            _dashed(surface, MUTED, py, left, w - round(8 * s))
            draw_text(surface, text, (w - 8 * s, py - 1), round(13 * s), MUTED, "bottomright")

    def _header(self, surface: pygame.Surface, t: float) -> None:
        s, w = self.s, surface.get_width()
        x = 8 * s
        draw_text(
            surface, "A race down a 20\u00b0 slope, let go together", (x, 4 * s), round(20 * s)
        )
        draw_text(surface, f"t = {t:4.2f} s", (w - x, 4 * s), round(20 * s), INK, "topright")
        draw_text(
            surface,
            "rolling: a = g sin(\u03b8) / (1 + I / (m r\u00b2)),   t = \u221a(2 L / a)",
            (x, 24 * s),
            round(17 * s),
        )
        draw_text(
            surface,
            "the slider is a disc with friction 0: it never turns, so it stands for a "
            "frictionless box",
            (x, 43 * s),
            round(14 * s),
            MUTED,
        )

    def _table(self, surface: pygame.Surface, t: float) -> None:
        """Measured against theory, a row a racer, under the lanes on the left."""
        s, h = self.s, surface.get_height()
        size, row = round(14 * s), 15 * s
        cols = [8 * s, 58 * s, 118 * s, 178 * s, 250 * s, 330 * s]
        top = h - 5 * row - 6 * s
        heads = ["", "I/(mr\u00b2)", "a m/s\u00b2", "theory s", "measured s", "rel. error"]
        for c, text in zip(cols, heads, strict=True):
            draw_text(surface, text, (c, top), size, MUTED)
        slider = self.race.racers[0]
        for k, r in enumerate(self.race.racers, 1):
            y = top + k * row
            done = r.finish is not None and r.finish <= t + 1e-12
            cells = [
                r.name,
                f"{r.ratio:g}",
                f"{race_acceleration(r.ratio):.4f}",
                f"{r.theory:.6f}",
                f"{r.finish:.6f}" if done and r.finish is not None else "...",
                f"{(r.finish - r.theory) / r.theory:+.0e}" if done and r.finish else "",
            ]
            for c, text in zip(cols, cells, strict=True):
                draw_text(surface, text, (c, y), size, r.colour if c == cols[0] else INK)
        hoop, disc = self.race.racers[2], self.race.racers[1]
        if hoop.finish is not None and hoop.finish <= t + 1e-12:
            assert slider.finish is not None and disc.finish is not None
            ratios = (
                f"times 1 : {disc.finish / slider.finish:.6f} : {hoop.finish / slider.finish:.6f}"
                f"   (1 : \u221a(3/2) : \u221a2 = 1 : {math.sqrt(1.5):.6f} : {math.sqrt(2):.6f})"
            )
        else:
            ratios = "times slider : disc : hoop should stand 1 : \u221a(3/2) : \u221a2"
        draw_text(surface, ratios, (cols[0], top + 4 * row), size, INK)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        surface.fill(PAPER)
        t = self.time(alpha)
        self._course(surface)
        self._bodies(surface, alpha)
        self._header(surface, t)
        self._table(surface, t)

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The three racers every strobe_interval, older images fainter: the spacing grows
        fastest for the slider, and the radius lines show how far each has turned."""
        self.build(surface.get_size())
        surface.fill(PAPER)
        self._course(surface)
        for k, t in enumerate(times):
            while self.race.t < t - 1e-9:
                self.race.step(self.dt)
            self._bodies(surface, 1.0, 0.3 + 0.7 * (k + 1) / len(times))
        s = self.s
        draw_text(
            surface,
            f"The racers every {self.strobe_interval:g} s to {times[-1]:g} s",
            (8 * s, 4 * s),
            round(20 * s),
        )
        draw_text(
            surface,
            "older images fainter; the radius lines turn with the hoop and the disc",
            (8 * s, 26 * s),
            round(14 * s),
            MUTED,
        )
        self._table(surface, times[-1])


@dataclass
class Slip:
    """A disc on a steep slope with little friction, and what it measured each step."""

    world: World = field(default_factory=World)
    samples: list[tuple[float, float, float]] = field(default_factory=list)  # (t, v, w r)
    accel: float = 0.0  # m/s^2 down the slope, over the last step
    angular: float = 0.0  # rad/s^2, clockwise (the way it rolls downhill), over the last step

    def __post_init__(self) -> None:
        th = SLIP_SLOPE
        self.down = Vector(math.cos(th), -math.sin(th))
        normal = Vector(math.sin(th), math.cos(th))
        self.world.add_force(Gravity((0.0, -G)))
        self.top = Vector(0.0, 0.0)
        self.bottom = self.down * SLIP_LANE
        self.world.add_collider(Segment(tuple(self.top - self.down * 0.3), tuple(self.bottom)))
        start = self.down * 0.3 + normal * SLIP_RADIUS
        self.disc = self.world.add(
            Body(start, radius=SLIP_RADIUS, mass=MASS, friction=SLIP_MU, restitution=0.0)
        )
        self.samples.append((0.0, 0.0, 0.0))

    @property
    def t(self) -> float:
        return self.world.t

    def speeds(self) -> tuple[float, float]:
        """(v down the slope, omega r with omega clockwise) (m/s), now."""
        return self.disc.vel.dot(self.down), -self.disc.angular_velocity * SLIP_RADIUS

    def at(self, t: float) -> tuple[float, float]:
        """(v, omega r) (m/s) at the time ``t`` (s), between the samples of the steps (both
        change at a constant rate within a step, so the blend is exact)."""
        (t0, v0, w0), (t1, v1, w1) = self.samples[0], self.samples[-1]
        for k in range(len(self.samples) - 1, 0, -1):
            if self.samples[k - 1][0] <= t:
                (t0, v0, w0), (t1, v1, w1) = self.samples[k - 1], self.samples[k]
                break
        f = min(max((t - t0) / (t1 - t0), 0.0), 1.0) if t1 > t0 else 1.0
        return v0 + (v1 - v0) * f, w0 + (w1 - w0) * f

    def step(self, dt: float) -> None:
        v0, w0 = self.speeds()
        self.world.step(dt)
        v1, w1 = self.speeds()
        self.accel = (v1 - v0) / dt
        self.angular = (w1 - w0) / SLIP_RADIUS / dt
        self.samples.append((self.world.t, v1, w1))

    def snapshot(self) -> Any:
        return self.world.snapshot(), list(self.samples), self.accel, self.angular

    def restore(self, snapshot: Any) -> None:
        self.world.restore(snapshot[0])
        self.samples = list(snapshot[1])
        self.accel, self.angular = snapshot[2], snapshot[3]


def slip_theory() -> tuple[float, float]:
    """(a = g (sin - mu cos) m/s^2, angular acceleration 2 mu g cos(theta) / r rad/s^2)."""
    th = SLIP_SLOPE
    return G * (math.sin(th) - SLIP_MU * math.cos(th)), 2 * SLIP_MU * G * math.cos(th) / SLIP_RADIUS


class SlipScene(Scene):
    """A disc slips down a 60 degree slope with mu = 0.25: a and its spin-up against theory."""

    name = "slip"
    summary = "a disc slips down 60 degrees with mu 0.25: a = g (sin - mu cos), spin 2 mu g cos / r"
    duration = 1.5
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.25
    world: Slip

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.slip = Slip()
        w, h = size
        s = self.s = h / 360
        m = round(8 * s)
        top = round(30 * s)
        th = SLIP_SLOPE
        view = (-0.6, -SLIP_LANE * math.sin(th) - 0.2, SLIP_LANE * math.cos(th) + 0.9, 1.3)
        column = round(w * 0.30)
        self.camera = Camera.fit(view, (m, top, column - m, h - top - m))
        left = column + m
        self.text_left = left
        plot_top = round(150 * s)
        self.plot = Plot(
            (left, plot_top, w - left - m, h - plot_top - m),
            t_max=self.duration,
            y_range=(0.0, 12.0),
            title="m/s:  v,  \u03c9 r,  slip v - \u03c9 r",
            t_step=0.5,
            y_step=2.0,
            text_scale=s,
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        slip, s, cam = self.slip, self.s, self.camera
        surface.fill(PAPER)
        t = self.time(alpha)
        pygame.draw.line(
            surface,
            INK,
            cam.point(tuple(slip.top - slip.down * 0.3)),
            cam.point(tuple(slip.bottom)),
            2,
        )
        p = slip.world.position_of(slip.disc, alpha)
        assert isinstance(p, Vector)  # a 2D World
        angle = angle_of(slip.world, slip.disc, alpha)
        draw_disc(surface, cam, (float(p.x), float(p.y)), SLIP_RADIUS, angle, VELOCITY)
        w = surface.get_width()
        draw_text(
            surface,
            "Slipping: a disc on a 60\u00b0 slope, \u03bc = 0.25",
            (8 * s, 4 * s),
            round(20 * s),
        )
        draw_text(surface, f"t = {t:4.2f} s", (w - 8 * s, 4 * s), round(20 * s), INK, "topright")
        a_th, alpha_th = slip_theory()
        x, size = self.text_left, round(15 * s)
        v, wr = slip.at(t)
        rows = [
            (
                f"a = {slip.accel:.9f} m/s\u00b2    g (sin \u03b8 - \u03bc cos \u03b8) = "
                f"{a_th:.9f}",
                INK,
            ),
            (
                f"\u03c9' = {slip.angular:.9f} rad/s\u00b2    2 \u03bc g cos \u03b8 / r = "
                f"{alpha_th:.9f}",
                INK,
            ),
            (
                f"v = {v:.3f} m/s,  \u03c9 r = {wr:.3f} m/s,  slip v - \u03c9 r = {v - wr:.3f} m/s",
                INK,
            ),
            (
                f"the slip grows at g (sin \u03b8 - 3 \u03bc cos \u03b8) = "
                f"{G * (math.sin(SLIP_SLOPE) - 3 * SLIP_MU * math.cos(SLIP_SLOPE)):.3f} m/s\u00b2",
                MUTED,
            ),
            (
                f"\u03c9 clockwise, the way it rolls; it would roll only with "
                f"\u03bc \u2265 tan \u03b8 / 3 = {math.tan(SLIP_SLOPE) / 3:.3f}",
                MUTED,
            ),
        ]
        for k, (text, colour) in enumerate(rows):
            draw_text(surface, text, (x, (32 + 22 * k) * s), size, colour)
        shown = [q for q in slip.samples if q[0] <= t + 1e-9]
        ts = [q[0] for q in shown]
        self.plot.draw_frame(surface)
        self.plot.draw_curve(surface, ts, [q[1] for q in shown], VELOCITY)
        self.plot.draw_curve(surface, ts, [q[2] for q in shown], POSITION)
        self.plot.draw_curve(surface, ts, [q[1] - q[2] for q in shown], EULER)
        if shown:
            # Each curve's name at its end, pushed apart where the curves run together (at
            # first all three are 0).
            ends: list[tuple[float, float, str, Color]] = []
            for value, name, colour in (
                (shown[-1][1], "v", VELOCITY),
                (shown[-1][2], "\u03c9 r", POSITION),
                (shown[-1][1] - shown[-1][2], "slip", EULER),
            ):
                px, py = self.plot.to_px(shown[-1][0], min(value, 12.0))
                ends.append((float(py) - 5 * s, float(px), name, colour))
            # Right of the curves' ends while they are short (left of them the axis has its
            # numbers), left of them once they are long.
            early = shown[-1][0] < 0.5 * self.duration
            ends.sort(reverse=True)
            above = math.inf
            for top, left, name, colour in ends:
                y = min(top, above - 16 * s)  # above the label below it
                above = y
                at = (left + 4 * s, y) if early else (left - 4 * s, y)
                anchor = "bottomleft" if early else "bottomright"
                draw_text(surface, name, at, round(15 * s), colour, anchor)

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The disc every strobe_interval: its radius line turns more slowly than it slides."""
        self.build(surface.get_size())
        surface.fill(PAPER)
        slip, cam, s = self.slip, self.camera, self.s
        pygame.draw.line(
            surface,
            INK,
            cam.point(tuple(slip.top - slip.down * 0.3)),
            cam.point(tuple(slip.bottom)),
            2,
        )
        for k, t in enumerate(times):
            while slip.t < t - 1e-9:
                slip.step(self.dt)
            fade = 0.3 + 0.7 * (k + 1) / len(times)
            p = slip.disc.pos
            draw_disc(
                surface, cam, (p.x, p.y), SLIP_RADIUS, slip.disc.angle, faded(VELOCITY, fade),
                faded(INK, fade),
            )  # fmt: skip
        draw_text(
            surface,
            f"slip: the disc every {self.strobe_interval:g} s; it turns less than a rolling "
            "disc would",
            (8 * s, 4 * s),
            round(18 * s),
        )
        a_th, alpha_th = slip_theory()
        draw_text(
            surface,
            f"a = g (sin \u03b8 - \u03bc cos \u03b8) = {a_th:.3f} m/s\u00b2,  "
            f"\u03c9' = 2 \u03bc g cos \u03b8 / r = {alpha_th:.3f} rad/s\u00b2",
            (self.text_left, 40 * s),
            round(15 * s),
        )


DEMO = Demo(
    name="incline",
    summary="A hoop, a disc and a frictionless slider race down a slope; a disc slips on a "
    "steep one",
    scenes={"race": RaceScene, "slip": SlipScene},
)
