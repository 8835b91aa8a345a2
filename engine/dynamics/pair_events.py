"""Events of contacts between bodies: which began and which ended in a step.

A contact between bodies begins either as an impact (at its exact moment, with its point,
normal and impulse: engine.exact.pair_impacts) or as a pair of a pile that touches now and did not
after the last step; it ends as an impact whose pair no longer touches at the step's end, or as
a pair that touched and no longer does. Pairs are keyed a * n + b (World rows a < b, n
bodies), and the pairs touching after a step are kept sorted, so both comparisons are binary
searches (engine.geometry.pair_math). A pair struck in the step is reported by its impact alone, not
again as a resting pair that began or ended.

The events are held as arrays, (rows, other rows, points, normals, impulses, times), one
tuple a batch, and unpacked into one tuple a contact (``unpack``) only when asked for; a
resting pair's point is None (taken from the state), its normal and impulse zero, and its time
the step's end.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..geometry.pair_math import isin_sorted, sorted_unique

__all__ = ["events_of", "unpack"]


def events_of(
    keys: np.ndarray,
    impacts: list[tuple[np.ndarray, ...]],
    n: int,
    t0: float,
    dt: float,
    before: np.ndarray,
    began: list[tuple[Any, ...]],
    ended: list[tuple[Any, ...]],
) -> np.ndarray:
    """Began: each impact, and each pair at rest touching now that did not before; ended:
    each impact whose pair no longer touches, and each pair that touched and no longer
    does. Appended to ``began`` and ``ended`` as (rows, other rows, points, normals,
    impulses, times) arrays. ``keys``: the pairs touching now; ``before``: those that
    touched after the last step (sorted); ``impacts``: in World rows, times within the step
    that began at t0. Returns the pairs touching now, sorted, for the next step."""
    keys = sorted_unique(keys)
    if not impacts and np.array_equal(keys, before):
        return keys  # the same pairs touch as before: nothing began or ended
    struck = np.zeros(0, dtype=np.int64)
    if impacts:
        for ga, gb, point, nrm, P, tau in impacts:  # (World rows)
            t = t0 + tau
            began.append((ga, gb, point, nrm, P, t))
            k = ga.astype(np.int64) * n + gb
            struck = np.concatenate([struck, k])
            apart = ~isin_sorted(k, keys)
            if apart.any():
                ended.append((ga[apart], gb[apart], point[apart], nrm[apart], P[apart], t[apart]))
    struck = sorted_unique(struck)
    new = keys[~isin_sorted(keys, before) & ~isin_sorted(keys, struck)]
    gone = before[~isin_sorted(before, keys) & ~isin_sorted(before, struck)]
    for which, sel in ((began, new), (ended, gone)):
        if len(sel):
            zero = np.zeros((len(sel), 2))
            which.append((sel // n, sel % n, None, zero, zero, np.full(len(sel), t0 + dt)))
    return keys


def unpack(parts: list[tuple[Any, ...]]) -> list[tuple[int, int, Any, Any, Any, float]]:
    """The events held as arrays, one tuple a contact: (row, other row, point, normal toward
    row, impulse on row, time)."""
    out: list[tuple[int, int, Any, Any, Any, float]] = []
    for rows, others, points, normals, impulses, times in parts:
        for k in range(len(rows)):
            p = None if points is None else points[k]
            out.append((int(rows[k]), int(others[k]), p, normals[k], impulses[k], float(times[k])))
    return out
