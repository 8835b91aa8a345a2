"""Collision types: pymunk's ``collision_type``, the int a Body or collider carries so that
``World.on_collision(type_a, type_b, ...)`` can name the pairs it handles
(engine.pipeline.collision_handlers). 0 is every thing's type until it is given one.

>>> as_collision_type(3)
3
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["as_collision_type"]


def as_collision_type(value: Any) -> int:
    """``value`` as a collision type (an int >= 0); else an error that says what is valid."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(
            f"collision_type must be an int >= 0 (0: the default type), got "
            f"{type(value).__name__} {value!r}"
        )
    if value < 0:
        raise ValueError(f"collision_type must be an int >= 0 (0: the default type), got {value!r}")
    return int(value)
