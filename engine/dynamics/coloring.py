"""Graph colouring of contact rows: rows of one colour share no body, so they are solved at once.

A Gauss-Seidel sweep solves contacts one after another, each seeing the velocities the ones
before it left: that is what holds a pile many layers deep in a few sweeps (a Jacobi sweep,
all at once, passes a push on by one contact a sweep). Box2D v3 runs it in parallel by
colouring its constraint graph: the contacts of one colour touch no body twice, so their
order within the colour does not matter, and a colour is one batch. In numpy a colour is one
set of array operations; the sweep is a loop over a handful of colours, not over contacts.

The colouring is greedy and parallel (``colors``): each round, the rows that come first
among the uncoloured rows at both their bodies take the lowest colour free at both (a bit
mask of the colours each body's rows hold). A disc in a pile touches at most six others and
a wall or two, so a pile needs about eight colours. Bodies that do not move
(the static world, a kinematic body, a pin) are left out: their velocity never changes, so
any number of rows of one colour may share one.

>>> import numpy as np
>>> a = np.array([0, 1, 2, 0]); b = np.array([1, 2, 3, 2])
>>> colors(a, b, np.array([True] * 4)).tolist()
[0, 2, 0, 1]
>>> none = np.zeros(0)  # the loop kernel, uncompiled (its .py): the same colours
>>> color_rows.py(a, b, np.array([True] * 4), none, none.astype(np.int64)).tolist()
[0, 2, 0, 1]

**Two paths, one colouring** (engine.kernels): ``colors`` and ``batches`` in numpy, a round
at a time, and their loop kernels ``color_rows`` and ``batch_rows`` (``fast=True``), which give
the same arrays (tests/test_kernels_coloring.py). With distinct priorities the parallel
rounds are the sequential greedy colouring in priority order, highest first: a row is
coloured in the round in which no uncoloured row at its bodies comes before it, so by then
every row before it at its bodies holds its colour and no row after it does, and it takes
the lowest colour those rows left free, as the sequential greedy does. ``color_rows`` is
that greedy, one sort and one pass; for tied priorities it runs the rounds themselves.
"""

from __future__ import annotations

import numpy as np

from .. import kernels
from ..kernels import stable_order

__all__ = ["colors", "batches", "color_rows", "batch_rows", "MAX_COLORS"]

#: Colours a body's mask holds; a row that finds none free at its bodies takes the last,
#: MAX_COLORS - 1, whose rows may share a body (``batches`` splits it into rounds).
MAX_COLORS = 62


def _lowest_free(mask: np.ndarray) -> np.ndarray:
    """The index of the lowest zero bit of each mask (int64), at most MAX_COLORS - 1."""
    free = ~mask & (mask + 1)  # the lowest zero bit, alone
    # 2^k = 0.5 * 2^(k + 1): frexp's exponent, less one, is its bit's place (k < 62: exact in
    # float64). (frexp reads the float's bits, where a log2 is a float function whose last bit
    # may differ with the processor's vector code.)
    out = np.frexp(free.astype(np.float64))[1].astype(np.int64) - 1
    return np.minimum(out, MAX_COLORS - 1)


def _winners(ka: np.ndarray, kb: np.ndarray) -> np.ndarray:
    """For rows asking for keys ka and kb (negative: no claim), whether each row is the
    first (in row order) to ask for both its keys."""
    m = len(ka)
    keys = np.concatenate([ka, kb])
    rows = np.concatenate([np.arange(m), np.arange(m)])
    order = np.lexsort((rows, keys))
    sk = keys[order]
    head = np.ones(2 * m, dtype=bool)
    head[1:] = sk[1:] != sk[:-1]
    first = np.empty(2 * m, dtype=bool)
    first[order] = head
    first |= keys < 0
    return first[:m] & first[m:]


