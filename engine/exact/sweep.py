"""Sweeping the step's paths against the faces: impacts in time order, and bounces.

The World hands the contacts each step's start state (x0, v0) and the state its method reached
(x1, v1) after dt. Between them a body's centre follows a known path:

    x(t) = x0 + v0 t + B t^2 / 2,    v(t) = v0 + W t,    0 <= t <= dt,

with B = W = the constant acceleration under the closed form ("exact"), which is exact; for an
integrator, W = (v1 - v0) / dt is the step's mean acceleration and B = 2 (x1 - x0 - v0 dt) / dt^2
makes the path end where the method ended (the step's own update is what is swept: explicit
Euler's straight line, velocity Verlet's parabola, semi-implicit Euler's x0 + v1 t in
its mean). A body that meets nothing on that path keeps (x1, v1) bit for bit.

Where the path first touches a face (``engine.geometry.impact`` solves for the time), the body is
moved there and bounces: with the unit normal n, the normal velocity v_n becomes -e v_n and
Coulomb friction takes up to mu (1 + e) |v_n| off the tangential velocity (never reversing
it), e and mu being the products of the body's and the collider's materials. It then goes on
along the same kind of path for the rest of the step, meeting whatever comes next, in time
order, up to ``MAX_IMPACTS`` impacts; past that it stops where the last impact put it, on
the surface, for the rest of the step, and is counted as capped. A body resting on one face
and settling against a second that together carry its load (a ball in a corner or a V) is
wedged: it stays put while the load presses into both. A rebound too slow to fly for one step
settles into rest on the face (engine.exact.resting says how a body rests, slides and lifts off).

**A slide's end.** A body sliding on a flat face with ends (a Segment's, a Polygon's edge)
leaves it where its point of contact passes the face's end: the first root of a quadratic in
the part's time, a simple root, found where the slide's path is set (engine.exact.resting's
``rest_paths``). The body goes on from there resting on that end's round face
(``Faces.ends``), around it or off it as that face decides (over it faster than it can turn
the body: flown on). The end's round face is not met as an impact while the body slides on its
face: it lies tangent to the slide's path, a double root, whose moment an ulp of the start
moves by its square root. Found that way (as it was until 2026-12-07), the moment was also
missed, and the body slid on past the face's end along its line until the next step's start
found it off: a ball reaching a 30 degree ramp's end at 5.1 m/s slid 4.7 cm past it along
the ramp's line in that step, and flew on 1.5% off the closed form's velocity
(tests/test_contacts.py: now to 1e-15).

The bodies that may meet a face this step, and the faces each may meet, come from the
broadphase (engine.geometry.face_grid). They are swept here many at once in numpy arrays
(``sweep``); a few are swept one at a time in Python floats (engine.exact.sweep_one): the same
arithmetic in the same order, so the same bits; only their cost differs.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..dynamics.rotation import Rolling, Spin, grip, rolling
from ..geometry.faces import Faces, behind_solid, dot, face_normals
from ..geometry.impact import disc_hits, line_hits
from .resting import project, rest_paths

__all__ = ["MAX_IMPACTS", "Paths", "PushOut", "bounce", "first_hits", "sweep"]

#: Impacts one body may meet in one step; past them it stops where the last one put it,
#: on a surface, for the rest of the step (counted in ``Contacts.capped``).
MAX_IMPACTS = 32
#: Two faces wedge a body only if their normals differ by more than this (the sine of the
#: angle between them): a face's round end, met by a ball just off the face with the face's
#: own normal to the rounding of the moment it is met (2.6e-8 at 2 m/s, where a slide's end
#: was found so: "A slide's end" above), is no wedge.
WEDGE_SIN = 1e-6

#: ``Contacts.push_out_rows``: push rows of X (with velocities V, radii r, World rows) out of
#: the solid faces they overlap, in place; which rows moved.
PushOut = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Paths:
    """The step's paths, x0 + v0 t + B t^2 / 2 with velocity v0 + W t for 0 <= t <= dt from
    the World's time t0, and what the bodies are: every array by World row."""

    x0: np.ndarray  # (N, 2) positions at the step's start (length units)
    v0: np.ndarray  # (N, 2) velocities then
    B: np.ndarray  # (N, 2) the path's curvature (``W`` itself under the closed form)
    W: np.ndarray  # (N, 2) the mean acceleration over the step
    dt: float  # the step (s)
    t0: float  # the World's time at its start (s)
    radius: np.ndarray  # (N,)
    restitution: np.ndarray  # (N,)
    friction: np.ndarray  # (N,)
    mass: np.ndarray  # (N,)


