"""Which of a step's moments a round of impacts resolves (engine.exact.pair_impacts).

A body's next moment within the step is the earliest of its pairs' impacts, of the wall its
path meets (a body an impact sent off may meet one on its new path), and of the next bounce of
a path the static contacts bent (engine.exact.bent_paths). Each round resolves

* every pair that is the earliest moment of both its bodies (ties: the lower pair index),
  since such pairs share no body, and that no earlier pair of the round has a body paired
  with one of its own (``first_after``): that pair's bodies leave on new paths, which may
  meet it first (five balls in a row: 2 and 3 met, then 3 and 4 at 2.3 ms and 1 and 2 at
  8 ms were taken in one round; 3 came back from 4 into 2 at 4.7 ms, and passed through it,
  2's path searched from 8 ms on); and in a group of at most ``SMALL_GROUP`` bodies linked
  by pairs (``groups``), only the group's first moment, since a new path reaches the
  group's other bodies through chains of them too (six balls 1 um apart: 1-2 and 4-5 in one
  round, where 2 met 3 and 3 met 4 before 4-5). A larger group, a crowd, still takes as
  many of its impacts a round as the first rule lets it, and there a chain of two links
  can still be missed;
* every body's wall or bounce that comes before every pair of its own;

and the paths that changed are searched again from their moments (``Order.choose``).

Walls and bounces are kept in time order among the bodies linked by pairs, through any chain of
them (``groups``; bodies of two groups never meet within the step, the pairs being all that can
touch): a wall or bounce waits for everything before it in its group, and no pair after it
there is resolved before it, for the path it starts may meet any of those bodies sooner (a ball
sent into a wall at 0.27 s comes back, at 0.4 s, into one that would meet its own wall only at
0.47 s; resolved in one round, that one's path is searched from 0.47 s on, and the meeting
missed). Pairs among themselves keep the round's order, which takes a crowd's many impacts a
round at a time.
"""

from __future__ import annotations

import numpy as np

__all__ = ["SMALL_GROUP", "Order", "first_after", "groups"]


def groups(pa: np.ndarray, pb: np.ndarray, n: int) -> np.ndarray:
    """Each of n bodies' group: the lowest body linked to it by the pairs (pa, pb) through any
    chain of them (labels spread along the pairs, then jump to their own labels)."""
    label = np.arange(n)
    while True:
        low = np.minimum(label[pa], label[pb])
        new = label.copy()
        np.minimum.at(new, pa, low)
        np.minimum.at(new, pb, low)
        new = new[new]
        if np.array_equal(new, label):
            return label
        label = new


def first_after(
    s: np.ndarray, toi: np.ndarray, pa: np.ndarray, pb: np.ndarray, n: int
) -> np.ndarray:
    """Which of the round's pairs (indices ``s``; bool, one each) come first among the
    round's pairs that their bodies are paired with (``pa``, ``pb``: all the pairs of n
    bodies, all that can touch within the step): no pair of the round before it (``toi``)
    has a body that may meet one of its own. The round's first pair always does."""
    when = np.full(n, np.inf)  # each body's moment in the round
    when[pa[s]] = toi[s]
    when[pb[s]] = toi[s]
    ta, tb = when[pa], when[pb]
    late = np.zeros(n, dtype=bool)  # paired with a body of an earlier pair of the round
    late[pa[ta > tb]] = True
    late[pb[tb > ta]] = True
    return ~late[pa[s]] & ~late[pb[s]]


#: The most bodies linked by pairs whose impacts are taken strictly in time order, one
#: moment a round (larger groups, a crowd: ``first_after``'s rule, many a round).
SMALL_GROUP = 16


class Order:
    """The rounds' choice (module text) for the pairs (pa, pb) of n local bodies."""

    def __init__(self, pa: np.ndarray, pb: np.ndarray, n: int) -> None:
        self.pa, self.pb, self.n = pa, pb, n
        self._group: np.ndarray | None = None  # made when first needed

    def group(self) -> np.ndarray:
        """Each body's group (``groups``: the lowest body linked to it by the pairs)."""
        if self._group is None:
            self._group = groups(self.pa, self.pb, self.n)
        return self._group

    def choose(
        self, toi: np.ndarray, face_t: np.ndarray, bend: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The round's moments (module text): (the pairs, the bodies whose wall, the bodies
        whose bounce), from each pair's time of impact ``toi`` and each body's wall time
        ``face_t`` and next bounce ``bend`` (None: no path is bent), all s in the step, inf
        for none."""
        pa, pb = self.pa, self.pb
        nxt = face_t if bend is None else np.minimum(face_t, bend)
        h = np.flatnonzero(np.isfinite(toi))
        best = nxt.copy()  # each body's next moment
        np.minimum.at(best, pa[h], toi[h])
        np.minimum.at(best, pb[h], toi[h])
        first = np.full(self.n, len(pa))
        ca = h[toi[h] == best[pa[h]]]
        cb = h[toi[h] == best[pb[h]]]
        np.minimum.at(first, pa[ca], ca)
        np.minimum.at(first, pb[cb], cb)
        s = h[(first[pa[h]] == h) & (first[pb[h]] == h)]
        s = s[(toi[s] < nxt[pa[s]]) & (toi[s] < nxt[pb[s]])]
        if len(s) > 1:
            # A pair waits for an earlier one of the round that a body of its own is paired
            # with (``first_after``): that one's bodies leave on new paths, which may meet it
            # sooner. In a small group of linked bodies, for any earlier one of its group:
            # the new paths reach it through a chain of others as well.
            g = self.group()
            small = np.bincount(g, minlength=self.n)[g[pa[s]]] <= SMALL_GROUP
            if small.any():
                first = np.full(self.n, np.inf)
                np.minimum.at(first, g[pa[s]], toi[s])
                s = s[~small | (toi[s] <= first[g[pa[s]]])]
            s = s[first_after(s, toi, pa, pb, self.n)]
        wall = np.flatnonzero(np.isfinite(face_t) & (face_t <= best))
        knot = np.zeros(0, dtype=np.intp)
        if np.isfinite(nxt).any():
            g = self.group()
            soon = np.full(self.n, np.inf)  # each group's first wall or bounce
            ahead = np.full(self.n, np.inf)  # and its first moment of any kind
            np.minimum.at(soon, g, nxt)
            np.minimum.at(ahead, g, best)
            s = s[toi[s] <= soon[g[pa[s]]]]
            wall = wall[face_t[wall] <= ahead[g[wall]]]
            if bend is not None:
                knot = np.flatnonzero(np.isfinite(bend) & (bend <= ahead[g]))
        return s, wall, knot
