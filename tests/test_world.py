"""engine.World: bodies, forces, step(dt), energy, method choice, failures, determinism."""

from __future__ import annotations

import copy
import hashlib
import math
import warnings
from collections.abc import Callable
from fractions import Fraction

import numpy as np
import pytest

from engine import (
    Body,
    DampedSpring,
    Rod,
    SimulationDiverged,
    StabilityWarning,
    Vector,
    World,
)
from engine.forces import ConstantForce, Drag, Gravity, Spring, Wind

# Theory, independent of engine.stability (see test_stability.py for the derivations).
OSC_LIMIT = {"semi_implicit_euler": 2.0, "velocity_verlet": 2.0, "rk4": 2.0 * math.sqrt(2.0)}
DECAY_LIMIT = {"semi_implicit_euler": 2.0, "velocity_verlet": 2.0, "rk4": 2.785293563405282}
METHODS = ["explicit_euler", "semi_implicit_euler", "velocity_verlet", "rk4"]


def state_hash(world: World) -> str:
    return hashlib.sha256(world.positions().tobytes() + world.velocities().tobytes()).hexdigest()


def busy_world(method: str) -> World:
    """Bodies under every kind of force, some forces on a subset."""
    world = World(integrator=method)
    rng = np.random.default_rng(42)
    bodies = [
        world.add(
            Body(
                Vector(*rng.normal(size=2)),
                Vector(*rng.normal(size=2)),
                Vector(*rng.normal(size=2) * 0.1),
                mass=float(rng.uniform(0.5, 2.0)),
            )
        )
        for _ in range(12)
    ]
    world.add_force(Gravity((0, -9.81)))
    if method != "exact":
        world.add_force(Spring((0.5, 0.5), k=3.0, rest_length=0.3), bodies=bodies[:6])
        world.add_force(Drag(0.2))
        world.add_force(Wind(lambda t: (math.sin(t), 0.0), k=0.1), bodies=bodies[3:9])
        world.add_force(lambda t, x, v, m: -x * m * 0.5)  # a plain callable
    else:
        world.add_force(ConstantForce((0.3, 0.1)), bodies=bodies[::2])
    return world


# -- bodies and forces -------------------------------------------------------------------------


def test_add_returns_the_body_and_the_world_holds_it() -> None:
    world = World()
    assert world.dim is None and world.bodies == ()
    b = Body(Vector(1, 2), Vector(0, 0), Vector(0, 0))
    assert world.add(b) is b
    assert world.bodies == (b,) and b.world is world and world.dim == 2
    g = Gravity((0, -1))
    assert world.add_force(g) is g and world.forces == (g,)


def test_bodies_state_is_live_and_kept_in_arrays() -> None:
    world = World("exact")
    a = world.add(Body(0.0, 1.0, 0.0))
    b = world.add(Body(10.0, -2.0, 0.0))
    world.step(0.5)
    assert world.positions().tolist() == [0.5, 9.0]
    assert world.velocities().tolist() == [1.0, -2.0]
    assert (a.pos, b.pos) == (0.5, 9.0)
    b.vel = 0.0
    world.step(0.5)
    assert (a.pos, b.pos) == (1.0, 9.0)
    # positions() is a copy: writing to it changes nothing
    world.positions()[0] = 99.0
    assert a.pos == 1.0


def test_add_force_with_bodies_acts_on_that_subset_only() -> None:
    world = World("rk4")
    falling = world.add(Body(Vector(0, 0), Vector(0, 0), Vector(0, 0)))
    floating = world.add(Body(Vector(5, 0), Vector(1, 0), Vector(0, 0)))
    world.add_force(Gravity((0, -10)), bodies=[falling])
    for _ in range(8):
        world.step(0.125)  # binary fractions: no rounding, so exact comparisons hold
    assert falling.pos.distance_to((0, -5)) < 1e-12  # -g t^2 / 2 at t = 1, exact for RK4
    assert floating.pos == Vector(6, 0) and floating.vel == Vector(1, 0)
    assert floating.acc == Vector(0, 0) and falling.acc == Vector(0, -10)