def sweep(
    faces: Faces,
    paths: Paths,
    rows: np.ndarray,
    pb: np.ndarray,
    pf: np.ndarray,
    resting: np.ndarray,
    push_out: PushOut,
    began: list[Any],
    ended: list[Any],
    spin: Spin | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Move the bodies in ``rows`` through their step, impact by impact, in time order.

    (pb, pf) are the (body, face) pairs to test, the body by its place in ``rows``: every
    face it could meet this step (whatever it bounces off, its path stays within
    ``engine.geometry.face_looks.reach`` of where it started). ``resting``: the face each body rests
    on or -1, by World row, updated here for ``rows``. Contacts that begin and end are
    reported in ``began`` and ``ended`` (arrays of rows, colliders, points, normals,
    impulses, times). Returns the rows that met anything (struck, rested, slid or lifted
    off), their new positions and velocities, and how many bodies were capped.

    ``spin`` (engine.dynamics.rotation), when some of the bodies turn: they turn on each part of the
    path, freely in flight and by the rolling law on a face (engine.exact.resting), and a bounce's
    friction acts at the point of contact (``bounce``); their angles and angular velocities
    are written into ``spin`` for the rows returned. Bodies that do not turn are swept as
    without it, to the bit.
    """
    x0, v0, Bf, Wf, dt, t0 = paths.x0, paths.v0, paths.B, paths.W, paths.dt, paths.t0
    X, V = x0.take(rows, axis=0), v0.take(rows, axis=0)
    Bb, Wb = Bf.take(rows, axis=0), Wf.take(rows, axis=0)
    r, eb = paths.radius[rows], paths.restitution[rows]
    mub, m = paths.friction[rows], paths.mass[rows]
    rest = resting[rows]
    left = np.full(len(rows), dt)
    touched = np.zeros(len(rows), dtype=bool)
    active = np.arange(len(rows))
    slot = np.full(len(rows), -1, dtype=np.intp)  # row -> index among the active
    capped = 0
    turn = rolling(spin, rows, paths.friction)
    if turn is not None:
        TH = turn.angle.copy()
    for _ in range(MAX_IMPACTS):
        Xa, Va, ta = X[active], V[active], left[active]
        Bp, Wp, ra = Bb[active], Wb[active], rest[active]
        # The angular acceleration of the part (engine.exact.resting sets it for those that roll).
        Ap = turn.alpha[active] if turn is not None else np.zeros(0)
        slot[active] = np.arange(len(active))
        live = _live(faces, slot, pb, pf, rest)
        bi, fj = slot[pb[live]], pf[live]
        dur = ta.copy()
        stop = np.zeros(len(active), dtype=bool)
        ending = np.full(len(active), -1, dtype=np.int64)  # a slide's end: the face it goes on
        res = np.flatnonzero(ra >= 0)
        if len(res):
            lifted, edge = rest_paths(
                faces, res, active, Xa, Va, Bp, Wp, dur, ra, Wb, mub, r, stop,
                t0 + dt - ta, rows, ended, None if turn is None else (turn, Ap), ending,
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
            live = _live(faces, slot, pb, pf, rest)
            bi, fj = slot[pb[live]], pf[live]
        t_hit, face, normal = first_hits(faces, Xa, Va, Bp, dur, r[active], bi, fj, ra < 0)
        hit = t_hit <= dur
        tt = np.where(hit, t_hit, dur)
        tc = tt[:, None]
        Xn = Xa + Va * tc + Bp * (0.5 * tc * tc)
        Vn = Va + Wp * tc
        stopped = stop & ~hit
        halted = stopped
        if turn is not None:
            OMn = turn.omega[active] + Ap * tt
            THn = TH[active] + turn.omega[active] * tt + Ap * (0.5 * tt * tt)
            # A body that turns and stops slipping rolls on (engine.exact.resting).
            halted = stopped & ~turn.rolls[active]
        if halted.any():
            Vn[halted] = 0.0  # slid to a stop: exactly at rest
        h = np.flatnonzero(hit)
        done = np.zeros(len(active), dtype=bool)
        if len(h):
            done[h] = bounce(
                faces,
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
                rows,
                began,
                ended,
                None if turn is None else (turn, OMn),
            )
            touched[active[h]] = True
        ends = np.flatnonzero((ending >= 0) & ~hit)
        if len(ends):
            # Slid to its face's end: on around the end's round face (A slide's end).
            rest[active[ends]] = ending[ends]
        rs = np.flatnonzero(rest[active] >= 0)
        if len(rs):
            project(faces, rs, active, Xn, Vn, rest, r, Wb)
            # A body rolling over a round edge onto a flat side it now overlaps has left
            # the edge: it stands on the side and is in flight again (it settles there).
            L = len(faces.p)
            rolled = rs[rest[active[rs]] >= L]
            if len(rolled):
                Xr, Vr = Xn[rolled], Vn[rolled]
                moved = push_out(Xr, Vr, r[active[rolled]], rows[active[rolled]])
                Xn[rolled], Vn[rolled] = Xr, Vr
                rest[active[rolled[moved]]] = -1
        if turn is not None:
            roll_exactly(faces, turn, active, rest, Xn, Vn, OMn, r)
            turn.omega[active], TH[active] = OMn, THn
        X[active], V[active] = Xn, Vn
        more = (hit | stopped | (ending >= 0)) & ~done
        left[active] = np.where(more, ta - tt, 0.0)
        slot[active] = -1
        active = active[more & (ta - tt > 0.0)]
        if not len(active):
            break
    else:
        # Past the cap: the body stays where its last impact put it, on a surface, and
        # stops there for the rest of the step (it would only strike again and again).
        capped = len(active)
        V[active] = 0.0
        touched[active] = True
        Xt, Vt = X[active], V[active]
        push_out(Xt, Vt, r[active], rows[active])
        X[active], V[active] = Xt, Vt
    touched |= rest >= 0
    touched |= resting[rows] >= 0  # lifted off this step
    resting[rows] = rest
    t = np.flatnonzero(touched)
    if turn is not None and spin is not None:
        # Only the rows that turn under friction: the others keep their free spin.
        k = t[turn.rolls[t]]
        spin.angle[rows[k]], spin.omega[rows[k]] = TH[k], turn.omega[k]
    return rows[t], X[t], V[t], capped


def _live(
    faces: Faces, slot: np.ndarray, pb: np.ndarray, pf: np.ndarray, rest: np.ndarray
) -> np.ndarray:
    """The pairs (body, face) to test in a round: the body's still moving (``slot`` >= 0),
    the face not the one it rests on, nor that face's round ends (``Faces.ends``: the slide
    goes on around an end where it reaches it, "A slide's end")."""
    on = rest[pb]  # (-1: none, which ``Faces.ends``' last row lists as having no ends)
    ends = faces.ends[on]
    return np.flatnonzero((slot[pb] >= 0) & (pf != on) & (pf != ends[:, 0]) & (pf != ends[:, 1]))


def roll_exactly(
    faces: Faces,
    turn: Rolling,
    active: np.ndarray,
    rest: np.ndarray,
    Xn: np.ndarray,
    Vn: np.ndarray,
    OMn: np.ndarray,
    r: np.ndarray,
) -> None:
    """Bodies that turn and end a part of the step resting on a face with a slip speed s =
    u - omega r under 1e-9 of their speeds roll: omega = u / r exactly (in place on OMn),
    so rounding does not build up into a slip over many steps."""
    on = np.flatnonzero((rest[active] >= 0) & turn.rolls[active])
    if not len(on):
        return
    i = active[on]
    nrm, _ = face_normals(faces, rest[i], Xn[on])
    u = Vn[on, 1] * nrm[:, 0] - Vn[on, 0] * nrm[:, 1]  # along t = (-n_y, n_x)
    rim = OMn[on] * r[i]
    near = np.abs(u - rim) <= 1e-9 * (np.abs(u) + np.abs(rim))
    OMn[on[near]] = u[near] / r[i[near]]


def first_hits(
    faces: Faces,
    X: np.ndarray,
    V: np.ndarray,
    B: np.ndarray,
    T: np.ndarray,
    r: np.ndarray,
    bi: np.ndarray,
    fj: np.ndarray,
    free: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each body's first impact within its time T among the (body, face) pairs given:
    (time or inf, face, normal). X, V, B, T, r: the bodies' (one row each); (bi, fj): the
    pairs, each body by its row; ``free`` (one a body, None: all): the bodies on no face,
    whose straight paths only grazing a round face pass it (engine.geometry.impact.disc_hits'
    ``graze``)."""
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
        graze = True if free is None else free[db]
        t[disc] = disc_hits(X[db], V[db], B[db], faces.c[df], faces.r[df] + r[db], T[db], graze)
    # A solid polygon's face a ball is behind, and not least behind of its polygon's, is
    # none of its contacts (engine.geometry.faces.behind_solid).
    t[behind_solid(faces, X, bi, fj)] = np.inf
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


