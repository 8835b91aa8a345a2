"""The values a Body is made of, checked: states, masses, materials and rotation's numbers.

Each check raises a TypeError or ValueError that names the argument, the value and what would
be valid, so that ``Body`` (engine.body) and the World's snapshots refuse bad input in one
wording. Standard library and engine.vector only, as Body itself.
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any

from . import checks
from .vector import Vector, as_pair

__all__ = [
    "RESTITUTION",
    "FRICTION",
    "DEFAULT_MASS",
    "State",
    "coerce_state",
    "coerce_mass",
    "coerce_density",
    "material",
    "real_number",
    "finite",
    "pair",
    "refuse_change",
]

#: A body's restitution when none is given: 0, no bounce unless asked for (Box2D's default;
#: pymunk's too). Materials multiply (engine.geometry.colliders), and a collider's own default is 1.
RESTITUTION = 0.0
#: A body's friction coefficient when none is given: 0.6, Box2D's default (pymunk's is 0, so
#: that everything slides unless told). On a collider of the default 1, mu = 0.6.
FRICTION = 0.6

_isfinite = math.isfinite


class _DefaultMass(float):
    """A float that is Body's default mass: ``mass is DEFAULT_MASS`` tells "not given" apart
    from a mass of 1.0 given, which a density given too contradicts."""

    __slots__ = ()


#: A body's mass (kg) when given neither ``mass`` nor ``density``: 1.0.
DEFAULT_MASS: float = _DefaultMass(1.0)

#: A state value: a float for a 1D body, a Vector for a 2D body.
State = float | Vector


def dim_of(value: Any) -> int | None:
    """1 for a real number, 2 for a Vector or pair of numbers, None for anything else."""
    if isinstance(value, Real) and not isinstance(value, bool):
        return 1
    if as_pair(value) is not None:
        return 2
    return None


def coerce_state(value: Any, dim: int, name: str) -> State:
    """Return ``value`` as a finite state of dimension ``dim`` (float or Vector), else raise.

    TypeError for the wrong kind (naming ``name`` and what would be valid), ValueError for
    nan or inf.
    """
    t = type(value)
    if (t is Vector and dim == 2 and _isfinite(value[0]) and _isfinite(value[1])) or (
        t is float and dim == 1 and _isfinite(value)
    ):
        return value  # the common case, already exactly right
    got = dim_of(value)
    if got != dim:
        want = "a real number (1D)" if dim == 1 else "a Vector or pair of numbers (2D)"
        what = {1: "a number (1D)", 2: "a Vector (2D)"}.get(got or 0, type(value).__name__)
        raise TypeError(f"{name} must be {want}, got {what}: {value!r}")
    try:
        state: State = float(value) if dim == 1 else Vector.coerce(value, name)
    except OverflowError:  # an int beyond the float range
        raise ValueError(f"{name} must be finite (within the float range), got {value!r}") from None
    finite = math.isfinite(state) if isinstance(state, float) else state.is_finite()
    if not finite:
        raise ValueError(f"{name} must be finite (no nan or inf), got {value!r}")
    return state


def coerce_mass(mass: Any) -> float:
    """Return ``mass`` as a positive finite float (kilograms, or the scene's mass unit)."""
    return checks.mass(mass)


def coerce_density(density: Any, name: str = "density") -> float:
    """Return ``density`` as a positive finite float (kg per length unit squared: a 2D density,
    the body's mass per unit of its shape's area): checks.mass's test, in density's words
    (``name``: the argument's, a shape's own ``density[i]``)."""
    try:
        return checks.mass(density, name)
    except TypeError:
        raise TypeError(
            f"{name} must be a real number (kg/m^2: the body's mass per square metre of its "
            f"shape, e.g. 1.0; with shapes=[...], a list of one for each), got "
            f"{type(density).__name__} {density!r}"
        ) from None
    except ValueError:
        raise ValueError(
            f"{name} must be > 0 and finite (kg/m^2: the body's mass per square metre of its "
            f"shape, e.g. 1.0, Box2D's default), got {density!r}"
        ) from None


def material(radius: Any, restitution: Any, friction: Any) -> tuple[float, float, float]:
    """(radius >= 0, restitution in [0, 1], friction >= 0), checked, each error naming its name."""
    r = checks.real(radius, "radius", nonneg=True)
    e = checks.real(restitution, "restitution")
    if not 0.0 <= e <= 1.0:
        raise ValueError(
            f"restitution must be in [0, 1] (0: no bounce, 1: elastic), got {restitution!r}"
        )
    return r, e, checks.real(friction, "friction", nonneg=True)


def real_number(value: Any, name: str) -> float:
    """A real number (not a bool) as a float; TypeError / ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")
    try:
        number = float(value)
    except OverflowError:  # an int or a fraction beyond the float range
        number = math.inf if value > 0 else -math.inf  # type: ignore[operator]
    if math.isnan(number):
        raise ValueError(f"{name} must be a number, got nan")
    return number


def finite(value: Any, name: str) -> float:
    """A finite real number as a float; TypeError / ValueError naming ``name``."""
    number = real_number(value, name)
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return number


def pair(value: Any, name: str) -> tuple[float, float]:
    """A finite 2D point or vector (a Vector or a pair of numbers), naming ``name``."""
    pair = as_pair(value)
    if pair is None:
        raise TypeError(
            f"{name} must be a Vector or a pair of numbers, got {type(value).__name__} {value!r}"
        )
    x, y = float(pair[0]), float(pair[1])
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return x, y


def refuse_change(name: str, value: Any) -> None:
    """Refuse a change of what a Body is made with, saying how to get it."""
    raise AttributeError(
        f"a Body's {name} is fixed when it is made (the World keeps it in its arrays), so "
        f"body.{name} = {value!r} cannot change it: make a new Body(..., {name}={value!r}) "
        f"instead (world.remove(body), then world.add(new))"
    )
