"""What ``draw_world`` lays over a World on request: contact points and bounding boxes.

pymunk's ``DrawOptions.DRAW_COLLISION_POINTS`` and Box2D's AABB bit, for seeing what the
engine sees. ``draw_contacts`` marks each contact open after the last step
(``world.touching``: a resting ball, a stacked box, a body against a body) with a dot at its
point and a short tick along its normal, toward the body; a bounce that began and ended
within the step has closed by then and is not marked. ``draw_bounds`` outlines each body's
axis-aligned bounding box (its shape turned by its angle, rounding included) and each
collider's (``Collider.bounds()``; a Plane, or a Box room, whose solid has no end, has none).
"""

from __future__ import annotations

import math
from typing import Any

import pygame

from engine.render.camera import Camera
from engine.render.draw import POSITION, Color

__all__ = ["draw_contacts", "draw_bounds", "body_bounds", "CONTACT", "BOUNDS", "MARK"]

CONTACT: Color = POSITION  #: a contact's dot and normal tick (bluish green)
BOUNDS: Color = (86, 180, 233)  #: bounding boxes (sky blue)
#: A contact's dot (radius) and normal tick (length), px on a canvas 360 px tall.
MARK = (2, 8)

Bounds = tuple[float, float, float, float]


def draw_contacts(surface: pygame.Surface, world: Any, camera: Camera) -> None:
    """A dot at each open contact's point and a tick along its normal (``world.touching``)."""
    size = surface.get_height() / 360
    dot, tick = max(1, round(MARK[0] * size)), MARK[1] * size
    for event in world.touching:
        px, py = camera.point((event.point.x, event.point.y))
        # The normal points up the world's y; the screen's y points down.
        end = (px + round(tick * event.normal.x), py - round(tick * event.normal.y))
        pygame.draw.line(surface, CONTACT, (px, py), end, max(1, round(size)))
        pygame.draw.circle(surface, CONTACT, (px, py), dot)


def draw_bounds(
    surface: pygame.Surface,
    world: Any,
    camera: Camera,
    poses: dict[int, tuple[float, float, float]],
) -> None:
    """Each body's bounding box at its drawn pose (``poses``: id -> (x, y, angle)) and each
    collider's whose solid is bounded, outlined one pixel wide."""
    boxes = [body_bounds(b, *poses[id(b)]) for b in world.bodies if id(b) in poses]
    boxes += [c.bounds() for c in world.colliders]
    for x0, y0, x1, y1 in boxes:
        if not all(map(math.isfinite, (x0, y0, x1, y1))):
            continue
        (ax, ay), (bx, by) = camera.point((x0, y1)), camera.point((x1, y0))
        pygame.draw.rect(surface, BOUNDS, pygame.Rect(ax, ay, bx - ax + 1, by - ay + 1), 1)


def body_bounds(body: Any, x: float, y: float, angle: float) -> Bounds:
    """(xmin, ymin, xmax, ymax) of ``body`` at (x, y) turned by ``angle`` (rad): its shape's
    corners (a Polygon's vertices, a Segment's ends) turned and grown by the shape's radius;
    a disc's centre +- its radius."""
    shape = body.shape
    kind = type(shape).__name__
    if kind not in ("Polygon", "Segment", "Compound"):
        r = body.radius
        return x - r, y - r, x + r, y + r
    c, s = math.cos(angle), math.sin(angle)
    boxes = []
    for part in body.shapes:  # (a body of several shapes: the box of its parts' boxes)
        name = type(part).__name__
        points = (
            part.vertices
            if name == "Polygon"
            else (part.a, part.b)
            if name == "Segment"
            else (part.center,)
        )
        xs = [x + c * p.x - s * p.y for p in points]
        ys = [y + s * p.x + c * p.y for p in points]
        r = part.radius
        boxes.append((min(xs) - r, min(ys) - r, max(xs) + r, max(ys) + r))
    return (
        min(b[0] for b in boxes), min(b[1] for b in boxes),
        max(b[2] for b in boxes), max(b[3] for b in boxes),
    )  # fmt: skip
