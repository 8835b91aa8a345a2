"""The World's parts: bodies as handles into its arrays, the affine Euler kernel and its
overflow proof, and the shared force model's stability check."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from engine import Body, SimulationDiverged, StabilityWarning, Vector, World
from engine.forces import Drag, Gravity, Wind
from engine.integrators import explicit_euler, semi_implicit_euler


def _world(method: str, n: int = 5, drag: float = 0.3) -> World:
    world = World(integrator=method)
    rng = np.random.default_rng(1)
    for p, v in zip(rng.uniform(-5, 5, (n, 2)), rng.uniform(-3, 3, (n, 2)), strict=True):
        world.add(Body(Vector(*p), Vector(*v), Vector(0, 0), mass=2.0))
    world.add_force(Gravity((0, -9.81)))
    if drag:
        world.add_force(Drag(drag))
    return world


@pytest.mark.parametrize(
    "method, step",
    [("semi_implicit_euler", semi_implicit_euler), ("explicit_euler", explicit_euler)],
)
def test_the_affine_kernel_is_the_integrator_bit_for_bit_without_drag(method, step) -> None:
    world = _world(method, drag=0.0)
    x, v = world.positions(), world.velocities()
    g = np.array([0.0, -9.81])
    for _ in range(500):
        world.step(1 / 60)
        x, v = step(x, v, lambda t, x, v: np.broadcast_to(g, x.shape), 0.0, 1 / 60)
    assert np.array_equal(world.positions(), x) and np.array_equal(world.velocities(), v)


@pytest.mark.parametrize(
    "method, step",
    [("semi_implicit_euler", semi_implicit_euler), ("explicit_euler", explicit_euler)],
)
def test_the_affine_kernel_with_drag_is_the_integrator_to_round_off(method, step) -> None:
    # v' = (1 - c dt) v + a0 dt is v + (a0 - c v) dt reassociated: equal to a few ulps.
    world = _world(method, drag=0.3)
    x, v = world.positions(), world.velocities()
    c = 0.3 / 2.0

    def accel(t, x, v):
        return np.array([0.0, -9.81]) - c * v

    for _ in range(500):
        world.step(1 / 60)
        x, v = step(x, v, accel, 0.0, 1 / 60)
    assert np.allclose(world.positions(), x, rtol=1e-12, atol=1e-12)
    assert np.allclose(world.velocities(), v, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("method", ["semi_implicit_euler", "explicit_euler"])
def test_the_affine_kernel_still_stops_a_blow_up_before_it_enters_the_state(method) -> None:
    # Drag rate c = 30 / 1 kg at dt = 0.1 s: c dt = 3 > 2, |1 - c dt| = 2, the velocity doubles
    # in size each step and reaches the float range after ~1000 steps.
    world = World(integrator=method)
    body = world.add(Body(Vector(1, 1), Vector(1, -1), Vector(0, 0)))
    world.add_force(Drag(30.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        with pytest.raises(SimulationDiverged, match=method):
            for _ in range(5000):
                world.step(0.1)
    assert math.isfinite(body.pos.x) and math.isfinite(body.vel.y)
    assert np.isfinite(world.positions()).all() and np.isfinite(world.velocities()).all()
    assert world.steps < 5000


def test_a_huge_but_finite_state_takes_the_checked_path_and_stays_exact() -> None:
    world = World()
    body = world.add(Body(Vector(1e301, 0), Vector(1e300, 0), Vector(0, 0)))
    world.add_force(Gravity((0, -10)))
    world.step(0.5)
    assert body.pos.x == 1e301 + 1e300 * 0.5 and body.vel.y == -5.0


def test_writing_own_acc_changes_one_entry_and_compiles_nothing() -> None:
    world = _world("semi_implicit_euler")
    world.step(1 / 60)
    model = world._model  # the compiled forces
    first = world.bodies[0]
    first.own_acc = Vector(3, 0)
    assert world._model is model
    reference = _world("semi_implicit_euler")
    reference.step(1 / 60)
    reference.bodies[0].own_acc = Vector(3, 0)
    for _ in range(10):
        world.step(1 / 60)
        reference.step(1 / 60)
    assert np.array_equal(world.positions(), reference.positions())
    assert first.own_acc == Vector(3, 0)
    # a = own + g - (k / m) v, read for this body alone
    expected = Vector(3, -9.81) - first.vel * (0.3 / 2.0)
    assert (first.acc - expected).magnitude() < 1e-12


def test_removing_a_body_leaves_every_other_handle_pointing_at_its_own_state() -> None:
    world = _world("semi_implicit_euler", n=6)
    world.step(1 / 60)
    bodies = world.bodies
    before = {id(b): (b.pos, b.vel) for b in bodies}
    world.remove(bodies[2])
    world.remove(bodies[0])
    assert world.bodies == (bodies[1], bodies[3], bodies[4], bodies[5])
    for b in world.bodies:
        assert (b.pos, b.vel) == before[id(b)]
    gone = bodies[2]
    assert gone.world is None and (gone.pos, gone.vel) == before[id(gone)] and gone.mass == 2.0
    bodies[5].pos = Vector(7, 7)
    assert world.positions()[-1].tolist() == [7.0, 7.0]


def test_world_evaluations_count_each_method_s_force_evaluations() -> None:
    for method, per_step in (("semi_implicit_euler", 1), ("velocity_verlet", 2), ("rk4", 4)):
        world = _world(method)
        world.step(1 / 60)
        start = world.evaluations
        for _ in range(10):
            world.step(1 / 60)
        assert world.evaluations - start == 10 * per_step, method


def test_a_gusty_wind_s_drag_counts_for_the_stability_limit() -> None:
    # Wind k = 30 N s/m on 1 kg: the velocity decays at 30 1/s; at dt = 0.1 s, 30 dt = 3 > 2.
    world = World()
    world.add(Body(Vector(0, 0), Vector(0, 0), Vector(0, 0)))
    world.add_force(Wind(lambda t: Vector(math.sin(t), 0.0), 30.0))
    with pytest.warns(StabilityWarning, match="damping rate=30"):
        world.step(0.1)
