"""How large an integrator's error will be, known before the run: what "auto" with a tolerance uses.

The model problem
-----------------
Every force the World understands (constant forces, gravity, linear drag, wind,
springs of rest length 0) makes each body obey, per coordinate,

    x'' = b - omega^2 x - c x'          (omega rad/s, c 1/s, b m/s^2 constant)

a linear, affine equation. Over one step h both the exact flow and every
integrator here are affine maps of the augmented state s = (x, v, b):

    exact:        s(t + h) = E(h) s(t),   E(h) = expm(A h),  A = [[0, 1, 0],
                                                                [-omega^2, -c, 1],
                                                                [0, 0, 0]]
    integrator:   s_{n+1}  = M(h) s_n     (M found by stepping the three basis states)

so after n steps the error is exactly

    s_n - s(n h) = (M^n - E(h)^n) s_0,

and the position error is the first row of that 3x3 matrix times (x0, v0, b).
This is not an estimate: on the model problem it is the error itself, the same
number a run would measure (up to round-off, ~1e-12 relative after 10^4 steps).
It contains everything the usual rule of thumb ``error ~ C dt^p`` is made of:
the method's order p shows up as M^n - E^n shrinking like h^p, and the error
constant C (which depends on omega, c, the state and the horizon) comes out
of the same product instead of being guessed. ``tests/test_auto.py`` checks
it against measured runs, and the work-precision chart (``python -m demos
tradeoff``) shows it: "auto" lands on the cheapest measured point that meets
each tolerance.

The tolerance
-------------
``World(integrator="auto", tolerance=tol)`` promises: over the next
:data:`HORIZON` seconds of simulated time from the state at which the method
is chosen (the first step of each new dt), no body's position (m) is predicted
to stray more than ``tol`` from the exact solution of the same forces. A
force the model does not know (a user's callable) is frozen at its current
value for the prediction; a spring with a rest length is linearised.

>>> from engine.integrators import rk4, semi_implicit_euler
>>> x0, v0, acc = np.array([[1.0]]), np.array([[0.0]]), np.array([[-1.0]])
>>> w, c = np.array([1.0]), np.array([0.0])
>>> e1 = predicted_error(semi_implicit_euler, x0, v0, acc, w, c, 0.01)
>>> e4 = predicted_error(rk4, x0, v0, acc, w, c, 0.01)
>>> 0.001 < e1 < 0.01, e4 < 1e-10
(True, True)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["HORIZON", "step_matrix", "exact_matrix", "expm", "error_rows", "predicted_error"]

#: Seconds of simulated time over which a tolerance is promised (s).
HORIZON = 1.0

# Above this many steps in the horizon, the error is sampled at this many evenly spaced
# steps instead of at every step (the error changes little from one step to the next).
_MAX_SAMPLES = 8192

# Above this many bodies sharing one (omega, c), bound their errors from the largest
# |x|, |v|, |b| instead of computing each body's (a bound: never smaller than the truth).
_MAX_BODIES = 256


def step_matrix(integrator: Callable[..., Any], omega: float, rate: float, dt: float) -> np.ndarray:
    """The 3x3 matrix M with (x, v, b)_{n+1} = M (x, v, b)_n for one step of ``integrator``.

    Found by stepping the basis states: the integrator is affine on the model problem, so the
    step of (1, 0, 0), (0, 1, 0) and (0, 0, 1) gives M's columns (b is carried unchanged).
    """
    w2 = omega * omega
    m = np.zeros((3, 3))
    for col, (x, v, b) in enumerate(((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))):

        def accel(t: float, xx: float, vv: float, b: float = b) -> float:
            return b - w2 * xx - rate * vv

        x1, v1 = integrator(x, v, accel, 0.0, dt)
        m[:, col] = (x1, v1, b)
    return m


def exact_matrix(omega: float, rate: float, dt: float) -> np.ndarray:
    """expm(A dt) for the model problem: the exact one-step map of (x, v, b)."""
    return expm(np.array([[0.0, 1.0, 0.0], [-omega * omega, -rate, 1.0], [0.0, 0.0, 0.0]]) * dt)


def expm(a: np.ndarray) -> np.ndarray:
    """The matrix exponential of a square matrix ``a`` (no unit): the exact flow of z' = A z
    over one step is expm(A dt)."""
    # Scaling and squaring: expm(A) = expm(A / 2^s)^(2^s), with ||A / 2^s|| <= 1/2 so that 20
    # Taylor terms are far below round-off (0.5^20 / 20! ~ 4e-25).
    norm = float(np.abs(a).sum(axis=0).max())
    s = max(0, math.ceil(math.log2(norm / 0.5))) if norm > 0.5 else 0
    a = a / 2.0**s
    term = total = np.eye(len(a))
    for k in range(1, 21):
        term = term @ a / k
        total = total + term
    for _ in range(s):
        total = total @ total
    return total


def _powers(m: np.ndarray, n: int) -> np.ndarray:
    """m^1 ... m^n as an (n, 3, 3) array, by doubling: P[k:2k] = P[0:k] @ m^k."""
    out = np.empty((n + 1, 3, 3))
    out[0] = np.eye(3)
    have, mk = 1, m
    while have <= n:
        take = min(have, n + 1 - have)
        out[have : have + take] = out[:take] @ mk
        have += take
        mk = mk @ mk
    return out[1:]


def error_rows(
    integrator: Callable[..., Any], omega: float, rate: float, dt: float, horizon: float = HORIZON
) -> np.ndarray:
    """Rows r_n (shape (samples, 3)) with position error after n steps = r_n . (x0, v0, b).

    n runs over every step up to ceil(horizon / dt) (sampled evenly beyond 8192 steps).
    """
    n = max(1, math.ceil(horizon / dt - 1e-9))
    m = step_matrix(integrator, omega, rate, dt)
    if not np.isfinite(m).all():
        return np.full((1, 3), math.inf)
    e = exact_matrix(omega, rate, dt)
    if n <= _MAX_SAMPLES:
        with np.errstate(over="ignore", invalid="ignore"):
            diff = _powers(m, n) - _powers(e, n)
        return diff[:, 0, :]
    stride = math.ceil(n / _MAX_SAMPLES)
    with np.errstate(over="ignore", invalid="ignore"):
        ms, es = (
            _powers(np.linalg.matrix_power(m, stride), n // stride),
            _powers(np.linalg.matrix_power(e, stride), n // stride),
        )
        rows = (ms - es)[:, 0, :]
        last = (np.linalg.matrix_power(m, n) - np.linalg.matrix_power(e, n))[0][None, :]
    return np.concatenate([rows, last])


def predicted_error(
    integrator: Callable[..., Any],
    x: np.ndarray,
    v: np.ndarray,
    acc: np.ndarray,
    omega: np.ndarray,
    rate: np.ndarray,
    dt: float,
    horizon: float = HORIZON,
) -> float:
    """Largest position error (m) of any body over ``horizon`` s of steps of ``dt`` s.

    ``x``, ``v``, ``acc``: positions (m), velocities (m/s) and accelerations now (m/s^2), shape
    (N,) or (N, D); ``omega`` (rad/s) and ``rate`` (1/s): each body's spring frequency and
    damping rate, shape (N,). The constant part is b = acc + omega^2 x + c v, read off the
    acceleration now, so anchors and constant forces need not be known. Returns ``math.inf``
    when the method blows up on the model problem within the horizon.
    """
    x, v, acc = (np.asarray(a, dtype=float) for a in (x, v, acc))
    if x.size == 0:
        return 0.0
    if x.ndim == 1:
        x, v, acc = x[:, None], v[:, None], acc[:, None]
    worst = 0.0
    pairs = np.stack([np.asarray(omega, dtype=float), np.asarray(rate, dtype=float)], axis=1)
    for w, c in np.unique(pairs, axis=0):
        sel = (pairs[:, 0] == w) & (pairs[:, 1] == c)
        xs, vs, acs = x[sel], v[sel], acc[sel]
        b = acs + (w * w) * xs + c * vs
        if w > 0.0:
            # Measure x from the spring's equilibrium b / omega^2: the constant part vanishes,
            # and no large, cancelling terms enter when the anchor is far from the origin.
            xs, b = xs - b / (w * w), np.zeros_like(b)
        rows = error_rows(integrator, float(w), float(c), dt, horizon)
        if not np.isfinite(rows).all():
            return math.inf
        if len(xs) > _MAX_BODIES:
            # Per coordinate: |r . s| <= sum_j |r_j| max|s_j|, an upper bound for every body.
            env = np.stack([np.abs(xs).max(0), np.abs(vs).max(0), np.abs(b).max(0)])  # (3, D)
            per = np.abs(rows) @ env  # (samples, D)
            err = float(np.sqrt((per * per).sum(axis=1)).max())
        else:
            state = np.stack([xs, vs, b], axis=-1)  # (B, D, 3)
            e = np.einsum("nj,bdj->nbd", rows, state)  # (samples, B, D)
            err = float(np.sqrt((e * e).sum(axis=2)).max())
        if not math.isfinite(err):
            return math.inf
        worst = max(worst, err)
    return worst
