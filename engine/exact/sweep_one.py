"""The one-body-at-a-time path: the static contacts of a few bodies in Python floats.

These are the same steps as the array code (engine.exact.sweep's ``sweep``, ``first_hits`` and
``bounce``; engine.exact.resting's ``asleep``, ``rest_paths`` and ``project``), for one body in
Python floats: ``_path_one`` is ``sweep``'s loop (with ``first_hits``' loop inline), and each
function ending in _one is its array twin line for line (same operations in the same order,
so the same bits), with an `if` where the array version computes both branches and picks with
np.where. tests/test_contacts_paths.py steps scenes both ways and compares every state and
event.

On a handful of bodies numpy's fixed cost per call (about a microsecond, a few hundred calls
per round of impacts) is most of the time; floats have none. Measured (2-core machine, the
contacts' own time): the Galton board's first 20 s 0.46 s in floats against 1.60 s in arrays,
breakout's ball 93 us a step it meets something against 438 us; eight balls resting in a box
check staying put (``asleep_few``) in half the time of the arrays. Contacts chooses by count
(``Contacts.few``, ``Contacts.few_resting``).

On the fast path (engine.kernels) the free bodies go through ``paths_loop``
(engine.exact.sweep_paths, beside this module), a loop kernel
of ``_path_one``'s arithmetic for a body that bounces and flies on (compiled by numba: about
1 us a body, against ~10 in floats); a body that rests, comes to rest, is capped or meets a
round face's quartic (whose eigenvalues are numpy's LAPACK) is left to ``_path_one``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..dynamics.rotation import Rolling, Spin, rolling
from ..geometry.faces import Faces
from ..geometry.impact import Pair, disc_hit_one, line_hit_one, quadratic_first_root_one
from .sweep import MAX_IMPACTS, WEDGE_SIN, Paths, PushOut
from .sweep_paths import MET, MISSED, PYTHON, paths_loop

__all__ = ["asleep_few", "solve_few"]


def asleep_few(
    faces: Faces,
    rest: np.ndarray,
    res: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    W: np.ndarray,
    friction: np.ndarray,
) -> np.ndarray:
    """``engine.exact.resting.asleep`` for a few rows, in Python floats (the same operations, so
    the same answer): a dozen array calls cost more than these few rows' arithmetic."""
    rows = res.tolist()
    V = v0.take(res, axis=0).tolist()
    X = x0.take(res, axis=0).tolist()
    Wl = W.take(res, axis=0).tolist()
    mub = friction.take(res).tolist()
    f_of = rest.take(res).tolist()
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


