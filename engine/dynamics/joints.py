"""Joints at anchors: a ``Hinge`` (two bodies share a point and turn about it, with optional
limits and a motor) and a ``Weld`` (two bodies held as one, rigidly or as a spring).

Rods, cables and pins (engine.dynamics.links) hold bodies at anchors too (``anchor_a``,
``anchor_b``, in each body's own frame). Every joint is a link: ``world.add_link(joint)`` adds it,
``world.remove_link(joint)`` takes it out, and ``world.static_body`` as the second body
joins a body to the world (its point then given in world coordinates). The joint solver
(engine.exact.joint_solver) corrects each step for them, all together: the positions and angles
exactly onto the joints (RATTLE, as for the rods of points), then the velocities.

pymunk's names: ``Hinge`` is its PivotJoint, with RotaryLimitJoint (``limits``) and
SimpleMotor (``motor_speed``, ``max_torque``) built in; ``Weld`` is Box2D's weld joint (pymunk
has none: a PivotJoint with a GearJoint).

The joint's angle is body_a's angle relative to body_b's, less what it was when the joint
was made: a hinge starts at angle 0, its limits and its motor act on that angle.
"""

from __future__ import annotations

import math
from typing import Any

from .. import checks
from ..body import Body
from ..vector import Vector
from .links import STATIC, Link, fixed_point, local_anchor, note_edit, plane_body, refuse_immobile
from .reported import Reported

__all__ = [
    "Hinge",
    "Weld",
    "Joint",
    "KINDS",
    "geometry",
    "settings",
    "check_settings",
    "apply_settings",
    "rebuild",
]


def _second(body_b: Any) -> Any:
    """body_b checked: a 2D Body, or world.static_body."""
    if body_b is STATIC:
        return None
    return plane_body(body_b, "body_b")


class Joint(Link):
    """What a Hinge and a Weld share: two bodies (or a body and the world), the angle of
    body_a relative to body_b when made, and the impulses of the last step."""

    __slots__ = ("_ref", "_linear_impulse", "_angular_impulse", "_collide")

    linear_impulse: Reported[Vector] = Reported(
        "The impulse (N s) the joint gave body_a in the last step (body_b took minus it)."
    )
    angular_impulse: Reported[float] = Reported(
        "The angular impulse (N m s) the joint's limits, motor or weld gave body_a in the "
        "last step, about its centre (body_b took minus it)."
    )

    def _setup(self, body_a: Any, body_b: Any, point: Any, collide: Any = False) -> None:
        self.revision = 0
        self.collide = collide
        self._body = plane_body(body_a, "body_a")
        other = _second(body_b)
        if other is self._body:
            raise ValueError(
                "body_b must be another Body or world.static_body, got body_a itself: a body "
                "joined to itself holds nothing"
            )
        refuse_immobile(self._body, other, type(self).__name__)
        p = fixed_point(point, "point")
        self._anchor_a = self._body.world_to_local(p)
        if other is None:
            self._other, self._point, self._anchor_b = None, p, Vector(0.0, 0.0)
        else:
            self._other, self._point = other, None
            self._anchor_b = other.world_to_local(p)
        self._length, self._e = 0.0, 0.0
        self._ref = self._body.angle - (0.0 if other is None else other.angle)
        self._pending = None  # a soft step's impulses, not yet put here (Link's)
        self.linear_impulse = Vector(0.0, 0.0)
        self.angular_impulse = 0.0
        self.impulse, self.warned = 0.0, False

    @property
    def collide(self) -> bool:
        """Whether the two bodies still collide with each other (False: Box2D's default); it
        may be set at any time (the next step takes it)."""
        return self._collide

    @collide.setter
    def collide(self, value: Any) -> None:
        if not isinstance(value, bool):
            raise TypeError(f"collide must be True or False, got {value!r}")
        self._collide = value
        self.revision += 1

    @property
    def kept_apart(self) -> tuple[Any, Any] | None:
        """The two bodies this joint keeps from colliding with each other (``collide`` False,
        neither end the world), or None."""
        if self._collide or self._other is None:
            return None
        return self._body, self._other

    @property
    def body_a(self) -> Any:
        """The first body."""
        return self._body

    @property
    def body_b(self) -> Any:
        """The second body, or world.static_body."""
        return STATIC if self._other is None else self._other

    @property
    def reference_angle(self) -> float:
        """body_a's angle less body_b's when the joint was made (rad)."""
        return self._ref

    @property
    def angle(self) -> float:
        """The joint's angle now (rad): body_a's turn relative to body_b since it was made."""
        b = 0.0 if self._other is None else self._other.angle
        return self._body.angle - b - self._ref

    @property
    def point(self) -> Vector:
        """Where the joint holds body_a now (world coordinates)."""
        return self.end_a()

    def force(self, dt: float) -> Vector:
        """The mean force (N) on body_a over the last step of ``dt`` s."""
        return self.linear_impulse / checks.seconds(dt)

    def torque(self, dt: float) -> float:
        """The mean torque (N m) of limits, motor or weld on body_a over the last step."""
        return self.angular_impulse / checks.seconds(dt)


