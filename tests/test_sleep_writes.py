"""Writing one body by hand (its velocity, position or own acceleration) wakes that body and its
sleeping group, not the whole World (engine.collisions.wake_body): a game that sets its
player's velocity every step lets the rest of the level sleep, and a body sent into a sleeper
wakes it when it meets it."""

from __future__ import annotations

from engine import Body, Polygon, Segment, Vector, World
from engine.forces import Gravity

DT = 1 / 60


def level() -> tuple[World, Body, Body, Body]:
    """A floor 30 m long; a stack of two crates at x = 20; a player box at x = 1 that never
    turns."""
    world = World(integrator="auto")
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
