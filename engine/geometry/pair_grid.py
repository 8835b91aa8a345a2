"""The broadphase for pairs of bodies: which pairs may touch within a step.

A step's pairs (engine.exact.collisions) are those whose discs can come within reach of each other
during it. Each body's centre moves on the path that ends at (x1, v1),

    x(t) = x1 - v1 s + A s^2 / 2,    v(t) = v1 - A s,    s = dt - t,

whose velocity is linear in t, so its speed |v(t)| is convex and peaks at an end of the step:
at most max(|v0|, |v1|) + |A| dt (a bounce off a wall within the step never speeds it up). A
centre is then never farther from its end position than its ``reach``, that speed times dt,
plus a margin (5% of its radius) for resting contacts about to close; two bodies can touch
within the step only if their end positions are at most r_a + r_b + reach_a + reach_b apart.
(That is the free path, which the pairs are found on before the static contacts; a body
they bounce off a collider may reach farther on its bent path, and is searched again after
them: engine.exact.bent_paths.)

**The grid** (``grid_pairs``). With cells of side h >= 2 (r_max + reach_max), two bodies
that can touch lie in the same or neighbouring cells. A cell (c_x, c_y) is keyed by one
integer, (c_x + 1) ny + (c_y + 1), the bodies sorted by key; each body looks up its own cell
and four of its eight neighbours, +1, ny - 1, ny and ny + 1 (the other four look it up), each a
range of the sorted keys found by binary search, so no Python loop runs over bodies. The
cells hold a body's reach up to a radius, or up to what all but the fastest 2% reach (a
falling crowd), at most four radii; the faster bodies, few, are tested against every body
(``pairs_of``): a grid of their size would make every cell hold everyone.

**Struck bodies** (``struck``). An impact can send a body off faster than its own speed
reaches: a light ball struck by a heavy one. An impact changes a's velocity by

    dv_a = (1 + e) u w_a / (w_a + w_b),    w = 1 / m,

for the closing speed u, which is at most the pair's relative speed over the step,
|v_a - v_b| at its start or end plus |A_a - A_b| dt, plus what impacts gave either. A body
whose gain over the step, times dt, passes the margin its reach has is searched again against
every body with the larger reach, and so on down a chain of such impacts (three links). A
crowd falling together, or a pile, has small relative speeds and gains nothing here.

Pairs are World rows (a < b), less those that never collide: two kinematic bodies pass
through each other (as in pymunk), and a pymunk-style filter turns pairs off (the same
nonzero group, or categories that the other's mask leaves out).

**Two paths, one algorithm** (engine.kernels): ``grid_pairs`` in numpy, and
``grid_pairs_loop``, the loop kernel of the fast path, which walks each point's five cells and
(for ``find_pairs``) drops the pairs beyond reach as it goes. They give the same pairs in the
same order, to the bit (tests/test_kernels_pair_grid.py).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from .. import kernels
from ..kernels import stable_order
from .pair_math import dot, norm, sorted_unique

__all__ = [
    "Search",
    "collide",
    "deepest_overlap",
    "find_pairs",
    "grid_pairs",
    "grid_pairs_loop",
    "pairs_of",
    "rows_of",
    "struck",
    "struck_pairs",
]


class Search(NamedTuple):
    """What the struck bodies' search (``struck``) needs from ``find_pairs``: each live body's
    end position, radius, start and end velocities, acceleration and reach (places in
    ``live``, the World rows of the bodies that collide)."""

    P: np.ndarray
    r: np.ndarray
    v0: np.ndarray
    v1: np.ndarray
    A: np.ndarray
    reach: np.ndarray
    live: np.ndarray


#: The farthest cell a grid keys, either way (its keys then stay within an int64).
CELLS = float(2**30)

#: How often a struck body's reach may grow (``struck_pairs``): each time its bound rises,
#: as the links of a chain of impacts give its neighbours more; a few times, so that a bound
#: that feeds on itself (a light ball between two others) stays of the chain's size.
GROWTHS = 3


def grid_pairs(P: np.ndarray, h: float, fast: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs of points (P: (N, 2), length units) in the same or neighbouring cells of a
    grid of side h (length units): each pair once, a < b within a cell.

    Cells are keyed by one integer, the points sorted by key; each point looks up its own
    cell and four of its eight neighbours (the other four look it up), each a range of the
    sorted keys found by binary search. No Python loop over points. ``fast``: the loop kernel
    (``grid_pairs_loop``, compiled), the same pairs in the same order.
    """
    if fast:
        a, b = grid_pairs_loop(
            np.ascontiguousarray(P, dtype=np.float64), float(h), _NONE, _NONE, False
        )
        return a, b
    n = len(P)
    # (Cells past +-2^30 are the edge cell: a body flung 1e19 away keys no overflow, and
    # shares its cell only with others as far out, which the distances then drop.)
    c = np.clip(np.floor(P * (1.0 / h)), -CELLS, CELLS)
    c -= c.min(axis=0)
    c = c.astype(np.int64)
    ny = int(c[:, 1].max()) + 3
    key = (c[:, 0] + 1) * ny + (c[:, 1] + 1)
    order = np.argsort(key, kind="stable")
    sk = key[order]
    offsets = np.array([0, 1, ny - 1, ny, ny + 1], dtype=np.int64)
    q = (key[:, None] + offsets[None, :]).ravel()
    lo = np.searchsorted(sk, q, "left")
    cnt = np.searchsorted(sk, q, "right") - lo
    total = int(cnt.sum())
    if not total:
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    a = np.repeat(np.arange(n * 5) // 5, cnt)
    first = np.cumsum(cnt) - cnt
    b = order[np.arange(total) - np.repeat(first - lo, cnt)]
    same = np.repeat(np.arange(n * 5) % 5 == 0, cnt)
    keep = np.where(same, a < b, True)
    return a[keep], b[keep]


def pairs_of(
    bodies: np.ndarray, P: np.ndarray, r: np.ndarray, reach: np.ndarray, fast: bool = False
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Each of ``bodies`` (a few) against every body it can reach this step: pairs (lower
    index, higher index) as one array per body (``fast``: all in one, by the loop kernel
    ``reach_pairs``), from the positions P, radii r and reaches."""
    if fast:
        a, b = reach_pairs(bodies, P, r, reach)
        return [a], [b]
    fa, fb = [], []
    for k in bodies.tolist():
        near = norm(P - P[k]) <= r + r[k] + reach + reach[k]
        near[k] = False
        j = np.flatnonzero(near)
        fa.append(np.minimum(j, k))
        fb.append(np.maximum(j, k))
    return fa, fb


def deepest_overlap(
    x: np.ndarray,
    radius: np.ndarray,
    filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
) -> float:
    """The deepest overlap (length units, 0 if none) of discs at positions x (N, 2) with radii
    ``radius`` (N,): max of r_a + r_b - |x_a - x_b| over every pair (that ``filters``, arrays of
    group, categories and mask, lets collide), found through a grid.

    >>> deepest_overlap(np.array([[0.0, 0.0], [0.9, 0.0], [5.0, 0.0]]), np.full(3, 0.5))
    0.09999999999999998
    """
    x = np.asarray(x, dtype=float).reshape(-1, 2)
    radius = np.broadcast_to(np.asarray(radius, dtype=float), (len(x),))
    if len(x) < 2:
        return 0.0
    a, b = grid_pairs(x, 2.0 * float(radius.max()) + 1e-300)
    if filters is not None and len(a):
        g, c, m = filters
        ok = ~((g[a] == g[b]) & (g[a] != 0)) & ((c[a] & m[b]) != 0) & ((c[b] & m[a]) != 0)
        a, b = a[ok], b[ok]
    if not len(a):
        return 0.0
    over = radius[a] + radius[b] - norm(x[a] - x[b])
    return max(float(over.max()), 0.0)


def find_pairs(
    x0: np.ndarray,
    v0: np.ndarray,
    x1: np.ndarray,
    v1: np.ndarray,
    A: np.ndarray,
    dt: float,
    live: np.ndarray,
    store: Any,
    has_kin: bool,
    plain: bool,
    fast: bool = False,
) -> tuple[np.ndarray, np.ndarray, Search]:
    """World rows (a < b) of the pairs that may touch within the step or are near enough
    to rest on each other: a grid for the many, every body for the fast few. With them, what
    the struck bodies' search needs once the piles are known (``struck``). ``has_kin``: some
    body is kinematic; ``plain``: every live body has the default filter. ``fast``: the
    grid and the filter by distance in the loop kernel (``grid_pairs_loop``), the same pairs
    in the same order."""
    P = x1[live]
    r = store.radius[live]
    # How far a centre can be from its end position during the step: its speed on a
    # parabola peaks at an end, and a bounce off a wall never speeds it up.
    speed = np.maximum(norm(v0[live]), norm(v1[live])) + norm(A[live]) * dt
    reach = speed * dt + 0.05 * r  # plus a margin for resting contacts about to close
    rmax = float(r.max())
    # The grid's cells hold a body's reach: up to a radius, or to what all but the
    # fastest 2% reach (a falling crowd), at most four radii. Faster bodies, few, are
    # tested against everyone.
    few = reach > rmax  # the fast few
    if few.any():
        cap = min(
            float(np.partition(reach, int(0.98 * (len(reach) - 1)))[int(0.98 * (len(reach) - 1))]),
            4.0 * rmax,
        )
        few = reach > max(rmax, cap)
    slow_reach = float(reach[~few].max()) if (~few).any() else 0.0
    h = 2.0 * (rmax + slow_reach)
    span = float((P.max(axis=0) - P.min(axis=0)).max())
    h = max(h, span / 2.0**30)  # keeps cell keys within int64
    F = np.flatnonzero(few)
    if fast:
        # The grid's pairs as (lower, higher), those beyond reach left out, in the grid's
        # order: what the lines below make of them (the filter keeps a pair or not by the
        # pair alone, so filtering before the union with the fast few's pairs, and again
        # after it, leaves what filtering once after it leaves).
        ia, ib = grid_pairs_loop(P, h, r, reach, True)
    else:
        ia, ib = grid_pairs(P, h)
        # Each pair as (lower row, higher row): one key per pair, step after step (the warm
        # start and the events find it by that key), and no pair listed twice below.
        ia, ib = np.minimum(ia, ib), np.maximum(ia, ib)
    if len(F):
        # Fast bodies against every body (few of them; a grid of their size would make
        # every cell hold everyone).
        fa, fb = pairs_of(F, P, r, reach, fast)
        ia = np.concatenate([ia, *fa])
        ib = np.concatenate([ib, *fb])
        key = sorted_unique(ia.astype(np.int64) * len(P) + ib)
        ia, ib = key // len(P), key % len(P)
    if len(ia) and (len(F) or not fast):
        D = P[ia] - P[ib]
        far = r[ia] + r[ib] + reach[ia] + reach[ib]
        keep = dot(D, D) <= far * far
        ia, ib = ia[keep], ib[keep]
    search = Search(P, r, v0[live], v1[live], A[live], reach, live)
    a, b = rows_of(ia, ib, live, store, has_kin, plain)
    return a, b, search


def struck(
    a: np.ndarray,
    b: np.ndarray,
    island: np.ndarray,
    dt: float,
    store: Any,
    search: Search | None,
    has_kin: bool,
    plain: bool,
    fast: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (a, b) with those of bodies not in a pile that an impact may send off
    faster than their own speed reaches (``struck_pairs``); a pile's bodies meet what
    they meet as contacts of the soft step, which needs no such search. ``search``: from
    ``find_pairs`` (None: no pairs were searched); ``fast``: the loop kernels."""
    if search is None:
        return a, b
    P, r, v0l, v1l, Al, reach, live = search
    free = ~island[live]
    if not free.any() or not len(a):
        return a, b
    where = np.full(len(island), -1, dtype=np.intp)
    where[live] = np.arange(len(live))
    ia, ib = where[a], where[b]
    both = free[ia] & free[ib]
    ja, jb = struck_pairs(
        ia[both], ib[both], P, r, v0l, v1l, Al, reach, dt, live, store, free, has_kin, plain,
        fast,
    )  # fmt: skip
    if len(ja) == int(both.sum()):
        return a, b  # nobody is struck faster than it reaches: the same pairs
    na, nb = rows_of(ja, jb, live, store, has_kin, plain)
    keys = sorted_unique(
        np.concatenate([a, na]).astype(np.int64) * len(island) + np.concatenate([b, nb])
    )
    return keys // len(island), keys % len(island)


def rows_of(
    ia: np.ndarray, ib: np.ndarray, live: np.ndarray, store: Any, has_kin: bool, plain: bool
) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of places in ``live`` as World rows, less those that never collide."""
    a, b = live[ia], live[ib]
    ok = collide(a, b, store, has_kin, plain)
    return (a, b) if ok is None else (a[ok], b[ok])


def collide(
    a: np.ndarray, b: np.ndarray, store: Any, has_kin: bool, plain: bool
) -> np.ndarray | None:
    """Which pairs of World rows (a, b) can collide (a mask), or None when all can: two
    bodies the game moves pass through each other (as in pymunk), and a pymunk-style filter
    turns pairs off. ``has_kin``: some body is kinematic; ``plain``: every live body has the
    default filter."""
    if not len(a) or (plain and not has_kin):
        return None
    ok = np.ones(len(a), dtype=bool)
    if has_kin:
        kin = store.kinematic
        ok &= ~(kin[a] & kin[b])
    if not plain:
        g, c, m = store.group, store.categories, store.mask
        ok &= ~((g[a] == g[b]) & (g[a] != 0))
        ok &= ((c[a] & m[b]) != 0) & ((c[b] & m[a]) != 0)
    return ok


def impact_gain(
    ia: np.ndarray, ib: np.ndarray, rel: np.ndarray, w: np.ndarray, e: np.ndarray, n: int
) -> np.ndarray:
    """What an impact may add to the speed of each of ``n`` bodies (length units/s): for a
    pair (ia, ib) closing at up to ``rel``, (1 + e_a e_b) w_a / (w_a + w_b) rel for body a
    (w = 1 / m, 0 for what the game moves), the most over its pairs."""
    tot = w[ia] + w[ib]
    close = (1.0 + e[ia] * e[ib]) * rel / np.where(tot > 0.0, tot, 1.0)
    gain = np.zeros(n)
    np.maximum.at(gain, ia, close * w[ia])
    np.maximum.at(gain, ib, close * w[ib])
    return gain


def struck_pairs(
    ia: np.ndarray,
    ib: np.ndarray,
    P: np.ndarray,
    r: np.ndarray,
    v0: np.ndarray,
    v1: np.ndarray,
    A: np.ndarray,
    reach: np.ndarray,
    dt: float,
    live: np.ndarray,
    store: Any,
    free: np.ndarray,
    has_kin: bool,
    plain: bool,
    fast: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (ia, ib) (places in live) with those of bodies an impact may send farther
    than their own speed reaches: a light ball struck by a fast one flies off at up to
    (1 + e) times their closing speed, and must meet the balls beyond it, not pass them.

    An impact changes a body's velocity by at most (1 + e) w_a / (w_a + w_b) times the
    pair's closing speed (w = 1 / m; a kinematic body, w = 0, gains nothing), and that
    is at most their relative speed over the step, |v_a - v_b| at its start or end plus
    |A_a - A_b| dt, plus what impacts gave either. A body whose gain over the step passes
    the margin its reach already has (5% of its radius) is searched again against every
    body with the larger reach, and so on down a chain of such impacts, to its end (three
    links missed the far end of a row of six balls 1 um apart struck at one end: its last
    two, 1.6 cm apart, were never paired, and one passed 1 mm into the other). A crowd
    falling together, or a pile, has small relative speeds and gains nothing here. A body
    grows again where its bound rises past what it grew by (a link further down the chain
    gave a neighbour more), up to ``GROWTHS`` times: grown once, a light ball struck by one
    that a heavy one had struck grew by the slow pair's bound alone, and flew 2 m in the step
    through a ball 1.1 m away.

    Only pairs that can collide pass a gain on (``collide``): a body filtered apart from a
    struck one is never struck by it, so a World that holds a second world filtered apart
    finds the first world's pairs as that world alone does (a stranger met along the way
    once sent gains round the chain in another order, and a pair of the first world was
    missed: two balls 2.27 m from where they went alone).
    """
    w = 1.0 / store.mass[live]
    if has_kin:
        w[store.kinematic[live]] = 0.0
    e = store.restitution[live]
    got = np.zeros(len(P))  # what impacts may add to each body's speed
    times = np.zeros(len(P), dtype=np.intp)  # how often each has grown
    own = reach
    for _ in range(GROWTHS * len(P)):  # (each body grows at most GROWTHS times)
        rel = np.maximum(norm(v0[ia] - v0[ib]), norm(v1[ia] - v1[ib]))
        rel += norm(A[ia] - A[ib]) * dt + got[ia] + got[ib]
        gain = impact_gain(ia, ib, rel, w, e, len(P))
        # Grown again where the gain has risen past what it grew by (a link further down
        # the chain gave a neighbour more): by the margin, as the first time.
        grown = np.flatnonzero(
            ((gain - got) * dt > 0.05 * r) & (gain * dt > 0.05 * r) & (times < GROWTHS) & free
        )
        if not len(grown):
            break
        times[grown] += 1
        got[grown] = gain[grown]
        reach = reach.copy()
        reach[grown] = own[grown] + gain[grown] * dt
        fa, fb = pairs_of(grown, P, r, reach, fast)
        for k in range(len(fa)):
            ok = collide(live[fa[k]], live[fb[k]], store, has_kin, plain)
            if ok is not None:
                fa[k], fb[k] = fa[k][ok], fb[k][ok]
        key = sorted_unique(
            np.concatenate([ia, *fa]).astype(np.int64) * len(P) + np.concatenate([ib, *fb])
        )
        ia, ib = key // len(P), key % len(P)
    return ia, ib


# -- the loop kernel (engine.kernels: the fast path) ------------------------------------------
# grid_pairs as the loop it is. The same keys (the same float products, floors and integer
# casts), the same stable sort by key, and then, point by point in index order, the same five
# ranges of the sorted keys in the same order (own cell, +1, ny - 1, ny, ny + 1): the same
# pairs in the same order. The ranges come without binary searches: the sorted keys fall into
# runs of one key (one cell each), the own cell is the run a point sits in, the cell +1 is the
# run after it if its key is one more, and the three cells of the next column are consecutive
# keys, found from the first key >= key + ny - 1 (a pointer that walks the sorted keys once).

_NONE = np.zeros(0)  # the radii and reaches of a call that filters nothing


def _sample_grid() -> tuple[object, ...]:
    """The smallest call of ``grid_pairs_loop``: two touching discs, filtered by reach."""
    return np.array([[0.0, 0.0], [1.0, 0.0]]), 2.0, np.full(2, 0.5), np.zeros(2), True


@kernels.loop(sample=_sample_grid)
def grid_pairs_loop(
    P: np.ndarray, h: float, r: np.ndarray, reach: np.ndarray, near: bool
) -> tuple[np.ndarray, np.ndarray]:
    """``grid_pairs(P, h)``'s pairs in its order (P: (N, 2), h: length units); with ``near``,
    each as (lower, higher), only those find_pairs keeps: centres at most r_a + r_b +
    reach_a + reach_b apart (r, reach: (N,), length units)."""
    n = len(P)
    inv = 1.0 / h
    fx, fy = np.empty(n), np.empty(n)
    for i in range(n):
        fx[i] = min(max(np.floor(P[i, 0] * inv), -CELLS), CELLS)
        fy[i] = min(max(np.floor(P[i, 1] * inv), -CELLS), CELLS)
    mx, my = fx.min(), fy.min()
    cx, cy = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64)
    for i in range(n):
        cx[i] = np.int64(fx[i] - mx)
        cy[i] = np.int64(fy[i] - my)
    ny = cy.max() + 3
    key = (cx + 1) * ny + (cy + 1)
    # Sorted by key, stably (as numpy's argsort, kind="stable"): a stable sort has one
    # result. Where the keys span few cells (a crowd), by counting; else by merge sort.
    kmin, kmax = key.min(), key.max()
    if kmax - kmin <= 4 * n + 64:
        first = np.zeros(kmax - kmin + 2, dtype=np.int64)  # where each key's run begins
        for i in range(n):
            first[key[i] - kmin + 1] += 1
        for k in range(1, len(first)):
            first[k] += first[k - 1]
        order = np.empty(n, dtype=np.int64)
        for i in range(n):
            k = key[i] - kmin
            order[first[k]] = i
            first[k] += 1
    else:
        order = stable_order(key)
    sk = key[order]
    rank = np.empty(n, dtype=np.int64)  # each point's place in the sorted keys
    for p in range(n):
        rank[order[p]] = p
    # The run of one key each sorted place is in: [start, end).
    start, end = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64)
    for p in range(n):
        start[p] = start[p - 1] if p and sk[p] == sk[p - 1] else p
    for p in range(n - 1, -1, -1):
        end[p] = end[p + 1] if p < n - 1 and sk[p] == sk[p + 1] else p + 1
    # The first sorted place whose key is >= key + ny - 1 (the next column's three cells).
    nxt = np.empty(n, dtype=np.int64)
    q = 0
    for p in range(n):
        while q < n and sk[q] < sk[p] + ny - 1:
            q += 1
        nxt[p] = q
    # Each point's five ranges (own cell, +1, ny - 1, ny, ny + 1; empty: lo = hi), counted.
    lo, hi = np.zeros((n, 5), dtype=np.int64), np.zeros((n, 5), dtype=np.int64)
    total = 0
    for i in range(n):
        p = rank[i]
        k = key[i]
        lo[i, 0], hi[i, 0] = start[p], end[p]
        e = end[p]
        if e < n and sk[e] == k + 1:
            lo[i, 1], hi[i, 1] = e, end[e]
        q = nxt[p]
        for j in range(3):
            if q < n and sk[q] == k + ny - 1 + j:
                lo[i, 2 + j], hi[i, 2 + j] = q, end[q]
                q = end[q]
        for j in range(5):
            total += hi[i, j] - lo[i, j]
    a, b = np.empty(total, dtype=np.int64), np.empty(total, dtype=np.int64)
    m = 0
    for i in range(n):
        for j in range(5):
            for q in range(lo[i, j], hi[i, j]):
                o = order[q]
                if j == 0 and o <= i:
                    continue  # within a cell, each pair once (a < b)
                if near:
                    # find_pairs' filter: (lower, higher), then |D|^2 <= far^2 with D and
                    # far summed in its order.
                    u, w = min(i, o), max(i, o)
                    dx, dy = P[u, 0] - P[w, 0], P[u, 1] - P[w, 1]
                    far = r[u] + r[w] + reach[u] + reach[w]
                    if not dx * dx + dy * dy <= far * far:
                        continue
                    a[m], b[m] = u, w
                else:
                    a[m], b[m] = i, o
                m += 1
    return a[:m], b[:m]


def _sample_reach() -> tuple[object, ...]:
    """The smallest call of ``reach_pairs``: one body against another within reach."""
    P = np.array([[0.0, 0.0], [1.0, 0.0]])
    return np.array([0]), P, np.full(2, 0.5), np.zeros(2)


@kernels.loop(sample=_sample_reach)
def reach_pairs(
    bodies: np.ndarray, P: np.ndarray, r: np.ndarray, reach: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``pairs_of`` as a loop, its pairs in one array each: each of ``bodies`` against every
    body whose centre is within r + r_k + reach + reach_k (summed in the twin's order)."""
    n = len(P)
    a = np.empty(len(bodies) * n, dtype=np.int64)
    b = np.empty(len(bodies) * n, dtype=np.int64)
    m = 0
    for k in bodies:
        for j in range(n):
            if j == k:
                continue
            dx, dy = P[j, 0] - P[k, 0], P[j, 1] - P[k, 1]
            if math.sqrt(dx * dx + dy * dy) <= r[j] + r[k] + reach[j] + reach[k]:
                a[m], b[m] = min(j, k), max(j, k)
                m += 1
    return a[:m], b[:m]
