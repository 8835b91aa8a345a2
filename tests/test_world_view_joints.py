"""Joints drawn by ``draw_world``, checked by their pixels: a link from anchor to anchor at the
blended pose, a hinge's ring, the arc of its limits, a weld's square, a mouse joint's line."""

from __future__ import annotations

import math

import pygame
import pytest

from engine import Body, Cable, Hinge, MouseJoint, Polygon, Rod, Vector, Weld, World
from engine.render import PAPER, Camera, draw_world, init_headless
from engine.render.world_view import ARC, JOINT, LIMIT, RING, SQUARE, limit_arc

#: 60 px a metre, the world's origin in the middle of a 360x360 canvas (sizes as drawn at
#: 360 px tall: a ring of RING px, an arc of ARC px).
CAMERA = Camera(60.0, (180.0, 180.0))


def canvas() -> pygame.Surface:
    init_headless()
    surface = pygame.Surface((360, 360))
    surface.fill(PAPER)
    return surface


def pixel(surface: pygame.Surface, x: float, y: float) -> tuple[int, int, int]:
    return tuple(surface.get_at((round(x), round(y))))[:3]  # type: ignore[return-value]


def around(
    surface: pygame.Surface, centre: tuple[float, float], radius: float, phi: float
) -> tuple[int, int, int]:
    """The colour ``radius`` px from the pixel ``centre`` at the world angle ``phi`` (rad,
    counter-clockwise; the screen's y points down)."""
    cx, cy = centre
    return pixel(surface, cx + radius * math.cos(phi), cy - radius * math.sin(phi))


def ray(
    surface: pygame.Surface, centre: tuple[float, float], r0: float, r1: float, phi: float
) -> set[tuple[int, int, int]]:
    """The colours from ``r0`` to ``r1`` px out of ``centre`` at the world angle ``phi``."""
    steps = max(2, round(4 * (r1 - r0)))
    return {around(surface, centre, r0 + (r1 - r0) * k / steps, phi) for k in range(steps + 1)}


def ring_at(surface: pygame.Surface, centre: tuple[float, float], phi: float) -> bool:
    """Whether ink lies within a pixel of the point RING px out of ``centre`` at ``phi``
    (pygame's small circles sit half a pixel off their centre and step round in pixels)."""
    cx, cy = centre
    x, y = round(cx + RING * math.cos(phi)), round(cy - RING * math.sin(phi))
    return any(pixel(surface, x + dx, y + dy) == JOINT for dx in (-1, 0, 1) for dy in (-1, 0, 1))


def plank(x: float, y: float, length: float = 2.0, **kw: float) -> Body:
    return Body(Vector(x, y), shape=Polygon.box(length, 0.1), **kw)  # type: ignore[arg-type]


def test_a_hinges_ring_sits_on_its_point_and_its_limits_arc_spans_lower_to_upper() -> None:
    world = World()
    door = world.add(plank(1.0, 0.0))  # hinged at its left end, pointing along +x
    world.add_link(Hinge(door, world.static_body, (0.0, 0.0), limits=(-0.5, 0.8)))
    surface = canvas()
    draw_world(surface, world, CAMERA)
    hinge = CAMERA.to_px(0.0, 0.0)
    # The ring: ink all round within RING px (a pixel either way: pygame's circles sit
    # half a pixel off their centre), paper past it (away from the door) and inside it.
    for phi in (0.5 * math.pi, 0.75 * math.pi, math.pi, 1.25 * math.pi, 1.5 * math.pi):
        assert ring_at(surface, hinge, phi), phi
        assert ray(surface, hinge, RING + 2, RING + 6, phi) == {PAPER}, phi
    assert pixel(surface, hinge[0] - 1, hinge[1] - 1) == PAPER
    # The arc: from -0.5 rad to 0.8 rad about the door's direction (+x), over the door.
    for phi in (-0.45, -0.2, 0.0, 0.3, 0.75):
        assert around(surface, hinge, ARC, phi) == LIMIT, phi
    for phi in (-0.7, 1.0, 0.5 * math.pi, math.pi):  # beyond the limits: no arc
        assert around(surface, hinge, ARC, phi) == PAPER, phi
    # A short radial line at each limit, out past the arc.
    for phi in (-0.5, 0.8):
        assert around(surface, hinge, 1.15 * ARC, phi) == LIMIT, phi
    assert limit_arc(world.links[0]) == pytest.approx((-0.5, 0.8), abs=1e-15)


def test_the_limits_turn_with_body_b_and_start_from_body_as_reference() -> None:
    # A hinge between two bodies: the arc is measured from body_a's direction at the joint's
    # angle 0 (here straight down from the hinge) and turns as body_b turns.
    world = World()
    arm = world.add(plank(0.0, 1.0, angle=0.0))  # body_b: a bar along x, centred at (0, 1)
    hanging = world.add(plank(0.0, 0.0, length=2.0, angle=math.pi / 2))  # hangs from (0, 1)
    hinge = world.add_link(Hinge(hanging, arm, (0.0, 1.0), limits=(-0.3, 0.3)))
    down = -math.pi / 2
    assert limit_arc(hinge) == pytest.approx((down - 0.3, down + 0.3), abs=1e-12)
    arm.angle = 0.4  # body_b turned: the range turns with it
    assert limit_arc(hinge) == pytest.approx((down + 0.1, down + 0.7), abs=1e-12)
    surface = canvas()
    draw_world(surface, world, CAMERA)
    at = hinge.end_a()
    centre = CAMERA.to_px(at.x, at.y)
    assert around(surface, centre, ARC, down + 0.4) == LIMIT
    assert around(surface, centre, ARC, down - 0.25) == PAPER  # inside the old range, not now


