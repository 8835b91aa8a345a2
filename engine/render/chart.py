"""A log-log chart panel drawn with pygame: decade ticks, lines with markers, marks off the top.

Made for the work-precision chart (error against cost) and the throughput chart (cost per
body-step against the number of bodies), where the quantities span many powers of ten, so
each axis is ``log10`` of the value and every power of ten gets a grid line.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pygame

from engine.render import marks
from engine.render.draw import GRID, INK, MUTED, Color, draw_text, font, ink

__all__ = ["LogLogChart", "decade_range", "draw_power_of_ten", "draw_legend"]

#: Height (px) of the strip above the plotting area where points with no finite value go.
TOP_STRIP = 16


def decade_range(values: Sequence[float], pad: float = 0.0) -> tuple[int, int]:
    """(lo, hi): the powers of ten that enclose the finite positive ``values`` (10^lo..10^hi)."""
    vals = [v for v in values if v > 0 and math.isfinite(v)]
    if not vals:
        return (0, 1)
    lo = math.floor(math.log10(min(vals)) - pad)
    hi = math.ceil(math.log10(max(vals)) + pad)
    return (lo, hi if hi > lo else lo + 1)


def draw_power_of_ten(
    surface: pygame.Surface,
    exponent: int,
    pos: tuple[float, float],
    size: int = 16,
    color: Color = MUTED,
    anchor: str = "midtop",
) -> pygame.Rect:
    """Write 10^exponent as "10" with a raised exponent; ``anchor`` places the whole label."""
    if exponent == 0:
        base, exp = font(size).render("1", True, color), None
    elif exponent == 1:
        base, exp = font(size).render("10", True, color), None
    else:
        base = font(size).render("10", True, color)
        exp = font(max(8, size * 3 // 4)).render(str(exponent).replace("-", "\u2212"), True, color)
    width = base.get_width() + (exp.get_width() + 1 if exp else 0)
    height = base.get_height() + (size // 4 if exp else 0)
    rect = pygame.Rect(0, 0, width, height)
    setattr(rect, anchor, (round(pos[0]), round(pos[1])))
    surface.blit(base, (rect.left, rect.bottom - base.get_height()))
    if exp is not None:
        surface.blit(exp, (rect.left + base.get_width() + 1, rect.top))
    text = "1" if exponent == 0 else "10" if exponent == 1 else f"10^{exponent}"
    marks.note(surface, "text", rect.inflate(-2, -2), text)
    return rect


class LogLogChart:
    """A panel with log10 axes inside the pixel rectangle ``rect`` (left, top, width, height).

    ``x_decades`` and ``y_decades`` = (lo, hi) set the axes to 10^lo .. 10^hi. ``y_label_every``
    numbers every k-th decade on the y axis (all get grid lines).
    """

    def __init__(
        self,
        rect: tuple[int, int, int, int] | pygame.Rect,
        x_decades: tuple[int, int],
        y_decades: tuple[int, int],
        title: str,
        x_label: str,
        y_label: str,
        y_label_every: int = 1,
        x_label_every: int = 1,
    ) -> None:
        self.rect = pygame.Rect(rect)
        if self.rect.width < 120 or self.rect.height < 120:
            raise ValueError(f"rect must be at least 120x120 px, got {self.rect.size}")
        for name, (lo, hi) in (("x_decades", x_decades), ("y_decades", y_decades)):
            if not hi > lo:
                raise ValueError(f"{name} must be (lo, hi) with hi > lo, got {(lo, hi)}")
        self.x_decades, self.y_decades = x_decades, y_decades
        self.title, self.x_label, self.y_label = title, x_label, y_label
        self.y_label_every, self.x_label_every = max(1, y_label_every), max(1, x_label_every)
        # Room: title and the strip for non-finite points above, numbers left and below.
        self.area = pygame.Rect(
            self.rect.left + 44,
            self.rect.top + 30 + TOP_STRIP,
            self.rect.width - 56,
            self.rect.height - 30 - TOP_STRIP - 44,
        )
        self.strip_y = self.area.top - TOP_STRIP // 2 - 1

    def to_px(self, x: np.ndarray | float, y: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates of the point (x, y) (both > 0) inside the panel, y up."""
        a = self.area
        (x0, x1), (y0, y1) = self.x_decades, self.y_decades
        with np.errstate(divide="ignore", invalid="ignore"):
            fx = (np.log10(np.asarray(x, dtype=float)) - x0) / (x1 - x0)
            fy = (np.log10(np.asarray(y, dtype=float)) - y0) / (y1 - y0)
        return a.left + fx * (a.width - 1), a.bottom - 1 - fy * (a.height - 1)

    def draw_frame(self, surface: pygame.Surface) -> None:
        """Background, a grid line at every power of ten, numbered decades, labels and title."""
        with marks.panel(self.rect):
            marks.note(surface, "panel", self.rect)
            self._draw_frame(surface)

    def _draw_frame(self, surface: pygame.Surface) -> None:
        pygame.draw.rect(surface, (255, 255, 255), self.rect, border_radius=4)
        pygame.draw.rect(surface, GRID, self.rect, 1, border_radius=4)
        a = self.area
        (x0, x1), (y0, y1) = self.x_decades, self.y_decades
        for k in range(x0, x1 + 1):
            px = round(float(self.to_px(10.0**k, 1.0)[0]))
            pygame.draw.line(surface, GRID, (px, a.top), (px, a.bottom - 1), 1)
            if (k - x0) % self.x_label_every == 0:
                draw_power_of_ten(surface, k, (px, a.bottom + 3), 16, MUTED, "midtop")
        for k in range(y0, y1 + 1):
            py = round(float(self.to_px(1.0, 10.0**k)[1]))
            pygame.draw.line(surface, GRID, (a.left, py), (a.right - 1, py), 1)
            if (k - y0) % self.y_label_every == 0:
                # The lowest sits above its line, clear of the x axis's first number.
                anchor = "bottomright" if k == y0 else "midright"
                draw_power_of_ten(surface, k, (a.left - 4, py + (k == y0)), 16, MUTED, anchor)
        pygame.draw.rect(surface, INK, a, 1)
        draw_text(surface, self.title, (self.rect.left + 8, self.rect.top + 6), 22, INK)
        draw_text(surface, self.x_label, (a.centerx, a.bottom + 22), 16, INK, "midtop")
        label = font(16).render(self.y_label, True, INK)
        label = pygame.transform.rotate(label, 90)
        where = label.get_rect(midleft=(self.rect.left + 3, a.centery))
        surface.blit(label, where)
        box = ink(self.y_label, 16)  # turned a quarter left: (x, y) -> (y, width - x)
        turned = pygame.Rect(box.top, where.height - box.right, box.height, box.width)
        marks.note(surface, "text", turned.move(where.topleft), self.y_label)

    def draw_series(
        self,
        surface: pygame.Surface,
        xs: Sequence[float],
        ys: Sequence[float],
        color: Color,
        width: int = 2,
        radius: int = 4,
        hollow: Sequence[bool] | None = None,
    ) -> int:
        """A line through the points, a dot on each; return how many went to the top strip.

        A point whose y is not finite (a run that diverged) is drawn as a cross in the strip
        above the plotting area, at its x, and breaks the line. ``hollow[i]`` draws point i as
        a ring (e.g. a step past the method's stability limit). y below the axis is clamped.
        """
        a = self.area
        floor = 10.0 ** self.y_decades[0]
        clip = surface.get_clip()
        surface.set_clip(self.rect)
        off_top = 0
        try:
            run: list[tuple[float, float]] = []
            runs = [run]
            marks: list[tuple[float, float, bool]] = []
            for i, (x, y) in enumerate(zip(xs, ys, strict=True)):
                if not (x > 0 and math.isfinite(x)):
                    continue
                px = float(self.to_px(x, 1.0)[0])
                if not math.isfinite(y):
                    off_top += 1
                    _cross(surface, (px, self.strip_y), 5, color)
                    run = []
                    runs.append(run)
                    continue
                py = float(self.to_px(x, max(y, floor))[1])
                py = min(max(py, a.top), a.bottom - 1)
                run.append((px, py))
                marks.append((px, py, bool(hollow[i]) if hollow is not None else False))
            surface.set_clip(a.inflate(2 * radius + 2, 2 * radius + 2))
            for r in runs:
                if len(r) >= 2:
                    pygame.draw.lines(surface, color, False, r, width)
            for px, py, ring in marks:
                centre = (round(px), round(py))
                if radius <= 0:
                    continue
                if ring:
                    pygame.draw.circle(surface, (255, 255, 255), centre, radius + 1)
                    pygame.draw.circle(surface, color, centre, radius + 1, 2)
                else:
                    pygame.draw.circle(surface, color, centre, radius)
        finally:
            surface.set_clip(clip)
        return off_top


