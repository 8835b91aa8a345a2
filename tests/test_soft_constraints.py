"""pymunk's constraints that only the soft step solves (engine.dynamics.constraints): SlideJoint,
GrooveJoint, GearJoint, RatchetJoint, RotaryLimitJoint and SimpleMotor, rows of
World(solver="soft")'s one solver (engine.dynamics.solver), checked against closed forms and
theorems on both paths, the same bits on each; the exact solver's refusal, and the errors."""

from __future__ import annotations

import math
import pickle
from typing import Any

import pytest

from engine import (
    Body,
    Cable,
    GearJoint,
    GrooveJoint,
    Pin,
    Polygon,
    RatchetJoint,
    Rod,
    RotaryLimitJoint,
    SimpleMotor,
    SlideJoint,
    Vector,
    World,
)
from engine.dynamics import solver
from engine.forces import Gravity
from tests.paths import FAST, PATHS

DT = 1.0 / 60.0
G = 9.81
#: The joints' spring (engine.dynamics.solver: 60 Hz at 4 substeps of 1/60 s), its angular
# frequency.
OMEGA = 2.0 * math.pi * solver.JOINT_HERTZ


def soft(kernels: str, gravity: bool = False) -> World:
    world = World(kernels=kernels, solver="soft")
    world.sleep_time = math.inf  # (what these tests measure would sleep where it slows)
    if gravity:
        world.add_force(Gravity((0.0, -G)))
    return world


def disc(x: float, y: float, mass: float, radius: float, **kw: Any) -> Body:
    return Body(Vector(x, y), mass=mass, radius=radius, **kw)


# -- GearJoint -----------------------------------------------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("ratio", [2.0, -0.5])
def test_geared_discs_keep_their_ratio_and_share_what_the_gear_conserves(
    kernels: str, ratio: float
) -> None:
    # Two free discs, a spun, geared: the gear's impulse lam turns a by -lam and b by
    # ratio lam, so ratio I_a omega_a + I_b omega_b is kept, and omega_a = ratio omega_b:
    # omega_b = (ratio I_a w0) / (ratio^2 I_a + I_b) at once (a perfectly inelastic mesh).
    world = soft(kernels)
    a = world.add(disc(0.0, 0.0, 1.0, 0.5, angular_velocity=3.0))
    b = world.add(disc(3.0, 0.0, 2.0, 1.0))
    gear = world.add_link(GearJoint(a, b, 0.0, ratio))
    wb = ratio * a.moment * 3.0 / (ratio**2 * a.moment + b.moment)
    worst_rate, slips = 0.0, []
    for _ in range(120):
        world.step(DT)
        worst_rate = max(worst_rate, abs(a.angular_velocity - ratio * b.angular_velocity))
        slips.append(abs(ratio * b.angle - a.angle - gear.phase))
        assert b.angular_velocity == pytest.approx(wb, rel=1e-12)
    # The ratio holds from the first step on (0 rad/s off, measured: the rigid relax takes
    # the speeds there in the first substep). The teeth slip in that first substep, while the
    # soft solve meets the 3 rad/s (5.3e-4 rad, measured), and the joints' 60 Hz spring takes
    # the slip back: 5e-9 rad after 10 steps, none after 2 s.
    assert worst_rate < 1e-13
    assert slips[0] < 1e-3 and slips[10] < 1e-8 and slips[-1] < 1e-12
    assert a.vel == Vector(0.0, 0.0) and b.vel == Vector(0.0, 0.0)  # (it only turns them)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_gear_turns_its_discs_to_its_phase_and_reports_its_impulse(kernels: str) -> None:
    # Made a quarter turn off its phase, the gear's 60 Hz spring brings ratio angle_b -
    # angle_a to the phase in a few of its periods, with no spin left; a step's angular
    # impulse on a is I_a's change of spin.
    world = soft(kernels)
    a = world.add(disc(0.0, 0.0, 1.0, 0.5))
    b = world.add(disc(3.0, 0.0, 1.0, 0.5, angle=0.25))
    gear = world.add_link(GearJoint(a, b, -0.5, 3.0))
    w0 = a.angular_velocity
    world.step(DT)
    assert gear.angular_impulse == pytest.approx(a.moment * (a.angular_velocity - w0), rel=1e-9)
    assert gear.impulse == abs(gear.angular_impulse) > 0.0
    for _ in range(60):
        world.step(DT)
    assert 3.0 * b.angle - a.angle == pytest.approx(-0.5, abs=1e-9)
    assert abs(a.angular_velocity) < 1e-9 and abs(b.angular_velocity) < 1e-9


# -- RatchetJoint --------------------------------------------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("ratchet", [0.4, -0.4])
def test_a_ratchet_turns_freely_one_way_and_stops_at_its_last_notch_the_other(
    kernels: str, ratchet: float
) -> None:
    # A wheel on a ratchet to the world (a = the world: the wheel's angle is angle_b - angle_a),
    # notches at 0.05 + k ratchet. Spun the free way it turns as a free wheel, bit for bit;
    # spun back it stops at the last notch it passed, floor((angle - 0.05) / ratchet) ratchet
    # + 0.05, and rests there.
    world, twin = soft(kernels), soft(kernels)
    sign = math.copysign(1.0, ratchet)
    wheel = world.add(disc(0.0, 0.0, 1.0, 0.5, angular_velocity=3.0 * sign))
    free = twin.add(disc(0.0, 0.0, 1.0, 0.5, angular_velocity=3.0 * sign))
    pawl = world.add_link(RatchetJoint(world.static_body, wheel, 0.05, ratchet))
    for _ in range(30):
        world.step(DT)
        twin.step(DT)
        assert wheel.angle == free.angle and wheel.angular_velocity == free.angular_velocity
    assert pawl.impulse == 0.0
    notch = math.floor((wheel.angle - 0.05) / ratchet) * ratchet + 0.05
    assert 0.0 < (wheel.angle - notch) * sign < abs(ratchet)  # (1.5 rad turned)
    wheel.angular_velocity = -3.0 * sign
    for _ in range(60):
        world.step(DT)
        # Never back past the notch: the speculative row stops it on it.
        assert (wheel.angle - notch) * sign >= -1e-12
    assert wheel.angle == pytest.approx(notch, abs=1e-12)
    assert wheel.angular_velocity == pytest.approx(0.0, abs=1e-12)
    assert pawl.angle == pytest.approx(notch, abs=1e-12)  # pymunk's angle: the notch


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ratchet_holds_a_plank_level_by_half_its_weight_times_its_length(kernels: str) -> None:
    # A 1 m plank of 2 kg hinged to the world at its end, level, on a ratchet that lets it
    # turn up: gravity turns it down onto the notch at 0, which holds it. About the plank's
    # centre the hinge's m g (at 0.5 m) and the ratchet's torque balance: the ratchet gives
    # tau = m g L / 2 cos(angle). Its row gives as the joints' 60 Hz spring does, by its
    # angular acceleration over omega^2: tau / (I omega^2) (I the plank's own moment).
    world = soft(kernels, gravity=True)
    plank = world.add(Body(Vector(0.5, 0.0), mass=2.0, shape=Polygon.box(1.0, 0.1)))
    world.add_link(Pin(plank, (0.0, 0.0), anchor_a=(-0.5, 0.0)))
    pawl = world.add_link(RatchetJoint(world.static_body, plank, 0.0, 0.1))
    tau = 2.0 * G * 0.5
    give = tau / (plank.moment * OMEGA**2)  # 4.1e-4 rad
    for _ in range(120):
        world.step(DT)
        assert plank.angle >= -give * 1.01
    assert plank.angle == pytest.approx(-give, rel=1e-3)
    # Its angular impulse on body_a (the world) is minus the plank's.
    assert -pawl.angular_impulse == pytest.approx(tau * math.cos(plank.angle) * DT, rel=1e-9)
    assert pawl.impulse == -pawl.angular_impulse
    # Lifted past a notch about its hinge and let go, it falls back onto that notch.
    plank.angle = 0.25
    plank.position = 0.5 * math.cos(0.25), 0.5 * math.sin(0.25)
    for _ in range(120):
        world.step(DT)
    assert pawl.angle == pytest.approx(0.2, abs=1e-12)
    assert plank.angle == pytest.approx(0.2 - give * math.cos(0.2), rel=1e-3)