def test_no_arc_without_limits_and_a_hinge_at_a_centre_measures_from_plus_x() -> None:
    world = World()
    wheel = world.add(Body(Vector(0.0, 0.0), radius=1.0))
    free = world.add_link(Hinge(wheel, world.static_body, (0.0, 0.0)))
    assert limit_arc(free) is None
    surface = canvas()
    draw_world(surface, world, CAMERA)
    hinge = CAMERA.to_px(0.0, 0.0)
    assert ring_at(surface, hinge, math.pi)
    assert LIMIT not in {around(surface, hinge, ARC, k * 0.3) for k in range(21)}
    free.limits = (0.1, 0.2)
    assert limit_arc(free) == pytest.approx((0.1, 0.2), abs=1e-15)  # the wheel's own +x


def test_a_rod_is_drawn_from_anchor_to_anchor_not_centre_to_centre() -> None:
    world = World()
    a = world.add(plank(-1.0, 0.0))
    b = world.add(plank(0.0, -1.5))
    world.add_link(Rod(a, b, anchor_a=(1.0, 0.0)))  # from a's right end (0, 0) to b's centre
    surface = canvas()
    draw_world(surface, world, CAMERA)
    for y in (-0.3, -0.75, -1.2):  # the line x = 0 between the anchors
        assert pixel(surface, *CAMERA.to_px(0.0, y)) == JOINT, y
    # Where the line from centre to centre passes (the old drawing): nothing.
    for y in (-0.3, -0.75, -1.2):
        assert pixel(surface, *CAMERA.to_px(-1.0 + (-y / 1.5), y)) == PAPER, y


def test_an_anchor_is_drawn_where_the_blended_angle_puts_it() -> None:
    # A bar turning a quarter turn in one step, a slack cable from its end to a fixed point:
    # alpha 0 draws the end where it was before the step (+x), alpha 1 after it (+y).
    dt = 0.1
    world = World()
    bar = world.add(plank(0.0, 0.0, length=2.0, angular_velocity=(math.pi / 2) / dt))
    world.add_link(Cable(bar, (2.0, 2.0), 10.0, anchor_a=(1.0, 0.0)))
    world.step(dt)
    assert bar.angle == pytest.approx(math.pi / 2, abs=1e-6)
    before, after = canvas(), canvas()
    draw_world(before, world, CAMERA, alpha=0.0)
    draw_world(after, world, CAMERA, alpha=1.0)
    end_before, end_now = (1.0, 0.0), tuple(bar.local_to_world((1.0, 0.0)))
    for surface, end, other in ((before, end_before, end_now), (after, end_now, end_before)):
        fixed = Vector(2.0, 2.0)
        # Three quarters of the way from the drawn end to the fixed point: the rod's line.
        on = (end[0] + 0.75 * (fixed.x - end[0]), end[1] + 0.75 * (fixed.y - end[1]))
        assert pixel(surface, *CAMERA.to_px(*on)) == JOINT
        off = (other[0] + 0.75 * (fixed.x - other[0]), other[1] + 0.75 * (fixed.y - other[1]))
        assert pixel(surface, *CAMERA.to_px(*off)) == PAPER


def test_a_weld_is_a_small_square_at_body_as_centre() -> None:
    world = World()
    a = world.add(Body(Vector(-1.0, 1.0), radius=0.05, fixed_rotation=True))
    b = world.add(plank(1.0, 1.0))
    world.add_link(Weld(a, b))
    surface = canvas()
    draw_world(surface, world, CAMERA)
    cx, cy = CAMERA.to_px(-1.0, 1.0)
    half = SQUARE // 2
    for dx, dy in ((-half, 0), (half, 0), (0, -half), (0, half), (-half, -half), (half, half)):
        assert pixel(surface, cx + dx, cy + dy) == JOINT, (dx, dy)
    assert pixel(surface, cx + half + 3, cy) == PAPER


def test_a_mouse_joint_is_drawn_from_its_held_point_to_its_target() -> None:
    world = World()
    box = world.add(plank(0.0, 0.0))
    world.add_link(MouseJoint(box, (0.0, -2.0), anchor=(1.0, 0.0)))  # from (1, 0) to (0, -2)
    surface = canvas()
    draw_world(surface, world, CAMERA)
    for f in (0.2, 0.5, 0.8):  # along the line from the held point to the target
        assert pixel(surface, *CAMERA.to_px(1.0 - f, -2.0 * f)) == JOINT, f
    surface = canvas()
    draw_world(surface, world, CAMERA, joints=False)
    assert pixel(surface, *CAMERA.to_px(0.5, -1.0)) == PAPER
