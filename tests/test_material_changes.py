"""A body's or a collider's material set after it is made (pymunk's habit: ``body.friction =
0.2``, ``shape.sensor = True``) takes effect at the World's next step, on either path.

Checked against closed forms: a ball's bounce height follows the new restitution from its next
impact (h' = e^2 h, e the product of the body's and the floor's); a box on a slope of angle
theta holds while mu > tan(theta) and slides with a = g (sin(theta) - mu cos(theta)) from the
step after mu is set below it; a pair whose filter is set apart moves in free flight from the
next step; a collider made a sensor lets a body fall freely through it and reports it. A value
refused is refused as when made (its name, the value, what is valid) and leaves the old one.
"""

from __future__ import annotations

import copy
import math
import pickle
import warnings
from dataclasses import replace

import numpy as np
import pytest
from test_collider_changes import check

from engine import Body, Circle, Filter, Plane, Polygon, Segment, Vector, World
from engine.forces import Gravity

G = 9.81
DT = 1.0 / 60.0


def _dropped(e_body: float, e_floor: float = 1.0) -> tuple[World, Body, Plane]:
    """A ball of radius 0.1 whose bottom is 1 m above a floor at y = 0, at rest, under g."""
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    floor = w.add_collider(Plane((0.0, 0.0), (0.0, 1.0), restitution=e_floor))
    ball = w.add(Body(Vector(0.0, 1.1), radius=0.1, restitution=e_body))
    return w, ball, floor


def _apexes(w: World, ball: Body, bounces: int, between: object = None) -> list[float]:
    """The heights (m, the ball's bottom above the floor) of the apexes after each of the
    next ``bounces`` impacts, from the state in flight: y + vy^2 / (2 g), exact under the
    closed form. ``between(k)`` is called once the k-th apex is known."""
    out: list[float] = []
    for _ in range(100000):
        w.step(DT)
        if any(ev.body is ball for ev in w.began):
            # Risen a step after the bounce: its apex is known from its state now.
            w.step(DT)
            y, vy = ball.pos.y - 0.1, ball.vel.y
            assert vy > 0.0
            out.append(y + vy * vy / (2.0 * G))
            if callable(between):
                between(len(out))
            if len(out) == bounces:
                return out
    raise AssertionError("the ball stopped bouncing")


@pytest.mark.parametrize("on", ["body", "collider"])
def test_a_ball_bounces_to_the_new_restitution_from_its_next_impact(on: str) -> None:
    # e = 0.9 for two bounces, then 0.5 (set while it rises), then 0.8: each apex is e^2
    # times the one before, with the e of the impact that made it (the product of the two).
    w, ball, floor = _dropped(0.9)
    news = {2: 0.5, 3: 0.8}

    def between(k: int) -> None:
        if k in news:
            (ball if on == "body" else floor).restitution = news[k]
            if on == "collider":
                check(w)  # the faces are what building them afresh gives

    got = _apexes(w, ball, 4, between)
    # By impact, the body's e times the floor's.
    if on == "body":
        es = [0.9, 0.9, 0.5, 0.8]
    else:
        es = [0.9, 0.9, 0.9 * 0.5, 0.9 * 0.8]
    want, h = [], 1.0
    for e in es:
        h *= e * e
        want.append(h)
    assert got == pytest.approx(want, rel=1e-9)


def _slope(mu: float, theta: float) -> tuple[World, Body, Plane]:
    """A 1 m box on a plane tilted by ``theta`` (rad), at rest on it, friction ``mu``."""
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    n = (-math.sin(theta), math.cos(theta))
    slope = w.add_collider(Plane((0.0, 0.0), n))
    box = w.add(
        Body(Vector(0.5 * n[0], 0.5 * n[1]), shape=Polygon.box(1.0, 1.0), angle=theta, friction=mu)
    )
    return w, box, slope


def _along(box: Body, theta: float) -> tuple[float, float]:
    """The box's position and velocity down the slope (m, m/s)."""
    d = (-math.cos(theta), -math.sin(theta))
    return box.pos.x * d[0] + box.pos.y * d[1], box.vel.x * d[0] + box.vel.y * d[1]


