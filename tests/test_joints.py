"""Joints at anchors (engine.dynamics.joints, engine.exact.joint_solver): hinges with limits and
motors, welds, and rods, cables and pins held away from a body's centre.

Each behaviour is checked against the closed form or a theorem: the period of a rod on a
hinge against the exact elliptic one, a motor's angular velocity against min(T t / I, speed),
a flipper against its limit, a chain of planks against its joints' gaps, a hanging body's hinge
force against m g, a welded pair against one rigid body's angular momentum.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import Body, Cable, Hinge, Pin, Polygon, Rod, Segment, Vector, Weld, World
from engine.forces import Gravity
from tests.paths import PATHS

G = 9.81


def plank(x: float, y: float, length: float = 1.0, width: float = 0.05, **kw: float) -> Body:
    shape = Polygon.box(length, width)
    return Body(Vector(x, y), Vector(0, 0), Vector(0, 0), shape=shape, **kw)  # type: ignore[arg-type]


def gravity_world(integrator: str = "auto") -> World:
    # The exact models, asked for: these are the lesson's joints, held to rounding (World()
    # would choose the soft step for a plank that a contact could push).
    world = World(integrator=integrator, solver="exact")
    world.add_force(Gravity((0.0, -G)))
    return world


def flipper_world(speed: float, torque: float) -> tuple[World, Body, Hinge]:
    """A 1 m flipper of 1 kg hinged at its end to the world, limits +-0.5 rad, its motor at
    ``speed`` (rad/s) with at most ``torque`` (N m), under gravity."""
    world = gravity_world()
    flipper = world.add(plank(0.5, 0.0, 1.0, 0.1, mass=1.0))
    hinge = Hinge(flipper, world.static_body, (0.0, 0.0), limits=(-0.5, 0.5),
                  motor_speed=speed, max_torque=torque)  # fmt: skip
    return world, flipper, world.add_link(hinge)


def elliptic_k(k: float) -> float:
    """The complete elliptic integral of the first kind K(k), by the arithmetic-geometric mean."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    for _ in range(40):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def turning_points(world: World, body: Body, dt: float, until: float) -> list[float]:
    """Times (s) at which body's angular velocity passes from < 0 to >= 0 (interpolated)."""
    times, prev_w, prev_t = [], body.angular_velocity, world.t
    while world.t < until:
        world.step(dt)
        w = body.angular_velocity
        if prev_w < 0.0 <= w:
            times.append(prev_t + dt * (-prev_w) / (w - prev_w))
        prev_w, prev_t = w, world.t
    return times


@pytest.mark.parametrize("integrator", ["auto", "velocity_verlet", "semi_implicit_euler"])
def test_a_rod_on_a_hinge_swings_with_the_exact_elliptic_period(integrator: str) -> None:
    # A uniform rod of length L hinged at its end and let go level (90 degrees): a physical
    # pendulum of equivalent length I_pivot / (m L / 2) = 2 L / 3 (for a thin rod), period
    # 4 sqrt(L_eq / g) K(sin 45 degrees).
    length, width, dt = 1.0, 0.05, 1.0 / 240.0
    world = gravity_world(integrator)
    rod = world.add(plank(length / 2, 0.0, length, width, mass=1.0))
    hinge = world.add_link(Hinge(rod, world.static_body, (0.0, 0.0)))
    i_pivot = rod.moment + rod.mass * (length / 2) ** 2
    assert rod.moment == pytest.approx((length**2 + width**2) / 12, rel=1e-12)
    l_eq = i_pivot / (rod.mass * length / 2)
    period = 4.0 * math.sqrt(l_eq / G) * elliptic_k(math.sin(math.pi / 4))
    times = turning_points(world, rod, dt, 3.2 * period)
    measured = np.diff(times)
    assert len(measured) >= 2
    assert np.abs(measured / period - 1.0).max() < 1e-4
    # The hinge point stays put, and the rod's end with it.
    assert hinge.point.length() < 1e-9
    assert rod.local_to_world((-length / 2, 0.0)).length() < 1e-9


