"""Stability limits, found by running each integrator, against the theory and engine.stability."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine.integrators import INTEGRATORS, explicit_euler, get_integrator
from engine.stability import (
    DECAY_LIMITS,
    OSCILLATION_LIMITS,
    SimulationDiverged,
    StabilityWarning,
    is_stable,
    max_stable_dt,
    spectral_radius,
)

# The theory, independent of the engine's tables.
# RK4 on v' = -k v multiplies v by R(-z) = 1 - z + z^2/2 - z^3/6 + z^4/24 (z = k dt); the
# limit is where R(-z) comes back up to 1 for z > 0, i.e. z^3 - 4 z^2 + 12 z - 24 = 0.
_roots = np.roots([1.0, -4.0, 12.0, -24.0])
RK4_DECAY = float(next(r.real for r in _roots if abs(r.imag) < 1e-12))
THEORY_OSCILLATION = {
    "semi_implicit_euler": 2.0,
    "velocity_verlet": 2.0,
    "rk4": 2.0 * math.sqrt(2.0),
}
THEORY_DECAY = {
    "explicit_euler": 2.0,
    "semi_implicit_euler": 2.0,
    "velocity_verlet": 2.0,
    "rk4": RK4_DECAY,
}


def find_limit(unstable: Callable[[float], bool], lo: float, hi: float, iters: int = 26) -> float:
    """Bisection on dt: the boundary between stable runs (below) and growing runs (above).

    Returns 0.0 when the run grows even at ``lo``: no dt is stable.
    """
    assert unstable(hi), "the upper end of the bracket must be unstable"
    if unstable(lo):
        return 0.0
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        if unstable(mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def oscillator_grows(name: str, omega: float, steps: int, factor: float) -> Callable[[float], bool]:
    """Run x'' = -omega^2 x from (1, 0) for ``steps`` steps: does |x| or |v|/omega pass ``factor``?

    A stable symplectic method keeps the state on an ellipse that stretches as omega dt
    nears 2 (by 1/sqrt(1 - (omega dt / 2)^2)), so ``factor`` must be far above that
    stretch and far below what a growing run reaches in ``steps`` steps.
    """
    step = get_integrator(name)
    w2 = omega * omega

    def accel(t: float, x: float, v: float) -> float:
        return -w2 * x

    def unstable(dt: float) -> bool:
        x, v = 1.0, 0.0
        for i in range(steps):
            x, v = step(x, v, accel, i * dt, dt)
            if not (abs(x) < factor and abs(v) < factor * omega):
                return True
        return False

    return unstable


def decay_grows(name: str, k: float, steps: int, factor: float) -> Callable[[float], bool]:
    """Run v' = -k v from v = 1: does |v| pass ``factor``? (|v_n| = |R|^n exactly.)"""
    step = get_integrator(name)

    def accel(t: float, x: float, v: float) -> float:
        return -k * v

    def unstable(dt: float) -> bool:
        x, v = 0.0, 1.0
        for i in range(steps):
            x, v = step(x, v, accel, i * dt, dt)
            if not abs(v) < factor:
                return True
        return False

    return unstable


# -- limits found by running the methods -------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "steps", "factor"),
    [
        # Growing just past the limit: semi-implicit Euler / Verlet multiply by
        # ~1 + 2.8 sqrt(delta) a step, so 2000 steps pass 1e6 for delta > 1e-5.
        ("semi_implicit_euler", 2000, 1e6),
        ("velocity_verlet", 2000, 1e6),
        # RK4 has no stretched ellipse (it shrinks the state below its limit); |R| grows
        # like 1 + 2.5 delta past it, so 3000 steps pass 1e3 for delta > 1e-3 * 2.83 / 3.
        ("rk4", 3000, 1e3),
    ],
)
def test_oscillator_limit_found_by_bisection_matches_theory(
    name: str, steps: int, factor: float
) -> None:
    omega = 3.0
    limit = find_limit(oscillator_grows(name, omega, steps, factor), 1e-3 / omega, 10.0 / omega)
    assert omega * limit == pytest.approx(THEORY_OSCILLATION[name], rel=0.005)
    print(f"{name}: oscillator omega*dt limit found {omega * limit:.5f}")


def test_explicit_euler_is_unstable_on_the_oscillator_at_every_dt() -> None:
    # Its energy is multiplied by 1 + (omega dt)^2 > 1 every step, so "grows" here means
    # the energy rises at every one of 300 steps (a stable method's energy cannot: it is
    # bounded, or for RK4 falls). Bisection then finds no stable dt at all, down to 1e-6.
    omega = 3.0

    def energy_rises_every_step(dt: float) -> bool:
        x, v = 1.0, 0.0
        e = 0.5 * (v * v + omega * omega * x * x)
        for i in range(300):
            x, v = explicit_euler(x, v, lambda t, x, v: -omega * omega * x, i * dt, dt)
            e_new = 0.5 * (v * v + omega * omega * x * x)
            if e_new > 1e200:
                return True  # it rose at every step until it (nearly) overflowed
            if not e_new > e:
                return False
            e = e_new
        return True

    assert find_limit(energy_rises_every_step, 1e-6, 1.0) == 0.0
    for dt in np.geomspace(1e-6, 10.0, 15):
        assert energy_rises_every_step(float(dt))
    # The same criterion does not call a stable method unstable.
    for name in ("semi_implicit_euler", "velocity_verlet", "rk4"):
        step = get_integrator(name)
        x, v = 1.0, 0.0
        energies = []
        for i in range(300):
            x, v = step(x, v, lambda t, x, v: -omega * omega * x, i * 0.01, 0.01)
            energies.append(0.5 * (v * v + omega * omega * x * x))
        assert not all(b > a for a, b in zip(energies, energies[1:], strict=False)), name


