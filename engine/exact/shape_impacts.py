"""The moment two fast shapes met within a step, for the pairs the soft step left inside
each other.

The pile's rows of shapes (engine.geometry.shaped, engine.exact.soft) are linear in the step: a
row's normal and its anchors are the manifold's at the step's start, and a body's turn moves its
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

and the same for the angle with omega and alpha. A pair is taken so when it moved fast in the
step (its relative sweep, |dx_B - dx_A| + |dtheta_A| R_A + |dtheta_B| R_B with R a body's
bounding radius, over ``FAST`` of the smaller R), began it apart (separation > -``SLOP`` of the
smaller R) and ended it deep (separation < -``DEEP`` of the smaller R) or through (B's centre
past A's along the normal the step began with). A pile pressed together over many steps never
starts a step apart, so it is left to the soft step. A body and a static collider are taken the
same way (``late_wall_impacts``), fast or not, and from a depth of ``DEEP_WALL``, counted in the
body's least extent where that is less than its bounding radius (a capsule's radius, a polygon's
least distance from its centroid to an edge: a capsule 1.4 m long and 6 cm thick, struck onto a
floor by a heavy disc, went 3.1 cm in, its centre past the floor, while DEEP_WALL of its
bounding radius was 3.7 cm): "through" is then the manifold's normal turned round (the body on
the collider's other side), and the advancement is against the colliders it went into only (a
box sliding along a floor into a wall is not stopped by the floor). A body that begins the step
in a collider (a corner an impact left there at the end of the step before, the body turning on
into the wall; or a light body a pile pressed in) and ends it ``DEEP_WALL`` deeper than it began
is taken again too, its moment the one where it is a hair deeper than it began, however deep it
began: a 0.1 kg box 0.1 m a side, held under an 8.2 kg box spinning over it (a mass ratio of 82,
past what the pile's 4 iterations hold, and warned), crept 3.6 mm into the floor over three steps
(each less than ``DEEP_WALL`` deeper) and then, taken again only while it began at most
``DEEP_WALL`` in, went 58 mm in over two more, its centre past the floor's line
(tests/test_fuzz_shapes.py); it now stays 3.6 mm in, held where it was (its velocity kept)
until the heavy box has passed over it. A body its own start motion does not bring there was
pushed by another within the step: it is stopped where its straight move from x0 to x1 first
touches (motion clamping). A body met by several is placed by the earliest.

A second impact within the step after the first (a box turning so fast that it meets the
wall again before the step ends) is not searched for: where the rest of the step would end
deep, the body ends it at its moment of impact instead (Box2D's time of impact: the rest of
the step's motion is lost, and the next step's rows hold it there).

t* is found by conservative advancement (Mirtich's, Box2D's time of impact): from a
separation d at time t, the two cannot meet before t + d / s, where s bounds how fast any
point of one closes on the other, |v_B - v_A| + |omega_A| R_A + |omega_B| R_B taken at the
larger of its values at t and at dt (the speeds change linearly). The separation is the
narrowphase's (engine.geometry.manifold) at the bodies' poses along the start motion. Where the
advancement has not touched within ``ROUNDS`` (a corner grazing a face creeps on by a hair a
round), the rest of the step is searched at ``SAMPLES`` moments for the first where the two
are in, and t* found between that and the moment before by bisection (``_first_touch``): a
real touching, where taking t* where the advancement got to (Box2D's, when its iterations
run out) let a thin body out of a room in another scene, and counting no impact let the
grazing 8-gon of tests/test_fuzz_shapes.py end 0.143 m in the floor. (A graze shorter than a
sample's span that goes in and out again between two samples is missed, as before.)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..dynamics.rotation import Spin
from ..geometry.manifold import collide
from ..geometry.shaped import CAPSULE, DISC, POLYGON, ShapeTable

#: The static colliders' manifolds for bodies at poses: walls(rows, x, angle, margin) ->
#: (row, collider, unit normal from the collider to the body, separation), a point a row.
Walls = Callable[
    [np.ndarray, np.ndarray, np.ndarray, float],
    tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
]

__all__ = [
    "DEEP_WALL",
    "retake",
    "late_impacts",
    "late_wall_impacts",
    "place",
    "pair_gaps",
    "Walls",
    "FAST",
    "DEEP",
    "SLOP",
]

#: A pair's relative sweep in a step, in the smaller bounding radius, past which it is fast.
FAST = 0.5
#: How deep (in the smaller bounding radius) a fast pair must end the step to be taken again.
DEEP = 0.25
#: The same against a static collider (in the body's least extent where that is less), which a
#: body pressed into it over many steps never starts a step apart from: any depth past the soft
#: step's own give is a missed impact.
DEEP_WALL = 0.05
#: How far into each other (in the smaller bounding radius) a pair may start and count as apart.
SLOP = 0.02
#: Conservative advancement stops this close (in the smaller bounding radius), or after
#: ``ROUNDS`` advances.
TOUCH = 1e-6
ROUNDS = 50
#: Out of rounds, the rest of the step is searched at this many moments for where the body
#: is first in, and the moment between that and the one before found by this many halvings.
SAMPLES = 32
BISECTIONS = 40


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
    the least of its manifold's points (engine.geometry.manifold, any distance apart; ``fast``: its
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


def _along(
    start: tuple[np.ndarray, ...],
    pull: tuple[np.ndarray, np.ndarray],
    rows: np.ndarray,
    t: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Where ``rows`` are at times t (s) along the start motion: (x (k, 2), angle (k,)), by
    x0 + v0 t + a t^2 / 2 and the same for the angle."""
    x0, v0, q0, w0 = start
    acc, alpha = pull
    half = 0.5 * t * t
    x = x0[rows] + v0[rows] * t[:, None] + acc[rows] * half[:, None]
    return x, q0[rows] + w0[rows] * t + alpha[rows] * half


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

    def bound(t: np.ndarray) -> np.ndarray:
        """How fast any point of b can close on a (length units / s) from t to dt."""
        out = np.zeros(len(a))
        for s in (t, np.full(len(a), dt)):
            dv = (v0[b] + acc[b] * s[:, None]) - (v0[a] + acc[a] * s[:, None])
            spin_a = np.abs(w0[a] + alpha[a] * s) * radius[a]
            spin_b = np.abs(w0[b] + alpha[b] * s) * radius[b]
            out = np.maximum(out, np.hypot(*dv.T) + spin_a + spin_b)
        return out

    def gap_at(i: np.ndarray, when: np.ndarray) -> np.ndarray:
        """Pairs i's separations at times ``when`` along the start motion."""
        xa, qa = _along(start, pull, a[i], when)
        xb, qb = _along(start, pull, b[i], when)
        return pair_gaps(table, a[i], b[i], xa, qa, xb, qb, fast)[0]

    t = np.zeros(len(a))
    hit = np.full(len(a), np.inf)
    live = np.ones(len(a), dtype=bool)
    for _ in range(ROUNDS):
        k = np.flatnonzero(live)
        if not len(k):
            break
        gap = gap_at(k, t[k])
        touch = gap <= TOUCH * r[k]
        hit[k[touch]] = t[k[touch]]
        live[k[touch]] = False
        k, gap = k[~touch], gap[~touch]
        speed = bound(t)[k]
        with np.errstate(divide="ignore"):
            t[k] = t[k] + np.where(speed > 0.0, gap / speed, np.inf)
        gone = t[k] > dt
        live[k[gone]] = False
    k = np.flatnonzero(live)
    if len(k):
        # Out of rounds (a corner grazing a face): the rest of the step searched (module text).
        hit[k] = _first_touch(gap_at, TOUCH * r, k, t[k], dt)
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
    v1, w1 = end[1], end[3]
    acc, alpha = pull
    rest = dt - when
    x, q = _along(start, pull, rows, when)
    x = x + v1[rows] * rest[:, None] - acc[rows] * (0.5 * rest * rest)[:, None]
    q = q + w1[rows] * rest - alpha[rows] * (0.5 * rest * rest)
    return x, q


