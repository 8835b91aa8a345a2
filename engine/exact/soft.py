"""Contacts solved together: Box2D v3's soft step, for the bodies of a pile.

Impacts one at a time, in time order, are right where they are few and each one matters (a
bounce, a cradle); in a pile every contact leans on every other through the stack, and the
contacts must be solved together. This module does it as Box2D v3 does (Catto, "Solver2D",
2024; ``solver.c`` and ``contact_solver.c``): the bodies of a pile are stepped again from the
start of the step in ``substeps`` parts of h = dt / substeps, each part

1. integrating velocities: v += a h (a: each body's acceleration over the step);
2. warm starting: every contact's impulse of the part before (the last step's, at first) is
   applied again, so a settled pile starts solved;
3. solving, with bias: each contact's normal impulse keeps the bodies from closing faster
   than their separation s allows: a contact still open (s > 0) may close by s in this part,
   no more (a speculative contact: a ball falling onto the pile stops on it, whatever its
   speed); one overlapping is pushed apart by a soft spring (``contact_hertz``, critically
   over-damped by ``damping``, the push capped at ``push_speed``), so a pile does not jitter;
4. integrating positions: x += v h;
5. relaxing: the same solve without the spring's push, so the push moves positions only and
   leaves no speed behind (it adds no energy), and friction (Coulomb: |lam_t| <= mu lam_n),
   against the slip less what the surfaces move along themselves (``slip``: a conveyor);

then, once, restitution for contacts that closed faster than ``threshold``: the normal speed
they part at is e times the one they met at. The impulses are kept for the next step.

Each solve is Gauss-Seidel, contact after contact, each seeing the velocities the ones
before it left (``engine.dynamics.coloring`` groups them into colours, rows of one colour sharing no
body, each colour one set of array operations). With a normal n from body A to body B, the
relative normal speed vn = (v_B - v_A).n, and the mass along it m_n = 1 / (w_A + w_B) (w = 1/m,
0 for what does not move), a row's normal impulse grows by

    d = -m_n (s_m vn + bias) - s_i lam_n,        lam_n = max(lam_n + d, 0),

A taking -d n / m_A and B d n / m_B. The soft spring (Box2D's b2MakeSoft) is zeta = ``damping``
and omega = 2 pi ``contact_hertz``: with a1 = 2 zeta + h omega, a2 = h omega a1 and
a3 = 1 / (1 + a2), bias = max(s_m (omega / a1) s, -push_speed), s_m = a2 a3 (mass scale) and
s_i = a3 (impulse scale); contacts with the static world take twice the frequency (stiffer:
the floor does not give).

**Discs that turn** (``Arms``). A row's contact point is at r_A = l_A n from A's centre and at
r_B = -l_B n from B's (l: the lever arm, about the radius; 0 for what does not turn: a point, a
box in this version, a body with ``fixed_rotation``, the static world). In 2D, omega x p is
omega (i p) in complex form, so the point of A moves at v_A + omega_A l_A (i n) = v_A +
omega_A l_A t, and B's at v_B - omega_B l_B t: the tangential slip of B on A is

    vt = (v_B - v_A).t - omega_B l_B - omega_A l_A.

The normal passes through both centres (r x n = 0), so the normal rows are those of bodies that
do not turn; only friction gains lever arms. A tangential impulse lam_t t on B (and -lam_t t on
A) turns B by i_B (r_B x lam_t t) = -i_B l_B lam_t (n x t = 1) and A by i_A (l_A n x -lam_t t) =
-i_A l_A lam_t (i = 1 / I, rad/s per N m s), so it changes vt by lam_t (w_A + w_B + l_A^2 i_A +
l_B^2 i_B), and the tangent row's mass is m_t = 1 / (w_A + w_B + l_A^2 i_A + l_B^2 i_B). The
warm start gives each body's spin the same share of the stored impulses, the substeps add the
torque's alpha h to omega as the forces' a h to v, and the angle moves by omega h a substep, as
the position by v h. With every lever arm 0 the numbers are those of bodies that do not turn,
bit for bit (x - 0.0 is x, k + 0.0 is k, and a spin that is 0 stays 0).

Velocities are complex numbers here, x + iy: with the normal n, d = dv conj(n) gives the
normal speed d.real and the tangential d.imag (along t = i n); the product is written out
(``_along``, ``_across``), so both paths round alike on every machine.

**Two paths, one algorithm** (engine.kernels): ``SoftStep.run`` in numpy, a colour at a
time, and ``run_rows``, the loop kernel of the fast path, a row at a time in the same order.
They give the same numbers to the last bit on the piles of the tests and benchmarks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import kernels
from ..dynamics import coloring

__all__ = ["Arms", "Rows", "SoftStep", "SUBSTEPS", "CONTACT_HERTZ", "DAMPING"]

#: Parts a step of the pile is taken in (Box2D v3's default).
SUBSTEPS = 4
#: The soft contacts' stiffness (Hz), at most an eighth of the substep rate (Box2D v3).
CONTACT_HERTZ = 30.0
#: Their damping ratio: far over critical, so a pile's overlap is taken out without a bounce.
DAMPING = 10.0
#: The share of the load a contact carried as the step began that its spring holds rigidly
#: (relaxing only the rest): a soft contact sags under a load M g by M g / (m omega^2), a
#: pile's bottom contacts by several percent of a radius; holding it all (1) lets a pile
#: ring (the ballpit demo's 2,000 balls never sleep); four fifths left deep piles 2% of a
#: radius into each other and awake (those 2,000, a column of 50); 0.95 brings both to rest
#: within 0.5% and asleep (``python -m demos.bench limits``). A wall or floor holds all of
#: its load.
HELD = 0.95
HELD_STATIC = 1.0
#: The same for the rows between bodies with corners that turn (lever arms r x n on the
#: normal): a box's load moves between its two points as it tips, and a load held by 0.9 or
#: more of it rocks a column of ten boxes, each 2 cm aside of the one below, for good; 0.8
#: brings it to rest, asleep, within 1 s, its top 6 mm down (0.7: 3 s, 9 mm; 0.5: 3 s,
#: 15 mm). On a wall or floor a box holds all of its load (as a disc does).
HELD_CORNER = 0.8
HELD_CORNER_STATIC = 1.0
#: Gauss-Seidel sweeps of restitution where bodies with corners are among the rows: the
#: points of a face that meets a wall flat are coupled through the body's spin, and one sweep,
#: point after point, would leave a box bounced off a wall turning (its energy in the spin);
#: swept again the points part at e times the speed they met at together, as the exact
#: simultaneous impact has it (a box thrown flat at a wall comes back at -e v, not turning:
#: each sweep takes the error by the coupling's factor, 1/5 for a square box).
RESTITUTION_SWEEPS = 30
#: Gauss-Seidel sweeps of the position pass that takes out what overlap the step left.
PROJECT_SWEEPS = 2


@dataclass
class Rows:
    """The contacts of a pile, one row each, between local bodies ``a`` and ``b`` (``b`` is
    the static slot, the last, for a contact with a collider)."""

    a: np.ndarray  # (R,) body A
    b: np.ndarray  # (R,) body B
    normal: np.ndarray  # (R,) complex unit normal from A to B
    separation: np.ndarray  # (R,) gap between the surfaces at the step's start (< 0: overlap)
    friction: np.ndarray  # (R,) Coulomb's mu of the pair
    restitution: np.ndarray  # (R,) e of the pair
    lam_n: np.ndarray  # (R,) normal impulse of a part (warm start), >= 0
    lam_t: np.ndarray  # (R,) tangential impulse of a part
    static: np.ndarray  # (R,) bool: B is the static world


@dataclass
class Arms:
    """The lever arms of a pile's rows, for the bodies that turn (module text): with r_A, r_B
    a row's contact point less A's and B's centre, ``a`` = r_A.n and ``b`` = -(r_B.n) (a
    disc's: its point is at ``a`` n from A's centre and at -``b`` n from B's), and the normal
    rows' ``na`` = r_A x n, ``nb`` = r_B x n (None: 0, a disc's)."""

    a: np.ndarray  # (R,) A's lever arm (length units), 0 where A does not turn
    b: np.ndarray  # (R,) B's lever arm (length units), 0 where B does not turn
    inv_moment: np.ndarray  # (n + 1,) 1 / I (1/(kg m^2)) by body, 0: does not turn (static: 0)
    na: np.ndarray | None = None  # (R,) r_A x n (length units), 0 where A does not turn
    nb: np.ndarray | None = None  # (R,) r_B x n (length units), 0 where B does not turn


# The products with the normal, written out: numpy's complex product may fuse a multiply and
# an add (one rounding, by the machine's SIMD), so written out the numpy twin rounds as the
# loop kernel does, on every machine.
def _along(d: np.ndarray, n: np.ndarray) -> np.ndarray:
    """(d conj(n)).real: the part of d (complex) along the unit normal n."""
    return d.real * n.real + d.imag * n.imag


def _across(d: np.ndarray, n: np.ndarray) -> np.ndarray:
    """(d conj(n)).imag: the part of d along the tangent t = i n."""
    return d.imag * n.real - d.real * n.imag


def _turn(n: np.ndarray, along: np.ndarray, across: np.ndarray) -> np.ndarray:
    """n (along + i across): a vector given by its parts along n and t = i n."""
    out = np.empty(np.shape(along), dtype=complex)
    out.real = n.real * along - n.imag * across
    out.imag = n.real * across + n.imag * along
    return out


def _soft(hertz: float, zeta: float, h: float) -> tuple[float, float, float]:
    """(bias rate 1/s, mass scale, impulse scale) of a soft constraint (Box2D's b2MakeSoft)."""
    omega = 2.0 * math.pi * hertz
    a1 = 2.0 * zeta + h * omega
    a2 = h * omega * a1
    a3 = 1.0 / (1.0 + a2)
    return omega / a1, a2 * a3, a3


class SoftStep:
    """One step of the bodies of a pile (module text): ``run`` them, then read the rows'
    impulses (``rows.lam_n``, ``rows.lam_t``, per part) and how hard each pressed
    (``total``)."""

    def __init__(
        self,
        rows: Rows,
        w: np.ndarray,
        moves: np.ndarray,
        dt: float,
        substeps: int = SUBSTEPS,
        push_speed: float | np.ndarray = math.inf,
        threshold: float = 0.0,
        slop: np.ndarray | None = None,
        prior: np.ndarray | None = None,
        fast: bool = False,
        arms: Arms | None = None,
        slip: np.ndarray | None = None,
    ) -> None:
        self.rows = rows
        self.fast = fast  # run the loop kernel (``run_rows``, compiled), not the numpy twin
        self.w = w  # (n + 1,) inverse masses, the static slot's 0
        self.dt, self.substeps = dt, substeps
        self.h = h = dt / substeps
        self.threshold = threshold
        # The solving order: batches of rows that share no moving body. Every per-row array
        # below is held in that order, so that a batch is a slice (a view, no copy).
        self.color = color = coloring.colors(rows.a, rows.b, moves, prior=prior, fast=fast)
        batches = coloring.batches(color, rows.a, rows.b, moves, fast=fast)
        order = np.concatenate(batches) if batches else np.zeros(0, dtype=np.intp)
        ends = np.cumsum([len(k) for k in batches]).tolist()
        self.slices = [slice(e - len(k), e) for k, e in zip(batches, ends, strict=True)]
        self.order = order
        self.a, self.b = rows.a[order], rows.b[order]
        self.n = rows.normal[order]
        self.sep = rows.separation[order]
        # The push out of an overlap is capped per row (length units/s).
        self.push = -np.broadcast_to(np.asarray(push_speed, dtype=float), rows.a.shape)[order]
        self.mu = rows.friction[order]
        # (R,) the surfaces' own motion (u_A - u_B).t (length units/s): a conveyor's surface
        # velocity u (pymunk's ``surface_velocity``) moves its side of the contact, so the
        # slip at the contact is vt - su, which friction drives to 0 (``slip`` None: 0).
        self.su = np.zeros(len(order)) if slip is None else slip[order]
        self.e = rows.restitution[order]
        self.wa, self.wb = w[self.a], w[self.b]
        k = self.wa + self.wb
        self.m = np.where(k > 0.0, 1.0 / np.where(k > 0.0, k, 1.0), 0.0)
        #: The mass the position projection moves the rows with: the bodies' alone.
        self.mp = self.m
        # Discs that turn (``arms``, module text): each row's lever arms l, the spin a unit
        # tangential impulse takes from A and B (l i, rad/s per N s), and the tangent row's
        # mass 1 / (w_A + w_B + l_A^2 i_A + l_B^2 i_B) (without lever arms: m, the same bits).
        self.turning = arms is not None
        if arms is not None:
            self.la, self.lb = arms.a[order], arms.b[order]
            self.ka = self.la * arms.inv_moment[self.a]
            self.kb = self.lb * arms.inv_moment[self.b]
            kt = k + self.la * self.ka + self.lb * self.kb
            self.mt = np.where(kt > 0.0, 1.0 / np.where(kt > 0.0, kt, 1.0), 0.0)
            # Bodies with corners: the normal rows' lever arms r x n, the spin a unit normal
            # impulse gives A (-kna) and B (+knb), and the normal row's mass
            # 1 / (w_A + w_B + na^2 i_A + nb^2 i_B) (with na = nb = 0: m, the same bits).
            zero = np.zeros(len(order))
            self.na = zero if arms.na is None else arms.na[order]
            self.nb = zero if arms.nb is None else arms.nb[order]
            self.kna = self.na * arms.inv_moment[self.a]
            self.knb = self.nb * arms.inv_moment[self.b]
            kn = k + self.na * self.kna + self.nb * self.knb
            self.m = np.where(kn > 0.0, 1.0 / np.where(kn > 0.0, kn, 1.0), 0.0)
        else:
            self.la = self.lb = self.ka = self.kb = np.zeros(len(order))
            self.na = self.nb = self.kna = self.knb = self.la
            self.mt = self.m
        #: After ``run``: each body's angular velocity (rad/s) and the angle it turned (rad),
        #: (n + 1,), the static slot last (zeros without ``arms``).
        self.omega = self.turned = np.zeros(0)
        # Soft contacts (Box2D's b2MakeSoft), stiffer with the static world: per row, the
        # bias rate times the mass scale, the mass scale, the impulse scale.
        hertz = min(CONTACT_HERTZ, 0.125 / h)
        ds, ss = _soft(hertz, DAMPING, h), _soft(2.0 * hertz, DAMPING, h)
        st = rows.static[order]
        self.soft = np.where(st, ss[0] * ss[1], ds[0] * ds[1])
        self.ms = np.where(st, ss[1], ds[1])
        self.isc = np.where(st, ss[2], ds[2])
        self.lam = rows.lam_n[order].copy()
        self.lam_t = rows.lam_t[order].copy()
        # The load each row carried as the step began (warm start), which its spring holds.
        share = np.where(st, HELD_STATIC, HELD)
        corner = (self.na != 0.0) | (self.nb != 0.0)
        #: Restitution's sweeps: one, or ``RESTITUTION_SWEEPS`` with bodies with corners.
        self.rest_sweeps = RESTITUTION_SWEEPS if corner.any() else 1
        if corner.any():
            # A row of a body with corners that turns: its load shifts between the points of
            # its pair as the body tips, which a load held rigidly would fight (a stack
            # would rock); it holds less of it.
            share = np.where(corner, np.where(st, HELD_CORNER_STATIC, HELD_CORNER), share)
        self.held = share * self.lam
        self.total = np.zeros(len(order))  # the normal impulse each row gave in the step
        self.slop = None if slop is None else slop[order]

    def run(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        acc: np.ndarray,
        omega0: np.ndarray | None = None,
        alpha: np.ndarray | None = None,
    ) -> tuple[np.ndarray, ...]:
        """Step the bodies from (x0, v0) (complex, (n + 1,), the static slot last) under the
        accelerations ``acc``: their (x, v) at the end, complex. The rows' impulses are
        written back to ``rows`` (per part) and ``total`` (over the step), in rows' order.
        With ``arms``: the bodies turn from ``omega0`` (rad/s, (n + 1,), 0 for what does not
        turn; None: all 0) under their own ``alpha`` (rad/s^2, None: 0), and end at
        ``self.omega``, having turned by ``self.turned`` (rad)."""
        h = self.h
        v = v0.copy()
        dp = np.zeros_like(v0)
        nb = len(v0)
        om = np.zeros(nb) if omega0 is None else np.array(omega0, dtype=float)
        th = np.zeros(nb)
        self.omega, self.turned = om, th
        if self.fast:
            slop = self.slop
            spin_step = np.zeros(nb) if alpha is None else alpha * h
            run_rows(
                v, dp, acc * h, self.a, self.b, self.n, self.sep, self.push, self.mu,
                self.e, self.wa, self.wb, self.m, self.soft, self.ms, self.isc, self.held,
                self.lam, self.lam_t, self.total, h, self.substeps, self.threshold,
                self.sep if slop is None else slop, 0 if slop is None else PROJECT_SWEEPS,
                om, th, spin_step, self.la, self.lb, self.ka, self.kb, self.mt,
                self.na, self.nb, self.kna, self.knb, self.mp, self.rest_sweeps, self.su,
            )  # fmt: skip
            return self._finish(x0, dp, v)
        # Each contact's relative normal speed as the step began, for restitution.
        rel = _along(v0[self.b] - v0[self.a], self.n)
        step = acc * h
        spin = om if self.turning else None
        if spin is not None:
            rel = self._spun(rel, spin)
        turn_step = None if alpha is None or spin is None else alpha * h
        idx = np.concatenate([self.a, self.b])
        for _ in range(self.substeps):
            v += step
            if turn_step is not None:
                om += turn_step
            self._warm_start(v, idx, spin)
            self._solve(v, dp, spin, th)
            dp += v * h
            if spin is not None:
                th += om * h
            self._relax(v, dp, spin, th)
        self._restitution(v, rel, spin)
        if self.slop is not None:
            self._project(dp, spin, th)
        return self._finish(x0, dp, v)

    def _spun(
        self, x: np.ndarray, om: np.ndarray, k: slice | np.ndarray = slice(None)
    ) -> np.ndarray:
        """x (a normal speed or gap along each row ``k``) plus the spins' (or angles') part,
        om_B nb - om_A na (written out as the loop kernel has it)."""
        return x + om[self.b[k]] * self.nb[k] - om[self.a[k]] * self.na[k]

    def _finish(self, x0: np.ndarray, dp: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, ...]:
        """Write the impulses back in rows' order; the end state (x0 + dp, v)."""
        rows, order = self.rows, self.order
        rows.lam_n[order], rows.lam_t[order] = self.lam, self.lam_t
        total = np.empty_like(self.total)
        total[order] = self.total
        self.total = total
        return x0 + dp, v

    def _warm_start(self, v: np.ndarray, idx: np.ndarray, om: np.ndarray | None) -> None:
        """Every row's impulse of the part before, again, at once (to the spins ``om`` of
        the bodies that turn too: -l i lam_t each)."""
        if not self.lam.any() and not self.lam_t.any():
            return
        p = _turn(self.n, self.lam, self.lam_t)
        self.total += self.lam
        dv = np.concatenate([-p * self.wa, p * self.wb])
        n = len(v)
        v += np.bincount(idx, dv.real, minlength=n) + 1j * np.bincount(idx, dv.imag, minlength=n)
        v[-1] = 0.0
        if om is not None:
            dw = np.concatenate(
                [
                    -self.ka * self.lam_t - self.kna * self.lam,
                    -self.kb * self.lam_t + self.knb * self.lam,
                ]
            )
            om += np.bincount(idx, dw, minlength=n)
            om[-1] = 0.0

    def _solve(self, v: np.ndarray, dp: np.ndarray, om: np.ndarray | None, th: np.ndarray) -> None:
        """The normal impulses, with the soft push out of overlap (Box2D's useBias); the
        spins ``om`` and the angles turned ``th`` of the bodies that turn count at the
        contact point."""
        inv_h, push_all = 1.0 / self.h, self.push
        lam_all, total = self.lam, self.total
        for k in self.slices:
            a, b, n, m = self.a[k], self.b[k], self.n[k], self.m[k]
            lam = lam_all[k]
            vn = _along(v[b] - v[a], n)
            s = self.sep[k] + _along(dp[b] - dp[a], n)
            if om is not None:
                vn = self._spun(vn, om, k)
                s = self._spun(s, th, k)
            # Open: the gap may close in this part, no more (speculative); closed: the
            # spring's push, and its relaxation of what the impulse grew past the load it
            # carried as the step began (a stack's weight is carried as by a rigid contact;
            # only its error is soft: little sag under load).
            bias = np.maximum(self.soft[k] * s, push_all[k])
            closed = -m * (self.ms[k] * vn + bias) - self.isc[k] * (lam - self.held[k])
            d = np.where(s > 0.0, -m * (vn + s * inv_h), closed)
            new = np.maximum(lam + d, 0.0)
            d = new - lam
            lam_all[k] = new
            total[k] += d
            p = self.n[k] * d
            v[a] -= p * self.wa[k]
            v[b] += p * self.wb[k]
            if om is not None:
                om[a] -= self.kna[k] * d
                om[b] += self.knb[k] * d
        v[-1] = 0.0
        if om is not None:
            om[-1] = 0.0

    def _relax(self, v: np.ndarray, dp: np.ndarray, om: np.ndarray | None, th: np.ndarray) -> None:
        """The normal impulses without the push (it moved positions, and leaves no speed),
        then friction, against the tangential slip at the contact point (the spins ``om``
        of the bodies that turn in it): |lam_t| <= mu lam_n."""
        inv_h = 1.0 / self.h
        lam_all, lam_t_all, total = self.lam, self.lam_t, self.total
        for k in self.slices:
            a, b, n, m = self.a[k], self.b[k], self.n[k], self.m[k]
            lam = lam_all[k]
            dv = v[b] - v[a]
            s = self.sep[k] + _along(dp[b] - dp[a], n)
            vn = _along(dv, n)
            if om is not None:
                vn = self._spun(vn, om, k)
                s = self._spun(s, th, k)
            new = np.maximum(lam - m * (vn + np.maximum(s, 0.0) * inv_h), 0.0)
            d = new - lam
            lam_all[k] = new
            total[k] += d
            # The tangential slip: a push along n changes no v.t, only the spins of bodies
            # with corners (r x n), which are taken into the slip first.
            if om is not None:
                om[a] -= self.kna[k] * d
                om[b] += self.knb[k] * d
            lt = lam_t_all[k]
            cap = self.mu[k] * new
            if om is None:
                newt = np.minimum(np.maximum(lt - m * (_across(dv, n) - self.su[k]), -cap), cap)
            else:
                # vt = (v_B - v_A).t - omega_B l_B - omega_A l_A (module text).
                vt = _across(dv, n) - om[b] * self.lb[k] - om[a] * self.la[k] - self.su[k]
                newt = np.minimum(np.maximum(lt - self.mt[k] * vt, -cap), cap)
                dlt = newt - lt
                om[a] -= self.ka[k] * dlt
                om[b] -= self.kb[k] * dlt
            p = _turn(n, d, newt - lt)
            lam_t_all[k] = newt
            v[a] -= p * self.wa[k]
            v[b] += p * self.wb[k]
        v[-1] = 0.0
        if om is not None:
            om[-1] = 0.0

    def _restitution(self, v: np.ndarray, rel: np.ndarray, om: np.ndarray | None) -> None:
        """Contacts that met faster than ``threshold`` and pressed part at e times that."""
        hit_all = (rel < -self.threshold) & (self.total > 0.0) & (self.e > 0.0)
        if not hit_all.any():
            return
        for k in [k for _ in range(self.rest_sweeps) for k in self.slices]:
            hit = np.flatnonzero(hit_all[k]) + k.start
            if not len(hit):
                continue
            a, b = self.a[hit], self.b[hit]
            vn = _along(v[b] - v[a], self.n[hit])
            if om is not None:
                vn = self._spun(vn, om, hit)
            lam = self.lam[hit]
            new = np.maximum(lam - self.m[hit] * (vn + self.e[hit] * rel[hit]), 0.0)
            d = new - lam
            self.lam[hit] = new
            self.total[hit] += d
            p = self.n[hit] * d
            v[a] -= p * self.wa[hit]
            v[b] += p * self.wb[hit]
            if om is not None:
                om[a] -= self.kna[hit] * d
                om[b] += self.knb[hit] * d
        v[-1] = 0.0
        if om is not None:
            om[-1] = 0.0

    def _project(self, dp: np.ndarray, om: np.ndarray | None, th: np.ndarray) -> None:
        """Take out what overlap is left past ``slop`` (per row) by moving positions only,
        Gauss-Seidel over the colours: the soft contacts still give a little under load, and
        a pile must not sink into itself step by step. Moving positions, not speeds, adds
        no kinetic energy."""
        assert self.slop is not None
        for _ in range(PROJECT_SWEEPS):
            for k in self.slices:
                a, b = self.a[k], self.b[k]
                s = self.sep[k] + _along(dp[b] - dp[a], self.n[k])
                if om is not None:
                    s = self._spun(s, th, k)  # the angles turned move the points
                deep = np.maximum(-s - self.slop[k], 0.0)
                push = self.n[k] * (deep * self.mp[k])
                dp[a] -= push * self.wa[k]
                dp[b] += push * self.wb[k]
            dp[-1] = 0.0


# -- the loop kernel (engine.kernels: the fast path) ------------------------------------------
# The same step as SoftStep.run, row after row in the solving order. Rows of one colour share
# no moving body, so taking them one at a time gives what the numpy twin's one array call a
# colour gives; the warm start sums each body's impulses in bincount's order (the a's, then
# the b's), so the two paths agree to rounding (tests/test_kernels.py).


def _sample_rows() -> tuple[object, ...]:
    """The smallest call of ``run_rows``: two bodies on the floor, one row each."""
    c, f, i = np.zeros(3, dtype=complex), np.zeros(2), np.array([2, 2])
    one, w = np.ones(2), np.zeros(3)
    return (c, c.copy(), c.copy(), i, np.array([0, 1]), one + 0j, f, f, f, f, f, one, one,
            f, f, f, f, f, f, f, 0.01, 1, 0.0, f, 1, w, w.copy(), w.copy(), f, f, f, f,
            one, f, f, f, f, one, 1, f)  # fmt: skip


@kernels.loop(sample=_sample_rows)
def run_rows(
    v: np.ndarray,
    dp: np.ndarray,
    step: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    n: np.ndarray,
    sep: np.ndarray,
    push: np.ndarray,
    mu: np.ndarray,
    e: np.ndarray,
    wa: np.ndarray,
    wb: np.ndarray,
    m: np.ndarray,
    soft: np.ndarray,
    ms: np.ndarray,
    isc: np.ndarray,
    held: np.ndarray,
    lam: np.ndarray,
    lam_t: np.ndarray,
    total: np.ndarray,
    h: float,
    substeps: int,
    threshold: float,
    slop: np.ndarray,
    sweeps: int,
    om: np.ndarray,
    th: np.ndarray,
    spin_step: np.ndarray,
    la: np.ndarray,
    lb: np.ndarray,
    ka: np.ndarray,
    kb: np.ndarray,
    mt: np.ndarray,
    na: np.ndarray,
    nb: np.ndarray,
    kna: np.ndarray,
    knb: np.ndarray,
    mp: np.ndarray,
    rest_sweeps: int,
    su: np.ndarray,
) -> None:
    """SoftStep.run's parts, restitution and projection, in place on v, dp (complex, the
    static slot last), lam, lam_t and total, over rows in the solving order; and on the
    spins om and angles turned th (rad/s, rad; all 0 for bodies that do not turn: their
    lever arms la, lb, na, nb and ka = la i_A, kb = lb i_B, kna = na i_A, knb = nb i_B are
    0, and mt is then m). m is the normal rows' mass (with na, nb), mp the bodies' alone
    (the projection's); su the surfaces' own slip (0 at rest)."""
    rows, bodies = len(a), len(v)
    last = bodies - 1
    inv_h = 1.0 / h
    rel = np.empty(rows)
    for k in range(rows):
        d = v[b[k]] - v[a[k]]
        rel[k] = d.real * n[k].real + d.imag * n[k].imag + om[b[k]] * nb[k] - om[a[k]] * na[k]
    acc_re, acc_im, acc_w = np.zeros(bodies), np.zeros(bodies), np.zeros(bodies)
    for _ in range(substeps):
        for j in range(bodies):
            v[j] += step[j]
            om[j] += spin_step[j]
        # Warm start: every row's impulse of the part before, summed by body as bincount does.
        warm = False
        for k in range(rows):
            if lam[k] != 0.0 or lam_t[k] != 0.0:
                warm = True
                break
        if warm:
            acc_re[:] = 0.0
            acc_im[:] = 0.0
            acc_w[:] = 0.0
            for k in range(rows):
                total[k] += lam[k]
                nr, ni = n[k].real, n[k].imag
                p = complex(nr * lam[k] - ni * lam_t[k], nr * lam_t[k] + ni * lam[k])
                q = -p * wa[k]
                acc_re[a[k]] += q.real
                acc_im[a[k]] += q.imag
                acc_w[a[k]] += -ka[k] * lam_t[k] - kna[k] * lam[k]
            for k in range(rows):
                nr, ni = n[k].real, n[k].imag
                p = complex(nr * lam[k] - ni * lam_t[k], nr * lam_t[k] + ni * lam[k])
                q = p * wb[k]
                acc_re[b[k]] += q.real
                acc_im[b[k]] += q.imag
                acc_w[b[k]] += -kb[k] * lam_t[k] + knb[k] * lam[k]
            for j in range(bodies):
                v[j] += complex(acc_re[j], acc_im[j])
                om[j] += acc_w[j]
            v[last] = 0.0
            om[last] = 0.0
        # Solve, with the soft push out of overlap.
        for k in range(rows):
            nr, ni = n[k].real, n[k].imag
            dv, dx = v[b[k]] - v[a[k]], dp[b[k]] - dp[a[k]]
            vn = dv.real * nr + dv.imag * ni + om[b[k]] * nb[k] - om[a[k]] * na[k]
            s = sep[k] + (dx.real * nr + dx.imag * ni) + th[b[k]] * nb[k] - th[a[k]] * na[k]
            if s > 0.0:
                d = -m[k] * (vn + s * inv_h)
            else:
                bias = max(soft[k] * s, push[k])
                d = -m[k] * (ms[k] * vn + bias) - isc[k] * (lam[k] - held[k])
            new = max(lam[k] + d, 0.0)
            d = new - lam[k]
            lam[k] = new
            total[k] += d
            p = n[k] * d
            v[a[k]] -= p * wa[k]
            v[b[k]] += p * wb[k]
            om[a[k]] -= kna[k] * d
            om[b[k]] += knb[k] * d
        v[last] = 0.0
        om[last] = 0.0
        for j in range(bodies):
            dp[j] += v[j] * h
            th[j] += om[j] * h
        # Relax: the normal impulses without the push, then friction.
        for k in range(rows):
            nr, ni = n[k].real, n[k].imag
            dv, dx = v[b[k]] - v[a[k]], dp[b[k]] - dp[a[k]]
            s = sep[k] + (dx.real * nr + dx.imag * ni) + th[b[k]] * nb[k] - th[a[k]] * na[k]
            vn = dv.real * nr + dv.imag * ni + om[b[k]] * nb[k] - om[a[k]] * na[k]
            new = max(lam[k] - m[k] * (vn + max(s, 0.0) * inv_h), 0.0)
            d = new - lam[k]
            lam[k] = new
            total[k] += d
            om[a[k]] -= kna[k] * d
            om[b[k]] += knb[k] * d
            lt = lam_t[k]
            cap = mu[k] * new
            # The slip at the contact point: vt = (v_B - v_A).t - omega_B l_B - omega_A l_A,
            # less the surfaces' own (a conveyor's).
            vt = (dv.imag * nr - dv.real * ni) - om[b[k]] * lb[k] - om[a[k]] * la[k] - su[k]
            newt = min(max(lt - mt[k] * vt, -cap), cap)
            dt_ = newt - lt
            om[a[k]] -= ka[k] * dt_
            om[b[k]] -= kb[k] * dt_
            p = complex(nr * d - ni * dt_, nr * dt_ + ni * d)
            lam_t[k] = newt
            v[a[k]] -= p * wa[k]
            v[b[k]] += p * wb[k]
        v[last] = 0.0
        om[last] = 0.0
    # Restitution for rows that met faster than threshold and pressed (``rest_sweeps`` times).
    hit = False
    hits = np.empty(rows, dtype=np.bool_)
    for k in range(rows):
        hits[k] = rel[k] < -threshold and total[k] > 0.0 and e[k] > 0.0
    for _ in range(rest_sweeps):
        for k in range(rows):
            if hits[k]:
                hit = True
                dv = v[b[k]] - v[a[k]]
                vn = dv.real * n[k].real + dv.imag * n[k].imag + om[b[k]] * nb[k] - om[a[k]] * na[k]
                new = max(lam[k] - m[k] * (vn + e[k] * rel[k]), 0.0)
                d = new - lam[k]
                lam[k] = new
                total[k] += d
                p = n[k] * d
                v[a[k]] -= p * wa[k]
                v[b[k]] += p * wb[k]
                om[a[k]] -= kna[k] * d
                om[b[k]] += knb[k] * d
    if hit:
        v[last] = 0.0
        om[last] = 0.0
    # Projection: what overlap is left past slop, out by positions only.
    for _ in range(sweeps):
        for k in range(rows):
            dx = dp[b[k]] - dp[a[k]]
            s = sep[k] + (dx.real * n[k].real + dx.imag * n[k].imag)
            s = s + th[b[k]] * nb[k] - th[a[k]] * na[k]
            deep = max(-s - slop[k], 0.0)
            p = n[k] * (deep * mp[k])
            dp[a[k]] -= p * wa[k]
            dp[b[k]] += p * wb[k]
        dp[last] = 0.0