class Hinge(Joint):
    """``body_a`` and ``body_b`` (or world.static_body) share ``point`` (world coordinates
    when made) and turn freely about it; ``limits=(lower, upper)`` (rad) bound the joint's
    angle, and a motor turns body_a relative to body_b at ``motor_speed`` (rad/s) with at
    most ``max_torque`` (N m; inf: as hard as it takes). The two bodies do not collide with
    each other unless ``collide=True``.

    Instead of ``point``, ``anchor_a`` and ``anchor_b`` (pymunk's PivotJoint by anchors) give
    the point in each body's own frame (anchor_b in world coordinates for the static body);
    they must be one point in the world when the hinge is made (to 1e-9 of the bodies'
    reach), as a ValueError naming the gap says otherwise."""

    __slots__ = ("_limits", "_speed", "_max_torque", "_motor_impulse")

    motor_impulse: Reported[float] = Reported(
        "The motor's part of angular_impulse (N m s) in the last step."
    )

    def __init__(
        self,
        body_a: Any,
        body_b: Any,
        point: Any = None,
        limits: Any = None,
        motor_speed: float | None = None,
        max_torque: float = math.inf,
        collide: bool = False,
        *,
        anchor_a: Any = None,
        anchor_b: Any = None,
    ) -> None:
        if anchor_a is not None or anchor_b is not None:
            if point is not None:
                raise TypeError(
                    "give the hinge's point (world coordinates) or its anchor_a and anchor_b "
                    f"(each body's own frame), not both: got point={point!r}, "
                    f"anchor_a={anchor_a!r}, anchor_b={anchor_b!r}"
                )
            point = _meeting(body_a, body_b, anchor_a, anchor_b)
            self._setup(body_a, body_b, point, collide)
            # The anchors as given (the point's frames again would round them).
            self._anchor_a = local_anchor(anchor_a, "anchor_a")
            if self._other is None:
                self._point = point
            else:
                self._anchor_b = local_anchor(anchor_b, "anchor_b")
        elif point is None:
            raise TypeError(
                "a Hinge needs its point (world coordinates), or anchor_a and anchor_b (each "
                "body's own frame): Hinge(body_a, body_b, point) or Hinge(body_a, body_b, "
                "anchor_a=..., anchor_b=...)"
            )
        else:
            self._setup(body_a, body_b, point, collide)
        self.motor_impulse = 0.0
        self._limits: tuple[float, float] | None = None
        self._speed: float | None = None
        self._max_torque = math.inf
        self.limits = limits
        self.motor_speed = motor_speed
        self.max_torque = max_torque

    def motor_torque(self, dt: float) -> float:
        """The mean torque (N m) of the motor on body_a over the last step of ``dt`` s."""
        return self.motor_impulse / checks.seconds(dt)

    @property
    def limits(self) -> tuple[float, float] | None:
        """(lower, upper) bounds of the joint's angle (rad), or None: it turns freely."""
        return self._limits

    @limits.setter
    def limits(self, value: Any) -> None:
        if value is None:
            self._set("_limits", None)
            return
        try:
            lower, upper = value
        except (TypeError, ValueError):
            raise TypeError(
                f"limits must be None or a pair (lower, upper) in radians, got {value!r}"
            ) from None
        lo = checks.real(lower, "limits[0]")
        hi = checks.real(upper, "limits[1]")
        if not lo <= hi:
            raise ValueError(
                f"limits must be in order, lower <= upper (rad), got lower={lo!r} upper={hi!r}"
            )
        self._set("_limits", (lo, hi))

    @property
    def motor_speed(self) -> float | None:
        """The speed the motor drives the joint's angle at (rad/s), or None: no motor."""
        return self._speed

    @motor_speed.setter
    def motor_speed(self, value: Any) -> None:
        self._set("_speed", None if value is None else checks.real(value, "motor_speed"))

    @property
    def max_torque(self) -> float:
        """The most torque the motor gives (N m; inf: as much as it takes)."""
        return self._max_torque

    @max_torque.setter
    def max_torque(self, value: Any) -> None:
        if isinstance(value, float) and value == math.inf:
            self._set("_max_torque", math.inf)
            return
        t = checks.real(value, "max_torque")
        if not t >= 0.0:
            raise ValueError(f"max_torque must be >= 0 in N m (inf: no bound), got {value!r}")
        self._set("_max_torque", t)

    def _set(self, name: str, value: Any) -> None:
        """Set the motor's or limits' setting ``name``; a change wakes the bodies (a motor
        started on a machine asleep turns it, as pymunk's wakes them): read at every step,
        it needs nothing made again."""
        if getattr(self, name, None) != value:
            setattr(self, name, value)
            note_edit()  # (read at every step: the soft step's rows take it)
            for body in (self._body, self._other):
                if body is not None:
                    body.activate()

    def __repr__(self) -> str:
        extra = ""
        if self._limits is not None:
            extra += f", limits={self._limits!r}"
        if self._speed is not None:
            extra += f", motor_speed={self._speed!r}, max_torque={self._max_torque!r}"
        return f"Hinge({self._body!r}, {self.body_b!r}{extra})"