def test_remove_takes_a_body_out_and_the_rest_carry_on() -> None:
    world = World("exact")
    a = world.add(Body(0.0, 1.0, 0.0))
    b = world.add(Body(0.0, 0.0, 0.0))
    c = world.add(Body(0.0, -1.0, 0.0))
    world.add_force(Gravity(-2.0), bodies=[b, c])
    world.step(1.0)
    world.remove(b)
    assert world.bodies == (a, c) and b.world is None
    assert (b.pos, b.vel) == (-1.0, -2.0)
    world.step(1.0)
    assert (a.pos, c.pos) == (2.0, -2.0 - 4.0)  # c: -t - t^2 at t = 2
    with pytest.raises(ValueError, match="not in this World"):
        world.remove(b)


def test_a_1d_world_refuses_2d_bodies_and_2d_forces() -> None:
    world = World()
    world.add(Body(0.0, 0.0, 0.0))
    with pytest.raises(TypeError, match="the body is 2D but this World is 1D"):
        world.add(Body(Vector(0, 0), Vector(0, 0), Vector(0, 0)))
    with pytest.raises(TypeError, match="is 2D but this World is 1D"):
        world.add_force(Gravity((0, -9.81)))
    assert len(world.bodies) == 1 and world.forces == ()


def test_a_2d_world_refuses_1d_bodies_and_1d_forces() -> None:
    world = World()
    world.add_force(Gravity((0, -9.81)))  # a shaped force fixes the dimension
    assert world.dim == 2
    with pytest.raises(TypeError, match="is 1D but this World is 2D"):
        world.add(Body(0.0, 0.0, 0.0))
    with pytest.raises(TypeError, match="is 1D but this World is 2D"):
        world.add_force(Spring(0.0, k=1.0))


def test_the_issue_example_matches_the_analytic_wind_and_gravity_solution() -> None:
    # m v' = m g - k (v - air): v(t) = vt + (v0 - vt) e^{-t/tau}, vt = air + g tau, tau = m/k.
    m, k, g, air, v0 = 0.5, 0.1, Vector(0, -9.81), Vector(2, 0), Vector(3, 4)
    tau = m / k
    vt = air + g * tau

    def exact(t: float) -> tuple[Vector, Vector]:
        decay = math.exp(-t / tau)
        return vt * t + (v0 - vt) * (tau * (1 - decay)), vt + (v0 - vt) * decay

    for method, tol in (("rk4", 1e-10), ("semi_implicit_euler", 0.1)):
        world = World(integrator=method)
        ball = world.add(Body(Vector(0, 0), v0, Vector(0, 0), mass=m))
        world.add_force(Gravity(g))
        world.add_force(Wind(air_velocity=air, k=k))
        for _ in range(60):
            world.step(1 / 60)
        x, v = exact(1.0)
        assert world.t == pytest.approx(1.0, rel=1e-15)
        assert ball.pos.distance_to(x) < tol and ball.vel.distance_to(v) < tol, method


# -- energy ------------------------------------------------------------------------------------


def test_energy_is_kinetic_plus_potential_of_gravity_spring_and_own_acceleration() -> None:
    world = World()
    b1 = world.add(Body(Vector(1, 2), Vector(3, -1), Vector(0.5, 0), mass=2.0))
    b2 = world.add(Body(Vector(-1, 4), Vector(0, 2), Vector(0, 0), mass=0.5))
    world.add_force(Gravity((0, -9.81)))
    world.add_force(Spring((0, 1), k=5.0, rest_length=0.5), bodies=[b2])
    world.add_force(Drag(0.3))  # no potential
    kinetic = 0.5 * 2.0 * (9 + 1) + 0.5 * 0.5 * 4
    gravity = 2.0 * 9.81 * 2 + 0.5 * 9.81 * 4  # m g h, y up
    spring = 0.5 * 5.0 * (math.hypot(-1, 3) - 0.5) ** 2
    own = -2.0 * 0.5 * 1  # -m a . x
    assert world.energy() == pytest.approx(kinetic + gravity + spring + own, rel=1e-14)
    assert b1.mass == 2.0


