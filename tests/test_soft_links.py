"""Rods, cables, pins and springs on World(solver="soft"): rows of the soft step's one solve
(engine.dynamics.solver's distance rows; a pin with an anchor is a hinge to the world, one that
holds its body makes it static), checked against statics, closed forms and the exact solver, on both
paths."""

import math
import warnings

import pytest

from engine import (
    Body,
    Cable,
    DampedRotarySpring,
    DampedSpring,
    Pin,
    Plane,
    Polygon,
    Rod,
    StabilityWarning,
    Vector,
    World,
)
from engine.forces import Gravity
from tests.paths import FAST, PATHS

DT = 1.0 / 60.0
G = 9.81


def soft(kernels: str) -> World:
    world = World(kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -G)))
    return world


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("kind", ["rod", "cable"])
def test_a_body_hanging_at_rest_pulls_its_link_by_its_weight(kernels: str, kind: str) -> None:
    world = soft(kernels)
    bob = world.add(Body(Vector(0.0, -1.0), mass=2.0, radius=0.1))
    link = Rod(bob, (0.0, 0.0)) if kind == "rod" else Cable(bob, (0.0, 0.0), 1.0)
    world.add_link(link)
    for _ in range(120):
        world.step(DT)
    # At rest the link carries the weight: its impulse over a step is m g dt, pulling.
    assert link.tension(DT) == pytest.approx(2.0 * G, rel=1e-9)
    # It gives as the joints' 60 Hz spring allows, no more (0.07 mm here, measured).
    assert abs(bob.pos) - 1.0 == pytest.approx(0.0, abs=1e-4)
    assert bob.pos.x == 0.0
    # Still, it sleeps as any body at rest does (a link joins an island as a joint does).
    assert world.is_sleeping(bob)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_rod_pendulum_swings_at_its_period_and_holds_its_length(kernels: str) -> None:
    world = soft(kernels)
    length, theta0 = 1.0, 0.1
    bob = world.add(
        Body(Vector(length * math.sin(theta0), -length * math.cos(theta0)), mass=1.0, radius=0.05)
    )
    world.add_link(Rod(bob, (0.0, 0.0)))
    worst, crossings, before = 0.0, [], bob.pos.x
    for _ in range(600):
        world.step(DT)
        worst = max(worst, abs(abs(bob.pos) - length))
        if before > 0.0 >= bob.pos.x:
            # Where the bob crossed the bottom, between the step's ends (linear in between).
            x0, x1 = before, bob.pos.x
            crossings.append(world.t - DT * x1 / (x1 - x0))
        before = bob.pos.x
    # The period of a pendulum of amplitude theta0, to its theta0^2 term.
    want = 2.0 * math.pi * math.sqrt(length / G) * (1.0 + theta0**2 / 16.0)
    period = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert period == pytest.approx(want, rel=2e-3)
    assert worst < 2e-4  # m: the rod's give, swinging (measured 7e-5)


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_slack_cable_does_nothing_and_snapping_taut_parts_at_e_times(
    kernels: str, e: float
) -> None:
    world, free = soft(kernels), soft(kernels)
    bob = world.add(Body(Vector(0.0, -0.5), mass=1.0, radius=0.05))
    twin = free.add(Body(Vector(0.0, -0.5), mass=1.0, radius=0.05))
    world.add_link(Cable(bob, (0.0, 0.0), 1.0, restitution=e))
    free.add_link(Cable(twin, (0.0, 0.0), 100.0))  # the same step, never taut
    for _ in range(60):
        start = twin.vel.y
        world.step(DT)
        free.step(DT)
        if bob.pos != twin.pos or bob.vel != twin.vel:
            break
        assert abs(bob.pos) < 1.0  # slack all the way: bit for bit a free fall
    else:
        pytest.fail("the cable never snapped taut")
    # The step that snapped it: the bob stopped at the cable's length (caught by the
    # speculative row, not past it), and parts at e times the speed the step began with
    # (Box2D's restitution, as a contact's).
    assert abs(bob.pos) <= 1.0
    if e > 0.0:
        assert bob.vel.y == pytest.approx(-e * start, rel=1e-12)
    else:
        # Stopped short of the length by the substep's fall, it closes no faster than that
        # gap in a substep (0.40 m/s from 3.1) and stays taut after.
        gap = 1.0 - abs(bob.pos)
        assert 0.0 <= -bob.vel.y <= gap / (DT / world.contact_iterations) + 1e-12
    top = bob.pos.y
    for _ in range(30):
        world.step(DT)
        top = max(top, bob.pos.y)
        assert abs(bob.pos) < 1.0 + 1e-4  # it never stretches past its length
    # Back up by (e v)^2 / 2g, as a ball thrown up at e v from where it snapped (2 mm
    # short of the length); at e = 0 it stays down.
    assert top + 1.0 == pytest.approx((e * start) ** 2 / (2 * G), rel=0.02, abs=3e-3)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_pinned_body_stays_put_when_struck_and_an_anchored_pin_swings_a_plank(
    kernels: str,
) -> None:
    world = soft(kernels)
    world.add_collider(Plane((0.0, -5.0), (0.0, 1.0)))
    post = world.add(Body(Vector(0.0, 0.0), mass=1.0, radius=0.5))
    world.add_link(Pin(post, (0.0, 0.0)))
    ball = world.add(Body(Vector(0.2, 2.0), mass=5.0, radius=0.3, restitution=0.5))
    plank = world.add(Body(Vector(11.0, 0.0), mass=1.0, shape=Polygon.box(2.0, 0.2)))
    hinge = world.add_link(Pin(plank, (10.0, 0.0), anchor_a=(-1.0, 0.0)))
    worst = 0.0
    hit = False
    for _ in range(300):
        world.step(DT)
        hit = hit or ball.pos.x > 0.3
        worst = max(worst, abs(plank.local_to_world(Vector(-1.0, 0.0)) - Vector(10.0, 0.0)))
        # The pin holds its body still: struck by a ball five times its mass, it never moves.
        assert post.pos == Vector(0.0, 0.0) and post.vel == Vector(0.0, 0.0)
    assert hit and ball.pos.y < -4.0  # the ball glanced off the post and fell to the floor
    # The anchored pin is a hinge to the world: the plank swings about its end, which stays
    # within the joint's give of the point (0.57 mm, measured); it carries the plank's weight.
    assert worst < 1e-3
    assert plank.angle < -0.5
    assert hinge.impulse > 0.0


