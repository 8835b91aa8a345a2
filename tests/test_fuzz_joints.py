"""Fuzzing joints (engine.dynamics.joints, engine.exact.joint_solver): anything a caller passes to a
Hinge or a Weld is a joint or a clear error naming the argument; any world of bodies that turn,
joined by hinges (with limits and motors), welds and anchored links, with a floor to land on, steps
without nan, holds every rigid joint to 1e-9 (unless it warned that a step was past what it
holds), keeps every hinge within its limits, and reruns bit for bit from a snapshot; and
balls thrown at a bat flipping on its motorized hinge never end a step inside it.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import (
    Body,
    Cable,
    Hinge,
    Pin,
    Polygon,
    Rod,
    Segment,
    StabilityWarning,
    Vector,
    Weld,
    World,
)
from engine.dynamics.solver import JOINT_HERTZ
from engine.forces import Gravity
from tests.fuzzing import anything, attempt, fuzz, numbers, pairs


def box(x: float = 0.0, y: float = 0.0) -> Body:
    return Body(Vector(x, y), shape=Polygon.box(1.0, 0.2))


seconds = st.one_of(st.just("b"), st.just("static"), st.just("a"), anything)


@fuzz(300)
@given(
    kind=st.sampled_from(["hinge", "weld"]),
    second=seconds,
    point=st.one_of(pairs, anything),
    limits=st.one_of(st.none(), st.tuples(numbers, numbers), anything),
    speed=st.one_of(st.none(), numbers, anything),
    torque=st.one_of(numbers, anything),
    hertz=st.one_of(st.none(), numbers, anything),
)
def test_any_joint_arguments_make_a_joint_or_a_clear_error(  # type: ignore[no-untyped-def]
    kind, second, point, limits, speed, torque, hertz
) -> None:
    world = World()
    a, b = box(0.0, 0.0), box(1.0, 0.0)
    other = (
        {"b": b, "static": world.static_body, "a": a}.get(second, second)
        if isinstance(second, str)
        else second
    )
    if kind == "hinge":
        ok, joint = attempt(
            lambda: Hinge(a, other, point, limits=limits, motor_speed=speed, max_torque=torque),
            "body_b", "point", "limits", "motor_speed", "max_torque",
        )  # fmt: skip
    else:
        ok, joint = attempt(lambda: Weld(a, other, hertz=hertz), "body_b", "hertz")
    if ok:
        assert joint is not None and joint.body_a is a and joint.body_b is not a
        assert joint.angle == 0.0
        if isinstance(joint, Hinge):
            assert joint.point == Vector(*point)  # type: ignore[misc]
            assert joint.limits is None or joint.limits[0] <= joint.limits[1]
            assert joint.max_torque >= 0.0


@st.composite
def jointed_worlds(draw: st.DrawFn) -> tuple[World, list[Body], list[object], float]:
    # The exact models, asked for (joints held to 1e-9: World() would take the soft step
    # for a box that a contact could push).
    world = World(
        integrator=draw(st.sampled_from(["auto", "semi_implicit_euler", "velocity_verlet"])),
        solver="exact",
    )
    world.add_force(Gravity((0.0, -9.81)))
    if draw(st.booleans()):
        world.add_collider(Segment((-20.0, -6.0), (20.0, -6.0)))
    n = draw(st.integers(1, 6))
    bodies = []
    for _ in range(n):
        pos = Vector(draw(st.floats(-4, 4)), draw(st.floats(-4, 4)))
        vel = Vector(draw(st.floats(-5, 5)), draw(st.floats(-5, 5)))
        mass = draw(st.floats(0.05, 20.0))
        spin = draw(st.floats(-10, 10))
        shape = draw(st.sampled_from(["box", "disc", "point"]))
        if shape == "box":
            size = (draw(st.floats(0.2, 2)), draw(st.floats(0.05, 1)))
            made = Body(pos, vel, shape=Polygon.box(*size), mass=mass, angular_velocity=spin)
        elif shape == "disc":
            made = Body(
                pos, vel, radius=draw(st.floats(0.1, 0.6)), mass=mass, angular_velocity=spin
            )
        else:
            made = Body(pos, vel, mass=mass, moment=mass * draw(st.floats(0.01, 1.0)))
        bodies.append(made)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # bodies that start overlapping
        world.add_all(bodies)
    joints: list[object] = []
    for _ in range(draw(st.integers(1, 6))):
        i, j = draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1))
        a = bodies[i]
        b = bodies[j] if i != j else world.static_body
        kind = draw(
            st.sampled_from(["hinge", "limited", "motor", "weld", "soft", "rod", "cable", "pin"])
        )
        point = (draw(st.floats(-4, 4)), draw(st.floats(-4, 4)))
        anchor = (draw(st.floats(-0.5, 0.5)), draw(st.floats(-0.5, 0.5)))
        lo = draw(st.floats(-2, 0))
        hi = draw(st.floats(0, 2))
        made: object
        if kind in ("hinge", "limited", "motor"):
            made = Hinge(a, b, point,
                         limits=(lo, hi) if kind == "limited" else None,
                         motor_speed=draw(st.floats(-10, 10)) if kind == "motor" else None,
                         max_torque=draw(st.floats(0, 100)))  # fmt: skip
        elif kind in ("weld", "soft"):
            made = Weld(a, b, hertz=draw(st.floats(0.5, 10)) if kind == "soft" else None)
        elif kind == "pin":
            made = Pin(a, point, anchor_a=anchor)
        else:
            other = b if isinstance(b, Body) else point
            anchor_b = anchor if isinstance(b, Body) else None
            try:
                made = (
                    Rod(a, other, anchor_a=anchor, anchor_b=anchor_b)
                    if kind == "rod"
                    else Cable(
                        a, other, draw(st.floats(0.5, 5)), anchor_a=anchor, anchor_b=anchor_b
                    )
                )
            except ValueError:
                continue  # the anchors at one point: a rod of length 0 (an error, tested)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ok, joint = attempt(lambda: world.add_link(made), "pinned", "kinematic")  # noqa: B023
        if ok:
            joints.append(joint)
    return world, bodies, joints, draw(st.sampled_from([1 / 60, 1 / 240]))


def gap(joint: object) -> float:
    """How far a rigid joint is from holding (length units, or rad for a weld's angle)."""
    if isinstance(joint, Hinge):
        return (joint.end_a() - joint.end_b()).length()
    if isinstance(joint, Weld):
        return max((joint.end_a() - joint.end_b()).length(), abs(joint.angle))
    if isinstance(joint, Rod):
        return abs((joint.end_a() - joint.end_b()).length() - joint.length)
    if isinstance(joint, Pin):
        return (joint.end_a() - joint.point).length()
    return 0.0


@fuzz(25)
@given(scene=jointed_worlds())
def test_jointed_worlds_step_finite_hold_their_joints_and_rerun_bit_for_bit(scene) -> None:  # type: ignore[no-untyped-def]
    world, bodies, joints, dt = scene
    snap = world.snapshot()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for _ in range(40):
            world.step(dt)
    x = world.positions().copy()
    assert np.isfinite(x).all() and np.isfinite(world.velocities()).all()
    warned = any(issubclass(w.category, StabilityWarning) for w in caught)
    if not warned:
        # Joints that can all hold at once hold (two welds or a weld and a hinge to the
        # world on one body ask the same; contradictory ones, such as two pins of one body
        # at different points, cannot, and are left out by asking for an overconstrained
        # set only through welds and hinges to one point).
        size = max(1.0, max(abs(c) for b in bodies for c in b.pos))
        for joint in joints:
            if isinstance(joint, Weld) and joint.hertz is not None:
                continue
            if consistent(joints):
                assert gap(joint) <= 1e-9 * size, joint
        for joint in joints:
            if isinstance(joint, Hinge) and joint.limits is not None and consistent(joints):
                lo, hi = joint.limits
                assert lo - 1e-6 <= joint.angle <= hi + 1e-6
    world.restore(snap)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(40):
            world.step(dt)
    assert np.array_equal(world.positions(), x)


def test_a_box_welded_to_the_world_stays_on_its_weld_beside_a_pinned_box_in_it() -> None:
    # The shrunk find (find 17, exploring at 1,500 examples): two unit boxes at one place, one
    # welded to the world, the other pinned at its centre (neither can move out of the other).
    # The pairs push the welded box out of the other; the joints' solve puts it back and lets
    # the contact give, and its last projection (what friction moved put back onto the joints)
    # took the contact in again and split the overlap with the weld: the box ended 0.666 m
    # off its weld, with no warning. The fuzz test's rule: each joint holds to 1e-9, or the
    # World warns that it cannot.
    world = World(solver="exact")
    world.add_force(Gravity((0.0, -9.81)))
    square = Polygon([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)])
    pinned = world.add(Body(Vector(-2.0, 0.0), mass=1.0, shape=square))
    welded = world.add(Body(Vector(-2.0, 0.0), mass=1.0, shape=square))
    world.add_link(Weld(welded, world.static_body))
    world.add_link(Pin(pinned, Vector(-2.0, 0.0)))
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        for _ in range(3):
            world.step(1 / 60)
    warned = any(issubclass(w.category, StabilityWarning) for w in said)
    assert warned or (welded.pos - Vector(-2.0, 0.0)).length() <= 1e-9
    assert warned or abs(welded.angle) <= 1e-9
    assert warned or (pinned.pos - Vector(-2.0, 0.0)).length() <= 1e-9


