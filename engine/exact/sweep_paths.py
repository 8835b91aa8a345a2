"""The free bodies' paths in one compiled loop: ``paths_loop``, the fast path's kernel of
engine.exact.sweep_one's ``_path_one`` (a body that bounces off faces and flies on).

The same operations as ``_path_one`` in the same order (``line_hit_one``, ``disc_hit_one``
up to its roots, ``_disc_normal_one`` and ``_bounce_one`` inline), so the same bits; a body
that rests, comes to rest, is capped or needs a quartic's roots is left to ``_path_one``.
Without numba it runs as plain Python (engine.kernels), as its twin tests do.
"""

from __future__ import annotations

import math

import numpy as np

from .. import kernels
from ..geometry.impact import TOUCH
from .sweep import MAX_IMPACTS

__all__ = ["MISSED", "MET", "PYTHON", "paths_loop"]

#: A body's status from ``paths_loop``: met nothing, met something (its new state given), or
#: left to ``_path_one`` (it rests, settles, needs a root of a quartic, or is capped).
MISSED, MET, PYTHON = 0, 1, 2


def _sample_paths() -> tuple[object, ...]:
    """The smallest call of ``paths_loop``: one ball falling onto one floor line."""
    one = np.ones(1)
    pair = np.array([[0.0, 0.0]])
    i = np.zeros(1, dtype=np.intp)
    line = (pair, np.array([[0.0, 1.0]]), 0.0 * one, i == 0, -one, one, i - 1, i[:1] * 0, i[:0])
    return (
        *line, np.zeros((0, 2)), np.zeros(0), one, one, i, np.array([[0.0, 0.1]]), pair,
        np.array([[0.0, -9.81]]), np.array([[0.0, -9.81]]), 0.1 * one, one, one, one, i - 1,
        i, i, 0.01, 0.0, True, 0.0 * one, one, 2.0 * one, 0.0 * one, i == 0,
    )  # fmt: skip


