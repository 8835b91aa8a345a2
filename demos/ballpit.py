"""A ball pit: thousands of balls dropped into a box, piling up, coming to rest and sleeping.

    python -m demos ballpit                   # frames: out/ballpit/drop/frame_00000.png ...
    python -m demos ballpit --balls 500       # fewer balls: quicker
    python -m demos ballpit --window          # real time, with the measured step time
    python -m demos ballpit --strobe          # the pit at a few moments, side by side

2,000 balls (``--balls N``) of radius 0.5 m, restitution 0.5 and friction 0.5, start on a grid
36 balls wide above a box 40 m wide (every other row shifted sideways, so that each row lands
in the gaps of the one below) and fall under gravity (9.81 m/s^2) in a World with
``integrator="auto"`` (the closed form: gravity is the only force) at dt = 1/60 s. The engine
solves each impact between two balls, or a ball and a wall, at its exact moment; balls
pressed together are resting contacts, solved as constraints; a group of touching balls that
stays still for half a second falls asleep and costs nothing until something hits it.

On screen: the pit, awake balls in one colour and sleeping ones in another; beside it the
count, how many sleep, the deepest overlap of two balls (or a ball and a wall) as a
percentage of the radius, now and the worst so far, and the kinetic and potential energy,
with their history, and the World's StabilityWarning once it comes. The overlap is measured
from the positions, pair by pair (``World.overlap``), and against the walls.
The step time is measured, so it differs from run to run: it is shown only in ``--window``;
the frames show only what the physics decides, so two runs write the same bytes.

What to look for: the block lands row by row and squeezes (the overlap peaks while it
lands), the pile settles into a crystal of balls six to a neighbour with a few seams, the
kinetic energy goes to zero (restitution 0.5 and friction take it), and the whole pile falls
asleep at once: a touching group sleeps only when every ball in it is still.

The number asleep and the colours are the World's ``sleeping`` and ``is_sleeping(body)``.
"""

from __future__ import annotations

import argparse
import time
from collections import deque
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np
import pygame

from demos.cli import Demo
from demos.warned import step_noting
from engine import Body, Box, Vector, World
from engine.forces import Gravity
from engine.render import EULER, INK, MUTED, PAPER, Camera, Plot, Scene, draw_text

__all__ = [
    "BALLS",
    "COLUMNS",
    "DT",
    "G",
    "RADIUS",
    "WIDTH",
    "Pit",
    "PitScene",
    "Readout",
    "asleep_mask",
    "deepest_overlap",
    "wall_overlap",
    "drop_grid",
    "pit_world",
    "readout",
    "DEMO",
]

#: The pit: balls by default, their radius (m), the box's inside width (m).
BALLS = 2000
RADIUS = 0.5
WIDTH = 40.0
#: Gravity (m/s^2), the physics step (s), the balls' material.
G = 9.81
DT = 1.0 / 60.0
RESTITUTION, FRICTION = 0.5, 0.5
#: The drop grid: balls a row, their spacing (m), the rows' spacing (m), the lowest row's height
#: (m, to the centres) and how far every other row is shifted sideways (m).
COLUMNS = 36
SPACING = 1.085
ROW = 1.2
FIRST = 1.0
SHIFT = 0.25
#: The most balls ``--balls`` takes.
MOST = 20000

#: Awake balls and sleeping ones: no other drawing uses these two colours, so a test finds the
#: balls by them.
AWAKE: tuple[int, int, int] = (213, 94, 0)
ASLEEP: tuple[int, int, int] = (0, 114, 178)
KINETIC, POTENTIAL = EULER, (0, 158, 115)
WALL = (70, 70, 78)
WARN = (190, 30, 45)

Color = tuple[int, int, int]


