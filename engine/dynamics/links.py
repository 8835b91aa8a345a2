"""Links between bodies: rods that hold a distance, cables that hold at most a length, pins.

Cyclone's particle engine completes its mass-aggregate physics with links; these are they,
for the World's 2D bodies. A link joins a body to another body or to a fixed point:

- ``Rod(body, other, length=None)``: the distance stays ``length`` (None: the distance when
  the rod is made). A pendulum, a chain, the rods of a Newton's cradle.
- ``Cable(body, other, length, restitution=0.0)``: the distance stays at most ``length``;
  slack, the cable does nothing; snapping taut, it takes the ends' parting speed and gives
  back ``restitution`` of it as they bounce together.
- ``Pin(body, point)``: the body stays at ``point``: no force moves it, and contacts and
  other links take it as immovable (an anchor for a chain).

How they are solved (``LinkSolver``). The step moves every body as if unlinked (the method's
own update, then the contacts); the links then correct it, as RATTLE does (Andersen 1983) for
velocity Verlet:

1. Positions. Each link k pulls its ends along its direction at the start of the step, r_k
   (at the end of it, for a link whose end was struck in the step or passed its other end:
   its start direction then says nothing of the pull): body i moves by w_i lam_k r_k and
   the other end by -w_j lam_k r_k (w = 1/m, 0 for what the
   game moves or a pin holds). The multipliers lam solve c_k(lam) = |d_k|^2 - L_k^2 = 0 for
   every link at once (d_k the link's vector from its other end to its body, after the
   moves), by Newton's method: its Jacobian is dc_k/dlam_l = 2 S_kl (d_k . r_l), with
   S = B W B^T from the links' incidence B (+1 at the body, -1 at the other end). One link
   needs three or four iterations to reach round-off; the links of a chain are solved
   together, not one after another, so a chain's error does not creep from link to link.
2. Velocities. A correction dx made in the step is an impulse that acted through it: the
   velocity gains dx / dt (RATTLE's first half-kick; for the closed form under constant
   forces this is exactly RATTLE). Then each link's ends are given the speed along it that
   the link allows (0 for a rod; for a cable the bounce of its snap) by one linear solve
   S_kl (n_k . n_l) mu = target - u.

A cable is a link only while it pulls: its correction must bring its ends together (lam r
toward the other end: lam <= 0 while r still points along the link, lam >= 0 where the end
passed its anchor within the step and r points back), and mu <= 0; a cable that would push
is left out and the rest solved again. A step that moves an end
farther than Newton's method can bring back along r_k (a body flung past what the step can
hold) is finished by projecting along the current direction instead, and warned about with a
StabilityWarning, once per link: take a smaller dt.

The error after a step: every rod's length, and every taut cable's, equals its length to
``TOLERANCE`` (1e-12 of it; the issue asks 1e-9) unless the warning was given.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from .. import checks
from ..vector import Vector
from .reported import Pending, Reported, reported_state

if TYPE_CHECKING:
    from ..body import Body

__all__ = ["Link", "Rod", "Cable", "Pin", "LinkSolver", "StaticBody", "STATIC", "TOLERANCE"]

#: A link's length error after the solve, relative to its length.
TOLERANCE = 1e-12
#: Newton iterations before a step counts as past what the solver can hold.
MAX_ITERATIONS = 25
#: Up to this many links that share no body are solved one by one in Python floats.
APART = 16

#: How many times a setting of any link, joint or spring was set in this process: each
#: ``revision`` counted (``Link.revision``, ``BodySpring.revision``) and each hinge's motor or
#: limits set (``note_edit``). A step that finds it as it was reads no link's own revision.
_EDITS = 0


def edits() -> int:
    """How many settings of links, joints and springs were set so far (``_EDITS``)."""
    return _EDITS


def note_edit() -> None:
    """Count a setting of a link, joint or spring as set (``edits``)."""
    global _EDITS
    _EDITS += 1


def fixed_point(value: Any, name: str) -> Vector:
    """A finite 2D point, or a TypeError / ValueError naming ``name``."""
    try:
        p = Vector.coerce(value, name)
    except TypeError:
        raise TypeError(
            f"{name} must be a Body or a point (a Vector or pair of numbers), got "
            f"{type(value).__name__} {value!r}"
        ) from None
    if not p.is_finite():
        raise ValueError(f"{name} must be finite (no nan or inf), got {value!r}")
    return p


class StaticBody:
    """The World itself as a body that never moves (``world.static_body``): a joint or link
    to it holds a body to a fixed point, given in world coordinates (pymunk's static body)."""

    __slots__ = ()

    def __repr__(self) -> str:
        return "world.static_body"


#: The one static body every World hands out as ``world.static_body``.
STATIC = StaticBody()


def local_anchor(value: Any, name: str) -> Vector:
    """A finite anchor in a body's own frame (length units), or an error naming ``name``."""
    if value is None:
        return Vector(0.0, 0.0)
    try:
        p = Vector.coerce(value, name)
    except TypeError:
        raise TypeError(
            f"{name} must be a point in the body's own frame (a Vector or pair of numbers), "
            f"got {type(value).__name__} {value!r}"
        ) from None
    if not p.is_finite():
        raise ValueError(f"{name} must be finite (no nan or inf), got {value!r}")
    return p


def plane_body(value: Any, name: str) -> Body:
    from ..body import Body

    if not isinstance(value, Body):
        raise TypeError(f"{name} must be a Body, got {type(value).__name__} {value!r}")
    if value.dim != 2:
        raise TypeError(f"{name} must be a 2D body (links join bodies on a plane), got a 1D body")
    return value


def refuse_immobile(body: Body, other: Body | None, what: str) -> None:
    """Refuse a link or joint none of whose ends the solver can move: ``body`` kinematic and
    ``other`` kinematic or the world (None). The game moves both ends, so the solver could
    only break it silently (pymunk refuses such a constraint too)."""
    if body.kinematic and (other is None or other.kinematic):
        second = "world.static_body or a fixed point" if other is None else "a kinematic body"
        raise ValueError(
            f"a {what} between a kinematic body and {second} cannot hold: the game moves both "
            f"ends, so nothing is left for it to pull; make one of the two bodies dynamic "
            f"(kinematic=False), or move the kinematic body along the path you want"
        )


class Link:
    """A link from ``body`` to ``other`` (a Body, or a fixed point): see the module's text."""

    __slots__ = (
        "_body", "_other", "_point", "_length", "_e", "_anchor_a", "_anchor_b", "_impulse",
        "_pending", "warned", "_revision",
    )  # fmt: skip

    impulse: Reported[float] = Reported(
        "The impulse (N s) the link gave in the last step, along it: > 0 pulls the ends "
        "together (a rod's tension), < 0 pushes them apart (a rod in compression)."
    )

    def __getstate__(self) -> tuple[None, dict[str, Any]]:
        """For ``copy`` and ``pickle``: the slots, the last step's impulses put on it first
        (engine.dynamics.reported.reported_state)."""
        return reported_state(self)

    @property
    def revision(self) -> int:
        """How many times its length, anchors or (a joint's) collide were set since it was
        made: the World's solvers take a link again when it changes (each counted in
        ``edits`` too)."""
        return self._revision

    @revision.setter
    def revision(self, value: int) -> None:
        self._revision = value
        note_edit()

    #: Whether the link holds the distance both ways (a rod) or only at most (a cable).
    rigid = True
    #: Whether only the soft step's solver holds it (engine.dynamics.constraints' joints); the exact
    #: models hold every other link.
    needs_soft: ClassVar[bool] = False

    def __init__(
        self,
        body: Any,
        other: Any,
        length: Any,
        restitution: float = 0.0,
        anchor_a: Any = None,
        anchor_b: Any = None,
    ) -> None:
        from ..body import Body

        self._body = plane_body(body, "body")
        self._anchor_a = local_anchor(anchor_a, "anchor_a")
        self._anchor_b = local_anchor(anchor_b, "anchor_b")
        if other is STATIC:
            # To the world: anchor_b is then the fixed point, in world coordinates.
            other, self._anchor_b = self._anchor_b, Vector(0.0, 0.0)
        if isinstance(other, Body):
            if other is body:
                raise ValueError(
                    "other must be another Body or a fixed point, got the body itself: a body "
                    "linked to itself holds nothing"
                )
            self._other: Body | None = plane_body(other, "other")
            self._point: Vector | None = None
        else:
            if anchor_b is not None and (self._anchor_b.x or self._anchor_b.y):
                raise ValueError(
                    f"anchor_b is the anchor on a second body; a link to a fixed point "
                    f"({other!r}) has none: give the point itself, got anchor_b={anchor_b!r}"
                )
            self._other, self._point = None, fixed_point(other, "other")
        refuse_immobile(self._body, self._other, type(self).__name__)
        if length is None:
            length = (self.end_a() - self.end_b()).length()
            if not length > 0.0:
                raise ValueError(
                    "the link's ends are at one point, so length=None gives 0: move them "
                    "apart or give a length > 0 (a Pin holds a body at a point)"
                )
        self._length = checks.real(length, "length", positive=True)
        e = checks.real(restitution, "restitution")
        if not 0.0 <= e <= 1.0:
            raise ValueError(
                f"restitution must be in [0, 1] (0: the cable stops the ends, 1: they bounce "
                f"back at their speed), got {restitution!r}"
            )
        self._e = e
        self._pending: Pending | None = None  # a soft step's impulses, not yet put here
        self.impulse = 0.0
        #: Whether the World has warned that this link was stretched past what a step holds.
        self.warned = False
        self.revision = 0  # (the property's text)

    def end_a(self) -> Vector:
        """Where the link holds ``body`` now: its anchor_a, in world coordinates."""
        return self._body.local_to_world(self._anchor_a)

    def end_b(self) -> Vector:
        """Where the link holds its other end now, in world coordinates."""
        if self._other is None:
            return self._point  # type: ignore[return-value]
        return self._other.local_to_world(self._anchor_b)

    @property
    def anchor_a(self) -> Vector:
        """Where the link holds ``body``, in its own frame (length units; (0, 0): the centre).
        A rod's or cable's may be set at any time (the next step holds the new one)."""
        return self._anchor_a

    @anchor_a.setter
    def anchor_a(self, value: Any) -> None:
        self._settable("anchor_a")
        self._anchor_a = local_anchor(value, "anchor_a")
        self.revision += 1

    @property
    def anchor_b(self) -> Vector:
        """Where the link holds ``other``, in its own frame ((0, 0) for a fixed point). A
        rod's or cable's between two bodies may be set at any time."""
        return self._anchor_b

    @anchor_b.setter
    def anchor_b(self, value: Any) -> None:
        self._settable("anchor_b")
        if self._other is None:
            raise ValueError(
                f"anchor_b is the anchor on a second body; this link holds its body to the fixed "
                f"point {self._point!r}, which has none: remove the link and add one to the new "
                f"point (got anchor_b={value!r})"
            )
        self._anchor_b = local_anchor(value, "anchor_b")
        self.revision += 1

    def _settable(self, name: str) -> None:
        """Refuse to set ``name`` on what holds no distance (a pin, a joint: fixed once made)."""
        if not self._length > 0.0:
            raise AttributeError(
                f"a {type(self).__name__}'s {name} is fixed once it is made (a rod's or "
                f"cable's length and anchors can be set): remove it and add a new one"
            )

    @property
    def anchored(self) -> bool:
        """Whether an end is held away from its body's centre (the joint solver then takes
        the World's links: engine.exact.joint_solver)."""
        a, b = self._anchor_a, self._anchor_b
        return bool(a.x or a.y or b.x or b.y)

    @property
    def body(self) -> Body:
        """The linked body."""
        return self._body

    @property
    def other(self) -> Body | Vector:
        """The other end: a Body, or a fixed point (length units)."""
        return self._other if self._other is not None else self._point  # type: ignore[return-value]

    @property
    def length(self) -> float:
        """The distance the link holds (length units): a rod's exactly, a cable's at most.
        It may be set at any time, as a winch does: the next step holds the new length (the
        exact solver's in one step, the ends given the speed that closes the change)."""
        return self._length

    @length.setter
    def length(self, value: Any) -> None:
        self._settable("length")
        self._length = checks.real(value, "length", positive=True)
        self.revision += 1

    @property
    def restitution(self) -> float:
        """For a cable: the fraction of the parting speed kept when it snaps taut."""
        return self._e

    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies the link joins (one for a link to a fixed point)."""
        return (self._body,) if self._other is None else (self._body, self._other)

    def tension(self, dt: float) -> float:
        """The mean force (N) along the link over the last step of ``dt`` s; > 0 pulls."""
        return self.impulse / checks.seconds(dt)

    def __repr__(self) -> str:
        other = "a point" if self._other is None else "a body"
        return f"{type(self).__name__}(length={self._length!r}, to {other})"


class Rod(Link):
    """A rod: the distance from ``body`` to ``other`` (a Body or a point) stays ``length``
    (length units; None: the distance when the rod is made)."""

    __slots__ = ()

    def __init__(
        self,
        body: Any,
        other: Any,
        length: float | None = None,
        anchor_a: Any = None,
        anchor_b: Any = None,
    ) -> None:
        super().__init__(body, other, length, 0.0, anchor_a, anchor_b)


class Cable(Link):
    """A cable: the distance stays at most ``length`` (length units); snapping taut, the ends
    part with ``restitution`` of the speed they met it with (0: they stop)."""

    __slots__ = ()
    rigid = False

    def __init__(
        self,
        body: Any,
        other: Any,
        length: float,
        restitution: float = 0.0,
        anchor_a: Any = None,
        anchor_b: Any = None,
    ) -> None:
        if length is None:
            raise TypeError("length must be a real number for a Cable (its longest reach)")
        super().__init__(body, other, length, restitution, anchor_a, anchor_b)


class Pin(Link):
    """A pin: ``body`` stays at ``point`` (length units); contacts and links take it as fixed.
    With ``anchor_a`` (in the body's own frame, away from its centre) that point of the body
    stays at ``point`` and the body swings about it (a hinge to the world)."""

    __slots__ = ()

    def __init__(self, body: Any, point: Any, anchor_a: Any = None) -> None:
        self._body = plane_body(body, "body")
        self._anchor_a = local_anchor(anchor_a, "anchor_a")
        self._anchor_b = Vector(0.0, 0.0)
        from ..body import Body

        if isinstance(point, Body):
            raise TypeError(
                "point must be a fixed point (a Vector or pair of numbers); to hold two bodies "
                "at a distance use a Rod"
            )
        self._other, self._point = None, fixed_point(point, "point")
        self._length, self._e = 0.0, 0.0
        self._pending = None  # a soft step's impulses, not yet put here
        self.impulse, self.warned, self.revision = 0.0, False, 0

    @property
    def point(self) -> Vector:
        """Where the body is held (length units)."""
        assert self._point is not None
        return self._point

    @property
    def holds(self) -> bool:
        """Whether the pin holds its body still (at its centre: a fixed body), not only a
        point of it (an anchor away from the centre: the body swings)."""
        return not self.anchored

    def __repr__(self) -> str:
        return f"Pin(at {self._point!r})"


class LinkSolver:
    """The World's links as arrays, and the correction of a step for them (module text)."""

    def __init__(self, links: list[Link], row_of: Any) -> None:
        rods = [k for k in links if not isinstance(k, Pin)]
        self.links = rods
        self.pins = [k for k in links if isinstance(k, Pin)]
        self.pin_rows = np.array([row_of(p.body) for p in self.pins], dtype=np.intp)
        self.pin_points = np.array([tuple(p.point) for p in self.pins], dtype=float).reshape(-1, 2)
        self.i = np.array([row_of(k.body) for k in rods], dtype=np.intp)
        self.j = np.array(
            [-1 if k._other is None else row_of(k._other) for k in rods], dtype=np.intp
        )
        self.p = np.array(
            [(0.0, 0.0) if k._point is None else tuple(k._point) for k in rods], dtype=float
        ).reshape(-1, 2)
        self.L = np.array([k.length for k in rods], dtype=float)
        self.rigid = np.array([k.rigid for k in rods], dtype=bool)
        self.e = np.array([k.restitution for k in rods], dtype=float)
        self.moved = False
        self.blow = False  # (it solves no contact: a blow is the impacts' own, JointSolver)
        self.stretched: list[Link] = []  # links past what the last step could hold
        # A few links that share no body are solved one by one in floats (_resolve_one).
        ends = np.concatenate([self.i, self.j[self.j >= 0]])
        self.apart = len(rods) <= APART and len(np.unique(ends)) == len(ends)

    def _ends(self, X: np.ndarray) -> np.ndarray:
        """Each link's vector from its other end to its body."""
        j = self.j
        other = np.where((j >= 0)[:, None], X[np.maximum(j, 0)], self.p)
        return X[self.i] - other

    def _spread(self, n: int, w: np.ndarray, f: np.ndarray, sel: np.ndarray) -> np.ndarray:
        """Each body's change (n, 2) from per-link vectors ``f`` (w applied) of links ``sel``."""
        i, j = self.i[sel], self.j[sel]
        has = j >= 0
        rows = np.concatenate([i, j[has]])
        f = np.concatenate([w[i, None] * f, -w[j[has], None] * f[has]])
        return np.stack(
            [np.bincount(rows, f[:, 0], minlength=n), np.bincount(rows, f[:, 1], minlength=n)],
            axis=1,
        )

    def _coupling(self, w: np.ndarray, sel: np.ndarray) -> np.ndarray:
        """S = B W B^T over the links ``sel``: how link l's multiplier moves link k's ends."""
        i, j = self.i[sel], self.j[sel]
        wj = np.where(j >= 0, w[np.maximum(j, 0)], 0.0)
        same = lambda a, b: (a[:, None] == b[None, :]) & (a[:, None] >= 0)  # noqa: E731
        S = (
            same(i, i) * w[i][:, None]
            - same(i, j) * w[i][:, None]
            - same(j, i) * wj[:, None]
            + same(j, j) * wj[:, None]
        )
        return S

    def resolve(
        self,
        x0: np.ndarray,
        x1: np.ndarray,
        v0: np.ndarray,
        v1: np.ndarray,
        w: np.ndarray,
        dt: float,
        kinked: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The step's end state (x1, v1) corrected for the links; ``w`` (N,): 1/m, 0 for
        bodies nothing moves (kinematic, pinned); ``kinked`` (N,) bool: bodies whose
        velocity a contact changed in the step."""
        self.moved = False
        self.stretched = []
        x, v = x1, v1
        if len(self.pin_rows):
            x, v = x.copy(), v.copy()
            x[self.pin_rows] = self.pin_points
            v[self.pin_rows] = 0.0
            self.moved = True
        K = len(self.L)
        if not K:
            return x, v
        for link in self.links:
            link.impulse = 0.0
        if self.apart:
            # Links that share no body (a pendulum, a lamp on a cable, the rods of a cradle):
            # each link's equation alone, in floats.
            if not self.moved:
                x, v = x.copy(), v.copy()
            for k in range(K):
                self._resolve_one(k, x0, x, v1, v, w, dt, kinked)
            return x, v
        n = len(x)
        L = self.L
        d_start = self._ends(x0)
        d_end = self._ends(x)
        # The direction each link pulls along: where it pointed as the step began (RATTLE),
        # or, for a link whose end was struck in the step (its path has a kink: the pull
        # before the blow is not the pull after it), where it points at the end.
        use_end = np.einsum("ij,ij->i", d_start, d_start) == 0.0
        # ... and for a link whose ends passed each other within the step (a cable's end
        # flung past its anchor): its start direction points back, and the correction
        # along it would find the far root, the end sent back through the anchor.
        use_end |= np.einsum("ij,ij->i", d_start, d_end) < 0.0
        if kinked is not None:
            use_end |= kinked[self.i] | ((self.j >= 0) & kinked[np.maximum(self.j, 0)])
        r = np.where(use_end[:, None], d_end, d_start)
        wi = w[self.i]
        wj = np.where(self.j >= 0, w[np.maximum(self.j, 0)], 0.0)
        movable = (wi + wj) > 0.0
        # A cable acts only when the step would leave it longer than its length.
        len_end = np.sqrt(np.einsum("ij,ij->i", d_end, d_end))
        active = movable & (self.rigid | (len_end > L))
        if not active.any():
            return x, v
        if not self.moved:
            x, v = x.copy(), v.copy()
        lam = np.zeros(K)
        # The active set: a pass drops the cables that would push, or takes in the slack
        # ones the others' pull has stretched (a chain of cables tightening end to end).
        for _ in range(2 * K + 2):
            sel = np.flatnonzero(active)
            lam_sel, ok = self._positions(x, r, w, sel, n)
            if not ok:
                break
            # A cable pushes when its correction moves its end away from the other: lam r
            # along the link as it is once corrected (where an end passed its anchor within
            # the step, r points back, and a pull is lam > 0).
            d_fix = self._ends(x + self._spread(n, w, lam_sel[:, None] * r[sel], sel))[sel]
            along = np.einsum("ij,ij->i", r[sel], d_fix)
            pushing = ~self.rigid[sel] & (lam_sel * along > 0.0)
            if pushing.any():
                active[sel[pushing]] = False
                if not active.any():
                    return x, v
                continue
            d = self._ends(x + self._spread(n, w, lam_sel[:, None] * r[sel], sel))
            stretched = (
                ~active & movable & (np.einsum("ij,ij->i", d, d) > (L * (1.0 + TOLERANCE)) ** 2)
            )
            if not stretched.any():
                break
            active |= stretched
            # One whose ends met at the step's start and end pulls along where they are now,
            # as does one whose ends the others' pull has sent past each other.
            none = stretched & (np.einsum("ij,ij->i", r, r) == 0.0)
            none |= stretched & (np.einsum("ij,ij->i", r, d) < 0.0)
            r[none] = d[none]
        else:
            # The set kept changing (ends flung past each other: Newton's roots for the pull
            # along r and for a push trade places): the projection along the links as they
            # point now settles it, with the warning of a step past what it can hold.
            ok = False
        sel = np.flatnonzero(active)
        if ok:
            lam[sel] = lam_sel
            dx = self._spread(n, w, lam_sel[:, None] * r[sel], sel)
        else:
            # Newton's multipliers are no use: the fallback's move is not along r. It takes
            # every link that can move (a cable only while it would be too long).
            sel = np.flatnonzero(movable)
            dx = self._project(x, w, sel, n)
            d = self._ends(x + dx)
            taut = self.rigid | (np.einsum("ij,ij->i", d, d) >= (L * (1.0 - 1e-9)) ** 2)
            sel = np.flatnonzero(movable & taut)
        x += dx
        v += dx * (1.0 / dt)
        self.moved = True
        # Velocities: along each active link, the speed the link allows.
        d = self._ends(x)[sel]
        length = np.sqrt(np.einsum("ij,ij->i", d, d))
        nrm = d / np.where(length > 0.0, length, 1.0)[:, None]
        rel_before = self._rel(v1, nrm, sel)
        target = np.zeros(len(sel))
        cable = ~self.rigid[sel]
        if cable.any():
            # A cable slack as the step began snaps taut in it: the ends part at -e u.
            slack0 = np.sqrt(np.einsum("ij,ij->i", d_start[sel], d_start[sel])) < L[sel] * (
                1.0 - 1e-9
            )
            snap = cable & slack0
            target[snap] = -self.e[sel][snap] * np.maximum(rel_before[snap], 0.0)
        keep = np.ones(len(sel), dtype=bool)
        mu = np.zeros(len(sel))
        for _ in range(len(sel) + 1):
            s = np.flatnonzero(keep)
            u = self._rel(v, nrm[s], sel[s])
            A = self._coupling(w, sel[s]) * (nrm[s] @ nrm[s].T)
            mu_s = solve_rows(A, target[s] - u)
            pushing = cable[s] & (mu_s > 0.0) & (u <= target[s])
            if not pushing.any():
                break
            keep[s[pushing]] = False
            if not keep.any():
                mu_s, s = np.zeros(0), s[:0]
                break
        mu[s] = mu_s
        v += self._spread(n, w, mu[:, None] * nrm, sel)
        # Each link's impulse along it, > 0 pulling: the position part acted as lam r / dt.
        along = -(lam[sel] * np.einsum("ij,ij->i", r[sel], nrm) / dt + mu)
        for k, p in zip(sel.tolist(), along.tolist(), strict=True):
            self.links[k].impulse = p
        return x, v

    def _resolve_one(
        self,
        k: int,
        x0: np.ndarray,
        x: np.ndarray,
        v1: np.ndarray,
        v: np.ndarray,
        w: np.ndarray,
        dt: float,
        kinked: np.ndarray | None,
    ) -> None:
        """``resolve`` for link k alone, in place on (x, v), in Python floats (a World whose
        links share no body: each is then a problem of its own).

        With one link Newton's equation is a quadratic: |d + s lam r|^2 = L^2 with s = w_i +
        w_j, so a lam^2 + b lam + c = 0 with a = s^2 |r|^2, b = 2 s (d . r), c = |d|^2 - L^2;
        the root nearer 0 is the smaller correction (taken in the stable form q = -(b +
        sign(b) sqrt(b^2 - 4ac)) / 2, roots q / a and c / q). The speed along the link then
        needs mu = (target - u) / s.
        """
        link = self.links[k]
        i, j = int(self.i[k]), int(self.j[k])
        L, rigid = float(self.L[k]), bool(self.rigid[k])
        wi = float(w[i])
        wj = float(w[j]) if j >= 0 else 0.0
        s = wi + wj
        if s == 0.0:
            return
        px, py = (float(x[j, 0]), float(x[j, 1])) if j >= 0 else (self.p[k, 0], self.p[k, 1])
        dx, dy = float(x[i, 0]) - px, float(x[i, 1]) - py
        length2 = dx * dx + dy * dy
        if not rigid and length2 <= L * L:
            return  # a slack cable
        if j >= 0:
            sx, sy = float(x0[i, 0] - x0[j, 0]), float(x0[i, 1] - x0[j, 1])
        else:
            sx, sy = float(x0[i, 0]) - px, float(x0[i, 1]) - py
        struck = kinked is not None and (bool(kinked[i]) or (j >= 0 and bool(kinked[j])))
        # Along the start direction (RATTLE), unless an end was struck in the step, or the
        # ends passed each other in it (then the start direction points back).
        crossed = sx * dx + sy * dy < 0.0
        rx, ry = (dx, dy) if struck or crossed or sx * sx + sy * sy == 0.0 else (sx, sy)
        a = s * s * (rx * rx + ry * ry)
        b = 2.0 * s * (dx * rx + dy * ry)
        c = length2 - L * L
        disc = b * b - 4.0 * a * c
        lam: float | None = None
        if a > 0.0 and disc >= 0.0:
            q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
            roots = [q / a] + ([c / q] if q != 0.0 else [])
            lam = min(roots, key=abs)
        if lam is None:
            # Past what a step can pull back along r: put the end on the circle along the
            # link as it points now (module text), and say so.
            self.stretched.append(link)
            dist = math.sqrt(length2)
            if dist == 0.0:
                return
            lam = (L - dist) / (s * dist)
            rx, ry = dx, dy
        elif not rigid and lam * (rx * dx + ry * dy) > 0.0:
            # The cable would push: it moves the end away from the other one (along r when r
            # and d agree; across the anchor, where the end passed it within the step and r
            # points back, a pull moves it along r).
            return
        self.moved = True
        cx, cy = lam * rx, lam * ry
        x[i, 0] += wi * cx
        x[i, 1] += wi * cy
        v[i, 0] += wi * cx / dt
        v[i, 1] += wi * cy / dt
        if j >= 0:
            x[j, 0] -= wj * cx
            x[j, 1] -= wj * cy
            v[j, 0] -= wj * cx / dt
            v[j, 1] -= wj * cy / dt
            px, py = float(x[j, 0]), float(x[j, 1])
        dx, dy = float(x[i, 0]) - px, float(x[i, 1]) - py
        dist = math.hypot(dx, dy)
        nx, ny = (dx / dist, dy / dist) if dist > 0.0 else (0.0, 0.0)

        def parting(vel: np.ndarray) -> float:
            ux, uy = float(vel[i, 0]), float(vel[i, 1])
            if j >= 0:
                ux, uy = ux - float(vel[j, 0]), uy - float(vel[j, 1])
            return ux * nx + uy * ny

        target = 0.0
        if not rigid:
            sl = math.sqrt(sx * sx + sy * sy)
            if sl < L * (1.0 - 1e-9):  # slack as the step began: it snaps taut in it
                target = -float(self.e[k]) * max(parting(v1), 0.0)
        u = parting(v)
        mu = (target - u) / s
        if not rigid and mu > 0.0 and u <= target:
            mu = 0.0  # the ends already close: a cable does not push them
        v[i, 0] += wi * mu * nx
        v[i, 1] += wi * mu * ny
        if j >= 0:
            v[j, 0] -= wj * mu * nx
            v[j, 1] -= wj * mu * ny
        link.impulse = -(lam * (rx * nx + ry * ny) / dt + mu)

    def _rel(self, v: np.ndarray, nrm: np.ndarray, sel: np.ndarray) -> np.ndarray:
        """Each link's parting speed along ``nrm`` (> 0: the ends move apart)."""
        j = self.j[sel]
        vo = np.where((j >= 0)[:, None], v[np.maximum(j, 0)], 0.0)
        return np.einsum("ij,ij->i", v[self.i[sel]] - vo, nrm)

    def _positions(
        self, x: np.ndarray, r: np.ndarray, w: np.ndarray, sel: np.ndarray, n: int
    ) -> tuple[np.ndarray, bool]:
        """Newton's method for the multipliers of links ``sel``; (lam, converged)."""
        rs, L = r[sel], self.L[sel]
        S = self._coupling(w, sel)
        lam = np.zeros(len(sel))
        for _ in range(MAX_ITERATIONS):
            X = x + self._spread(n, w, lam[:, None] * rs, sel)
            d = self._ends(X)[sel]
            c = np.einsum("ij,ij->i", d, d) - L * L
            if float(np.abs(c / (L * L)).max()) <= 2.0 * TOLERANCE:
                return lam, True
            J = 2.0 * S * (d @ rs.T)
            step = solve_rows(J, -c)
            if not np.isfinite(step).all():
                break
            lam = lam + step
        return lam, False

    def _project(self, x: np.ndarray, w: np.ndarray, sel: np.ndarray, n: int) -> np.ndarray:
        """The fallback: links one after another, each end moved along the link's current
        direction to its length (Gauss-Seidel; always possible; a cable only while it is
        too long), until they hold."""
        X = x.copy()
        i, j, L = self.i[sel], self.j[sel], self.L[sel]
        rigid = self.rigid[sel]
        d0 = self._ends(x)[sel]
        too_long = (np.hypot(d0[:, 0], d0[:, 1]) > L).tolist()
        for k, long_ in zip(sel.tolist(), too_long, strict=True):
            if long_ or self.rigid[k]:
                self.stretched.append(self.links[k])
        for _ in range(200):
            worst = 0.0
            for a, b, length, p, rod in zip(
                i.tolist(), j.tolist(), L.tolist(), self.p[sel], rigid.tolist(), strict=True
            ):
                end = X[b] if b >= 0 else p
                d = X[a] - end
                dist = math.hypot(float(d[0]), float(d[1]))
                wa, wb = w[a], (w[b] if b >= 0 else 0.0)
                if dist == 0.0 or wa + wb == 0.0 or (not rod and dist <= length):
                    continue  # (a slack cable pulls nothing)
                err = dist - length
                worst = max(worst, abs(err) / length)
                corr = d * (err / (dist * (wa + wb)))
                X[a] -= wa * corr
                if b >= 0:
                    X[b] += wb * corr
            if worst <= TOLERANCE:
                break
        return X - x


def solve_rows(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A x = b; least squares where A is singular (links that repeat one another)."""
    try:
        return np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        return np.linalg.lstsq(A, b, rcond=None)[0]
