"""Alfred the ant, lesson 1's figures as moving scenes (inches and seconds).

- ``lazy``: Alfred sits at 5 in: s(t) = 5 in, v = 0, a = 0 (figure 7).
- ``stroll``: from 0 at 1 in/s to the end of his 10-inch tube: s(t) = t (figures 5, 8, 9); the
  shaded area under v(t) is the distance walked.
- ``sprint``: from rest at 1 in/s^2 (figure 6), as two ants on two tubes. The lesson's "he
  reaches the end in 4 s" (0, 1, 3, 6, 10 in) is semi-implicit Euler with a 1 s step; the exact
  answer, s = t^2 / 2 = 10 in, is t = sqrt(20) = 4.47 s. The shaded areas under v(t) show why:
  Euler moves each whole second at the speed it has at the end of that second.
- ``paper``: Alfred's 2D walk x(t) = t^2 / 2, y(t) = 2t - t^2 on a sheet of paper, with his
  position vector from the origin and his velocity (t, 2 - 2t) tangent to the path
  (figures 15 to 18).

One scene a module: ``lazy.py``, ``stroll.py``, ``sprint.py`` and ``paper.py``; the tube scenes'
shared layout, stepping and drawing in ``tube.py``; the sprites and type sizes every scene uses
in ``common.py``.
"""

from __future__ import annotations

from demos.cli import Demo

from .common import ANT_BODY, ASSETS, EULER_ANT_BODY, ant_sprite
from .lazy import Lazy
from .paper import Paper
from .sprint import Sprint
from .stroll import Stroll
from .tube import TUBE_LENGTH, TUBE_THICKNESS, Ant, Tubes, TubeScene

__all__ = [
    "ANT_BODY",
    "ASSETS",
    "EULER_ANT_BODY",
    "TUBE_LENGTH",
    "TUBE_THICKNESS",
    "Ant",
    "Tubes",
    "TubeScene",
    "ant_sprite",
    "Lazy",
    "Stroll",
    "Sprint",
    "Paper",
    "DEMO",
]

DEMO = Demo(
    name="alfred",
    summary="Alfred the ant, lesson 1: sitting, strolling, sprinting, walking on paper",
    scenes={"lazy": Lazy, "stroll": Stroll, "sprint": Sprint, "paper": Paper},
)
