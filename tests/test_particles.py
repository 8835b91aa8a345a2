"""Many particles (engine.particles): physics against exact answers, bookkeeping, bad input."""

from __future__ import annotations

import math
import tracemalloc
import warnings

import numpy as np
import pytest

from engine import kinematics
from engine.forces import ConstantForce, Drag, Gravity, Spring, Wind
from engine.particles import Particles
from engine.stability import StabilityWarning

G = (0.0, -9.81)


def fan(n: int) -> np.ndarray:
    """n distinct launch velocities (m/s) spread over a half circle."""
    angle = np.linspace(0.1, math.pi - 0.1, n)
    speed = np.linspace(5.0, 25.0, n)
    return np.column_stack((speed * np.cos(angle), speed * np.sin(angle)))


# ------------------------------------------------------------------ physics


def test_spark_under_gravity_matches_closed_form_plus_semi_implicit_lead() -> None:
    # Under constant a, semi-implicit Euler's velocity is exact and its position leads the
    # closed form by exactly a T h / 2 (it moves each step at the velocity at the step's end).
    dt, steps = 1 / 60, 600
    p = Particles(50, dt=dt, forces=[Gravity(G)])
    assert p.uses_fast_path
    x0, v0 = np.array([1.0, 2.0]), fan(50)
    p.emit(50, x0, v0)
    p.run(steps)
    T = steps * dt
    a = np.array(G)
    exact_x = kinematics.position(x0, v0, a, T)
    np.testing.assert_allclose(p.velocities, kinematics.velocity(v0, a, T), rtol=0, atol=1e-10)
    np.testing.assert_allclose(p.positions - exact_x, np.tile(a * T * dt / 2, (50, 1)), atol=1e-9)


@pytest.mark.parametrize("integrator", ["velocity_verlet", "rk4"])
def test_spark_under_gravity_is_exact_with_second_order_methods(integrator: str) -> None:
    dt, steps = 0.01, 300
    p = Particles(20, dt=dt, forces=[Gravity(G)], integrator=integrator)
    assert not p.uses_fast_path
    v0 = fan(20)
    p.emit(20, (0.0, 0.0), v0)
    p.run(steps)
    T = steps * dt
    np.testing.assert_allclose(p.positions, kinematics.position(0.0, v0, np.array(G), T), atol=1e-9)


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "rk4"])
def test_spark_in_wind_tends_to_terminal_velocity(integrator: str) -> None:
    # m v' = m g - k (v - air) = 0  at  v = air + g m / k. It is also the exact fixed
    # point of the discrete schemes, so after many time constants m/k the velocity is there.
    air, k, m, dt = (3.0, 1.0), 0.5, 2.0, 1 / 30
    p = Particles(10, dt=dt, forces=[Gravity(G), Wind(air, k)], mass=m, integrator=integrator)
    p.emit(10, (0.0, 100.0), fan(10))
    p.run(round(30 * (m / k) / dt))  # 30 time constants: e^-30 ~ 1e-13
    terminal = np.array(air) + np.array(G) * m / k
    np.testing.assert_allclose(p.velocities, np.tile(terminal, (10, 1)), atol=1e-9)


def test_fast_path_equals_general_path_with_gusty_wind_and_drag() -> None:
    def gust(t: float) -> tuple[float, float]:
        return (4.0 * math.sin(0.7 * t), 0.5 * math.cos(1.3 * t))

    def build(fast: bool) -> Particles:
        forces = [Gravity(G), Drag(0.1), Wind(gust, 0.3), ConstantForce((0.2, 0.0))]
        p = Particles(64, dt=1 / 120, forces=forces, mass=0.5, fast_path=fast)
        p.emit(64, (0.0, 0.0), fan(64), lifetime=np.linspace(0.5, 3.0, 64))
        return p

    fast, general = build(True), build(False)
    assert fast.uses_fast_path and not general.uses_fast_path
    for _ in range(240):
        assert fast.step() == general.step()
        np.testing.assert_array_equal(fast.ids, general.ids)
    np.testing.assert_allclose(fast.positions, general.positions, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(fast.velocities, general.velocities, rtol=1e-11, atol=1e-11)


def test_general_path_takes_any_force() -> None:
    # A spring to the origin: x'' = -omega^2 x. Semi-implicit Euler keeps the
    # "modified energy" bounded; over a few periods the swing stays the same size.
    p = Particles(4, dt=0.01, forces=[Spring((0.0, 0.0), 4.0)])
    assert not p.uses_fast_path
    p.emit(4, [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)])
    p.run(int(2 * math.pi / 2.0 / 0.01) * 3)  # about three periods of omega = 2 rad/s
    radius = np.hypot(*p.positions.T)
    np.testing.assert_allclose(radius, 1.0, atol=0.02)


