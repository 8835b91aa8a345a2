"""A ball bouncing on a floor, solved at the exact moment of each impact, against a discrete check.

    python -m demos bounce                    # frames: out/bounce/drop/, tunnel/, drift/
    python -m demos bounce --scene drop --window
    python -m demos bounce --strobe           # one motion diagram per scene

Scene ``drop``: a ball (radius 0.5 m, restitution e = 0.8) falls from h0 = 10 m (measured to
its bottom) onto a floor, in a World with the closed-form method ("auto" picks "exact" for
gravity alone) at dt = 1/60 s. Each bounce keeps e of the speed, so e^2 of the energy, and
the n-th apex is h0 e^(2n). The engine solves each impact's moment within the step, so the
apexes it reaches are that formula to rounding (about 1e-15), however coarse dt is. Beside
the ball: its height y(t) with each apex measured and labelled against h0 e^(2n), and its
energy E(t) per kg stepping down by e^2 = 0.64 at each bounce.

Scenes ``tunnel`` and ``drift``: the same physics against the loop most games (and pymunk,
in effect) run, written out in :class:`DiscreteBall`: move the ball a whole step, then test
whether it overlaps a wall, and if it does push it out and reflect its velocity.

* ``tunnel`` (slow motion, one 1/60 s step every 0.4 s): a ball of radius 0.1 m at 200 m/s
  toward a wall of zero thickness. The discrete check sees the ball 2.0 m before the wall
  and then 1.3 m past it, never overlapping: it passes straight through. The engine sweeps
  the step's path, finds the impact 59.5 ms in and bounces.
* ``drift``: e = 1, dropped from 10 m. The discrete check notices the floor only once the
  ball is already in it, and pushing it out lifts it without taking back the speed it gained
  falling that extra depth: every bounce adds energy, and the apexes climb (10.08, 10.31,
  10.55 m, ...). The engine's stay at 10 m.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import pygame

from demos.cli import Demo
from engine import Body, Plane, Segment, Vector, World
from engine.forces import Gravity
from engine.render import (
    EULER,
    EXACT,
    GRID,
    INK,
    MUTED,
    PAPER,
    POSITION,
    Camera,
    Plot,
    Scene,
    marks,
)
from engine.render import draw_text as _draw_text

__all__ = [
    "G",
    "H0",
    "DT",
    "DiscreteBall",
    "Drop",
    "Tunnel",
    "Drift",
    "DropScene",
    "TunnelScene",
    "DriftScene",
    "DEMO",
]

#: Gravity (m/s^2), the drop height to the ball's bottom (m) and the physics step (s).
G = 9.81
H0 = 10.0
DT = 1.0 / 60.0
#: The ball's colour: no other drawing uses it, so a test finds the ball by it.
BALL = (196, 40, 60)
#: The discrete check's colour and the engine's (a numerical answer, the exact one).
NAIVE, ENGINE = EULER, EXACT
ENERGY = (0, 114, 178)
#: The tunnel rows show x from -VIEW to VIEW (m).
VIEW = 15.5

Color = tuple[int, int, int]


def draw_text(
    surface: pygame.Surface,
    text: str,
    pos: tuple[float, float],
    size: int,
    color: Color = INK,
    anchor: str = "topleft",
) -> pygame.Rect:
    """The renderer's draw_text with the size kept legible (at least 12 px)."""
    return _draw_text(surface, text, pos, max(12, size), color, anchor)


