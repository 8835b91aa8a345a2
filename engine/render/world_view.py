"""A whole World in one call: every collider, body and link (pymunk's ``debug_draw``).

A game that needs no art of its own, a test, or a lesson that shows the physics as it is,
draws the World with ``draw_world(surface, world, camera)``: colliders in ink (sensors as
outlines only), bodies as discs of their radius (points as dots) with a radius line at the
angle of a disc that turns (``Body.turns``), so a roll is seen, or as their shape (a box,
a polygon, a capsule: ``Body(..., shape=...)``), in blue, asleep in grey,
moved by the game in vermillion. A link (a rod, a cable, a SlideJoint) is a line from anchor
to anchor, the points where it holds its bodies (``end_a()``, ``end_b()``), and a GrooveJoint
its groove, under the bodies; over them, a hinge's point (and a pin's, and a groove's anchor)
is a small ring, a hinge's limits an arc about that point from the lower limit to the upper,
and a weld a small square at the point it holds. pymunk's constraints between angles (a gear,
a ratchet, a rotary limit, a motor) are not drawn, as pymunk's ``debug_draw`` draws none.
``alpha`` blends the last two steps as ``World.positions(alpha)`` does, for a fixed-step loop:
positions and angles both, so an anchor is drawn where the blended body holds it.

A body or a collider given a ``colour`` (engine.colours: a pygame tuple, name or hex string)
is filled with it instead (a shaped body keeps its ink outline, a sensor stays an outline);
pymunk's ``DrawOptions`` flags are ``draw_world``'s keywords: ``shapes``, ``joints``,
``contacts`` and ``bounds`` (the last two drawn by engine.render.world_overlays). With the
defaults, and no colour given, a frame is what it was before colours and switches came.
"""

from __future__ import annotations

import math
from typing import Any

import pygame

from engine.dynamics.constraints import GrooveJoint, SlideJoint, SoftJoint
from engine.dynamics.joints import Hinge, Joint, Weld
from engine.dynamics.links import Pin
from engine.dynamics.springs import DampedSpring
from engine.render.camera import Camera
from engine.render.draw import (
    ACCELERATION,
    EULER,
    INK,
    MUTED,
    PAPER,
    VELOCITY,
    Color,
    draw_disc,
)
from engine.render.world_overlays import draw_bounds, draw_contacts

__all__ = [
    "draw_world",
    "paint",
    "angle_of",
    "pose_of",
    "limit_arc",
    "BODY",
    "ASLEEP",
    "KINEMATIC",
    "SOLID",
    "SENSOR",
    "JOINT",
    "LIMIT",
    "RING",
    "ARC",
    "SQUARE",
]

BODY: Color = VELOCITY  #: a body that moves under forces
ASLEEP: Color = MUTED  #: a body asleep in a still pile
KINEMATIC: Color = ACCELERATION  #: a body the game moves (a paddle, a platform)
SOLID: Color = INK  #: the colliders
SENSOR: Color = (204, 121, 167)  #: a sensor's outline
JOINT: Color = INK  #: links, a hinge's ring, a weld's square
LIMIT: Color = EULER  #: a hinge's limits: the arc its angle may sweep
#: Sizes on a canvas 360 px tall, in px (scaled with the canvas's height): a hinge's ring
#: (radius), its limits' arc (radius) and a weld's square (side).
RING, ARC, SQUARE = 3, 20, 9


def draw_world(
    surface: pygame.Surface,
    world: Any,
    camera: Camera,
    alpha: float = 1.0,
    *,
    shapes: bool = True,
    joints: bool = True,
    contacts: bool = False,
    bounds: bool = False,
) -> None:
    """Draw every collider, link and body of ``world`` on ``surface`` through ``camera``.

    The switches are pymunk's ``DrawOptions`` flags: ``shapes`` the colliders and bodies
    (each in its ``colour`` where it has one), ``joints`` the links, springs and joints (a
    mouse joint: a line from its held point to its target), ``contacts`` a mark at each
    contact open after the last step (its point, and its normal as a short tick;
    ``world.touching``), ``bounds`` each body's and each bounded collider's
    axis-aligned bounding box (engine.render.world_overlays). The defaults draw what pymunk's
    ``debug_draw`` does less its contact points."""
    if shapes:
        for collider in world.colliders:
            _draw_collider(surface, collider, camera)
    if world.bodies and world.dim == 2:
        _draw_bodies(surface, world, camera, alpha, shapes, joints, bounds)
    elif bounds:
        draw_bounds(surface, world, camera, {})
    if contacts:
        draw_contacts(surface, world, camera)


