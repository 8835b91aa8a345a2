"""Pendulums on rods: one swinging wide, a double pendulum's chaos, a chain hanging from a pin.

    python -m demos pendulum                  # frames: out/pendulum/single/, double/, chain/
    python -m demos pendulum --scene double --window
    python -m demos pendulum --strobe         # one motion diagram per scene

Every bob is a point Body of 1 kg under gravity g = 9.81 m/s^2, held by ``Rod`` links
(``engine.dynamics.links``), in a World with ``integrator="auto"``: gravity alone folds to the
closed form ("exact") for the free step, and the rods are solved as RATTLE, at dt = 1/240 s.

* ``single``: one bob on a rod of L = 1 m from a fixed point, let go from rest at
  theta0 = 120 degrees. Beside it theta(t) in degrees, with the exact period marked,
  T = 4 sqrt(L / g) K(sin(theta0 / 2)) = 2.7546 s (K the complete elliptic integral of the
  first kind, by the arithmetic-geometric mean: ``demos.bench.pendulum.period``), far from the
  small-angle 2 pi sqrt(L / g) = 2.006 s; and the energies in J (kinetic, potential with
  y = 0 at the pivot, and their sum, which stays at m g L cos(60 deg) = 4.905 J). The period
  measured from the run (between crossings of the bottom, the same way) is 3.0e-5 of T short
  (2.75401 s); the energy stays within 1.2e-4 m g L of its start.
* ``double``: two double pendulums (rods of 1 m, bobs of 1 kg) let go from rest at
  theta1 = 120, theta2 = 150 degrees, drawn over each other in two colours; the orange copy
  starts 1e-9 rad further round at the top joint. The larger of the two angle differences is
  plotted on a log scale: it grows by seven decades from 2 s to 12 s (about fivefold a
  second: the motion is chaotic) until, after about 14 s, the two copies swing apart. Each
  copy is its own World, so each is exactly what it would be alone. Their energies are
  plotted too: each stays within 5.4e-3 m g L of its start over the 20 s (RATTLE's error,
  O(dt^2): short dips at the fastest whips, no drift).
* ``chain``: six bobs on rods of 0.3 m, the first hanging from a pinned body (``Pin``) at the
  origin, let go from rest stretched out level to the right: it falls and whips. Beside it
  the tension in the top rod (N, from ``link.tension(dt)``: about 1,280 N for one step at
  the whip, and briefly -156 N, a push), and every rod's length now; the largest length error
  over the 6 s is 1.0e-12 of a rod, the solver's tolerance (``engine.dynamics.links.TOLERANCE``).

Lengths in m, times in s, angles measured from straight down, counterclockwise positive.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import pygame

from demos.bench.pendulum import period
from demos.bounce import dashed, draw_text  # the legible text and dashes of the bounce lesson
from demos.cli import Demo
from demos.cradle import faded  # colours mixed toward white, as the cradle's strobe fades
from demos.stability import fitting
from engine import Body, Pin, Rod, Vector, World
from engine.forces import Gravity
from engine.render import GRID, INK, MUTED, PAPER, Camera, Plot, Scene, marks

__all__ = [
    "G",
    "DT",
    "LENGTH",
    "THETA0",
    "DOUBLE_START",
    "NUDGE",
    "LINKS",
    "LINK_LENGTH",
    "BOB",
    "COPY_A",
    "COPY_B",
    "CHAIN",
    "Single",
    "Double",
    "Chain",
    "SingleScene",
    "DoubleScene",
    "ChainScene",
    "angle_of",
    "DEMO",
]

#: Gravity (m/s^2) and the physics step (s).
G = 9.81
DT = 1.0 / 240.0
#: The single pendulum: its rod (m) and the angle it is let go from (rad).
LENGTH = 1.0
THETA0 = math.radians(120.0)
#: The double pendulum's start (rad, from straight down: top rod, bottom rod) and the change
#: of the second copy's top angle (rad).
DOUBLE_START = (math.radians(120.0), math.radians(150.0))
NUDGE = 1e-9
#: The chain: how many rods and each one's length (m).
LINKS = 6
LINK_LENGTH = 0.3
#: Colours no other drawing uses, so a test finds each bob by its colour (Okabe-Ito).
BOB = (0, 114, 178)  # blue: the single pendulum, the double's first copy
COPY_A = BOB
COPY_B = (213, 94, 0)  # vermillion: the double's second copy
CHAIN = (0, 158, 115)  # bluish green
ROD = (60, 60, 70)
KINETIC, POTENTIAL, TOTAL = (230, 159, 0), (86, 180, 233), (150, 60, 40)
TENSION = (204, 121, 167)

Color = tuple[int, int, int]


def angle_of(pos: Vector, pivot: Vector) -> float:
    """The angle (rad, -pi to pi) of the rod from ``pivot`` to ``pos``, from straight down,
    counterclockwise: theta with pos = pivot + L (sin theta, -cos theta)."""
    d = pos - pivot
    return math.atan2(d.x, -d.y)


def _bob(world: World, pos: Vector) -> Body:
    return world.add(Body(pos, Vector(0.0, 0.0), Vector(0.0, 0.0), mass=1.0))


def _world() -> World:
    world = World(integrator="auto")  # gravity and rods alone: the closed form, and RATTLE
    world.add_force(Gravity((0.0, -G)))
    return world


def _energy(bodies: Sequence[Body]) -> tuple[float, float]:
    """Kinetic and potential energy (J) of ``bodies``, y = 0 at the pivot: sum m v^2 / 2 and
    sum m g y."""
    ke = pe = 0.0
    for b in bodies:
        v = b.vel
        ke += 0.5 * b.mass * (v.x * v.x + v.y * v.y)
        pe += b.mass * G * b.pos.y
    return ke, pe


class SingleSample(NamedTuple):
    """The single pendulum at one moment: time (s), angle (deg), kinetic and potential
    energy (J)."""

    t: float
    theta: float
    kinetic: float
    potential: float


class Single:
    """One bob on a rod of ``length`` m from the origin, let go from rest at ``theta0`` rad.

    A Steppable. ``history`` holds a sample at the start and after every step; ``crossings``
    the times (s) the bob passed the bottom moving the way it first does (theta falling from
    theta0 > 0 through 0), each found by linear interpolation within its step, so that
    consecutive ones are one period apart.
    """

    def __init__(self, theta0: float = THETA0, length: float = LENGTH) -> None:
        self.theta0, self.length = theta0, length
        self.world = _world()
        self.bob = _bob(self.world, Vector(length * math.sin(theta0), -length * math.cos(theta0)))
        self.rod = self.world.add_link(Rod(self.bob, (0.0, 0.0)))
        self.history: list[SingleSample] = [self.sample()]
        self.crossings: list[float] = []

    @property
    def t(self) -> float:
        return self.world.t

    def sample(self) -> SingleSample:
        ke, pe = _energy([self.bob])
        theta = angle_of(self.bob.pos, Vector(0.0, 0.0))
        return SingleSample(self.world.t, math.degrees(theta), ke, pe)

    def step(self, dt: float) -> None:
        x0, t0 = self.bob.pos.x, self.world.t
        self.world.step(dt)
        x1 = self.bob.pos.x
        # theta0 > 0 starts the bob right of the pivot; it crosses x = 0 leftward (x from
        # > 0 to <= 0) once a period, below the pivot. The crossing within the step, by
        # linear interpolation: x0 + (x1 - x0) f = 0 at f = x0 / (x0 - x1).
        if x0 > 0.0 >= x1 and self.bob.pos.y < 0.0:
            self.crossings.append(t0 + (self.world.t - t0) * x0 / (x0 - x1))
        self.history.append(self.sample())

    def measured_period(self) -> float | None:
        """The mean period (s) between the first and last crossing, or None before two."""
        c = self.crossings
        return (c[-1] - c[0]) / (len(c) - 1) if len(c) >= 2 else None

    def snapshot(self) -> tuple[Any, ...]:
        return self.world.snapshot(), tuple(self.history), tuple(self.crossings)

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, history, crossings = snapshot
        self.world.restore(world)
        self.history, self.crossings = list(history), list(crossings)


class DoubleCopy:
    """One double pendulum in a World of its own: rods of ``length`` m from the origin to bob
    1 and from bob 1 to bob 2, let go from rest at ``angles`` (rad, each rod's from down)."""

    def __init__(self, angles: tuple[float, float], length: float = LENGTH) -> None:
        t1, t2 = angles
        self.world = _world()
        p1 = Vector(length * math.sin(t1), -length * math.cos(t1))
        p2 = p1 + Vector(length * math.sin(t2), -length * math.cos(t2))
        self.bobs = [_bob(self.world, p1), _bob(self.world, p2)]
        self.rods = [
            self.world.add_link(Rod(self.bobs[0], (0.0, 0.0))),
            self.world.add_link(Rod(self.bobs[1], self.bobs[0])),
        ]

    def angles(self) -> tuple[float, float]:
        """Each rod's angle (rad) from straight down."""
        a, b = self.bobs
        return angle_of(a.pos, Vector(0.0, 0.0)), angle_of(b.pos, a.pos)

    def energy(self) -> float:
        """Kinetic plus potential energy (J), y = 0 at the pivot."""
        ke, pe = _energy(self.bobs)
        return ke + pe


class DoubleSample(NamedTuple):
    """The two copies at one moment: time (s), the larger angle difference (rad) and each
    copy's energy (J)."""

    t: float
    difference: float
    energy_a: float
    energy_b: float


class Double:
    """Two double pendulums, the second started NUDGE rad further round at the top; a Steppable."""

    def __init__(self, start: tuple[float, float] = DOUBLE_START, nudge: float = NUDGE) -> None:
        self.a = DoubleCopy(start)
        self.b = DoubleCopy((start[0] + nudge, start[1]))
        self.history: list[DoubleSample] = [self.sample()]
        #: The outer bobs' paths (m), one point a step.
        self.paths: tuple[list[tuple[float, float]], list[tuple[float, float]]] = ([], [])
        self._trace()

    @property
    def t(self) -> float:
        return self.a.world.t

    def difference(self) -> float:
        """The larger of the two rods' angle differences (rad), each taken round the circle
        (-pi to pi), so a difference of one whole turn counts as none."""
        return max(
            abs(math.remainder(p - q, 2.0 * math.pi))
            for p, q in zip(self.a.angles(), self.b.angles(), strict=True)
        )

    def sample(self) -> DoubleSample:
        return DoubleSample(self.t, self.difference(), self.a.energy(), self.b.energy())

    def _trace(self) -> None:
        for copy, path in zip((self.a, self.b), self.paths, strict=True):
            p = copy.bobs[1].pos
            path.append((p.x, p.y))

    def step(self, dt: float) -> None:
        self.a.world.step(dt)
        self.b.world.step(dt)
        self._trace()
        self.history.append(self.sample())

    def snapshot(self) -> tuple[Any, ...]:
        return (
            self.a.world.snapshot(),
            self.b.world.snapshot(),
            tuple(self.history),
            tuple(self.paths[0]),
            tuple(self.paths[1]),
        )

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        a, b, history, path_a, path_b = snapshot
        self.a.world.restore(a)
        self.b.world.restore(b)
        self.history = list(history)
        self.paths = (list(path_a), list(path_b))


class ChainSample(NamedTuple):
    """The chain at one moment: time (s), the top rod's tension (N) over the last step and
    the largest relative length error of any rod now."""

    t: float
    tension: float
    length_error: float


class Chain:
    """LINKS bobs on rods of ``link`` m, the first hanging from a body pinned at the origin;
    let go from rest stretched out level to the right. A Steppable."""

    def __init__(self, links: int = LINKS, link: float = LINK_LENGTH) -> None:
        self.world = _world()
        self.anchor = _bob(self.world, Vector(0.0, 0.0))
        self.world.add_link(Pin(self.anchor, (0.0, 0.0)))
        self.bobs = [_bob(self.world, Vector(link * (k + 1), 0.0)) for k in range(links)]
        ends = [self.anchor, *self.bobs]
        self.rods = [self.world.add_link(Rod(ends[k + 1], ends[k], link)) for k in range(links)]
        self.dt = 0.0
        self.history: list[ChainSample] = [self.sample()]

    @property
    def t(self) -> float:
        return self.world.t

    def length_error(self) -> float:
        """The largest |distance between a rod's ends - its length| / its length, now."""
        worst = 0.0
        for rod in self.rods:
            other = rod.other
            end = other.pos if isinstance(other, Body) else other
            worst = max(worst, abs((rod.body.pos - end).length() - rod.length) / rod.length)
        return worst

    def sample(self) -> ChainSample:
        tension = self.rods[0].tension(self.dt) if self.dt > 0.0 else 0.0
        return ChainSample(self.world.t, tension, self.length_error())

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


# -- drawing --------------------------------------------------------------------------------


class PendulumScene(Scene):
    """What the three scenes share: the layout (the motion left, plots right) and the title."""

    name = "pendulum"
    title = ""
    dt = DT
    min_size = (480, 270)
    #: The motion's view (m): left, bottom, right, top.
    view = (-1.25, -1.25, 1.25, 1.25)

    def layout(self, size: tuple[int, int]) -> None:
        w, h = size
        s = self.s = h / 360
        self.size = size
        m = self.margin = round(8 * s)
        left_w = round(w * 0.42)
        top = round(50 * s)
        self.camera = Camera.fit(self.view, (m, top, left_w - m, h - top - m))
        self.plot_left = left_w + round(6 * s)
        self.plot_w = w - self.plot_left - m
        self.half = (h - round(6 * s)) // 2

    def plot(self, row: int, y_range: tuple[float, float], title: str, **kw: Any) -> Plot:
        """The top (row 0) or bottom (row 1) plot panel on the right."""
        s, half = self.s, self.half
        top = round(4 * s) + row * (half + round(2 * s))
        return Plot(
            (self.plot_left, top, self.plot_w, half - round(2 * s)),
            t_max=self.duration,
            y_range=y_range,
            title=title,
            text_scale=s,
            **kw,
        )

    #: Shorter titles, for a narrow left column (the first that fits is shown).
    short_titles: tuple[str, ...] = ()

    def header(self, surface: pygame.Surface, t: float, line: str) -> None:
        s, m = self.s, self.margin
        size = max(12, round(18 * s))
        title = fitting([self.title, *self.short_titles], size, self.plot_left - m - 4 * s)
        draw_text(surface, title, (m, 4 * s), round(18 * s))
        draw_text(surface, f"t = {t:5.2f} s   {line}", (m, 25 * s), round(14 * s), MUTED)

    def pivot(self, surface: pygame.Surface, at: tuple[float, float] = (0.0, 0.0)) -> None:
        """The fixed point: a short hatched bar with the pivot under it."""
        s = self.s
        x, y = self.camera.point(at)
        half = round(16 * s)
        pygame.draw.line(surface, ROD, (x - half, y), (x + half, y), max(2, round(2 * s)))
        for k in range(-half, half, max(4, round(6 * s))):
            pygame.draw.line(
                surface, GRID, (x + k, y - 1), (x + k + round(5 * s), y - round(6 * s))
            )
        pygame.draw.circle(surface, ROD, (x, y), max(3, round(3 * s)))

    def rod(self, surface: pygame.Surface, a: tuple[float, float], b: tuple[float, float]) -> None:
        pygame.draw.line(
            surface, ROD, self.camera.point(a), self.camera.point(b), max(2, round(2 * self.s))
        )

    def bob(
        self, surface: pygame.Surface, at: tuple[float, float], colour: Color, radius: float = 0.07
    ) -> None:
        r = max(4, round(self.camera.length(radius)))
        pygame.draw.circle(surface, colour, self.camera.point(at), r)


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


class SingleScene(PendulumScene):
    """One wide swing: theta(t) with the exact period marked, and the energies."""

    name = "single"
    title = "A pendulum on a rod: L = 1 m, let go at 120\u00b0"
    short_titles = ("Pendulum: L = 1 m, from 120\u00b0",)
    summary = "one bob let go at 120 deg: theta(t) against the exact period, energy kept"
    duration = 10.0
    strobe_interval = 0.1
    world: Single

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.single = Single()
        self.layout(size)
        self.exact = period(THETA0)
        self.theta_plot = self.plot(
            0, (-160.0, 220.0), "\u03b8(t)  degrees", t_step=2.0, y_step=60.0, color=BOB
        )
        # Room above KE's peaks (m g L (1 - cos 120 deg) = 14.7 J) for the total's read-out,
        # and under PE's troughs (-m g L = -9.8 J) for the names of the curves.
        self.energy_plot = self.plot(
            1, (-15.0, 24.0), "energy  J", t_step=2.0, y_step=6.0, color=TOTAL
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        single, s = self.single, self.s
        surface.fill(PAPER)
        measured = single.measured_period()
        line = "measured T = " + ("..." if measured is None else f"{measured:.5f} s")
        self.header(surface, t, line)
        self.pivot(surface)
        pos = single.world.position_of(single.bob, alpha)
        assert isinstance(pos, Vector)  # a 2D World
        self.rod(surface, (0.0, 0.0), (pos.x, pos.y))
        self.bob(surface, (pos.x, pos.y), BOB)
        samples = _every(_upto(single.history, t, self.dt))
        ts = [p.t for p in samples]
        plot = self.theta_plot
        plot.draw_frame(surface)
        a = plot.area
        small_angle = 2 * math.pi * math.sqrt(LENGTH / G)
        captions = [
            f"dashed: T = 4 sqrt(L/g) K(sin(\u03b80/2)) = {self.exact:.4f} s  "
            f"(small-angle: {small_angle:.3f} s)",
            f"dashed: T = {self.exact:.4f} s exactly  (small-angle: {small_angle:.3f} s)",
            f"dashed: T = {self.exact:.4f} s",
        ]
        size = max(12, round(13 * s))  # (bounce's draw_text keeps text at least 12 px)
        caption = draw_text(
            surface,
            fitting(captions, size, a.width - 8 * s),
            (a.left + 3 * s, a.top + 2 * s),
            round(13 * s),
            INK,
        )
        # The exact period: a dashed line at every whole period, where theta is back at theta0,
        # from under the caption down.
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
        plot.draw_curve(surface, ts, [p.theta for p in samples])
        plot = self.energy_plot
        plot.draw_frame(surface)
        for values, colour in (
            ([p.kinetic for p in samples], KINETIC),
            ([p.potential for p in samples], POTENTIAL),
            ([p.kinetic + p.potential for p in samples], TOTAL),
        ):
            plot.draw_curve(surface, ts, values, color=colour)
        now, first = samples[-1], single.history[0]
        change = now.kinetic + now.potential - first.kinetic - first.potential
        a = plot.area
        draw_text(
            surface,
            f"E = KE + PE = {now.kinetic + now.potential:.6f} J  ({change:+.1e})",
            (a.right - 4 * s, a.top + 2 * s),
            round(13 * s),
            TOTAL,
            "topright",
        )
        draw_text(
            surface, "KE", (a.left + 4 * s, a.bottom - 2 * s), round(13 * s), KINETIC, "bottomleft"
        )
        draw_text(
            surface,
            "PE (y = 0 at the pivot)",
            (a.left + 28 * s, a.bottom - 2 * s),
            round(13 * s),
            POTENTIAL,
            "bottomleft",
        )

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The bob every strobe_interval over one period, older images fainter."""
        self.build(surface.get_size())
        shown = [t for t in times if t <= self.exact + 1e-9]
        surface.fill(PAPER)
        s, m = self.s, self.margin
        draw_text(
            surface,
            f"single: the bob every {self.strobe_interval:g} s over one period "
            f"(T = {self.exact:.4f} s); spacing = speed",
            (m, 4 * s),
            round(18 * s),
        )
        self.camera = Camera.fit(
            self.view, (m, round(30 * s), self.size[0] - 2 * m, self.size[1] - round(36 * s))
        )
        self.pivot(surface)
        for k, t in enumerate(shown):
            while self.single.t < t - 1e-9:
                self.single.step(self.dt)
            p = self.single.bob.pos
            fade = 0.25 + 0.75 * (k + 1) / len(shown)
            pygame.draw.line(
                surface, faded(ROD, fade * 0.5), self.camera.point((0.0, 0.0)),
                self.camera.point((p.x, p.y)), 1,
            )  # fmt: skip
            self.bob(surface, (p.x, p.y), faded(BOB, fade), 0.05)


class DoubleScene(PendulumScene):
    """Two double pendulums 1e-9 rad apart: the difference on a log scale, and the energies."""

    name = "double"
    title = "Double pendulum: two copies 1e-9 rad apart"
    short_titles = ("Two double pendulums 1e-9 apart", "Two double pendulums")
    summary = "chaos: two double pendulums 1e-9 rad apart, the difference growing on a log plot"
    duration = 20.0
    strobe_interval = 0.05
    view = (-2.2, -2.2, 2.2, 2.2)
    world: Double

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.double = Double()
        self.layout(size)
        self.diff_plot = self.plot(
            0,
            (-10.0, 1.0),
            "log10 of the angle difference (rad)",
            t_step=4.0,
            y_step=2.0,
            color=INK,
        )
        e0 = self.double.history[0].energy_a
        self.e0 = e0
        self.energy_plot = self.plot(
            1, (e0 - 0.25, e0 + 0.25), "energy of each copy  J", t_step=4.0, y_step=0.1
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        d, s = self.double, self.s
        surface.fill(PAPER)
        samples = _every(_upto(d.history, t, self.dt))
        now = samples[-1]
        self.header(surface, t, f"difference now: {now.difference:.1e} rad")
        self.pivot(surface)
        shown = len(_upto(d.history, t, self.dt))
        trail = round(1.5 / self.dt)  # the outer bobs' last 1.5 s
        for path, colour in ((d.paths[0], COPY_A), (d.paths[1], COPY_B)):
            points = path[max(0, shown - trail) : shown]
            if len(points) >= 2:
                pygame.draw.lines(
                    surface, faded(colour, 0.35), False, [self.camera.point(p) for p in points], 2
                )
        for copy, colour in ((d.a, COPY_A), (d.b, COPY_B)):
            p1 = copy.world.position_of(copy.bobs[0], alpha)
            p2 = copy.world.position_of(copy.bobs[1], alpha)
            assert isinstance(p1, Vector) and isinstance(p2, Vector)
            self.rod(surface, (0.0, 0.0), (p1.x, p1.y))
            self.rod(surface, (p1.x, p1.y), (p2.x, p2.y))
            self.bob(surface, (p1.x, p1.y), colour, 0.08)
            self.bob(surface, (p2.x, p2.y), colour, 0.08)
        ts = [p.t for p in samples]
        plot = self.diff_plot
        plot.draw_frame(surface)
        # log10 of the difference; the start's 1e-9 exactly, and the floor at 1e-10.
        logs = [math.log10(max(p.difference, 1e-10)) for p in samples]
        plot.draw_curve(surface, ts, logs)
        a = plot.area
        draw_text(
            surface,
            "the larger of the two rods' |\u0394\u03b8|",
            (a.right - 4 * s, a.bottom - 2 * s),
            round(13 * s),
            MUTED,
            "bottomright",
        )
        plot = self.energy_plot
        plot.draw_frame(surface)
        plot.draw_curve(surface, ts, [p.energy_a for p in samples], color=COPY_A)
        plot.draw_curve(surface, ts, [p.energy_b for p in samples], color=COPY_B)
        a = plot.area
        for row, (value, colour) in enumerate(((now.energy_a, COPY_A), (now.energy_b, COPY_B))):
            draw_text(
                surface,
                f"E - E0 = {value - self.e0:+.4f} J",
                (a.right - 4 * s, a.top + 2 * s + row * 14 * s),
                round(13 * s),
                colour,
                "topright",
            )

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """Both copies' outer bobs every strobe_interval, as dots: together, then apart."""
        self.build(surface.get_size())
        surface.fill(PAPER)
        s, m = self.s, self.margin
        w, h = self.size
        draw_text(
            surface,
            f"double: the outer bobs every {self.strobe_interval:g} s for "
            f"{self.duration:g} s, later ones darker; orange on top (alone: together)",
            (m, 4 * s),
            round(18 * s),
        )
        self.camera = Camera.fit(self.view, (m, round(30 * s), w - 2 * m, h - round(36 * s)))
        self.pivot(surface)
        d = self.double
        for k, t in enumerate(times):
            while d.t < t - 1e-9:
                d.step(self.dt)
            fade = 0.2 + 0.8 * (k + 1) / len(times)
            for copy, colour in ((d.a, COPY_A), (d.b, COPY_B)):
                p = copy.bobs[1].pos
                pygame.draw.circle(
                    surface,
                    faded(colour, fade),
                    self.camera.point((p.x, p.y)),
                    max(2, round(2 * s)),
                )


class ChainScene(PendulumScene):
    """A chain of six bobs from a pin, let go level: the top rod's tension and the lengths."""

    name = "chain"
    title = "A chain of six bobs on 0.3 m rods"
    short_titles = ("A chain of six bobs",)
    summary = "six bobs on rods from a pinned body, let go level: the whip, the lengths held"
    duration = 6.0
    strobe_interval = 0.1
    view = (-2.0, -2.0, 2.0, 0.4)
    world: Chain
    #: The tension plot's range (N): the whip's peak is about 1,280 N, for one step.
    tension_range = (-300.0, 1500.0)

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.chain = Chain()
        self.layout(size)
        self.tension_plot = self.plot(
            0, self.tension_range, "tension in the top rod  N", t_step=1.0, y_step=300.0,
            color=TENSION,
        )  # fmt: skip

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        c, s = self.chain, self.s
        surface.fill(PAPER)
        samples = _upto(c.history, t, self.dt)
        worst = max(p.length_error for p in samples)
        self.header(surface, t, f"worst length error so far: {worst:.1e} of a rod")
        self.pivot(surface)
        points: list[tuple[float, float]] = [(0.0, 0.0)]
        for bob in c.bobs:
            at = c.world.position_of(bob, alpha)
            assert isinstance(at, Vector)
            points.append((at.x, at.y))
        for start, end in zip(points, points[1:], strict=False):
            self.rod(surface, start, end)
        for point in points[1:]:
            self.bob(surface, point, CHAIN, 0.06)
        shown = _every(samples)
        plot = self.tension_plot
        plot.draw_frame(surface)
        plot.draw_curve(surface, [p.t for p in shown], [p.tension for p in shown])
        a = plot.area
        draw_text(
            surface,
            f"now {samples[-1].tension:7.2f} N;  the chain's weight {LINKS * G:.1f} N",
            (a.right - 4 * s, a.top + 2 * s),
            round(13 * s),
            TENSION,
            "topright",
        )
        self._lengths(surface, samples[-1].t)

    def _lengths(self, surface: pygame.Surface, t: float) -> None:
        """Each rod's length now, to 12 decimals, in the bottom panel."""
        s = self.s
        top = round(4 * s) + self.half + round(2 * s)
        box = pygame.Rect(self.plot_left, top, self.plot_w, self.half - round(2 * s))
        pygame.draw.rect(surface, (255, 255, 255), box, border_radius=4)
        pygame.draw.rect(surface, GRID, box, 1, border_radius=4)
        draw_text(
            surface,
            f"each rod's length now (m); it holds {LINK_LENGTH:g} m",
            (box.left + 6 * s, box.top + 3 * s),
            round(15 * s),
        )
        ends = [self.chain.anchor, *self.chain.bobs]
        size = round(13 * s)
        for k in range(LINKS):
            length = (ends[k + 1].pos - ends[k].pos).length()
            draw_text(
                surface,
                f"rod {k + 1}:  {length:.15f}",
                (box.left + 10 * s, box.top + 24 * s + k * 16 * s),
                size,
                CHAIN if k % 2 == 0 else INK,
            )

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The chain every strobe_interval for its first second: the fall and the whip."""
        self.build(surface.get_size())
        surface.fill(PAPER)
        s, m = self.s, self.margin
        w, h = self.size
        shown = [t for t in times if t <= 1.0 + 1e-9]
        draw_text(
            surface,
            f"chain: every {self.strobe_interval:g} s for 1 s, later ones darker",
            (m, 4 * s),
            round(18 * s),
        )
        self.camera = Camera.fit(self.view, (m, round(30 * s), w - 2 * m, h - round(36 * s)))
        self.pivot(surface)
        c = self.chain
        for k, t in enumerate(shown):
            while c.t < t - 1e-9:
                c.step(self.dt)
            fade = 0.2 + 0.8 * (k + 1) / len(shown)
            points = [(0.0, 0.0)] + [(b.pos.x, b.pos.y) for b in c.bobs]
            pixels = [self.camera.point(p) for p in points]
            pygame.draw.lines(surface, faded(ROD, fade * 0.6), False, pixels, 1)
            for p in pixels[1:]:
                pygame.draw.circle(surface, faded(CHAIN, fade), p, max(3, round(3 * s)))


DEMO = Demo(
    name="pendulum",
    summary="Pendulums on rods: a wide swing against the exact period, a double's chaos, a chain",
    scenes={"single": SingleScene, "double": DoubleScene, "chain": ChainScene},
)
