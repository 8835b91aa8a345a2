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
order, up to ``MAX_IMPACTS`` impacts; past that it stops where the last impact put it, on
the surface, for the rest of the step, and the count is kept in ``capped``. A body resting on
one face and settling against a second that together carry its load (a ball in a corner or a
V) is wedged: it stays put while the load presses into both.

Rest: a rebound too slow to fly for one step (normal speed below |a_n| dt / 2, where a_n is
the acceleration pressing the body onto the surface) ends in rest: the body's centre is put at
exactly its radius from the surface, the surface takes the pressing part of its acceleration,
and it slides along the surface under the tangential part, slowed by friction mu |a_n| until
it stops, at the exact moment the closed form gives, and stays stopped while the tangential
pull is at most mu |a_n| (Coulomb: static on a slope of tan(theta) <= mu). It lifts off when
pulled away from the surface, when its velocity is set to leave it, or when it goes over a
round edge faster than the edge can turn it (v^2 / rho > |a_n|).

A sensor does not push: the contacts report when a body begins and ends overlapping it.

How a step is solved, cheapest test first (in a typical scene few bodies meet anything):

1. ``_near``, over every body in about twenty array operations: a lower bound on its distance
   to every face (one look-up in the grid, whose cells' bounds hold the endless lines too)
   against how far it can reach.
2. ``_narrow``, over those near a face: the faces each can reach, and whether its path, not
   yet turned by any bounce, can meet one at all (a tangent-line bound; see there). Bodies
   that cannot, and do not rest on a face, keep (x1, v1). Usually every body it looks at is
   in a cell clear of the endless lines' backs, and then each body's faces, endless or not,
   come from one row of a table and are tested alike (``_FaceGrid._fast_lists``).
3. The rest are solved impact by impact: a few one body at a time in Python floats
   (``_solve_few``), many at once in numpy arrays (``_solve``). Both do the same arithmetic in
   the same order and give the same bits; only their cost differs (numpy's fixed cost per
   call is about a microsecond, which a handful of bodies never pays back).

At a thousand bodies the cost is the count of array operations, each a microsecond or two
whatever its length, and the Python of the few impacts, not the arithmetic per body. A
clearance budget carried from step to step (a body's distance to the faces when last
looked at, less how far it has moved since) was measured and does not pay here: in the
benchmark's box balls move 0.1 to 0.2 m a step and the nearest face is a metre or two away,
so 110 to 140 of 1,000 need a fresh bound every step even with exact distances, and an
operation on 140 rows costs nearly what one on 1,000 does.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .colliders import Collider
from .events import ContactEvent
from .face_grid import FaceGrid, narrow, near
from .faces import (
    Faces,
    allowed_pairs,
    compile_faces,
    dot,
    face_meets,
    face_normals,
    signed_distance,
)
from .impact import Pair, disc_hit_one, disc_hits, line_hit_one, line_hits
from .push_out import push_out, push_out_rows
from .resting import asleep, project, rest_paths
from .sensors import sense

__all__ = ["Contacts", "ContactEvent", "MAX_IMPACTS", "signed_distance"]

#: Impacts one body may meet in one step; past them it stops where the last one put it,
#: on a surface, for the rest of the step (counted in ``capped``).
MAX_IMPACTS = 32


class Contacts:
    """The World's static colliders and the contact state of its bodies (resting or free)."""

    def __init__(self) -> None:
        self.colliders: list[Collider] = []
        self._faces: Faces | None = None
        self._sensors: list[int] = []
        self.rest = np.zeros(0, dtype=np.intp) - 1  # (N,) face each body rests on, -1 if free
        self.inside = np.zeros((0, 0), dtype=bool)  # (N, sensors) overlapping each sensor
        self.capped = 0  # bodies placed on a surface after MAX_IMPACTS impacts in one step
        self._began: list[tuple[Any, ...]] = []  # arrays of (rows, colliders, points, ...)
        self._ended: list[tuple[Any, ...]] = []
        self._grid: FaceGrid | None = None
        self._rows = np.zeros(0, dtype=np.intp)  # the rows being solved (local -> World row)
        #: Fewer rows than this to solve in a step are solved one body at a time in Python
        #: floats (``_solve_few``), more in numpy arrays (``_solve``): the same results. The
        #: arrays cost a few hundred numpy calls a round whatever their size, the floats about
        #: 12 us a body: measured, the arrays win from about 100 rows (a 2-core machine).
        self.few = 100
        #: Fewer resting bodies than this are checked for staying put (``_asleep``) in Python
        #: floats: a dozen array calls (~30 us) cost more than a few rows' arithmetic.
        self.few_resting = 8
        self.moved = False  # whether the last step's contacts changed any body's state
        #: The World's bodies' filters (group, categories, mask arrays by row), for colliders
        #: with filters of their own (``allowed``); set by the World.
        self.body_filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    # -- colliders and bodies ---------------------------------------------------------------
    def add(self, collider: Collider) -> None:
        """Add a collider (the World checks its type and pushes bodies out of it)."""
        keys = self._face_keys()
        self.colliders.append(collider)
        self._rebuild()
        self._renumber(keys, removed=None)

    def remove(self, collider: Collider) -> None:
        """Take a collider out; bodies resting on it are in flight again."""
        k = self.colliders.index(collider)
        if collider.sensor:
            self.inside = np.delete(self.inside, self._sensors.index(k), axis=1)
        keys = self._face_keys()
        del self.colliders[k]
        self._rebuild()
        self._renumber(keys, removed=k)

    def _face_keys(self) -> list[tuple[int, bool, int]]:
        """Each face's (collider, round?, rank among that collider's faces of its kind)."""
        faces = self.faces
        L = len(faces.p)
        seen: dict[tuple[int, bool], int] = {}
        keys = []
        for j, owner in enumerate(faces.owner.tolist()):
            kind = (owner, j >= L)
            seen[kind] = seen.get(kind, -1) + 1
            keys.append((owner, j >= L, seen[kind]))
        return keys

    def _renumber(self, old_keys: list[tuple[int, bool, int]], removed: int | None) -> None:
        """Faces were renumbered (a collider added or removed): follow the resting bodies."""
        resting = np.flatnonzero(self.rest >= 0)
        if not len(resting):
            return
        new_index = {key: j for j, key in enumerate(self._face_keys())}
        for i in resting:
            owner, kind, rank = old_keys[int(self.rest[i])]
            if owner == removed:
                self.rest[i] = -1  # its face is gone: it falls
                continue
            if removed is not None and owner > removed:
                owner -= 1
            self.rest[i] = new_index[(owner, kind, rank)]

    def _rebuild(self) -> None:
        solid = [k for k, c in enumerate(self.colliders) if not c.sensor]
        self._sensors = [k for k, c in enumerate(self.colliders) if c.sensor]
        self._faces = compile_faces(self.colliders, solid)
        n = len(self.rest)
        if self.inside.shape != (n, len(self._sensors)):
            inside = np.zeros((n, len(self._sensors)), dtype=bool)
            common = min(self.inside.shape[1], len(self._sensors))
            inside[:, :common] = self.inside[:, :common]
            self.inside = inside
        self._grid = None

    @property
    def faces(self) -> Faces:
        if self._faces is None:
            self._rebuild()
        assert self._faces is not None
        return self._faces

    def bodies_added(self, k: int) -> None:
        """k bodies were appended to the World: they start free and outside every sensor."""
        self.rest = np.concatenate([self.rest, np.full(k, -1, dtype=np.intp)])
        self.inside = np.concatenate([self.inside, np.zeros((k, self.inside.shape[1]), dtype=bool)])

    def body_removed(self, row: int) -> None:
        """The body in ``row`` left the World."""
        self.rest = np.delete(self.rest, row)
        self.inside = np.delete(self.inside, row, axis=0)

    # -- state ------------------------------------------------------------------------------
    def state(self) -> tuple[Any, ...]:
        """A copy of the contact state (what a snapshot holds)."""
        return (self.rest.copy(), self.inside.copy(), self.capped)

    def check_state(self, state: Any, n: int) -> None:
        """ValueError unless ``state`` (from ``state()``) fits ``n`` bodies and these colliders."""
        ok = isinstance(state, tuple) and len(state) == 3
        if ok:
            rest, inside, capped = state
            ok = (
                isinstance(rest, np.ndarray)
                and rest.shape == (n,)
                and rest.dtype.kind == "i"
                and isinstance(inside, np.ndarray)
                and inside.shape == (n, len(self._sensors))
                and inside.dtype == bool
                and bool(np.all((rest >= -1) & (rest < len(self.faces.owner))))
                and isinstance(capped, int)
                and not isinstance(capped, bool)
                and capped >= 0
            )
        if not ok:
            raise ValueError(
                "snapshot.contacts must be the contact state from World.snapshot() of a World "
                f"with these colliders and {n} bodies"
            )

    def set_state(self, state: tuple[Any, ...], n: int) -> None:
        """Bring back ``state()``; ValueError if it does not fit ``n`` bodies."""
        self.check_state(state, n)
        rest, inside, capped = state
        self.rest, self.inside, self.capped = rest.copy(), inside.copy(), int(capped)

    def allowed(self, rows: np.ndarray, faces: np.ndarray) -> np.ndarray:
        """Whether each body (World row) meets each face (pairs of equal length): their
        filters collide (engine.filters), as for two bodies. All True without filters."""
        return allowed_pairs(self.faces, self.body_filters, rows, faces)

    # -- pushing bodies out -----------------------------------------------------------------
    def push_out(
        self, x: np.ndarray, v: np.ndarray, radius: np.ndarray, rows: np.ndarray
    ) -> list[tuple[int, int]]:
        """Move bodies (World ``rows``) that overlap a solid collider they meet to the nearest
        place outside every one (``push_out_rows``), in place; return (place in x, a
        collider it overlapped) for each (engine.push_out).

        The velocity's part into the surfaces it then touches is removed.
        """
        return push_out(self.colliders, self.faces, self.body_filters, x, v, radius, rows)

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
        frozen: np.ndarray | None = None,
        sense: bool = True,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The state after dt with every contact on the way applied: new (x, v) arrays.

        ``acceleration`` (N, 2): the bodies' constant acceleration over the step when it is
        known (the closed form); else the path is taken from the step's own update.
        ``frozen`` (N,) bool: bodies left alone here (asleep, moved by the game, or in a pile:
        engine.collisions steps them). ``sense``: report the sensors now (else the World
        calls ``sense`` once the bodies between them have moved too).
        """
        self._began, self._ended = [], []
        faces = self.faces
        x, v = x1, v1
        if acceleration is not None:
            W = B = acceleration
        else:
            W = (v1 - v0) * (1.0 / dt)
            B = (x1 - x0 - v0 * dt) * (2.0 / (dt * dt))
        self.moved = False
        if len(faces.owner):
            rows, asleep, cell, reach, a_bound = self._near(x0, v0, B, W, dt, radius, friction)
            if frozen is not None and frozen[rows].any():
                awake = ~frozen[rows]
                rows, reach = rows[awake], reach[awake]
                cell = None if cell is None else cell[awake]
            if len(asleep):
                # Resting and held by friction: they stay put, whatever the method computed.
                x, v = x1.copy(), v1.copy()
                x[asleep], v[asleep] = x0[asleep], 0.0
                self.moved = True
            if len(rows):
                busy = self.rest.take(rows) >= 0  # resting bodies slide, lift or stay
                allowed = self.allowed if faces.filters is not None else None
                rows, pb, pf = narrow(
                    self.grid, rows, busy, cell, reach, a_bound, x0, v0, dt, radius, allowed
                )
            if len(rows):
                # A few bodies are solved one at a time in Python floats, many in arrays:
                # the same arithmetic, so the same result either way.
                solve = self._solve_few if len(rows) < self.few else self._solve
                changed, X, V = solve(
                    rows, pb, pf, x0, v0, B, W, dt, t0, radius, restitution, friction, mass
                )
                # Only bodies that met something change: the rest keep (x1, v1) bit for bit.
                if len(changed):
                    if not self.moved:
                        x, v = x1.copy(), v1.copy()
                    x[changed], v[changed] = X, V
                    self.moved = True
        if sense:
            self.sense(x, dt, t0, radius)
        return x, v

    def record(
        self,
        rows: np.ndarray,
        colliders: np.ndarray,
        points: np.ndarray,
        normals: np.ndarray,
        impulses: np.ndarray,
        times: np.ndarray,
    ) -> None:
        """Report bounces found elsewhere (engine.collisions: a body sent into a wall by
        another): each begins and ends in the step, as a bounce here does. ``impulses``: the
        bodies' changes of velocity, made changes of momentum here by their masses."""
        if len(rows):
            self._began.append((rows, colliders, points, normals, impulses, times))
            self._ended.append((rows, colliders, points, normals, impulses, times))

    def quiet(self) -> None:
        """A step passed in which no body moved (all asleep): no events."""
        self._began, self._ended = [], []
        self.moved = False

    @property
    def began(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts that began in the last step: (row, collider index, point, normal, impulse,
        time) each, in the order they were found."""
        return _unpack(self._began)

    @property
    def ended(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts that ended in the last step, as ``began``."""
        return _unpack(self._ended)

    @property
    def grid(self) -> FaceGrid:
        """The broadphase over the solid faces (engine.face_grid), built when first needed."""
        if self._grid is None:
            self._grid = FaceGrid(self.faces)
        return self._grid

    def _grid_of(self) -> FaceGrid:
        """``grid`` by its old name, for callers not yet switched (engine.collisions)."""
        return self.grid

    def _near(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        B: np.ndarray,
        W: np.ndarray,
        dt: float,
        radius: np.ndarray,
        friction: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray, float]:
        """(rows whose path this step may come within reach of a solid face or that move on
        one, rows that rest and stay put, the first rows' grid cells or None, their reach,
        a bound on every body's |B| and |W|): ``face_grid.near``, with the resting bodies."""
        need, cell, reach, a_bound = near(self.grid, x0, v0, B, W, dt, radius)
        asleep = np.zeros(0, dtype=np.intp)
        if len(self.rest) and self.rest.max() >= 0:
            resting = np.flatnonzero(self.rest >= 0)
            asleep = self._asleep(resting, x0, v0, W, friction)
            need[resting] = True
            need[asleep] = False
        rows = np.flatnonzero(need)
        cell_rows = None if cell is None else cell.take(rows)
        return rows, asleep, cell_rows, reach.take(rows), a_bound

    def _asleep(
        self,
        res: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        W: np.ndarray,
        friction: np.ndarray,
    ) -> np.ndarray:
        """Resting rows that stay exactly where they are this step: still (v = 0), pressed
        onto their face (a_n <= 0) and held by static friction (|a_t| <= mu |a_n|)."""
        if len(res) < self.few_resting:
            return self._asleep_few(res, x0, v0, W, friction)
        return asleep(self.faces, self.rest, res, x0, v0, W, friction)

    def _asleep_few(
        self,
        res: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        W: np.ndarray,
        friction: np.ndarray,
    ) -> np.ndarray:
        """``_asleep`` for a few rows, in Python floats (the same operations, so the same
        answer): a dozen array calls cost more than these few rows' arithmetic."""
        faces = self.faces
        rows = res.tolist()
        V = v0.take(res, axis=0).tolist()
        X = x0.take(res, axis=0).tolist()
        Wl = W.take(res, axis=0).tolist()
        mub = friction.take(res).tolist()
        f_of = self.rest.take(res).tolist()
        out = []
        for i, row in enumerate(rows):
            if V[i][0] != 0.0 or V[i][1] != 0.0:
                continue
            f = f_of[i]
            nx, ny, _ = _normal_one(faces, f, (X[i][0], X[i][1]))
            wx, wy = Wl[i]
            a_n = wx * nx + wy * ny
            a_t = wy * nx - wx * ny  # along the tangent (-n_y, n_x)
            if a_n <= 0.0 and abs(a_t) <= mub[i] * faces.mu_list[f] * -a_n * (1.0 + 1e-12):
                out.append(row)
        return np.array(out, dtype=np.intp)

    def _solve(
        self,
        rows: np.ndarray,
        pb: np.ndarray,
        pf: np.ndarray,
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
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Move the bodies in ``rows`` through their step, impact by impact, in time order.

        (pb, pf) are the (body, face) pairs to test, the body by its place in ``rows``: every
        face it could meet this step (whatever it bounces off, its path stays within _reach
        of where it started). Returns the rows that met anything (struck, rested, slid or
        lifted off) and their new positions and velocities.
        """
        self._rows = rows
        faces = self.faces
        X, V = x0.take(rows, axis=0), v0.take(rows, axis=0)
        Bb, Wb = Bf.take(rows, axis=0), Wf.take(rows, axis=0)
        r, eb, mub, m = radius[rows], restitution[rows], friction[rows], mass[rows]
        rest = self.rest[rows]
        left = np.full(len(rows), dt)
        touched = np.zeros(len(rows), dtype=bool)
        active = np.arange(len(rows))
        slot = np.full(len(rows), -1, dtype=np.intp)  # row -> index among the active
        for _ in range(MAX_IMPACTS):
            Xa, Va, ta = X[active], V[active], left[active]
            Bp, Wp, ra = Bb[active], Wb[active], rest[active]
            slot[active] = np.arange(len(active))
            live = np.flatnonzero((slot[pb] >= 0) & (pf != rest[pb]))
            bi, fj = slot[pb[live]], pf[live]
            dur = ta.copy()
            stop = np.zeros(len(active), dtype=bool)
            res = np.flatnonzero(ra >= 0)
            if len(res):
                lifted, edge = rest_paths(
                    faces, res, active, Xa, Va, Bp, Wp, dur, ra, Wb, mub, r, stop,
                    t0 + dt - ta, rows, self._ended,
                )  # fmt: skip
                if len(lifted):
                    rest[active[lifted]] = -1
                    ra = rest[active]
                if len(edge):
                    # Gone over a round edge: the rest of its step is flown on the mean
                    # acceleration W, the path that leaves the edge (the method's own path
                    # B, 2 a for semi-implicit Euler, curves back into it: the ball would
                    # land again at once, and again, up to the cap).
                    Bp[edge] = Wp[edge]
                    Bb[active[edge]] = Wb[active[edge]]
            if len(res) and len(lifted):
                live = np.flatnonzero((slot[pb] >= 0) & (pf != rest[pb]))
                bi, fj = slot[pb[live]], pf[live]
            t_hit, face, normal = self._first_hits(Xa, Va, Bp, dur, r[active], bi, fj)
            hit = t_hit <= dur
            tt = np.where(hit, t_hit, dur)
            tc = tt[:, None]
            Xn = Xa + Va * tc + Bp * (0.5 * tc * tc)
            Vn = Va + Wp * tc
            stopped = stop & ~hit
            if stopped.any():
                Vn[stopped] = 0.0  # slid to a stop: exactly at rest
            h = np.flatnonzero(hit)
            done = np.zeros(len(active), dtype=bool)
            if len(h):
                done[h] = self._bounce(
                    h,
                    active,
                    Xn,
                    Vn,
                    face,
                    normal,
                    rest,
                    Wb,
                    r,
                    eb,
                    mub,
                    m,
                    dt,
                    t0 + dt - ta + t_hit,
                )
                touched[active[h]] = True
            rs = np.flatnonzero(rest[active] >= 0)
            if len(rs):
                project(faces, rs, active, Xn, Vn, rest, r, Wb)
                # A body rolling over a round edge onto a flat side it now overlaps has left
                # the edge: it stands on the side and is in flight again (it settles there).
                L = len(self.faces.p)
                rolled = rs[rest[active[rs]] >= L]
                if len(rolled):
                    Xr, Vr = Xn[rolled], Vn[rolled]
                    moved = self.push_out_rows(Xr, Vr, r[active[rolled]], rows[active[rolled]])
                    Xn[rolled], Vn[rolled] = Xr, Vr
                    rest[active[rolled[moved]]] = -1
            X[active], V[active] = Xn, Vn
            more = (hit | stopped) & ~done
            left[active] = np.where(more, ta - tt, 0.0)
            slot[active] = -1
            active = active[more & (ta - tt > 0.0)]
            if not len(active):
                break
        else:
            # Past the cap: the body stays where its last impact put it, on a surface, and
            # stops there for the rest of the step (it would only strike again and again).
            self.capped += len(active)
            V[active] = 0.0
            touched[active] = True
            Xt, Vt = X[active], V[active]
            self.push_out_rows(Xt, Vt, r[active], rows[active])
            X[active], V[active] = Xt, Vt
        touched |= rest >= 0
        touched |= self.rest[rows] >= 0  # lifted off this step
        self.rest[rows] = rest
        t = np.flatnonzero(touched)
        return rows[t], X[t], V[t]

    def push_out_rows(
        self, X: np.ndarray, V: np.ndarray, r: np.ndarray, rows: np.ndarray | None = None
    ) -> np.ndarray:
        """Push rows of X out of any solid face they overlap (by more than TOUCH), in place;
        return which rows moved (engine.push_out). ``rows``: the World rows of X's rows, whose
        filters say which faces they meet (needed only when a collider has a filter)."""
        faces = self.faces
        meets = None if rows is None else face_meets(faces, self.body_filters, rows)
        return push_out_rows(faces, self.colliders, X, V, r, meets)

    def _normals(self, f: np.ndarray, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Unit normals toward X of faces f (one per row), and 1 / radius (0 for flat faces)."""
        return face_normals(self.faces, f, X)

    def _first_hits(
        self,
        X: np.ndarray,
        V: np.ndarray,
        B: np.ndarray,
        T: np.ndarray,
        r: np.ndarray,
        bi: np.ndarray,
        fj: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each body's first impact within its time T among the (body, face) pairs given:
        (time or inf, face, normal)."""
        faces = self.faces
        k = len(X)
        L = len(faces.p)
        best = np.full(k, np.inf)
        face = np.full(k, -1, dtype=np.intp)
        normal = np.zeros((k, 2))
        if not len(bi):
            return best, face, normal
        t = np.empty(len(bi))
        line = np.flatnonzero(fj < L)
        disc = np.flatnonzero(fj >= L)
        nrm_line = None
        if len(line):
            lb, lf = bi[line], fj[line]
            t[line], nrm_line = line_hits(
                X[lb],
                V[lb],
                B[lb],
                faces.p[lf],
                faces.n[lf],
                faces.rho[lf] + r[lb],
                faces.two[lf],
                faces.lo[lf],
                faces.hi[lf],
                T[lb],
            )
        if len(disc):
            db, df = bi[disc], fj[disc] - L
            t[disc] = disc_hits(X[db], V[db], B[db], faces.c[df], faces.r[df] + r[db], T[db])
        # The earliest impact of each body (ties: the last pair listed, deterministically).
        np.minimum.at(best, bi, t)
        win = np.flatnonzero((t == best[bi]) & (t < np.inf))
        if not len(win):
            return best, face, normal
        wb, wf = bi[win], fj[win]
        face[wb] = wf
        # Normals of the winners: a flat face's from its kernel, a round face's from where the
        # ball's centre is at the impact.
        tw = t[win][:, None]
        xt = X[wb] + V[wb] * tw + B[wb] * (0.5 * tw * tw)
        is_disc = wf >= L
        c = faces.c[np.where(is_disc, wf - L, 0)] if len(faces.c) else xt
        d = xt - c
        length = np.sqrt(dot(d, d))
        nd = d / np.where(length > 0.0, length, 1.0)[:, None]
        if nrm_line is not None:
            pos = np.full(len(bi), -1, dtype=np.intp)
            pos[line] = np.arange(len(line))
            nl = nrm_line[np.maximum(pos[win], 0)]
            normal[wb] = np.where(is_disc[:, None], nd, nl)
        else:
            normal[wb] = nd
        return best, face, normal

    def _bounce(
        self,
        h: np.ndarray,
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
    ) -> np.ndarray:
        """Apply the impacts of the bodies ``active[h]``: restitution, friction, rest.

        Returns which of them are wedged between two faces (at rest for the rest of the step).

        With the unit normal n: v_n' = -e v_n; the tangential speed loses up to mu (1 + e)
        |v_n| (the friction impulse is at most mu times the normal one), never reversing.
        A rebound slower than |a_n| dt / 2 (it would fly for less than one step) settles.
        """
        faces = self.faces
        i = active[h]
        f = face[h]
        n = normal[h]
        vel = Vn[h]
        vn = dot(vel, n)
        vt = vel - n * vn[:, None]
        e = eb[i] * faces.e[f]
        mu = mub[i] * faces.mu[f]
        vn_in = np.minimum(vn, 0.0)
        vn_out = -e * vn_in
        speed_t = np.sqrt(dot(vt, vt))
        keep = np.maximum(speed_t + mu * (1.0 + e) * vn_in, 0.0)
        scale = keep / np.where(speed_t > 0.0, speed_t, 1.0)
        a_n = dot(Wb[i], n)
        settles = (a_n < 0.0) & (vn_out <= -a_n * (0.5 * dt))
        vn_out = np.where(settles, 0.0, vn_out)
        new_v = vt * scale[:, None] + n * vn_out[:, None]
        # A body resting on one face that hits another across it (a floor into a wall) stays
        # resting on the first; anything else that bounces is in flight.
        old = rest[i]
        was = old >= 0
        stays = np.zeros(len(h), dtype=bool)
        wedged = np.zeros(len(h), dtype=bool)
        if was.any():
            on, _ = self._normals(np.where(was, old, 0), Xn[h])
            stays = was & (np.abs(dot(on, n)) < 1e-9)
            # Wedged: resting on face 1, settling on face 2, and the acceleration presses into
            # both: W = l1 n1 + l2 n2 with l1, l2 <= 0. The two faces then carry it all and
            # the body stays put for the rest of the step (the forces are constant within it).
            det = on[:, 0] * n[:, 1] - on[:, 1] * n[:, 0]
            w = Wb[i]
            safe = np.where(np.abs(det) > 1e-12, det, 1.0)
            l1 = (w[:, 0] * n[:, 1] - w[:, 1] * n[:, 0]) / safe
            l2 = (on[:, 0] * w[:, 1] - on[:, 1] * w[:, 0]) / safe
            # It settles there when the rebound is too slow to fly one step against the load
            # -l2 that face 2 would carry (as for one face, with l2 in place of a_n).
            slow = vn_out <= -l2 * (0.5 * dt)
            wedged = was & slow & (np.abs(det) > 1e-12) & (l1 <= 0.0) & (l2 <= 0.0)
            if wedged.any():
                new_v[wedged] = 0.0
        rest[i] = np.where(wedged | stays, old, np.where(settles, f, -1))
        point = Xn[h] - n * r[i][:, None]
        impulse = (new_v - vel) * m[i][:, None]
        # A touch with no speed into the face (a body sliding into a wedge it sits in) is
        # not reported: nothing struck.
        struck = vn_in < 0.0
        rows = self._rows[i]
        owner = faces.owner[f]
        if struck.any():
            b = struck
            self._began.append((rows[b], owner[b], point[b], n[b], impulse[b], when[h][b]))
            b = struck & ~settles
            if b.any():
                self._ended.append((rows[b], owner[b], point[b], n[b], impulse[b], when[h][b]))
        Vn[h] = new_v
        return wedged

    # -- a few bodies, one at a time ---------------------------------------------------------
    # The same steps as _solve and its helpers, for one body in Python floats: _path_one is
    # _solve's loop (with _first_hits' loop inline), and each function ending in _one (after
    # this class) is its array twin line for line (same operations in the same order, so the
    # same bits), with an `if` where the array version computes both branches and picks with
    # np.where. On a handful of
    # bodies numpy's fixed cost per call (about a microsecond, a few hundred calls per round
    # of impacts) is most of the time; floats have none.
    def _solve_few(
        self,
        rows: np.ndarray,
        pb: np.ndarray,
        pf: np.ndarray,
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
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``_solve``, one body after another in Python floats (for a few rows)."""
        faces = self.faces
        faces_of: list[list[int]] = [[] for _ in range(len(rows))]
        for b, f in zip(pb.tolist(), pf.tolist(), strict=True):
            faces_of[b].append(f)
        X = x0.take(rows, axis=0).tolist()
        V = v0.take(rows, axis=0).tolist()
        Bl = Bf.take(rows, axis=0).tolist()
        Wl = Bl if Wf is Bf else Wf.take(rows, axis=0).tolist()
        r, e = radius.take(rows).tolist(), restitution.take(rows).tolist()
        mu, m = friction.take(rows).tolist(), mass.take(rows).tolist()
        rest = self.rest.take(rows).tolist()
        row_list = rows.tolist()
        # Events with a key (round, phase, place) that puts them in _solve's order: round by
        # round, lift-offs before impacts, bodies in row order.
        began: list[tuple[tuple[int, int, int], tuple[Any, ...]]] = []
        ended: list[tuple[tuple[int, int, int], tuple[Any, ...]]] = []
        changed: list[int] = []
        Xc: list[float] = []
        Vc: list[float] = []
        for k, row in enumerate(row_list):
            x, v, touched, rest_k = self._path_one(
                faces, k, row, X[k], V[k], Bl[k], Wl[k], r[k], e[k], mu[k], m[k], rest[k],
                faces_of[k], dt, t0, began, ended,
            )  # fmt: skip
            if touched:
                changed.append(row)
                Xc += x  # flat: one np.array of floats is cheaper than one of pairs
                Vc += v
                self.rest[row] = rest_k
        for where, events in ((self._began, began), (self._ended, ended)):
            if events:
                events.sort()  # by key: each (round, phase, place) holds one event
                where.append(tuple(zip(*[ev for _, ev in events], strict=True)))
        shape = (len(changed), 2)
        return (
            np.array(changed, dtype=np.intp),
            np.array(Xc, dtype=float).reshape(shape),
            np.array(Vc, dtype=float).reshape(shape),
        )

    def _path_one(
        self,
        faces: Faces,
        k: int,
        row: int,
        x: Pair,
        v: Pair,
        b: Pair,
        w: Pair,
        r: float,
        e: float,
        mu: float,
        m: float,
        rest: int,
        faces_of: list[int],
        dt: float,
        t0: float,
        began: list[Any],
        ended: list[Any],
    ) -> tuple[Pair, Pair, bool, int]:
        """One body through its step, impact by impact (_solve's loop for one row ``row``,
        ``k`` its place among the rows solved): (x, v, whether it met anything, its rest)."""
        line_list, disc_list = faces.line_list, faces.disc_list
        L = len(line_list)
        rest_before = rest
        touched = False
        left = dt
        for round_ in range(MAX_IMPACTS):
            ta = left
            vp, bp, wp = v, b, w  # this round's path (a resting body slides along its face)
            dur = ta
            stop = False
            if rest >= 0:
                slide = _rest_path_one(faces, rest, x, v, w, mu)
                if slide is False:  # over a round edge: flown on W (as in _solve)
                    b = bp = w
                if slide is None or slide is False:  # lifts off
                    nx, ny, _ = _normal_one(faces, rest, x)
                    point = (x[0] - nx * r, x[1] - ny * r)
                    event = (row, faces.owner_list[rest], point, (nx, ny), (0.0, 0.0))
                    ended.append(((round_, 0, k), (*event, t0 + dt - ta)))
                    rest = -1
                else:
                    assert not isinstance(slide, bool)
                    vp, bp, ts = slide
                    wp = bp
                    if ts < dur:
                        dur, stop = ts, True
            # Contacts._first_hits for this body (inlined: the innermost loop of a step): the
            # earliest impact among its faces (ties: the last listed), and its normal.
            t_hit, face, normal = math.inf, -1, (0.0, 0.0)
            for f in faces_of:
                if f == rest:
                    continue
                if f < L:
                    p, n, rho, two, lo, hi = line_list[f]
                    t, nrm = line_hit_one(x, vp, bp, p, n, rho + r, two, lo, hi, dur)
                else:
                    c, rho = disc_list[f - L]
                    t, nrm = disc_hit_one(x, vp, bp, c, rho + r, dur), (0.0, 0.0)
                if t <= t_hit and t < math.inf:
                    t_hit, face, normal = t, f, nrm
            if face >= L:
                normal = _disc_normal_one(disc_list[face - L][0], x, vp, bp, t_hit)
            hit = t_hit <= dur
            tt = t_hit if hit else dur
            half_tt2 = 0.5 * tt * tt
            xn = (x[0] + vp[0] * tt + bp[0] * half_tt2, x[1] + vp[1] * tt + bp[1] * half_tt2)
            vn = (vp[0] + wp[0] * tt, vp[1] + wp[1] * tt)
            stopped = stop and not hit
            if stopped:
                vn = (0.0, 0.0)  # slid to a stop: exactly at rest
            done = False
            if hit:
                when = t0 + dt - ta + t_hit
                vn, rest, done = _bounce_one(
                    faces, k, row, round_, xn, vn, face, normal, rest, w, r, e, mu, m, dt, when,
                    began, ended,
                )  # fmt: skip
                touched = True
            if rest >= 0:
                xn, vn = _project_one(faces, rest, xn, vn, r, w)
                if rest >= L:  # rolled over a round edge onto a flat side it overlaps?
                    Xr, Vr = np.array([xn]), np.array([vn])
                    if self.push_out_rows(Xr, Vr, np.array([r]), np.array([row]))[0]:
                        rest = -1
                    xn, vn = (float(Xr[0, 0]), float(Xr[0, 1])), (float(Vr[0, 0]), float(Vr[0, 1]))
            x, v = xn, vn
            more = (hit or stopped) and not done
            left = ta - tt if more else 0.0
            if not (more and ta - tt > 0.0):
                break
        else:
            # Past the cap: it stops where its last impact put it, on a surface (as _solve).
            self.capped += 1
            touched = True
            Xt, Vt = np.array([x]), np.zeros((1, 2))
            self.push_out_rows(Xt, Vt, np.array([r]), np.array([row]))
            x, v = (float(Xt[0, 0]), float(Xt[0, 1])), (float(Vt[0, 0]), float(Vt[0, 1]))
        return x, v, touched or rest >= 0 or rest_before >= 0, rest

    # -- sensors ----------------------------------------------------------------------------
    def sense(self, x1: np.ndarray, dt: float, t0: float, radius: np.ndarray) -> None:
        """Report bodies that began or ended overlapping each sensor this step (x1: where the
        bodies ended it; engine.sensors)."""
        sense(
            self.colliders, self._sensors, self.inside, self.body_filters, x1, dt, t0, radius,
            self._began, self._ended,
        )  # fmt: skip


# -- one body at a time: the twins of Contacts._solve's helpers ------------------------------


def _normal_one(faces: Faces, f: int, x: Pair) -> tuple[float, float, float]:
    """``Contacts._normals`` for one face and point: (n_x, n_y, 1 / radius or 0 if flat)."""
    L = len(faces.line_list)
    if f < L:
        p, (nx, ny), _, two, _, _ = faces.line_list[f]
        side = -1.0 if two and (x[0] - p[0]) * nx + (x[1] - p[1]) * ny < 0.0 else 1.0
        return nx * side, ny * side, 0.0
    (cx, cy), _ = faces.disc_list[f - L]
    dx, dy = x[0] - cx, x[1] - cy
    dist = math.sqrt(dx * dx + dy * dy)
    safe = dist if dist > 0.0 else 1.0
    return dx / safe, dy / safe, 1.0 / safe


def _rest_path_one(
    faces: Faces, f: int, x: Pair, v: Pair, w: Pair, mub: float
) -> tuple[Pair, Pair, float] | bool | None:
    """``Contacts._rest_paths`` for one body resting on face f: None if it lifts off (False
    if over a round edge faster than it can turn it), else its sliding path (velocity,
    acceleration along the face, time it stops or inf)."""
    nx, ny, curve = _normal_one(faces, f, x)
    tx, ty = -ny, nx
    a_n = w[0] * nx + w[1] * ny
    v_n = v[0] * nx + v[1] * ny
    u = v[0] * tx + v[1] * ty
    off_end = False
    if f < len(faces.line_list):
        p, n, _, _, lo, hi = faces.line_list[f]
        pos = (x[0] - p[0]) * -n[1] + (x[1] - p[1]) * n[0]
        off_end = pos < lo or pos > hi
    if a_n > 0.0 or v_n > 1e-9 or off_end:
        return None
    if u * u * curve + a_n > 0.0:
        return False
    a_t = w[0] * tx + w[1] * ty
    fr = mub * faces.mu_list[f] * max(-a_n, 0.0)
    if u > 0.0:
        a = a_t - fr
    elif u < 0.0:
        a = a_t + fr
    elif abs(a_t) <= fr * (1.0 + 1e-12):  # held by static friction
        a = 0.0
    else:
        a = a_t - math.copysign(fr, a_t)
    slowing = (u > 0.0 and a < 0.0) or (u < 0.0 and a > 0.0)
    ts = -u / a if slowing else math.inf
    return (tx * u, ty * u), (tx * a, ty * a), ts


def _disc_normal_one(c: Pair, x: Pair, v: Pair, b: Pair, t: float) -> Pair:
    """The normal of a round face (centre c) at an impact at time t: from the centre to where
    the ball's centre is then (``Contacts._first_hits``'s, for one body)."""
    dx = x[0] + v[0] * t + b[0] * (0.5 * t * t) - c[0]
    dy = x[1] + v[1] * t + b[1] * (0.5 * t * t) - c[1]
    length = math.sqrt(dx * dx + dy * dy)
    safe = length if length > 0.0 else 1.0
    return (dx / safe, dy / safe)


def _bounce_one(
    faces: Faces,
    k: int,
    row: int,
    round_: int,
    x: Pair,
    vel: Pair,
    f: int,
    n: Pair,
    old: int,
    w: Pair,
    r: float,
    eb: float,
    mub: float,
    m: float,
    dt: float,
    when: float,
    began: list[Any],
    ended: list[Any],
) -> tuple[Pair, int, bool]:
    """``Contacts._bounce`` for one body: (new velocity, face it rests on or -1, wedged)."""
    nx, ny = n
    vx, vy = vel
    wx, wy = w
    vn = vx * nx + vy * ny
    vtx, vty = vx - nx * vn, vy - ny * vn
    e = eb * faces.e_list[f]
    mu = mub * faces.mu_list[f]
    vn_in = min(vn, 0.0)
    vn_out = -e * vn_in
    speed_t = math.sqrt(vtx * vtx + vty * vty)
    keep = max(speed_t + mu * (1.0 + e) * vn_in, 0.0)
    scale = keep / (speed_t if speed_t > 0.0 else 1.0)
    a_n = wx * nx + wy * ny
    settles = a_n < 0.0 and vn_out <= -a_n * (0.5 * dt)
    if settles:
        vn_out = 0.0
    new_v = (vtx * scale + nx * vn_out, vty * scale + ny * vn_out)
    stays = wedged = False
    if old >= 0:
        onx, ony, _ = _normal_one(faces, old, x)
        stays = abs(onx * nx + ony * ny) < 1e-9
        det = onx * ny - ony * nx
        safe = det if abs(det) > 1e-12 else 1.0
        l1 = (wx * ny - wy * nx) / safe
        l2 = (onx * wy - ony * wx) / safe
        slow = vn_out <= -l2 * (0.5 * dt)
        wedged = slow and abs(det) > 1e-12 and l1 <= 0.0 and l2 <= 0.0
        if wedged:
            new_v = (0.0, 0.0)
    rest = old if wedged or stays else (f if settles else -1)
    if vn_in < 0.0:  # struck (a touch with no speed into the face is not reported)
        point = (x[0] - nx * r, x[1] - ny * r)
        impulse = ((new_v[0] - vx) * m, (new_v[1] - vy) * m)
        event = (row, faces.owner_list[f], point, n, impulse, when)
        began.append(((round_, 1, k), event))
        if not settles:
            ended.append(((round_, 1, k), event))
    return new_v, rest, wedged


def _project_one(faces: Faces, f: int, x: Pair, vel: Pair, r: float, w: Pair) -> tuple[Pair, Pair]:
    """``Contacts._project`` for one body resting on face f: (position, velocity)."""
    L = len(faces.line_list)
    nx, ny, _ = _normal_one(faces, f, x)
    vn = vel[0] * nx + vel[1] * ny
    if f < L:
        p, _, rho, _, _, _ = faces.line_list[f]
        gap = (x[0] - p[0]) * nx + (x[1] - p[1]) * ny - rho - r
        return (x[0] - nx * gap, x[1] - ny * gap), (vel[0] - nx * vn, vel[1] - ny * vn)
    c, rho = faces.disc_list[f - L]
    x_on = (c[0] + nx * (rho + r), c[1] + ny * (rho + r))
    tx, ty = -ny, nx
    # The pull's work from the tangent to the arc (_project): |v|^2 gains 2 W.dx.
    gain = 2.0 * (w[0] * (x_on[0] - x[0]) + w[1] * (x_on[1] - x[1]))
    x = x_on
    speed = math.sqrt(max(vel[0] * vel[0] + vel[1] * vel[1] + gain, 0.0))
    sign = 1.0 if vel[0] * tx + vel[1] * ty >= 0.0 else -1.0
    return x, (tx * (sign * speed), ty * (sign * speed))


def _unpack(parts: list[tuple[Any, ...]]) -> list[tuple[int, int, Any, Any, Any, float]]:
    out: list[tuple[int, int, Any, Any, Any, float]] = []
    for rows, owner, point, normal, impulse, when in parts:
        for j in range(len(rows)):
            out.append(
                (int(rows[j]), int(owner[j]), point[j], normal[j], impulse[j], float(when[j]))
            )
    return out
