"""Springs between bodies: pymunk's ``DampedSpring`` and ``DampedRotarySpring``.

A spring is a force, not a constraint: it pulls, and the bodies move as the pull allows.

- ``DampedSpring(a, b, anchor_a, anchor_b, rest_length, stiffness, damping)``: between the
  anchors p_a and p_b (each in its body's own frame; for ``b = world.static_body``, anchor_b
  is a point in world coordinates), with d = p_b - p_a and n = d / |d|, the force on b is

      F_b = -stiffness (|d| - rest_length) n - damping ((v_b - v_a) . n) n      (N)

  and on a it is -F_b, each at its anchor (so it turns a body that turns: torque r x F).
  v_a, v_b are the anchors' velocities (v + omega x r). The damping acts along the spring
  only, as pymunk's does.
- ``DampedRotarySpring(a, b, rest_angle, stiffness, damping)``: the torque on a is

      tau_a = -stiffness (angle_a - angle_b - rest_angle) - damping (omega_a - omega_b)  (N m)

  and on b it is -tau_a (``b = world.static_body``: a spring to the world's angle 0).

``world.add_link(spring)`` adds one, ``world.remove_link(spring)`` takes it out, and
``world.springs`` lists them; every setting can be changed after the spring is made, as in
pymunk. How the World moves them (engine.exact.spring_step): the closed form when the scene is
linear (a damped harmonic oscillator, exact at any dt), else pymunk's scheme made second order.

>>> from engine import Body, Vector
>>> a, b = Body(Vector(0, 0), mass=1.0), Body(Vector(3, 4), mass=1.0)
>>> s = DampedSpring(a, b, (0, 0), (0, 0), rest_length=2.0, stiffness=10.0, damping=0.0)
>>> s.length, s.energy()
(5.0, 45.0)
"""

from __future__ import annotations

from typing import Any, ClassVar

from .. import checks
from ..body import Body
from ..vector import Vector
from .links import STATIC, StaticBody, fixed_point, local_anchor, note_edit, plane_body
from .reported import Pending, Reported, reported_state

__all__ = ["DampedSpring", "DampedRotarySpring", "BodySpring"]


def _second(value: Any, name: str) -> Body | None:
    """The second body, or None for ``world.static_body`` (an error names anything else)."""
    if value is STATIC or isinstance(value, StaticBody):
        return None
    if not isinstance(value, Body):
        raise TypeError(
            f"{name} must be a Body or world.static_body (to hold to the world), got "
            f"{type(value).__name__} {value!r}"
        )
    return plane_body(value, name)


def _first(a: Any, b: Body | None) -> Body:
    """The first body: a 2D Body, not ``b`` itself, and not both immovable."""
    if a is STATIC or isinstance(a, StaticBody):
        raise TypeError("a must be a Body: give the moving body first and world.static_body second")
    body = plane_body(a, "a")
    if body is b:
        raise ValueError("b must be another Body or world.static_body, got a itself")
    return body


def _nonneg(value: Any, name: str, unit: str) -> float:
    """``value`` as a finite float >= 0, or an error naming ``name`` and its unit."""
    try:
        return checks.real(value, name, nonneg=True)
    except ValueError:
        raise ValueError(f"{name} must be a finite number >= 0 {unit}, got {value!r}") from None


