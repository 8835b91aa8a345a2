"""Pixel measurements the picture tests share: where a sprite is and which way it points, and
what each drawing helper put on a frame (an arrow's pixels, a sprite's, a body's), so that a
test can tell an arrow hidden under a sprite or a label lying on a body."""

from __future__ import annotations

import functools
import math
import sys
import weakref
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np
import pygame
import pytest

from engine.render import draw, marks, world_view


def long_axis(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Centroid (x, y) of a mask's pixels, the unit vector along their long axis pointing to
    the end that reaches further from the centroid, and how far (px) each end reaches."""
    xs, ys = np.nonzero(mask)
    assert len(xs) > 20, "no ant in the picture"
    points = np.stack([xs, ys], axis=1).astype(float)
    centroid = points.mean(axis=0)
    # The principal axis: the eigenvector of the covariance of the coordinates with the larger
    # eigenvalue (the direction along which the pixels spread most).
    values, vectors = np.linalg.eigh(np.cov((points - centroid).T))
    assert values[1] > 4 * values[0], "the pixels are not elongated: no long axis to measure"
    axis = vectors[:, 1]
    along = (points - centroid) @ axis
    if along.max() < -along.min():
        axis, along = -axis, -along
    return centroid, axis, float(along.max()), float(-along.min())


def angle_between(u: np.ndarray, v: np.ndarray) -> float:
    """Angle (degrees, 0 to 180) between two pixel directions."""
    cos = np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v))
    return math.degrees(math.acos(max(-1.0, min(1.0, float(cos)))))


# -- what the drawing helpers put on a frame ------------------------------------------------


@dataclass(frozen=True)
class Drawn:
    """One call of a drawing helper on a surface: its ``kind`` ("arrow", "sprite" or "body":
    a body or a collider, ``draw_disc`` or ``draw_world``), the ``pixels`` it changed ((w, h)
    bools, indexed [x, y] as pygame.surfarray), an arrow's ``head`` box (its arrowhead mark),
    the helper's name, how many marks the surface held when it was done (the marks from that
    index on were drawn after it), and the surface's colours just then ((w, h, 3))."""

    kind: str
    pixels: np.ndarray
    head: pygame.Rect | None
    helper: str
    noted: int
    colours: np.ndarray

    def showing(self, final: np.ndarray) -> float:
        """The share of its pixels that still show what it drew in the ``final`` colours
        ((w, h, 3), the finished frame's): 1.0 when nothing drawn later covers any."""
        count = int(self.pixels.sum())
        if count == 0:
            return 1.0
        same = np.all(final[self.pixels] == self.colours[self.pixels], axis=-1)
        return float(same.mean())

    def __str__(self) -> str:
        xs, ys = np.nonzero(self.pixels)
        if len(xs) == 0:
            return f"{self.kind} ({self.helper}) drawing nothing"
        box = (int(xs.min()), int(ys.min()), int(np.ptp(xs)) + 1, int(np.ptp(ys)) + 1)
        return f"{self.kind} ({self.helper}) at {box}"


#: The helpers watched, by kind. A body a demo draws with pygame itself is not seen: draw it
#: with these (``draw_disc`` for a disc, ``draw_world`` for a World) to have it checked.
WATCHED: dict[str, tuple[Callable[..., Any], ...]] = {
    "arrow": (draw.draw_arrow,),
    "sprite": (draw.draw_sprite,),
    "body": (draw.draw_disc, world_view.draw_world),
}


class Layers:
    """What the watched helpers drew on each surface, in drawing order (see :func:`watching`).

    A helper called inside another (``draw_world`` drawing a disc) is part of the outer one's
    drawing. The pixels a call drew are those that differ after it from before it (a pixel
    drawn in the colour it already had shows nothing new); a sprite's are its image's opaque
    ones, as its mask has them (``pygame.mask.from_surface``: alpha over half), not the faint
    edge its soft border tints.
    """

    def __init__(self) -> None:
        self._drawn: weakref.WeakKeyDictionary[pygame.Surface, list[Drawn]] = (
            weakref.WeakKeyDictionary()
        )
        self._depth = 0

    def take(self, surface: pygame.Surface) -> list[Drawn]:
        """What was drawn on ``surface`` since the last take, and forget it."""
        return self._drawn.pop(surface, [])

    def wrap(self, helper: Callable[..., Any], kind: str) -> Callable[..., Any]:
        @functools.wraps(helper)
        def watched(surface: pygame.Surface, *args: Any, **kwargs: Any) -> Any:
            if self._depth:
                return helper(surface, *args, **kwargs)
            before = pygame.surfarray.array3d(surface)
            before_marks = len(marks.marks(surface))
            self._depth += 1
            try:
                result = helper(surface, *args, **kwargs)
            finally:
                self._depth -= 1
            after = pygame.surfarray.array3d(surface)
            changed = (after != before).any(axis=2)
            if kind == "sprite":
                image = kwargs["image"] if "image" in kwargs else args[0]
                changed = _placed(_opaque(image), result, changed.shape)
            new = marks.marks(surface)[before_marks:]
            heads = [m.rect for m in new if m.kind == "arrowhead"]
            head = heads[-1] if kind == "arrow" and heads else None
            done = len(marks.marks(surface))
            self._drawn.setdefault(surface, []).append(
                Drawn(kind, changed, head, helper.__name__, done, after)
            )
            return result

        return watched