def drop_grid(balls: int) -> np.ndarray:
    """The balls' starting centres (m), shape (balls, 2): rows of COLUMNS from the bottom up.

    Row k is at height FIRST + k ROW; its balls are SPACING apart from x = 1 m, shifted by
    -SHIFT on even rows and +SHIFT on odd ones, so that a row lands in the gaps of the one below.
    """
    k = np.arange(balls)
    row, col = np.divmod(k, COLUMNS)
    x = 1.0 + SPACING * col + np.where(row % 2 == 1, SHIFT, -SHIFT)
    y = FIRST + ROW * row
    return np.stack([x, y], axis=1).astype(float)


def box_height(balls: int) -> float:
    """The box's height (m): 2 m above the top of the grid, so every ball starts inside it."""
    return float(drop_grid(balls)[:, 1].max()) + RADIUS + 2.0


def pit_world(balls: int = BALLS) -> tuple[World, list[Body]]:
    """The pit's World: gravity, the box (a ``Box`` room 40 m wide) and the balls on the grid."""
    if not 1 <= balls <= MOST:
        raise ValueError(f"balls must be from 1 to {MOST}, got {balls!r}")
    world = World(integrator="auto")  # gravity alone: the closed form
    world.add_force(Gravity((0.0, -G)))
    world.add_collider(Box((0.0, 0.0), (WIDTH, box_height(balls))))
    bodies = world.add_all(
        Body(
            Vector(float(x), float(y)),
            Vector(0.0, 0.0),
            Vector(0.0, 0.0),
            radius=RADIUS,
            restitution=RESTITUTION,
            friction=FRICTION,
            # Balls that do not turn, as when the pit was measured (asleep by 3 s): balls that
            # turn roll on in a pile too (engine.exact.soft's lever arms; no rolling resistance),
            # and these 400 sleep at about 4.5 s.
            fixed_rotation=True,
        )
        for x, y in drop_grid(balls)
    )
    return world, bodies


def asleep_mask(world: World) -> np.ndarray:
    """Which bodies sleep, a (N,) bool array in the World's order (``World.is_sleeping``).

    (A sleeping body's velocity is exactly zero, but so is that of a ball held still on the
    floor by friction, so the velocities alone cannot tell.)
    """
    return np.fromiter((world.is_sleeping(b) for b in world.bodies), dtype=bool)


def wall_overlap(positions: np.ndarray, radius: float = RADIUS, width: float = WIDTH) -> float:
    """The deepest overlap (m, 0 if none) of a ball into the box's walls or floor."""
    P = np.asarray(positions, dtype=float).reshape(-1, 2)
    if not len(P):
        return 0.0
    return max(
        0.0,
        float((radius - P[:, 0]).max()),
        float((P[:, 0] - (width - radius)).max()),
        float((radius - P[:, 1]).max()),
    )


def deepest_overlap(world: World) -> float:
    """The deepest overlap (m) now of two balls (``World.overlap``: every pair, measured from
    the positions) or of a ball and the box's walls or floor."""
    return max(world.overlap(), wall_overlap(world.positions()))


class Readout(NamedTuple):
    """What the frames show of the pit at one moment: all of it decided by the physics."""

    t: float  # s
    balls: int
    asleep: int
    overlap: float  # the deepest overlap, as a fraction of the radius
    kinetic: float  # J: the sum of m |v|^2 / 2
    potential: float  # J: the sum of m g (y - r), zero for a ball on the floor


def readout(world: World) -> Readout:
    """The read-outs of ``world`` now (every ball's mass is 1 kg; heights from the floor)."""
    x, v = world.positions(), world.velocities()
    m = np.array([b.mass for b in world.bodies]) if len(x) else np.zeros(0)
    kinetic = 0.5 * float(np.sum(m * (v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1]))) if len(x) else 0.0
    potential = float(np.sum(m * G * (x[:, 1] - RADIUS))) if len(x) else 0.0
    return Readout(
        world.t,
        len(x),
        world.sleeping,
        deepest_overlap(world) / RADIUS,
        kinetic,
        potential,
    )