def dashed(
    surface: pygame.Surface,
    color: Color,
    start: tuple[float, float],
    end: tuple[float, float],
    dash: int = 6,
) -> None:
    """A dashed straight line from pixel ``start`` to pixel ``end``."""
    (x0, y0), (x1, y1) = start, end
    length = math.hypot(x1 - x0, y1 - y0)
    if length < 1:
        return
    steps = int(length // dash)
    for k in range(0, steps + 1, 2):
        a, b = k * dash / length, min(1.0, (k + 1) * dash / length)
        pygame.draw.line(
            surface,
            color,
            (x0 + a * (x1 - x0), y0 + a * (y1 - y0)),
            (x0 + b * (x1 - x0), y0 + b * (y1 - y0)),
        )


def ball_world(
    h0: float, radius: float, restitution: float, start: tuple[float, float] = (0.0, 0.0)
) -> tuple[World, Body]:
    """A World ("auto": the closed form) with one ball whose bottom is at ``h0`` over a floor."""
    world = World(integrator="auto")
    ball = world.add(
        Body(
            Vector(start[0], h0 + radius),
            Vector(0.0, 0.0),
            Vector(0.0, 0.0),
            radius=radius,
            restitution=restitution,
        )
    )
    world.add_force(Gravity((0.0, -G)))
    world.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    return world, ball


class DiscreteBall:
    """The usual game loop's contact, written out: move a whole step, then test and fix.

    Between checks it moves exactly as the engine's ball does (the closed form of constant
    acceleration), so the only difference is the check: after each step, a ball that overlaps
    the floor (y < radius) or a wall (its centre within radius of the wall) is pushed out to
    the surface and its velocity into it is reflected, times e. That is "move, then test
    overlap and reflect".
    """

    def __init__(
        self,
        pos: tuple[float, float],
        vel: tuple[float, float],
        radius: float,
        restitution: float,
        gravity: float,
        floor: bool = True,
        wall: Segment | None = None,
    ) -> None:
        self.x, self.y = pos
        self.vx, self.vy = vel
        self.radius, self.e, self.g = radius, restitution, gravity
        self.floor, self.wall = floor, wall
        #: Whether a check ever found the ball overlapping the wall.
        self.hit_wall = False

    def step(self, dt: float) -> None:
        """One step: move by the closed form, then test for overlap and reflect."""
        self.x += self.vx * dt
        self.y += self.vy * dt - 0.5 * self.g * dt * dt
        self.vy -= self.g * dt
        r = self.radius
        if self.floor and self.y < r and self.vy < 0.0:
            self.y = r  # pushed out...
            self.vy = -self.e * self.vy  # ...with the speed it has now, deeper than contact
        wall = self.wall
        if wall is not None and wall.distance((self.x, self.y)) < r:
            self.hit_wall = True
            _, n, d = wall.closest((self.x, self.y))
            vn = self.vx * n.x + self.vy * n.y
            self.x += (r - d) * n.x
            self.y += (r - d) * n.y
            if vn < 0.0:
                self.vx -= (1.0 + self.e) * vn * n.x
                self.vy -= (1.0 + self.e) * vn * n.y

    def energy(self) -> float:
        """Energy per kg (J/kg) with the floor contact height as zero."""
        return self.g * (self.y - self.radius) + 0.5 * (self.vx * self.vx + self.vy * self.vy)

    def state(self) -> tuple[float, float, float, float, bool]:
        """Everything it needs to resume."""
        return self.x, self.y, self.vx, self.vy, self.hit_wall

    def set_state(self, state: tuple[float, float, float, float, bool]) -> None:
        """Bring back :meth:`state`."""
        self.x, self.y, self.vx, self.vy, self.hit_wall = state


class _Clock:
    """A Steppable's clock: t = n steps of dt (no drift)."""

    def __init__(self) -> None:
        self.n = 0
        self.dt = 0.0

    @property
    def t(self) -> float:
        """The time (s)."""
        return self.n * self.dt

    def tick(self, dt: float) -> None:
        if not (isinstance(dt, (int, float)) and 0.0 < dt < math.inf):
            raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}")
        self.dt = float(dt)
        self.n += 1


def _apex(y0: float, v0: float, v1: float, radius: float) -> float | None:
    """The top of a free flight within a step that began at (y0, v0) and ended at v1, or None.

    Under constant gravity it is y0 + v0^2 / (2 g) above the start; measured to the bottom.
    """
    if v0 > 0.0 >= v1:
        return y0 + v0 * v0 / (2.0 * G) - radius
    return None