@kernels.loop(sample=_sample_paths)
def paths_loop(
    lp: np.ndarray,
    ln: np.ndarray,
    lrho: np.ndarray,
    ltwo: np.ndarray,
    llo: np.ndarray,
    lhi: np.ndarray,
    spoly: np.ndarray,
    sstart: np.ndarray,
    sflat: np.ndarray,
    dc: np.ndarray,
    dr: np.ndarray,
    fe: np.ndarray,
    fmu: np.ndarray,
    rows: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    Bm: np.ndarray,
    Wm: np.ndarray,
    r: np.ndarray,
    eb: np.ndarray,
    mub: np.ndarray,
    m: np.ndarray,
    rest: np.ndarray,
    pb: np.ndarray,
    pf: np.ndarray,
    dt: float,
    t0: float,
    spun: bool,
    th0: np.ndarray,
    om0: np.ndarray,
    sqm: np.ndarray,
    sal: np.ndarray,
    srolls: np.ndarray,
) -> tuple[np.ndarray, ...]:
    """``_path_one`` for each free body that bounces off faces and flies on: (status, new
    positions, new velocities, its impacts: k, round, face, point, normal, impulse, time;
    each body's faces, ``flat[start[k]:start[k + 1]]``, for ``_path_one``; and the angles
    and angular velocities of the bodies that turn under friction).

    ``spun``: whether any does; then by place among the rows, each one's angle, angular
    velocity, q = m r^2 / I and own angular acceleration at the start (``th0``, ``om0``,
    ``sqm``, ``sal``) and whether it turns under friction (``srolls``): ``_path_one``'s
    ``turn``.

    The faces as ``Faces`` holds them (lines p, n, rho, two, lo, hi; the solid polygons'
    faces as ``Faces.solid`` holds them; discs c, r; e, mu), the
    World ``rows`` solved, the bodies' arrays by World row (x, v, B, W, radius, restitution,
    friction, mass, resting face), and the pairs (place in rows ``pb``, face ``pf``). A
    body that rests or comes to rest, meets a round face's quartic (its eigenvalues are
    LAPACK's, in numpy) or is capped is left to ``_path_one`` (status PYTHON). Each number
    is ``_path_one``'s own operations in their order (``line_hit_one``, ``disc_hit_one`` up
    to its roots, ``_disc_normal_one`` and ``_bounce_one`` inline), so the bits are its.
    """
    K = rows.shape[0]
    L = lp.shape[0]
    # Each body's faces together, in pair order (a counting sort of the pairs by body).
    start = np.zeros(K + 1, dtype=np.intp)
    for q in range(pb.shape[0]):
        start[pb[q] + 1] += 1
    for j in range(K):
        start[j + 1] += start[j]
    flat = np.empty(pb.shape[0], dtype=np.intp)
    fill = start[:K].copy()
    for q in range(pb.shape[0]):
        flat[fill[pb[q]]] = pf[q]
        fill[pb[q]] += 1
    inf = math.inf
    status = np.zeros(K, dtype=np.intp)
    Xo = np.empty((K, 2))
    Vo = np.empty((K, 2))
    THo = np.zeros(K)
    OMo = np.zeros(K)
    ev = np.empty((K * MAX_IMPACTS, 10))
    ne = 0
    for j in range(K):
        i = rows[j]
        if rest[i] >= 0:
            status[j] = PYTHON
            continue
        turning = spun and srolls[j]
        th = om = sqj = al = 0.0
        if turning:
            th, om, sqj, al = th0[j], om0[j], sqm[j], sal[j]
        x, y = X[i, 0], X[i, 1]
        vx, vy = V[i, 0], V[i, 1]
        bx, by = Bm[i, 0], Bm[i, 1]
        wx, wy = Wm[i, 0], Wm[i, 1]
        rr = r[i]
        left = dt
        touched = False
        python = False
        through = False  # the rounds ended (not capped)
        first_event = ne
        for round_ in range(MAX_IMPACTS):
            ta = left
            dur = ta
            # The earliest impact among its faces (ties: the last listed), and its normal.
            t_hit, face, hnx, hny = inf, -1, 0.0, 0.0
            for q in range(start[j], start[j + 1]):
                f = flat[q]
                snx, sny = 0.0, 0.0
                if f < L and spoly[f] >= 0:
                    # _behind_solid_one: a solid polygon's face it is behind, not least
                    # behind of its polygon's, is none of its contacts.
                    d0 = (x - lp[f, 0]) * ln[f, 0] + (y - lp[f, 1]) * ln[f, 1]
                    if d0 < 0.0:
                        kp = spoly[f]
                        best = -inf
                        for qs in range(sstart[kp], sstart[kp + 1]):
                            g = sflat[qs]
                            dg = (x - lp[g, 0]) * ln[g, 0] + (y - lp[g, 1]) * ln[g, 1]
                            best = dg if dg > best else best
                        if d0 < best - 1e-9 * (1.0 + abs(best)):
                            continue
                if f < L:
                    # line_hit_one(x, v, b, p, n, rho + r, two, lo, hi, dur)
                    px, py = lp[f, 0], lp[f, 1]
                    nx, ny = ln[f, 0], ln[f, 1]
                    rho = lrho[f] + rr
                    two = ltwo[f]
                    d0 = (x - px) * nx + (y - py) * ny
                    vn = vx * nx + vy * ny
                    side = -1.0 if two and d0 < 0.0 else 1.0
                    if two and d0 == 0.0 and vn > 0.0:
                        side = -1.0
                    snx, sny = nx * side, ny * side
                    g0 = side * d0 - rho
                    if abs(g0) <= TOUCH * (1.0 + rho):
                        g0 = 0.0
                    g1 = side * vn
                    g2 = 0.5 * side * (bx * nx + by * ny)
                    if g0 <= 0.0:
                        slack = 1e-12 * math.sqrt(vx * vx + vy * vy)
                        if g1 < -slack or (g1 <= slack and g2 < 0.0):
                            t = 0.0
                        elif g2 < 0.0 and g1 > 0.0:
                            if g0 < 0.0:  # behind the line: the later root
                                disc = g1 * g1 - 4.0 * g2 * g0
                                t = -0.5 * (g1 + math.sqrt(disc)) / g2 if disc >= 0.0 else inf
                            else:
                                t = -g1 / g2
                        else:
                            t = inf
                    elif g2 == 0.0:
                        t = -g0 / g1 if g1 < 0.0 else inf
                    else:
                        disc = g1 * g1 - 4.0 * g2 * g0
                        if disc < 0.0:
                            t = inf
                        else:
                            sq = math.sqrt(0.0 if 0.0 > disc else disc)
                            qq = -0.5 * (g1 + math.copysign(sq, g1))
                            r1 = qq / g2
                            r2 = g0 / qq if qq != 0.0 else inf
                            r1 = r1 if r1 >= 0.0 else inf
                            r2 = r2 if r2 >= 0.0 else inf
                            t = r1 if r1 < r2 else r2
                    if not t <= dur:
                        t = inf
                    if t == 0.0 and g0 == 0.0:
                        # leaves_end_one: touching at an end and leaving the face that way.
                        slack = 1e-12 * math.sqrt(vx * vx + vy * vy)
                        u0 = (x - px) * -ny + (y - py) * nx
                        ut = vx * -ny + vy * nx
                        edge = TOUCH * (1.0 + abs(u0))
                        if g1 >= -slack and (
                            (ut > 0.0 and u0 >= lhi[f] - edge) or (ut < 0.0 and u0 <= llo[f] + edge)
                        ):
                            t = inf
                    if t != inf:
                        xt = x + vx * t + bx * (0.5 * t * t)
                        yt = y + vy * t + by * (0.5 * t * t)
                        u = (xt - px) * -ny + (yt - py) * nx
                        if not llo[f] <= u <= lhi[f]:
                            t = inf
                else:
                    # disc_hit_one(x, v, b, c, rho + r, dur), up to its roots.
                    cx, cy = dc[f - L, 0], dc[f - L, 1]
                    rho = dr[f - L] + rr
                    T = dur
                    Dx, Dy = x - cx, y - cy
                    dd, vv = Dx * Dx + Dy * Dy, vx * vx + vy * vy
                    dv, db, bb = Dx * vx + Dy * vy, Dx * bx + Dy * by, bx * bx + by * by
                    dist0 = math.sqrt(dd) - rho
                    reach = math.sqrt(vv) * T + math.sqrt(bb) * (0.5 * T * T)
                    leaving = False
                    t = -1.0  # not yet known
                    if dist0 <= TOUCH * (1.0 + rho):  # touching
                        k1 = 2.0 * dv
                        slack = 1e-12 * math.sqrt(dd * vv)
                        k2 = vv + db
                        if k1 < -slack or (k1 <= slack and k2 < 0.0):
                            t = 0.0
                        elif k2 < 0.0 and k1 <= -k2 * T * 1e-9:
                            t = 0.0  # back within 1e-9 of the step: pressed in (disc_hits)
                        elif not reach > 0.0:
                            t = inf
                        else:
                            leaving = True
                    elif not dist0 <= reach * (1.0 + 1e-9):
                        t = inf
                    if t < 0.0:
                        s = -dv / (vv if vv > 0.0 else 1.0)
                        s = 0.0 if 0.0 > s else s
                        s = T if T < s else s
                        Cx, Cy = Dx + vx * s, Dy + vy * s
                        stray = 0.5 * math.sqrt(bb) * T * T
                        if not (
                            math.sqrt(Cx * Cx + Cy * Cy) - stray <= rho * (1.0 + 1e-9) + TOUCH
                            or leaving
                        ):
                            t = inf
                    if t < 0.0:
                        T2 = T * T
                        k0 = dd - rho * rho
                        k1 = 2.0 * dv * T
                        k2 = (vv + db) * T2
                        k3 = (vx * bx + vy * by) * (T2 * T)
                        k4 = 0.25 * bb * (T2 * T2)
                        if leaving:
                            k0, k1, k2, k3, k4 = k1, k2, k3, k4, 0.0
                        scale = max(abs(k0), abs(k1), abs(k2), abs(k3), abs(k4))
                        low = k0 + (0.0 if 0.0 < k1 else k1) + (0.0 if 0.0 < k2 else k2)
                        low = low + (0.0 if 0.0 < k3 else k3) + (0.0 if 0.0 < k4 else k4)
                        if not math.isnan(k0 + k1 + k2 + k3 + k4) and low > 1e-6 * scale:
                            t = inf  # clear of zero on [0, 1]: no root
                        else:
                            python = True  # the roots: numpy's LAPACK, in _path_one
                            break
                if t <= t_hit and t < inf:
                    t_hit, face, hnx, hny = t, f, snx, sny
            if python:
                break
            if face >= L:  # _disc_normal_one
                ddx = x + vx * t_hit + bx * (0.5 * t_hit * t_hit) - dc[face - L, 0]
                ddy = y + vy * t_hit + by * (0.5 * t_hit * t_hit) - dc[face - L, 1]
                length = math.sqrt(ddx * ddx + ddy * ddy)
                safe = length if length > 0.0 else 1.0
                hnx, hny = ddx / safe, ddy / safe
            hit = t_hit <= dur
            tt = t_hit if hit else dur
            half_tt2 = 0.5 * tt * tt
            xn, yn = x + vx * tt + bx * half_tt2, y + vy * tt + by * half_tt2
            vxn, vyn = vx + wx * tt, vy + wy * tt
            om_n = om + al * tt
            th_n = th + om * tt + al * half_tt2
            if hit:
                # _bounce_one for a free body (old = -1)
                when = t0 + dt - ta + t_hit
                nx, ny = hnx, hny
                vn = vxn * nx + vyn * ny
                vtx, vty = vxn - nx * vn, vyn - ny * vn
                e = eb[i] * fe[face]
                mu = mub[i] * fmu[face]
                vn_in = 0.0 if 0.0 < vn else vn
                vn_out = -e * vn_in
                speed_t = math.sqrt(vtx * vtx + vty * vty)
                keep = speed_t + mu * (1.0 + e) * vn_in
                keep = 0.0 if 0.0 > keep else keep
                scale = keep / (speed_t if speed_t > 0.0 else 1.0)
                a_n = wx * nx + wy * ny
                if a_n < 0.0 and vn_out <= -a_n * (0.5 * dt):
                    python = True  # it settles: rest, in _path_one
                    break
                new_vx, new_vy = vtx * scale + nx * vn_out, vty * scale + ny * vn_out
                if turning:  # friction at the point of contact (_bounce_one's turn)
                    u = vxn * -ny + vyn * nx
                    slip = u - om_n * rr
                    cap = mu * (1.0 + e) * -vn_in
                    most = abs(slip) / (1.0 + sqj)
                    du = -math.copysign(most if most < cap else cap, slip)
                    new_vx = -ny * (u + du) + nx * vn_out
                    new_vy = nx * (u + du) + ny * vn_out
                    om_n = om_n - du * sqj / rr
                if vn_in < 0.0:  # struck: the impact begins and ends
                    row = ev[ne]
                    row[0], row[1], row[2] = j, round_, face
                    row[3], row[4] = xn - nx * rr, yn - ny * rr
                    row[5], row[6] = nx, ny
                    row[7], row[8] = (new_vx - vxn) * m[i], (new_vy - vyn) * m[i]
                    row[9] = when
                    ne += 1
                vxn, vyn = new_vx, new_vy
                touched = True
            x, y, vx, vy = xn, yn, vxn, vyn
            th, om = th_n, om_n
            left = ta - tt if hit else 0.0
            if not (hit and ta - tt > 0.0):
                through = True
                break
        if python or not through:
            status[j] = PYTHON
            ne = first_event
            continue
        status[j] = MET if touched else MISSED
        Xo[j, 0], Xo[j, 1] = x, y
        Vo[j, 0], Vo[j, 1] = vx, vy
        THo[j], OMo[j] = th, om
    return status, Xo, Vo, ev[:ne], start, flat, THo, OMo