def consistent(joints: list[object]) -> bool:
    """Whether the joints can all hold at once: each body in at most one joint (a tree of
    joints can always hold; loops of joints made at random points often cannot)."""
    seen: set[int] = set()
    for joint in joints:
        ends = [joint.body] + ([joint.other] if isinstance(joint.other, Body) else [])  # type: ignore[attr-defined]
        for body in ends:
            if id(body) in seen:
                return False
            seen.add(id(body))
    return True


_ = math


@st.composite
def bats_and_balls(draw: st.DrawFn) -> tuple[World, Body, Hinge, list[Body], float, int]:
    """A bat (a tapered polygon or a capsule) of random length, thickness and mass on a hinge
    at its root, with limits and a motor of random speed and torque, and a few balls of random
    size thrown at it from random sides at up to 40 (length units)/s, under gravity; when the
    key is pressed (the step) and dt."""
    length = draw(st.floats(2.0, 10.0))
    root = draw(st.floats(0.3, 1.5))
    tip = draw(st.floats(0.15, 1.0)) * root
    shape: Polygon | Segment
    if draw(st.booleans()):
        shape = Polygon([(0.0, -root), (length, -tip), (length, tip), (0.0, root)])
    else:  # a capsule (a Segment with a radius)
        shape = Segment((0.0, 0.0), (length, 0.0), radius=root)
        tip = root
    # The exact models, asked for: the bat meets each ball at its moment.
    world = World(integrator="auto", solver="exact")
    world.add_force(Gravity((0.0, -draw(st.floats(0.0, 20.0)))))
    bat = world.add(Body(Vector(0.0, 0.0), shape=shape, mass=draw(st.floats(0.05, 5.0)),
                         restitution=draw(st.floats(0.0, 1.0)),
                         friction=draw(st.floats(0.0, 1.0))))  # fmt: skip
    swing = draw(st.floats(0.2, 1.5))
    speed = draw(st.floats(5.0, 60.0))
    hinge = world.add_link(
        Hinge(bat, world.static_body, (0.0, 0.0), limits=(0.0, swing), motor_speed=-speed,
              max_torque=draw(st.floats(1.0, 1e3)) * bat.moment)
    )  # fmt: skip
    balls = []
    for k in range(draw(st.integers(1, 3))):
        r = draw(st.floats(0.1, 1.0))
        aim = draw(st.floats(0.1, 1.0)) * length
        side = draw(st.sampled_from([1.0, -1.0]))
        toward = draw(st.floats(-1.2, 1.2)) + (-math.pi / 2 if side > 0 else math.pi / 2)
        v = draw(st.floats(1.0, 40.0))
        start = Vector(aim, side * (root + r + 3.0 * k + draw(st.floats(0.05, 15.0))))
        # None starts inside another: one drawn onto an earlier ball is put just beyond it
        # on its side (found exploring, find 18: two balls drawn at one point, which the
        # World can only part in a direction it picks, and says so).
        moved = True
        while moved:
            moved = False
            for other in balls:
                if (start - other.pos).length() < r + other.radius + 0.05:
                    top = abs(other.pos.y) + other.radius + r + 0.05
                    start = Vector(aim, side * max(top, abs(start.y)))
                    moved = True
        vel = Vector(math.cos(toward), math.sin(toward)) * v
        balls.append(world.add(Body(start, vel, radius=r, mass=draw(st.floats(0.01, 2.0)),
                                    restitution=draw(st.floats(0.0, 1.0)),
                                    friction=draw(st.floats(0.0, 1.0)))))  # fmt: skip
    key = draw(st.integers(0, 30))
    dt = draw(st.sampled_from([1 / 60, 1 / 120, 1 / 240]))
    return world, bat, hinge, balls, dt, key