def test_a_thin_rod_period_is_that_of_the_point_pendulum_two_thirds_as_long() -> None:
    # The rod of the lesson: a body of moment m L^2 / 12 (no shape) on a hinge at its end has
    # the period of a point on a rod of 2 L / 3 (both measured here, side by side).
    length, dt = 1.5, 1.0 / 240.0
    world = gravity_world()
    rod = world.add(
        Body(
            Vector(length / 2, 0), Vector(0, 0), Vector(0, 0), mass=2.0, moment=2.0 * length**2 / 12
        )
    )
    world.add_link(Hinge(rod, world.static_body, (0.0, 0.0)))
    point_world = gravity_world()
    bob = point_world.add(Body(Vector(2 * length / 3, 0), Vector(0, 0), Vector(0, 0), mass=1.0))
    point_world.add_link(Rod(bob, (0.0, 0.0)))
    t_rod = np.diff(turning_points(world, rod, dt, 6.0))
    # The bob's angle about the pivot, by its velocity across the rod.
    times, prev, prev_t = [], 0.0, 0.0
    while point_world.t < 6.0:
        point_world.step(dt)
        w = bob.pos.cross(bob.vel) / bob.pos.length_squared()
        if prev < 0.0 <= w:
            times.append(prev_t + dt * (-prev) / (w - prev))
        prev, prev_t = w, point_world.t
    t_point = np.diff(times)
    exact = 4.0 * math.sqrt((2 * length / 3) / G) * elliptic_k(math.sin(math.pi / 4))
    assert np.abs(t_rod / exact - 1).max() < 1e-4
    assert np.abs(t_point / exact - 1).max() < 1e-4


def test_a_motor_spins_a_wheel_up_at_its_torque_and_holds_its_speed() -> None:
    # w(t) = min(T t / I, speed) at every step, to round-off: the motor's impulse each step
    # is T dt until the speed is reached, then what holds it.
    world = World(integrator="auto")
    wheel = world.add(Body(Vector(2, 1), Vector(0, 0), Vector(0, 0), mass=2.0, radius=0.5))
    torque, speed, dt = 0.3, 4.0, 1.0 / 60.0
    hinge = world.add_link(
        Hinge(wheel, world.static_body, (2, 1), motor_speed=speed, max_torque=torque)
    )
    inertia = wheel.moment
    worst = 0.0
    for n in range(1, 600):
        world.step(dt)
        worst = max(worst, abs(wheel.angular_velocity - min(torque * n * dt / inertia, speed)))
        if n == 10:
            assert hinge.motor_torque(dt) == pytest.approx(torque, rel=1e-12)
            assert hinge.torque(dt) == hinge.motor_torque(dt)  # no limits
    assert worst < 1e-9
    # Its angle too: T t^2 / (2 I) while the torque drives it (what the motor does to the
    # speed acts on the angle through the step, as a force's a dt^2 / 2).
    assert wheel.angular_velocity == pytest.approx(speed, abs=1e-9)
    assert abs(hinge.torque(dt)) < 1e-9  # holding a free wheel's speed takes no torque
    assert (wheel.pos - Vector(2, 1)).length() < 1e-12


def test_a_flipper_thrown_at_its_limit_stops_there_and_never_passes_it() -> None:
    world = gravity_world()
    flipper = world.add(plank(0.5, 0.0, 1.0, 0.1, mass=1.0, angular_velocity=30.0))
    hinge = world.add_link(Hinge(flipper, world.static_body, (0.0, 0.0), limits=(-0.5, 0.4)))
    highest = lowest = 0.0
    for _ in range(240):
        world.step(1.0 / 60.0)
        highest, lowest = max(highest, hinge.angle), min(lowest, hinge.angle)
    assert highest <= 0.4 + 1e-6
    assert highest == pytest.approx(0.4, abs=1e-6)  # it reached the upper limit
    assert lowest >= -0.5 - 1e-6
    assert hinge.angle == pytest.approx(-0.5, abs=1e-6)  # it hangs at the lower one
    assert flipper.angular_velocity == pytest.approx(0.0, abs=1e-9)


