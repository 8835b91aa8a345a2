"""A body put inside solid colliders (added there, teleported there, or caught by a new
collider) is pushed to the nearest place outside all of them, warned about, and rests on
nothing it no longer touches."""

from __future__ import annotations

import random
import warnings

import pytest

from engine import Body, Box, Circle, OverlapWarning, Plane, Segment, Vector, World
from engine.forces import Gravity


def overlaps(world: World, body: Body) -> list[tuple[object, float]]:
    """The solid colliders the body overlaps (by more than 1e-9), with the depth."""
    out = []
    for c in world.colliders:
        if not c.sensor:
            d = c.distance(body.pos) - body.radius
            if d < -1e-9:
                out.append((c, d))
    return out


def test_a_ball_added_in_a_peg_under_a_short_wall_ends_outside_both() -> None:
    # Straight up out of the peg is into the wall, straight down out of the wall is into the
    # peg: the nearest place outside both is beside them, where their surfaces meet.
    w = World()
    w.add_collider(Circle((0, 0), 0.5))
    w.add_collider(Segment((-0.5, 0.9), (0.5, 0.9)))
    with pytest.warns(OverlapWarning, match="started inside"):
        b = w.add(Body(Vector(0, 0.2), Vector(0, 0), Vector(0, 0), radius=0.3))
    assert overlaps(w, b) == []
    # It is where the peg's surface (offset by r) meets the wall's end cap (offset by r).
    assert abs(b.pos.distance_to((0, 0)) - 0.8) < 1e-9
    assert abs(b.pos.distance_to((0.5, 0.9)) - 0.3) < 1e-9 or abs(b.pos.y - 0.6) < 1e-9
    for _ in range(30):
        w.step(1 / 60)
        assert overlaps(w, b) == []


def test_random_balls_added_on_walls_and_among_pegs_end_outside_every_one() -> None:
    rng = random.Random(7)
    for _ in range(200):
        w = World()
        a = (rng.uniform(-2, 2), rng.uniform(-2, 2))
        z = (rng.uniform(-2, 2), rng.uniform(-2, 2))
        w.add_collider(Segment(a, z, radius=rng.choice([0.0, 0.1])))
        for _ in range(rng.randint(0, 3)):
            w.add_collider(Circle((rng.uniform(-2, 2), rng.uniform(-2, 2)), rng.uniform(0.1, 0.8)))
        u = rng.uniform(-0.3, 1.3)  # on the wall's line, on it or beyond an end
        p = (a[0] + u * (z[0] - a[0]), a[1] + u * (z[1] - a[1]))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OverlapWarning)
            b = w.add(Body(Vector(*p), Vector(0, 0), Vector(0, 0), radius=rng.uniform(0.05, 0.5)))
        assert overlaps(w, b) == [], (p, w.colliders, b)


def test_writing_pos_into_a_collider_pushes_out_and_warns() -> None:
    w = World()
    w.add_collider(Circle((0, 0), 1.0))
    b = w.add(Body(Vector(3, 0), Vector(0, 0), Vector(0, 0), radius=0.3))
    with pytest.warns(OverlapWarning, match="was put inside") as record:
        b.pos = Vector(0.5, 0)
    assert record[0].filename == __file__  # the warning points at the line that wrote pos
    assert b.pos == Vector(1.3, 0.0)


def test_a_ball_pushed_into_a_new_smaller_room_stays_in_it() -> None:
    # Resting on the old floor, the ball is caught by a new room whose floor is higher: it is
    # pushed into the room and lands on the new floor, not snapped back onto the old one.
    w = World(integrator="auto")
    w.add_force(Gravity((0, -9.81)))
    w.add_collider(Plane((0, 0), (0, 1)))
    b = w.add(Body(Vector(0, 0.5), Vector(0, 0), Vector(0, 0), radius=0.5))
    for _ in range(10):
        w.step(1 / 60)
    assert w.resting(b) is not None
    with pytest.warns(OverlapWarning):
        room = w.add_collider(Box((-2, 1), (2, 5)))
    assert w.resting(b) is None
    for _ in range(120):
        w.step(1 / 60)
        assert overlaps(w, b) == []
    assert w.resting(b) is room and abs(b.pos.y - 1.5) < 1e-12