def inside(bat: Body, ball: Body) -> float:
    """How deep the ball's centre is inside the bat (> 0 inside; length units)."""
    p = bat.world_to_local(ball.pos)
    if isinstance(bat.shape, Segment):
        a, b = Vector(*bat.shape.a), Vector(*bat.shape.b)
        u = min(max((p - a).dot(b - a) / (b - a).dot(b - a), 0.0), 1.0)
        return bat.shape.radius - (p - (a + (b - a) * u)).length()
    vs = list(bat.shape.vertices)  # type: ignore[union-attr]
    depth = math.inf
    for a, b in zip(vs, vs[1:] + vs[:1], strict=True):
        edge = b - a
        out = Vector(edge.y, -edge.x).normalize()  # counter-clockwise: outward on the right
        depth = min(depth, -(p - a).dot(out))
    return depth


@fuzz(40)
@given(scene=bats_and_balls())
def test_no_ball_ends_a_step_inside_a_flipping_bat(scene) -> None:  # type: ignore[no-untyped-def]
    # The joints' solve turns the bat far within a step (knocked onto its stop, or swung at
    # full torque); a ball's row is its distance from the bat wherever it turns, from the
    # side it came in by (engine.exact.joint_contacts), so none ends a step inside the bat.
    flip_the_bat(scene)