def colors(
    a: np.ndarray,
    b: np.ndarray,
    moves: np.ndarray,
    priority: np.ndarray | None = None,
    prior: np.ndarray | None = None,
    fast: bool = False,
) -> np.ndarray:
    """A colour (int, 0 up) for each row (a[k], b[k]) such that no two rows of one colour
    share a body that ``moves`` (bool by body); MAX_COLORS - 1 for rows left over.

    Jones and Plassmann's parallel greedy colouring: in each round, every row whose priority
    is the highest among the uncoloured rows at both its bodies takes the lowest colour
    free at both (such rows share no body, so they never clash).
    ``priority`` (float by row, distinct): a row's place in that order; by default the
    order of its bodies (lower first), so that the same pair gets the same colour step after
    step, and a pile the same colours whatever other bodies the World holds. ``prior``: a
    colour (or -1) each row keeps from the step before (the rows of a pile persist: only the
    new ones need colouring; those kept must not clash, as a colouring's subset does not;
    colours below MAX_COLORS). ``fast``: run the loop kernel ``color_rows`` (the same colours).
    """
    if fast:
        order = np.zeros(0) if priority is None else priority  # empty: the default
        kept = np.zeros(0, dtype=np.int64) if prior is None else prior  # empty: none kept
        return color_rows(a, b, moves, order, kept)  # type: ignore[no-any-return]
    rows = len(a)
    color = np.full(rows, -1, dtype=np.int64)
    if not rows:
        return color
    n = len(moves)
    if priority is None:
        # The pair's place in the order of the bodies (the lower first), ties broken by row:
        # it depends on the bodies' order only, not on their row numbers, so two piles that
        # never meet colour (and solve) their rows as each would alone. (A hash of the row
        # numbers, which spread the order at random, did not: a pile solved differently with
        # another World's bodies numbered among its own.)
        priority = -(a.astype(np.float64) * n + b) - np.arange(rows) / (rows + 1.0)
    mask = np.zeros(n + 1, dtype=np.int64)  # bit c set: a row of colour c holds the body
    ma = np.where(moves[a], a, n)  # bodies that do not move: the slot n, never claimed
    mb = np.where(moves[b], b, n)
    left = np.arange(rows)
    if prior is not None:
        kept = np.flatnonzero(prior >= 0)
        # Colours kept from different steps may clash (two rows of one colour at a body):
        # such rows are coloured afresh.
        slot = np.concatenate([ma[kept], mb[kept]]) * np.int64(64) + np.tile(prior[kept], 2)
        ids = np.tile(kept, 2)
        real = slot < n * 64
        slot, ids = slot[real], ids[real]
        order = np.argsort(slot, kind="stable")
        s = slot[order]
        dup = np.flatnonzero(s[1:] == s[:-1])
        if len(dup):
            prior = prior.copy()
            prior[ids[order[dup]]] = -1
            prior[ids[order[dup + 1]]] = -1
            kept = np.flatnonzero(prior >= 0)
        color[kept] = prior[kept]
        bit = np.left_shift(np.int64(1), prior[kept])
        np.bitwise_or.at(mask, ma[kept], bit)
        np.bitwise_or.at(mask, mb[kept], bit)
        mask[n] = 0
        left = np.flatnonzero(prior < 0)
    top = np.full(n + 1, -np.inf)
    while len(left):
        la, lb, pr = ma[left], mb[left], priority[left]
        top[:] = -np.inf
        np.maximum.at(top, la, pr)
        np.maximum.at(top, lb, pr)
        go = ((pr >= top[la]) | (la == n)) & ((pr >= top[lb]) | (lb == n))
        want = _lowest_free(mask[la[go]] | mask[lb[go]])
        color[left[go]] = want
        bit = np.left_shift(np.int64(1), want)
        mask[la[go]] |= bit
        mask[lb[go]] |= bit
        mask[n] = 0
        left = left[~go]
    return color


def batches(
    color: np.ndarray, a: np.ndarray, b: np.ndarray, moves: np.ndarray, fast: bool = False
) -> list[np.ndarray]:
    """The rows in solving order, one index array per batch: each colour in turn, and the
    last colour's rows split into rounds in which no moving body repeats (a row joins two
    different bodies). ``fast``: run the loop kernel ``batch_rows`` (the same batches)."""
    if fast:
        order, ends = batch_rows(color, a, b, moves)
        bounds = [0, *ends.tolist()]
        return [order[s:e] for s, e in zip(bounds, bounds[1:], strict=False)]
    if not len(color):
        return []
    order = np.argsort(color, kind="stable")
    sc = color[order]
    starts: list[int] = []
    if len(sc):
        starts = np.flatnonzero(np.concatenate(([True], sc[1:] != sc[:-1]))).tolist()
    out: list[np.ndarray] = []
    for s, e in zip(starts, [*starts[1:], len(sc)], strict=True):
        rows = order[s:e]
        if sc[s] < MAX_COLORS - 1:
            out.append(rows)
            continue
        while len(rows):  # a body touching more than MAX_COLORS - 1 others
            m = len(rows)
            ka = np.where(moves[a[rows]], a[rows], -1 - np.arange(m))
            kb = np.where(moves[b[rows]], b[rows], -1 - np.arange(m))
            take = _winners(ka, kb)
            out.append(rows[take])
            rows = rows[~take]
    return out


