"""pymunk's constraints that only the soft step solves: ``SlideJoint``, ``GrooveJoint``,
``GearJoint``, ``RatchetJoint``, ``RotaryLimitJoint`` and ``SimpleMotor``.

Each is a row, or a few, of the soft step's one solver (``World(solver="soft")``;
engine.dynamics.solver, Box2D v3's soft step, where the derivations are): the exact models
(``solver="exact"``) hold none of them, and a World made with that solver refuses one when it
is added, saying so (``World(solver="auto")`` chooses the soft step for a scene that holds
one). ``world.add_link(joint)`` adds one, ``world.remove_link(joint)`` takes it out.

pymunk's arguments and meanings; ``body_a`` and ``body_b`` are each a Body or
``world.static_body`` (not both), and the world's anchors and grooves are world coordinates:

- ``SlideJoint(body_a, body_b, anchor_a, anchor_b, min, max)``: the anchors (each in its
  body's own frame) stay min to max apart (m): a rod where min == max, a cable (that does not
  bounce) where min is 0; a chain's links.
- ``GrooveJoint(body_a, body_b, groove_a, groove_b, anchor_b)``: body_b's anchor stays on the
  segment groove_a..groove_b of body_a's frame, and body_b turns freely about it (Box2D's
  prismatic joint with its ends as limits and no hold on the angle).
- ``GearJoint(body_a, body_b, phase, ratio)``: ratio angle_b - angle_a = phase (rad), so
  omega_a = ratio omega_b: a turns ratio times as fast as b.
- ``RatchetJoint(body_a, body_b, phase, ratchet)``: angle_b - angle_a turns freely the way
  ``ratchet``'s sign says, and back no farther than the last notch it passed (notches at
  phase + k ratchet, rad): a socket wrench.
- ``RotaryLimitJoint(body_a, body_b, min, max)``: min <= angle_b - angle_a <= max (rad).
- ``SimpleMotor(body_a, body_b, rate, max_torque=inf)``: omega_a - omega_b = rate (rad/s),
  with at most ``max_torque`` (N m).

Angles are the bodies' own (pymunk's), not relative to when the joint was made. Every setting
pymunk lets a game change can be changed here at any time (the next step takes it, waking the
bodies). After a step each reports ``linear_impulse`` (N s) and ``angular_impulse`` (N m s),
what it gave body_a in the step (body_b took minus them; a gear gives b -ratio times the
angular one), and ``impulse``, their size (a slide joint's: along it, > 0 pulling, as a rod's).
The two bodies of a joint do not collide with each other unless ``collide=True`` (Box2D's
default, as a Hinge's; pymunk's ``collide_bodies`` is True).

Each has pymunk's three settings of how hard it holds (engine.dynamics.solver's module doc has the
rows' terms), set at any time:

- ``max_force`` (N; N m for the gear, ratchet, rotary limit and motor, whose force is a
  torque; default inf): the most force it gives, at any time: each of its rows' impulse
  summed over a substep of h is kept within max_force h (a groove's along it and across it
  as one vector), so over a step of dt it gives at most max_force dt, and a joint pulled
  harder gives way (a bob that weighs more than a slide joint bears falls at g - max_force
  / m). A SimpleMotor's ``max_force`` is its ``max_torque``, one setting by either name.
- ``max_bias`` (m/s; rad/s for the angular ones; default inf): the fastest it corrects an
  error (a stretched slide joint, a gear off its phase) back; a motor has no error.
- ``error_bias``: pymunk's share of an error left after 1 s (0 to 1), or None (the default):
  the soft step's own joint spring (engine.dynamics.solver: JOINT_HERTZ, 60 Hz at JOINT_DAMPING 2),
  which leaves far less (e^-70 of it after 1 s at steps of 1/60 s in 4 substeps) than
  pymunk's default, (1 - 0.1)^60 = 0.0018 (set ``error_bias = (1 - 0.1) ** 60`` for
  pymunk's slower correction). Set, the joint corrects as pymunk's (Chipmunk's) does: its
  rows rigid, each substep of h pushing the error back at (1 - error_bias^h) / h times itself
  (at most max_bias), so an error left to itself is error_bias of itself after 1 s, at any
  step. It is not mapped onto a stiffness of the spring, though one would correct as slowly
  (8.6 Hz at damping ratio 2 for pymunk's default, at 1/60 s in 4 substeps): a spring gives
  under a steady load, by F / (m omega^2) (3.4 mm under a bob's weight at those 8.6 Hz,
  0.07 mm at 60 Hz), where pymunk's joint holds (its rows are rigid, only their error's
  correction slow). A set error_bias makes the rows rigid with Chipmunk's bias: the spring's
  limit as its stiffness and damping grow with its correction rate kept.

A joint's correction moves its bodies but leaves them no speed (Box2D's relax,
engine.dynamics.solver), where pymunk's bodies move at the correction's speed. The soft step's sleep
counts that move as their speed (engine.pipeline.game_sleep): a body a joint corrects faster than
the sleep's tolerance (0.05 m/s, 2 degrees/s) stays awake, and one corrected more slowly sleeps
(after ``world.sleep_time``) with the rest of its error left, as pymunk's does below its idle speed:
an error e closes at e ln(1 / error_bias) (m/s), under 0.05 m/s for e < 0.47 m at error_bias
0.9, e < 0.072 m at 0.5.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

from .. import checks
from ..body import Body
from ..vector import Vector
from .joints import Joint
from .links import STATIC, StaticBody, local_anchor, refuse_immobile

__all__ = [
    "SoftJoint",
    "SlideJoint",
    "GrooveJoint",
    "GearJoint",
    "RatchetJoint",
    "RotaryLimitJoint",
    "SimpleMotor",
]


def _end(value: Any, name: str) -> Body | None:
    """A joint's body: a 2D Body, or None for ``world.static_body``."""
    if value is STATIC or isinstance(value, StaticBody):
        return None
    if not isinstance(value, Body):
        raise TypeError(
            f"{name} must be a Body or world.static_body, got {type(value).__name__} {value!r}"
        )
    if value.dim != 2:
        raise TypeError(f"{name} must be a 2D body (joints join bodies on a plane), got a 1D body")
    return value


