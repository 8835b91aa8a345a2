"""Contacts with static colliders: impacts solved at their exact moment, rest, and sliding.

The World hands this module each step's start state (x0, v0) and the state its method reached
(x1, v1) after dt. Between them a body's centre follows a known path:

    x(t) = x0 + v0 t + B t^2 / 2,    v(t) = v0 + W t,    0 <= t <= dt,

with B = W = the constant acceleration under the closed form ("exact"), which is exact; for an
integrator, W = (v1 - v0) / dt is the step's mean acceleration and B = 2 (x1 - x0 - v0 dt) / dt^2
makes the path end where the method ended (the step's own update is what is swept: explicit
Euler's straight line, velocity Verlet's parabola, semi-implicit Euler's x0 + v1 t in
its mean). A body that meets nothing on that path keeps (x1, v1) bit for bit.

Where the path first touches a collider (``engine.impact`` solves for the time), the body is
moved there and bounces: with the unit normal n, the normal velocity v_n becomes -e v_n and
Coulomb friction takes up to mu (1 + e) |v_n| off the tangential velocity (never reversing
it), e and mu being the products of the body's and the collider's materials. It then goes on
along the same kind of path for the rest of the step, meeting whatever comes next, in time
order, up to ``MAX_IMPACTS`` impacts; past that it is placed on the surface and the count is
kept in ``capped``.

Rest: a rebound too slow to fly for one step (normal speed below |a_n| dt / 2, where a_n is
the acceleration pressing the body onto the surface) ends in rest: the body's centre is put at
exactly its radius from the surface, the surface takes the pressing part of its acceleration,
and it slides along the surface under the tangential part, slowed by friction mu |a_n| until
it stops, at the exact moment the closed form gives, and stays stopped while the tangential
pull is at most mu |a_n| (Coulomb: static on a slope of tan(theta) <= mu). It lifts off when
pulled away from the surface, when its velocity is set to leave it, or when it goes over a
round edge faster than the edge can turn it (v^2 / rho > |a_n|).

A sensor does not push: the contacts report when a body begins and ends overlapping it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from .colliders import Collider
from .impact import TOUCH, disc_hits, line_hits
from .vector import Vector

__all__ = ["Contacts", "ContactEvent", "MAX_IMPACTS", "signed_distance"]

#: Impacts one body may meet in one step before it is placed on the surface (``capped``).
MAX_IMPACTS = 32

#: Events kept per step (the counts are exact; the lists stop growing past this).
MAX_EVENTS = 4096


class ContactEvent(NamedTuple):
    """A contact that began or ended: which body and collider, where, and how hard.

    ``point`` is on the collider's surface, ``normal`` the unit normal there toward the
    body, ``impulse`` (N s, a Vector) the change of the body's momentum, ``time`` (s) the
    World time of the contact within the step.
    """

    body: Any
    collider: Collider
    point: Vector
    normal: Vector
    impulse: Vector
    time: float


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def signed_distance(collider: Collider, X: np.ndarray) -> np.ndarray:
    """Signed distance (length units) from each row of X (N, 2) to the collider's surface.

    Positive in free space (inside a Box, outside everything else).
    """
    from .colliders import Box, Circle, Plane, Segment

    if isinstance(collider, Plane):
        return (X[:, 0] - collider.point.x) * collider.normal.x + (
            X[:, 1] - collider.point.y
        ) * collider.normal.y
    if isinstance(collider, Circle):
        return np.hypot(X[:, 0] - collider.center.x, X[:, 1] - collider.center.y) - collider.radius
    if isinstance(collider, Segment):
        a, b = collider.a, collider.b
        dx, dy = b.x - a.x, b.y - a.y
        u = ((X[:, 0] - a.x) * dx + (X[:, 1] - a.y) * dy) / (dx * dx + dy * dy)
        u = np.clip(u, 0.0, 1.0)
        return np.hypot(X[:, 0] - a.x - u * dx, X[:, 1] - a.y - u * dy) - collider.radius
    if isinstance(collider, Box):
        (x0, y0), (x1, y1) = collider.lower_left, collider.upper_right
        return np.minimum(
            np.minimum(X[:, 0] - x0, x1 - X[:, 0]), np.minimum(X[:, 1] - y0, y1 - X[:, 1])
        )
    raise TypeError(f"unknown collider {collider!r}")


@dataclass
class _Faces:
    """The solid colliders' faces as arrays: flat ones first, then round ones."""

    p: np.ndarray  # (L, 2) a point on each flat face's line
    n: np.ndarray  # (L, 2) its unit normal
    rho: np.ndarray  # (L,) offset of the face from the line
    two: np.ndarray  # (L,) bool: met from either side
    lo: np.ndarray  # (L,) extent along the tangent
    hi: np.ndarray
    c: np.ndarray  # (D, 2) round faces' centres
    r: np.ndarray  # (D,) their radii
    owner: np.ndarray  # (L + D,) index of the collider each face belongs to
    e: np.ndarray  # (L + D,) the owner's restitution
    mu: np.ndarray  # (L + D,) the owner's friction
    infinite: np.ndarray  # (L,) bool: a line with no end (a Plane or a Box wall)
    bound: float  # every finite face lies within this of the origin... see _Faces.reach