@pytest.mark.parametrize("name", list(INTEGRATORS))
def test_drag_limit_found_by_bisection_matches_theory(name: str) -> None:
    # |v| is multiplied by exactly |R(k dt)| each step; 4000 steps pass a factor 10 for
    # |R| > 1 + 6e-4, so the boundary is found to well under 0.1%.
    k = 0.5
    limit = find_limit(decay_grows(name, k, 4000, 10.0), 1e-3 / k, 10.0 / k)
    assert k * limit == pytest.approx(THEORY_DECAY[name], rel=0.005)
    print(f"{name}: drag k*dt limit found {k * limit:.5f}")


# -- engine.stability agrees with theory -------------------------------------------------------


def test_tables_agree_with_theory() -> None:
    assert OSCILLATION_LIMITS["explicit_euler"] == 0.0
    for name, limit in THEORY_OSCILLATION.items():
        assert OSCILLATION_LIMITS[name] == pytest.approx(limit, rel=1e-12)
    for name, limit in THEORY_DECAY.items():
        assert DECAY_LIMITS[name] == pytest.approx(limit, rel=1e-12)
    assert RK4_DECAY == pytest.approx(2.785, abs=5e-4)


@pytest.mark.parametrize("omega", [0.1, 1.0, 7.0])
def test_max_stable_dt_agrees_with_theory_on_the_oscillator(omega: float) -> None:
    assert max_stable_dt("explicit_euler", omega=omega) == 0.0
    for name, limit in THEORY_OSCILLATION.items():
        assert max_stable_dt(name, omega=omega) == pytest.approx(limit / omega, rel=1e-9)


@pytest.mark.parametrize("rate", [0.2, 1.0, 50.0])
def test_max_stable_dt_agrees_with_theory_on_drag(rate: float) -> None:
    for name, limit in THEORY_DECAY.items():
        assert max_stable_dt(name, damping_rate=rate) == pytest.approx(limit / rate, rel=1e-9)


def test_max_stable_dt_is_infinite_with_nothing_to_limit_it() -> None:
    assert max_stable_dt("rk4") == math.inf
    assert max_stable_dt("explicit_euler", omega=0.0, damping_rate=0.0) == math.inf


def test_spectral_radius_matches_the_known_amplification() -> None:
    for y in (0.01, 0.5, 1.0, 3.0):
        assert spectral_radius("explicit_euler", 1.0, 0.0, y) == pytest.approx(
            math.sqrt(1 + y * y), rel=1e-12
        )
    # Symplectic methods below their limit sit exactly on the unit circle (det = 1).
    for y in (0.1, 1.0, 1.99):
        assert spectral_radius("semi_implicit_euler", 1.0, 0.0, y) == pytest.approx(1.0, abs=1e-12)
        assert is_stable("velocity_verlet", 1.0, 0.0, y)
    assert not is_stable("velocity_verlet", 1.0, 0.0, 2.01)
    assert spectral_radius("explicit_euler", 0.0, 1.0, 2.5) == pytest.approx(1.5)


# -- explicit Euler's energy growth, exactly ---------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(
    omega=st.floats(0.1, 10.0),
    dt=st.floats(1e-4, 1.0),
    x0=st.floats(-5.0, 5.0),
    v0=st.floats(-5.0, 5.0),
)
def test_explicit_euler_multiplies_energy_by_exactly_1_plus_omega_dt_squared(
    omega: float, dt: float, x0: float, v0: float
) -> None:
    # x1 = x + v h, v1 = v - w^2 x h  =>  v1^2 + w^2 x1^2 = (1 + w^2 h^2)(v^2 + w^2 x^2):
    # the cross terms cancel, so the factor is exact, step after step.
    if x0 == 0.0 and v0 == 0.0:
        x0 = 1.0
    w2 = omega * omega

    def energy(x: float, v: float) -> float:
        return 0.5 * (v * v + w2 * x * x)

    factor = 1.0 + (omega * dt) ** 2
    x, v = x0, v0
    for i in range(20):
        e = energy(x, v)
        x, v = explicit_euler(x, v, lambda t, x, v: -w2 * x, i * dt, dt)
        assert energy(x, v) == pytest.approx(e * factor, rel=1e-12)


# -- what the World raises and warns with ------------------------------------------------------


def test_stability_errors_are_our_own_types_carrying_what_happened() -> None:
    assert issubclass(StabilityWarning, UserWarning)
    assert issubclass(SimulationDiverged, ArithmeticError)
    err = SimulationDiverged("boom", integrator="rk4", dt=0.5, t=1.0, max_stable_dt=0.25)
    assert (err.integrator, err.dt, err.t, err.max_stable_dt) == ("rk4", 0.5, 1.0, 0.25)
    assert str(err) == "boom"
