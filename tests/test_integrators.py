"""engine.integrators: one signature for floats, Vectors and arrays; orders and exact errors."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import Vector
from engine.integrators import (
    INTEGRATORS,
    explicit_euler,
    get_integrator,
    rk4,
    semi_implicit_euler,
    velocity_verlet,
)

NAMES = list(INTEGRATORS)


def run(step, x, v, accel, dt, n):  # type: ignore[no-untyped-def]
    """n steps of dt from t = 0, time counted as i * dt."""
    for i in range(n):
        x, v = step(x, v, accel, i * dt, dt)
    return x, v


def constant(a):  # type: ignore[no-untyped-def]
    return lambda t, x, v: a


def oscillator(t, x, v):  # type: ignore[no-untyped-def]
    """x'' = -x (omega = 1): written once, it works on floats, Vectors and arrays alike."""
    return x * -1.0


# -- the lesson's numbers ----------------------------------------------------------------------


def test_alfreds_sprint_under_semi_implicit_euler_is_0_1_3_6_10() -> None:
    # a = 1 in/s^2, dt = 1 s, from rest at the left end of the 10-inch tube.
    x, v = 0.0, 0.0
    seen = [x]
    for i in range(4):
        x, v = semi_implicit_euler(x, v, constant(1.0), float(i), 1.0)
        seen.append(x)
    assert seen == [0.0, 1.0, 3.0, 6.0, 10.0]
    assert v == 4.0  # at the end of the tube at t = 4 s (the truth is sqrt(20) s)


def test_alfreds_sprint_under_explicit_euler_lags_one_step() -> None:
    x, v = 0.0, 0.0
    seen = [x]
    for i in range(5):
        x, v = explicit_euler(x, v, constant(1.0), float(i), 1.0)
        seen.append(x)
    assert seen == [0.0, 0.0, 1.0, 3.0, 6.0, 10.0]


# -- constant acceleration: the exact error of each method -------------------------------------


@pytest.mark.parametrize(
    ("a", "h", "n"), [(1.0, 1.0, 10), (-9.75, 0.25, 40), (3.5, 0.0625, 160), (2.0, 0.5, 7)]
)
def test_constant_acceleration_errors_are_exactly_a_t_h_over_2(a: float, h: float, n: int) -> None:
    # With dyadic a and h every operation below is exact in binary floating point, so
    # the theorems hold with ==:  explicit Euler x_n = a h^2 n(n-1)/2 = a T^2/2 - a T h/2,
    # semi-implicit Euler x_n = a h^2 n(n+1)/2 = a T^2/2 + a T h/2.
    T = n * h
    truth = a * T * T / 2
    x_ee, v_ee = run(explicit_euler, 0.0, 0.0, constant(a), h, n)
    x_si, v_si = run(semi_implicit_euler, 0.0, 0.0, constant(a), h, n)
    assert x_ee - truth == -a * T * h / 2
    assert x_si - truth == +a * T * h / 2
    assert v_ee == v_si == a * T  # velocities are exact for both


@settings(max_examples=40, deadline=None)
@given(
    a=st.floats(-20, 20).filter(lambda a: abs(a) > 1e-3),
    h=st.floats(1e-3, 0.5),
    n=st.integers(1, 200),
    x0=st.floats(-10, 10),
    v0=st.floats(-10, 10),
)
def test_constant_acceleration_errors_hold_for_any_a_and_step(
    a: float, h: float, n: int, x0: float, v0: float
) -> None:
    T = n * h
    truth = x0 + v0 * T + a * T * T / 2
    scale = abs(x0) + abs(v0) * T + abs(a) * T * T + abs(a * T * h)
    tol = 1e-12 * scale * n
    x_ee, _ = run(explicit_euler, x0, v0, constant(a), h, n)
    x_si, _ = run(semi_implicit_euler, x0, v0, constant(a), h, n)
    assert x_ee - truth == pytest.approx(-a * T * h / 2, abs=tol)
    assert x_si - truth == pytest.approx(+a * T * h / 2, abs=tol)
    for exact_method in (velocity_verlet, rk4):
        x, v = run(exact_method, x0, v0, constant(a), h, n)
        assert x == pytest.approx(truth, abs=tol), exact_method.__name__
        assert v == pytest.approx(v0 + a * T, abs=1e-12 * (abs(v0) + abs(a) * T) * n)


def test_verlet_and_rk4_are_exact_under_constant_acceleration_in_2d() -> None:
    # Dyadic numbers again: no rounding anywhere, so equality is exact.
    a, v0, h, n = Vector(0.5, -9.75), Vector(3, 4), 0.125, 64
    T = n * h
    truth_x, truth_v = v0 * T + a * (T * T / 2), v0 + a * T
    for method in (velocity_verlet, rk4):
        x, v = run(method, Vector(0, 0), v0, constant(a), h, n)
        assert (x, v) == (truth_x, truth_v), method.__name__


# -- orders of accuracy, measured --------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "order", "steps"),
    [
        ("explicit_euler", 1, [50, 100, 200, 400, 800]),
        ("semi_implicit_euler", 1, [50, 100, 200, 400, 800]),
        ("velocity_verlet", 2, [20, 40, 80, 160, 320]),
        ("rk4", 4, [10, 20, 40, 80, 160]),
    ],
)
def test_order_of_accuracy_on_the_oscillator(name: str, order: int, steps: list[int]) -> None:
    # x'' = -x from (1, 0) over T = 1: the truth is (cos t, -sin t). Fit log(error)
    # against log(dt) over halvings of dt; the slope is the global order. The step
    # ranges keep every error well above round-off (RK4's smallest is ~1e-11).
    step = get_integrator(name)
    T = 1.0
    dts, errors = [], []
    for n in steps:
        dt = T / n
        x, v = run(step, 1.0, 0.0, oscillator, dt, n)
        dts.append(dt)
        errors.append(math.hypot(x - math.cos(T), v + math.sin(T)))
    slope = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert abs(slope - order) < 0.1, (name, slope)
    assert step.order == order


# -- one function, any state -------------------------------------------------------------------


def damped_oscillator(t, x, v):  # type: ignore[no-untyped-def]
    # Written with only * by a float and - between states, in the same order for every
    # type, so a float, a Vector component and an array element see the same operations.
    return x * -4.0 - v * 0.3


@pytest.mark.parametrize("name", NAMES)
def test_same_answer_on_a_float_a_vector_and_an_array(name: str) -> None:
    # Bit-identical, not merely close: every integrator is a fixed sequence of IEEE
    # operations (+, -, * by a float), each correctly rounded, and Vector and numpy
    # apply exactly the same operation to each component / element in the same order
    # (numpy's element-wise ufuncs do not fuse multiply-add or reassociate). So the
    # three representations must agree to the last bit; any difference means one of
    # them computes something else.
    step = get_integrator(name)
    dt, n = 0.01, 500
    x1, v1 = run(step, 1.25, -0.5, damped_oscillator, dt, n)
    xv, vv = run(step, Vector(1.25, 0.7), Vector(-0.5, 2.0), damped_oscillator, dt, n)
    xa, va = run(step, np.array([1.25]), np.array([-0.5]), damped_oscillator, dt, n)
    assert type(xv) is Vector and isinstance(xa, np.ndarray)
    assert xv.x == x1 and vv.x == v1
    assert xa[0] == x1 and va[0] == v1
    # and the 2D array of the same 2D body matches the Vector run
    x2, v2 = run(step, np.array([[1.25, 0.7]]), np.array([[-0.5, 2.0]]), damped_oscillator, dt, n)
    assert tuple(x2[0]) == tuple(xv) and tuple(v2[0]) == tuple(vv)


@pytest.mark.parametrize("name", NAMES)
def test_many_bodies_in_one_array_match_each_body_stepped_alone(name: str) -> None:
    step = get_integrator(name)
    rng = np.random.default_rng(7)
    x0, v0 = rng.normal(size=(6, 2)), rng.normal(size=(6, 2))
    xs, vs = run(step, x0.copy(), v0.copy(), damped_oscillator, 0.02, 200)
    for i in range(6):
        x, v = run(step, Vector(*x0[i]), Vector(*v0[i]), damped_oscillator, 0.02, 200)
        assert tuple(xs[i]) == tuple(x) and tuple(vs[i]) == tuple(v)  # bit-identical, as above


@pytest.mark.parametrize("name", NAMES)
def test_integrators_never_modify_their_inputs(name: str) -> None:
    step = get_integrator(name)
    x, v = np.array([[1.0, 2.0]]), np.array([[0.5, -0.5]])
    x_new, v_new = step(x, v, damped_oscillator, 0.0, 0.1)
    assert x.tolist() == [[1.0, 2.0]] and v.tolist() == [[0.5, -0.5]]
    assert x_new is not x and v_new is not v


@pytest.mark.parametrize("name", NAMES)
def test_time_handed_to_accel_lies_within_the_step(name: str) -> None:
    seen: list[float] = []

    def accel(t, x, v):  # type: ignore[no-untyped-def]
        seen.append(t)
        return 0.0

    get_integrator(name)(0.0, 0.0, accel, 2.0, 0.5)
    assert len(seen) == INTEGRATORS[name].evaluations
    assert seen[0] == 2.0 and all(2.0 <= t <= 2.5 for t in seen)


def test_rk4_integrates_a_time_dependent_acceleration_to_fourth_order() -> None:
    # a(t) = cos t from rest: v = sin t, x = 1 - cos t. One step of RK4 is Simpson's rule.
    accel = lambda t, x, v: math.cos(t)  # noqa: E731
    x, v = run(rk4, 0.0, 0.0, accel, 0.1, 10)
    assert v == pytest.approx(math.sin(1.0), abs=1e-7)
    assert x == pytest.approx(1 - math.cos(1.0), abs=1e-7)


# -- velocity Verlet's energy over a long run --------------------------------------------------


@pytest.mark.parametrize("y", [0.05, 0.5, 1.5])
def test_velocity_verlet_energy_error_stays_bounded_over_a_long_run(y: float) -> None:
    # On x'' = -omega^2 x velocity Verlet (kick-drift-kick) conserves exactly
    #   I = v^2 + omega^2 x^2 (1 - y^2/4),   y = omega dt,
    # so E = (v^2 + omega^2 x^2)/2 stays within [I/2, I/(2 (1 - y^2/4))]: the relative
    # energy error is at most (y^2/4) / (1 - y^2/4) = O((omega dt)^2) forever, no drift.
    # 10^5 steps are run on 64 bodies at once (one array), from different phases.
    omega = 2.0
    dt = y / omega
    phase = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    x, v = np.cos(phase) * 0.7, np.sin(phase) * 1.1

    def accel(t, x, v):  # type: ignore[no-untyped-def]
        return x * -(omega * omega)

    e0 = 0.5 * (v * v + omega * omega * x * x)
    bound = (y * y / 4) / (1 - y * y / 4)
    worst = 0.0
    for i in range(100_000):
        x, v = velocity_verlet(x, v, accel, i * dt, dt)
        if i % 97 == 0 or i > 99_000:
            e = 0.5 * (v * v + omega * omega * x * x)
            worst = max(worst, float(np.max(np.abs(e / e0 - 1))))
    assert worst <= bound * (1 + 1e-9) + 1e-12
    assert worst > 0.2 * bound  # the bound is the size of the error, not a loose ceiling


# -- the registry ------------------------------------------------------------------------------


def test_registry_lists_the_four_methods_cheapest_first() -> None:
    assert NAMES == ["explicit_euler", "semi_implicit_euler", "velocity_verlet", "rk4"]
    assert [INTEGRATORS[n].order for n in NAMES] == [1, 1, 2, 4]
    assert [INTEGRATORS[n].evaluations for n in NAMES] == [1, 1, 2, 4]
    assert get_integrator("rk4") is rk4


def test_unknown_integrator_name_lists_the_valid_ones() -> None:
    with pytest.raises(ValueError, match="unknown integrator 'euler'.*semi_implicit_euler"):
        get_integrator("euler")
    with pytest.raises(TypeError, match="integrator name must be a str"):
        get_integrator(4)  # type: ignore[arg-type]


def test_euler_errors_are_exact_in_rational_arithmetic() -> None:
    # The Euler methods multiply only by dt itself, so they run on Fractions unchanged and
    # check the theorem with no rounding at all, for a and h that are not binary fractions.
    # (Verlet and RK4 multiply by float constants such as 0.5 and 1/6, so they turn
    # Fractions into floats; their exactness is checked above with dyadic numbers.)
    a, h, n = Fraction(1, 3), Fraction(1, 7), 30
    T = n * h
    x, v = run(explicit_euler, Fraction(0), Fraction(0), constant(a), h, n)
    assert x - a * T * T / 2 == -a * T * h / 2 and v == a * T
    x, v = run(semi_implicit_euler, Fraction(0), Fraction(0), constant(a), h, n)
    assert x - a * T * T / 2 == +a * T * h / 2 and v == a * T