class Drop:
    """The ``drop`` scene's physics: the engine's ball and what it has done so far.

    A Steppable: ``step(dt)`` is one step of the World, ``t`` its time. ``apexes`` lists
    (time s, height m) of each apex, measured from the engine's state: in a step whose start
    state (y0, v0 > 0) rises and ends falling with no contact, the top is y0 + v0^2 / (2 g).
    """

    radius = 0.5
    restitution = 0.8

    def __init__(self) -> None:
        self.world, self.ball = ball_world(H0, self.radius, self.restitution)
        self.samples: list[tuple[float, float, float]] = [(0.0, H0, self.energy())]
        self.apexes: list[tuple[float, float]] = []
        self.bounces: list[float] = []  # the times of impact (s)

    @property
    def t(self) -> float:
        return self.world.t

    def energy(self) -> float:
        """The ball's energy per kg (J/kg), zero at rest on the floor."""
        b = self.ball
        return G * (b.pos.y - self.radius) + 0.5 * b.vel.magnitude() ** 2

    def step(self, dt: float) -> None:
        y0, v0, t0 = self.ball.pos.y, self.ball.vel.y, self.world.t
        self.world.step(dt)
        self.bounces.extend(ev.time for ev in self.world.began)
        top = None if self.world.began else _apex(y0, v0, self.ball.vel.y, self.radius)
        if top is not None:
            self.apexes.append((t0 + v0 / G, top))
        self.samples.append((self.world.t, self.ball.pos.y - self.radius, self.energy()))

    def snapshot(self) -> tuple[Any, ...]:
        return (
            self.world.snapshot(),
            tuple(self.samples),
            tuple(self.apexes),
            tuple(self.bounces),
        )

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, samples, apexes, bounces = snapshot
        self.world.restore(world)
        self.samples, self.apexes, self.bounces = list(samples), list(apexes), list(bounces)


class Tunnel:
    """The ``tunnel`` scene's physics: a fast ball at a thin wall, the engine's and a discrete
    check's, one physics step of ``DT`` per call of ``step`` (slow motion).

    Its ``t`` is the scene's clock, the slowed time on screen; ``steps * DT`` is the physics
    time. ``engine_path`` and ``naive_path`` hold each ball's centre after every step.
    """

    speed = 200.0  # m/s
    radius = 0.1  # m
    start = -12.0  # m; the wall is at x = 0
    wall = Segment((0.0, -1.0), (0.0, 1.0))

    def __init__(self) -> None:
        self.clock = _Clock()
        self.world = World(integrator="auto")
        self.ball = self.world.add(
            Body(
                Vector(self.start, 0.0),
                Vector(self.speed, 0.0),
                Vector(0.0, 0.0),
                radius=self.radius,
                restitution=1.0,
            )
        )
        self.world.add_collider(self.wall)
        self.naive = DiscreteBall(
            (self.start, 0.0), (self.speed, 0.0), self.radius, 1.0, 0.0, False, self.wall
        )
        self.engine_path: list[tuple[float, float]] = [(self.start, 0.0)]
        self.naive_path: list[tuple[float, float]] = [(self.start, 0.0)]
        self.impacts: list[tuple[float, float, float]] = []  # (time s, x, y) of each contact

    @property
    def t(self) -> float:
        return self.clock.t

    @property
    def steps(self) -> int:
        return self.world.steps

    def step(self, dt: float) -> None:
        self.clock.tick(dt)
        self.world.step(DT)
        self.naive.step(DT)
        self.impacts.extend((ev.time, ev.point.x, ev.point.y) for ev in self.world.began)
        self.engine_path.append((self.ball.pos.x, self.ball.pos.y))
        self.naive_path.append((self.naive.x, self.naive.y))

    def snapshot(self) -> tuple[Any, ...]:
        return (
            (self.clock.n, self.clock.dt),
            self.world.snapshot(),
            self.naive.state(),
            tuple(self.engine_path),
            tuple(self.naive_path),
            tuple(self.impacts),
        )

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        (n, dt), world, naive, engine_path, naive_path, impacts = snapshot
        self.clock.n, self.clock.dt = n, dt
        self.world.restore(world)
        self.naive.set_state(naive)
        self.engine_path, self.naive_path = list(engine_path), list(naive_path)
        self.impacts = list(impacts)


