"""Colliders take a Filter as bodies do (pymunk's shape filters on static shapes): a body whose
filter and a collider's do not collide passes through it, is not pushed out of it and is not
sensed by it."""

from __future__ import annotations

import warnings

import pytest

from engine import Body, Circle, Filter, OverlapWarning, Plane, Segment, Vector, World
from engine.forces import Gravity

PLAYERS, GHOSTS = 0b01, 0b10


def test_a_floor_for_one_category_lets_the_other_fall_through() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0, -9.81)))
    ghost_floor = w.add_collider(
        Plane((0, 0), (0, 1), filter=Filter(categories=GHOSTS, mask=GHOSTS))
    )
    ground = w.add_collider(Plane((0, -5), (0, 1)))
    player = w.add(
        Body(Vector(0, 1), Vector(0, 0), Vector(0, 0), radius=0.5, filter=Filter(PLAYERS, PLAYERS))
    )
    ghost = w.add(
        Body(Vector(3, 1), Vector(0, 0), Vector(0, 0), radius=0.5, filter=Filter(0, GHOSTS))
    )
    plain = w.add(Body(Vector(6, 1), Vector(0, 0), Vector(0, 0), radius=0.5))
    for _ in range(300):
        w.step(1 / 60)
    assert w.resting(player) is ground and player.pos.y == -4.5
    assert w.resting(ghost) is ghost_floor and ghost.pos.y == 0.5
    assert w.resting(plain) is ghost_floor  # the default filter meets every category


def test_a_group_keeps_its_own_bodies_from_its_collider() -> None:
    # The same nonzero group never collides: a crane's parts pass through its own beam.
    w = World()
    beam = w.add_collider(Circle((0, 0), 1.0, filter=Filter(group=7)))
    part = w.add(
        Body(Vector(-3, 0), Vector(10, 0), Vector(0, 0), radius=0.2, filter=Filter(group=7))
    )
    other = w.add(Body(Vector(-3, 2), Vector(10, -10), Vector(0, 0), radius=0.2))
    with warnings.catch_warnings():
        warnings.simplefilter("error", OverlapWarning)
        part.pos = Vector(0, 0)  # inside its own group's collider: not pushed out
    assert part.pos == Vector(0, 0)
    for _ in range(30):
        w.step(1 / 60)
    assert part.pos.x > 4.0  # straight through
    assert other.vel.x < 0.0 or other.vel.y > 0.0  # bounced off the beam
    assert beam in w.colliders


def test_a_sensor_senses_only_the_bodies_its_filter_meets() -> None:
    w = World()
    cup = w.add_collider(
        Circle((0, 0), 2.0, sensor=True, filter=Filter(categories=GHOSTS, mask=GHOSTS))
    )
    seen: list[Body] = []
    w.on_contact(cup, begin=lambda e: seen.append(e.body))
    player = w.add(
        Body(Vector(0, 0), Vector(0, 0), Vector(0, 0), radius=0.5, filter=Filter(0, PLAYERS))
    )
    ghost = w.add(
        Body(Vector(1, 0), Vector(0, 0), Vector(0, 0), radius=0.5, filter=Filter(0, GHOSTS))
    )
    w.step(1 / 60)
    assert seen == [ghost] and player not in seen


def test_a_body_that_meets_nothing_passes_through_colliders_with_default_filters() -> None:
    """Filter.collides says a body of mask 0 (it meets nothing) or of categories 0 (nothing
    meets it) collides with no collider, even one with the default filter: it falls through
    the floor at g (x = x0 - g t^2 / 2, exactly: the closed form) and no sensor senses it,
    while a plain ball rests on the floor."""
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -10.0)))
    world.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    sensor = world.add_collider(Circle((0.0, -3.0), 1.0, sensor=True))
    blind = world.add(Body(Vector(0.0, 1.0), radius=0.5, filter=Filter(mask=0)))
    unseen = world.add(Body(Vector(0.0, 1.0), radius=0.5, filter=Filter(categories=0)))
    ball = world.add(Body(Vector(5.0, 0.5), radius=0.5))
    sensed = []
    for _ in range(60):
        world.step(1 / 60)
        sensed += [e.body for e in world.began if e.collider is sensor]
    for body in (blind, unseen):
        assert body.pos.y == pytest.approx(1.0 - 5.0 * world.t**2, abs=1e-9)
    assert ball.pos.y == 0.5
    assert sensed == []


def test_a_body_that_meets_nothing_still_passes_after_the_colliders_change() -> None:
    """The same after a collider is taken out and put back and another added (the faces are
    made again): the body of mask 0 keeps falling at g, through the new floor too."""
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -10.0)))
    floor = world.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    blind = world.add(Body(Vector(0.0, 1.0), radius=0.5, filter=Filter(mask=0)))
    world.step(1 / 60)
    world.remove_collider(floor)
    world.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    world.add_collider(Segment((5.0, 0.0), (6.0, 0.0)))
    for _ in range(59):
        world.step(1 / 60)
    assert blind.pos.y == pytest.approx(1.0 - 5.0 * world.t**2, abs=1e-9)