def two_balls_on_a_flipping_bat() -> tuple[World, Body, Hinge, list[Body], float, int]:
    """Found by the fuzz exploring (fast path, 1,000 examples a test): a capsule bat of 3.5 m
    (radius 0.80 m, 1.36 kg) on a hinge at its end, limits 0 to 0.73 rad, its motor at -5
    rad/s reversed at step 6; no gravity, no restitution; a 2 kg ball of 0.57 m drifting onto
    it and a 0.5 kg ball of 0.25 m falling onto that one at 19 m/s."""
    world = World(integrator="auto", solver="exact")
    world.add_force(Gravity((0.0, -0.0)))
    bat = world.add(Body(Vector(0.0, 0.0), shape=Segment((0.0, 0.0), (3.5, 0.0),
                                                         radius=0.8007130488109113),
                         mass=1.3573817785595834, restitution=0.0,
                         friction=0.9182274791370173))  # fmt: skip
    hinge = world.add_link(
        Hinge(bat, world.static_body, (0.0, 0.0), limits=(0.0, 0.7294304980436703),
              motor_speed=-5.0, max_torque=1518.811690036856)
    )  # fmt: skip
    balls = [
        world.add(Body(Vector(2.1875, 3.3701743004562745),
                       Vector(0.8414709848078965, -0.5403023058681397), radius=0.5694612516453632,
                       mass=2.0, restitution=0.0, friction=1.0)),
        world.add(Body(Vector(3.171875, 5.050713048810911), Vector(1.1634144591899855e-15, -19.0),
                       radius=0.25, mass=0.5, restitution=0.0, friction=1.0)),
    ]  # fmt: skip
    return world, bat, hinge, balls, 1.0 / 60.0, 6


def test_two_balls_on_a_flipping_bat_stay_apart() -> None:
    # Found exploring (find 16): the ball on the bat was pushed 7 cm (27% of its radius) into
    # the one above it, and the World warned, for the joints' solve was handed the rows that
    # touch the bat alone (engine.exact.pile.pushed_on now hands it the rows of the bodies
    # the bat pushes on too, within PUSHED_ON_ROWS).
    scene = two_balls_on_a_flipping_bat()
    balls = scene[3]
    deepest = flip_the_bat(scene, lambda: ball_overlap(balls))
    assert deepest <= 0.01 * balls[1].radius  # 0.5 mm here (0.2%); 68 mm before


