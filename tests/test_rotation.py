"""Bodies that turn: free rotation, rolling and slipping on a slope, spin at a bounce, the API.

Each number is checked against the closed form or a theorem (issue "Bodies that turn").
"""

from __future__ import annotations

import math

import pytest

from engine import Body, Plane, Polygon, Segment, Vector, World
from engine.forces import Gravity
from tests.paths import PATHS

G = 9.81
R = 0.5


def slope_world(theta: float, mu: float, **body: object) -> tuple[World, Body, Vector, Vector]:
    """A disc of radius R resting on a plane through the origin tilted by ``theta`` (rad),
    downhill toward -x; (world, disc, unit normal, unit vector uphill)."""
    n = Vector(-math.sin(theta), math.cos(theta))
    up = Vector(math.cos(theta), math.sin(theta))
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), n, friction=1.0))
    b = w.add(Body(n * R, radius=R, friction=mu, restitution=0.0, **body))  # type: ignore[arg-type]
    return w, b, n, up


def run(w: World, seconds: float, dt: float = 1 / 60) -> None:
    for _ in range(round(seconds / dt)):
        w.step(dt)


# -- free rotation -------------------------------------------------------------------------


def test_free_rotation_under_constant_torque_is_the_closed_form() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.3, mass=2.0, angle=0.4, angular_velocity=-1.5))
    tau = 0.7
    b.torque = tau
    alpha = tau / b.moment
    assert b.moment == pytest.approx(0.5 * 2.0 * 0.3**2, rel=1e-15)
    dt, steps = 1 / 60, 600
    for _ in range(steps):
        w.step(dt)
    t = steps * dt
    theta = 0.4 - 1.5 * t + 0.5 * alpha * t * t
    assert b.angle == pytest.approx(theta, rel=1e-12)
    assert b.angular_velocity == pytest.approx(-1.5 + alpha * t, rel=1e-12)


def test_a_spinning_disc_in_flight_keeps_its_energy_and_angular_momentum() -> None:
    w = World()
    w.add_force(Gravity((0.0, -G)))
    b = w.add(Body(Vector(0, 0), Vector(3, 40), radius=0.5, mass=1.5, angular_velocity=10.0))
    e0 = 0.5 * b.moment * b.angular_velocity**2
    L0 = b.moment * b.angular_velocity
    for _ in range(10_000):
        w.step(1 / 600)
    assert 0.5 * b.moment * b.angular_velocity**2 == pytest.approx(e0, rel=1e-12)
    assert b.moment * b.angular_velocity == pytest.approx(L0, rel=1e-12)
    assert b.angle == pytest.approx(10.0 * w.t, rel=1e-12)


def test_a_world_with_nothing_that_turns_does_no_rotation() -> None:
    w = World()
    points = [w.add(Body(Vector(k, 0))) for k in range(3)]
    w.add(Body(Vector(5, 0), shape=Polygon.box(1, 1), fixed_rotation=True))  # a box turns
    w.add(Body(Vector(8, 0), radius=0.5, fixed_rotation=True))
    assert w.turning == ()
    disc = w.add(Body(Vector(9, 0), radius=0.5))
    assert w.turning == (disc,)
    assert not any(p.turns for p in points)


# -- rolling and slipping ----------------------------------------------------------------


def test_a_disc_rolls_down_a_30_degree_slope_without_slipping() -> None:
    theta = math.radians(30)
    w, b, n, up = slope_world(theta, 0.5)
    a = G * math.sin(theta) / (1 + 0.5)  # I / (m r^2) = 1/2: a = (2/3) g sin(theta)
    run(w, 1.0)
    v = b.vel.dot(up)
    assert v == pytest.approx(-a * 1.0, rel=1e-9)
    assert b.angular_velocity == pytest.approx(-v / R, rel=1e-9)  # w = v / r
    assert b.pos.dot(up) == pytest.approx(-0.5 * a, rel=1e-6)
    assert abs(b.pos.dot(n) - R) <= 1e-9  # on the slope, not in it


