"""Springs between bodies (engine.dynamics.springs, engine.exact.spring_step): pymunk's DampedSpring
and DampedRotarySpring.

Checked against closed forms and theorems: a damped oscillator's x(t) on the closed form, to
1e-9 (one body to the world, and two bodies, whose relative motion is an oscillator of the
reduced mass); momentum kept by the kicks; energy within a bound that shrinks as dt^2; the
periods 2 pi sqrt(mu / k) and 2 pi sqrt(I / k); and against pymunk's own step on the same
scenes. pymunk's test_constraint.py tests of the two springs' settings are ported at the end,
each named for the one it ports.
"""

from __future__ import annotations

import math
import pickle
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from paths import FAST

from engine import (
    Body,
    DampedRotarySpring,
    DampedSpring,
    Polygon,
    SimulationDiverged,
    StabilityWarning,
    Vector,
    World,
)
from engine.forces import Gravity


def point(x: float, y: float, vx: float = 0.0, vy: float = 0.0, mass: float = 1.0) -> Body:
    return Body(Vector(x, y), Vector(vx, vy), mass=mass)


def damped(t: float, x0: float, v0: float, w0: float, gamma: float) -> float:
    """x(t) of x'' = -w0^2 x - 2 gamma x' (under-damped), from x0 (m) and v0 (m/s)."""
    wd = math.sqrt(w0 * w0 - gamma * gamma)
    return math.exp(-gamma * t) * (
        x0 * math.cos(wd * t) + (v0 + gamma * x0) / wd * math.sin(wd * t)
    )


def period(world: World, dt: float, steps: int, read: Callable[[], float]) -> float:
    """The mean time (s) between upward crossings of 0 by ``read()`` over ``steps`` steps."""
    times, values = [], []
    for _ in range(steps):
        world.step(dt)
        times.append(world.t)
        values.append(read())
    ups = crossings(times, values)
    return (ups[-1] - ups[0]) / (len(ups) - 1)


def crossings(times: list[float], values: list[float]) -> list[float]:
    """The times (s) at which ``values`` cross 0 upward, by linear interpolation."""
    out = []
    for k in range(1, len(values)):
        if values[k - 1] < 0.0 <= values[k]:
            f = values[k - 1] / (values[k - 1] - values[k])
            out.append(times[k - 1] + f * (times[k] - times[k - 1]))
    return out


# -- the closed form ---------------------------------------------------------------------------
@pytest.mark.parametrize("integrator", ["auto", "exact"])
def test_a_mass_on_a_damped_spring_follows_the_damped_oscillator_to_1e_9(integrator: str) -> None:
    m, k, c = 2.0, 50.0, 1.5
    world = World(integrator=integrator)
    world.add_force(Gravity((-3.0, 0.0)))  # along the spring's line: its rest point moves
    body = world.add(point(1.0, 0.5, 0.5, 0.0, mass=m))
    world.add_link(DampedSpring(body, world.static_body, (0, 0), (0.0, 0.5), 0.0, k, c))
    dt = 1.0 / 60.0
    world.step(dt)
    assert world.method == "exact"
    assert integrator == "exact" or "every spring linear" in world.method_reason
    rest = -3.0 * m / k  # where gravity and the spring balance
    worst = 0.0
    for _ in range(1200):  # 20 s, 22 periods
        world.step(dt)
        x = damped(world.t, 1.0 - rest, 0.5, math.sqrt(k / m), c / (2 * m)) + rest
        worst = max(worst, abs(body.pos.x - x), abs(body.pos.y - 0.5))
    assert worst < 1e-9


def test_two_bodies_on_an_undamped_spring_oscillate_with_the_reduced_mass_exactly() -> None:
    m1, m2, k = 1.0, 3.0, 40.0
    world = World(integrator="auto")
    a = world.add(point(0.0, 0.0, 0.3, 0.2, mass=m1))
    b = world.add(point(1.0, 0.5, -0.1, 0.4, mass=m2))
    world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 0.0, k, 0.0))
    mu = m1 * m2 / (m1 + m2)
    w = math.sqrt(k / mu)
    d0, u0 = np.array([1.0, 0.5]), np.array([-0.4, 0.2])  # b - a
    p0 = m1 * np.array([0.3, 0.2]) + m2 * np.array([-0.1, 0.4])
    worst = 0.0
    for _ in range(600):
        world.step(1.0 / 30.0)  # omega dt = 0.24: no integrator's step, the closed form's
        t = world.t
        d = d0 * math.cos(w * t) + u0 / w * math.sin(w * t)
        worst = max(worst, float(np.abs(np.array(b.pos - a.pos) - d).max()))
        p = m1 * np.array(a.vel) + m2 * np.array(b.vel)
        worst = max(worst, float(np.abs(p - p0).max()))
    assert world.method == "exact"
    assert worst < 1e-9