def flip_the_bat(
    scene: tuple[World, Body, Hinge, list[Body], float, int],
    overlap: Callable[[], float] = lambda: 0.0,
) -> float:
    """60 steps of a bat scene (``bats_and_balls``), its motor reversed at step ``key``: no
    ball ends a step inside the bat, no StabilityWarning, the hinge within its limits.
    Returns the greatest ``overlap()`` at a step's end."""
    world, bat, hinge, balls, dt, key = scene
    deepest = -math.inf
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        for k in range(60):
            if k == key:
                hinge.motor_speed = -hinge.motor_speed  # the key: it swings up
            world.step(dt)
            for ball in balls:
                assert inside(bat, ball) <= 1e-6 * ball.radius, (k, ball)
            deepest = max(deepest, overlap())
    assert np.isfinite(world.positions()).all() and np.isfinite(world.velocities()).all()
    lo, hi = hinge.limits  # type: ignore[misc]
    assert lo - 1e-6 <= hinge.angle <= hi + 1e-6
    return deepest


def struck_on_a_swinging_bat(iterations: int) -> tuple[World, Body, Hinge, list[Body]]:
    """Found exploring test_no_ball_ends_a_step_inside_a_flipping_bat (2,000 examples, fast
    path, 2026-12-05; numpy alike): a 7.6 m capsule bat (4.8 kg) swung up at 5 rad/s from
    the first step carries a 0.038 kg ball resting on it up into a 0.44 kg ball falling
    at 30 m/s; no gravity, no friction. The exact models, ``iterations`` contact iterations."""
    world = World(integrator="auto", solver="exact")
    world.contact_iterations = iterations
    world.add_force(Gravity((0.0, -0.0)))
    half = 3.803637326375178
    bat = world.add(Body(Vector(half, 0.0), shape=Segment((-half, 0.0), (half, 0.0),
                                                          radius=1.4529193854893967),
                         mass=4.806904589206616, restitution=0.0, friction=0.0))  # fmt: skip
    hinge = world.add_link(Hinge(bat, world.static_body, (0.0, 0.0), limits=(0.0, 0.5),
                                 motor_speed=5.0, max_torque=607.7155898200972))  # fmt: skip
    balls = [
        world.add(Body(Vector(x, y), Vector(vx, vy), mass=m, radius=r, restitution=e,
                       friction=0.0))
        for x, y, vx, vy, m, r, e in [
            (6.950574519538851, 2.152985611891479, 8.605510297321135e-16, -14.05386484219389,
             0.03792158054968278, 0.6500662264020824, 0.0),
            (4.068984483160669, 14.211904675118756, -12.365907842344075, -4.807612325793443,
             1.2636536591096534, 0.9702483064888192, 0.6737627640433806),
            (3.5487930773884777, 18.398134759946892, 2.2761794520383652e-15,
             -37.172831442063625, 0.44390917345532, 0.1, 0.9474696616119986),
        ]
    ]  # fmt: skip
    return world, bat, hinge, balls


def ball_overlap(balls: list[Body]) -> float:
    """The deepest overlap of two of ``balls`` (length units; <= 0: none)."""
    return max(
        a.radius + b.radius - (a.pos - b.pos).length()
        for i, a in enumerate(balls)
        for b in balls[i + 1 :]
    )


def test_a_light_ball_on_a_swinging_bat_struck_by_a_heavy_one_at_4_iterations() -> None:
    # At step 24 the light ball, carried up at 15 m/s, meets the heavy one coming down at
    # 30 m/s: the three are one pile of the soft step (the heavy ball reaches it within the
    # step). The joints' solve, holding the light ball on the bat, once pushed it 0.095 m (95%
    # of the heavy ball's radius) into the heavy one at 4 contact iterations, which the World
    # warned of: it was handed the light ball's rows with the bat alone. Handed the pile's
    # rows that the bat reaches through the light ball (engine.exact.pile.pushed_on), it moves
    # the heavy ball too: under 0.1% of its radius at 4 iterations as at 8, and no warning.
    for iterations in (4, 8):
        world, bat, hinge, balls = struck_on_a_swinging_bat(iterations)
        worst, warned = -math.inf, 0
        for _ in range(60):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", StabilityWarning)
                world.step(1 / 60)
            warned += sum(issubclass(w.category, StabilityWarning) for w in caught)
            worst = max(worst, ball_overlap(balls))
            assert all(inside(bat, ball) + ball.radius <= 1e-6 for ball in balls)
        assert worst <= 1e-4 and warned == 0, (iterations, worst, warned)