def test_a_disc_slips_down_a_60_degree_slope_with_little_friction() -> None:
    theta, mu = math.radians(60), 0.25
    w, b, n, up = slope_world(theta, mu)
    run(w, 1.0)
    a = G * (math.sin(theta) - mu * math.cos(theta))
    assert b.vel.dot(up) == pytest.approx(-a, rel=1e-9)
    assert b.angular_velocity == pytest.approx(2 * mu * G * math.cos(theta) / R, rel=1e-9)
    assert abs(b.pos.dot(n) - R) <= 1e-9


def test_the_rolling_law_can_fail() -> None:
    """The same slope with fixed_rotation: the disc slides as a block (a = g (sin - mu cos)
    at 30 degrees with mu 0.5 is 0.66 m/s^2, not 3.27): the test above could fail."""
    theta = math.radians(30)
    w, b, _, up = slope_world(theta, 0.5, fixed_rotation=True)
    run(w, 1.0)
    assert b.vel.dot(up) == pytest.approx(-G * (math.sin(theta) - 0.5 * math.cos(theta)))
    assert b.angular_velocity == 0.0


def test_a_hoop_a_disc_and_a_frictionless_box_race_in_the_closed_form_ratios() -> None:
    theta = math.radians(20)
    n = Vector(-math.sin(theta), math.cos(theta))
    up = Vector(math.cos(theta), math.sin(theta))
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), n, friction=1.0))
    hoop = w.add(Body(n * R, radius=R, friction=0.8, moment=1.0 * R * R, restitution=0.0))
    disc = w.add(Body(n * R + up * 3, radius=R, friction=0.8, restitution=0.0))
    # Without friction nothing turns it: it slides as a frictionless box does (a box itself
    # rests on a corner on a slope while bodies with corners do not turn).
    box = w.add(Body(n * R + up * 6, radius=R, friction=0.0, restitution=0.0))
    start = {b: b.pos.dot(up) for b in (hoop, disc, box)}
    run(w, 1.5)
    gone = {b: start[b] - b.pos.dot(up) for b in start}
    # From rest, d = a t^2 / 2: distances in the ratio of a = g sin / (1 + I / (m r^2)).
    g_s = G * math.sin(theta)
    assert gone[box] == pytest.approx(0.5 * g_s * 1.5**2, rel=1e-9)
    assert gone[disc] / gone[box] == pytest.approx(2 / 3, rel=1e-9)
    assert gone[hoop] / gone[box] == pytest.approx(1 / 2, rel=1e-9)
    assert box.angular_velocity == 0.0


def test_a_disc_thrown_along_a_floor_slips_then_rolls_at_two_thirds_of_its_speed() -> None:
    mu, v0 = 0.3, 6.0
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    b = w.add(Body(Vector(0, R), Vector(v0, 0), radius=R, friction=mu, restitution=0.0))
    # Slipping: u' = -mu g, omega' = -mu g q / r (q = m r^2 / I = 2), until u = -omega r.
    t_roll = v0 / (mu * G * 3)
    run(w, 2.0)
    assert t_roll < 2.0
    assert b.vel.x == pytest.approx(2 / 3 * v0, rel=1e-9)
    assert b.angular_velocity == pytest.approx(-b.vel.x / R, rel=1e-9)
    x_roll = v0 * t_roll - 0.5 * mu * G * t_roll**2
    assert b.pos.x == pytest.approx(x_roll + 2 / 3 * v0 * (w.t - t_roll), rel=1e-9)
    assert b.pos.y == pytest.approx(R, abs=1e-12)


def test_a_bounce_keeps_the_angular_momentum_about_the_point_of_contact() -> None:
    """Friction and the normal push both act at the point of contact: the angular momentum
    about it, m (r x v) + I omega, is the same before and after the impact (a theorem)."""
    w = World()
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0), friction=1.0))
    m = 2.0
    b = w.add(
        Body(Vector(0, 1), Vector(4, -8), radius=R, mass=m, friction=0.9, restitution=0.5,
             angular_velocity=3.0)
    )  # fmt: skip

    def about_contact() -> float:
        # The contact point is below the centre: r = (0, R) from it to the centre.
        return m * (0.0 * b.vel.y - R * b.vel.x) + b.moment * b.angular_velocity

    before = about_contact()
    w.step(0.1)  # lands at t = 1 / 16 (no gravity) and leaves
    assert b.vel.y == pytest.approx(4.0, rel=1e-12)  # e v_n
    assert about_contact() == pytest.approx(before, rel=1e-12)
    # With mu 0.9 the impulse is enough to leave it rolling: v = -omega r.
    assert b.vel.x == pytest.approx(-b.angular_velocity * R, rel=1e-12)


