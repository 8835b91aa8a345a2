"""Force generators: what puts the "?" in the lesson's figure 10 (update acceleration).

A force is pure: ``force(t, x, v, mass)`` returns the force (mass * length / s^2)
on a body at time ``t`` (s) with position ``x`` and velocity ``v``, and never
writes into a body. So an integrator such as RK4 may evaluate it at trial
states that never happen. The same force works on

* floats (a 1D body),
* Vectors (a 2D body),
* numpy arrays of many bodies: x and v of shape (N,) in 1D or (N, 2) in 2D, and
  ``mass`` broadcastable to them (shape (N,) in 1D, (N, 1) in 2D).

Each force also says what the World needs to know about it without calling it:

* ``constant``: it depends on none of t, x, v (then the closed form applies);
* ``stiffness`` (N/m) and ``damping`` (N s/m): for the stability limits
  (a spring k on mass m oscillates at omega = sqrt(k/m); a drag k makes the
  velocity decay at rate k/m);
* ``potential(x, mass)``: its potential energy, or None when it has none;
* ``affine()``: for forces of the form a_0 + F_0/m - (c/m) v, those three
  parts, so a World can fold them into per-body arrays once instead of
  calling the force every step (``engine.dynamics.forcefield``: broadcasting a small
  vector every step costs several times more than adding two arrays).

A generator may give a torque too (N m, counter-clockwise), on the bodies it acts on that
turn (``Body.turns``; a point, a kinematic body or one with ``fixed_rotation`` is never
asked): ``torque(t, angle, omega, moment)``, the rotational twin of the force's signature,
with angle (rad), omega (rad/s) and moment (kg m^2) arrays of shape (k,), one entry per body
that turns. ``Torque`` is the base of generators that give a torque and no force
(``ConstantTorque``, ``AngularDrag``, ``CallableTorque``), and says what the World needs:

* ``torque_affine()``: (tau0, c) for a torque tau0 - c omega with constants (N m, N m s):
  folded, and turned by the exact closed form of the step (engine.dynamics.rotation), at any dt;
* ``angular_damping`` (N m s): for any other torque, which the World evaluates once at the
  step's start and holds over the step (first order in dt), the stability limit of that
  hold: a drag c on a moment I decays at rate c / I and the hold overshoots past c dt / I = 2.

>>> g = Gravity((0, -9.81))
>>> g(0.0, Vector(0, 0), Vector(0, 0), 2.0)
Vector(0.0, -19.62)
>>> Drag(0.5)(0.0, 1.0, 4.0, 1.0)
-2.0
"""

from __future__ import annotations

from collections.abc import Callable
from numbers import Real
from typing import Any

import numpy as np

from .checks import real
from .vector import Vector, as_pair

__all__ = [
    "Force",
    "Gravity",
    "Drag",
    "Wind",
    "Spring",
    "ConstantForce",
    "CallableForce",
    "Torque",
    "ConstantTorque",
    "AngularDrag",
    "CallableTorque",
    "as_force",
]


class _Param:
    """A constant of a force, a float (1D) or a Vector (2D), kept in every form it is used in."""

    __slots__ = ("dim", "value", "array")
    dim: int
    value: Any  # float (1D) or Vector (2D)
    array: Any  # float (1D) or a (2,) numpy array (2D)

    def __init__(self, value: Any, name: str) -> None:
        if isinstance(value, Real) and not isinstance(value, bool):
            f = real(value, name)
            self.dim, self.value, self.array = 1, f, f
            return
        pair = as_pair(value)
        if pair is None:
            raise TypeError(
                f"{name} must be a number (1D) or a Vector / pair of numbers (2D), "
                f"got {type(value).__name__} {value!r}"
            )
        vec = Vector(*pair)
        if not vec.is_finite():
            raise ValueError(f"{name} must be finite, got {value!r}")
        self.dim, self.value = 2, vec
        self.array = np.array(pair, dtype=float)

    def like(self, x: Any) -> Any:
        """The constant in the form that combines with ``x``: array for arrays, else value."""
        return self.array if isinstance(x, np.ndarray) else self.value


def _dot(a: Any, b: Any) -> Any:
    """Per-body dot product: float*float, Vector.Vector, or row-wise over (N, 2) arrays."""
    if isinstance(a, np.ndarray) and a.ndim == 2:
        return a @ np.asarray(b, dtype=float) if np.ndim(b) == 1 else np.einsum("ij,ij->i", a, b)
    if isinstance(a, Vector):
        return a.dot(b)
    return a * b