@pytest.mark.parametrize("on", ["body", "collider"])
def test_a_box_on_a_slope_holds_or_slides_by_the_friction_set(on: str) -> None:
    theta = math.radians(30.0)  # tan(theta) = 0.577
    w, box, slope = _slope(0.8, theta)
    owner = box if on == "body" else slope
    for _ in range(120):  # 2 s: settled, and asleep
        w.step(DT)
    assert w.is_sleeping(box)  # (a friction set wakes it)
    s0, _ = _along(box, theta)
    for _ in range(60):
        w.step(DT)
    s1, v1 = _along(box, theta)
    assert abs(s1 - s0) < 1e-4 and abs(v1) < 1e-3  # mu 0.8 > tan(theta): it holds
    # mu 0.3 < tan(theta) (for the collider: 0.8 x 0.375): it slides from the next step, at
    # a = g (sin - mu cos).
    owner.friction = 0.3 if on == "body" else 0.375
    mu = 0.3
    a = G * (math.sin(theta) - mu * math.cos(theta))
    for _ in range(6):
        w.step(DT)
    sa, va = _along(box, theta)
    for _ in range(30):
        w.step(DT)
    sb, vb = _along(box, theta)
    assert va > 0.5 * a * 6 * DT
    assert (vb - va) / (30 * DT) == pytest.approx(a, rel=0.02)
    # Set back above tan(theta): it slows at g (mu cos - sin) and stops, and stays.
    owner.friction = 0.8 if on == "body" else 1.0
    stop = vb / (G * (0.8 * math.cos(theta) - math.sin(theta)))
    for _ in range(math.ceil(stop / DT) + 30):
        w.step(DT)
    s2, v2 = _along(box, theta)
    assert abs(v2) < 1e-3
    assert s2 - sb == pytest.approx(vb * stop / 2.0, rel=0.05, abs=0.01)


def test_two_balls_set_apart_by_their_filter_pass_through_each_other() -> None:
    w = World(integrator="auto")
    a = w.add(Body(Vector(-1.0, 0.0), Vector(2.0, 0.0), radius=0.25, restitution=1.0))
    b = w.add(Body(Vector(1.0, 0.0), Vector(-2.0, 0.0), radius=0.25, restitution=1.0))
    w.step(DT)
    a.filter = Filter(group=3)
    b.filter = Filter(group=3)
    for k in range(2, 61):
        w.step(DT)
        # Free flight: x = x0 + v t, to rounding.
        assert a.pos.x == pytest.approx(-1.0 + 2.0 * k * DT, abs=1e-12)
        assert b.pos.x == pytest.approx(1.0 - 2.0 * k * DT, abs=1e-12)
        assert not w.began
    # Together again: the next meeting bounces (equal masses swap velocities).
    a.filter = b.filter = Filter()
    a.vel, b.vel = Vector(-2.0, 0.0), Vector(2.0, 0.0)
    for _ in range(60):
        w.step(DT)
    assert a.vel.x > 0.0 and b.vel.x < 0.0


def test_a_floor_and_a_ball_set_apart_by_their_filters_let_it_fall_through() -> None:
    w, ball, floor = _dropped(0.0)
    for _ in range(90):
        w.step(DT)
    assert w.resting(ball) is floor
    ball.filter = Filter(categories=0b01)
    for _ in range(10):
        w.step(DT)
    assert w.resting(ball) is floor  # the floor still meets category 1
    floor.filter = Filter(categories=0b10, mask=0b10)
    check(w)
    y0 = ball.pos.y
    for k in range(1, 31):
        w.step(DT)
        assert ball.pos.y == pytest.approx(y0 - 0.5 * G * (k * DT) ** 2, abs=1e-12)


def test_a_collider_made_a_sensor_lets_a_body_through_and_reports_it() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    shelf = w.add_collider(Segment((-2.0, 1.0), (2.0, 1.0)))
    w.add_collider(Plane((0.0, -3.0), (0.0, 1.0)))
    ball = w.add(Body(Vector(0.0, 1.5), radius=0.1, restitution=0.0))
    for _ in range(90):
        w.step(DT)
    assert w.resting(ball) is shelf
    shelf.sensor = True
    check(w)
    assert w.resting(ball) is None
    began, ended, y0 = [], [], ball.pos.y
    for k in range(1, 21):
        w.step(DT)
        assert ball.pos.y == pytest.approx(y0 - 0.5 * G * (k * DT) ** 2, abs=1e-12)
        began += [(k, ev.body, ev.collider) for ev in w.began]
        ended += [(k, ev.body, ev.collider) for ev in w.ended]
    # The rest on the shelf ends at the first step, as the overlap of the sensor begins; the
    # overlap ends when the ball's top passes y = 1: y0 - g t^2 / 2 < 0.9.
    out = math.ceil(math.sqrt(2.0 * (y0 - 0.9) / G) / DT)
    assert began == [(1, ball, shelf)] and ended == [(1, ball, shelf), (out, ball, shelf)]
    # Solid again: the ball now on the floor below is not inside it; one dropped on it lands.
    shelf.sensor = False
    check(w)
    high = w.add(Body(Vector(1.0, 2.0), radius=0.1, restitution=0.0))
    for _ in range(90):
        w.step(DT)
    assert w.resting(high) is shelf and high.pos.y == pytest.approx(1.1, abs=1e-9)


def test_a_sensor_made_solid_pushes_out_the_body_inside_it() -> None:
    w = World(integrator="auto")
    coin = w.add_collider(Circle((0.0, 0.0), 0.5, sensor=True))
    ball = w.add(Body(Vector(0.2, 0.0), radius=0.1))
    w.step(DT)
    assert [ev.collider for ev in w.began] == [coin]
    with pytest.warns(Warning, match="pushed out"):
        coin.sensor = False
    assert abs(ball.pos) == pytest.approx(0.6, abs=1e-9)
    check(w)


