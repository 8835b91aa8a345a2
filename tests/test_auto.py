""" "auto": the closed form when forces are constant, never a method past its stability limit,
and with a tolerance the cheapest method whose error over 1 s really stays within it."""

from __future__ import annotations

import math

import pytest

from engine import Body, Vector, World
from engine.dynamics.policy import AUTO_ORDER
from engine.forces import ConstantForce, Drag, Gravity, Spring, Wind
from engine.integrators import INTEGRATORS
from engine.measure import PROBLEMS, measure
from engine.stability import is_stable


def _world(forces: list, tolerance: float | None = None) -> World:
    world = World(integrator="auto", tolerance=tolerance)
    world.add(Body(Vector(1.0, 0.0), Vector(0.0, 2.0), Vector(0.0, 0.0)))
    for f in forces:
        world.add_force(f)
    return world


@pytest.mark.parametrize("tolerance", [None, 1e-3, 1e-12])
def test_gravity_alone_picks_the_closed_form(tolerance: float | None) -> None:
    world = _world([Gravity((0.0, -9.81)), ConstantForce((1.0, 0.0))], tolerance)
    assert world.choose_method(0.25)[0] == "exact"
    world.step(0.25)
    assert world.method == "exact" and "constant" in world.method_reason


@pytest.mark.parametrize("omega", [1.0, 2 * math.pi, 50.0])
@pytest.mark.parametrize("rate", [0.0, 3.0, 80.0])
@pytest.mark.parametrize("tolerance", [None, 1e-2, 1e-6])
def test_auto_never_picks_a_method_past_its_limit(
    omega: float, rate: float, tolerance: float | None
) -> None:
    world = _world([Spring((0.0, 0.0), omega * omega), Drag(rate)], tolerance)
    for k in range(-12, 4):
        dt = 2.0**k / omega
        name, reason = world.choose_method(dt)
        anyone = any(is_stable(INTEGRATORS[n], omega, rate, dt) for n in AUTO_ORDER)
        if anyone:
            assert is_stable(INTEGRATORS[name], omega, rate, dt), (dt, name, reason)
        else:
            assert name == "rk4" and "no method is stable" in reason


@pytest.mark.parametrize("problem", ["spring", "wind"])
@pytest.mark.parametrize("tolerance", [1e-1, 1e-3, 1e-6])
@pytest.mark.parametrize("dt", [1 / 8, 1 / 32, 1 / 128])
def test_tolerance_is_met_by_the_cheapest_method_that_meets_it(
    problem: str, tolerance: float, dt: float
) -> None:
    prob = PROBLEMS[problem]
    world, _ = prob.world("auto", tolerance)
    name, reason = world.choose_method(dt)
    measured = {n: measure(prob, n, dt, repeats=1, min_steps=1).error for n in AUTO_ORDER}
    if "predicted within" in reason:
        assert measured[name] <= tolerance, (name, measured)
        cheaper = AUTO_ORDER[: AUTO_ORDER.index(name)]
        assert all(measured[n] > tolerance for n in cheaper), measured
    else:
        assert name == "rk4" and all(e > tolerance for e in measured.values()), measured


@pytest.mark.parametrize("problem", ["spring", "wind"])
@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_predicted_error_is_the_measured_error(problem: str, method: str) -> None:
    prob = PROBLEMS[problem]
    world, _ = prob.world("auto")
    for dt in (1 / 8, 1 / 64):
        predicted = world.predicted_error(method, dt)
        measured = measure(prob, method, dt, repeats=1, min_steps=1).error
        assert predicted == pytest.approx(measured, rel=1e-6)


def test_tolerance_reason_names_a_dt_that_would_meet_it() -> None:
    world = _world([Spring((0.0, 0.0), 400.0)], tolerance=1e-9)
    name, reason = world.choose_method(0.01)
    assert name == "rk4" and "would meet it" in reason


@pytest.mark.parametrize("bad", [0.0, -1e-3, math.nan, math.inf])
def test_tolerance_must_be_a_positive_length(bad: float) -> None:
    with pytest.raises(ValueError, match="tolerance"):
        World(integrator="auto", tolerance=bad)


def test_tolerance_only_with_auto() -> None:
    with pytest.raises(ValueError, match="only applies to integrator='auto'"):
        World(integrator="rk4", tolerance=1e-3)
    with pytest.raises(TypeError, match="tolerance"):
        World(integrator="auto", tolerance="1e-3")  # type: ignore[arg-type]


def test_wind_with_gravity_is_not_closed_form_but_stays_stable() -> None:
    world = _world([Gravity((0.0, -9.81)), Wind((3.0, 0.0), 50.0)], tolerance=1e-3)
    name, _ = world.choose_method(0.05)  # rate * dt = 2.5: only RK4 is stable
    assert name == "rk4"


def test_the_repr_shows_the_tolerance_when_there_is_one() -> None:
    world = _world([Gravity((0.0, -9.81))], tolerance=1e-3)
    assert repr(world) == "World(integrator='auto', tolerance=0.001, bodies=1, forces=1, t=0)"
    assert "tolerance" not in repr(_world([Gravity((0.0, -9.81))]))