def test_the_closed_form_measures_a_springs_impulse_as_the_momentum_it_gave() -> None:
    # Two bodies on a damped spring along the line u (anchors off their centres, along u;
    # points do not turn), their own accelerations along it too, pulling them apart (so that
    # the ends, 0.9 m apart at rest, never meet): the closed form. Over each step the spring
    # gave a the impulse m_a (v_a' - v_a) - m_a g_a dt, all along n = (p_b - p_a) / |p_b -
    # p_a|; its size along n is ``impulse`` (> 0 pulling). It was once 0, "not measured on
    # the closed form".
    u = Vector(0.6, 0.8)
    world = World(integrator="auto")
    a = world.add(Body(u * 0.0, u * 0.2, u * -2.0, mass=2.0))
    b = world.add(Body(u * 1.8, u * -0.1, u * 1.0, mass=3.0))
    spring = world.add_link(DampedSpring(a, b, u * 0.1, u * -0.2, 0.0, 4.0, 1.5))
    dt = 1.0 / 30.0
    pulls = []
    for _ in range(90):  # 3 s, more than a period
        va = a.vel
        world.step(dt)
        assert world.method == "exact"
        given = (a.vel - va) * a.mass - a.own_acc * (a.mass * dt)
        n = (spring.end_b() - spring.end_a()).normalized()
        assert spring.impulse == pytest.approx(given.dot(n), rel=1e-12)
        assert abs(given.cross(n)) < 1e-14  # all along the spring
        pulls.append(spring.impulse)
    assert min(pulls) > 0.0 and max(pulls) > 1.5 * min(pulls)


def test_the_closed_form_impulse_of_a_spring_that_turns_is_short_by_theta_squared_over_24() -> None:
    # Two bodies circling on an undamped spring: the closed form gives k |int d dt|, which
    # falls short of k int |d| dt (the sum of the impulses of many short steps) by about
    # theta^2 / 24 of it, theta the angle the spring turns within the step.
    def run(dt: float, steps: int) -> tuple[float, float]:
        world = World(integrator="auto")
        a = world.add(point(0.0, 0.0, 0.0, 0.3))
        b = world.add(point(1.0, 0.0, 0.0, 2.0))
        spring = world.add_link(DampedSpring(a, b, (0.1, 0), (0, 0.2), 0.0, 4.0, 0.0))
        before = spring.end_b() - spring.end_a()
        total = 0.0
        for _ in range(steps):
            world.step(dt / steps)
            total += spring.impulse
        after = spring.end_b() - spring.end_a()
        return total, abs(math.atan2(before.cross(after), before.dot(after)))

    (one, theta), (many, _) = run(0.05, 1), run(0.05, 1000)
    assert 0.0 < many - one == pytest.approx(many * theta**2 / 24, rel=0.2)


def test_exact_refuses_a_spring_that_is_not_linear_and_auto_leaves_the_closed_form() -> None:
    world = World(integrator="exact")
    body = world.add(point(1.0, 0.0))
    world.add_link(DampedSpring(body, world.static_body, (0, 0), (0, 0), 0.5, 10.0, 0.0))
    with pytest.raises(ValueError, match="rest length.*integrator='auto'"):
        world.step(0.01)
    auto = World(integrator="auto")
    body = auto.add(point(1.0, 0.0, 0.0, 1.0))  # moving off the spring's line
    spring = auto.add_link(DampedSpring(body, auto.static_body, (0, 0), (0, 0), 0.0, 10.0, 1.0))
    auto.step(0.01)
    assert auto.method != "exact"  # a damped spring whose ends leave its line is not linear
    spring.damping = 0.0
    assert spring.revision == 1


