"""Contacts between bodies (engine.exact.collisions), checked against the closed-form collision.

Two discs that meet with unit normal n (from b to a) and closing speed u = -(v_a - v_b).n
leave with v_a' = v_a + J n / m_a and v_b' = v_b - J n / m_b, J = (1 + e) u / (1/m_a + 1/m_b):
momentum is conserved exactly, and with e = 1 kinetic energy too. Newton's cradle is the test
of order; a stack on a floor the test of rest; filters and points the test of who collides.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import Body, Box, ContactEvent, Filter, Plane, Rod, Vector, World
from engine.exact.collisions import SLOP
from engine.forces import Gravity
from engine.pipeline.stepping import AGAIN
from engine.stability import StabilityWarning

G = 9.81


def disc(world: World, pos: tuple[float, float], vel: tuple[float, float], **kw: object) -> Body:
    return world.add(Body(Vector(*pos), Vector(*vel), Vector(0.0, 0.0), **kw))  # type: ignore[arg-type]


def expected(
    xa: np.ndarray,
    va: np.ndarray,
    ma: float,
    xb: np.ndarray,
    vb: np.ndarray,
    mb: float,
    R: float,
    e: float,
) -> tuple[float, np.ndarray, np.ndarray]:
    """(time of impact, v_a', v_b') of two discs on straight paths, in closed form."""
    d, w = xa - xb, va - vb
    # |d + w t| = R: the smaller root of |w|^2 t^2 + 2 d.w t + |d|^2 - R^2 = 0.
    A, B, C = w @ w, 2 * d @ w, d @ d - R * R
    t = (-B - math.sqrt(B * B - 4 * A * C)) / (2 * A)
    n = (d + w * t) / R
    u = -(w @ n)
    J = (1 + e) * u / (1 / ma + 1 / mb)
    return t, va + J * n / ma, vb - J * n / mb


@settings(max_examples=60, deadline=None)
@given(
    angle=st.floats(-1.2, 1.2),
    ratio=st.floats(-3.0, 3.0),
    e=st.sampled_from([1.0, 0.8, 0.5, 0.0]),
    speed=st.floats(0.5, 50.0),
)
def test_two_discs_leave_as_the_closed_form_says(
    angle: float, ratio: float, e: float, speed: float
) -> None:
    w = World(integrator="auto")
    ma, mb = 1.0, 10.0**ratio
    ra, rb = 0.5, 0.3
    xa, va = np.array([0.0, 0.0]), np.array([speed, 0.0])
    # b sits ahead, offset sideways so the blow is oblique (|offset| < ra + rb).
    xb = np.array([3.0, (ra + rb) * math.sin(angle)])
    vb = np.array([-0.3 * speed, 0.0])
    a = disc(w, tuple(xa), tuple(va), mass=ma, radius=ra, restitution=e, friction=0.0)
    b = disc(w, tuple(xb), tuple(vb), mass=mb, radius=rb, restitution=1.0, friction=0.0)
    t_hit, va_want, vb_want = expected(xa, va, ma, xb, vb, mb, ra + rb, e)
    p0 = ma * va + mb * vb
    dt = 1 / 60
    for _ in range(int(t_hit / dt) + 3):
        w.step(dt)
    va1, vb1 = np.array(a.vel), np.array(b.vel)
    scale = speed * (ma + mb)
    assert np.abs(ma * va1 + mb * vb1 - p0).max() <= 1e-12 * scale
    assert np.abs(va1 - va_want).max() <= 1e-9 * speed * (1 + mb / ma)
    assert np.abs(vb1 - vb_want).max() <= 1e-9 * speed * (1 + ma / mb)
    if e == 1.0:
        E0 = 0.5 * (ma * va @ va + mb * vb @ vb)
        E1 = 0.5 * (ma * va1 @ va1 + mb * vb1 @ vb1)
        assert abs(E1 - E0) <= 1e-9 * E0
    # And each is where its new straight path from the moment of impact puts it.
    t_end = w.t
    xa_want = xa + va * t_hit + va_want * (t_end - t_hit)
    assert np.abs(np.array(a.pos) - xa_want).max() <= 1e-9 * (1 + speed * t_end)


@pytest.mark.parametrize("floor", [False, True])
def test_newtons_cradle_passes_the_speed_down_the_row(floor: bool) -> None:
    w = World(integrator="auto")
    if floor:
        # Lying on a frictionless line under gravity.
        w.add_force(Gravity((0.0, -G)))
        w.add_collider(Plane((0.0, -0.5), (0.0, 1.0), friction=0.0))
    balls = [
        disc(w, (float(k), 0.0), (0.0, 0.0), radius=0.5, restitution=1.0, friction=0.0)
        for k in range(5)
    ]
    balls[0].pos = Vector(-0.7, 0.0)
    balls[0].vel = Vector(2.0, 0.0)
    for _ in range(60):
        w.step(1 / 60)
    v = [b.vel for b in balls]
    assert abs(v[4].x - 2.0) <= 1e-6
    for b in v[:4]:
        assert abs(b.x) <= 1e-6 and abs(b.y) <= 1e-6
    assert abs(v[4].y) <= 1e-6


def test_points_never_collide_and_a_filter_turns_pairs_off() -> None:
    w = World()
    p = disc(w, (0.0, 0.0), (1.0, 0.0))  # radius 0: a point
    q = disc(w, (0.5, 0.0), (-1.0, 0.0))
    g1 = disc(w, (0.0, 5.0), (1.0, 0.0), radius=0.5, filter=Filter(group=3))
    g2 = disc(w, (1.5, 5.0), (-1.0, 0.0), radius=0.5, filter=Filter(group=3))
    m1 = disc(w, (0.0, 10.0), (1.0, 0.0), radius=0.5, filter=Filter(categories=1, mask=1))
    m2 = disc(w, (1.5, 10.0), (-1.0, 0.0), radius=0.5, filter=Filter(categories=2, mask=2))
    # (restitution 1: they bounce apart, so that a collision shows in their velocities)
    c1 = disc(w, (0.0, 15.0), (1.0, 0.0), radius=0.5, filter=Filter(categories=1, mask=2),
              restitution=1.0)  # fmt: skip
    c2 = disc(w, (1.5, 15.0), (-1.0, 0.0), radius=0.5, filter=Filter(categories=2, mask=1),
              restitution=1.0)  # fmt: skip
    for _ in range(90):
        w.step(1 / 60)
    for body, vx in ((p, 1.0), (q, -1.0), (g1, 1.0), (g2, -1.0), (m1, 1.0), (m2, -1.0)):
        assert body.vel.x == vx  # untouched, bit for bit
    assert c1.vel.x < 0.0 < c2.vel.x  # categories that meet each other's masks collide


def test_filter_errors_name_the_argument() -> None:
    with pytest.raises(ValueError, match="group"):
        Filter(group=-1)
    with pytest.raises(TypeError, match="mask"):
        Filter(mask=1.5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="categories"):
        Filter(categories=1 << 40)
    with pytest.raises(TypeError, match="filter"):
        Body(Vector(0, 0), Vector(0, 0), Vector(0, 0), filter=3)  # type: ignore[arg-type]


def test_an_impact_is_an_event_of_both_bodies() -> None:
    w = World()
    a = disc(w, (0.0, 0.0), (4.0, 0.0), radius=0.5, restitution=1.0, friction=0.0)
    b = disc(w, (3.0, 0.0), (0.0, 0.0), radius=0.5, restitution=1.0, friction=0.0)
    seen: list[ContactEvent] = []
    w.on_contact(b, begin=seen.append)
    hits: list[ContactEvent] = []
    for _ in range(60):
        w.step(1 / 60)
        hits += w.began
    # The handler on b sees the same contact from b's side (b is its body).
    assert len(hits) == 1 and len(seen) == 1 and seen[0].body is b
    assert seen == [e if e.body is b else e.flipped() for e in hits]
    ev = hits[0]
    assert {ev.body, ev.collider} == {a, b}
    assert abs(ev.time - 0.5) <= 1e-12  # 2 m of gap at 4 m/s
    # The impulse on ev.body is its change of momentum: 4 kg m/s along the line.
    assert abs(abs(ev.impulse.x) - 4.0) <= 1e-12 and ev.impulse.y == 0.0
    assert abs(ev.point.x - 2.5) <= 1e-12  # where they touch: a at x = 2, b at x = 3


@pytest.mark.parametrize("height", [2, 5, 10])
def test_a_stack_on_a_floor_comes_to_rest_and_sleeps(height: int) -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    r = 0.5
    stack = [disc(w, (0.0, r + 1.05 * k), (0.0, 0.0), radius=r) for k in range(height)]
    for _ in range(600):
        w.step(1 / 60)
    y = np.array([b.pos.y for b in stack])
    gaps = np.diff(y) - 2 * r
    assert gaps.min() >= -0.01 * r  # overlap at most 1% of the radius
    assert gaps.max() <= SLOP * r  # and touching, within the solver's slop: nobody floats
    assert all(b.vel.x == 0.0 and b.vel.y == 0.0 for b in stack)  # asleep: exactly still
    before = [b.pos for b in stack]
    for _ in range(600):
        w.step(1 / 60)
    assert [b.pos for b in stack] == before  # no creep, no jitter


def test_a_sleeping_stack_wakes_when_struck() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    stack = [disc(w, (0.0, 0.5 + 1.0 * k), (0.0, 0.0), radius=0.5) for k in range(3)]
    for _ in range(300):
        w.step(1 / 60)
    assert w.sleeping == 3
    disc(w, (-5.0, 2.5), (10.0, 0.0), radius=0.5, restitution=1.0)
    for _ in range(60):
        w.step(1 / 60)
    # The striker, falling on its way, meets the middle ball: knocked out from under the top
    # one, which falls (they turn: the top ball no longer rolls off sideways as a block did).
    assert stack[1].pos.x > 1.0 and stack[2].pos.y < 2.0
    assert not any(w.is_sleeping(b) for b in stack)


def test_snapshot_restore_replays_collisions_bit_for_bit() -> None:
    def build() -> World:
        w = World(integrator="auto")
        w.add_force(Gravity((0.0, -G)))
        w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
        rng = np.random.default_rng(3)
        for k in range(30):
            disc(w, (float(k % 6), 0.5 + 1.1 * (k // 6)), tuple(rng.uniform(-1, 1, 2)), radius=0.5)
        return w

    w = build()
    for _ in range(50):
        w.step(1 / 60)
    snap = w.snapshot()
    for _ in range(50):
        w.step(1 / 60)
    want = w.positions().copy()
    w.restore(snap)
    for _ in range(50):
        w.step(1 / 60)
    assert np.array_equal(w.positions(), want)


def test_a_pile_past_the_solver_is_warned_about() -> None:
    # 200 balls poured into a box 12 m wide with one iteration a step: the side-by-side
    # contacts, which only the iterations hold, give way.
    w = World(integrator="auto")
    w.contact_iterations = 1
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Box((0.0, 0.0), (12.0, 1000.0)))
    for k in range(200):
        x = 1.0 + (k % 10) + 0.5 * ((k // 10) % 2)
        disc(w, (x, 1.0 + 1.1 * (k // 10)), (0.0, 0.0), radius=0.5)
    with pytest.warns(StabilityWarning, match="contact_iterations"):
        for _ in range(150):
            w.step(1 / 60)
    with pytest.raises(ValueError, match="contact_iterations"):
        w.contact_iterations = 0


def test_a_pile_sinking_on_is_told_again_only_as_it_sinks_deeper() -> None:
    # A 10 kg disc on a 0.1 kg one on the floor, one contact iteration a step: the pair sinks
    # into each other step by step. The World says so when it first passes 5% of the smaller
    # radius, and again only where it is AGAIN times as deep as it last said, so a pile that
    # sinks on is told of each fourfold and one that stays is not told every step.
    w = World(solver="exact")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    disc(w, (0.0, 0.1), (0.0, 0.0), radius=0.1, mass=0.1)
    disc(w, (0.0, 0.4), (0.0, 0.0), radius=0.2, mass=10.0)
    w.contact_iterations = 1
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for _ in range(240):
            w.step(1 / 60)
    said = [str(c.message) for c in caught if issubclass(c.category, StabilityWarning)]
    assert said and all("raise world.contact_iterations" in m for m in said), said
    told = [float(m.split("overlap by ")[1].split(" ")[0]) for m in said]
    assert len(told) >= 2, said
    assert 0.05 * 0.1 <= told[0] < AGAIN * 0.05 * 0.1, said  # (first past 5% of 0.1 m)
    assert all(b >= AGAIN * a for a, b in zip(told, told[1:], strict=False)), said


def test_a_pyramid_stands_for_ten_thousand_steps() -> None:
    """The pile's solver holds weight: a pyramid of discs that do not turn stands. (Discs that
    turn roll apart, in this engine as in pymunk 7: its 21-ball pyramid of circles spreads 83 m
    in 2,000 steps with friction 1.0, measured; a pyramid of cylinders on a floor needs
    friction at every contact, and no rolling resistance holds it.)"""
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    r, rows = 0.5, 6
    balls = []
    for row in range(rows):  # 6, 5, ..., 1 balls, each resting in the pocket of two below
        for k in range(rows - row):
            x = (k + 0.5 * row) * 2 * r
            y = r + row * 2 * r * math.sqrt(3) / 2
            balls.append(disc(w, (x, y), (0.0, 0.0), radius=r, friction=0.5, fixed_rotation=True))
    start = np.array([b.pos for b in balls])
    for _ in range(10_000):
        w.step(1 / 60)
    end = np.array([b.pos for b in balls])
    assert np.abs(end - start).max() <= 0.01 * r  # standing, not sagging or sliding apart
    assert w.overlap() <= 0.01 * r
    assert w.sleeping == len(balls)


def test_a_ball_held_on_a_floor_sleeps_and_a_frictionless_glide_does_not() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0), friction=1.0))
    held = disc(w, (0.0, 0.5), (0.0, 0.0), radius=0.5, friction=0.5)
    puck = disc(w, (5.0, 0.5), (0.05, 0.0), radius=0.5, friction=0.0)
    other = disc(w, (50.0, 0.5), (0.0, 0.0), radius=0.5)  # two bodies that may collide
    for _ in range(120):
        w.step(1 / 60)
    assert w.is_sleeping(held) and w.is_sleeping(other)
    assert not w.is_sleeping(puck)
    assert abs(puck.vel.x - 0.05) <= 1e-12  # gliding on at its speed


def test_no_ball_leaves_a_pit_in_a_hundred_thousand_steps() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Box((0.0, 0.0), (12.0, 1000.0)))
    for k in range(300):
        x = 1.0 + (k % 10) + 0.5 * ((k // 10) % 2)
        disc(w, (x, 1.0 + 1.1 * (k // 10)), (0.0, 0.0), radius=0.5, restitution=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(100_000):
            w.step(1 / 60)
    x = w.positions()
    assert (x[:, 0] >= 0.5 - 1e-9).all() and (x[:, 0] <= 11.5 + 1e-9).all()
    assert (x[:, 1] >= 0.5 - 1e-9).all()
    assert w.overlap() <= 0.01 * 0.5
    assert w.sleeping == 300
    v = w.velocities()
    assert float((v * v).sum()) == 0.0  # asleep: no jitter, no creep


@pytest.mark.parametrize("gap", [0.0, 0.01, 0.05, 0.5])
def test_a_ball_struck_into_a_wall_bounces_back_at_once(gap: float) -> None:
    # e = 1, no friction: b is sent into the wall, bounces, and hands its speed back to a.
    w = World(integrator="auto")
    w.add_collider(Plane((0.5 + gap, 0.0), (-1.0, 0.0)))
    b = disc(w, (0.0, 0.0), (0.0, 0.0), radius=0.5, restitution=1.0, friction=0.0)
    a = disc(w, (-1.5, 0.0), (2.0, 0.0), radius=0.5, restitution=1.0, friction=0.0)
    for _ in range(90):
        w.step(1 / 60)
    assert abs(a.vel.x + 2.0) <= 1e-9 and abs(b.vel.x) <= 1e-9


@pytest.mark.parametrize("speed", [2.0, 5.0, 20.0])
def test_a_ball_dropped_on_a_resting_ball_keeps_the_energy(speed: float) -> None:
    # e = 1 everywhere: the lower ball is struck into the floor and bounces within the step.
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    lo = disc(w, (0.0, 0.5), (0.0, 0.0), radius=0.5, restitution=1.0, friction=0.0)
    hi = disc(w, (0.0, 1.6), (0.0, -speed), radius=0.5, restitution=1.0, friction=0.0)

    def energy() -> float:
        return sum(0.5 * b.vel.dot(b.vel) + G * b.pos.y for b in (lo, hi))

    e0 = energy()
    hits: list[ContactEvent] = []
    for _ in range(20):
        w.step(1 / 60)
        hits += w.began
    assert abs(energy() - e0) <= 1e-9 * e0
    assert any(isinstance(ev.collider, Plane) and ev.body is lo for ev in hits)


def test_bodies_placed_on_one_another_are_pushed_apart() -> None:
    w = World()
    a = disc(w, (1.0, 2.0), (0.0, 0.0), radius=0.5)
    b = disc(w, (1.0, 2.0), (0.0, 0.0), radius=0.5)  # the very same place
    c = disc(w, (1.3, 2.0), (0.0, 0.0), radius=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(60):
            w.step(1 / 60)
    assert w.overlap() <= 2 * SLOP * 0.5
    momentum = a.vel + b.vel + c.vel
    assert abs(momentum.x) <= 1e-12 and abs(momentum.y) <= 1e-12  # only positions were moved


def test_sleep_can_be_turned_off() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    stack = [disc(w, (0.0, 0.5 + 1.0 * k), (0.0, 0.0), radius=0.5) for k in range(3)]
    for _ in range(120):
        w.step(1 / 60)
    assert w.sleeping == 3
    w.sleep_time = math.inf  # everyone wakes, and no one sleeps again
    for _ in range(120):
        w.step(1 / 60)
    assert w.sleeping == 0 and w.overlap() <= 0.01 * 0.5
    assert all(abs(b.vel.y) <= 1e-6 for b in stack)  # awake, and still at rest
    for bad in (-1.0, float("nan"), "1"):
        with pytest.raises(ValueError, match="sleep_time"):
            w.sleep_time = bad  # type: ignore[assignment]


def test_adding_a_body_leaves_the_others_as_they_were() -> None:
    """A ball added far from a pile (a game spawning one) changes nothing for the pile: a
    settling pile keeps the contact impulses it carries from step to step, so it moves as
    in a World without the new ball (to rounding), and a sleeping one stays asleep, bit for
    bit where it was. (Every add used to wake the World and drop those impulses.)"""

    def pyramid() -> tuple[World, list[Body]]:
        w = World(integrator="auto")
        w.add_force(Gravity((0.0, -G)))
        w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
        r, rows = 0.5, 5
        balls = [  # discs that do not turn: a pyramid of discs that turn rolls apart
            disc(
                w,
                ((k + 0.5 * row) * 2 * r, r + row * r * math.sqrt(3)),
                (0.0, 0.0),
                radius=r,
                fixed_rotation=True,
            )
            for row in range(rows)
            for k in range(rows - row)
        ]
        return w, balls

    spawned, balls = pyramid()
    alone, twins = pyramid()
    for _ in range(20):  # settling: awake, its impulses carried from step to step
        spawned.step(1 / 60)
        alone.step(1 / 60)
    assert spawned.sleeping == 0
    disc(spawned, (40.0, 3.0), (0.0, 0.0), radius=0.5)  # falls onto the floor, far away
    for _ in range(200):
        spawned.step(1 / 60)
        alone.step(1 / 60)
        x = np.array([b.pos for b in balls])
        assert np.abs(x - np.array([b.pos for b in twins])).max() <= 1e-12
    assert spawned.sleeping == len(balls) + 1  # the pyramid and the new ball on the floor
    still = np.array([b.pos for b in balls])
    disc(spawned, (-40.0, 3.0), (0.0, 0.0), radius=0.5)
    for _ in range(60):
        spawned.step(1 / 60)
        assert all(spawned.is_sleeping(b) for b in balls)
    assert np.array_equal(np.array([b.pos for b in balls]), still)


@pytest.mark.parametrize("apart", [(1e-200, 0.0), (0.0, 1e-200), (1e-170, 1e-170), (1e-310, 0.0)])
@pytest.mark.parametrize("va", [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0)])
def test_discs_whose_centres_nearly_coincide_part_without_nan(apart, va) -> None:
    # The normal d / |d| of centres 1e-200 apart divided by a norm that squared to 0.
    w = World()
    w.add_collider(Plane((0.0, -0.5), (0.0, 1.0)))
    a = disc(w, (0.0, 0.0), va, radius=0.5)
    b = disc(w, apart, (1.0, 0.0), radius=0.5)
    for _ in range(5):
        w.step(1 / 60)
    state = np.concatenate([w.positions(), w.velocities()])
    assert np.isfinite(state).all()
    assert (a.pos - b.pos).magnitude() > 0.99  # parted, from 1e-200 to nearly touching


def test_two_bodies_landing_on_a_wall_in_one_step_beside_a_link() -> None:
    # With a link in the World, contacts that began in the same step on the few-bodies path
    # (rows held as a tuple) raised "too many indices for array".
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    a = disc(w, (0.0, 0.6), (0.0, -3.0), radius=0.5, restitution=0.0)
    b = disc(w, (3.0, 0.6), (0.0, -3.0), radius=0.5, restitution=0.0)
    c = disc(w, (6.0, 5.0), (0.0, 0.0), radius=0.5)
    w.add_link(Rod(c, (6.0, 7.0)))
    for _ in range(10):
        w.step(1 / 60)
    assert a.pos.y == pytest.approx(0.5) and b.pos.y == pytest.approx(0.5)


@pytest.mark.parametrize("e", [1.0, 0.5, 0.0])
def test_a_light_body_of_a_pile_struck_by_a_heavy_one_leaves_as_it_would_alone(e: float) -> None:
    # Two 1 g discs stacked on a frictionless floor (a pile: the lower carries the upper); a
    # 1,000 kg disc slides in at 30 m/s, a bullet to the pile, and strikes the lower one head
    # on. Alone, the struck disc would leave at (1 + e^2) m_a v / (m_a + m_b) (e^2: the pair's
    # restitution); as the pile's "moving wall" it took the impulse of an immovable wall,
    # (1 + e^2) m_a v, and left at 1e6 times that. Now it leaves as it would alone, the
    # momentum along the floor is kept to rounding, and the energy does not grow (to the
    # 1e-8 that the pile's kick, given from the step's start, moves the upper disc's height).
    w = World()
    w.add_force(Gravity(Vector(0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0), friction=0.0, restitution=0.0))
    kw = {"radius": 0.1, "friction": 0.0, "restitution": e}
    ma, mb, v = 1e3, 1e-3, 30.0
    light = disc(w, (0.0, 0.1), (0.0, 0.0), mass=mb, **kw)
    disc(w, (0.0, 0.3), (0.0, 0.0), mass=mb, **kw)
    disc(w, (-2.0, 0.1), (v, 0.0), mass=ma, **kw)

    def energy() -> float:
        return sum(b.mass * (0.5 * (b.vel.x**2 + b.vel.y**2) + G * b.pos.y) for b in w.bodies)

    alone = (1.0 + e * e) * ma * v / (ma + mb)
    E0 = energy()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(6):
            w.step(1.0 / 60.0)
            assert energy() <= E0 * (1.0 + 1e-8)
            assert math.hypot(light.vel.x, light.vel.y) <= alone * (1.0 + 1e-3)
    assert light.vel.x == pytest.approx(alone, rel=1e-3)
    px = sum(b.mass * b.vel.x for b in w.bodies)
    assert px == pytest.approx(ma * v, rel=1e-12)
