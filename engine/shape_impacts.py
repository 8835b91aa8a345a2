"""The moment two fast shapes met within a step, for the pairs the soft step left inside
each other.

The pile's rows of shapes (engine.shaped, engine.soft) are linear in the step: a row's
normal and its anchors are the manifold's at the step's start, and a body's turn moves its
anchors along the tangent only. That holds while a body turns a little in a step. A box
thrown at 100 m/s at a disc 0.1 m off its centre line meets it early in the step and leaves
turning at 430 rad/s: within the step the row stops the point, not the centres, and the box
turns 3 rad about it while the disc goes on past its centre. The velocities come out as the
closed form's (restitution acts on the velocities), but the bodies end the step inside each
other.

For such a pair (``late_impacts``) the step is taken again in two parts, as an exact impact
is: the motion the step began with, from the start to the moment t* the two meet, then the
velocities the soft step ended with from t* to the step's end. With the forces' pull a and
own angular acceleration alpha constant over the step (so the velocity after the impact is
v(t) = v1 - a (dt - t) for the end velocity v1):

    x(t*) = x0 + v0 t* + a t*^2 / 2,     x1 = x(t*) + v1 (dt - t*) - a (dt - t*)^2 / 2,

and the same for the angle with omega and alpha. A pair is taken so when it moved fast in
the step (its relative sweep, |dx_B - dx_A| + |dtheta_A| R_A + |dtheta_B| R_B with R a body's
bounding radius, over ``FAST`` of the smaller R), began it apart (separation > -``SLOP`` of
the smaller R) and ended it deep (separation < -``DEEP`` of the smaller R) or through (B's
centre past A's along the normal the step began with). A pile pressed together over many
steps never starts a step apart, so it is left to the soft step.

t* is found by conservative advancement (Mirtich's, Box2D's time of impact): from a
separation d at time t, the two cannot meet before t + d / s, where s bounds how fast any
point of one closes on the other, |v_B - v_A| + |omega_A| R_A + |omega_B| R_B taken at the
larger of its values at t and at dt (the speeds change linearly). The separation is the
narrowphase's (engine.manifold) at the bodies' poses along the start motion.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .manifold import collide
from .rotation import Spin
from .shaped import ShapeTable

__all__ = ["retake", "late_impacts", "place", "pair_gaps", "FAST", "DEEP", "SLOP"]

#: A pair's relative sweep in a step, in the smaller bounding radius, past which it is fast.
FAST = 0.5
#: How deep (in the smaller bounding radius) a fast pair must end the step to be taken again.
DEEP = 0.25
#: How far into each other (in the smaller bounding radius) a pair may start and count as apart.
SLOP = 0.02
#: Conservative advancement stops this close (in the smaller bounding radius), or after
#: ``ROUNDS`` advances.
TOUCH = 1e-6
ROUNDS = 50


def pair_gaps(
    table: ShapeTable,
    a: np.ndarray,
    b: np.ndarray,
    xa: np.ndarray,
    qa: np.ndarray,
    xb: np.ndarray,
    qb: np.ndarray,
    fast: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """The separation (length units, < 0: overlap) of each pair k of bodies a[k], b[k] (World
    rows, for their shapes) placed at xa[k], xb[k] (P, 2) and turned to qa[k], qb[k] (rad):
    the least of its manifold's points (engine.manifold, any distance apart; ``fast``: its
    loop kernels); and the manifolds' unit normals from a to b (P, 2)."""
    out = np.full(len(a), np.inf)
    normal = np.zeros((len(a), 2))
    ka, kb = table.kind[a], table.kind[b]
    for code_a in np.unique(ka).tolist():
        for code_b in np.unique(kb).tolist():
            sel = np.flatnonzero((ka == code_a) & (kb == code_b))
            if not len(sel):
                continue
            m = collide(table.kinds(a[sel]), xa[sel], qa[sel], table.kinds(b[sel]), xb[sel],
                        qb[sel], np.inf, fast)  # fmt: skip
            sep = np.where(np.arange(2) < m.count[:, None], m.separation, np.inf)
            out[sel] = sep.min(axis=1)
            normal[sel] = m.normal
    return out, normal


