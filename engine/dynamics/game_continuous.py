"""The soft step's continuous collision: fast bodies swept to their time of impact.

The soft step's contacts are speculative (engine.pipeline.game_step): each pair within what it can
close in the step gets rows taken along the features nearest at the step's start. A thin box turning
a third of a radian a step and thrown at 200 m/s meets a thin wall with another corner than
those, and a row cannot stop a feature it does not hold: the box ends the step through the
wall. Box2D v3 answers it after the solve (``b2SolveContinuous`` in its src/solver.c), and so
does this stage, on both paths (``continuous_loop``: the fast path's compiled kernel, the numpy
path its plain-Python twin, so the same bits):

* **fast bodies**: a dynamic, awake body that is no sensor and moved far for its size in the
  step, |x1 - x0| + |q1 - q0| R > ``SAFETY`` e (e its least extent: a disc's or capsule's
  radius, a polygon's least distance from its centroid to an edge plus its rounding, Box2D's
  ``safetyFactor`` and ``minExtent``; R its core's farthest point from its centre, where
  Box2D takes the shape's: a disc that rolls does not move its surface by turning). A body
  that rests, slides, rolls or falls a little is never one, and a step with none costs next
  to nothing: a test from above (|dx| + |dy| for the move) in numpy, or at the end of the
  fast path's compiled step (engine.pipeline.game_loop's ``step_loop``, which says ``maybe``);
* **deep bodies**: one that ends the step deeper than ``DEEP`` of its least extent in what the
  solve does not move, by its contacts' rows (``ended_depth``: each point's separation moved
  with its bodies, as the solver's), is swept too: a light body squeezed into a wall by a
  heavy one, which the rows give way to (a 0.11 kg capsule struck at 50 m/s between a 3 kg box
  and a wall ended 0.17 m in it; tests/test_fuzz_shapes.py). It touches the wall as the step
  begins, so the sweep below stops it a slop deeper than it began;
* **the sweep**: a fast body moves from its pose at the step's start (x0, q0) to its end
  (x1, q1) as pose(t) = (x0 + t (x1 - x0), q0 + t (q1 - q0)), t the fraction of the step, and
  is swept against what its swept box meets: the static colliders (their filters passed, a
  sensor's or a face pre_solve ignored left out) and the bodies that do not move by the solve
  and stand still (static ones, and kinematic ones at rest); a bullet (``Body.bullet``, Box2D's
  ``isBullet``; off by default, as Box2D's) against the moving kinematic bodies too, and the
  dynamic bodies that are not bullets (Box2D's rule: two bullets are each other's solve's),
  each where the solve leaves it, at its end pose, still (Box2D's: a body the solve moved is
  swept from its end pose to its end pose), so the order of the fast bodies does not matter.
  (On the moving body's own sweep, a ball that a pinball's bat carried up at 40 rad/s, a few
  millimetres into it under the load that turns it, came within the time of impact's target
  of the bat early in a step and was set back there, while the bat went on a third of a
  radian to its end pose: its centre ended inside the bat, 1.05 to 1.25 of its radius deep;
  so 0.29 to 0.39: tests/test_soft_continuous.py.) (Box2D sweeps a body that is no bullet
  against static shapes alone. Swept
  against a turning kinematic wall too, the boxes a tumbler's wall carries at 6 m/s were set
  back from the poses the solve gave them, and into the boxes it did not set back: two boxes
  went 186 mm into each other where 50 of them tumble at 25 degrees a second, 40 mm so (42
  mm since the solver bounds an impact's held change: engine.dynamics.solver); and at 90
  degrees a second, 500 boxes, 64 centres passed a wall, none so:
  tests/test_soft_continuous.py);
* **the impact**: where the first time of impact t < 1 is found, the body is set back to
  pose(t), its velocities kept (Box2D's), so that it stops before the wall and the next step's
  speculative contacts, taken there, hold it.

**Time of impact** (``toi`` in the kernel): conservative advancement (Mirtich's) on the
distance of the two shapes' cores (a shape less its rounding: a disc's centre, a capsule's
segment, a polygon's corners). At time t, with the cores d apart and n the unit normal from
A's closest point p_A to B's, the line through p_A across n separates them: A is behind it, B
at least d in front. A point at r from its body's centre c is at c(s) + R(q(s)) r; from t to s
it moves along n by (s - t) n.dc (dc the centre's move over the whole step) plus
n.(R(q(s)) r - R(q(t)) r), at most |q(s) - q(t)| |r| = (s - t) |dq| |r| (a chord is no longer
than its arc). So the gap along n closes by at most (s - t) w, with

    w = n.(dc_A - dc_B) + |dq_A| R_A + |dq_B| R_B,

R a core's farthest point from its body's centre: the cores cannot come within ``target`` of
each other before t + (d - target) / w, which is the next t (w <= 0: they never do in the
step). It stops where d < target + tol (Box2D's b2TimeOfImpact: target = max(slop, r_A + r_B -
slop) with r the roundings, so flat shapes stop a slop apart and rounded ones a slop into each
other; tol = slop / 4), or after ``ITERATIONS`` advances at the t reached (safe: nothing
touched before it). The distance of two convex cores is 0 where they overlap (the separating
axes of their edges' normals, and of a segment's direction, say so), else the least distance
of a corner of one from an edge of the other.

**A pair that touches at the step's start** (t = 0) is swept twice more, and the earlier
impact of the two is taken:

* with the body's core circle (its centroid, radius ``CORE`` e), as Box2D's fallback does,
  which stops a centre about to pass through a wall;
* where A does not move in the step (a collider, a static body, a kinematic one at rest),
  with its whole shape, to where the cores come a slop nearer than they were at the start
  (target min(target, d(0) - slop), at least 0, but for a half plane, whose distance is its
  corners' least, signed: a thin triangle flipped off a floor at 59 rad/s swung its other end
  0.257 m into it while the target was held at 0, where its distance already was; and for
  cores that overlap at the start, whose distance is 0 however deep: there d is B's
  separation along the best of A's edge normals, signed, and its closing speed bounded by
  B's whole motion, so a light polygon battered into a corner of polygon walls goes a slop
  deeper a step, not 6 cm): the conservative advancement above holds for any target below
  d(0). A capsule that struck a
  wall with one end and spins off it at 98 rad/s swings its other end a quarter turn into
  the wall within the next step, a feature none of the
  step's rows held (the speculative rows are the nearest features at the start); Box2D's
  fallback alone lets it end 0.112 m in (tests/test_fuzz_shapes.py), this sweep 8 mm. A
  body sliding or rolling along a floor keeps its distance from it and is stopped by
  neither. Against a body the solve moved it is not taken: its start would be B's start
  against A's end pose, not where the two were (a bullet ball set back on a flipping bat
  that way, when A was swept on its own sweep, ended inside the bat or past it in 4 of
  demos.bench.pinball's 40 throws, where it passes none).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import kernels
from ..geometry import narrowphase
from ..geometry.manifold_kinds import LINEAR_SLOP
from .turning_faces import (
    FACE_A,
    FACE_NUMBERS,
    ROUND,
    face_gap,
    face_start,
    round_gap,
    round_start,
)  # fmt: skip

__all__ = ["CORE", "Continuous", "DEEP", "ITERATIONS", "SAFETY", "continuous_loop", "ended_depth"]

#: A body is fast when it moves more than this share of its least extent in a step (Box2D's
#: default ``safetyFactor``).
SAFETY = 0.5
#: The core circle's radius, in the body's least extent (Box2D's ``B2_CORE_FRACTION``).
CORE = 0.25
#: Conservative advancement stops after this many advances, at the time reached.
ITERATIONS = 30
#: A body is swept too when a point of its contacts with what does not move ends the step
#: deeper than this share of its least extent (``ended_depth``: a light body squeezed into a
#: wall by a heavy one, which the solve's rows give way to).
DEEP = 0.25


def _ended_sample() -> tuple[Any, ...]:
    """The smallest call of ``ended_depth``: a unit box (row 0) on the static body (row 1)."""
    i64 = np.int64
    return (
        np.array([[0.0, 0.5]]), np.zeros(1), np.array([[0.0, 0.45]]), np.zeros(1),
        np.array([True, False]), np.array([1], dtype=i64), np.array([0], dtype=i64),
        np.array([0.0]), np.array([1.0]), np.array([2], dtype=i64),
        np.array([-0.5, 0.5]), np.zeros(2), np.array([-0.5, 0.5]), np.array([-0.5, -0.5]),
        np.zeros(2), np.zeros(1, dtype=i64), np.zeros(FACE_NUMBERS),
    )  # fmt: skip


@kernels.loop(sample=_ended_sample)
def ended_depth(
    x0: Any, q0: Any, x1: Any, q1: Any, moving: Any, ca: Any, cb: Any, nx: Any, ny: Any,
    count: Any, rax: Any, ray: Any, rbx: Any, rby: Any, sep: Any, face: Any, fround: Any,
) -> Any:  # fmt: skip
    """Each body's least separation at the step's end (m; inf: none) at its contacts' points
    with what the solve does not move, and the deepest overlap at the end at any of the rows
    (m, >= 0: the pile's, which the World warns of), from the rows: bodies at
    poses ``x0`` (n, 2) m, ``q0`` rad at the step's start and ``x1``, ``q1`` at its end,
    ``moving`` (n + 1: the static body last) those the solve moves; the solver's contacts
    (engine.dynamics.solver.solve's ``ca`` ... ``csep``: bodies, normal from A to B, points,
    anchors about each body at the start, separation then). A point's separation moves with
    its bodies as the solver's (its ``gap``): sep + (dx_B - dx_A).n + (r_B x n) sin(dq_B) -
    (r_A x n) sin(dq_A); a point's on a face that turns (``face``, ``fround``: the rows' kinds
    and rounding radii, engine.dynamics.turning_faces.face_rows) exactly, as the face and the
    point are at the end (that module's ``face_gap``), and one between a disc and a static
    shape's round feature likewise (``round_gap``). Returns (the least separations (n,),
    the deepest overlap)."""
    n = len(q0)
    out = np.full(n, np.inf)
    pile = 0.0
    # Each body's turn in the step, its cosine and sine (the static body's last: none).
    tc = np.ones(n + 1)
    ts = np.zeros(n + 1)
    for i in range(n):
        tc[i] = math.cos(q1[i] - q0[i])
        ts[i] = math.sin(q1[i] - q0[i])
    for k in range(len(ca)):
        a = ca[k]
        b = cb[k]
        if not moving[a] and not moving[b]:
            continue
        both = moving[a] and moving[b]
        mover = a if moving[a] else b
        mx, my = 0.0, 0.0
        if a < n:
            mx, my = mx - (x1[a, 0] - x0[a, 0]), my - (x1[a, 1] - x0[a, 1])
        if b < n:
            mx, my = mx + (x1[b, 0] - x0[b, 0]), my + (x1[b, 1] - x0[b, 1])
        fa = a if a < n else n
        fb = b if b < n else n
        sa, sb = ts[fa], ts[fb]
        for j in range(count[k]):
            p = 2 * k + j
            if face[k] >= ROUND:
                # (A disc and a static shape's core: their distance, as the solver takes it.)
                ox = (x1[b, 0] if b < n else 0.0) - (x1[a, 0] if a < n else 0.0)
                oy = (x1[b, 1] if b < n else 0.0) - (x1[a, 1] if a < n else 0.0)
                f = FACE_NUMBERS * k
                ra, rb = fround[f], fround[f + 1]
                # (A SEGMENT's ends are a static shape's: the world's axes, its origin.)
                eax, eay, e1x, e1y, e2x, e2y = round_start(
                    face[k], nx[k], ny[k], rax[p], ray[p], rbx[p], rby[p], sep[p], ra, rb,
                    fround[f + 2], fround[f + 3], fround[f + 4], fround[f + 5],
                )  # fmt: skip
                gap = round_gap(
                    nx[k], ny[k], ox, oy, tc[fa], ts[fa], tc[fb], ts[fb], eax, eay, e1x, e1y,
                    e2x, e2y, ra, rb,
                )[0]  # fmt: skip
            elif face[k] != 0:
                # (A point on a face that turns: the rows' own offsets, as the solver takes
                # them.)
                r = fround[FACE_NUMBERS * k]
                n0x, n0y = nx[k], ny[k]
                ox = (x1[b, 0] if b < n else 0.0) - (x1[a, 0] if a < n else 0.0)
                oy = (x1[b, 1] if b < n else 0.0) - (x1[a, 1] if a < n else 0.0)
                ex, ey, f0 = face_start(
                    face[k], n0x, n0y, rax[p], ray[p], rbx[p], rby[p], sep[p], r
                )
                f, d = (fa, fb) if face[k] == FACE_A else (fb, fa)
                gap = face_gap(
                    face[k], n0x, n0y, ox, oy, tc[f], ts[f], tc[d], ts[d], ex, ey, r, f0
                )[0]
            else:
                rna = rax[p] * ny[k] - ray[p] * nx[k]
                rnb = rbx[p] * ny[k] - rby[p] * nx[k]
                gap = sep[p] + mx * nx[k] + my * ny[k] + rnb * sb - rna * sa
            if -gap > pile:
                pile = -gap
            if not both and gap < out[mover]:
                out[mover] = gap
    return out, pile


def _sample() -> tuple[Any, ...]:
    """The smallest call of ``continuous_loop``: a 0.1 by 1 m box (polygon 0) that moved 5 m
    through a static wall (polygon 1, a 0.05 m plate), a disc (circle 0) standing by, a
    half plane (the floor) far below."""
    i64 = np.int64
    box = np.array([[-0.05, -0.5], [0.05, -0.5], [0.05, 0.5], [-0.05, 0.5]])
    wall = box * np.array([0.5, 10.0])
    normals = np.array([[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])
    x0 = np.array([[-3.0, 0.0], [0.0, 3.0]])
    x1 = np.array([[2.0, 0.0], [0.0, 3.0]])
    q0, q1 = np.zeros(2), np.array([0.3, 0.0])
    bodies = (
        np.array([0.05, 0.5]), np.array([0.5025, 0.0]), np.zeros((2, 2)), np.array([0.5025, 0.5]),
        np.zeros(2, dtype=bool), np.ones(2), np.zeros(2, dtype=bool), np.array([True, False]),
        np.zeros(2, dtype=i64),
        np.ones(2, dtype=i64), np.ones(2, dtype=i64), np.array([False, True]),
        np.array([0, 0], dtype=i64), np.zeros(0, dtype=i64),
    )  # fmt: skip
    statics = (
        np.array([0, 1], dtype=i64),
        np.array([[-0.025, -5.0, 0.025, 5.0], [-np.inf, -np.inf, np.inf, np.inf]]),
        np.zeros(2, dtype=bool), np.array([1, -1], dtype=i64), np.zeros(2, dtype=bool),
        np.zeros(2, dtype=i64), np.ones(2, dtype=i64), np.ones(2, dtype=i64),
        np.zeros(0, dtype=i64),
    )  # fmt: skip
    tables = (
        np.stack([box, wall]), np.stack([normals, normals]), np.array([4, 4], dtype=i64),
        np.zeros(2), np.zeros((1, 2)), np.array([0.5]), np.array([[0.0, -10.0]]),
        np.array([[0.0, 1.0]]),
    )  # fmt: skip
    return (x0, q0, x1, q1, np.full(2, np.inf), *bodies, *statics, *tables, 0.005)


@kernels.loop(sample=_sample)
def continuous_loop(
    x0: Any, q0: Any, x1: Any, q1: Any, ended: Any,
    least: Any, core: Any, centroid: Any, reach: Any, kinematic: Any, mass: Any, sensor: Any,
    bullet: Any, group: Any, cats: Any, mask: Any, body_circle: Any, body_index: Any, apart: Any,
    owner: Any, bounds: Any, static_circle: Any, static_index: Any, c_sensor: Any,
    c_group: Any, c_cats: Any, c_mask: Any, ignored: Any,
    V: Any, Nrm: Any, cnt: Any, rad: Any, center: Any, rnd: Any, hp: Any, hn: Any,
    slop: float,
) -> tuple[Any, Any, Any, int]:  # fmt: skip
    """The fast bodies swept to their first time of impact (module doc).

    Bodies (n): poses at the step's start ``x0`` (n, 2) m, ``q0`` rad and end ``x1``, ``q1``;
    ``ended`` each one's least separation at the end from what the solve does not move
    (m; ``ended_depth``: swept too where deeper than ``DEEP`` of its least extent);
    ``least`` each one's least extent (m), ``core`` its core's farthest point from its centre
    (m), ``centroid`` (n, 2) its shape's centroid in its frame (m), ``reach`` its bounding
    radius (m); ``kinematic``, ``mass`` (kg; inf: static), ``sensor``, ``bullet`` (swept
    against the dynamic bodies that are not bullets too: Box2D's), the filters ``group``,
    ``cats``, ``mask``; its shape in the tables (``body_circle``, ``body_index``:
    engine.geometry.narrowphase.Places); ``apart`` the pairs kept apart (sorted keys
    a n + b, a < b). Static shapes (k): ``owner`` each one's collider place, ``bounds`` (k, 4)
    its box, ``static_circle``, ``static_index`` its place in the tables (a half plane h as
    -1 - h); the colliders' ``c_sensor``, ``c_group``, ``c_cats``, ``c_mask`` by place;
    ``ignored`` the faces pre_solve left out (sorted keys row (colliders + 1) + place). The
    tables: polygons ``V``, ``Nrm`` (P, M, 2), ``cnt``, ``rad``; circles ``center`` (C, 2),
    ``rnd``; half planes ``hp``, ``hn`` (H, 2). ``slop``: the linear slop (m). A bullet meets
    each dynamic body on its sweep of the solve (so the order of the fast bodies does not
    matter).

    Returns the rows set back (int64, ascending), their poses at the impact ((k, 2) m, (k,)
    rad) and the number of fast bodies found."""
    n = len(reach)
    m = V.shape[1]
    places = len(c_sensor)
    va = np.zeros((m, 2))  # A's core corners and edge normals at the pose in hand (world)
    na = np.zeros((m, 2))
    vb = np.zeros((m, 2))  # B's (the fast body's)
    nb = np.zeros((m, 2))
    tol = 0.25 * slop

    def load(
        v: Any, nv: Any, circle: bool, j: int, px: float, py: float, q: float
    ) -> tuple[int, float]:
        """Shape ``j`` of the tables (a circle's or a polygon's) at pose (px, py, q) into
        ``v``, ``nv`` (world): its corner count and rounding (m)."""
        c, s = math.cos(q), math.sin(q)
        if circle:
            v[0, 0] = c * center[j, 0] - s * center[j, 1] + px
            v[0, 1] = s * center[j, 0] + c * center[j, 1] + py
            return 1, rnd[j]
        k = cnt[j]
        for i in range(k):
            v[i, 0] = c * V[j, i, 0] - s * V[j, i, 1] + px
            v[i, 1] = s * V[j, i, 0] + c * V[j, i, 1] + py
            nv[i, 0] = c * Nrm[j, i, 0] - s * Nrm[j, i, 1]
            nv[i, 1] = s * Nrm[j, i, 0] + c * Nrm[j, i, 1]
        return k, rad[j]

    def overlap(ka: int, kb: int) -> float:
        """The largest separation of A's and B's cores along a separating axis: each
        polygon's (and capsule's) edge normals, a segment's direction (<= 0: they overlap)."""
        sep = -math.inf
        for i in range(ka if ka >= 2 else 0):
            low = math.inf
            for j in range(kb):
                low = min(low, na[i, 0] * (vb[j, 0] - va[i, 0]) + na[i, 1] * (vb[j, 1] - va[i, 1]))
            sep = max(sep, low)
        for j in range(kb if kb >= 2 else 0):
            low = math.inf
            for i in range(ka):
                low = min(low, nb[j, 0] * (va[i, 0] - vb[j, 0]) + nb[j, 1] * (va[i, 1] - vb[j, 1]))
            sep = max(sep, low)
        for side in range(2):
            k = ka if side == 0 else kb
            if k != 2:
                continue
            # A segment's own direction e: the two shadows [lo, hi] on it apart.
            if side == 0:
                ex, ey = va[1, 0] - va[0, 0], va[1, 1] - va[0, 1]
            else:
                ex, ey = vb[1, 0] - vb[0, 0], vb[1, 1] - vb[0, 1]
            alo, ahi, blo, bhi = math.inf, -math.inf, math.inf, -math.inf
            for i in range(ka):
                p = ex * va[i, 0] + ey * va[i, 1]
                alo, ahi = min(alo, p), max(ahi, p)
            for j in range(kb):
                p = ex * vb[j, 0] + ey * vb[j, 1]
                blo, bhi = min(blo, p), max(bhi, p)
            sep = max(sep, max(blo - ahi, alo - bhi))
        return sep

    def gap(ka: int, kb: int) -> tuple[float, float, float]:
        """The distance (m) of A's and B's cores (0 where they overlap) and the unit normal
        from A's closest point to B's."""
        if ka == 1 and kb == 1:
            dx, dy = vb[0, 0] - va[0, 0], vb[0, 1] - va[0, 1]
            d = math.sqrt(dx * dx + dy * dy)
            if d > 0.0:
                return d, dx / d, dy / d
            return 0.0, 0.0, 0.0
        if overlap(ka, kb) <= 0.0:
            return 0.0, 0.0, 0.0
        # Apart: the least distance of a corner of one from an edge of the other (a point's
        # one edge is itself, a segment's one edge is itself).
        best, bx, by = math.inf, 0.0, 0.0
        for side in range(2):
            kp, ke = (kb, ka) if side == 0 else (ka, kb)
            for j in range(kp):
                px, py = (vb[j, 0], vb[j, 1]) if side == 0 else (va[j, 0], va[j, 1])
                for i in range(1 if ke <= 2 else ke):
                    i1 = (i + 1) % ke
                    if side == 0:
                        ax, ay, ex, ey = va[i, 0], va[i, 1], va[i1, 0], va[i1, 1]
                    else:
                        ax, ay, ex, ey = vb[i, 0], vb[i, 1], vb[i1, 0], vb[i1, 1]
                    ex, ey = ex - ax, ey - ay
                    length = ex * ex + ey * ey
                    u = 0.0
                    if length > 0.0:
                        u = min(max(((px - ax) * ex + (py - ay) * ey) / length, 0.0), 1.0)
                    # From the edge's point to the corner: B's side less A's.
                    dx, dy = px - (ax + u * ex), py - (ay + u * ey)
                    if side == 1:
                        dx, dy = -dx, -dy
                    d2 = dx * dx + dy * dy
                    if d2 < best:
                        best, bx, by = d2, dx, dy
        d = math.sqrt(best)
        if d > 0.0:
            return d, bx / d, by / d
        return 0.0, 0.0, 0.0

    def toi(
        a_circle: bool, a_index: int, ax: float, ay: float, aq: float, adx: float,
        ady: float, adq: float, a_core: float, b: int, point: bool, t_max: float,
        closer: bool,
    ) -> float:  # fmt: skip
        """The first time (a fraction of the step, < ``t_max``) at which shape A (the tables'
        ``a_index``, a half plane where < 0; at (ax, ay, aq) at the start, moving by (adx, ady,
        adq) in the step) and fast body ``b`` (its core circle where ``point``) come within
        the target; ``t_max`` where they do not before it, 0 where they are within it at
        the start. ``closer``: the target is a slop nearer than the cores are at the start
        where that is nearer (a pair that touches at the start: module doc)."""
        bx, by, bq = x0[b, 0], x0[b, 1], q0[b]
        bdx, bdy, bdq = x1[b, 0] - bx, x1[b, 1] - by, q1[b] - bq
        b_core = core[b]
        rb = 0.0
        if point:
            b_core = math.sqrt(centroid[b, 0] * centroid[b, 0] + centroid[b, 1] * centroid[b, 1])
            rb = CORE * least[b]
        half = a_index < 0
        ra = 0.0
        t = 0.0
        start = 0.0  # (the cores' distance at the start, where ``closer``)
        signed = half  # (whether that distance is signed: a half plane's, or cores that overlap)
        start_inside = False  # (the cores overlapped at the start: ``closer``'s signed distance)
        inside = False
        for _ in range(ITERATIONS):
            c, s = math.cos(bq + t * bdq), math.sin(bq + t * bdq)
            px, py = bx + t * bdx, by + t * bdy
            if point:
                vb[0, 0] = c * centroid[b, 0] - s * centroid[b, 1] + px
                vb[0, 1] = s * centroid[b, 0] + c * centroid[b, 1] + py
                kb = 1
            else:
                kb, rb = load(vb, nb, body_circle[b], body_index[b], px, py, bq + t * bdq)
            if half:
                h = -1 - a_index
                nx, ny = hn[h, 0], hn[h, 1]
                d = math.inf
                for j in range(kb):
                    d = min(d, nx * (vb[j, 0] - hp[h, 0]) + ny * (vb[j, 1] - hp[h, 1]))
            else:
                ka, ra = load(va, na, a_circle, a_index, ax + t * adx, ay + t * ady, aq + t * adq)
                d, nx, ny = gap(ka, kb)
                if closer and t == 0.0:
                    start_inside = d == 0.0 and ka >= 2
                inside = start_inside and d == 0.0
                if inside:
                    # The cores overlapped at the start and still do (A, a wall's polygon or
                    # capsule, does not move): B's separation along the best of A's edge
                    # normals, signed (<= 0), as a half plane's distance is (module doc).
                    d = -math.inf
                    for i in range(ka):
                        low = math.inf
                        for j in range(kb):
                            ox, oy = vb[j, 0] - va[i, 0], vb[j, 1] - va[i, 1]
                            low = min(low, na[i, 0] * ox + na[i, 1] * oy)
                        d = max(d, low)
            target = max(slop, ra + rb - slop)
            if closer:
                if t == 0.0:
                    start = d
                    signed = half or start_inside
                # (A signed d, a half plane's or overlapping cores', may go below 0, and a
                # slop below where it started is a corner swung in or a body pushed on in,
                # however deep it began.)
                target = min(target, start - slop if signed else max(start - slop, 0.0))
            if d < target + tol:
                return t
            if not half and inside:
                # How fast B's corners can close on any of A's edges (A still): B's motion.
                w = math.sqrt(bdx * bdx + bdy * bdy) + abs(bdq) * b_core
                if w <= 0.0:
                    return t_max
                t = t + (d - target) / w
                if t >= t_max:
                    return t_max
                continue
            # How fast (a step's worth) the gap can close along n (module doc).
            w = nx * (adx - bdx) + ny * (ady - bdy) + abs(adq) * a_core + abs(bdq) * b_core
            if w <= 0.0:
                return t_max
            t = t + (d - target) / w
            if t >= t_max:
                return t_max
        return t

    def sweep(
        r: int, a_circle: bool, a_index: int, ax: float, ay: float, aq: float, adx: float,
        ady: float, adq: float, a_core: float, fraction: float,
    ) -> float:  # fmt: skip
        """``fraction`` made the earlier of it and body ``r``'s impact on shape A (``toi``);
        where its shape touches A at the start, the earlier of its core circle's (Box2D's
        fallback) and, where A does not move, its shape's coming a slop closer than it
        started (module doc)."""
        # (One call of ``toi`` in a loop over the three sweeps, not three calls: numba inlines
        # an inner function at each call, and the kernel's compile time grows with each.)
        still = adx == 0.0 and ady == 0.0 and adq == 0.0
        if not still:
            # A body the solve moved: B meets it where the solve leaves it (module doc).
            ax, ay, aq = ax + adx, ay + ady, aq + adq
            adx = ady = adq = 0.0
        out = fraction
        for mode in range(3):  # the shape; its core circle; the shape, a slop closer
            if mode == 2 and not still:
                break  # (B's start against A's end pose is not where the two were)
            f = toi(a_circle, a_index, ax, ay, aq, adx, ady, adq, a_core, r, mode == 1, out,
                    mode == 2)  # fmt: skip
            if mode == 0 and f > 0.0:
                return f if f < fraction else fraction  # (it does not touch A at the start)
            if 0.0 < f < out:
                out = f
        return out

    # The bodies to sweep against, once: the static and kinematic ones, and where a body is a
    # bullet the dynamic ones that are not bullets (``moved``: a bullet's alone, as a moving
    # kinematic one is: Box2D's rule); no sensor.
    anyone = False
    for o in range(n):
        if bullet[o]:
            anyone = True
    others = np.zeros(n, dtype=np.int64)
    moved = np.zeros(n, dtype=np.bool_)
    many = 0
    for o in range(n):
        if sensor[o]:
            continue
        if kinematic[o] or not mass[o] < math.inf:
            others[many] = o
            moved[many] = kinematic[o] and (
                x1[o, 0] != x0[o, 0] or x1[o, 1] != x0[o, 1] or q1[o] != q0[o]
            )
            many += 1
        elif anyone and not bullet[o]:
            others[many] = o
            moved[many] = True
            many += 1
    # Each one's box over its sweep: its shape's at both ends, grown by its rounding and by
    # |dq| times its core's reach (a corner strays from the line between its two ends by at
    # most that as the body turns between them).
    obox = np.zeros((many, 4))
    for e in range(many):
        o = others[e]
        obox[e, 0], obox[e, 1], obox[e, 2], obox[e, 3] = math.inf, math.inf, -math.inf, -math.inf
        for end in range(2):
            px, py, q = (x0[o, 0], x0[o, 1], q0[o]) if end == 0 else (x1[o, 0], x1[o, 1], q1[o])
            k, rounding = load(va, na, body_circle[o], body_index[o], px, py, q)
            for i in range(k):
                obox[e, 0], obox[e, 1] = min(obox[e, 0], va[i, 0]), min(obox[e, 1], va[i, 1])
                obox[e, 2], obox[e, 3] = max(obox[e, 2], va[i, 0]), max(obox[e, 3], va[i, 1])
        grow = rounding + abs(q1[o] - q0[o]) * core[o]
        obox[e, 0], obox[e, 1] = obox[e, 0] - grow, obox[e, 1] - grow
        obox[e, 2], obox[e, 3] = obox[e, 2] + grow, obox[e, 3] + grow
    statics = len(owner)
    hit = np.zeros(n, dtype=np.int64)
    hx = np.zeros((n, 2))
    hq = np.zeros(n)
    count = 0
    found = 0
    for r in range(n):
        if kinematic[r] or sensor[r] or not mass[r] < math.inf:
            continue
        dx, dy, dq = x1[r, 0] - x0[r, 0], x1[r, 1] - x0[r, 1], q1[r] - q0[r]
        if not (
            math.sqrt(dx * dx + dy * dy) + abs(dq) * core[r] > SAFETY * least[r]
            or ended[r] < -DEEP * least[r]
        ):
            continue
        found += 1
        # The box the body sweeps: its bounding circle at both ends.
        lox = min(x0[r, 0], x1[r, 0]) - reach[r]
        loy = min(x0[r, 1], x1[r, 1]) - reach[r]
        hix = max(x0[r, 0], x1[r, 0]) + reach[r]
        hiy = max(x0[r, 1], x1[r, 1]) + reach[r]
        fraction = 1.0
        # The static shapes (k of them), then the bodies the solve does not move: static
        # ones, kinematic ones at rest (and, for a bullet, moving kinematic ones and the
        # dynamic ones that are not bullets, at their end poses); one call of ``sweep``
        # for both (``toi``'s note).
        for j in range(statics + many):
            if j < statics:
                s = j
                # (Its box's sides read one by one: a row of ``bounds`` taken as an array is a
                # view numba makes and counts a reference to, which cost this loop five times
                # its time on 1,000 fast balls among 50 segments.)
                left, bottom, right, top = bounds[s, 0], bounds[s, 1], bounds[s, 2], bounds[s, 3]
                if left > hix or right < lox or bottom > hiy or top < loy:
                    continue
                if static_index[s] < 0:
                    # A half plane (its box is the world): skipped where the whole swept box
                    # stays more than a slop in front of it (the least of n.(corner - p) over
                    # its corners).
                    h = -1 - static_index[s]
                    nx, ny = hn[h, 0], hn[h, 1]
                    front = nx * (0.5 * (lox + hix) - hp[h, 0]) + ny * (
                        0.5 * (loy + hiy) - hp[h, 1]
                    )
                    if front - 0.5 * (abs(nx) * (hix - lox) + abs(ny) * (hiy - loy)) > slop:
                        continue
                p = owner[s]
                if c_sensor[p] or (group[r] != 0 and group[r] == c_group[p]):
                    continue
                if (cats[r] & c_mask[p]) == 0 or (c_cats[p] & mask[r]) == 0:
                    continue
                if len(ignored):
                    key = r * (places + 1) + p
                    at = np.searchsorted(ignored, key)
                    if at < len(ignored) and ignored[at] == key:
                        continue
                a_circle, a_index = static_circle[s], static_index[s]
                ax = ay = aq = adx = ady = adq = a_core = 0.0
            else:
                e = j - statics
                o = others[e]
                if o == r or (moved[e] and not bullet[r]):
                    continue
                if obox[e, 0] > hix or obox[e, 2] < lox or obox[e, 1] > hiy or obox[e, 3] < loy:
                    continue
                if group[r] != 0 and group[r] == group[o]:
                    continue
                if (cats[r] & mask[o]) == 0 or (cats[o] & mask[r]) == 0:
                    continue
                if len(apart):
                    key = min(r, o) * n + max(r, o)
                    at = np.searchsorted(apart, key)
                    if at < len(apart) and apart[at] == key:
                        continue
                a_circle, a_index = body_circle[o], body_index[o]
                ax, ay, aq = x0[o, 0], x0[o, 1], q0[o]
                adx, ady, adq = x1[o, 0] - ax, x1[o, 1] - ay, q1[o] - aq
                a_core = core[o]
            fraction = sweep(r, a_circle, a_index, ax, ay, aq, adx, ady, adq, a_core, fraction)
        if fraction < 1.0:
            hit[count] = r
            hx[count, 0] = x0[r, 0] + fraction * dx
            hx[count, 1] = x0[r, 1] + fraction * dy
            hq[count] = q0[r] + fraction * dq
            count += 1
    return hit[:count].copy(), hx[:count].copy(), hq[:count].copy(), found