def _compile(colliders: list[Collider], indices: list[int]) -> _Faces:
    lines: list[Any] = []
    discs: list[Any] = []
    lown: list[int] = []
    down: list[int] = []
    for k in indices:
        c = colliders[k]
        for line in c.lines():
            lines.append(line)
            lown.append(k)
        for disc in c.discs():
            discs.append(disc)
            down.append(k)
    L = len(lines)
    p = np.array([ln[0] for ln in lines], float).reshape(L, 2)
    n = np.array([ln[1] for ln in lines], float).reshape(L, 2)
    rho = np.array([ln[2] for ln in lines], float)
    two = np.array([ln[3] for ln in lines], bool)
    lo = np.array([ln[4] for ln in lines], float)
    hi = np.array([ln[5] for ln in lines], float)
    c = np.array([d[0] for d in discs], float).reshape(len(discs), 2)
    r = np.array([d[1] for d in discs], float)
    owner = np.array(lown + down, dtype=np.intp)
    e = np.array([colliders[k].restitution for k in owner], float)
    mu = np.array([colliders[k].friction for k in owner], float)
    infinite = np.isinf(lo) & np.isinf(hi)
    return _Faces(p, n, rho, two, lo, hi, c, r, owner, e, mu, infinite, 0.0)


class Contacts:
    """The World's static colliders and the contact state of its bodies (resting or free)."""

    def __init__(self) -> None:
        self.colliders: list[Collider] = []
        self._faces: _Faces | None = None
        self._sensors: list[int] = []
        self.rest = np.zeros(0, dtype=np.intp) - 1  # (N,) face each body rests on, -1 if free
        self.inside = np.zeros((0, 0), dtype=bool)  # (N, sensors) overlapping each sensor
        self.capped = 0  # bodies placed on a surface after MAX_IMPACTS impacts in one step
        self.began: list[tuple[int, int, Any, Any, Any, float]] = []
        self.ended: list[tuple[int, int, Any, Any, Any, float]] = []
        self._grid: Any = None
        self._rows = np.zeros(0, dtype=np.intp)  # the rows being solved (local -> World row)

    # -- colliders and bodies ---------------------------------------------------------------
    def add(self, collider: Collider) -> None:
        """Add a collider (the World checks its type and pushes bodies out of it)."""
        self.colliders.append(collider)
        self._rebuild()

    def remove(self, collider: Collider) -> None:
        """Take a collider out; every resting body is in flight again (and settles anew)."""
        k = self.colliders.index(collider)
        if collider.sensor:
            self.inside = np.delete(self.inside, self._sensors.index(k), axis=1)
        del self.colliders[k]
        self.rest[:] = -1  # face numbers change; a body still on a surface settles at once
        self._rebuild()

    def _rebuild(self) -> None:
        solid = [k for k, c in enumerate(self.colliders) if not c.sensor]
        self._sensors = [k for k, c in enumerate(self.colliders) if c.sensor]
        self._faces = _compile(self.colliders, solid)
        n = len(self.rest)
        if self.inside.shape != (n, len(self._sensors)):
            inside = np.zeros((n, len(self._sensors)), dtype=bool)
            common = min(self.inside.shape[1], len(self._sensors))
            inside[:, :common] = self.inside[:, :common]
            self.inside = inside
        self._grid = None

    @property
    def faces(self) -> _Faces:
        if self._faces is None:
            self._rebuild()
        assert self._faces is not None
        return self._faces

    def bodies_added(self, k: int) -> None:
        """k bodies were appended to the World: they start free and outside every sensor."""
        self.rest = np.concatenate([self.rest, np.full(k, -1, dtype=np.intp)])
        self.inside = np.concatenate(
            [self.inside, np.zeros((k, self.inside.shape[1]), dtype=bool)]
        )

    def body_removed(self, row: int) -> None:
        """The body in ``row`` left the World."""
        self.rest = np.delete(self.rest, row)
        self.inside = np.delete(self.inside, row, axis=0)

    # -- state ------------------------------------------------------------------------------
    def state(self) -> tuple[Any, ...]:
        """A copy of the contact state (what a snapshot holds)."""
        return (self.rest.copy(), self.inside.copy(), self.capped)

    def set_state(self, state: tuple[Any, ...], n: int) -> None:
        """Bring back ``state()``; ValueError if it does not fit ``n`` bodies."""
        rest, inside, capped = state
        nfaces = len(self.faces.owner)
        if not (
            isinstance(rest, np.ndarray)
            and rest.shape == (n,)
            and isinstance(inside, np.ndarray)
            and inside.shape == (n, len(self._sensors))
            and np.all((rest >= -1) & (rest < nfaces))
        ):
            raise ValueError("snapshot.contacts does not fit this World's bodies and colliders")
        self.rest, self.inside, self.capped = rest.copy(), inside.copy(), int(capped)

    # -- pushing bodies out -----------------------------------------------------------------
    def push_out(self, x: np.ndarray, v: np.ndarray, radius: np.ndarray) -> list[tuple[int, int]]:
        """Move bodies that overlap a solid collider onto its surface; return (row, collider).

        The velocity's part into the surface is removed.
        """
        moved: list[tuple[int, int]] = []
        if len(x) == 0:
            return moved
        for _ in range(4):  # a body in a corner may be pushed by one wall into another
            changed = False
            for k, c in enumerate(self.colliders):
                if c.sensor:
                    continue
                d = signed_distance(c, x) - radius
                bad = np.flatnonzero(d < -1e-9 * (1.0 + radius))
                for i in bad:
                    point, normal, dist = c.closest(x[i])
                    if dist < 0.0 and not isinstance(c, _box_type()):
                        normal = -normal  # the centre is inside the solid: out the near way
                    nx, ny = normal
                    target = point + normal * float(radius[i])
                    x[i] = (target.x, target.y)
                    vn = v[i, 0] * nx + v[i, 1] * ny
                    if vn < 0.0:
                        v[i] = (v[i, 0] - vn * nx, v[i, 1] - vn * ny)
                    moved.append((int(i), k))
                    changed = True
            if not changed:
                break
        return moved

    # -- the step ---------------------------------------------------------------------------
    def resolve(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        dt: float,
        t0: float,
        radius: np.ndarray,
        restitution: np.ndarray,
        friction: np.ndarray,
        mass: np.ndarray,
        acceleration: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The state after dt with every contact on the way applied: new (x, v) arrays.

        ``acceleration`` (N, 2): the bodies' constant acceleration over the step when it is
        known (the closed form); else the path is taken from the step's own update.
        """
        self.began, self.ended = [], []
        faces = self.faces
        x, v = x1.copy(), v1.copy()
        if acceleration is not None:
            W = B = np.broadcast_to(acceleration, x0.shape)
        else:
            W = (v1 - v0) / dt
            B = (x1 - x0 - v0 * dt) * (2.0 / (dt * dt))
        if len(faces.owner):
            rows = self._near(x0, v0, B, dt, radius)
            if len(rows):
                X, V = self._solve(rows, x0, v0, B, W, dt, t0, radius, restitution, friction, mass)
                x[rows], v[rows] = X, V
        if self._sensors:
            self._sense(x0, x, dt, t0, radius)
        return x, v

    def _near(
        self, x0: np.ndarray, v0: np.ndarray, B: np.ndarray, dt: float, radius: np.ndarray
    ) -> np.ndarray:
        """Rows whose path this step may come within reach of a solid face, or that rest."""
        faces = self.faces
        # Every point of the path lies within reach = |v0| dt + |B| dt^2 / 2 of x0.
        reach = (
            np.sqrt(_dot(v0, v0)) * dt + np.sqrt(_dot(B, B)) * (0.5 * dt * dt) + radius
        )
        reach = reach * (1.0 + 1e-9) + TOUCH
        need = self.rest >= 0
        inf_lines = np.flatnonzero(faces.infinite)
        if len(inf_lines):
            d = x0 @ faces.n[inf_lines].T - _dot(faces.p[inf_lines], faces.n[inf_lines])
            need |= (d - faces.rho[inf_lines] <= reach[:, None]).any(axis=1)
        if len(faces.owner) > len(inf_lines):
            need |= self._clearance(x0) <= reach
        return np.flatnonzero(need)

    def _clearance(self, x0: np.ndarray) -> np.ndarray:
        """A lower bound on each point's distance to every finite face (a grid of bounds)."""
        if self._grid is None:
            self._grid = _ClearanceGrid(self.faces)
        return self._grid.lookup(x0)

    def _solve(
        self,
        rows: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        Bf: np.ndarray,
        Wf: np.ndarray,
        dt: float,
        t0: float,
        radius: np.ndarray,
        restitution: np.ndarray,
        friction: np.ndarray,
        mass: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Move the bodies in ``rows`` through their step, impact by impact, in time order."""
        faces = self.faces
        self._rows = rows
        X, V = x0[rows].copy(), v0[rows].copy()
        Bb, Wb = Bf[rows], Wf[rows]
        r, eb, mub, m = radius[rows], restitution[rows], friction[rows], mass[rows]
        rest = self.rest[rows].copy()
        left = np.full(len(rows), dt)
        active = np.arange(len(rows))
        L = len(faces.p)
        for _ in range(MAX_IMPACTS):
            if not len(active):
                break
            Xa, Va = X[active], V[active]
            ra, ta = rest[active], left[active]
            Bp, Wp = Bb[active].copy(), Wb[active].copy()
            dur = ta.copy()
            resting = np.flatnonzero(ra >= 0)
            stop = np.zeros(len(active), dtype=bool)
            if len(resting):
                out = self._rest_paths(
                    resting, active, Xa, Va, Bp, Wp, dur, ra, Wb, mub, r, stop, t0 + dt - ta
                )
                for j in out:
                    rest[active[j]] = -1
                ra = rest[active]
            t_hit, face, normal = self._first_hits(Xa, Va, Bp, dur, r[active], ra)
            hit = t_hit <= dur
            tt = np.where(hit, t_hit, dur)[:, None]
            Xn = Xa + Va * tt + Bp * (0.5 * tt * tt)
            Vn = Va + Wp * tt
            # Bodies that slid to a stop this iteration stop exactly.
            stopped = stop & ~hit
            Vn[stopped] = 0.0
            hi = np.flatnonzero(hit)
            if len(hi):
                self._bounce(hi, active, Xn, Vn, face, normal, rest, Wb, r, eb, mub, m, dt,
                             t0 + dt - ta + t_hit, L)
            # Resting bodies stay exactly on their surface.
            rs = np.flatnonzero(rest[active] >= 0)
            if len(rs):
                self._project(rs, active, Xn, Vn, rest, r)
            X[active], V[active] = Xn, Vn
            left[active] = ta - tt[:, 0]
            left[active[~hit & ~stopped]] = 0.0
            active = active[left[active] > 0.0]
        if len(active):
            # Past the cap: finish the step along the path, then stand on the surface.
            self.capped += len(active)
            Xa, Va, ta = X[active], V[active], left[active][:, None]
            X[active] = Xa + Va * ta + Bb[active] * (0.5 * ta * ta)
            V[active] = Va + Wb[active] * ta
        self.rest[rows] = rest
        # Whatever rounding left a hair inside a face is put back on it (never inside).
        moved = self.push_out_rows(X, V, r)
        del moved
        return X, V

    def push_out_rows(self, X: np.ndarray, V: np.ndarray, r: np.ndarray) -> None:
        """Push rows of X out of any solid face they overlap (by more than TOUCH)."""
        faces = self.faces
        L = len(faces.p)
        if L:
            d = X @ faces.n.T - _dot(faces.p, faces.n)
            side = np.where(faces.two[None, :] & (d < 0.0), -1.0, 1.0)
            gap = side * d - faces.rho[None, :] - r[:, None]
            u = X @ np.stack([-faces.n[:, 1], faces.n[:, 0]], axis=1).T - (
                -faces.p[:, 0] * faces.n[:, 1] + faces.p[:, 1] * faces.n[:, 0]
            )
            inside = (gap < -TOUCH * (1.0 + r[:, None])) & (u >= faces.lo) & (u <= faces.hi)
            # A one-sided face (a plane) is also crossed by whatever is deep behind it.
            for i, j in zip(*np.nonzero(inside), strict=True):
                nrm = side[i, j] * faces.n[j]
                X[i] -= gap[i, j] * nrm
                vn = V[i] @ nrm
                if vn < 0.0:
                    V[i] -= vn * nrm
        if len(faces.c):
            D = X[:, None, :] - faces.c[None, :, :]
            dist = np.sqrt((D * D).sum(axis=2))
            gap = dist - faces.r[None, :] - r[:, None]
            for i, j in zip(*np.nonzero(gap < -TOUCH * (1.0 + r[:, None])), strict=True):
                nrm = D[i, j] / dist[i, j] if dist[i, j] > 0 else np.array([0.0, 1.0])
                X[i] = faces.c[j] + nrm * (faces.r[j] + r[i])
                vn = V[i] @ nrm
                if vn < 0.0:
                    V[i] -= vn * nrm

    def _rest_paths(
        self,
        resting: np.ndarray,
        active: np.ndarray,
        Xa: np.ndarray,
        Va: np.ndarray,
        Bp: np.ndarray,
        Wp: np.ndarray,
        dur: np.ndarray,
        ra: np.ndarray,
        Wb: np.ndarray,
        mub: np.ndarray,
        r: np.ndarray,
        stop: np.ndarray,
        when: np.ndarray,
    ) -> list[int]:
        """Set the sliding path of resting bodies; return those that lift off (local index)."""
        faces = self.faces
        L = len(faces.p)
        lifted: list[int] = []
        for j in resting:
            i = active[j]
            f = int(ra[j])
            x, vel, w = Xa[j], Va[j], Wb[i]
            if f < L:
                nrm = faces.n[f]
                if faces.two[f] and (x - faces.p[f]) @ nrm < 0.0:
                    nrm = -nrm
                tang = np.array([-faces.n[f][1], faces.n[f][0]])
                u_pos = (x - faces.p[f]) @ tang
                off_end = not (faces.lo[f] <= u_pos <= faces.hi[f])
                curve = 0.0
            else:
                d = x - faces.c[f - L]
                dist = math.hypot(d[0], d[1])
                nrm = d / dist
                curve = 1.0 / dist
                off_end = False
            tang = np.array([-nrm[1], nrm[0]])
            a_n = float(w @ nrm)
            v_n = float(vel @ nrm)
            u = float(vel @ tang)
            if a_n > 0.0 or v_n > 1e-9 or off_end or u * u * curve + a_n > 0.0:
                lifted.append(int(j))
                self._event(self.ended, i, f, x - nrm * r[i], nrm, np.zeros(2), when[j])
                continue
            a_t = float(w @ tang)
            fr = mub[i] * faces.mu[f] * -a_n  # Coulomb: mu times the normal pressure per mass
            if u > 0.0:
                a = a_t - fr
                ts = -u / a if a < 0.0 else math.inf
            elif u < 0.0:
                a = a_t + fr
                ts = -u / a if a > 0.0 else math.inf
            elif abs(a_t) <= fr * (1.0 + 1e-12):
                a, ts = 0.0, math.inf  # static friction holds
            else:
                a = a_t - math.copysign(fr, a_t)
                ts = math.inf
            Va[j] = tang * u
            Bp[j] = Wp[j] = tang * a
            if ts < dur[j]:
                dur[j] = ts
                stop[j] = True
        return lifted

    def _project(
        self,
        rs: np.ndarray,
        active: np.ndarray,
        Xn: np.ndarray,
        Vn: np.ndarray,
        rest: np.ndarray,
        r: np.ndarray,
    ) -> None:
        """Put resting bodies exactly at contact distance; turn velocity along a round face."""
        faces = self.faces
        L = len(faces.p)
        for j in rs:
            i = active[j]
            f = int(rest[i])
            if f < L:
                nrm = faces.n[f]
                d = (Xn[j] - faces.p[f]) @ nrm
                side = -1.0 if faces.two[f] and d < 0.0 else 1.0
                gap = side * d - faces.rho[f] - r[i]
                Xn[j] = Xn[j] - gap * side * nrm
                vn = Vn[j] @ nrm
                Vn[j] = Vn[j] - vn * nrm
            else:
                c, rho = faces.c[f - L], faces.r[f - L] + r[i]
                d = Xn[j] - c
                dist = math.hypot(d[0], d[1])
                nrm = d / dist
                speed = math.hypot(Vn[j][0], Vn[j][1])
                tang = np.array([-nrm[1], nrm[0]])
                sign = 1.0 if Vn[j] @ tang >= 0.0 else -1.0
                Xn[j] = c + nrm * rho
                Vn[j] = tang * (sign * speed)

    def _first_hits(
        self,
        X: np.ndarray,
        V: np.ndarray,
        B: np.ndarray,
        T: np.ndarray,
        r: np.ndarray,
        rest: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each body's first impact within its time T: (time or inf, face, normal)."""
        faces = self.faces
        k = len(X)
        L, D = len(faces.p), len(faces.c)
        best = np.full(k, np.inf)
        face = np.full(k, -1, dtype=np.intp)
        normal = np.zeros((k, 2))
        if k == 0:
            return best, face, normal
        reach = np.sqrt(_dot(V, V)) * T + np.sqrt(_dot(B, B)) * (0.5 * T * T) + r
        reach = reach * (1.0 + 1e-9) + TOUCH
        if L:
            d = X @ faces.n.T - _dot(faces.p, faces.n)[None, :]
            dd = np.where(faces.two[None, :], np.abs(d), d)
            near = dd - faces.rho[None, :] <= reach[:, None]
            near &= rest[:, None] != np.arange(L)[None, :]
            bi, fj = np.nonzero(near)
            if len(bi):
                t, nrm = line_hits(
                    X[bi], V[bi], B[bi], faces.p[fj], faces.n[fj], faces.rho[fj] + r[bi],
                    faces.two[fj], faces.lo[fj], faces.hi[fj], T[bi],
                )
                self._keep_first(bi, fj, t, nrm, best, face, normal)
        if D:
            Dv = X[:, None, :] - faces.c[None, :, :]
            dist = np.sqrt((Dv * Dv).sum(axis=2))
            near = dist - faces.r[None, :] <= reach[:, None]
            near &= rest[:, None] != (L + np.arange(D))[None, :]
            bi, fj = np.nonzero(near)
            if len(bi):
                t = disc_hits(X[bi], V[bi], B[bi], faces.c[fj], faces.r[fj] + r[bi], T[bi])
                tt = np.where(np.isfinite(t), t, 0.0)[:, None]
                xt = X[bi] + V[bi] * tt + B[bi] * (0.5 * tt * tt)
                nrm = xt - faces.c[fj]
                length = np.sqrt(_dot(nrm, nrm))
                nrm = nrm / np.where(length > 0.0, length, 1.0)[:, None]
                self._keep_first(bi, fj + L, t, nrm, best, face, normal)
        return best, face, normal

    @staticmethod
    def _keep_first(
        bi: np.ndarray,
        fj: np.ndarray,
        t: np.ndarray,
        nrm: np.ndarray,
        best: np.ndarray,
        face: np.ndarray,
        normal: np.ndarray,
    ) -> None:
        ok = np.flatnonzero(np.isfinite(t))
        if not len(ok):
            return
        bi, fj, t, nrm = bi[ok], fj[ok], t[ok], nrm[ok]
        order = np.lexsort((fj, t, bi))  # per body, earliest first (ties: lowest face)
        bi, fj, t, nrm = bi[order], fj[order], t[order], nrm[order]
        first = np.r_[True, bi[1:] != bi[:-1]]
        bi, fj, t, nrm = bi[first], fj[first], t[first], nrm[first]
        better = t < best[bi]
        b = bi[better]
        best[b], face[b], normal[b] = t[better], fj[better], nrm[better]

    def _bounce(
        self,
        hi: np.ndarray,
        active: np.ndarray,
        Xn: np.ndarray,
        Vn: np.ndarray,
        face: np.ndarray,
        normal: np.ndarray,
        rest: np.ndarray,
        Wb: np.ndarray,
        r: np.ndarray,
        eb: np.ndarray,
        mub: np.ndarray,
        m: np.ndarray,
        dt: float,
        when: np.ndarray,
        L: int,
    ) -> None:
        """Apply the impacts of the bodies ``active[hi]`` (restitution, friction, rest)."""
        faces = self.faces
        i = active[hi]
        f = face[hi]
        n = normal[hi]
        vel = Vn[hi]
        vn = _dot(vel, n)
        vt = vel - n * vn[:, None]
        e = eb[i] * faces.e[f]
        mu = mub[i] * faces.mu[f]
        vn_in = np.minimum(vn, 0.0)
        vn_out = -e * vn_in
        speed_t = np.sqrt(_dot(vt, vt))
        keep = np.maximum(speed_t + mu * (1.0 + e) * vn_in, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            scale = np.where(speed_t > 0.0, keep / speed_t, 0.0)
        a_n = _dot(Wb[i], n)
        settles = (a_n < 0.0) & (vn_out <= -a_n * (0.5 * dt))
        vn_out = np.where(settles, 0.0, vn_out)
        new_v = vt * scale[:, None] + n * vn_out[:, None]
        # A body resting on one face that hits another across it (a floor into a wall) stays
        # resting on the first; anything else that bounces is in flight.
        old = rest[i]
        for k in range(len(hi)):
            j = hi[k]
            body = i[k]
            if settles[k]:
                rest[body] = f[k]
            elif old[k] >= 0:
                keep_rest = abs(float(self._rest_normal(old[k], Xn[j], r[body]) @ n[k])) < 1e-9
                if not keep_rest:
                    rest[body] = -1
            point = Xn[j] - n[k] * r[body]
            impulse = (new_v[k] - vel[k]) * m[body]
            self._event(self.began, body, f[k], point, n[k], impulse, when[j])
            if not settles[k]:
                self._event(self.ended, body, f[k], point, n[k], impulse, when[j])
        Vn[hi] = new_v

    def _rest_normal(self, f: int, x: np.ndarray, r: float) -> np.ndarray:
        faces = self.faces
        L = len(faces.p)
        if f < L:
            nrm = faces.n[f]
            return -nrm if faces.two[f] and (x - faces.p[f]) @ nrm < 0.0 else nrm
        d = x - faces.c[f - L]
        return np.asarray(d / math.hypot(d[0], d[1]))

    def _event(
        self,
        where: list[Any],
        row: int,
        f: int,
        point: Any,
        normal: Any,
        impulse: Any,
        when: float,
    ) -> None:
        if len(where) < MAX_EVENTS:
            body = int(self._rows[row])
            collider = int(self.faces.owner[f])
            where.append((body, collider, point, normal, impulse, float(when)))

    # -- sensors ----------------------------------------------------------------------------
    def _sense(
        self, x0: np.ndarray, x1: np.ndarray, dt: float, t0: float, radius: np.ndarray
    ) -> None:
        """Report bodies that began or ended overlapping each sensor this step."""
        from .colliders import Box

        for s, k in enumerate(self._sensors):
            c = self.colliders[k]
            d = signed_distance(c, x1)
            now = d > -radius if isinstance(c, Box) else d < radius
            was = self.inside[:, s]
            for i in np.flatnonzero(now & ~was):
                self._sensor_event(self.began, int(i), k, c, x1[i], t0 + dt)
            for i in np.flatnonzero(was & ~now):
                self._sensor_event(self.ended, int(i), k, c, x1[i], t0 + dt)
            self.inside[:, s] = now

    def _sensor_event(
        self, where: list[Any], i: int, k: int, c: Collider, x: np.ndarray, when: float
    ) -> None:
        if len(where) < MAX_EVENTS:
            point, normal, _ = c.closest((float(x[0]), float(x[1])))
            where.append((i, k, np.array(point), np.array(normal), np.zeros(2), when))


def _box_type() -> type:
    from .colliders import Box

    return Box


class _ClearanceGrid:
    """Lower bounds on the distance from any point of a cell to the nearest finite face.

    Each cell of a uniform grid over the finite faces (plus a margin) stores the exact
    distance from its centre to the nearest face, less half its diagonal: no point of the cell
    is nearer. Outside the grid every finite face is at least the margin away.
    """

    def __init__(self, faces: _Faces) -> None:
        fin = np.flatnonzero(~faces.infinite)
        L = len(faces.p)
        pts = []
        for j in fin:
            tang = np.array([-faces.n[j][1], faces.n[j][0]])
            a = faces.p[j] + tang * faces.lo[j]
            b = faces.p[j] + tang * faces.hi[j]
            pts += [a, b]
        for j in range(len(faces.c)):
            pts += [faces.c[j] - faces.r[j], faces.c[j] + faces.r[j]]
        P = np.array(pts, float).reshape(-1, 2)
        lo, hi = P.min(axis=0), P.max(axis=0)
        size = max(float((hi - lo).max()), 1e-9)
        self.margin = 0.25 * size + 1.0
        self.lo = lo - self.margin
        span = (hi - lo) + 2 * self.margin
        n_faces = len(fin) + len(faces.c)
        cells = int(min(256, max(8, math.sqrt(4000.0 * max(n_faces, 1)))))
        self.h = float(span.max()) / cells
        nx, ny = (np.ceil(span / self.h).astype(int) + 1).tolist()
        self.shape = (nx, ny)
        gx = self.lo[0] + (np.arange(nx) + 0.5) * self.h
        gy = self.lo[1] + (np.arange(ny) + 0.5) * self.h
        C = np.stack(np.meshgrid(gx, gy, indexing="ij"), axis=-1).reshape(-1, 2)
        best = np.full(len(C), np.inf)
        for j in fin:
            tang = np.array([-faces.n[j][1], faces.n[j][0]])
            a = faces.p[j] + tang * faces.lo[j]
            length = faces.hi[j] - faces.lo[j]
            u = np.clip((C - a) @ tang, 0.0, length)
            q = a + u[:, None] * tang
            best = np.minimum(best, np.hypot(*(C - q).T) - faces.rho[j])
        for j in range(len(faces.c)):
            best = np.minimum(best, np.hypot(*(C - faces.c[j]).T) - faces.r[j])
        del L
        self.bound = (best - self.h * math.sqrt(0.5)).reshape(nx, ny)

    def lookup(self, x: np.ndarray) -> np.ndarray:
        ij = np.floor((x - self.lo) / self.h)
        i, j = ij[:, 0], ij[:, 1]
        nx, ny = self.shape
        inside = (i >= 0) & (i < nx) & (j >= 0) & (j < ny)
        ii = np.where(inside, i, 0).astype(np.intp)
        jj = np.where(inside, j, 0).astype(np.intp)
        return np.where(inside, self.bound[ii, jj], self.margin)
