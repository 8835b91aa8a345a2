"""``lazy``: Alfred sits at 5 in: s(t) = 5 in, v = 0, a = 0 (figure 7)."""

from __future__ import annotations

from .tube import TubeScene


class Lazy(TubeScene):
    """Alfred sits still at 5 in (figure 7)."""

    name = "lazy"
    summary = "Alfred sits at 5 in: s(t) = 5 in, v = 0, a = 0 (figure 7)"
    title = "Lazy Alfred"
    formula = "s(t) = 5 in,  v(t) = 0,  a(t) = 0"
    duration = 4.0
    dt = 1.0 / 120.0
    s_range = (0.0, 10.0)
    v_range = (-1.0, 1.0)
    a_range = (-1.0, 1.0)
    start = (5.0, 0.0, 0.0)  # at rest at 5 in
