"""draw_world's colours and switches (pymunk's ``shape.color`` and ``DrawOptions`` flags),
checked by their pixels: a body or collider drawn in its own ``colour``, the contact marks
at the points ``world.touching`` reports, the bounding boxes where a turned shape's corners
reach, and each switch leaving out what it names. That the defaults draw today's frames
pixel for pixel was checked against the module before the switches (24 frames of two scenes:
every collider kind, shaped bodies, links and joints, two sizes, alpha 1 and 0.4).
"""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest

from engine import Body, Circle, Plane, Polygon, Rod, Segment, Vector, World
from engine.forces import Gravity
from engine.render import PAPER, Camera, draw_world, init_headless
from engine.render.world_overlays import BOUNDS, CONTACT
from engine.render.world_view import ASLEEP, BODY, INK, SENSOR, SOLID

#: 60 px a metre, the world's origin at the bottom middle of a 480x360 canvas.
CAMERA = Camera(60.0, (240.0, 300.0))
RED = (255, 0, 0)


def canvas() -> pygame.Surface:
    init_headless()
    surface = pygame.Surface((480, 360))
    surface.fill(PAPER)
    return surface


def drawn(world: World, **switches: bool) -> pygame.Surface:
    surface = canvas()
    draw_world(surface, world, CAMERA, **switches)
    return surface


def at(surface: pygame.Surface, p: tuple[float, float]) -> tuple[int, int, int]:
    return tuple(surface.get_at(CAMERA.point(p)))[:3]  # type: ignore[return-value]


def pixels(surface: pygame.Surface) -> np.ndarray:
    return pygame.surfarray.array3d(surface)


def _resting() -> tuple[World, Body, Body, Plane]:
    """A ball and a box at rest on a floor (asleep after 2 s), a peg, a sensor, a rod."""
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -9.81)))
    floor = w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    w.add_collider(Circle((-2.5, 3.0), 0.4))
    w.add_collider(Segment((2.0, 3.5), (3.5, 3.5), 0.1, sensor=True))
    ball = w.add(Body(Vector(-1.0, 0.5), radius=0.5, restitution=0.0))
    box = w.add(Body(Vector(1.0, 0.5), shape=Polygon.box(1.0, 1.0), restitution=0.0))
    bob = w.add(Body(Vector(-3.0, 1.5), radius=0.2))
    w.add_link(Rod(bob, (-3.0, 4.0)))
    for _ in range(120):
        w.step(1.0 / 60.0)
    return w, ball, box, floor


def test_a_body_and_a_collider_are_drawn_in_their_own_colour() -> None:
    w, ball, box, _ = _resting()
    peg, rail = w.colliders[1], w.colliders[2]
    before = pixels(drawn(w))
    assert w.is_sleeping(ball) and at(drawn(w), (-1.0, 0.5)) == ASLEEP
    ball.colour = RED  # asleep or not: a colour given is the body's
    box.colour = "gold"  # a pygame name
    peg.colour = (0, 200, 0)
    rail.colour = "#8000ff"  # a sensor: still an outline, in its colour
    surface = drawn(w)
    assert at(surface, (-1.0, 0.5)) == RED
    assert at(surface, (1.0, 0.5)) == tuple(pygame.Color("gold"))[:3]
    assert at(surface, (-2.5, 3.0)) == (0, 200, 0)
    assert at(surface, (2.75, 3.6)) == (128, 0, 255) and at(surface, (2.75, 3.5)) == PAPER
    # The outline of a shaped body stays in ink; the floor, given no colour, in ink too.
    assert at(surface, (1.0, 0.0)) == SOLID and at(surface, (1.5, 0.5)) == INK
    # Back to None: the World's own colours again, the frame as before any colour was set.
    ball.colour = box.colour = peg.colour = rail.colour = None
    assert np.array_equal(pixels(drawn(w)), before)


def test_a_colour_that_is_the_default_draws_the_same_frame() -> None:
    w = World()
    w.add_collider(Circle((2.0, 2.0), 0.5))
    w.add_collider(Circle((-2.0, 2.0), 0.5, sensor=True))
    ball = w.add(Body(Vector(0.0, 2.0), Vector(1.0, 0.0), radius=0.5))
    w.step(1.0 / 60.0)
    plain = pixels(drawn(w))
    ball.colour = BODY
    w.colliders[0].colour, w.colliders[1].colour = SOLID, SENSOR
    assert np.array_equal(pixels(drawn(w)), plain)
    assert np.array_equal(pixels(drawn(w, shapes=True, joints=True)), plain)