# -- the kicks: theorems -----------------------------------------------------------------------
def pair(dt: float, damping: float = 0.0, integrator: str = "velocity_verlet") -> World:
    world = World(integrator=integrator)
    a = world.add(point(0.0, 0.0, 0.2, 0.1, mass=1.0))
    b = world.add(point(1.5, 0.2, -0.3, 0.0, mass=3.0))
    world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 1.0, 100.0, damping))
    return world


def energy(world: World) -> float:
    """Kinetic energy and the springs' (J), summed here: what World.energy() must give."""
    a, b = world.bodies
    kinetic = 0.5 * (a.mass * a.vel.length() ** 2 + b.mass * b.vel.length() ** 2)
    total = kinetic + sum(s.energy() for s in world.springs)
    assert world.energy() == pytest.approx(total, rel=1e-12)
    return total


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "rk4"])
def test_two_bodies_on_a_spring_keep_their_momentum(integrator: str) -> None:
    world = pair(1.0 / 120.0, damping=2.0, integrator=integrator)
    a, b = world.bodies
    p0 = a.vel * a.mass + b.vel * b.mass
    for _ in range(600):
        world.step(1.0 / 120.0)
    p = a.vel * a.mass + b.vel * b.mass
    assert (p - p0).length() < 1e-13
    assert world.springs[0].impulse != 0.0


def test_undamped_energy_stays_within_a_bound_that_shrinks_as_dt_squared() -> None:
    spreads = []
    for dt in (1.0 / 100.0, 1.0 / 200.0):
        world = pair(dt)
        e0, worst = energy(world), 0.0
        for _ in range(round(2.0 / dt)):
            world.step(dt)
            worst = max(worst, abs(energy(world) - e0))
        spreads.append(worst / e0)
    assert spreads[0] < 5e-3
    assert spreads[0] / spreads[1] == pytest.approx(4.0, rel=0.02)


def test_the_period_of_two_masses_is_2_pi_sqrt_mu_over_k() -> None:
    m1, m2, k, dt = 1.0, 3.0, 100.0, 1.0 / 1000.0
    world = World(integrator="semi_implicit_euler")
    a = world.add(point(0.0, 0.0, mass=m1))
    b = world.add(point(1.2, 0.0, mass=m2))
    world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 1.0, k, 0.0))  # a rest length: kicks
    measured = period(world, dt, 3000, lambda: b.pos.x - a.pos.x - 1.0)
    expected = 2 * math.pi * math.sqrt(m1 * m2 / (m1 + m2) / k)
    # Velocity Verlet's period is 2 pi / w' with sin(w' dt / 2) = w dt / 2: 1 + (w dt)^2 / 24.
    assert measured == pytest.approx(expected, rel=1e-4)


def test_a_wheel_on_a_rotary_spring_turns_with_the_period_2_pi_sqrt_i_over_k() -> None:
    world = World()
    wheel = world.add(Body(Vector(0, 0), mass=2.0, radius=0.5))
    inertia = 2.0 * 0.5**2 / 2
    k, dt = 3.0, 1.0 / 1000.0
    world.add_link(DampedRotarySpring(wheel, world.static_body, 0.0, k, 0.0))
    wheel.angular_velocity = 1.0
    measured = period(world, dt, 4000, lambda: wheel.angle)
    assert measured == pytest.approx(2 * math.pi * math.sqrt(inertia / k), rel=1e-4)
    assert wheel.pos.length() == 0.0  # a torque moves no centre


def test_a_damped_rotary_spring_decays_as_its_damping_says() -> None:
    world = World()
    wheel = world.add(Body(Vector(0, 0), mass=2.0, radius=0.5))
    spring = world.add_link(DampedRotarySpring(wheel, world.static_body, 0.0, 0.0, 0.1))
    wheel.angular_velocity = 2.0
    for _ in range(60):
        world.step(1.0 / 60.0)
    # Implicit damping: omega e^(-c dt / I) a step, exactly.
    assert wheel.angular_velocity == pytest.approx(2.0 * math.exp(-0.1 / 0.25), rel=1e-12)
    assert spring.impulse < 0.0