# -- GrooveJoint ---------------------------------------------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
def test_a_bead_slides_down_a_slanted_groove_at_g_sin_theta(kernels: str) -> None:
    # A bead on a groove of the world sloping down at theta: along it gravity's g sin(theta)
    # is all there is (the groove pushes across it only), so the bead moves as the step's
    # semi-implicit Euler moves a body at that acceleration: after N substeps of h,
    # v = g sin(theta) N h and s = g sin(theta) h^2 N (N + 1) / 2. Across it, the joints'
    # 60 Hz spring gives under g cos(theta) by g cos(theta) / omega^2 (6.4e-5 m here).
    world = soft(kernels, gravity=True)
    theta = 0.4
    u = Vector(math.cos(theta), -math.sin(theta))
    n = Vector(math.sin(theta), math.cos(theta))  # the groove's normal, up
    bead = world.add(disc(0.0, 0.0, 1.0, 0.1, angular_velocity=2.0))
    groove = world.add_link(GrooveJoint(world.static_body, bead, -u * 5.0, u * 5.0, (0.0, 0.0)))
    h = DT / world.contact_iterations
    worst = 0.0
    for step in range(1, 61):
        world.step(DT)
        steps = step * world.contact_iterations
        a = G * math.sin(theta)
        assert bead.vel.dot(u) == pytest.approx(a * steps * h, rel=1e-12)
        assert bead.pos.dot(u) == pytest.approx(a * h * h * steps * (steps + 1) / 2, rel=1e-9)
        worst = max(worst, abs(bead.pos.dot(n)))
    assert worst == pytest.approx(G * math.cos(theta) / OMEGA**2, rel=1e-3)
    # It turns freely: the groove's push goes through the anchor, its centre.
    assert bead.angular_velocity == 2.0
    # The groove's push on the world is minus the bead's: m g cos(theta) dt, along n.
    assert groove.linear_impulse.dot(n) == pytest.approx(-G * math.cos(theta) * DT, rel=1e-6)
    assert groove.impulse == pytest.approx(G * math.cos(theta) * DT, rel=1e-6)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_bead_stops_at_the_end_of_its_groove(kernels: str) -> None:
    # Thrown along a level 2 m groove at 3 m/s, the bead stops at its end (the limit's
    # speculative row: on it, not past it) and rests there; thrown back, at its start.
    world = soft(kernels)
    bead = world.add(disc(0.0, 0.0, 1.0, 0.1, velocity=(3.0, 0.0)))
    world.add_link(GrooveJoint(world.static_body, bead, (-1.0, 0.0), (1.0, 0.0), (0.0, 0.0)))
    for _ in range(60):
        world.step(DT)
        assert bead.pos.x <= 1.0 + 1e-12
    assert bead.pos.x == pytest.approx(1.0, abs=1e-12) and bead.vel.x == 0.0
    bead.velocity = -3.0, 0.0
    for _ in range(60):
        world.step(DT)
        assert bead.pos.x >= -1.0 - 1e-12
    assert bead.pos.x == pytest.approx(-1.0, abs=1e-12) and bead.vel.x == 0.0
    assert bead.pos.y == 0.0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_bead_flung_out_along_a_spinning_wheels_groove_keeps_the_angular_momentum(
    kernels: str,
) -> None:
    # A free wheel with a radial groove, spinning, and a bead in it near the centre: the bead
    # slides out to the groove's end, the wheel slows, and the angular momentum of the two
    # about their centre of mass, sum(I omega + m r x v), stays what it was (the groove's
    # impulses are internal). The bead stays in the groove within the joints' give.
    world = soft(kernels)
    wheel = world.add(disc(0.0, 0.0, 4.0, 1.0, angular_velocity=2.0))
    bead = world.add(disc(0.1, 0.0, 0.5, 0.05, velocity=(0.0, 0.2)))
    groove = world.add_link(GrooveJoint(wheel, bead, (0.0, 0.0), (0.9, 0.0), (0.0, 0.0)))

    def momentum() -> float:
        total = 0.0
        for b in (wheel, bead):
            total += b.moment * b.angular_velocity + b.mass * b.pos.cross(b.vel)
        return total

    l0 = momentum()
    worst = 0.0
    for _ in range(120):
        world.step(DT)
        local = wheel.world_to_local(bead.pos)
        worst = max(worst, abs(local.y))
        assert momentum() == pytest.approx(l0, rel=1e-12)
    # At the end, out by the give of its limit under the spin's pull (9e-5 m, measured);
    # across, within the joints' give as the bead is flung (1.9e-4 m, measured).
    assert wheel.world_to_local(bead.pos).x == pytest.approx(0.9, abs=2e-4)
    assert wheel.angular_velocity < 1.8  # slowed by the bead's reach
    assert worst < 5e-4
    assert groove.impulse > 0.0


# -- SlideJoint ----------------------------------------------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
def test_a_pendulum_on_a_slide_joint_swings_within_its_bounds(kernels: str) -> None:
    # A bob on a slide joint of 0.5 to 1 m from a pivot, thrown up and in from the bottom: it
    # flies slack, its distance between the bounds, until one catches it; never nearer than
    # min nor farther than max, but for the joints' give.
    world = soft(kernels, gravity=True)
    bob = world.add(disc(0.0, -1.0, 1.0, 0.05, velocity=(1.0, 6.0)))
    joint = world.add_link(SlideJoint(world.static_body, bob, (0.0, 0.0), (0.0, 0.0), 0.5, 1.0))
    near, far = math.inf, 0.0
    for _ in range(300):
        world.step(DT)
        near, far = min(near, joint.distance), max(far, joint.distance)
    # It came in to min (stopped 0.2 mm short of it by the speculative row, gravity acting
    # in the substep), and out to max, by the joints' 60 Hz give as it caught the bob at
    # 4 m/s (0.22 mm measured).
    assert 0.5 <= near < 0.501
    assert 1.0 <= far < 1.0 + 5e-4