def _angle(body: Body | None) -> float:
    return 0.0 if body is None else body.angle


def _range(low: float, high: float, names: tuple[str, str], unit: str) -> None:
    """Refuse a range out of order, saying which to set first."""
    if not low <= high:
        raise ValueError(
            f"{names[0]} must be <= {names[1]} ({unit}): got {names[0]}={low!r} with "
            f"{names[1]}={high!r}; to move both, set {names[1]} first when raising them, "
            f"{names[0]} first when lowering them"
        )


class SoftJoint(Joint):
    """What pymunk's constraints on the soft step share (the module's text).

    ``body_a`` and ``body_b`` in pymunk's roles (either may be ``world.static_body``), the
    impulses of the last step, ``collide``; the exact models do not solve them
    (``needs_soft``)."""

    __slots__ = ("_a", "_b", "_max_force", "_max_bias", "_error_bias")

    #: Only the soft step's solver holds it (a World with solver="exact" refuses it).
    needs_soft: ClassVar[bool] = True
    #: What its force is measured in (a rotary joint's is a torque) and its bias speed.
    _units: ClassVar[tuple[str, str]] = ("N", "m/s")

    def _join(self, body_a: Any, body_b: Any, collide: Any) -> None:
        self.revision = 0
        self.collide = collide
        a, b = _end(body_a, "body_a"), _end(body_b, "body_b")
        if a is None and b is None:
            raise TypeError(
                "body_a and body_b are both world.static_body: a joint of the world to itself "
                "holds nothing; give a Body as one of them"
            )
        if a is b:
            raise ValueError(
                "body_b must be another Body or world.static_body, got body_a itself: a body "
                "joined to itself holds nothing"
            )
        self._a, self._b = a, b
        # The World's links know a body and its other end (None: the world, at its origin).
        body, other = (a, b) if a is not None else (b, None)
        assert body is not None
        refuse_immobile(body, other, type(self).__name__)
        self._body, self._other = body, other
        self._point = Vector(0.0, 0.0) if other is None else None
        self._anchor_a = self._anchor_b = Vector(0.0, 0.0)
        self._length, self._e = 0.0, 0.0
        self._ref = _angle(a) - _angle(b)
        self._max_force, self._max_bias = math.inf, math.inf
        self._error_bias: float | None = None
        self._pending = None  # a soft step's impulses, not yet put here (Link's)
        # The impulse (N s) the joint gave body_a in the last step (body_b took minus it);
        # the angular impulse (N m s) its angular rows gave body_a.
        self.linear_impulse = Vector(0.0, 0.0)
        self.angular_impulse = 0.0
        self.impulse, self.warned = 0.0, False

    def _changed(self) -> None:
        """A setting changed: the next step takes it, and wakes the bodies (Link.revision)."""
        self.revision += 1

    def _bound(self, name: str, value: Any) -> None:
        """Set ``name`` (a bound's slot) to ``value``, waking the bodies where it changes."""
        if getattr(self, name) != value:
            setattr(self, name, value)
            self._changed()

    @property
    def max_force(self) -> float:
        """The most force the joint gives (N; N m for a rotary joint; inf: as much as it
        takes), pymunk's: each row's impulse over a substep of h at most max_force h."""
        return self._max_force

    @max_force.setter
    def max_force(self, value: Any) -> None:
        self._bound("_max_force", _most(value, "max_force", self._units[0]))

    @property
    def max_bias(self) -> float:
        """The fastest the joint corrects its error (m/s; rad/s for a rotary joint; inf: as
        fast as its spring or error_bias takes it), pymunk's."""
        return self._max_bias

    @max_bias.setter
    def max_bias(self, value: Any) -> None:
        self._bound("_max_bias", _most(value, "max_bias", self._units[1]))

    @property
    def error_bias(self) -> float | None:
        """pymunk's share of an error left after 1 s (0 to 1), or None: the soft step's joint
        spring (the module's text says how they differ)."""
        return self._error_bias

    @error_bias.setter
    def error_bias(self, value: Any) -> None:
        self._bound("_error_bias", _share(value))

    @property
    def body_a(self) -> Any:
        """The first body (pymunk's ``a``), or world.static_body."""
        return STATIC if self._a is None else self._a

    @property
    def body_b(self) -> Any:
        """The second body (pymunk's ``b``), or world.static_body."""
        return STATIC if self._b is None else self._b

    @property
    def angle(self) -> float:
        """body_a's turn relative to body_b since the joint was made (rad), as a Hinge's."""
        return _angle(self._a) - _angle(self._b) - self._ref

    def end_a(self) -> Vector:
        """Where the joint holds body_a now (world coordinates)."""
        p = self._anchor_a
        return p if self._a is None else self._a.local_to_world(p)

    def end_b(self) -> Vector:
        """Where the joint holds body_b now (world coordinates)."""
        p = self._anchor_b
        return p if self._b is None else self._b.local_to_world(p)

    def __repr__(self) -> str:
        bounds = ""
        if self._max_force != math.inf and not isinstance(self, SimpleMotor):
            bounds += f", max_force={self._max_force!r}"
        if self._max_bias != math.inf:
            bounds += f", max_bias={self._max_bias!r}"
        if self._error_bias is not None:
            bounds += f", error_bias={self._error_bias!r}"
        name = type(self).__name__
        return f"{name}({self.body_a!r}, {self.body_b!r}{self._settings()}{bounds})"

    def _settings(self) -> str:
        return ""


