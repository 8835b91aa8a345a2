"""pymunk's constraints that only the soft step solves (engine.constraints): SlideJoint,
GrooveJoint, GearJoint, RatchetJoint, RotaryLimitJoint and SimpleMotor, rows of
World(solver="soft")'s one solver (engine.solver), checked against closed forms and theorems on
both paths, the same bits on each; the exact solver's refusal, and the errors."""

from __future__ import annotations

import math
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
    solver,
)
from engine.forces import Gravity
from tests.paths import FAST, PATHS

DT = 1.0 / 60.0
G = 9.81
#: The joints' spring (engine.solver: 60 Hz at 4 substeps of 1/60 s), its angular frequency.
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
        ends = []
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
        (lambda: GearJoint(a, b, "0", 1.0), TypeError, r"phase must be a real number"),
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
