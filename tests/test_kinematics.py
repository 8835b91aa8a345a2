"""engine.kinematics: the lesson's closed-form motion, and the numbers the lesson prints."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import Body, Vector, World
from engine.kinematics import position, stopping_distance, time_to_reach, velocity


def test_lessons_s_of_3_is_5() -> None:
    # s0 = 2, v = 1 in/s, no acceleration: s(3) = 1 * 3 + 2 = 5.
    assert position(2.0, 1.0, 0.0, 3.0) == 5.0
    assert time_to_reach(2.0, 1.0, 0.0, 5.0) == 3.0


def test_alfreds_sprint_takes_sqrt_20_seconds_in_closed_form() -> None:
    # From rest at 1 in/s^2: 10 = t^2 / 2  =>  t = sqrt(20) = 4.47 s (Euler with dt = 1 s says 4).
    t = time_to_reach(0.0, 0.0, 1.0, 10.0)
    assert t == pytest.approx(math.sqrt(20), rel=1e-15)
    assert position(0.0, 0.0, 1.0, t) == pytest.approx(10.0, rel=1e-15)
    assert [position(0.0, 0.0, 1.0, float(s)) for s in range(5)] == [0.0, 0.5, 2.0, 4.5, 8.0]


def walk(t: float) -> Vector:
    """The lesson's 2D stroll: x(t) = t^2 / 2, y(t) = 2 t - t^2."""
    return Vector(t * t / 2, 2 * t - t * t)


def test_the_2d_walk_has_velocity_1_0_at_t_1_by_numerical_differentiation() -> None:
    # Central differences are exact for a quadratic up to round-off.
    h = 1e-4
    v = (walk(1 + h) - walk(1 - h)) / (2 * h)
    assert v.x == pytest.approx(1.0, abs=1e-9) and v.y == pytest.approx(0.0, abs=1e-9)


def test_the_2d_walk_is_a_body_moved_by_the_exact_method() -> None:
    # s(t) = s0 + v0 t + a t^2/2 with s0 = 0, v0 = (0, 2), a = (1, -2) is the walk above.
    world = World(integrator="exact")
    alfred = world.add(Body(Vector(0, 0), Vector(0, 2), Vector(1, -2)))
    assert world.method == "exact"
    dt = 0.1
    for n in range(1, 31):
        world.step(dt)
        t = n * dt
        assert alfred.pos.x == pytest.approx(walk(t).x, rel=1e-14, abs=1e-14)
        assert alfred.pos.y == pytest.approx(walk(t).y, rel=1e-14, abs=1e-14)
        if n == 10:
            assert alfred.vel.x == pytest.approx(1.0, abs=1e-14)
            assert alfred.vel.y == pytest.approx(0.0, abs=1e-14)
            assert alfred.pos.distance_to((0.5, 1.0)) < 1e-14


def test_closed_form_works_on_floats_vectors_and_arrays() -> None:
    assert position(Vector(1, 1), Vector(0, 2), Vector(1, -2), 2.0) == Vector(3, 1)
    assert velocity(Vector(0, 2), Vector(1, -2), 1.0) == Vector(1, 0)
    s = position(np.array([0.0, 1.0]), np.array([1.0, 0.0]), np.array([2.0, -2.0]), 3.0)
    assert s.tolist() == [12.0, -8.0]
    assert velocity(np.array([1.0]), np.array([2.0]), 0.5).tolist() == [2.0]


@given(
    s0=st.floats(-100, 100),
    v0=st.floats(-50, 50),
    a=st.one_of(st.just(0.0), st.floats(0.01, 20), st.floats(-20, -0.01)),
    t=st.floats(0, 30),
)
def test_time_to_reach_lands_on_the_position_and_is_the_first_time(
    s0: float, v0: float, a: float, t: float
) -> None:
    target = position(s0, v0, a, t)
    found = time_to_reach(s0, v0, a, target)
    # The target is rounded, so the time that reaches it exactly can differ from t by the
    # rounding over the speed there, or by sqrt(2 rounding / |a|) at a turning point.
    scale = abs(s0) + abs(v0) * t + abs(a) * t * t + 1.0
    rounding = 1e-13 * scale
    speed = abs(velocity(v0, a, t))
    slack = min(
        rounding / speed if speed else math.inf,
        math.sqrt(2 * rounding / abs(a)) if a else math.inf,
    )
    assert found <= t + 10 * slack + 1e-12  # the first time: never later than a known one
    assert position(s0, v0, a, found) == pytest.approx(target, abs=1e-9 * scale)


def test_time_to_reach_is_infinite_when_never_reached() -> None:
    assert time_to_reach(0.0, 1.0, 0.0, -1.0) == math.inf  # moving away
    assert time_to_reach(0.0, 0.0, 0.0, 1.0) == math.inf  # lazy Alfred
    assert time_to_reach(0.0, 4.0, -2.0, 5.0) == math.inf  # turns back at s = 4
    assert time_to_reach(0.0, 4.0, -2.0, 4.0) == pytest.approx(2.0)  # just touches
    assert time_to_reach(0.0, 4.0, -2.0, -5.0) == pytest.approx(5.0)  # 4t - t^2 = -5, t > 0
    assert time_to_reach(3.0, 1.0, 1.0, 3.0) == 0.0


def test_time_to_reach_avoids_cancellation_for_a_tiny_acceleration() -> None:
    # a t^2/2 tiny against v0 t: the naive (-v0 + sqrt(v0^2 + 2 a d)) / a loses all digits.
    t = time_to_reach(0.0, 1.0, 1e-12, 1.0)
    assert t == pytest.approx(1.0 - 0.5e-12, rel=1e-15)


def test_stopping_distance() -> None:
    # v^2 = v0^2 - 2 a s with v = 0
    assert stopping_distance(4.0, 2.0) == 4.0
    assert time_to_reach(0.0, 4.0, -2.0, stopping_distance(4.0, 2.0)) == pytest.approx(2.0)
    with pytest.raises(ValueError, match="deceleration must be > 0"):
        stopping_distance(4.0, 0.0)