def _meeting(body_a: Any, body_b: Any, anchor_a: Any, anchor_b: Any) -> Vector:
    """The world point where a hinge's anchors meet (anchor_a in body_a's frame, anchor_b in
    body_b's, or in world coordinates for the static body), or a ValueError naming the gap."""
    a = plane_body(body_a, "body_a")
    other = _second(body_b)
    pa = a.local_to_world(local_anchor(anchor_a, "anchor_a"))
    if other is None:
        pb = fixed_point(anchor_b if anchor_b is not None else (0.0, 0.0), "anchor_b")
    else:
        pb = other.local_to_world(local_anchor(anchor_b, "anchor_b"))
    gap = abs(pa - pb)
    if not gap <= 1e-9 * max(1.0, abs(pa), abs(pb)):
        raise ValueError(
            f"a hinge's anchors must be one point in the world when it is made: anchor_a is at "
            f"{tuple(pa)!r} and anchor_b at {tuple(pb)!r}, {gap:.6g} m apart; move a body by "
            f"({pb.x - pa.x:.6g}, {pb.y - pa.y:.6g}) first, or give the hinge its point"
        )
    return pb if other is None else pa


class Weld(Joint):
    """``body_a`` and ``body_b`` (or world.static_body) held as one body: body_a's centre
    stays where it is in body_b's frame and their angles keep their difference. With
    ``hertz`` (the weld's own frequency, Hz) it is a spring instead, damped by
    ``damping_ratio`` (1: critically), as Box2D's soft weld."""

    __slots__ = ("_hertz", "_zeta")

    def __init__(
        self,
        body_a: Any,
        body_b: Any,
        hertz: float | None = None,
        damping_ratio: float = 1.0,
        collide: bool = False,
    ) -> None:
        a = plane_body(body_a, "body_a")
        self._setup(a, body_b, a.pos, collide)
        self._hertz: float | None = None
        if hertz is not None:
            self._hertz = checks.real(hertz, "hertz", positive=True)
        self._zeta = checks.real(damping_ratio, "damping_ratio", nonneg=True)

    @property
    def hertz(self) -> float | None:
        """The spring's frequency (Hz), or None for a rigid weld."""
        return self._hertz

    @property
    def damping_ratio(self) -> float:
        """The spring's damping ratio (1: critical; no effect on a rigid weld)."""
        return self._zeta

    def __repr__(self) -> str:
        soft = "" if self._hertz is None else f", hertz={self._hertz!r}"
        return f"Weld({self._body!r}, {self.body_b!r}{soft})"


# -- what a snapshot keeps of a link (engine.pipeline.snapshot) ------------------------------------
#: Kinds of link by name, for a snapshot restored into a World built afresh.
KINDS = ("Rod", "Cable", "Pin", "Hinge", "Weld")


def geometry(link: Link) -> tuple[Any, ...]:
    """What a link was made with, beyond its bodies: (anchor_a x, y, anchor_b x, y, reference
    angle (rad), hertz (None: rigid), damping ratio, collide). (A rod's or cable's anchors and
    a joint's collide may be set since: ``settings`` holds them as they are.)"""
    a, b = link.anchor_a, link.anchor_b
    if isinstance(link, Joint):
        hz = link.hertz if isinstance(link, Weld) else None
        zeta = link.damping_ratio if isinstance(link, Weld) else 0.0
        return (a.x, a.y, b.x, b.y, link.reference_angle, hz, zeta, link.collide)
    return (a.x, a.y, b.x, b.y, 0.0, None, 0.0, True)