def _flat_mass(mass: Any) -> Any:
    """Mass as one value per body: (N, 1) -> (N,), float stays float."""
    return mass[:, 0] if isinstance(mass, np.ndarray) and mass.ndim == 2 else mass


class Force:
    """Base class of force generators: ``force(t, x, v, mass) -> force`` (N, or kg m/s^2)."""

    #: True when the force depends on none of t, x, v (the closed form then applies).
    constant: bool = False
    #: Spring stiffness (N/m) for the stability limit omega = sqrt(stiffness / mass); 0 if none.
    stiffness: float = 0.0
    #: Linear drag coefficient (N s/m) for the stability limit rate = damping / mass; 0 if none.
    damping: float = 0.0
    #: 1 or 2 when the force only makes sense in that dimension, None for either.
    dim: int | None = None
    #: Angular drag (N m s) of a torque held over each step (``torque`` without
    #: ``torque_affine``), for that hold's stability limit c dt / I < 2; 0 if none.
    angular_damping: float = 0.0

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        raise NotImplementedError

    def torque(self, t: float, angle: Any, omega: Any, moment: Any) -> Any:
        """Torque (N m, counter-clockwise) at time t (s) on bodies at ``angle`` (rad) turning at
        ``omega`` (rad/s) with moment ``moment`` (kg m^2): a number, or one per body (arrays of
        shape (k,)). A generator that gives no torque leaves this undefined (None)."""
        return None

    @property
    def gives_torque(self) -> bool:
        """Whether this generator gives a torque (its class defines ``torque``)."""
        return type(self).torque is not Force.torque

    def torque_affine(self) -> tuple[float, float] | None:
        """(tau0 N m, c N m s) when the torque is tau0 - c omega with constants; else None."""
        return None

    def potential(self, x: Any, mass: Any) -> Any:
        """Potential energy (J) at ``x``, per body for arrays; None when the force has none."""
        return None

    def affine(self) -> tuple[Any, Any, float] | None:
        """(a0, f0, c) when the force is m a0 + f0 - c v with constants; else None."""
        return None


class Gravity(Force):
    """Uniform gravity: the same acceleration ``g`` (m/s^2) for every mass, F = m g.

    ``g`` is a float in 1D (e.g. -9.81) or a Vector in 2D (e.g. (0, -9.81), y up).
    """

    constant = True

    def __init__(self, g: Any) -> None:
        self._g = _Param(g, "g")
        self.dim = self._g.dim

    @property
    def g(self) -> Any:
        """The acceleration (m/s^2): a float in 1D, a Vector in 2D."""
        return self._g.value

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        return self._g.like(x) * mass

    def potential(self, x: Any, mass: Any) -> Any:
        # F = m g = -grad U  =>  U = -m g . x (zero at the origin).
        return -_flat_mass(mass) * _dot(x, self._g.like(x))

    def affine(self) -> tuple[Any, Any, float]:
        return self._g.value, 0.0, 0.0

    def __repr__(self) -> str:
        return f"Gravity({self.g!r})"


class ConstantForce(Force):
    """A constant force ``f`` (N) on each body it acts on: a thrust, a steady push."""

    constant = True

    def __init__(self, f: Any) -> None:
        self._f = _Param(f, "f")
        self.dim = self._f.dim

    @property
    def f(self) -> Any:
        """The force (N): a float in 1D, a Vector in 2D."""
        return self._f.value

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        f = self._f.like(x)
        return f + 0.0 * x if isinstance(x, np.ndarray) else f

    def potential(self, x: Any, mass: Any) -> Any:
        return -_dot(x, self._f.like(x))

    def affine(self) -> tuple[Any, Any, float]:
        return 0.0, self._f.value, 0.0

    def __repr__(self) -> str:
        return f"ConstantForce({self.f!r})"


class Drag(Force):
    """Linear drag F = -k v (``k`` in N s/m): slows a body toward rest at rate k/m."""

    def __init__(self, k: float) -> None:
        self.k = real(k, "k", nonneg=True)
        self.damping = self.k

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        return v * -self.k

    def affine(self) -> tuple[Any, Any, float]:
        return 0.0, 0.0, self.k

    def __repr__(self) -> str:
        return f"Drag(k={self.k!r})"


