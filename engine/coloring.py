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
"""

from __future__ import annotations

import numpy as np

__all__ = ["colors", "batches", "MAX_COLORS"]

#: Colours a body's mask holds; a row that finds none free at its bodies takes the last,
#: MAX_COLORS - 1, whose rows may share a body (``batches`` splits it into rounds).
MAX_COLORS = 62


def _lowest_free(mask: np.ndarray) -> np.ndarray:
    """The index of the lowest zero bit of each mask (int64), at most MAX_COLORS - 1."""
    free = ~mask & (mask + 1)  # the lowest zero bit, alone
    # log2 of a power of two is its bit's place, exactly (2^k, k < 62, in float64).
    out = np.log2(free.astype(np.float64)).astype(np.int64)
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
    new ones need colouring; those kept must not clash, as a colouring's subset does not).
    """
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


def batches(color: np.ndarray, a: np.ndarray, b: np.ndarray, moves: np.ndarray) -> list[np.ndarray]:
    """The rows in solving order, one index array per batch: each colour in turn, and the
    last colour's rows split into rounds in which no moving body repeats."""
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