def _draw_bodies(
    surface: pygame.Surface,
    world: Any,
    camera: Camera,
    alpha: float,
    shapes: bool,
    joints: bool,
    bounds: bool,
) -> None:
    """The links, springs, bodies and joints of a 2D World with bodies, as ``draw_world``
    switches them, and the bounding boxes over them."""
    xy = world.positions(alpha)
    poses = {
        id(b): (float(xy[k, 0]), float(xy[k, 1]), _drawn_angle(world, b, alpha))
        for k, b in enumerate(world.bodies)
    }
    for link in world.links if joints else ():
        if isinstance(link, SoftJoint):
            _draw_constraint(surface, link, camera, poses, 0.0)
        elif not isinstance(link, (Joint, Pin)):
            a, b = _ends(link, poses)
            pygame.draw.line(surface, JOINT, camera.point(a), camera.point(b), 2)
    for spring in getattr(world, "springs", ()) if joints else ():
        if isinstance(spring, DampedSpring):
            _draw_spring(surface, spring, camera, poses)
    for drag in getattr(world, "mouse_joints", ()) if joints else ():
        # A mouse joint: a line from the held point to its target.
        held = _at(poses[id(drag.body)], drag.anchor)
        pygame.draw.line(surface, JOINT, camera.point(held), camera.point(drag.target), 2)
    for body in world.bodies if shapes else ():
        shape = body.shape
        own = body.colour if body.colour is not None else getattr(shape, "colour", None)
        if own is not None:
            colour = paint(own, body)
        else:
            colour = KINEMATIC if body.kinematic else ASLEEP if world.is_sleeping(body) else BODY
        x, y, angle = poses[id(body)]
        if shape is not None and type(shape).__name__ in ("Polygon", "Segment", "Compound"):
            # (A body of several shapes, engine.body_shapes: each part; a round one a disc.)
            c, s = math.cos(angle), math.sin(angle)
            for part in body.shapes:
                if type(part).__name__ == "Circle":
                    px, py = part.center
                    at = (x + c * px - s * py, y + s * px + c * py)
                    draw_disc(surface, camera, at, part.radius, angle, colour)
                    continue
                _draw_shape(surface, part, camera, (x, y), colour, 0, angle)
                _draw_shape(surface, part, camera, (x, y), INK, 1, angle)
            continue
        turned = body.turns or (body.kinematic and (body.angle or body.angular_velocity))
        draw_disc(surface, camera, (x, y), body.radius, angle if turned else None, colour)
    size = surface.get_height() / 360
    for link in world.links if joints else ():
        if isinstance(link, SoftJoint):
            _draw_constraint(surface, link, camera, poses, size)
        elif isinstance(link, (Joint, Pin)):
            _draw_joint(surface, link, camera, poses, size)
    if bounds:
        draw_bounds(surface, world, camera, poses)


def paint(colour: Any, thing: Any) -> Color:
    """A body's or collider's ``colour`` (engine.colours) as pygame draws it; a ValueError
    naming ``thing`` for a name pygame does not know."""
    if not isinstance(colour, str):
        return colour  # type: ignore[no-any-return]
    try:
        return pygame.Color(colour)  # type: ignore[return-value]
    except ValueError:
        raise ValueError(
            f"colour {colour!r} of {thing!r} is not a colour pygame knows: give a name such "
            f"as 'red' (pygame.color.THECOLORS lists them), a hex string such as '#ff8800', "
            f"or an (r, g, b) tuple of ints 0 to 255"
        ) from None


#: A spring is drawn as a zigzag of this many teeth, this wide (px on a canvas 360 px tall).
TEETH, TOOTH = 8, 4


