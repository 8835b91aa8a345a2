"""The camera: world coordinates (inches or metres, y up) to pixels (y down) and back."""

from __future__ import annotations

import math
from typing import Any, overload

import numpy as np

from engine.checks import real

__all__ = ["Camera"]


def _four(value: Any, name: str) -> tuple[float, float, float, float]:
    """Four finite floats from ``value``; TypeError / ValueError naming ``name`` otherwise."""
    try:
        a, b, c, d = value
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be four numbers, got {value!r}") from None
    return real(a, name), real(b, name), real(c, name), real(d, name)


class Camera:
    """Maps world points to pixels by a scale and an origin; works on floats and numpy arrays.

    ``scale`` is pixels per world unit (e.g. 50 px per inch); ``origin`` is the pixel where the
    world point (0, 0) lands. World y points up and pixel y points down, so

        px = origin_x + scale * x
        py = origin_y - scale * y

    >>> cam = Camera(scale=50.0, origin=(40.0, 300.0))
    >>> cam.to_px(2.0, 1.0)
    (140.0, 250.0)
    >>> cam.to_world(140.0, 250.0)
    (2.0, 1.0)
    """

    __slots__ = ("scale", "origin")

    def __init__(self, scale: float, origin: tuple[float, float] = (0.0, 0.0)) -> None:
        scale = real(scale, "scale")
        if not scale > 0.0:
            raise ValueError(f"scale must be a positive finite pixels per unit, got {scale}")
        self.scale = scale
        try:
            ox, oy = origin
        except (TypeError, ValueError):
            raise TypeError(f"origin must be a pixel pair (x, y), got {origin!r}") from None
        self.origin = (real(ox, "origin x"), real(oy, "origin y"))

    @classmethod
    def fit(
        cls,
        world: tuple[float, float, float, float],
        rect: tuple[float, float, float, float],
    ) -> Camera:
        """Largest camera that shows the world box ``(x0, y0, x1, y1)`` inside the pixel ``rect``.

        ``rect`` is ``(left, top, width, height)`` in pixels; the world box is centred in it and
        keeps its aspect ratio (one scale for both axes, so circles stay round).
        """
        x0, y0, x1, y1 = _four(world, "world box (x0, y0, x1, y1)")
        left, top, width, height = _four(rect, "rect (left, top, width, height)")
        if x1 <= x0 or y1 <= y0:
            raise ValueError(f"world box must have x1 > x0 and y1 > y0, got {world}")
        if width <= 0 or height <= 0:
            raise ValueError(f"rect must have a positive width and height, got {rect}")
        scale = min(width / (x1 - x0), height / (y1 - y0))
        # Centre: the box's middle lands on the rect's middle.
        ox = left + width / 2 - scale * (x0 + x1) / 2
        oy = top + height / 2 + scale * (y0 + y1) / 2
        return cls(scale, (ox, oy))

    @overload
    def to_px(self, x: float, y: float = 0.0) -> tuple[float, float]: ...
    @overload
    def to_px(self, x: np.ndarray, y: Any = 0.0) -> tuple[np.ndarray, np.ndarray]: ...

    def to_px(self, x: Any, y: Any = 0.0) -> tuple[Any, Any]:
        """Pixel coordinates (floats) of the world point (x, y); x, y may be numpy arrays."""
        return self.origin[0] + self.scale * x, self.origin[1] - self.scale * y

    def point(self, p: Any) -> tuple[int, int]:
        """Whole pixel nearest to a world point: a float (1D, on y = 0), Vector or (x, y) pair."""
        try:
            if isinstance(p, (int, float, np.floating, np.integer)):
                x, y = float(p), 0.0
            else:
                x, y = float(p[0]), float(p[1])
            px, py = self.to_px(x, y)
            # floor(v + 0.5): halves always round the same way (round() goes to even).
            return math.floor(px + 0.5), math.floor(py + 0.5)
        except (TypeError, ValueError, LookupError, OverflowError):
            raise ValueError(
                f"point p must be a finite world point, a number (1D) or an (x, y) pair, "
                f"landing within the float range in pixels, got {p!r}"
            ) from None

    def points(self, xy: Any) -> np.ndarray:
        """Pixel coordinates, shape (N, 2) floats, of world points given as an (N, 2) array."""
        arr = np.asarray(xy, dtype=float)
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise ValueError(f"xy must have shape (N, 2), got {arr.shape}")
        out = np.empty_like(arr)
        out[:, 0] = self.origin[0] + self.scale * arr[:, 0]
        out[:, 1] = self.origin[1] - self.scale * arr[:, 1]
        return out

    def to_world(self, px: Any, py: Any) -> tuple[Any, Any]:
        """World coordinates of the pixel (px, py): the inverse of :meth:`to_px`."""
        return (px - self.origin[0]) / self.scale, (self.origin[1] - py) / self.scale

    def length(self, world_length: float) -> float:
        """Pixels spanned by a world length."""
        return self.scale * world_length

    def __repr__(self) -> str:
        return f"Camera(scale={self.scale!r}, origin={self.origin!r})"