# At 32 contact iterations the bodies end apart, yet the World warned that they overlapped
# by 0.0499 m (50% of the smallest radius): it took the pile's shape rows' separation
# (linearised about the step's start while the bat turns, and before the joints' solve holds
# the ball on the bat exactly) for the end overlap. It measures the shapes where they ended
# now, after the joints' solve (engine.exact.collisions, ``ended_overlap``).
def test_a_light_ball_on_a_swinging_bat_is_warned_of_no_overlap_it_does_not_have() -> None:
    world, bat, hinge, balls = struck_on_a_swinging_bat(32)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        for _ in range(60):
            world.step(1 / 60)
            assert ball_overlap(balls) <= 1e-4
            assert all(inside(bat, ball) + ball.radius <= 1e-6 for ball in balls)


def stalled_past_the_limit(hinge: Hinge, bat: Body, torque: float) -> float:
    """How far past its limit the soft step holds a hinge whose motor pushes into it with all
    of ``torque`` (N m): the limit row is Box2D's soft joint, a spring of JOINT_HERTZ (60 Hz at
    dt 1/60, 4 substeps) on the bat's turn about its centre of mass, so it gives
    T / (omega^2 I_cm), omega = 2 pi 60. Box2D v3 (3.2.0, its own test program, float) holds
    the 9.8 m bat below 0.0019210577 rad past, ours 0.0019210714 (the closed form to 1e-12)."""
    omega = 2.0 * math.pi * JOINT_HERTZ
    return torque / (omega * omega * bat.moment)


@pytest.mark.parametrize("solver", ["exact", "soft"])
def test_a_ball_on_a_capsule_bat_flipped_at_the_first_step_stays_out_of_it(solver: str) -> None:
    # Found exploring test_no_ball_ends_a_step_inside_a_flipping_bat (300 examples, when the
    # World chose the exact models for it): a 1 m ball 1 m above the middle of a 10 m capsule
    # bat, falling at 1 m/s, no gravity, no restitution or friction, as the bat's motor flips
    # to +16 rad/s at the first step (it swings up into the ball): the World warned that
    # bodies overlapped by 1.77 m. Both solvers keep the ball out of the bat; the exact models
    # hold the limit to 1e-6 rad, the soft step as Box2D does, past it by its joint spring's
    # give under the stalled motor (``stalled_past_the_limit``).
    world = World(integrator="auto", solver=solver)
    world.add_force(Gravity((0.0, -0.0)))
    capsule = Segment((0.0, 0.0), (9.993077081392435, 0.0), radius=0.3212416030394271)
    bat = world.add(Body(Vector(0.0, 0.0), shape=capsule, mass=3.576488370951384,
                         restitution=0.0, friction=0.0))  # fmt: skip
    swing, speed, torque = 0.7286793563850764, -15.95475708320602, 51965.92865071327
    hinge = world.add_link(Hinge(bat, world.static_body, (0.0, 0.0), limits=(0.0, swing),
                                 motor_speed=speed, max_torque=torque))  # fmt: skip
    ball = world.add(Body(Vector(4.996538540696218, 2.321241603039427), Vector(0.0, -1.0),
                          radius=1.0, mass=1.0, restitution=0.0, friction=0.0))  # fmt: skip
    if solver == "exact":
        scene = (world, bat, hinge, [ball], 1 / 60, 0)
        fuzzed = test_no_ball_ends_a_step_inside_a_flipping_bat.hypothesis  # type: ignore[attr-defined]
        fuzzed.inner_test(scene)
        return
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        hinge.motor_speed = -speed
        for _ in range(60):
            world.step(1 / 60)
            assert inside(bat, ball) <= 1e-6 * ball.radius
    past = hinge.angle - swing
    assert past == pytest.approx(stalled_past_the_limit(hinge, bat, torque), rel=1e-9)
    assert abs(bat.angular_velocity) < 1e-9


