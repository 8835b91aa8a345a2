"""engine.forces: pure force generators on floats, Vectors and arrays of many bodies."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import Vector
from engine.forces import (
    CallableForce,
    ConstantForce,
    Drag,
    Force,
    Gravity,
    Spring,
    Wind,
    as_force,
)


def test_gravity_is_the_same_acceleration_for_every_mass() -> None:
    g = Gravity((0, -9.81))
    for m in (0.5, 1.0, 70.0):
        assert g(0.0, Vector(1, 2), Vector(3, 4), m) == Vector(0, -9.81 * m)
    assert Gravity(-9.81)(0.0, 5.0, 1.0, 2.0) == -19.62
    assert g.constant and g.dim == 2 and Gravity(-1.0).dim == 1
    assert (g.stiffness, g.damping) == (0.0, 0.0)


def test_drag_opposes_velocity_and_wind_pulls_toward_the_air() -> None:
    assert Drag(0.5)(0.0, 1.0, 4.0, 1.0) == -2.0
    assert Drag(0.5)(0.0, Vector(0, 0), Vector(2, -4), 1.0) == Vector(-1, 2)
    w = Wind(air_velocity=(2, 0), k=0.1)
    f = w(0.0, Vector(0, 0), Vector(3, 4), 1.0)
    assert f.x == pytest.approx(-0.1 * (3 - 2), rel=1e-15) and f.y == pytest.approx(-0.4)
    # A body moving with the air feels nothing.
    assert w(0.0, Vector(0, 0), Vector(2, 0), 1.0) == Vector(0, 0)
    assert not Drag(1).constant and Drag(3).damping == 3.0 and w.damping == 0.1


def test_wind_that_changes_with_time_is_evaluated_at_t() -> None:
    w = Wind(air_velocity=lambda t: (t, 0.0), k=2.0)
    assert w(3.0, Vector(0, 0), Vector(0, 0), 1.0) == Vector(6, 0)
    assert w.air(1.5) == Vector(1.5, 0)
    assert w.affine() is None and not w.constant


def test_spring_pulls_toward_rest_length_and_not_at_all_at_the_anchor() -> None:
    s = Spring((0, 0), k=10.0, rest_length=1.0)
    assert s(0.0, Vector(3, 0), Vector(0, 0), 1.0) == Vector(-20, 0)  # stretched by 2
    assert s(0.0, Vector(0, 0.5), Vector(0, 0), 1.0) == Vector(0, 5)  # squeezed by 0.5
    assert s(0.0, Vector(0, 0), Vector(0, 0), 1.0) == Vector(0, 0)
    hooke = Spring(1.0, k=4.0)
    assert hooke(0.0, 3.0, 0.0, 1.0) == -8.0
    assert hooke.stiffness == 4.0 and not hooke.constant


@pytest.mark.parametrize(
    "force",
    [
        Gravity((0.5, -9.81)),
        ConstantForce((3.0, -1.0)),
        Spring((1.0, -2.0), k=3.0),
        Spring((1.0, -2.0), k=3.0, rest_length=0.7),
    ],
    ids=repr,
)
def test_potential_is_minus_the_work_of_the_force(force: Force) -> None:
    # F = -grad U: compare with central differences of U (exact for U of degree <= 2;
    # O(h^2) otherwise).
    m, h = 2.0, 1e-5
    for p in (Vector(0.3, 0.9), Vector(-2, 1.5), Vector(4, -4)):
        f = force(0.0, p, Vector(0, 0), m)
        for e in (Vector(1, 0), Vector(0, 1)):
            du = force.potential(p + e * h, m) - force.potential(p - e * h, m)
            assert -du / (2 * h) == pytest.approx(f.dot(e), rel=1e-6, abs=1e-6)


def test_forces_without_a_potential_say_none() -> None:
    assert Drag(1.0).potential(1.0, 1.0) is None
    assert Wind(1.0, 1.0).potential(1.0, 1.0) is None
    assert CallableForce(lambda t, x, v, m: x).potential(1.0, 1.0) is None


@pytest.mark.parametrize(
    "force",
    [
        Gravity((0.5, -9.81)),
        ConstantForce((3.0, -1.0)),
        Drag(0.3),
        Wind((1.0, 2.0), 0.7),
        Spring((1.0, -2.0), k=3.0),
        Spring((1.0, -2.0), k=3.0, rest_length=0.7),
    ],
    ids=repr,
)
def test_each_force_gives_the_same_answer_on_vectors_and_on_an_array_of_bodies(
    force: Force,
) -> None:
    rng = np.random.default_rng(1)
    x, v = rng.normal(size=(5, 2)), rng.normal(size=(5, 2))
    m = rng.uniform(0.5, 2.0, size=5)
    x0, v0 = x.copy(), v.copy()
    many = force(0.25, x, v, m[:, None])
    assert many.shape == (5, 2)
    for i in range(5):
        one = force(0.25, Vector(*x[i]), Vector(*v[i]), float(m[i]))
        assert tuple(many[i]) == pytest.approx(tuple(one), rel=1e-14, abs=1e-15)
    # Pure: the inputs are not written to.
    assert np.array_equal(x, x0) and np.array_equal(v, v0)


def test_each_force_works_on_1d_arrays_too() -> None:
    x, v, m = np.array([1.0, -2.0, 3.0]), np.array([0.5, 0.0, -1.0]), np.array([1.0, 2.0, 4.0])
    assert Gravity(-10.0)(0.0, x, v, m).tolist() == [-10.0, -20.0, -40.0]
    assert Drag(2.0)(0.0, x, v, m).tolist() == [-1.0, 0.0, 2.0]
    assert Spring(1.0, k=2.0)(0.0, x, v, m).tolist() == [0.0, 6.0, -4.0]
    assert Spring(0.0, k=2.0, rest_length=1.0)(0.0, x, v, m).tolist() == [0.0, 2.0, -4.0]


def test_a_plain_callable_becomes_a_force() -> None:
    fn = lambda t, x, v, m: -x * m  # noqa: E731
    f = as_force(fn)
    assert isinstance(f, CallableForce) and f(0.0, 2.0, 0.0, 3.0) == -6.0
    assert as_force(f) is f
    known = CallableForce(fn, stiffness=2.0, damping=1.0, constant=False)
    assert (known.stiffness, known.damping) == (2.0, 1.0)


# -- refusals ----------------------------------------------------------------------------------


def test_bad_force_parameters_are_refused_with_their_name() -> None:
    with pytest.raises(TypeError, match="g must be a number"):
        Gravity("down")
    with pytest.raises(ValueError, match="g must be finite"):
        Gravity((0, math.inf))
    with pytest.raises(ValueError, match="k must be >= 0"):
        Drag(-1)
    with pytest.raises(TypeError, match="k must be a real number"):
        Drag("lots")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="k must be finite"):
        Spring((0, 0), k=math.nan)
    with pytest.raises(ValueError, match="rest_length must be >= 0"):
        Spring((0, 0), k=1.0, rest_length=-1.0)
    with pytest.raises(TypeError, match="anchor must be a number"):
        Spring(None, k=1.0)
    with pytest.raises(TypeError, match="air_velocity must be"):
        Wind("east", k=1.0)
    with pytest.raises(TypeError, match="f must be a number"):
        ConstantForce([1, 2, 3])
    with pytest.raises(ValueError, match="stiffness must be >= 0"):
        CallableForce(lambda t, x, v, m: x, stiffness=-1)


def test_something_that_is_not_a_force_is_refused() -> None:
    with pytest.raises(TypeError, match="force must be a Force"):
        as_force(42)
    with pytest.raises(TypeError, match="callable"):
        CallableForce("not callable")  # type: ignore[arg-type]
    assert math.isfinite(Gravity(1.0)(0.0, 0.0, 0.0, 1.0))
