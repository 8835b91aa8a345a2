"""Kinematic bodies (``Body(kinematic=True)``): moved by the game, immovable to everything else.

No force acts on one; contacts take its mass as infinite, so a ball it strikes leaves as from
a moving wall (v' = V + e (V - v) along the normal), and a ball resting on it rides it by
friction. Static colliders and other kinematic bodies do not stop it.
"""

from __future__ import annotations

import warnings

import pytest

from engine import Body, Box, Vector, World
from engine.forces import Gravity

DT = 1.0 / 120.0


def disc(x: float, y: float, vx: float = 0.0, vy: float = 0.0, **kw: object) -> Body:
    return Body(Vector(x, y), Vector(vx, vy), Vector(0, 0), **kw)  # type: ignore[arg-type]


def test_no_force_acts_on_a_kinematic_body() -> None:
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -9.81)))
    paddle = world.add(disc(0.0, 0.0, 2.0, 0.0, radius=0.5, kinematic=True))
    stone = world.add(disc(5.0, 5.0, radius=0.5))
    for _ in range(120):
        world.step(DT)
    assert paddle.pos == Vector(2.0, 0.0) and paddle.vel == Vector(2.0, 0.0)
    assert stone.pos.y == pytest.approx(5.0 - 0.5 * 9.81, rel=1e-12)  # the rest still fall


def test_writing_pos_moves_it_there_over_the_next_step() -> None:
    world = World()
    paddle = world.add(disc(0.0, 0.0, radius=0.5, kinematic=True, restitution=0.5))
    paddle.pos = Vector(0.3, -0.1)
    assert paddle.pos == Vector(0.0, 0.0)  # not a teleport: it gets there by moving
    world.step(DT)
    assert paddle.pos.x == pytest.approx(0.3, rel=1e-15)
    assert paddle.pos.y == pytest.approx(-0.1, rel=1e-15)
    # ... and stops there: its velocity is the one last written (none).
    assert paddle.vel == Vector(0.0, 0.0)
    world.step(DT)
    assert paddle.pos.x == pytest.approx(0.3, rel=1e-15)
    # Moved by pos, it strikes what is in its way at the speed of the move.
    ball = world.add(disc(1.3 + 0.3, 0.0, radius=0.5, restitution=1.0))
    paddle.vel = Vector(1.0, 0.0)
    paddle.pos = Vector(0.6, 0.0)  # 0.3 m in one step: 36 m/s, through the ball's edge
    world.step(DT)
    assert paddle.vel == Vector(1.0, 0.0)
    assert ball.vel.x == pytest.approx(0.3 / DT * (1.0 + 0.5 * 1.0), rel=1e-9)  # V + e (V - 0)


@pytest.mark.parametrize("e_ball", [1.0, 0.5, 0.0])
def test_a_moving_kinematic_body_strikes_a_ball_as_a_moving_wall(e_ball: float) -> None:
    world = World(integrator="auto")
    pusher = world.add(disc(0.0, 0.0, 3.0, 0.0, radius=0.5, kinematic=True, restitution=1.0))
    target = world.add(disc(2.0, 0.0, -1.0, 0.0, radius=0.5, restitution=e_ball, mass=50.0))
    for _ in range(60):
        world.step(DT)
    # v' = V + e (V - v) with V = 3, v = -1: the ball's mass does not matter.
    assert target.vel.x == pytest.approx(3.0 + e_ball * 4.0, rel=1e-9)
    assert pusher.vel == Vector(3.0, 0.0)
    assert (target.pos - pusher.pos).length() >= 1.0 - 1e-9


def test_a_ball_on_a_moving_platform_rides_it() -> None:
    # A ball that does not turn (fixed_rotation): one that turns rolls (the test below).
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -9.81)))
    platform = world.add(disc(0.0, 0.0, radius=5.0, kinematic=True, friction=1.0))
    rider = world.add(
        disc(0.0, 5.5, radius=0.5, friction=1.0, restitution=0.0, fixed_rotation=True)
    )
    for _ in range(60):
        world.step(DT)
    assert rider.pos.y == pytest.approx(5.5, abs=0.01 * 0.5)
    platform.vel = Vector(1.0, 0.0)
    for _ in range(240):
        world.step(DT)
    assert rider.vel.x == pytest.approx(1.0, rel=1e-6)
    # It slips while friction mu g brings it up to speed: by v^2 / (2 mu g) in the closed
    # form; the step's discrete pushes may miss that by a step's worth of slip (v dt / 2).
    slip = 1.0**2 / (2.0 * 1.0 * 9.81)
    assert platform.pos.x - rider.pos.x == pytest.approx(slip, abs=0.5 * DT)
    assert rider.pos.y == pytest.approx(5.5, abs=0.01 * 0.5)


def test_a_ball_that_turns_rolls_on_a_platform_set_moving_under_it() -> None:
    # A solid disc at rest on a platform that sets off at u: friction's impulse J gives it
    # v = J / m and omega r = J r^2 / I = 2 v, until its underside moves with the platform,
    # v + omega r = u: v = u / 3, omega r = 2 u / 3 (a ball on a belt). It then rolls back
    # along the platform's round top, off it. Before the step made the spin of a World
    # without colliders, the pile's friction acted on its centre and it rode the platform.
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -9.81)))
    platform = world.add(disc(0.0, 0.0, radius=5.0, kinematic=True, friction=1.0))
    rider = world.add(disc(0.0, 5.5, radius=0.5, friction=1.0, restitution=0.0))
    for _ in range(60):
        world.step(DT)
    platform.vel = Vector(1.0, 0.0)
    for _ in range(12):  # 0.1 s: friction mu g stops the slip u in u / (3 mu g) = 0.034 s
        world.step(DT)
    r = 0.5
    # Within 1% (the platform's top curves away under it as it rolls back, 7 cm by now).
    assert rider.vel.x == pytest.approx(1.0 / 3.0, abs=0.01)
    assert rider.vel.x + rider.angular_velocity * r == pytest.approx(1.0, abs=0.01)


