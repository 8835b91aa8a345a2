"""A small live plot panel: a quantity against time, drawn in step with the motion.

The lesson's figures 7 to 9 plot Alfred's position s(t), velocity v(t) and acceleration a(t)
against time and shade the area under v(t), which is the displacement. :class:`Plot` draws one
such panel into a pixel rectangle: a frame with ticks, the curve up to "now", a marker on the
current value and, if asked, the shaded area between the curve and zero.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pygame

from engine.render import marks
from engine.render.draw import GRID, INK, MUTED, Color, draw_text, font, ink, tick_label, ticks
from engine.render.marks import panel

__all__ = ["Plot"]


class Plot:
    """A panel plotting y against t (s) inside the pixel rectangle ``rect`` (left, top, w, h).

    ``t_max`` (s) and ``y_range`` = (y_min, y_max) fix the axes so the panel does not jump as the
    curve grows; ``t_step`` and ``y_step`` space the numbered ticks; ``title`` is written at the
    top left (e.g. "v(t)  in/s"); ``text_scale`` enlarges the lettering for big canvases.
    """

    def __init__(
        self,
        rect: tuple[int, int, int, int] | pygame.Rect,
        t_max: float,
        y_range: tuple[float, float],
        title: str,
        t_step: float = 1.0,
        y_step: float = 1.0,
        color: Color = INK,
        text_scale: float = 1.0,
    ) -> None:
        self.rect = pygame.Rect(rect)
        if self.rect.width < 40 or self.rect.height < 40:
            raise ValueError(f"rect must be at least 40x40 px, got {self.rect.size}")
        if not t_max > 0:
            raise ValueError(f"t_max must be > 0 s, got {t_max}")
        if not y_range[1] > y_range[0]:
            raise ValueError(f"y_range must have y_max > y_min, got {y_range}")
        self.t_max = float(t_max)
        self.y_min, self.y_max = float(y_range[0]), float(y_range[1])
        self.title = title
        self.t_step = float(t_step)
        self.y_step = float(y_step)
        self.color = color
        self.text_scale = float(text_scale)
        k = self.text_scale
        self.number_size = round(15 * k)
        self.title_size = round(18 * k)
        # The plotting area: room on the left for y numbers (the widest, 4 px from the axis
        # and 3 px from the panel's edge), below for t numbers, above for the title.
        numbers = [tick_label(float(y)) for y in self._y_ticks()]
        size = self.number_size
        widest = max((font(size).size(t)[0] - ink(t, size).left for t in numbers), default=0)
        left = max(round(26 * k), widest + 4 + 3)
        # The top y number, centred on the top grid line, stays a pixel under the title.
        top_number = tick_label(float(self._y_ticks()[-1])) if len(self._y_ticks()) else "0"
        half = font(size).size(top_number)[1] // 2 - ink(top_number, size).top
        top = max(round(20 * k), 3 + ink(title, self.title_size).bottom + 1 + half)
        self.area = pygame.Rect(
            self.rect.left + left,
            self.rect.top + top,
            self.rect.width - left - round(8 * k),
            self.rect.height - top - round(18 * k),
        )

    def _y_ticks(self) -> np.ndarray:
        return ticks(self.y_min, self.y_max, self.y_step)

    def to_px(self, t: np.ndarray | float, y: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates of the point (t s, y) inside the panel (y up)."""
        a = self.area
        px = a.left + (np.asarray(t, dtype=float) / self.t_max) * (a.width - 1)
        frac = (np.asarray(y, dtype=float) - self.y_min) / (self.y_max - self.y_min)
        py = a.bottom - 1 - frac * (a.height - 1)
        return px, py

    def draw_frame(self, surface: pygame.Surface) -> None:
        """The panel's background, grid, axes, tick numbers and title."""
        with panel(self.rect):
            marks.note(surface, "panel", self.rect)
            self._draw_frame(surface)

    def _draw_frame(self, surface: pygame.Surface) -> None:
        pygame.draw.rect(surface, (255, 255, 255), self.rect, border_radius=4)
        pygame.draw.rect(surface, GRID, self.rect, 1, border_radius=4)
        a = self.area
        for t in ticks(0.0, self.t_max, self.t_step):
            px = round(float(self.to_px(t, 0.0)[0]))
            pygame.draw.line(surface, GRID, (px, a.top), (px, a.bottom - 1), 1)
            draw_text(
                surface, tick_label(float(t)), (px, a.bottom + 2), self.number_size, MUTED, "midtop"
            )
        for y in self._y_ticks():
            py = round(float(self.to_px(0.0, y)[1]))
            pygame.draw.line(surface, GRID, (a.left, py), (a.right - 1, py), 1)
            draw_text(
                surface, tick_label(float(y)), (a.left - 4, py), self.number_size, MUTED, "midright"
            )
        # The axes: t along y = 0 (or the bottom if 0 is out of range), y along t = 0.
        zero = min(max(0.0, self.y_min), self.y_max)
        py0 = round(float(self.to_px(0.0, zero)[1]))
        pygame.draw.line(surface, INK, (a.left, py0), (a.right - 1, py0), 1)
        pygame.draw.line(surface, INK, (a.left, a.top), (a.left, a.bottom - 1), 1)
        draw_text(
            surface,
            self.title,
            (self.rect.left + 6, self.rect.top + 3),
            self.title_size,
            self.color,
        )
        draw_text(
            surface,
            "t (s)",
            (self.rect.right - 5, self.rect.top + 4),
            self.number_size,
            MUTED,
            "topright",
        )

    def draw_curve(
        self,
        surface: pygame.Surface,
        ts: Sequence[float] | np.ndarray,
        ys: Sequence[float] | np.ndarray,
        color: Color | None = None,
        width: int = 2,
        shade: bool = False,
        marker: bool = True,
    ) -> None:
        """Draw the samples (ts[i] s, ys[i]) as a line; ``shade`` fills down to y = 0.

        The shaded area is the integral of y over t so far: under v(t) it is the displacement.
        ``marker`` puts a dot on the last sample, the value "now".
        """
        color = self.color if color is None else color
        t = np.asarray(ts, dtype=float)
        y = np.clip(np.asarray(ys, dtype=float), self.y_min, self.y_max)
        if len(t) == 0:
            return
        px, py = self.to_px(t, y)
        points = list(zip(px.tolist(), py.tolist(), strict=True))
        clip = surface.get_clip()
        surface.set_clip(self.area.clip(clip) if clip else self.area)
        try:
            if shade and len(points) >= 2:
                zero = float(self.to_px(0.0, min(max(0.0, self.y_min), self.y_max))[1])
                polygon = [(points[0][0], zero), *points, (points[-1][0], zero)]
                light = tuple(round(255 - (255 - c) * 0.28) for c in color)
                pygame.draw.polygon(surface, light, polygon)
            if len(points) >= 2:
                pygame.draw.lines(surface, color, False, points, width)
            if marker:
                last = (round(points[-1][0]), round(points[-1][1]))
                pygame.draw.circle(surface, color, last, 4)
        finally:
            surface.set_clip(clip)

    def draw(
        self,
        surface: pygame.Surface,
        ts: Sequence[float] | np.ndarray,
        ys: Sequence[float] | np.ndarray,
        shade: bool = False,
    ) -> None:
        """The frame and one curve in the panel's colour: the usual one-quantity plot."""
        self.draw_frame(surface)
        self.draw_curve(surface, ts, ys, shade=shade)
