"""The mouse joint: a point of a body pulled toward a target the game moves, by a bounded
force (Box2D's ``b2MouseJoint``; in pymunk, a ``PivotJoint`` to a kinematic body that follows
the mouse, with ``max_force`` and ``error_bias``).

``MouseJoint(body, target, anchor=None, hertz=5.0, damping_ratio=0.7, max_force=inf,
angular_damping=0.0)``: the
anchor (a point in the body's own frame; None: where ``target`` lies on the body now) is pulled
toward ``target`` (world coordinates; set it every frame). As Box2D's, the stiffness is given
as a frequency and a damping ratio, whatever the body's mass: the anchor's error e = p - target
(m) and its velocity u = dp/dt (m/s) follow the damped oscillator

    e'' + 2 zeta omega e' + omega^2 e = 0,     omega = 2 pi hertz,  zeta = damping_ratio,

as long as the force it takes stays within ``max_force`` (N). The joint is a hand that holds
the body: it carries the body's weight and whatever else pulls on it, so a body held still rests
at the target exactly (Box2D's soft joint sags by g / omega^2 under gravity instead; pymunk's
pivot does not sag either).

How a step does it. The step's start gives (e0, u0); the exact flow of the oscillator over dt,
expm(A dt) with A = [[0, 1], [-omega^2, -2 zeta omega]], gives where the anchor should end,
(e1, u1). The method's step (gravity, springs, the body's own forces) ended it at (e', u').
The joint gives the body the impulse J = K^-1 (u1 - u') (N s) at the anchor and moves it by the
position impulse P = K^-1 (e1 - e') (kg m), with K = (1/m) 1 + (1/I) r_perp r_perp^T the
anchor's inverse effective mass (r: the anchor's lever arm, r_perp = (-r_y, r_x)); so the body
turns by (r x J) / I and (r x P) / I. For an anchor that does not turn (at the centre, or a body
that does not turn) the anchor then follows the oscillator to round-off at any dt; an anchor
off the centre, to first order in the turn of a step. When |J| > max_force dt, J and P are
scaled down together to |J| = max_force dt: the mean force of the step, J / dt, never exceeds
``max_force``, and a body heavier than max_force / g sinks.

A body pulled off its centre hangs from the anchor and swings about it; ``angular_damping``
(1/s) calms it, as Box2D's mouse joint damps the body's spin: a grip that takes exp(-k dt) of
the body's turn about the anchor each step (implicit), before the anchor is placed, so the
anchor still follows the oscillator; its impulse counts in ``impulse`` and in the bound.

The joint acts before the contacts: a body dragged into a wall is stopped by the wall, as by any
force. It keeps its body awake. ``world.add_link(joint)`` adds it, ``world.remove_link(joint)``
takes it out (as a mouse button let go), and it leaves with its body.

>>> from engine import Body, World
>>> world = World()
>>> crate = world.add(Body((0.0, 0.0), mass=2.0))
>>> drag = world.add_link(MouseJoint(crate, (1.0, 0.0), anchor=(0.0, 0.0), max_force=100.0))
>>> for _ in range(120):
...     world.step(1 / 60)
>>> round(crate.pos.x, 6), round(crate.pos.y, 6)
(1.0, 0.0)
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import checks
from ..accuracy import expm
from ..vector import Vector
from .links import fixed_point, local_anchor, plane_body
from .reported import Pending, Reported, reported_state

if TYPE_CHECKING:
    from ..body import Body
    from .rotation import Spin
    from .store import BodyStore

__all__ = ["MouseJoint", "MouseJoints"]


def _nonneg(value: Any, name: str, unit: str, positive: bool = False) -> float:
    """``value`` as a float >= 0 (> 0 if ``positive``; ``max_force`` may be inf), or an error
    naming it."""
    if name == "max_force" and isinstance(value, float) and value == math.inf:
        return math.inf
    try:
        return checks.real(value, name, nonneg=not positive, positive=positive)
    except ValueError:
        raise ValueError(
            f"{name} must be a finite number {'>' if positive else '>='} 0 ({unit}"
            + ("; or math.inf: no bound" if name == "max_force" else "")
            + f"), got {value!r}"
        ) from None


class MouseJoint:
    """A body's point pulled toward a moving target by a bounded force (the module's text).

    ``impulse`` (N s, a Vector): what the joint gave the body in the last step; its mean force
    is ``impulse / dt``, never longer than ``max_force``.
    """

    __slots__ = (
        "_body", "_target", "_anchor", "_hertz", "_zeta", "_max", "_spin", "_impulse", "_flow",
        "_pending",
    )  # fmt: skip

    impulse: Reported[Vector] = Reported(
        "The impulse (N s) the joint gave its body in the last step."
    )

    def __getstate__(self) -> tuple[None, dict[str, Any]]:
        """For ``copy`` and ``pickle``: the slots, the last step's impulses put on it first
        (engine.dynamics.reported.reported_state)."""
        return reported_state(self)

    def __init__(
        self,
        body: Any,
        target: Any,
        anchor: Any = None,
        hertz: float = 5.0,
        damping_ratio: float = 0.7,
        max_force: float = math.inf,
        angular_damping: float = 0.0,
    ) -> None:
        self._body: Body = plane_body(body, "body")
        self._target = fixed_point(target, "target (a point in world coordinates)")
        if anchor is None:
            self._anchor = self._body.world_to_local(self._target)
        else:
            self._anchor = local_anchor(anchor, "anchor")
        self._hertz = _nonneg(hertz, "hertz", "Hz", positive=True)
        self._zeta = _nonneg(damping_ratio, "damping_ratio", "no unit; 1: critical")
        self._max = _nonneg(max_force, "max_force", "N")
        self._spin = _nonneg(angular_damping, "angular_damping", "1/s")
        self._pending: Pending | None = None  # a soft step's impulse, not yet put here
        self.impulse = Vector(0.0, 0.0)
        self._flow: tuple[float, np.ndarray] | None = None  # (dt, expm(A dt))

    @property
    def body(self) -> Body:
        """The body dragged."""
        return self._body

    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies the joint holds (its one body)."""
        return (self._body,)

    @property
    def target(self) -> Vector:
        """Where the anchor is pulled to, in world coordinates (m); set it every frame."""
        return self._target

    @target.setter
    def target(self, value: Any) -> None:
        self._target = fixed_point(value, "target (a point in world coordinates)")

    @property
    def anchor(self) -> Vector:
        """The point pulled, in the body's own frame (m)."""
        return self._anchor

    @anchor.setter
    def anchor(self, value: Any) -> None:
        self._anchor = local_anchor(value, "anchor")

    @property
    def hertz(self) -> float:
        """The frequency of the anchor's undamped oscillation about the target (Hz, > 0)."""
        return self._hertz

    @hertz.setter
    def hertz(self, value: Any) -> None:
        self._hertz = _nonneg(value, "hertz", "Hz", positive=True)
        self._flow = None

    @property
    def damping_ratio(self) -> float:
        """The oscillation's damping ratio (no unit; 1: critical, no overshoot)."""
        return self._zeta

    @damping_ratio.setter
    def damping_ratio(self, value: Any) -> None:
        self._zeta = _nonneg(value, "damping_ratio", "no unit; 1: critical")
        self._flow = None

    @property
    def max_force(self) -> float:
        """The largest mean force the joint gives in a step (N; inf: no bound)."""
        return self._max

    @max_force.setter
    def max_force(self, value: Any) -> None:
        self._max = _nonneg(value, "max_force", "N")

    @property
    def angular_damping(self) -> float:
        """How fast the body's turn about the held point dies away (1/s): omega is multiplied
        by exp(-angular_damping dt) each step (0: not at all, as pymunk's pivot)."""
        return self._spin

    @angular_damping.setter
    def angular_damping(self, value: Any) -> None:
        self._spin = _nonneg(value, "angular_damping", "1/s")

    def world_anchor(self) -> Vector:
        """Where the anchor is now, in world coordinates (m)."""
        return self._body.local_to_world(self._anchor)

    def flow(self, dt: float) -> np.ndarray:
        """expm(A dt) (2 x 2): (e, u) at the step's start to (e, u) at its end (the module's
        text); made once per dt and setting."""
        if self._flow is None or self._flow[0] != dt:
            w = 2.0 * math.pi * self._hertz
            a = np.array([[0.0, 1.0], [-w * w, -2.0 * self._zeta * w]])
            self._flow = (dt, expm(a * dt))
        return self._flow[1]

    def __repr__(self) -> str:
        return (
            f"MouseJoint(target={self._target!r}, anchor={self._anchor!r}, "
            f"hertz={self._hertz!r}, damping_ratio={self._zeta!r}, max_force={self._max!r}, "
            f"angular_damping={self._spin!r})"
        )