def settings(link: Link) -> tuple[Any, ...]:
    """What a game may change on a link or joint, and a joint's last impulses: for a Hinge
    (limits, motor speed, max torque, (impulse x, y), angular impulse, motor impulse, collide);
    for a Weld ((impulse x, y), angular impulse, collide); for a rod or cable (length, (anchor_a
    x, y), (anchor_b x, y)); () for a pin."""
    if isinstance(link, Hinge):
        p = link.linear_impulse
        return (link.limits, link.motor_speed, link.max_torque, (p.x, p.y),
                link.angular_impulse, link.motor_impulse, link.collide)  # fmt: skip
    if isinstance(link, Joint):
        p = link.linear_impulse
        return ((p.x, p.y), link.angular_impulse, link.collide)
    if link.length > 0.0:
        a, b = link.anchor_a, link.anchor_b
        return (link.length, (a.x, a.y), (b.x, b.y))
    return ()


def check_settings(kind: str, values: Any) -> bool:
    """Whether ``values`` are settings a joint of ``kind`` can take (a snapshot's, checked
    before anything is restored)."""
    if not isinstance(values, tuple):
        return False

    def real(v: Any) -> bool:
        return isinstance(v, float) and math.isfinite(v)

    def impulse(v: Any) -> bool:
        return isinstance(v, tuple) and len(v) == 2 and all(real(c) for c in v)

    if kind == "Hinge":
        if len(values) != 7 or not isinstance(values[6], bool):
            return False
        limits, speed, torque, p, ang, motor, _ = values
        ok = limits is None or (
            isinstance(limits, tuple) and len(limits) == 2 and all(real(c) for c in limits)
            and limits[0] <= limits[1]
        )  # fmt: skip
        ok = ok and (speed is None or real(speed))
        ok = ok and isinstance(torque, float) and torque >= 0.0
        return ok and impulse(p) and real(ang) and real(motor)
    if kind == "Weld":
        return (
            len(values) == 3 and impulse(values[0]) and real(values[1])
            and isinstance(values[2], bool)
        )  # fmt: skip
    if kind in ("Rod", "Cable"):
        return (
            len(values) == 3 and real(values[0]) and values[0] > 0.0 and impulse(values[1])
            and impulse(values[2])
        )  # fmt: skip
    return values == ()


def apply_settings(link: Link, values: tuple[Any, ...]) -> None:
    """Put back what ``settings`` read (checked by ``check_settings`` first)."""
    if isinstance(link, Hinge):
        limits, speed, torque, p, ang, motor, collide = values
        link.limits, link.motor_speed, link.max_torque = limits, speed, torque
        link.linear_impulse, link.angular_impulse, link.motor_impulse = Vector(*p), ang, motor
        if link.collide != collide:
            link.collide = collide
    elif isinstance(link, Joint):
        link.linear_impulse, link.angular_impulse = Vector(*values[0]), values[1]
        if link.collide != values[2]:
            link.collide = values[2]
    elif values:
        length, a, b = values
        if (length, a, b) != settings(link):
            link._length, link._anchor_a, link._anchor_b = length, Vector(*a), Vector(*b)
            link.revision += 1


def rebuild(
    kind: str, body: Any, other: Any, length: float, e: float, shape: tuple[Any, ...]
) -> Link:
    """A new link of ``kind`` between ``body`` and ``other`` (a Body, or a fixed point), made
    with the ``geometry`` ``shape`` (a snapshot's link that this World no longer holds)."""
    from .links import Cable, Pin, Rod

    ax, ay, bx, by, ref, hz, zeta, collide = shape
    anchor_b = (bx, by) if isinstance(other, Body) else None
    if kind == "Pin":
        return Pin(body, other, anchor_a=(ax, ay))
    if kind == "Cable":
        return Cable(body, other, length, e, anchor_a=(ax, ay), anchor_b=anchor_b)
    if kind == "Rod":
        return Rod(body, other, length, anchor_a=(ax, ay), anchor_b=anchor_b)
    second = other if isinstance(other, Body) else STATIC
    point = body.local_to_world((ax, ay))
    joint: Joint
    if kind == "Hinge":
        joint = Hinge(body, second, point, collide=collide)
    else:
        joint = Weld(body, second, hz, zeta, collide=collide)
    # As made: the anchors and the reference angle of the snapshot, not of the state now.
    joint._anchor_a = Vector(ax, ay)
    joint._anchor_b = Vector(bx, by) if isinstance(other, Body) else Vector(0.0, 0.0)
    if not isinstance(other, Body):
        joint._point = Vector(*other)
    joint._ref = ref
    return joint
