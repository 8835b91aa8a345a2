"""A 2D point handed in by a user, checked: a Vector or a pair of numbers, finite.

The colliders (engine.geometry.colliders) and the mass functions (engine.geometry.mass) take their
points here, in one wording: a TypeError or ValueError that names the argument and shows the value.

>>> point_of((1, 2), "center")
(1.0, 2.0)
>>> point_of("ab", "center")
Traceback (most recent call last):
TypeError: center must be a 2D point, a Vector or a pair of numbers such as (1.0, 2.0), got str 'ab'
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any

from .vector import as_pair

__all__ = ["point_of"]


def point_of(value: Any, name: str) -> tuple[float, float]:
    """A finite 2D point (a Vector or a pair of numbers); TypeError / ValueError naming ``name``."""
    pair = as_pair(value)
    if pair is None and not isinstance(value, (str, bytes)):
        try:  # any other 2-sequence of real numbers: a numpy row, a pygame Vector2
            if len(value) == 2 and all(
                isinstance(c, Real) and not isinstance(c, bool) for c in value
            ):
                pair = (float(value[0]), float(value[1]))
        except TypeError:
            pair = None
        except OverflowError:  # an int or a Fraction beyond the float range
            pair = (math.inf, math.inf)
    if pair is None:
        raise TypeError(
            f"{name} must be a 2D point, a Vector or a pair of numbers such as (1.0, 2.0), "
            f"got {type(value).__name__} {value!r}"
        )
    try:
        x, y = float(pair[0]), float(pair[1])
    except OverflowError:  # an int or a Fraction beyond the float range
        x = y = math.inf
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(f"{name} must be finite (no nan or inf), got {value!r}")
    return x, y