class SlideJoint(SoftJoint):
    """Two anchors kept from ``min`` to ``max`` apart (m): pymunk's SlideJoint.

    ``anchor_a`` on body_a and ``anchor_b`` on body_b, each in its body's own frame (m; the
    world's in world coordinates); a rod where min == max, a cable that does not bounce where
    min is 0."""

    __slots__ = ("_min", "_max")

    def __init__(
        self,
        body_a: Any,
        body_b: Any,
        anchor_a: Any,
        anchor_b: Any,
        min: float,
        max: float,
        collide: bool = False,
    ) -> None:
        self._join(body_a, body_b, collide)
        self._anchor_a = local_anchor(anchor_a, "anchor_a")
        self._anchor_b = local_anchor(anchor_b, "anchor_b")
        low = checks.real(min, "min", nonneg=True)
        high = checks.real(max, "max", positive=True)
        _range(low, high, ("min", "max"), "m")
        self._min, self._max = low, high

    @property
    def anchor_a(self) -> Vector:
        """Where it holds body_a, in its own frame (m; the world's: world coordinates)."""
        return self._anchor_a

    @anchor_a.setter
    def anchor_a(self, value: Any) -> None:
        self._anchor_a = local_anchor(value, "anchor_a")
        self._changed()

    @property
    def anchor_b(self) -> Vector:
        """Where it holds body_b, in its own frame (m; the world's: world coordinates)."""
        return self._anchor_b

    @anchor_b.setter
    def anchor_b(self, value: Any) -> None:
        self._anchor_b = local_anchor(value, "anchor_b")
        self._changed()

    @property
    def min(self) -> float:
        """The least distance between the anchors (m, >= 0, <= max)."""
        return self._min

    @min.setter
    def min(self, value: Any) -> None:
        low = checks.real(value, "min", nonneg=True)
        _range(low, self._max, ("min", "max"), "m")
        self._min = low
        self._changed()

    @property
    def max(self) -> float:
        """The most distance between the anchors (m, > 0, >= min)."""
        return self._max

    @max.setter
    def max(self, value: Any) -> None:
        high = checks.real(value, "max", positive=True)
        _range(self._min, high, ("min", "max"), "m")
        self._max = high
        self._changed()

    @property
    def distance(self) -> float:
        """The distance between the anchors now (m)."""
        return (self.end_b() - self.end_a()).length()

    def _settings(self) -> str:
        return f", min={self._min!r}, max={self._max!r}"


