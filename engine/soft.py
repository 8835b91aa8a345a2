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
   leaves no speed behind (it adds no energy), and friction (Coulomb: |lam_t| <= mu lam_n);

then, once, restitution for contacts that closed faster than ``threshold``: the normal speed
they part at is e times the one they met at. The impulses are kept for the next step.

Each solve is Gauss-Seidel, contact after contact, each seeing the velocities the ones
before it left (``engine.coloring`` groups them into colours, rows of one colour sharing no
body, each colour one set of array operations). With a normal n from body A to body B, the
relative normal speed vn = (v_B - v_A).n, and the mass along it m_n = 1 / (w_A + w_B) (w = 1/m,
0 for what does not move), a row's normal impulse grows by

    d = -m_n (s_m vn + bias) - s_i lam_n,        lam_n = max(lam_n + d, 0),

A taking -d n / m_A and B d n / m_B. The soft spring (Box2D's b2MakeSoft) is zeta = ``damping``
and omega = 2 pi ``contact_hertz``: with a1 = 2 zeta + h omega, a2 = h omega a1 and
a3 = 1 / (1 + a2), bias = max(s_m (omega / a1) s, -push_speed), s_m = a2 a3 (mass scale) and
s_i = a3 (impulse scale); contacts with the static world take twice the frequency (stiffer:
the floor does not give).

Velocities are complex numbers here, x + iy: with the normal n, d = dv conj(n) gives the
normal speed d.real and the tangential d.imag (along t = i n) in one product.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import coloring

__all__ = ["Rows", "SoftStep", "SUBSTEPS", "CONTACT_HERTZ", "DAMPING"]

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
    ) -> None:
        self.rows = rows
        self.w = w  # (n + 1,) inverse masses, the static slot's 0
        self.dt, self.substeps = dt, substeps
        self.h = h = dt / substeps
        self.threshold = threshold
        # The solving order: batches of rows that share no moving body. Every per-row array
        # below is held in that order, so that a batch is a slice (a view, no copy).
        self.color = color = coloring.colors(rows.a, rows.b, moves, prior=prior)
        batches = coloring.batches(color, rows.a, rows.b, moves)
        order = np.concatenate(batches) if batches else np.zeros(0, dtype=np.intp)
        ends = np.cumsum([len(k) for k in batches]).tolist()
        self.slices = [slice(e - len(k), e) for k, e in zip(batches, ends, strict=True)]
        self.order = order
        self.a, self.b = rows.a[order], rows.b[order]
        self.n = rows.normal[order]
        self.nc = np.conj(self.n)
        self.sep = rows.separation[order]
        # The push out of an overlap is capped per row (length units/s).
        self.push = -np.broadcast_to(np.asarray(push_speed, dtype=float), rows.a.shape)[order]
        self.mu = rows.friction[order]
        self.e = rows.restitution[order]
        self.wa, self.wb = w[self.a], w[self.b]
        k = self.wa + self.wb
        self.m = np.where(k > 0.0, 1.0 / np.where(k > 0.0, k, 1.0), 0.0)
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
        self.held = np.where(st, HELD_STATIC, HELD) * self.lam
        self.total = np.zeros(len(order))  # the normal impulse each row gave in the step
        self.slop = None if slop is None else slop[order]

    def run(self, x0: np.ndarray, v0: np.ndarray, acc: np.ndarray) -> tuple[np.ndarray, ...]:
        """Step the bodies from (x0, v0) (complex, (n + 1,), the static slot last) under the
        accelerations ``acc``: their (x, v) at the end, complex. The rows' impulses are
        written back to ``rows`` (per part) and ``total`` (over the step), in rows' order."""
        h = self.h
        v = v0.copy()
        dp = np.zeros_like(v0)
        # Each contact's relative normal speed as the step began, for restitution.
        rel = ((v0[self.b] - v0[self.a]) * self.nc).real
        step = acc * h
        idx = np.concatenate([self.a, self.b])
        for _ in range(self.substeps):
            v += step
            self._warm_start(v, idx)
            self._solve(v, dp)
            dp += v * h
            self._relax(v, dp)
        self._restitution(v, rel)
        if self.slop is not None:
            self._project(dp)
        rows, order = self.rows, self.order
        rows.lam_n[order], rows.lam_t[order] = self.lam, self.lam_t
        total = np.empty_like(self.total)
        total[order] = self.total
        self.total = total
        return x0 + dp, v

    def _warm_start(self, v: np.ndarray, idx: np.ndarray) -> None:
        """Every row's impulse of the part before, again, at once."""
        if not self.lam.any() and not self.lam_t.any():
            return
        p = self.n * (self.lam + 1j * self.lam_t)
        self.total += self.lam
        dv = np.concatenate([-p * self.wa, p * self.wb])
        n = len(v)
        v += np.bincount(idx, dv.real, minlength=n) + 1j * np.bincount(idx, dv.imag, minlength=n)
        v[-1] = 0.0

    def _solve(self, v: np.ndarray, dp: np.ndarray) -> None:
        """The normal impulses, with the soft push out of overlap (Box2D's useBias)."""
        inv_h, push_all = 1.0 / self.h, self.push
        lam_all, total = self.lam, self.total
        for k in self.slices:
            a, b, nc, m = self.a[k], self.b[k], self.nc[k], self.m[k]
            lam = lam_all[k]
            vn = ((v[b] - v[a]) * nc).real
            s = self.sep[k] + ((dp[b] - dp[a]) * nc).real
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
        v[-1] = 0.0

    def _relax(self, v: np.ndarray, dp: np.ndarray) -> None:
        """The normal impulses without the push (it moved positions, and leaves no speed),
        then friction, against the tangential speed: |lam_t| <= mu lam_n."""
        inv_h = 1.0 / self.h
        lam_all, lam_t_all, total = self.lam, self.lam_t, self.total
        for k in self.slices:
            a, b, nc, m = self.a[k], self.b[k], self.nc[k], self.m[k]
            lam = lam_all[k]
            z = (v[b] - v[a]) * nc
            s = self.sep[k] + ((dp[b] - dp[a]) * nc).real
            new = np.maximum(lam - m * (z.real + np.maximum(s, 0.0) * inv_h), 0.0)
            d = new - lam
            lam_all[k] = new
            total[k] += d
            # The tangential speed is the one before the normal impulse: the bodies do not
            # turn, so a push along n leaves it.
            lt = lam_t_all[k]
            cap = self.mu[k] * new
            newt = np.minimum(np.maximum(lt - m * z.imag, -cap), cap)
            p = self.n[k] * (d + 1j * (newt - lt))
            lam_t_all[k] = newt
            v[a] -= p * self.wa[k]
            v[b] += p * self.wb[k]
        v[-1] = 0.0

    def _restitution(self, v: np.ndarray, rel: np.ndarray) -> None:
        """Contacts that met faster than ``threshold`` and pressed part at e times that."""
        hit_all = (rel < -self.threshold) & (self.total > 0.0) & (self.e > 0.0)
        if not hit_all.any():
            return
        for k in self.slices:
            hit = np.flatnonzero(hit_all[k]) + k.start
            if not len(hit):
                continue
            a, b = self.a[hit], self.b[hit]
            vn = ((v[b] - v[a]) * self.nc[hit]).real
            lam = self.lam[hit]
            new = np.maximum(lam - self.m[hit] * (vn + self.e[hit] * rel[hit]), 0.0)
            d = new - lam
            self.lam[hit] = new
            self.total[hit] += d
            p = self.n[hit] * d
            v[a] -= p * self.wa[hit]
            v[b] += p * self.wb[hit]
        v[-1] = 0.0

    def _project(self, dp: np.ndarray) -> None:
        """Take out what overlap is left past ``slop`` (per row) by moving positions only,
        Gauss-Seidel over the colours: the soft contacts still give a little under load, and
        a pile must not sink into itself step by step. Moving positions, not speeds, adds
        no kinetic energy."""
        assert self.slop is not None
        for _ in range(PROJECT_SWEEPS):
            for k in self.slices:
                a, b = self.a[k], self.b[k]
                s = self.sep[k] + ((dp[b] - dp[a]) * self.nc[k]).real
                deep = np.maximum(-s - self.slop[k], 0.0)
                push = self.n[k] * (deep * self.m[k])
                dp[a] -= push * self.wa[k]
                dp[b] += push * self.wb[k]
            dp[-1] = 0.0