# -- the loop kernels (engine.kernels: the fast path) ------------------------------------------


def _sample_rows() -> tuple[object, ...]:
    """The smallest call of ``color_rows``: two rows at one body, one against the static slot."""
    return (np.array([0, 1]), np.array([1, 2]), np.array([True, True, False]), np.zeros(0),
            np.array([-1, 0]))  # fmt: skip


@kernels.loop(sample=_sample_rows)
def color_rows(
    a: np.ndarray, b: np.ndarray, moves: np.ndarray, priority: np.ndarray, prior: np.ndarray
) -> np.ndarray:
    """``colors`` as loops (int64 colour by row): ``priority`` (float by row) and ``prior``
    (int by row) are used when they hold a value for each row (empty: none)."""
    rows, n = len(a), len(moves)
    color = np.full(rows, -1, dtype=np.int64)
    if rows == 0:
        return color
    pr = np.empty(rows)
    if len(priority) == rows:
        for k in range(rows):
            pr[k] = priority[k]
    else:  # the twin's default order, rounded as its array expression rounds
        for k in range(rows):
            pr[k] = -(float(a[k]) * n + b[k]) - k / (rows + 1.0)
    # The bodies that move, and the slot n for those that do not (never claimed).
    ma, mb = np.empty(rows, dtype=np.int64), np.empty(rows, dtype=np.int64)
    for k in range(rows):
        ma[k] = a[k] if moves[a[k]] else n
        mb[k] = b[k] if moves[b[k]] else n
    mask = np.zeros(n + 1, dtype=np.int64)  # bit c set: a row of colour c holds the body
    if len(prior) == rows:
        # Colours kept from the step before, but not two of one colour at a moving body
        # (every row of such a clash is coloured afresh): a bit per body and colour marks
        # a colour seen, and one seen twice.
        seen, twice = np.zeros(n + 1, dtype=np.int64), np.zeros(n + 1, dtype=np.int64)
        for k in range(rows):
            if prior[k] >= 0:
                bit = np.int64(1) << prior[k]
                for j in (ma[k], mb[k]):
                    if j < n:
                        if seen[j] & bit:
                            twice[j] |= bit
                        seen[j] |= bit
        for k in range(rows):
            if prior[k] >= 0:
                bit = np.int64(1) << prior[k]
                if (ma[k] < n and twice[ma[k]] & bit) or (mb[k] < n and twice[mb[k]] & bit):
                    continue
                color[k] = prior[k]
                mask[ma[k]] |= bit
                mask[mb[k]] |= bit
        mask[n] = 0
    left = np.flatnonzero(color < 0)  # in row order, as the twin's
    key = np.empty(len(left))
    for i in range(len(left)):
        key[i] = -pr[left[i]] + 0.0  # (+ 0.0: -0.0 is 0.0, a tie, as in numpy's sort)
    # Highest priority first, stably: the floats' bits as int64 keys in the same order (a
    # negative float's bits, all but the sign's, flipped), sorted by ``stable_order``.
    bits = key.view(np.int64)
    order_keys = bits ^ ((bits >> 63) & np.int64(0x7FFFFFFFFFFFFFFF))
    by = stable_order(order_keys)
    tied = False
    for i in range(len(by) - 1):
        if key[by[i]] == key[by[i + 1]]:
            tied = True
            break
    if not tied:
        # The sequential greedy in priority order: the twin's rounds (module text).
        for i in range(len(by)):
            k = left[by[i]]
            m = mask[ma[k]] | mask[mb[k]]
            c = 0
            while c < MAX_COLORS - 1 and (m >> c) & 1:  # the lowest colour free at both
                c += 1
            color[k] = c
            bit = np.int64(1) << c
            mask[ma[k]] |= bit
            mask[mb[k]] |= bit
            mask[n] = 0
        return color
    # Tied priorities: the twin's rounds themselves, step by step as its array calls take
    # them (rows tied at a body may both go in one round, and take one colour).
    top = np.empty(n + 1)
    go = np.zeros(rows, dtype=np.bool_)
    want = np.zeros(rows, dtype=np.int64)
    new = np.zeros(rows, dtype=np.int64)
    while len(left):
        top[:] = -np.inf
        for r in left:
            top[ma[r]] = max(top[ma[r]], pr[r])
            top[mb[r]] = max(top[mb[r]], pr[r])
        for r in left:  # who goes, and the colour each takes, from the masks before the round
            go[r] = (pr[r] >= top[ma[r]] or ma[r] == n) and (pr[r] >= top[mb[r]] or mb[r] == n)
            if go[r]:
                m = mask[ma[r]] | mask[mb[r]]
                c = 0
                while c < MAX_COLORS - 1 and (m >> c) & 1:
                    c += 1
                want[r] = c
                color[r] = c
        # mask[la[go]] |= bit, then mask[lb[go]] |= bit: each read whole before it is
        # written, a repeated body keeping the last row's value.
        for r in left:
            if go[r]:
                new[r] = mask[ma[r]] | (np.int64(1) << want[r])
        for r in left:
            if go[r]:
                mask[ma[r]] = new[r]
        for r in left:
            if go[r]:
                new[r] = mask[mb[r]] | (np.int64(1) << want[r])
        for r in left:
            if go[r]:
                mask[mb[r]] = new[r]
        mask[n] = 0
        rest = 0
        for r in left:
            if not go[r]:
                left[rest] = r
                rest += 1
        left = left[:rest]
    return color