def swung_bat(solver: str) -> tuple[World, Body, Hinge, Body]:
    """A 9.8 m capsule bat on a hinge at its root, limits (0, 1) rad, its motor at 9 rad/s
    from the first step, and a 0.25 m ball falling onto its middle at 1 m/s, on ``solver``:
    (world, bat, hinge, ball)."""
    world = World(integrator="auto", solver=solver)
    capsule = Segment((0.0, 0.0), (9.803110278350163, 0.0), radius=0.5)
    bat = world.add(Body(Vector(0.0, 0.0), shape=capsule, mass=3.6386623031139185,
                         restitution=0.0, friction=0.0))  # fmt: skip
    hinge = world.add_link(Hinge(bat, world.static_body, (0.0, 0.0), limits=(0.0, 1.0),
                                 motor_speed=9.0, max_torque=9375.402248987055))  # fmt: skip
    ball = world.add(Body(Vector(4.901555139175081, 1.75), Vector(0.0, -1.0), radius=0.25,
                          mass=1.0, restitution=0.0, friction=0.0))  # fmt: skip
    return world, bat, hinge, ball


@pytest.mark.parametrize(
    "solver",
    [
        # Found exploring (--hypothesis-profile=explore): once the bat reached its motor speed
        # with the ball on it (step 9), bat and ball froze in mid-swing, their velocities
        # saying 9 rad/s and 58 m/s. The ball slides out along the bat as it turns, and the
        # pile's rows, linear in the step, left it 7.7 cm into the bat: retaken from its
        # moment of impact, the step's start (they touched), it ended as deep, and was put
        # back where it began, every step. That fallback is for impacts within the step.
        "exact",
        "soft",
    ],
)
def test_a_ball_on_a_bat_swung_up_by_its_motor_flies_off_and_the_bat_reaches_its_limit(
    solver: str,
) -> None:
    # The shrunk example of test_no_ball_ends_a_step_inside_a_flipping_bat that exploring finds
    # at once: a 9.8 m capsule bat on a hinge at its root, limits (0, 1) rad, its motor turned
    # up at 9 rad/s as the first step begins; a 0.25 m ball falls onto its middle at 1 m/s.
    # No gravity, no restitution, no friction: the bat throws the ball, then stops at 1 rad.
    world, bat, hinge, ball = swung_bat(solver)
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        for _ in range(10):
            world.step(1 / 60)
        thrown = ball.pos
        for _ in range(50):
            world.step(1 / 60)
            assert inside(bat, ball) <= 1e-6 * ball.radius
    # The motor drove it onto its limit: held there to 1e-6 rad by the exact models, as
    # Box2D holds it by the soft step.
    past = 0.0 if solver == "exact" else stalled_past_the_limit(hinge, bat, 9375.402248987055)
    assert hinge.angle - 1.0 == pytest.approx(past, abs=1e-6 if solver == "exact" else 1e-12)
    assert (ball.pos - thrown).length() > 5.0  # 50 steps at tens of m/s in free space
    told = [str(w.message) for w in said if issubclass(w.category, StabilityWarning)]
    if solver == "exact":
        assert not told
    else:
        # The soft step lets the ball sink into the bat swinging up at 9 rad/s (its centre
        # stays out of the bat's core: above), 7.8 cm at step 9, 31% of its radius, and the
        # World says so then, once (engine.pipeline.stepping's ``SOFT_GIVE``; the ball
        # goes 9.9 cm in at worst: the strict xfail below).
        assert len(told) == 1 and "raise world.contact_iterations" in told[0], told


@pytest.mark.xfail(
    strict=True,
    reason="the soft step's limit: a ball on a bat swung up by its motor at 9 rad/s sinks "
    "9.9 cm into it (40% of its radius; 5.3 cm with 8 substeps, 3.0 with 16, 1.8 with 32: "
    "its soft contact gives under the load that throws it), where the exact models hold it "
    "out; the World warns of it (the test above)",
)
def test_on_the_soft_step_a_ball_on_a_bat_swung_up_by_its_motor_stays_out_of_it() -> None:
    world = swung_bat("soft")[0]
    deepest = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(60):
            world.step(1 / 60)
            deepest = max(deepest, world.overlap())
    assert deepest <= 0.05 * 0.25  # the exact models' told overlap: 5% of the radius