def test_expired_particles_are_reported_as_they_were() -> None:
    dt = 0.1
    p = Particles(8, dt=dt, forces=[Gravity(G)])
    p.emit(4, (0.0, 0.0), (1.0, 10.0), lifetime=0.35, kind=3)  # lives ceil(3.5) = 4 steps
    p.emit(4, (0.0, 0.0), (2.0, 10.0), lifetime=10.0, kind=1)
    assert [p.step() for _ in range(3)] == [0, 0, 0]
    x_before = p.positions[p.kinds == 3].copy()
    v_before = p.velocities[p.kinds == 3]
    assert p.step() == 4
    gone = p.expired
    assert sorted(gone.ids.tolist()) == [0, 1, 2, 3]
    assert (gone.kinds == 3).all()
    # The reported state is the state after the step in which they expired.
    np.testing.assert_allclose(gone.velocities, v_before + np.array(G) * dt, atol=1e-12)
    np.testing.assert_allclose(gone.positions, x_before + gone.velocities * dt, atol=1e-12)
    assert sorted(p.ids.tolist()) == [4, 5, 6, 7] and len(p) == 4
    p.step()
    assert len(p.expired.ids) == 0


def test_positions_at_alpha_blends_previous_and_current() -> None:
    p = Particles(3, dt=0.05, forces=[Gravity(G)])
    p.emit(3, (0.0, 0.0), fan(3))
    p.step()
    before = p.positions.copy()
    p.step()
    np.testing.assert_allclose(p.positions_at(0.0), before, atol=1e-12)
    np.testing.assert_allclose(p.positions_at(1.0), p.positions, atol=0)
    np.testing.assert_allclose(p.positions_at(0.25), 0.75 * before + 0.25 * p.positions)


# ------------------------------------------------------------- bookkeeping


def test_count_ages_and_alive_set_stay_consistent_over_10_000_steps() -> None:
    rng = np.random.default_rng(1)
    dt = 1 / 100
    p = Particles(300, dt=dt, forces=[Gravity(G), Wind((2.0, 0.0), 0.2)])
    born: dict[int, tuple[int, float]] = {}  # id -> (birth step, lifetime): an independent model
    next_id = 0
    for step in range(10_000):
        want = int(rng.integers(0, 6))
        life = rng.uniform(0.05, 2.0, want)
        got = p.emit(want, (0.0, 0.0), rng.normal(0.0, 5.0, (want, 2)), lifetime=life)
        assert got == min(want, 300 - len(born))
        for i in range(got):
            born[next_id + i] = (step, float(life[i]))
        next_id += got
        if step % 97 == 0 and len(p):  # kill some by hand, as a scene would
            victims = p.ids[::5].tolist()
            assert p.kill(np.arange(0, len(p), 5)) == len(victims)
            for i in victims:
                del born[i]
        expired = p.step()
        # The model: a particle expires at the first step where age >= lifetime.
        dead = [i for i, (b, life_i) in born.items() if (step + 1 - b) * dt >= life_i - 1e-9]
        assert sorted(p.expired.ids.tolist()) == sorted(dead)
        assert expired == len(dead)
        for i in dead:
            del born[i]
        assert len(p) == len(born) <= p.capacity
        if step % 250 == 0:
            assert sorted(p.ids.tolist()) == sorted(born)
            order = np.argsort(p.ids)
            ages = np.array([(step + 1 - born[i][0]) * dt for i in sorted(born)])
            np.testing.assert_allclose(p.ages[order], ages, atol=1e-9)
            assert (p.ages < p.lifetimes).all() and (p.ages >= dt - 1e-12).all()
    assert p.emitted == next_id
    assert p.steps == 10_000 and p.t == pytest.approx(100.0, abs=1e-9)


def test_capacity_is_never_exceeded_and_the_emitter_says_when_full() -> None:
    p = Particles(10, forces=[Gravity(G)])
    assert p.emit(6, (0, 0), lifetime=1.0) == 6
    assert not p.full and p.dropped == 0
    assert p.emit(7, (0, 0), lifetime=1.0) == 4
    assert p.full and len(p) == 10 and p.dropped == 3
    assert p.emit(5, (0, 0)) == 0
    assert p.dropped == 8 and len(p) == 10 and p.emitted == 10
    p.run(int(1.0 / p.dt) + 1)
    assert len(p) == 0 and not p.full
    assert p.emit(10, (0, 0)) == 10


def test_the_first_of_a_partly_emitted_batch_are_kept() -> None:
    p = Particles(3)
    p.emit(5, np.arange(10.0).reshape(5, 2), lifetime=np.arange(1.0, 6.0), kind=np.arange(5))
    assert p.kinds.tolist() == [0, 1, 2]
    assert p.positions.tolist() == [[0, 1], [2, 3], [4, 5]]
    assert p.lifetimes.tolist() == [1.0, 2.0, 3.0]


