"""What every Alfred scene shares: his sprites, and type and numbers sized for the canvas."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pygame

#: Where the sprites live (made by assets/make_assets.py).
ASSETS = Path(__file__).resolve().parents[2] / "assets"
#: Alfred's body colour in ant.png, used nowhere else in a frame (tests find him by it).
ANT_BODY = (156, 66, 33)
#: The body colour of the second ant in the sprint (semi-implicit Euler's Alfred).
EULER_ANT_BODY = (222, 140, 10)


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


def sprite_zoom(size: tuple[int, int]) -> int:
    """How many times to enlarge Alfred on a ``size`` px canvas: he is drawn for 640x360."""
    return max(1, int(min(size[0] / 640, size[1] / 360) + 0.25))


def font_size(size: tuple[int, int], px: int) -> int:
    """Type size (px) on a ``size`` px canvas for ``px`` at 640x360; never below 10 px."""
    k = min(size[0] / 640, size[1] / 360)
    return max(10, round(px * k))


def fmt(value: float, digits: int = 2) -> str:
    """``value`` with ``digits`` decimals and a true minus sign; never "-0.00"."""
    text = f"{value:.{digits}f}"
    return text.replace("-", "\u2212") if value < -0.5 * 10**-digits else text.lstrip("-")


def number(value: float) -> str:
    """``value`` with at most 2 decimals and no trailing zeros: 0.5 -> "0.5", 2.0 -> "2"."""
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return text or "0"
