"""Alfred the ant, lesson 1's figures as moving scenes (inches and seconds).

- ``lazy``: Alfred sits at 5 in: s(t) = 5 in, v = 0, a = 0 (figure 7).
- ``stroll``: from 0 at 1 in/s to the end of his 10-inch tube: s(t) = t (figures 5, 8, 9); the
  shaded area under v(t) is the distance walked.
- ``sprint``: from rest at 1 in/s^2 (figure 6), as two ants on two tubes. The lesson's "he
  reaches the end in 4 s" (0, 1, 3, 6, 10 in) is semi-implicit Euler with a 1 s step; the exact
  answer, s = t^2 / 2 = 10 in, is t = sqrt(20) = 4.47 s. The shaded areas under v(t) show why:
  Euler moves each whole second at the speed it has at the end of that second.
- ``paper``: Alfred's 2D walk x(t) = t^2 / 2, y(t) = 2t - t^2 on a sheet of paper, with his
  position vector from the origin and his velocity (t, 2 - 2t) tangent to the path
  (figures 15 to 18).

The 1D scenes are simulated with floats in a 1D World; constant-acceleration motion is moved by
the closed form (``World(integrator="exact")``). Alfred stops at the end of his tube (10 in):
he knows what lies beyond.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pygame

from demos.cli import Demo
from engine import Body, Vector, World, kinematics
from engine.render import (
    ACCELERATION,
    EULER,
    EXACT,
    GRID,
    INK,
    MUTED,
    PAPER,
    POSITION,
    VELOCITY,
    Camera,
    Plot,
    Scene,
    draw_arrow,
    draw_dot,
    draw_grid,
    draw_ruler,
    draw_sprite,
    draw_text,
    draw_vector,
    font,
)

#: Where the sprites live (made by assets/make_assets.py).
ASSETS = Path(__file__).resolve().parent.parent / "assets"
#: Alfred's body colour in ant.png, used nowhere else in a frame (tests find him by it).
ANT_BODY = (156, 66, 33)
#: The body colour of the second ant in the sprint (semi-implicit Euler's Alfred).
EULER_ANT_BODY = (222, 140, 10)
#: The tube is 10 inches long: Alfred's whole world in 1D.
TUBE_LENGTH = 10.0
#: Tube thickness (in).
TUBE_THICKNESS = 0.28
TUBE_FILL = (214, 222, 200)
TUBE_EDGE = (150, 160, 140)


@cache
def ant_sprite(
    body: tuple[int, int, int] = ANT_BODY, small: bool = False, zoom: int = 1, top: bool = False
) -> pygame.Surface:
    """Alfred's sprite (55x35 px, or 33x21 ``small``, facing +x), body recoloured to ``body``.

    ``top`` gives him seen from above instead (39x27 px, head to +x, his body's middle in the
    middle of the image), for a sheet of paper: rotate him to face his velocity. ``zoom``
    enlarges him a whole number of times for big canvases; nearest-neighbour scaling keeps his
    body colour exact.
    """
    if small and top:
        raise ValueError("small is a size of the side view: pass small=False with top=True")
    path = ASSETS / ("ant_top.png" if top else "ant_small.png" if small else "ant.png")
    if not path.exists():
        raise FileNotFoundError(f"{path} is missing: remake it with `python assets/make_assets.py`")
    image = pygame.image.load(str(path))
    if body != ANT_BODY:
        image = image.copy()
        pixels = pygame.PixelArray(image)
        # Only the exact body colour changes: the soft edges keep the original brown tint.
        pixels.replace((*ANT_BODY, 255), (*body, 255), distance=0)
        del pixels
    if zoom > 1:
        image = pygame.transform.scale(image, (image.get_width() * zoom, image.get_height() * zoom))
    return image


def _zoom(size: tuple[int, int]) -> int:
    # Alfred is drawn for 640x360; a canvas twice as big draws him twice as big.
    return max(1, int(min(size[0] / 640, size[1] / 360) + 0.25))


def _font_size(size: tuple[int, int], px: int) -> int:
    # Type scaled with the canvas: px at 640x360, never below 10 px.
    k = min(size[0] / 640, size[1] / 360)
    return max(10, round(px * k))


def _fmt(value: float, digits: int = 2) -> str:
    text = f"{value:.{digits}f}"
    return text.replace("-", "\u2212") if value < -0.5 * 10**-digits else text.lstrip("-")


@dataclass
class Ant:
    """One Alfred on one tube: his Body, the World moving him, and how to draw and plot him."""

    body: Body
    world: World
    row: float  # the world y (in) of the top of his tube
    color: tuple[int, int, int]  # his curves and labels
    sprite: pygame.Surface
    label: str  # his tube's name, lines split by "\\n"
    s0: float
    v0: float
    a: float
    short: str = ""  # a one-word name for the plots
    arrival: float = math.inf  # when he reached the end of the tube (s)
    stepped: bool = False  # a numerical integrator's ant: drawn between its steps as it moves
    #: A stepped ant's states after each step so far: (t s, position in, velocity in/s).
    history: list[tuple[float, float, float]] = field(default_factory=list)


class Tubes:
    """What a tube scene steps: every ant's World as one, and what the stepped ants did.

    Speaks :class:`engine.Steppable`. ``step(dt)`` steps each World once (the sprint's two
    ants live in two Worlds, one per method) and then notes each stepped ant's state and
    when he reached the end; ``t`` is their common time, the scene's one clock; the snapshot
    holds every World's with the histories and arrival times beside them.
    """

    def __init__(self, ants: list[Ant]) -> None:
        self.ants = ants
        self.worlds = list({id(ant.world): ant.world for ant in ants}.values())
        for ant in ants:
            if ant.stepped:
                ant.history = [(0.0, ant.s0, ant.v0)]

    @property
    def t(self) -> float:
        """The time (s): every World has taken the same steps."""
        return self.worlds[0].t

    def step(self, dt: float) -> None:
        """One physics step of every ant's world; note when a stepped ant reaches the end."""
        for world in self.worlds:
            world.step(dt)
        for ant in self.ants:
            if ant.stepped:
                t_prev, s_prev, _ = ant.history[-1]
                s = float(ant.body.pos)
                ant.history.append((ant.world.t, s, float(ant.body.vel)))
                if ant.arrival == math.inf and s >= TUBE_LENGTH > s_prev:
                    # Between steps the ant is drawn moving in a straight line, so he reaches
                    # the end where that line crosses it.
                    ant.arrival = t_prev + (TUBE_LENGTH - s_prev) / (s - s_prev) * (
                        ant.world.t - t_prev
                    )

    def snapshot(self) -> tuple[list[Any], list[list[Any]], list[float]]:
        """Every World's snapshot, in order, with each ant's history and arrival time."""
        return (
            [world.snapshot() for world in self.worlds],
            [list(ant.history) for ant in self.ants],
            [ant.arrival for ant in self.ants],
        )

    def restore(self, snapshot: tuple[list[Any], list[list[Any]], list[float]]) -> None:
        """Return every ant and his history to the moment of ``snapshot``."""
        states, histories, arrivals = snapshot
        if len(states) != len(self.worlds) or len(arrivals) != len(self.ants):
            raise ValueError(
                f"the snapshot holds {len(states)} worlds and {len(arrivals)} ants but these "
                f"tubes have {len(self.worlds)} and {len(self.ants)}: restore into the same scene"
            )
        for world, state in zip(self.worlds, states, strict=True):
            world.restore(state)
        for ant, history, arrival in zip(self.ants, histories, arrivals, strict=True):
            ant.history, ant.arrival = list(history), arrival