def test_memory_stays_flat_over_a_long_run() -> None:
    p = Particles(2000, dt=1 / 60, forces=[Gravity(G), Wind((1.0, 0.0), 0.3)])
    rng = np.random.default_rng(0)

    def churn(steps: int) -> None:
        for _ in range(steps):
            p.emit(40, (0.0, 0.0), rng.normal(0, 3, (40, 2)), rng.uniform(0.2, 1.0, 40))
            p.step()
            p.kill(p.positions[:, 1] < -3.0)

    churn(200)
    tracemalloc.start()
    churn(50)
    base, _ = tracemalloc.get_traced_memory()
    churn(2000)
    now, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert now - base < 50_000  # bytes: nothing grows with the number of steps
    assert peak - base < 500_000  # and no step allocates anything like the arrays


def test_positions_view_is_read_only() -> None:
    p = Particles(2)
    p.emit(2, (0, 0))
    with pytest.raises(ValueError):
        p.positions[0, 0] = 5.0


def test_stability_warning_when_drag_is_too_stiff_for_dt() -> None:
    with pytest.warns(StabilityWarning, match="dt"):
        Particles(4, dt=0.5, forces=[Drag(5.0)], mass=1.0)  # k dt / m = 2.5 > 2
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Particles(4, dt=0.1, forces=[Drag(5.0)], mass=1.0)


# --------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("kwargs", "error", "words"),
    [
        ({"capacity": -1}, ValueError, ["capacity", "-1", ">= 1"]),
        ({"capacity": 0}, ValueError, ["capacity", "0", ">= 1"]),
        ({"capacity": 2.5}, TypeError, ["capacity", "2.5", "int"]),
        ({"capacity": 5, "dt": 0}, ValueError, ["dt", "0", "> 0"]),
        ({"capacity": 5, "mass": -1}, ValueError, ["mass", "-1", "> 0"]),
        ({"capacity": 5, "integrator": "leapfrog"}, ValueError, ["leapfrog", "rk4"]),
    ],
)
def test_bad_construction_names_the_argument(kwargs: dict, error: type, words: list[str]) -> None:
    with pytest.raises(error) as info:
        Particles(**kwargs)
    for word in words:
        assert word in str(info.value)


@pytest.mark.parametrize(
    ("args", "error", "words"),
    [
        ((-3, (0, 0)), ValueError, ["count", "-3", ">= 0"]),
        (("3", (0, 0)), TypeError, ["count", "'3'", "int"]),
        ((2, (0, 0), (0, 0), -1.0), ValueError, ["lifetime", "-1", "> 0"]),
        ((2, (0, 0), (0, 0), 0.0), ValueError, ["lifetime", "0", "> 0"]),
        ((2, (0, 0), (0, 0), [1.0, math.nan]), ValueError, ["lifetime", "nan"]),
        ((2, (0, 0), (0, 0), "long"), TypeError, ["lifetime", "'long'"]),
        ((2, (0, 0, 0)), ValueError, ["position", "(2, 2)", "(3,)"]),
        ((2, "here"), TypeError, ["position", "'here'"]),
        ((2, (0, 0), (math.inf, 0)), ValueError, ["velocity", "finite"]),
        ((2, (0, 0), (0, 0), 1.0, -1), ValueError, ["kind", "-1", ">= 0"]),
        ((2, (0, 0), (0, 0), 1.0, 1.5), TypeError, ["kind", "1.5", "int"]),
    ],
)
def test_bad_emit_names_the_argument(args: tuple, error: type, words: list[str]) -> None:
    p = Particles(5)
    with pytest.raises(error) as info:
        p.emit(*args)
    for word in words:
        assert word in str(info.value)
    assert len(p) == 0 and p.emitted == 0


def test_wind_that_is_not_a_vector_is_refused() -> None:
    with pytest.raises(TypeError, match="air_velocity"):
        Particles(5, forces=[Wind("east", 1.0)])
    with pytest.raises(ValueError, match="1D.*particles are 2D"):
        Particles(5, forces=[Wind(3.0, 1.0)])
    with pytest.raises(TypeError, match="force"):
        Particles(5, forces=[42])


def test_kill_refuses_a_mask_of_the_wrong_length() -> None:
    p = Particles(5)
    p.emit(3, (0, 0))
    with pytest.raises(ValueError, match=r"which.*\(3,\)"):
        p.kill(np.ones(5, dtype=bool))
    with pytest.raises(ValueError, match="which"):
        p.kill([7])