def test_a_rotary_springs_impulse_is_the_angular_impulse_on_a_as_its_docstring_says() -> None:
    # Two wheels twisted apart, spring and damper: a's change of angular momentum over the
    # step is ``impulse``, b's the opposite. The docstring said "(pymunk's sign)", which is
    # the other (pymunk's testTorqueFunc: +13.25 here, -21.5 there).
    world = World()
    a = world.add(Body(Vector(0, 0), mass=10, moment=10, angular_velocity=-0.1))
    b = world.add(Body(Vector(0, 0), mass=20, moment=20, angle=2, angular_velocity=0.05))
    spring = world.add_link(DampedRotarySpring(a, b, 0, 10, 0.5))
    wa, wb = a.angular_velocity, b.angular_velocity
    world.step(0.1)
    assert spring.impulse > 0.0  # twist < 0: a turned counter-clockwise, back toward b
    assert a.moment * (a.angular_velocity - wa) == pytest.approx(spring.impulse, rel=1e-12)
    assert b.moment * (b.angular_velocity - wb) == pytest.approx(-spring.impulse, rel=1e-12)
    doc = DampedRotarySpring.__doc__ or ""
    assert "the angular impulse it gave body a" in " ".join(doc.split())
    assert "(pymunk's sign)" not in doc