class Wind(Force):
    """Drag toward the air's velocity: F = -k (v - air) (``k`` in N s/m, air in m/s).

    A body left in the wind tends to the terminal velocity air + m g / k under
    gravity g. ``air_velocity`` is a constant (float or Vector) or a function
    of time ``air_velocity(t) -> float or Vector`` for a wind that changes.
    """

    def __init__(self, air_velocity: Any, k: float) -> None:
        self.k = real(k, "k", nonneg=True)
        self.damping = self.k
        self._fn: Callable[[float], Any] | None = None
        if callable(air_velocity) and not isinstance(air_velocity, Vector):
            self._fn = air_velocity
            self._air = _Param(air_velocity(0.0), "air_velocity(0)")
        else:
            self._air = _Param(air_velocity, "air_velocity")
        self.dim = self._air.dim

    def air(self, t: float) -> Any:
        """The air's velocity (m/s) at time t (s)."""
        if self._fn is None:
            return self._air.value
        return _Param(self._fn(t), f"air_velocity({t})").value

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        if self._fn is None:
            air = self._air.like(v)
        else:
            p = _Param(self._fn(t), f"air_velocity({t})")
            air = p.like(v)
        return (v - air) * -self.k

    def affine(self) -> tuple[Any, Any, float] | None:
        if self._fn is not None:
            return None
        # -k (v - air) = k air - k v
        return 0.0, self._air.value * self.k, self.k

    def __repr__(self) -> str:
        air = self._fn if self._fn is not None else self._air.value
        return f"Wind(air_velocity={air!r}, k={self.k!r})"


class Spring(Force):
    """A spring from a fixed ``anchor`` point: F = -k (|d| - L) d / |d|, d = x - anchor.

    ``k`` is the stiffness (N/m) and ``rest_length`` L (m) the length at which
    it pulls nothing. With L = 0 this is the harmonic oscillator F = -k d, whose
    angular frequency on a mass m is omega = sqrt(k / m) (rad/s).
    """

    def __init__(self, anchor: Any, k: float, rest_length: float = 0.0) -> None:
        self._anchor = _Param(anchor, "anchor")
        self.dim = self._anchor.dim
        self.k = real(k, "k", nonneg=True)
        self.stiffness = self.k
        self.rest_length = real(rest_length, "rest_length", nonneg=True)

    @property
    def anchor(self) -> Any:
        """The fixed end of the spring (m): a float in 1D, a Vector in 2D."""
        return self._anchor.value

    def _stretch(self, x: Any) -> tuple[Any, Any]:
        """(d, e): the displacement from the anchor and the spring's extension |d| - L."""
        d = x - self._anchor.like(x)
        if isinstance(d, np.ndarray):
            length = np.abs(d) if d.ndim == 1 else np.hypot(d[:, 0], d[:, 1])
        else:
            length = abs(d)
        return d, length - self.rest_length

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        d, extension = self._stretch(x)
        if self.rest_length == 0.0:
            return d * -self.k  # -k (|d|) d/|d| = -k d, smooth through the anchor
        # Direction d/|d|; at the anchor itself the direction is undefined: no force.
        if isinstance(d, np.ndarray):
            length = extension + self.rest_length
            scale = np.divide(
                -self.k * extension, length, out=np.zeros_like(length), where=length > 0
            )
            return d * (scale if d.ndim == 1 else scale[:, None])
        length = extension + self.rest_length
        if length == 0.0:
            return d * 0.0
        return d * (-self.k * extension / length)

    def potential(self, x: Any, mass: Any) -> Any:
        _, extension = self._stretch(x)
        return 0.5 * self.k * extension * extension

    def __repr__(self) -> str:
        return f"Spring(anchor={self.anchor!r}, k={self.k!r}, rest_length={self.rest_length!r})"


class CallableForce(Force):
    """Wraps a user's function ``fn(t, x, v, mass) -> force`` as a Force.

    Say what you know of it so the World can use it: ``constant=True`` when it
    depends on none of t, x, v; ``stiffness`` / ``damping`` for the stability
    limits; ``potential(x, mass)`` for ``World.energy()``.
    """

    def __init__(
        self,
        fn: Callable[[float, Any, Any, Any], Any],
        *,
        constant: bool = False,
        stiffness: float = 0.0,
        damping: float = 0.0,
        potential: Callable[[Any, Any], Any] | None = None,
    ) -> None:
        if not callable(fn):
            raise TypeError(
                f"a force must be a Force or a callable fn(t, x, v, mass) -> force, "
                f"got {type(fn).__name__} {fn!r}"
            )
        self.fn = fn
        self.constant = bool(constant)
        self.stiffness = real(stiffness, "stiffness", nonneg=True)
        self.damping = real(damping, "damping", nonneg=True)
        self._potential = potential

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        return self.fn(t, x, v, mass)

    def potential(self, x: Any, mass: Any) -> Any:
        return None if self._potential is None else self._potential(x, mass)

    def __repr__(self) -> str:
        return f"CallableForce({self.fn!r})"