def _draw_spring(surface: pygame.Surface, spring: DampedSpring, camera: Camera, poses: Any) -> None:
    """A DampedSpring as a zigzag from anchor to anchor (a line where its ends meet)."""
    a = _at(poses[id(spring.a)], spring.anchor_a)
    b_body = spring.second
    anchor = spring.anchor_b
    b = (anchor.x, anchor.y) if b_body is None else _at(poses[id(b_body)], anchor)
    pa, pb = camera.point(a), camera.point(b)
    dx, dy = pb[0] - pa[0], pb[1] - pa[1]
    length = math.hypot(dx, dy)
    if length < 1.0:
        return
    # Across the spring, alternately either side of its line, TOOTH px out.
    half = TOOTH * surface.get_height() / 360
    nx, ny = -dy / length * half, dx / length * half
    points: list[tuple[float, float]] = [pa]
    for k in range(1, 2 * TEETH):
        f, side = k / (2 * TEETH), 1 if k % 2 else -1
        points.append((pa[0] + f * dx + side * nx, pa[1] + f * dy + side * ny))
    points.append(pb)
    pygame.draw.lines(surface, JOINT, False, points, 1)


def pose_of(world: Any, body: Any, alpha: float = 1.0) -> tuple[float, float, float]:
    """Where ``body`` is drawn: its position and angle (m, m, rad) blended by ``alpha`` as
    ``draw_world`` blends them (a body that does not turn keeps its angle)."""
    p = world.position_of(body, alpha)
    return float(p.x), float(p.y), _drawn_angle(world, body, alpha)


def _drawn_angle(world: Any, body: Any, alpha: float) -> float:
    angle = angle_of(world, body, alpha)
    return float(body.angle) if angle is None else angle


def _at(pose: tuple[float, float, float], local: Any) -> tuple[float, float]:
    """A point given in a body's own frame, in the world, for the body at ``pose``."""
    x, y, angle = pose
    c, s = math.cos(angle), math.sin(angle)
    return (x + c * local.x - s * local.y, y + s * local.x + c * local.y)


def _ends(link: Any, poses: dict[int, tuple[float, float, float]]) -> tuple[Any, Any]:
    """Where ``link`` holds its two ends, for the bodies at their drawn ``poses``: its
    ``end_a()`` and ``end_b()`` at the blended positions and angles."""
    a = _at(poses[id(link.body)], link.anchor_a)
    other = link.other
    if isinstance(other, tuple) or not hasattr(other, "pos"):
        return a, (float(other[0]), float(other[1]))  # a fixed point, in world coordinates
    return a, _at(poses[id(other)], link.anchor_b)


def _draw_constraint(
    surface: pygame.Surface, link: Any, camera: Camera, poses: Any, size: float
) -> None:
    """pymunk's constraints (engine.dynamics.constraints) as its ``debug_draw`` shows them: a slide
    joint a line from anchor to anchor, a groove its segment (``size`` 0: under the bodies),
    then a ring at the anchor held in it (over them); nothing for the others."""

    def held(body: Any, local: Any) -> tuple[float, float]:
        # A body's point at its drawn pose, or the world's (its anchors: world coordinates).
        return _at(poses[id(body)], local) if id(body) in poses else (local.x, local.y)

    if isinstance(link, SlideJoint) and not size:
        a, b = held(link.body_a, link.anchor_a), held(link.body_b, link.anchor_b)
        pygame.draw.line(surface, JOINT, camera.point(a), camera.point(b), 2)
    elif isinstance(link, GrooveJoint) and not size:
        a, b = held(link.body_a, link.groove_a), held(link.body_a, link.groove_b)
        pygame.draw.line(surface, JOINT, camera.point(a), camera.point(b), 2)
    elif isinstance(link, GrooveJoint):
        cx, cy = camera.to_px(*held(link.body_b, link.anchor_b))
        centre = (math.floor(cx + 0.5), math.floor(cy + 0.5))
        pygame.draw.circle(surface, JOINT, centre, max(2, round(RING * size)), max(1, round(size)))


