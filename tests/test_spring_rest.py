"""Damped springs come to rest where their pull balances the constant forces, on the kicks
(engine.exact.spring_step, "The dampers"): k stretch = m g to round-off, whatever the method.

The kicks once decayed each half kick's velocity after its pull, so the damper decayed the
pull that holds the weight: a crate of 2 kg on 100 N/m and 20 N s/m at dt = 1/60 s rested
25.9 mm low on semi-implicit Euler (the World's default) and 8.9 mm on velocity Verlet, and a
wheel on a rotary spring under a torque 2.6% past tau / k. At rest the dampers now give
nothing over a step, so the rest is the undamped one. The speed at rest is 0 where the
method's step is symmetric (velocity Verlet, rk4, a body's free turn), and g dt / (2 s) up on
semi-implicit Euler, s = e^(-c dt / (2 m)): its step kicks by g dt before it drifts, the
spring's pull lags it by half a step (as undamped: g dt / 2, halved with dt).
"""

from __future__ import annotations

import math

import pytest
from paths import PATHS

from engine import Body, DampedRotarySpring, DampedSpring, Polygon, Vector, World
from engine.forces import Gravity

G, DT, K, C, M = 9.81, 1.0 / 60.0, 100.0, 20.0, 2.0


def stagger(integrator: str, damping: float, mass: float) -> float:
    """The speed (m/s, up > 0) at rest of a body hanging on a damped spring: the module's
    u* = (G2 - G1) / (2 q), G1 and G2 the step's kicks before and after its drift."""
    if integrator != "semi_implicit_euler":
        return 0.0
    q = max(math.exp(-damping * DT / (2 * mass)), -math.expm1(-damping * DT / mass))
    return G * DT / (2 * q)


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "velocity_verlet"])
def test_a_crate_on_a_damped_spring_rests_where_k_stretch_is_m_g(
    path: str, integrator: str
) -> None:
    world = World(integrator=integrator, kernels=path)
    world.add_force(Gravity((0.0, -G)))
    crate = world.add(
        Body(Vector(0, 4.75), mass=M, shape=Polygon.box(1.0, 1.0))
    )  # (no closed form)
    spring = world.add_link(DampedSpring(crate, world.static_body, (0, 0), (0, 5), 0.0, K, C))
    for _ in range(330):  # (within 1e-11 after 272 steps)
        world.step(DT)
    assert world.method == integrator
    assert abs(crate.pos.y - (5.0 - M * G / K)) < 1e-9  # was 25.9 mm low on semi-implicit Euler
    assert abs(crate.vel.y - stagger(integrator, C, M)) < 1e-9
    assert crate.pos.x == 0.0 and crate.vel.x == 0.0
    # At rest the damper gives nothing over the step: the spring's impulse is the weight's.
    assert spring.impulse == pytest.approx(M * G * DT, rel=1e-9)


@pytest.mark.parametrize("path", PATHS)
def test_a_crate_at_its_rest_stays_there_from_the_first_step(path: str) -> None:
    world = World(integrator="velocity_verlet", kernels=path)
    world.add_force(Gravity((0.0, -G)))
    crate = world.add(Body(Vector(0, 5.0 - M * G / K), mass=M, shape=Polygon.box(1.0, 1.0)))
    world.add_link(DampedSpring(crate, world.static_body, (0, 0), (0, 5), 0.0, K, C))
    for _ in range(5):
        world.step(DT)
        assert abs(crate.pos.y - (5.0 - M * G / K)) < 1e-14
        assert abs(crate.vel.y) < 1e-12


