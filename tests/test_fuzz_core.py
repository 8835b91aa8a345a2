"""Fuzzing the value types and forces: Vector, Body and every force generator.

Examples per test (max_examples, run in full unless a test is refused early):
Vector constructor 1000, Vector operators 1000, Vector methods 600, Body constructor 1000,
Body setters 600, Body.step 600, forces 1000, force evaluation 400: 6,200 in this file.
The fuzz files together run 10,000+ (see tests/test_fuzz_world.py for the running total).
"""

from __future__ import annotations

import math
import operator
import warnings
from typing import Any

import numpy as np
import pytest
from fuzzing import (
    anything,
    attempt,
    check_message,
    fuzz,
    in_float_range,
    is_real,
    junk,
    moderate,
    numbers,
    pairs,
    same_float,
)
from hypothesis import given
from hypothesis import strategies as st
from pygame.math import Vector2

from engine import Body, Vector, World
from engine.forces import CallableForce, ConstantForce, Drag, Gravity, Spring, Wind, as_force


def _scalar_ok(value: Any) -> bool:
    return is_real(value) and in_float_range(value)


def _pair_ok(value: Any) -> bool:
    """A Vector, or a 2-sequence (tuple, list, 1D numpy array, pygame Vector2) of real numbers."""
    if isinstance(value, (Vector, Vector2)):
        return True
    if isinstance(value, np.ndarray):
        return value.shape == (2,) and all(_scalar_ok(c) for c in value)
    return (
        isinstance(value, (tuple, list)) and len(value) == 2 and all(_scalar_ok(c) for c in value)
    )


# -- Vector ---------------------------------------------------------------------------------


@fuzz(1000)
@given(x=anything, y=anything)
def test_vector_constructor_keeps_numbers_and_names_the_bad_component(x: Any, y: Any) -> None:
    ok, v = attempt(lambda: Vector(x, y), "component x", "component y")
    assert ok == (_scalar_ok(x) and _scalar_ok(y)), (x, y)
    if ok:
        assert isinstance(v, Vector)
        assert same_float(v.x, float(x)) and same_float(v.y, float(y))
        assert v.is_finite() == (math.isfinite(float(x)) and math.isfinite(float(y)))


OPS = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv}


@fuzz(1000)
@given(x=moderate, y=moderate, op=st.sampled_from(sorted(OPS)), other=anything, left=st.booleans())
def test_vector_operators_give_the_componentwise_answer_or_a_clear_type_error(
    x: float, y: float, op: str, other: Any, left: bool
) -> None:
    v = Vector(x, y)
    fn = OPS[op]
    if op == "/" and left:
        left = False  # number / Vector is not defined; Vector / number is
    if left and isinstance(other, Vector2):
        # pygame's operator answers first there (the README's "Mixing with pygame"): its result
        # is pygame's, a Vector2 for + and -, the dot product for *.
        return
    try:
        result = fn(other, v) if left else fn(v, other)
    except ZeroDivisionError as exc:
        assert op == "/" and _scalar_ok(other) and float(other) == 0.0
        assert "zero" in str(exc)
        return
    except (TypeError, ValueError) as exc:
        # An operand the Vector does not take: Python's (or numpy's) own operator message,
        # "unsupported operand type(s) for +: 'Vector' and 'str'", unless the Vector's own.
        if str(exc).startswith("Vector"):
            check_message(exc, ("vector", "scale", "divisor"))
        if op in "+-":
            assert not _pair_ok(other)
        else:
            assert not _scalar_ok(other)
        return
    assert isinstance(result, Vector)
    if op in "+-":
        ox, oy = (float(c) for c in other)
        sign = 1.0 if op == "+" else -1.0
        if left and op == "-":
            want = (ox - x, oy - y)
        else:
            want = (x + sign * ox, y + sign * oy)
    elif op == "*":
        s = float(other)
        want = (x * s, y * s)
    else:
        s = float(other)
        want = (x / s, y / s)
    assert same_float(result.x, want[0]) and same_float(result.y, want[1])


