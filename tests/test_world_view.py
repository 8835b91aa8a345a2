"""draw_world: a whole World in one call (pymunk's debug_draw), checked by its pixels."""

from __future__ import annotations

import math

import pygame

from engine import Body, Box, Circle, Pin, Plane, Rod, Segment, Vector, World
from engine.forces import Gravity
from engine.render import Camera, draw_world, init_headless
from engine.render.world_view import ASLEEP, BODY, KINEMATIC, SENSOR, SOLID

BG = (250, 248, 242)


def at(surface: pygame.Surface, camera: Camera, p: tuple[float, float]) -> tuple[int, int, int]:
    return tuple(surface.get_at(camera.point(p)))[:3]  # type: ignore[return-value]


def test_every_collider_body_and_link_is_drawn_where_the_camera_puts_it() -> None:
    init_headless()
    w = World(integrator="auto")
    w.add_force(Gravity((0, -9.81)))
    w.add_collider(Plane((0, 0), (0, 1)))
    w.add_collider(Box((-10, -1), (10, 11)))
    w.add_collider(Segment((2, 4), (6, 4), radius=0.3))
    w.add_collider(Circle((-5, 6), 1.0))
    w.add_collider(Circle((-5, 2), 1.5, sensor=True))
    ball = w.add(Body(Vector(4, 8), Vector(0, 0), Vector(0, 0), radius=0.5))
    paddle = w.add(Body(Vector(0, 2), Vector(0, 0), Vector(0, 0), radius=0.6, kinematic=True))
    bob = w.add(Body(Vector(8, 6), Vector(0, 0), Vector(0, 0), radius=0.2))
    w.add_link(Rod(bob, (8, 9)))
    anchor = w.add(Body(Vector(-8, 9), Vector(0, 0), Vector(0, 0), radius=0.3))
    w.add_link(Pin(anchor, (-8, 9)))
    resting = w.add(Body(Vector(-1, 0.5), Vector(0, 0), Vector(0, 0), radius=0.5))
    for _ in range(60):
        w.step(1 / 60)
    assert w.is_sleeping(resting)
    surface = pygame.Surface((640, 400))
    surface.fill(BG)
    cam = Camera.fit((-11, -2, 11, 12), (0, 0, 640, 400))
    draw_world(surface, w, cam)
    assert at(surface, cam, (4, 4)) == SOLID  # the capsule's middle
    assert at(surface, cam, (4, 4.25)) == SOLID  # within its radius
    assert at(surface, cam, (-5, 6)) == SOLID  # the peg
    assert at(surface, cam, (-5, 2)) == BG  # a sensor is an outline ...
    assert at(surface, cam, (-5, 3.5)) == SENSOR  # ... on its edge
    assert at(surface, cam, (3, 0)) == SOLID  # the floor's line
    assert at(surface, cam, (tuple(ball.pos)[0], tuple(ball.pos)[1])) == BODY
    assert at(surface, cam, (0, 2)) == KINEMATIC and paddle.kinematic
    assert at(surface, cam, (-1, 0.5)) == ASLEEP
    # The rod: a line from the anchor point to the bob, midway along it.
    mid = ((8 + bob.pos.x) / 2, (9 + bob.pos.y) / 2)
    assert at(surface, cam, mid) == SOLID
    assert math.isclose((bob.pos - Vector(8, 9)).magnitude(), 3.0, rel_tol=1e-9)