def late_wall_impacts(
    walls: Walls,
    rows: np.ndarray,
    start: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    end: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    pull: tuple[np.ndarray, np.ndarray],
    radius: np.ndarray,
    dt: float,
    clamped: dict[int, tuple[np.ndarray, float]] | None = None,
    least: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray] | None:
    """``late_impacts`` for bodies (World ``rows``, with shapes, that can be moved) against
    the static colliders: ``walls(rows, x, angle, margin)`` gives their manifolds' points
    (row, collider, unit normal from the collider to the body, separation) at poses x (N, 2),
    ``angle`` (N,), for colliders within ``margin``. A body is taken again when it moved fast,
    began the step apart from a collider and ended it deep in it or through it (on its other
    side: the normal turned by more than 120 degrees); returns (rows, t*) or None. A body
    that went in by another's push, not by its start motion, is written into ``clamped``
    (row -> its pose (x, angle) where its straight move first touches), if given. ``least``
    (N,): the scale of the depths, each body's least extent (None: its ``radius``)."""
    x0, q0 = start[0], start[2]
    x1, q1 = end[0], end[2]
    r = radius[rows]
    scale = radius if least is None else np.minimum(radius, least)
    sweep = np.hypot(*(x1[rows] - x0[rows]).T) + np.abs(q1[rows] - q0[rows]) * r
    # (Any body that went from apart to DEEP_WALL deep moved at least that: the rest stand.)
    moving = sweep > DEEP_WALL * scale[rows]
    rows, r, sweep = rows[moving], r[moving], sweep[moving]
    if not len(rows):
        return None
    reach = float((sweep + r).max())
    b0, c0, n0, s0 = _nearest(*walls(rows, x0, q0, reach))
    b1, c1, n1, s1 = _nearest(*walls(rows, x1, q1, reach))
    size = scale[b0]
    # Each (body, collider) of the start met again at the end (both sorted by key).
    k0, k1 = b0 * (1 << 32) + c0, b1 * (1 << 32) + c1
    at = np.searchsorted(k1, k0)
    found = at < len(k1)
    found[found] = k1[at[found]] == k0[found]
    hit = np.zeros(len(k0), dtype=bool)
    f = np.flatnonzero(found)
    began, ended, lim = s0[f], s1[at[f]], size[f]
    # Apart at the start: deep is DEEP_WALL in. In at the start (a corner left there by an
    # impact at the end of the step before, the body turning on into the wall; a light body a
    # pile pressed in, however deep): DEEP_WALL deeper than it began. Through (the normal turned
    # round) only for a body that began apart or in by no more than the soft step's own give:
    # one deeper may be leaving by the far side.
    apart = began > -SLOP * lim
    within = apart | (began > -DEEP_WALL * lim)
    deep = ended < np.where(apart, 0.0, began) - DEEP_WALL * lim
    through = _dot(n1[at[f]], n0[f]) < -0.5
    hit[f] = deep | (through & within)
    if not hit.any():
        return None
    body, col = b0[hit], c0[hit]
    # Conservative advancement of each such body against the colliders it went into: to
    # touching, or for one that began in, to a hair deeper than it began.
    movers = np.unique(body)
    level = np.zeros(len(radius))
    inside = hit.copy()
    inside[f] &= ~apart
    np.minimum.at(level, b0[inside], s0[inside] - 2.0 * TOUCH * size[inside])
    when = _time_of_wall_impact(walls, movers, body, col, start, pull, radius, dt, reach,
                                level)  # fmt: skip
    # A body that its own start motion does not bring there was sent by another's push
    # within the step (engine.geometry.shaped): it is stopped where its actual move, taken as
    # straight (x0 to x1, angle0 to angle1), first touches one of them (motion clamping).
    pushed = movers[~np.isfinite(when)]
    if len(pushed) and clamped is not None:
        v = (x1 - x0) * (1.0 / dt)
        w = (q1 - q0) * (1.0 / dt)
        zero = (np.zeros_like(x0), np.zeros_like(q0))
        stop = _time_of_wall_impact(walls, pushed, body, col, (x0, v, q0, w), zero, radius, dt,
                                    reach, level)  # fmt: skip
        for k, t in zip(pushed.tolist(), stop.tolist(), strict=True):
            if clamped is not None and math.isfinite(t):
                clamped[k] = (x0[k] + v[k] * t, float(q0[k] + w[k] * t))
    met = np.isfinite(when)
    return (movers[met], when[met]) if met.any() else None