class Pit:
    """The pit's physics and its history: a Steppable (``step(dt)``, ``t``, snapshots).

    ``history`` holds a :class:`Readout` after every step (and one at the start). ``step_ms``
    holds the measured duration of the last steps (ms): it differs from run to run, so it is
    not part of a snapshot, and the frames do not show it.
    """

    def __init__(self, balls: int = BALLS) -> None:
        self.world, self.balls = pit_world(balls)
        self.history: list[Readout] = [readout(self.world)]
        self.step_ms: deque[float] = deque(maxlen=30)
        # The World gives its StabilityWarning once in its life, and a restore does not undo
        # that: the first one seen is kept across restores, so a rerun from a snapshot taken
        # before it still shows it at its moment (a fresh World warns again by itself).
        self._warned: tuple[float, str] | None = None

    @property
    def t(self) -> float:
        return self.world.t

    @property
    def now(self) -> Readout:
        """The read-outs after the last step."""
        return self.history[-1]

    @property
    def warning(self) -> tuple[float, str] | None:
        """The World's StabilityWarning, (time s, message), once the pit's time has reached it."""
        warned = self._warned
        return warned if warned is not None and warned[0] <= self.world.t else None

    def step(self, dt: float) -> None:
        start = time.perf_counter()
        self._warned = step_noting(self.world, dt, self._warned)
        self.step_ms.append(1000.0 * (time.perf_counter() - start))
        self.history.append(readout(self.world))

    def snapshot(self) -> tuple[Any, ...]:
        return self.world.snapshot(), tuple(self.history)

    def restore(self, snapshot: tuple[Any, ...]) -> None:
        world, history = snapshot
        self.world.restore(world)
        self.history = list(history)


# -- drawing --------------------------------------------------------------------------------


def draw_pit(
    surface: pygame.Surface,
    camera: Camera,
    positions: np.ndarray,
    asleep: np.ndarray,
    top: float,
) -> None:
    """The box's walls and floor (up to height ``top``) and every ball, coloured by sleep."""
    r_px = max(1, round(camera.length(RADIUS)))
    xs, ys = camera.to_px(positions[:, 0], positions[:, 1]) if len(positions) else ((), ())
    for x, y, sleeping in zip(
        np.rint(xs).tolist(), np.rint(ys).tolist(), asleep.tolist(), strict=True
    ):
        pygame.draw.circle(surface, ASLEEP if sleeping else AWAKE, (int(x), int(y)), r_px)
    thick = max(2, round(camera.length(0.25)))
    corners = [(0.0, top), (0.0, 0.0), (WIDTH, 0.0), (WIDTH, top)]
    points = [camera.point(p) for p in corners]
    # The walls are drawn just outside the box, so a ball against them stays whole.
    a, b, c, d = points
    half = thick // 2 + 1
    pygame.draw.lines(
        surface,
        WALL,
        False,
        [
            (a[0] - half, a[1]),
            (b[0] - half, b[1] + half),
            (c[0] + half, c[1] + half),
            (d[0] + half, d[1]),
        ],
        thick,
    )


