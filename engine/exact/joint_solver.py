"""The joint solver: a step corrected for joints at anchors (engine.dynamics.joints) and links held
away from a body's centre, on bodies that turn.

Each joint is a few scalar rows c(q) = 0 on the configuration q = (x, y, theta) of its two
bodies (engine.exact.joint_rows: a point two bodies share, a distance, an angle; a motor's and a
soft weld's rows, for speeds only; the contacts of joined bodies). The mass matrix
diag(m, m, I) of (x, y, theta) is constant, so RATTLE (Andersen 1983) holds as for the rods
of points (engine.dynamics.links), now with the angle as one more coordinate:

1. Positions. The step moved every body as if free (its method, the free rotation under
   torque, the contacts). The correction moves q along the rows' gradients G at the start of
   the step, dq = W G^T lam (W = diag(1/m, 1/m, 1/I); 0 for what is held or does not turn),
   and Newton's method finds lam with c(q1 + dq) = 0: its Jacobian is J(q) W G^T. All the
   rows at once, so a chain's error does not creep from joint to joint.
2. Velocities. The joints' correction is an impulse: v gains dq / dt (a contact's is not: it
   only keeps two bodies from closing; it moves along its gradient where the bodies are, as
   a disc's distance from a polygon is exact wherever the polygon turns, engine.exact.joint_rows).
   Then the velocity rows at the end, J v = target (0 for a joint's rows; the motor's speed;
   a cable's bounce; for a contact that touches or met in the step, 0, or e times the speed
   it closed at as the step began where the pile's own bounce was undone), solve
   (J W J^T) mu = target - J v.
3. What acts on speeds alone (a motor, friction, a soft weld) moves the positions by half its
   change of speed times dt, as a force's a dt^2 / 2, and the joints and the contacts that
   held are put back after (no impulse).

Inequalities (a cable, a limit, a contact) take part only while they hold something: an
active set, dropping a row whose multiplier would push the wrong way and taking in one the
others' correction violated; a motor whose impulse would pass max_torque dt is held at it;
friction past mu times its normal impulse slides (Coulomb: its impulse is then mu_f times
the normal's, a column of that unknown). A soft weld is a velocity row with the implicit
spring-damper's mixing (Box2D v3's soft step): its frequency omega and damping ratio zeta
give (A + A_rr / (h omega (h omega + 2 zeta))) mu = -J v - c omega / (h omega + 2 zeta).

The error after a step: every joint's rows to 1e-12 of the scene's size (TOLERANCE), a
contact's to 1e-9 (CONTACT_TOLERANCE; contacts the joints leave no room for give way), unless
a StabilityWarning said the step was past what Newton's method could hold (joints that cannot
all hold are then projected as near as they go, by least squares, with no impulse).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..body import Body
from ..dynamics.joints import Hinge, Joint, Weld
from ..dynamics.links import Cable, Link, Pin
from ..geometry.manifold_kinds import Polygons
from .joint_rows import (
    ANGLE,
    CN,
    CT,
    DIST,
    MOTOR,
    PX,
    PY,
    SOFT_ANGLE,
    SOFT_X,
    SOFT_Y,
    Plan,
    Touch,
    evaluate,
)  # fmt: skip

__all__ = ["JointSolver", "TOLERANCE"]

#: A row's error after the solve, relative to the scene's size (its largest anchor or length).
TOLERANCE = 1e-12
#: A contact's row's error after the solve, relative to the scene's size: a contact beside a
#: joint (a plank folded onto the one it is hinged to) may meet it only to second order in
#: the step (its row is linear in the angles), which is far below any overlap that shows.
CONTACT_TOLERANCE = 1e-9
#: Newton iterations before a step counts as past what the solver can hold.
MAX_ITERATIONS = 25


class JointSolver:
    """The World's links and joints as rows, and the correction of a step for them."""

    def __init__(self, links: list[Link], row_of: Any, fast: bool = False) -> None:
        self.links = links
        #: The rows' values and gradients by the loop kernel (engine.exact.joint_rows.rows_loop).
        self.fast = fast
        self.pins = [k for k in links if isinstance(k, Pin) and k.holds]
        self.pin_rows = np.array([row_of(p.body) for p in self.pins], dtype=np.intp)
        self.pin_points = np.array([tuple(p.point) for p in self.pins], dtype=float).reshape(-1, 2)
        joined = [k for k in links if not (isinstance(k, Pin) and k.holds)]
        self.joined = joined
        self.i = np.array([row_of(k.body) for k in joined], dtype=np.intp)
        self.j = np.array(
            [row_of(k.other) if isinstance(k.other, Body) else -1 for k in joined], dtype=np.intp
        )
        self.aa = np.array([tuple(k.anchor_a) for k in joined], dtype=float).reshape(-1, 2)
        # The anchor on body_b, or the fixed point for a link to the world.
        self.ab = np.array(
            [tuple(k.anchor_b) if isinstance(k.other, Body) else tuple(k.other) for k in joined],
            dtype=float,
        ).reshape(-1, 2)
        rows = np.concatenate([self.i, self.j[self.j >= 0]])
        self.bodies = np.unique(rows) if len(rows) else np.zeros(0, dtype=np.intp)
        col = np.full(int(self.bodies.max()) + 1 if len(self.bodies) else 0, -1, dtype=np.intp)
        col[self.bodies] = np.arange(len(self.bodies))
        self.ca = col[self.i] if len(self.i) else self.i
        self.cb = np.where(self.j >= 0, col[np.maximum(self.j, 0)], -1) if len(self.j) else self.j
        size = [1.0]
        for k in joined:
            size += [abs(k.anchor_a.x), abs(k.anchor_a.y), abs(k.anchor_b.x), abs(k.anchor_b.y)]
            size.append(k.length)
        self.size = max(size)
        self._touch(None, None, None)
        self._polygons: Polygons | None = None
        #: The contacts (rows of the last ``touch``) the last step held touching.
        self.held = np.zeros(0, dtype=np.intp)
        #: Whether the last step caught a blow: a contact it held that closed fast (resolve).
        self.blow = False
        self.moved = False
        self.stretched: list[Link] = []

    def _touch(
        self,
        touch: Touch | None,
        x: np.ndarray | None,
        th: np.ndarray | None,
        x0: np.ndarray | None = None,
        th0: np.ndarray | None = None,
    ) -> None:
        """The bodies and per-link arrays the rows index, with one entry more for each contact
        of ``touch`` and its bodies among the joints' (x, th: where the step left them; x0,
        th0: where it began, the place of a contact against a face, Touch.turn)."""
        self._bodies = self.bodies
        self._i, self._j, self._aa, self._ab = self.i, self.j, self.aa, self.ab
        self._ca, self._cb = self.ca, self.cb
        K = len(self.i)
        z2, z1 = np.zeros((K, 2)), np.zeros(K)
        z0, none = np.zeros(K, dtype=np.int8), np.full(K, -1, dtype=np.intp)
        self._contact: tuple[np.ndarray, ...] = (z2, z2, z2, z2, z2, z1, z1, z1, z0, none, z1)
        if touch is None or x is None or th is None:
            return
        k = len(touch.body)
        other = touch.other
        has = other >= 0
        rows = np.concatenate([self.bodies, touch.body, other[has]])
        self._bodies = np.unique(rows)
        col = np.full(int(self._bodies.max()) + 1, -1, dtype=np.intp)
        col[self._bodies] = np.arange(len(self._bodies))
        self._i = np.concatenate([self.i, touch.body])
        self._j = np.concatenate([self.j, other])
        self._aa = np.concatenate([self.aa, np.zeros((k, 2))])
        self._ab = np.concatenate([self.ab, np.zeros((k, 2))])
        self._ca = col[self._i]
        self._cb = np.where(self._j >= 0, col[np.maximum(self._j, 0)], -1)
        oc = np.maximum(other, 0)
        refb, thb = x[touch.body], th[touch.body]
        refo = np.where(has[:, None], x[oc], 0.0)
        tho = np.where(has, th[oc], 0.0)
        if x0 is not None and th0 is not None and touch.turn.any():
            face = touch.turn != 0
            refb = np.where(face[:, None], x0[touch.body], refb)
            thb = np.where(face, th0[touch.body], thb)
            refo = np.where((face & has)[:, None], x0[oc], refo)
            tho = np.where(face & has, th0[oc], tho)
        self._contact = tuple(
            np.concatenate([base, extra])
            for base, extra in zip(
                self._contact,
                (
                    touch.normal,
                    touch.r_body,
                    touch.r_other,
                    refb,
                    refo,
                    thb,
                    tho,
                    touch.gap,
                    touch.turn,
                    touch.poly,
                    touch.radius,
                ),  # fmt: skip
                strict=True,
            )
        )

    # -- rows ----------------------------------------------------------------------------
    def _rows(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The rows as they stand now (limits and motors can change between steps): each
        row's link, kind, bound, sign (0 an equation; +1 c >= 0; -1 c <= 0) and, for a motor,
        its speed."""
        link, kind, bound, sign, speed = [], [], [], [], []

        def add(k: int, what: int, b: float = 0.0, s: int = 0, v: float = 0.0) -> None:
            link.append(k)
            kind.append(what)
            bound.append(b)
            sign.append(s)
            speed.append(v)

        for k, item in enumerate(self.joined):
            if isinstance(item, Weld):
                soft = item.hertz is not None
                add(k, SOFT_X if soft else PX)
                add(k, SOFT_Y if soft else PY)
                add(k, SOFT_ANGLE if soft else ANGLE, item.reference_angle)
            elif isinstance(item, Hinge):
                add(k, PX)
                add(k, PY)
                if item.limits is not None:
                    lo, hi = item.limits
                    add(k, ANGLE, item.reference_angle + lo, +1)
                    add(k, ANGLE, item.reference_angle + hi, -1)
                if item.motor_speed is not None:
                    add(k, MOTOR, 0.0, 0, item.motor_speed)
            elif isinstance(item, Pin):
                add(k, PX)
                add(k, PY)
            else:
                add(k, DIST, item.length, -1 if isinstance(item, Cable) else 0)
        return (
            np.array(link, dtype=np.intp),
            np.array(kind, dtype=np.intp),
            np.array(bound, dtype=float),
            np.array(sign, dtype=np.intp),
            np.array(speed, dtype=float),
        )

    def _plan(self, link: np.ndarray, kind: np.ndarray, bound: np.ndarray) -> Plan:
        """The rows as arrays by row, bodies by their place among the joints' bodies: the
        links' packed fields (``_pack``) taken by row, beside each row's kind and bound."""
        li, lf = self._pack()
        ints = np.column_stack([kind, li[link]])
        floats = np.column_stack([bound, lf[link]])
        return Plan.packed(ints, floats, 3 * len(self._bodies), self._polygons)

    def _pack(self) -> tuple[np.ndarray, np.ndarray]:
        """Each link's (and contact's) fields as Plan.packed holds them, less a row's kind and
        bound: (a, b, turn, poly) and (aa, ab, n, rbod, roth, refb, refo, thb, tho, gap,
        radius)."""
        n, rbod, roth, refb, refo, thb, tho, gap, turn, poly, radius = self._contact
        ints = np.stack([self._ca, self._cb, turn, poly], 1).astype(np.int64)
        floats = np.column_stack(
            [self._aa, self._ab, n, rbod, roth, refb, refo, thb, tho, gap, radius]
        )
        return ints, floats

    def _eval(self, X: np.ndarray, TH: np.ndarray, P: Plan) -> tuple[np.ndarray, np.ndarray]:
        """Each row's value c and gradient J (engine.exact.joint_rows)."""
        return evaluate(X, TH, P, self.fast)

    def resolve(
        self,
        x0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        th0: np.ndarray,
        th1: np.ndarray,
        om1: np.ndarray,
        w: np.ndarray,
        k: np.ndarray,
        dt: float,
        kinked: np.ndarray | None = None,
        touch: Touch | None = None,
        polygons: Polygons | None = None,
        start: tuple[np.ndarray, np.ndarray] | None = None,
        bounce_at: float = math.inf,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The step's end state (x1, v1, th1, om1) corrected for the joints; ``w`` (N,): 1/m
        and ``k`` (N,): 1/I, 0 for what nothing moves or turns; ``kinked``: bodies whose
        velocity a contact changed in the step; ``touch``: the joints' bodies resting on a
        collider, whose contact takes part in the correction (a wheel driven by a motor
        rolls on its friction), with the impulse it already gave counted; ``polygons``: the
        World's, which its discs against polygons index (Touch.poly); ``start``: the
        velocities and angular velocities as the step began, and ``bounce_at`` (length
        units/s): a contact of the pile caught closing bounces with its restitution times
        the speed it closed at then, if faster than this. ``held`` then lists the contacts
        (rows of ``touch``) held touching, and ``blow`` says whether one of those it acted on
        had closed faster than that (a blow the solve caught, not a rest or a carry)."""
        self.moved = False
        self.blow = False
        self._polygons = polygons
        self.held = np.zeros(0, dtype=np.intp)
        self.stretched = []
        x, v, th, om = x1, v1, th1, om1
        if len(self.pin_rows):
            x, v = x.copy(), v.copy()
            x[self.pin_rows] = self.pin_points
            v[self.pin_rows] = 0.0
            self.moved = True
        for item in self.joined:
            item.impulse = 0.0
            if isinstance(item, Joint):
                item.linear_impulse = item.linear_impulse * 0.0
                item.angular_impulse = 0.0
                if isinstance(item, Hinge):
                    item.motor_impulse = 0.0
        if not self.joined:
            return x, v, th, om
        link, kind, bound, sign, speed = self._rows()
        self._touch(touch, x, th, x0, th0)
        K = len(self.joined)
        if touch is not None:
            # Each contact: a row along its normal (no closer; position and velocity) and one
            # of its slip (velocity only, within the friction's reach).
            k_t = len(touch.body)
            rest = K + np.arange(k_t)
            link = np.concatenate([link, rest, rest])
            kind = np.concatenate([kind, np.full(k_t, CN), np.full(k_t, CT)])
            bound = np.concatenate([bound, np.zeros(2 * k_t)])
            sign = np.concatenate([sign, np.ones(k_t, dtype=np.intp), np.zeros(k_t, dtype=np.intp)])
            speed = np.concatenate([speed, np.zeros(2 * k_t)])
        b = self._bodies
        m = len(b)
        Wm = np.stack([w[b], w[b], k[b]], 1).ravel()
        X1, T1 = x[b], th[b]
        plan = self._plan(link, kind, bound)

        # 1. Positions.
        held = (kind != MOTOR) & (kind != SOFT_X) & (kind != SOFT_Y) & (kind != SOFT_ANGLE)
        held &= kind != CT
        c1, J1 = self._eval(X1, T1, plan)
        _, G = self._eval(x0[b], th0[b], plan)
        use_end = np.zeros(len(link), dtype=bool)
        if kinked is not None:
            hit = kinked[self._i] | ((self._j >= 0) & kinked[np.maximum(self._j, 0)])
            use_end |= hit[link]
        use_end |= (kind == DIST) & (np.einsum("ij,ij->i", G, J1) < 0.0)
        G[use_end] = J1[use_end]
        movable = np.abs(J1) @ Wm > 0.0
        tol = TOLERANCE * self.size
        contact = kind == CN  # (moved along their gradient where the bodies are: no impulse)
        active = held & movable & ((sign == 0) | (sign * c1 < 0.0))
        lam = np.zeros(len(link))
        dq = np.zeros(3 * m)
        ok = True
        relaxed = False
        end: tuple[np.ndarray, np.ndarray] | None = None  # (c, J) where the correction ends
        for _ in range(2 * len(link) + 2):
            end = None
            sel = np.flatnonzero(active)
            if not len(sel):
                lam[:] = 0.0
                dq = np.zeros(3 * m)
                end = (c1, J1)
                break
            lam_s, dq, ok = self._newton(
                X1, T1, plan.take(sel), G[sel], Wm, tol, contact[sel], (c1[sel], J1[sel])
            )
            if not ok and contact[sel].any():
                # Contacts the joints leave no room for (two points of a plank folded onto
                # the one it is hinged to: one turn left, and rows linear in it): the joints
                # hold, the contacts give (the next step's pile takes the overlap out).
                active &= ~contact
                relaxed = True
                continue
            if not ok:
                break
            lam[:] = 0.0
            lam[sel] = lam_s
            wrong = (sign[sel] != 0) & (sign[sel] * lam_s < 0.0)
            if wrong.any():
                active[sel[wrong]] = False
                continue
            D = dq.reshape(m, 3)
            end = self._eval(X1 + D[:, :2], T1 + D[:, 2], plan)
            c = end[0]
            broken = held & movable & ~active & (sign != 0) & (sign * c < -tol)
            if relaxed:
                broken &= ~contact
            if not broken.any():
                break
            active |= broken
        if not ok:
            # Past what Newton's method holds along the start gradients: project along the
            # gradients where the bodies are (always possible), and say so.
            sel = np.flatnonzero(held & movable & ((sign == 0) | (sign * c1 <= 0.0)))
            dq = self._project(X1, T1, plan.take(sel), Wm, tol)
            lam[:] = 0.0
            self.stretched = list(
                {id(self.joined[q]): self.joined[q] for q in link[sel] if q < K}.values()
            )
        x, v, th, om = x.copy(), v.copy(), th.copy(), om.copy()
        D = dq.reshape(m, 3)
        x[b] += D[:, :2]
        th[b] += D[:, 2]
        if ok:
            # The joints' correction is an impulse (RATTLE); a contact's only keeps the two
            # from closing, and gives them no speed.
            own = link < K
            kick = (Wm * (G[own].T @ lam[own])).reshape(m, 3) if own.any() else D * 0.0
            v[b] += kick[:, :2] * (1.0 / dt)
            om[b] += kick[:, 2] * (1.0 / dt)
        # (The fallback's move is a projection, not an impulse: joints that cannot all hold
        # would otherwise feed its correction into the speeds step after step. The velocity
        # solve below is a projection in the mass metric too, so no energy comes of it.)
        self.moved = True
        # 2. Velocities, at the end configuration (as the last check of positions left it).
        c, J = end if ok and end is not None else self._eval(x[b], th[b], plan)
        V = np.stack([v[b, 0], v[b, 1], om[b]], 1).ravel()
        target = np.zeros(len(link))
        target[kind == MOTOR] = speed[kind == MOTOR]
        cable = (kind == DIST) & (sign != 0)
        if cable.any():
            # A cable slack as the step began snaps taut in it: the ends part at -e u.
            c0, J0 = self._eval(x0[b], th0[b], plan)
            V1 = np.stack([v1[b, 0], v1[b, 1], om1[b]], 1).ravel()
            e = np.array(
                [self.joined[q].restitution if cable[r] else 0.0 for r, q in enumerate(link)]
            )
            snap = cable & (c0 < -1e-9 * np.maximum(bound, 1e-300))
            target[snap] = -e[snap] * np.maximum(J0[snap] @ V1, 0.0)
        soft = (kind == SOFT_X) | (kind == SOFT_Y) | (kind == SOFT_ANGLE)
        # Inequalities act at their bound only (a cable taut, a limit reached).
        at = (sign != 0) & (sign * c <= tol)
        rows = movable & ((sign == 0) | at)
        if touch is not None:
            # A contact acts where its two touch as the step ends or met in it (the pile
            # gave it an impulse), and only pushes (the active set lets go of one that would
            # pull): they do not close, and a disc resting on a collider may press harder or
            # lift. Its slip with it. (Not sooner: two apart by a gap are the next step's
            # pile's, whose speculative row sees the speeds this solve leaves; here such a
            # row, linear about where the step left the two, would brake a ball passing by a
            # bat's tip.)
            cn = np.flatnonzero(kind == CN)
            rows[cn] = movable[cn] & (at[cn] | (touch.pn > 0.0))
            if start is not None and math.isfinite(bounce_at):
                # One of the pile's that closed as the step began leaves at e times that
                # speed at least: the pile's own bounce is undone where the joints' solve
                # puts a bat back that the pile let give way (a light bat at its stop).
                v0, om0 = start
                V0 = np.stack([v0[b, 0], v0[b, 1], om0[b]], 1).ravel()
                approach = -(J[cn] @ V0)
                e = touch.restitution
                closing = rows[cn] & (approach > bounce_at)
                self.blow = bool(closing.any())
                bounce = closing & (e > 0.0)
                target[cn[bounce]] = (e * approach)[bounce]
            rows[cn + len(cn)] = rows[cn]
        clamp = np.full(len(link), np.inf)
        is_motor = kind == MOTOR
        for q in np.flatnonzero(is_motor):
            clamp[q] = self.joined[link[q]].max_torque * dt  # type: ignore[attr-defined]
        mix = np.zeros(len(link))
        if soft.any():
            for q in np.flatnonzero(soft):
                weld = self.joined[link[q]]
                om_ = 2.0 * math.pi * weld.hertz  # type: ignore[attr-defined]
                z = weld.damping_ratio  # type: ignore[attr-defined]
                a_rr = float(J[q] ** 2 @ Wm)
                hw = dt * om_
                mix[q] = a_rr / (hw * (hw + 2.0 * z)) if a_rr > 0.0 else 0.0
                target[q] = -c[q] * om_ / (hw + 2.0 * z)
        fixed = np.zeros(len(link))  # impulses of motors held at their max_torque dt
        free = rows.copy()
        # A motor turning its joint into a limit it is at pushes with all it has.
        for q in np.flatnonzero(is_motor & rows):
            same = (link == link[q]) & at & (kind == ANGLE)
            if (same & (sign * speed[q] < 0.0)).any():
                free[q] = False
                fixed[q] = math.copysign(clamp[q], speed[q]) if math.isfinite(clamp[q]) else 0.0
        # The least each row may give (sign * mu >= sign * floor): 0 for a cable or a limit;
        # for a resting disc's normal, minus what its contact already gave (it may lift).
        floor = np.zeros(len(link))
        slip = np.flatnonzero(kind == CT)
        slide = np.zeros(len(link))  # a sliding disc's friction: the sign it acts with
        normal_of = np.zeros(len(link), dtype=np.intp)
        pt_row = np.zeros(len(link))
        pn_row = np.zeros(len(link))
        reach = np.zeros(len(link))
        if touch is not None:
            floor[kind == CN] = np.where(touch.lift, -touch.pn, 0.0)
            normal_of[slip] = slip - len(slip)  # each slip row's normal row (in order)
            pt_row[slip], pn_row[slip], reach[slip] = touch.pt, touch.pn, touch.mu
        mu = np.zeros(len(link))  # each row's impulse (N s, or N m s), the rows' part
        tried = np.zeros(len(link), dtype=bool)  # a sliding disc tried sticking again

        def solve() -> None:
            # Unknowns: the free rows. A sliding disc's friction is mu_f times its whole
            # normal impulse, against its slip (Coulomb): a column of its normal's unknown.
            F = np.flatnonzero(free)
            E = np.zeros((len(link), len(F)))
            E[F, np.arange(len(F))] = 1.0
            lam0 = np.where(free, 0.0, fixed)
            where = np.full(len(link), -1, dtype=np.intp)
            where[F] = np.arange(len(F))
            for q in np.flatnonzero(slide != 0.0):
                nq = normal_of[q]
                k = slide[q] * reach[q]
                lam0[q] = k * (pn_row[q] + (0.0 if free[nq] else fixed[nq])) - pt_row[q]
                if free[nq]:
                    E[q, where[nq]] = k
            mu[:] = lam0
            if len(F):
                WJE = (Wm[:, None] * J.T) @ E
                A = J[F] @ WJE + np.diag(mix[F])
                mu[:] = lam0 + E @ _solve(A, target[F] - J[F] @ (V + Wm * (J.T @ lam0)))

        for _ in range(4 * len(link) + 2):
            solve()
            # A motor past its torque first (an unbounded one asks for anything), then rows
            # that would pull, then friction past its reach; a row let go that the speeds
            # then break is taken back.
            over = free & is_motor & (np.abs(mu) > clamp)
            if over.any():
                # At its torque, toward its speed from where the joint turns now (the rows'
                # split among motors that drive one motion together says nothing of that).
                free[over] = False
                fixed[over] = np.copysign(clamp[over], target[over] - J[over] @ V)
                continue
            wrong = free & (sign != 0) & (sign * (mu - floor) < 0.0)
            if wrong.any():
                free[wrong] = False
                fixed[wrong] = floor[wrong]
                continue
            if len(slip):
                # Friction within mu_f times the normal impulse, both counted whole (what the
                # contact gave in the step and what the rows add); past it, the disc slides.
                total = pt_row[slip] + mu[slip]
                most = reach[slip] * np.maximum(pn_row[slip] + mu[normal_of[slip]], 0.0)
                past = free[slip] & (np.abs(total) > most * (1.0 + 1e-12))
                if past.any():
                    q = slip[past]
                    free[q] = False
                    slide[q] = np.sign(total[past])
                    continue
                # A sliding disc whose friction would drive its slip, not stop it, sticks.
                u = J[slip] @ (V + Wm * (J.T @ mu))
                wrong_way = (slide[slip] != 0.0) & (slide[slip] * u > 1e-12) & ~tried[slip]
                if wrong_way.any():
                    q = slip[wrong_way]
                    free[q], slide[q], tried[q] = True, 0.0, True
                    continue
            held_m = is_motor & rows & ~free & ~tried
            if held_m.any():
                # A motor held at its torque that drove its joint past its speed lets go.
                u = J[held_m] @ (V + Wm * (J.T @ mu))
                past_m = (target[held_m] - u) * fixed[held_m] < -1e-12
                if past_m.any():
                    q = np.flatnonzero(held_m)[past_m]
                    free[q], fixed[q], tried[q] = True, 0.0, True
                    continue
            let_go = rows & ~free & (sign != 0)
            if let_go.any():
                u = J[let_go] @ (V + Wm * (J.T @ mu))
                back = sign[let_go] * (u - target[let_go]) < -1e-9
                if back.any():
                    q = np.flatnonzero(let_go)[back]
                    free[q], fixed[q] = True, 0.0
                    continue
            break
        else:
            solve()  # (out of turns: the rows as they stand now, solved together)
        V = V + Wm * (J.T @ mu)
        Vm = V.reshape(m, 3)
        v[b] = Vm[:, :2]
        om[b] = Vm[:, 2]
        # 3. What acts on speeds alone (a motor, friction, a soft weld) acted through the step
        # as the forces did: the positions take half its change of speed times dt (as the
        # closed form's a dt^2 / 2), and are put back onto the joints and onto the contacts
        # that held in the velocity solve (no impulse). A motor's wheel then turns by
        # T t^2 / (2 I), and a car held by its brakes on a slope stays where it is.
        alone = (kind == MOTOR) | (kind == CT) | soft
        for q in np.flatnonzero(is_motor & (mu != 0.0)):
            # A motor held at a limit its joint is at moves nothing: the limit takes it all
            # (it pushes with all it has, max_torque dt, and the limit pushes back).
            stop = (link == link[q]) & rows & at & (kind == ANGLE) & (mu != 0.0)
            if stop.any():
                alone[q] = False
        if alone.any() and mu[alone].any():
            shift = (Wm * (J[alone].T @ mu[alone])) * (0.5 * dt)
            S = shift.reshape(m, 3)
            Xs, Ts = x[b] + S[:, :2], th[b] + S[:, 2]
            c2, _ = self._eval(Xs, Ts, plan)
            # (A contact that held while touching is kept touching, as a wheel on the ground;
            # a speculative one, apart by its gap, only from closing past it.)
            touching = (kind == CN) & rows & (c <= tol)
            keep = held & movable & ((sign == 0) | (sign * c2 < 0.0) | touching)
            if relaxed:
                # The positions' solve let the contacts give way to joints that leave them no
                # room (above): they give here too, or the projection would split the overlap
                # between them and the joints (a box welded to the world beside a box pinned
                # at its place, pushed two thirds of the way out, its weld broken).
                keep &= ~contact
            for _ in range(4):
                back = self._project(Xs, Ts, plan.take(np.flatnonzero(keep)), Wm, tol)
                B = back.reshape(m, 3)
                c2, _ = self._eval(Xs + B[:, :2], Ts + B[:, 2], plan)
                broken = held & movable & ~keep & (sign != 0) & (sign * c2 < -tol)
                if relaxed:
                    broken &= ~contact
                if not broken.any():
                    break
                keep |= broken
            x[b], th[b] = Xs + B[:, :2], Ts + B[:, 2]
        self._report(link, kind, sign, G, J, lam, mu, dt)
        if touch is not None:
            cn = np.flatnonzero(kind == CN)
            acted = (rows[cn] & (mu[cn] > 0.0)) | (active[cn] & (lam[cn] > 0.0))
            self.held = np.flatnonzero(acted & (c[cn] <= tol))
        return x, v, th, om

    def _newton(
        self,
        X1: np.ndarray,
        T1: np.ndarray,
        P: Plan,
        Gs: np.ndarray,
        Wm: np.ndarray,
        tol: float,
        follow: np.ndarray | None = None,
        first: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> tuple[np.ndarray, np.ndarray, bool]:
        """Newton's method for the multipliers of rows ``P``: (lam, dq, converged). Rows
        ``follow`` (contacts) move along their gradient at each iterate, not at the start: a
        contact is a projection, not an impulse, and a bat turned far in the step meets the
        ball with another face than it began with. ``first``: the rows' (c, J) at (X1, T1),
        if known."""
        m = len(X1)
        lam = np.zeros(len(P.kind))
        WG = Wm[:, None] * Gs.T  # (3m, rows): dq = WG lam
        dq = np.zeros(3 * m)
        follows = follow is not None and bool(follow.any())
        scale = tol if not follows else np.where(follow, CONTACT_TOLERANCE * tol / TOLERANCE, tol)  # type: ignore[arg-type]
        prev = math.inf
        for it in range(MAX_ITERATIONS):
            if it == 0 and first is not None:
                c, J = first
            else:
                D = dq.reshape(m, 3)
                c, J = self._eval(X1 + D[:, :2], T1 + D[:, 2], P)
            # Done at round-off: far below the tolerance, or within it and no longer halving
            # (an error left at the tolerance step after step would creep up to it). A
            # contact's tolerance is CONTACT_TOLERANCE's: its row is linear in the angles
            # where a joint's is not, and a contact beside a hinge can hold both only to
            # second order in the step.
            err = float((np.abs(c) / scale).max())
            if it and (err <= 1e-3 or (err <= 1.0 and err > 0.5 * prev)):
                return lam, dq, True
            prev = err
            if follows:
                WG = Wm[:, None] * np.where(follow[:, None], J, Gs).T  # type: ignore[index]
            step = _solve(J @ WG, -c)
            if not np.isfinite(step).all():
                break
            lam = lam + step
            dq = dq + WG @ step if follows else WG @ lam
        return lam, dq, False

    def _project(
        self, X1: np.ndarray, T1: np.ndarray, P: Plan, Wm: np.ndarray, tol: float
    ) -> np.ndarray:
        """The fallback: Gauss-Newton along the gradients where the bodies are now."""
        m = len(X1)
        dq = np.zeros(3 * m)
        if not len(P.kind):
            return dq
        prev = math.inf
        for _ in range(50):
            D = dq.reshape(m, 3)
            c, J = self._eval(X1 + D[:, :2], T1 + D[:, 2], P)
            err = float(np.abs(c).max())
            if err <= tol or err > 0.99 * prev:
                break  # held, or as near as joints that cannot all hold allow
            prev = err
            WJ = Wm[:, None] * J.T
            dq = dq - WJ @ _solve(J @ WJ, c)
        return dq

    def _report(
        self,
        link: np.ndarray,
        kind: np.ndarray,
        sign: np.ndarray,
        G: np.ndarray,
        J: np.ndarray,
        lam: np.ndarray,
        mu: np.ndarray,
        dt: float,
    ) -> None:
        """Each joint's impulses over the step: the position part acted as G^T lam / dt."""
        P = G * (lam / dt)[:, None] + J * mu[:, None]  # each row's generalized impulse
        pins: dict[int, tuple[float, float]] = {}
        for q in range(len(link)):
            if link[q] >= len(self.joined):
                continue  # a resting disc's contact rows: the contact's own report
            item = self.joined[link[q]]
            col = 3 * self.ca[link[q]]
            px, py, pt = float(P[q, col]), float(P[q, col + 1]), float(P[q, col + 2])
            if kind[q] == DIST:
                # > 0 pulls the ends together: body_a's gradient points away from the other.
                n0 = G[q, col : col + 2]
                n1 = J[q, col : col + 2]
                item.impulse = -(float(lam[q] * (n0 @ n1)) / dt + float(mu[q]))
            elif isinstance(item, Joint):
                if kind[q] in (PX, PY, SOFT_X, SOFT_Y):
                    item.linear_impulse = item.linear_impulse + (px, py)
                    item.impulse = item.linear_impulse.length()
                else:
                    item.angular_impulse += pt
                    if kind[q] == MOTOR:
                        item.motor_impulse += pt  # type: ignore[attr-defined]
            else:  # a Pin with an anchor: the size of its impulse (N s)
                ox, oy = pins.get(int(link[q]), (0.0, 0.0))
                pins[int(link[q])] = (ox + px, oy + py)
                item.impulse = math.hypot(*pins[int(link[q])])


#: Singular values below this share of the largest count as zero (rows that repeat others).
RCOND = 1e-10
#: Up to this many rows, least squares always (the singular value decomposition costs little
#: more than a direct solve there, and motors or welds that repeat one another are common).
FEW = 16


def _solve(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A x = b for joint rows: the direct solve where A is well conditioned, else the least
    squares solution of least norm (joints that repeat each other, or cannot all hold: a
    direct solve would answer round-off with huge impulses)."""
    if len(A) <= FEW:
        return np.linalg.lstsq(A, b, rcond=RCOND)[0]
    try:
        x = np.linalg.solve(A, b)
        # |A| |x| >= |b| always; far more means A amplified round-off (it is near singular).
        big = float(np.abs(A).sum(axis=1).max()) * float(np.abs(x).max())
        if np.isfinite(x).all() and big <= float(np.abs(b).max()) / RCOND:
            return x
    except np.linalg.LinAlgError:
        pass
    return np.linalg.lstsq(A, b, rcond=RCOND)[0]