def test_a_motor_drives_a_flipper_into_its_limit_and_holds_it_there() -> None:
    # Gravity pulls the flipper down; the motor (max torque well above m g L / 2) lifts it
    # to its upper limit at full torque and holds it.
    world, flipper, hinge = flipper_world(20.0, 50.0)
    for _ in range(120):
        world.step(1.0 / 60.0)
        assert hinge.angle <= 0.5 + 1e-6
    assert hinge.angle == pytest.approx(0.5, abs=1e-6)
    assert hinge.motor_torque(1 / 60) == pytest.approx(50.0, rel=1e-9)  # the motor at its max
    hinge.motor_speed = -20.0
    for _ in range(60):
        world.step(1.0 / 60.0)
        assert hinge.angle >= -0.5 - 1e-6
    assert hinge.angle == pytest.approx(-0.5, abs=1e-6)


def test_a_chain_of_twenty_planks_holds_every_hinge_while_it_swings() -> None:
    world = gravity_world()
    planks = [world.add(plank(0.5 + k, 0.0, 1.0, 0.1, mass=1.0)) for k in range(20)]
    world.add_link(Hinge(planks[0], world.static_body, (0.0, 0.0)))
    hinges = [world.add_link(Hinge(planks[k], planks[k + 1], (k + 1.0, 0.0))) for k in range(19)]
    gap = 0.0
    for _ in range(480):
        world.step(1.0 / 240.0)
        gap = max(gap, max((h.end_a() - h.end_b()).length() for h in hinges))
    assert gap < 1e-9  # the issue asks 1e-4
    assert planks[-1].pos.y < -5.0  # it fell and swings


def test_a_hanging_body_feels_m_g_at_its_hinge() -> None:
    world = gravity_world()
    dt = 1.0 / 60.0
    box = world.add(plank(0.0, -0.5, 0.1, 1.0, mass=3.0))
    hinge = world.add_link(Hinge(box, world.static_body, (0.0, 0.0)))
    for _ in range(30):
        world.step(dt)
    force = hinge.force(dt)
    assert force.x == pytest.approx(0.0, abs=1e-9)
    assert force.y == pytest.approx(3.0 * G, rel=1e-9)
    assert hinge.impulse == pytest.approx(3.0 * G * dt, rel=1e-9)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_hanging_body_feels_m_g_at_its_hinge_on_the_soft_step_too(kernels: str) -> None:
    world = World(integrator="auto", kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -G)))
    dt = 1.0 / 60.0
    box = world.add(plank(0.0, -0.5, 0.1, 1.0, mass=3.0))
    hinge = world.add_link(Hinge(box, world.static_body, (0.0, 0.0)))
    for _ in range(60):
        world.step(dt)
    assert hinge.force(dt).y == pytest.approx(3.0 * G, rel=1e-6)
    assert hinge.impulse == pytest.approx(3.0 * G * dt, rel=1e-6)  # its size, as on exact


def test_a_pin_at_an_anchor_is_a_hinge_to_the_world() -> None:
    def swing(make: str) -> list[tuple[float, float, float]]:
        world = gravity_world()
        body = world.add(plank(0.5, 0.0, 1.0, 0.1, mass=1.0))
        if make == "pin":
            world.add_link(Pin(body, (0.0, 0.0), anchor_a=(-0.5, 0.0)))
        else:
            world.add_link(Hinge(body, world.static_body, (0.0, 0.0)))
        out = []
        for _ in range(100):
            world.step(1 / 120)
            out.append((body.pos.x, body.pos.y, body.angle))
        return out

    assert swing("pin") == swing("hinge")