class BodySpring:
    """What both springs share: the two bodies, the settings' revision, the last impulse."""

    __slots__ = (
        "_a", "_b", "_stiffness", "_damping", "_revision", "_impulse", "_pending", "warned",
    )  # fmt: skip

    impulse: Reported[float] = Reported(
        "The impulse the spring gave in the last step (see each class)."
    )

    def __getstate__(self) -> tuple[None, dict[str, Any]]:
        """For ``copy`` and ``pickle``: the slots, the last step's impulses put on it first
        (engine.dynamics.reported.reported_state)."""
        return reported_state(self)

    @property
    def revision(self) -> int:
        """Counts changes of the settings (the World rebuilds what it keeps of them; each
        counted in engine.dynamics.links' ``edits`` too)."""
        return self._revision

    @revision.setter
    def revision(self, value: int) -> None:
        self._revision = value
        note_edit()

    #: Both solvers hold a spring (engine.dynamics.constraints' joints are the soft step's alone).
    needs_soft: ClassVar[bool] = False

    def __init__(self, a: Any, b: Any, stiffness: Any, damping: Any, unit: str) -> None:
        self._b = _second(b, "b")
        self._a = _first(a, self._b)
        self._stiffness = _nonneg(stiffness, "stiffness", unit)
        self._damping = _nonneg(damping, "damping", unit + " s")
        self.revision = 0  # (the property's text)
        self._pending: Pending | None = None  # a soft step's impulse, not yet put here
        self.impulse = 0.0
        #: Whether the World has warned that this spring is too stiff for its dt.
        self.warned = False

    def _changed(self) -> None:
        self.revision += 1

    @property
    def a(self) -> Body:
        """The first body (pymunk's ``a``)."""
        return self._a

    @property
    def b(self) -> Body | StaticBody:
        """The second body, or ``world.static_body`` (pymunk's ``b``)."""
        return STATIC if self._b is None else self._b

    @property
    def second(self) -> Body | None:
        """The second body, or None for a spring to the world."""
        return self._b

    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies the spring joins (one for a spring to the world)."""
        return (self._a,) if self._b is None else (self._a, self._b)

    def energy(self) -> float:
        """The energy the spring stores now (J)."""
        raise NotImplementedError

    @property
    def stiffness(self) -> float:
        """The spring constant (N/m, or N m/rad for the rotary spring)."""
        return self._stiffness

    @stiffness.setter
    def stiffness(self, value: Any) -> None:
        self._stiffness = _nonneg(value, "stiffness", "(N/m, or N m/rad)")
        self._changed()

    @property
    def damping(self) -> float:
        """The damping (N s/m, or N m s/rad for the rotary spring)."""
        return self._damping

    @damping.setter
    def damping(self, value: Any) -> None:
        self._damping = _nonneg(value, "damping", "(N s/m, or N m s/rad)")
        self._changed()


class DampedSpring(BodySpring):
    """A spring and damper between anchors of two bodies (see the module's text).

    ``impulse`` (N s): the impulse it gave along it in the last step, the integral over the
    step of its tension stiffness (|d| - rest_length) + damping d|d|/dt, > 0 pulling the ends
    together, as a rod's (pymunk's ``impulse`` has the other sign). By kicks it is what the
    step's two half kicks gave (velocity Verlet's: half the pull where the step starts, half
    where it ends, and the damper's). On the closed form (engine.exact.spring_step: rest length 0,
    a linear scene) it is measured from the closed-form solution, exactly (to round-off)
    while the spring keeps its direction through the step: its ends move along one line (a
    damped spring's must there) and do not pass each other. Where it turns by an angle theta
    within the step (an undamped spring whose ends circle), it falls short by about
    theta^2 / 24 of itself; in a step where the ends pass each other, by more.
    """

    __slots__ = ("_anchor_a", "_anchor_b", "_rest")

    def __init__(
        self,
        a: Any,
        b: Any,
        anchor_a: Any,
        anchor_b: Any,
        rest_length: float,
        stiffness: float,
        damping: float,
    ) -> None:
        super().__init__(a, b, stiffness, damping, "(N/m)")
        self._anchor_a = local_anchor(anchor_a, "anchor_a")
        self._anchor_b = self._point_b(anchor_b)
        self._rest = _nonneg(rest_length, "rest_length", "(m)")

    def _point_b(self, value: Any) -> Vector:
        if self._b is None:
            return fixed_point(value, "anchor_b (a point in world coordinates, b being the world)")
        return local_anchor(value, "anchor_b")

    @property
    def anchor_a(self) -> Vector:
        """Where the spring holds a, in a's own frame (m)."""
        return self._anchor_a

    @anchor_a.setter
    def anchor_a(self, value: Any) -> None:
        self._anchor_a = local_anchor(value, "anchor_a")
        self._changed()

    @property
    def anchor_b(self) -> Vector:
        """Where the spring holds b, in b's own frame (m; in world coordinates for the world)."""
        return self._anchor_b

    @anchor_b.setter
    def anchor_b(self, value: Any) -> None:
        self._anchor_b = self._point_b(value)
        self._changed()

    @property
    def rest_length(self) -> float:
        """The length at which the spring pulls nothing (m)."""
        return self._rest

    @rest_length.setter
    def rest_length(self, value: Any) -> None:
        self._rest = _nonneg(value, "rest_length", "(m)")
        self._changed()

    def end_a(self) -> Vector:
        """Where the spring holds a now, in world coordinates (m)."""
        return self._a.local_to_world(self._anchor_a)

    def end_b(self) -> Vector:
        """Where the spring holds b now, in world coordinates (m)."""
        return self._anchor_b if self._b is None else self._b.local_to_world(self._anchor_b)

    @property
    def length(self) -> float:
        """The distance between the anchors now (m)."""
        return (self.end_b() - self.end_a()).length()

    def energy(self) -> float:
        """The energy the spring stores now (J): stiffness (|d| - rest_length)^2 / 2."""
        e = self.length - self._rest
        return 0.5 * self._stiffness * e * e

    def __repr__(self) -> str:
        to = "the world" if self._b is None else "a body"
        return (
            f"DampedSpring(rest_length={self._rest!r}, stiffness={self._stiffness!r}, "
            f"damping={self._damping!r}, to {to})"
        )


class DampedRotarySpring(BodySpring):
    """A torsion spring and damper between the angles of two bodies (see the module's text).

    ``impulse`` (N m s): the angular impulse it gave body a in the last step, counter-clockwise
    > 0 (b was given the opposite): > 0 when it turns a counter-clockwise, as when twist < 0.
    It is what the step's two half kicks gave (velocity Verlet's: half the torque where the
    step starts, half where it ends, and the damper's). pymunk's ``impulse`` has the other
    sign: its spring's part is the angular impulse on b (pymunk's testTorqueFunc scene gives
    +13.25 here, -21.5 in pymunk, whose step takes the torque where it ends).
    """

    __slots__ = ("_rest",)

    def __init__(self, a: Any, b: Any, rest_angle: float, stiffness: float, damping: float) -> None:
        super().__init__(a, b, stiffness, damping, "(N m/rad)")
        self._rest = checks.real(rest_angle, "rest_angle")

    @property
    def rest_angle(self) -> float:
        """The angle of a relative to b at which the spring twists nothing (rad)."""
        return self._rest

    @rest_angle.setter
    def rest_angle(self, value: Any) -> None:
        self._rest = checks.real(value, "rest_angle")
        self._changed()

    @property
    def twist(self) -> float:
        """angle_a - angle_b - rest_angle now (rad)."""
        b = 0.0 if self._b is None else self._b.angle
        return self._a.angle - b - self._rest

    def energy(self) -> float:
        """The energy the spring stores now (J): stiffness twist^2 / 2."""
        return 0.5 * self._stiffness * self.twist**2

    def __repr__(self) -> str:
        to = "the world" if self._b is None else "a body"
        return (
            f"DampedRotarySpring(rest_angle={self._rest!r}, stiffness={self._stiffness!r}, "
            f"damping={self._damping!r}, to {to})"
        )