def limit_arc(link: Any, poses: Any = None) -> tuple[float, float] | None:
    """The world angles (rad, counter-clockwise from +x) the arc of a Hinge's limits runs
    between, lower to upper, or None without limits. They are measured from body_a's
    direction at the hinge's reference angle (joint angle 0): the direction from the hinge
    point to body_a's centre (for a hinge at the centre, body_a's own +x), turned as body_b
    is now (``poses``: the drawn pose of each body by id; None: as the bodies are)."""
    if not isinstance(link, Hinge) or link.limits is None:
        return None
    b_angle = 0.0
    if link.bodies[1:]:
        second = link.bodies[1]
        b_angle = poses[id(second)][2] if poses is not None else float(second.angle)
    anchor = link.anchor_a
    own = math.atan2(-anchor.y, -anchor.x) if (anchor.x or anchor.y) else 0.0
    zero = b_angle + link.reference_angle + own
    lower, upper = link.limits
    return zero + lower, zero + upper


def _draw_joint(
    surface: pygame.Surface,
    link: Any,
    camera: Camera,
    poses: dict[int, tuple[float, float, float]],
    size: float,
) -> None:
    """A hinge's (or a pin's) ring at its point, with the arc of its limits; a weld's square."""
    a, _ = _ends(link, poses)
    cx, cy = camera.to_px(*a)
    line = max(1, round(2 * size))
    if isinstance(link, Weld):
        side = max(4, round(SQUARE * size))
        square = pygame.Rect(0, 0, side, side)
        square.center = (math.floor(cx + 0.5), math.floor(cy + 0.5))
        pygame.draw.rect(surface, JOINT, square, line)
        return
    arc = limit_arc(link, poses)
    if arc is not None:
        _draw_arc(surface, (cx, cy), max(6.0, ARC * size), arc, line)
    centre = (math.floor(cx + 0.5), math.floor(cy + 0.5))
    pygame.draw.circle(surface, JOINT, centre, max(2, round(RING * size)), max(1, round(size)))


def _draw_arc(
    surface: pygame.Surface,
    centre: tuple[float, float],
    radius: float,
    angles: tuple[float, float],
    width: int,
) -> None:
    """An arc of ``radius`` px about the pixel ``centre`` from the world angle ``angles[0]``
    to ``angles[1]`` (counter-clockwise; the screen's y points down), and a short radial line
    at each end, so that limits a whole turn apart still show where they are."""
    lower, upper = angles
    cx, cy = centre
    count = max(2, math.ceil(abs(upper - lower) * radius / 3) + 1)
    points = [
        (cx + radius * math.cos(phi), cy - radius * math.sin(phi))
        for phi in (lower + (upper - lower) * k / (count - 1) for k in range(count))
    ]
    pygame.draw.lines(surface, LIMIT, False, points, width)
    for phi in (lower, upper):
        inner = (cx + 0.5 * radius * math.cos(phi), cy - 0.5 * radius * math.sin(phi))
        outer = (cx + 1.25 * radius * math.cos(phi), cy - 1.25 * radius * math.sin(phi))
        pygame.draw.line(surface, LIMIT, inner, outer, width)


def angle_of(world: Any, body: Any, alpha: float = 1.0) -> float | None:
    """The angle (rad) to draw a body that turns at, blended like its position; None for a
    body that does not turn. The World keeps no angle from before its last step, so the
    angle is taken back along the angular velocity by (1 - alpha) of that step: exact while
    the spin is steady, otherwise off by less than the step's change of angular velocity
    times dt (a few hundredths of a degree for a disc spinning up on a slope at 1/120 s).
    A kinematic body is drawn at the angle the game turned it to."""
    if not (body.turns or body.kinematic):
        return None
    dt = getattr(world, "dt", None)
    if dt is None or alpha >= 1.0:
        return float(body.angle)
    return float(body.angle - (1.0 - alpha) * dt * body.angular_velocity)


def _draw_collider(surface: pygame.Surface, c: Any, camera: Camera) -> None:
    kind = type(c).__name__
    colour = paint(c.colour, c) if c.colour is not None else SENSOR if c.sensor else SOLID
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