@pytest.mark.parametrize("path", PATHS)
def test_a_stiff_damper_holds_its_crate_at_rest_where_k_stretch_is_m_g(path: str) -> None:
    # c dt / m = 17 on 1000 N/m: the kicks once rested this crate 1.38 m low, 70 times its
    # stretch (the bias grew as e^(c dt / 2 m)).
    k, c = 1000.0, 2000.0
    world = World(kernels=path)
    world.add_force(Gravity((0.0, -G)))
    crate = world.add(Body(Vector(0, 4.9), mass=M, shape=Polygon.box(1.0, 1.0)))
    world.add_link(DampedSpring(crate, world.static_body, (0, 0), (0, 5), 0.0, k, c))
    for _ in range(360):  # (within 1e-11 after 316 steps)
        world.step(DT)
    assert abs(crate.pos.y - (5.0 - M * G / k)) < 1e-9
    assert abs(crate.vel.y - stagger("semi_implicit_euler", c, M)) < 1e-9


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "velocity_verlet"])
def test_two_bodies_hung_one_from_the_other_rest_where_each_spring_holds_its_load(
    integrator: str,
) -> None:
    # a from the world, b from a (rest lengths 0.5 m): a's spring holds both bodies, b's one.
    # (Bodies without shapes: no kernel of either path, and four times cheaper a step.)
    world = World(integrator=integrator)
    world.add_force(Gravity((0.0, -G)))
    a = world.add(Body(Vector(0, 4.2), mass=1.0))
    b = world.add(Body(Vector(0, 3.5), mass=M))
    world.add_link(DampedSpring(a, world.static_body, (0, 0), (0, 5), 0.5, K, C))
    world.add_link(DampedSpring(b, a, (0, 0), (0, 0), 0.5, K, C))
    for _ in range(660):  # (within 1e-11 after 570 steps)
        world.step(DT)
    ya = 5.0 - 0.5 - (1.0 + M) * G / K
    assert abs(a.pos.y - ya) < 1e-9  # was 27 mm low on semi-implicit Euler, 9.7 on Verlet
    assert abs(b.pos.y - (ya - 0.5 - M * G / K)) < 1e-9
    if integrator == "velocity_verlet":
        assert abs(a.vel.y) < 1e-9 and abs(b.vel.y) < 1e-9


def test_a_body_carried_on_a_spring_by_a_moving_hand_hangs_k_stretch_below_it() -> None:
    # The damper acts on the spring's change of length: a hand moving at 1 m/s carries the
    # body at 1 m/s, hanging as from a hand at rest.
    world = World(integrator="velocity_verlet")
    world.add_force(Gravity((0.0, -G)))
    hand = world.add(Body(Vector(0, 5), Vector(1, 0), mass=1.0, kinematic=True))
    crate = world.add(Body(Vector(0, 4.75), Vector(1, 0), mass=M))
    world.add_link(DampedSpring(hand, crate, (0, 0), (0, 0), 0.0, K, C))
    for _ in range(330):
        world.step(DT)
    hang = crate.pos - hand.pos
    assert abs(hang.x) < 1e-9 and abs(hang.y + M * G / K) < 1e-9
    assert abs(crate.vel.x - 1.0) < 1e-9 and abs(crate.vel.y) < 1e-9


@pytest.mark.parametrize("path", PATHS)
def test_a_wheel_on_a_damped_rotary_spring_rests_where_k_twist_is_its_torque(path: str) -> None:
    # I = 0.25 kg m^2, k = 3 N m/rad, c = 1.5 N m s/rad, torque 0.3 N m: at rest the twist is
    # tau / k = 0.1 rad (was 0.1026: the damper decayed the pull that holds the torque).
    world = World(kernels=path)
    wheel = world.add(Body(Vector(0, 0), mass=2.0, radius=0.5, torque=0.3))
    world.add_link(DampedRotarySpring(wheel, world.static_body, 0.0, 3.0, 1.5))
    for _ in range(600):
        world.step(DT)
    assert abs(wheel.angle - 0.1) < 1e-9
    assert abs(wheel.angular_velocity) < 1e-9


def test_damped_kicks_are_second_order() -> None:
    # Two bodies on a damped spring with a rest length (the kicks): halving dt quarters the
    # error against a fine step's (velocity Verlet on the spring, its damper split about the
    # method's step). The dampers once decayed after each pull, first order: halving dt
    # halved it.
    def ends(dt: float) -> tuple[float, ...]:
        world = World(integrator="velocity_verlet")
        world.add_force(Gravity((0.0, -G)))
        a = world.add(Body(Vector(0, 0), Vector(0.3, 0.5), mass=1.0))
        b = world.add(Body(Vector(1.2, -0.4), mass=3.0, kinematic=False))
        world.add_link(DampedSpring(a, b, (0, 0), (0, 0), 1.0, 60.0, 6.0))
        for _ in range(round(1.0 / dt)):
            world.step(dt)
        return (*a.pos, *b.pos, *a.vel, *b.vel)

    fine = ends(1.0 / 960.0)
    errors = [
        max(abs(p - q) for p, q in zip(ends(dt), fine, strict=True)) for dt in (1 / 60, 1 / 120)
    ]
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.15)
