"""How a Vector takes its input and refuses what it cannot take (engine.vector): a component
checked as a real number, the message for what is not a pair, C's rounding, and pygame's
names that would change a Vector in place.
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any

__all__ = [
    "component", "not_a_pair", "round_half_away", "is_scalar", "Omitted", "OMITTED",
    "NotInPlace", "ClassOnly", "IN_PLACE", "refuse_in_place",
]  # fmt: skip


def component(value: Any, name: str) -> float:
    """Return ``value`` as a float, or raise TypeError naming the component."""
    # bool is a subclass of int, but Vector(True, False) is almost surely a mistake.
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(
            f"Vector component {name} must be a real number (int or float), "
            f"got {type(value).__name__} {value!r}"
        )
    try:
        return float(value)
    except OverflowError:  # an int (or Fraction) beyond the float range, ~1.8e308
        raise ValueError(
            f"Vector component {name} must be a number within the float range (|x| < 1.8e308), "
            f"got {value!r}"
        ) from None


def not_a_pair(value: Any, name: str) -> str:
    """The message for a value that is not a 2-sequence of real numbers."""
    why = ""
    if not isinstance(value, (str, bytes)):
        try:
            n = len(value)
        except TypeError:
            pass
        else:
            why = f" (it has {n} items)" if n != 2 else " (its items are not both real numbers)"
    return (
        f"{name} must be a Vector or a pair of real numbers like (1.0, 2.0) "
        f"(a tuple, list, numpy row or pygame Vector2), got {type(value).__name__} {value!r}{why}"
    )


def round_half_away(y: float) -> float:
    """C's round(y): the nearest integer, halves away from zero, keeping the sign of zero."""
    if not math.isfinite(y):
        return y
    t = math.copysign(float(math.trunc(y)), y)
    # y - trunc(y) is exact (both have the same sign and exponent or t is 0), so the
    # comparison with 0.5 decides the half cases exactly.
    if abs(y - t) >= 0.5:
        t += math.copysign(1.0, y)
    return t


def is_scalar(value: Any) -> bool:
    t = type(value)
    if t is float or t is int:
        return True
    return isinstance(value, Real) and not isinstance(value, bool)


class Omitted:
    """The default of ``Vector(x, y)``'s y: omitted, y is 0.0, or x is a pair."""

    def __repr__(self) -> str:
        return "0.0"


OMITTED: Any = Omitted()


class NotInPlace:
    """A pygame in-place name (``normalize_ip``...): AttributeError naming what to write instead.

    An immutable Vector cannot change in place; looking the name up raises at once, so
    ``hasattr(v, "normalize_ip")`` is False and ``v.normalize_ip()`` says what to write.
    """

    def __init__(self, instead: str) -> None:
        self.instead = instead
        self.name = ""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __get__(self, obj: object, owner: type | None = None) -> Any:
        raise AttributeError(
            f"Vector is immutable, so it has no {self.name}(): write {self.instead} "
            f"(a new Vector, bound to the name again)"
        )


class ClassOnly(classmethod):  # type: ignore[type-arg]
    """A classmethod that refuses instances: pygame's ``v.from_polar(p)`` changed v in place."""

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        if obj is not None:
            raise AttributeError(
                "Vector is immutable, so v.from_polar(...) cannot change v: "
                "write v = Vector.from_polar((r, degrees))"
            )
        return super().__get__(obj, owner)


#: pygame's names that change a Vector2 in place, and what to write instead.
IN_PLACE = {
    "normalize_ip": "v = v.normalize()",
    "scale_to_length_ip": "v = v.scale_to_length(length)",
    "rotate_ip": "v = v.rotate(degrees)",
    "rotate_rad_ip": "v = v.rotate_rad(radians)",
    "rotate_ip_rad": "v = v.rotate_rad(radians)",
    "reflect_ip": "v = v.reflect(normal)",
    "move_towards_ip": "v = v.move_towards(target, max_distance)",
    "clamp_magnitude_ip": "v = v.clamp_magnitude(max_length)",
    "update": "v = Vector(x, y)",
}


def refuse_in_place(cls: type) -> None:
    """Give ``cls`` (Vector) pygame's in-place names, each refusing with what to write."""
    for name, instead in IN_PLACE.items():
        refusal = NotInPlace(instead)
        refusal.__set_name__(cls, name)
        setattr(cls, name, refusal)
