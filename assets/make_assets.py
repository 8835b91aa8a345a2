"""Draw the demos' sprites and save them beside this script: ``python assets/make_assets.py``.

- ``ant.png`` (55x35 px): Alfred, the lesson's ant, side view facing right (+x). His body is
  one flat colour, ``ANT_BODY``, used nowhere else in a frame, so tests can find him by it.
  His feet touch the bottom edge: draw him with anchor "midbottom" on the tube's top.
- ``ant_small.png`` (33x21 px): the same Alfred, smaller.
- ``ant_top.png`` (39x27 px): Alfred seen from above, head to the right (+x), for his walk on a
  sheet of paper: the demo rotates him to face his velocity. The middle of his body (the
  centroid of its ``ANT_BODY`` pixels) is the middle of the image: draw him with anchor
  "center" on his position.
- ``car.png`` (64x32 px): a small side-view car facing right, body colour ``CAR_BODY``,
  wheels touching the bottom edge (anchor "midbottom" on the road).

Each sprite is drawn with plain shapes at four times its size and scaled down smoothly, so the
edges are soft while the inside of each part keeps its exact colour. The PNGs are committed so
the demos run without this script; rerun it after changing a sprite.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pygame  # noqa: E402

HERE = Path(__file__).resolve().parent
SUPER = 4  # drawn at 4x, then scaled down

ANT_SIZE = (55, 35)
ANT_SMALL_SIZE = (33, 21)
ANT_TOP_SIZE = (39, 27)
ANT_BODY = (156, 66, 33)  # Alfred's unique colour: head, thorax and abdomen
ANT_DARK = (62, 36, 24)  # legs, antennae, waist
ANT_EYE = (255, 255, 255)

CAR_SIZE = (64, 32)
CAR_BODY = (196, 42, 54)  # the car's unique colour
CAR_TRIM = (120, 20, 30)
CAR_GLASS = (170, 214, 236)
TYRE = (30, 30, 34)
HUB = (175, 178, 184)


def _canvas(size: tuple[int, int]) -> pygame.Surface:
    surface = pygame.Surface((size[0] * SUPER, size[1] * SUPER), pygame.SRCALPHA)
    surface.fill((0, 0, 0, 0))
    return surface


def _finish(big: pygame.Surface, size: tuple[int, int]) -> pygame.Surface:
    return pygame.transform.smoothscale(big, size)


def draw_ant(size: tuple[int, int] = ANT_SIZE) -> pygame.Surface:
    """Alfred, side view, facing right, feet on the bottom edge (transparent).

    He is laid out on a 44x28 grid; ``size`` must be a whole multiple of a quarter of it
    (55x35 px by default, 33x21 px for the small one on the sheet of paper).
    """
    s = _canvas(size)
    u = round(SUPER * size[0] / 44)  # canvas pixels per grid unit
    ground = size[1] * SUPER - 1
    # Legs first, behind the body: three pairs from the thorax, bent at the knee.
    for hip_x, knee_dx, foot_dx in ((21, -5, -9), (23, 0, 0), (25, 5, 9)):
        hip = (hip_x * u, 15 * u)
        knee = ((hip_x + knee_dx) * u, 19 * u)
        foot = ((hip_x + foot_dx) * u, ground)
        pygame.draw.lines(s, ANT_DARK, False, [hip, knee, foot], 2 * u)
    # Antennae from the head, up and forward.
    pygame.draw.lines(s, ANT_DARK, False, [(36 * u, 9 * u), (39 * u, 2 * u), (43 * u, 1 * u)], u)
    pygame.draw.lines(s, ANT_DARK, False, [(35 * u, 9 * u), (36 * u, 2 * u), (39 * u, 0)], u)
    # Waists, then abdomen (back), thorax (middle), head (front).
    pygame.draw.line(s, ANT_DARK, (14 * u, 14 * u), (34 * u, 13 * u), 2 * u)
    pygame.draw.ellipse(s, ANT_BODY, pygame.Rect(1 * u, 7 * u, 17 * u, 13 * u))
    pygame.draw.ellipse(s, ANT_BODY, pygame.Rect(18 * u, 10 * u, 10 * u, 7 * u))
    pygame.draw.ellipse(s, ANT_BODY, pygame.Rect(30 * u, 7 * u, 11 * u, 10 * u))
    # An eye: white with a dark pupil, looking ahead.
    pygame.draw.circle(s, ANT_EYE, (37 * u, 11 * u), int(2.2 * u))
    pygame.draw.circle(s, ANT_DARK, (38 * u, 11 * u), u)
    return _finish(s, size)


def draw_ant_top() -> pygame.Surface:
    """Alfred seen from above, head to the right (+x), body centred (39x27 px, transparent).

    Drawn like ant_small (0.75 px per grid unit) in grid units around the middle of the image:
    x forward along his axis, y to one side (he is symmetric, so the sign of y does not matter).
    """
    s = _canvas(ANT_TOP_SIZE)
    u = SUPER * 0.75  # canvas pixels per grid unit
    cx, cy = ANT_TOP_SIZE[0] * SUPER / 2, ANT_TOP_SIZE[1] * SUPER / 2

    def at(x: float, y: float) -> tuple[int, int]:
        return round(cx + x * u), round(cy + y * u)

    def oval(x0: float, x1: float, width: float) -> pygame.Rect:
        # An ellipse on the axis from x0 (back) to x1 (front), ``width`` units across.
        left, top = at(x0, -width / 2)
        right, bottom = at(x1, width / 2)
        return pygame.Rect(left, top, right - left, bottom - top)

    # The parts: abdomen [-15, 0] x 11 units, thorax [1, 12] x 6, head [13, 22] x 8. Their
    # ellipse areas (pi/4 * length * width) are 165, 66 and 72 times pi/4, centred at x = -7.5,
    # 6.5 and 17.5, so the whole body's centroid is at
    # (165 * -7.5 + 66 * 6.5 + 72 * 17.5) / 303 = (-1237.5 + 429 + 1260) / 303 = +1.5 units.
    # But tests find him by his exact ANT_BODY pixels, and the soft edges and the eyes take a
    # bigger share of the thin head and thorax than of the abdomen: the exact pixels' centroid
    # lies about 1.8 units (1.4 px) behind the area's, so this layout puts it in the middle of
    # the image, 0.2 px off (tests/test_alfred.py checks it to within half a pixel).
    # Legs first, behind the body: three pairs from the thorax, each bent at the knee; the
    # front pair reaches forward, the middle pair out to the side, the hind pair backward.
    legs = (((9, 2), (13, 7), (18, 11)), ((6, 2), (7, 8), (5, 12)), ((3, 2), (-2, 7), (-9, 11)))
    for side in (-1, 1):
        for leg in legs:
            pygame.draw.lines(s, ANT_DARK, False, [at(x, side * y) for x, y in leg], round(1.5 * u))
        # An antenna from the front of the head: out, then bent forward at the elbow.
        antenna = [at(20, side * 1.5), at(22, side * 6), at(24.5, side * 7.5)]
        pygame.draw.lines(s, ANT_DARK, False, antenna, round(u))
    # The waist and the neck join the parts; then abdomen (back), thorax, head (front).
    pygame.draw.line(s, ANT_DARK, at(-2, 0), at(15, 0), round(2 * u))
    pygame.draw.ellipse(s, ANT_BODY, oval(-15, 0, 11))
    pygame.draw.ellipse(s, ANT_BODY, oval(1, 12, 6))
    pygame.draw.ellipse(s, ANT_BODY, oval(13, 22, 8))
    # Two eyes, one each side of the head, looking ahead.
    for side in (-1, 1):
        pygame.draw.circle(s, ANT_DARK, at(19, side * 3), round(1.2 * u))
    return _finish(s, ANT_TOP_SIZE)


def draw_car() -> pygame.Surface:
    """A small car, side view, facing right, wheels on the bottom edge (64x32 px, transparent)."""
    s = _canvas(CAR_SIZE)
    u = SUPER
    # Body: a long lower box with rounded ends, a cabin on top.
    pygame.draw.rect(s, CAR_BODY, pygame.Rect(1 * u, 12 * u, 62 * u, 12 * u), border_radius=4 * u)
    cabin = [(14 * u, 13 * u), (21 * u, 3 * u), (42 * u, 3 * u), (51 * u, 13 * u)]
    pygame.draw.polygon(s, CAR_BODY, cabin)
    # Windows: two panes split by a pillar.
    pygame.draw.polygon(
        s, CAR_GLASS, [(18 * u, 12 * u), (23 * u, 5 * u), (31 * u, 5 * u), (31 * u, 12 * u)]
    )
    pygame.draw.polygon(
        s, CAR_GLASS, [(34 * u, 12 * u), (34 * u, 5 * u), (41 * u, 5 * u), (47 * u, 12 * u)]
    )
    # Trim line, a door seam, a headlight (front, right) and a tail light (back, left).
    pygame.draw.line(s, CAR_TRIM, (3 * u, 17 * u), (61 * u, 17 * u), u)
    pygame.draw.line(s, CAR_TRIM, (32 * u, 13 * u), (32 * u, 22 * u), u // 2)
    pygame.draw.rect(s, (255, 230, 140), pygame.Rect(59 * u, 14 * u, 4 * u, 3 * u), border_radius=u)
    pygame.draw.rect(s, CAR_TRIM, pygame.Rect(1 * u, 14 * u, 3 * u, 3 * u), border_radius=u)
    # Wheels: tyres touching the bottom edge, grey hubs.
    for cx in (15, 49):
        centre = (cx * u, (CAR_SIZE[1] - 7) * u)
        pygame.draw.circle(s, TYRE, centre, 7 * u)
        pygame.draw.circle(s, HUB, centre, 3 * u)
    return _finish(s, CAR_SIZE)


def main(folder: Path = HERE) -> list[Path]:
    """Draw every sprite and save it as a PNG in ``folder``; return the paths written."""
    pygame.display.init()
    written = []
    sprites = (
        ("ant.png", draw_ant),
        ("ant_small.png", lambda: draw_ant(ANT_SMALL_SIZE)),
        ("ant_top.png", draw_ant_top),
        ("car.png", draw_car),
    )
    for name, draw in sprites:
        path = folder / name
        pygame.image.save(draw(), str(path))
        written.append(path)
    return written


if __name__ == "__main__":
    for path in main(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE):
        print(f"wrote {path}")
