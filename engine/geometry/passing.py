"""A speculative contact that the pair's path passes by: the soft step's test of a round pair.

The soft step's narrowphase (engine.geometry.narrowphase, engine.pipeline.game_contacts) keeps a
pair's point while the two are nearer than they can move in the step, so that the solve stops
a fast body at the surface it is coming to (a speculative contact: the relative normal speed
may close at most the gap in the step). The solve takes the surface near that point as a line
through it, across the normal. For a face that is what it is. For a corner (a capsule's end,
a polygon's vertex, a circle) it is not: a ball passing a wall's end, or another ball, closes
along the line between the two centres by more than the gap although its path never comes
within both radii, and the solve stops it at a line it was only passing (a "ghost"
collision: a ball shot up a pinball's lane stops at the guide's end 1 mm beside its path).
Box2D v3 keeps points only within 4 slops and sweeps fast bodies for their moment of impact
instead; this engine keeps them, and drops the ones whose pair cannot meet in the step:

A round pair (A a circle or a polygon, a capsule among them, B a circle; engine.geometry's
``round_loop``) of a body and a static shape whose point is apart by more than
``SPECULATIVE_DISTANCE`` is kept only where
B's centre, moving in A's frame by u (the pair's relative displacement over the step at their
velocities at its start), comes within rA + rB + slack of A's core (a point, a segment or a
polygon): the least distance of the segment c..c + u from A's core, exact (the segments'
nearest points, or 0 where they cross, or where c is within the polygon: the caller asks only
of pairs apart, whose c is outside, but a pair deep in each other is kept, not dropped).
``slack`` is a slop (engine.geometry.manifold_kinds' LINEAR_SLOP: what the narrowphase counts
as touching) and what the two can move beyond
their velocities (their reach less |v| dt: the held accelerations and the turning), so a pair
that can meet in the step keeps its point. One that passes within the speculative distance
is met again at the next step's start, as near points are, along its own normal there. A pair
of bodies keeps its points: another body may push either toward the other within the step
(tested: a disc squeezed 0.126 m into the floor by a neighbour whose point was dropped, in an
exploring run of the shapes fuzz), where a static shape's partner is the only one that moves.

``passing_loop`` is the test a pair at a time (the fast path's, inside its contacts stage, and
the numpy path's for a few pairs); ``passing`` is the same products over arrays (the numpy
path's for many), in the same order, so both give the same answer.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import kernels

__all__ = ["passing", "passing_loop"]


def _sample() -> tuple[Any, ...]:
    """The smallest call: a unit box against a ball passing beside its corner, and a ball
    against a ball coming at it."""
    v = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]])
    c, r = np.array([4]), np.zeros(1)
    centers, radii = np.zeros((2, 2)), np.array([0.25, 0.5])
    flag = np.array([False, True])
    i, x, q = np.array([0, 0]), np.zeros((2, 2)), np.zeros(2)
    xb = np.array([[1.0, -2.0], [0.0, 2.0]])
    u = np.array([[0.0, 3.0], [0.0, -2.0]])
    return v, c, r, centers, radii, flag, i, x, q, np.array([1, 1]), xb, q, u, np.full(2, 0.02)


@kernels.loop(sample=_sample)
def passing_loop(
    VA: Any, cA: Any, rA: Any, C: Any, rC: Any, circle_a: Any,
    ia: Any, xa: Any, qa: Any, ib: Any, xb: Any, qb: Any, u: Any, slack: Any,
) -> Any:  # fmt: skip
    """Whether each round pair can meet in the step (module doc): pair k is polygon ``ia[k]``
    of (VA, cA, rA), or circle ``ia[k]`` of (C, rC) where ``circle_a[k]``, at (xa[k], qa[k]),
    against circle ``ib[k]`` of (C, rC) at (xb[k], qb[k]), B moving by ``u[k]`` (world, m)
    relative to A over the step; ``slack[k]`` (m) what the test allows beyond both radii.
    Returns a bool array, True where B's path comes within reach of A's core."""

    def dist2(px: float, py: float, cx: float, cy: float, ex: float, ey: float) -> float:
        """The squared distance of point p from the segment c..c + e."""
        ee = ex * ex + ey * ey
        t = 0.0
        if ee > 0.0:
            t = min(max(((px - cx) * ex + (py - cy) * ey) / ee, 0.0), 1.0)
        wx, wy = cx + t * ex - px, cy + t * ey - py
        return wx * wx + wy * wy

    n = len(ia)
    out = np.zeros(n, dtype=np.bool_)
    for k in range(n):
        # B's centre c in A's frame (round_loop's products), and its move e there.
        ca, sn = np.cos(qa[k]), np.sin(qa[k])
        dx, dy = xb[k, 0] - xa[k, 0], xb[k, 1] - xa[k, 1]
        px, py = ca * dx + sn * dy, -sn * dx + ca * dy
        rel = qb[k] - qa[k]
        c, s = np.cos(rel), np.sin(rel)
        j = ib[k]
        vx, vy = C[j, 0], C[j, 1]
        cx, cy = c * vx - s * vy + px, s * vx + c * vy + py
        ex, ey = ca * u[k, 0] + sn * u[k, 1], -sn * u[k, 0] + ca * u[k, 1]
        i = ia[k]
        circle = circle_a[k]
        reach = (rC[i] if circle else rA[i]) + rC[j] + slack[k]
        # A's core as edges a..b (a circle's: its centre, an edge of no length; a capsule's
        # one; a polygon's each): 0 where the path crosses one, else the least of each end's
        # squared distance from the other segment.
        m = 1 if circle or cA[i] == 2 else cA[i]
        d2 = np.inf
        inside = m > 1  # a polygon's core holds c while c is left of every edge (s1 >= 0)
        for edge in range(m):
            if circle:
                ax = bx = C[i, 0]
                ay = by = C[i, 1]
            else:
                e2 = (edge + 1) % cA[i]
                ax, ay, bx, by = VA[i, edge, 0], VA[i, edge, 1], VA[i, e2, 0], VA[i, e2, 1]
            fx, fy = bx - ax, by - ay
            s1 = fx * (cy - ay) - fy * (cx - ax)
            s2 = fx * (cy + ey - ay) - fy * (cx + ex - ax)
            s3 = ex * (ay - cy) - ey * (ax - cx)
            s4 = ex * (by - cy) - ey * (bx - cx)
            inside = inside and s1 >= 0.0
            if ((s1 < 0.0 < s2) or (s2 < 0.0 < s1)) and ((s3 < 0.0 < s4) or (s4 < 0.0 < s3)):
                d2 = 0.0
                continue
            for w in range(4):  # a's and b's from the path, the path's ends from a..b
                if w == 0:
                    got = dist2(ax, ay, cx, cy, ex, ey)
                elif w == 1:
                    got = dist2(bx, by, cx, cy, ex, ey)
                elif w == 2:
                    got = dist2(cx, cy, ax, ay, fx, fy)
                else:
                    got = dist2(cx + ex, cy + ey, ax, ay, fx, fy)
                d2 = min(d2, got)
        if inside:
            d2 = 0.0  # B's centre starts within A's polygon (deep in it: a pair to keep)
        out[k] = d2 <= reach * reach
    return out


def passing(
    VA: np.ndarray, cA: np.ndarray, rA: np.ndarray, C: np.ndarray, rC: np.ndarray,
    circle_a: np.ndarray, ia: np.ndarray, xa: np.ndarray, qa: np.ndarray, ib: np.ndarray,
    xb: np.ndarray, qb: np.ndarray, u: np.ndarray, slack: np.ndarray,
) -> np.ndarray:  # fmt: skip
    """``passing_loop`` over arrays: the same products in the same order."""
    n = len(ia)
    if not n:
        return np.zeros(0, dtype=bool)
    ca, sn = np.cos(qa), np.sin(qa)
    dx, dy = xb[:, 0] - xa[:, 0], xb[:, 1] - xa[:, 1]
    px, py = ca * dx + sn * dy, -sn * dx + ca * dy
    rel = qb - qa
    c, s = np.cos(rel), np.sin(rel)
    vx, vy = C[ib, 0], C[ib, 1]
    cx, cy = c * vx - s * vy + px, s * vx + c * vy + py
    ex, ey = ca * u[:, 0] + sn * u[:, 1], -sn * u[:, 0] + ca * u[:, 1]
    circle = np.asarray(circle_a, dtype=bool)
    # (Each row's index into its own table; the other table's lookups read a row 0 not used.)
    ci, pi = np.where(circle, ia, 0), np.where(circle, 0, ia)
    reach = np.where(circle, rC[ci], rA[pi]) + rC[ib] + slack
    count = np.where(circle, 1, cA[pi])
    m = np.where(circle | (count == 2), 1, count)
    d2 = np.full(n, np.inf)
    inside = m > 1
    for edge in range(int(m.max())):
        live = edge < m
        e2 = (edge + 1) % count
        ax = np.where(circle, C[ci, 0], VA[pi, edge, 0])
        ay = np.where(circle, C[ci, 1], VA[pi, edge, 1])
        bx = np.where(circle, C[ci, 0], VA[pi, e2, 0])
        by = np.where(circle, C[ci, 1], VA[pi, e2, 1])
        fx, fy = bx - ax, by - ay
        s1 = fx * (cy - ay) - fy * (cx - ax)
        s2 = fx * (cy + ey - ay) - fy * (cx + ex - ax)
        s3 = ex * (ay - cy) - ey * (ax - cx)
        s4 = ex * (by - cy) - ey * (bx - cx)
        inside &= ~live | (s1 >= 0.0)
        cross = (((s1 < 0.0) & (0.0 < s2)) | ((s2 < 0.0) & (0.0 < s1))) & (
            ((s3 < 0.0) & (0.0 < s4)) | ((s4 < 0.0) & (0.0 < s3))
        )
        got = d2
        for w in range(4):
            if w == 0:
                d = _dist2(ax, ay, cx, cy, ex, ey)
            elif w == 1:
                d = _dist2(bx, by, cx, cy, ex, ey)
            elif w == 2:
                d = _dist2(cx, cy, ax, ay, fx, fy)
            else:
                d = _dist2(cx + ex, cy + ey, ax, ay, fx, fy)
            got = np.minimum(got, d)
        d2 = np.where(live, np.where(cross, 0.0, got), d2)
    d2 = np.where(inside, 0.0, d2)
    return d2 <= reach * reach


def _dist2(
    px: np.ndarray, py: np.ndarray, cx: np.ndarray, cy: np.ndarray, ex: np.ndarray,
    ey: np.ndarray,
) -> np.ndarray:  # fmt: skip
    """``passing_loop``'s ``dist2`` over arrays."""
    ee = ex * ex + ey * ey
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(
            ee > 0.0,
            np.minimum(np.maximum(((px - cx) * ex + (py - cy) * ey) / ee, 0.0), 1.0),
            0.0,
        )
    wx, wy = cx + t * ex - px, cy + t * ey - py
    return wx * wx + wy * wy
