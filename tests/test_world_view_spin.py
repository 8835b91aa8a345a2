"""A disc that turns is drawn with a radius line at its angle (``draw_disc``, ``draw_world``),
checked by its pixels: ink along the angle, the disc's own colour across it."""

from __future__ import annotations

import math

import pygame
import pytest

from engine import Body, Vector, World
from engine.render import INK, PAPER, Camera, draw_disc, draw_world, init_headless
from engine.render.world_view import BODY

R = 1.0  # m
#: 40 px a metre, the world's origin in the middle of a 200x200 canvas.
CAMERA = Camera(40.0, (100.0, 100.0))


def canvas() -> pygame.Surface:
    init_headless()
    surface = pygame.Surface((200, 200))
    surface.fill(PAPER)
    return surface


def colour(surface: pygame.Surface, x: float, y: float) -> tuple[int, int, int]:
    """The colour of the pixel at the world point (x, y)."""
    return tuple(surface.get_at(CAMERA.point((x, y))))[:3]  # type: ignore[return-value]


def along(surface: pygame.Surface, dx: float, dy: float) -> list[tuple[int, int, int]]:
    """Colours at 0.3, 0.5, 0.7 and 0.9 of the radius from the centre, along (dx, dy)."""
    return [colour(surface, f * R * dx, f * R * dy) for f in (0.3, 0.5, 0.7, 0.9)]


@pytest.mark.parametrize(
    ("angle", "inked", "clear"),
    [(0.0, (1, 0), (0, 1)), (math.pi / 2, (0, 1), (1, 0)), (math.pi, (-1, 0), (0, -1))],
)
def test_draw_disc_puts_its_radius_line_at_the_angle(
    angle: float, inked: tuple[int, int], clear: tuple[int, int]
) -> None:
    surface = canvas()
    draw_disc(surface, CAMERA, (0.0, 0.0), R, angle, BODY)
    assert along(surface, *inked) == [INK] * 4
    assert along(surface, *clear) == [BODY] * 4
    assert colour(surface, 0.0, 0.0) == BODY  # the centre keeps the disc's colour
    assert colour(surface, 1.2 * R, 0.0) == PAPER  # the line stops at the rim


def test_a_disc_without_an_angle_has_no_line() -> None:
    surface = canvas()
    draw_disc(surface, CAMERA, (0.0, 0.0), R, None, BODY)
    for dx, dy in ((1, 0), (0, 1), (-1, 0), (0, -1)):
        assert along(surface, dx, dy) == [BODY] * 4


def test_draw_world_draws_the_angle_of_a_disc_that_turns() -> None:
    w = World()
    disc = w.add(Body(Vector(0, 0), radius=R, angle=0.0))
    still = w.add(Body(Vector(1.8, -1.8), radius=R * 0.5, fixed_rotation=True))
    surface = canvas()
    draw_world(surface, w, CAMERA)
    assert along(surface, 1, 0) == [INK] * 4 and along(surface, 0, 1) == [BODY] * 4
    disc.angle = math.pi / 2
    surface = canvas()
    draw_world(surface, w, CAMERA)
    assert along(surface, 0, 1) == [INK] * 4 and along(surface, 1, 0) == [BODY] * 4
    # A disc that does not turn is drawn as before: no line.
    assert not still.turns
    ring = [(1.8 + 0.3 * dx, -1.8 + 0.3 * dy) for dx, dy in ((1, 0), (0, 1), (-1, 0), (0, -1))]
    assert {colour(surface, x, y) for x, y in ring} == {BODY}


def test_the_angle_is_blended_between_steps_like_the_position() -> None:
    """A disc spinning a quarter turn a step: alpha 0 shows the angle before the step
    (along +x), alpha 1 the angle after it (along +y), as positions(alpha) does."""
    dt = 0.1
    w = World()
    w.add(Body(Vector(0, 0), radius=R, angular_velocity=(math.pi / 2) / dt))
    w.step(dt)
    before, after = canvas(), canvas()
    draw_world(before, w, CAMERA, alpha=0.0)
    draw_world(after, w, CAMERA, alpha=1.0)
    assert along(before, 1, 0) == [INK] * 4 and along(before, 0, 1) == [BODY] * 4
    assert along(after, 0, 1) == [INK] * 4 and along(after, 1, 0) == [BODY] * 4