class Drift:
    """The ``drift`` scene's physics: e = 1, the engine's ball beside a discrete check's.

    ``apexes[name]`` lists (time s, height m) of each apex, measured the same way for both.
    """

    radius = 0.5

    def __init__(self) -> None:
        self.world, self.ball = ball_world(H0, self.radius, 1.0, (1.0, 0.0))
        self.naive = DiscreteBall((-1.0, H0 + self.radius), (0.0, 0.0), self.radius, 1.0, G)
        e0 = G * H0
        self.samples: list[tuple[float, float, float, float, float]] = [
            (0.0, H0, H0, 1.0, 1.0)
        ]  # t, naive height, engine height, naive E / E0, engine E / E0
        self.e0 = e0
        self.apexes: dict[str, list[tuple[float, float]]] = {"naive": [], "engine": []}

    @property
    def t(self) -> float:
        return self.world.t

    def engine_energy(self) -> float:
        b = self.ball
        return G * (b.pos.y - self.radius) + 0.5 * b.vel.magnitude() ** 2

    def step(self, dt: float) -> None:
        t0 = self.world.t
        y0, v0 = self.ball.pos.y, self.ball.vel.y
        ny0, nv0 = self.naive.y, self.naive.vy
        self.world.step(dt)
        self.naive.step(dt)
        r = self.radius
        top = None if self.world.began else _apex(y0, v0, self.ball.vel.y, r)
        if top is not None:
            self.apexes["engine"].append((t0 + v0 / G, top))
        top = None if self.naive.y <= r else _apex(ny0, nv0, self.naive.vy, r)
        if top is not None:
            self.apexes["naive"].append((t0 + nv0 / G, top))
        self.samples.append(
            (
                self.world.t,
                self.naive.y - r,
                self.ball.pos.y - r,
                self.naive.energy() / self.e0,
                self.engine_energy() / self.e0,
            )
        )

    def snapshot(self) -> tuple[Any, ...]:
        return (
            self.world.snapshot(),
            self.naive.state(),
            tuple(self.samples),
            tuple(self.apexes["naive"]),
            tuple(self.apexes["engine"]),
        )

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, naive, samples, naive_apexes, engine_apexes = snapshot
        self.world.restore(world)
        self.naive.set_state(naive)
        self.samples = list(samples)
        self.apexes = {"naive": list(naive_apexes), "engine": list(engine_apexes)}


# -- drawing --------------------------------------------------------------------------------


def draw_ball(
    surface: pygame.Surface, camera: Camera, pos: tuple[float, float], radius: float, color: Color
) -> tuple[int, int]:
    """The ball at world ``pos``, at least 4 px across; returns its centre pixel."""
    centre = camera.point(pos)
    r = max(4, round(camera.length(radius)))
    pygame.draw.circle(surface, color, centre, r)
    return centre


def draw_floor(surface: pygame.Surface, camera: Camera, x0: float, x1: float) -> None:
    """The floor y = 0 from x0 to x1 (m), hatched below."""
    left, y = camera.point((x0, 0.0))
    right, _ = camera.point((x1, 0.0))
    pygame.draw.line(surface, INK, (left, y), (right, y), 2)
    for x in range(left, right, 8):
        pygame.draw.line(surface, MUTED, (x + 6, y + 1), (x, y + 7))


def _blend(samples: Sequence[tuple[float, ...]], t: float) -> list[tuple[float, ...]]:
    """The samples up to time ``t``, the last one cut at ``t`` by linear blending."""
    out = [s for s in samples if s[0] <= t]
    later = [s for s in samples if s[0] > t]
    if out and later:
        a, b = out[-1], later[0]
        f = (t - a[0]) / (b[0] - a[0])
        out.append(tuple(p + f * (q - p) for p, q in zip(a, b, strict=True)))
    return out


