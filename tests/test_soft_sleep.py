"""Sleep in the soft step (engine.pipeline.game_sleep): still islands sleep, exactly still, with
their contacts open; an awake body that comes, a hand that writes, or a platform that moves wakes
them; on both paths."""

import math

import numpy as np
import pytest

from demos import stack
from engine import Body, Hinge, Polygon, World
from engine.forces import Gravity
from tests.paths import PATHS

DT = 1.0 / 60.0


def pile(kernels: str, base: int = 5) -> tuple[World, list[Body]]:
    """A soft pyramid of ``base`` boxes at the bottom (demos.stack's)."""
    return stack.pyramid(base, kernels=kernels, solver="soft")


def contacts(world: World, but: Body) -> list[tuple[int, int, tuple[float, ...]]]:
    """The open contacts but ``but``'s: whose, where, along what, with what impulse (N s)."""
    return sorted(
        (id(e.body), id(e.collider), (*e.point, *e.normal, *e.impulse))
        for e in world.touching
        if but not in (e.body, e.collider)
    )


def settle(world: World, seconds: float) -> None:
    for _ in range(round(seconds / DT)):
        world.step(DT)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_still_pile_sleeps_exactly_still_with_its_contacts_open(kernels: str) -> None:
    world, boxes = pile(kernels)
    # A puck sliding on far away, frictionless: the World stays awake around the pile.
    puck = world.add(Body((40.0, 0.25), (2.0, 0.0), mass=1.0, radius=0.25, friction=0.0))
    ended = 0
    for _ in range(120):
        world.step(DT)
        ended += len(world.ended)
    assert world.sleeping == len(boxes) and not world.is_sleeping(puck)
    x, touching = world.positions()[: len(boxes)].copy(), contacts(world, puck)
    for _ in range(60):
        world.step(DT)
        ended += len(world.ended)
    assert np.array_equal(world.positions()[: len(boxes)], x)  # not a hair
    assert all(b.vel.x == b.vel.y == b.angular_velocity == 0.0 for b in boxes)
    # Nothing ended as it fell asleep, nor while it sleeps.
    assert ended == 0 and contacts(world, puck) == touching


@pytest.mark.parametrize("kernels", PATHS)
def test_a_body_is_still_by_its_shapes_fastest_point_as_box2d_v3_tests_it(kernels: str) -> None:
    # Box2D v3 (b2FinalizeBodiesTask): |v| + r |omega| under 0.05 m/s, r the body's extent.
    # Tested apart, as Box2D v2.4 did (0.05 m/s, 2 degrees a second), a 6 m plank turning at
    # 0.03 rad/s looked still and slept while its ends swept at 9 cm/s, and a 5 cm disc
    # spinning in place at 0.5 rad/s (its rim at 2.5 cm/s) never slept. No gravity: each
    # flies the closed form, spinning at its own rate, until it sleeps.
    from engine import Plane

    world = World(kernels=kernels, solver="soft")
    world.add_collider(Plane((0.0, -50.0), (0.0, 1.0)))
    plank = world.add(Body((0.0, 0.0), shape=Polygon.box(6.0, 0.2), mass=1.0))
    disc = world.add(Body((20.0, 0.0), radius=0.05, mass=1.0))
    plank.angular_velocity, disc.angular_velocity = 0.03, 0.5
    settle(world, 2.0)
    assert not world.is_sleeping(plank)
    assert plank.angle == pytest.approx(0.06, abs=1e-12) and plank.angular_velocity == 0.03
    assert world.is_sleeping(disc) and disc.angular_velocity == 0.0
    # It slept once still for World.sleep_time (0.5 s): its turn stopped there.
    assert disc.angle == pytest.approx(0.5 * world.sleep_time, abs=0.5 * DT + 1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_nothing_sleeps_with_sleep_off(kernels: str) -> None:
    world, boxes = pile(kernels)
    world.sleep_time = math.inf
    settle(world, 2.0)
    assert world.sleeping == 0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_thrown_at_a_sleeping_pile_wakes_it_and_knocks_it(kernels: str) -> None:
    world, boxes = pile(kernels)
    settle(world, 2.0)
    assert world.sleeping == len(boxes)
    top = boxes[-1]
    before = top.pos
    ball = world.add(Body((-6.0, 4.6), (12.0, 0.0), mass=20.0, radius=0.4))
    settle(world, 1.0)
    assert world.sleeping < len(boxes)
    assert (top.pos - before).length() > 0.5  # the top box was knocked off
    assert ball.pos.x < 6.0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_rolling_past_a_sleeping_crate_wakes_it_only_when_it_comes_near(
    kernels: str,
) -> None:
    # A 1 m crate asleep on a floor; a ball of radius 0.35 rolls along the floor past its side,
    # 0.1 m clear of it: inside the crate's bounding circle (radius 0.71) but outside its box
    # by more than the speculative distance, so the crate sleeps on (the crates demo's ball,
    # rolling on for ever at 3 cm/s, kept its column awake); then the ball is sent at it, and
    # the crate wakes as they meet.
    from engine import Plane, Vector

    world = World(kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    crate = world.add(Body(Vector(0.0, 0.5), shape=Polygon.box(1.0, 1.0), mass=2.0))
    settle(world, 1.0)
    assert world.is_sleeping(crate)
    ball = world.add(Body(Vector(-0.95, 0.35), radius=0.35, friction=0.0))
    settle(world, 0.5)  # the ball settles, 0.1 m from the crate's side
    assert world.is_sleeping(crate)
    ball.vel = Vector(0.02, 0.0)  # slow, and still 0.09 m clear after 0.5 s
    settle(world, 0.5)
    assert world.is_sleeping(crate) and -0.95 < ball.pos.x < -0.9
    ball.vel = Vector(2.0, 0.0)  # now it comes: the crate wakes as they meet
    settle(world, 0.5)
    assert crate.pos.x > 0.01  # woken and shoved along the floor (a sleeper never moves)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_box_written_by_hand_wakes_its_island(kernels: str) -> None:
    world, boxes = pile(kernels)
    settle(world, 2.0)
    boxes[0].vel = (0.0, 0.1)  # the game nudges a bottom box
    world.step(DT)
    assert world.sleeping == 0  # the pile is one island: it all woke


@pytest.mark.parametrize("kernels", PATHS)
def test_a_platform_that_starts_to_move_wakes_the_crate_on_it(kernels: str) -> None:
    world = World(kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -9.81)))
    lift = world.add(Body((0, 0), shape=Polygon.box(4, 0.5), kinematic=True))
    crate = world.add(Body((0, 0.75), mass=1.0, shape=Polygon.box(1, 1), friction=0.8))
    settle(world, 1.5)
    assert world.is_sleeping(crate)
    lift.vel = (1.0, 0.0)
    settle(world, 1.0)
    assert not world.is_sleeping(crate)
    # Carried, not left behind: it slips while friction (0.8 g) brings it to the lift's
    # speed, a tenth of a metre, then rides at it.
    assert crate.vel.x == pytest.approx(1.0, abs=1e-3)
    assert crate.pos.x > 0.8