def rope_bridge(kernels: str) -> tuple[World, list[Rod], Body]:
    """Twelve planks linked end to end by rods between two fixed points 6 m apart (the
    platformer's rope bridge), and a crate dropped on its middle."""
    world = soft(kernels)
    count, span = 12, 6.0
    step = span / count
    planks = [
        world.add(Body(Vector(-span / 2 + step * (k + 0.5), 0.0), mass=0.5,
                       shape=Polygon.box(0.8 * step, 0.08)))
        for k in range(count)
    ]  # fmt: skip
    gap = 0.1 * step
    rods = [world.add_link(Rod(planks[0], (-span / 2, 0.0), anchor_a=(-0.4 * step, 0.0)))]
    for a, b in zip(planks, planks[1:], strict=False):
        rods.append(
            world.add_link(
                Rod(a, b, gap * 2, anchor_a=(0.4 * step, 0.0), anchor_b=(-0.4 * step, 0.0))
            )
        )
    rods.append(world.add_link(Rod(planks[-1], (span / 2, 0.0), anchor_a=(0.4 * step, 0.0))))
    crate = world.add(Body(Vector(0.1, 1.5), mass=2.0, shape=Polygon.box(0.6, 0.6), friction=0.8))
    return world, rods, crate


@pytest.mark.parametrize("kernels", PATHS)
def test_a_rope_bridge_of_rods_holds_a_crate(kernels: str) -> None:
    world, rods, crate = rope_bridge(kernels)
    worst = 0.0
    for step in range(240):
        world.step(DT)
        for rod in rods:
            worst = max(worst, abs(abs(rod.end_a() - rod.end_b()) - rod.length))
        if step > 30:
            # Landed at 5.4 m/s, the crate rides the bridge as it swings (0.1 m up and down),
            # on it all the while: above the planks' line, within the span, upright.
            assert -0.2 < crate.pos.y < 0.4 and abs(crate.pos.x) < 1.0
            assert abs(crate.angle) < 0.3
    # Every rod holds its length within the joints' give: 11 mm at the crate's landing, the
    # most (measured; the chain's pull is large for its sag, and a soft row gives with it).
    assert worst < 0.02