class DropScene(Scene):
    """The ball, its height y(t) with each apex labelled against h0 e^(2n), its energy E(t)."""

    name = "drop"
    summary = "e = 0.8 from 10 m: apexes h0 e^(2n), energy down by e^2 a bounce"
    duration = 14.0
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.25
    world: Drop

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.drop = Drop()
        w, h = size
        s = self.s = h / 360
        self.size = size
        ball_w = round(w * 0.22)
        # The ball's column: x from -2 to 2 m, y from -0.6 to 11.4 m, under a title line.
        self.camera = Camera.fit((-2.0, -0.6, 2.0, 11.4), (0, 40 * s, ball_w, h - 46 * s))
        plot_left = ball_w + round(4 * s)
        plot_w = round(w * 0.50)
        half = (h - round(8 * s)) // 2
        self.y_plot = Plot(
            (plot_left, round(4 * s), plot_w, half),
            t_max=self.duration,
            y_range=(0.0, 11.0),
            title="y(t)  m, to the ball's bottom",
            t_step=2.0,
            y_step=2.0,
            color=POSITION,
            text_scale=s,
        )
        self.e_plot = Plot(
            (plot_left, round(4 * s) + half + round(4 * s), plot_w, half - round(4 * s)),
            t_max=self.duration,
            y_range=(0.0, 110.0),
            title="E(t)  J/kg:  x e\u00b2 = 0.64 each bounce",
            t_step=2.0,
            y_step=20.0,
            color=ENERGY,
            text_scale=s,
        )
        self.table_left = plot_left + plot_w + round(8 * s)

    def step(self, dt: float) -> None:
        self.drop.step(dt)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        drop, s = self.drop, self.s
        surface.fill(PAPER)
        draw_text(surface, f"t = {t:5.2f} s", (8 * s, 6 * s), round(20 * s))
        draw_text(surface, "e = 0.8, dt = 1/60 s", (8 * s, 24 * s), round(15 * s), MUTED)
        self._column(surface)
        pos = drop.world.position_of(drop.ball, alpha)
        assert isinstance(pos, Vector)  # a 2D World
        draw_ball(surface, self.camera, (pos.x, pos.y), drop.radius, BALL)
        samples = _blend(drop.samples, t)
        self.y_plot.draw_frame(surface)
        self._formula_lines(surface, self.y_plot, H0, 1, 4)
        self.y_plot.draw_curve(surface, [p[0] for p in samples], [p[1] for p in samples])
        self.e_plot.draw_frame(surface)
        self._formula_lines(surface, self.e_plot, G * H0, 1, 3)
        self.e_plot.draw_curve(surface, [p[0] for p in samples], [p[2] for p in samples])
        apexes = [a for a in drop.apexes if a[0] <= t]
        for n, (ta, ha) in enumerate(apexes[:3], 1):
            px, py = self.y_plot.to_px(ta, ha)
            pygame.draw.circle(surface, INK, (round(float(px)), round(float(py))), 3)
            draw_text(
                surface,
                f"n={n}",
                (float(px) + 4 * s, float(py) - 2 * s),
                round(14 * s),
                INK,
                "bottomleft",
            )
        self._table(surface, apexes)

    def _column(self, surface: pygame.Surface) -> None:
        """The floor and the heights h0 e^(2n) the apexes reach, dashed."""
        cam, s = self.camera, self.s
        draw_floor(surface, cam, -2.0, 2.0)
        e2 = Drop.restitution**2
        for n in range(4):
            h = H0 * e2**n
            left = cam.point((-2.0, h))
            right = cam.point((2.0, h))
            dashed(surface, GRID if n else MUTED, left, right)
            label = "h0 = 10 m" if n == 0 else f"n={n}: {h:.2f} m"
            draw_text(
                surface, label, (right[0] - 2, right[1] - 1), round(13 * s), MUTED, "bottomright"
            )

    def _formula_lines(
        self, surface: pygame.Surface, plot: Plot, top: float, first: int, count: int
    ) -> None:
        """Dashed levels top e^(2n) for n = first .. first + count - 1 across the plot."""
        a = plot.area
        for n in range(first, first + count):
            _, py = plot.to_px(0.0, top * Drop.restitution ** (2 * n))
            dashed(surface, GRID, (a.left, float(py)), (a.right - 1, float(py)))

    def _table(self, surface: pygame.Surface, apexes: list[tuple[float, float]]) -> None:
        """Each apex so far: the measured height and h0 e^(2n), to 9 decimals."""
        s, x = self.s, self.table_left
        size = round(14 * s)
        step = round(16 * s)
        draw_text(surface, "apex n: measured", (x, 6 * s), round(16 * s), INK)
        draw_text(surface, "and h0 e^(2n), m", (x, 6 * s + step), round(16 * s), MUTED)
        y = 6 * s + 2.4 * step
        e2 = Drop.restitution**2
        for n, (_, h) in enumerate(apexes[:8], 1):
            draw_text(surface, f"{n}  {h:.9f}", (x, y), size, INK)
            draw_text(surface, f"   {H0 * e2**n:.9f}", (x, y + step * 0.85), size, MUTED)
            y += step * 2
        if apexes:
            n = min(len(apexes), 8)
            worst = max(abs(h / (H0 * e2**k) - 1.0) for k, (_, h) in enumerate(apexes[:n], 1))
            draw_text(surface, f"worst: {worst:.0e} relative", (x, y), size, POSITION)

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The ball at each of ``times`` up to 4 s (the first two bounces), placed left to right
        by its time and labelled with it: a motion diagram along t, older images fainter, over
        the heights h0 e^(2n) it reaches, named in a column of their own on the left."""
        self.build(surface.get_size())
        shown = [t for t in times if t <= 4.0 + 1e-9]
        w, h = surface.get_size()
        s = self.s
        surface.fill(PAPER)
        step = shown[1] - shown[0] if len(shown) > 1 else 0.0
        draw_text(
            surface,
            f"The ball every {step:g} s to {shown[-1]:g} s, placed left to right by its time",
            (8 * s, 6 * s),
            round(18 * s),
        )
        draw_text(
            surface,
            "dashed: the heights h0 e^(2n) of the apexes, measured to the ball's bottom",
            (8 * s, 25 * s),
            round(13 * s),
            MUTED,
        )
        # Heights: the floor to 12.2 m (room above the first ball for its time); times: from
        # the names' column to the right edge, a ball's width kept clear at each end.
        names_w, label = round(88 * s), round(12 * s)
        top, bottom = 36 * s, h - 20 * s  # pixel rows of 12.2 m and of -0.6 m
        scale = (bottom - top) / 12.8
        cam = Camera(scale, (0.0, top + 12.2 * scale))  # y only: x goes by time below
        r = max(4, round(cam.length(Drop.radius)))
        x0, x1 = names_w + r + 2, w - round(8 * s) - r

        def at(t: float, y: float) -> tuple[int, int]:
            span = (shown[-1] - shown[0]) or 1.0
            return round(x0 + (x1 - x0) * (t - shown[0]) / span), round(cam.to_px(0.0, y)[1])

        floor_y = at(0.0, 0.0)[1]
        pygame.draw.line(surface, INK, (names_w, floor_y), (w - round(8 * s), floor_y), 2)
        for x in range(names_w, w - round(8 * s), 8):
            pygame.draw.line(surface, MUTED, (x + 6, floor_y + 1), (x, floor_y + 7))
        e2 = Drop.restitution**2
        for n in range(4):
            level = H0 * e2**n
            y = at(0.0, level)[1]
            dashed(surface, GRID if n else MUTED, (names_w, y), (w - round(8 * s), y))
            name = "h0 = 10 m" if n == 0 else f"n={n}: {level:.2f} m"
            draw_text(surface, name, (names_w - 4 * s, y), round(13 * s), MUTED, "midright")
        for k, t in enumerate(shown):
            while self.drop.t < t - 1e-9:
                self.drop.step(self.dt)
            fade = 0.25 + 0.75 * (k + 1) / len(shown)
            colour: Color = (
                round(255 - (255 - BALL[0]) * fade),
                round(255 - (255 - BALL[1]) * fade),
                round(255 - (255 - BALL[2]) * fade),
            )
            cx, cy = at(t, self.drop.ball.pos.y)
            pygame.draw.circle(surface, colour, (cx, cy), r)
            marks.note(surface, "marker", pygame.Rect(cx - r, cy - r, 2 * r + 1, 2 * r + 1))
            draw_text(surface, f"{t:g}", (cx, cy - r - 1), label, INK, "midbottom")
        draw_text(surface, "t (s)", (w - 8 * s, floor_y + 3 * s), round(13 * s), MUTED, "topright")


class TunnelScene(Scene):
    """A ball at 200 m/s against a thin wall: the discrete check passes it, the engine does not."""

    name = "tunnel"
    summary = "200 m/s at a thin wall, in slow motion: the discrete check passes through"
    #: Scene seconds per physics step of 1/60 s: slow motion, 24 times slower.
    dt = 0.4
    duration = 3.2
    min_size = (480, 270)
    strobe_interval = 0.4
    world: Tunnel

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.tunnel = Tunnel()
        w, h = size
        s = self.s = h / 360
        self.size = size
        # Two rows, each showing x from -VIEW to VIEW m: the engine above, the discrete check below.
        self.rows = [
            (Camera.fit((-VIEW, -1.6, VIEW, 1.6), (0, 70 * s, w, 110 * s)), "engine"),
            (Camera.fit((-VIEW, -1.6, VIEW, 1.6), (0, 215 * s, w, 110 * s)), "naive"),
        ]

    @property
    def cameras(self) -> dict[str, Camera]:
        return {name: cam for cam, name in self.rows}

    def step(self, dt: float) -> None:
        self.tunnel.step(dt)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        tun, s = self.tunnel, self.s
        surface.fill(PAPER)
        # The steps taken by the time shown (the world runs one step ahead of the frame).
        shown = min(tun.steps, math.floor(self.time(alpha) / self.dt + 1e-9))
        ms = shown * DT * 1000.0
        draw_text(
            surface,
            f"200 m/s at a wall of zero thickness, dt = 1/60 s: step {shown}, t = {ms:5.1f} ms",
            (8 * s, 6 * s),
            round(20 * s),
        )
        draw_text(
            surface,
            "slow motion: one step every 0.4 s; dots: where each loop has the ball after each step",
            (8 * s, 30 * s),
            round(15 * s),
            MUTED,
        )
        for cam, which in self.rows:
            self._row(surface, cam, which, shown + 1)

    def _row(self, surface: pygame.Surface, cam: Camera, which: str, count: int) -> None:
        tun, s = self.tunnel, self.s
        path = (tun.engine_path if which == "engine" else tun.naive_path)[:count]
        colour = ENGINE if which == "engine" else NAIVE
        top = cam.point((-VIEW, 1.6))[1]
        # The wall, and a ruler line through the path.
        a, b = cam.point(tuple(tun.wall.a)), cam.point(tuple(tun.wall.b))
        pygame.draw.line(surface, GRID, cam.point((-VIEW, 0.0)), cam.point((VIEW, 0.0)), 1)
        pygame.draw.line(surface, INK, a, b, 3)
        draw_text(surface, "wall", (a[0] + 4 * s, a[1]), round(14 * s), INK, "bottomleft")
        for k, p in enumerate(path[:-1]):
            c = cam.point(p)
            pygame.draw.circle(surface, colour, c, max(3, round(4 * s)), 2)
            draw_text(surface, str(k), (c[0], c[1] + 6 * s), round(12 * s), MUTED, "midtop")
        if which == "engine":
            title = "this engine: sweeps each step's path, finds the moment of impact, bounces"
            for _, x, y in [i for i in tun.impacts if i[0] <= (count - 1) * DT + 1e-12]:
                px = cam.point((x, y))
                pygame.draw.line(
                    surface, ENGINE, (px[0], px[1] - 14 * s), (px[0], px[1] + 14 * s), 2
                )
                draw_text(
                    surface,
                    f"hit at {tun.impacts[0][0] * 1000:.1f} ms",
                    (px[0] - 4 * s, px[1] - 16 * s),
                    round(14 * s),
                    ENGINE,
                    "bottomright",
                )
        else:
            title = "discrete check: move a step, then test overlap; no step overlaps the wall"
            if path and path[-1][0] > 0.0 and not tun.naive.hit_wall:
                draw_text(
                    surface,
                    "passed straight through",
                    (cam.point((8.0, 0.0))[0], cam.point((0.0, -0.8))[1]),
                    round(16 * s),
                    NAIVE,
                    "midtop",
                )
        draw_text(surface, title, (8 * s, top - 4 * s), round(16 * s), colour, "topleft")
        if path:
            draw_ball(surface, cam, path[-1], tun.radius, BALL)

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """Every step at once: both loops' positions, numbered."""
        self.build(surface.get_size())
        while self.tunnel.t < max(times) - 1e-9:
            self.tunnel.step(self.dt)
        self.draw(surface, 1.0)  # the last time's state: every step before it as a dot