def test_a_disc_at_rest_on_a_floor_stays_put() -> None:
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Segment((-5, 0), (5, 0)))
    b = w.add(Body(Vector(0, R), radius=R, friction=0.5))
    run(w, 2.0)
    assert (b.pos.x, b.pos.y, b.vel.x, b.vel.y) == (0.0, R, 0.0, 0.0)
    assert b.angular_velocity == 0.0


# -- the API -------------------------------------------------------------------------------


def test_apply_impulse_at_a_point_gives_push_and_spin() -> None:
    b = Body(Vector(1, 2), radius=0.5, mass=2.0)
    b.apply_impulse(Vector(0, 3), at=(1.5, 2))
    assert (b.vel.x, b.vel.y) == (0.0, 1.5)
    assert b.angular_velocity == pytest.approx(0.5 * 3 / b.moment, rel=1e-15)
    w = World()
    w.add(b)
    b.apply_impulse((2, 0))
    assert (b.vel.x, b.vel.y) == (1.0, 1.5)


def test_local_and_world_points_turn_with_the_body() -> None:
    b = Body(Vector(1, 2), radius=0.5, angle=math.pi / 2)
    p = b.local_to_world((1, 0))
    assert p.x == pytest.approx(1.0, abs=1e-15) and p.y == pytest.approx(3.0)
    q = b.world_to_local(p)
    assert q.x == pytest.approx(1.0) and q.y == pytest.approx(0.0, abs=1e-15)


def test_a_points_velocity_is_v_plus_omega_cross_r() -> None:
    # r = (0.5, 0) and (0, 0.25) from (1, 2), omega = 2 rad/s: omega x r = (-omega r_y, omega r_x).
    b = Body(Vector(1, 2), Vector(3, -1), radius=0.5, angular_velocity=2.0)
    assert b.velocity_at_world_point((1.5, 2)) == Vector(3.0, 0.0)
    assert b.velocity_at_world_point(Vector(1, 2.25)) == Vector(2.5, -1.0)
    assert b.velocity_at_world_point((1, 2)) == b.vel  # the centre moves at v
    b.angle = math.pi / 6  # the local point (0.5, 0) is 0.5 (cos 30, sin 30) from the centre
    r = Vector(0.5 * math.cos(math.pi / 6), 0.5 * math.sin(math.pi / 6))
    turned = b.velocity_at_local_point((0.5, 0))
    assert turned.distance_to(Vector(3.0 - 2.0 * r.y, -1.0 + 2.0 * r.x)) < 1e-15
    assert turned.distance_to(b.velocity_at_world_point(b.local_to_world((0.5, 0)))) < 1e-15
    # A body that does not turn moves every point at v, exactly.
    point = Body(Vector(1, 2), Vector(3, -1))
    crate = Body(Vector(1, 2), Vector(3, -1), shape=Polygon.box(1, 1), fixed_rotation=True)
    for still in (point, crate):
        assert still.velocity_at_world_point((7, -5)) == still.velocity_at_local_point((7, -5))
        assert still.velocity_at_world_point((7, -5)) == Vector(3, -1)
    # pymunk's own test (test_body.testVelocityAtPoint), the same numbers.
    pm = Body(Vector(1, 2), radius=1.0, angular_velocity=1.2)
    assert pm.velocity_at_world_point((1, 1)) == Vector(1.2, 0)
    assert pm.velocity_at_local_point((1, 1)) == Vector(-1.2, 1.2)
    with pytest.raises(TypeError, match=r"velocity_at_world_point takes a 2D body.*body\.vel"):
        Body(0.0, 1.0).velocity_at_world_point((1, 0))
    with pytest.raises(TypeError, match=r"point must be a Vector or a pair"):
        b.velocity_at_local_point("corner")