class GrooveJoint(SoftJoint):
    """body_b's anchor held on body_a's groove, groove_a to groove_b (m): pymunk's GrooveJoint.

    ``anchor_b`` in body_b's frame, the groove's ends in body_a's (m; the world's in world
    coordinates): body_b slides along the groove and turns freely about its anchor."""

    __slots__ = ("_groove_b",)

    def __init__(
        self,
        body_a: Any,
        body_b: Any,
        groove_a: Any,
        groove_b: Any,
        anchor_b: Any,
        collide: bool = False,
    ) -> None:
        self._join(body_a, body_b, collide)
        self._anchor_a = local_anchor(groove_a, "groove_a")
        self._groove_b = local_anchor(groove_b, "groove_b")
        self._anchor_b = local_anchor(anchor_b, "anchor_b")

    @property
    def groove_a(self) -> Vector:
        """The groove's start, in body_a's frame (m; the world's: world coordinates)."""
        return self._anchor_a

    @groove_a.setter
    def groove_a(self, value: Any) -> None:
        self._anchor_a = local_anchor(value, "groove_a")
        self._changed()

    @property
    def groove_b(self) -> Vector:
        """The groove's end, in body_a's frame (m; the world's: world coordinates)."""
        return self._groove_b

    @groove_b.setter
    def groove_b(self, value: Any) -> None:
        self._groove_b = local_anchor(value, "groove_b")
        self._changed()

    @property
    def anchor_b(self) -> Vector:
        """The point of body_b held in the groove, in its own frame (m; the world's: world
        coordinates)."""
        return self._anchor_b

    @anchor_b.setter
    def anchor_b(self, value: Any) -> None:
        self._anchor_b = local_anchor(value, "anchor_b")
        self._changed()

    @property
    def axis(self) -> tuple[float, float]:
        """The groove's direction in body_a's frame (radians from its x axis; 0 for a groove
        of no length, a pivot) and its length (m)."""
        d = self._groove_b - self._anchor_a
        length = d.length()
        return (math.atan2(d.y, d.x) if length > 0.0 else 0.0), length

    def _settings(self) -> str:
        return f", groove_a={tuple(self._anchor_a)!r}, groove_b={tuple(self._groove_b)!r}"