class Continuous:
    """The soft step's continuous stage (module doc) and what it keeps from step to step:
    each body's extents, made again when the shapes' tables are."""

    def __init__(self, fast: bool, slop: float = LINEAR_SLOP) -> None:
        self.fast = fast  # the compiled kernels (engine.kernels) or their plain-Python twins
        #: Whether the stage runs (Box2D's ``enableContinuous``).
        self.enabled = True
        #: The last step's fast bodies, and how many of them were set back.
        self.found = 0
        self.hits = 0
        #: Whether a body may be fast after the step (the fast path's step_loop says).
        self.maybe = False
        #: The slop in the World's length units (LINEAR_SLOP's metres scaled by the World's
        #: ``length_units_per_meter``).
        self.slop = slop
        self._kept: tuple[Any, np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None
        # Where a body is of several shapes: the parts' places and extents (``_sweep_parts``).
        self._kept_parts: tuple[Any, ...] | None = None

    def sweep(
        self, store: Any, sc: Any, x: np.ndarray, angle: np.ndarray, ended: np.ndarray
    ) -> None:
        """Set back each fast body of ``store`` (the World's rows, at the step's start) that
        meets something on its sweep to its end pose ``x`` (n, 2), ``angle`` (n,), in place
        (``sc``: the step's engine.pipeline.game_step._Scene); ``ended`` (n,) each body's
        least separation at the end from what the solve does not move (``ended_depth``)."""
        self.found = self.hits = 0
        n = len(x)
        if not self.enabled or not n:
            return
        parts = sc.table.parts
        if self.fast and not self.maybe and parts is None:
            return  # (step_loop's test: no body may be fast; the most steps of a game)
        if parts is not None:
            self._sweep_parts(store, sc, x, angle, ended)
            return
        places = sc.places
        kept = self._kept
        if kept is None or kept[0] is not places or len(kept[1]) != n:
            least, core, centroid = sc.table.extents()
            # A bound from below of SAFETY e, for the test's bound from above of the move.
            limit = SAFETY * least * (1.0 - 1e-9)
            kept = self._kept = (places, limit, least, core, centroid)
        x0, q0 = store.x, store.angle
        # (The fast path asked step_loop's test above; the numpy path asks it here, each
        # "any" a np.count_nonzero: a C call, where ndarray.any() costs several times more.)
        if not self.fast and not (
            np.count_nonzero(np.abs(x - x0).sum(axis=1) + np.abs(angle - q0) * kept[3] > kept[1])
            or np.count_nonzero(ended < -DEEP * kept[2])
        ):
            return
        t = places.tables
        f64, i64 = np.float64, np.int64
        asc = np.ascontiguousarray
        cs = sc.cs
        hp = asc(sc.statics.half_planes.point, f64)
        hn = asc(sc.statics.half_planes.normal, f64)
        args = (
            asc(x0, f64), asc(q0, f64), asc(x, f64), asc(angle, f64), asc(ended, f64), kept[2],
            kept[3],
            kept[4], asc(store.radius, f64), asc(store.kinematic), asc(store.mass, f64),
            sc.sensors, asc(store.bullet), asc(store.group, i64), asc(store.categories, i64),
            asc(store.mask, i64),
            places.body_circle, places.body_index, asc(sc.apart, i64), asc(sc.owner, i64),
            asc(sc.bounds, f64), places.static_circle, places.static_index, cs.sensor,
            cs.group, cs.categories, cs.mask, asc(sc.ignored, i64), *t.kernel_polygons, t.center,
            t.round, hp, hn, self.slop,
        )  # fmt: skip
        run: Any = continuous_loop if self.fast else continuous_loop.py
        hit, hx, hq, self.found = run(*args)
        self.hits = len(hit)
        if self.hits:
            x[hit] = hx
            angle[hit] = hq

    def _sweep_parts(
        self, store: Any, sc: Any, x: np.ndarray, angle: np.ndarray, ended: np.ndarray
    ) -> None:
        """``sweep`` where a body is of several shapes (engine.body_shapes): each part swept
        at its body's poses as a body of its own (the same kernel, each part's extents about
        its body's position), the parts of one body kept apart, and a body set back to the
        first impact of any of its parts (Box2D's b2SolveContinuous loops over a body's
        shapes likewise)."""
        parts = sc.table.parts
        owner = parts.owner
        n, p = len(x), len(owner)
        kept = self._kept_parts
        if kept is None or kept[0] is not parts or kept[1] is not sc.statics:
            places = narrowphase.places_of(parts.table, sc.statics)
            least, core, centroid = parts.table.extents()
            kept = self._kept_parts = (parts, sc.statics, places, least, core, centroid)
        places, least, core, centroid = kept[2:]
        limit = SAFETY * least * (1.0 - 1e-9)
        x0, q0 = store.x, store.angle
        moved = np.abs(x - x0).sum(axis=1)[owner] + np.abs(angle - q0)[owner] * core
        if not ((moved > limit).any() or (ended[owner] < -DEEP * least).any()):
            return
        # The pairs kept apart, as pairs of parts: every part pair of a body pair kept apart
        # (keys a n + b, a < b), and every pair of one body's parts.
        a, b = np.divmod(np.asarray(sc.apart, dtype=np.int64), n)
        keys: list[np.ndarray] = []
        for body in np.flatnonzero(parts.size > 1).tolist():
            i, j = np.meshgrid(_rows(parts, body), _rows(parts, body))
            keys.append(i[i < j] * p + j[i < j])
        for u, w in zip(a.tolist(), b.tolist(), strict=True):
            i, j = np.meshgrid(_rows(parts, u), _rows(parts, w))
            keys.append(np.minimum(i, j).ravel() * p + np.maximum(i, j).ravel())
        apart = np.unique(np.concatenate(keys)) if keys else np.zeros(0, dtype=np.int64)
        # The faces pre_solve left out, likewise (keys row (colliders + 1) + place).
        width = len(sc.cs.sensor) + 1
        rows, spot = np.divmod(np.asarray(sc.ignored, dtype=np.int64), width)
        ignored = np.sort(
            np.concatenate(
                [
                    _rows(parts, r) * width + q
                    for r, q in zip(rows.tolist(), spot.tolist(), strict=True)
                ]
                or [np.zeros(0, dtype=np.int64)]
            )
        )
        t = places.tables
        f64, i64 = np.float64, np.int64
        asc = np.ascontiguousarray
        cs = sc.cs
        # Each part's bounding radius about its body's position: its core's farthest point and
        # its rounding (a disc's radius).
        reach = core.copy()
        for r in range(p):
            j = int(places.body_index[r])
            reach[r] += float(t.round[j] if places.body_circle[r] else t.radius[j])
        args = (
            asc(x0[owner], f64), asc(q0[owner], f64), asc(x[owner], f64), asc(angle[owner], f64),
            asc(ended[owner], f64), least, core, centroid, reach, asc(store.kinematic[owner]),
            asc(store.mass[owner], f64),
            asc(sc.sensors[owner]), asc(store.bullet[owner]), asc(store.group[owner], i64),
            asc(store.categories[owner], i64), asc(store.mask[owner], i64),
            places.body_circle, places.body_index, asc(apart, i64), asc(sc.owner, i64),
            asc(sc.bounds, f64), places.static_circle, places.static_index, cs.sensor,
            cs.group, cs.categories, cs.mask, asc(ignored, i64), *t.kernel_polygons, t.center,
            t.round, asc(sc.statics.half_planes.point, f64),
            asc(sc.statics.half_planes.normal, f64), self.slop,
        )  # fmt: skip
        run: Any = continuous_loop if self.fast else continuous_loop.py
        hit, hx, hq, self.found = run(*args)
        # Each body set back to its first impact: the part's pose nearest its start.
        first: dict[int, tuple[float, int]] = {}
        for k, part in enumerate(hit.tolist()):
            body = int(owner[part])
            far = abs(hx[k, 0] - x0[body, 0]) + abs(hx[k, 1] - x0[body, 1])
            far += abs(hq[k] - q0[body]) * (1.0 + core[part])
            if body not in first or far < first[body][0]:
                first[body] = (far, k)
        self.hits = len(first)
        for body, (_, k) in first.items():
            x[body] = hx[k]
            angle[body] = hq[k]


def _rows(parts: Any, body: int) -> np.ndarray:
    """The part rows of ``body`` (int64)."""
    start = int(parts.first[body])
    return np.arange(start, start + int(parts.size[body]), dtype=np.int64)
