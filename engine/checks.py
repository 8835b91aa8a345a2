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

__all__ = ["real"]


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