def _nearest(
    row: np.ndarray, col: np.ndarray, normal: np.ndarray, sep: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per (row, collider), the point of least separation: (row, collider, its normal, its
    separation), sorted by row then collider."""
    order = np.lexsort((sep, col, row))
    row, col, normal, sep = row[order], col[order], normal[order], sep[order]
    first = np.ones(len(row), dtype=bool)
    first[1:] = (row[1:] != row[:-1]) | (col[1:] != col[:-1])
    return row[first].astype(np.int64), col[first].astype(np.int64), normal[first], sep[first]


def _time_of_wall_impact(
    walls: Walls,
    movers: np.ndarray,
    body: np.ndarray,
    col: np.ndarray,
    start: tuple[np.ndarray, ...],
    pull: tuple[np.ndarray, np.ndarray],
    radius: np.ndarray,
    dt: float,
    reach: float,
    level: np.ndarray | None = None,
) -> np.ndarray:
    """When (s) each of ``movers`` first touches one of the colliders it went into (the
    pairs ``body``, ``col``) along the start motion, by conservative advancement; inf where
    it does not within the step. ``level`` (by row, <= 0; None: 0): the separation taken
    as the surface (a body that began the step in: a hair deeper than it began)."""
    x0, v0, q0, w0 = start
    acc, alpha = pull
    wanted = set(zip(body.tolist(), col.tolist(), strict=True))

    def gap_at(i: np.ndarray, when: np.ndarray) -> np.ndarray:
        """Movers i's least separations from the colliders they went into, at times
        ``when`` along the start motion."""
        m = movers[i]
        x, q = x0.copy(), q0.copy()
        x[m], q[m] = _along(start, pull, m, when)
        row, c, _, sep = walls(m, x, q, reach)
        mine = np.array([(a, b) in wanted for a, b in zip(row.tolist(), c.tolist(), strict=True)],
                        dtype=bool)  # fmt: skip
        gap = np.full(len(x0), np.inf)
        np.minimum.at(gap, row[mine], sep[mine])
        return gap[m]

    t = np.zeros(len(movers))
    hit = np.full(len(movers), np.inf)
    live = np.ones(len(movers), dtype=bool)
    floor = np.zeros(len(movers)) if level is None else level[movers]
    for _ in range(ROUNDS):
        k = np.flatnonzero(live)
        if not len(k):
            break
        m, tk = movers[k], t[k]
        gap = gap_at(k, tk) - floor[k]
        touch = gap <= TOUCH * radius[m]
        hit[k[touch]] = tk[touch]
        live[k[touch]] = False
        k, gap, m = k[~touch], gap[~touch], m[~touch]
        speed = np.zeros(len(k))
        for s in (t[k], np.full(len(k), dt)):
            v = v0[m] + acc[m] * s[:, None]
            speed = np.maximum(speed, np.hypot(*v.T) + np.abs(w0[m] + alpha[m] * s) * radius[m])
        with np.errstate(divide="ignore", invalid="ignore"):
            t[k] = t[k] + np.where(speed > 0.0, gap / speed, np.inf)
        live[k[~(t[k] <= dt)]] = False
    k = np.flatnonzero(live)
    if len(k):
        # Out of rounds (a corner grazing a face creeps on by a hair a round): the rest of
        # the step is searched for where the body is first in, and the moment it touches
        # found by bisection between that and the pose before (module text).
        hit[k] = _first_touch(gap_at, floor + TOUCH * radius[movers], k, t[k], dt)
    return hit


def _first_touch(
    gap_at: Callable[[np.ndarray, np.ndarray], np.ndarray],
    touch: np.ndarray,
    k: np.ndarray,
    t: np.ndarray,
    dt: float,
) -> np.ndarray:
    """For each of ``k`` (apart at its time ``t``), the first of SAMPLES moments from t to
    ``dt`` at which its separation ``gap_at(k, when)`` is within its ``touch`` distance (in),
    and from the one before it (apart) the moment of touching by bisection (BISECTIONS
    halvings); inf where none is in."""
    out = np.full(len(k), np.inf)
    lo = t.copy()
    hi = np.full(len(k), np.inf)
    for j in range(1, SAMPLES + 1):
        todo = np.flatnonzero(~np.isfinite(hi))
        if not len(todo):
            break
        when = t[todo] + (dt - t[todo]) * (j / SAMPLES)
        inside = gap_at(k[todo], when) <= touch[k[todo]]
        hi[todo[inside]] = when[inside]
        lo[todo[~inside]] = when[~inside]
    found = np.flatnonzero(np.isfinite(hi))
    if not len(found):
        return out
    a, b = lo[found], hi[found]
    for _ in range(BISECTIONS):
        mid = 0.5 * (a + b)
        inside = gap_at(k[found], mid) <= touch[k[found]]
        b = np.where(inside, mid, b)
        a = np.where(inside, a, mid)
    out[found] = a  # apart by at most the touch distance: the moment it touches
    return out


def retake(
    table: ShapeTable,
    pairs: tuple[np.ndarray, np.ndarray],
    walls: tuple[Walls, np.ndarray] | None,
    before: tuple[np.ndarray, np.ndarray],
    after: tuple[np.ndarray, np.ndarray],
    spin: Spin | None,
    acc: np.ndarray,
    store: Any,
    dt: float,
    fast: bool = False,
    held: np.ndarray | None = None,
) -> np.ndarray | None:
    """``late_impacts`` and ``late_wall_impacts`` for a pile: its pairs with a shape (World
    rows a, b: one row a point, so a pair may repeat) and its bodies with rows on the static
    colliders (``walls``: the function and those rows, or None), from the step's start
    (``before``: x0, v0; ``spin``'s angle0 and omega0) to where the soft step left them
    (``after``: x, v; ``spin``'s angle and omega), under the forces' pull ``acc`` (N, 2).
    Each body taken again ends where its earliest impact sends it, written in place (x, and
    ``spin.angle``); returns their World rows, or None. ``held`` (N,) bool: the bodies held by
    joints, whose contacts of a disc with a polygon or a capsule the joints' solve holds
    exactly after (engine.exact.joint_contacts), or None."""
    x0, v0 = before
    x, v = after
    n = len(x)
    if spin is None:
        zero = np.zeros(n)
        q0 = q1 = w0 = w1 = alpha = zero
    else:
        q0, q1, w0, w1, alpha = spin.angle0, spin.angle, spin.omega0, spin.omega, spin.alpha
    start, end, pull = (x0, v0, q0, w0), (x, v, q1, w1), (acc, alpha)
    moves = ~store.kinematic
    first = np.full(n, np.inf)
    a, b = pairs
    if len(a):
        key = np.unique(a.astype(np.int64) * n + b)
        got = late_impacts(table, key // n, key % n, start, end, pull, store.radius, moves, dt,
                           fast)  # fmt: skip
        if got is not None:
            np.minimum.at(first, *got)
    clamped: dict[int, tuple[np.ndarray, float]] = {}
    # A wall's depths are counted in a body's least extent where its bounding radius is more
    # (``late_wall_impacts``; a body of several shapes: its bounding radius).
    least = table.extents()[0]
    least = np.minimum(store.radius, np.where(least > 0.0, least, store.radius))
    if walls is not None:
        rows = np.unique(walls[1])
        got = late_wall_impacts(walls[0], rows[moves[rows]], start, end, pull, store.radius, dt,
                                clamped, least)  # fmt: skip
        if got is not None:
            np.minimum.at(first, *got)
    for j, (xj, qj) in clamped.items():
        if not np.isfinite(first[j]):  # (an impact of its own places it otherwise)
            x[j] = xj
            q1[j] = qj
    stopped = np.array(sorted(j for j in clamped if not np.isfinite(first[j])), dtype=np.intp)
    rows = np.flatnonzero(np.isfinite(first))
    if not len(rows):
        return stopped if len(stopped) else None
    when = first[rows]
    x[rows], angle = place(rows, when, start, end, pull, dt)
    q = q1.copy()
    q[rows] = angle
    if walls is not None:
        # A body placed by its impact with another may have passed a wall on the way there:
        # its start motion brought it to the wall before the two met (a box knocked on
        # against a wall it was turning into, a capsule rising into a ceiling as a box meets
        # it). Where its pose at the moment of impact, or the pose placed from there, is
        # deep in a collider it began the step apart from, the wall's moment along the start
        # motion is the earlier impact, and places it.
        xs, qs = x.copy(), q.copy()
        xs[rows], qs[rows] = _along(start, pull, rows, when)
        for pose in ((xs, v, qs, w1), (x, v, q, w1)):
            got = late_wall_impacts(walls[0], rows, start, pose, pull, store.radius, dt,
                                    least=least)  # fmt: skip
            if got is not None:
                np.minimum.at(first, *got)
        if not np.array_equal(first[rows], when):
            when = first[rows]
            x[rows], angle = place(rows, when, start, end, pull, dt)
            q[rows] = angle
    # Where the rest of the step at the end velocities still ends deep (a body turning so
    # fast that it meets the wall again within the step: module text), it ends at the
    # moment of impact instead, losing the rest of the step's motion (Box2D's time of
    # impact); the next step's rows hold it there.
    deep = np.zeros(n, dtype=bool)
    r = store.radius
    if walls is not None:
        sep = np.full(n, np.inf)
        row, _, _, s = walls[0](rows, x, q, float(r[rows].max()))
        np.minimum.at(sep, row, s)
        deep |= sep < -DEEP_WALL * least
    if len(a):
        a, b = key // n, key % n
        mine = np.isin(a, rows) | np.isin(b, rows)
        a, b = a[mine], b[mine]
        gap = pair_gaps(table, a, b, x[a], q[a], x[b], q[b], fast)[0]
        bad = gap < -DEEP * np.minimum(r[a], r[b])
        if held is not None:
            # Not a disc on a polygon or a capsule held by a joint: the joints' solve holds
            # that contact exactly, however far the body turned (engine.exact.joint_contacts),
            # where the rows, linear in the step, leave it deep (a ball slid out along a bat
            # its motor swings: 7.7 cm into it, retaken from the step's start, where the two
            # touched, as deep; put back where they began, they stayed there every step
            # after, their speeds saying 9 rad/s and 58 m/s).
            ka, kb = table.kind[a], table.kind[b]
            pa_, pb_ = (ka == POLYGON) | (ka == CAPSULE), (kb == POLYGON) | (kb == CAPSULE)
            disc_on_polygon = ((ka == DISC) & pb_) | ((kb == DISC) & pa_)
            bad &= ~(disc_on_polygon & (held[a] | held[b]))
        deep[a[bad]] = deep[b[bad]] = True
    back = deep[rows]
    if back.any():
        k = rows[back]
        x[k], angle[back] = _along(start, pull, k, when[back])
    if spin is not None:
        spin.angle[rows] = angle
    return np.union1d(rows, stopped)


def _dot(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    return p[:, 0] * q[:, 0] + p[:, 1] * q[:, 1]
