"""A 2D vector: the lesson's ``rbpmath.Vector``, as an immutable value type.

The lesson builds its Vector from two ideas, scaling and addition (section 3.3):

    a v   = (a v_x, a v_y)
    v + u = (v_x + u_x, v_y + u_y)
    |v|   = sqrt(v_x^2 + v_y^2)          (Pythagoras)

Everything here follows from those. Unlike the lesson's reference code, a Vector
never changes after it is made: ``v += w`` rebinds the name ``v`` to a new
vector, so a vector that someone else holds (a body's position, say) can never
change behind their back. Any 2-sequence of real numbers (a tuple, a list, a numpy
row, a pygame ``Vector2``) is accepted wherever a Vector is.

It also speaks the game author's language: pygame's ``Vector2`` names (``length``,
``normalize``, ``rotate`` in degrees, ``reflect``, ``move_towards``...) and pymunk's
``Vec2d`` names (``rotated`` in radians, ``perpendicular``, ``angle``, ``projection``),
each returning a new vector; the README's table says which name comes from where.

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
>>> Vector((3, 4)) == Vector([3, 4]) == a
True
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from numbers import Real
from operator import itemgetter
from typing import Any, SupportsFloat, TypeVar, Union

from .vector_checks import (
    OMITTED,
    ClassOnly,
    component,
    is_scalar,
    not_a_pair,
    refuse_in_place,
    round_half_away,
)

__all__ = [
    "Vector",
    "VectorLike",
    "as_pair",
    "new_unchecked",
    "arithmetic_returning",
    "Elementwise",
]

VectorLike = Union["Vector", tuple[float, float]]

_V = TypeVar("_V", bound="Vector")

# Vector is a tuple underneath: immutable for free, made at C speed, compared and hashed like
# the pair it holds (Vector(1, 2) == (1.0, 2.0), equal hashes), turned into arrays directly.
#: ``new_unchecked(Vector, (x, y))``: a Vector of two floats (length units) made at C speed,
#: without the checks of ``Vector(x, y)``; only where x and y are already floats (the
#: results of float arithmetic).
new_unchecked: Callable[..., Any] = tuple.__new__
_new = new_unchecked  # the old name, used throughout this module

# pygame's Vector2 tolerance (VECTOR_EPSILON in pygame's src_c/math.c): the methods named
# after pygame's use it exactly where pygame does, so they refuse the same near-zero input.
_EPSILON = 1e-6


def as_pair(other: Any) -> tuple[float, float] | None:
    """The (x, y) floats (in the value's own units) of a Vector or 2-sequence of reals, else None.

    A 2-sequence is anything with ``len(s) == 2`` and ``s[0]``, ``s[1]``: a tuple, a list,
    a numpy row, a pygame ``Vector2``, a pymunk ``Vec2d``. Strings and mappings are not.
    """
    t = type(other)
    if t is Vector:
        return other  # type: ignore[return-value]
    if t is tuple or t is list:
        if len(other) != 2:
            return None
        x, y = other
    else:
        if isinstance(other, (str, bytes, Mapping)):
            return None
        try:
            if len(other) != 2:
                return None
            x, y = other[0], other[1]
        except (TypeError, IndexError, KeyError):  # no len, or not indexable by 0 and 1
            return None
    tx, ty = type(x), type(y)
    if not ((tx is float or tx is int) and (ty is float or ty is int)):
        if isinstance(x, bool) or isinstance(y, bool):
            return None
        if not (isinstance(x, Real) and isinstance(y, Real)):
            return None
    try:
        return float(x), float(y)
    except OverflowError:  # an int beyond the float range is not a usable pair
        return None


def _pair(value: Any, name: str) -> tuple[float, float]:
    """The (x, y) of ``value`` (see ``as_pair``), else TypeError naming ``name``."""
    pair = value if type(value) is Vector else as_pair(value)
    if pair is None:
        raise TypeError(not_a_pair(value, name))
    return pair


class Vector(tuple):  # type: ignore[type-arg]
    """An immutable 2D vector of floats, in whatever length unit the scene uses."""

    __slots__ = ()

    # numpy must not treat a Vector as a sequence in arithmetic: without this,
    # np.float64(2) * Vector(1, 2) (a dt read from an array, say) is array([2., 4.]).
    # None makes numpy's operators return NotImplemented, so Vector.__rmul__ answers.
    __array_ufunc__ = None

    def __new__(
        cls: type[_V], x: SupportsFloat | Iterable[SupportsFloat] = 0.0, y: SupportsFloat = OMITTED
    ) -> _V:
        # The fast path, first: two plain floats or ints (the lesson's Vector(x, y)).
        tx, ty = type(x), type(y)
        if (tx is float or tx is int) and (ty is float or ty is int):
            try:
                return _new(cls, (float(x), float(y)))  # type: ignore[arg-type]
            except OverflowError:
                pass  # an int beyond the float range: component() names it
        if y is OMITTED:
            # One argument: a number is the lesson's Vector(x) = (x, 0); a pair is pygame's
            # Vector2((x, y)), the vector from a position tuple.
            if is_scalar(x):
                return _new(cls, (component(x, "x"), 0.0))
            pair = as_pair(x)
            if pair is None:
                raise TypeError(
                    "Vector(x) with one argument takes a number x (y is then 0) or a pair: "
                    + not_a_pair(x, "x")
                )
            return _new(cls, pair)
        return _new(cls, (component(x, "x"), component(y, "y")))

    x = property(itemgetter(0), doc="The x component (length units).")
    y = property(itemgetter(1), doc="The y component (length units).")

    @classmethod
    def coerce(cls, value: Any, name: str = "value") -> Vector:
        """Return ``value`` as a Vector (a Vector or any 2-sequence of numbers), else TypeError.

        >>> import numpy as np
        >>> Vector.coerce(np.array([1.5, 2.0]))
        Vector(1.5, 2.0)
        """
        if type(value) is Vector:
            return value
        pair = as_pair(value)
        if pair is None:
            raise TypeError(not_a_pair(value, name))
        return _new(cls, pair)

    @classmethod
    def zero(cls: type[_V]) -> _V:
        """The zero vector (0, 0), as pymunk's ``Vec2d.zero()``.

        >>> Vector.zero()
        Vector(0.0, 0.0)
        """
        return _new(cls, (0.0, 0.0))

    @ClassOnly
    def from_polar(cls: type[_V], polar: Any) -> _V:  # noqa: N805
        """The vector of length r at phi degrees from the x axis, from the pair (r, phi).

        pygame's ``Vector2.from_polar((r, phi))``: r cos(phi), r sin(phi), phi in degrees.
        Called on the class only (pygame's ``v.from_polar(p)`` changed v in place).

        >>> Vector.from_polar((2, 90))  # cos(pi / 2) is 6e-17 in floating point, as in pygame
        Vector(1.2246467991473532e-16, 2.0)
        >>> Vector.from_polar((1, 0))
        Vector(1.0, 0.0)
        """
        r, phi = _pair(polar, "polar (r, phi in degrees)")
        phi = phi * math.pi / 180.0  # pygame's DEG2RAD, in its order of operations
        return _new(cls, (r * math.cos(phi), r * math.sin(phi)))

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

    def copy(self: _V) -> _V:
        """A new Vector equal to this one (pygame's ``copy()``; a Vector never changes anyway).

        >>> v = Vector(1, 2)
        >>> v.copy() == v, v.copy() is v
        (True, False)
        """
        return _new(type(self), (self[0], self[1]))

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

    def __contains__(self, value: object) -> bool:
        """True when ``value`` is one of the components; TypeError for a non-number, as pygame.

        >>> 2 in Vector(1, 2), 3 in Vector(1, 2)
        (True, False)
        """
        if not is_scalar(value):
            raise TypeError(
                f"'value in vector' needs a real number, got {type(value).__name__} {value!r}"
            )
        return value == self[0] or value == self[1]

    def components(self) -> tuple[float, float]:
        """The lesson's ``components()``: the tuple (x, y), e.g. for drawing functions."""
        return (self[0], self[1])

    # -- arithmetic ---------------------------------------------------------------------
    # The hot paths (+, -, * by a number) name Vector itself: _new(type(self), ...) would cost
    # every Vector ~5 ns (1.5%) an operation. A subclass gets the same operators returning the
    # subclass instead, made for it by __init_subclass__ (``arithmetic_returning``, below).
    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        for name, method in arithmetic_returning(cls).items():
            inherited = getattr(cls, name)
            # Replace only Vector's own operator or one made here: never the subclass's own.
            if getattr(Vector, name) is inherited or getattr(inherited, "_made_for", None):
                if name not in cls.__dict__:
                    setattr(cls, name, method)

    def __add__(self, other: Any) -> Vector:  # type: ignore[override]
        pair = other if type(other) is Vector else as_pair(other)
        if pair is None:
            return NotImplemented
        return _new(Vector, (self[0] + pair[0], self[1] + pair[1]))

    def __radd__(self, other: Any) -> Vector:
        pair = as_pair(other)
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
        pair = other if type(other) is Vector else as_pair(other)
        if pair is None:
            return NotImplemented
        return _new(Vector, (self[0] - pair[0], self[1] - pair[1]))

    def __rsub__(self, other: Any) -> Vector:
        pair = as_pair(other)
        if pair is None:
            return NotImplemented
        return _new(Vector, (pair[0] - self[0], pair[1] - self[1]))

    def __neg__(self) -> Vector:
        return _new(Vector, (-self[0], -self[1]))

    def __pos__(self) -> Vector:
        # A new object, as pygame's +v is (the value is the same: a Vector never changes).
        return _new(Vector, (self[0], self[1]))

    def __mul__(self, other: Any) -> Vector:  # type: ignore[override]
        # Scaling only. The lesson's `*` meant the dot product between two vectors,
        # which hides bugs (a vector times a vector silently becomes a number); and
        # its `*=` scaled only when the other operand was a vector.
        t = type(other)
        if t is float or t is int or is_scalar(other):
            try:
                s = float(other)
            except OverflowError:  # an int beyond the float range
                s = component(other, "scale")  # raises ValueError naming it
            return _new(Vector, (self[0] * s, self[1] * s))
        if isinstance(other, (tuple, list)) or as_pair(other) is not None:
            raise TypeError(
                "Vector * Vector is ambiguous: use v.dot(w) for the dot product, "
                "v.cross(w) for the 2D cross product or v.elementwise() * w for "
                "(v.x w.x, v.y w.y); * scales by a number"
            )
        return NotImplemented

    __rmul__ = __mul__  # type: ignore[assignment]

    def _divisor(self, other: Any, name: str) -> float:
        try:
            s = float(other)
        except OverflowError:  # an int beyond the float range
            s = component(other, name)  # raises ValueError naming it
        if s == 0.0:
            raise ZeroDivisionError(f"cannot divide a Vector by zero ({name} is {other!r})")
        return s

    def __truediv__(self, other: Any) -> Vector:
        if not is_scalar(other):
            return NotImplemented
        s = self._divisor(other, "divisor")
        return _new(Vector, (self[0] / s, self[1] / s))

    def __floordiv__(self, other: Any) -> Vector:
        """Floor division of each component by a number: (x // s, y // s), as Python's //.

        >>> Vector(7, -7) // 2
        Vector(3.0, -4.0)
        """
        if not is_scalar(other):
            return NotImplemented
        s = self._divisor(other, "divisor")
        # Python's float // is the floor of the exact quotient; pygame computes floor(x * (1/s)),
        # which can differ by one where x is an exact multiple of s that 1/s rounds away from.
        return _new(type(self), (self[0] // s, self[1] // s))

    def __round__(self, ndigits: int | None = None) -> Vector:
        """Each component rounded to ``ndigits`` decimals, halves away from zero (pygame's round).

        pygame rounds x * 10^n to the nearest integer, halves away from zero (C's round), then
        divides by 10^n; Python's round(x, n) would send halves to even (round(2.5) is 2).

        >>> round(Vector(1.26, -5.5), 1), round(Vector(2.5, 6.5))
        (Vector(1.3, -5.5), Vector(3.0, 7.0))
        """
        if ndigits is None:
            n = 0
        elif isinstance(ndigits, int) and not isinstance(ndigits, bool):
            n = ndigits
        else:
            raise TypeError(
                f"round(vector, ndigits): ndigits must be an int, "
                f"got {type(ndigits).__name__} {ndigits!r}"
            )
        m = 10.0**n
        return _new(
            type(self), (round_half_away(self[0] * m) / m, round_half_away(self[1] * m) / m)
        )

    # += -= *= are deliberately not defined: Python then falls back to + - *,
    # which rebinds the name to a new Vector and never mutates a shared one.

    def __abs__(self) -> float:
        return self.magnitude()

    def elementwise(self) -> Elementwise:
        """pygame's proxy for component-by-component operations: v.elementwise() * w.

        >>> Vector(2, 3).elementwise() * (4, 5)
        Vector(8.0, 15.0)
        >>> Vector(2, 3).elementwise() > 1
        True
        """
        return Elementwise(self)

    # -- lengths --------------------------------------------------------------------------
    def magnitude(self) -> float:
        """Length |v| = sqrt(x^2 + y^2), in the vector's unit."""
        return math.hypot(self[0], self[1])

    def length(self) -> float:
        """Length |v| = sqrt(x^2 + y^2) (pygame's name for ``magnitude()``), length units.

        math.hypot: within an ulp of pygame's sqrt(x*x + y*y), and without its overflow to inf
        for components beyond 1e154.

        >>> Vector(3, 4).length()
        5.0
        """
        return math.hypot(self[0], self[1])

    def length_squared(self) -> float:
        """|v|^2 = x^2 + y^2 (no square root: cheap for comparisons), length units squared."""
        return self[0] * self[0] + self[1] * self[1]

    magnitude_squared = length_squared

    def is_normalized(self) -> bool:
        """True when |v|^2 is within pygame's 1e-6 of 1 (a unit vector, to rounding).

        >>> Vector(0.6, 0.8).is_normalized(), Vector(3, 4).is_normalized()
        (True, False)
        """
        return abs(self[0] * self[0] + self[1] * self[1] - 1.0) < _EPSILON

    def dot(self, other: VectorLike) -> float:
        """Dot product v . w = v_x w_x + v_y w_y.

        >>> Vector(1, 2).dot((3, 4))
        11.0
        """
        ox, oy = _pair(other, "other")
        return self[0] * ox + self[1] * oy

    def cross(self, other: VectorLike) -> float:
        """2D cross product v x w = v_x w_y - v_y w_x (the z part of the 3D cross product).

        >>> Vector(1, 0).cross((0, 1))
        1.0
        """
        ox, oy = _pair(other, "other")
        return self[0] * oy - self[1] * ox

    def normalized(self: _V) -> _V:
        """The unit vector in the same direction; ValueError for the zero vector.

        >>> Vector(3, 4).normalized()
        Vector(0.6, 0.8)
        """
        m = self.magnitude()
        if m == 0.0:
            raise ValueError(
                "cannot normalize the zero vector: it has no direction "
                "(pygame: Can't normalize Vector of length zero); test `if v:` first"
            )
        if not 1e-290 < m < math.inf:
            if not self.is_finite():
                raise ValueError(f"cannot normalize {self!r}: it must be finite (no nan or inf)")
            # Subnormal components have few bits, so |v| rounds so coarsely that v / |v| is not
            # a unit vector (5e-324 * (1, 1) would give (1, 1)); near the top of the float range
            # |v| overflows to inf (1e308 * (1, 1) would give (0, 0)). Scaling by a power of two
            # first is exact and keeps the direction.
            k = 2.0**600 if m < 1.0 else 2.0**-600
            return _new(type(self), (self[0] * k, self[1] * k)).normalized()
        return _new(type(self), (self[0] / m, self[1] / m))

    def normalize(self: _V) -> _V:
        """The unit vector v / |v| (pygame's name for ``normalized()``); ValueError for zero.

        >>> Vector(0, -7).normalize()
        Vector(0.0, -1.0)
        >>> Vector(0, 0).normalize()
        Traceback (most recent call last):
        ...
        ValueError: cannot normalize the zero vector: it has no direction (pygame: Can't normalize Vector of length zero); test `if v:` first
        """  # noqa: E501
        return self.normalized()

    def scale_to_length(self: _V, length: float) -> _V:
        """A new vector in the same direction with |v| = ``length`` (length units).

        pygame scales v in place and returns None; like pymunk's, this returns the new vector.
        ValueError when |v| < 1e-6 (pygame's threshold): a (near) zero vector has no direction.

        >>> Vector(3, 4).scale_to_length(10)
        Vector(6.0, 8.0)
        """
        new = component(length, "length")
        old = math.sqrt(self[0] * self[0] + self[1] * self[1])
        if old < _EPSILON:
            raise ValueError(
                f"Cannot scale a vector with zero length: |{self!r}| = {old!r} < 1e-6 "
                f"has no direction to keep"
            )
        fraction = new / old
        return _new(type(self), (self[0] * fraction, self[1] * fraction))

    def clamp_magnitude(self: _V, *lengths: float) -> _V:
        """This vector scaled so min <= |v| <= max: ``clamp_magnitude(max)`` or ``(min, max)``.

        pygame's arguments: one number is the maximum length (the minimum is then 0), two
        are (min, max). ValueError for a negative length, min > max, or the zero vector.

        >>> Vector(30, 40).clamp_magnitude(5)
        Vector(3.0, 4.0)
        >>> Vector(0.3, 0.4).clamp_magnitude(1, 5)
        Vector(0.6, 0.8)
        """
        if len(lengths) == 1:
            min_length, max_length = 0.0, component(lengths[0], "max_length")
        elif len(lengths) == 2:
            min_length = component(lengths[0], "min_length")
            max_length = component(lengths[1], "max_length")
        else:
            raise TypeError(
                f"clamp_magnitude takes (max_length) or (min_length, max_length), "
                f"got {len(lengths)} arguments: {lengths!r}"
            )
        if min_length < 0.0 or max_length < 0.0:
            raise ValueError(
                f"Arguments to Vector clamp must be non-negative, got min_length={min_length!r}, "
                f"max_length={max_length!r}"
            )
        if min_length > max_length:
            raise ValueError(
                f"Argument min_length cannot exceed max_length, got min_length={min_length!r} > "
                f"max_length={max_length!r}"
            )
        length_sq = self[0] * self[0] + self[1] * self[1]
        if length_sq == 0.0:
            raise ValueError(
                "Cannot clamp a vector with zero length: the zero vector has no direction"
            )
        # Compare squares (no root needed unless the length changes), as pygame does.
        fraction = 1.0
        if length_sq > max_length * max_length:
            fraction = max_length / math.sqrt(length_sq)
        if length_sq < min_length * min_length:
            fraction = min_length / math.sqrt(length_sq)
        return _new(type(self), (self[0] * fraction, self[1] * fraction))

    # -- distances and interpolation ------------------------------------------------------
    def distance_to(self, other: VectorLike) -> float:
        """Distance |v - w| between two points."""
        ox, oy = _pair(other, "other")
        return math.hypot(self[0] - ox, self[1] - oy)

    def distance_squared_to(self, other: VectorLike) -> float:
        """Squared distance |w - v|^2 between two points (no root: cheap for comparisons).

        >>> Vector(1, 1).distance_squared_to((4, 5))
        25.0
        """
        ox, oy = _pair(other, "other")
        dx = ox - self[0]
        dy = oy - self[1]
        return dx * dx + dy * dy

    def lerp(self: _V, other: VectorLike, t: float) -> _V:
        """The point a fraction 0 <= t <= 1 of the way from v to w: v (1 - t) + w t.

        As pygame's: ValueError for t outside [0, 1]; t = 0 gives v and t = 1 gives w exactly.

        >>> Vector(0, 0).lerp((10, 20), 0.25)
        Vector(2.5, 5.0)
        """
        ox, oy = _pair(other, "other")
        t = component(t, "t")
        if not 0.0 <= t <= 1.0:
            raise ValueError(f"lerp's t must be in range [0, 1], got {t!r}")
        s = 1.0 - t
        return _new(type(self), (self[0] * s + ox * t, self[1] * s + oy * t))

    def slerp(self: _V, other: VectorLike, t: float) -> _V:
        """Spherical interpolation: turn from v towards w by the fraction t of the angle.

        The length goes linearly from |v| to |w|. As pygame's: -1 <= t <= 1, a negative t
        takes the long way round; ValueError for a zero vector or for w opposite to v.

        >>> Vector(1, 0).slerp((0, 1), 0.5).angle_to((1, 1))
        0.0
        """
        ox, oy = _pair(other, "other")
        t = component(t, "t")
        if abs(t) > 1.0:
            raise ValueError(f"slerp's t must be in range [-1, 1], got {t!r}")
        x, y = self[0], self[1]
        length1 = math.sqrt(x * x + y * y)
        length2 = math.sqrt(ox * ox + oy * oy)
        if length1 < _EPSILON or length2 < _EPSILON:
            raise ValueError(
                f"can't use slerp with Zero-Vector: |v| = {length1!r}, |other| = {length2!r} "
                f"(both must be >= 1e-6 to have a direction)"
            )
        # cos(angle) = v . w / (|v| |w|), clamped so rounding cannot push acos out of [-1, 1].
        c = (x * ox + y * oy) / (length1 * length2)
        angle = math.acos(-1.0 if c < -1.0 else (1.0 if c > 1.0 else c))
        if t < 0.0:  # the long arc: the other way round the circle
            angle -= 2.0 * math.pi
            t = -t
        if x * oy < y * ox:  # w is clockwise from v
            angle = -angle
        if abs(angle) < _EPSILON or abs(abs(angle) - 2.0 * math.pi) < _EPSILON:
            # 1 / sin(angle) diverges: the same direction, so interpolate linearly.
            return _new(type(self), (x * (1.0 - t) + ox * t, y * (1.0 - t) + oy * t))
        if abs(abs(angle) - math.pi) < _EPSILON:
            raise ValueError(
                "SLERP with 180 degrees is undefined: other points opposite to this vector"
            )
        # The slerp formula (sin((1-t) a) v/|v| + sin(t a) w/|w|) / sin(a), scaled to the
        # interpolated length (|w| - |v|) t + |v|.
        f0 = ((length2 - length1) * t + length1) / math.sin(angle)
        f1 = math.sin(angle * (1.0 - t)) / length1
        f2 = math.sin(angle * t) / length2
        return _new(type(self), ((x * f1 + ox * f2) * f0, (y * f1 + oy * f2) * f0))

    def move_towards(self: _V, target: VectorLike, max_distance: float) -> _V:
        """The point at most ``max_distance`` from v towards ``target`` (length units).

        Reaching the target returns the target; a negative distance moves away from it.

        >>> Vector(0, 0).move_towards((6, 8), 5)
        Vector(3.0, 4.0)
        >>> Vector(0, 0).move_towards((3, 4), 10)
        Vector(3.0, 4.0)
        """
        tx, ty = _pair(target, "target")
        d = component(max_distance, "max_distance")
        cls = type(self)
        if d == 0.0:
            return _new(cls, (self[0], self[1]))
        dx = tx - self[0]
        dy = ty - self[1]
        dist = math.sqrt(dx * dx + dy * dy)
        if dist <= d or dist == 0.0:  # there already (dist == 0: no direction to move in)
            return _new(cls, (tx, ty))
        f = d / dist  # the fraction of the way there, as pygame 2.6 computes it
        return _new(cls, (self[0] + dx * f, self[1] + dy * f))

    def is_finite(self) -> bool:
        """True when both components are finite (neither nan nor inf)."""
        return math.isfinite(self[0]) and math.isfinite(self[1])

    # -- angles and rotation --------------------------------------------------------------
    @property
    def angle(self) -> float:
        """The angle of v from the x axis, atan2(y, x), in radians in [-pi, pi] (pymunk's).

        >>> Vector(0, 2).angle == math.pi / 2
        True
        """
        return math.atan2(self[1], self[0])

    def angle_to(self, other: VectorLike) -> float:
        """The angle from v to w in degrees: atan2(w) - atan2(v), in (-360, 360) as pygame's.

        >>> Vector(1, 0).angle_to((0, 1))
        90.0
        """
        ox, oy = _pair(other, "other")
        return (math.atan2(oy, ox) - math.atan2(self[1], self[0])) * 180.0 / math.pi

    def as_polar(self) -> tuple[float, float]:
        """The pair (r, phi): length and angle from the x axis in degrees (pygame's).

        >>> Vector(0, 2).as_polar()
        (2.0, 90.0)
        """
        return (self.magnitude(), math.atan2(self[1], self[0]) * 180.0 / math.pi)

    def _rotated_by(self: _V, radians: float) -> _V:
        """pygame's rotation: exact for multiples of 90 degrees (to within 1e-6 rad)."""
        x, y = self[0], self[1]
        # Bring the angle into [0, 2 pi), then quarter turns are exact swaps and sign flips
        # (cos and sin of pi/2 are not exactly 0 and 1 in floating point).
        angle = math.fmod(radians, 2.0 * math.pi)
        if angle < 0.0:
            angle += 2.0 * math.pi
        if math.fmod(angle + _EPSILON, math.pi / 2.0) < 2.0 * _EPSILON:
            quarter = int((angle + _EPSILON) / (math.pi / 2.0))
            if quarter == 1:
                return _new(type(self), (-y, x))
            if quarter == 2:
                return _new(type(self), (-x, -y))
            if quarter == 3:
                return _new(type(self), (y, -x))
            return _new(type(self), (x, y))  # 0 or 4 quarters (360 degrees, pygame issue 214)
        # The rotation matrix [[cos, -sin], [sin, cos]] applied to (x, y).
        s, c = math.sin(angle), math.cos(angle)
        return _new(type(self), (c * x - s * y, s * x + c * y))

    def rotate(self: _V, degrees: float) -> _V:
        """This vector turned counter-clockwise by ``degrees`` (pygame's rotate, degrees).

        >>> Vector(1, 0).rotate(90)
        Vector(-0.0, 1.0)
        """
        return self._rotated_by(component(degrees, "degrees") * math.pi / 180.0)

    def rotate_rad(self: _V, radians: float) -> _V:
        """This vector turned counter-clockwise by ``radians`` (pygame's rotate_rad, radians).

        >>> Vector(1, 0).rotate_rad(math.pi)
        Vector(-1.0, -0.0)
        """
        return self._rotated_by(component(radians, "radians"))

    def rotated(self: _V, radians: float) -> _V:
        """This vector turned counter-clockwise by ``radians`` (pymunk's rotated, radians).

        pymunk's formula, cos and sin with no special cases: Vector(1, 0).rotated(pi / 2)
        has an x of 6e-17 where ``rotate_rad`` gives exactly 0.

        >>> Vector(2, 0).rotated(math.pi / 3).angle == math.pi / 3
        True
        """
        a = component(radians, "radians")
        c, s = math.cos(a), math.sin(a)
        x, y = self[0], self[1]
        return _new(type(self), (x * c - y * s, x * s + y * c))

    def perpendicular(self: _V) -> _V:
        """v turned a quarter turn counter-clockwise: (-y, x) (pymunk's perpendicular).

        >>> Vector(1, 2).perpendicular()
        Vector(-2.0, 1.0)
        """
        return _new(type(self), (-self[1], self[0]))

    # -- reflection and projection --------------------------------------------------------
    def reflect(self: _V, normal: VectorLike) -> _V:
        """v mirrored in the line through 0 perpendicular to ``normal``: v - 2 (v . n) n.

        n is ``normal`` made a unit vector; a bounce off a wall whose normal is ``normal``.
        ValueError when |normal|^2 < 1e-6 (pygame's threshold): a zero normal has no direction.

        >>> Vector(1, -1).reflect((0, 1))
        Vector(1.0, 1.0)
        """
        nx, ny = _pair(normal, "normal")
        n2 = nx * nx + ny * ny
        if n2 < _EPSILON:
            raise ValueError(
                f"Normal must not be of length zero: |normal|^2 = {n2!r} < 1e-6, got {normal!r}"
            )
        # With the unit normal n/|n|: v' = v - 2 (v . n/|n|) n/|n| = v - n (2 (v . n) / (n . n)).
        # The right-hand form needs no square root, so it is exact wherever the products are:
        # (1, -1) reflected in (-1, 1) is exactly (-1, 1), where pygame's normalizing first
        # gives (-0.9999999999999996, ...). For a unit normal the two are the same floats.
        k = 2.0 * (self[0] * nx + self[1] * ny) / n2
        return _new(type(self), (self[0] - nx * k, self[1] - ny * k))

    def project(self: _V, other: VectorLike) -> _V:
        """The projection of v onto w: w (v . w) / (w . w) (pygame's project).

        ValueError when |w|^2 < 1e-6 (pygame's threshold); pymunk's ``projection`` returns
        the zero vector for w = 0 instead.

        >>> Vector(2, 3).project((10, 0))
        Vector(2.0, 0.0)
        """
        ox, oy = _pair(other, "other")
        b2 = ox * ox + oy * oy
        if b2 < _EPSILON:
            raise ValueError(
                f"Cannot project onto a vector with zero length: |other|^2 = {b2!r} < 1e-6, "
                f"got {other!r}"
            )
        factor = (self[0] * ox + self[1] * oy) / b2
        return _new(type(self), (ox * factor, oy * factor))

    def projection(self: _V, other: VectorLike) -> _V:
        """The projection of v onto w: w (v . w) / (w . w); the zero vector for w = 0 (pymunk's).

        >>> Vector(10, 1).projection((10, 5))
        Vector(8.4, 4.2)
        >>> Vector(10, 1).projection((0, 0))
        Vector(0.0, 0.0)
        """
        ox, oy = _pair(other, "other")
        b2 = ox * ox + oy * oy
        if b2 == 0.0:
            return _new(type(self), (0.0, 0.0))
        factor = (self[0] * ox + self[1] * oy) / b2
        return _new(type(self), (ox * factor, oy * factor))


refuse_in_place(Vector)  # pygame's in-place names, each saying what to write instead


# -- the operators made for others: a subclass's arithmetic, and v.elementwise() -------------
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