def test_contacts_are_marked_at_the_points_the_world_reports() -> None:
    w, ball, box, floor = _resting()
    touching = [ev for ev in w.touching if ev.collider is floor]
    assert {id(ev.body) for ev in touching} == {id(ball), id(box)}
    foot = next(ev.point for ev in touching if ev.body is ball)
    assert foot.x == pytest.approx(-1.0, abs=1e-9) and foot.y == pytest.approx(0.0, abs=1e-9)
    plain, marked = drawn(w), drawn(w, contacts=True)
    for ev in touching:
        p = (ev.point.x, ev.point.y)
        assert at(plain, p) != CONTACT and at(marked, p) == CONTACT
        # The tick along the normal (up, into the body): 5 px above the point.
        x, y = CAMERA.point(p)
        assert tuple(marked.get_at((x, y - 5)))[:3] == CONTACT
    # Nothing else changes: the marks are all the frames differ by.
    differ = (pixels(plain) != pixels(marked)).any(axis=2)
    assert (pixels(marked)[differ] == CONTACT).all()


def test_bounds_outline_where_a_turned_box_reaches() -> None:
    w = World()
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))  # no end: no box
    w.add_collider(Circle((-3.0, 2.0), 0.5))
    box = w.add(Body(Vector(0.0, 2.0), shape=Polygon.box(1.0, 1.0), angle=math.pi / 4))
    reach = math.sqrt(0.5)  # a unit box at 45 degrees reaches half its diagonal
    plain, boxed = drawn(w), drawn(w, bounds=True)
    for p in ((-reach, 2.0), (reach, 2.0), (0.0, 2.0 + reach), (0.0, 2.0 - reach)):
        # The box's corner touches its bounds there: the outline is one px out or on it.
        x, y = CAMERA.point(p)
        near = {tuple(boxed.get_at((x + dx, y + dy)))[:3] for dx in (-1, 0, 1) for dy in (-1, 0, 1)}
        assert BOUNDS in near
    for p in ((-reach, 2.0 + reach), (reach, 2.0 - reach)):  # the bounds' corners
        assert at(boxed, p) == BOUNDS and at(plain, p) == PAPER
    for p in ((-3.5, 2.5), (-2.5, 1.5)):  # the peg's square
        assert at(boxed, p) == BOUNDS and at(plain, p) == PAPER
    assert at(boxed, (3.0, 0.0)) == SOLID  # the floor, unbounded, has none
    assert box.angle == pytest.approx(math.pi / 4)


def test_each_switch_leaves_out_what_it_names() -> None:
    w, ball, _, _ = _resting()
    mid = (-3.0, (4.0 + w.bodies[2].pos.y) / 2)  # along the rod
    full = drawn(w)
    assert at(full, mid) == INK
    no_joints = drawn(w, joints=False)
    assert at(no_joints, mid) == PAPER and at(no_joints, (-1.0, 0.5)) == ASLEEP
    no_shapes = drawn(w, shapes=False)
    assert at(no_shapes, mid) == INK
    for p in ((-1.0, 0.5), (1.0, 0.5), (-2.5, 3.0), (0.0, 0.0)):
        assert at(no_shapes, p) == PAPER
    nothing = drawn(w, shapes=False, joints=False)
    assert (pixels(nothing) == PAPER).all()
    del ball


def test_a_colour_pygame_does_not_know_is_refused_by_its_owner() -> None:
    w = World()
    w.add(Body(Vector(0.0, 1.0), radius=0.5, colour="not a colour"))
    with pytest.raises(ValueError, match=r"colour 'not a colour' of Body\(.*pygame"):
        drawn(w)
    with pytest.raises(ValueError, match=r"ints 0 to 255.*got tuple \(0, 0, 256\)"):
        Circle((0.0, 0.0), 1.0, colour=(0, 0, 256))
    with pytest.raises(TypeError, match="got float 0.5"):
        Body(Vector(0.0, 0.0), colour=0.5)
    with pytest.raises(AttributeError, match="spells it colour"):
        w.bodies[0].color = RED  # type: ignore[attr-defined]