def test_a_rod_between_anchors_holds_the_anchors_apart() -> None:
    world = gravity_world()
    a = world.add(plank(0.0, 0.0, 1.0, 0.1, mass=1.0))
    b = world.add(plank(0.0, -2.0, 1.0, 0.1, mass=1.0, angular_velocity=3.0))
    world.add_link(Pin(a, (0.0, 0.0)))  # a held at its centre: it turns about it
    rod = world.add_link(Rod(a, b, anchor_a=(0.5, 0.0), anchor_b=(-0.5, 0.0)))
    assert rod.length == pytest.approx(math.hypot(1.0, 2.0), rel=1e-15)
    cable = world.add_link(Cable(b, (3.0, -2.0), 10.0, anchor_a=(0.5, 0.0)))
    for _ in range(300):
        world.step(1 / 120)
        assert (rod.end_a() - rod.end_b()).length() == pytest.approx(rod.length, rel=1e-12)
        assert (cable.end_a() - cable.end_b()).length() <= cable.length * (1 + 1e-12)
    assert a.pos == Vector(0.0, 0.0)
    assert abs(a.angle) > 0.01  # the rod turned the pinned plank


def test_a_weld_holds_two_bodies_as_one_that_keeps_its_angular_momentum() -> None:
    world = World(integrator="auto")
    a = world.add(plank(0.0, 0.0, 1.0, 0.2, mass=1.0))
    b = world.add(plank(0.4, 0.3, 0.5, 0.5, mass=2.0))
    # Spin the pair as one rigid body about its centre of mass at 2 rad/s.
    com = (a.pos * a.mass + b.pos * b.mass) / (a.mass + b.mass)
    w0 = 2.0
    for body in (a, b):
        r = body.pos - com
        body.vel = Vector(-w0 * r.y, w0 * r.x) + Vector(1.0, 0.5)
        body.angular_velocity = w0
    weld = world.add_link(Weld(a, b))

    def momentum() -> tuple[Vector, float]:
        p = a.vel * a.mass + b.vel * b.mass
        com_now = (a.pos * a.mass + b.pos * b.mass) / (a.mass + b.mass)
        ang = sum(
            (body.pos - com_now).cross(body.vel - p / 3.0) * body.mass
            + body.moment * body.angular_velocity
            for body in (a, b)
        )
        return p, ang

    p0, l0 = momentum()
    gap0 = (b.pos - a.pos).length()
    for _ in range(600):
        world.step(1 / 60)
    p1, l1 = momentum()
    assert (p1 - p0).length() < 1e-12
    assert abs(l1 - l0) < 1e-9 * abs(l0)
    assert (b.pos - a.pos).length() == pytest.approx(gap0, rel=1e-12)
    assert weld.angle == pytest.approx(0.0, abs=1e-12)
    assert a.angular_velocity == pytest.approx(w0, rel=1e-9)


def test_a_soft_weld_rings_at_its_frequency() -> None:
    # A body on a soft weld to the world, pulled aside, swings back at about its hertz (the
    # implicit spring rings a little slower at a finite step) and, undamped, does not grow.
    world = World(integrator="auto")
    box = world.add(plank(0.0, 0.0, 0.5, 0.5, mass=1.0))
    world.add_link(Weld(box, world.static_body, hertz=2.0, damping_ratio=0.0))
    box.pos = Vector(0.1, 0.0)
    dt, xs = 1 / 600, []
    for _ in range(1200):
        world.step(dt)
        xs.append(box.pos.x)
    x = np.array(xs)
    ups = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    period = float(np.diff(ups).mean()) * dt
    assert period == pytest.approx(0.5, rel=0.02)
    assert np.abs(x).max() <= 0.1 + 1e-12


def test_bodies_on_a_joint_do_not_collide_unless_asked() -> None:
    def folded(collide: bool) -> float:
        # A plank welded to the world and one hinged to its end, end to end; the second
        # swings round at 5 rad/s and folds onto the first: it passes through unless asked
        # to collide, then stops on it (the planks are 0.1 m thick: 0.1 rad short of pi).
        world = World(integrator="auto")
        a = world.add(plank(-0.5, 0.0, 1.0, 0.1, mass=1.0))
        b = world.add(plank(0.5, 0.0, 1.0, 0.1, mass=1.0, angular_velocity=5.0))
        b.vel = Vector(0.0, 2.5)  # the hinge's point at rest
        world.add_link(Weld(a, world.static_body))
        hinge = world.add_link(Hinge(b, a, (0.0, 0.0), collide=collide))
        most = 0.0
        for _ in range(60):
            world.step(1 / 60)
            most = max(most, hinge.angle)
        return most

    assert folded(False) > math.pi  # through
    assert folded(True) < math.pi - 0.05  # stopped on the other


