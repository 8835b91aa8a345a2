"""Drawing helpers that work on any pygame Surface: bodies, arrows, trails, labels, rulers, grids.

Each helper takes the surface to draw on and, where world coordinates are involved, a
:class:`~engine.render.camera.Camera`. Nothing here keeps state between calls except caches of
fonts by size and of rendered text (tick numbers repeat every frame). Colours are RGB tuples;
the palette below is the Okabe-Ito set, which stays distinct for colour-blind readers and on a
projector.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable
from typing import Any, cast

import numpy as np
import pygame

from engine.render import marks
from engine.render.camera import Camera

__all__ = [
    "ACCELERATION",
    "EULER",
    "EXACT",
    "GRID",
    "INK",
    "MUTED",
    "PAPER",
    "POSITION",
    "VELOCITY",
    "Color",
    "draw_arrow",
    "draw_disc",
    "draw_dot",
    "draw_grid",
    "draw_ruler",
    "draw_sprite",
    "draw_text",
    "draw_trail",
    "draw_vector",
    "font",
    "tick_label",
    "ticks",
]

Color = tuple[int, int, int]

PAPER: Color = (250, 248, 242)  #: background, a warm white
INK: Color = (34, 34, 40)  #: text and outlines
MUTED: Color = (120, 120, 128)  #: secondary text, minor ticks
GRID: Color = (226, 224, 216)  #: grid lines
POSITION: Color = (0, 158, 115)  #: position vectors and s(t), bluish green
VELOCITY: Color = (0, 114, 178)  #: velocity arrows and v(t), blue
ACCELERATION: Color = (213, 94, 0)  #: acceleration arrows and a(t), vermillion
EULER: Color = (230, 159, 0)  #: a numerical integrator's answer, orange
EXACT: Color = (204, 121, 167)  #: the exact (closed-form) answer, reddish purple


@functools.lru_cache(maxsize=32)
def font(size: int) -> pygame.font.Font:
    """pygame's built-in font at ``size`` pixels (works headless; cached per size)."""
    if not pygame.font.get_init():
        pygame.font.init()
    return pygame.font.Font(None, size)


@functools.lru_cache(maxsize=1024)
def _rendered(
    text: str, size: int, color: tuple[int, ...], background: tuple[int, ...] | None
) -> pygame.Surface:
    # Tick numbers, titles and units repeat every frame: render each once. The cached images
    # are only ever blitted, never drawn on.
    return font(size).render(text, True, color, background)


@functools.lru_cache(maxsize=1024)
def ink(text: str, size: int) -> pygame.Rect:
    """The box of the pixels ``text`` inks at ``size``, within its rendered image (px).

    The font's own box is a pixel or two wider and taller than the letters; the marks of a
    frame (``engine.render.marks``) hold this tighter one, so lines set close but clear of
    each other do not count as touching.
    """
    image = font(size).render(text, True, (0, 0, 0))
    boxes = cast(list[pygame.Rect], pygame.mask.from_surface(image).get_bounding_rects())
    if not boxes:
        return pygame.Rect(0, 0, 0, 0)
    return boxes[0].unionall(boxes[1:])


def draw_text(
    surface: pygame.Surface,
    text: str,
    pos: tuple[float, float],
    size: int = 20,
    color: Color = INK,
    anchor: str = "topleft",
    background: Color | None = None,
) -> pygame.Rect:
    """Draw ``text`` with its ``anchor`` (a Rect attribute such as "midbottom") at pixel ``pos``."""
    image = _rendered(text, size, tuple(color), None if background is None else tuple(background))
    rect = image.get_rect()
    if not hasattr(rect, anchor) or anchor in ("size", "width", "height", "w", "h"):
        raise ValueError(f"anchor must be a pygame.Rect position such as 'center', got {anchor!r}")
    setattr(rect, anchor, (round(pos[0]), round(pos[1])))
    surface.blit(image, rect)
    box = rect if background is not None else ink(text, size).move(rect.topleft)
    marks.note(surface, "text", box, text)
    return rect