@FAST
def test_both_paths_give_the_same_rope_bridge() -> None:
    ends = []
    for kernels in ("numpy", "fast"):
        world, rods, crate = rope_bridge(kernels)
        for _ in range(120):
            world.step(DT)
        ends.append(
            [
                (b.pos.x, b.pos.y, b.angle, b.vel.x, b.vel.y, b.angular_velocity)
                for b in world.bodies
            ]
            + [rod.impulse for rod in rods]
        )
    assert ends[0] == ends[1]


# -- springs: forces given once a substep (engine.dynamics.solver's SPRING and ROTARY_SPRING) ------


def spring_world(kernels: str) -> World:
    world = World(kernels=kernels, solver="soft")
    world.sleep_time = math.inf  # (a slow last swing would sleep, as Box2D's does)
    return world


@pytest.mark.parametrize("kernels", PATHS)
def test_a_mass_on_a_spring_oscillates_at_sqrt_k_over_m(kernels: str) -> None:
    world = spring_world(kernels)
    m, k, amplitude = 2.0, 50.0, 0.3
    bob = world.add(Body(Vector(1.0 + amplitude, 0.0), mass=m, radius=0.1))
    spring = world.add_link(DampedSpring(bob, world.static_body, (0, 0), (0, 0), 1.0, k, 0.0))
    omega = math.sqrt(k / m)
    e0 = 0.5 * k * amplitude**2
    worst_x = worst_e = 0.0
    for _ in range(600):
        world.step(DT)
        worst_x = max(worst_x, abs(bob.pos.x - (1.0 + amplitude * math.cos(omega * world.t))))
        worst_e = max(worst_e, abs(world.energy() - e0) / e0)
    # The stiffness is a kick a substep (symplectic Euler at h = 1/240 s, omega h = 0.02):
    # 3.4 mm off the closed form after 10 s (its phase); the energy read at the steps' ends
    # swings by omega h / 2 about its start (1.05% measured) and does not drift.
    assert worst_x < 5e-3
    assert worst_e < 1.5e-2
    assert bob.pos.y == 0.0 and spring.energy() >= 0.0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_damped_spring_decays_as_the_damped_oscillator(kernels: str) -> None:
    world = spring_world(kernels)
    m, k, c = 2.0, 50.0, 2.0
    bob = world.add(Body(Vector(1.3, 0.0), mass=m, radius=0.1))
    world.add_link(DampedSpring(bob, world.static_body, (0, 0), (0, 0), 1.0, k, c))
    gamma = c / (2 * m)
    wd = math.sqrt(k / m - gamma**2)
    worst = 0.0
    for _ in range(600):
        world.step(DT)
        t = world.t
        x = 1.0 + 0.3 * math.exp(-gamma * t) * (math.cos(wd * t) + gamma / wd * math.sin(wd * t))
        worst = max(worst, abs(bob.pos.x - x))
    assert worst < 3e-3  # m (2.3e-3: the kick, then the damper's exact decay, a substep)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_rotary_spring_turns_a_box_at_sqrt_k_over_i(kernels: str) -> None:
    world = spring_world(kernels)
    box = world.add(Body(Vector(0, 0), mass=1.0, shape=Polygon.box(1.0, 1.0), angle=0.2))
    spring = world.add_link(DampedRotarySpring(box, world.static_body, 0.0, 2.0, 0.0))
    omega = math.sqrt(2.0 / box.moment)
    worst = 0.0
    for _ in range(600):
        world.step(DT)
        worst = max(worst, abs(box.angle - 0.2 * math.cos(omega * world.t)))
    assert worst < 3e-3  # rad (1.5e-3 measured)
    # The spring's angular impulse on the box over a step is its change of spin.
    w0 = box.angular_velocity
    world.step(DT)
    assert spring.impulse == pytest.approx(box.moment * (box.angular_velocity - w0), rel=1e-9)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_crate_hanging_on_a_spring_rests_where_its_weight_stretches_it(kernels: str) -> None:
    world = soft(kernels)
    world.sleep_time = math.inf  # (asleep, it stops where it is slow: 0.37 mm short here)
    crate = world.add(Body(Vector(0.0, -1.0), mass=2.0, shape=Polygon.box(0.4, 0.4)))
    spring = world.add_link(
        DampedSpring(crate, world.static_body, (0.0, 0.2), (0.0, 0.0), 0.8, 400.0, 20.0)
    )
    for _ in range(300):
        world.step(DT)
    # k x = m g: the spring 0.8 + 2 g / 400 long, pulling by m g dt a step.
    assert abs(spring.end_a() - spring.end_b()) == pytest.approx(0.8 + 2.0 * G / 400.0, abs=1e-6)
    world.step(DT)
    assert spring.impulse == pytest.approx(2.0 * G * DT, rel=1e-6)