def test_snapshot_and_restore_bring_back_joints_their_settings_and_impulses() -> None:
    world, flipper, hinge = flipper_world(5.0, 20.0)
    for _ in range(10):
        world.step(1 / 60)
    snap = world.snapshot()
    before = (hinge.linear_impulse, hinge.angular_impulse)
    ahead = []
    for _ in range(30):
        world.step(1 / 60)
        ahead.append((flipper.pos, flipper.angle))
    hinge.motor_speed = -5.0  # a game changed it after the snapshot
    world.restore(snap)
    assert world.links == (hinge,)  # the same joint, its settings back
    assert hinge.motor_speed == 5.0 and (hinge.linear_impulse, hinge.angular_impulse) == before
    again = []
    for _ in range(30):
        world.step(1 / 60)
        again.append((flipper.pos, flipper.angle))
    assert again == ahead
    # Into a World built afresh: a new Hinge as made, not as the state now.
    fresh = gravity_world()
    other = fresh.add(plank(0.5, 0.0, 1.0, 0.1, mass=1.0))
    fresh.restore(snap)
    (made,) = fresh.links
    assert isinstance(made, Hinge) and made.limits == (-0.5, 0.5) and made.reference_angle == 0.0
    assert made.body_a is other
    replay = []
    for _ in range(30):
        fresh.step(1 / 60)
        replay.append((other.pos, other.angle))
    assert replay == ahead


def test_removing_a_joint_frees_its_bodies() -> None:
    world = gravity_world()
    body = world.add(plank(0.5, 0.0, 1.0, 0.1, mass=1.0))
    hinge = world.add_link(Hinge(body, world.static_body, (0.0, 0.0)))
    world.step(1 / 60)
    world.remove_link(hinge)
    vy = body.vel.y
    world.step(1 / 60)
    assert body.vel.y == pytest.approx(vy - G / 60, rel=1e-12)  # falls freely
    with pytest.raises(ValueError, match="not in this World"):
        world.remove_link(hinge)


@pytest.mark.parametrize(
    "make, error, match",
    [
        (lambda a, b: Hinge(a, a, (0, 0)), ValueError, "joined to itself"),
        (lambda a, b: Hinge(a, b, (math.nan, 0)), ValueError, "point must be finite"),
        (lambda a, b: Hinge(a, b, (0, 0), limits=(1.0, -1.0)), ValueError, "lower <= upper"),
        (lambda a, b: Hinge(a, b, (0, 0), limits=(math.nan, 1.0)), ValueError, "limits"),
        (lambda a, b: Hinge(a, b, (0, 0), limits=3.0), TypeError, "pair"),
        (lambda a, b: Hinge(a, b, (0, 0), max_torque=-1.0), ValueError, "max_torque must be >= 0"),
        (lambda a, b: Hinge(a, b, (0, 0), motor_speed=math.inf), ValueError, "motor_speed"),
        (lambda a, b: Hinge(a, "b", (0, 0)), TypeError, "body_b must be a Body"),
        (lambda a, b: Hinge(a, b, (0, 0), collide=1), TypeError, "collide"),
        (lambda a, b: Weld(a, b, hertz=0.0), ValueError, "hertz must be > 0"),
        (lambda a, b: Weld(a, b, hertz=1.0, damping_ratio=-1.0), ValueError, "damping_ratio"),
        (lambda a, b: Rod(a, b, anchor_a=(0, math.inf)), ValueError, "anchor_a must be finite"),
        (lambda a, b: Rod(a, (3, 3), anchor_b=(1, 0)), ValueError, "anchor_b"),
        (lambda a, b: Pin(a, (0, 0), anchor_a="x"), TypeError, "anchor_a"),
    ],
)
def test_bad_joints_are_clear_errors(make, error, match) -> None:  # type: ignore[no-untyped-def]
    a = plank(0.0, 0.0)
    b = plank(2.0, 0.0)
    with pytest.raises(error, match=match):
        make(a, b)


