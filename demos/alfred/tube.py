"""The tube scenes' shared parts: Alfred on a 10-inch tube, with s(t), v(t) and a(t) below.

An :class:`Ant` is one Alfred on one tube; :class:`Tubes` steps every ant's World as one (what
a tube scene steps); :class:`TubeScene` lays out the tube(s), the ruler and the plots, and
draws the frames and the motion diagram. The 1D scenes are simulated with floats in a 1D
World; constant-acceleration motion is moved by the closed form (``World(integrator="exact")``).
Alfred stops at the end of his tube (10 in): he knows what lies beyond.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pygame

from engine import Body, Vector, World, kinematics
from engine.render import (
    ACCELERATION,
    INK,
    MUTED,
    PAPER,
    POSITION,
    VELOCITY,
    Camera,
    Plot,
    Scene,
    draw_ruler,
    draw_sprite,
    draw_text,
    draw_vector,
    font,
)

from .common import ant_sprite, fmt, font_size, number, sprite_zoom

#: The tube is 10 inches long: Alfred's whole world in 1D.
TUBE_LENGTH = 10.0
#: Tube thickness (in).
TUBE_THICKNESS = 0.28
TUBE_FILL = (214, 222, 200)
TUBE_EDGE = (150, 160, 140)


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
            ant_1d(
                world,
                s0,
                v0,
                a,
                row=0.0,
                color=POSITION,
                sprite=ant_sprite(zoom=sprite_zoom(self.size)),
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
        # The tube spans 0..10 in; leave 0.7 in on the left for Alfred's body, and on the
        # right room for his longest velocity arrow (its head 11 px past its length).
        reach = self.arrow_seconds * max(self.top_speed(ant) for ant in self.ants)
        right = max(0.7, reach)
        scale = (w - 40 - 11 - self.label_width) / (TUBE_LENGTH + 0.7 + right)
        # Pixel rows of the tube tops: below the title, with room above each tube for Alfred
        # (35 px) and his velocity arrow; the ruler under the last tube; plots below that.
        first = (0.33 if rows == 1 else 0.31) * h
        # Room above the first tube, under the two lines of title, for Alfred and the label
        # of his velocity arrow, whatever the canvas.
        big, small = font_size(size, 24), font_size(size, 17)
        under_title = 10 + big + font(small).get_linesize()
        label = font(font_size(size, 18)).get_height()
        sprite_h = ant_sprite(zoom=sprite_zoom(size)).get_height()
        first = max(first, under_title + label + 9 + sprite_h)
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
        fits = pw >= 120 and ph >= 70
        self.plots = [
            Plot(
                (12 + i * (pw + gap), plot_top, pw, ph),
                self.duration,
                y_range,
                title,
                y_step=tick_step(y_range),
                color=color,
                text_scale=font_size(size, 100) / 100,
            )
            for i, (title, y_range, color) in enumerate(panels)
            if fits
        ]
        self.world = Tubes(self.ants)

    def top_speed(self, ant: Ant) -> float:
        """The fastest Alfred goes (in/s) until he reaches the end or the scene ends.

        A stepped ant's speed is taken from his own method, run ahead on a copy of his body:
        what he walks at between steps (semi-implicit Euler at dt = 1 s: 1, 2, 3, 4 in/s).
        """
        if not ant.stepped:
            end = min(ant.arrival, self.duration)
            return max(abs(ant.v0), abs(float(kinematics.velocity(ant.v0, ant.a, end))))
        world = World(integrator=ant.world.integrator)
        body = world.add(Body(ant.s0, ant.v0, ant.a))
        fastest, s = abs(ant.v0), ant.s0
        while s < TUBE_LENGTH and world.t < self.duration:
            world.step(self.dt)
            s, fastest = float(body.pos), max(fastest, abs(float(body.vel)))
        return fastest

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
        """Alfred's velocity (in/s) at t: for a stepped ant, the slope he is drawn moving at.

        At the moment he reaches the end he still has the speed he arrived with; after it he
        stands still.
        """
        if t > ant.arrival:
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
            arrow_y = anchor[1] - ant.sprite.get_height() - 9
            size = font_size(self.size, 18)
            if v != 0.0:
                draw_vector(
                    surface,
                    self.camera,
                    (s, self.camera.to_world(0.0, arrow_y)[1]),
                    v,
                    self.arrow_seconds,
                    VELOCITY,
                    label=self.speed_label(ant, t, v),
                    label_side=0,
                    label_size=size,
                )
            else:
                # No arrow to draw: say so, where it would be.
                still = "v = 0: at the end" if t > ant.arrival else "v = 0 in/s"
                draw_text(surface, still, (anchor[0], arrow_y), size, VELOCITY, "midleft")
            draw_sprite(surface, ant.sprite, anchor, "midbottom")
        self.draw_plots(surface, t)

    def speed_label(self, ant: Ant, t: float, v: float) -> str:
        """The words by his velocity arrow: v, and for a stepped ant, which moment's it is.

        Semi-implicit Euler moves each step at the velocity it has at the step's end, so the
        ant the lesson lets go from rest at t = 0 walks the first second at v(1 s) = 1 in/s.
        """
        if not ant.stepped:
            return f"v = {fmt(v, 1)} in/s"
        history = ant.history
        # The step he is drawn walking (as _stepped_at finds it) ends at t1.
        t1 = next(
            (b[0] for a, b in zip(history, history[1:], strict=False) if a[0] <= t <= b[0]),
            ant.world.t,
        )
        return f"v({number(t1)} s) = {fmt(v, 1)} in/s"

    def draw_background(self, surface: pygame.Surface, t: float, clock: str = "") -> None:
        """Paper, title, the time (or ``clock``), the tubes with their names and the ruler."""
        surface.fill(PAPER)
        size = self.size
        big, small = font_size(size, 24), font_size(size, 17)
        draw_text(surface, self.title, (12, 8), big, INK)
        draw_text(surface, self.formula, (12, 10 + big), small, MUTED)
        draw_text(
            surface,
            clock or f"t = {t:.2f} s",
            (size[0] - 12, 8),
            font_size(size, 26),
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
            size=font_size(size, 16),
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
            lines.append((f"{prefix}area = {fmt(walked, 1)} in", ant.color if prefix else VELOCITY))
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
        self.draw_background(surface, t_end, f"Alfred every {number(step)} s" if step else "")
        label_size = font_size(self.size, 16)
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
                label = ", ".join(number(t) for t in ts) + (" s" if last else "")
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


def tick_step(limits: tuple[float, float]) -> float:
    """Tick spacing that gives about 3 to 6 numbered ticks over the range ``limits``."""
    span = limits[1] - limits[0]
    for step in (0.5, 1.0, 2.0, 5.0, 10.0):
        if span / step <= 6:
            return step
    return 20.0


def ant_1d(world: World, s0: float, v0: float, a: float, **kw: object) -> Ant:
    """An Ant added to ``world`` at s0 (in), v0 (in/s), a (in/s^2); ``kw`` as :class:`Ant`."""
    body = world.add(Body(s0, v0, a))
    ant = Ant(body=body, world=world, s0=s0, v0=v0, a=a, **kw)  # type: ignore[arg-type]
    if not ant.stepped:
        # The closed form says when he reaches the end (for the sprint: t^2 / 2 = 10 in at
        # t = sqrt(20) s); a stepped ant's arrival is seen as his world steps.
        ant.arrival = kinematics.time_to_reach(s0, v0, a, TUBE_LENGTH)
    return ant
