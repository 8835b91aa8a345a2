"""The joint solver: a step corrected for joints at anchors (engine.joints) and links held
away from a body's centre, on bodies that turn.

Each joint is a few scalar equations c(q) = 0 on the configuration q = (x, y, theta) of its
two bodies, where an anchor a (in body i's frame) is at p = x_i + R(theta_i) a, with lever
arm r = R(theta_i) a, and moves with dp/dtheta_i = perp(r) = (-r_y, r_x):

- a point the two bodies share (Hinge, Weld, a Pin with an anchor): c = p_a - p_b, two rows;
- a distance (Rod; Cable, at most): c = |p_a - p_b| - L, gradient n = d / |d| at each end
  (n . perp(r) = r x n on the angle);
- an angle (Weld; a Hinge's limits, at least or at most): c = theta_a - theta_b - ref - bound;
- a motor (velocity only): theta_a' - theta_b' = motor_speed, with |impulse| <= max_torque dt.

The mass matrix diag(m, m, I) of (x, y, theta) is constant, so RATTLE (Andersen 1983) holds
as for the rods of points (engine.links), now with the angle as one more coordinate:

1. Positions. The step moved every body as if free (its method, the free rotation under
   torque, the contacts). The correction moves q along the rows' gradients G at the start of
   the step, dq = W G^T lam (W = diag(1/m, 1/m, 1/I); 0 for what is held or does not turn),
   and Newton's method finds lam with c(q1 + dq) = 0: its Jacobian is J(q) W G^T. All the
   rows at once, so a chain's error does not creep from joint to joint.
2. Velocities. The correction is an impulse: v gains dq / dt. Then the velocity rows at the
   end, J v = target (0 for a joint's rows; the motor's speed; a cable's bounce), solve
   (J W J^T) mu = target - J v.

Inequalities (a cable, a limit) take part only while they hold something: an active set,
dropping a row whose multiplier would push the wrong way and taking in one the others'
correction violated; a motor whose impulse would pass max_torque dt is held at it. A soft
weld is a velocity row with the implicit spring-damper's mixing (Box2D v3's soft step): its
frequency omega and damping ratio zeta give (A + A_rr / (h omega (h omega + 2 zeta))) mu =
-J v - c omega / (h omega + 2 zeta).

The error after a step: every joint's rows to 1e-12 of the scene's size (TOLERANCE), unless
a StabilityWarning said the step was past what Newton's method could hold.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .body import Body
from .joints import Hinge, Joint, Weld
from .links import Cable, Link, Pin, solve_rows

__all__ = ["JointSolver", "TOLERANCE"]

#: A row's error after the solve, relative to the scene's size (its largest anchor or length).
TOLERANCE = 1e-12
#: Newton iterations before a step counts as past what the solver can hold.
MAX_ITERATIONS = 25

# Row kinds.
_PX, _PY, _DIST, _ANGLE, _MOTOR, _SOFT_X, _SOFT_Y, _SOFT_ANGLE = range(8)


class JointSolver:
    """The World's links and joints as rows, and the correction of a step for them."""

    def __init__(self, links: list[Link], row_of: Any) -> None:
        self.links = links
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
        self.moved = False
        self.stretched: list[Link] = []

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
                add(k, _SOFT_X if soft else _PX)
                add(k, _SOFT_Y if soft else _PY)
                add(k, _SOFT_ANGLE if soft else _ANGLE, item.reference_angle)
            elif isinstance(item, Hinge):
                add(k, _PX)
                add(k, _PY)
                if item.limits is not None:
                    lo, hi = item.limits
                    add(k, _ANGLE, item.reference_angle + lo, +1)
                    add(k, _ANGLE, item.reference_angle + hi, -1)
                if item.motor_speed is not None:
                    add(k, _MOTOR, 0.0, 0, item.motor_speed)
            elif isinstance(item, Pin):
                add(k, _PX)
                add(k, _PY)
            else:
                add(k, _DIST, item.length, -1 if isinstance(item, Cable) else 0)
        return (
            np.array(link, dtype=np.intp),
            np.array(kind, dtype=np.intp),
            np.array(bound, dtype=float),
            np.array(sign, dtype=np.intp),
            np.array(speed, dtype=float),
        )

    def _eval(
        self, X: np.ndarray, TH: np.ndarray, link: np.ndarray, kind: np.ndarray, bound: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Each row's value c and gradient J (rows, 3 m) at positions X and angles TH."""
        i, j = self.i, self.j
        has = j >= 0
        ta = TH[i]
        ca, sa = np.cos(ta), np.sin(ta)
        ra = np.stack(
            [ca * self.aa[:, 0] - sa * self.aa[:, 1], sa * self.aa[:, 0] + ca * self.aa[:, 1]], 1
        )
        tb = np.where(has, TH[np.maximum(j, 0)], 0.0)
        cb, sb = np.cos(tb), np.sin(tb)
        rb = np.stack(
            [cb * self.ab[:, 0] - sb * self.ab[:, 1], sb * self.ab[:, 0] + cb * self.ab[:, 1]], 1
        )
        rb[~has] = 0.0
        pa = X[i] + ra
        pb = np.where(has[:, None], X[np.maximum(j, 0)] + rb, self.ab)
        d = pa - pb
        R = len(link)
        c = np.zeros(R)
        J = np.zeros((R, 3 * len(self.bodies)))
        ga = np.zeros((R, 3))  # the gradient on body_a: (x, y, theta)
        ra_r, rb_r, d_r = ra[link], rb[link], d[link]
        px = (kind == _PX) | (kind == _SOFT_X)
        py = (kind == _PY) | (kind == _SOFT_Y)
        c[px], c[py] = d_r[px, 0], d_r[py, 1]
        ga[px] = np.stack([np.ones(px.sum()), np.zeros(px.sum()), -ra_r[px, 1]], 1)
        ga[py] = np.stack([np.zeros(py.sum()), np.ones(py.sum()), ra_r[py, 0]], 1)
        gb = -ga.copy()
        gb[px, 2] = rb_r[px, 1]
        gb[py, 2] = -rb_r[py, 0]
        dist = kind == _DIST
        if dist.any():
            dd = d_r[dist]
            length = np.sqrt(np.einsum("ij,ij->i", dd, dd))
            n = dd / np.where(length > 0.0, length, 1.0)[:, None]
            c[dist] = length - bound[dist]
            ga[dist] = np.stack(
                [n[:, 0], n[:, 1], ra_r[dist, 0] * n[:, 1] - ra_r[dist, 1] * n[:, 0]], 1
            )
            gb[dist] = -np.stack(
                [n[:, 0], n[:, 1], rb_r[dist, 0] * n[:, 1] - rb_r[dist, 1] * n[:, 0]], 1
            )
        ang = (kind == _ANGLE) | (kind == _SOFT_ANGLE) | (kind == _MOTOR)
        if ang.any():
            c[ang] = ta[link[ang]] - tb[link[ang]] - bound[ang]
            ga[ang] = (0.0, 0.0, 1.0)
            gb[ang] = (0.0, 0.0, -1.0)
        r = np.arange(R)
        for q in range(3):
            J[r, 3 * self.ca[link] + q] = ga[:, q]
        on_b = self.cb[link] >= 0
        for q in range(3):
            J[r[on_b], 3 * self.cb[link][on_b] + q] += gb[on_b, q]
        return c, J

    # -- the step ------------------------------------------------------------------------
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
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The step's end state (x1, v1, th1, om1) corrected for the joints; ``w`` (N,): 1/m
        and ``k`` (N,): 1/I, 0 for what nothing moves or turns; ``kinked``: bodies whose
        velocity a contact changed in the step."""
        self.moved = False
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
        b = self.bodies
        m = len(b)
        Wm = np.stack([w[b], w[b], k[b]], 1).ravel()
        X1, T1 = x[b], th[b]

        def full(Xc: np.ndarray, Tc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            X, T = x.copy(), th.copy()
            X[b], T[b] = Xc, Tc
            return X, T

        # 1. Positions.
        held = (kind != _MOTOR) & (kind != _SOFT_X) & (kind != _SOFT_Y) & (kind != _SOFT_ANGLE)
        c1, J1 = self._eval(*full(X1, T1), link, kind, bound)
        _, G = self._eval(x0, th0, link, kind, bound)
        use_end = np.zeros(len(link), dtype=bool)
        if kinked is not None:
            hit = kinked[self.i] | ((self.j >= 0) & kinked[np.maximum(self.j, 0)])
            use_end |= hit[link]
        use_end |= (kind == _DIST) & (np.einsum("ij,ij->i", G, J1) < 0.0)
        G[use_end] = J1[use_end]
        movable = np.abs(J1) @ Wm > 0.0
        tol = TOLERANCE * self.size
        active = held & movable & ((sign == 0) | (sign * c1 < 0.0))
        lam = np.zeros(len(link))
        dq = np.zeros(3 * m)
        ok = True
        for _ in range(2 * len(link) + 2):
            sel = np.flatnonzero(active)
            if not len(sel):
                lam[:] = 0.0
                dq = np.zeros(3 * m)
                break
            lam_s, dq, ok = self._newton(X1, T1, full, link, kind, bound, G[sel], Wm, sel, tol)
            if not ok:
                break
            lam[:] = 0.0
            lam[sel] = lam_s
            wrong = (sign[sel] != 0) & (sign[sel] * lam_s < 0.0)
            if wrong.any():
                active[sel[wrong]] = False
                continue
            c, _ = self._eval(
                *full(X1 + dq.reshape(m, 3)[:, :2], T1 + dq.reshape(m, 3)[:, 2]), link, kind, bound
            )
            broken = held & movable & ~active & (sign != 0) & (sign * c < -tol)
            if not broken.any():
                break
            active |= broken
        if not ok:
            # Past what Newton's method holds along the start gradients: project along the
            # gradients where the bodies are (always possible), and say so.
            sel = np.flatnonzero(held & movable & ((sign == 0) | (sign * c1 <= 0.0)))
            dq = self._project(X1, T1, full, link, kind, bound, Wm, sel, tol)
            lam[:] = 0.0
            self.stretched = list({id(self.joined[q]): self.joined[q] for q in link[sel]}.values())
        x, v, th, om = x.copy(), v.copy(), th.copy(), om.copy()
        D = dq.reshape(m, 3)
        x[b] += D[:, :2]
        th[b] += D[:, 2]
        v[b] += D[:, :2] * (1.0 / dt)
        om[b] += D[:, 2] * (1.0 / dt)
        self.moved = True
        # 2. Velocities, at the end configuration.
        c, J = self._eval(x, th, link, kind, bound)
        V = np.stack([v[b, 0], v[b, 1], om[b]], 1).ravel()
        target = np.zeros(len(link))
        target[kind == _MOTOR] = speed[kind == _MOTOR]
        cable = (kind == _DIST) & (sign != 0)
        if cable.any():
            # A cable slack as the step began snaps taut in it: the ends part at -e u.
            c0, J0 = self._eval(x0, th0, link, kind, bound)
            V1 = np.stack([v1[b, 0], v1[b, 1], om1[b]], 1).ravel()
            e = np.array([self.joined[q].restitution for q in link])
            snap = cable & (c0 < -1e-9 * np.maximum(bound, 1e-300))
            target[snap] = -e[snap] * np.maximum(J0[snap] @ V1, 0.0)
        soft = (kind == _SOFT_X) | (kind == _SOFT_Y) | (kind == _SOFT_ANGLE)
        # Inequalities act at their bound only (a cable taut, a limit reached).
        at = (sign != 0) & (sign * c <= tol)
        rows = movable & ((sign == 0) | at)
        clamp = np.full(len(link), np.inf)
        is_motor = kind == _MOTOR
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
            same = (link == link[q]) & at & (kind == _ANGLE)
            if (same & (sign * speed[q] < 0.0)).any():
                free[q] = False
                fixed[q] = math.copysign(clamp[q], speed[q]) if math.isfinite(clamp[q]) else 0.0
        mu = np.zeros(len(link))
        for _ in range(2 * len(link) + 2):
            s = np.flatnonzero(free)
            Vf = V + Wm * (J.T @ fixed)
            mu[:] = 0.0
            if len(s):
                Js = J[s]
                A = (Js * Wm) @ Js.T + np.diag(mix[s])
                mu[s] = solve_rows(A, target[s] - Js @ Vf)
            wrong = free & (sign != 0) & (sign * mu < 0.0)
            over = free & is_motor & (np.abs(mu) > clamp)
            if wrong.any():
                free[wrong] = False
                continue
            if over.any():
                free[over] = False
                fixed[over] = np.copysign(clamp[over], mu[over])
                continue
            break
        mu += fixed
        V = V + Wm * (J.T @ mu)
        Vm = V.reshape(m, 3)
        v[b] = Vm[:, :2]
        om[b] = Vm[:, 2]
        self._report(link, kind, sign, G, J, lam, mu, dt)
        return x, v, th, om

    def _newton(
        self,
        X1: np.ndarray,
        T1: np.ndarray,
        full: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
        link: np.ndarray,
        kind: np.ndarray,
        bound: np.ndarray,
        Gs: np.ndarray,
        Wm: np.ndarray,
        sel: np.ndarray,
        tol: float,
    ) -> tuple[np.ndarray, np.ndarray, bool]:
        """Newton's method for the multipliers of rows ``sel``: (lam, dq, converged)."""
        m = len(X1)
        lam = np.zeros(len(sel))
        WG = Wm[:, None] * Gs.T  # (3m, rows): dq = WG lam
        dq = np.zeros(3 * m)
        prev = math.inf
        for it in range(MAX_ITERATIONS):
            D = dq.reshape(m, 3)
            c, J = self._eval(*full(X1 + D[:, :2], T1 + D[:, 2]), link[sel], kind[sel], bound[sel])
            # Done at round-off: far below the tolerance, or within it and no longer halving
            # (an error left at the tolerance step after step would creep up to it).
            err = float(np.abs(c).max())
            if it and (err <= 1e-3 * tol or (err <= tol and err > 0.5 * prev)):
                return lam, dq, True
            prev = err
            step = solve_rows(J @ WG, -c)
            if not np.isfinite(step).all():
                break
            lam = lam + step
            dq = WG @ lam
        return lam, dq, False

    def _project(
        self,
        X1: np.ndarray,
        T1: np.ndarray,
        full: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
        link: np.ndarray,
        kind: np.ndarray,
        bound: np.ndarray,
        Wm: np.ndarray,
        sel: np.ndarray,
        tol: float,
    ) -> np.ndarray:
        """The fallback: Gauss-Newton along the gradients where the bodies are now."""
        m = len(X1)
        dq = np.zeros(3 * m)
        if not len(sel):
            return dq
        for _ in range(200):
            D = dq.reshape(m, 3)
            c, J = self._eval(*full(X1 + D[:, :2], T1 + D[:, 2]), link[sel], kind[sel], bound[sel])
            if float(np.abs(c).max()) <= tol:
                break
            WJ = Wm[:, None] * J.T
            dq = dq - WJ @ solve_rows(J @ WJ, c)
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
            item = self.joined[link[q]]
            col = 3 * self.ca[link[q]]
            px, py, pt = float(P[q, col]), float(P[q, col + 1]), float(P[q, col + 2])
            if kind[q] == _DIST:
                # > 0 pulls the ends together: body_a's gradient points away from the other.
                n0 = G[q, col : col + 2]
                n1 = J[q, col : col + 2]
                item.impulse = -(float(lam[q] * (n0 @ n1)) / dt + float(mu[q]))
            elif isinstance(item, Joint):
                if kind[q] in (_PX, _PY, _SOFT_X, _SOFT_Y):
                    item.linear_impulse = item.linear_impulse + (px, py)
                    item.impulse = item.linear_impulse.length()
                else:
                    item.angular_impulse += pt
                    if kind[q] == _MOTOR:
                        item.motor_impulse += pt  # type: ignore[attr-defined]
            else:  # a Pin with an anchor: the size of its impulse (N s)
                ox, oy = pins.get(int(link[q]), (0.0, 0.0))
                pins[int(link[q])] = (ox + px, oy + py)
                item.impulse = math.hypot(*pins[int(link[q])])