def test_a_joint_to_a_body_of_another_world_is_refused() -> None:
    world, other = World(), World()
    a = world.add(plank(0.0, 0.0))
    b = other.add(plank(1.0, 0.0))
    with pytest.raises(ValueError, match="in this World first"):
        world.add_link(Hinge(a, b, (0.5, 0.0)))
    assert world.links == ()


def test_the_static_body_is_the_world_and_cannot_be_replaced() -> None:
    world = World()
    assert world.static_body is World().static_body
    assert repr(world.static_body) == "world.static_body"
    with pytest.raises(AttributeError):
        world.static_body = plank(0.0, 0.0)  # type: ignore[misc]


def test_a_car_driven_by_motors_climbs_a_slope_at_the_closed_form_speed() -> None:
    # Two wheels (discs of mass m, radius r, I = m r^2 / 2) on hinges under a box chassis,
    # each hinge's motor at max torque T: rolling without slipping, the car's speed along the
    # slope grows at a = (2 T / r - M g sin(theta)) / (M + 2 I / r^2) (M: the whole car;
    # the motors' work 2 T v / r against gravity's M g sin(theta) v), until the wheels turn
    # at the motor's speed relative to the chassis: v = |motor_speed| r, held.
    # (With twice the torque the front wheel, unloaded by the motors' pull on the chassis,
    # would need more friction than mu N: then it slips, as it should.)
    theta, r, dt = math.radians(15), 0.3, 1 / 60
    m_wheel, m_body, torque, speed = 1.0, 2.0, 2.5, -10.0
    along = Vector(math.cos(theta), math.sin(theta))
    up = Vector(-math.sin(theta), math.cos(theta))
    world = gravity_world()
    world.add_collider(Segment(along * -20.0, along * 60.0))
    back = world.add(Body(up * r, radius=r, mass=m_wheel, friction=1.0))
    front = world.add(Body(up * r + along * 1.5, radius=r, mass=m_wheel, friction=1.0))
    body = world.add(
        Body(up * (r + 0.4) + along * 0.75, shape=Polygon.box(2.0, 0.3), mass=m_body, angle=theta)
    )
    for wheel in (back, front):
        world.add_link(Hinge(wheel, body, wheel.pos, motor_speed=speed, max_torque=torque))
    total = 2 * m_wheel + m_body
    a = (2 * torque / r - total * G * math.sin(theta)) / (
        total + 2 * (m_wheel * r * r / 2) / (r * r)
    )
    worst_v = worst_roll = worst_gap = 0.0
    for n in range(1, 181):
        world.step(dt)
        v = back.vel.dot(along)
        worst_v = max(worst_v, abs(v - min(a * n * dt, -speed * r)))
        for wheel in (back, front):
            worst_roll = max(worst_roll, abs(wheel.angular_velocity * r + wheel.vel.dot(along)))
            worst_gap = max(worst_gap, abs(wheel.pos.dot(up) - r))
    assert worst_v < 1e-9
    assert worst_roll < 1e-9  # rolling, not slipping
    assert worst_gap < 1e-9  # on the slope, not in it
    assert body.angle == pytest.approx(theta, abs=1e-9)
    assert back.vel.dot(along) == pytest.approx(-speed * r, abs=1e-9)  # 3 m/s, held


def test_a_motor_turns_its_wheel_through_the_closed_forms_angle() -> None:
    world = World(integrator="auto")
    wheel = world.add(Body(Vector(0, 0), Vector(0, 0), Vector(0, 0), mass=2.0, radius=0.5))
    torque, dt = 0.3, 1 / 60
    world.add_link(Hinge(wheel, world.static_body, (0, 0), motor_speed=100.0, max_torque=torque))
    worst = 0.0
    for n in range(1, 121):
        world.step(dt)
        worst = max(worst, abs(wheel.angle - torque * (n * dt) ** 2 / (2 * wheel.moment)))
    assert worst < 1e-12