def test_a_too_stiff_spring_is_warned_about_before_it_blows_up() -> None:
    world = World(integrator="rk4")
    a = world.add(point(0.0, 0.0))
    b = world.add(point(1.1, 0.0))
    world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 1.0, 1e4, 0.0))
    with pytest.warns(StabilityWarning, match=r"omega\*dt=2.357.*limit 2.*dt < 0.01414"):
        world.step(1.0 / 60.0)  # omega = sqrt(2e4) = 141 rad/s
    with pytest.raises(SimulationDiverged, match="stable only for dt < 0.01414 s") as err:
        for _ in range(2000):
            world.step(1.0 / 60.0)
    assert err.value.max_stable_dt == pytest.approx(2.0 / math.sqrt(2e4))
    calm = World()
    a, b = calm.add(point(0.0, 0.0)), calm.add(point(1.1, 0.0))
    calm.add_link(DampedSpring(a, b, (0, 0), (0, 0), 1.0, 1e4, 0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        for _ in range(100):
            calm.step(1.0 / 100.0)  # omega dt = 1.41


# -- against pymunk ----------------------------------------------------------------------------
@pytest.fixture
def pymunk() -> Any:
    """pymunk (the bench extra), or the test that asks for it is skipped: a module-level
    importorskip here skipped every test of the file where pymunk is not installed (CI)."""
    return pytest.importorskip("pymunk")


def test_a_turning_box_on_a_spring_moves_as_pymunks_to_round_off(pymunk: Any) -> None:
    """Undamped, the kicks' positions are pymunk's (a kick, then a move: the same recursion)
    once pymunk starts with the first half kick's velocities, v0 + F(x0) dt / (2 m)."""
    dt, k, m, inertia = 1.0 / 60.0, 20.0, 2.0, 0.4
    anchor, point_b = (0.3, 0.1), (1.0, -1.0)
    world = World()
    box = world.add(Body(Vector(0, 0), Vector(0.5, 0), mass=m, moment=inertia))
    world.add_link(DampedSpring(box, world.static_body, anchor, point_b, 0.5, k, 0.0))
    # The first half kick, by hand: F = -k (|d| - L) n on the box's anchor, at r = anchor.
    d = np.subtract(point_b, anchor)
    f = k * (np.hypot(*d) - 0.5) * d / np.hypot(*d)
    tau = anchor[0] * f[1] - anchor[1] * f[0]
    space = pymunk.Space()
    body = pymunk.Body(m, inertia)
    body.velocity = (0.5 + f[0] * dt / (2 * m), f[1] * dt / (2 * m))
    body.angular_velocity = tau * dt / (2 * inertia)
    space.add(body, pymunk.DampedSpring(body, space.static_body, anchor, point_b, 0.5, k, 0.0))
    worst = 0.0
    for _ in range(300):
        world.step(dt)
        space.step(dt)
        worst = max(worst, abs(box.pos.x - body.position.x), abs(box.pos.y - body.position.y))
        worst = max(worst, abs(box.angle - body.angle))
    assert worst < 1e-11


def test_damped_springs_stay_within_a_stated_tolerance_of_pymunks(pymunk: Any) -> None:
    """With damping, ours splits it in two half kicks a step and pymunk gives it once after
    the spring's kick: first order apart, at most 2 omega dt of the motion's size here."""
    dt, n = 1.0 / 240.0, 480
    world = pair(dt, damping=2.0)
    a, b = world.bodies
    space = pymunk.Space()
    pa, pb = pymunk.Body(1.0, math.inf), pymunk.Body(3.0, math.inf)
    pa.position, pa.velocity = (0, 0), (0.2, 0.1)
    pb.position, pb.velocity = (1.5, 0.2), (-0.3, 0.0)
    space.add(pa, pb, pymunk.DampedSpring(pa, pb, (0, 0), (0, 0), 1.0, 100.0, 2.0))
    worst = 0.0
    for _ in range(n):
        world.step(dt)
        space.step(dt)
        ours, theirs = b.pos - a.pos, pb.position - pa.position
        worst = max(worst, abs(ours.x - theirs.x), abs(ours.y - theirs.y))
    omega = math.sqrt(100.0 / 0.75)
    assert worst < 2 * omega * dt * 0.5  # (0.5 m: the stretch it starts with)


# -- pymunk's test_constraint.py, ported -------------------------------------------------------
def bodies() -> tuple[Body, Body]:
    return Body(Vector(0, 0), mass=10, moment=10), Body(Vector(0, 0), mass=20, moment=20)


def test_constraint_UnitTestDampedSpring_testAnchor() -> None:
    a, b = bodies()
    j = DampedSpring(a, b, (1, 2), (3, 4), 0, 0, 0)
    assert (j.anchor_a, j.anchor_b) == ((1, 2), (3, 4))
    j.anchor_a, j.anchor_b = (5, 6), (7, 8)
    assert (j.anchor_a, j.anchor_b) == ((5, 6), (7, 8))


@pytest.mark.parametrize("name", ["rest_length", "stiffness", "damping"])
def test_constraint_UnitTestDampedSpring_testRestLength_testStiffness_testDamping(
    name: str,
) -> None:
    a, b = bodies()
    j = DampedSpring(a, b, (0, 0), (0, 0), 1, 1, 1)
    assert getattr(j, name) == 1
    setattr(j, name, 2)
    assert getattr(j, name) == 2
    with pytest.raises(ValueError, match=f"{name} must be a finite number >= 0"):
        setattr(j, name, -1)


def test_constraint_UnitTestDampedSpring_testPickle() -> None:
    a, b = bodies()
    j2 = pickle.loads(pickle.dumps(DampedSpring(a, b, (1, 2), (3, 4), 5, 6, 7)))
    assert (j2.anchor_a, j2.anchor_b, j2.rest_length) == ((1, 2), (3, 4), 5)
    assert (j2.stiffness, j2.damping, j2.a.mass, j2.second.mass) == (6, 7, 10, 20)  # type: ignore[union-attr]


@pytest.mark.parametrize("name", ["rest_angle", "stiffness", "damping"])
def test_constraint_UnitTestDampedRotarySpring_testRestAngle_testStiffness_testDamping(
    name: str,
) -> None:
    a, b = bodies()
    j = DampedRotarySpring(a, b, 1, 1, 1)
    assert getattr(j, name) == 1
    setattr(j, name, 2)
    assert getattr(j, name) == 2


def test_constraint_UnitTestDampedRotarySpring_testPickle() -> None:
    a, b = bodies()
    j2 = pickle.loads(pickle.dumps(DampedRotarySpring(a, b, 1, 2, 3)))
    assert (j2.rest_angle, j2.stiffness, j2.damping, j2.a.mass) == (1, 2, 3, 10)


def test_a_spring_goes_with_its_body_and_is_refused_twice_or_between_other_worlds() -> None:
    world, other = World(), World()
    a, b = world.add(point(0, 0)), world.add(point(1, 0))
    spring = world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 0, 1, 0))
    assert world.springs == (spring,) and world.links == ()
    with pytest.raises(ValueError, match="already in this World"):
        world.add_link(spring)
    with pytest.raises(ValueError, match="in this World first"):
        other.add_link(DampedSpring(a, b, (0, 0), (0, 0), 0, 1, 0))
    with pytest.raises(TypeError, match="b must be a Body or world.static_body"):
        DampedSpring(a, (1, 2), (0, 0), (0, 0), 0, 1, 0)
    world.remove(b)
    assert world.springs == ()
    world.step(0.01)


