"""Checks of the numbers a user hands in: one place, one wording for each refusal.

Standard library only, so every layer may use it, down to Vector and Body, which import
nothing but the standard library.

>>> real(2, "k")
2.0
>>> real(float("nan"), "k")
Traceback (most recent call last):
ValueError: k must be finite, got nan
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any

__all__ = ["real", "seconds", "mass"]


def real(value: Any, name: str, *, positive: bool = False, nonneg: bool = False) -> float:
    """``value`` as a finite float; TypeError / ValueError naming ``name`` otherwise.

    ``positive`` also refuses values <= 0, ``nonneg`` values < 0. A bool is refused: True
    where a number belongs is almost always a mistake.
    """
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")
    try:
        f = float(value)
    except OverflowError:  # an int beyond the float range
        f = math.inf
    if not math.isfinite(f):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if positive and f <= 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    if nonneg and f < 0.0:
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return f


def seconds(value: Any, name: str = "dt") -> float:
    """``value`` as a finite time step > 0 s; TypeError / ValueError naming ``name``.

    >>> seconds(1 / 60)
    0.016666666666666666
    >>> seconds(0)
    Traceback (most recent call last):
    ValueError: dt must be a finite number of seconds > 0 (e.g. 1/60), got 0
    """
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a number of seconds, got {type(value).__name__} {value!r}")
    try:
        f = float(value)
    except OverflowError:  # an int beyond the float range
        f = math.inf
    if not (math.isfinite(f) and f > 0.0):
        raise ValueError(
            f"{name} must be a finite number of seconds > 0 (e.g. 1/60), got {value!r}"
        )
    return f


def mass(value: Any, name: str = "mass") -> float:
    """``value`` as a positive finite mass (kg, or the scene's unit); errors name ``name``."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(
            f"{name} must be a positive real number, got {type(value).__name__} {value!r}"
        )
    try:
        m = float(value)
    except OverflowError:  # an int beyond the float range
        m = math.inf
    if not (math.isfinite(m) and m > 0.0):
        raise ValueError(f"{name} must be positive and finite (> 0, e.g. 1.0), got {value!r}")
    return m
