"""Closed-form motion under constant acceleration (lesson, section 3.2.3).

Integrating a constant acceleration a twice, with s(0) = s0 and v(0) = v0:

    v(t) = v0 + a t
    s(t) = s0 + v0 t + a t^2 / 2

These are exact at any t, so a scene whose forces are all constant can be
moved by them at each frame's time, with no error piling up from step to
step. They work on floats (1D), Vectors (2D) and numpy arrays alike.

>>> position(2.0, 1.0, 0.0, 3.0)      # the lesson's s(3) = 1*3 + 2
5.0
>>> velocity(0.0, 1.0, 4.0)
4.0
>>> round(time_to_reach(0.0, 0.0, 1.0, 10.0), 4)   # Alfred's sprint: sqrt(20) s
4.4721
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["position", "velocity", "time_to_reach", "stopping_distance"]


def position(s0: Any, v0: Any, a: Any, t: Any) -> Any:
    """Position s0 + v0 t + a t^2 / 2 (length units) after time t (s)."""
    return s0 + v0 * t + a * (0.5 * t * t)


def velocity(v0: Any, a: Any, t: Any) -> Any:
    """Velocity v0 + a t (length units per s) after time t (s)."""
    return v0 + a * t


def time_to_reach(s0: float, v0: float, a: float, s: float) -> float:
    """First time t >= 0 (s) at which a 1D body reaches position ``s``; ``math.inf`` if never.

    Solves a t^2 / 2 + v0 t - (s - s0) = 0. With d = s - s0 the roots are
    t = (-v0 +- sqrt(v0^2 + 2 a d)) / a; the product form t = 2d / (-v0 -+ sqrt(...))
    avoids cancellation when a t is small against v0.

    >>> time_to_reach(2.0, 1.0, 0.0, 5.0)
    3.0
    >>> time_to_reach(0.0, 1.0, 0.0, -1.0)
    inf
    """
    d = float(s) - float(s0)
    v0, a = float(v0), float(a)
    if d == 0.0:
        return 0.0
    if a == 0.0:
        if v0 == 0.0:
            return math.inf
        t = d / v0
        return t if t >= 0.0 else math.inf
    disc = v0 * v0 + 2.0 * a * d
    if disc < 0.0:
        return math.inf
    root = math.sqrt(disc)
    # q has the sign of -v0 with no cancellation; the roots are q / a and -2d / q ... see
    # Numerical Recipes 5.6: for A t^2 + B t + C = 0, q = -(B + sign(B) sqrt(B^2 - 4AC)) / 2,
    # t1 = q / A, t2 = C / q. Here A = a/2, B = v0, C = -d.
    q = -0.5 * (v0 + math.copysign(root, v0 if v0 != 0.0 else 1.0))
    candidates = [q / (0.5 * a)]
    if q != 0.0:
        candidates.append(-d / q)
    ahead = [t for t in candidates if t >= 0.0]
    return min(ahead) if ahead else math.inf


def stopping_distance(speed: float, deceleration: float) -> float:
    """Distance v^2 / (2 a) (length units) to stop from ``speed`` at constant ``deceleration``.

    From v(t)^2 = v0^2 - 2 a s with v = 0 at the stop.

    >>> stopping_distance(4.0, 2.0)
    4.0
    """
    if deceleration <= 0.0:
        raise ValueError(f"deceleration must be > 0, got {deceleration!r}")
    return speed * speed / (2.0 * deceleration)