@pytest.mark.parametrize("dt", [0.01, 0.3, 2.0])
def test_the_exact_method_conserves_energy(dt: float) -> None:
    world = World("exact")
    world.add(Body(Vector(0, 10), Vector(3, 20), Vector(0.5, 0.25), mass=2.0))
    world.add(Body(Vector(-5, 0), Vector(-1, 0), Vector(0, 0), mass=0.7))
    world.add_force(Gravity((0, -9.81)))
    e0 = world.energy()
    for _ in range(1000):
        world.step(dt)
        # round-off relative to the size of the terms that cancel
        scale = 0.5 * 2.0 * world.velocities()[0] @ world.velocities()[0] + abs(e0) + 1.0
        assert abs(world.energy() - e0) <= 1e-12 * scale


# -- the closed form, exact over a long run ----------------------------------------------------


@pytest.mark.parametrize("dt", [1 / 60, 0.1, 1.0])
def test_closed_form_world_is_exact_over_100000_steps(dt: float) -> None:
    x0, v0, a = (1.0, -2.0), (3.0, 40.0), (0.5, -9.81)
    world = World("exact")
    body = world.add(Body(Vector(*x0), Vector(*v0), Vector(0, 0)))
    world.add_force(Gravity(a))
    n = 100_000
    for _ in range(n):
        world.step(dt)
    # The truth at t = n dt, in exact rational arithmetic, rounded once.
    t = Fraction(dt) * n
    assert world.t == float(t)  # time counted in whole steps: no drift from adding dt
    for i in range(2):
        fx0, fv0, fa = Fraction(x0[i]), Fraction(v0[i]), Fraction(a[i])
        x_true = float(fx0 + fv0 * t + fa * t * t / 2)
        v_true = float(fv0 + fa * t)
        assert body.pos[i] == pytest.approx(x_true, rel=1e-12)
        assert body.vel[i] == pytest.approx(v_true, rel=1e-12)


def test_auto_picks_the_closed_form_when_every_force_is_constant() -> None:
    world = World("auto")
    ball = world.add(Body(Vector(0, 0), Vector(3, 4), Vector(0, 0)))
    world.add_force(Gravity((0, -10)))
    world.add_force(ConstantForce((1, 0)))
    for _ in range(7):
        world.step(1 / 7)
    assert world.method == "exact"
    assert "constant" in world.method_reason
    assert ball.pos.distance_to((3 + 0.5, 4 - 5)) < 1e-14


def test_auto_picks_semi_implicit_euler_for_a_soft_spring() -> None:
    world = World("auto")
    world.add(Body(1.0, 0.0, 0.0))
    world.add_force(Spring(0.0, k=1.0))  # omega = 1 rad/s
    world.step(1 / 60)
    assert world.method == "semi_implicit_euler"
    assert "stable" in world.method_reason


@pytest.mark.parametrize("k", [1.0, 400.0])
def test_auto_never_picks_a_method_past_its_limit(k: float) -> None:
    # Sweep dt across every limit on a spring (omega = sqrt(k/m)) and on a drag (rate k/m).
    m = 1.0
    omega, rate = math.sqrt(k / m), k / m
    for force, limits, scale in (
        (Spring(0.0, k=k), OSC_LIMIT, omega),
        (Drag(k), DECAY_LIMIT, rate),
    ):
        for y in np.linspace(0.05, 3.5, 71):
            if any(abs(y - lim) < 1e-6 for lim in limits.values()):
                continue  # exactly at a limit "stable" depends on rounding; not sampled
            dt = float(y / scale)
            world = World("auto")
            world.add(Body(1.0, 1.0, 0.0, mass=m))
            world.add_force(force)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                world.step(dt)
            stable = [name for name, lim in limits.items() if y < lim * (1 - 1e-9)]
            unstable_warned = any(issubclass(w.category, StabilityWarning) for w in caught)
            if stable:
                assert world.method in stable, (force, y, world.method)
                assert not unstable_warned
            elif y > max(limits.values()) * (1 + 1e-9):
                # nothing is stable: the widest limit, and a warning saying so
                assert world.method == "rk4" and unstable_warned


