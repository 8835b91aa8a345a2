"""Operators made for others (engine.vector): a subclass's arithmetic, returning the subclass,
and pygame's elementwise proxy, ``v.elementwise()``.
"""

from __future__ import annotations

from collections.abc import Callable
from numbers import Real
from typing import Any

from .vector import Vector, as_pair, new_unchecked
from .vector_checks import is_scalar

__all__ = ["arithmetic_returning", "Elementwise"]


def arithmetic_returning(cls: type[Vector]) -> dict[str, Callable[..., Any]]:
    """Vector's operators, returning ``cls``: a subclass's arithmetic keeps the subclass.

    The same bodies as Vector's own (tests/test_vector.py checks they agree), with the
    subclass in place of Vector; Vector keeps its own so that it pays nothing for this.
    """

    def __add__(self: Vector, other: Any) -> Any:
        pair = other if type(other) is Vector else as_pair(other)
        if pair is None:
            return NotImplemented
        return new_unchecked(cls, (self[0] + pair[0], self[1] + pair[1]))

    def __radd__(self: Vector, other: Any) -> Any:
        if as_pair(other) is None:
            return Vector.__radd__(self, other)  # NotImplemented, or its TypeError for a tuple
        return __add__(self, other)

    def __sub__(self: Vector, other: Any) -> Any:
        pair = other if type(other) is Vector else as_pair(other)
        if pair is None:
            return NotImplemented
        return new_unchecked(cls, (self[0] - pair[0], self[1] - pair[1]))

    def __rsub__(self: Vector, other: Any) -> Any:
        pair = as_pair(other)
        if pair is None:
            return NotImplemented
        return new_unchecked(cls, (pair[0] - self[0], pair[1] - self[1]))

    def __neg__(self: Vector) -> Any:
        return new_unchecked(cls, (-self[0], -self[1]))

    def __pos__(self: Vector) -> Any:
        return new_unchecked(cls, (self[0], self[1]))

    def __mul__(self: Vector, other: Any) -> Any:
        result = Vector.__mul__(self, other)  # the checks and the messages are Vector's
        return result if result is NotImplemented else new_unchecked(cls, result)

    def __truediv__(self: Vector, other: Any) -> Any:
        result = Vector.__truediv__(self, other)
        return result if result is NotImplemented else new_unchecked(cls, result)

    methods: dict[str, Callable[..., Any]] = {
        "__add__": __add__,
        "__radd__": __radd__,
        "__sub__": __sub__,
        "__rsub__": __rsub__,
        "__neg__": __neg__,
        "__pos__": __pos__,
        "__mul__": __mul__,
        "__rmul__": __mul__,
        "__truediv__": __truediv__,
    }
    for method in methods.values():
        method._made_for = cls  # type: ignore[attr-defined]
    return methods


def _operand(other: Any) -> tuple[float, float] | None:
    """The other side of an Elementwise operator as a pair: another proxy's vector, a pair,
    or a number for both components; None: not an operand."""
    if type(other) is Elementwise:
        return other.vector
    pair = as_pair(other)
    if pair is None and is_scalar(other):
        return float(other), float(other)
    return pair


def _binary(
    op: Callable[[float, float], float], reflected: bool = False
) -> Callable[[Elementwise, Any], Any]:
    """An operator of Elementwise: ``op`` on each component, with a pair or a number."""

    def method(self: Elementwise, other: Any) -> Any:
        v = self.vector
        pair = _operand(other)
        if pair is None:
            return NotImplemented
        a, b = pair
        if reflected:
            x, y = op(a, v[0]), op(b, v[1])
        else:
            x, y = op(v[0], a), op(v[1], b)
        if not (isinstance(x, Real) and isinstance(y, Real)):  # (-1) ** 0.5 is complex
            raise ValueError("negative number cannot be raised to a fractional power")
        return new_unchecked(type(v), (float(x), float(y)))

    return method


def _compare(op: Callable[[float, float], bool]) -> Callable[[Elementwise, Any], Any]:
    """A comparison of Elementwise: True when ``op`` holds for both components."""

    def method(self: Elementwise, other: Any) -> Any:
        v = self.vector
        pair = _operand(other)
        if pair is None:
            return NotImplemented
        a, b = pair
        return op(v[0], a) and op(v[1], b)

    return method


class Elementwise:
    """pygame's VectorElementwiseProxy: operators apply to each component on its own.

    ``v.elementwise() * w`` is (v.x w.x, v.y w.y); ``v.elementwise() > 0`` is True when both
    components are. The results are Vectors (of v's type); comparisons are plain bools.
    """

    __slots__ = ("vector",)

    def __init__(self, vector: Vector) -> None:
        self.vector = vector

    __add__ = __radd__ = _binary(lambda a, b: a + b)
    __sub__ = _binary(lambda a, b: a - b)
    __rsub__ = _binary(lambda a, b: a - b, reflected=True)
    __mul__ = __rmul__ = _binary(lambda a, b: a * b)
    __truediv__ = _binary(lambda a, b: a / b)
    __rtruediv__ = _binary(lambda a, b: a / b, reflected=True)
    __floordiv__ = _binary(lambda a, b: a // b)
    __rfloordiv__ = _binary(lambda a, b: a // b, reflected=True)
    __mod__ = _binary(lambda a, b: a % b)
    __rmod__ = _binary(lambda a, b: a % b, reflected=True)
    __pow__ = _binary(lambda a, b: a**b)
    __rpow__ = _binary(lambda a, b: a**b, reflected=True)

    __eq__ = _compare(lambda a, b: a == b)  # type: ignore[assignment]
    # pygame's elementwise != holds when every component differs (not "not ==").
    __ne__ = _compare(lambda a, b: a != b)  # type: ignore[assignment]
    __lt__ = _compare(lambda a, b: a < b)
    __le__ = _compare(lambda a, b: a <= b)
    __gt__ = _compare(lambda a, b: a > b)
    __ge__ = _compare(lambda a, b: a >= b)
    __hash__ = None  # type: ignore[assignment]

    def __abs__(self) -> Vector:
        v = self.vector
        return new_unchecked(type(v), (abs(v[0]), abs(v[1])))

    def __neg__(self) -> Vector:
        return -self.vector

    def __pos__(self) -> Vector:
        return +self.vector

    def __bool__(self) -> bool:
        return bool(self.vector)

    def __repr__(self) -> str:
        return f"{self.vector!r}.elementwise()"