def _lever(angle: float, local: Vector) -> tuple[float, float]:
    """The anchor's lever arm r = R(angle) local (m)."""
    c, s = math.cos(angle), math.sin(angle)
    return c * local.x - s * local.y, s * local.x + c * local.y


class MouseJoints:
    """A World's mouse joints, in the order added, and their part of a step."""

    def __init__(self) -> None:
        self.items: list[MouseJoint] = []

    def __bool__(self) -> bool:
        return bool(self.items)

    def add(self, joint: MouseJoint, world: Any) -> None:
        """Add ``joint`` on a body of ``world`` (once)."""
        if any(j is joint for j in self.items):
            raise ValueError(f"that mouse joint is already in this World (added once): {joint!r}")
        if joint.body.world is not world:
            raise ValueError(
                f"the mouse joint's body must be in this World first (world.add(body)): "
                f"{joint.body!r}"
            )
        self.items.append(joint)

    def remove(self, joint: MouseJoint) -> None:
        """Take ``joint`` out."""
        if not any(j is joint for j in self.items):
            raise ValueError(f"that mouse joint is not in this World: {joint!r}")
        self.items = [j for j in self.items if j is not joint]

    def body_removed(self, body: Body) -> None:
        """A body left the World: its joints go with it."""
        self.items = [j for j in self.items if j.body is not body]

    def rows(self, store: BodyStore) -> list[int]:
        """The World rows of the bodies dragged."""
        return [store.row(j.body.slot) for j in self.items]

    def turn(self, store: BodyStore) -> bool:
        """Whether a joint may turn its body (an anchor off the centre of a body that turns)."""
        inv = store.inv_moment
        return any(
            inv[store.row(j.body.slot)] > 0.0 and (j.anchor.x or j.anchor.y) for j in self.items
        )

    def pull(
        self,
        store: BodyStore,
        x1: np.ndarray,
        v1: np.ndarray,
        spin: Spin | None,
        dt: float,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The step's end (x, v; and the spin's angle and omega, in place) after each joint's
        impulse and position impulse (the module's text); the step started at the store's
        state and the method ended it at ``x1``, ``v1`` (and ``spin``)."""
        x1, v1 = x1.copy(), v1.copy()
        for j in self.items:
            i = store.row(j.body.slot)
            wm = 0.0 if store.kinematic[i] else 1.0 / float(store.mass[i])
            wi = 0.0 if store.kinematic[i] or spin is None else float(store.inv_moment[i])
            j.impulse = Vector(0.0, 0.0)
            if wm == 0.0:
                continue  # the game moves it
            t = (j.target.x, j.target.y)
            # Where the anchor started and how fast it moved: e0, u0 = v + omega x r.
            rx, ry = _lever(float(store.angle[i]), j.anchor)
            w0 = float(store.omega[i])
            e0 = (float(store.x[i, 0]) + rx - t[0], float(store.x[i, 1]) + ry - t[1])
            u0 = (float(store.v[i, 0]) - w0 * ry, float(store.v[i, 1]) + w0 * rx)
            m = j.flow(dt)
            # Where the oscillator ends it: (e1, u1) = expm(A dt) (e0, u0), per coordinate.
            e1 = (m[0, 0] * e0[0] + m[0, 1] * u0[0], m[0, 0] * e0[1] + m[0, 1] * u0[1])
            u1 = (m[1, 0] * e0[0] + m[1, 1] * u0[0], m[1, 0] * e0[1] + m[1, 1] * u0[1])
            # Where the method ended the body: (x, y, angle, v, omega).
            end = (
                float(x1[i, 0]),
                float(x1[i, 1]),
                float(store.angle[i] if spin is None else spin.angle[i]),
                float(v1[i, 0]),
                float(v1[i, 1]),
                float(store.omega[i] if spin is None else spin.omega[i]),
            )
            free, gx, gy = end, 0.0, 0.0
            if j.angular_damping > 0.0 and wi > 0.0:
                # The grip first: the body's turn about the held point dies away as
                # exp(-k dt) (implicit: no dt overshoots). A turn about the anchor leaves the
                # anchor's velocity as it was (v' = v - d_omega x r), so the placing below
                # keeps it; the hand gives the impulse g = m (v' - v) for it.
                rx, ry = _lever(end[2], j.anchor)
                dw = end[5] * math.expm1(-j.angular_damping * dt)
                gx, gy = dw * ry / wm, -dw * rx / wm
                end = (*end[:3], end[3] + dw * ry, end[4] - dw * rx, end[5] + dw)
            body = _Moved(*end, wm, wi, j.anchor)
            # The position impulse P = K^-1 (e1 - e'), taken again at the new angle while the
            # body turns (Newton's iteration on where the anchor is: its miss, of the order of
            # r dtheta^2, shrinks as its square), then J = K^-1 (u1 - u') at the last lever.
            for _ in range(ITERATIONS if wi > 0.0 else 1):
                miss = body.position_to(e1, t)
                if miss == 0.0:
                    break
            jx, jy = body.velocity_to(u1)
            jx, jy = jx + gx, jy + gy
            bound = j.max_force * dt
            if math.hypot(jx, jy) > bound:
                # Past max_force: from the method's end (no grip), J and P scaled alike to
                # |J| = bound (the lever arm the method's end has).
                body = _Moved(*free, wm, wi, j.anchor)
                jx, jy = body.velocity_to(u1, apply=False)
                px, py = body.position_to(e1, t, apply=False)
                s = min(1.0, bound / math.hypot(jx, jy))
                body.give(px * s, py * s, jx * s, jy * s)
                jx, jy = jx * s, jy * s
            x1[i, 0], x1[i, 1], v1[i, 0], v1[i, 1] = body.x, body.y, body.vx, body.vy
            if spin is not None:
                spin.angle[i], spin.omega[i] = body.angle, body.omega
            j.impulse = Vector(jx, jy)
        return x1, v1


#: Newton's iterations on an anchor's position when its body turns (each squares the miss).
ITERATIONS = 4


class _Moved:
    """One body's state at the step's end, as the joint moves it (m, rad, m/s, rad/s), with
    its inverse mass wm (1/kg) and inverse moment wi (1/(kg m^2); 0 where it does not turn)."""

    __slots__ = ("x", "y", "angle", "vx", "vy", "omega", "wm", "wi", "local")

    def __init__(
        self,
        x: float,
        y: float,
        angle: float,
        vx: float,
        vy: float,
        omega: float,
        wm: float,
        wi: float,
        local: Vector,
    ) -> None:
        self.x, self.y, self.angle = x, y, angle
        self.vx, self.vy, self.omega = vx, vy, omega
        self.wm, self.wi, self.local = wm, wi, local

    def _solve(self, dx: float, dy: float) -> tuple[float, float, float, float]:
        """(rx, ry, qx, qy): the lever arm now, and q = K^-1 d, with K = wm 1 + wi r_perp
        r_perp^T (r_perp = (-ry, rx)): the anchor moves by K q when the body is given q at
        it (v += wm q, omega += wi (r x q))."""
        rx, ry = _lever(self.angle, self.local)
        wm, wi = self.wm, self.wi
        k11, k12, k22 = wm + wi * ry * ry, -wi * rx * ry, wm + wi * rx * rx
        det = k11 * k22 - k12 * k12  # = wm (wm + wi |r|^2) > 0
        return rx, ry, (k22 * dx - k12 * dy) / det, (k11 * dy - k12 * dx) / det

    def position_to(
        self, e1: tuple[float, float], t: tuple[float, float], apply: bool = True
    ) -> Any:
        """Move the anchor toward t + e1 by a position impulse P (kg m); the miss before the
        move (m), or P itself when not ``apply``."""
        rx, ry = _lever(self.angle, self.local)
        dx, dy = e1[0] - (self.x + rx - t[0]), e1[1] - (self.y + ry - t[1])
        rx, ry, px, py = self._solve(dx, dy)
        if not apply:
            return px, py
        self.x += self.wm * px
        self.y += self.wm * py
        self.angle += self.wi * (rx * py - ry * px)
        return math.hypot(dx, dy)

    def velocity_to(self, u1: tuple[float, float], apply: bool = True) -> tuple[float, float]:
        """Give the anchor the velocity u1 by an impulse J (N s) there; J."""
        rx, ry = _lever(self.angle, self.local)
        w = self.omega
        rx, ry, jx, jy = self._solve(u1[0] - (self.vx - w * ry), u1[1] - (self.vy + w * rx))
        if apply:
            self.give(0.0, 0.0, jx, jy)
        return jx, jy

    def give(self, px: float, py: float, jx: float, jy: float) -> None:
        """Give the body the position impulse P (kg m) and the impulse J (N s) at the anchor,
        both with the lever arm it has now."""
        rx, ry = _lever(self.angle, self.local)
        self.x += self.wm * px
        self.y += self.wm * py
        self.vx += self.wm * jx
        self.vy += self.wm * jy
        self.omega += self.wi * (rx * jy - ry * jx)
        self.angle += self.wi * (rx * py - ry * px)
