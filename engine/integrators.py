"""Numerical integrators: one signature, any state.

Every integrator here is a plain function

    step(x, v, accel, t, dt) -> (x_new, v_new)

where ``x`` is position, ``v`` velocity, ``t`` the time (s) at the start of the
step, ``dt`` the step (s), and ``accel(t, x, v)`` returns the acceleration. The
functions use only ``+``, ``-`` and multiplication by a float, so the same code
advances a float (Alfred on his tube), a Vector (Alfred on his paper) or numpy
arrays of many bodies. They return new objects and never modify their inputs.

The lesson derives v = integral of a dt and s = integral of v dt (section 3.2.3).
Over one small step dt the integrals are approximated; what differs between
methods is *which* velocity and acceleration stand in for the whole step:

================== ============ ============================ ===========================
method             order        oscillator (omega dt) limit  decay (k dt) limit
================== ============ ============================ ===========================
explicit_euler     1            unstable for every dt        2 (no sign flip below 1)
semi_implicit_euler 1           2                            2
velocity_verlet    2            2                            2
rk4                4            2 sqrt(2) = 2.828            2.785
================== ============ ============================ ===========================

"Order p" means the error after a fixed time T shrinks like dt^p: halving dt
divides it by 2, 2, 4 and 16. ``engine.stability`` holds the limits and
checks them numerically.

>>> explicit_euler(0.0, 1.0, lambda t, x, v: 1.0, 0.0, 1.0)
(1.0, 2.0)
>>> semi_implicit_euler(0.0, 1.0, lambda t, x, v: 1.0, 0.0, 1.0)
(2.0, 2.0)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol, TypeVar

__all__ = [
    "Integrator",
    "explicit_euler",
    "semi_implicit_euler",
    "velocity_verlet",
    "rk4",
    "INTEGRATORS",
    "get_integrator",
]

S = TypeVar("S")
Accel = Callable[[float, Any, Any], Any]


class Integrator(Protocol):
    """``step(x, v, accel, t, dt) -> (x_new, v_new)``, with ``.order`` and ``.evaluations``."""

    __name__: str
    order: int
    evaluations: int

    def __call__(self, x: Any, v: Any, accel: Accel, t: float, dt: float) -> tuple[Any, Any]: ...


def _describe(order: int, evaluations: int) -> Callable[[Callable[..., Any]], Any]:
    def mark(fn: Callable[..., Any]) -> Any:
        fn.order = order  # type: ignore[attr-defined]
        fn.evaluations = evaluations  # type: ignore[attr-defined]
        return fn

    return mark


@_describe(order=1, evaluations=1)
def explicit_euler(x: Any, v: Any, accel: Accel, t: float, dt: float) -> tuple[Any, Any]:
    """Explicit (forward) Euler: position first, with the OLD velocity; then velocity.

        x_{n+1} = x_n + v_n dt
        v_{n+1} = v_n + a(t_n, x_n, v_n) dt

    Order 1. On an oscillator it multiplies the energy by exactly 1 + (omega dt)^2
    every step, so it is unstable for every dt; on a linear drag k it is stable for
    k dt < 2. Under constant acceleration a its position lags the truth by a T dt / 2.
    """
    a = accel(t, x, v)
    return x + v * dt, v + a * dt


@_describe(order=1, evaluations=1)
def semi_implicit_euler(x: Any, v: Any, accel: Accel, t: float, dt: float) -> tuple[Any, Any]:
    """Semi-implicit (symplectic) Euler: velocity first; then position with the NEW velocity.

        v_{n+1} = v_n + a(t_n, x_n, v_n) dt
        x_{n+1} = x_n + v_{n+1} dt

    Order 1, but symplectic: on an oscillator its energy stays bounded for
    omega dt < 2. On linear drag k it is stable for k dt < 2. Under constant
    acceleration a its position leads the truth by a T dt / 2: this is the
    lesson's "Alfred reaches the end in 4 s" (0, 1, 3, 6, 10 inches at dt = 1 s).
    """
    a = accel(t, x, v)
    v_new = v + a * dt
    return x + v_new * dt, v_new


@_describe(order=2, evaluations=2)
def velocity_verlet(x: Any, v: Any, accel: Accel, t: float, dt: float) -> tuple[Any, Any]:
    """Velocity Verlet: position from the Taylor series, velocity from the mean acceleration.

        x_{n+1} = x_n + v_n dt + a_n dt^2 / 2
        a_{n+1} = a(t_n + dt, x_{n+1}, v_n + a_n dt)
        v_{n+1} = v_n + (a_n + a_{n+1}) dt / 2

    Order 2, symplectic for forces of position alone; stable on an oscillator for
    omega dt < 2. Exact under constant acceleration. The velocity handed to the
    second evaluation is the Euler prediction v_n + a_n dt, which keeps the method
    second order when the force also depends on velocity (drag).
    """
    a0 = accel(t, x, v)
    x_new = x + v * dt + a0 * (0.5 * dt * dt)
    a1 = accel(t + dt, x_new, v + a0 * dt)
    return x_new, v + (a0 + a1) * (0.5 * dt)


@_describe(order=4, evaluations=4)
def rk4(x: Any, v: Any, accel: Accel, t: float, dt: float) -> tuple[Any, Any]:
    """Classical Runge-Kutta: four slopes across the step, weighted 1, 2, 2, 1.

    For the state (x, v) with x' = v, v' = a(t, x, v):

        k1 = (v,               a(t,        x,              v))
        k2 = (v + k1_v dt/2,   a(t + dt/2, x + k1_x dt/2,  v + k1_v dt/2))
        k3 = (v + k2_v dt/2,   a(t + dt/2, x + k2_x dt/2,  v + k2_v dt/2))
        k4 = (v + k3_v dt,     a(t + dt,   x + k3_x dt,    v + k3_v dt))
        (x, v)_{n+1} = (x, v)_n + (k1 + 2 k2 + 2 k3 + k4) dt / 6

    Order 4. On an oscillator it is stable for omega dt < 2 sqrt(2) (energy decays
    slowly below that); on linear drag k for k dt < 2.785. Exact under constant
    acceleration.
    """
    h = 0.5 * dt
    k1x, k1v = v, accel(t, x, v)
    k2x = v + k1v * h
    k2v = accel(t + h, x + k1x * h, k2x)
    k3x = v + k2v * h
    k3v = accel(t + h, x + k2x * h, k3x)
    k4x = v + k3v * dt
    k4v = accel(t + dt, x + k3x * dt, k4x)
    sixth = dt / 6.0
    x_new = x + (k1x + (k2x + k3x) * 2.0 + k4x) * sixth
    v_new = v + (k1v + (k2v + k3v) * 2.0 + k4v) * sixth
    return x_new, v_new


#: The integrators by name, cheapest first.
INTEGRATORS: dict[str, Integrator] = {
    "explicit_euler": explicit_euler,
    "semi_implicit_euler": semi_implicit_euler,
    "velocity_verlet": velocity_verlet,
    "rk4": rk4,
}


def get_integrator(name: str) -> Integrator:
    """The integrator registered as ``name``; ValueError listing the valid names otherwise."""
    if not isinstance(name, str):
        raise TypeError(f"integrator name must be a str, got {type(name).__name__} {name!r}")
    try:
        return INTEGRATORS[name]
    except KeyError:
        valid = ", ".join(INTEGRATORS)
        raise ValueError(f"unknown integrator {name!r}; valid names: {valid}") from None
