"""Resting on a face: staying put, sliding under friction, lifting off, following an arc.

Rest: a rebound too slow to fly for one step (normal speed below |a_n| dt / 2, where a_n is
the acceleration pressing the body onto the surface) ends in rest (engine.exact.sweep): the body's
centre is put at exactly its radius from the surface (``project``), the surface takes the
pressing part of its acceleration, and it slides along the surface under the tangential part,
slowed by friction mu |a_n| until it stops, at the exact moment the closed form gives, and
stays stopped while the tangential pull is at most mu |a_n| (Coulomb: static on a slope of
tan(theta) <= mu; ``asleep``). It lifts off when pulled away from the surface, when its
velocity is set to leave it, or when it goes over a round edge faster than the edge can turn
it (v^2 / rho > |a_n|; ``rest_paths``).

The resting bodies' state is ``rest``, by World row: the face each rests on (an index into
engine.geometry.faces' arrays), -1 for a body in flight.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..geometry.faces import Faces, dot, face_normals
from ..geometry.impact import quadratic_first_root

__all__ = ["asleep", "project", "rest_paths"]


def asleep(
    faces: Faces,
    rest: np.ndarray,
    res: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    W: np.ndarray,
    friction: np.ndarray,
) -> np.ndarray:
    """Resting rows that stay exactly where they are this step: still (v = 0), pressed
    onto their face (a_n <= 0) and held by static friction (|a_t| <= mu |a_n|). ``rest``:
    the face each body rests on, by World row; ``res``: the resting rows (World rows)."""
    still = res[(v0[res, 0] == 0.0) & (v0[res, 1] == 0.0)]
    if not len(still):
        return still
    f = rest[still]
    nrm, _ = face_normals(faces, f, x0[still])
    w = W[still]
    a_n = dot(w, nrm)
    a_t = w[:, 1] * nrm[:, 0] - w[:, 0] * nrm[:, 1]  # along the tangent (-n_y, n_x)
    held = np.abs(a_t) <= friction[still] * faces.mu[f] * -a_n * (1.0 + 1e-12)
    return still[(a_n <= 0.0) & held]


def rest_paths(
    faces: Faces,
    res: np.ndarray,
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
    rows: np.ndarray,
    ended: list[Any],
    turning: tuple[Any, np.ndarray] | None = None,
    ending: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Set the sliding path of resting bodies (local ``res``); return those that lift off,
    and those of them that went over a round edge faster than it can turn them.

    The arrays are engine.exact.sweep's (``sweep``: ``active`` the places among ``rows`` of the
    bodies still moving, ``Xa`` ... ``dur`` and ``stop`` theirs, set here for the resting
    ones; ``Wb``, ``mub`` and ``r`` by place among ``rows``). A lift-off ends the body's
    contact: it is reported in ``ended`` (World ``rows``), at time ``when``.

    A slide that reaches the end of its flat face within ``dur`` (before it stops) ends
    there: ``dur`` is set to that moment and ``ending`` (by active place; -1 where none) to
    the round face the body goes on around (``Faces.ends``; sweep's "A slide's end").

    Along the surface the motion is one-dimensional: speed u along the tangent, pull a_t,
    and friction mu |a_n| against the motion. While sliding, u' = a_t - sign(u) mu |a_n|;
    the stop comes at t_s = -u / u' (exactly, by the closed form); at rest the body stays
    while |a_t| <= mu |a_n| and else starts sliding at a_t - sign(a_t) mu |a_n|.

    ``turning``: (engine.dynamics.rotation's ``Rolling`` by place among ``rows``, the angular
    acceleration of the part by active place, set here) when some bodies turn. A disc that
    turns, with q = m r^2 / I, own angular acceleration alpha0 and slip speed
    s = u - omega r (engine.dynamics.rotation), takes the friction f (per mass, along the tangent):

    * rolling (s = 0), while it can: f = -(a_t - alpha0 r) / (1 + q), which keeps s' = 0,
      so u' = a_t + f (a = g sin(theta) q / (1 + q) down a slope: 2/3 of it for a disc);
    * slipping: f = -sign(s) mu |a_n| (or, from rolling, -sign(a_t - alpha0 r) mu |a_n|
      when rolling would need more than that), until s reaches 0 at t_s = -s / s' with
      s' = a_t - alpha0 r + f (1 + q); it rolls from there;

    and omega' = alpha0 - f q / r. All of it is constant over the part: the closed form.
    """
    L = len(faces.p)
    i = active[res]
    f = ra[res]
    x, vel, w = Xa[res], Va[res], Wb[i]
    nrm, curve = face_normals(faces, f, x)
    tang = np.stack([-nrm[:, 1], nrm[:, 0]], axis=1)
    a_n = dot(w, nrm)
    v_n = dot(vel, nrm)
    u = dot(vel, tang)
    off_end = np.zeros(len(res), dtype=bool)
    line = f < L
    if line.any():
        fl = np.where(line, f, 0)
        t0 = np.stack([-faces.n[fl, 1], faces.n[fl, 0]], axis=1)
        pos = dot(x - faces.p[fl], t0)
        off_end = line & ((pos < faces.lo[fl]) | (pos > faces.hi[fl]))
    over = u * u * curve + a_n > 0.0  # faster than the edge can turn it
    lift = (a_n > 0.0) | (v_n > 1e-9) | off_end | over
    edge = lift & over & ~((a_n > 0.0) | (v_n > 1e-9) | off_end)
    if lift.any():
        for k in np.flatnonzero(lift):
            _report(
                ended,
                rows,
                faces,
                int(i[k]),
                int(f[k]),
                x[k] - nrm[k] * r[i[k]],
                nrm[k],
                np.zeros(2),
                float(when[res[k]]),
            )
    a_t = dot(w, tang)
    fr = mub[i] * faces.mu[f] * np.maximum(-a_n, 0.0)  # mu times the pressure per mass
    static = np.abs(a_t) <= fr * (1.0 + 1e-12)
    a = np.where(
        u > 0.0,
        a_t - fr,
        np.where(u < 0.0, a_t + fr, np.where(static, 0.0, a_t - np.copysign(fr, a_t))),
    )
    slowing = ((u > 0.0) & (a < 0.0)) | ((u < 0.0) & (a > 0.0))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # a subnormal a: inf
        ts = np.where(slowing, -u / np.where(a != 0.0, a, 1.0), np.inf)
    keep = ~lift
    if turning is not None:
        turn, Ap = turning
        spun = turn.rolls[i]
        if spun.any():
            # The rolling law (docstring), for the bodies that turn.
            q, rr = turn.q[i], r[i]
            om, al0 = turn.omega[i], turn.alpha[i]
            s = u - om * rr
            gs = a_t - al0 * rr
            tol = 1e-12 * (np.abs(u) + np.abs(om * rr))
            can_roll = np.abs(gs) <= fr * (1.0 + q) * (1.0 + 1e-12)
            f = np.where(
                s > tol,
                -fr,
                np.where(s < -tol, fr, np.where(can_roll, -gs / (1.0 + q), -np.copysign(fr, gs))),
            )
            ds = gs + f * (1.0 + q)
            slows = ((s > tol) & (ds < 0.0)) | ((s < -tol) & (ds > 0.0))
            with np.errstate(divide="ignore", invalid="ignore"):
                ts_turn = np.where(slows, -s / np.where(ds != 0.0, ds, 1.0), np.inf)
            a = np.where(spun, a_t + f, a)
            ts = np.where(spun, ts_turn, ts)
            turned = spun & keep
            with np.errstate(divide="ignore", invalid="ignore"):
                Ap[res[turned]] = (al0 - f * q / rr)[turned]
    k = res[keep]
    Va[k] = tang[keep] * u[keep][:, None]
    Bp[k] = Wp[k] = tang[keep] * a[keep][:, None]
    stops = keep & (ts < dur[res])
    if ending is not None and line.any():
        # The slide's end (engine.exact.sweep, "A slide's end"): where the point of contact,
        # pos + w t + b t^2 / 2 along the face's tangent t0 (w, b: the slide's speed and pull
        # along it), reaches hi or lo: the first root of hi - pos(t) or pos(t) - lo in the
        # part, a simple one. Before the body would stop there, it ends the part.
        ends = faces.ends[fl]
        w_t = dot(tang * u[:, None], t0)
        b_t = dot(tang * a[:, None], t0)
        rounded = line & keep & (ends[:, 0] >= 0) & (ends[:, 1] >= 0)  # (both ends round)
        T = dur[res]
        with np.errstate(invalid="ignore", over="ignore"):
            to_hi = quadratic_first_root(
                np.where(rounded, faces.hi[fl] - pos, 1.0), -w_t, -0.5 * b_t, T
            )
            to_lo = quadratic_first_root(
                np.where(rounded, pos - faces.lo[fl], 1.0), w_t, 0.5 * b_t, T
            )
        high = to_hi <= to_lo
        te = np.where(high, to_hi, to_lo)
        off = rounded & (te < ts) & (te <= T)
        if off.any():
            stops &= ~off
            dur[res[off]] = te[off]
            ending[res[off]] = np.where(high, ends[:, 1], ends[:, 0])[off]
    dur[res[stops]] = ts[stops]
    stop[res[stops]] = True
    return res[lift], res[edge]