def test_a_points_velocity_is_the_rate_its_world_position_changes() -> None:
    # A box turning at omega in free flight; the central difference of a corner's world
    # position over two steps of h misses the derivative by |r| omega^3 h^2 / 6 (a uniform
    # turn), far above rounding at this h.
    w, h, omega = World(), 1e-5, 3.0
    box = Polygon.box(1.0, 0.5)
    b = w.add(Body(Vector(1, 2), Vector(3, -1), shape=box, angular_velocity=omega, angle=0.4))
    corner = Vector(0.5, 0.25)
    before = b.local_to_world(corner)
    w.step(h)
    at_mid = b.velocity_at_local_point(corner)
    assert b.velocity_at_world_point(b.local_to_world(corner)).distance_to(at_mid) < 1e-14
    # It is not the centre's velocity: the corner adds omega |r| across its arm.
    assert at_mid.distance_to(b.vel) == pytest.approx(omega * corner.length(), rel=1e-12)
    w.step(h)
    moved = (b.local_to_world(corner) - before) / (2 * h)
    assert moved.distance_to(at_mid) < corner.length() * omega**3 * h**2 / 6 + 1e-10


def test_moments_from_the_shape() -> None:
    assert Body(Vector(0, 0), radius=2.0, mass=3.0).moment == 6.0  # m r^2 / 2
    assert Body(Vector(0, 0), radius=2.0, mass=3.0, moment=12.0).moment == 12.0  # a hoop
    assert Body(Vector(0, 0), radius=2.0, fixed_rotation=True).moment == math.inf
    assert Body(Vector(0, 0)).moment == math.inf  # a point does not turn
    assert Body(Vector(0, 0), moment=1.0).turns  # unless given a moment


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"angular_velocity": 1.0}, "a point has no moment"),
        ({"radius": 1.0, "angle": math.nan}, "angle must be a number"),
        ({"radius": 1.0, "torque": math.inf}, "torque must be finite"),
        ({"radius": 1.0, "moment": -1.0}, "moment must be a moment of inertia > 0"),
        ({"radius": 1.0, "fixed_rotation": True, "angular_velocity": 2.0}, "fixed_rotation=True"),
        ({"shape": Polygon.box(1, 1), "kinematic": True, "torque": 2.0}, "turned by the game"),
        ({"radius": 1.0, "kinematic": True, "torque": 1.0}, "set its angular_velocity"),
    ],
)
def test_rotation_errors_name_the_argument(kwargs: dict[str, object], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        Body(Vector(0, 0), **kwargs)  # type: ignore[arg-type]


def test_a_body_that_cannot_turn_refuses_a_spin_and_keeps_its_state() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), shape=Polygon.box(1, 1), fixed_rotation=True))
    with pytest.raises(ValueError, match="angular_velocity=2.0"):
        b.angular_velocity = 2.0
    assert b.angular_velocity == 0.0
    with pytest.raises(TypeError, match="fixed_rotation must be True"):
        Body(Vector(0, 0), radius=1.0, fixed_rotation=1)  # type: ignore[arg-type]


def test_a_body_whose_moment_was_inf_turns_again_when_given_a_finite_one() -> None:
    # pymunk's body.moment = inf, then a finite one: the body turns again. (The setter once
    # asked whether the body turns with the inf it had just stored, and refused.)
    alone = Body(Vector(0, 0), mass=2, moment=3)
    alone.moment = math.inf
    assert not alone.turns
    alone.moment = 3
    assert alone.moment == 3 and alone.turns and alone.angular_velocity == 0.0
    alone.angular_velocity = 1.5  # taken now that it turns
    # A point made with moment=math.inf (pymunk's Body(mass, math.inf)) too.
    point = Body(Vector(0, 0), mass=2, moment=math.inf)
    point.moment = 5
    assert point.turns and point.moment == 5
    # What cannot turn whatever its moment still refuses one, naming it and the value.
    fixed = Body(Vector(0, 0), radius=1.0, fixed_rotation=True)
    with pytest.raises(ValueError, match=r"moment=3.0\): the body was made with fixed_rot"):
        fixed.moment = 3
    with pytest.raises(ValueError, match=r"moment=3.0\): a 1D body does not turn"):
        Body(0.0).moment = 3
    assert fixed.moment == math.inf