def test_a_car_held_by_its_brakes_stays_where_it_is_on_a_slope() -> None:
    # Motors at speed 0 with no torque bound hold the wheels to the chassis; friction holds
    # the wheels to the slope: the car neither moves nor creeps (it crept at 17 mm/s when the
    # brakes acted on the speeds alone, not on the positions through the step).
    theta, r = math.radians(15), 0.3
    along = Vector(math.cos(theta), math.sin(theta))
    up = Vector(-math.sin(theta), math.cos(theta))
    world = gravity_world()
    world.add_collider(Segment(along * -20.0, along * 60.0))
    back = world.add(Body(up * r, radius=r, mass=1.0, friction=1.0))
    front = world.add(Body(up * r + along * 1.5, radius=r, mass=1.0, friction=1.0))
    body = world.add(
        Body(up * (r + 0.4) + along * 0.75, shape=Polygon.box(2.0, 0.3), mass=2.0, angle=theta)
    )
    for wheel in (back, front):
        world.add_link(Hinge(wheel, body, wheel.pos, motor_speed=0.0, max_torque=math.inf))
    start = [b.pos for b in (back, front, body)]
    for _ in range(240):
        world.step(1 / 60)
    for b, p in zip((back, front, body), start, strict=True):
        assert (b.pos - p).length() < 1e-12
        assert b.vel.length() < 1e-12
    assert body.angle == pytest.approx(theta, abs=1e-12)


def test_a_ball_bounces_off_a_bat_held_at_its_stop_with_its_restitution() -> None:
    # A bat held down on its stop by its motor is a wall to the ball: the ball leaves with e
    # times its speed along the bat's normal (e = 1 here) and keeps its speed along it (the
    # exact models' impact, asked for).
    world = World(integrator="auto", solver="exact")
    bat = world.add(plank(0.5, 0.0, 1.0, 0.1, mass=0.15, restitution=1.0, friction=0.0))
    hinge = world.add_link(
        Hinge(bat, world.static_body, (0, 0), limits=(-0.5, 0.5), motor_speed=-10.0, max_torque=1e6)
    )
    ball = world.add(
        Body(Vector(0.6, 0.5), Vector(0.0, -5.0), radius=0.05, mass=0.08, restitution=1.0,
             friction=0.0)
    )  # fmt: skip
    began: list[object] = []
    ended: list[object] = []
    world.on_contact(ball, begin=began.append, end=ended.append)
    for _ in range(40):
        world.step(1 / 120)
    n = Vector(math.sin(0.5), math.cos(0.5))  # the bat's top face at its stop, -0.5 rad
    assert hinge.angle == pytest.approx(-0.5, abs=1e-9)
    # The soft step let the light bat give way; the joints' solve put it back on its stop
    # and gave the ball the bounce the soft step's was undone of: e times the speed it came
    # in at, along the normal.
    assert ball.vel.dot(n) == pytest.approx(5.0 * math.cos(0.5), abs=1e-9)
    # And the contact's events: it began once and ended once.
    assert len(began) == 1 and len(ended) == 1


def _kinematic(x: float) -> Body:
    return Body(Vector(x, 0.0), Vector(1.0, 0.0), kinematic=True, shape=Polygon.box(1.0, 0.2))


@pytest.mark.parametrize(
    "make",
    [
        lambda a, b, s: Hinge(a, b, (0.5, 0.0)),
        lambda a, b, s: Hinge(a, s, (0.5, 0.0)),
        lambda a, b, s: Weld(a, b, (0.5, 0.0)),
        lambda a, b, s: Weld(a, s, (0.5, 0.0)),
        lambda a, b, s: Rod(a, b, None),
        lambda a, b, s: Cable(a, (3.0, 0.0), 4.0),
    ],
    ids=["hinge", "hinge-to-world", "weld", "weld-to-world", "rod", "cable-to-point"],
)
def test_a_joint_no_end_of_which_can_move_is_refused_when_made(make) -> None:  # type: ignore[no-untyped-def]
    # Both ends moved by the game (kinematic, or the world): nothing is left for the joint to
    # pull, and it would be silently broken at once (a hinge point 1 m apart after 1 s).
    world = World()
    a, b = _kinematic(0.0), _kinematic(1.0)
    with pytest.raises(ValueError, match="kinematic body and .*dynamic"):
        make(a, b, world.static_body)