class PitScene(Scene):
    """Balls dropped on a grid into a 40 m box: they pile up, settle and fall asleep."""

    name = "drop"
    summary = "2,000 balls dropped into a box 40 m wide: they pile up, settle and sleep"
    duration = 10.0
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.5
    world: Pit
    #: The balls in the pit (``--balls``).
    balls = BALLS
    #: Whether the measured step time is drawn (only in ``--window``: it varies run to run).
    live = False

    def build(self, size: tuple[int, int]) -> None:
        self.world = self.pit = Pit(self.balls)
        w, h = size
        s = self.s = h / 360
        self.size = size
        self.top = box_height(self.balls)
        # The pit on the right, as tall as the canvas allows, its floor at the bottom; the
        # read-outs and the plots in the panel left of it (at least 300 px of 640).
        m = self.margin = round(8 * s)
        x0, y0, x1, y1 = -0.6, -0.8, WIDTH + 0.6, self.top - 1.5
        room = w - round(300 * s) - 2 * m
        scale = min((h - 2 * m) / (y1 - y0), room / (x1 - x0))
        self.camera = Camera(scale, ((w - m) - scale * x1, (h - m) + scale * y0))
        self.panel = round(self.camera.to_px(x0, 0.0)[0]) - 2 * m  # its width (px)
        gap = round(8 * s)
        plot_w = (self.panel - gap) // 2
        top = round(144 * s)
        plot_h = h - m - top
        t_step = _nice(self.duration / 4)
        energy = _nice(max(1.0, self.pit.now.potential + self.pit.now.kinetic) / 1000.0)
        self.energy_plot = Plot(
            (m, top, plot_w, plot_h),
            t_max=self.duration,
            y_range=(0.0, energy),
            title="energy  kJ",
            t_step=t_step,
            y_step=energy / 2,
            color=INK,
            text_scale=s,
        )
        self.sleep_plot = Plot(
            (m + plot_w + gap, top, plot_w, plot_h),
            t_max=self.duration,
            y_range=(0.0, float(self.balls)),
            title="balls asleep",
            t_step=t_step,
            y_step=float(self.balls) / 2,
            color=ASLEEP,
            text_scale=s,
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        pit = self.pit
        surface.fill(PAPER)
        draw_pit(surface, self.camera, pit.world.positions(alpha), asleep_mask(pit.world), self.top)
        t = self.time(alpha)
        shown = [r for r in pit.history if r.t <= t + 1e-9] or pit.history[:1]
        self._readouts(surface, t, shown[-1], max(r.overlap for r in shown))
        self._plots(surface, shown)

    def _plots(self, surface: pygame.Surface, shown: Sequence[Readout]) -> None:
        """Potential and kinetic energy, and the balls asleep, against time."""
        s = self.s
        ts = [r.t for r in shown]
        plot = self.energy_plot
        plot.draw_frame(surface)
        plot.draw_curve(surface, ts, [r.potential / 1000 for r in shown], POTENTIAL)
        plot.draw_curve(surface, ts, [r.kinetic / 1000 for r in shown], KINETIC)
        a = plot.area
        for k, (label, colour) in enumerate((("potential", POTENTIAL), ("kinetic", KINETIC))):
            draw_text(
                surface,
                label,
                (a.right - 4 * s, a.top + (3 + 16 * k) * s),
                round(15 * s),
                colour,
                "topright",
            )
        self.sleep_plot.draw_frame(surface)
        self.sleep_plot.draw_curve(surface, ts, [r.asleep for r in shown])

    def _readouts(self, surface: pygame.Surface, t: float, now: Readout, worst: float) -> None:
        """The title, the material, and the read-outs of the state shown (and the step time in
        a window)."""
        s, x = self.s, self.margin
        right = x + self.panel
        size, step = round(17 * s), round(19 * s)
        draw_text(surface, f"Ball pit: {now.balls:,} balls", (x, 4 * s), round(22 * s))
        draw_text(surface, f"t = {t:5.2f} s", (right, 4 * s), round(22 * s), INK, "topright")
        draw_text(
            surface,
            "box 40 m wide, r = 0.5 m, e = 0.5, mu = 0.5, dt = 1/60 s",
            (x, 26 * s),
            round(15 * s),
            MUTED,
        )
        y = round(46 * s)
        dot = max(3, round(5 * s))
        for k, (label, count, colour) in enumerate(
            (("awake", now.balls - now.asleep, AWAKE), ("asleep", now.asleep, ASLEEP))
        ):
            left = x + k * round(self.panel / 2)
            rect = draw_text(surface, f"{label}  {count:,}", (left + 3 * dot, y), size, colour)
            pygame.draw.circle(surface, colour, (left + dot, rect.centery), dot)
        y += step
        draw_text(
            surface,
            f"deepest overlap  {100 * now.overlap:.2f}% of r   (worst so far {100 * worst:.1f}%)",
            (x, y),
            size,
        )
        y += step
        draw_text(surface, f"kinetic  {now.kinetic / 1000:.3f} kJ", (x, y), size, KINETIC)
        draw_text(
            surface,
            f"potential  {now.potential / 1000:.1f} kJ",
            (x + round(self.panel / 2), y),
            size,
            POTENTIAL,
        )
        y += step
        warned = self.pit.warning
        if warned is not None and warned[0] <= t + 1e-9:
            draw_text(
                surface,
                f"StabilityWarning at t = {warned[0]:.2f} s: overlap past 5% of r",
                (x, y),
                round(15 * s),
                WARN,
            )
        y += step
        if self.live and self.pit.step_ms:
            # Measured, so it differs from run to run: only ever drawn in a window.
            ms = sum(self.pit.step_ms) / len(self.pit.step_ms)
            draw_text(surface, f"step time  {ms:.1f} ms (measured)", (x, y), size, INK)

    def strobe_times(self) -> list[float]:
        """The moments the strobe picture shows (s): the grid, the landing, and the end."""
        return [t for t in (0.0, 1.0, 2.0) if t < self.duration] + [self.duration]

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The pit at each of ``times`` (s), side by side, coloured by sleep."""
        self.build(surface.get_size())
        w, h = surface.get_size()
        s, m = self.s, self.margin
        surface.fill(PAPER)
        draw_text(
            surface,
            f"Ball pit: {self.balls:,} balls dropped into a box 40 m wide",
            (m, 4 * s),
            round(22 * s),
        )
        dot = max(3, round(5 * s))
        x = w - m
        for label, colour in (("asleep", ASLEEP), ("awake", AWAKE)):
            rect = draw_text(surface, label, (x, 6 * s), round(17 * s), colour, "topright")
            pygame.draw.circle(surface, colour, (rect.left - 2 * dot, rect.centery), dot)
            x = rect.left - 5 * dot
        n = max(1, len(times))
        gap = round(10 * s)
        width = (w - 2 * m - (n - 1) * gap) / n
        x0, y0, x1, y1 = -0.6, -0.8, WIDTH + 0.6, self.top - 1.5
        top, bottom = round(32 * s), h - round(24 * s)
        scale = min(width / (x1 - x0), (bottom - top) / (y1 - y0))
        for k, t in enumerate(times):
            while self.pit.t < t - 1e-9:
                self.pit.step(self.dt)
            left = m + k * (width + gap)
            right = left + (width + scale * (x1 - x0)) / 2
            camera = Camera(scale, (right - scale * x1, bottom + scale * y0))
            draw_pit(
                surface, camera, self.pit.world.positions(), asleep_mask(self.pit.world), self.top
            )
            now = self.pit.now
            draw_text(
                surface,
                f"t = {t:g} s: {now.asleep:,} asleep",
                (left + width / 2, bottom + 4 * s),
                round(15 * s),
                INK,
                "midtop",
            )


def _nice(value: float) -> float:
    """The smallest of 1, 2, 5 times a power of ten that is >= value."""
    power = 10.0 ** np.floor(np.log10(value))
    for k in (1.0, 2.0, 5.0, 10.0):
        if k * power >= value:
            return float(k * power)
    return float(10 * power)


def _balls_arg(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if not 1 <= value <= MOST:
        raise argparse.ArgumentTypeError(
            f"must be a whole number of balls from 1 to {MOST:,}, got {text!r}"
        )
    return value


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--balls",
        type=_balls_arg,
        default=BALLS,
        help=f"balls in the pit (default {BALLS:,}; 1 to {MOST:,})",
    )


def _configure(scene: PitScene, args: argparse.Namespace) -> None:
    scene.balls = args.balls
    scene.live = bool(args.window)


DEMO = Demo(
    name="ballpit",
    summary="Thousands of balls dropped into a box: they pile up, settle and fall asleep",
    scenes={"drop": PitScene},
    add_arguments=_add_arguments,
    configure=_configure,
)
