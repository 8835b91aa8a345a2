"""``stroll``: from 0 at 1 in/s to the end of his 10-inch tube, s(t) = t (figures 5, 8, 9)."""

from __future__ import annotations

from .tube import TubeScene


class Stroll(TubeScene):
    """From 0 at 1 in/s to the end of the tube in 10 s (figures 5, 8, 9)."""

    name = "stroll"
    summary = "Alfred walks 0 -> 10 in at 1 in/s; area under v(t) = distance (figures 5, 8, 9)"
    title = "Alfred's stroll"
    formula = "s(t) = s0 + v t = t in,  v = 1 in/s,  a = 0"
    duration = 10.0
    dt = 1.0 / 120.0
    v_range = (0.0, 2.0)
    a_range = (-1.0, 1.0)
    start = (0.0, 1.0, 0.0)  # from 0 at 1 in/s