def draw_dot(
    surface: pygame.Surface,
    pos: tuple[float, float],
    radius: float = 5,
    color: Color = INK,
    outline: Color | None = None,
) -> None:
    """A filled circle of ``radius`` px centred on the pixel ``pos`` (a body drawn as a dot)."""
    centre = (round(pos[0]), round(pos[1]))
    pygame.draw.circle(surface, color, centre, radius)
    if outline is not None:
        pygame.draw.circle(surface, outline, centre, radius, 1)


def draw_disc(
    surface: pygame.Surface,
    camera: Camera,
    centre: tuple[float, float],
    radius: float,
    angle: float | None = 0.0,
    color: Color = VELOCITY,
    outline: Color = INK,
) -> None:
    """A disc of ``radius`` (world units) about the world point ``centre``, filled with
    ``color`` and outlined in ``outline``, with a radius line in ``outline`` at ``angle``
    (rad, counter-clockwise from +x, as ``Body.angle``) so that a roll is seen.

    The line runs from the hub (a few pixels out, so the centre keeps the disc's colour: a
    test or a game finds a body by the colour at its centre) to the rim; it is about 2 px wide
    on a 360 px tall canvas, wider on bigger ones, and left out on a disc under 4 px across
    its radius. ``angle=None`` draws no line (a disc that does not turn). A disc under 1.5 px
    is drawn as a dot of 2 px.
    """
    cx, cy = float(centre[0]), float(centre[1])
    px, py = camera.to_px(cx, cy)
    at = (math.floor(px + 0.5), math.floor(py + 0.5))
    r_px = radius * camera.scale
    if r_px < 1.5:
        pygame.draw.circle(surface, color, at, 2)
        return
    pygame.draw.circle(surface, color, at, round(r_px))
    pygame.draw.circle(surface, outline, at, round(r_px), 1)
    if angle is None or r_px < 4:
        return
    width = max(1, min(round(2 * surface.get_height() / 360), round(r_px / 4)))
    c, s = math.cos(angle), math.sin(angle)
    hub = width + 1.0
    # Pixels have y down: the world's counter-clockwise angle turns the other way on screen.
    start = (px + hub * c, py - hub * s)
    end = (px + r_px * c, py - r_px * s)
    pygame.draw.line(surface, outline, start, end, width)


def draw_sprite(
    surface: pygame.Surface,
    image: pygame.Surface,
    pos: tuple[float, float],
    anchor: str = "center",
    alpha: int | None = None,
) -> pygame.Rect:
    """Blit ``image`` with its ``anchor`` point (e.g. "midbottom": the feet) on the pixel ``pos``.

    The image is not scaled or rotated, so its pixels land unchanged (tests find a sprite by a
    colour it alone uses). ``alpha`` (0 to 255) fades the whole sprite, e.g. in a strobe image.
    """
    rect = image.get_rect()
    setattr(rect, anchor, (math.floor(pos[0] + 0.5), math.floor(pos[1] + 0.5)))
    if alpha is not None and alpha < 255:
        faded = image.copy()
        # Multiply every pixel's alpha by alpha/255, keeping the colours.
        faded.fill((255, 255, 255, max(0, int(alpha))), special_flags=pygame.BLEND_RGBA_MULT)
        image = faded
    surface.blit(image, rect)
    return rect


def draw_arrow(
    surface: pygame.Surface,
    start: tuple[float, float],
    end: tuple[float, float],
    color: Color,
    width: float = 3,
    head: float = 11,
) -> None:
    """An arrow from pixel ``start`` to pixel ``end``: shaft ``width`` px wide, head ``head`` px.

    Arrows shorter than their head are drawn as a head alone, scaled down; a zero-length arrow
    draws nothing (there is no direction to show).
    """
    sx, sy = float(start[0]), float(start[1])
    dx, dy = float(end[0]) - sx, float(end[1]) - sy
    length = math.hypot(dx, dy)
    if length < 1e-9:
        return
    ux, uy = dx / length, dy / length  # unit vector along the arrow
    nx, ny = -uy, ux  # its normal
    head_len = min(head, length)
    half_head = 0.5 * head_len
    bx, by = sx + dx - ux * head_len, sy + dy - uy * head_len  # where the head's base sits
    w = 0.5 * width
    if length > head_len:
        shaft = [
            (sx + nx * w, sy + ny * w),
            (bx + nx * w, by + ny * w),
            (bx - nx * w, by - ny * w),
            (sx - nx * w, sy - ny * w),
        ]
        pygame.draw.polygon(surface, color, shaft)
    tip = [
        (sx + dx, sy + dy),
        (bx + nx * half_head, by + ny * half_head),
        (bx - nx * half_head, by - ny * half_head),
    ]
    pygame.draw.polygon(surface, color, tip)
    pygame.draw.aalines(surface, color, True, tip)
    xs, ys = [p[0] for p in tip], [p[1] for p in tip]
    left, top = math.floor(min(xs)), math.floor(min(ys))
    head_box = pygame.Rect(left, top, math.ceil(max(xs)) - left + 1, math.ceil(max(ys)) - top + 1)
    marks.note(surface, "arrowhead", head_box)


