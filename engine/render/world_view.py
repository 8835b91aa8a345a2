"""A whole World in one call: every collider, body and link (pymunk's ``debug_draw``).

A game that needs no art of its own, a test, or a lesson that shows the physics as it is,
draws the World with ``draw_world(surface, world, camera)``: colliders in ink (sensors as
outlines only), bodies as discs of their radius (points as dots) with a radius line at the
angle of a disc that turns (``Body.turns``), so a roll is seen, or as their shape (a box,
a polygon, a capsule: ``Body(..., shape=...)``), in blue, asleep in grey,
moved by the game in vermillion, links as lines. ``alpha`` blends the last two steps as
``World.positions(alpha)`` does, for a fixed-step loop.
"""

from __future__ import annotations

import math
from typing import Any

import pygame

from engine.render.camera import Camera
from engine.render.draw import ACCELERATION, INK, MUTED, PAPER, VELOCITY, Color, draw_disc

__all__ = ["draw_world", "angle_of", "BODY", "ASLEEP", "KINEMATIC", "SOLID", "SENSOR"]

BODY: Color = VELOCITY  #: a body that moves under forces
ASLEEP: Color = MUTED  #: a body asleep in a still pile
KINEMATIC: Color = ACCELERATION  #: a body the game moves (a paddle, a platform)
SOLID: Color = INK  #: the colliders
SENSOR: Color = (204, 121, 167)  #: a sensor's outline


def draw_world(surface: pygame.Surface, world: Any, camera: Camera, alpha: float = 1.0) -> None:
    """Draw every collider, link and body of ``world`` on ``surface`` through ``camera``."""
    for collider in world.colliders:
        _draw_collider(surface, collider, camera)
    if not world.bodies or world.dim != 2:
        return
    xy = world.positions(alpha)
    row = {id(b): k for k, b in enumerate(world.bodies)}
    for link in world.links:
        a = camera.point(tuple(xy[row[id(link.body)]]))
        other = link.other
        if isinstance(other, tuple) or not hasattr(other, "pos"):
            b = camera.point(tuple(other))
        else:
            b = camera.point(tuple(xy[row[id(other)]]))
        pygame.draw.line(surface, INK, a, b, 2)
    for k, body in enumerate(world.bodies):
        colour = KINEMATIC if body.kinematic else ASLEEP if world.is_sleeping(body) else BODY
        shape = body.shape
        at = (float(xy[k, 0]), float(xy[k, 1]))
        if shape is not None and type(shape).__name__ in ("Polygon", "Segment"):
            angle = angle_of(world, body, alpha) or 0.0  # a box that turns, at its angle
            _draw_shape(surface, shape, camera, at, colour, 0, angle)
            _draw_shape(surface, shape, camera, at, INK, 1, angle)
            continue
        draw_disc(surface, camera, at, body.radius, angle_of(world, body, alpha), colour)


def angle_of(world: Any, body: Any, alpha: float = 1.0) -> float | None:
    """The angle (rad) to draw a body that turns at, blended like its position; None for a
    body that does not turn. The World keeps no angle from before its last step, so the
    angle is taken back along the angular velocity by (1 - alpha) of that step: exact while
    the spin is steady, otherwise off by less than the step's change of angular velocity
    times dt (a few hundredths of a degree for a disc spinning up on a slope at 1/120 s)."""
    if not body.turns:
        return None
    dt = getattr(world, "dt", None)
    if dt is None or alpha >= 1.0:
        return float(body.angle)
    return float(body.angle - (1.0 - alpha) * dt * body.angular_velocity)