def test_a_hinge_from_a_kinematic_body_to_a_dynamic_one_holds_the_dynamic_one() -> None:
    # The allowed case: the game moves one end, the joint carries the other with it.
    world = World()
    lift = world.add(_kinematic(0.0))
    load = world.add(plank(1.0, 0.0))
    hinge = world.add_link(Hinge(lift, load, (0.5, 0.0)))
    for _ in range(60):
        world.step(1 / 60)
    assert (hinge.end_a() - hinge.end_b()).length() < 1e-9
    assert lift.pos.x == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("solver", ["exact", "soft"])
def test_a_hinge_made_by_two_anchors_is_the_hinge_made_by_their_point(solver: str) -> None:
    # pymunk's PivotJoint(a, b, anchor_a, anchor_b): each body's own frame. A plank turned by
    # 0.3 rad hangs from a wheel by its end; both ways of making the hinge hold the same
    # anchors and swing the same.
    runs = []
    for by_anchors in (False, True):
        w = World(solver=solver)
        w.add_force(Gravity((0.0, -9.81)))
        wheel = w.add(Body(Vector(0.0, 0.0), mass=2.0, shape=Polygon.box(0.4, 0.4)))
        w.add_link(Pin(wheel, (0.0, 0.0)))
        plank = w.add(Body(Vector(0.0, 0.0), mass=1.0, shape=Polygon.box(2.0, 0.1), angle=0.3))
        end = plank.local_to_world(Vector(-1.0, 0.0))
        plank.pos = plank.pos - end + Vector(0.2, 0.0)  # its end at the wheel's right side
        if by_anchors:
            hinge = w.add_link(Hinge(plank, wheel, anchor_a=(-1.0, 0.0), anchor_b=(0.2, 0.0)))
            assert hinge.anchor_a == Vector(-1.0, 0.0) and hinge.anchor_b == Vector(0.2, 0.0)
        else:
            hinge = w.add_link(Hinge(plank, wheel, (0.2, 0.0)))
            assert abs(hinge.anchor_a - Vector(-1.0, 0.0)) < 1e-15
        for _ in range(60):
            w.step(1 / 60)
        runs.append([*plank.pos, plank.angle, *plank.vel, plank.angular_velocity])
    # (The point's anchors are the given ones to rounding: the runs agree to rounding.)
    assert runs[0] == pytest.approx(runs[1], abs=1e-9)


def test_a_hinge_by_anchors_to_the_world_and_what_it_refuses() -> None:
    w = World()
    box = w.add(Body(Vector(3.0, 2.0), mass=1.0, shape=Polygon.box(1.0, 1.0)))
    hinge = Hinge(box, w.static_body, anchor_a=(-0.5, 0.5), anchor_b=(2.5, 2.5))
    assert hinge.point == Vector(2.5, 2.5) and hinge.anchor_a == Vector(-0.5, 0.5)
    other = w.add(Body(Vector(0.0, 0.0), mass=1.0, radius=0.2))
    with pytest.raises(ValueError, match=r"0\.3 m apart; move a body by \(0\.3, 0\) first"):
        Hinge(box, other, anchor_a=(-0.5, 0.0), anchor_b=(2.8, 2.0))
    with pytest.raises(TypeError, match="not both"):
        Hinge(box, other, (2.5, 2.0), anchor_a=(-0.5, 0.0), anchor_b=(2.5, 2.0))
    with pytest.raises(TypeError, match="needs its point"):
        Hinge(box, other)
