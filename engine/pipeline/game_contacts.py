"""A game step's contacts in one compiled call: broadphase, narrowphase and rows, on the fast path.

The soft step (engine.pipeline.game_step) finds its contacts in three stages: the pairs that may
touch (the broadphase: bodies' bounding circles, and bodies' circles against the static shapes'
boxes, each within what the two can move in the step), a manifold for each (the
narrowphase: engine.geometry.narrowphase's two tables), and the solver's rows (materials, the
conveyor's speed, the warm start by key). On the numpy path each stage is a handful of array
calls, and at a game's size (twenty bodies, a dozen segments) numpy's fixed cost per call is
nearly all of their time: about 0.25 ms a step for work that takes microseconds.
``contacts_loop`` is the three stages as one loop kernel, over the same arrays, in the same
order, with the same products, so the fast path's contacts are the numpy path's to the bit
(tests/test_soft_solver.py checks whole games against each other):

1. the body pairs given (every pair of a small scene, or the grid's: engine.geometry.pair_grid),
   kept when their circles and their boxes come within reach (a long plank's box is far tighter than
   its circle), one of them moves, neither is a sensor, the filters pass and no joint or pre_solve
   keeps them apart;
2. every body against every static shape whose box its reach toward static shapes overlaps
   (its own, grown by its pairs' partners': engine.pipeline.game_broadphase.struck), kept
   likewise (a sensor collider is kept: its overlaps are events), but a body too far in front
   of a half plane (whose box is the whole plane) to get a point from it: the numpy path meets
   that pair and gets none;
3. the manifolds: polygon against polygon in one call of ``polygon_loop``, the round pairs in
   one of ``round_loop`` (a polygon against a circle taken with the polygon as A, then flipped
   back), a half plane against a capsule or a polygon in one of ``half_plane_polygon_loop``
   each and against a disc here (the half plane as A, flipped back), each group with the
   largest reach among its pairs as its speculative margin, met in the broadphase's order;
4. each manifold with a point a contact row, but a sensor collider's, which is an overlap
   (the body's row, the collider's place) where a point is inside.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import kernels
from ..body_shapes import MAX_PARTS
from ..dynamics.events import COLLIDER
from ..geometry.manifold import half_plane_polygon_loop
from ..geometry.manifold_kinds import LINEAR_SLOP, SPECULATIVE_DISTANCE
from ..geometry.manifold_polygon import polygon_loop
from ..geometry.narrowphase import round_loop
from ..geometry.pair_grid import grid_pairs_loop
from ..geometry.passing import passing_loop
from ..kernels import stable_order

__all__ = [
    "STATIC",
    "body_boxes",
    "candidates_loop",
    "contacts_loop",
    "contacts_sample",
    "report_loop",
]

#: Warm-start keys: (the pair's code << FEATURE) | the point's feature id (16 bits); a pair's
#: code is (slot_a << OTHER) | slot_b, or | STATIC | the static shape's place.
FEATURE = 16
OTHER = 21
STATIC = 1 << 20
#: A point of a pair of parts of bodies of several shapes (engine.body_shapes, at most
#: MAX_PARTS each) has (A's part's number * MAX_PARTS + B's) << PART in its key, above the
#: pair's code (slots < 2^20, so the code and feature fill bits 0 to 56, and these 57 to 62).
PART = 57


def contacts_sample() -> tuple[Any, ...]:
    """The smallest call: a unit box resting on a segment's capsule, a disc beside it, both
    warm started."""
    f = np.zeros
    x = np.array([[0.0, 0.5], [1.2, 0.5]])
    q = f(2)
    radius = np.array([0.71, 0.5])
    reach = np.array([0.01, 0.01])
    yes = np.ones(2, dtype=bool)
    no = np.zeros(2, dtype=bool)
    i2 = f(2, dtype=np.int64)
    cats = np.ones(2, dtype=np.int64)
    mask = np.full(2, -1, dtype=np.int64)
    slots = np.array([0, 1], dtype=np.int64)
    mat = np.array([0.6, 0.6])
    v = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]],
                  [[-2.0, 0.0], [2.0, 0.0], [2.0, 0.0], [2.0, 0.0]]])  # fmt: skip
    nn = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]],
                   [[0.0, -1.0], [0.0, 1.0], [0.0, 1.0], [0.0, 1.0]]])  # fmt: skip
    count = np.array([4, 2], dtype=np.int64)
    rad = np.array([0.0, 0.02])
    center = f((1, 2))
    rnd = np.array([0.5])
    pa, pb = np.array([0], dtype=np.int64), np.array([1], dtype=np.int64)
    owner = np.array([0], dtype=np.int64)
    bounds = np.array([[-2.02, -0.02, 2.02, 0.02]])
    s_circle = np.zeros(1, dtype=bool)
    s_index = np.array([1], dtype=np.int64)
    c_mat = np.array([0.5])
    surface = f((1, 2))
    c_i = f(1, dtype=np.int64)
    none = f(0, dtype=np.int64)
    keys = np.array([0], dtype=np.int64)
    lam = f((1, 3))
    kind = np.array([2, 0], dtype=np.int64)
    up = np.array([[0.0, 1.0]])
    parts = np.array([[0, 1], [1, 1]], dtype=np.int64)  # (one part a body: itself, number 0)
    part_of = np.array([[0, 0], [1, 0]], dtype=np.int64)
    return (x, q, radius, reach, yes, no, i2, cats, mask, slots, mat, mat, np.array([False, True]),
            np.array([0, 0], dtype=np.int64), kind, parts, part_of, pa, pb, owner, bounds,
            s_circle, s_index,
            np.zeros(1, dtype=bool), c_mat, c_mat, surface, c_i, c_i + 1, c_i - 1, v, nn, count,
            rad, center, rnd, f((1, 2)), up, none, none, keys, lam, f((2, 2)),
            1.0 / 60.0, 1.0)  # fmt: skip


def _boxes_sample() -> tuple[Any, ...]:
    """A disc of radius 0.5 and a unit box turned a quarter turn beside it."""
    corners = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]])
    return (np.array([[0.0, 0.5], [1.2, 0.5]]), np.array([0.0, 0.5 * np.pi]),
            np.array([0.5, 0.71]), np.array([True, False]), np.zeros(2, dtype=np.int64),
            np.array([[0, 1], [1, 1]], dtype=np.int64), corners, np.zeros(1), np.zeros((2, 2)),
            np.array([0.5, 0.0]))  # fmt: skip


@kernels.loop(sample=_boxes_sample)
def body_boxes(
    x: Any, q: Any, radius: Any, body_circle: Any, body_index: Any, body_parts: Any, V: Any,
    rad: Any, center: Any, rnd: Any,
) -> Any:  # fmt: skip
    """Each body's box (n, 4: xmin, ymin, xmax, ymax, m): a disc's centre +- its ``radius``, a
    polygon's (a capsule's) corners ``V[body_index]`` turned by ``q`` (rad) and moved to ``x``,
    +- its rounding ``rad`` (engine.pipeline.game_broadphase's ``boxes``: the same products).
    The shapes are the parts' (``body_parts``: each body's first part and how many); a body of
    several takes the box of its parts' boxes (a round part's ``center``, ``rnd``)."""
    n = len(radius)
    box = np.empty((n, 4))
    for a in range(n):
        r = radius[a]
        box[a, 0], box[a, 1] = x[a, 0] - r, x[a, 1] - r
        box[a, 2], box[a, 3] = x[a, 0] + r, x[a, 1] + r
        first = body_parts[a, 0]
        if body_parts[a, 1] != 1:
            # A body of several shapes: the least and greatest of its parts' corners (a round
            # part's centre) turned and moved, each part's +- its rounding
            # (engine.pipeline.game_broadphase's ``part_boxes``: the same products).
            co, si = np.cos(q[a]), np.sin(q[a])
            for u in range(body_parts[a, 1]):
                part = first + u
                j = body_index[part]
                lox, loy, hix, hiy = np.inf, np.inf, -np.inf, -np.inf
                if body_circle[part]:
                    wx = co * center[j, 0] - si * center[j, 1] + x[a, 0]
                    wy = si * center[j, 0] + co * center[j, 1] + x[a, 1]
                    lox, loy, hix, hiy = wx - rnd[j], wy - rnd[j], wx + rnd[j], wy + rnd[j]
                else:
                    for v in range(V.shape[1]):
                        wx = co * V[j, v, 0] - si * V[j, v, 1] + x[a, 0]
                        wy = si * V[j, v, 0] + co * V[j, v, 1] + x[a, 1]
                        lox, loy = min(lox, wx), min(loy, wy)
                        hix, hiy = max(hix, wx), max(hiy, wy)
                    lox, loy = lox - rad[j], loy - rad[j]
                    hix, hiy = hix + rad[j], hiy + rad[j]
                if u == 0:
                    box[a, 0], box[a, 1], box[a, 2], box[a, 3] = lox, loy, hix, hiy
                else:
                    box[a, 0], box[a, 1] = min(box[a, 0], lox), min(box[a, 1], loy)
                    box[a, 2], box[a, 3] = max(box[a, 2], hix), max(box[a, 3], hiy)
            continue
        if not body_circle[first]:
            j = body_index[first]
            co, si = np.cos(q[a]), np.sin(q[a])
            for v in range(V.shape[1]):
                wx = co * V[j, v, 0] - si * V[j, v, 1] + x[a, 0]
                wy = si * V[j, v, 0] + co * V[j, v, 1] + x[a, 1]
                if v == 0 or wx < box[a, 0]:
                    box[a, 0] = wx
                if v == 0 or wy < box[a, 1]:
                    box[a, 1] = wy
                if v == 0 or wx > box[a, 2]:
                    box[a, 2] = wx
                if v == 0 or wy > box[a, 3]:
                    box[a, 3] = wy
            box[a, 0] -= rad[j]
            box[a, 1] -= rad[j]
            box[a, 2] += rad[j]
            box[a, 3] += rad[j]
    return box


def _candidates_sample() -> tuple[Any, ...]:
    """Three discs of radius 0.5 in a row, the last a wall of radius 3 (a big body), falling."""
    x = np.array([[0.0, 0.5], [1.2, 0.5], [5.0, 0.0]])
    v = np.array([[0.0, -1.0], [0.0, -1.0], [0.0, 0.0]])
    accel = np.array([[0.0, -9.81], [0.0, -9.81], [0.0, 0.0]])
    radius = np.array([0.5, 0.5, 3.0])
    return x, v, accel, np.zeros(3), radius, np.zeros(3, dtype=np.int64), 1.0 / 60.0, 0.5, 1.0


@kernels.loop(sample=_candidates_sample)
def candidates_loop(
    x: Any, v: Any, accel: Any, omega: Any, radius: Any, group: Any, dt: float, median: float,
    unit: float,
) -> tuple[Any, Any, Any]:  # fmt: skip
    """engine.pipeline.game_step's ``_reach`` and ``_candidates`` past its few bodies, in one
    call: each body's reach (m: |v| dt + |a| dt^2 + |omega| dt r, its products in its order),
    and the pairs of rows (a < b) the broadphase tests: none where every body is in one
    group (not 0), else those of a grid (engine.geometry.pair_grid's ``grid_pairs_loop``) of the
    bodies whose radius and reach come within four times the ``median`` radius (m) and a
    speculative distance, then each bigger body with every other (a pair of big ones once),
    in ``_candidates``' order; ``unit`` the World's length units a metre (its
    ``length_units_per_meter``), which the speculative distance is scaled by. Returns (a, b,
    reach)."""
    speculative = SPECULATIVE_DISTANCE * unit
    n = len(radius)
    reach = np.empty(n)
    for i in range(n):
        speed = np.hypot(v[i, 0], v[i, 1])
        acc = np.hypot(accel[i, 0], accel[i, 1])
        reach[i] = speed * dt + acc * dt * dt + np.abs(omega[i]) * dt * radius[i]
    one = n > 0 and group[0] != 0
    for i in range(n):
        if group[i] != group[0]:
            one = False
            break
    if one or n < 2:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64), reach
    limit = 4.0 * median + speculative
    big = np.empty(n, dtype=np.bool_)
    rows = np.empty(n, dtype=np.int64)
    nr, ends = 0, 0
    top = -np.inf  # the largest r of the grid's bodies (a nan kept, as numpy's max keeps it)
    for i in range(n):
        r = radius[i] + reach[i]
        big[i] = r > limit
        if big[i]:
            ends += 1
        else:
            rows[nr] = i
            nr += 1
            if r > top or r != r:
                if top == top:
                    top = r
    if nr:
        P = np.empty((nr, 2))
        for k in range(nr):
            P[k, 0], P[k, 1] = x[rows[k], 0], x[rows[k], 1]
        none = np.zeros(0)
        ga, gb = grid_pairs_loop(P, 2.0 * top + speculative, none, none, False)
    else:
        ga, gb = np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    m = len(ga)
    a = np.empty(m + ends * n, dtype=np.int64)
    b = np.empty(len(a), dtype=np.int64)
    for k in range(m):
        i, j = rows[ga[k]], rows[gb[k]]
        a[k], b[k] = min(i, j), max(i, j)
    for e in range(n):  # each big body with every other, a pair of big bodies once
        if not big[e]:
            continue
        for j in range(n):
            if j != e and not (big[j] and j < e):
                a[m], b[m] = min(e, j), max(e, j)
                m += 1
    return a[:m], b[:m], reach


@kernels.loop(sample=contacts_sample)
def contacts_loop(
    x: Any, q: Any, radius: Any, reach: Any, moving: Any, sensor: Any,
    group: Any, cats: Any, mask: Any, slots: Any, friction: Any, restitution: Any,
    body_circle: Any, body_index: Any, kind: Any, body_parts: Any, part_of: Any,
    pa: Any, pb: Any,
    owner: Any, bounds: Any, static_circle: Any, static_index: Any,
    c_sensor: Any, c_friction: Any, c_restitution: Any, c_surface: Any,
    c_group: Any, c_cats: Any, c_mask: Any,
    V: Any, Nrm: Any, cnt: Any, rad: Any, center: Any, rnd: Any, hp: Any, hn: Any,
    apart: Any, ignored: Any, warm_keys: Any, warm_lam: Any, vel: Any, dt: float, unit: float,
) -> tuple[Any, ...]:  # fmt: skip
    """The step's contacts (module doc). Bodies (n rows): pose ``x`` (n, 2) m and ``q`` rad,
    bounding ``radius`` m, ``reach`` (how far each can move in the step, m), ``moving``
    (pushed by contacts), ``sensor``, the filter's ``group``, ``cats``, ``mask``, ``slots``,
    ``friction``, ``restitution``, where the shape is in the tables (``body_circle``: the
    circles', else the polygons'; ``body_index``), its ``kind`` (engine.geometry.shaped: DISC,
    CAPSULE, POLYGON), these three by part (engine.geometry.shaped.Parts: ``body_parts`` (n, 2)
    each body's first part and how many, ``part_of`` (P, 2) each part's body and its number
    among the body's; a body of one shape is one part). ``pa``, ``pb``: the pairs to test,
    rows. Static shapes (K): the collider ``owner``, ``bounds`` (K, 4) xmin, ymin, xmax, ymax,
    ``static_circle``, ``static_index`` (a half plane h: -1 - h). Colliders (C, by place):
    sensor, friction, restitution, surface velocity (C, 2) m/s, filter. The tables
    (engine.geometry.narrowphase:
    polygons ``V``, ``Nrm``, ``cnt``, ``rad``; circles ``center``, ``rnd``), the half planes'
    points ``hp`` and unit normals ``hn`` (H, 2).
    ``apart``: sorted keys a n + b of pairs kept apart; ``ignored``: sorted keys row (C + 1)
    + place of faces pre_solve ignored; ``warm_keys`` sorted, ``warm_lam`` (k, 3): the last
    step's points, their impulses and held loads (N s a substep). ``vel`` (n, 2): the
    bodies' velocities (m/s) at the step's start, and ``dt`` the step (s): a round pair's
    point that its path passes by is dropped (engine.geometry.passing). ``unit``: the World's
    length units a metre (its ``length_units_per_meter``), which the speculative distance and
    the slop are scaled by.

    Returns the solver's contact arrays (engine.dynamics.solver.solve's ca ... chold, 16 of them),
    each point's key (2 per row), each row's static place (-1 for a body pair) and first point
    (x, y, m); the sensors' overlaps (rows, collider places)."""
    speculative = SPECULATIVE_DISTANCE * unit
    slop = LINEAR_SLOP * unit
    n = len(radius)
    k_shapes = len(owner)
    n_col = len(c_sensor)
    # -- 1. the body pairs -----------------------------------------------------------------
    box = body_boxes(x, q, radius, body_circle, body_index, body_parts, V, rad, center, rnd)
    cand_a = np.empty(len(pa) + n * k_shapes, dtype=np.int64)
    cand_b = np.empty(len(cand_a), dtype=np.int64)  # B's row, or n for a static shape
    cand_p = np.empty(len(cand_a), dtype=np.int64)  # the static shape, or -1
    m = 0
    for i in range(len(pa)):
        a, b = pa[i], pb[i]
        dx, dy = x[b, 0] - x[a, 0], x[b, 1] - x[a, 1]
        r = radius[a] + radius[b] + reach[a] + reach[b] + speculative
        if dx * dx + dy * dy > r * r:
            continue
        r = reach[a] + reach[b] + speculative
        if box[b, 0] - box[a, 2] > r or box[a, 0] - box[b, 2] > r:
            continue
        if box[b, 1] - box[a, 3] > r or box[a, 1] - box[b, 3] > r:
            continue
        if not (moving[a] or moving[b]) or sensor[a] or sensor[b]:
            continue
        if not radius[a] + radius[b] > 0.0:
            continue
        if group[a] != 0 and group[a] == group[b]:
            continue
        if (cats[a] & mask[b]) == 0 or (cats[b] & mask[a]) == 0:
            continue
        if len(apart):
            key = a * n + b
            at = np.searchsorted(apart, key)
            if at < len(apart) and apart[at] == key:
                continue
        cand_a[m], cand_b[m], cand_p[m] = a, b, -1
        m += 1
    # -- 1b. each body's reach toward a static shape: its own, or its reach and twice its
    # farthest partner's (engine.pipeline.game_broadphase.struck: a body struck from rest)
    face = reach.copy()
    for i in range(m):
        a, b = cand_a[i], cand_b[i]
        face[a] = max(face[a], reach[a] + 2.0 * reach[b])
        face[b] = max(face[b], reach[b] + 2.0 * reach[a])
    # -- 2. the static shapes ----------------------------------------------------------------
    sx0 = np.empty(k_shapes)
    sy0 = np.empty(k_shapes)
    sx1 = np.empty(k_shapes)
    sy1 = np.empty(k_shapes)
    hit = np.empty(k_shapes, dtype=np.bool_)
    for s in range(k_shapes):  # the boxes side by side: the test below in vector lanes
        sx0[s], sy0[s], sx1[s], sy1[s] = bounds[s, 0], bounds[s, 1], bounds[s, 2], bounds[s, 3]
    # A half plane's box is the whole plane, so every body would be its candidate (a room's
    # four walls: four pairs a body, each gathered and met, in a pit of 1,000 balls most of
    # its pairs). A pair's manifold keeps a point only where it is at most its group's
    # speculative margin apart (step 3), and that margin is the largest of the group's
    # ``face + speculative``: at most ``far``. A body whose bounding circle is
    # farther than ``far`` in front of the plane gets no point from it, and is left out here;
    # its margin is kept (``dropped``), so each group's margin, and every point of the
    # pairs that stay, is what it was with it (the numpy path's, which keeps every pair).
    far = -np.inf
    for a in range(n):
        far = max(far, face[a])
    far += speculative
    dropped = np.full(5, -np.inf)  # each group's margin among the pairs left out
    for a in range(n):
        if sensor[a]:
            continue  # (a sensor body meets no static shape)
        grow = radius[a] + face[a] + speculative
        lox, loy = x[a, 0] - grow, x[a, 1] - grow
        hix, hiy = x[a, 0] + grow, x[a, 1] + grow
        for s in range(k_shapes):
            hit[s] = (lox <= sx1[s]) & (hix >= sx0[s]) & (loy <= sy1[s]) & (hiy >= sy0[s])
        for s in range(k_shapes):
            if not hit[s]:
                continue
            c = owner[s]
            if not (moving[a] or c_sensor[c]) or sensor[a]:
                continue
            if group[a] != 0 and group[a] == c_group[c]:
                continue
            if (cats[a] & c_mask[c]) == 0 or (c_cats[c] & mask[a]) == 0:
                continue
            if len(ignored):
                key = a * (n_col + 1) + c
                at = np.searchsorted(ignored, key)
                if at < len(ignored) and ignored[at] == key:
                    continue
            if static_index[s] < 0:
                h = -1 - static_index[s]
                ahead = (x[a, 0] - hp[h, 0]) * hn[h, 0] + (x[a, 1] - hp[h, 1]) * hn[h, 1]
                # (A micrometre to spare, and more far from the origin: the manifold
                # measures from the shape's own centre and rounding, each within the body's
                # circle to the last bits of its coordinates.)
                spare = 1e-6 + 1e-12 * (abs(x[a, 0]) + abs(x[a, 1]) + abs(hp[h, 0]) + abs(hp[h, 1]))
                if ahead - radius[a] > far + spare:
                    r = face[a] + speculative  # (step 3's margin, as there)
                    for pu in range(body_parts[a, 1]):
                        g = 2 + kind[body_parts[a, 0] + pu]
                        dropped[g] = max(dropped[g], r)
                    continue
            cand_a[m], cand_b[m], cand_p[m] = a, n, s
            m += 1
    # -- 2b. the parts: a body of several shapes (engine.body_shapes) meets by every part of A
    # with every part of B, and each part with a static shape (the numpy path's order:
    # engine.pipeline.game_step.GameStep._collide); ``part_a``, ``part_b`` each candidate's
    # parts (B's -1 for a static shape), ``cand_a``, ``cand_b`` still their bodies.
    total = 0
    for i in range(m):
        many = body_parts[cand_a[i], 1]
        if cand_p[i] < 0:
            many *= body_parts[cand_b[i], 1]
        total += many
    part_a = np.empty(total, dtype=np.int64)
    part_b = np.empty(total, dtype=np.int64)
    if total == m:  # (one part a body among the candidates: the bodies' own rows)
        for i in range(m):
            part_a[i] = body_parts[cand_a[i], 0]
            part_b[i] = body_parts[cand_b[i], 0] if cand_p[i] < 0 else -1
    else:
        ea = np.empty(total, dtype=np.int64)
        eb = np.empty(total, dtype=np.int64)
        ep = np.empty(total, dtype=np.int64)
        e = 0
        for i in range(m):
            a, b, s = cand_a[i], cand_b[i], cand_p[i]
            for pu in range(body_parts[a, 1]):
                for pw in range(body_parts[b, 1] if s < 0 else 1):
                    ea[e], eb[e], ep[e] = a, b, s
                    part_a[e] = body_parts[a, 0] + pu
                    part_b[e] = body_parts[b, 0] + pw if s < 0 else -1
                    e += 1
        cand_a, cand_b, cand_p, m = ea, eb, ep, total
    # -- 3. the manifolds, by group --------------------------------------------------------
    # Groups: 0 polygon against polygon, 1 the round pairs, 2 to 4 a half plane against a
    # disc, a capsule, a polygon (the half plane as A). ``swap``: the manifold is B's to A's,
    # flipped back in the rows.
    group_of = np.empty(m, dtype=np.int64)
    swap = np.zeros(m, dtype=np.bool_)
    size = np.zeros(5, dtype=np.int64)
    margins = dropped  # (the pairs left out in step 2 count toward their group's margin)
    for i in range(m):
        a, b, s = cand_a[i], cand_b[i], cand_p[i]
        r = face[a] if s >= 0 else reach[a] + reach[b]
        r = r + speculative
        if s >= 0 and static_index[s] < 0:
            g = 2 + kind[part_a[i]]  # DISC, CAPSULE, POLYGON: 0, 1, 2
            swap[i] = True
        else:
            ca = body_circle[part_a[i]]
            cb = static_circle[s] if s >= 0 else body_circle[part_b[i]]
            g = 1 if ca or cb else 0
            swap[i] = ca and not cb
        group_of[i] = g
        size[g] += 1
        margins[g] = max(margins[g], r)
    start = np.zeros(6, dtype=np.int64)
    for g in range(5):
        start[g + 1] = start[g] + size[g]
    # Each group's pairs, gathered: A's shape and pose, B's (a static shape at the origin,
    # unturned).
    gi_a = np.empty(m, dtype=np.int64)
    gi_b = np.empty(m, dtype=np.int64)
    # (A half plane is at the origin, unturned: its group's A poses stay 0. Every B pose is
    # written below: no memset of what is written anyway, a few hundred kilobytes a step of
    # a pit's thousands of pairs.)
    gx_a = np.zeros((m, 2))
    gx_b = np.empty((m, 2))
    gq_a = np.zeros(m)
    gq_b = np.empty(m)
    flag = np.zeros(m, dtype=np.bool_)  # the round pairs': A is a circle
    where = np.empty(m, dtype=np.int64)  # each candidate's place among the gathered
    fill = start[:5].copy()
    for i in range(m):
        a, b, s = cand_a[i], cand_b[i], cand_p[i]
        g = group_of[i]
        j = fill[g]
        fill[g] += 1
        where[i] = j
        ia = body_index[part_a[i]]
        if g >= 2:  # the half plane -1 - index as A, at the origin; the body as B
            gi_a[j], gi_b[j] = -1 - static_index[s], ia
            gx_b[j, 0], gx_b[j, 1], gq_b[j] = x[a, 0], x[a, 1], q[a]
            continue
        ib = static_index[s] if s >= 0 else body_index[part_b[i]]
        xbx, xby, qb = 0.0, 0.0, 0.0
        if s < 0:
            xbx, xby, qb = x[b, 0], x[b, 1], q[b]
        flag[j] = body_circle[part_a[i]] and not swap[i]
        if swap[i]:  # the polygon as A
            gi_a[j], gi_b[j] = ib, ia
            gx_a[j, 0], gx_a[j, 1], gq_a[j] = xbx, xby, qb
            gx_b[j, 0], gx_b[j, 1], gq_b[j] = x[a, 0], x[a, 1], q[a]
        else:
            gi_a[j], gi_b[j] = ia, ib
            gx_a[j, 0], gx_a[j, 1], gq_a[j] = x[a, 0], x[a, 1], q[a]
            gx_b[j, 0], gx_b[j, 1], gq_b[j] = xbx, xby, qb
    # Each manifold: its normal, points, anchors, separations and features. Every pair of the
    # groups the manifold kernels take is copied whole from theirs below; a half plane
    # against a disc (group 2) writes its one point where it is near, so its pairs start as
    # a manifold of no point (no point, separations inf, features -1: what the rows read of
    # a point past ``count``).
    normal = np.empty((m, 2))
    count = np.empty(m, dtype=np.int64)
    point = np.empty((m, 2, 2))
    anchor_a = np.empty((m, 2, 2))
    anchor_b = np.empty((m, 2, 2))
    separation = np.empty((m, 2))
    feature = np.empty((m, 2), dtype=np.int64)
    for j in range(start[2], start[3]):
        count[j] = 0
        for c in range(2):
            separation[j, c], feature[j, c] = np.inf, -1
            for d in range(2):
                point[j, c, d], anchor_a[j, c, d], anchor_b[j, c, d] = 0.0, 0.0, 0.0
    # (Each group's arrays as slices: numba keeps a slice of a C-contiguous array's first
    # index C-contiguous, the kernels' sample types.)
    for g in (0, 1, 3, 4):
        lo, hi = start[g], start[g + 1]
        if lo == hi:
            continue
        if g == 0:
            out = polygon_loop(
                V, Nrm, cnt, rad, gi_a[lo:hi], gx_a[lo:hi], gq_a[lo:hi],
                V, Nrm, cnt, rad, gi_b[lo:hi], gx_b[lo:hi], gq_b[lo:hi],
                margins[g],
            )  # fmt: skip
        elif g == 1:
            out = round_loop(
                V, Nrm, cnt, rad, center, rnd, flag[lo:hi], gi_a[lo:hi],
                gx_a[lo:hi], gq_a[lo:hi], gi_b[lo:hi], gx_b[lo:hi],
                gq_b[lo:hi], margins[g],
            )  # fmt: skip
        else:  # a capsule is the tables' two-vertex polygon
            out = half_plane_polygon_loop(
                hp, hn, gi_a[lo:hi], gx_a[lo:hi], gq_a[lo:hi], V, Nrm, cnt,
                rad, gi_b[lo:hi], gx_b[lo:hi], gq_b[lo:hi], margins[g],
            )  # fmt: skip
        # Row by row, not by slices: a slice's assignment checks the shapes and compiles
        # numba's message for a mismatch (3.4 s of a cold compile).
        for j in range(hi - lo):
            r = lo + j
            count[r] = out[1][j]
            for c in range(2):
                normal[r, c] = out[0][j, c]
                separation[r, c], feature[r, c] = out[5][j, c], out[6][j, c]
                for d in range(2):
                    point[r, c, d] = out[2][j, c, d]
                    anchor_a[r, c, d], anchor_b[r, c, d] = out[3][j, c, d], out[4][j, c, d]
    # A half plane against a disc (engine.geometry.manifold.collide_half_plane_circle, its products
    # in its order): the plane at the origin, unturned, so A's frame is the world's.
    for j in range(start[2], start[3]):
        h, b = gi_a[j], gi_b[j]
        co, si = np.cos(0.0), np.sin(0.0)
        dx, dy = gx_b[j, 0] - 0.0, gx_b[j, 1] - 0.0
        ox, oy = co * dx + si * dy, -si * dx + co * dy
        rel = gq_b[j] - 0.0
        cr, sr = np.cos(rel), np.sin(rel)
        vx, vy = center[b, 0], center[b, 1]
        cx, cy = cr * vx - sr * vy + ox, sr * vx + cr * vy + oy
        nx, ny = hn[h, 0], hn[h, 1]
        d = (cx - hp[h, 0]) * nx + (cy - hp[h, 1]) * ny
        rb = rnd[b]
        ax_, ay_ = cx - d * nx, cy - d * ny
        bx_, by_ = cx - rb * nx, cy - rb * ny
        gap = d - rb
        normal[j, 0], normal[j, 1] = co * nx - si * ny, si * nx + co * ny
        if gap <= margins[2]:
            mx, my = 0.5 * (ax_ + bx_), 0.5 * (ay_ + by_)
            wx, wy = co * mx - si * my, si * mx + co * my
            anchor_a[j, 0, 0], anchor_a[j, 0, 1] = wx, wy
            point[j, 0, 0], point[j, 0, 1] = wx + 0.0, wy + 0.0
            anchor_b[j, 0, 0] = wx + (0.0 - gx_b[j, 0])
            anchor_b[j, 0, 1] = wy + (0.0 - gx_b[j, 1])
            separation[j, 0], feature[j, 0] = gap, 0
            count[j] = 1
    # -- 3b. a body's round point against a static shape kept for reach that its path passes
    # by is dropped (engine.geometry.passing; engine.geometry.narrowphase.collide_pairs'
    # products, in its order; a pair of bodies keeps its points)
    lo, hi = start[1], start[2]
    ask = np.empty(hi - lo, dtype=np.int64)  # the group's places asked, in its order
    n_ask = 0
    for j in range(lo, hi):
        if count[j] > 0 and separation[j, 0] > speculative:
            ask[n_ask] = j
            n_ask += 1
    if n_ask:
        asked = np.zeros(hi - lo, dtype=np.bool_)
        u = np.zeros((hi - lo, 2))
        slack = np.zeros(hi - lo)
        for i in range(m):
            j = where[i] - lo
            if group_of[i] != 1 or cand_p[i] < 0:
                continue
            a = cand_a[i]
            vx, vy = vel[a, 0], vel[a, 1]
            slack[j] = slop + max(face[a] - np.sqrt(vx * vx + vy * vy) * dt, 0.0)
            if swap[i]:  # the shape as A: the body moves by its own
                u[j, 0], u[j, 1] = (vx - 0.0) * dt, (vy - 0.0) * dt
            else:
                u[j, 0], u[j, 1] = (0.0 - vx) * dt, (0.0 - vy) * dt
            asked[j] = True
        k = 0
        for t in range(n_ask):
            if asked[ask[t] - lo]:
                ask[k] = ask[t]
                k += 1
        if k:
            at = ask[:k]
            keep = passing_loop(
                V, cnt, rad, center, rnd, flag[at], gi_a[at], gx_a[at], gq_a[at], gi_b[at],
                gx_b[at], gq_b[at], u[at - lo], slack[at - lo],
            )  # fmt: skip
            for t in range(k):
                if not keep[t]:
                    count[at[t]] = 0
    # -- 4. the rows, in the broadphase's order ------------------------------------------------
    rows = 0
    sensing = 0
    for i in range(m):
        j = where[i]
        if count[j] == 0:
            continue
        s = cand_p[i]
        if s >= 0 and c_sensor[owner[s]]:
            sensing += 1
        else:
            rows += 1
    ca_ = np.empty(rows, dtype=np.int64)
    cb_ = np.empty(rows, dtype=np.int64)
    nx_ = np.empty(rows)
    ny_ = np.empty(rows)
    count_ = np.empty(rows, dtype=np.int64)
    rax = np.empty(2 * rows)
    ray = np.empty(2 * rows)
    rbx = np.empty(2 * rows)
    rby = np.empty(2 * rows)
    sep = np.empty(2 * rows)
    fric = np.empty(rows)
    rest = np.empty(rows)
    speed = np.zeros(rows)
    ln = np.zeros(2 * rows)
    lt = np.zeros(2 * rows)
    lh = np.zeros(2 * rows)
    keys = np.empty(2 * rows, dtype=np.int64)
    place = np.empty(rows, dtype=np.int64)
    px = np.empty(rows)
    py = np.empty(rows)
    sense_row = np.empty(sensing, dtype=np.int64)
    sense_place = np.empty(sensing, dtype=np.int64)
    # The warm start's keys by hash (open addressing, linear probing): each key's first place
    # in ``warm_keys``, the place a binary search finds, in a probe or two (numba's
    # searchsorted took about 55 ns a point, most of this loop's time on a pile).
    wn = len(warm_keys)
    bits = 4
    while (1 << bits) < 2 * wn:
        bits += 1
    full = (1 << bits) - 1
    table = np.full(full + 1, -1, dtype=np.int64)
    for i in range(wn):
        key = warm_keys[i]
        h = (key >> 37) * 73856093 + (key >> 16 & 2097151) * 19349663  # (A's slot, B's code,
        h = (h + (key & 65535) * 83492791) & full  # the feature: each times a prime)
        while table[h] >= 0 and warm_keys[table[h]] != key:
            h = (h + 1) & full
        if table[h] < 0:
            table[h] = i
    k = 0
    z = 0
    for i in range(m):
        j = where[i]
        if count[j] == 0:
            continue
        a, b, s = cand_a[i], cand_b[i], cand_p[i]
        flip = swap[i]
        if s >= 0 and c_sensor[owner[s]]:
            if separation[j, 0] < 0.0 or separation[j, 1] < 0.0:
                sense_row[z], sense_place[z] = a, owner[s]
                z += 1
            continue
        sign = -1.0 if flip else 1.0
        nx, ny = sign * normal[j, 0], sign * normal[j, 1]
        ca_[k], cb_[k], nx_[k], ny_[k], count_[k] = a, b, nx, ny, count[j]
        place[k] = s
        px[k], py[k] = point[j, 0, 0], point[j, 0, 1]
        code_b = slots[b] if s < 0 else STATIC + s
        code = (slots[a] << OTHER) | code_b
        # The parts' numbers above the pair's code (``PART``; 0 for bodies of one shape).
        number = part_of[part_a[i], 1] * MAX_PARTS
        if s < 0:
            number += part_of[part_b[i], 1]
        code |= number << (PART - FEATURE)
        for p in range(2):
            t = 2 * k + p
            if flip:
                rax[t], ray[t] = anchor_b[j, p, 0], anchor_b[j, p, 1]
                rbx[t], rby[t] = anchor_a[j, p, 0], anchor_a[j, p, 1]
            else:
                rax[t], ray[t] = anchor_a[j, p, 0], anchor_a[j, p, 1]
                rbx[t], rby[t] = anchor_b[j, p, 0], anchor_b[j, p, 1]
            gap = separation[j, p]
            sep[t] = gap if np.isfinite(gap) else 0.0
            f = feature[j, p]
            if flip and f >= 0:
                f = (f & 255) << 8 | (f >> 8)
            key = (code << FEATURE) | (f if f >= 0 else 0)
            keys[t] = key
            if p < count[j] and wn:
                h = (key >> 37) * 73856093 + (key >> 16 & 2097151) * 19349663
                h = (h + (key & 65535) * 83492791) & full
                while table[h] >= 0:
                    at = table[h]
                    if warm_keys[at] == key:
                        ln[t], lt[t], lh[t] = warm_lam[at, 0], warm_lam[at, 1], warm_lam[at, 2]
                        break
                    h = (h + 1) & full
        # Materials: friction mu_a mu_b, restitution e_a e_b; a conveyor's surface speed.
        if s < 0:
            mu_b, e_b = friction[b], restitution[b]
        else:
            c = owner[s]
            mu_b, e_b = c_friction[c], c_restitution[c]
            tx, ty = -ny, nx
            speed[k] = -(c_surface[c, 0] * tx + c_surface[c, 1] * ty)
        fric[k] = friction[a] * mu_b
        rest[k] = restitution[a] * e_b
        k += 1
    return (ca_, cb_, nx_, ny_, count_, rax, ray, rbx, rby, sep, fric, rest, speed, ln, lt, lh,
            keys, place, px, py, sense_row[:z], sense_place[:z])  # fmt: skip


def _sample_report() -> tuple[Any, ...]:
    """The smallest call of ``report_loop``: a box resting on a segment by two points, and
    a disc against the box by one."""
    i = np.array([0, 1], dtype=np.int64)
    b = np.array([2, 0], dtype=np.int64)
    normal = np.array([0.0, 1.0])
    count = np.array([2, 1], dtype=np.int64)
    sep = np.array([0.0, 0.001, 0.002, 0.0])
    keys = np.array([1, 2, 3, 0], dtype=np.int64)
    place = np.array([0, -1], dtype=np.int64)
    point = np.zeros(2)
    lam = np.array([0.1, 0.1, 0.0, 0.0])
    slots = np.array([0, 1], dtype=np.int64)
    owner = np.zeros(1, dtype=np.int64)
    return (i, b, normal, normal, count, sep, keys, place, point, point, lam, lam, lam, lam, slots,
            owner, owner + 1, 4, 0.005)  # fmt: skip


@kernels.loop(sample=_sample_report)
def report_loop(
    ca: Any, cb: Any, nx: Any, ny: Any, count: Any, sep: Any, keys: Any, place: Any,
    px: Any, py: Any, ln: Any, lt: Any, lh: Any, total: Any, slots: Any, owner: Any,
    serial: Any,
    substeps: int, slop: float,
) -> tuple[Any, ...]:  # fmt: skip
    """What the solved contacts leave (engine.pipeline.game_step's ``_keep`` and ``_events`` as one
    loop, their products in their order): each point's impulses by key, sorted, for the next
    step's warm start; and the contacts that touch (a point that pushed in the step, or one
    nearer than ``slop`` at its start), each with its event key (engine.dynamics.events: the bodies'
    slots, or the slot and the collider's ``serial`` by place), first point (m), the normal
    toward the key's first body and the impulse on it over the step (N s), sorted by key.

    ``ca`` ... ``sep``, ``keys``, ``place``, ``px``, ``py``: the contacts as
    ``contacts_loop`` gave them; ``ln``, ``lt``, ``lh``, ``total``: the solver's impulses (a
    substep's normal and tangent, the held load, the step's normal); ``slots`` by row,
    ``owner`` each static shape's collider place. Returns the kept keys and impulses and held
    loads ((k, 3)), then the touching contacts' keys and their points, normals and impulses as
    the columns of one table (t, 6)."""
    n = len(slots)
    k = len(ca)
    real = 0
    for i in range(k):
        real += count[i]
    kept = np.empty(real, dtype=np.int64)
    lam = np.empty((real, 3))
    r = 0
    for i in range(k):
        for p in range(count[i]):
            kept[r] = keys[2 * i + p]
            lam[r, 0], lam[r, 1], lam[r, 2] = ln[2 * i + p], lt[2 * i + p], lh[2 * i + p]
            r += 1
    order = stable_order(kept)  # stable, as numpy's
    touch = np.zeros(k, dtype=np.bool_)
    t = 0
    for i in range(k):
        for p in range(count[i]):
            if total[2 * i + p] > 0.0 or sep[2 * i + p] < slop:
                touch[i] = True
        if touch[i]:
            t += 1
    event = np.empty(t, dtype=np.int64)
    table = np.empty((t, 6))  # each one's point, normal and impulse
    e = 0
    for i in range(k):  # the event keys first, to sort the touching contacts by them
        if not touch[i]:
            continue
        a, b = ca[i], cb[i]
        if b < n:
            lo, hi = min(slots[a], slots[b]), max(slots[a], slots[b])
            event[e] = (lo << 32) | hi
        else:
            event[e] = (slots[a] << 32) | (serial[owner[place[i]]] | COLLIDER)
        e += 1
    by_key = stable_order(event)  # stable, as numpy's
    e = 0
    for i in range(k):
        if not touch[i]:
            continue
        a, b = ca[i], cb[i]
        first = 1.0
        if b < n and slots[a] > slots[b]:
            first = -1.0
        # The impulse on A, -(lam_n n + lam_t t), t = (-n_y, n_x), over the whole step.
        # (Summed as numpy's sum of two: the first, plus 0.0 + the second; -0.0 + -0.0 is
        # +0.0 so, and the events' zeros keep numpy's signs.)
        tn = total[2 * i] + (0.0 + total[2 * i + 1])
        tt = (lt[2 * i] + (0.0 + lt[2 * i + 1])) * substeps
        jx = -(tn * nx[i] + tt * -ny[i])
        jy = -(tn * ny[i] + tt * nx[i])
        table[e, 0], table[e, 1] = px[i], py[i]
        table[e, 2], table[e, 3] = -nx[i] * first, -ny[i] * first
        table[e, 4], table[e, 5] = jx * first, jy * first
        e += 1
    return kept[order], lam[order], event[by_key], table[by_key]
