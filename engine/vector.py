"""A 2D vector: the lesson's ``rbpmath.Vector``, as an immutable value type.

The lesson builds its Vector from two ideas, scaling and addition (section 3.3):

    a v   = (a v_x, a v_y)
    v + u = (v_x + u_x, v_y + u_y)
    |v|   = sqrt(v_x^2 + v_y^2)          (Pythagoras)

Everything here follows from those. Unlike the lesson's reference code, a Vector
never changes after it is made: ``v += w`` rebinds the name ``v`` to a new
vector, so a vector that someone else holds (a body's position, say) can never
change behind their back. Plain 2-tuples are accepted wherever a Vector is.

>>> a = Vector(3, 4)
>>> a.magnitude()
5.0
>>> a + (1, 1)
Vector(4.0, 5.0)
>>> 2 * a - a
Vector(3.0, 4.0)
>>> print(a)
X: 3.0 Y: 4.0
>>> a.dot(Vector(1, 0)), a.cross(Vector(1, 0))
(3.0, -4.0)
"""

from __future__ import annotations

import math
from numbers import Real
from operator import itemgetter
from typing import Any, SupportsFloat, Union

__all__ = ["Vector", "VectorLike"]

VectorLike = Union["Vector", tuple[float, float]]

# Vector is a tuple underneath: immutable for free, made at C speed, compared and hashed
# like the pair it holds (so Vector(1, 2) == (1.0, 2.0) and their hashes agree), and
# turned into numpy arrays directly. _new(Vector, (x, y)) skips the checks in __new__
# and is used where x and y are already floats (the results of float arithmetic).
_new = tuple.__new__


def _component(value: Any, name: str) -> float:
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


def _as_pair(other: Any) -> tuple[float, float] | None:
    """The (x, y) of a Vector or of a 2-sequence of real numbers, else None."""
    if type(other) is Vector:
        return other  # type: ignore[return-value]
    if isinstance(other, (tuple, list)) and len(other) == 2:
        x, y = other
        if all(isinstance(c, Real) and not isinstance(c, bool) for c in (x, y)):
            try:
                return float(x), float(y)
            except OverflowError:  # an int beyond the float range is not a usable pair
                return None
    return None


def _is_scalar(value: Any) -> bool:
    t = type(value)
    if t is float or t is int:
        return True
    return isinstance(value, Real) and not isinstance(value, bool)