class DriftScene(Scene):
    """e = 1: the discrete check's apexes climb (late detection gains energy); the engine's stay."""

    name = "drift"
    summary = "e = 1 from 10 m: the discrete check's apexes climb, the engine's stay at h0"
    duration = 15.0
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.5
    world: Drift
    #: The most apexes the table above the balls lists.
    APEX_ROWS = 6

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.drift = Drift()
        w, h = size
        s = self.s = h / 360
        self.size = size
        col = self.column = round(w * 0.34)
        # Above the balls, a table of every apex so far, numbered (as many rows as the
        # scene's apexes, up to APEX_ROWS; past that, the latest).
        period = 2.0 * math.sqrt(2.0 * H0 / G)
        self.apex_rows = max(1, min(self.APEX_ROWS, int(self.duration / period)))
        self.table_top = 42 * s
        top = self.table_top + (self.apex_rows + 0.5) * 14 * s
        self.camera = Camera.fit((-2.2, -0.6, 2.2, 12.0), (0, top, col, h - top - 6 * s))
        plot_left = col + round(6 * s)
        plot_w = w - plot_left - round(4 * s)
        half = (h - round(8 * s)) // 2
        self.y_plot = Plot(
            (plot_left, round(4 * s), plot_w, half),
            t_max=self.duration,
            y_range=(0.0, 12.0),
            title="y(t)  m",
            t_step=2.0,
            y_step=2.0,
            color=ENGINE,
            text_scale=s,
        )
        self.e_plot = Plot(
            (plot_left, round(4 * s) + half + round(4 * s), plot_w, half - round(4 * s)),
            t_max=self.duration,
            y_range=(0.95, 1.2),
            title="E(t) / E0",
            t_step=2.0,
            y_step=0.05,
            color=ENGINE,
            text_scale=s,
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        d, s, cam = self.drift, self.s, self.camera
        surface.fill(PAPER)
        draw_text(surface, f"e = 1, dt = 1/60 s, t = {t:5.2f} s", (8 * s, 6 * s), round(18 * s))
        draw_floor(surface, cam, -2.2, 2.2)
        top_l, top_r = cam.point((-2.2, H0)), cam.point((2.2, H0))
        dashed(surface, MUTED, top_l, top_r)
        draw_text(surface, "h0", (top_r[0] - 2, top_r[1] - 1), round(13 * s), MUTED, "bottomright")
        samples = _blend(d.samples, t)
        last = samples[-1]
        # The discrete ball on the left, the engine's on the right (blended like the plots).
        draw_ball(surface, cam, (-1.0, last[1] + d.radius), d.radius, NAIVE)
        pos = d.world.position_of(d.ball, alpha)
        assert isinstance(pos, Vector)  # a 2D World
        draw_ball(surface, cam, (pos.x, pos.y), d.radius, ENGINE)
        # Every apex so far, numbered: the discrete check's climb against the engine's 10 m.
        tops = {name: [h for ta, h in d.apexes[name] if ta <= t] for name in d.apexes}
        count = max(len(v) for v in tops.values())
        first = max(0, count - self.apex_rows)
        col = self.column
        draw_text(surface, "apex", (col * 0.12, 26 * s), round(15 * s), INK, "midtop")
        for k in range(first, count):
            y = self.table_top + (k - first) * 14 * s
            draw_text(surface, f"{k + 1}", (col * 0.12, y), round(14 * s), INK, "midtop")
        for x, name, colour, label in (
            (0.45, "naive", NAIVE, "discrete"),
            (0.8, "engine", ENGINE, "engine"),
        ):
            draw_text(surface, label, (col * x, 26 * s), round(15 * s), colour, "midtop")
            for k in range(first, min(count, len(tops[name]))):
                y = self.table_top + (k - first) * 14 * s
                text = f"{tops[name][k]:.3f} m"
                draw_text(surface, text, (col * x, y), round(14 * s), colour, "midtop")
        ts = [p[0] for p in samples]
        self.y_plot.draw_frame(surface)
        _, py = self.y_plot.to_px(0.0, H0)
        a = self.y_plot.area
        dashed(surface, MUTED, (a.left, float(py)), (a.right - 1, float(py)))
        self.y_plot.draw_curve(surface, ts, [p[1] for p in samples], color=NAIVE)
        self.y_plot.draw_curve(surface, ts, [p[2] for p in samples], color=ENGINE)
        self.e_plot.draw_frame(surface)
        self.e_plot.draw_curve(surface, ts, [p[3] for p in samples], color=NAIVE)
        self.e_plot.draw_curve(surface, ts, [p[4] for p in samples], color=ENGINE)
        a = self.e_plot.area
        draw_text(
            surface,
            f"discrete {last[3]:.4f}   engine {last[4]:.4f}",
            (a.right - 4 * s, a.top + 2 * s),
            round(14 * s),
            INK,
            "topright",
        )


DEMO = Demo(
    name="bounce",
    summary="A ball bouncing on a floor, exact at every impact, against a discrete check",
    scenes={"drop": DropScene, "tunnel": TunnelScene, "drift": DriftScene},
)