# -- with joints and contacts, on both paths ---------------------------------------------------
def hinged(kernels: str) -> tuple[World, Body, Body]:
    """A plank on a hinge at its centre, twisted back by a rotary spring, and a ball hung from
    its end by a damped spring, falling onto a floor, on the exact models (asked for: the
    hinge held to 1e-9 m)."""
    from engine import Hinge, Plane

    world = World(kernels=kernels, solver="exact")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Plane((0.0, 0.0), (0.0, 1.0), restitution=0.0))
    plank = world.add(Body(Vector(0, 2), mass=4.0, shape=Polygon.box(2.0, 0.2)))
    world.add_link(Hinge(plank, world.static_body, (0, 2)))
    world.add_link(DampedRotarySpring(plank, world.static_body, 0.0, 30.0, 0.5))
    ball = world.add(Body(Vector(1.0, 1.2), mass=1.0, radius=0.2, restitution=0.0))
    world.add_link(DampedSpring(plank, ball, (1.0, 0.0), (0, 0), 0.8, 15.0, 1.0))
    return world, plank, ball


@FAST
def test_springs_with_a_hinge_and_contacts_end_alike_on_both_paths() -> None:
    ends = []
    for kernels in ("numpy", "fast"):
        world, plank, ball = hinged(kernels)
        low = math.inf
        for _ in range(120):
            world.step(1.0 / 60.0)
            low = min(low, ball.pos.y)
        assert (plank.pos - Vector(0, 2)).length() < 1e-9  # the hinge holds
        assert 0.2 - 1e-3 < low < 0.2 + 1e-3  # the ball came down onto the floor, held there
        ends.append((*plank.pos, plank.angle, *ball.pos, *ball.vel))
    assert np.allclose(ends[0], ends[1], rtol=0, atol=1e-9)


def test_a_hinged_plank_on_a_rotary_spring_turns_with_the_period_2_pi_sqrt_i_over_k() -> None:
    from engine import Hinge

    world = World()
    plank = world.add(Body(Vector(0, 0), mass=4.0, shape=Polygon.box(2.0, 0.2)))
    world.add_link(Hinge(plank, world.static_body, (0, 0)))
    k, dt = 30.0, 1.0 / 60.0  # (the joint solver's step is costly: few steps)
    world.add_link(DampedRotarySpring(plank, world.static_body, 0.0, k, 0.0))
    plank.angular_velocity = 0.5
    measured = period(world, dt, 300, lambda: plank.angle)
    # Velocity Verlet's period, longer by (omega dt)^2 / 24 = 2.5e-4 here.
    assert measured == pytest.approx(2 * math.pi * math.sqrt(plank.moment / k), rel=5e-4)


# -- drawn -------------------------------------------------------------------------------------
def test_a_spring_is_drawn_as_a_zigzag_and_a_zero_length_one_draws_nothing() -> None:
    """Also pymunk's test_space.testDebugDrawZeroLengthSpring (skipped in pymunk itself): a
    spring of length 0 to the static body is drawn without error."""
    pygame = pytest.importorskip("pygame")
    from engine.render import PAPER, Camera, draw_world, init_headless
    from engine.render.world_view import JOINT, TOOTH

    init_headless()
    camera = Camera(60.0, (180.0, 180.0))  # 60 px a metre, the origin in the middle
    world = World()
    a, b = world.add(point(-2.0, 0.0)), world.add(point(2.0, 0.0))
    world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 4.0, 1.0, 0.0))
    world.add_link(DampedSpring(a, world.static_body, (0, 0), (-2.0, 0.0), 0.0, 10.0, 1.0))
    surface = pygame.Surface((360, 360))
    surface.fill(PAPER)
    draw_world(surface, world, camera)
    # A column at x = 0.3 m: the zigzag crosses it within TOOTH px of the line y = 0, not on it
    # only; far from it, nothing.
    column = [tuple(surface.get_at((198, y)))[:3] for y in range(170, 191)]
    hit = [180 - (170 + k) for k, c in enumerate(column) if c == JOINT]
    assert hit and all(abs(h) <= TOOTH + 1 for h in hit)
    assert tuple(surface.get_at((198, 100)))[:3] == PAPER