def _sample_batches() -> tuple[object, ...]:
    """The smallest call of ``batch_rows``: two rows of one colour and one of the last."""
    return (np.array([0, 0, MAX_COLORS - 1]), np.array([0, 1, 0]), np.array([2, 2, 1]),
            np.array([True, True, False]))  # fmt: skip


@kernels.loop(sample=_sample_batches)
def batch_rows(
    color: np.ndarray, a: np.ndarray, b: np.ndarray, moves: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``batches`` as loops: the rows in solving order (int64) and the end of each batch in
    it (int64)."""
    rows = len(color)
    # The rows by colour, in row order within one (the twin's stable sort): a counting sort
    # for the colours ``colors`` gives, 0 to MAX_COLORS - 1, a merge sort for any others.
    low, high = 0, MAX_COLORS - 1
    for k in range(rows):
        low, high = min(low, color[k]), max(high, color[k])
    if low < 0 or high >= MAX_COLORS:
        order = stable_order(color)
    else:
        start = np.zeros(MAX_COLORS + 1, dtype=np.int64)
        for k in range(rows):
            start[color[k] + 1] += 1
        for c in range(MAX_COLORS):
            start[c + 1] += start[c]
        order = np.empty(rows, dtype=np.int64)
        for k in range(rows):
            order[start[color[k]]] = k
            start[color[k]] += 1
    out = np.empty(rows, dtype=np.int64)
    ends = np.empty(rows, dtype=np.int64)  # at most a batch a row
    n_ends = 0
    pos = 0
    mark = np.zeros(len(moves), dtype=np.int64)  # the round that last claimed a body
    rnd = 0
    s = 0
    while s < rows:
        e = s + 1
        while e < rows and color[order[e]] == color[order[s]]:
            e += 1
        if color[order[s]] < MAX_COLORS - 1:
            for i in range(s, e):
                out[pos] = order[i]
                pos += 1
            ends[n_ends] = pos
            n_ends += 1
        else:
            # Rounds: a row goes if no row before it among those left claims one of its
            # moving bodies (claimed by every row that asks, taken or not: the twin's
            # "first to ask for both its keys").
            left = order[s:e].copy()
            while len(left):
                rnd += 1
                rest = 0
                for k in left:
                    ok = (not moves[a[k]] or mark[a[k]] != rnd) and (
                        not moves[b[k]] or mark[b[k]] != rnd
                    )
                    if moves[a[k]]:
                        mark[a[k]] = rnd
                    if moves[b[k]]:
                        mark[b[k]] = rnd
                    if ok:
                        out[pos] = k
                        pos += 1
                    else:
                        left[rest] = k
                        rest += 1
                ends[n_ends] = pos
                n_ends += 1
                left = left[:rest]
        s = e
    return out, ends[:n_ends]