def project(
    faces: Faces,
    rs: np.ndarray,
    active: np.ndarray,
    Xn: np.ndarray,
    Vn: np.ndarray,
    rest: np.ndarray,
    r: np.ndarray,
    Wb: np.ndarray,
) -> None:
    """Put resting bodies exactly at contact distance; turn velocity along a round face.

    On a round face the round's path ran along the tangent (``rest_paths``) and is put
    back on the arc here, at the same speed plus the pull's work over that move: with
    the pull W constant, |v|^2 gains 2 W.dx (the surface's push does no work), so a ball
    going over a peg keeps the energy it has on the arc, and leaves the peg where the
    closed form says, within a step."""
    L = len(faces.p)
    i = active[rs]
    f = rest[i]
    x, vel = Xn[rs], Vn[rs]
    nrm, _ = face_normals(faces, f, x)
    line = f < L
    fl = np.where(line, f, 0)
    fd = np.where(line, 0, f - L)
    if L:
        gap = dot(x - faces.p[fl], nrm) - faces.rho[fl] - r[i]
        x_line = x - nrm * gap[:, None]
    else:
        x_line = x
    gain: Any = 0.0
    if len(faces.c):
        x_disc = faces.c[fd] + nrm * (faces.r[fd] + r[i])[:, None]
        gain = 2.0 * dot(Wb[i], x_disc - x)
        x = np.where(line[:, None], x_line, x_disc)
    else:
        x = x_line
    vn = dot(vel, nrm)
    v_flat = vel - nrm * vn[:, None]
    tang = np.stack([-nrm[:, 1], nrm[:, 0]], axis=1)
    # A body at rest (slid to a stop, or wedged between two faces: its velocity exactly 0)
    # keeps none: the move is the rounding of its place on the arc, not a path it ran (its
    # work is rounding's size, and its root far larger: a stopped ball was kicked at
    # 1e-7 m/s, and at 0.05 m/s up a peg, along whichever tangent a zero's sign picks).
    v2 = dot(vel, vel)
    speed = np.where(v2 != 0.0, np.sqrt(np.maximum(v2 + gain, 0.0)), 0.0)
    sign = np.where(dot(vel, tang) >= 0.0, 1.0, -1.0)
    v_round = tang * (sign * speed)[:, None]
    Xn[rs] = x
    Vn[rs] = np.where(line[:, None], v_flat, v_round)


def _report(
    where: list[Any],
    rows: np.ndarray,
    faces: Faces,
    local: int,
    f: int,
    point: Any,
    normal: Any,
    impulse: Any,
    when: float,
) -> None:
    """Report one contact of the body in place ``local`` of ``rows`` with face f, as the
    solvers' reports are kept: arrays of (rows, colliders, points, normals, impulses, times)."""
    where.append(
        (
            rows[[local]],
            faces.owner[[f]],
            np.asarray(point, float)[None, :],
            np.asarray(normal, float)[None, :],
            np.asarray(impulse, float)[None, :],
            np.array([when]),
        )
    )