def _cross(surface: pygame.Surface, centre: tuple[float, float], r: int, color: Color) -> None:
    cx, cy = round(centre[0]), round(centre[1])
    pygame.draw.line(surface, color, (cx - r, cy - r), (cx + r, cy + r), 3)
    pygame.draw.line(surface, color, (cx - r, cy + r), (cx + r, cy - r), 3)


def draw_legend(
    surface: pygame.Surface,
    items: Sequence[tuple[str, Color, int]],
    pos: tuple[int, int],
    max_width: int,
    size: int = 18,
) -> pygame.Rect:
    """Legend entries (label, colour, line width) in rows from ``pos``, wrapping at max_width."""
    x0, y = pos
    x = x0
    row_h = size + 6
    right = x0
    for label, color, width in items:
        text = font(size).render(label, True, INK)
        w = 34 + text.get_width() + 18
        if x + w > x0 + max_width and x > x0:
            x, y = x0, y + row_h
        mid = y + row_h // 2
        pygame.draw.line(surface, color, (x, mid), (x + 26, mid), max(2, width))
        pygame.draw.circle(surface, color, (x + 13, mid), 4)
        surface.blit(text, (x + 34, mid - text.get_height() // 2))
        box = ink(label, size).move(x + 34, mid - text.get_height() // 2)
        marks.note(surface, "text", box, label)
        x += w
        right = max(right, x)
    return pygame.Rect(x0, pos[1], right - x0, y + row_h - pos[1])