class Vector(tuple):  # type: ignore[type-arg]
    """An immutable 2D vector of floats, in whatever length unit the scene uses."""

    __slots__ = ()

    # numpy must not treat a Vector as a sequence in arithmetic: without this,
    # np.float64(2) * Vector(1, 2) (a dt read from an array, say) is array([2., 4.]).
    # None makes numpy's operators return NotImplemented, so Vector.__rmul__ answers.
    __array_ufunc__ = None

    def __new__(cls, x: SupportsFloat = 0.0, y: SupportsFloat = 0.0) -> Vector:
        tx, ty = type(x), type(y)
        if (tx is float or tx is int) and (ty is float or ty is int):
            try:
                return _new(cls, (float(x), float(y)))  # type: ignore[arg-type]
            except OverflowError:
                pass  # an int beyond the float range: _component names it
        return _new(cls, (_component(x, "x"), _component(y, "y")))

    x = property(itemgetter(0), doc="The x component (length units).")
    y = property(itemgetter(1), doc="The y component (length units).")

    @classmethod
    def coerce(cls, value: Any, name: str = "value") -> Vector:
        """Return ``value`` as a Vector (a Vector or a 2-sequence of numbers), else TypeError."""
        if type(value) is Vector:
            return value
        pair = _as_pair(value)
        if pair is None:
            raise TypeError(
                f"{name} must be a Vector or a pair of real numbers like (1.0, 2.0), "
                f"got {type(value).__name__} {value!r}"
            )
        return _new(cls, pair)

    # -- immutability, copying, pickling ------------------------------------------------
    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(
            f"Vector is immutable: make a new one, e.g. v = Vector(x, y) or v = v + (dx, dy) "
            f"(tried to set {name!r})"
        )

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"Vector is immutable (tried to delete {name!r})")

    def __getnewargs__(self) -> tuple[float, float]:
        return (self[0], self[1])

    # -- text -------------------------------------------------------------------------
    def __str__(self) -> str:
        """The lesson's text: ``X: 1.0 Y: 2.0``."""
        return f"X: {self[0]} Y: {self[1]}"

    def __repr__(self) -> str:
        return f"Vector({self[0]!r}, {self[1]!r})"

    # -- comparison ---------------------------------------------------------------------
    # == and hash are the tuple's: component by component, equal to the plain pair.
    # The lesson's __ne__ returned NotImplemented whenever __eq__ answered, so two equal
    # vectors compared unequal; the tuple's != is exactly "not ==".
    def __eq__(self, other: object) -> bool:
        if isinstance(other, list) and len(other) == 2:
            return tuple.__eq__(self, tuple(other))
        return tuple.__eq__(self, other)

    def __ne__(self, other: object) -> bool:
        eq = self.__eq__(other)
        return NotImplemented if eq is NotImplemented else not eq

    __hash__ = tuple.__hash__

    def _unordered(self, other: object) -> bool:
        return NotImplemented

    # Vectors have no order; a tuple's would compare x first, which means nothing here.
    __lt__ = __le__ = __gt__ = __ge__ = _unordered  # type: ignore[assignment]

    def __bool__(self) -> bool:
        return self[0] != 0.0 or self[1] != 0.0

    def components(self) -> tuple[float, float]:
        """The lesson's ``components()``: the tuple (x, y), e.g. for drawing functions."""
        return (self[0], self[1])

    # -- arithmetic ---------------------------------------------------------------------
    def __add__(self, other: Any) -> Vector:  # type: ignore[override]
        pair = other if type(other) is Vector else _as_pair(other)
        if pair is None:
            return NotImplemented
        return _new(Vector, (self[0] + pair[0], self[1] + pair[1]))

    def __radd__(self, other: Any) -> Vector:
        pair = _as_pair(other)
        if pair is None:
            if isinstance(other, tuple):
                # NotImplemented would let the tuple answer: (1,) + v would concatenate into
                # the plain tuple (1, x, y).
                raise TypeError(
                    f"a Vector adds only to a Vector or a pair of real numbers like (1.0, 2.0), "
                    f"got {type(other).__name__} {other!r}"
                )
            return NotImplemented
        return _new(Vector, (self[0] + pair[0], self[1] + pair[1]))

    def __sub__(self, other: Any) -> Vector:
        # The lesson's __sub__ added the y components; this subtracts both.
        pair = other if type(other) is Vector else _as_pair(other)
        if pair is None:
            return NotImplemented
        return _new(Vector, (self[0] - pair[0], self[1] - pair[1]))

    def __rsub__(self, other: Any) -> Vector:
        pair = _as_pair(other)
        if pair is None:
            return NotImplemented
        return _new(Vector, (pair[0] - self[0], pair[1] - self[1]))

    def __neg__(self) -> Vector:
        return _new(Vector, (-self[0], -self[1]))

    def __pos__(self) -> Vector:
        return self

    def __mul__(self, other: Any) -> Vector:  # type: ignore[override]
        # Scaling only. The lesson's `*` meant the dot product between two vectors,
        # which hides bugs (a vector times a vector silently becomes a number); and
        # its `*=` scaled only when the other operand was a vector.
        t = type(other)
        if t is float or t is int or _is_scalar(other):
            try:
                s = float(other)
            except OverflowError:  # an int beyond the float range
                s = _component(other, "scale")  # raises ValueError naming it
            return _new(Vector, (self[0] * s, self[1] * s))
        if isinstance(other, (tuple, list)):
            raise TypeError(
                "Vector * Vector is ambiguous: use v.dot(w) for the dot product or "
                "v.cross(w) for the 2D cross product; * scales by a number"
            )
        return NotImplemented

    __rmul__ = __mul__  # type: ignore[assignment]

    def __truediv__(self, other: Any) -> Vector:
        if not _is_scalar(other):
            return NotImplemented
        try:
            s = float(other)
        except OverflowError:  # an int beyond the float range
            s = _component(other, "divisor")  # raises ValueError naming it
        if s == 0.0:
            raise ZeroDivisionError("cannot divide a Vector by zero")
        return _new(Vector, (self[0] / s, self[1] / s))

    # += -= *= are deliberately not defined: Python then falls back to + - *,
    # which rebinds the name to a new Vector and never mutates a shared one.

    def __abs__(self) -> float:
        return self.magnitude()

    # -- the lesson's magnitude and pygame's familiar names -----------------------------------
    def magnitude(self) -> float:
        """Length |v| = sqrt(x^2 + y^2), in the vector's unit."""
        return math.hypot(self[0], self[1])

    def length_squared(self) -> float:
        """|v|^2 = x^2 + y^2 (no square root: cheap for comparisons)."""
        return self[0] * self[0] + self[1] * self[1]

    def dot(self, other: VectorLike) -> float:
        """Dot product v . w = v_x w_x + v_y w_y.

        >>> Vector(1, 2).dot((3, 4))
        11.0
        """
        ox, oy = Vector.coerce(other, "other")
        return self[0] * ox + self[1] * oy

    def cross(self, other: VectorLike) -> float:
        """2D cross product v x w = v_x w_y - v_y w_x (the z part of the 3D cross product).

        >>> Vector(1, 0).cross((0, 1))
        1.0
        """
        ox, oy = Vector.coerce(other, "other")
        return self[0] * oy - self[1] * ox

    def normalized(self) -> Vector:
        """The unit vector in the same direction; ValueError for the zero vector.

        >>> Vector(3, 4).normalized()
        Vector(0.6, 0.8)
        """
        m = self.magnitude()
        if m == 0.0:
            raise ValueError("cannot normalize the zero vector: it has no direction")
        if not 1e-290 < m < math.inf:
            if not self.is_finite():
                raise ValueError(f"cannot normalize {self!r}: it must be finite (no nan or inf)")
            # Subnormal components have few bits, so |v| rounds so coarsely that v / |v| is not
            # a unit vector (5e-324 * (1, 1) would give (1, 1)); near the top of the float range
            # |v| overflows to inf (1e308 * (1, 1) would give (0, 0)). Scaling by a power of two
            # first is exact and keeps the direction.
            k = 2.0**600 if m < 1.0 else 2.0**-600
            return _new(Vector, (self[0] * k, self[1] * k)).normalized()
        return _new(Vector, (self[0] / m, self[1] / m))

    def distance_to(self, other: VectorLike) -> float:
        """Distance |v - w| between two points."""
        ox, oy = Vector.coerce(other, "other")
        return math.hypot(self[0] - ox, self[1] - oy)

    def lerp(self, other: VectorLike, t: float) -> Vector:
        """The point a fraction t of the way from v to w: v + (w - v) t.

        >>> Vector(0, 0).lerp((10, 20), 0.25)
        Vector(2.5, 5.0)
        """
        ox, oy = Vector.coerce(other, "other")
        t = _component(t, "t")
        return _new(Vector, (self[0] + (ox - self[0]) * t, self[1] + (oy - self[1]) * t))

    def is_finite(self) -> bool:
        """True when both components are finite (neither nan nor inf)."""
        return math.isfinite(self[0]) and math.isfinite(self[1])