def _as_xy(value: Any) -> tuple[float, float]:
    # A 1D quantity (a float) points along x; a Vector or pair has both components.
    if isinstance(value, (int, float, np.floating, np.integer)):
        return float(value), 0.0
    return float(value[0]), float(value[1])


def draw_vector(
    surface: pygame.Surface,
    camera: Camera,
    tail: Any,
    vector: Any,
    scale: float,
    color: Color,
    label: str | None = None,
    width: float = 3,
    label_side: int = 1,
    label_size: int = 18,
) -> None:
    """Draw a vector quantity (velocity, acceleration) as an arrow from the world point ``tail``.

    ``scale`` is world length per unit of the quantity: a velocity (in/s) drawn with scale 1.0 s
    is an arrow as long as the distance covered in one second. ``tail`` and ``vector`` are floats
    (1D, along x) or Vectors / (x, y) pairs. ``label`` is written beside the arrow's middle, above
    it for ``label_side`` = 1 and below it for -1, or past its tip for 0 (before its tail if the
    tip is too near the surface's edge).
    """
    tx, ty = _as_xy(tail)
    vx, vy = _as_xy(vector)
    start = camera.to_px(tx, ty)
    end = camera.to_px(tx + vx * scale, ty + vy * scale)
    draw_arrow(surface, start, end, color, width)
    if label and label_side == 0:
        rect = pygame.Rect((0, 0), font(label_size).size(label))
        forward = end[0] >= start[0]
        rect.midleft = (round(max(end[0], start[0]) + 6), round(end[1]))
        if not forward or rect.right > surface.get_width():
            rect.midright = (round(min(end[0], start[0]) - 6), round(end[1]))
        if forward and rect.left < 0:
            rect.midleft = (round(end[0] + 6), round(end[1]))
        draw_text(surface, label, rect.topleft, label_size, color)
    elif label:
        dx, dy = end[0] - start[0], end[1] - start[1]
        length = math.hypot(dx, dy)
        if length < 1e-9:
            nx, ny = 0.0, -1.0
        else:
            nx, ny = dy / length, -dx / length  # the normal on the screen's "up" side
            if ny > 0:
                nx, ny = -nx, -ny
        nx, ny = nx * label_side, ny * label_side
        mid = (start[0] + dx / 2 + nx * 14, start[1] + dy / 2 + ny * 14)
        anchor = "midbottom" if label_side > 0 else "midtop"
        draw_text(surface, label, mid, label_size, color, anchor=anchor)


def draw_trail(
    surface: pygame.Surface,
    camera: Camera,
    points: Iterable[Any] | np.ndarray,
    color: Color,
    width: int = 2,
) -> None:
    """A polyline through world points (an (N, 2) array, or Vectors / pairs), e.g. a path so far."""
    arr = np.asarray([_as_xy(p) for p in points] if not isinstance(points, np.ndarray) else points)
    if arr.ndim == 1:  # 1D positions: along x at y = 0
        arr = np.column_stack((arr, np.zeros_like(arr)))
    if len(arr) < 2:
        return
    px = camera.points(arr)
    if width <= 1:
        pygame.draw.aalines(surface, color, False, px.tolist())
    else:
        pygame.draw.lines(surface, color, False, px.tolist(), width)


def ticks(start: float, stop: float, step: float) -> np.ndarray:
    """Multiples of ``step`` in [start, stop], each k * step (no float drift from adding)."""
    first = math.ceil(start / step - 1e-9)
    last = math.floor(stop / step + 1e-9)
    return np.arange(first, last + 1) * step