@pytest.mark.parametrize("kernels", PATHS)
def test_a_body_pushed_toward_the_other_stops_at_min_as_one_inelastic_pair(kernels: str) -> None:
    # Two bodies 2 m apart on a slide joint of 1 to 3 m, one thrown at the other: at min the
    # joint stops their closing (no bounce), and both go on at the pair's velocity,
    # momentum / (m_a + m_b); thrown apart, likewise at max.
    world = soft(kernels)
    a = world.add(disc(0.0, 0.0, 1.0, 0.1))
    b = world.add(disc(2.0, 0.0, 3.0, 0.1, velocity=(-4.0, 0.0)))
    joint = world.add_link(SlideJoint(a, b, (0.0, 0.0), (0.0, 0.0), 1.0, 3.0))
    for _ in range(30):
        world.step(DT)
        assert joint.distance >= 1.0 - 1e-12
    assert joint.distance == pytest.approx(1.0, abs=1e-12)
    assert a.vel.x == pytest.approx(-3.0, rel=1e-12) and b.vel.x == pytest.approx(-3.0, rel=1e-12)
    b.velocity = 4.0, 0.0  # (a still moves at -3: they part at 7 m/s)
    pair = (a.mass * a.vel.x + b.mass * b.vel.x) / (a.mass + b.mass)  # 2.25 m/s
    for _ in range(30):
        world.step(DT)
        assert joint.distance <= 3.0 + 1e-12
    assert joint.distance == pytest.approx(3.0, abs=1e-12)
    assert a.vel.x == pytest.approx(pair, rel=1e-12) and b.vel.x == pytest.approx(pair, rel=1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_slide_joint_of_min_max_is_a_rod_and_of_min_0_a_cable_bit_for_bit(kernels: str) -> None:
    # Its rows are a rod's (min == max) or a cable's without restitution (min 0), with the same
    # ends: the same motion to the bit, and the same impulse.
    for make in (
        lambda a, b: (Rod(b, a, 1.2, (0.1, 0.0), (0.0, 0.2)),
                      SlideJoint(a, b, (0.0, 0.2), (0.1, 0.0), 1.2, 1.2)),
        lambda a, b: (Cable(b, a, 1.5, 0.0, (0.1, 0.0), (0.0, 0.2)),
                      SlideJoint(a, b, (0.0, 0.2), (0.1, 0.0), 0.0, 1.5)),
    ):  # fmt: skip
        ends: list[list[Any]] = []
        for pick in (0, 1):
            world = soft(kernels, gravity=True)
            a = world.add(Body(Vector(0.0, 0.0), mass=2.0, shape=Polygon.box(0.4, 0.4)))
            b = world.add(Body(Vector(0.8, -0.8), mass=1.0, shape=Polygon.box(0.3, 0.2)))
            world.add_link(Rod(a, (0.0, 0.5)))
            link = world.add_link(make(a, b)[pick])
            for _ in range(90):
                world.step(DT)
            ends.append([(x.pos, x.vel, x.angle, x.angular_velocity) for x in (a, b)])
            ends[-1].append(link.impulse)
        assert ends[0] == ends[1]


# -- RotaryLimitJoint ----------------------------------------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
def test_a_rotary_limit_stops_two_discs_at_its_bounds_keeping_their_angular_momentum(
    kernels: str,
) -> None:
    # Two free discs turning apart: angle_b - angle_a stops at max, then (turned back) at min,
    # each time at once (the speculative row), both then turning at the pair's rate
    # (I_a omega_a + I_b omega_b) / (I_a + I_b), which the joint keeps.
    world = soft(kernels)
    a = world.add(disc(0.0, 0.0, 1.0, 0.5, angular_velocity=-1.0))
    b = world.add(disc(2.0, 0.0, 2.0, 0.5, angular_velocity=2.0))
    limit = world.add_link(RotaryLimitJoint(a, b, -0.3, 0.6))

    def spin() -> float:
        return a.moment * a.angular_velocity + b.moment * b.angular_velocity

    s0 = spin()
    for _ in range(60):
        world.step(DT)
        assert b.angle - a.angle <= 0.6 + 1e-12
        assert spin() == pytest.approx(s0, rel=1e-12, abs=1e-15)
    assert b.angle - a.angle == pytest.approx(0.6, abs=1e-12)
    common = s0 / (a.moment + b.moment)
    assert a.angular_velocity == pytest.approx(common, rel=1e-12)
    assert b.angular_velocity == pytest.approx(common, rel=1e-12)
    a.angular_velocity = 3.0
    for _ in range(60):
        world.step(DT)
        assert b.angle - a.angle >= -0.3 - 1e-12
    assert b.angle - a.angle == pytest.approx(-0.3, abs=1e-12)
    assert limit.max == 0.6 and limit.min == -0.3


# -- SimpleMotor ---------------------------------------------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
def test_a_motor_spins_up_at_its_torque_over_i_then_holds_its_rate(kernels: str) -> None:
    # A wheel on a motor to the world of rate 5 rad/s and at most 0.2 N m: while below the
    # rate, omega = (tau / I) t exactly (tau h a substep); at the rate it stays there, giving
    # no torque.
    world = soft(kernels)
    wheel = world.add(disc(0.0, 0.0, 2.0, 0.5))
    motor = world.add_link(SimpleMotor(wheel, world.static_body, 5.0, max_torque=0.2))
    alpha = 0.2 / wheel.moment  # 0.8 rad/s^2: the rate in 6.25 s
    for step in range(1, 361):
        world.step(DT)
        assert wheel.angular_velocity == pytest.approx(alpha * step * DT, rel=1e-12)
        assert motor.angular_impulse == pytest.approx(0.2 * DT, rel=1e-12)
        assert motor.torque(DT) == pytest.approx(0.2, rel=1e-12)
    for _ in range(60):
        world.step(DT)
    assert wheel.angular_velocity == pytest.approx(5.0, rel=1e-12)
    assert abs(motor.angular_impulse) < 1e-15
    motor.rate = -1.0  # set at any time: it turns back, as hard as it may
    world.step(DT)
    assert wheel.angular_velocity == pytest.approx(5.0 - alpha * DT, rel=1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_motor_between_two_discs_turns_them_apart_at_its_rate(kernels: str) -> None:
    # pymunk's rate is omega_a - omega_b; the motor's torques are opposite, so
    # I_a omega_a + I_b omega_b stays 0: omega_a = rate I_b / (I_a + I_b).
    world = soft(kernels)
    a = world.add(disc(0.0, 0.0, 1.0, 0.5))
    b = world.add(disc(2.0, 0.0, 3.0, 0.5))
    world.add_link(SimpleMotor(a, b, 2.0))
    world.step(DT)
    assert a.angular_velocity - b.angular_velocity == pytest.approx(2.0, rel=1e-12)
    assert a.angular_velocity == pytest.approx(2.0 * b.moment / (a.moment + b.moment), rel=1e-12)


# -- max_force, max_bias, error_bias (pymunk's bounds) -------------------------------------------


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("least", [1.0, 0.0, 0.5], ids=["rod", "cable", "slide"])
def test_a_bob_on_a_slide_joint_bearing_a_quarter_of_its_weight_falls_at_three_quarters_g(
    kernels: str, least: float
) -> None:
    # A 2 kg bob 1 m below a pivot on a slide joint (a rod, a cable, or between) whose
    # max_force is a quarter of its weight: the joint pulls as hard as it may, max_force h
    # each substep from the first on (its row asks for more and is kept at that), so the bob
    # falls as the step's semi-implicit Euler moves a body at a = g - max_force / m = 3/4 g:
    # after N substeps of h, v = -a N h and y = -1 - a h^2 N (N + 1) / 2. The joint reports
    # max_force dt a step, pulling; with no bound it would hold the bob.
    world = soft(kernels, gravity=True)
    bob = world.add(disc(0.0, -1.0, 2.0, 0.1))
    ws = world.static_body
    joint = world.add_link(SlideJoint(ws, bob, (0.0, 0.0), (0.0, 0.0), least, 1.0))
    assert joint.max_force == math.inf
    joint.max_force = 0.25 * bob.mass * G  # 4.905 N
    a = G - joint.max_force / bob.mass
    h = DT / world.contact_iterations
    for step in range(1, 61):
        world.step(DT)
        n = step * world.contact_iterations
        assert bob.vel.y == pytest.approx(-a * n * h, rel=1e-12)
        assert bob.pos.y + 1.0 == pytest.approx(-a * h * h * n * (n + 1) / 2, rel=1e-12)
        assert joint.impulse == pytest.approx(joint.max_force * DT, rel=1e-12)
        assert joint.impulse <= joint.max_force * DT * (1.0 + 1e-12)
        assert joint.linear_impulse.y == pytest.approx(-joint.impulse, rel=1e-12)  # (on the world)
    assert bob.vel.x == 0.0 and bob.pos.x == 0.0 and bob.angular_velocity == 0.0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_motor_with_max_force_spins_a_wheel_up_at_max_force_over_i(kernels: str) -> None:
    # pymunk bounds its SimpleMotor by max_force (a torque, N m): here one setting with
    # max_torque, by either name. Below its rate of 5 rad/s a wheel of moment I spins up at
    # max_force / I (0.8 rad/s^2), each step's angular impulse max_force dt; raised, at the
    # new bound from the next step on.
    world = soft(kernels)
    wheel = world.add(disc(0.0, 0.0, 2.0, 0.5))
    motor = world.add_link(SimpleMotor(wheel, world.static_body, 5.0))
    assert motor.max_force == motor.max_torque == math.inf
    motor.max_force = 0.2
    assert motor.max_torque == 0.2
    alpha = 0.2 / wheel.moment
    for step in range(1, 121):
        world.step(DT)
        assert wheel.angular_velocity == pytest.approx(alpha * step * DT, rel=1e-12)
        assert motor.impulse == pytest.approx(0.2 * DT, rel=1e-12)
        assert motor.impulse <= 0.2 * DT * (1.0 + 1e-12)
    motor.max_torque = 0.4
    assert motor.max_force == 0.4
    w0 = wheel.angular_velocity
    world.step(DT)
    assert wheel.angular_velocity == pytest.approx(w0 + 0.4 / wheel.moment * DT, rel=1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_gear_bearing_max_force_slips_each_disc_at_max_force_over_its_moment(
    kernels: str,
) -> None:
    # Disc a spun at 3 rad/s, geared 1:1 to b at rest, the gear's max_force 0.1 N m: its teeth
    # slip, turning a down at 0.1 / I_a (0.8 rad/s^2) and b up at 0.1 / I_b (0.1 rad/s^2)
    # until they turn alike (3.3 s on), I_a omega_a + I_b omega_b kept; with no bound they
    # would turn alike at once.
    world = soft(kernels)
    a = world.add(disc(0.0, 0.0, 1.0, 0.5, angular_velocity=3.0))
    b = world.add(disc(3.0, 0.0, 2.0, 1.0))
    gear = world.add_link(GearJoint(a, b, 0.0, 1.0))
    gear.max_force = 0.1
    for step in range(1, 61):
        world.step(DT)
        t = step * DT
        assert a.angular_velocity == pytest.approx(3.0 - 0.1 / a.moment * t, rel=1e-12)
        assert b.angular_velocity == pytest.approx(0.1 / b.moment * t, rel=1e-12)
        assert gear.impulse == pytest.approx(0.1 * DT, rel=1e-12)
        assert gear.impulse <= 0.1 * DT * (1.0 + 1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_pivot_bearing_max_force_gives_way_along_the_pull(kernels: str) -> None:
    # A 2 kg bead on a groove of no length to the world (pymunk's PivotJoint) under gravity
    # slanted to (0.6, -0.8) g: the groove's ends push along its axis and its point across
    # it, bounded as one vector (Chipmunk's) by max_force 5 N, so the bead gives way straight
    # down the pull at g - 5 / 2, as semi-implicit Euler moves it (v = a N h after N
    # substeps). (Bounded row by row it would be held by 5 N each way, 7.1 N, off the line.)
    world = World(kernels=kernels, solver="soft")
    world.sleep_time = math.inf
    down = Vector(0.6, -0.8)
    world.add_force(Gravity(tuple(down * G)))
    bead = world.add(disc(0.0, 0.0, 2.0, 0.1))
    pivot = world.add_link(GrooveJoint(world.static_body, bead, (0.0, 0.0), (0.0, 0.0), (0, 0)))
    pivot.max_force = 5.0
    a = G - 5.0 / bead.mass
    h = DT / world.contact_iterations
    for step in range(1, 61):
        world.step(DT)
        v = down * (a * step * world.contact_iterations * h)
        assert abs(bead.vel - v) <= 1e-12 * abs(v)
        assert pivot.impulse == pytest.approx(5.0 * DT, rel=1e-12)
        assert pivot.impulse <= 5.0 * DT * (1.0 + 1e-12)
    assert bead.angular_velocity == 0.0


@pytest.mark.parametrize("kernels", PATHS)
def test_max_bias_bounds_the_speed_a_joint_corrects_its_error_at(kernels: str) -> None:
    # Left with an error, each joint closes it at max_bias, no faster, from the first step:
    # a rod of 1 m with its bob 2 m out (max_bias 0.5 m/s), a 2:1 gear 1 rad off its phase
    # (0.2 rad/s), a pivot (a groove of no length) 0.5 m off its point, slantwise (0.25 m/s,
    # along the error: its rows' bias bounded as one vector). The relax takes each push's
    # speed away: the bodies are still after each step. The joints' 60 Hz spring alone
    # closes 69% of an error in a step (test_error_bias_...).
    world = soft(kernels)
    bob = world.add(disc(2.0, 0.0, 1.0, 0.1))
    ws = world.static_body
    rod = world.add_link(SlideJoint(ws, bob, (0.0, 0.0), (0.0, 0.0), 1.0, 1.0))
    a = world.add(disc(0.0, 3.0, 1.0, 0.5))
    b = world.add(disc(3.0, 3.0, 2.0, 1.0, angle=0.5))
    gear = world.add_link(GearJoint(a, b, 0.0, 2.0))
    bead = world.add(disc(10.3, -0.4, 1.0, 0.1))
    pivot = world.add_link(GrooveJoint(ws, bead, (10.0, 0.0), (10.0, 0.0), (0.0, 0.0)))
    assert rod.max_bias == gear.max_bias == pivot.max_bias == math.inf
    rod.max_bias, gear.max_bias, pivot.max_bias = 0.5, 0.2, 0.25
    for step in range(1, 61):
        world.step(DT)
        t = step * DT
        assert rod.distance == pytest.approx(2.0 - 0.5 * t, abs=1e-12)
        assert 2.0 * b.angle - a.angle == pytest.approx(1.0 - 0.2 * t, abs=1e-12)
        off = bead.pos - Vector(10.0, 0.0)
        assert abs(off) == pytest.approx(0.5 - 0.25 * t, abs=1e-12)
        assert off.x / off.y == pytest.approx(-0.75, abs=1e-12)
        for body in (bob, a, b, bead):
            assert abs(body.vel) < 1e-12 and abs(body.angular_velocity) < 1e-12


def _keeps(h: float) -> float:
    """The share of an error the joints' spring leaves in a substep of h, left to itself
    (engine.dynamics.solver: its push s_m bias_rate C moves the bodies for h, the relax takes the
    speed away): 1 - h^2 w^2 / (1 + 2 zeta h w + h^2 w^2), w = 2 pi min(60 Hz, 1 / (4 h))."""
    w = 2.0 * math.pi * min(solver.JOINT_HERTZ, 0.25 / h)
    zeta = solver.JOINT_DAMPING
    return 1.0 - h * h * w * w / (1.0 + 2.0 * zeta * h * w + h * h * w * w)


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("dt", [1 / 30, 1 / 60, 1 / 120])
def test_error_bias_leaves_its_share_of_an_error_after_1_s_at_any_step(
    kernels: str, dt: float
) -> None:
    # Two discs geared 2:1, b turned 0.5 rad off (an error of 1 rad). Set to 0.3, error_bias
    # leaves 0.3^dt of the error a step (Chipmunk's bias, each substep's push taken away by
    # the relax), 0.3 of it after 1 s whatever the step. Left None, the joints' spring leaves
    # _keeps(h) a substep: 31% a step at 1/60 s, e^-70 after 1 s, far less than pymunk's
    # default error_bias, 0.9^60 = 0.0018.
    errors = []
    for share in (None, 0.3):
        world = soft(kernels)
        a = world.add(disc(0.0, 0.0, 1.0, 0.5))
        b = world.add(disc(3.0, 0.0, 2.0, 1.0, angle=0.5))
        gear = world.add_link(GearJoint(a, b, 0.0, 2.0))
        assert gear.error_bias is None
        gear.error_bias = share
        world.step(dt)
        errors.append(2.0 * b.angle - a.angle)
        for _ in range(round(1.0 / dt) - 1):
            world.step(dt)
        errors.append(2.0 * b.angle - a.angle)
    keeps = _keeps(dt / solver.SUBSTEPS) ** solver.SUBSTEPS
    assert errors[0] == pytest.approx(keeps, rel=1e-12)
    assert abs(errors[1]) < 1e-15  # (rounding: e^-70 of it is left)
    assert errors[2] == pytest.approx(0.3**dt, rel=1e-12)
    assert errors[3] == pytest.approx(0.3, rel=1e-12)
    assert _keeps(DT / 4) ** 240 == pytest.approx(math.exp(-70.0), rel=0.03)


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("share", [None, 0.9**60, 0.5])
def test_a_set_error_bias_bears_a_load_without_the_springs_give(
    kernels: str, share: float | None
) -> None:
    # A wheel driven at 1 rad/s by a motor of 100 N m against a rotary limit at 1 rad, and a
    # 2 kg bob hanging on a 1 m rod: the joints' 60 Hz spring gives under the load by its
    # acceleration over omega^2 (100 / (I omega^2) = 7.0e-5 rad; g / omega^2 = 6.9e-5 m);
    # with error_bias set (pymunk's default, or another), the rows are rigid, as pymunk's,
    # and give nothing, bearing the same load (100 N m dt, m g dt a step).
    world, hanging = soft(kernels), soft(kernels, gravity=True)
    wheel = world.add(Body(Vector(0.0, 0.0), mass=10.0, moment=10.0))
    stop = world.add_link(RotaryLimitJoint(world.static_body, wheel, 0.0, 1.0))
    world.add_link(SimpleMotor(wheel, world.static_body, 1.0, max_torque=100.0))
    bob = hanging.add(disc(0.0, -1.0, 2.0, 0.1))
    ws = hanging.static_body
    rod = hanging.add_link(SlideJoint(ws, bob, (0.0, 0.0), (0.0, 0.0), 1.0, 1.0))
    stop.error_bias = rod.error_bias = share
    for _ in range(120):
        world.step(DT)
        hanging.step(DT)
    give = (100.0 / (wheel.moment * OMEGA**2), G / OMEGA**2) if share is None else (0.0, 0.0)
    assert wheel.angle - 1.0 == pytest.approx(give[0], rel=1e-9, abs=1e-15)
    assert rod.distance - 1.0 == pytest.approx(give[1], rel=1e-9, abs=1e-15)
    assert stop.impulse == pytest.approx(100.0 * DT, rel=1e-12)
    assert rod.impulse == pytest.approx(bob.mass * G * DT, rel=1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_setting_a_bound_wakes_the_bodies_and_the_next_step_takes_it(kernels: str) -> None:
    # A bob asleep on a cable: the same bound set again changes nothing and wakes nothing; a
    # new max_force of a quarter of its weight wakes it, and it falls at 3/4 g from the next
    # step (the cable's kept impulse, its weight, is taken back to the bound in the first
    # substep).
    world = World(kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -G)))
    bob = world.add(disc(0.0, -1.0, 2.0, 0.1))
    cable = world.add_link(SlideJoint(world.static_body, bob, (0.0, 0.0), (0.0, 0.0), 0.0, 1.0))
    for _ in range(120):
        world.step(DT)
    assert world.is_sleeping(bob)
    revision = cable.revision
    cable.max_force, cable.max_bias, cable.error_bias = math.inf, math.inf, None
    assert cable.revision == revision
    world.step(DT)
    assert world.is_sleeping(bob)
    cable.max_force = 0.25 * bob.mass * G
    assert cable.revision == revision + 1
    world.step(DT)
    assert not world.is_sleeping(bob)
    assert bob.vel.y == pytest.approx(-0.75 * G * DT, rel=1e-12)
    assert cable.impulse == pytest.approx(cable.max_force * DT, rel=1e-12)


def test_the_bounds_errors_name_the_argument_the_value_and_what_is_valid() -> None:
    world = World(solver="soft")
    a, b = world.add(disc(0, 0, 1, 0.1)), world.add(disc(1, 0, 1, 0.1))
    slide = SlideJoint(a, b, (0, 0), (0, 0), 0.5, 1.0)
    gear = GearJoint(a, b, 0.0, 1.0)
    motor = SimpleMotor(a, b, 1.0)
    share = r"error_bias must be the share of an error left after 1 s, from 0 to 1 \(pymunk's "
    share += r"default: \(1 - 0\.1\) \*\* 60\), or None for the soft step's joint spring; got "
    cases: list[tuple[Any, str, Any, type[Exception], str]] = [
        (slide, "max_force", -1.0, ValueError,
         r"max_force must be >= 0 in N \(inf: no bound\), got -1\.0"),
        (gear, "max_force", -1, ValueError,
         r"max_force must be >= 0 in N m \(inf: no bound\), got -1$"),
        (motor, "max_force", math.nan, ValueError,
         r"max_force must be >= 0 in N m \(inf: no bound\), got nan"),
        (motor, "max_torque", -2.0, ValueError,
         r"max_torque must be >= 0 in N m \(inf: no bound\), got -2\.0"),
        (slide, "max_force", "10", TypeError, r"max_force must be a real number, got str '10'"),
        (slide, "max_bias", math.nan, ValueError,
         r"max_bias must be >= 0 in m/s \(inf: no bound\), got nan"),
        (gear, "max_bias", -math.inf, ValueError,
         r"max_bias must be >= 0 in rad/s \(inf: no bound\), got -inf"),
        (gear, "error_bias", 1.5, ValueError, share + r"1\.5"),
        (gear, "error_bias", -0.1, ValueError, share + r"-0\.1"),
        (slide, "error_bias", math.inf, ValueError, share + r"inf"),
        (slide, "error_bias", True, TypeError, r"error_bias must be a real number, got bool True"),
    ]  # fmt: skip
    for joint, name, value, kind, message in cases:
        before, revision = getattr(joint, name), joint.revision
        with pytest.raises(kind, match=message):
            setattr(joint, name, value)
        assert getattr(joint, name) == before and joint.revision == revision
    # The ends of each range are valid: no force (it holds nothing), no correction, no bound;
    # an error all left, none left, and the spring again.
    for value in (0, math.inf, 2):
        slide.max_force = slide.max_bias = value
        assert slide.max_force == slide.max_bias == value
        assert type(slide.max_force) is float
    for share_ in (0, 1, 0.25, None):
        gear.error_bias = share_
        assert gear.error_bias == share_
    assert type(SimpleMotor(a, b, 1.0, max_torque=3).max_force) is float


def test_the_bounds_are_kept_by_a_copy_and_shown_by_repr() -> None:
    a, b = disc(0, 0, 1, 0.1), disc(1, 0, 1, 0.1)
    slide = SlideJoint(a, b, (0, 0), (0, 0), 0.5, 1.0)
    slide.max_force, slide.max_bias, slide.error_bias = 3.0, 0.5, 0.25
    motor = SimpleMotor(a, b, 1.0, max_torque=2.0)
    motor.max_bias = 1.0
    for joint in (slide, motor):
        twin = pickle.loads(pickle.dumps(joint))
        assert (twin.max_force, twin.max_bias, twin.error_bias) == (
            joint.max_force,
            joint.max_bias,
            joint.error_bias,
        )
    assert repr(slide).endswith(", min=0.5, max=1.0, max_force=3.0, max_bias=0.5, error_bias=0.25)")
    assert repr(motor).endswith(", rate=1.0, max_torque=2.0, max_bias=1.0)")
    assert "max_force" not in repr(motor)
    assert "max_" not in repr(GearJoint(a, b, 0.0, 1.0))


# -- what every one shares -----------------------------------------------------------------------


def every_joint(world: World) -> list[Any]:
    """One of each, in a small scene of their own (as ``world.add_link`` takes them)."""
    w = world
    a = w.add(Body(Vector(0.0, 0.0), mass=1.0, shape=Polygon.box(0.5, 0.3), angle=0.2))
    b = w.add(Body(Vector(1.0, 0.2), mass=2.0, shape=Polygon.box(0.4, 0.4), angular_velocity=1))
    c = w.add(disc(-1.0, 0.5, 1.0, 0.2, velocity=(1.0, 2.0)))
    d = w.add(disc(2.0, -1.0, 1.5, 0.3, angular_velocity=-2.0))
    return [
        SlideJoint(a, b, (0.25, 0.0), (-0.2, 0.0), 0.3, 0.9),
        GrooveJoint(w.static_body, c, (-2.0, 0.0), (2.0, 1.0), (0.0, 0.1)),
        GearJoint(b, d, 0.1, -1.5),
        RatchetJoint(a, w.static_body, 0.0, 0.3),
        RotaryLimitJoint(c, d, -0.4, 0.4),
        SimpleMotor(d, w.static_body, 3.0, max_torque=1.0),
        SlideJoint(d, w.static_body, (0.0, 0.3), (2.0, 1.0), 0.5, 2.5),
    ]


@FAST
def test_both_paths_give_the_same_constraints() -> None:
    ends = []
    for kernels in ("numpy", "fast"):
        world = soft(kernels, gravity=True)
        joints = [world.add_link(j) for j in every_joint(world)]
        for _ in range(120):
            world.step(DT)
        ends.append(
            [(x.pos, x.vel, x.angle, x.angular_velocity) for x in world.bodies]
            + [(j.impulse, j.linear_impulse, j.angular_impulse) for j in joints]
        )
    assert ends[0] == ends[1]


@FAST
def test_both_paths_give_the_same_bounded_constraints() -> None:
    # The same scene with every joint bounded (max_force and max_bias that bind, error_bias
    # on every other joint): the same bits on both paths (error_bias^h is one pow on each).
    ends = []
    for kernels in ("numpy", "fast"):
        world = soft(kernels, gravity=True)
        joints = [world.add_link(j) for j in every_joint(world)]
        for i, joint in enumerate(joints):
            joint.max_force, joint.max_bias = 1.5, 0.4
            joint.error_bias = 0.2 if i % 2 == 0 else None
        bound = 0
        for _ in range(120):
            world.step(DT)
            bound += sum(j.impulse == pytest.approx(1.5 * DT, rel=1e-12) for j in joints)
            assert all(j.impulse <= 1.5 * DT * (1.0 + 1e-12) for j in joints)
        assert bound > 100  # (the bound binds)
        ends.append(
            [(x.pos, x.vel, x.angle, x.angular_velocity) for x in world.bodies]
            + [(j.impulse, j.linear_impulse, j.angular_impulse) for j in joints]
        )
    assert ends[0] == ends[1]


@pytest.mark.parametrize("kernels", PATHS)
def test_bodies_held_by_them_to_the_world_fall_asleep_and_wake_when_one_is_set(
    kernels: str,
) -> None:
    # Still scenes under gravity, the world as body_a or as body_b: a plank held level by a
    # ratchet, one by a gear, a bead at the foot of its groove, a bob hanging on a slide
    # joint, a wheel held by a rotary limit and a motor at rate 0. Each sleeps as any still
    # body does (a joint to the world joins no island); setting a joint's parameter wakes its
    # bodies (its revision, as a winch's length does).
    world = World(kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -G)))
    ws = world.static_body
    planks = []
    for x in (0.0, 3.0):
        plank = world.add(Body(Vector(x + 0.5, 0.0), mass=2.0, shape=Polygon.box(1.0, 0.1)))
        world.add_link(Pin(plank, (x, 0.0), anchor_a=(-0.5, 0.0)))
        planks.append(plank)
    world.add_link(RatchetJoint(ws, planks[0], 0.0, 0.1))
    world.add_link(GearJoint(planks[1], ws, 0.0, 1.0))
    bead = world.add(disc(6.0, 0.0, 1.0, 0.1))
    world.add_link(GrooveJoint(ws, bead, (5.0, 0.5), (6.0, 0.0), (0.0, 0.0)))
    bob = world.add(disc(8.0, -1.0, 1.0, 0.1))
    world.add_link(SlideJoint(ws, bob, (8.0, 0.0), (0.0, 0.0), 0.2, 1.0))
    wheel = world.add(disc(10.0, 0.0, 1.0, 0.5))
    world.add_link(Rod(wheel, (10.0, 1.0)))
    world.add_link(RotaryLimitJoint(wheel, ws, -0.1, 0.1))
    motor = world.add_link(SimpleMotor(wheel, ws, 0.0))
    for _ in range(120):
        world.step(DT)
    assert [world.is_sleeping(body) for body in world.bodies] == [True] * 5
    motor.rate = 4.0
    world.step(DT)
    assert not world.is_sleeping(wheel) and world.is_sleeping(bob)
    assert wheel.angular_velocity != 0.0


def _still_steps(dt: float, sleep_time: float) -> int:
    """The steps a body still from a step on takes to sleep: its still time, dt summed a
    step, reaches sleep_time (31 of 1/60 s for 0.5 s: 30 sum to just under it)."""
    t, k = 0.0, 0
    while t < sleep_time:
        t, k = t + dt, k + 1
    return k


@pytest.mark.parametrize("kernels", PATHS)
def test_a_body_its_constraint_still_corrects_stays_awake_until_the_correction_is_slow(
    kernels: str,
) -> None:
    # The relax takes a correction's speed away (test_max_bias_...): a body a joint corrects
    # has no speed, though it moves. Sleep on (0.5 s), no gravity: a bead 0.5 m off its pivot
    # (a groove of no length) with error_bias 0.5, another with max_bias 0.25 m/s, and two
    # discs geared 2:1 1 rad off their phase with error_bias 0.5. Each is still only once the
    # step moves it by less than LINEAR dt (0.05 m/s) and turns it by less than ANGULAR dt
    # (2 degrees/s), and sleeps 0.5 s later. The bead's error, e0 0.5^t, closes by e (1 -
    # 0.5^dt) a step: under LINEAR dt from the first step that starts under 0.0726 m (the
    # 169th); it sleeps at step 199 with 0.050 m left. The gear's closes alike, disc a
    # turning 2/3 of it (i_a / (i_a + 4 i_b) = 8 / 12): under ANGULAR dt from the first step
    # that starts under 0.076 rad (the 225th); it sleeps at step 255 with 0.053 rad left. The
    # bounded bead moves at 0.25 m/s for 2 s and sleeps once the spring has closed the rest.
    # Counted by their speed alone (0), each would sleep at step 31: 0.35 m, 0.37 m and 0.70
    # rad off, moving at 0.24 m/s, 0.25 m/s and 0.32 rad/s.
    world = World(kernels=kernels, solver="soft")
    assert world.sleep_time == 0.5
    ws = world.static_body
    slow = world.add(disc(0.5, 0.0, 1.0, 0.1))
    pivot = world.add_link(GrooveJoint(ws, slow, (0.0, 0.0), (0.0, 0.0), (0.0, 0.0)))
    pivot.error_bias = 0.5
    bounded = world.add(disc(10.5, 0.0, 1.0, 0.1))
    world.add_link(GrooveJoint(ws, bounded, (10.0, 0.0), (10.0, 0.0), (0.0, 0.0))).max_bias = 0.25
    a = world.add(disc(0.0, 5.0, 1.0, 0.5))
    b = world.add(disc(3.0, 5.0, 2.0, 1.0, angle=0.5))
    world.add_link(GearJoint(a, b, 0.0, 2.0)).error_bias = 0.5

    def first_still(e0: float, share: float, limit: float) -> int:
        """The first step that moves a body by less than limit dt: e0 0.5^t closing."""
        k = 1
        while share * e0 * 0.5 ** ((k - 1) * DT) * (1.0 - 0.5**DT) >= limit * DT:
            k += 1
        return k

    wait = _still_steps(DT, world.sleep_time)
    assert wait == 31
    expected = {
        id(slow): first_still(0.5, 1.0, 0.05) + wait - 1,
        id(a): first_still(1.0, 2.0 / 3.0, math.radians(2.0)) + wait - 1,
    }
    assert list(expected.values()) == [199, 255]
    slept: dict[int, tuple[int, float]] = {}
    for step in range(1, 301):
        world.step(DT)
        errors = {id(slow): abs(slow.pos), id(bounded): abs(bounded.pos - Vector(10.0, 0.0)),
                  id(a): 2.0 * b.angle - a.angle}  # fmt: skip
        for body in (slow, bounded, a):
            if id(body) not in slept and world.is_sleeping(body):
                slept[id(body)] = (step, errors[id(body)])
        assert world.is_sleeping(a) == world.is_sleeping(b)  # (one island)
    assert slept[id(slow)][0] == expected[id(slow)]
    assert slept[id(slow)][1] == pytest.approx(0.5 * 0.5 ** (199 * DT), rel=1e-9)  # 0.050 m
    assert slept[id(a)][0] == expected[id(a)]
    assert slept[id(a)][1] == pytest.approx(0.5 ** (255 * DT), rel=1e-9)  # 0.053 rad
    assert 150 < slept[id(bounded)][0] < 160 and slept[id(bounded)][1] < 1e-15


def test_the_exact_solver_refuses_them_naming_the_soft_step() -> None:
    world = World(solver="exact")
    made = every_joint(world)
    for joint in made:
        name = type(joint).__name__
        with pytest.raises(ValueError, match=rf"a {name} is a row of the soft step's") as err:
            world.add_link(joint)
        assert "World(solver='soft')" in str(err.value)
        assert "solver='auto'" in str(err.value)
    assert world.links == ()
    soft_world = World(solver="soft")
    for joint in every_joint(soft_world):
        assert soft_world.add_link(joint) is joint
    assert [type(k).needs_soft for k in soft_world.links] == [True] * len(made)
    assert not Rod.needs_soft and not Cable.needs_soft


def test_their_errors_name_the_argument_the_value_and_what_is_valid() -> None:
    world = World(solver="soft")
    a, b = world.add(disc(0, 0, 1, 0.1)), world.add(disc(1, 0, 1, 0.1))
    still = world.add(disc(2, 0, 1, 0.1, kinematic=True))
    ws = world.static_body
    cases: list[tuple[Any, type[Exception], str]] = [
        (lambda: SlideJoint(a, b, (0, 0), (0, 0), 2.0, 1.0), ValueError,
         r"min must be <= max \(m\): got min=2\.0 with max=1\.0; to move both, set max "
         r"first when raising them, min first when lowering them"),
        (lambda: SlideJoint(a, b, (0, 0), (0, 0), -1.0, 1.0), ValueError, r"min must be >= 0"),
        (lambda: SlideJoint(a, b, (0, 0), (0, 0), 0.0, 0.0), ValueError, r"max must be > 0"),
        (lambda: SlideJoint(a, b, (0, 0), "x", 0.0, 1.0), TypeError, r"anchor_b must be a point"),
        (lambda: RotaryLimitJoint(a, b, 1.0, 0.5), ValueError,
         r"min must be <= max \(rad\): got min=1\.0 with max=0\.5"),
        (lambda: RatchetJoint(a, b, 0.0, 0.0), ValueError, r"ratchet must be != 0 \(rad\)"),
        (lambda: GearJoint(a, b, 0.0, math.nan), ValueError, r"ratio must be finite, got nan"),
        (lambda: GearJoint(a, b, "0", 1.0), TypeError,  # type: ignore[arg-type]
         r"phase must be a real number"),
        (lambda: SimpleMotor(a, b, 1.0, max_torque=-1.0), ValueError,
         r"max_torque must be >= 0 in N m \(inf: no bound\), got -1\.0"),
        (lambda: SimpleMotor(ws, ws, 1.0), TypeError,
         r"body_a and body_b are both world.static_body"),
        (lambda: GearJoint(a, a, 0.0, 1.0), ValueError, r"got body_a itself"),
        (lambda: GearJoint(a, "b", 0.0, 1.0), TypeError,
         r"body_b must be a Body or world.static_body, got str 'b'"),
        (lambda: SimpleMotor(still, ws, 1.0), ValueError, r"cannot hold: the game moves both"),
    ]  # fmt: skip
    for make, kind, message in cases:
        with pytest.raises(kind, match=message):
            make()
    joint = SlideJoint(a, b, (0, 0), (0, 0), 0.5, 1.0)
    with pytest.raises(ValueError, match=r"min must be <= max \(m\): got min=2\.0 with max=1\.0"):
        joint.min = 2.0
    joint.max = 3.0
    joint.min = 2.0  # (raising both: max first, then min)
    assert (joint.min, joint.max) == (2.0, 3.0)


def test_draw_world_shows_a_slide_joint_and_a_groove_as_pymunk_draws_them() -> None:
    # A slide joint is a line from anchor to anchor, a groove its segment with a ring at the
    # anchor held in it (the world's in world coordinates); a gear, as in pymunk, nothing.
    pygame = pytest.importorskip("pygame")
    from engine.render.camera import Camera
    from engine.render.world_view import BACKGROUND, JOINT, RING, draw_world

    def drawn(gear: bool) -> Any:
        world = World(solver="soft")
        a = world.add(disc(-2.0, 0.0, 1.0, 0.2))
        b = world.add(disc(0.0, 2.0, 1.0, 0.2))
        world.add_link(SlideJoint(a, world.static_body, (0.0, 0.0), (-2.0, 3.0), 0.5, 4.0))
        world.add_link(GrooveJoint(world.static_body, b, (-1.0, 2.0), (3.0, 2.0), (0.0, 0.0)))
        if gear:
            world.add_link(GearJoint(a, b, 0.0, 2.0))
        surface = pygame.Surface((200, 200))
        surface.fill(BACKGROUND)
        camera = Camera.fit((-4.0, -1.0, 4.0, 5.0), (0, 0, 200, 200))
        draw_world(surface, world, camera)
        return surface, camera

    surface, camera = drawn(gear=False)
    for point in ((-2.0, 1.5), (2.0, 2.0), (-0.6, 2.0)):  # the slide's middle, the groove's
        assert tuple(surface.get_at(camera.point(point)))[:3] == JOINT
    x, y = camera.point((0.0, 2.0))  # the bead's anchor: a ring about it, over its disc
    radius = max(2, round(RING * 200 / 360))
    assert tuple(surface.get_at((x + radius, y)))[:3] == JOINT
    geared, _ = drawn(gear=True)
    assert pygame.image.tobytes(geared, "RGB") == pygame.image.tobytes(surface, "RGB")


def test_a_snapshot_refuses_them_at_once_and_a_copy_takes_them() -> None:
    """A snapshot could not bring one back: it says so when taken, not at the restore."""
    w = World(solver="soft")
    a = w.add(Body(Vector(0.0, 0.0), radius=0.5))
    b = w.add(Body(Vector(2.0, 0.0), radius=0.5))
    w.add_link(GearJoint(a, b, 0.0, 2.0))
    a.angular_velocity = 1.0
    w.step(1 / 60)
    with pytest.raises(ValueError, match=r"snapshot\(\) does not take a GearJoint.*world\.copy"):
        w.snapshot()
    twin = w.copy()
    for _ in range(10):
        w.step(1 / 60)
        twin.step(1 / 60)
    assert twin.bodies[1].angular_velocity == w.bodies[1].angular_velocity != 0.0