def test_walls_and_other_kinematic_bodies_do_not_stop_it() -> None:
    world = World()
    world.add_collider(Box((-1.0, -1.0), (1.0, 1.0)))
    a = world.add(disc(0.0, 0.0, 5.0, 0.0, radius=0.2, kinematic=True))
    b = world.add(disc(0.5, 0.0, -5.0, 0.0, radius=0.2, kinematic=True))
    for _ in range(120):
        world.step(DT)
    assert a.pos.x == pytest.approx(5.0, rel=1e-12)
    assert b.pos.x == pytest.approx(-4.5, rel=1e-12)


def test_moving_a_kinematic_body_does_not_wake_a_pile_it_does_not_touch() -> None:
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Box((0.0, 0.0), (10.0, 10.0)))
    pile = world.add_all(disc(1.0 + k, 0.5, radius=0.5, restitution=0.0) for k in range(3))
    paddle = world.add(disc(8.0, 5.0, radius=0.5, kinematic=True))
    for _ in range(240):
        world.step(DT)
    assert all(world.is_sleeping(b) for b in pile)
    for k in range(60):
        paddle.vel = Vector(0.0, 0.1 if k % 2 else -0.1)
        world.step(DT)
    assert all(world.is_sleeping(b) for b in pile)
    assert not world.is_sleeping(paddle)
    # ... and it wakes what it runs into.
    paddle.pos = Vector(2.0, 1.52)
    for _ in range(2):
        world.step(DT)
    assert not all(world.is_sleeping(b) for b in pile)


def test_kinematic_must_be_a_bool_and_shows_in_repr() -> None:
    with pytest.raises(TypeError, match="kinematic must be True"):
        disc(0.0, 0.0, kinematic=1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert "kinematic=True" in repr(disc(0.0, 0.0, kinematic=True))
        assert "kinematic" not in repr(disc(0.0, 0.0))


def test_a_snapshot_keeps_a_move_written_but_not_yet_taken() -> None:
    world = World()
    paddle = world.add(disc(0.0, 0.0, radius=0.5, kinematic=True, restitution=0.5))
    paddle.pos = Vector(1.0, 0.0)
    snap = world.snapshot()
    world.step(DT)
    assert paddle.pos == Vector(1.0, 0.0)
    world.restore(snap)
    assert paddle.pos == Vector(0.0, 0.0)
    world.step(DT)
    assert paddle.pos == Vector(1.0, 0.0)  # the move came back with the snapshot


def test_contact_handlers_see_their_own_body_first_and_can_be_taken_off() -> None:
    world = World()
    a = world.add(disc(0.0, 0.0, 1.0, 0.0, radius=0.5, restitution=1.0))
    b = world.add(disc(2.0, 0.0, radius=0.5, restitution=1.0))
    seen: list[tuple[Body, Body, float]] = []
    world.on_contact(a, begin=lambda ev: seen.append((ev.body, ev.collider, ev.normal.x)))
    stop = world.on_contact(b, begin=lambda ev: seen.append((ev.body, ev.collider, ev.normal.x)))
    for _ in range(180):
        world.step(DT)
    # One blow, seen by each from its own side: the normal points toward the handler's body.
    assert seen == [(a, b, -1.0), (b, a, 1.0)] or seen == [(b, a, 1.0), (a, b, -1.0)]
    stop()
    stop()  # twice is harmless
    seen.clear()
    b.vel = Vector(-2.0, 0.0)
    a.vel = Vector(0.0, 0.0)
    for _ in range(180):
        world.step(DT)
    assert [s[0] for s in seen] == [a]


def test_the_worlds_energy_leaves_out_what_the_game_moves() -> None:
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -9.81)))
    stone = world.add(disc(0.0, 10.0, mass=2.0))
    lift = world.add(disc(5.0, 0.0, 0.0, 3.0, mass=100.0, kinematic=True))
    e0 = world.energy()
    assert e0 == pytest.approx(2.0 * 9.81 * 10.0, rel=1e-15)
    for _ in range(60):
        world.step(DT)
    assert lift.pos.y > 1.0  # it rose, and its energy is not the World's
    # The stone fell for 0.5 s, trading height for speed.
    assert stone.pos.y == pytest.approx(10.0 - 0.5 * 9.81 * 0.5**2, rel=1e-12)
    assert world.energy() == pytest.approx(e0, rel=1e-12)


def test_a_kinematic_body_may_start_inside_a_wall() -> None:
    world = World()
    world.add_collider(Box((0.0, 0.0), (4.0, 4.0)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no OverlapWarning: it is not pushed out
        gate = world.add(disc(0.0, 2.0, radius=0.5, kinematic=True))
    assert gate.pos == Vector(0.0, 2.0)


def test_a_kinematic_body_pushing_a_ball_along_a_wall_stays_on_its_path() -> None:
    world = World()
    world.add_collider(Box((0.0, 0.0), (10.0, 10.0)))
    # The gate moves along the floor, half sunk into it, and sweeps a ball ahead of it.
    gate = world.add(disc(1.0, 0.2, 2.0, 0.0, radius=0.5, kinematic=True))
    ball = world.add(disc(2.0, 0.5, radius=0.5, restitution=0.0, friction=0.0))
    for _ in range(120):
        world.step(DT)
        assert gate.pos.y == 0.2  # never pushed out of the floor
    assert gate.pos.x == pytest.approx(3.0, rel=1e-12)
    assert ball.pos.x > gate.pos.x  # ahead of it, pushed along