@FAST
def test_both_paths_give_the_same_springs() -> None:
    ends = []
    for kernels in ("numpy", "fast"):
        world = soft(kernels)
        a = world.add(Body(Vector(0.0, 0.0), mass=1.0, shape=Polygon.box(0.5, 0.5)))
        b = world.add(Body(Vector(1.5, 0.5), mass=2.0, shape=Polygon.box(0.5, 0.3), angle=0.3))
        world.add_link(DampedSpring(a, world.static_body, (0.2, 0.2), (0.0, 1.0), 0.5, 80, 1))
        world.add_link(DampedSpring(a, b, (0.25, 0.0), (-0.25, 0.0), 1.0, 40.0, 0.5))
        world.add_link(DampedRotarySpring(b, a, 0.0, 3.0, 0.1))
        for _ in range(120):
            world.step(DT)
        ends.append([(x.pos.x, x.pos.y, x.angle, x.vel.x, x.vel.y) for x in world.bodies])
    assert ends[0] == ends[1]


def test_a_spring_too_stiff_for_the_substeps_is_said_before_it_blows_up() -> None:
    # Kicked once a substep, a spring holds while omega h < 2 (h = dt / 4 by default): at
    # k = 1e6 N/m on 1 kg, omega = 1000 rad/s, omega h = 4.17. The warning names the dt and
    # the stiffness that would hold; at 10 substeps it holds.
    world = World(solver="soft")
    bob = world.add(Body(Vector(1.1, 0.0), mass=1.0, radius=0.1))
    world.add_link(DampedSpring(bob, world.static_body, (0, 0), (0, 0), 1.0, 1e5, 0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        world.step(DT)  # omega = 316 rad/s, omega h = 1.3: stable, no warning
    stiff = World(solver="soft")
    bob = stiff.add(Body(Vector(1.1, 0.0), mass=1.0, radius=0.1))
    stiff.add_link(DampedSpring(bob, stiff.static_body, (0, 0), (0, 0), 1.0, 1e6, 0.0))
    with pytest.warns(StabilityWarning, match=r"omega\*h=4\.167.*dt < 0\.008 s") as got:
        stiff.step(DT)
    assert got[0].filename == __file__  # said at the game's own call
    stiff = World(solver="soft")
    stiff.contact_iterations = 10  # h = dt / 10: omega h = 1.67
    bob = stiff.add(Body(Vector(1.1, 0.0), mass=1.0, radius=0.1))
    stiff.add_link(DampedSpring(bob, stiff.static_body, (0, 0), (0, 0), 1.0, 1e6, 0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for _ in range(60):
            stiff.step(DT)
    assert abs(bob.pos.x - 1.0) <= 0.1 + 1e-9  # held: it swings within its amplitude


@pytest.mark.parametrize("kernels", PATHS)
def test_a_joints_impulses_read_late_or_after_a_write_are_its_last_steps(kernels: str) -> None:
    # The soft step leaves each step's impulses pending until one is read or written
    # (engine.dynamics.reported). A hinge whose reports are read after every step and its twin
    # read only at the end report the same bits; a value written on a joint keeps the step's
    # others; the next step reports afresh.
    from engine import Hinge, MouseJoint

    def scene() -> tuple[World, Hinge, Rod, DampedSpring, MouseJoint]:
        world = soft(kernels)
        plank = world.add(Body(Vector(1.0, 0.0), shape=Polygon.box(2.0, 0.2), mass=3.0))
        bob = world.add(Body(Vector(2.0, -1.0), mass=1.0, radius=0.1))
        ball = world.add(Body(Vector(-2.0, 0.0), mass=1.0, radius=0.1))
        hinge = world.add_link(Hinge(plank, world.static_body, (0.0, 0.0), motor_speed=0.5,
                                     max_torque=4.0))  # fmt: skip
        rod = world.add_link(Rod(bob, plank, anchor_b=(1.0, 0.0)))
        spring = world.add_link(
            DampedSpring(ball, world.static_body, (0.0, 0.0), (-2.0, 1.0), 0.5, 40.0, 1.0)
        )
        mouse = world.add_link(MouseJoint(ball, (-1.5, 0.2), max_force=30.0))
        return world, hinge, rod, spring, mouse

    def values(h: Hinge, r: Rod, s: DampedSpring, m: MouseJoint) -> tuple[float, ...]:
        return (*h.linear_impulse, h.angular_impulse, h.motor_impulse, h.impulse, r.impulse,
                s.impulse, *m.impulse)  # fmt: skip

    eager, late = scene(), scene()
    seen = []
    for _ in range(30):
        eager[0].step(DT)
        late[0].step(DT)
        seen.append(values(*eager[1:]))
    assert values(*late[1:]) == seen[-1]
    assert len(set(seen[-3:])) == 3  # (each step reports its own)
    assert 0.0 < abs(seen[-1][3]) <= 4.0 * DT * (1 + 1e-12)  # the motor's bound held
    # A write first puts the pending step's values on every joint, then takes its own.
    late[0].step(DT)
    eager[0].step(DT)
    late[1].motor_impulse = 123.0
    assert values(*late[1:]) == (*values(*eager[1:])[:3], 123.0, *values(*eager[1:])[4:])
    late[0].step(DT)
    eager[0].step(DT)
    assert values(*late[1:])[3] == values(*eager[1:])[3] != 123.0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_joint_copied_or_pickled_before_its_impulses_are_read_has_the_steps(
    kernels: str,
) -> None:
    # A copy of a joint whose step's impulses are still pending takes them (a copy is no joint
    # of the step's, so it would never be filled); a pickle likewise carries the values, and
    # neither keeps the step's report as its own.
    import copy
    import pickle

    from engine import Hinge

    def stepped() -> Hinge:
        world = soft(kernels)
        plank = world.add(Body(Vector(1.0, 0.0), shape=Polygon.box(2.0, 0.2), mass=3.0))
        hinge = world.add_link(Hinge(plank, world.static_body, (0.0, 0.0)))
        for _ in range(10):
            world.step(DT)
        return hinge

    read = stepped()
    want = (read.linear_impulse, read.angular_impulse, read.impulse)
    assert want[0] != Vector(0.0, 0.0)  # (it holds the plank up: a push to compare)
    for make in (copy.copy, lambda j: pickle.loads(pickle.dumps(j))):
        twin = make(stepped())
        assert twin._pending is None
        assert (twin.linear_impulse, twin.angular_impulse, twin.impulse) == want
