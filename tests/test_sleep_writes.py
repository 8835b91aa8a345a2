"""Writing one body by hand (its velocity, position or own acceleration) wakes that body and its
sleeping group, not the whole World (engine.exact.collisions.wake_body): a game that sets its
player's velocity every step lets the rest of the level sleep, and a body sent into a sleeper
wakes it when it meets it. The game can put a body to sleep itself, with what touches it, and
wake it (Body.sleep, Body.activate: pymunk's names)."""

from __future__ import annotations

import math

import pytest

from engine import Body, Polygon, Segment, Vector, World
from engine.forces import Gravity

DT = 1 / 60


def level() -> tuple[World, Body, Body, Body]:
    """A floor 30 m long; a stack of two crates at x = 20; a player box at x = 1 that never
    turns. The exact models, asked for: a sleeper let go falls the closed form's parabola."""
    world = World(integrator="auto", solver="exact")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Segment((0.0, 0.0), (30.0, 0.0)))
    low = world.add(Body(Vector(20.0, 0.5), shape=Polygon.box(1.0, 1.0), mass=2.0,
                         restitution=0.0, friction=0.6))  # fmt: skip
    high = world.add(Body(Vector(20.0, 1.5), shape=Polygon.box(1.0, 1.0), mass=2.0,
                          restitution=0.0, friction=0.6))  # fmt: skip
    player = world.add(Body(Vector(1.0, 0.8), shape=Polygon.box(0.8, 1.6), mass=4.0,
                            restitution=0.0, friction=0.6, fixed_rotation=True))  # fmt: skip
    return world, low, high, player


def test_a_pile_sleeps_while_the_game_sets_its_players_velocity_every_step() -> None:
    world, low, high, player = level()
    for _ in range(120):
        player.vel = Vector(0.0, player.vel.y)  # the game's control, every step
        world.step(DT)
    assert world.is_sleeping(low) and world.is_sleeping(high)


def test_writing_a_sleepers_velocity_wakes_its_whole_group() -> None:
    world, low, high, player = level()
    for _ in range(120):
        world.step(DT)
    assert world.is_sleeping(low) and world.is_sleeping(high)
    high.vel = Vector(2.0, 0.0)  # shove the top crate
    assert not world.is_sleeping(high) and not world.is_sleeping(low)


def test_a_player_sent_into_a_sleeping_crate_wakes_it_and_pushes_it() -> None:
    world, low, high, player = level()
    for _ in range(120):
        player.vel = Vector(0.0, player.vel.y)
        world.step(DT)
    assert world.is_sleeping(low)
    x0 = low.pos.x
    for _ in range(300):  # run right at 5 m/s into the stack
        player.vel = Vector(5.0, player.vel.y)
        world.step(DT)
    assert low.pos.x > x0 + 1.0  # woken and shoved along the floor
    assert player.pos.x < low.pos.x - 0.5 - 0.4 + 1e-3  # never through it


# -- the game puts a body to sleep and wakes it (Body.sleep, Body.activate: pymunk's names) -----


def test_a_body_put_to_sleep_in_flight_stays_put_until_activated() -> None:
    world, low, high, player = level()
    ball = world.add(Body(Vector(10.0, 5.0), Vector(2.0, 3.0), radius=0.25))
    for _ in range(6):
        world.step(DT)
    ball.sleep()
    at = ball.pos
    assert ball.is_sleeping and world.is_sleeping(ball) and ball.vel == Vector(0.0, 0.0)
    assert not player.is_sleeping
    for _ in range(30):
        world.step(DT)
    assert ball.pos == at and ball.vel == Vector(0.0, 0.0) and ball.is_sleeping
    ball.activate()
    assert not ball.is_sleeping
    for _ in range(30):
        world.step(DT)
    # From rest where it slept: the closed form y = y0 - g t^2 / 2 at t = 0.5 s.
    assert ball.pos.x == at.x
    assert ball.pos.y == pytest.approx(at.y - 9.81 * 0.5**2 / 2, rel=1e-12)


def test_sleep_takes_the_bodies_touching_and_activate_wakes_them_all() -> None:
    world, low, high, player = level()
    for _ in range(10):  # the crates rest on each other, not yet asleep
        world.step(DT)
    assert world.sleeping == 0
    high.sleep()
    assert low.is_sleeping and high.is_sleeping and not player.is_sleeping
    held = (low.pos, high.pos, low.angle, high.angle)
    for _ in range(60):
        world.step(DT)
    assert (low.pos, high.pos, low.angle, high.angle) == held
    low.activate()
    assert not low.is_sleeping and not high.is_sleeping
    low.activate()  # awake already: nothing to do
    assert not low.is_sleeping and not high.is_sleeping


def test_a_sleeper_wakes_when_an_awake_body_meets_it() -> None:
    world, low, high, player = level()
    ball = world.add(Body(Vector(10.0, 3.0), radius=0.25))
    world.step(DT)
    ball.sleep()
    world.add(Body(Vector(10.0, 5.0), radius=0.25))  # falls onto the sleeper
    for _ in range(60):
        world.step(DT)
    assert not ball.is_sleeping and ball.pos.y < 3.0


def test_sleep_is_refused_where_the_body_cannot_sleep_saying_why() -> None:
    lone = Body(Vector(0.0, 5.0), radius=0.25)
    with pytest.raises(ValueError, match=r"in none: add it first \(world\.add\(body\)\)"):
        lone.sleep()
    lone.activate()  # out of a World nothing sleeps: there is nothing to wake
    assert not lone.is_sleeping
    world, low, high, player = level()
    paddle = world.add(Body(Vector(5.0, 3.0), shape=Polygon.box(2, 0.2), kinematic=True))
    with pytest.raises(ValueError, match="kinematic.*never sleeps.*Body"):
        paddle.sleep()
    world.sleep_time = math.inf
    with pytest.raises(ValueError, match=r"sleep is off.*world\.sleep_time"):
        low.sleep()
    line = World()
    beads = line.add_all([Body(0.0, 1.0, radius=0.1), Body(1.0, 0.0, radius=0.1)])
    with pytest.raises(ValueError, match="no two bodies of this World can meet"):
        beads[0].sleep()
    assert not any(b.is_sleeping for b in (paddle, low, *beads))