def _opaque(image: pygame.Surface) -> np.ndarray:
    """An image's pixels whose alpha is over half ((w, h) bools), as its mask has them."""
    if image.get_flags() & pygame.SRCALPHA:
        return pygame.surfarray.array_alpha(image) > 127
    return np.ones(image.get_size(), dtype=bool)


def _placed(pixels: np.ndarray, rect: pygame.Rect, shape: tuple[int, ...]) -> np.ndarray:
    """``pixels`` of an image put at ``rect`` on a canvas of ``shape`` (w, h), clipped."""
    out = np.zeros(shape[:2], dtype=bool)
    box = rect.clip(pygame.Rect((0, 0), shape[:2]))
    x, y = box.x - rect.x, box.y - rect.y
    out[box.left : box.right, box.top : box.bottom] = pixels[x : x + box.w, y : y + box.h]
    return out


@contextmanager
def watching() -> Iterator[Layers]:
    """Watch the helpers of :data:`WATCHED` wherever the engine's renderer and the demos hold
    them (each loaded module's own name for them), for the ``with`` block."""
    layers = Layers()
    wrapped = {id(h): layers.wrap(h, kind) for kind, hs in WATCHED.items() for h in hs}
    with pytest.MonkeyPatch.context() as patch:
        for module in list(sys.modules.values()):
            name = getattr(module, "__name__", "")
            if not (name == "demos" or name.startswith(("demos.", "engine.render"))):
                continue
            for attr, value in list(vars(module).items()):
                if id(value) in wrapped:
                    patch.setattr(module, attr, wrapped[id(value)])
        yield layers


#: An arrow is hidden when more than this share of its head's pixels, or of all its pixels,
#: is covered by a sprite or a body drawn after it: its direction no longer shows.
HIDDEN = 0.5


def hidden_arrows(drawn: Iterable[Drawn]) -> list[str]:
    """Each arrow whose head or whole is mostly covered (:data:`HIDDEN`) by the sprites and
    bodies drawn after it, in words."""
    drawn = list(drawn)
    out = []
    for i, arrow in enumerate(drawn):
        if arrow.kind != "arrow" or not arrow.pixels.any():
            continue
        later = [d for d in drawn[i + 1 :] if d.kind in ("sprite", "body")]
        if not later:
            continue
        over = np.logical_or.reduce([d.pixels for d in later])
        parts = [("arrow", arrow.pixels)]
        if arrow.head is not None:
            head = np.zeros_like(arrow.pixels)
            r = arrow.head.clip(pygame.Rect((0, 0), arrow.pixels.shape))
            head[r.left : r.right, r.top : r.bottom] = True
            parts.insert(0, ("arrowhead", arrow.pixels & head))
        for part, pixels in parts:
            count = int(pixels.sum())
            share = int((pixels & over).sum()) / count if count else 0.0
            if share > HIDDEN:
                under = ", ".join(str(d) for d in later if (pixels & d.pixels).any())
                out.append(f"{part} of the {arrow} is {share:.0%} hidden under {under}")
                break
    return out


def labels_on_bodies(
    found: Sequence[marks.Mark], drawn: Iterable[Drawn], overlap_ok: Iterable[str] = ()
) -> list[str]:
    """Each label (a text mark of ``found``, a surface's marks in drawing order) written over
    a pixel of a sprite or body drawn before it, in words; labels whose text contains one of
    ``overlap_ok`` may. (A body drawn over a label, as a moving body crosses an axis's
    numbers, is motion, not layout: allowed, as ``marks.problems`` allows an arrow over a
    label.)"""
    bodies = [d for d in drawn if d.kind in ("sprite", "body")]
    allowed = tuple(overlap_ok)
    out = []
    for i, m in enumerate(found):
        if m.kind != "text" or any(word in m.text for word in allowed):
            continue
        for d in bodies:
            if i < d.noted:
                continue  # the label was there first
            r = m.rect.clip(pygame.Rect((0, 0), d.pixels.shape))
            count = int(d.pixels[r.left : r.right, r.top : r.bottom].sum())
            if count:
                out.append(f"{m} lies on the {d} ({count} px)")
    return out