def test_a_value_refused_says_what_is_valid_and_leaves_the_old_one() -> None:
    w = World()
    body = w.add(Body(Vector(0.0, 0.0), radius=0.5, restitution=0.25, friction=0.5))
    peg = w.add_collider(Circle((5.0, 0.0), 1.0, friction=0.7))
    cases = [
        (body, "restitution", 1.5, ValueError, r"restitution must be in \[0, 1\].*got 1\.5"),
        (body, "restitution", "high", TypeError, "restitution must be a real number"),
        (body, "friction", -0.1, ValueError, r"friction must be >= 0, got -0\.1"),
        (body, "friction", math.nan, ValueError, "friction must be finite, got nan"),
        (body, "filter", 3, TypeError, "filter must be an engine.Filter"),
        (peg, "restitution", -1, ValueError, r"restitution must be in \[0, 1\].*got -1"),
        (peg, "friction", math.inf, ValueError, "friction must be finite, got inf"),
        (peg, "sensor", 1, TypeError, "sensor must be True or False, got int 1"),
        (peg, "filter", None, TypeError, "filter must be an engine.Filter"),
    ]
    for thing, name, value, error, words in cases:
        before = getattr(thing, name)
        with pytest.raises(error, match=words):
            setattr(thing, name, value)
        assert getattr(thing, name) == before
    assert float(w._s.store.restitution[0]) == 0.25 and float(w._s.store.friction[0]) == 0.5
    check(w)
    # The geometry is still fixed, and says so.
    with pytest.raises(AttributeError, match="cannot change once it is made"):
        peg.radius = 2.0  # type: ignore[misc]


def test_a_collider_in_two_worlds_tells_both_and_a_copy_neither() -> None:
    peg = Circle((0.0, 0.0), 0.5)
    worlds = [World(integrator="auto") for _ in range(2)]
    balls = []
    for w in worlds:
        w.add_collider(peg)
        balls.append(w.add(Body(Vector(0.0, 0.8), Vector(0.0, -3.0), radius=0.1)))
    twin = copy.deepcopy(peg)
    again = pickle.loads(pickle.dumps(peg))
    peg.sensor = True
    for w in worlds:
        check(w)
        for _ in range(30):
            w.step(DT)
    assert all(b.pos.y < -0.5 for b in balls)  # through the peg in both
    assert not twin.sensor and not again.sensor
    twin.friction = 0.5  # held by no World
    worlds[1].remove_collider(peg)
    peg.friction = 0.25
    check(worlds[0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        peg.sensor = False  # no ball is inside it now
    check(worlds[0])


def test_a_snapshot_keeps_the_materials_and_a_restore_sets_them_back() -> None:
    w, ball, floor = _dropped(0.9)
    shelf = w.add_collider(Segment((-1.0, 0.5), (1.0, 0.5), sensor=True))
    other = w.add(Body(Vector(0.5, 2.0), radius=0.1, restitution=0.7, friction=0.1))
    for _ in range(20):
        w.step(DT)
    snap = w.snapshot()
    want = []
    for _ in range(90):
        w.step(DT)
        want.append((w.positions().copy(), w.velocities().copy()))
    w.restore(snap)
    ball.restitution, other.friction, other.filter = 0.2, 0.9, Filter(group=2)
    floor.restitution = 0.5
    with pytest.warns(Warning, match=r"was \(a sensor made solid\) inside Segment"):
        shelf.sensor = False  # the ball is in it
    for _ in range(30):
        w.step(DT)
    with pytest.raises(ValueError, match=r"snapshot.materials\[1\]: restitution must be in"):
        w.restore(replace(snap, materials=((0.9, 0.5, Filter()), (1.5, 0.1, Filter()))))
    assert (other.restitution, floor.restitution, shelf.sensor) == (0.7, 0.5, False)
    w.restore(snap)
    assert (ball.restitution, other.friction, other.filter) == (0.9, 0.1, Filter())
    assert (floor.restitution, shelf.sensor) == (1.0, True)
    check(w)
    for k in range(90):
        w.step(DT)
        assert np.array_equal(w.positions(), want[k][0]), k
        assert np.array_equal(w.velocities(), want[k][1]), k


def test_the_queries_see_a_filter_set_on_a_body_or_a_collider() -> None:
    w = World()
    ball = w.add(Body(Vector(0.0, 0.0), radius=0.5, filter=Filter(categories=0b01)))
    peg = w.add_collider(Circle((3.0, 0.0), 0.5, filter=Filter(categories=0b01)))
    seen = Filter(mask=0b10)  # a query that sees category 2 only
    for _ in range(2):  # (the second time from the tables the first query made)
        assert w.point_query((0.0, 0.0), 0.0, filter=seen) == []
        assert w.point_query((3.0, 0.0), 0.0, filter=seen) == []
    ball.filter = Filter(categories=0b10)
    peg.filter = Filter(categories=0b11)
    assert [hit.shape for hit in w.point_query((0.0, 0.0), 0.0, filter=seen)] == [ball]
    assert [hit.shape for hit in w.point_query((3.0, 0.0), 0.0, filter=seen)] == [peg]