def late_impacts(
    table: ShapeTable,
    a: np.ndarray,
    b: np.ndarray,
    start: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    end: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    pull: tuple[np.ndarray, np.ndarray],
    radius: np.ndarray,
    moves: np.ndarray,
    dt: float,
    fast: bool = False,
) -> tuple[np.ndarray, np.ndarray] | None:
    """The bodies of fast pairs (World rows a, b of the pile's pairs with a shape) that ended
    the step deep in each other, taken again from the moment they met (module text).

    ``start``: (x0 (N, 2), v0, angle0 (N,), omega0) as the step began; ``end``: (x1, v1,
    angle1, omega1) as the soft step left them; ``pull``: (a (N, 2), alpha (N,)) the forces'
    and own torque's accelerations; ``radius`` (N,): bounding radii; ``moves`` (N,): bodies
    that can be moved (a kinematic body keeps its path); ``fast``: the narrowphase's loop
    kernels. Returns (rows, t*) of the bodies to place again, each at the earliest moment any
    of its pairs met, or None where none."""
    x0, q0 = start[0], start[2]
    x1, q1 = end[0], end[2]
    r = np.minimum(radius[a], radius[b])
    dxa, dxb = x1[a] - x0[a], x1[b] - x0[b]
    sweep = np.hypot(*(dxb - dxa).T) + np.abs(q1[a] - q0[a]) * radius[a]
    sweep += np.abs(q1[b] - q0[b]) * radius[b]
    swift = np.flatnonzero(sweep > FAST * r)
    if not len(swift):
        return None
    a, b, r = a[swift], b[swift], r[swift]
    gap0, n0 = pair_gaps(table, a, b, x0[a], q0[a], x0[b], q0[b], fast)
    # Deep at the end, or through: B's centre past A's along the start's normal.
    deep = pair_gaps(table, a, b, x1[a], q1[a], x1[b], q1[b], fast)[0] < -DEEP * r
    deep |= (_dot(x1[b] - x1[a], n0) < 0.0) & (_dot(x0[b] - x0[a], n0) > 0.0)
    deep &= gap0 > -SLOP * r
    if not deep.any():
        return None
    a, b, r = a[deep], b[deep], r[deep]
    hit = _time_of_impact(table, a, b, r, start, pull, radius, dt, fast)
    met = np.isfinite(hit)
    if not met.any():
        return None
    rows = np.concatenate([a[met], b[met]])
    when = np.concatenate([hit[met], hit[met]])
    keep = moves[rows]
    rows, when = rows[keep], when[keep]
    first = np.full(len(x0), np.inf)
    np.minimum.at(first, rows, when)
    rows = np.flatnonzero(np.isfinite(first))
    return (rows, first[rows]) if len(rows) else None