class GearJoint(SoftJoint):
    """ratio angle_b - angle_a held at phase (rad): pymunk's GearJoint.

    body_a turns ``ratio`` times as fast as body_b (a negative ratio: the other way, as two
    toothed wheels in mesh)."""

    __slots__ = ("_phase", "_ratio")
    _units = ("N m", "rad/s")

    def __init__(
        self, body_a: Any, body_b: Any, phase: float, ratio: float, collide: bool = False
    ) -> None:
        self._join(body_a, body_b, collide)
        self._phase = checks.real(phase, "phase")
        self._ratio = checks.real(ratio, "ratio")

    @property
    def phase(self) -> float:
        """ratio angle_b - angle_a held (rad)."""
        return self._phase

    @phase.setter
    def phase(self, value: Any) -> None:
        self._phase = checks.real(value, "phase")
        self._changed()

    @property
    def ratio(self) -> float:
        """omega_a / omega_b held (1: as one; 0 holds body_a still at angle -phase)."""
        return self._ratio

    @ratio.setter
    def ratio(self, value: Any) -> None:
        self._ratio = checks.real(value, "ratio")
        self._changed()

    def _settings(self) -> str:
        return f", phase={self._phase!r}, ratio={self._ratio!r}"


class RatchetJoint(SoftJoint):
    """angle_b - angle_a free one way, held at its last notch the other (rad): RatchetJoint.

    A socket wrench (pymunk's): it turns freely the way ``ratchet``'s sign says (the angle
    between notches, != 0) and back no farther than the last notch it passed, at ``phase`` +
    k ``ratchet``."""

    __slots__ = ("_phase", "_ratchet", "_notch")
    _units = ("N m", "rad/s")

    def __init__(
        self, body_a: Any, body_b: Any, phase: float, ratchet: float, collide: bool = False
    ) -> None:
        self._join(body_a, body_b, collide)
        self._phase = checks.real(phase, "phase")
        self._ratchet = _ratchet(ratchet)
        self._notch = _angle(self._b) - _angle(self._a)

    @property
    def angle(self) -> float:  # type: ignore[override]
        """The notch the pawl rests against (rad, on angle_b - angle_a), pymunk's ``angle``:
        angle_b - angle_a when the joint is made; it follows the angle forward, notch by
        notch, as the joint turns (each step, from where the step starts)."""
        return self._notch

    @angle.setter
    def angle(self, value: Any) -> None:
        self._notch = checks.real(value, "angle")
        self._changed()

    @property
    def phase(self) -> float:
        """Where the notches are: at phase + k ratchet (rad)."""
        return self._phase

    @phase.setter
    def phase(self, value: Any) -> None:
        self._phase = checks.real(value, "phase")
        self._changed()

    @property
    def ratchet(self) -> float:
        """The angle between notches (rad, != 0); > 0: angle_b - angle_a turns up freely."""
        return self._ratchet

    @ratchet.setter
    def ratchet(self, value: Any) -> None:
        self._ratchet = _ratchet(value)
        self._changed()

    def _advance(self, delta: float) -> float:
        """The notch for angle_b - angle_a = ``delta`` (rad) at a step's start, kept: where
        delta has not fallen back past the notch, the last notch it has reached,
        floor((delta - phase) / ratchet) ratchet + phase (Chipmunk's preStep; with a negative
        ratchet the same formula counts down)."""
        r = self._ratchet
        if (self._notch - delta) * r <= 0.0:
            self._notch = math.floor((delta - self._phase) / r) * r + self._phase
        return self._notch

    def _settings(self) -> str:
        return f", phase={self._phase!r}, ratchet={self._ratchet!r}"