@pytest.mark.parametrize("kernels", PATHS)
def test_in_a_world_a_body_given_a_finite_moment_after_inf_turns_at_tau_over_i(
    kernels: str,
) -> None:
    w = World(integrator="auto", kernels=kernels)
    b = w.add(Body(Vector(0, 0), mass=2, moment=3))
    w.step(0.1)
    b.moment = math.inf
    w.step(0.1)
    assert w.turning == ()
    b.moment = 4
    # The World's arrays hold the new moment (the steps read 1 / I from them).
    store = w._s.store
    assert store is not None
    assert store.moment.tolist() == [4.0] and store.inv_moment.tolist() == [0.25]
    assert w.turning == (b,) and b.moment == 4
    # From rest, a constant torque tau: omega = (tau / I) t, angle = (tau / I) t^2 / 2.
    b.torque = 2.0
    for _ in range(10):
        w.step(0.1)
    assert b.angular_velocity == pytest.approx(2.0 / 4 * 1.0, rel=1e-12)
    assert b.angle == pytest.approx(2.0 / 4 * 1.0**2 / 2, rel=1e-12)


def test_snapshot_restore_and_removal_keep_the_spin() -> None:
    theta = math.radians(30)
    w, b, _, _ = slope_world(theta, 0.5)
    run(w, 0.5)
    snap = w.snapshot()
    run(w, 0.5)
    angle, omega = b.angle, b.angular_velocity
    w.restore(snap)
    run(w, 0.5)
    assert (b.angle, b.angular_velocity) == (angle, omega)
    w.remove(b)
    assert (b.angle, b.angular_velocity) == (angle, omega)


def test_apply_force_lasts_one_step_and_turns_a_disc() -> None:
    """pymunk's apply_force_at_world_point: F over the next step only, and (at - pos) x F."""
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.5, mass=2.0, acceleration=Vector(0.0, -1.0)))
    dt = 0.1
    b.apply_force(Vector(4.0, 0.0), at=(0.0, 0.5))  # on top of the disc, to the right
    w.step(dt)
    assert b.vel.x == pytest.approx(4.0 / 2.0 * dt, rel=1e-15)
    torque = 0.5 * -4.0  # r x F = (0, 0.5) x (4, 0) = -2 N m: clockwise
    assert b.angular_velocity == pytest.approx(torque / b.moment * dt, rel=1e-15)
    # Gone after the step: the body's own acceleration and torque are back as they were.
    assert (b.own_acc.x, b.own_acc.y, b.torque) == (0.0, -1.0, 0.0)
    v, w0 = b.vel, b.angular_velocity
    w.step(dt)
    assert b.vel.x == v.x and b.angular_velocity == w0
    with pytest.raises(ValueError, match="add the body to a World first"):
        Body(Vector(0, 0), radius=1.0).apply_force((1, 0))
    with pytest.raises(ValueError, match="force must be finite"):
        b.apply_force((math.nan, 0))


def test_apply_force_every_frame_is_a_constant_force() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), mass=3.0))
    for _ in range(60):
        b.apply_force((6.0, 0.0))
        w.step(1 / 60)
    assert b.vel.x == pytest.approx(2.0, rel=1e-12)  # a = F / m = 2 for 1 s
    assert b.own_acc.x == 0.0


def test_a_point_given_a_moment_turns_freely_past_colliders() -> None:
    # A point (radius 0) has no surface to roll on: it meets colliders as points do (not at
    # all) and keeps turning at its own rate; it once divided by its radius there.
    world = World(integrator="auto")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Segment((-5.0, 0.0), (5.0, 0.0)))
    world.add_collider(Plane((0.0, -20.0), (0.0, 1.0)))
    point = world.add(Body(Vector(0.0, 1.0), mass=1.0, moment=0.1, angular_velocity=2.0))
    for _ in range(120):
        world.step(1 / 60)
    assert point.angle == pytest.approx(4.0, abs=1e-12)
    assert point.angular_velocity == 2.0


def test_a_push_for_the_next_step_does_not_leave_with_a_body_taken_out() -> None:
    # apply_force lasts the World's next step; a body taken out before it keeps nothing of it
    # (else, added to a World again, it would carry the push for ever).
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.5, mass=2.0, acceleration=Vector(0.0, -1.0)))
    b.apply_force(Vector(4.0, 0.0), at=(0.0, 0.5))
    w.remove(b)
    assert (b.own_acc.x, b.own_acc.y, b.torque) == (0.0, -1.0, 0.0)
    again = World()
    again.add(b)
    again.step(0.1)
    assert b.vel.x == 0.0 and b.angular_velocity == 0.0