def bounce(
    faces: Faces,
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
    rows: np.ndarray,
    began: list[Any],
    ended: list[Any],
    turning: tuple[Rolling, np.ndarray] | None = None,
) -> np.ndarray:
    """Apply the impacts of the bodies ``active[h]`` (places among ``rows``; the arrays are
    ``sweep``'s), at the World's times ``when``: restitution, friction, rest.

    Returns which of them are wedged between two faces (at rest for the rest of the step).

    With the unit normal n: v_n' = -e v_n; the tangential speed loses up to mu (1 + e)
    |v_n| (the friction impulse is at most mu times the normal one), never reversing.
    A rebound slower than |a_n| dt / 2 (it would fly for less than one step) settles.

    ``turning``: (the bodies' spin, their angular velocities by active place, written here)
    when some turn. Friction then acts at the point of contact: it takes the slip speed
    s = u - omega r toward 0 (engine.dynamics.rotation: an impulse per mass du changes s by
    du (1 + q)), by at most mu (1 + e) |v_n| in u, so u' = u + du and omega' =
    omega - du q / r; a ball thrown spinning onto a floor leaves it rolling, or with the
    spin friction could not take out.
    """
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
    if turning is not None:
        turn, OMn = turning
        spun = np.flatnonzero(turn.rolls[i])
        if len(spun):
            k, ik = h[spun], i[spun]
            nk = n[spun]
            tang = np.stack([-nk[:, 1], nk[:, 0]], axis=1)
            u = dot(vel[spun], tang)
            q, rk = turn.q[ik], r[ik]
            cap = mu[spun] * (1.0 + e[spun]) * -vn_in[spun]  # the most friction takes off u
            du, OMn[k] = grip(u, OMn[k], q, rk, cap)
            new_v[spun] = tang * (u + du)[:, None] + nk * vn_out[spun][:, None]
    # A body resting on one face that hits another across it (a floor into a wall) stays
    # resting on the first; anything else that bounces is in flight.
    old = rest[i]
    was = old >= 0
    stays = np.zeros(len(h), dtype=bool)
    wedged = np.zeros(len(h), dtype=bool)
    if was.any():
        on, _ = face_normals(faces, np.where(was, old, 0), Xn[h])
        stays = was & (np.abs(dot(on, n)) < 1e-9)
        # Wedged: resting on face 1, settling on face 2, and the acceleration presses into
        # both: W = l1 n1 + l2 n2 with l1, l2 <= 0. The two faces then carry it all and
        # the body stays put for the rest of the step (the forces are constant within it).
        det = on[:, 0] * n[:, 1] - on[:, 1] * n[:, 0]
        w = Wb[i]
        safe = np.where(np.abs(det) > WEDGE_SIN, det, 1.0)
        l1 = (w[:, 0] * n[:, 1] - w[:, 1] * n[:, 0]) / safe
        l2 = (on[:, 0] * w[:, 1] - on[:, 1] * w[:, 0]) / safe
        # It settles there when the rebound is too slow to fly one step against the load
        # -l2 that face 2 would carry (as for one face, with l2 in place of a_n).
        slow = vn_out <= -l2 * (0.5 * dt)
        wedged = was & slow & (np.abs(det) > WEDGE_SIN) & (l1 <= 0.0) & (l2 <= 0.0)
        if wedged.any():
            new_v[wedged] = 0.0
    rest[i] = np.where(wedged | stays, old, np.where(settles, f, -1))
    point = Xn[h] - n * r[i][:, None]
    impulse = (new_v - vel) * m[i][:, None]
    # A touch with no speed into the face (a body sliding into a wedge it sits in) is
    # not reported: nothing struck.
    struck = vn_in < 0.0
    body = rows[i]
    owner = faces.owner[f]
    if struck.any():
        b = struck
        began.append((body[b], owner[b], point[b], n[b], impulse[b], when[h][b]))
        b = struck & ~settles
        if b.any():
            ended.append((body[b], owner[b], point[b], n[b], impulse[b], when[h][b]))
    Vn[h] = new_v
    return wedged