# -- warnings and failures ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("method", "force", "dt", "limit"),
    [
        ("semi_implicit_euler", Spring(0.0, k=100.0), 0.25, 0.2),  # omega dt = 2.5 > 2
        ("rk4", Spring(0.0, k=100.0), 0.3, 2 * math.sqrt(2) / 10),  # 3.0 > 2.83
        ("explicit_euler", Drag(10.0), 0.25, 0.2),  # k dt = 2.5 > 2
        ("rk4", Drag(10.0), 0.3, 0.2785293563405282),
    ],
)
def test_stability_warning_comes_once_when_dt_passes_a_limit_and_the_run_goes_on(
    method: str, force: object, dt: float, limit: float
) -> None:
    world = World(method)
    body = world.add(Body(1.0, 1.0, 0.0))
    world.add_force(force)
    with pytest.warns(StabilityWarning, match=rf"{method} is unstable at dt={dt:g} s") as rec:
        world.step(dt)
    assert len([w for w in rec if issubclass(w.category, StabilityWarning)]) == 1
    assert f"stable for dt < {limit:.4g} s" in str(rec[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StabilityWarning)
        for _ in range(4):
            world.step(dt)  # still runs, silently
    assert world.steps == 5 and world.t == pytest.approx(5 * dt)
    assert abs(body.pos) > 1.0 or abs(body.vel) > 1.0  # and it is growing, as warned


def test_no_stability_warning_below_the_limit() -> None:
    world = World("semi_implicit_euler")
    world.add(Body(1.0, 0.0, 0.0))
    world.add_force(Spring(0.0, k=100.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for _ in range(100):
            world.step(0.19)


def test_explicit_euler_on_a_spring_warns_that_no_dt_is_stable() -> None:
    world = World("explicit_euler")
    world.add(Body(1.0, 0.0, 0.0))
    world.add_force(Spring(0.0, k=1.0))
    with pytest.warns(StabilityWarning, match="no dt is stable"):
        world.step(1e-3)


@pytest.mark.parametrize("method", ["semi_implicit_euler", "velocity_verlet", "rk4"])
def test_a_blow_up_raises_simulation_diverged_and_keeps_the_last_finite_state(
    method: str,
) -> None:
    world = World(method)
    stiff = world.add(Body(Vector(1, 0), Vector(0, 0), Vector(0, 0)))
    world.add(Body(Vector(0, 0), Vector(1, 1), Vector(0, 0)))
    world.add(Body(Vector(2, 0), Vector(0, 0), Vector(0, -1)))
    world.add_force(Spring((0, 0), k=100.0), bodies=[stiff])  # omega = 10
    dt = 1.0  # omega dt = 10: far past every limit
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        warnings.simplefilter("error", RuntimeWarning)  # no numpy overflow noise first
        for _ in range(2000):
            before = (world.positions(), world.velocities(), world.t, world.steps)
            try:
                world.step(dt)
            except SimulationDiverged as caught:
                err = caught  # `caught` is unbound when the except block ends
                break
        else:
            pytest.fail("the run never diverged")
    assert err.integrator == method and err.dt == dt
    assert err.max_stable_dt == pytest.approx(OSC_LIMIT[method] / 10, rel=1e-9)
    assert err.t == before[2]
    message = str(err)
    assert method in message and "dt=1 s" in message
    assert f"stable only for dt < {OSC_LIMIT[method] / 10:.4g} s" in message
    x, v = world.positions(), world.velocities()
    assert np.isfinite(x).all() and np.isfinite(v).all()
    assert np.array_equal(x, before[0]) and np.array_equal(v, before[1])
    assert (world.t, world.steps) == before[2:]


def test_explicit_euler_blow_up_says_no_dt_is_stable() -> None:
    world = World("explicit_euler")
    world.add(Body(1.0, 0.0, 0.0))
    world.add_force(Spring(0.0, k=100.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        with pytest.raises(SimulationDiverged, match="unstable at every dt"):
            for _ in range(5000):
                world.step(1.0)


@pytest.mark.parametrize(
    ("bad", "error"),
    [
        (0.0, ValueError),
        (0, ValueError),
        (-0.01, ValueError),
        (math.nan, ValueError),
        (math.inf, ValueError),
        (-math.inf, ValueError),
        (True, TypeError),
        (False, TypeError),
        ("0.01", TypeError),
        (None, TypeError),
    ],
)
def test_step_refuses_a_bad_dt_naming_it_and_changes_nothing(bad: object, error: type) -> None:
    world = World()
    body = world.add(Body(Vector(0, 0), Vector(1, 0), Vector(0, -1)))
    world.step(1.0)  # a previous step of 1.0 s: True == 1.0 must not slip through
    before = (world.t, world.steps, state_hash(world), world.positions(0.0).tobytes())
    with pytest.raises(error, match=r"dt must be a (finite )?number of seconds"):
        world.step(bad)  # type: ignore[arg-type]
    assert (world.t, world.steps, state_hash(world), world.positions(0.0).tobytes()) == before
    assert body.pos == Vector(1, -1)


# -- determinism -------------------------------------------------------------------------------


@pytest.mark.parametrize("method", [*METHODS, "exact", "auto"])
def test_two_identical_runs_end_in_bit_identical_state(method: str) -> None:
    hashes = set()
    for _ in range(2):
        world = busy_world(method)
        for _ in range(300):
            world.step(1 / 120)
        hashes.add(state_hash(world))
    assert len(hashes) == 1


@pytest.mark.parametrize("method", [*METHODS, "exact", "auto"])
def test_snapshot_run_restore_run_is_bit_identical(method: str) -> None:
    world = busy_world(method)
    for _ in range(50):
        world.step(1 / 120)
    snap = world.snapshot()
    t_snap = world.t
    for _ in range(150):
        world.step(1 / 120)
    first = (state_hash(world), world.t, world.steps, world.positions(0.5).tobytes())
    world.restore(snap)
    assert world.t == t_snap and world.steps == 50
    for _ in range(150):
        world.step(1 / 120)
    assert (state_hash(world), world.t, world.steps, world.positions(0.5).tobytes()) == first


def test_restore_brings_back_changed_own_acceleration_and_mass() -> None:
    world = World("exact")
    b = world.add(Body(0.0, 0.0, 1.0, mass=2.0))
    snap = world.snapshot()
    b.own_acc = 5.0
    b.mass = 3.0
    world.step(1.0)
    world.restore(snap)
    assert (b.pos, b.vel, b.own_acc, b.mass, world.t) == (0.0, 0.0, 1.0, 2.0, 0.0)
    world.step(1.0)
    assert (b.pos, b.vel) == (0.5, 1.0)


def test_restore_refuses_a_snapshot_of_a_different_body_count() -> None:
    world = World()
    world.add(Body(0.0, 0.0, 0.0))
    world.add(Body(1.0, 0.0, 0.0))
    snap = world.snapshot()
    world.add(Body(2.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="snapshot holds 2 bodies but this World has 3"):
        world.restore(snap)
    with pytest.raises(TypeError, match="restore takes a WorldSnapshot"):
        world.restore({"x": 1})  # type: ignore[arg-type]


# -- copies ------------------------------------------------------------------------------------


def linked_world() -> World:
    """Two bodies on a rod, one hung from the world by a damped spring, a third on its own
    under a force of its own (a plain callable), gravity; stepped 0.5 s."""
    world = World(integrator="auto")
    world.add_force(Gravity((0, -9.81)))
    a = world.add(Body(Vector(0, 3), mass=1.0))
    b = world.add(Body(Vector(2, 3), Vector(0, 1), mass=2.0))
    c = world.add(Body(Vector(5, 0), Vector(1, 0), mass=1.5))
    world.add_link(Rod(a, b))
    world.add_link(DampedSpring(a, world.static_body, (0, 0), (0, 5), 1.0, 20.0, 0.5))
    world.add_force(lambda t, x, v, m: -x * m, bodies=[c])
    for _ in range(30):
        world.step(1 / 60)
    return world


@pytest.mark.parametrize("how", ["copy.copy", "world.copy", "copy.deepcopy"])
def test_a_copied_world_is_independent_and_steps_as_the_original(how: str) -> None:
    # pymunk's space.copy() is a deep copy; a copy.copy(world) that shared the World's state
    # moved the original's bodies when the copy was stepped.
    world = linked_world()
    copiers: dict[str, Callable[[World], World]] = {
        "copy.copy": copy.copy,
        "world.copy": lambda w: w.copy(),  # pymunk's name
        "copy.deepcopy": copy.deepcopy,
    }
    clone = copiers[how](world)
    assert type(clone) is World and clone is not world
    before = (world.positions().tolist(), world.velocities().tolist(), world.t, world.steps)
    assert (clone.positions().tolist(), clone.velocities().tolist(), clone.t, clone.steps) == (
        before
    )
    assert not {id(b) for b in clone.bodies} & {id(b) for b in world.bodies}
    assert [type(k).__name__ for k in (*clone.links, *clone.springs)] == ["Rod", "DampedSpring"]
    assert len(clone.forces) == 2
    for _ in range(60):
        clone.step(1 / 60)
    after = (world.positions().tolist(), world.velocities().tolist(), world.t, world.steps)
    assert after == before  # the original has not moved
    for _ in range(60):
        world.step(1 / 60)
    # Each steps as the other would, bit for bit.
    assert clone.positions().tolist() == world.positions().tolist()
    assert clone.velocities().tolist() == world.velocities().tolist()


# -- drawing between steps ---------------------------------------------------------------------


def test_positions_blend_the_previous_and_current_state() -> None:
    world = World("exact")
    b = world.add(Body(Vector(0, 0), Vector(2, 0), Vector(0, 0)))
    world.step(1.0)
    assert world.positions(0.0).tolist() == [[0.0, 0.0]]
    assert world.positions(0.25).tolist() == [[0.5, 0.0]]
    assert world.positions().tolist() == [[2.0, 0.0]]
    assert world.position_of(b, 0.5) == Vector(1, 0)
    for bad in (-0.1, 1.5, math.nan, "0.5"):
        with pytest.raises(ValueError, match="alpha must be a number in"):
            world.positions(bad)  # type: ignore[arg-type]


# -- refusals ----------------------------------------------------------------------------------


def test_world_refuses_unknown_integrators_and_non_bodies() -> None:
    with pytest.raises(ValueError, match="unknown integrator 'euler'.*rk4.*exact.*auto"):
        World("euler")
    with pytest.raises(TypeError, match="integrator must be a name"):
        World(42)  # type: ignore[arg-type]
    world = World()
    with pytest.raises(TypeError, match="World.add takes a Body"):
        world.add((0, 0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="force must be a Force"):
        world.add_force(42)  # type: ignore[arg-type]


def test_a_body_can_be_in_one_world_once() -> None:
    w1, w2 = World(), World()
    b = w1.add(Body(0.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="already in this World"):
        w1.add(b)
    with pytest.raises(ValueError, match="already in another World"):
        w2.add(b)
    with pytest.raises(ValueError, match="bodies must be bodies already added to this World"):
        w2.add_force(Gravity(-1.0), bodies=[b])


def test_exact_refuses_a_force_that_is_not_constant() -> None:
    world = World("exact")
    world.add(Body(0.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="'exact'.*needs constant forces"):
        world.add_force(Spring(0.0, k=1.0))
    assert world.forces == ()