@pytest.mark.parametrize("kernels", PATHS)
def test_body_sleep_puts_its_touching_island_to_sleep(kernels: str) -> None:
    world, boxes = pile(kernels)
    world.sleep_time = 60.0  # not on its own in this test
    settle(world, 0.5)
    assert world.sleeping == 0
    boxes[0].sleep()
    assert world.sleeping == len(boxes)  # every box touches another: one island
    x = world.positions().copy()
    world.step(DT)
    assert np.array_equal(world.positions(), x)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_motor_started_on_a_hinge_asleep_wakes_it_and_turns_it(kernels: str) -> None:
    """A wheel on a hinge whose motor stands at 0 falls asleep; a motor speed (or torque, or
    limits) set then wakes it, as pymunk's wakes the bodies, and the motor turns it."""
    w = World(solver="soft", kernels=kernels)
    wheel = w.add(Body((0.0, 0.0), mass=1.0, shape=Polygon.box(1.0, 1.0)))
    hinge = w.add_link(Hinge(wheel, w.static_body, (0.0, 0.0), motor_speed=0.0, max_torque=5.0))
    for _ in range(60):
        w.step(DT)
    assert w.is_sleeping(wheel)
    hinge.motor_speed = 0.0  # no change: it sleeps on
    assert w.is_sleeping(wheel)
    hinge.motor_speed = 2.0
    assert not w.is_sleeping(wheel)
    for _ in range(30):
        w.step(DT)
    # I = 1/6 kg m^2, 5 N m: at the speed within 0.07 s, and held there.
    assert wheel.angular_velocity == pytest.approx(2.0, abs=1e-9)
    for setting, value in (("max_torque", 4.0), ("limits", (-1.0, 100.0))):
        hinge.motor_speed = 0.0
        for _ in range(60):
            w.step(DT)
        assert w.is_sleeping(wheel)
        setattr(hinge, setting, value)
        assert not w.is_sleeping(wheel), setting


@pytest.mark.parametrize("kernels", PATHS)
def test_a_body_taken_out_wakes_what_it_touched_and_no_other_pile(kernels: str) -> None:
    # Box2D wakes the bodies a destroyed body touched or was joined to, alone: a puck taken
    # out wakes no pile asleep, a box taken from under another wakes that one
    # (which falls), and a box hinged to one taken out wakes (a puck sliding on, taken out).
    world, boxes = pile(kernels, base=3)
    top = boxes[-1]
    ball = world.add(Body((30.0, 0.25), (2.0, 0.0), mass=1.0, radius=0.25, friction=0.0))
    hinged = world.add(Body((-30.0, 0.5), shape=Polygon.box(1.0, 1.0), mass=1.0))
    holder = world.add(Body((-28.0, 0.5), shape=Polygon.box(1.0, 1.0), mass=1.0))
    world.add_link(Hinge(hinged, holder, (-29.0, 0.5)))
    settle(world, 4.0)
    assert world.sleeping == len(boxes) + 2 and not world.is_sleeping(ball)  # (it slides on)
    world.remove(ball)
    world.step(DT)
    assert world.sleeping == len(boxes) + 2
    world.remove(holder)
    world.step(DT)
    assert not world.is_sleeping(hinged)
    assert world.sleeping == len(boxes)
    below = boxes[-2]  # (one of the two boxes under the top: it rests on both)
    was = top.pos
    world.remove(below)
    world.step(DT)
    assert not world.is_sleeping(top)
    settle(world, 1.0)
    assert (top.pos - was).length() > 0.01  # it tips over the gap