def _draw_collider(surface: pygame.Surface, c: Any, camera: Camera) -> None:
    kind = type(c).__name__
    colour = SENSOR if c.sensor else SOLID
    width = 2 if c.sensor else 0
    scale = camera.scale
    if kind == "Circle":
        centre = camera.point(tuple(c.center))
        pygame.draw.circle(surface, colour, centre, max(round(c.radius * scale), 1), width)
    elif kind == "Segment":
        a, b = camera.point(tuple(c.a)), camera.point(tuple(c.b))
        r_px = round(c.radius * scale)
        if r_px < 1:
            pygame.draw.line(surface, colour, a, b, 2)
            return
        if c.sensor:
            _capsule_outline(surface, colour, a, b, r_px)
            return
        pygame.draw.line(surface, colour, a, b, 2 * r_px)
        pygame.draw.circle(surface, colour, a, r_px)
        pygame.draw.circle(surface, colour, b, r_px)
    elif kind == "Box":
        x0, y0 = camera.point(tuple(c.lower_left))
        x1, y1 = camera.point(tuple(c.upper_right))
        rect = pygame.Rect(min(x0, x1), min(y0, y1), abs(x1 - x0), abs(y1 - y0))
        pygame.draw.rect(surface, colour, rect, 2)
    elif kind == "Polygon":
        _draw_shape(surface, c, camera, (0.0, 0.0), colour, width)
    elif kind == "Plane":
        # The line across the whole surface: its point +- the surface's diagonal along it.
        w, h = surface.get_size()
        reach = math.hypot(w, h) / scale
        p, n = c.point, c.normal
        t = (-n.y, n.x)
        a = camera.point((p.x - t[0] * reach, p.y - t[1] * reach))
        b = camera.point((p.x + t[0] * reach, p.y + t[1] * reach))
        pygame.draw.line(surface, colour, a, b, 2)


def _draw_shape(
    surface: pygame.Surface,
    shape: Any,
    camera: Camera,
    at: tuple[float, float],
    colour: Color,
    width: int,
    angle: float = 0.0,
) -> None:
    """A Polygon (with its rounding) or a Segment (a capsule) whose coordinates are about
    ``at`` (a body's position; the origin for a collider), turned by ``angle`` (rad,
    counter-clockwise) about it; ``width`` 0 fills it."""
    ox, oy = at
    c, s = math.cos(angle), math.sin(angle)

    def place(v: Any) -> tuple[int, int]:
        return camera.point((c * v.x - s * v.y + ox, s * v.x + c * v.y + oy))

    r_px = round(shape.radius * camera.scale)
    if type(shape).__name__ == "Segment":
        a, b = place(shape.a), place(shape.b)
        if width and r_px:
            _capsule_outline(surface, colour, a, b, r_px)
            return
        if width:
            pygame.draw.line(surface, colour, a, b, width)
            return
        pygame.draw.line(surface, colour, a, b, max(2 * r_px, 2))
        for end in (a, b):
            pygame.draw.circle(surface, colour, end, max(r_px, 1))
        return
    pts = [place(v) for v in shape.vertices]
    if r_px >= 1:
        # The rounding: the edges thickened by r and a disc at each corner.
        for p, q in zip(pts, pts[1:] + pts[:1], strict=True):
            pygame.draw.line(surface, colour, p, q, 2 * r_px if not width else width)
        for p in pts:
            pygame.draw.circle(surface, colour, p, r_px, width)
    pygame.draw.polygon(surface, colour, pts, width)


def _capsule_outline(
    surface: pygame.Surface, colour: Color, a: tuple[int, int], b: tuple[int, int], r: int
) -> None:
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = math.hypot(dx, dy) or 1.0
    nx, ny = -dy / length * r, dx / length * r
    for sign in (1, -1):
        pygame.draw.line(
            surface,
            colour,
            (a[0] + sign * nx, a[1] + sign * ny),
            (b[0] + sign * nx, b[1] + sign * ny),
            2,
        )
    pygame.draw.circle(surface, colour, a, r, 2)
    pygame.draw.circle(surface, colour, b, r, 2)


#: The background a World is usually drawn on (the engine's paper).
BACKGROUND: Color = PAPER
