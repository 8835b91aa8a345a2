"""Where each integrator fails, known in advance and checked as the World runs.

The test problem of all linear stability theory is the damped oscillator

    x'' = -omega^2 x - c x'          (omega in rad/s, c = damping / mass in 1/s)

A one-step method applied to it maps the state (x, v) to M (x, v) with a 2x2
matrix M that depends only on omega dt and c dt. The method is stable when
the spectral radius of M (its largest |eigenvalue|) is at most 1; above 1
every step multiplies the error, and the state blows up to inf and nan.

This module finds M by running the integrator itself on the two basis
states, so it works for any integrator with the common signature, and its
answers can be checked against the theory:

=================== ====================== ==================
integrator          oscillator omega dt <  decay c dt <
=================== ====================== ==================
explicit_euler      0 (never stable)       2
semi_implicit_euler 2                      2
velocity_verlet     2                      2
rk4                 2 sqrt(2) ~ 2.828      2.785
=================== ====================== ==================

>>> round(max_stable_dt("semi_implicit_euler", omega=1.0), 6)
2.0
>>> round(max_stable_dt("rk4", damping_rate=1.0), 3)
2.785
>>> max_stable_dt("explicit_euler", omega=1.0)
0.0
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from typing import Any

from .integrators import get_integrator

__all__ = [
    "StabilityWarning",
    "SimulationDiverged",
    "OSCILLATION_LIMITS",
    "DECAY_LIMITS",
    "amplification_matrix",
    "spectral_radius",
    "is_stable",
    "max_stable_dt",
]

#: omega dt limit on an undamped oscillator; 0.0 means unstable at every dt.
OSCILLATION_LIMITS: dict[str, float] = {
    "explicit_euler": 0.0,
    "semi_implicit_euler": 2.0,
    "velocity_verlet": 2.0,
    "rk4": 2.0 * math.sqrt(2.0),
}

#: c dt limit on linear decay v' = -c v. RK4's is the real root of
#: 1 - z + z^2/2 - z^3/6 + z^4/24 = 1, i.e. z^3 - 4 z^2 + 12 z - 24 = 0.
DECAY_LIMITS: dict[str, float] = {
    "explicit_euler": 2.0,
    "semi_implicit_euler": 2.0,
    "velocity_verlet": 2.0,
    "rk4": 2.785293563405282,
}

# A spectral radius this close to 1 counts as 1: symplectic methods sit exactly on
# the unit circle below their limit, and round-off must not call that unstable.
_RADIUS_TOLERANCE = 1e-12
# Eigenvalues this close to -1 together mark the limit itself (round-off keeps them apart).
_AT_LIMIT = 1e-7


class StabilityWarning(UserWarning):
    """The time step is past an integrator's stability limit for a force in the World."""


class SimulationDiverged(ArithmeticError):
    """A step produced a non-finite state; the World kept the last finite one.

    ``integrator``, ``dt`` (s), ``t`` (s) and ``max_stable_dt`` (s, or None when
    unknown) say what happened and what would be stable.
    """

    def __init__(
        self, message: str, *, integrator: str, dt: float, t: float, max_stable_dt: float | None
    ) -> None:
        super().__init__(message)
        self.integrator = integrator
        self.dt = dt
        self.t = t
        self.max_stable_dt = max_stable_dt


def _resolve(integrator: str | Callable[..., Any]) -> Callable[..., Any]:
    return get_integrator(integrator) if isinstance(integrator, str) else integrator


def amplification_matrix(
    integrator: str | Callable[..., Any], omega: float, damping_rate: float, dt: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The matrix M with (x, v)_{n+1} = M (x, v)_n for x'' = -omega^2 x - c x'.

    Found by stepping the basis states (1, 0) and (0, 1): the method is linear on a
    linear problem, so the two results are the columns of M.
    """
    step = _resolve(integrator)
    w2, c = omega * omega, damping_rate

    def accel(t: float, x: float, v: float) -> float:
        return -w2 * x - c * v

    x1, v1 = step(1.0, 0.0, accel, 0.0, dt)
    x2, v2 = step(0.0, 1.0, accel, 0.0, dt)
    return ((x1, x2), (v1, v2))


def _eigenvalues(
    integrator: str | Callable[..., Any], omega: float, damping_rate: float, dt: float
) -> tuple[complex, complex] | None:
    """The two eigenvalues of the amplification matrix, or None when it is not finite."""
    (a, b), (c, d) = amplification_matrix(integrator, omega, damping_rate, dt)
    if not all(math.isfinite(e) for e in (a, b, c, d)):
        return None
    # Eigenvalues of a 2x2 matrix: tr/2 +- sqrt(tr^2/4 - det). The discriminant is
    # computed as ((a - d)/2)^2 + b c, which is the same number without the cancellation
    # of tr^2/4 - det when the eigenvalues are nearly equal (RK4 on drag near its limit has
    # eigenvalues 1 and R -> 1; the cancelled form put max_stable_dt off by ~3e-5).
    half_trace = 0.5 * (a + d)
    half_diff = 0.5 * (a - d)
    root = cmath.sqrt(half_diff * half_diff + b * c)
    return half_trace + root, half_trace - root


def spectral_radius(
    integrator: str | Callable[..., Any], omega: float, damping_rate: float, dt: float
) -> float:
    """Largest |eigenvalue| of the amplification matrix: > 1 means the method blows up."""
    pair = _eigenvalues(integrator, omega, damping_rate, dt)
    return math.inf if pair is None else max(abs(pair[0]), abs(pair[1]))


def is_stable(
    integrator: str | Callable[..., Any], omega: float, damping_rate: float, dt: float
) -> bool:
    """True when stepping x'' = -omega^2 x - c x' with this dt does not grow without bound.

    Exactly at an oscillation limit (omega dt = 2 for semi-implicit Euler and Verlet) both
    eigenvalues meet at -1 in a Jordan block: M^n then grows like n, slowly but without
    bound, so the limit itself counts as unstable, as "stable for omega dt < 2" says.
    (A double eigenvalue +1 is different: that is free drift, x growing like v t.)
    """
    pair = _eigenvalues(integrator, omega, damping_rate, dt)
    if pair is None:
        return False
    first, second = pair
    if max(abs(first), abs(second)) > 1.0 + _RADIUS_TOLERANCE:
        return False
    return not (abs(first + 1.0) < _AT_LIMIT and abs(second + 1.0) < _AT_LIMIT)


def max_stable_dt(
    integrator: str | Callable[..., Any], omega: float = 0.0, damping_rate: float = 0.0
) -> float:
    """The largest dt (s) that is stable for omega (rad/s) and damping rate c (1/s).

    ``math.inf`` when no force limits the step (omega = c = 0) or none was found up to
    10^6 / rate; ``0.0`` when the method is unstable even at a tiny step (explicit Euler
    on an undamped oscillator). Found by bisection on the spectral radius.
    """
    rate = max(omega, damping_rate)
    if rate <= 0.0:
        return math.inf
    lo = 1e-3 / rate
    if not is_stable(integrator, omega, damping_rate, lo):
        return 0.0
    hi = lo
    while is_stable(integrator, omega, damping_rate, hi):
        lo, hi = hi, hi * 2.0
        if hi * rate > 1e6:
            return math.inf
    # Invariant: lo stable, hi unstable. 60 halvings reach far below float spacing.
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if is_stable(integrator, omega, damping_rate, mid):
            lo = mid
        else:
            hi = mid
    return lo
