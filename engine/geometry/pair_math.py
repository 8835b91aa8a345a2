"""What the contacts between bodies share: row-by-row arithmetic, sorted pair keys, the slop.

The pairs of bodies (engine.exact.collisions and the modules it composes) are held as arrays: an
(N, 2) array of vectors, one a row, and pairs of World rows (a, b) with a < b. The vector
helpers here work row by row with two multiplications and an addition a row (no einsum, no
axis reductions), so that every module that computes a norm or a dot gets the same bits from
the same operations in the same order.

A pair is keyed by one integer, a * n + b for n bodies (or a * base + b where the faces are
numbered past the bodies): sorting the keys sorts the pairs by a, then b, and a binary search
finds a pair of one step among another's. ``sorted_unique`` and ``isin_sorted`` are numpy's
``unique`` and ``isin`` for such keys, by a sort and binary searches (numpy 2 hashes first,
several times slower on the ~10^4 keys of a pile).

Two discs touch when their centres are r_a + r_b apart; they count as touching, not
overlapping, down to ``SLOP`` of the smaller radius inside that (contacts touch, they do not
chatter): the pile's rows aim there, and only a deeper overlap is pushed apart.
"""

from __future__ import annotations

import numpy as np

from .faces import dot

__all__ = ["SLOP", "dot", "isin_sorted", "norm", "sorted_unique", "state_at", "unit"]

#: Overlap (fraction of the smaller radius) that counts as touching: contacts touch, they do
#: not chatter.
SLOP = 0.002


def norm(a: np.ndarray) -> np.ndarray:
    """Row by row lengths of an (N, 2) array: (N,)."""
    return np.sqrt(a[:, 0] * a[:, 0] + a[:, 1] * a[:, 1])


def unit(d: np.ndarray, dist: np.ndarray) -> np.ndarray:
    """d / dist row by row; where two centres coincide (dist 0), straight up (0, 1), so that
    bodies placed on top of one another are still pushed apart."""
    out = d / np.where(dist > 0.0, dist, 1.0)[:, None]
    same = dist == 0.0
    if same.any():
        out[same] = (0.0, 1.0)
    return out


def state_at(
    i: np.ndarray, t: np.ndarray, X: np.ndarray, V: np.ndarray, A: np.ndarray, dt: float
) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity of bodies i at times t (s, in the step), on the paths ending at
    (X, V) after dt with accelerations A: x(t) = X - V s + A s^2 / 2, v(t) = V - A s, s = dt - t
    (engine.exact.pair_impacts)."""
    s = (dt - t)[:, None]
    Ai = A[i]
    return X[i] - V[i] * s + Ai * (0.5 * s * s), V[i] - Ai * s


def sorted_unique(a: np.ndarray) -> np.ndarray:
    """``np.unique(a)`` for integers: sorted, without repeats (a sort and a mask; numpy 2's
    np.unique hashes first, several times slower on the ~10^4 keys of a pile)."""
    s = np.sort(a)
    if len(s) > 1:
        s = s[np.concatenate(([True], s[1:] != s[:-1]))]
    return s


def isin_sorted(a: np.ndarray, s: np.ndarray) -> np.ndarray:
    """``np.isin(a, s)`` for ``s`` sorted without repeats: one binary search per element."""
    if not len(s):
        return np.zeros(len(a), dtype=bool)
    pos = np.searchsorted(s, a)
    pos[pos == len(s)] = 0
    return s[pos] == a