def tick_label(value: float) -> str:
    """A tick's number as text: "3" rather than "3.0", "0.5" kept, never "-0"."""
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def draw_ruler(
    surface: pygame.Surface,
    camera: Camera,
    x0: float,
    x1: float,
    y: float = 0.0,
    step: float = 1.0,
    minor: int = 4,
    unit: str = "",
    color: Color = INK,
    size: int = 18,
) -> None:
    """A horizontal ruler from world x0 to x1 at height y: ticks every ``step``, numbered below.

    ``minor`` ticks (e.g. 4: quarter inches) go between the numbered ones; ``unit`` is written
    after the last number.
    """
    if step <= 0 or not math.isfinite(step):
        raise ValueError(f"step must be a positive world length, got {step}")
    left, py = camera.to_px(x0, y)
    right, _ = camera.to_px(x1, y)
    py = round(py)
    pygame.draw.line(surface, color, (round(left), py), (round(right), py), 2)
    if minor > 0:
        for x in ticks(x0, x1, step / minor):
            px = round(camera.to_px(float(x), y)[0])
            pygame.draw.line(surface, MUTED, (px, py), (px, py + 5), 1)
    last = None
    for x in ticks(x0, x1, step):
        px = round(camera.to_px(float(x), y)[0])
        pygame.draw.line(surface, color, (px, py), (px, py + 10), 2)
        last = draw_text(surface, tick_label(float(x)), (px, py + 12), size, color, "midtop")
    if unit and last is not None:
        draw_text(surface, unit, (last.right + 4, last.top), size, color, "topleft")


def draw_grid(
    surface: pygame.Surface,
    camera: Camera,
    box: tuple[float, float, float, float],
    step: float = 1.0,
    color: Color = GRID,
    axes: Color | None = MUTED,
    labels: bool = True,
    unit: str = "",
    size: int = 16,
) -> None:
    """Grid lines every ``step`` over the world box (x0, y0, x1, y1), axes through 0, numbered.

    With ``labels`` the x axis is numbered below and the y axis to the left; ``unit`` is
    appended to the last x number.
    """
    x0, y0, x1, y1 = box
    left, top = camera.to_px(x0, y1)
    right, bottom = camera.to_px(x1, y0)
    for x in ticks(x0, x1, step):
        px = round(camera.to_px(float(x))[0])
        pygame.draw.line(surface, color, (px, round(top)), (px, round(bottom)), 1)
    for yv in ticks(y0, y1, step):
        py = round(camera.to_px(0.0, float(yv))[1])
        pygame.draw.line(surface, color, (round(left), py), (round(right), py), 1)
    if axes is None:
        return
    ox, oy = (round(v) for v in camera.to_px(0.0, 0.0))
    if y0 <= 0.0 <= y1:
        pygame.draw.line(surface, axes, (round(left), oy), (round(right), oy), 2)
    if x0 <= 0.0 <= x1:
        pygame.draw.line(surface, axes, (ox, round(top)), (ox, round(bottom)), 2)
    if not labels:
        return
    label_y = min(max(oy, round(top)), round(bottom))
    last = None
    for x in ticks(x0, x1, step):
        if x == 0.0:
            continue
        px = round(camera.to_px(float(x))[0])
        last = draw_text(surface, tick_label(float(x)), (px, label_y + 3), size, MUTED, "midtop")
    if unit and last is not None:
        if last.right + 3 + font(size).size(unit)[0] <= right:
            draw_text(surface, unit, (last.right + 3, last.top), size, MUTED)
        else:  # no room after the last number, within the box: under it
            draw_text(surface, unit, (last.centerx, last.bottom), size, MUTED, "midtop")
    label_x = min(max(ox, round(left)), round(right))
    for yv in ticks(y0, y1, step):
        if yv == 0.0:
            continue
        py = round(camera.to_px(0.0, float(yv))[1])
        draw_text(surface, tick_label(float(yv)), (label_x - 4, py), size, MUTED, "midright")
    draw_text(surface, "0", (label_x - 4, label_y + 3), size, MUTED, "topright")
