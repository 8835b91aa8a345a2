"""A body with a shape meets a sensor by its shape, not by its bounding circle
(engine.geometry.sensors): a coin beside a player's box, inside the box's bounding circle but clear
of its corners, is not collected; one that overlaps the box, or a corner of a turned box, is."""

from __future__ import annotations

import math

import pytest

from engine import Body, Circle, Plane, Polygon, Segment, Vector, World

DT = 1 / 60


def one_step(body: Body, sensor: object) -> list[object]:
    """The colliders whose contacts with ``body`` began in one step, no gravity."""
    world = World()
    world.add(body)
    world.add_collider(sensor)  # type: ignore[arg-type]
    world.step(DT)
    return [e.collider for e in world.began]


def player(angle: float = 0.0) -> Body:
    # A 0.8 x 1.6 box: bounding radius sqrt(0.4^2 + 0.8^2) = 0.894 m.
    body = Body(Vector(0.0, 0.0), shape=Polygon.box(0.8, 1.6), mass=4.0)
    body.angle = angle
    return body


@pytest.mark.parametrize(
    ("center", "radius", "meets"),
    [
        ((0.8, 0.2), 0.3, False),  # 0.1 m clear of the side, 0.82 m from the centre
        ((0.65, 0.2), 0.3, True),  # 0.05 m into the side
        ((0.6, 0.9), 0.15, False),  # off the corner (0.4, 0.8) by 0.224 - 0.15 m
        ((0.5, 0.85), 0.15, True),  # over the corner: 0.112 < 0.15 m
    ],
)
def test_a_circle_sensor_meets_a_box_by_its_sides_and_corners(center, radius, meets) -> None:  # type: ignore[no-untyped-def]
    coin = Circle(center, radius, sensor=True)
    assert (coin in one_step(player(), coin)) is meets


def test_a_turned_box_meets_a_sensor_its_corner_reaches() -> None:
    # Turned 45 degrees, the box's corner (0.4, 0.8) lies at (-0.283, 0.849): a coin there meets
    # it; unturned, the same coin is 0.03 m clear of the box's top.
    coin = Circle((-0.283, 1.03), 0.2, sensor=True)
    assert coin in one_step(player(math.pi / 4), coin)
    assert coin not in one_step(player(0.0), coin)


def test_a_capsule_meets_a_segment_sensor_by_its_length() -> None:
    # A 2 m capsule of radius 0.1 lying along x; a thin sensor line at y = 0.3 clear of it,
    # then at y = 0.15, and at y = 0.05 (in it).
    for y, meets in ((0.3, False), (0.15, False), (0.05, True)):
        body = Body(Vector(0.0, 0.0), shape=Segment((-1.0, 0.0), (1.0, 0.0), radius=0.1), mass=1)
        line = Segment((0.5, y), (3.0, y), sensor=True)
        assert (line in one_step(body, line)) is meets, y


def test_a_box_leaving_a_sensor_ends_its_contact_when_its_shape_leaves() -> None:
    # A zone: everything right of x = 0 (a Plane whose free side faces -x). A 0.8 m wide box
    # starts across its edge, runs into it for a second, then back out at 3 m/s: its contact
    # ends in the step in which its right side x + 0.4 passes below 0, not while its bounding
    # circle (0.894 m) still reaches the zone.
    world = World()
    box = world.add(Body(Vector(0.0, 0.0), Vector(3.0, 0.0), shape=Polygon.box(0.8, 1.6), mass=4))
    zone = world.add_collider(Plane((0.0, 0.0), (-1.0, 0.0), sensor=True))
    for _ in range(60):
        world.step(DT)
        assert not any(e.collider is zone for e in world.ended)
    box.vel = Vector(-3.0, 0.0)
    for _ in range(180):
        world.step(DT)
        if any(e.collider is zone for e in world.ended):
            assert box.pos.x + 0.4 < 0.0 <= box.pos.x + 0.4 + 3.0 * DT + 1e-12
            return
    pytest.fail("the box's contact with the zone never ended")