def _ratchet(value: Any) -> float:
    r = checks.real(value, "ratchet")
    if r == 0.0:
        raise ValueError(
            "ratchet must be != 0 (rad): the angle between notches, > 0 where angle_b - "
            "angle_a turns up freely, < 0 where it turns down freely; got 0"
        )
    return r


class RotaryLimitJoint(SoftJoint):
    """min <= angle_b - angle_a <= max (rad): pymunk's RotaryLimitJoint.

    The range may span more than a turn."""

    __slots__ = ("_min", "_max")
    _units = ("N m", "rad/s")

    def __init__(
        self, body_a: Any, body_b: Any, min: float, max: float, collide: bool = False
    ) -> None:
        self._join(body_a, body_b, collide)
        low, high = checks.real(min, "min"), checks.real(max, "max")
        _range(low, high, ("min", "max"), "rad")
        self._min, self._max = low, high

    @property
    def min(self) -> float:
        """The least angle_b - angle_a (rad, <= max)."""
        return self._min

    @min.setter
    def min(self, value: Any) -> None:
        low = checks.real(value, "min")
        _range(low, self._max, ("min", "max"), "rad")
        self._min = low
        self._changed()

    @property
    def max(self) -> float:
        """The most angle_b - angle_a (rad, >= min)."""
        return self._max

    @max.setter
    def max(self, value: Any) -> None:
        high = checks.real(value, "max")
        _range(self._min, high, ("min", "max"), "rad")
        self._max = high
        self._changed()

    def _settings(self) -> str:
        return f", min={self._min!r}, max={self._max!r}"


class SimpleMotor(SoftJoint):
    """omega_a - omega_b driven to rate (rad/s) by at most max_torque (N m): SimpleMotor.

    pymunk's SimpleMotor, its ``max_force`` as ``max_torque`` (inf: as hard as it takes): one
    setting by either name."""

    __slots__ = ("_rate",)
    _units = ("N m", "rad/s")

    def __init__(
        self,
        body_a: Any,
        body_b: Any,
        rate: float,
        max_torque: float = math.inf,
        collide: bool = False,
    ) -> None:
        self._join(body_a, body_b, collide)
        self._rate = checks.real(rate, "rate")
        self._max_force = _most(max_torque, "max_torque", "N m")

    @property
    def rate(self) -> float:
        """omega_a - omega_b the motor drives at (rad/s)."""
        return self._rate

    @rate.setter
    def rate(self, value: Any) -> None:
        self._rate = checks.real(value, "rate")
        self._changed()

    @property
    def max_torque(self) -> float:
        """The most torque the motor gives (N m; inf: as much as it takes): its
        ``max_force``."""
        return self._max_force

    @max_torque.setter
    def max_torque(self, value: Any) -> None:
        self._bound("_max_force", _most(value, "max_torque", "N m"))

    def _settings(self) -> str:
        return f", rate={self._rate!r}, max_torque={self._max_force!r}"


def _most(value: Any, name: str, unit: str) -> float:
    """A bound (max_force, max_bias, max_torque): a real number >= 0 in ``unit``, or inf."""
    if isinstance(value, float) and value == math.inf:
        return math.inf
    try:
        t = checks.real(value, name, nonneg=True)
    except ValueError:
        raise ValueError(f"{name} must be >= 0 in {unit} (inf: no bound), got {value!r}") from None
    return t


def _share(value: Any) -> float | None:
    """An error_bias: None, or a real number from 0 to 1."""
    if value is None:
        return None
    try:
        e = checks.real(value, "error_bias")
    except ValueError:
        e = math.nan
    if not 0.0 <= e <= 1.0:
        raise ValueError(
            "error_bias must be the share of an error left after 1 s, from 0 to 1 (pymunk's "
            f"default: (1 - 0.1) ** 60), or None for the soft step's joint spring; got {value!r}"
        )
    return e