class Torque(Force):
    """Base of generators that give a torque and no force: subclass it and define
    ``torque(t, angle, omega, moment) -> torque`` (N m, counter-clockwise; arrays of shape (k,)
    for the k bodies it acts on that turn), and ``torque_affine`` / ``angular_damping`` when
    you know them (see the module's docstring).

    >>> class Motor(Torque):
    ...     def torque(self, t, angle, omega, moment):
    ...         return 2.0 * (omega < 10.0)  # 2 N m until it turns at 10 rad/s
    """

    constant = True  # its force, none, depends on nothing
    dim = 2  # bodies turn in a 2D World

    def __call__(self, t: float, x: Any, v: Any, mass: Any) -> Any:
        return x * 0.0  # no force

    def affine(self) -> tuple[Any, Any, float]:
        return 0.0, 0.0, 0.0

    def torque(self, t: float, angle: Any, omega: Any, moment: Any) -> Any:
        raise NotImplementedError(
            f"{type(self).__name__} is a Torque: define torque(t, angle, omega, moment) -> N m"
        )


class ConstantTorque(Torque):
    """A constant torque ``tau`` (N m, counter-clockwise) on each body it acts on that turns:
    a motor without a speed limit, a steady twist. Exact at any dt: it adds to the body's own
    torque (``Body.torque``), so theta = theta0 + omega0 t + (tau / I) t^2 / 2."""

    def __init__(self, tau: float) -> None:
        self.tau = real(tau, "tau")

    def torque(self, t: float, angle: Any, omega: Any, moment: Any) -> Any:
        return self.tau + 0.0 * omega

    def torque_affine(self) -> tuple[float, float]:
        return self.tau, 0.0

    def __repr__(self) -> str:
        return f"ConstantTorque({self.tau!r})"


class AngularDrag(Torque):
    """Angular drag tau = -c omega (``c`` in N m s): slows a spin toward rest at rate c / I.

    Exact at any dt (no stability limit): a body that turns freely takes the closed form
    omega(t) = tau0 / c + (omega0 - tau0 / c) e^(-c t / I), with tau0 its other constant
    torques, and the angle its integral.
    """

    def __init__(self, c: float) -> None:
        self.c = real(c, "c", nonneg=True)

    def torque(self, t: float, angle: Any, omega: Any, moment: Any) -> Any:
        return omega * -self.c

    def torque_affine(self) -> tuple[float, float]:
        return 0.0, self.c

    def __repr__(self) -> str:
        return f"AngularDrag(c={self.c!r})"


class CallableTorque(Torque):
    """Wraps a user's function ``fn(t, angle, omega, moment) -> torque`` (N m) as a Torque.

    The World calls it once a step, at the step's start, with arrays of shape (k,) for the k
    bodies it acts on that turn, and holds its torque over the step: first order in dt. A torque
    that slows a spin, like -c omega, overshoots past c dt / I = 2: say its ``angular_damping``
    c (N m s) and the World warns before that (better: ``AngularDrag(c)`` is exact).
    """

    def __init__(
        self, fn: Callable[[float, Any, Any, Any], Any], *, angular_damping: float = 0.0
    ) -> None:
        if not callable(fn):
            raise TypeError(
                f"a torque must be a callable fn(t, angle, omega, moment) -> torque in N m, "
                f"got {type(fn).__name__} {fn!r}"
            )
        self.fn = fn
        self.angular_damping = real(angular_damping, "angular_damping", nonneg=True)

    def torque(self, t: float, angle: Any, omega: Any, moment: Any) -> Any:
        return self.fn(t, angle, omega, moment)

    def __repr__(self) -> str:
        return f"CallableTorque({self.fn!r})"


def as_force(force: Any) -> Force:
    """``force`` itself if it is a Force, a CallableForce around a callable, else TypeError."""
    if isinstance(force, Force):
        return force
    if callable(force):
        return CallableForce(force)
    raise TypeError(
        f"force must be a Force (Gravity, Drag, Wind, Spring, ...) or a callable "
        f"fn(t, x, v, mass) -> force, got {type(force).__name__} {force!r}"
    )