@fuzz(600)
@given(x=numbers, y=numbers, other=anything, t=anything)
def test_vector_methods_refuse_bad_arguments_by_name(x: Any, y: Any, other: Any, t: Any) -> None:
    if not (_scalar_ok(x) and _scalar_ok(y)):
        return
    v = Vector(x, y)
    for name, call in (
        ("dot", lambda: v.dot(other)),
        ("cross", lambda: v.cross(other)),
        ("distance_to", lambda: v.distance_to(other)),
        ("lerp", lambda: v.lerp(other, t)),
    ):
        ok, result = attempt(call, "other", "component t", "t must")
        # pygame's lerp takes 0 <= t <= 1 (a ValueError naming t outside it)
        t_ok = _scalar_ok(t) and 0.0 <= float(t) <= 1.0
        assert ok == (_pair_ok(other) and (name != "lerp" or t_ok)), (name, other, t)
        if ok:
            assert isinstance(result, Vector if name == "lerp" else float)
    ok, unit = attempt(v.normalized, "zero vector", "finite")
    assert ok == ((v.x != 0.0 or v.y != 0.0) and v.is_finite())
    if ok and v.is_finite():
        assert abs(unit.magnitude() - 1.0) < 1e-12, (v, unit)
    ok, coerced = attempt(lambda: Vector.coerce(other, "where"), "where")
    assert ok == _pair_ok(other)


# -- Body -----------------------------------------------------------------------------------

state_1d = st.one_of(numbers, junk)
state_any = st.one_of(numbers, pairs, junk)


def _finite_state(value: Any, dim: int) -> bool:
    if dim == 1:
        return _scalar_ok(value) and math.isfinite(float(value))
    return _pair_ok(value) and all(math.isfinite(float(c)) for c in value)


def _dim(value: Any) -> int | None:
    if _scalar_ok(value):
        return 1
    if _pair_ok(value):
        return 2
    return None


def _body_is_finite(b: Body) -> bool:
    values = [b.pos, b.vel, b.own_acc, b.mass]
    flat = [c for v in values for c in ((v,) if isinstance(v, float) else v)]
    return all(math.isfinite(c) for c in flat) and b.mass > 0


@fuzz(1000)
@given(p=state_any, v=state_any, a=state_any, mass=st.one_of(numbers, junk))
def test_body_constructor_accepts_only_finite_states_of_one_dimension(
    p: Any, v: Any, a: Any, mass: Any
) -> None:
    ok, body = attempt(lambda: Body(p, v, a, mass), "position", "velocity", "acceleration", "mass")
    # None for the velocity or the acceleration is the default: zero, of the position's kind.
    zero = {1: 0.0, 2: (0.0, 0.0)}.get(_dim(p) or 0, 0.0)
    v, a = (zero if s is None else s for s in (v, a))
    dims = {_dim(p), _dim(v), _dim(a)}
    valid = (
        len(dims) == 1
        and None not in dims
        and all(_finite_state(s, dims.copy().pop()) for s in (p, v, a))  # type: ignore[arg-type]
        and _scalar_ok(mass)
        and 0.0 < float(mass) < math.inf
    )
    assert ok == valid, (p, v, a, mass)
    if ok:
        assert body is not None and _body_is_finite(body)
        assert body.dim == dims.pop()
        want = float(p) if body.dim == 1 else tuple(float(c) for c in p)
        assert body.pos == want


SETTERS = ("pos", "vel", "own_acc", "mass", "acc")


@fuzz(600)
@given(
    dim=st.sampled_from([1, 2]),
    in_world=st.booleans(),
    changes=st.lists(st.tuples(st.sampled_from(SETTERS), state_any), min_size=1, max_size=6),
)
def test_body_setters_refuse_bad_values_by_name_and_keep_the_world_finite(
    dim: int, in_world: bool, changes: list[tuple[str, Any]]
) -> None:
    zero = 0.0 if dim == 1 else Vector(0.0, 0.0)
    body = Body(zero, zero, zero)
    world = World()
    if in_world:
        world.add(body)
    for name, value in changes:
        before = repr(body)
        try:
            setattr(body, name, value)
        except AttributeError as exc:  # acc in a World is read-only: own_acc is the setting
            assert name == "acc" and in_world and "own_acc" in str(exc)
            continue
        except (TypeError, ValueError) as exc:
            check_message(exc, (name,))
            assert repr(body) == before  # a refused value changes nothing
            continue
        valid = (
            _scalar_ok(value) and 0.0 < float(value) < math.inf
            if name == "mass"
            else _finite_state(value, dim)
        )
        assert valid, (name, value)
        assert _body_is_finite(body)
        got = getattr(body, name)
        if name != "acc":
            want = float(value) if dim == 1 or name == "mass" else tuple(map(float, value))
            assert got == want, (name, value, got)
        if in_world:
            assert np.isfinite(world.positions()).all() and np.isfinite(world.velocities()).all()