class TubeScene(Scene):
    """Shared layout of the 1D scenes: tube(s) with a ruler, the s, v, a plots below."""

    title = ""
    formula = ""
    #: Plot ranges: s (in), v (in/s), a (in/s^2).
    s_range = (0.0, 10.0)
    v_range = (0.0, 2.0)
    a_range = (-1.0, 1.0)
    #: Seconds of travel a velocity arrow shows: 1.0 draws it as long as one second's walk.
    arrow_seconds = 1.0

    ants: list[Ant]

    #: One ant's start for the default make_ants: position (in), velocity (in/s),
    #: acceleration (in/s^2). Scenes with more than one ant override make_ants.
    start: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def make_ants(self) -> list[Ant]:
        """One ant moved by the closed form from ``start`` (scenes with more ants override)."""
        s0, v0, a = self.start
        world = World(integrator="exact")
        return [
            _ant_1d(
                world,
                s0,
                v0,
                a,
                row=0.0,
                color=POSITION,
                sprite=ant_sprite(zoom=_zoom(self.size)),
                label="",
            )
        ]

    def build(self, size: tuple[int, int]) -> None:
        """Place the tube(s), the ruler and the plots for a canvas of ``size`` px."""
        self.size = size
        w, h = size
        self.ants = self.make_ants()
        rows = len(self.ants)
        # With two tubes, a column on the left names them.
        self.label_width = round(0.2 * w) if rows > 1 else 0
        # The tube spans 0..10 in; leave 0.7 in each side for Alfred's body and the arrows.
        scale = (w - 40 - self.label_width) / (TUBE_LENGTH + 1.4)
        # Pixel rows of the tube tops: below the title, with room above each tube for Alfred
        # (35 px) and his velocity arrow; the ruler under the last tube; plots below that.
        first = (0.33 if rows == 1 else 0.31) * h
        row_px = [first + 0.215 * h * i for i in range(rows)]
        self.camera = Camera(scale, (20 + self.label_width + 0.7 * scale, row_px[0]))
        for ant, px in zip(self.ants, row_px, strict=True):
            ant.row = (row_px[0] - px) / scale  # world y (in) of this tube's top
        self.ruler_y = self.ants[-1].row - TUBE_THICKNESS - 4 / scale
        plot_top = round(row_px[-1] + (0.17 if rows == 1 else 0.155) * h)
        gap = 12
        pw = (w - 2 * 12 - 2 * gap) // 3
        ph = h - plot_top - 6
        panels = [
            ("s(t)  in", self.s_range, INK),
            ("v(t)  in/s", self.v_range, VELOCITY),
            ("a(t)  in/s\u00b2", self.a_range, ACCELERATION),
        ]
        # On a small canvas there is no room for readable plots: leave them out.
        fits = pw >= 120 and ph >= 80
        self.plots = [
            Plot(
                (12 + i * (pw + gap), plot_top, pw, ph),
                self.duration,
                y_range,
                title,
                y_step=_step(y_range),
                color=color,
                text_scale=_font_size(size, 100) / 100,
            )
            for i, (title, y_range, color) in enumerate(panels)
            if fits
        ]
        self.world = Tubes(self.ants)

    # --- where an ant is -------------------------------------------------------------------

    def position(self, ant: Ant, t: float, alpha: float | None = None) -> float:
        """Alfred's position (in) at time t: stepped ants blended between steps, others exact."""
        if ant.stepped and alpha is not None:
            # A numerical integrator's ant: blended between the states before and after the
            # world's last step, the straight line he walks between steps.
            blended = ant.world.position_of(ant.body, alpha)
            assert not isinstance(blended, Vector)  # the tube is a 1D world
            s = float(blended)
        elif ant.stepped:
            s = self._stepped_at(ant, t)[0]
        elif alpha is not None:
            # The world moved him by the closed form; from its current state (time world.t)
            # the same closed form gives him exactly at t, even between steps.
            s = float(
                kinematics.position(
                    float(ant.body.pos), float(ant.body.vel), ant.a, t - ant.world.t
                )
            )
        else:
            s = float(kinematics.position(ant.s0, ant.v0, ant.a, t))
        return min(s, TUBE_LENGTH)

    def _stepped_at(self, ant: Ant, t: float) -> tuple[float, float]:
        # Position on the straight line between the steps around t, and that line's slope.
        history = ant.history
        for (t0, s0, _), (t1, s1, _) in zip(history, history[1:], strict=False):
            if t0 <= t <= t1:
                return s0 + (s1 - s0) * (t - t0) / (t1 - t0), (s1 - s0) / (t1 - t0)
        return history[-1][1], 0.0

    def velocity(self, ant: Ant, t: float) -> float:
        """Alfred's velocity (in/s) at t: for a stepped ant, the slope he is drawn moving at."""
        if t >= ant.arrival:
            return 0.0
        if ant.stepped:
            return self._stepped_at(ant, t)[1]
        return float(kinematics.velocity(ant.v0, ant.a, t))

    # --- drawing ---------------------------------------------------------------------------

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """One frame: the tube(s) with Alfred and his velocity arrow, the ruler, the plots."""
        t = self.time(alpha)
        self.draw_background(surface, t)
        for ant in self.ants:
            s = self.position(ant, t, alpha)
            anchor = self.camera.to_px(s, ant.row)
            v = self.velocity(ant, t)
            if t < ant.arrival and v != 0.0:
                arrow_y = anchor[1] - ant.sprite.get_height() - 9
                draw_vector(
                    surface,
                    self.camera,
                    (s, self.camera.to_world(0.0, arrow_y)[1]),
                    v,
                    self.arrow_seconds,
                    VELOCITY,
                    label=f"v = {_fmt(v, 1)} in/s",
                    label_side=0,
                    label_size=_font_size(self.size, 18),
                )
            draw_sprite(surface, ant.sprite, anchor, "midbottom")
        self.draw_plots(surface, t)

    def draw_background(self, surface: pygame.Surface, t: float, clock: str = "") -> None:
        """Paper, title, the time (or ``clock``), the tubes with their names and the ruler."""
        surface.fill(PAPER)
        size = self.size
        big, small = _font_size(size, 24), _font_size(size, 17)
        draw_text(surface, self.title, (12, 8), big, INK)
        draw_text(surface, self.formula, (12, 10 + big), small, MUTED)
        draw_text(
            surface,
            clock or f"t = {t:.2f} s",
            (size[0] - 12, 8),
            _font_size(size, 26),
            INK,
            "topright",
        )
        for ant in self.ants:
            self.draw_tube(surface, ant.row)
            if ant.label:
                # The tube's name in the left column, level with Alfred.
                _, top = self.camera.to_px(0.0, ant.row)
                lines = ant.label.split("\n")
                if t >= ant.arrival:
                    lines.append(f"end at {ant.arrival:.2f} s")
                y = top - len(lines) * (small + 1) + 8
                for line in lines:
                    draw_text(surface, line, (10, y), small, ant.color)
                    y += small + 1
        draw_ruler(
            surface,
            self.camera,
            0.0,
            TUBE_LENGTH,
            self.ruler_y,
            step=1.0,
            minor=4,
            unit="in",
            size=_font_size(size, 16),
        )

    def draw_tube(self, surface: pygame.Surface, row: float) -> None:
        """Alfred's tube: 0 to 10 in, its top at world height ``row``."""
        left, top = self.camera.to_px(0.0, row)
        right, bottom = self.camera.to_px(TUBE_LENGTH, row - TUBE_THICKNESS)
        rect = pygame.Rect(round(left), round(top), round(right - left), round(bottom - top))
        pygame.draw.rect(surface, TUBE_FILL, rect, border_radius=rect.height // 2)
        pygame.draw.rect(surface, TUBE_EDGE, rect, 1, border_radius=rect.height // 2)
        pygame.draw.line(
            surface, (240, 244, 232), (rect.left + 6, rect.top + 3), (rect.right - 6, rect.top + 3)
        )

    def draw_plots(
        self, surface: pygame.Surface, t: float, strobe: list[float] | None = None
    ) -> None:
        """s(t), v(t) and a(t) from 0 to t; the area under v(t) shaded (it is the distance)."""
        if not self.plots:
            return
        s_plot, v_plot, a_plot = self.plots
        for plot in self.plots:
            plot.draw_frame(surface)
        for ant in self.ants:
            end = min(t, ant.arrival)
            if ant.stepped:
                ts, ss, vs = self._stepped_curves(ant, end)
            else:
                ts = np.linspace(0.0, end, 200)
                ss = kinematics.position(ant.s0, ant.v0, ant.a, ts)
                vs = kinematics.velocity(ant.v0, ant.a, ts)
            s_plot.draw_curve(surface, ts, ss, ant.color)
            v_plot.draw_curve(
                surface, ts, vs, VELOCITY if len(self.ants) == 1 else ant.color, shade=True
            )
            a_plot.draw_curve(surface, ts, np.full_like(ts, ant.a), ACCELERATION)
            if strobe:
                for ts_k in strobe:
                    if ts_k <= end:
                        x, y = s_plot.to_px(ts_k, self.position(ant, ts_k))
                        pygame.draw.circle(
                            surface, ant.color, (round(float(x)), round(float(y))), 4
                        )
        # The area under v(t) from 0 to t is the distance walked: say so beside the curve.
        lines = []
        for ant in self.ants:
            end = min(t, ant.arrival)
            walked = self.position(ant, end) - ant.s0
            prefix = f"{ant.short}: " if len(self.ants) > 1 else ""
            lines.append(
                (f"{prefix}area = {_fmt(walked, 1)} in", ant.color if prefix else VELOCITY)
            )
        area = v_plot.area
        for i, (text, color) in enumerate(lines):
            size = v_plot.number_size
            draw_text(surface, text, (area.left + 4, area.top + 2 + size * i), size, color)

    def _stepped_curves(self, ant: Ant, end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        # s: straight lines between the steps; v: the slope of each line, a staircase.
        history = [h for h in ant.history if h[0] <= end]
        ts = [history[0][0]]
        ss = [history[0][1]]
        vs = [self._stepped_at(ant, 0.0)[1]]
        for t0, s0 in ((h[0], h[1]) for h in history[1:]):
            if t0 >= end:
                break
            # A corner of the s line, a riser of the v staircase.
            ts += [t0, t0]
            ss += [s0, s0]
            vs += [vs[-1], self._stepped_at(ant, t0 + 1e-9)[1]]
        s_end, slope = self._stepped_at(ant, end)
        ts.append(end)
        ss.append(min(s_end, TUBE_LENGTH))
        vs.append(slope if end > ts[0] else vs[-1])
        return np.array(ts), np.array(ss), np.array(vs)

    # --- the motion diagram -----------------------------------------------------------------

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """Alfred at each of ``times`` along his tube, older images fainter, each labelled t."""
        t_end = max(times)
        # Run the simulation far enough to know where the stepped ants are at every time.
        while self.world.t < t_end + self.dt:
            self.step(self.dt)
        step = times[1] - times[0] if len(times) > 1 else 0.0
        self.draw_background(surface, t_end, f"Alfred every {_number(step)} s" if step else "")
        label_size = _font_size(self.size, 16)
        for ant in self.ants:
            # Times at which Alfred is on the same pixel share one image and one label.
            placed: dict[int, list[float]] = {}
            for t in times:
                px = round(self.camera.to_px(self.position(ant, t), ant.row)[0])
                placed.setdefault(px, []).append(t)
            images = sorted(placed.items(), key=lambda item: item[1][-1])
            label_rows: list[float] = []  # right edge of the last label in each row
            for i, (px, ts) in enumerate(images):
                age = 1.0 - i / max(1, len(images) - 1)  # 1 for the oldest, 0 for the newest
                anchor = (px, self.camera.to_px(0.0, ant.row)[1])
                rect = draw_sprite(
                    surface, ant.sprite, anchor, "midbottom", alpha=round(255 - 175 * age)
                )
                last = i == len(images) - 1
                label = ", ".join(_number(t) for t in ts) + (" s" if last else "")
                half = font(label_size).size(label)[0] / 2
                # The first row where this label clears the one before it; else a new row.
                row = next((r for r, right in enumerate(label_rows) if right < px - half - 3), None)
                if row is None:
                    label_rows.append(-math.inf)
                    row = len(label_rows) - 1
                label_rows[row] = px + half
                y = rect.top - 2 - row * (label_size + 1)
                draw_text(surface, label, (px, y), label_size, ant.color, "midbottom")
        self.draw_plots(surface, t_end, strobe=list(times))


def _number(value: float) -> str:
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return text or "0"


def _step(limits: tuple[float, float]) -> float:
    # Tick spacing that gives about 3 to 6 numbered ticks over the range.
    span = limits[1] - limits[0]
    for step in (0.5, 1.0, 2.0, 5.0, 10.0):
        if span / step <= 6:
            return step
    return 20.0


def _ant_1d(world: World, s0: float, v0: float, a: float, **kw: object) -> Ant:
    body = world.add(Body(s0, v0, a))
    ant = Ant(body=body, world=world, s0=s0, v0=v0, a=a, **kw)  # type: ignore[arg-type]
    if not ant.stepped:
        # The closed form says when he reaches the end (for the sprint: t^2 / 2 = 10 in at
        # t = sqrt(20) s); a stepped ant's arrival is seen as his world steps.
        ant.arrival = kinematics.time_to_reach(s0, v0, a, TUBE_LENGTH)
    return ant


class Lazy(TubeScene):
    """Alfred sits still at 5 in (figure 7)."""

    name = "lazy"
    summary = "Alfred sits at 5 in: s(t) = 5 in, v = 0, a = 0 (figure 7)"
    title = "Lazy Alfred"
    formula = "s(t) = 5 in,  v(t) = 0,  a(t) = 0"
    duration = 4.0
    dt = 1.0 / 120.0
    s_range = (0.0, 10.0)
    v_range = (-1.0, 1.0)
    a_range = (-1.0, 1.0)
    start = (5.0, 0.0, 0.0)  # at rest at 5 in


class Stroll(TubeScene):
    """From 0 at 1 in/s to the end of the tube in 10 s (figures 5, 8, 9)."""

    name = "stroll"
    summary = "Alfred walks 0 -> 10 in at 1 in/s; area under v(t) = distance (figures 5, 8, 9)"
    title = "Alfred's stroll"
    formula = "s(t) = s0 + v t = t in,  v = 1 in/s,  a = 0"
    duration = 10.0
    dt = 1.0 / 120.0
    v_range = (0.0, 2.0)
    a_range = (-1.0, 1.0)
    start = (0.0, 1.0, 0.0)  # from 0 at 1 in/s


class Sprint(TubeScene):
    """From rest at 1 in/s^2: semi-implicit Euler at dt = 1 s against the exact closed form."""

    name = "sprint"
    summary = "from rest at 1 in/s\u00b2: Euler with dt = 1 s says 4 s, the exact answer is 4.47 s"
    title = "Alfred's sprint: a = 1 in/s\u00b2 from rest"
    formula = "Euler with 1 s steps says he reaches 10 in at 4 s; the exact answer is \u221a20 s"
    duration = 5.5
    arrow_seconds = 0.5
    #: The lesson's own time step: one second.
    dt = 1.0
    s_range = (0.0, 10.0)
    v_range = (0.0, 8.0)  # room above the curves for the area labels
    a_range = (0.0, 2.0)

    def make_ants(self) -> list[Ant]:
        """Semi-implicit Euler's Alfred (top) and the exact Alfred (bottom)."""
        euler = _ant_1d(
            World(integrator="semi_implicit_euler"),
            0.0,
            0.0,
            1.0,
            row=0.0,
            color=EULER,
            sprite=ant_sprite(EULER_ANT_BODY, zoom=_zoom(self.size)),
            label="semi-implicit\nEuler, dt = 1 s",
            short="Euler",
            stepped=True,
        )
        exact = _ant_1d(
            World(integrator="exact"),
            0.0,
            0.0,
            1.0,
            row=-1.0,
            color=EXACT,
            sprite=ant_sprite(zoom=_zoom(self.size)),
            label="exact\ns = t\u00b2/2",
            short="exact",
        )
        return [euler, exact]


class Paper(Scene):
    """Alfred's 2D walk on a sheet of paper (figures 15 to 18)."""

    name = "paper"
    summary = (
        "2D walk x = t\u00b2/2, y = 2t - t\u00b2: position vector and tangent velocity (figs 15-18)"
    )
    duration = 3.0
    dt = 1.0 / 120.0
    strobe_interval = 0.5
    #: The sheet of paper, in inches: x0, y0, x1, y1.
    box = (-0.4, -3.4, 5.4, 1.5)
    #: A velocity arrow shows this many seconds of travel.
    arrow_seconds = 0.5
    s0 = Vector(0.0, 0.0)
    v0 = Vector(0.0, 2.0)
    a = Vector(1.0, -2.0)
    world: World

    def build(self, size: tuple[int, int]) -> None:
        """The paper on the left, the numbers on the right."""
        self.size = size
        w, h = size
        self.world = World(integrator="exact")
        # x(t) = t^2/2 and y(t) = 2t - t^2 are s0 + v0 t + a t^2/2 with s0 = 0, v0 = (0, 2),
        # a = (1, -2): constant acceleration, so the closed form moves Alfred exactly.
        self.alfred = self.world.add(Body(self.s0, self.v0, self.a))
        # Seen from above, head to +x; facing() turns him to his velocity.
        self.sprite = ant_sprite(top=True, zoom=_zoom(size))
        title_h = _font_size(size, 24) + 14
        paper_w = min(w * 0.6, (h - title_h - 10) * 1.1)
        self.paper_rect = pygame.Rect(10, title_h, round(paper_w), h - title_h - 10)
        inner = self.paper_rect.inflate(-16, -16)
        self.camera = Camera.fit(self.box, (inner.x, inner.y, inner.w, inner.h))

    def exact(self, t: float) -> tuple[Vector, Vector]:
        """Alfred's position (in) and velocity (in/s) at time t by the closed form."""
        return kinematics.position(self.s0, self.v0, self.a, t), kinematics.velocity(
            self.v0, self.a, t
        )

    def heading(self, t: float, vel: Vector) -> float:
        """The way Alfred faces at time t (s) with velocity vel (in/s): degrees counter-clockwise
        from the world's +x (y up)."""
        # At a stop, a velocity stepped back from the world's time is rounding noise (1e-16
        # in/s), whose atan2 points anywhere: below 1e-9 in/s he counts as stopped.
        if vel.magnitude() > 1e-9:
            direction = vel
        elif t > 0 and self.a.magnitude() > 0:
            # Stopped for an instant: keep the way he was walking. Just before, with constant a,
            # v(t - h) = v(t) - a h = -a h, so he was walking along -a.
            direction = -self.a
        elif self.a.magnitude() > 0:
            # Starting from rest: v(h) = a h, the way he is about to walk.
            direction = self.a
        else:
            return 0.0  # he never moves: the sprite's own heading, +x
        return math.degrees(math.atan2(direction.y, direction.x))

    def facing(self, t: float, vel: Vector) -> pygame.Surface:
        """Alfred's top-view sprite turned to face his velocity vel (in/s) at time t (s)."""
        # The sprite's head points along pixel +x. pygame.transform.rotate(image, theta) turns
        # it theta degrees counter-clockwise as seen on screen; pixel y points down, so the head
        # then points along the pixel direction (cos theta, -sin theta). The camera maps a world
        # direction (vx, vy), y up, to the pixel direction (vx, -vy) (times a positive scale).
        # Equal when (cos theta, sin theta) is along (vx, vy): theta = atan2(vy, vx), the
        # world angle as it is; the two y flips cancel. rotate samples the nearest pixel, so
        # his body keeps its exact colour (rotozoom would blend it).
        return pygame.transform.rotate(self.sprite, self.heading(t, vel))

    def draw_paper(self, surface: pygame.Surface, t: float) -> None:
        """The sheet with its grid and axes, and the whole path, faint."""
        surface.fill(PAPER)
        draw_text(surface, "Alfred on a sheet of paper", (12, 8), _font_size(self.size, 24), INK)
        pygame.draw.rect(surface, (255, 255, 255), self.paper_rect)
        pygame.draw.rect(surface, GRID, self.paper_rect, 1)
        draw_grid(surface, self.camera, self.box, 1.0, unit="in", size=_font_size(self.size, 15))
        ts = np.linspace(0.0, self.duration, 120)
        xs, ys = ts * ts / 2, 2 * ts - ts * ts
        px, py = self.camera.to_px(xs, ys)
        pygame.draw.aalines(
            surface, (190, 190, 196), False, list(zip(px.tolist(), py.tolist(), strict=True))
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """Path so far, position vector, velocity arrow, Alfred, and the numbers."""
        t = self.time(alpha)
        self.draw_paper(surface, t)
        pos = self.world.position_of(self.alfred, alpha)
        assert isinstance(pos, Vector)  # the paper is a 2D world
        # The world's velocity is at world.t, a step ahead; a is constant, so step it back.
        vel = kinematics.velocity(self.alfred.vel, self.a, t - self.world.t)
        # The path walked so far.
        ts = np.linspace(0.0, t, max(2, int(t * 60)))
        px, py = self.camera.to_px(ts * ts / 2, 2 * ts - ts * ts)
        if t > 0:
            pygame.draw.lines(
                surface, POSITION, False, list(zip(px.tolist(), py.tolist(), strict=True)), 2
            )
        # Position vector from the origin, velocity arrow along the path.
        draw_arrow(
            surface, self.camera.to_px(0.0, 0.0), self.camera.to_px(pos.x, pos.y), POSITION, 3
        )
        draw_vector(
            surface, self.camera, pos, vel, self.arrow_seconds, VELOCITY, label="v", label_side=-1
        )
        # Seen from above, he stands centred on his position.
        anchor = self.camera.to_px(pos.x, pos.y)
        draw_sprite(surface, self.facing(t, vel), anchor, "center")
        draw_dot(surface, anchor, 3, INK)
        self.draw_numbers(surface, t, pos, vel)

    def draw_numbers(self, surface: pygame.Surface, t: float, pos: Vector, vel: Vector) -> None:
        """The readout on the right: t, s, v, a with their formulas."""
        x = self.paper_rect.right + 14
        fs = _font_size(self.size, 20)
        small = _font_size(self.size, 16)
        y = self.paper_rect.top + 2
        lines = [
            (f"t = {t:.2f} s", INK, fs + 6),
            ("position  s = (x, y)", POSITION, fs),
            ("  x = t\u00b2/2,  y = 2t \u2212 t\u00b2", MUTED, small),
            (f"  s = ({_fmt(pos.x)}, {_fmt(pos.y)}) in", POSITION, fs),
            ("velocity  v = (t, 2 \u2212 2t)", VELOCITY, fs),
            (f"  v = ({_fmt(vel.x)}, {_fmt(vel.y)}) in/s", VELOCITY, fs),
            (f"  |v| = {_fmt(vel.magnitude())} in/s", VELOCITY, small),
            ("acceleration", ACCELERATION, fs),
            (f"  a = ({_fmt(self.a.x, 0)}, {_fmt(self.a.y, 0)}) in/s\u00b2", ACCELERATION, fs),
            ("", INK, small // 2),
            ("green: s from the origin", MUTED, small),
            (f"blue: v, drawn as {self.arrow_seconds:g} s of travel,", MUTED, small),
            ("  tangent to the path", MUTED, small),
        ]
        for text, color, size in lines:
            if text:
                draw_text(surface, text, (x, y), size, color)
            y += size + 4

    def strobe_times(self) -> list[float]:
        """Every half second from 0 to 3 s."""
        return [
            k * self.strobe_interval for k in range(int(self.duration / self.strobe_interval) + 1)
        ]

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """Alfred at equal time steps along his path, older images fainter, each labelled t."""
        self.draw_paper(surface, max(times))
        n = len(times)
        # Each time's age (0 newest, 1 oldest), pixel position and velocity (in/s).
        states = []
        for i, t in enumerate(times):
            pos, vel = self.exact(t)
            states.append((1.0 - i / max(1, n - 1), self.camera.to_px(pos.x, pos.y), vel))
        for age, anchor, _ in states:  # every arrow first, under all the ants
            draw_arrow(surface, self.camera.to_px(0.0, 0.0), anchor, _fade(POSITION, age), 2, 8)
        # Where each image's pixels are (a rotated image is mostly empty corners).
        drawn: list[tuple[pygame.Rect, pygame.mask.Mask]] = []
        for t, (age, anchor, vel) in zip(times, states, strict=True):
            image = self.facing(t, vel)
            rect = draw_sprite(surface, image, anchor, "center", alpha=round(255 - 175 * age))
            draw_dot(surface, anchor, 3, INK)
            drawn.append((rect, pygame.mask.from_surface(image)))
        # Each label goes beside its image, across his heading, where it covers no other ant
        # and no label: first on the outside of the bend (away from a, where the path is not),
        # then the inside, a little further out at each try; if none is free, the first place
        # on the paper.
        size = _font_size(self.size, 16)
        reach = self.sprite.get_height() / 2  # his legs' reach either side of his axis (px)
        ax, ay = self.a.x, -self.a.y  # a as a pixel direction (pixel y points down)
        labels: list[pygame.Rect] = []
        for i, t in enumerate(times):
            _, anchor, vel = states[i]
            text = f"t = {_number(t)} s"
            box = pygame.Rect((0, 0), font(size).size(text))
            theta = math.radians(self.heading(t, vel))
            # His heading in pixels is (cos theta, -sin theta) (see facing); across it are
            # (sin theta, cos theta) and its opposite (their dot product with it is 0).
            across = [(math.sin(theta), math.cos(theta)), (-math.sin(theta), -math.cos(theta))]
            across.sort(key=lambda d: d[0] * ax + d[1] * ay)  # against a first
            others = drawn[:i] + drawn[i + 1 :]
            places = []
            for gap in (2, 6, 10, 14):
                for dx, dy in across:
                    # A box w x h reaches |dx| w/2 + |dy| h/2 from its centre in the direction
                    # (dx, dy): centred this far out, all of it lies gap px beyond his legs.
                    r = reach + abs(dx) * box.w / 2 + abs(dy) * box.h / 2 + gap
                    places.append((anchor[0] + dx * r, anchor[1] + dy * r))
            on_paper = []
            for place in places:
                box.center = (round(place[0]), round(place[1]))
                if self.paper_rect.contains(box):
                    on_paper.append(place)
                    if box.collidelist(labels) < 0 and not _covers(box, others):
                        point = place
                        break
            else:
                point = (on_paper or places)[0]
            labels.append(draw_text(surface, text, point, size, INK, "center"))
        pos, vel = self.exact(max(times))
        self.draw_numbers(surface, max(times), pos, vel)


def _covers(box: pygame.Rect, images: Sequence[tuple[pygame.Rect, pygame.mask.Mask]]) -> bool:
    """Whether the pixel rectangle ``box`` covers a visible pixel of any of ``images``."""
    solid = pygame.mask.Mask(box.size, fill=True)
    return any(
        mask.overlap(solid, (box.x - rect.x, box.y - rect.y)) is not None for rect, mask in images
    )


def _fade(color: tuple[int, int, int], age: float) -> tuple[int, int, int]:
    # Mix toward white: age 0 is the full colour, age 1 is 70% white.
    return tuple(round(c + (255 - c) * 0.7 * age) for c in color)  # type: ignore[return-value]


DEMO = Demo(
    name="alfred",
    summary="Alfred the ant, lesson 1: sitting, strolling, sprinting, walking on paper",
    scenes={"lazy": Lazy, "stroll": Stroll, "sprint": Sprint, "paper": Paper},
)