def solve_few(
    faces: Faces,
    paths: Paths,
    rows: np.ndarray,
    pb: np.ndarray,
    pf: np.ndarray,
    resting: np.ndarray,
    push_out: PushOut,
    began: list[Any],
    ended: list[Any],
    fast: bool = False,
    spin: Spin | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """``engine.exact.sweep.sweep``, one body after another in Python floats (for a few rows): the
    same arguments and results (``spin`` too: the bodies that turn under friction have
    their angle and angular velocity written there). ``fast``: the free bodies go through
    the loop kernel ``paths_loop`` first (the same bits), the rest through ``_path_one``."""
    spins = rolling(spin, rows, paths.friction)
    if fast:
        return _solve_fast(faces, paths, rows, pb, pf, resting, push_out, began, ended, spin, spins)
    x0, v0, Bf, Wf, dt, t0 = paths.x0, paths.v0, paths.B, paths.W, paths.dt, paths.t0
    faces_of: list[list[int]] = [[] for _ in range(len(rows))]
    for b, f in zip(pb.tolist(), pf.tolist(), strict=True):
        faces_of[b].append(f)
    X = x0.take(rows, axis=0).tolist()
    V = v0.take(rows, axis=0).tolist()
    Bl = Bf.take(rows, axis=0).tolist()
    Wl = Bl if Wf is Bf else Wf.take(rows, axis=0).tolist()
    r, e = paths.radius.take(rows).tolist(), paths.restitution.take(rows).tolist()
    mu, m = paths.friction.take(rows).tolist(), paths.mass.take(rows).tolist()
    rest = resting.take(rows).tolist()
    row_list = rows.tolist()
    # Events with a key (round, phase, place) that puts them in sweep's order: round by
    # round, lift-offs before impacts, bodies in row order.
    began_keyed: list[tuple[tuple[int, int, int], tuple[Any, ...]]] = []
    ended_keyed: list[tuple[tuple[int, int, int], tuple[Any, ...]]] = []
    capped = 0
    changed: list[int] = []
    Xc: list[float] = []
    Vc: list[float] = []
    for k, row in enumerate(row_list):
        turn = None if spins is None else spins.one(k)
        x, v, touched, rest_k, cap, turned = _path_one(
            faces, k, row, X[k], V[k], Bl[k], Wl[k], r[k], e[k], mu[k], m[k], rest[k],
            faces_of[k], dt, t0, began_keyed, ended_keyed, push_out, turn,
        )  # fmt: skip
        capped += cap
        if touched:
            changed.append(row)
            Xc += x  # flat: one np.array of floats is cheaper than one of pairs
            Vc += v
            resting[row] = rest_k
            if turned is not None and spin is not None:
                spin.angle[row], spin.omega[row] = turned
    _keep_events(began, ended, began_keyed, ended_keyed)
    shape = (len(changed), 2)
    return (
        np.array(changed, dtype=np.intp),
        np.array(Xc, dtype=float).reshape(shape),
        np.array(Vc, dtype=float).reshape(shape),
        capped,
    )


Keyed = list[tuple[tuple[int, int, int], tuple[Any, ...]]]
#: A body that turns under friction, for ``_path_one``: (angle, angular velocity, q = m r^2 /
#: I, own angular acceleration) at the step's start (engine.dynamics.rotation).
SpinOne = tuple[float, float, float, float]


def _keep_events(
    began: list[Any], ended: list[Any], began_keyed: Keyed, ended_keyed: Keyed
) -> None:
    """Put the keyed events in sweep's order, each list as one batch of columns."""
    for where, events in ((began, began_keyed), (ended, ended_keyed)):
        if events:
            events.sort()  # by key: each (round, phase, place) holds one event
            where.append(tuple(zip(*[ev for _, ev in events], strict=True)))


def _solve_fast(
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
    spins: Rolling | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """``solve_few`` on the fast path: the loop kernel ``paths_loop`` for the free bodies,
    ``_path_one`` for those it leaves (the same results, in the same order)."""
    status, X, V, kev, start, flat, TH, OM = _paths_fast(faces, paths, rows, pb, pf, resting, spins)
    began_keyed: Keyed = []
    ended_keyed: Keyed = []
    row_list = rows.tolist()
    # The kernel's impacts, each begun and ended at once (``_bounce_one``'s reports).
    owner = faces.owner_list
    for k, rnd, f, px, py, nx, ny, ix, iy, when in kev.tolist():
        k, rnd, f = int(k), int(rnd), int(f)
        event = (row_list[k], owner[f], (px, py), (nx, ny), (ix, iy), when)
        began_keyed.append(((rnd, 1, k), event))
        ended_keyed.append(((rnd, 1, k), event))
    capped = 0
    left = np.flatnonzero(status == PYTHON)
    if len(left):
        # The bodies the kernel left, in Python floats (their places k among the rows kept).
        sub = rows.take(left)
        Xl = paths.x0.take(sub, axis=0).tolist()
        Vl = paths.v0.take(sub, axis=0).tolist()
        Bl = paths.B.take(sub, axis=0).tolist()
        Wl = Bl if paths.W is paths.B else paths.W.take(sub, axis=0).tolist()
        r, e = paths.radius.take(sub).tolist(), paths.restitution.take(sub).tolist()
        mu, m = paths.friction.take(sub).tolist(), paths.mass.take(sub).tolist()
        rest = resting.take(sub).tolist()
        bounds = start.tolist()
        for i, k in enumerate(left.tolist()):
            row = row_list[k]
            x, v, touched, rest_k, cap, turned = _path_one(
                faces, k, row, Xl[i], Vl[i], Bl[i], Wl[i], r[i], e[i], mu[i], m[i], rest[i],
                flat[bounds[k] : bounds[k + 1]].tolist(), paths.dt, paths.t0, began_keyed,
                ended_keyed, push_out, None if spins is None else spins.one(k),
            )  # fmt: skip
            capped += cap
            status[k] = MET if touched else MISSED
            if touched:
                X[k], V[k] = x, v
                resting[row] = rest_k
                if turned is not None:
                    TH[k], OM[k] = turned
    _keep_events(began, ended, began_keyed, ended_keyed)
    met = np.flatnonzero(status == MET)
    changed = rows.take(met)
    if spins is not None and spin is not None:
        turned = met[spins.rolls[met]]
        spin.angle[rows[turned]], spin.omega[rows[turned]] = TH[turned], OM[turned]
    return changed, X.take(met, axis=0), V.take(met, axis=0), capped


def _paths_fast(
    faces: Faces,
    paths: Paths,
    rows: np.ndarray,
    pb: np.ndarray,
    pf: np.ndarray,
    resting: np.ndarray,
    spins: Rolling | None = None,
) -> tuple[np.ndarray, ...]:
    """``paths_loop``'s (status, x, v, impacts) for ``rows``, each row's faces in pair
    order, ``flat[start[k]:start[k + 1]]`` (start, flat), and the angles and angular
    velocities of those that turn under friction (``spins``, by place among the rows)."""
    none = np.zeros(1)
    th, om, q, al, rolls = (none, none, none, none, none == 1.0) if spins is None else spins
    spoly, sstart, sflat = faces.solid
    return paths_loop(  # type: ignore[no-any-return]
        faces.p, faces.n, faces.rho, faces.two, faces.lo, faces.hi, spoly, sstart, sflat,
        faces.c, faces.r,
        faces.e, faces.mu, rows, paths.x0, paths.v0, paths.B, paths.W, paths.radius,
        paths.restitution, paths.friction, paths.mass, resting,
        # C arrays (np.nonzero's are strided views): the kernel's one specialisation.
        np.ascontiguousarray(pb), np.ascontiguousarray(pf), paths.dt, paths.t0,
        spins is not None, th, om, q, al, rolls,
    )  # fmt: skip


def _path_one(
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
    push_out: PushOut,
    turn: SpinOne | None = None,
) -> tuple[Pair, Pair, bool, int, bool, tuple[float, float] | None]:
    """One body through its step, impact by impact (sweep's loop for one row ``row``,
    ``k`` its place among the rows solved): (x, v, whether it met anything, its rest,
    whether it was capped, and for a body that turns under friction (``turn``) its angle
    and angular velocity at the end, else None)."""
    line_list, disc_list = faces.line_list, faces.disc_list
    L = len(line_list)
    solid = faces.solid if faces.polygons else None
    rest_before = rest
    touched = capped = False
    left = dt
    th = om = q = al = 0.0
    if turn is not None:
        th, om, q, al = turn
    for round_ in range(MAX_IMPACTS):
        ta = left
        vp, bp, wp = v, b, w  # this round's path (a resting body slides along its face)
        ap = al  # its angular acceleration (a rolling body's from the rolling law)
        dur = ta
        stop = False
        ending = -1  # a slide's end: the round face it goes on around (sweep)
        if rest >= 0:
            slide = _rest_path_one(faces, rest, x, v, w, mu, r, (om, q, al) if turn else None)
            if slide is False:  # over a round edge: flown on W (as in sweep)
                b = bp = w
            if slide is None or slide is False:  # lifts off
                nx, ny, _ = _normal_one(faces, rest, x)
                point = (x[0] - nx * r, x[1] - ny * r)
                event = (row, faces.owner_list[rest], point, (nx, ny), (0.0, 0.0))
                ended.append(((round_, 0, k), (*event, t0 + dt - ta)))
                rest = -1
            else:
                assert not isinstance(slide, bool)
                vp, bp, ts, ap = slide
                wp = bp
                te, end = _slide_end_one(faces, rest, x, vp, bp, dur)
                if te < ts and te <= dur:
                    dur, ending = te, end
                elif ts < dur:
                    dur, stop = ts, True
        # engine.exact.sweep.first_hits for this body (inlined: the innermost loop of a step): the
        # earliest impact among its faces (ties: the last listed), and its normal; not the face
        # it rests on, nor that face's round ends (sweep's ``_live``).
        e0, e1 = faces.ends_list[rest] if 0 <= rest < L else (-2, -2)
        t_hit, face, normal = math.inf, -1, (0.0, 0.0)
        for f in faces_of:
            if f == rest or f == e0 or f == e1:
                continue
            if f < L:
                if solid is not None and _behind_solid_one(faces, solid, f, x):
                    continue  # (engine.geometry.faces.behind_solid: no contact of it)
                p, n, rho, two, lo, hi = line_list[f]
                t, nrm = line_hit_one(x, vp, bp, p, n, rho + r, two, lo, hi, dur)
            else:
                c, rho = disc_list[f - L]
                t, nrm = disc_hit_one(x, vp, bp, c, rho + r, dur, rest < 0), (0.0, 0.0)
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
        if turn is not None:
            om_n = om + ap * tt
            th_n = th + om * tt + ap * (0.5 * tt * tt)
        if stopped and turn is None:
            vn = (0.0, 0.0)  # slid to a stop: exactly at rest (one that turns rolls on)
        done = False
        if hit:
            when = t0 + dt - ta + t_hit
            vn, rest, done, om_n = _bounce_one(
                faces, k, row, round_, xn, vn, face, normal, rest, w, r, e, mu, m, dt, when,
                began, ended, (om_n, q) if turn is not None else None,
            )  # fmt: skip
            touched = True
        if ending >= 0 and not hit:
            rest = ending  # slid to its face's end: on around its round end (sweep)
        if rest >= 0:
            xn, vn = _project_one(faces, rest, xn, vn, r, w)
            if rest >= L:  # rolled over a round edge onto a flat side it overlaps?
                Xr, Vr = np.array([xn]), np.array([vn])
                if push_out(Xr, Vr, np.array([r]), np.array([row]))[0]:
                    rest = -1
                xn, vn = (float(Xr[0, 0]), float(Xr[0, 1])), (float(Vr[0, 0]), float(Vr[0, 1]))
        if turn is not None:
            if rest >= 0:  # engine.exact.sweep.roll_exactly
                nx, ny, _ = _normal_one(faces, rest, xn)
                u = vn[1] * nx - vn[0] * ny
                rim = om_n * r
                if abs(u - rim) <= 1e-9 * (abs(u) + abs(rim)):
                    om_n = u / r
            th, om = th_n, om_n
        x, v = xn, vn
        more = (hit or stopped or ending >= 0) and not done
        left = ta - tt if more else 0.0
        if not (more and ta - tt > 0.0):
            break
    else:
        # Past the cap: it stops where its last impact put it, on a surface (as sweep).
        capped = True
        touched = True
        Xt, Vt = np.array([x]), np.zeros((1, 2))
        push_out(Xt, Vt, np.array([r]), np.array([row]))
        x, v = (float(Xt[0, 0]), float(Xt[0, 1])), (float(Vt[0, 0]), float(Vt[0, 1]))
    turned = None if turn is None else (th, om)
    return x, v, touched or rest >= 0 or rest_before >= 0, rest, capped, turned


def _behind_solid_one(faces: Faces, solid: tuple[np.ndarray, ...], f: int, x: Pair) -> bool:
    """``engine.geometry.faces.behind_solid`` for one body at x and one flat face f (the same
    operations): a solid polygon's face it is behind, not least behind of its polygon's."""
    poly, start, flat = solid
    k = int(poly[f])
    if k < 0:
        return False
    P, N = faces.p, faces.n
    d0 = (x[0] - P[f, 0]) * N[f, 0] + (x[1] - P[f, 1]) * N[f, 1]
    if not d0 < 0.0:
        return False
    best = -math.inf
    for g in flat[start[k] : start[k + 1]].tolist():
        d = (x[0] - P[g, 0]) * N[g, 0] + (x[1] - P[g, 1]) * N[g, 1]
        best = d if d > best else best
    return bool(d0 < best - 1e-9 * (1.0 + abs(best)))


def _normal_one(faces: Faces, f: int, x: Pair) -> tuple[float, float, float]:
    """``engine.geometry.faces.face_normals`` for one face and point: (n_x, n_y, 1 / radius or 0 if
    flat)."""
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
    faces: Faces,
    f: int,
    x: Pair,
    v: Pair,
    w: Pair,
    mub: float,
    r: float = 0.0,
    turn: tuple[float, float, float] | None = None,
) -> tuple[Pair, Pair, float, float] | bool | None:
    """``engine.exact.resting.rest_paths`` for one body resting on face f: None if it lifts off
    (False if over a round edge faster than it can turn it), else its sliding path (velocity,
    acceleration along the face, time it stops or inf, angular acceleration). ``turn``:
    (angular velocity, q, own angular acceleration) of a body of radius ``r`` that turns
    under friction: the rolling law."""
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
    if turn is not None:
        om, q, al0 = turn
        sl = u - om * r
        gs = a_t - al0 * r
        tol = 1e-12 * (abs(u) + abs(om * r))
        if sl > tol:
            fric = -fr
        elif sl < -tol:
            fric = fr
        elif abs(gs) <= fr * (1.0 + q) * (1.0 + 1e-12):  # it can roll
            fric = -gs / (1.0 + q)
        else:
            fric = -math.copysign(fr, gs)
        ds = gs + fric * (1.0 + q)
        slows = (sl > tol and ds < 0.0) or (sl < -tol and ds > 0.0)
        ts = -sl / (ds if ds != 0.0 else 1.0) if slows else math.inf
        a = a_t + fric
        return (tx * u, ty * u), (tx * a, ty * a), ts, al0 - fric * q / r
    slowing = (u > 0.0 and a < 0.0) or (u < 0.0 and a > 0.0)
    ts = -u / a if slowing else math.inf
    return (tx * u, ty * u), (tx * a, ty * a), ts, 0.0


def _slide_end_one(
    faces: Faces, f: int, x: Pair, vp: Pair, bp: Pair, dur: float
) -> tuple[float, int]:
    """``engine.exact.resting.rest_paths``' slide's end for one body sliding on flat face f
    from x (velocity vp, acceleration bp along it): (the moment its point of contact reaches
    an end of the face within ``dur``, the round face there), or (inf, -1) (a round face f,
    or a flat one with no round ends)."""
    if f >= len(faces.line_list):
        return math.inf, -1
    e0, e1 = faces.ends_list[f]
    if e0 < 0 or e1 < 0:
        return math.inf, -1
    p, n, _, _, lo, hi = faces.line_list[f]
    t0x, t0y = -n[1], n[0]
    pos = (x[0] - p[0]) * t0x + (x[1] - p[1]) * t0y
    w_t = vp[0] * t0x + vp[1] * t0y
    b_t = bp[0] * t0x + bp[1] * t0y
    to_hi = quadratic_first_root_one(hi - pos, -w_t, -0.5 * b_t, dur)
    to_lo = quadratic_first_root_one(pos - lo, w_t, 0.5 * b_t, dur)
    return (to_hi, e1) if to_hi <= to_lo else (to_lo, e0)


def _disc_normal_one(c: Pair, x: Pair, v: Pair, b: Pair, t: float) -> Pair:
    """The normal of a round face (centre c) at an impact at time t: from the centre to where
    the ball's centre is then (``engine.exact.sweep.first_hits``', for one body)."""
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
    turn: tuple[float, float] | None = None,
) -> tuple[Pair, int, bool, float]:
    """``engine.exact.sweep.bounce`` for one body: (new velocity, face it rests on or -1, wedged,
    angular velocity). ``turn``: (angular velocity, q) of a body that turns under friction:
    friction acts at the point of contact."""
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
    om = 0.0
    if turn is not None:
        om, q = turn
        u = vx * -ny + vy * nx
        slip = u - om * r
        cap = mu * (1.0 + e) * -vn_in
        du = -math.copysign(min(abs(slip) / (1.0 + q), cap), slip)
        new_v = (-ny * (u + du) + nx * vn_out, nx * (u + du) + ny * vn_out)
        om = om - du * q / r
    stays = wedged = False
    if old >= 0:
        onx, ony, _ = _normal_one(faces, old, x)
        stays = abs(onx * nx + ony * ny) < 1e-9
        det = onx * ny - ony * nx
        safe = det if abs(det) > WEDGE_SIN else 1.0
        l1 = (wx * ny - wy * nx) / safe
        l2 = (onx * wy - ony * wx) / safe
        slow = vn_out <= -l2 * (0.5 * dt)
        wedged = slow and abs(det) > WEDGE_SIN and l1 <= 0.0 and l2 <= 0.0
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
    return new_v, rest, wedged, om


def _project_one(faces: Faces, f: int, x: Pair, vel: Pair, r: float, w: Pair) -> tuple[Pair, Pair]:
    """``engine.exact.resting.project`` for one body resting on face f: (position, velocity)."""
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
    # The pull's work from the tangent to the arc (``project``): |v|^2 gains 2 W.dx.
    # A body at rest keeps none (``project``).
    gain = 2.0 * (w[0] * (x_on[0] - x[0]) + w[1] * (x_on[1] - x[1]))
    x = x_on
    v2 = vel[0] * vel[0] + vel[1] * vel[1]
    speed = math.sqrt(max(v2 + gain, 0.0)) if v2 != 0.0 else 0.0
    sign = 1.0 if vel[0] * tx + vel[1] * ty >= 0.0 else -1.0
    return x, (tx * (sign * speed), ty * (sign * speed))
