"""Stability at the limits: integrators x dt x forces. Below each limit the state stays bounded
and the World is silent; above it the World warns; a blow-up raises SimulationDiverged before
any non-finite number reaches the World's state."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from engine import Body, SimulationDiverged, StabilityWarning, Vector, World
from engine.forces import Drag, Gravity, Spring, Wind
from engine.integrators import INTEGRATORS

W = 2 * math.pi  # rad/s
C = 3.0  # 1/s

MIXES = {
    "spring": lambda: [Spring((0.0, 0.0), W * W)],
    "drag": lambda: [Drag(C)],
    "spring+drag": lambda: [Spring((0.0, 0.0), W * W), Drag(C)],
    "spring+gravity": lambda: [Spring((0.0, 0.0), W * W), Gravity((0.0, -9.81))],
    "wind+gravity": lambda: [Wind((4.0, 0.0), C), Gravity((0.0, -9.81))],
}

# The textbook limits (the README's "Choosing an integrator" table): omega dt on a spring,
# c dt on a drag.
THEORY = {
    ("explicit_euler", "spring"): 0.0,
    ("semi_implicit_euler", "spring"): 2.0 / W,
    ("velocity_verlet", "spring"): 2.0 / W,
    ("rk4", "spring"): 2.0 * math.sqrt(2.0) / W,
    ("explicit_euler", "drag"): 2.0 / C,
    ("semi_implicit_euler", "drag"): 2.0 / C,
    ("velocity_verlet", "drag"): 2.0 / C,
    ("rk4", "drag"): 2.785293563405282 / C,
}


def _world(method: str, mix: str) -> World:
    world = World(integrator=method)
    world.add(Body(Vector(1.0, 0.0), Vector(0.0, 1.0), Vector(0.0, 0.0)))
    for force in MIXES[mix]():
        world.add_force(force)
    return world


CASES = [(m, mix) for m in INTEGRATORS for mix in MIXES]


@pytest.mark.parametrize(("method", "mix"), [k for k in THEORY])
def test_limits_are_the_textbook_ones(method: str, mix: str) -> None:
    assert _world(method, mix).max_stable_dt() == pytest.approx(THEORY[method, mix], rel=1e-9)


@pytest.mark.parametrize(("method", "mix"), CASES)
def test_below_the_limit_silent_and_bounded(method: str, mix: str) -> None:
    world = _world(method, mix)
    limit = world.max_stable_dt()
    if limit == 0.0:
        pytest.skip("no stable dt: explicit Euler on an undamped spring")
    dt = 0.95 * limit
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        for _ in range(3000):
            world.step(dt)
    # Bounded: a stable linear map keeps the state within a constant of its start. Start
    # |x| = 1 m, |v| = 1 m/s, equilibria within 0.3 m, drift at most the wind + g / c.
    drift = (4.0 + 9.81 / C) * world.t if mix == "wind+gravity" else 0.0
    assert np.abs(world.positions()).max() < 10.0 + drift
    assert np.abs(world.velocities()).max() < 100.0


@pytest.mark.parametrize(("method", "mix"), CASES)
def test_above_the_limit_the_world_warns(method: str, mix: str) -> None:
    world = _world(method, mix)
    limit = world.max_stable_dt()
    dt = 1.05 * limit if limit > 0 else 0.01
    with pytest.warns(StabilityWarning, match=method):
        world.step(dt)


@pytest.mark.parametrize(("method", "mix"), CASES)
def test_a_blow_up_raises_before_the_state_turns_non_finite(method: str, mix: str) -> None:
    world = _world(method, mix)
    limit = world.max_stable_dt()
    dt = 1.6 * limit if limit > 0 else 1.0 / W  # explicit Euler on a spring: any dt
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        with pytest.raises(SimulationDiverged) as info:
            for _ in range(100_000):
                world.step(dt)
    assert info.value.integrator == method and info.value.dt == dt
    x, v = world.positions(), world.velocities()
    assert np.isfinite(x).all() and np.isfinite(v).all()
    assert np.isfinite(world.positions(0.5)).all()
    assert np.abs(x).max() > 1e100  # it really was running away: the last finite state


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_gravity_alone_has_no_limit(method: str) -> None:
    world = World(integrator=method)
    world.add(Body(Vector(0.0, 0.0), Vector(1.0, 1.0), Vector(0.0, 0.0)))
    world.add_force(Gravity((0.0, -9.81)))
    assert world.max_stable_dt() == math.inf
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        for dt in (1e-3, 0.5, 10.0):
            world.step(dt)