def _time_of_impact(
    table: ShapeTable,
    a: np.ndarray,
    b: np.ndarray,
    r: np.ndarray,
    start: tuple[np.ndarray, ...],
    pull: tuple[np.ndarray, np.ndarray],
    radius: np.ndarray,
    dt: float,
    fast: bool,
) -> np.ndarray:
    """When (s, within [0, dt]) each pair first touches along the start motion, by
    conservative advancement; inf for a pair that does not meet within the step."""
    x0, v0, q0, w0 = start
    acc, alpha = pull

    def poses(rows: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        tt = t[:, None]
        x = x0[rows] + v0[rows] * tt + acc[rows] * (0.5 * tt * tt)
        return x, q0[rows] + w0[rows] * t + alpha[rows] * (0.5 * t * t)

    def bound(t: np.ndarray) -> np.ndarray:
        """How fast any point of b can close on a (length units / s) from t to dt."""
        out = np.zeros(len(a))
        for s in (t, np.full(len(a), dt)):
            dv = (v0[b] + acc[b] * s[:, None]) - (v0[a] + acc[a] * s[:, None])
            spin_a = np.abs(w0[a] + alpha[a] * s) * radius[a]
            spin_b = np.abs(w0[b] + alpha[b] * s) * radius[b]
            out = np.maximum(out, np.hypot(*dv.T) + spin_a + spin_b)
        return out

    t = np.zeros(len(a))
    hit = np.full(len(a), np.inf)
    live = np.ones(len(a), dtype=bool)
    for _ in range(ROUNDS):
        k = np.flatnonzero(live)
        if not len(k):
            break
        xa, qa = poses(a[k], t[k])
        xb, qb = poses(b[k], t[k])
        gap = pair_gaps(table, a[k], b[k], xa, qa, xb, qb, fast)[0]
        touch = gap <= TOUCH * r[k]
        hit[k[touch]] = t[k[touch]]
        live[k[touch]] = False
        k, gap = k[~touch], gap[~touch]
        speed = bound(t)[k]
        with np.errstate(divide="ignore"):
            t[k] = t[k] + np.where(speed > 0.0, gap / speed, np.inf)
        gone = t[k] > dt
        live[k[gone]] = False
    return hit


def place(
    rows: np.ndarray,
    when: np.ndarray,
    start: tuple[np.ndarray, ...],
    end: tuple[np.ndarray, ...],
    pull: tuple[np.ndarray, np.ndarray],
    dt: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Where ``rows`` end the step when their impact came at ``when`` (s): (x (k, 2), angle
    (k,)) by the start motion to then and the end velocities after (module text)."""
    x0, v0, q0, w0 = start
    v1, w1 = end[1], end[3]
    acc, alpha = pull
    t, rest = when, dt - when
    x = x0[rows] + v0[rows] * t[:, None] + acc[rows] * (0.5 * t * t)[:, None]
    x = x + v1[rows] * rest[:, None] - acc[rows] * (0.5 * rest * rest)[:, None]
    q = q0[rows] + w0[rows] * t + alpha[rows] * (0.5 * t * t)
    q = q + w1[rows] * rest - alpha[rows] * (0.5 * rest * rest)
    return x, q


def retake(
    table: ShapeTable,
    a: np.ndarray,
    b: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    spin: Spin | None,
    acc: np.ndarray,
    store: Any,
    dt: float,
    fast: bool = False,
) -> np.ndarray | None:
    """``late_impacts`` for the pile's pairs with a shape (World rows a, b: one row a point,
    so a pair may repeat), from the step's start (x0, v0; ``spin``'s angle0 and omega0) to
    where the soft step left them (x, v; ``spin``'s angle and omega), under the forces' pull
    ``acc`` (N, 2): the bodies taken again are written in place (x, and ``spin.angle``);
    returns their World rows, or None."""
    if not len(a):
        return None
    n = len(x)
    key = np.unique(a.astype(np.int64) * n + b)
    a, b = key // n, key % n
    if spin is None:
        zero = np.zeros(n)
        q0 = q1 = w0 = w1 = alpha = zero
    else:
        q0, q1, w0, w1, alpha = spin.angle0, spin.angle, spin.omega0, spin.omega, spin.alpha
    start, end, pull = (x0, v0, q0, w0), (x, v, q1, w1), (acc, alpha)
    got = late_impacts(table, a, b, start, end, pull, store.radius, ~store.kinematic, dt, fast)
    if got is None:
        return None
    rows, when = got
    x[rows], angle = place(rows, when, start, end, pull, dt)
    if spin is not None:
        spin.angle[rows] = angle
    return rows


def _dot(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    return p[:, 0] * q[:, 0] + p[:, 1] * q[:, 1]