def test_bodies_tied_by_a_spring_sleep_and_wake_as_one_group() -> None:
    """A crate asleep on a floor, tied by a spring to one pushed away, is pulled after it:
    the spring joins their sleeping group (as a constraint joins pymunk's islands)."""
    from engine import Plane

    world = World()
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Plane((0, 0), (0, 1), restitution=0.0, friction=0.5))
    crates = [
        world.add(
            Body(Vector(x, 0.5), mass=1.0, shape=Polygon.box(1, 1), restitution=0, friction=0.5)
        )
        for x in (0.0, 3.0)
    ]
    world.add_link(DampedSpring(crates[0], crates[1], (0, 0), (0, 0), 3.0, 50.0, 1.0))
    for _ in range(120):
        world.step(1.0 / 60.0)
    assert world.is_sleeping(crates[0]) and world.is_sleeping(crates[1])
    crates[1].vel = Vector(6.0, 0.0)  # wakes its group: both
    for _ in range(60):
        world.step(1.0 / 60.0)
        # Never one asleep while the other moves: friction (4.9 N) yields to the pull.
        assert world.is_sleeping(crates[0]) == world.is_sleeping(crates[1])
    assert crates[0].pos.x > 1.0


def test_many_springs_in_arrays_move_as_few_in_floats(monkeypatch: pytest.MonkeyPatch) -> None:
    """Past FEW springs the kicks go in arrays, the dampers a colour at a time: a free chain
    of 20 damped springs keeps its momentum and ends where the one-by-one kicks leave it."""
    import engine.exact.spring_step as spring_step

    rng = np.random.default_rng(7)
    speeds = rng.normal(size=(21, 2))

    def chain() -> tuple[World, list[Body]]:
        world = World()
        beads = [world.add(point(0.5 * i, 0.0, *speeds[i], mass=1.0 + i % 3)) for i in range(21)]
        for a, b in zip(beads, beads[1:], strict=False):
            world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 0.4, 200.0, 0.5))
        return world, beads

    ends = []
    for few in (spring_step.FEW, 100):
        monkeypatch.setattr(spring_step, "FEW", few)
        world, beads = chain()
        p0 = sum((b.vel * b.mass for b in beads), Vector(0, 0))
        for _ in range(200):
            world.step(1.0 / 240.0)
        p = sum((b.vel * b.mass for b in beads), Vector(0, 0))
        assert (p - p0).length() < 1e-12
        ends.append([c for b in beads for c in (*b.pos, *b.vel)])
    assert np.allclose(ends[0], ends[1], rtol=0, atol=1e-9)


def test_a_spring_keeps_its_bodies_when_another_body_leaves_the_world() -> None:
    world = World()
    gone = world.add(point(-5.0, 0.0))
    a, b = world.add(point(0.0, 0.0)), world.add(point(2.0, 0.0))
    spring = world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 1.0, 10.0, 0.0))
    world.step(0.01)
    world.remove(gone)  # the rows of a and b shift down
    world.step(0.01)
    # Pulled toward each other, by equal and opposite impulses: not toward the old rows.
    assert a.vel.x > 0.0 and b.vel.x == pytest.approx(-a.vel.x, rel=1e-12)
    assert spring.impulse > 0.0


def test_a_kinematic_hand_drags_a_box_by_a_corner_as_pymunks_does(pymunk: Any) -> None:
    """A spring from a body the game moves (a mouse's hand) to a box's corner: the box is
    dragged and turned; damped, first order apart from pymunk's (measured 0.017 m, 0.004 rad
    after 5 s), held under 0.05."""
    world = World()
    hand = world.add(Body(Vector(0, 0), Vector(1, 0), mass=1.0, kinematic=True))
    box = world.add(Body(Vector(0, -1), mass=2.0, shape=Polygon.box(0.5, 0.5)))
    world.add_link(DampedSpring(hand, box, (0, 0), (0.2, 0.2), 0.5, 40.0, 4.0))
    space = pymunk.Space()
    their_hand = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
    their_hand.velocity = (1, 0)
    their_box = pymunk.Body(2.0, pymunk.moment_for_box(2.0, (0.5, 0.5)))
    their_box.position = (0, -1)
    space.add(
        their_hand,
        their_box,
        pymunk.DampedSpring(their_hand, their_box, (0, 0), (0.2, 0.2), 0.5, 40.0, 4.0),
    )
    for _ in range(300):
        world.step(1.0 / 60.0)
        space.step(1.0 / 60.0)
    assert hand.pos == Vector(5.0, 0.0) or abs(hand.pos.x - 5.0) < 1e-12
    assert (box.pos - Vector(*their_box.position)).length() < 0.05
    assert abs(box.angle - their_box.angle) < 0.05
    assert box.pos.x > 4.0  # dragged along