@fuzz(600)
@given(
    dim=st.sampled_from([1, 2]),
    start=st.floats(-1e300, 1e300),
    dt=st.one_of(numbers, junk),
    acceleration=st.one_of(st.none(), state_any),
)
def test_body_step_refuses_bad_dt_and_acceleration_and_never_goes_non_finite(
    dim: int, start: float, dt: Any, acceleration: Any
) -> None:
    s = start if dim == 1 else Vector(start, -start)
    body = Body(s, s, s)
    before = repr(body)
    ok, _ = attempt(lambda: body.step(dt, acceleration), "dt", "acceleration")
    if ok:
        assert _scalar_ok(dt) and 0.0 < float(dt) < math.inf
        assert acceleration is None or _finite_state(acceleration, dim)
        assert _body_is_finite(body)
    else:
        assert repr(body) == before


# -- forces ---------------------------------------------------------------------------------

FORCES = {
    "Gravity": (lambda a, b, c: Gravity(a), ("g",)),
    "ConstantForce": (lambda a, b, c: ConstantForce(a), ("f",)),
    "Drag": (lambda a, b, c: Drag(a), ("k",)),
    "Wind": (lambda a, b, c: Wind(a, b), ("air_velocity", "k")),
    "Wind(t)": (lambda a, b, c: Wind(lambda t: a, b), ("air_velocity", "k")),
    "Spring": (lambda a, b, c: Spring(a, b, c), ("anchor", "k", "rest_length")),
    "CallableForce": (
        lambda a, b, c: CallableForce(a, stiffness=b, damping=c),
        ("force", "stiffness", "damping"),
    ),
    "as_force": (lambda a, b, c: as_force(a), ("force",)),
}


@fuzz(1000)
@given(kind=st.sampled_from(sorted(FORCES)), a=anything, b=anything, c=anything)
def test_force_constructors_keep_finite_parameters_or_name_the_bad_one(
    kind: str, a: Any, b: Any, c: Any
) -> None:
    make, names = FORCES[kind]
    ok, force = attempt(lambda: make(a, b, c), *names)
    if not ok:
        return
    # What was accepted is finite and non-negative where it must be.
    for attr in ("k", "rest_length", "stiffness", "damping"):
        value = getattr(force, attr, 0.0)
        assert math.isfinite(value) and value >= 0.0, (kind, attr, value)
    for attr in ("g", "f", "anchor"):
        value = getattr(force, attr, 0.0)
        parts = (value,) if isinstance(value, float) else tuple(value)
        assert all(math.isfinite(p) for p in parts), (kind, attr, value)
    if kind.startswith("Wind"):
        air = force.air(0.0)
        assert all(math.isfinite(p) for p in ((air,) if isinstance(air, float) else air))


@fuzz(400)
@given(
    kind=st.sampled_from(["Gravity", "ConstantForce", "Drag", "Wind", "Spring"]),
    param=st.one_of(moderate, st.tuples(moderate, moderate)),
    k=st.floats(0.0, 1e3),
    x=moderate,
    y=moderate,
    n=st.integers(0, 4),
)
def test_forces_on_finite_states_are_finite_for_floats_vectors_and_arrays(
    kind: str, param: Any, k: float, x: float, y: float, n: int
) -> None:
    force = {
        "Gravity": lambda: Gravity(param),
        "ConstantForce": lambda: ConstantForce(param),
        "Drag": lambda: Drag(k),
        "Wind": lambda: Wind(param, k),
        "Spring": lambda: Spring(param, k, 0.5),
    }[kind]()
    dim = force.dim or (1 if isinstance(param, float) else 2)
    if dim == 1:
        single = force(0.0, x, y, 2.0)
        many = force(0.0, np.full(n, x), np.full(n, y), np.full(n, 2.0))
        assert math.isfinite(single)
        assert many.shape == (n,)
        np.testing.assert_array_equal(many, np.full(n, single))
    else:
        single = force(0.0, Vector(x, y), Vector(y, x), 2.0)
        assert isinstance(single, Vector) and single.is_finite()
        many = force(0.0, np.tile([x, y], (n, 1)), np.tile([y, x], (n, 1)), np.full((n, 1), 2.0))
        assert many.shape == (n, 2)
        np.testing.assert_allclose(many, np.tile(tuple(single), (n, 1)), rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("bad", [math.nan, math.inf, "wind", None])
def test_a_gusty_wind_that_turns_bad_later_is_named_when_it_does(bad: Any) -> None:
    wind = Wind(lambda t: (1.0, 0.0) if t < 1 else (bad, 0.0), 0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises((TypeError, ValueError)) as info:
            wind(2.0, Vector(0, 0), Vector(0, 0), 1.0)
    check_message(info.value, ("air_velocity",))
